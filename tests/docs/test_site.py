"""The documentation site's hand-written pages stay complete (the build itself runs in CI with warnings
as errors: ``scripts/build-docs.sh``)."""

from __future__ import annotations

import inspect
import re

import bearingfe as bf
from tests.helpers import ROOT

DOCS = ROOT / "docs"


def test_the_api_page_documents_every_public_name():
    page = (DOCS / "api.md").read_text(encoding="utf-8")
    documented = set(re.findall(r"\.\. auto(?:class|function|data):: bearingfe\.(\w+)", page))
    modules = set(re.findall(r"\.\. automodule:: (bearingfe[\w.]*)", page))
    named = documented | {name for name in bf.__all__
                          if inspect.ismodule(getattr(bf, name)) and getattr(bf, name).__name__ in modules}
    assert set(bf.__all__) - named == set()
    assert documented - set(bf.__all__) == set()


def test_every_page_is_in_the_site():
    index = (DOCS / "index.md").read_text(encoding="utf-8")
    entries = set(re.findall(r"^([\w/]+)$", index, flags=re.M))
    pages = {p.stem for p in DOCS.glob("*.md") if p.stem != "index"}
    assert pages - entries == set()
    assert "_generated/gallery" in entries


def test_the_readme_says_how_to_build_the_site():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "bash scripts/build-docs.sh" in readme
    assert (ROOT / "scripts" / "build-docs.sh").is_file()
