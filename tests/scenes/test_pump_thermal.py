"""The pump scene's ``[thermal]`` table: off by default, and when on, every design at its level-1
effective temperature (the balance is validated in tests/thermal). Consistency checks: fed where the
oil has the mechanism file's viscosity, the isothermal run of the balance is the scene's own run (to
round-off), and the heated film is thinner."""

from pathlib import Path

import pytest

from bearingfe.scenes import SCENES, SceneError, load_scene
from bearingfe.scenes.pump import settings
from tests.helpers import ROOT

OIL = {"grade": "VG 46", "kinematic_viscosity_100C": 6.8e-6}


def _data(**thermal):
    data, label = load_scene(ROOT / "scenes" / "pump.toml")
    data["pump"]["mechanism"] = str(ROOT / "mechanisms" / "eccentric_pump.toml")
    data["run"].update(mesh_size=0.3, element="P1", frames=0)
    data["output"] = {"pictures": []}
    if thermal:
        data["thermal"] = thermal
    return data, label


def test_off_by_default():
    data, label = _data()
    assert settings(data, label)["thermal"]["enabled"] is False


@pytest.mark.slow
def test_both_designs_at_their_effective_temperature(tmp_path):
    data, label = _data(enabled=True, **OIL)
    summary = SCENES["pump"](data, label, tmp_path)
    for name in ("pocket", "plain"):
        th, run = summary["thermal"][name], summary["results"][name]
        assert th["supply_viscosity_Pa_s"] == pytest.approx(0.03, rel=1e-9)   # the mechanism file's
        assert th["isothermal_smallest_film_m"] == pytest.approx(run["smallest_film_m"], rel=1e-9)
        assert th["smallest_film_m"] < th["isothermal_smallest_film_m"]
        assert th["peak_temperature_C"] > th["effective_temperature_C"] > th["supply_temperature_C"]
    assert any(row[0] == "pocket: effective film temperature (level 1)" for row in summary["table"])


@pytest.mark.parametrize("thermal, words", [
    ({"enabled": True}, "[thermal]: names no lubricant"),
    ({"enabled": True, "grade": "VG 46"}, "[thermal] kinematic_viscosity_100C: goes with grade"),
    ({"enabled": True, **OIL, "conducted_fraction": 1.0}, "[thermal] conducted_fraction: must be in [0, 1)"),
    ({"enabled": "yes"}, "[thermal] enabled: expected true or false"),
])
def test_schema_errors_name_the_field(thermal, words):
    data, label = _data(**thermal)
    with pytest.raises(SceneError) as info:
        settings(data, label)
    assert words in str(info.value)


def test_without_a_lubricant_the_mechanism_files_oil_is_used(tmp_path):
    text = (ROOT / "mechanisms" / "eccentric_pump.toml").read_text(encoding="utf-8")
    text = text.replace("viscosity = 0.03 ", "# viscosity from [oil] ")
    text += '\n[oil]\ngrade = "VG 46"\nkinematic_viscosity_100C = 6.8e-6\nsupply_temperature_C = 55.0\n'
    (tmp_path / "pump.toml").write_text(text, encoding="utf-8")
    data, label = _data(enabled=True)
    data["pump"]["mechanism"] = str(tmp_path / "pump.toml")
    th = settings(data, label)["thermal"]
    assert (th["enabled"], th["grade"], th["supply_temperature_C"]) == (True, "VG 46", 55.0)
