"""The journal scene (``bearingfe run scenes/journal.toml``): files, SI conversion, schema errors, pads.

Coarse meshes (element size 0.2 R instead of the shipped 0.05) keep it fast. The checks are on
consistency and units, not on converged numbers: the summary must equal the direct API calls
(equilibrium + dynamic_coefficients + to_si) to round-off, and its SI values must agree with scales
computed here by hand (pressure mu omega R^2/c^2, force mu omega R^4/c^2, flow omega R^2 c: journal.py
and scales.py; L enters only through the half width a = L/D) and with the Raimondi-Boyd chart variables
of bearingfe.bearings.journal.performance at the summary's eccentricity.
"""

import csv
import json
import math
import tomllib

import numpy as np
import pytest

from bearingfe.cli import main
from bearingfe.bearings.journal import Groove, JournalBearing, dynamic_coefficients, equilibrium, performance
from bearingfe.scenes.journal import settings as journal_settings
from bearingfe.scenes import SCENES, SceneError, load_scene
from tests.helpers import ROOT

SHIPPED = ROOT / "scenes" / "journal.toml"
COARSE = 0.2


def _inputs():
    """D, L, c [m], mu [Pa s], speed [rpm], W [N] as written in the shipped file."""
    d = tomllib.loads(SHIPPED.read_text())
    b, op = d["bearing"], d["operating"]
    return b["diameter"], b["length"], b["radial_clearance"], op["viscosity"], op["speed"], op["load"]


def _hand_scales(D, c, mu, rpm):
    R, omega = D / 2, 2 * math.pi * rpm / 60
    pressure = mu * omega * R**2 / c**2       # P = p mu omega R^2 / c^2
    return R, omega, pressure, pressure * R**2, omega * R**2 * c  # force mu omega R^4/c^2, flow omega R^2 c


def _run_shipped(tmp_path, **changes):
    data, label = load_scene(SHIPPED)
    data["solver"]["size"] = COARSE
    for table, fields in changes.items():
        data.setdefault(table, {}).update(fields)
    out = tmp_path / "out"
    out.mkdir(parents=True)
    return SCENES["journal"](data, label, out), out


def test_shipped_scene_runs_end_to_end_and_writes_its_files(tmp_path, capsys, scene_file):
    scene = scene_file("journal", solver={"size": COARSE})
    out = tmp_path / "out"
    assert main(["run", str(scene), "--out", str(out), "--no-progress"]) == 0
    names = {p.name for p in out.iterdir()} - {".bearingfe-manifest.json"}  # the manifest lists these
    assert names == {"summary.json", "pressure_field.csv", "coefficients.csv", "pressure.png",
                     "pressure_wrapped.png", "film.png"}
    for png in out.glob("*.png"):
        assert png.stat().st_size > 5000
    s = json.loads((out / "summary.json").read_text())
    r = s["results"]
    assert s["kind"] == "journal" and set(s["files"]) == names
    with open(out / "pressure_field.csv") as fh:
        rows = list(csv.DictReader(fh))
    # one row per mesh node; the largest nodal pressure is the summary's, no node thinner than h_min
    assert len(rows) == s["cost"]["nodes"]
    assert max(float(x["pressure [Pa]"]) for x in rows) == pytest.approx(r["max_pressure_Pa"], rel=1e-12)
    assert min(float(x["film [m]"]) for x in rows) >= r["min_film_m"] * (1 - 1e-12)
    assert min(float(x["pressure [Pa]"]) for x in rows) >= 0.0  # Swift-Stieber: no sub-ambient pressure
    with open(out / "coefficients.csv") as fh:
        (row,) = list(csv.DictReader(fh))
    units = {"frequency": "rad/s", "k": "N/m", "c": "N s/m"}  # the ROSS keywords' SI units
    for key, value in s["ross_bearing_element"].items():
        unit = units["frequency" if key == "frequency" else key[0]]
        assert float(row[f"{key} [{unit}]"]) == pytest.approx(value[0], rel=1e-15)
    # the shipped file asks for an error estimate: half the element size changes eps by < 2 % here
    err = s["error_estimate"]
    assert err["nodes"] > s["cost"]["nodes"] and 0 <= err["eccentricity"] < 0.02
    printed = capsys.readouterr().out
    assert "friction power" in printed and "kyy" in printed


def test_summary_equals_api_and_hand_computed_si(tmp_path):
    s, _ = _run_shipped(tmp_path, solver={"estimate_error": False}, output={"pictures": [], "tables": []})
    r, co = s["results"], s["coefficients"]
    D, L, c, mu, rpm, W = _inputs()
    R, omega, p_scale, f_scale, q_scale = _hand_scales(D, c, mu, rpm)
    N = rpm / 60
    # 1. the same calls through the API: identical to round-off
    bearing = JournalBearing(L / D)
    eq = equilibrium(bearing, (0.0, -W / f_scale), size=COARSE)
    dc = dynamic_coefficients(eq)
    K, C = dc.to_si(viscosity=mu, speed=omega, radius=R, clearance=c)
    res = eq.state.results[0]
    assert r["eccentricity"] == pytest.approx(eq.eps, rel=1e-12)
    assert r["attitude_deg"] == pytest.approx(eq.attitude, rel=1e-12)
    np.testing.assert_allclose(co["K_N_per_m"], K, rtol=1e-12, atol=1e-12 * np.abs(K).max())
    np.testing.assert_allclose(co["C_Ns_per_m"], C, rtol=1e-12, atol=1e-12 * np.abs(C).max())
    np.testing.assert_allclose(co["K_c_over_W"], dc.K, rtol=1e-12, atol=1e-12 * np.abs(dc.K).max())
    np.testing.assert_allclose(co["C_c_omega_over_W"], dc.C, rtol=1e-12, atol=1e-12 * np.abs(dc.C).max())
    ross = dc.to_ross_kwargs(viscosity=mu, speed=omega, radius=R, clearance=c)
    for key in ross:
        np.testing.assert_allclose(s["ross_bearing_element"][key], ross[key], rtol=1e-12,
                                   atol=1e-12 * np.abs(K).max())
    assert r["max_pressure_Pa"] == pytest.approx(res.max_pressure * p_scale, rel=1e-12)
    assert s["scales"]["pressure_Pa"] == pytest.approx(p_scale, rel=1e-14)
    assert s["scales"]["force_N"] == pytest.approx(f_scale, rel=1e-14)
    # 2. by hand: K = (K c/W) W/c, C = (C c omega/W) W/(c omega) with the applied W (the film carries
    # it to Newton's tolerance 1e-8); h_min = (1 - eps) c for the 360-degree film (closed form)
    np.testing.assert_allclose(co["K_N_per_m"], dc.K * W / c, rtol=1e-7, atol=1e-7 * np.abs(K).max())
    np.testing.assert_allclose(co["C_Ns_per_m"], dc.C * W / (c * omega), rtol=1e-7, atol=1e-7 * np.abs(C).max())
    assert r["min_film_m"] == pytest.approx((1 - r["eccentricity"]) * c, rel=1e-12)
    # Sommerfeld S = mu N L D / W (R/c)^2: 0.2 for the shipped numbers (file comment)
    S = mu * N * L * D / W * (R / c) ** 2
    assert r["sommerfeld"] == pytest.approx(S, rel=1e-12) and S == pytest.approx(0.2, rel=1e-12)
    # 3. the chart variables of performance() at the summary's eps on a mesh graded for that eps (the
    # equilibrium's mesh was graded for the Newton start: a different mesh of the same size; measured
    # differences 8e-5 in S, 0.0024 deg, 8e-5 in friction, 1e-4 in the flows)
    p = performance(bearing, r["eccentricity"], size=COARSE)
    assert p.sommerfeld == pytest.approx(S, rel=1e-3)
    assert p.attitude == pytest.approx(r["attitude_deg"], abs=0.02)
    # friction: (R/c) f = T/(W c); power = T omega
    assert r["friction_power_W"] == pytest.approx(p.friction_variable * W * c * omega, rel=1e-3)
    # flows: Q/(R c N L) and Qs/Q
    assert r["total_flow_m3s"] == pytest.approx(p.flow_variable * R * c * N * L, rel=1e-3)
    assert r["side_flow_m3s"] == pytest.approx(p.side_flow_ratio * p.flow_variable * R * c * N * L, rel=1e-3)
    # friction identity of the 360-degree film (tests/bearings/test_journal.py): (R/c) f = 2 pi^2 S/sqrt(1-eps^2)
    # + eps sin(att)/2, from S, eps and the attitude alone; the discrete solution obeys it to 6e-11 here
    eps, att = r["eccentricity"], math.radians(r["attitude_deg"])
    T = (2 * math.pi**2 * S / math.sqrt(1 - eps**2) + eps * math.sin(att) / 2) * W * c
    assert r["friction_power_W"] == pytest.approx(T * omega, rel=1e-7)
    assert r["total_flow_m3s"] == pytest.approx(-res.flows["arc_start"] * q_scale, rel=1e-12)


def test_load_direction_turns_the_coefficients(tmp_path):
    # the 360-degree bearing is axisymmetric: turning the load by 30 degrees turns the journal's
    # position and the coefficient matrices (in the fixed x, y frame) by the same angle
    grav, _ = _run_shipped(tmp_path / "g", solver={"estimate_error": False}, output={"pictures": [], "tables": []})
    turned, _ = _run_shipped(tmp_path / "t", solver={"estimate_error": False},
                             operating={"load_direction_deg": -60.0}, output={"pictures": [], "tables": []})
    a = math.radians(30.0)
    Q = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    for key in ("K_N_per_m", "C_Ns_per_m"):
        M = np.array(grav["coefficients"][key])
        np.testing.assert_allclose(turned["coefficients"][key], Q @ M @ Q.T, rtol=1e-9, atol=1e-9 * np.abs(M).max())
    np.testing.assert_allclose(turned["results"]["position_m"], Q @ np.array(grav["results"]["position_m"]),
                               rtol=1e-9, atol=1e-18)
    assert turned["results"]["eccentricity"] == pytest.approx(grav["results"]["eccentricity"], rel=1e-12)


def _grooved(**groove):
    """The bearing table of a half film (pads 0-180 degrees) with one groove."""
    return {"pads": [[0.0, 180.0]], "grooves": [groove]}


@pytest.mark.parametrize("change,message", [
    (dict(bearing={"radial_clearance": -75e-6}), r"\[bearing\] radial_clearance: must be > 0"),
    (dict(bearing={"radial_clearance": 0.006}),
     r"\[bearing\] radial_clearance: must be in \(0, diameter/20 = 0.005\]"),
    (dict(bearing={"length": 0.5}), r"\[bearing\] length: L/D must be in \[0.001, 4\]; got L/D = 5"),
    (dict(bearing={"diameter": None}), r"\[bearing\] diameter: missing \(required\)"),
    (dict(operating={"viscosity": None, "viscosty": 0.018}),
     r"\[operating\] viscosty: unknown field; allowed: speed, speed_rad_s, viscosity"),
    (dict(operating={"load": 0.0}), r"\[operating\] load: must be > 0"),
    (dict(operating={"speed": "fast"}), r"\[operating\] speed: expected a finite number"),
    (dict(bearing={"pads": [[10.0, 5.0]]}),
     r"\[bearing\] pads: expected a list of pads \[\[start_deg, end_deg\], ...\] with start < end <= start \+ 360"),
    (dict(bearing={"pads": [[0.0, 200.0], [150.0, 300.0]]}), r"\[bearing\] pads: .* pads overlap"),
    (dict(bearing={"grooves": [{"angle_deg": 90.0, "width_deg": 10.0}]}), r"\[bearing\] grooves: need pads"),
    (dict(bearing={"supply_pressure": 1e5}), r"\[bearing\] supply_pressure: needs \[\[bearing.grooves\]\]"),
    (dict(bearing=_grooved(angle_deg=90.0, width_deg=190.0)),
     r"\[bearing.grooves.0\] width_deg: must be in \(0, 180\)"),
    (dict(bearing=_grooved(angle_deg=270.0, width_deg=10.0)),
     r"\[bearing.grooves.0\] angle_deg: the groove .* must lie inside one of the pads"),
    (dict(bearing=_grooved(angle_deg=90.0, width_deg=10.0, length_fraction=1.0)),
     r"\[bearing.grooves.0\] length_fraction: must be in \(0, 1\)"),
    (dict(solver={"cavitation": "gumbel"}),
     r"\[solver\] cavitation: must be one of 'reynolds', 'none', 'jfo'; got 'gumbel'"),
    (dict(solver={"estimate_error": "yes"}), r"\[solver\] estimate_error: expected true or false"),
    (dict(solver={"size": 2.0}), r"\[solver\] size: must be in \(0, 1\]"),
    (dict(solver={"size": 0.1, "min_size": 0.2}), r"\[solver\] min_size: must be in \(0, size"),
    (dict(output={"pictures": ["orbit"]}),
     r"\[output\] pictures: must be one of 'pressure', 'wrapped', 'film'; got 'orbit'"),
    (dict(output={"tables": ["flows"]}), r"\[output\] tables: must be one of 'pressure', 'coefficients'"),
    (dict(operating=None, operation={"speed": 3000.0, "viscosity": 0.018, "load": 10e3}),
     r"operation: unknown table or field; allowed: kind, title, bearing"),
])
def test_schema_errors_name_file_table_field_and_range(scene_file, change, message):
    path = scene_file("journal", change, name="bad.toml")
    data, label = load_scene(path)
    with pytest.raises(SceneError, match=r"^bad\.toml: " + message):
        journal_settings(data, label)


def test_schema_error_through_the_command_line(tmp_path, capsys, scene_file):
    path = scene_file("journal", name="bad.toml", bearing={"radial_clearance": -75e-6})
    out = tmp_path / "o"
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 2
    assert not out.exists()
    assert "bad.toml: [bearing] radial_clearance: must be > 0" in capsys.readouterr().err


def test_pads_and_supply_groove(tmp_path, scene_file):
    # the shipped file's commented variant: a film cut at the horizontal split (0 degrees, where the
    # film diverges) with a supply groove at the top
    path = scene_file("journal", name="pads.toml", title=None,
                      bearing={"pads": [[0.0, 360.0]], "supply_pressure": 1.0e5,
                               "grooves": [{"angle_deg": 90.0, "width_deg": 10.0, "length_fraction": 0.8}]},
                      solver={"size": 0.15, "estimate_error": None}, output={"pictures": ["pressure", "wrapped"]})
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    assert {"pressure.png", "pressure_wrapped.png", "pressure_field.csv", "coefficients.csv",
            "summary.json"} == {p.name for p in out.iterdir()} - {".bearingfe-manifest.json"}
    s = json.loads((out / "summary.json").read_text())
    r = s["results"]
    D, L, c, mu, rpm, W = 0.1, 0.05, 75e-6, 0.018, 3000.0, 10e3
    R, omega, p_scale, f_scale, q_scale = _hand_scales(D, c, mu, rpm)
    # the same bearing through the API: supply pressure made non-dimensional by hand
    bearing = JournalBearing(0.5, pads=((0.0, 2 * math.pi),), grooves=(Groove(math.pi / 2, math.radians(10), 0.8),),
                             supply_pressure=1e5 / p_scale)
    eq = equilibrium(bearing, (0.0, -W / f_scale), size=0.15)
    dc = dynamic_coefficients(eq)
    K, C = dc.to_si(viscosity=mu, speed=omega, radius=R, clearance=c)
    assert r["eccentricity"] == pytest.approx(eq.eps, rel=1e-12)
    np.testing.assert_allclose(s["coefficients"]["K_N_per_m"], K, rtol=1e-9, atol=1e-9 * np.abs(K).max())
    np.testing.assert_allclose(s["coefficients"]["C_Ns_per_m"], C, rtol=1e-9, atol=1e-9 * np.abs(C).max())
    res = eq.state.results[0]
    # the groove feeds the film; its flow in SI is the non-dimensional flow times omega R^2 c
    assert r["inlet_flow_m3s"] > 0
    assert r["inlet_flow_m3s"] == pytest.approx(res.flows["inlet"] * q_scale, rel=1e-12)
    assert r["total_flow_m3s"] == pytest.approx((res.flows["inlet"] - res.flows["arc_start"]) * q_scale, rel=1e-12)
    # the groove's edge nodes carry the supply pressure exactly (Dirichlet), converted back to 1 bar
    with open(out / "pressure_field.csv") as fh:
        rows = list(csv.DictReader(fh))
    phi = np.array([float(x["phi [deg]"]) for x in rows])
    z = np.array([float(x["z [m]"]) for x in rows])
    p = np.array([float(x["pressure [Pa]"]) for x in rows])
    on_groove = (np.abs(phi - 90.0) <= 5.0 + 1e-9) & (np.abs(z) <= 0.8 * L / 2 + 1e-12)
    assert on_groove.sum() >= 8
    np.testing.assert_allclose(p[on_groove], 1e5, rtol=1e-9)
    # the pad ends (0 and 360 degrees) are at ambient pressure
    ends = np.minimum(phi, 360.0 - phi) < 1e-9
    assert ends.sum() >= 4 and np.all(p[ends] == 0.0)
    assert s["ross_bearing_element"]["frequency"] == [pytest.approx(omega, rel=1e-15)]


def test_speed_in_rpm_or_rad_per_s(scene_file):
    # 3000 rpm = 2 pi 3000/60 = 100 pi rad/s: either field gives the same settings
    rpm, label = load_scene(scene_file("journal", name="rpm.toml"))
    rad, _ = load_scene(scene_file("journal", name="rad.toml", operating={"speed": None, "speed_rad_s": 100 * math.pi}))
    a, b = journal_settings(rpm, label)["operating"], journal_settings(rad, label)["operating"]
    assert a["speed"] == 3000.0 and b["speed"] == pytest.approx(3000.0, rel=1e-15)
    assert a["speed_rad_s"] == pytest.approx(100 * math.pi, rel=1e-15) == b["speed_rad_s"]
    for change in ({"speed_rad_s": 314.0}, {"speed": None}):  # both, neither
        data, label = load_scene(scene_file("journal", name="bad.toml", operating=change))
        with pytest.raises(SceneError, match=r"^bad\.toml: \[operating\] speed: give exactly one of speed \[rpm\] "
                                             r"and speed_rad_s \[rad/s\]"):
            journal_settings(data, label)


def test_limits_are_flagged_in_the_summary(tmp_path, capsys):
    # limits on either side of the computed figures: the smallest film must stay >= 1 um (it is ~23 um),
    # the peak pressure <= 1 MPa (it is ~6 MPa: violated), the friction power <= 1 MW, the total flow <= 1 m^3/s
    limits = {"min_film": 1e-6, "max_pressure": 1e6, "max_friction_power": 1e6, "max_leakage": 1.0}
    s, out = _run_shipped(tmp_path, limits=limits, solver={"estimate_error": False},
                          output={"pictures": [], "tables": []})
    r = s["results"]
    assert {k: v["ok"] for k, v in r["limits"].items()} == {"min_film": True, "max_pressure": False,
                                                           "max_friction_power": True, "max_leakage": True}
    assert r["limits"]["max_pressure"]["value"] == r["max_pressure_Pa"]
    assert r["limits"]["max_leakage"]["value"] == r["total_flow_m3s"]
    assert r["limits"]["min_film"] == {"quantity": "smallest film", "value": r["min_film_m"], "limit": 1e-6,
                                       "unit": "m", "relation": ">=", "ok": True}
    assert r["within_limits"] is False
    rows = {q: v for q, v, _ in s["table"]}
    assert rows[f"limit max_pressure: {r['max_pressure_Pa']:.4g} <= 1e+06 Pa"] == "VIOLATED"
    assert rows["peak pressure"] == r["max_pressure_Pa"]  # Pa in the table too


def test_limits_schema_names_field_and_range(scene_file):
    data, label = load_scene(scene_file("journal", name="bad.toml", limits={"min_film": -1e-6}))
    with pytest.raises(SceneError, match=r"^bad\.toml: \[limits\] min_film: must be > 0; got -1e-06"):
        journal_settings(data, label)
    data, label = load_scene(scene_file("journal", name="bad.toml", limits={"min_flim": 1e-6}))
    with pytest.raises(SceneError, match=r"\[limits\] min_flim: unknown field; allowed: min_film, max_pressure"):
        journal_settings(data, label)


def test_pictures_are_titled_with_readable_axes_and_legends(tmp_path, monkeypatch):
    """The unwrapped maps: a title with the operating point, phi in degrees, z in mm, tick labels that do
    not overlap, the colour bar labelled with its unit, the red rupture boundary in the legend."""
    from bearingfe.plot import maps

    drawn = []
    draw = maps.field_panels
    monkeypatch.setattr(maps, "field_panels", lambda *a, **k: drawn.append(draw(*a, **k)) or drawn[-1])
    s, out = _run_shipped(tmp_path, solver={"estimate_error": False},
                          output={"pictures": ["pressure", "film"], "tables": []})
    assert len(drawn) == 2
    r = s["results"]
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    for fig, unit in zip(drawn, ("p [MPa]", "h [um]")):
        canvas = FigureCanvasAgg(fig)
        canvas.draw()
        (field,), (bar,) = fig.axes, fig.artists  # the colour bar: an artist of the figure
        assert fig._suptitle.get_text() == s["title"]
        assert field.get_title().startswith(f"eccentricity {r['eccentricity']:.3f}, attitude "
                                            f"{r['attitude_deg']:.1f} deg")
        assert (field.get_xlabel(), field.get_ylabel(), bar.label) == ("phi [deg]", "z [mm]", unit)
        # at least three labels on the map's axes, two on the bar (e.g. 50 and 100 um of a 23..127 um film at
        # the bar's steps of 1, 2, 2.5, 5 times ten: two labelled values fix its scale), none overlapping
        for labels, least in ((field.yaxis.get_ticklabels(), 3), (field.xaxis.get_ticklabels(), 3),
                              (bar.tick_labels, 2)):
            boxes = [t.get_window_extent() for t in labels if t.get_visible() and t.get_text()]
            assert len(boxes) >= least
            assert not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:])
        # the colour bar with its labels and title lies inside the figure: nothing cut
        assert bar.get_tightbbox(canvas.get_renderer()).x1 <= fig.bbox.x1
    pressure = drawn[0].axes[0]
    assert [t.get_text() for t in pressure.get_legend().get_texts()] == ["film rupture boundary"]
