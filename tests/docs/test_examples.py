"""Every numbered example runs (coarse meshes: BEARINGFE_QUICK=1), passes its own
assertions against its stated reference, and the pictures it writes are non-blank;
each writes into its own folder, and the pump example prints the documented pocket gain."""

import re
import runpy

import numpy as np
import pytest

from tests.helpers import ROOT

EXAMPLES = sorted((ROOT / "examples").glob("[0-9]*.py"))


def test_there_are_examples():
    assert any(p.name == "02_pressure_field.py" for p in EXAMPLES)


@pytest.mark.slow
@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs_and_draws(script, tmp_path, monkeypatch, capsys):
    import matplotlib.image as mpimg

    monkeypatch.setenv("BEARINGFE_QUICK", "1")
    monkeypatch.setenv("BEARINGFE_OUT", str(tmp_path))
    runpy.run_path(str(script), run_name="__main__")
    pictures = sorted(tmp_path.rglob("*.png"))
    assert pictures, f"{script.name} wrote no picture"
    for png in pictures:
        img = mpimg.imread(png)[..., :3]
        colours = np.unique((img.reshape(-1, 3) * 255).round().astype(int), axis=0)
        assert len(colours) > 20 and np.mean(np.any(img < 0.95, axis=-1)) > 0.05, png.name
    if script.stem == "01_pump_inlet_pocket":
        # the main scene's settings whatever BEARINGFE_QUICK says: the gain docs/papers.md generates
        papers = (ROOT / "docs" / "papers.md").read_text(encoding="utf-8")
        gain = re.search(r"\*\*Pocket gain of the shipped pump: ([+-]\d+ %)\*\*", papers)[1]
        assert f"pocket gain {gain}" in capsys.readouterr().out


@pytest.mark.parametrize("script", [p for p in EXAMPLES if p.stem != "02_pressure_field"],
                         ids=lambda p: p.stem)
def test_example_writes_into_its_own_folder(script, monkeypatch):
    # loaded without running (their work is under `if __name__ == "__main__"`): the default output
    # folder is examples/output/<the example's name>, whatever the working directory
    monkeypatch.delenv("BEARINGFE_OUT", raising=False)
    names = runpy.run_path(str(script), run_name="example")
    assert names["OUT"] == ROOT / "examples" / "output" / script.stem


def test_script_example_writes_into_its_own_folder():
    # 02 runs at import: its default folder is read from its text
    text = (ROOT / "examples" / "02_pressure_field.py").read_text(encoding="utf-8")
    assert 'Path(__file__).resolve().parent / "output" / Path(__file__).stem' in text
    for script in EXAMPLES:  # and no example names the main job's out/ folder
        assert not re.search(r"[\"'(]out/|\"out/?\"\)|default=\"out", script.read_text(encoding="utf-8"))
