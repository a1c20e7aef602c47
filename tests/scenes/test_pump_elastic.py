"""The pump scene on an elastic support: files, units and the rigid/elastic comparison.

Coarse settings (P1, mesh 0.3 R0, a tenth of a turn from a steady start) keep it fast; the checks are
on consistency: the summary's smallest films are the minima of the CSV columns, the ratios their
quotients, the thinnest-state figures are the SI values of the re-solved state, and a deflection
picture without an elastic run is a schema error naming the field.
"""

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from bearingfe.cli import main
from bearingfe.scenes import SceneError, load_scene
from tests.helpers import ROOT

#: The coarse elastic scene of these tests (overrides of the shipped scenes/pump.toml): the half-space model.
COARSE = dict(title="coarse elastic pump", elastic={"enabled": True, "model": None},
              run={"revolutions": 0.1, "start": "steady", "mesh_size": 0.3, "element": "P1", "rtol": None, "frames": 0},
              output={"pictures": ["pressure", "film", "deflection"]})


def _min_column(path: Path, name: str) -> float:
    with open(path) as fh:
        return min(float(row[name]) for row in csv.DictReader(fh))


@pytest.mark.slow  # 4 runs and 5 pictures of 4 maps each: about 5 s on an idle 2-core machine, more when loaded
def test_elastic_pump_scene(tmp_path, scene_file):
    out = tmp_path / "out"
    assert main(["run", str(scene_file("pump", COARSE)), "--out", str(out), "--no-progress"]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"trajectory_pocket_elastic.csv", "trajectory_plain_elastic.csv", "pressure.png",
            "pressure_elastic.png", "film.png", "film_elastic.png", "deflection.png"} <= names
    res = json.loads((out / "summary.json").read_text())["results"]
    for name in ("pocket", "plain", "pocket_elastic", "plain_elastic"):
        assert res[name]["smallest_film_m"] == pytest.approx(
            _min_column(out / f"trajectory_{name}.csv", "h_min [m]"), rel=1e-12)
    for name in ("pocket_elastic", "plain_elastic"):
        largest = _min_column(out / f"trajectory_{name}.csv", "max_deflection [m]")  # positive everywhere
        assert 0 < largest <= res[name]["largest_deflection_m"]
    assert res["film_ratio_elastic"] == pytest.approx(
        res["pocket_elastic"]["smallest_film_m"] / res["plain_elastic"]["smallest_film_m"], rel=1e-12)
    thin = res["pocket_elastic"]["thinnest_state"]
    assert thin["film_m"] == pytest.approx(res["pocket_elastic"]["smallest_film_m"], rel=1e-3)
    assert 0 <= thin["beta_deg"] < 360 and thin["deflection_m"] > 1e-6
    assert thin["peak_pressure_Pa"] >= thin["pressure_at_thinnest_Pa"]
    assert res["pocket"]["thinnest_state"]["deflection_m"] == 0.0
    for name in ("pocket_elastic", "plain_elastic"):  # every elastic run pictured at its own states
        assert res[name]["loaded_state"]["deflection_m"] > 0.0


def test_quasi_static_dynamics_with_cavitation(tmp_path, scene_file):
    path = scene_file("pump", COARSE, pump={"compare_plain": False}, elastic={"dynamics": "quasi-static"},
                      run={"cavitation": "reynolds", "revolutions": 0.03}, output={"pictures": ["pressure"]})
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["elastic"]["dynamics"] == "quasi-static"
    res = summary["results"]["pocket_elastic"]
    assert 0 < res["thinnest_state"]["deflection_m"] <= res["largest_deflection_m"] * (1 + 1e-9)


def test_deflection_picture_needs_the_elastic_run(tmp_path, scene_file):
    from bearingfe.scenes.pump import settings as pump_settings

    data, label = load_scene(scene_file("pump", COARSE, elastic={"enabled": False}))
    with pytest.raises(SceneError, match=r"\[output\] pictures: 'deflection' needs \[elastic\] enabled"):
        pump_settings(data, label, tmp_path)
    data, label = load_scene(scene_file("pump", COARSE))
    data["run"]["cavitation"] = "reynolds"
    with pytest.raises(SceneError, match=r"\[elastic\] dynamics: 'squeeze' needs \[run\] cavitation = 'none'"):
        pump_settings(data, label, tmp_path)
    bad = scene_file("pump", name="bad.toml", elastic={"model": "rubber"})
    data, label = load_scene(bad)
    with pytest.raises(SceneError, match=r"\[elastic\] model: must be one of 'half-space', 'block', 'shoe'"):
        pump_settings(data, label, tmp_path)


def test_film_ratios_need_completed_runs_of_their_own_pair():
    """The rigid ratio pocket/plain needs the two rigid runs completed, the elastic ratio the two elastic
    runs: a stopped elastic run (its smallest film is where it stopped) leaves the rigid ratio standing."""
    from types import SimpleNamespace

    from bearingfe.scenes.pump import _film_ratio

    done = SimpleNamespace(status="completed", smallest_film=9e-6)
    plain = SimpleNamespace(status="completed", smallest_film=6e-6)
    stopped = SimpleNamespace(status="no-equilibrium", smallest_film=1e-6)
    assert _film_ratio(done, plain, "") == (1.5, (1.5, "-"))
    ratio, row = _film_ratio(done, stopped, "_elastic")
    assert ratio is None and row == ("not computed: pocket_elastic completed, plain_elastic no-equilibrium", "")


def test_pump_scene_on_the_real_shoe_body(tmp_path, scene_file):
    # model = "shoe": the scene builds the machine file's shoe body (bearingfe.elastic.shoe) and runs the
    # squeeze model on it; the same run through the API gives the same smallest film (deterministic)
    import bearingfe as bf
    from bearingfe.transient import simulate_elastic
    from bearingfe.elastic.shoe import shoe_compliance

    path = scene_file("pump", COARSE, pump={"compare_plain": False}, elastic={"model": "shoe"},
                      output={"pictures": ["trajectory"]})
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["elastic"]["model"] == "shoe"
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    mesh = bf.transient.pump_mesh(pump, 0.3, order=1)
    C = shoe_compliance(mesh, pump.scale, pump.shoe_material, pump.shoe_body, counterpart=pump.eccentric_material,
                        element="P1")
    run = simulate_elastic(pump, C, 0.1, start="steady", rtol=1e-6)
    assert summary["results"]["pocket_elastic"]["smallest_film_m"] == pytest.approx(run.smallest_film, rel=1e-9)
