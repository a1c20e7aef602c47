"""The journal scene with an ``[oil]`` table: the viscosity from the level-1 heat balance.

Consistency, not new physics (the balance is validated in tests/thermal): the scene's summary must
be :func:`bearingfe.thermal.effective_temperature` of the same bearing, duty, oil and solver settings
(to round-off), its film results those of the effective viscosity, and its schema must name what is
wrong. Coarse meshes (0.2 R) keep it fast.
"""

import math

import pytest

from bearingfe.bearings.journal import JournalBearing
from bearingfe.scenes import SCENES, SceneError, load_scene
from bearingfe.scenes.journal import settings
from bearingfe.thermal import HeatBalance, JournalDuty, effective_temperature, iso_vg, kelvin
from tests.helpers import ROOT

OIL = {"grade": "VG 32", "kinematic_viscosity_100C": 5.4e-6, "density_15C": 860.0, "supply_temperature_C": 40.0}


def _data(oil=OIL, viscosity=None):
    data, label = load_scene(ROOT / "scenes" / "journal.toml")
    data["solver"].update(size=0.2, estimate_error=False)
    data["output"] = {"pictures": [], "tables": []}
    data["operating"].pop("viscosity")
    if viscosity is not None:
        data["operating"]["viscosity"] = viscosity
    if oil is not None:
        data["oil"] = dict(oil)
    return data, label


def test_oil_gives_the_effective_temperature_and_its_viscosity(tmp_path):
    data, label = _data()
    summary = SCENES["journal"](data, label, tmp_path)
    th = summary["thermal"]
    b, op = data["bearing"], data["operating"]
    duty = JournalDuty(b["diameter"] / 2, b["radial_clearance"], 2 * math.pi * op["speed"] / 60, op["load"])
    oil = iso_vg("VG 32", 5.4e-6, density=860.0)
    ref = effective_temperature(JournalBearing(b["length"] / b["diameter"]), duty, oil, HeatBalance(kelvin(40.0)),
                                size=0.2, min_size=None, cavitation="reynolds")
    assert th["effective_temperature_C"] == pytest.approx(ref.temperature - 273.15, rel=1e-12)
    assert th["temperature_rise_K"] == pytest.approx(ref.temperature_rise, rel=1e-12)
    assert th["effective_viscosity_Pa_s"] == summary["operating"]["viscosity"]
    assert th["effective_viscosity_Pa_s"] == pytest.approx(ref.viscosity, rel=1e-12)
    # the film results are those of the effective viscosity: power loss, eccentricity, film
    r = summary["results"]
    assert r["friction_power_W"] == pytest.approx(th["power_loss_W"], rel=1e-12)
    assert r["eccentricity"] == pytest.approx(ref.eccentricity, rel=1e-12)
    assert r["min_film_m"] == pytest.approx(ref.min_film, rel=1e-12)
    assert th["convected_power_W"] + th["conducted_power_W"] == pytest.approx(th["power_loss_W"], rel=1e-12)
    assert th["moved"]["min_film"] < 0 < th["moved"]["eccentricity"]
    labels = [row[0] for row in summary["table"]]
    assert {"effective temperature", "temperature rise", "effective viscosity"} <= set(labels)


def test_without_oil_nothing_changes():
    data, label = load_scene(ROOT / "scenes" / "journal.toml")
    s = settings(data, label)
    assert s["oil"] is None and s["operating"]["viscosity"] == data["operating"]["viscosity"]


@pytest.mark.parametrize("oil, viscosity, words", [
    (None, None, "[operating] viscosity: missing (required without an [oil] table)"),
    (OIL, 0.018, "[operating] viscosity: must be absent with an [oil] table"),
    ({**OIL, "vogel": [1e-4, 900.0, 150.0]}, None, "[oil]: give exactly one of grade"),
    ({k: v for k, v in OIL.items() if k != "kinematic_viscosity_100C"}, None,
     "[oil] kinematic_viscosity_100C: goes with grade"),
    ({k: v for k, v in OIL.items() if k != "supply_temperature_C"}, None, "[oil] supply_temperature_C: missing"),
    ({**OIL, "grade": "VG 33"}, None, "[oil] grade: must be one of"),
    ({**OIL, "carry_over": 1.5}, None, "[oil] carry_over: must be in [0, 1]"),
    ({"kinematic_viscosity": [[40.0, 32e-6]], "supply_temperature_C": 40.0}, None,
     "[oil] kinematic_viscosity: expected two points"),
    ({"kinematic_viscosity": [[40.0, 32e-6], [100.0, 50e-6]], "supply_temperature_C": 40.0}, None,
     "[oil] WaltherViscosity.through needs two temperatures"),
    ({"vogel": [1e-4, -900.0, 150.0], "supply_temperature_C": 40.0}, None, "[oil] VogelViscosity.b must be > 0"),
])
def test_schema_errors_name_the_field(tmp_path, oil, viscosity, words):
    data, label = _data(oil, viscosity)
    with pytest.raises(SceneError) as info:
        SCENES["journal"](data, label, tmp_path)
    assert words in str(info.value)
