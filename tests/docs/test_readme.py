"""The README's Python examples run as written (from the repository root)."""

import re

import pytest

from tests.helpers import ROOT

BLOCKS = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), flags=re.S)


def test_readme_has_examples():
    assert len(BLOCKS) >= 2


@pytest.mark.slow
@pytest.mark.parametrize("k", range(len(BLOCKS)))
def test_readme_block_runs(k, tmp_path, monkeypatch, capsys):
    # paths in the README are relative to the repository root; pictures go to tmp_path
    code = BLOCKS[k].replace('"mechanisms/', f'"{ROOT.as_posix()}/mechanisms/')
    monkeypatch.chdir(tmp_path)
    exec(compile(code, f"README block {k}", "exec"), {"__name__": "readme"})
    for png in tmp_path.glob("*.png"):
        assert png.stat().st_size > 1000
