"""The pump scene through the command line (``bearingfe run scenes/pump.toml``).

Coarse settings (mesh 0.2 R0, a steady start, a quarter turn) keep it fast;
the checks are on consistency, not on converged numbers: every file is
written, the summary's smallest films are the minima of the CSV columns,
the film ratio is their quotient, and a pictured state re-solved from the
trajectory balances the applied load (paper eq. 13-14: film force + load = 0).
"""

import contextlib
import csv
import io
import json
from pathlib import Path

import numpy as np
import pytest

from bearingfe.cli import main
from bearingfe.transient import state_result
from bearingfe.scenes import SceneError, load_scene
from tests.helpers import ROOT

#: The coarse scene of these tests (overrides of the shipped scenes/pump.toml).
COARSE = dict(title="coarse pump", run={"revolutions": 0.25, "start": "steady", "mesh_size": 0.2, "rtol": None,
                                        "frames": 3}, elastic=None, output=None)


def _min_column(path: Path, name: str) -> float:
    with open(path) as fh:
        return min(float(row[name]) for row in csv.DictReader(fh))


def test_pump_scene_writes_everything_consistent(coarse_run):
    out, summary, printed, _ = coarse_run
    names = {p.name for p in out.iterdir()}
    assert {"trajectory_pocket.csv", "trajectory_plain.csv", "trajectory.png", "orbit.png", "pressure.png",
            "film.png", "summary.png", "pressure.pvd", "summary.json"} <= names
    res = summary["results"]
    pocket = _min_column(out / "trajectory_pocket.csv", "h_min [m]")
    plain = _min_column(out / "trajectory_plain.csv", "h_min [m]")
    assert res["pocket"]["smallest_film_m"] == pytest.approx(pocket, rel=1e-12)
    assert res["plain"]["smallest_film_m"] == pytest.approx(plain, rel=1e-12)
    assert res["film_ratio"] == pytest.approx(pocket / plain, rel=1e-12)
    assert res["pocket"]["status"] == "completed" and res["plain"]["status"] == "completed"
    assert 0.0 < res["pocket"]["balance_ratio"] < 1.0  # the shipped pocket is below hydrostatic balance
    assert "smallest film ratio" in printed
    rows = {q: v for q, v, _ in summary["table"]}
    assert rows["pocket gain (smallest film)"] == f"{100 * (res['film_ratio'] - 1):+.0f} %"


def test_pictured_state_balances_the_load():
    import bearingfe as bf

    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    mesh = bf.transient.pump_mesh(pump, 0.2)
    traj = bf.simulate(pump, mesh, 0.1, start="steady", points_per_revolution=40)
    k = traj.beta.size - 1
    res = state_result(pump, mesh, traj, k)
    # film force + applied load = 0 at every stored state (transient.py docstring), load non-dimensional
    np.testing.assert_allclose(res.force, -traj.load[k], rtol=1e-6, atol=1e-9 * np.abs(traj.load[k]).max())


def test_pump_scene_errors_name_the_field(tmp_path, scene_file):
    bad = scene_file("pump", name="bad.toml", run={"start": "cold"})
    with pytest.raises(SceneError, match=r"\[run\] start: must be one of 'periodic', 'steady'"):
        from bearingfe.scenes.pump import settings as pump_settings
        data, label = load_scene(bad)
        pump_settings(data, label, tmp_path)
    missing = scene_file("pump", name="missing.toml", pump={"mechanism": "nowhere.toml"})
    assert main(["run", str(missing), "--out", str(tmp_path / "o"), "--no-progress"]) == 2
    assert not (tmp_path / "o").exists()
    # the deflection squeeze model holds the pocket at the chamber pressure: a fed pocket is refused before any run
    fed = scene_file("pump", name="fed.toml", elastic={"enabled": True},
                     pump={"mechanism": (ROOT / "mechanisms" / "eccentric_pump_orifice.toml").as_posix()})
    with pytest.raises(SceneError, match=r"\[elastic\] dynamics: 'squeeze'.*quasi-static"):
        from bearingfe.scenes.pump import run as run_pump_scene
        data, label = load_scene(fed)
        run_pump_scene(data, label, tmp_path / "f", base_dir=fed.parent)


def _csv(path: Path) -> dict[str, np.ndarray]:
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


#: The shipped pump (mechanisms/eccentric_pump.toml): 1500 rpm = 50 pi rad/s; its force scale
#: mu omega R0^4/c^2 = 0.03 * 50 pi * 0.05^4 / (20e-6)^2 = 73.63 kN.
OMEGA = 50 * np.pi
FORCE_SCALE = 0.03 * OMEGA * 0.05**4 / 20e-6**2


@pytest.fixture(scope="module")
def coarse_run(tmp_path_factory):
    """The coarse scene with limits on either side of its figures, run once: its folder, summary, printed
    text and the figures it drew (``trajectory``, ``orbit`` and the field grids, in order)."""
    from unittest import mock

    import bearingfe.scenes.pump as pump_scene
    from bearingfe.plot import curves, maps
    from tests.helpers import scene_data, toml_text

    folder = tmp_path_factory.mktemp("pump")
    scene = folder / "pump.toml"
    scene.write_text(toml_text(scene_data("pump", COARSE, limits={"min_film": 10e-6, "max_pressure": 40e6,
                                                                   "max_friction_power": 1.0,
                                                                   "max_leakage": 1.0})))
    out = folder / "out"
    figures = {"fields": []}

    def keep(name, draw):
        def wrapped(*args, **kwargs):
            fig = draw(*args, **kwargs)
            figures[name].append(fig) if name == "fields" else figures.__setitem__(name, fig)
            return fig
        return wrapped

    printed = io.StringIO()
    from bearingfe.core import parallel

    # every picture drawn in this process (not in forked ones), so that its figure can be kept
    with mock.patch.object(parallel, "PROCESSES", 1), mock.patch.object(curves, "trajectory_plot", keep("trajectory", curves.trajectory_plot)), \
            mock.patch.object(curves, "orbit_plot", keep("orbit", curves.orbit_plot)), \
            mock.patch.object(maps, "field_panels", keep("fields", maps.field_panels)), \
            mock.patch.object(pump_scene, "_summary_page", keep("summary", pump_scene._summary_page)), \
            contextlib.redirect_stdout(printed):
        assert main(["run", str(scene), "--out", str(out), "--no-progress"]) == 0
    return out, json.loads((out / "summary.json").read_text()), printed.getvalue(), figures


def test_the_run_releases_the_objects_it_froze_for_the_collector(coarse_run):
    """The run freezes the objects alive before its forks (gc.freeze) and unfreezes them at its end: none is
    left out of the collector's reach after it."""
    import gc

    assert gc.get_freeze_count() == 0


def test_trajectory_csv_headers_carry_units_and_si_values(coarse_run):
    out, summary, _, _ = coarse_run
    cols = _csv(out / "trajectory_pocket.csv")
    assert all(name.endswith("]") and " [" in name for name in cols)  # "name [unit]" everywhere
    assert {"t [s]", "beta [deg]", "delta [deg]", "h_min [m]", "chamber_pressure [Pa]", "friction_moment [N m]",
            "flow_inlet [m^3/s]", "load_x [N]", "inlet_pressure_nondimensional [-]", "load_x_nondimensional [-]"
            } <= set(cols)
    # angles in degrees: a quarter turn from a steady start at beta = 0
    assert cols["beta [deg]"][0] == pytest.approx(0.0, abs=1e-9) and cols["beta [deg]"][-1] == pytest.approx(90.0)
    # t = beta / omega; load [N] = the non-dimensional load times the force scale
    np.testing.assert_allclose(cols["t [s]"], np.radians(cols["beta [deg]"]) / OMEGA, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(cols["load_x [N]"], cols["load_x_nondimensional [-]"] * FORCE_SCALE, rtol=1e-12)


def test_summary_gives_power_leakage_peak_pressure_and_limit_flags(coarse_run):
    out, summary, _, _ = coarse_run
    rows = {q: (v, u) for q, v, u in summary["table"]}
    for design in ("pocket", "plain"):
        r = summary["results"][design]
        cols = _csv(out / f"trajectory_{design}.csv")
        # friction power = mean friction moment x shaft speed [W]; leakage = mean pocket inflow in l/min
        assert r["mean_friction_power_W"] == pytest.approx(np.mean(cols["friction_moment [N m]"]) * OMEGA, rel=1e-12)
        assert rows[f"{design}: mean friction power"] == (pytest.approx(r["mean_friction_power_W"]), "W")
        assert rows[f"{design}: leakage (mean inflow from the pocket)"] == (
            pytest.approx(np.mean(cols["flow_inlet [m^3/s]"]) * 6e4, rel=1e-12), "l/min")
        # the peak pressure is at least that of each pictured state, and at least the chamber's at the
        # most loaded state with a pocket (the pocket carries the chamber pressure)
        peak = r["peak_pressure_Pa"]
        assert rows[f"{design}: peak pressure"] == (pytest.approx(peak), "Pa")
        assert peak >= max(r["loaded_state"]["peak_pressure_Pa"], r["thinnest_state"]["peak_pressure_Pa"])
        assert r["loaded_state"]["load_N"] == pytest.approx(max(abs(cols["load_x [N]"])), rel=1e-12)
        assert r["thinnest_state"]["film_m"] == pytest.approx(r["smallest_film_m"], rel=1e-3)
        # limits: 10 um smallest film, 40 MPa, 1 W (violated: hundreds of W), 1 m^3/s
        verdicts = r["limits"]
        assert verdicts["min_film"]["ok"] == (r["smallest_film_m"] >= 10e-6)
        assert verdicts["max_pressure"]["ok"] and verdicts["max_leakage"]["ok"]
        assert not verdicts["max_friction_power"]["ok"] and r["within_limits"] is False
        v = verdicts["max_friction_power"]
        assert rows[f"{design}: limit max_friction_power: {v['value']:.4g} <= 1 W"] == ("VIOLATED", "")
    pocket = summary["results"]["pocket"]
    assert pocket["loaded_state"]["peak_pressure_Pa"] >= pocket["loaded_state"]["chamber_pressure_Pa"]


def test_pictures_draw_both_designs(coarse_run):
    """Every comparison picture holds both designs: lines per design, one field map per design and state."""
    _, summary, _, figures = coarse_run
    film = figures["trajectory"].axes[2]
    assert [ln.get_label() for ln in film.lines if ln.get_marker() in ("None", "")] == ["pocket: h_min", "plain: h_min"]
    assert len([ln for ln in film.lines if ln.get_marker() == "o"]) == 2  # the smallest film of each marked
    assert len(figures["orbit"].axes[0].lines) == 1 + 2 * 3
    panels = figures["fields"]
    assert len(panels) == 2  # pressure.png, film.png (in the order they are drawn)
    units = []
    for fig in panels:
        titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
        assert len(titles) == 4  # two designs x (most loaded, thinnest film)
        bars = [a.label for a in fig.artists if hasattr(a, "tick_labels")]  # the colour bars: one unit a picture
        assert len(bars) == 4 and len(set(bars)) == 1
        units.append(bars[0])
        for design in ("pocket", "plain"):
            for key, what in (("loaded", "most loaded"), ("thinnest", "thinnest film")):
                st = summary["results"][design][f"{key}_state"]
                heading = (f"{design}, {what}: beta = {st['beta_deg']:.0f} deg\n"
                           f"p_max = {st['peak_pressure_Pa'] / 1e6:.3g} MPa, h_min = {st['film_m'] * 1e6:.3g} um")
                assert heading in titles
    assert sorted(units) == ["h [um]", "p [MPa]"]


def test_summary_page_compares_the_designs_with_their_verdicts(coarse_run):
    out, summary, _, figures = coarse_run
    assert (out / "summary.png").stat().st_size > 20000
    page = figures["summary"]
    films, *rest = page.axes
    assert [ln.get_label() for ln in films.lines] == [
        "pocket", f"pocket: min {summary['results']['pocket']['smallest_film_m'] * 1e6:.3g} um at "
                  f"{summary['results']['pocket']['thinnest_state']['beta_deg']:.0f} deg",
        "plain", f"plain: min {summary['results']['plain']['smallest_film_m'] * 1e6:.3g} um at "
                 f"{summary['results']['plain']['thinnest_state']['beta_deg']:.0f} deg",
        "limit min_film"]
    assert films.lines[-1].get_ydata()[0] == pytest.approx(10.0)  # the 10 um limit, drawn in um
    maps = [ax for ax in rest if ax.get_title().startswith(("pocket, most loaded", "plain, most loaded"))]
    assert len(maps) == 2
    (table,) = [ax for ax in rest if "unit" in (t.get_text() for t in ax.texts)]
    by_row: dict = {}  # the ruled table's cells: one text each, a row at one height, columns left to right
    for t in table.texts:
        by_row.setdefault(t.get_position()[1], []).append(t)
    lines = [[t.get_text() for t in sorted(by_row[y], key=lambda t: t.get_position()[0])]
             for y in sorted(by_row, reverse=True)]
    assert lines[0] == ["", "pocket", "plain", "unit"]
    rows = {line[0]: (line[1], line[2]) for line in lines[1:]}
    assert rows["mean friction power <= 1 W"] == ("VIOLATED", "VIOLATED")
    assert all(t.get_color() == "red" for t in table.texts if t.get_text() == "VIOLATED")
    assert rows["peak pressure <= 40 MPa"] == ("ok", "ok")
    ok = {d: "ok" if summary["results"][d]["limits"]["min_film"]["ok"] else "VIOLATED" for d in ("pocket", "plain")}
    assert rows["smallest film >= 10 um"] == (ok["pocket"], ok["plain"])


#: The shipped pump's pressure scale mu omega R0^2/c^2 = 0.03 * 50 pi * 0.05^2 / (20e-6)^2 = 29.45 MPa.
PRESSURE_SCALE = 0.03 * OMEGA * 0.05**2 / 20e-6**2


def _losses_of(cols: dict, rows: dict, design: str, entry: dict, fed: bool):
    """The summary's leakage and power of one design against its own CSV columns (the definitions: powers are
    means of flow x pressure drop and of friction moment x shaft speed; peaks the largest samples)."""
    p_r, p_ch = cols["pocket_pressure [Pa]"], cols["chamber_pressure [Pa]"]
    np.testing.assert_allclose(p_r, cols["inlet_pressure_nondimensional [-]"] * PRESSURE_SCALE, rtol=1e-12)
    friction = np.mean(cols["friction_moment [N m]"]) * OMEGA
    film = np.mean(cols["flow_inlet [m^3/s]"] * p_r)
    restrictor = np.mean(cols["flow_restrictor [m^3/s]"] * (p_ch - p_r)) if fed else 0.0
    assert entry["friction_power_W"] == pytest.approx(friction, rel=1e-9)
    assert entry["film_power_W"] == pytest.approx(film, rel=1e-9, abs=1e-12)
    assert entry["restrictor_power_W"] == pytest.approx(restrictor, rel=1e-9, abs=1e-12)
    assert entry["pumping_power_W"] == pytest.approx(entry["restrictor_power_W"] + entry["film_power_W"], rel=1e-12)
    assert entry["total_power_W"] == pytest.approx(entry["friction_power_W"] + entry["pumping_power_W"], rel=1e-12)
    assert rows[f"{design}: total power loss (friction + pumping, mean)"] == (pytest.approx(entry["total_power_W"]), "W")
    assert entry["side_flow_peak_m3s"] == pytest.approx(np.max(cols["flow_side [m^3/s]"]), rel=1e-9)
    assert rows[f"{design}: side leakage (peak)"] == (pytest.approx(entry["side_flow_peak_m3s"] * 6e4), "l/min")
    if fed:
        assert entry["restrictor_flow_mean_m3s"] == pytest.approx(np.mean(cols["flow_restrictor [m^3/s]"]), rel=1e-9)
        assert rows[f"{design}: restrictor flow (peak)"] == (
            pytest.approx(np.max(cols["flow_restrictor [m^3/s]"]) * 6e4, rel=1e-9), "l/min")
    else:
        assert entry["restrictor_flow_mean_m3s"] is None and "flow_restrictor [m^3/s]" not in cols
    np.testing.assert_allclose(cols["total_power [W]"], cols["friction_power [W]"] + cols["pumping_power [W]"],
                               rtol=1e-12)


def test_leakage_and_power_of_the_prescribed_pocket_and_the_plain_shoe(coarse_run):
    # the shipped pump holds its pocket at the chamber pressure: no restrictor, the pumping power is the film's
    # (pocket outflow x chamber pressure); the plain shoe has no pocket: its pumping power is 0
    out, summary, _, _ = coarse_run
    rows = {q: (v, u) for q, v, u in summary["table"]}
    for design in ("pocket", "plain"):
        cols = _csv(out / f"trajectory_{design}.csv")
        _losses_of(cols, rows, design, summary["results"][design]["losses"], fed=False)
    pocket = _csv(out / "trajectory_pocket.csv")
    np.testing.assert_allclose(pocket["pocket_pressure [Pa]"], pocket["chamber_pressure [Pa]"], rtol=1e-9)
    assert summary["results"]["plain"]["losses"]["pumping_power_W"] == 0.0
    assert summary["results"]["pocket"]["losses"]["pumping_power_W"] > 0.0
    assert "pocket.png" in summary["files"] and (out / "pocket.png").stat().st_size > 20000


def test_the_orifice_fed_pocket_reports_its_pressure_leakage_and_power(tmp_path):
    """The shipped orifice machine (coarse, half a revolution) and its plain twin: the pocket pressure over the cycle
    in the CSV and pocket.png, the restrictor's flow, and the power split that sums to the total (the flow balance
    itself is checked in tests/transient/test_fed.py)."""
    from unittest import mock

    from bearingfe.core import parallel
    from bearingfe.plot import curves
    from tests.helpers import scene_data, toml_text

    scene = tmp_path / "orifice.toml"
    scene.write_text(toml_text(scene_data(
        "pump", COARSE, pump={"mechanism": (ROOT / "mechanisms" / "eccentric_pump_orifice.toml").as_posix(),
                              "compare_plain": True},
        run={"revolutions": 0.5, "mesh_size": 0.3, "frames": 0}, output={"pictures": ["pocket"]})))
    drawn, draw = {}, curves.pocket_plot

    def keep(*args, **kwargs):
        drawn["fig"] = fig = draw(*args, **kwargs)
        return fig

    with mock.patch.object(parallel, "PROCESSES", 1), mock.patch.object(curves, "pocket_plot", keep), \
            contextlib.redirect_stdout(io.StringIO()):
        assert main(["run", str(scene), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    rows = {q: (v, u) for q, v, u in summary["table"]}
    cols = _csv(tmp_path / "out" / "trajectory_pocket.csv")
    entry = summary["results"]["pocket"]["losses"]
    _losses_of(cols, rows, "pocket", entry, fed=True)
    # the plain twin has no pocket to feed: the rigid model, no restrictor, no pumping power
    _losses_of(_csv(tmp_path / "out" / "trajectory_plain.csv"), rows, "plain", summary["results"]["plain"]["losses"],
               fed=False)
    assert summary["results"]["plain"]["losses"]["pumping_power_W"] == 0.0
    # the orifice drops the pressure while it feeds: the pocket stays below the chamber in discharge, and its loss
    # is part of the pumping power (both positive)
    discharge = cols["chamber_pressure [Pa]"] > 0.9 * cols["chamber_pressure [Pa]"].max()
    assert np.all(cols["pocket_pressure [Pa]"][discharge] < cols["chamber_pressure [Pa]"][discharge])
    assert entry["restrictor_power_W"] > 0 and entry["film_power_W"] > 0
    assert rows["pocket: pocket pressure (peak)"] == (pytest.approx(np.max(cols["pocket_pressure [Pa]"])), "Pa")
    # the curve: chamber then pocket pressure in MPa on the first panel, the restrictor's flow on the second
    pressure, flow, _ = drawn["fig"].axes
    np.testing.assert_allclose(pressure.lines[1].get_ydata(), cols["pocket_pressure [Pa]"] / 1e6, rtol=1e-12)
    assert [ln.get_label() for ln in flow.lines] == ["pocket: pocket into the film", "pocket: side",
                                                     "pocket: restrictor", "plain: side"]  # plain: no pocket
    np.testing.assert_allclose(flow.lines[2].get_ydata(), cols["flow_restrictor [m^3/s]"] * 6e4, rtol=1e-12)


def test_periodic_tolerance_reaches_the_transient(monkeypatch):
    """[run] periodic_tol (default the transient's 1e-6) is what the periodic start is asked for; a value that
    is not a positive number is refused naming the field."""
    import tomllib

    import bearingfe.transient as transient
    from bearingfe.scenes.pump import settings, simulate_design
    from tests.helpers import ROOT

    data = tomllib.loads((ROOT / "scenes" / "pump.toml").read_text())
    assert settings(data, "pump.toml", ROOT / "scenes")["run"]["periodic_tol"] == 1e-6
    data["run"]["periodic_tol"] = 1e-4
    run = settings(data, "pump.toml", ROOT / "scenes")["run"]
    seen = {}
    monkeypatch.setattr(transient, "pump_mesh", lambda pump, size, order: None)
    monkeypatch.setattr(transient, "simulate", lambda *a, **k: seen.update(k))
    simulate_design(object(), run)
    assert seen["periodic_tol"] == 1e-4 and seen["rtol"] == run["rtol"]
    data["run"]["periodic_tol"] = -1.0
    with pytest.raises(SceneError, match="periodic_tol"):
        settings(data, "pump.toml", ROOT / "scenes")


def test_pictures_and_frames_are_shared_by_cost():
    # the shipped scene's work on two processes: every job once, each share dearest first, the cheaper share
    # first (this process's), and no assignment of the jobs to two processes has a cheaper dearest share
    # (checked here against all 2^7 of them)
    from itertools import product

    from bearingfe.scenes.pump import _COSTS, _shares

    names = ["trajectory", "orbit", "pocket", "pressure", "film", "summary", "frames"]
    groups = _shares(names, 2)
    assert sorted(n for g in groups for n in g) == sorted(names)
    for g in groups:
        assert g == sorted(g, key=lambda n: -_COSTS[n])
    costs = [sum(_COSTS[n] for n in g) for g in groups]
    assert costs[0] <= costs[1]
    best = min(max(sum(_COSTS[n] for n, k in zip(names, which) if k == side) for side in (0, 1))
               for which in product((0, 1), repeat=len(names)))
    assert max(costs) == pytest.approx(best, abs=1e-9)
    assert max(costs) <= 0.51 * sum(_COSTS[n] for n in names)  # this scene's jobs split within 1 % of half
    assert _shares(names, 1) == [sorted(names, key=lambda n: -_COSTS[n])]  # one process: all, dearest first
    assert _shares(["orbit"], 2) == [["orbit"]]  # no empty share
    many = [f"job{k}" for k in range(13)]  # beyond the exhaustive search: the greedy shares, all jobs once
    assert sorted(n for g in _shares(many, 2) for n in g) == sorted(many)


def test_scene_kinds_import_their_module_on_first_use():
    # running one kind must not import the others' modules (the command line's start); the table still
    # lists every kind and gives each module's own runner
    import subprocess
    import sys

    code = ("import sys; from bearingfe.scenes import SCENES, SETTINGS; import bearingfe.scenes.pump as p; "
            "assert SCENES['pump'] is p.run and SETTINGS['pump'] is p.settings; "
            "print(sorted(SCENES), [m for m in ('journal', 'thrust', 'reynolds') if 'bearingfe.scenes.' + m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True).stdout
    assert out.strip() == "['journal', 'pump', 'reynolds', 'thrust'] []"
    from bearingfe.scenes import SCENES

    with pytest.raises(KeyError):
        SCENES["nonsense"]
