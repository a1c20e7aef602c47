"""The ``[oil]`` table of machine files: checked like the scenes', and the film's viscosity from it.

Expected values: the shipped pump's [shoe] viscosity is 0.03 Pa s; with an [oil] table instead, the viscosity is
the lubricant's own at the supply temperature (Lubricant.viscosity, tested in tests/thermal/test_lubricant.py),
so the two must agree to round-off.
"""

import pytest

from bearingfe.core.schema import SchemaError
from bearingfe.mechanisms.files import load_mechanism, mechanism_oil
from bearingfe.thermal import iso_vg, kelvin
from tests.helpers import ROOT

PUMP = (ROOT / "mechanisms" / "eccentric_pump.toml").read_text(encoding="utf-8")
OIL = """
[oil]
grade = "VG 46"
kinematic_viscosity_100C = 6.8e-6
density_15C = 870.0
supply_temperature_C = 50.0
"""


def _write(tmp_path, text):
    p = tmp_path / "pump.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _without_viscosity(text):
    lines = [line for line in text.splitlines() if not line.startswith("viscosity = ")]
    assert len(lines) == len(text.splitlines()) - 1
    return "\n".join(lines) + "\n"


def test_oil_table_gives_the_film_viscosity(tmp_path):
    path = _write(tmp_path, _without_viscosity(PUMP) + OIL)
    pump = load_mechanism(path)
    expected = iso_vg("VG 46", 6.8e-6, density=870.0).viscosity(kelvin(50.0))
    assert pump.viscosity == pytest.approx(expected, rel=1e-14)
    oil = mechanism_oil(path)
    assert oil["grade"] == "VG 46" and oil["supply_temperature_C"] == 50.0


def test_shipped_pump_has_no_oil_table():
    assert mechanism_oil(ROOT / "mechanisms" / "eccentric_pump.toml") is None
    assert load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml").viscosity == 0.03


@pytest.mark.parametrize("text, message", [
    (PUMP + OIL, r"\[shoe\] viscosity: must be absent with an \[oil\] table"),
    (_without_viscosity(PUMP), r"\[shoe\] viscosity: missing \(required without an \[oil\] table\)"),
    (_without_viscosity(PUMP) + OIL.replace("supply_temperature_C = 50.0", ""),
     r"\[oil\] supply_temperature_C: missing"),
    (_without_viscosity(PUMP) + OIL.replace('grade = "VG 46"', 'grade = "VG 47"'), r"\[oil\] grade"),
    (_without_viscosity(PUMP) + OIL.replace("density_15C", "densty_15C"), r"densty_15C"),
    (_without_viscosity(PUMP) + OIL + "vogel = [1e-4, 900.0, 150.0]\n", r"give exactly one of"),
])
def test_oil_table_errors_name_file_and_field(tmp_path, text, message):
    path = _write(tmp_path, text)
    with pytest.raises(SchemaError, match=message) as info:
        load_mechanism(path)
    assert "pump.toml" in str(info.value)


def test_grade_with_a_viscosity_index(tmp_path):
    # the 100 degC viscosity of VG 46 (46 mm^2/s at 40 degC) and VI 100 by ASTM D2270 (tests/thermal/
    # test_viscosity_index.py), then the same Walther oil as through that viscosity
    from bearingfe.thermal import viscosity_100

    text = _without_viscosity(PUMP) + OIL.replace("kinematic_viscosity_100C = 6.8e-6", "viscosity_index = 100")
    pump = load_mechanism(_write(tmp_path, text))
    nu100 = viscosity_100(46e-6, 100.0)
    assert 6.7e-6 < nu100 < 6.9e-6  # VG 46 mineral oils of VI ~100 list 6.8 mm^2/s
    assert pump.viscosity == pytest.approx(iso_vg("VG 46", nu100, density=870.0).viscosity(kelvin(50.0)), rel=1e-14)
    both = text.replace("viscosity_index = 100", "viscosity_index = 100\nkinematic_viscosity_100C = 6.8e-6")
    with pytest.raises(SchemaError, match="viscosity_index: give it or kinematic_viscosity_100C, not both"):
        load_mechanism(_write(tmp_path, both))
