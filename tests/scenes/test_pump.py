"""The pump scene through the command line (``bearingfe run scenes/pump.toml``).

Coarse settings (mesh 0.2 R0, a steady start, a quarter turn) keep it fast;
the checks are on consistency, not on converged numbers: every file is
written, the summary's smallest films are the minima of the CSV columns,
the film ratio is their quotient, and a pictured state re-solved from the
trajectory balances the applied load (paper eq. 13-14: film force + load = 0).
"""

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from bearingfe.cli import main
from bearingfe.transient import state_result
from bearingfe.scenes import SceneError, load_scene
from tests.helpers import ROOT

#: The coarse scene of these tests (overrides of the shipped scenes/pump.toml).
COARSE = dict(title="coarse pump", run={"revolutions": 0.25, "start": "steady", "mesh_size": 0.2, "rtol": None,
                                        "frames": 3}, elastic=None, output=None)


def _min_column(path: Path, name: str) -> float:
    with open(path) as fh:
        return min(float(row[name]) for row in csv.DictReader(fh))


def test_pump_scene_writes_everything_consistent(tmp_path, capsys, scene_file):
    out = tmp_path / "out"
    assert main(["run", str(scene_file("pump", COARSE)), "--out", str(out), "--no-progress"]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"trajectory_pocket.csv", "trajectory_plain.csv", "trajectory.png", "orbit.png", "pressure.png",
            "pressure.pvd", "summary.json"} <= names
    summary = json.loads((out / "summary.json").read_text())
    res = summary["results"]
    pocket = _min_column(out / "trajectory_pocket.csv", "h_min")
    plain = _min_column(out / "trajectory_plain.csv", "h_min")
    assert res["pocket"]["smallest_film_m"] == pytest.approx(pocket, rel=1e-12)
    assert res["plain"]["smallest_film_m"] == pytest.approx(plain, rel=1e-12)
    assert res["film_ratio"] == pytest.approx(pocket / plain, rel=1e-12)
    assert res["pocket"]["status"] == "completed" and res["plain"]["status"] == "completed"
    assert 0.0 < res["pocket"]["balance_ratio"] < 1.0  # the shipped pocket is below hydrostatic balance
    assert "smallest film ratio" in capsys.readouterr().out


def test_pictured_state_balances_the_load():
    import bearingfe as bf

    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    mesh = bf.transient.pump_mesh(pump, 0.2)
    traj = bf.simulate(pump, mesh, 0.1, start="steady", points_per_revolution=40)
    k = traj.beta.size - 1
    res = state_result(pump, mesh, traj, k)
    # film force + applied load = 0 at every stored state (transient.py docstring), load non-dimensional
    np.testing.assert_allclose(res.force, -traj.load[k], rtol=1e-6, atol=1e-9 * np.abs(traj.load[k]).max())


def test_pump_scene_errors_name_the_field(tmp_path, scene_file):
    bad = scene_file("pump", name="bad.toml", run={"start": "cold"})
    with pytest.raises(SceneError, match=r"\[run\] start: must be one of 'periodic', 'steady'"):
        from bearingfe.scenes.pump import settings as pump_settings
        data, label = load_scene(bad)
        pump_settings(data, label, tmp_path)
    missing = scene_file("pump", name="missing.toml", pump={"mechanism": "nowhere.toml"})
    assert main(["run", str(missing), "--out", str(tmp_path / "o"), "--no-progress"]) == 2
    assert not (tmp_path / "o").exists()
