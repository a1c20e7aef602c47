"""Benchmarks, scripts and examples name only what the package has.

They run outside the test suite (benchmarks take minutes), so a module moved or a name renamed would
otherwise surface only when someone reruns a page. Read with ``ast``, without running them: every
``from bearingfe... import name`` (at any depth, also inside functions) must resolve, and every
``bf.<name>`` (``import bearingfe as bf``) must be a public name of the package.
"""

from __future__ import annotations

import ast
import importlib

import pytest

import bearingfe as bf
from tests.helpers import ROOT

FILES = sorted([*ROOT.glob("benchmarks/*.py"), *ROOT.glob("scripts/*.py"), *ROOT.glob("examples/*.py"),
                ROOT / "docs" / "conf.py", *ROOT.glob("docs/_ext/*.py")])


def _unresolved(path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    missing = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0 \
                and node.module.split(".")[0] == "bearingfe":
            module = importlib.import_module(node.module)
            missing += [f"{node.module}.{a.name} (line {node.lineno})" for a in node.names
                        if not hasattr(module, a.name) and not _is_submodule(node.module, a.name)]
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "bearingfe":
                    importlib.import_module(alias.name)
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "bf" \
                and not hasattr(bf, node.attr):
            missing.append(f"bf.{node.attr} (line {node.lineno})")
    return missing


def _is_submodule(package: str, name: str) -> bool:
    try:
        importlib.import_module(f"{package}.{name}")
    except ModuleNotFoundError:
        return False
    return True


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_package_name_a_script_uses_exists(path):
    assert _unresolved(path) == []


def test_the_check_finds_a_missing_name(tmp_path):
    script = tmp_path / "old.py"
    script.write_text("import bearingfe as bf\nfrom bearingfe.core.schema import no_such_name\nbf.linalg\n")
    assert _unresolved(script) == ["bearingfe.core.schema.no_such_name (line 2)", "bf.linalg (line 3)"]
