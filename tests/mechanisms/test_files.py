"""load_mechanism: shipped files load, schema errors name file and field."""

import pytest

from bearingfe.mechanisms.machines import CrankMechanism, MillDrive, RotorFrame
from bearingfe.mechanisms.files import LOADERS, load_mechanism
from tests.helpers import ROOT

MECH = ROOT / "mechanisms"

SNT32 = (MECH / "snt32.toml").read_text(encoding="utf-8")


def _write(tmp_path, text, name="snt32.toml"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_shipped_files_load_into_frozen_objects():
    snt = load_mechanism(MECH / "snt32.toml")
    assert isinstance(snt, CrankMechanism)
    # paper 000 Table 3 values, as stored
    assert (snt.linkage.crank, snt.linkage.rod, snt.cylinders, snt.plunger_diameter) == (0.0188, 0.288, 3, 0.045)
    assert snt.drive.rpm == pytest.approx(588.0, rel=1e-12)
    d816 = load_mechanism(MECH / "converter_tilt_d816.toml")
    assert isinstance(d816, RotorFrame)
    assert (d816.rotor.mass, d816.plate_mass, d816.section.name) == (1670.0, 10920.0, "20a")
    assert len(d816.sections) == 6
    mill = load_mechanism(MECH / "hpt_mill.toml")
    assert isinstance(mill, MillDrive)
    with pytest.raises(AttributeError):
        snt.name = "x"  # frozen


def test_loaders_table_has_the_three_kinds():
    assert set(LOADERS) >= {"crank_slider", "rotor_frame", "linkage"}


@pytest.mark.parametrize(
    "old, new, message",
    [
        ("rod = 0.288 ", "", r"snt32.toml: \[crank\] rod: missing"),
        ("rod = 0.288 ", 'rod = "long" ', r"snt32.toml: \[crank\] rod: expected a finite number"),
        ("rod = 0.288 ", "rod = 0.01 ", r"snt32.toml: \[crank\] rod must be longer than crank"),
        ("slider = 15.29", "slider = -1.0", r"snt32.toml: \[crank\] slider_mass must be >= 0"),
        ('kind = "crank_slider"', 'kind = "turbine"', r"snt32.toml: kind: must be one of"),
        ('kind = "crank_slider"', "", r"snt32.toml: kind: missing"),
        ("speed_rpm = 588", "speed_rpm = 0", r"snt32.toml: \[drive\] speed_rpm must be > 0"),
        ("speed_rpm = 588", "", r"snt32.toml: \[drive\] speed_rpm/omega: give exactly one"),
        ("cylinders = 3 ", "cylinders = 2.5 ", r"snt32.toml: \[pump\] cylinders: expected an integer"),
        ("[crank]", "[crank_]", r"snt32.toml: \[crank\]: missing table"),
    ],
)
def test_schema_errors_name_file_and_field(tmp_path, old, new, message):
    assert old in SNT32
    with pytest.raises(ValueError, match=message):
        load_mechanism(_write(tmp_path, SNT32.replace(old, new, 1)))


def test_rotor_frame_errors(tmp_path):
    text = (MECH / "converter_tilt_d816.toml").read_text(encoding="utf-8")
    with pytest.raises(ValueError, match=r"d816.toml: \[frame\] section: section must be one of"):
        load_mechanism(_write(tmp_path, text.replace('section = "20a"', 'section = "19"'), "d816.toml"))
    with pytest.raises(ValueError, match=r"d816.toml: \[rotor.material\] youngs_modulus: missing"):
        load_mechanism(_write(tmp_path, text.replace("youngs_modulus = 2.1e11", ""), "d816.toml"))
    with pytest.raises(ValueError, match=r"d816.toml: \[frame\] axis must be 'x' or 'y'"):
        load_mechanism(_write(tmp_path, text.replace('axis = "x"', 'axis = "z"'), "d816.toml"))


def test_linkage_errors(tmp_path):
    text = (MECH / "hpt_mill.toml").read_text(encoding="utf-8")
    with pytest.raises(ValueError, match=r"mill.toml: \[linkage\] pin_friction: expected 3 numbers"):
        load_mechanism(_write(tmp_path, text.replace("pin_friction = [0.05, 0.05, 0.05]", "pin_friction = [0.05]"), "mill.toml"))
    with pytest.raises(ValueError, match=r"mill.toml: not valid TOML"):
        load_mechanism(_write(tmp_path, "kind = ", "mill.toml"))
