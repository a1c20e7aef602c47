"""Design sweeps: changes, local processes vs a Dask LocalCluster, failures, resume, study files."""

import json
import math
import os
import uuid
from pathlib import Path

import numpy as np
import pytest

from bearingfe import CosineFilm, Circle, Ellipse, Rectangle, Slot, Surface, mesh_surface, solve_reynolds
from bearingfe.sweep import (CHANGES, ShoeCase, apply_changes, best_design, check_change_name, expand_cases,
                             read_study, run_shoe, set_field, sweep)
from tests.helpers import ROOT

BASE = ShoeCase(surface=Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=(Circle((0.0, 0.0), 0.12),)),
                gamma=0.5, inlet_pressure=1.0, mesh_size=0.2)
# gamma = 2.5 closes the film at phi = 0 (h = 1 - 2.5): the run fails inside the worker.
GRID = {"pocket_fraction": [0.0, 0.08], "gamma": [0.3, 2.5]}
OUTPUTS = ["h_min", "load", "flow_inlet", "friction_loss", "peak_pressure"]
COMPARED = ["pocket_fraction", "gamma"] + OUTPUTS + ["error", "key"]


def counting_run(case):
    """The shoe run, leaving one file per call in $BEARINGFE_TEST_RUNS (counts runs across processes)."""
    Path(os.environ["BEARINGFE_TEST_RUNS"], uuid.uuid4().hex).touch()
    return run_shoe(case)


# -- changes ---------------------------------------------------------------------------

@pytest.mark.parametrize("shape", [Circle((0.1, 0.05), 0.1), Ellipse((0.0, 0.0), (0.15, 0.05), 0.3),
                                   Rectangle((0.0, 0.0), (0.2, 0.1)), Slot((0.0, 0.0), 0.2, 0.08)])
def test_pocket_fraction_and_position_are_exact(shape):
    base = ShoeCase(surface=Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=(shape,)))
    new = apply_changes(base, {"pocket_fraction": 0.1, "pocket_position": 0.25})
    # expected: the requested fraction of the 1.2 x 0.8 outline (closed-form areas), to rounding
    assert new.surface.inlet_fraction == pytest.approx(0.1, rel=1e-12)
    # area centroid at alpha1 + 0.25 (alpha2 - alpha1) = -0.3; z of the centroid unchanged
    from bearingfe.sweep import centroid
    cx, cy = centroid(new.surface.inlets[0])
    assert cx == pytest.approx(-0.3, abs=1e-12)
    assert cy == pytest.approx(centroid(shape)[1], abs=1e-12)
    assert apply_changes(base, {"pocket_fraction": 0.0}).surface.inlets == ()


@pytest.mark.parametrize("kind", ["circle", "square", "ellipse", "slot"])
def test_pocket_shape_keeps_area(kind):
    new = apply_changes(BASE, {"pocket_shape": kind})
    # expected: the base circle's area pi 0.12^2 (closed form)
    assert new.surface.inlet_area == pytest.approx(math.pi * 0.12**2, rel=1e-12)


def test_dotted_paths_and_bad_names():
    new = set_field(BASE, "surface.half_width", 0.45)
    assert new.surface.half_width == 0.45 and new.gamma == BASE.gamma and BASE.surface.half_width == 0.4
    with pytest.raises(ValueError, match="no field 'halfwidth'"):
        check_change_name(BASE, "surface.halfwidth")
    with pytest.raises(ValueError, match="pocket_fraction must be in"):
        apply_changes(BASE, {"pocket_fraction": 1.5})
    with pytest.raises(ValueError, match="ShoeCase.mesh_size"):
        apply_changes(BASE, {"mesh_size": -1.0})
    assert set(CHANGES) >= {"pocket_fraction", "pocket_position"}


def test_grid_order_and_case_lists():
    assert expand_cases({"a": [1, 2], "b": [3, 4]}) == [
        {"a": 1, "b": 3}, {"a": 1, "b": 4}, {"a": 2, "b": 3}, {"a": 2, "b": 4}]
    assert expand_cases([{"a": 1}, {"b": 2}]) == [{"a": 1}, {"b": 2}]
    with pytest.raises(ValueError, match="'a' must be a list"):
        expand_cases({"a": 1})


# -- local vs cluster, failures, resume ---------------------------------------------------

def test_local_and_cluster_tables_identical_and_failure_recorded(tmp_path):
    from distributed import Client, LocalCluster

    local = sweep(BASE, GRID, OUTPUTS, run="shoe", max_workers=2)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        remote = sweep(BASE, GRID, OUTPUTS, run="shoe", client=client)
    assert local[COMPARED].equals(remote[COMPARED])

    ok, failed = local[local.gamma == 0.3], local[local.gamma == 2.5]
    assert len(ok) == 2 and ok["error"].isna().all() and not local["cached"].any()
    # h_min of h = 1 + gamma cos(phi - pi) on an arc through phi = 0 is 1 - gamma (closed form)
    np.testing.assert_allclose(ok["h_min"], 0.7, atol=1e-12)
    # the sweep's numbers are those of the same solve done here (same gmsh mesh: deterministic)
    design = apply_changes(BASE, {"pocket_fraction": 0.08, "gamma": 0.3})
    direct = solve_reynolds(mesh_surface(design.surface, 0.2), CosineFilm(0.3, math.pi), inlet_pressure=1.0)
    row = ok[ok.pocket_fraction == 0.08].iloc[0]
    assert row["load"] == pytest.approx(np.hypot(*direct.force), rel=1e-10)
    assert row["flow_inlet"] == pytest.approx(direct.flows["inlet"], rel=1e-10)
    assert row["peak_pressure"] == pytest.approx(1.0, rel=1e-12)  # the pocket pressure dominates
    assert len(failed) == 2 and failed["h_min"].isna().all()
    assert all("h_min" in e and e.startswith("ValueError") for e in failed["error"])


def test_resume_reruns_nothing_finished(tmp_path, monkeypatch):
    runs = tmp_path / "runs"
    runs.mkdir()
    monkeypatch.setenv("BEARINGFE_TEST_RUNS", str(runs))
    cache = tmp_path / "cache"
    cases = [{"pocket_fraction": 0.0}, {"pocket_fraction": 0.05}, {"gamma": 2.5},
             {"pocket_position": 0.99}, {"pocket_fraction": 0.0}]  # an impossible pocket; a repeat
    first = sweep(BASE, cases, ["h_min", "load"], run=counting_run, cache=cache, max_workers=2)
    # 3 distinct runnable designs run once each (the repeat is shared, the impossible one never runs)
    assert len(list(runs.iterdir())) == 3
    assert first.loc[3, "error"].startswith("ValueError: Surface.inlets[0]")
    assert first.loc[4, "key"] == first.loc[0, "key"] and first.loc[4, "load"] == first.loc[0, "load"]
    stamps = {p.name: p.stat().st_mtime_ns for p in cache.iterdir()}

    again = sweep(BASE, cases, ["h_min", "load"], run=counting_run, cache=cache, max_workers=2)
    assert len(list(runs.iterdir())) == 3  # nothing rerun
    assert again["cached"].tolist() == [True, True, True, False, True]
    assert {p.name: p.stat().st_mtime_ns for p in cache.iterdir()} == stamps
    cols = ["h_min", "load", "error", "key"]
    assert again[cols].equals(first[cols])

    retried = sweep(BASE, cases, ["h_min", "load"], run=counting_run, cache=cache, retry_failed=True,
                    max_workers=1)
    assert len(list(runs.iterdir())) == 4  # only the failed run again
    assert retried["cached"].tolist() == [True, True, False, False, True]
    record = json.loads((cache / f"{first.loc[2, 'key']}.json").read_text())
    assert record["error"].startswith("ValueError") and record["outputs"]["h_min"] is None


def test_cache_key_names_package_functions_by_the_public_module():
    import hashlib

    from bearingfe import __version__
    from bearingfe.sweep import OUTPUTS, case_key

    # expected: the key text of the one-module bearingfe.sweep ("version|module:qualname|outputs|repr"),
    # sha256 to 24 hex digits; caches written before the split into submodules must still be hit
    text = "|".join([__version__, "bearingfe.sweep:run_shoe", "bearingfe.sweep:_h_min,load", repr(BASE)])
    assert case_key(BASE, run_shoe, [OUTPUTS["h_min"], "load"]) == hashlib.sha256(text.encode()).hexdigest()[:24]
    assert case_key(BASE, counting_run, ["load"]) == hashlib.sha256(
        "|".join([__version__, f"{__name__}:counting_run", "load", repr(BASE)]).encode()).hexdigest()[:24]

def test_best_design():
    import pandas as pd

    table = pd.DataFrame({"x": [1, 2, 3], "h_min": [0.2, math.nan, 0.1], "error": [None, "boom", None]})
    assert best_design(table, "h_min", "max")["x"] == 1
    assert best_design(table, "h_min", "min")["x"] == 3
    with pytest.raises(ValueError, match="sense"):
        best_design(table, "h_min", "best")


# -- study files and the command ------------------------------------------------------------

STUDY = """
[study]
name = "tiny"
run = "shoe"
outputs = ["h_min", "load"]
objective = "load"
[base]
kind = "shoe"
[base.set]
mesh_size = 0.2
gamma = 0.4
[grid]
pocket_fraction = [0.0, 0.08]
"""


def test_study_errors_name_the_field(tmp_path):
    path = tmp_path / "s.toml"
    for text, message in [
        (STUDY.replace('run = "shoe"', 'run = "shoo"'), r"s\.toml: \[study\] run: must be one of 'shoe', 'pump'; got 'shoo'"),
        (STUDY.replace('"load"]', '"lod"]'), r"s\.toml: \[study\] outputs: must be one of 'h_min', .*; got 'lod'"),
        (STUDY.replace("mesh_size = 0.2", "mesh_size = -0.2"), r"\[base.set\] mesh_size: ShoeCase.mesh_size"),
        (STUDY.replace("pocket_fraction =", "pocket_frac ="), r"\[grid\]: change 'pocket_frac'"),
        (STUDY.replace("[0.0, 0.08]", "0.08"), r"\[grid\]: grid values of 'pocket_fraction' must be a list"),
        (STUDY + "[[cases]]\ngamma = 0.1\n", "exactly one of"),
        (STUDY.replace("[grid]", "[gird]"), r"s\.toml: gird: unknown table or field; allowed: study, base, grid, cases"),
    ]:
        path.write_text(text)
        with pytest.raises(ValueError, match=message):
            read_study(path)


def test_pocket_study_file_reads():
    study = read_study(ROOT / "studies" / "pocket_study.toml")
    assert study.objective in study.outputs and study.sense == "max"
    # the shipped study: pocket area fraction 0-20 % x position along the arc
    assert min(study.changes["pocket_fraction"]) == 0.0 and max(study.changes["pocket_fraction"]) == 0.2
    assert len(expand_cases(study.changes)) >= 20


def test_sweep_command_writes_table_and_best(tmp_path, capsys):
    from bearingfe.cli import main

    (tmp_path / "s.toml").write_text(STUDY)
    argv = ["sweep", str(tmp_path / "s.toml"), "--out", str(tmp_path / "out"), "--no-progress"]
    assert main(argv) == 0
    best = json.loads((tmp_path / "out" / "best.json").read_text())
    assert best["pocket_fraction"] == 0.08  # the pocket at p_s = 1 carries more than the plain shoe
    assert "2 cases: 2 completed, 0 ruptured" in capsys.readouterr().out
    # the shoe run's outputs are non-dimensional: "[-]" in the CSV headers, seconds in s
    header = (tmp_path / "out" / "results.csv").read_text().splitlines()[0].split(",")
    assert header == ["pocket_fraction [-]", "h_min [-]", "load [-]", "seconds [s]", "status", "error", "cached", "key"]
    assert main(argv) == 0
    assert "2 from cache" in capsys.readouterr().out
    (tmp_path / "bad.toml").write_text("[study\n")
    assert main(["sweep", str(tmp_path / "bad.toml"), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    assert "not valid TOML" in capsys.readouterr().err


def test_pocket_study_example_quick(tmp_path, monkeypatch):
    import importlib.util

    import matplotlib.image

    monkeypatch.setenv("BEARINGFE_QUICK", "1")
    path = ROOT / "examples" / "03_pocket_study.py"
    spec = importlib.util.spec_from_file_location("pocket_study_example", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.main(str(tmp_path))  # asserts its own sanity bounds (see its docstring)
    image = matplotlib.image.imread(tmp_path / "pocket_study.png")
    assert image.std() > 0.05  # a drawn contour plot, not a blank canvas
    assert (tmp_path / "pocket_study.csv").read_text().count("\n") == 5  # header + 2 x 2 grid


SCALE = """
[scale]
radius = 0.05
clearance = 20e-6
viscosity = 0.03
speed_rpm = 1500.0
"""


def test_si_columns_are_the_outputs_times_their_scales():
    """Each SI column is its output times the scale of bearingfe.core.scales (closed forms: pressure
    mu omega R0^2 / c^2, force mu omega R0^4 / c^2, flow omega R0^2 c, power mu omega^2 R0^4 / c)."""
    import pandas as pd

    from bearingfe.core.scales import Scale
    from bearingfe.sweep import csv_headers, si_columns

    mu, omega, r, c = 0.03, 50 * math.pi, 0.05, 20e-6
    table = pd.DataFrame({"pocket_fraction": [0.0, 0.1], "h_min": [0.4, 0.5], "peak_pressure": [2.0, 3.0],
                          "flow_inlet": [0.0, 0.01], "friction_loss": [1.5, 1.6], "load": [0.7, 0.9],
                          "balance_ratio": [0.8, 0.9], "seconds": [1.0, 1.0], "status": ["completed"] * 2})
    out = si_columns(table, Scale(radius=r, clearance=c, viscosity=mu, speed=omega))
    assert list(out.columns) == ["pocket_fraction", "h_min", "h_min_si", "peak_pressure", "peak_pressure_si",
                                 "flow_inlet", "flow_inlet_si", "friction_loss", "friction_loss_si", "load",
                                 "load_si", "balance_ratio", "seconds", "status"]
    for output, scale in (("h_min", c), ("peak_pressure", mu * omega * r**2 / c**2), ("flow_inlet", omega * r**2 * c),
                          ("friction_loss", mu * omega**2 * r**4 / c), ("load", mu * omega * r**4 / c**2)):
        np.testing.assert_allclose(out[f"{output}_si"], table[output] * scale, rtol=1e-14)
    assert si_columns(table, None) is table
    headers = csv_headers(out.columns, "shoe")
    assert (headers["h_min"], headers["h_min_si"], headers["load_si"], headers["friction_loss_si"]) == (
        "h_min [-]", "h_min_si [m]", "load_si [N]", "friction_loss_si [W]")


def test_study_scale_is_checked(tmp_path):
    path = tmp_path / "s.toml"
    for text, message in [
        (STUDY + SCALE.replace("speed_rpm = 1500.0", ""), r"\[scale\] speed_rpm/omega: give exactly one"),
        (STUDY + SCALE.replace("radius = 0.05", ""), r"\[scale\] radius: missing"),
        (STUDY + SCALE.replace("clearance = 20e-6", "clearance = 0.1"), r"\[scale\].*clearance"),
        (STUDY.replace('run = "shoe"', 'run = "pump"').replace('kind = "shoe"', 'kind = "pump"')
         .replace("mesh_size = 0.2\ngamma = 0.4\n", "").replace('outputs = ["h_min", "load"]', 'outputs = ["h_min"]')
         .replace('objective = "load"', 'objective = "h_min"') + SCALE, r"\[scale\]: only for run = \"shoe\""),
    ]:
        path.write_text(text)
        with pytest.raises(ValueError, match=message):
            read_study(path)
    path.write_text(STUDY + SCALE)
    assert read_study(path).scale.speed == pytest.approx(50 * math.pi)  # 1500 rpm
    assert read_study(ROOT / "studies" / "pocket_study.toml").scale.clearance == 20e-6


def test_sweep_command_writes_si_columns_beside_the_outputs(tmp_path, capsys):
    """With [scale] the table and best.json carry h_min_si [m] = h_min c and load_si [N] = load x the force
    scale mu omega R0^4 / c^2 beside the non-dimensional columns."""
    import pandas as pd

    from bearingfe.cli import main

    (tmp_path / "s.toml").write_text(STUDY.replace("pocket_fraction = [0.0, 0.08]", "pocket_fraction = [0.08]")
                                     + SCALE)
    assert main(["sweep", str(tmp_path / "s.toml"), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    table = pd.read_csv(tmp_path / "out" / "results.csv")
    assert list(table.columns[:5]) == ["pocket_fraction [-]", "h_min [-]", "h_min_si [m]", "load [-]", "load_si [N]"]
    force = 0.03 * 50 * math.pi * 0.05**4 / 20e-6**2
    assert table["h_min_si [m]"][0] == pytest.approx(table["h_min [-]"][0] * 20e-6, rel=1e-12)
    assert table["load_si [N]"][0] == pytest.approx(table["load [-]"][0] * force, rel=1e-12)
    best = json.loads((tmp_path / "out" / "best.json").read_text())
    assert best["load_si"] == pytest.approx(best["load"] * force, rel=1e-12)
    assert "load_si [N]=" in capsys.readouterr().out
