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


def _fake_checkout(tmp_path):
    """run-main.sh in a copy of the repository layout whose set-up does nothing and whose ``bearingfe``
    prints the arguments it was given (the real set-up installs packages: not for a test)."""
    import shutil

    (tmp_path / "scripts").mkdir()
    shutil.copy(ROOT / "scripts" / "run-main.sh", tmp_path / "scripts" / "run-main.sh")
    (tmp_path / "scripts" / "setup.sh").write_text("true\n")
    bin_dir = tmp_path / ".venv" / "bin"
    bin_dir.mkdir(parents=True)
    (bin_dir / "bearingfe").write_text('#!/usr/bin/env bash\nprintf "%s\\n" "$@"\n')
    (bin_dir / "bearingfe").chmod(0o755)
    return tmp_path / "scripts" / "run-main.sh"


@pytest.mark.parametrize("args, passed", [
    ([], ["run", "scenes/pump.toml", "--out", "out"]),
    (["--force"], ["run", "scenes/pump.toml", "--out", "out", "--force"]),
    (["results", "--force", "--no-progress"], ["run", "scenes/pump.toml", "--out", "results", "--force",
                                               "--no-progress"]),
])
def test_run_main_passes_extra_arguments_to_the_command(tmp_path, args, passed):
    import subprocess

    script = _fake_checkout(tmp_path)
    done = subprocess.run(["bash", str(script), *args], capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == passed


def test_one_pocket_gain_quoted_everywhere():
    """The README quotes the pocket gain that docs/papers.md generates (scripts/make_papers_doc.py, with the
    main scene's settings through bearingfe.scenes.pump.simulate_design; tests/docs/test_papers.py checks
    the page is the generated one): the same number, and the same as docs/elastic.md's rigid ratio."""
    papers = (ROOT / "docs" / "papers.md").read_text(encoding="utf-8")
    generated = re.search(r"\*\*Pocket gain of the shipped pump: ([+-]\d+) %\*\* \(smallest film ratio "
                          r"pocket/plain (\d\.\d+)\)", papers)
    assert generated, "docs/papers.md has no generated headline"
    gain, ratio = int(generated[1]), float(generated[2])
    assert gain == round(100 * (ratio - 1))
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    quoted = re.findall(r"pocket\s+raises the smallest film by ([+-]\d+) %", readme)
    assert quoted == [str(f"{gain:+d}")]
    # no other gain of the shipped pump is quoted: every "+NN %" of the README is this one
    assert set(re.findall(r"\+\d+ %", readme)) == {f"{gain:+d} %"}
    elastic = (ROOT / "docs" / "elastic.md").read_text(encoding="utf-8")
    assert f"| pocket / plain | {ratio:.3f} |" in elastic  # its rigid column: the same computation
