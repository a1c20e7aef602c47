"""The one input-file schema (bearingfe.core.schema): every file kind gives the same error form.

Each row below edits a valid file (a shipped scene through the ``scene_file`` fixture, a shipped
mechanism file, a small study) into a bad one and names the fragment its error must contain:
``<file>: [<table>] <field>: <what is wrong>`` with the allowed range or choices. The expected
texts are the documented error form of :mod:`bearingfe.core.schema` (module docstring), not output
copied from a run.
"""

import math

import pytest

from bearingfe.mechanisms.files import load_mechanism
from bearingfe.scenes.journal import settings as journal_settings
from bearingfe.scenes.pump import settings as pump_settings
from bearingfe.scenes import SceneError, load_scene
from bearingfe.scenes.reynolds import settings as reynolds_settings
from bearingfe.core.schema import (REQUIRED, Range, SchemaError, Table, Tables, choice, finite, in_range, integer,
                              nonnegative, number, one_of, positive, read_table)
from bearingfe.sweep import read_study
from tests.helpers import ROOT

STUDY = """[study]
run = "shoe"
outputs = ["h_min", "load"]
[base.set]
mesh_size = 0.2
[grid]
pocket_fraction = [0.0, 0.08]
"""


def _edit(text: str, old: str, new: str) -> str:
    assert old in text, old  # the row edits something that is there
    return text.replace(old, new, 1)


def _scene_error(path, settings) -> str:
    with pytest.raises(SceneError) as info:
        data, label = load_scene(path)
        settings(data, label)
    return str(info.value)


@pytest.mark.parametrize("change, fragment", [
    (dict(surface={"inlets": {0: {"radius": -0.16}}}), "bad.toml: [surface.inlets.0] radius: must be > 0; got -0.16"),
    (dict(surface={"inlets": {0: {"shape": None}}}),
     "bad.toml: [surface.inlets.0] shape: missing (required); allowed: 'circle', "),
    (dict(film={"gamma": -0.6}), "bad.toml: [film] gamma: must be >= 0; got -0.6"),
    (dict(film={"gamma": "big"}), "bad.toml: [film] gamma: expected a finite number; got 'big'"),
    (dict(film={"gamma": math.nan}), "bad.toml: [film] gamma: expected a finite number; got nan"),
    (dict(solver={"element": "P9"}), "bad.toml: [solver] element: must be one of 'P1', 'P2'; got 'P9'"),
    (dict(solver={"formulation": "x"}), "bad.toml: [solver] formulation: must be one of 'pi', 'direct'"),
    (dict(solver={"linear_solver": "magic"}), "bad.toml: [solver] linear_solver: must be one of 'splu'"),
    (dict(solver={"size": None, "sise": 0.1}),
     "bad.toml: [solver] sise: unknown field; allowed: size, inlet_size, element"),
    (dict(film=None, flim={"gamma": 0.6}),
     "bad.toml: flim: unknown table or field; allowed: kind, title, surface, film, operating, solver, output, scale "
     "(and bad.toml: [film]: missing table (required): a misspelling?)"),
    (dict(surface={"half_width": [0.4]}), "bad.toml: [surface] half_width: expected a finite number; got [0.4]"),
    (dict(surface={"arc": [-0.5]}), "bad.toml: [surface] arc: expected a pair of numbers [x, y]; got [-0.5]"),
    (dict(title=3), "bad.toml: title: expected a string; got 3"),
])
def test_reynolds_scene_errors(scene_file, change, fragment):
    assert fragment in _scene_error(scene_file("reynolds", change, name="bad.toml"), reynolds_settings)


@pytest.mark.parametrize("change, fragment", [
    (dict(run={"revolutions": 0}), "bad.toml: [run] revolutions: must be > 0; got 0"),
    (dict(run={"frames": 2.5}), "bad.toml: [run] frames: expected an integer; got 2.5"),
    (dict(run={"frames": -1}), "bad.toml: [run] frames: must be an integer >= 0; got -1"),
    (dict(run={"cavitation": "jfo7"}), "bad.toml: [run] cavitation: must be one of 'none', "),
    (dict(run={"element": "P3"}), "bad.toml: [run] element: must be one of 'P1', 'P2'; got 'P3'"),
    (dict(run={"start": "cold"}), "bad.toml: [run] start: must be one of 'periodic', 'steady'"),
    (dict(pump={"compare_plain": 1}), "bad.toml: [pump] compare_plain: expected true or false; got 1"),
    (dict(run=None, runs={"revolutions": 1.0}),
     "bad.toml: runs: unknown table or field; allowed: kind, title, pump, run, elastic, limits, output"),
])
def test_pump_scene_errors(tmp_path, scene_file, change, fragment):
    path = scene_file("pump", change, name="bad.toml")
    assert fragment in _scene_error(path, lambda d, l: pump_settings(d, l, tmp_path))


def test_pump_scene_cavitation_choices_come_from_the_solver():
    from bearingfe.reynolds import CAVITATION
    from bearingfe.scenes.pump import SPEC as PUMP

    check = PUMP["run"].spec["cavitation"][0]
    assert all(check("w", name) == name for name in CAVITATION)  # every model the solver has, no copy


@pytest.mark.parametrize("change, fragment", [
    (dict(bearing={"diameter": 0}), "bad.toml: [bearing] diameter: must be > 0; got 0"),
    (dict(solver={"size": 0}), "bad.toml: [solver] size: must be in (0, 1]; got 0"),
    (dict(solver={"cavitation": "gumbel"}),
     "bad.toml: [solver] cavitation: must be one of 'reynolds', 'none', 'jfo'; got 'gumbel'"),
    (dict(bearing={"pads": [[0.0, 180.0]], "grooves": [{"angle_deg": 90.0}]}),
     "bad.toml: [bearing.grooves.0] width_deg: missing (required)"),
    (dict(bearing={"pads": [[0.0, 180.0]], "grooves": 3}),
     "bad.toml: [bearing] grooves: expected an array of tables [[bearing.grooves]]; got 3"),
    (dict(operating={"speed": None}), "bad.toml: [operating] speed: give exactly one of speed [rpm] and "
                                      "speed_rad_s [rad/s]; got speed = None, speed_rad_s = None"),
])
def test_journal_scene_errors(scene_file, change, fragment):
    assert fragment in _scene_error(scene_file("journal", change, name="bad.toml"), journal_settings)


def _mechanism_error(tmp_path, name: str, old: str, new: str) -> str:
    path = tmp_path / name
    path.write_text(_edit((ROOT / "mechanisms" / name).read_text(encoding="utf-8"), old, new), encoding="utf-8")
    with pytest.raises(SchemaError) as info:
        load_mechanism(path)
    return str(info.value)


@pytest.mark.parametrize("name, old, new, fragment", [
    ("snt32.toml", "rod = 0.288 ", "rod = 0.288\nrod_length = 1.0\n",
     "snt32.toml: [crank] rod_length: unknown field; allowed: crank, rod, rod_cg_from_crank_pin"),
    ("snt32.toml", "cylinders = 3 ", "cylinders = 0 ", "snt32.toml: [pump] cylinders must be an integer >= 1"),
    ("snt32.toml", "speed_rpm = 588", "speed_rpm = 588\nomega = 61.6",
     "snt32.toml: [drive] speed_rpm/omega: give exactly one"),
    ("snt32.toml", 'name = "SNT-32 three-plunger pump"', "name = 32", "snt32.toml: name: expected a string; got 32"),
    ("eccentric_pump.toml", "radius = 0.1748", "radius = -0.1748",
     "eccentric_pump.toml: [surface.inlets.0] radius: must be > 0; got -0.1748"),
    ("eccentric_pump.toml", "arc = [-0.6, 0.6]", "", "eccentric_pump.toml: [surface] arc: missing (required)"),
    ("eccentric_pump.toml", "clearance = 20e-6", "clearance = -20e-6",
     "eccentric_pump.toml: [eccentric] EccentricPump.clearance must be > 0, got -2e-05"),
    ("eccentric_pump.toml", "preload = 200.0", "preload = -1.0",
     "eccentric_pump.toml: [eccentric] EccentricPump.preload must be >= 0 N, got -1.0"),
    ("converter_tilt_d816.toml", "height = 0.7 ", 'height = "tall" ',
     "converter_tilt_d816.toml: [frame] height: expected a finite number; got 'tall'"),
    ("converter_tilt_d816.toml", "height_range = [0.1, 2.0]", "height_range = [0.1]",
     "converter_tilt_d816.toml: [frame] height_range: expected [lo, hi] in m; got [0.1]"),
    ("hpt_mill.toml", "guide_friction = 0.08", "guide_friction = 1.5",
     "hpt_mill.toml: [linkage] guide_friction must be in [0, 1)"),
])
def test_mechanism_file_errors(tmp_path, name, old, new, fragment):
    assert fragment in _mechanism_error(tmp_path, name, old, new)


def test_missing_files_are_named(tmp_path):
    with pytest.raises(SchemaError, match="mechanism file not found: .*nowhere.toml"):
        load_mechanism(tmp_path / "nowhere.toml")
    with pytest.raises(SchemaError, match="study file not found: .*nowhere.toml"):
        read_study(tmp_path / "nowhere.toml")
    with pytest.raises(SchemaError, match="scene file not found: .*nowhere.toml"):
        load_scene(tmp_path / "nowhere.toml")


@pytest.mark.parametrize("old, new, fragment", [
    ('run = "shoe"', 'run = "turbine"', "s.toml: [study] run: must be one of 'shoe', 'pump'; got 'turbine'"),
    ('outputs = ["h_min", "load"]', "outputs = []", "s.toml: [study] outputs: expected a non-empty list drawn from"),
    ('outputs = ["h_min", "load"]', 'outputs = ["h_min", "load"]\nobjective = "flow"',
     "s.toml: [study] objective: must be one of 'h_min', 'load'; got 'flow'"),
    ('outputs = ["h_min", "load"]', 'outputs = ["h_min", "load"]\nsense = "best"',
     "s.toml: [study] sense: must be one of 'max', 'min'; got 'best'"),
    ("[base.set]", '[base]\nkind = "rotor"\n[base.set]', "s.toml: [base] kind: must be one of 'shoe', 'pump'"),
    ("mesh_size = 0.2", "mesh_size = -0.2", "s.toml: [base.set] mesh_size: ShoeCase.mesh_size must be"),
    ("[study]", "[studies]", "s.toml: studies: unknown table or field; allowed: study, base, grid, cases"),
])
def test_study_file_errors(tmp_path, old, new, fragment):
    path = tmp_path / "s.toml"
    path.write_text(_edit(STUDY, old, new))
    with pytest.raises(SchemaError) as info:
        read_study(path)
    assert fragment in str(info.value)


# -- the pieces of the schema -----------------------------------------------------------------

@pytest.mark.parametrize("allowed, text, inside, outside", [
    (Range(0.0, lo_open=True), "> 0", 1e-300, 0.0),
    (Range(0.0), ">= 0", 0.0, -1e-300),
    (Range(None, 1.0, hi_open=True), "< 1", 0.999, 1.0),
    (Range(0.0, 1.0, lo_open=True), "in (0, 1]", 1.0, 0.0),
    (Range(0.0, math.pi, hi_open=True), "in [0, 3.14159)", 0.0, math.pi),
])
def test_range_text_and_membership(allowed, text, inside, outside):
    assert str(allowed) == text
    assert inside in allowed and outside not in allowed


@pytest.mark.parametrize("call, message", [
    (lambda: positive("Drive.omega", 0.0, "rad/s"), "Drive.omega must be > 0 rad/s, got 0.0"),
    (lambda: positive("x", math.inf), "x must be a finite number, got inf"),
    (lambda: positive("x", True), "x must be a finite number, got True"),
    (lambda: nonnegative("load", -1, "N"), "load must be >= 0 N, got -1"),
    (lambda: in_range("eps", 1.0, Range(0.0, 1.0, hi_open=True)), "eps must be in [0, 1), got 1.0"),
    (lambda: one_of("element", "P3", ("P1", "P2")), "element must be one of 'P1', 'P2', got 'P3'"),
    (lambda: finite("gamma", "0.5"), "gamma must be a finite number, got '0.5'"),
])
def test_value_checks_name_the_parameter_and_range(call, message):
    with pytest.raises(ValueError) as info:
        call()
    assert str(info.value) == message


def test_value_checks_return_floats():
    import numpy as np

    assert positive("x", 2) == 2.0 and type(positive("x", np.float32(0.5))) is float
    assert finite("x", np.int64(3)) == 3.0


def test_read_table_defaults_nested_tables_and_lazy_choices():
    names = ["a"]
    spec = {"n": (integer(), 2), "x": (number(Range(0.0)), REQUIRED), "mode": (choice(lambda: names), "a"),
            "sub": Table({"y": (number(), 1.5)}), "items": Tables({"z": (number(), REQUIRED)})}
    out = read_table({"x": 1, "items": [{"z": 3}]}, "f.toml", "", spec)
    assert out == {"n": 2, "x": 1.0, "mode": "a", "sub": {"y": 1.5}, "items": ({"z": 3.0},)}
    names.append("b")  # a choice added to the owning list later is accepted without touching the spec
    assert read_table({"x": 0, "mode": "b"}, "f.toml", "t", spec)["mode"] == "b"
    with pytest.raises(SchemaError, match=r"^f.toml: \[t.items.1\] z: missing \(required\)$"):
        read_table({"x": 0, "items": [{"z": 1}, {}]}, "f.toml", "t", spec)
    with pytest.raises(SchemaError, match=r"^f.toml: \[t.sub\]: expected a table; got 3$"):
        read_table({"x": 0, "sub": 3}, "f.toml", "t", spec)


def test_old_field_reader_still_works_and_names_its_replacement():
    from bearingfe.mechanisms.files import field

    with pytest.warns(DeprecationWarning, match="bearingfe.core.schema.read_table"):
        assert field({"rod": 2}, "crank", "rod", "m.toml") == 2.0
    with pytest.warns(DeprecationWarning), pytest.raises(SchemaError, match=r"^m.toml: \[crank\] rod: missing"):
        field({}, "crank", "rod", "m.toml")


def test_limits_table_and_verdicts():
    from bearingfe.core.schema import LIMITS, LIMITS_TABLE, SchemaError, check_limits, read_table

    # every limit has its SI unit and is optional: an empty [limits] checks nothing
    assert {n: (l.unit, l.relation) for n, l in LIMITS.items()} == {
        "min_film": ("m", ">="), "max_pressure": ("Pa", "<="), "max_friction_power": ("W", "<="),
        "max_leakage": ("m^3/s", "<=")}
    empty = read_table({}, "s.toml", "limits", LIMITS_TABLE.spec)
    assert empty == dict.fromkeys(LIMITS) and check_limits({}, empty) == {}
    with pytest.raises(SchemaError, match=r"^s\.toml: \[limits\] max_pressure: must be > 0; got 0"):
        read_table({"max_pressure": 0}, "s.toml", "limits", LIMITS_TABLE.spec)
    # a film of 9.9 um against 8 um (kept), a peak of 32 MPa against 30 MPa (exceeded); equality passes
    values = {"min_film": 9.9e-6, "max_pressure": 32e6, "max_friction_power": 280.0, "max_leakage": 5e-7}
    verdicts = check_limits(values, {"min_film": 8e-6, "max_pressure": 30e6, "max_friction_power": 280.0,
                                     "max_leakage": None})
    assert {k: v["ok"] for k, v in verdicts.items()} == {"min_film": True, "max_pressure": False,
                                                        "max_friction_power": True}
    assert verdicts["max_pressure"] == {"quantity": "peak pressure", "value": 32e6, "limit": 30e6, "unit": "Pa",
                                        "relation": "<=", "ok": False}
