"""The ``"reynolds"`` scene's error estimate: ``[solver] estimate_error`` reaches the summary and its table."""

import json

import pytest

from bearingfe.cli import main

#: A small P1 scene (overrides of the shipped scenes/default.toml), no pictures.
SMALL = dict(solver={"size": 0.1, "inlet_size": None, "linear_solver": None, "element": "P1"},
             output={"pictures": []})


@pytest.mark.parametrize("estimate", [False, True])
def test_estimate_error_reaches_the_summary(tmp_path, scene_file, estimate):
    out = tmp_path / "out"
    assert main(["run", str(scene_file("reynolds", SMALL, solver={"estimate_error": estimate})), "--out", str(out),
                 "--no-progress"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    rows = {row[0]: row[1] for row in summary["table"]}
    if not estimate:
        assert summary["results"]["load_error"] is None and "load error (estimated)" not in rows
        return
    err = summary["results"]["load_error"]
    # the P1 0.1 mesh of the shipped shoe: a few tenths of a percent, not converged to 1e-4, not 10 %
    assert 1e-4 < err < 0.1 and rows["load error (estimated)"] == err
    assert any("load is not converged" in n for n in summary["notes"]) == (err > 0.01)
