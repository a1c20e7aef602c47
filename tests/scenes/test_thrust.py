"""The thrust scene: six tilting pads in SI through ``bearingfe run``, its tables and pictures, the fixed-pad
and [oil] variants, and the checks of its input.

References: the rigid isoviscous similarity of the film (the scene's curve: h_min ~ W^-1/2, power ~ W^1/2),
the sums the tables must make (pads' loads and flows add to the bearing's), the library calls the scene
stands for (the same numbers through the Python API)."""

from __future__ import annotations

import csv
import json
import math
import tomllib

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.cli import main
from bearingfe.scenes import SceneError
from bearingfe.scenes.thrust import settings
from tests.helpers import ROOT, toml_text

SHIPPED = ROOT / "scenes" / "thrust.toml"


def _coarse(**changes) -> dict:
    data = tomllib.loads(SHIPPED.read_text())
    data["solver"].update(size=0.1, element="P1")
    data["operating"].update(load_points=3)
    for table, fields in changes.items():
        data.setdefault(table, {}).update(fields)
    return data


def _run(folder, data) -> tuple:
    (folder / "s.toml").write_text(toml_text(data))
    assert main(["run", str(folder / "s.toml"), "--out", str(folder / "out"), "--no-progress"]) == 0
    return folder / "out", json.loads((folder / "out" / "summary.json").read_text())


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return _run(tmp_path_factory.mktemp("thrust"), _coarse())


def test_scene_is_the_library_call(run):
    """The scene's numbers are those of tilting_equilibrium on the same pad, mesh and scale."""
    out, summary = run
    r = summary["results"]
    pad = bf.ThrustPad(0.05, 0.1, math.radians(45), n_pads=6, pivot_offset=0.6)
    scale = bf.Scale(0.1, 20e-6, 0.03, 2 * math.pi * 3000 / 60)
    perf = bf.tilting_equilibrium(pad, pad.mesh(0.1), scale, 20e3, cavitation="reynolds")
    assert r["load_N"] == pytest.approx(20e3, rel=1e-8)
    assert r["h_min_um"] == pytest.approx(perf.h_min * 1e6, rel=1e-9)
    assert r["power_W"] == pytest.approx(perf.power, rel=1e-9)
    assert sorted(summary["files"]) == sorted(["pressure.png", "film.png", "curve.png", "pads.csv", "curve.csv",
                                               "summary.json"])


def test_pad_table_adds_up_to_the_bearing(run):
    """pads.csv has one row per pad; their loads, power and flows add up to the bearing's."""
    out, summary = run
    rows = list(csv.DictReader((out / "pads.csv").open()))
    assert len(rows) == 6
    r = summary["results"]
    for column in ("load_N", "power_W", "leading_flow_l_min", "outer_flow_l_min"):
        assert sum(float(row[column]) for row in rows) == pytest.approx(r[column], rel=1e-12)
    assert [float(row["leading_edge_deg"]) for row in rows] == pytest.approx([0, 60, 120, 180, 240, 300])


def test_curve_follows_the_film_similarity(run):
    """Rigid isoviscous pads: h_min W^(1/2) and power W^(-1/2) are the same at every load of the curve."""
    out, _ = run
    cols = {k: np.array([float(r[k]) for r in csv.DictReader((out / "curve.csv").open())])
            for k in ("load_N", "h_min_um", "power_W")}
    assert cols["load_N"] == pytest.approx([5e3, 22.5e3, 40e3])
    np.testing.assert_allclose(cols["h_min_um"] * np.sqrt(cols["load_N"]),
                               cols["h_min_um"][0] * math.sqrt(5e3), rtol=1e-6)
    np.testing.assert_allclose(cols["power_W"] / np.sqrt(cols["load_N"]), cols["power_W"][0] / math.sqrt(5e3),
                               rtol=1e-6)


def test_fixed_pads_and_the_oil_table(tmp_path):
    """Fixed taper-land pads carry the load on the film Newton finds; with [oil] the film runs at the
    effective temperature of the heat balance, hotter and thinner than at the supply temperature."""
    data = _coarse(pads=dict(pivot="fixed", pivot_offset=0.5, profile=[[0.0, 20e-6], [0.7, 0.0], [1.0, 0.0]]))
    del data["operating"]["viscosity"]
    data["oil"] = dict(grade="VG 46", kinematic_viscosity_100C=6.8e-6, supply_temperature_C=45.0)
    _, summary = _run(tmp_path, data)
    r, th = summary["results"], summary["thermal"]
    assert r["load_N"] == pytest.approx(20e3, rel=1e-8)
    assert r["pitch_urad"] == 0.0 and r["roll_urad"] == 0.0
    assert th["effective_temperature_C"] > 45.0
    assert r["h_min_um"] < th["isothermal_min_film_um"]


@pytest.mark.parametrize("change, message", [
    (dict(pads=dict(angle_deg=70.0)), "angle_deg"),
    (dict(pads=dict(outer_diameter=0.05)), "outer_diameter"),
    (dict(pads=dict(pitch_urad=100.0)), "pitch_urad"),
    (dict(operating=dict(load_range=[4e4, 5e3])), "load_range"),
    (dict(solver=dict(cavitation="gumbel")), "cavitation"),
])
def test_bad_scene_files_are_named(change, message):
    with pytest.raises(SceneError, match=message):
        settings(_coarse(**change), "t.toml")


def test_viscosity_or_oil_exactly_one():
    data = _coarse()
    data["oil"] = dict(grade="VG 46", kinematic_viscosity_100C=6.8e-6, supply_temperature_C=45.0)
    with pytest.raises(SceneError, match="viscosity"):
        settings(data, "t.toml")
