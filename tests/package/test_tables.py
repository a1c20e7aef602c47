"""Every package's docstring tables its modules, so the tables cannot drift from the code.

Expected values come from the file system: every module and subpackage of a package
(``bearingfe`` and each of its subpackages) must have a row in the table of that
package's ``__init__.py``, and every row must name a module that exists there, once.
"""

import importlib
import re

import pytest
from tests.helpers import ROOT

PACKAGE = ROOT / "bearingfe"
PACKAGES = ["bearingfe"] + sorted(f"bearingfe.{p.parent.name}" for p in PACKAGE.glob("*/__init__.py"))


def _table_names(package: str) -> list[str]:
    doc = importlib.import_module(package).__doc__ or ""
    rows = re.findall(r"^``([a-z_0-9]+)``\s", doc, flags=re.MULTILINE)
    assert rows, f"the docstring of {package} has no module table"
    return rows


def _modules(package: str) -> set[str]:
    folder = PACKAGE.parent.joinpath(*package.split("."))
    names = {p.stem for p in folder.glob("*.py") if p.stem not in ("__init__", "__main__")}
    names |= {p.parent.name for p in folder.glob("*/__init__.py")}
    return names


@pytest.mark.parametrize("package", PACKAGES)
def test_every_module_has_a_row(package):
    missing = sorted(_modules(package) - set(_table_names(package)))
    assert missing == [], f"modules missing from the table in {package}: {missing}"


@pytest.mark.parametrize("package", PACKAGES)
def test_every_row_names_a_module_once(package):
    rows = _table_names(package)
    assert sorted(set(rows) - _modules(package)) == []
    assert len(rows) == len(set(rows))


def test_the_packages_are_found():
    # the layout's folders, read from the disk (a test that found no subpackage would pass vacuously)
    assert {"bearingfe.core", "bearingfe.film", "bearingfe.transient", "bearingfe.scenes"} <= set(PACKAGES)
