"""Every numbered example runs (coarse meshes: BEARINGFE_QUICK=1), passes its own
assertions against its stated reference, and the pictures it writes are non-blank."""

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
