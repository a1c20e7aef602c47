"""The repository stands on its own: nothing it ships cites the planning notes beside it or issue numbers.

A reader of the package, its docs, benchmarks, scripts, examples, input files or tests has neither the
project's issue tracker nor the folder of planning notes next to the checkout, so a reference to either is
a dead link. The scan covers every text file under those folders (generated pages included: their
generators are scanned too) and the files at the top of the checkout (README, pyproject.toml).
"""
from __future__ import annotations

import re
from pathlib import Path

from tests.helpers import ROOT

FOLDERS = ("bearingfe", "bearingfe_cli", "docs", "benchmarks", "scripts", "examples", "scenes", "mechanisms",
           "studies", "meshes", "tests", ".ci")
SUFFIXES = {".py", ".md", ".toml", ".sh", ".geo", ".txt", ".cfg", ".json", ".rst", ""}
SKIP = {"_build", "_generated", "output", "__pycache__"}
ISSUE = re.compile(r"(?i)\bissues?[ -]?#?\d+")
SHARED = re.compile(r"\.\./shared\b|/work/shared\b")


def _texts():
    files = [p for p in ROOT.iterdir() if p.is_file() and p.suffix in SUFFIXES]
    for folder in FOLDERS:
        base = ROOT / folder
        if base.is_dir():
            files += [p for p in base.rglob("*") if p.is_file() and p.suffix in SUFFIXES
                      and not SKIP.intersection(p.relative_to(ROOT).parts)]
    return [p for p in files if p.resolve() != Path(__file__).resolve()]


def test_the_scan_sees_the_package():
    names = {p.relative_to(ROOT).as_posix() for p in _texts()}
    assert {"README.md", "pyproject.toml", "bearingfe/reynolds.py", "docs/index.md", "scenes/pump.toml"} <= names


def test_no_issue_numbers_and_no_planning_folder():
    hits = []
    for path in _texts():
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        for number, line in enumerate(text.splitlines(), 1):
            if ISSUE.search(line) or SHARED.search(line):
                hits.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()[:100]}")
    assert not hits, "cites an issue number or the planning folder:\n" + "\n".join(hits)


def test_the_patterns_catch_what_they_must():
    assert ISSUE.search("see issue 14") and ISSUE.search("Issue #3") and ISSUE.search("the issue-13 targets")
    assert SHARED.search("as ../shared/SPEC.md says") and not ISSUE.search("the issue's goal")
