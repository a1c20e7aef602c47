"""The journal scene with [tilting_pad]: a five-pad bearing in SI through ``bearingfe run``, its tables,
pictures, stability map and ROSS bearing files, and the checks of its input."""

from __future__ import annotations

import csv
import json
import math
import tomllib

import numpy as np
import pytest

from bearingfe.cli import main
from bearingfe.io.writers import ROSS_COEFFICIENTS, read_ross_bearing, write_ross3_bearing, write_ross_bearings
from bearingfe.scenes.journal import settings
from tests.helpers import ROOT, toml_text

SHIPPED = ROOT / "scenes" / "journal_tilting.toml"
#: The keywords of ``ross.BearingElement.__init__`` (ROSS 2.4, ross/bearing_seal_element.py), written out:
#: ``BearingElement.load`` passes a file's keys that are among them, and any other as an extra keyword.
ROSS_KEYWORDS = {"n", "kxx", "cxx", "mxx", "kyy", "kxy", "kyx", "cyy", "cxy", "cyx", "myy", "mxy", "myx", "kzz",
                 "czz", "mzz", "frequency", "tag", "n_link", "scale_factor", "color"}


def _coarse() -> dict:
    data = tomllib.loads(SHIPPED.read_text())
    data["solver"]["size"] = 0.2
    data["tilting_pad"].update(stability_points=3, stability_speeds=[3000.0, 9000.0], frequency_ratios=[1.0, 2.0])
    return data


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("tilting")
    (folder / "s.toml").write_text(toml_text(_coarse()))
    assert main(["run", str(folder / "s.toml"), "--out", str(folder / "out"), "--no-progress"]) == 0
    return folder / "out", json.loads((folder / "out" / "summary.json").read_text())


def test_pads_carry_the_load_through_their_pivots(run):
    """A free pad has no moment about its pivot, so its film force acts along the pivot line n_i: the pad
    loads along their pivot lines add up to the applied load, (0, -3924) N (force balance, to the
    equilibrium's tolerance); each rotation is q C_p / R_piv."""
    _, summary = run
    pads = summary["results"]["pads"]
    assert len(pads) == 5
    total = sum(p["load_N"] * np.array([math.cos(math.radians(p["pivot_deg"])),
                                        math.sin(math.radians(p["pivot_deg"]))]) for p in pads)
    np.testing.assert_allclose(total, [0.0, -3924.0], atol=1e-5 * 3924.0)
    # load between pads: the pads lie symmetrically about the load line, so do their loads and rotations
    by_angle = {round((p["pivot_deg"] + 90.0) % 360.0, 6): p for p in pads}
    for angle, pad in by_angle.items():
        twin = by_angle[round((360.0 - angle) % 360.0, 6)]
        assert pad["load_N"] == pytest.approx(twin["load_N"], rel=1e-6)
    assert summary["results"]["attitude_deg"] == pytest.approx(0.0, abs=1e-4)  # the symmetry again


def test_coefficient_table_ross_files_and_the_summary_agree(run):
    """The synchronous coefficients of the summary, the row of coefficients.csv at Omega/omega = 1 and the
    ROSS file of the operating speed at that frequency come from two code paths (the reduction at the
    operating point; the table over speed and frequency): they must agree to round-off."""
    out, summary = run
    K = np.array(summary["coefficients"]["K_N_per_m"])
    C = np.array(summary["coefficients"]["C_Ns_per_m"])
    with open(out / "coefficients.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [float(r["frequency_ratio [-]"]) for r in rows] == [1.0, 2.0]
    assert float(rows[0]["kyy [N/m]"]) == pytest.approx(K[1, 1], rel=1e-12)
    assert float(rows[0]["cxy [N s/m]"]) == pytest.approx(C[0, 1], rel=1e-12, abs=1e-12 * abs(C).max())
    files = sorted(out.glob("tilting_pad_*rpm.toml"))
    assert [f.name for f in files] == ["tilting_pad_3000rpm.toml", "tilting_pad_6000rpm.toml",
                                       "tilting_pad_9000rpm.toml"]
    ross = read_ross_bearing(out / "tilting_pad_6000rpm.toml")
    assert set(ross) - ROSS_KEYWORDS == {"speed"}  # an extra keyword ROSS's load passes on and ignores
    omega = 6000 * math.pi / 30
    np.testing.assert_allclose(ross["frequency"], [omega, 2 * omega], rtol=1e-15)
    assert ross["speed"] == pytest.approx(omega, rel=1e-15)
    for name, (i, j) in (("kxx", (0, 0)), ("kyy", (1, 1)), ("cxx", (0, 0)), ("cyy", (1, 1))):
        assert ross[name][0] == pytest.approx((K if name[0] == "k" else C)[i, j], rel=1e-9)
    # the ROSS 3.x file: the whole table, speeds 3000, 6000, 9000 rpm by whirl frequencies 1 and 2 omega
    ross3 = read_ross_bearing(out / "tilting_pad_ross3.toml")
    np.testing.assert_allclose(ross3["speed"], np.array([3000.0, 6000.0, 9000.0]) * math.pi / 30, rtol=1e-15)
    np.testing.assert_array_equal(ross3["frequency"], ross["frequency"])
    for name in ROSS_COEFFICIENTS:
        np.testing.assert_array_equal(ross3[name][1], ross[name])  # the 6000 rpm row is the 2.x file
    assert {"coefficients.csv", "stability.csv", "pressure.png", "stability.png",
            "tilting_pad_ross3.toml"} <= set(summary["files"])
    assert (out / "pressure.png").stat().st_size > 20000 and (out / "stability.png").stat().st_size > 10000


def test_stability_map_of_the_rigid_rotor(run):
    """Tilting pads without pivot friction have (almost) no cross-coupled stiffness: the rigid rotor is
    stable over the whole map (Lund; examples/05_tilting_pad.py finds the same), the decrement positive."""
    out, summary = run
    st = summary["stability"]
    assert st["speed_rpm"] == pytest.approx([3000.0, 6000.0, 9000.0])
    assert st["threshold_rpm"] is None and min(st["log_decrement"]) > 0.1
    assert st["rotor_mass_kg"] == 800.0
    with open(out / "stability.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [float(r["log_decrement [-]"]) for r in rows] == pytest.approx(st["log_decrement"], rel=1e-12)
    # a higher speed lifts the shaft: the eccentricity falls with speed under the same load
    eps = [float(r["eccentricity [-]"]) for r in rows]
    assert eps[0] > eps[1] > eps[2]


def test_ross_files_read_back(tmp_path):
    """Two speeds x three frequencies written and read back exactly (repr of every float)."""
    rng = np.random.default_rng(1)
    table = {"speed": [300.0, 600.0], "frequency": [100.0, 300.0, 600.0],
             **{k: rng.normal(size=(2, 3)) * 1e8 for k in ROSS_COEFFICIENTS}}
    paths = write_ross_bearings(table, tmp_path, n=3, tag="brg")
    assert [p.name for p in paths] == ["brg_2864p79rpm.toml", "brg_5729p58rpm.toml"]
    for i, path in enumerate(paths):
        back = read_ross_bearing(path)
        assert back["n"] == 3 and back["tag"] == path.stem and back["speed"] == table["speed"][i]
        for k in ROSS_COEFFICIENTS:
            np.testing.assert_array_equal(back[k], table[k][i])
        assert next(iter(tomllib.loads(path.read_text()))) == f"BearingElement_{path.stem}"
    with pytest.raises(ValueError, match="shape"):
        write_ross_bearings({**table, "kxx": [[1.0]]}, tmp_path)
    with pytest.raises(ValueError, match="tag"):
        write_ross_bearings(table, tmp_path, tag="a b")
    with pytest.raises(ValueError, match="finite"):
        write_ross_bearings({**table, "cyy": np.full((2, 3), np.inf)}, tmp_path)


def test_ross3_file_reads_back(tmp_path):
    """One ROSS 3.x file over two speeds x three frequencies: the layout ROSS 3.1.0's
    ``BearingElement.save`` writes for a 2-D table (its keys, sorted; one section
    ``BearingElement_<tag>``; every coefficient (speeds, frequencies)), read back exactly. (That ROSS 3.1
    itself loads it and evaluates the same coefficients: benchmarks/tilting_pad_ross3.py.)"""
    rng = np.random.default_rng(2)
    table = {"speed": [300.0, 600.0], "frequency": [100.0, 300.0, 600.0],
             **{k: rng.normal(size=(2, 3)) * 1e8 for k in ROSS_COEFFICIENTS}}
    path = write_ross3_bearing(table, tmp_path / "brg.toml", n=3, tag="brg")
    data = tomllib.loads(path.read_text())
    assert list(data) == ["BearingElement_brg"]
    ross31_keys = ["color", "cxx", "cxy", "cyx", "cyy", "czz", "frequency", "interpolation", "kxx", "kxy", "kyx",
                   "kyy", "kzz", "mxx", "mxy", "myx", "myy", "mzz", "n", "scale_factor", "speed", "tag"]
    assert list(data["BearingElement_brg"]) == ross31_keys
    back = read_ross_bearing(path)
    assert back["n"] == 3 and back["tag"] == "brg" and back["interpolation"] == "pchip" and back["scale_factor"] == 1
    np.testing.assert_array_equal(back["speed"], table["speed"])
    np.testing.assert_array_equal(back["frequency"], table["frequency"])
    for k in ROSS_COEFFICIENTS:
        np.testing.assert_array_equal(back[k], table[k])
    for k in ("kzz", "czz", "mxx", "mxy", "myx", "myy", "mzz"):
        np.testing.assert_array_equal(back[k], np.zeros((2, 3)))
    with pytest.raises(ValueError, match="shape"):
        write_ross3_bearing({**table, "kxx": [[1.0]]}, tmp_path / "a.toml")
    with pytest.raises(ValueError, match="increasing"):
        write_ross3_bearing({**table, "speed": [600.0, 300.0]}, tmp_path / "a.toml")
    with pytest.raises(ValueError, match="interpolation"):
        write_ross3_bearing(table, tmp_path / "a.toml", interpolation="cubic")
    with pytest.raises(ValueError, match="finite"):
        write_ross3_bearing({**table, "cyy": np.full((2, 3), np.nan)}, tmp_path / "a.toml")


@pytest.mark.parametrize("change, message", [
    (lambda d: d["bearing"].update(pads=[[0.0, 100.0]]), r"\[bearing\] pads: must be absent with \[tilting_pad\]"),
    (lambda d: d["operating"].update(load_direction_deg=0.0), r"load_direction_deg: must be -90"),
    (lambda d: d["solver"].update(cavitation="none"), r"\[solver\] cavitation: must be one of"),
    (lambda d: d["tilting_pad"].update(n_pads=13), r"\[tilting_pad\] n_pads: must be an integer"),
    (lambda d: d["tilting_pad"].update(frequency_ratios=[1.0, 0.5]), r"frequency_ratios: expected 1 to 20 increasing"),
    (lambda d: d["tilting_pad"].update(stability_speeds=[9000.0, 3000.0]), r"stability_speeds: must be \[lowest"),
])
def test_bad_tilting_pad_input_names_the_field(change, message):
    data = _coarse()
    change(data)
    with pytest.raises(ValueError, match=message):
        settings(data, "t.toml")


def test_the_shipped_scene_reads():
    s = settings(tomllib.loads(SHIPPED.read_text()), "journal_tilting.toml")
    assert s["tilting_pad"]["n_pads"] == 5 and s["tilting_pad"]["preload"] == 0.25


def test_flexible_pivots_deflect_by_load_over_stiffness(tmp_path):
    """On flexible pivots each loaded pad's pivot moves out until the spring carries the pad's load:
    deflection = load / k (the spring balance k xi_i = F_i . n_i, the load along the pivot line), and the
    softer bearing sits lower (a larger eccentricity) than on rigid pivots."""
    data = _coarse()
    data["tilting_pad"]["pivot_stiffness"] = 1e9
    data["output"] = {"pictures": [], "tables": []}
    (tmp_path / "s.toml").write_text(toml_text(data))
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    pads = [p for p in summary["results"]["pads"] if p["loaded"]]
    assert pads
    for p in pads:
        assert p["pivot_deflection_m"] == pytest.approx(p["load_N"] / 1e9, rel=1e-5)
    assert "pressure.png" not in summary["files"] and "coefficients.csv" not in summary["files"]


def test_tilting_pads_with_an_oil_table_run_at_their_effective_temperature(tmp_path):
    """[oil] with [tilting_pad]: the pads' level-1 heat balance sets the viscosity of everything the scene
    reports; the summary says how far the film moved from the isothermal one at the supply temperature."""
    data = _coarse()
    data["tilting_pad"].update(stability_points=2)
    del data["operating"]["viscosity"]
    data["oil"] = dict(grade="VG 32", kinematic_viscosity_100C=5.4e-6, supply_temperature_C=40.0)
    (tmp_path / "s.toml").write_text(toml_text(data))
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    th = summary["thermal"]
    assert th["effective_temperature_C"] > 40.0 and th["effective_viscosity_Pa_s"] < th["supply_viscosity_Pa_s"]
    assert th["convected_power_W"] + th["conducted_power_W"] == pytest.approx(th["power_loss_W"], rel=1e-10)
    assert th["moved"]["min_film"] < 0  # hotter, thinner
    assert summary["results"]["friction_power_W"] == pytest.approx(th["power_loss_W"], rel=1e-6)
    assert any(row[0] == "effective temperature" for row in summary["table"])
