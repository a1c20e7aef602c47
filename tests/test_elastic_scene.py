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

ROOT = Path(__file__).resolve().parents[1]

SCENE = """
kind = "pump"
title = "coarse elastic pump"
[pump]
mechanism = "{mechanism}"
compare_plain = {plain}
[run]
revolutions = 0.1
start = "steady"
mesh_size = 0.3
element = "P1"
frames = 0
[elastic]
enabled = {enabled}
[output]
pictures = {pictures}
"""


def _scene(tmp_path, enabled="true", pictures='["pressure", "film", "deflection"]', plain="true"):
    text = SCENE.format(mechanism=(ROOT / "mechanisms" / "eccentric_pump.toml").as_posix(), enabled=enabled,
                        pictures=pictures, plain=plain)
    path = tmp_path / "pump.toml"
    path.write_text(text)
    return path


def _min_column(path: Path, name: str) -> float:
    with open(path) as fh:
        return min(float(row[name]) for row in csv.DictReader(fh))


def test_elastic_pump_scene(tmp_path):
    out = tmp_path / "out"
    assert main(["run", str(_scene(tmp_path)), "--out", str(out), "--no-progress"]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"trajectory_pocket_elastic.csv", "trajectory_plain_elastic.csv", "pressure.png",
            "pressure_elastic.png", "film.png", "film_elastic.png", "deflection.png"} <= names
    res = json.loads((out / "summary.json").read_text())["results"]
    for name in ("pocket", "plain", "pocket_elastic", "plain_elastic"):
        assert res[name]["smallest_film_m"] == pytest.approx(
            _min_column(out / f"trajectory_{name}.csv", "h_min"), rel=1e-12)
    for name in ("pocket_elastic", "plain_elastic"):
        largest = _min_column(out / f"trajectory_{name}.csv", "max_deflection")  # positive everywhere
        assert 0 < largest <= res[name]["largest_deflection_m"]
    assert res["film_ratio_elastic"] == pytest.approx(
        res["pocket_elastic"]["smallest_film_m"] / res["plain_elastic"]["smallest_film_m"], rel=1e-12)
    thin = res["pocket_elastic"]["thinnest_state"]
    assert thin["film_um"] == pytest.approx(res["pocket_elastic"]["smallest_film_m"] * 1e6, rel=1e-3)
    assert 0 <= thin["beta_deg"] < 360 and thin["deflection_um"] > 1.0
    assert thin["peak_pressure_MPa"] >= thin["pressure_at_thinnest_MPa"]
    assert res["pocket"]["thinnest_state"]["deflection_um"] == 0.0


def test_quasi_static_dynamics_with_cavitation(tmp_path):
    path = _scene(tmp_path, pictures='["pressure"]', plain="false")
    text = path.read_text().replace('element = "P1"', 'element = "P1"\ncavitation = "reynolds"')
    text = text.replace("revolutions = 0.1", "revolutions = 0.03")
    path.write_text(text.replace("[elastic]\nenabled = true", '[elastic]\nenabled = true\ndynamics = "quasi-static"'))
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["elastic"]["dynamics"] == "quasi-static"
    res = summary["results"]["pocket_elastic"]
    assert 0 < res["thinnest_state"]["deflection_um"] <= res["largest_deflection_m"] * 1e6 * (1 + 1e-9)


def test_deflection_picture_needs_the_elastic_run(tmp_path):
    from bearingfe.scenes.pump import settings as pump_settings

    data, label = load_scene(_scene(tmp_path, enabled="false"))
    with pytest.raises(SceneError, match=r"\[output\] pictures: 'deflection' needs \[elastic\] enabled"):
        pump_settings(data, label, tmp_path)
    data, label = load_scene(_scene(tmp_path))
    data["run"]["cavitation"] = "reynolds"
    with pytest.raises(SceneError, match=r"\[elastic\] dynamics: 'squeeze' needs \[run\] cavitation = 'none'"):
        pump_settings(data, label, tmp_path)
    bad = tmp_path / "bad.toml"
    bad.write_text('kind = "pump"\n[elastic]\nmodel = "rubber"\n')
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


def test_pump_scene_on_the_real_shoe_body(tmp_path):
    # model = "shoe": the scene builds the machine file's shoe body (bearingfe.elastic.shoe) and runs the
    # squeeze model on it; the same run through the API gives the same smallest film (deterministic)
    import bearingfe as bf
    from bearingfe.transient import simulate_elastic
    from bearingfe.elastic.shoe import shoe_compliance

    path = _scene(tmp_path, pictures='["trajectory"]', plain="false")
    path.write_text(path.read_text().replace("[elastic]\nenabled = true", '[elastic]\nenabled = true\nmodel = "shoe"'))
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
