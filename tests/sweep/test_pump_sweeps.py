"""Design sweeps over the pump transient (``run="pump"``).

Expected values come from the transient itself: a swept case must report
exactly what :func:`bearingfe.simulate` gives for the same design (smallest
film over the cycle, mean inlet flow, mean friction moment times shaft speed),
and a pocket change must act on ``pump.surface``.
"""

import json
import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.sweep import PumpCase, apply_changes, sweep


@pytest.fixture(scope="module")
def base():
    return PumpCase(mesh_size=0.3, element="P1", start="steady")


def test_pump_sweep_reports_what_simulate_gives(base, tmp_path):
    table = sweep(base, [{"pocket_fraction": 0.06}], ["h_min", "flow_inlet", "friction_loss", "balance_ratio",
                                                      "pumping_power", "total_power"],
                  run="pump", cache=tmp_path / "cache", max_workers=1)
    row = table.iloc[0]
    assert row["error"] is None or (isinstance(row["error"], float) and math.isnan(row["error"]))
    design = apply_changes(base, {"pocket_fraction": 0.06})
    assert design.pump.surface.inlet_fraction == pytest.approx(0.06, rel=1e-12)
    mesh = bf.transient.pump_mesh(design.pump, 0.3)
    traj = bf.simulate(design.pump, mesh, 1.0, start="steady", element="P1")
    assert row["h_min"] == pytest.approx(traj.smallest_film, rel=1e-9)
    assert row["flow_inlet"] == pytest.approx(np.mean(traj.flow_inlet), rel=1e-9)
    assert row["friction_loss"] == pytest.approx(np.mean(traj.friction_moment) * design.pump.drive.omega,
                                                 rel=1e-9)
    assert row["balance_ratio"] == pytest.approx(bf.balance_ratio(design.pump, mesh), rel=1e-9)
    # the power lost, as the pump scene reports it (cycle_losses: the pocket at the chamber pressure, so the
    # pumping power is the film's inflow times that pressure, Q_film p_ch, and no restrictor loss)
    from bearingfe.transient.trajectory import cycle_losses
    losses = cycle_losses(traj, design.pump)
    assert losses.restrictor_power == 0.0 and losses.pumping_power > 0
    assert row["pumping_power"] == pytest.approx(losses.pumping_power, rel=1e-9)
    assert row["pumping_power"] == pytest.approx(np.mean(traj.flow_inlet * traj.chamber_pressure), rel=1e-9)
    assert row["total_power"] == pytest.approx(losses.total_power, rel=1e-9)
    assert row["friction_loss"] == pytest.approx(losses.friction_power, rel=1e-9)


def test_the_power_outputs_of_a_static_film():
    # a film result: the pockets' outflow times their pressure (non-dimensional, power scale mu omega^2 R0^4 / c)
    from bearingfe.sweep import OUTPUTS, csv_headers
    from tests.helpers import ROOT
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    mesh = bf.transient.pump_mesh(pump, 0.3)
    res = bf.solve_reynolds(mesh, bf.CosineFilm(0.5, 3.0), wedge=1.0, inlet_pressure=0.4)
    assert OUTPUTS["pumping_power"](res) == pytest.approx(res.flows["inlet"] * 0.4, rel=1e-14)
    assert OUTPUTS["total_power"](res) == pytest.approx(res.friction + res.flows["inlet"] * 0.4, rel=1e-14)
    assert csv_headers(["pumping_power", "total_power"], "pump") == {"pumping_power": "pumping_power [W]",
                                                                     "total_power": "total_power [W]"}


def test_pump_case_validation_names_the_field():
    with pytest.raises(ValueError, match="PumpCase.element"):
        PumpCase(element="P3")
    with pytest.raises(ValueError, match="PumpCase.mesh_size"):
        PumpCase(mesh_size=0.0)
    with pytest.raises(ValueError, match="PumpCase.pump"):
        PumpCase(pump="not a pump")


def test_case_status_and_csv_headers():
    from bearingfe.sweep import case_status, csv_headers

    assert case_status(None) == "completed"
    assert case_status("FilmRuptured: film ruptured: smallest film reached 0.02 c at beta = 0.9 rad") == "ruptured"
    assert case_status("LiftOffError: the pocket lifts the shoe") == "failed"
    columns = ["pocket_fraction", "h_min", "peak_pressure", "flow_inlet", "friction_loss", "seconds", "status"]
    assert csv_headers(columns, "pump") == {
        "pocket_fraction": "pocket_fraction [-]", "h_min": "h_min [m]", "peak_pressure": "peak_pressure [Pa]",
        "flow_inlet": "flow_inlet [m^3/s]", "friction_loss": "friction_loss [W]", "seconds": "seconds [s]"}
    assert csv_headers(["h_min", "load"], "shoe") == {"h_min": "h_min [-]", "load": "load [-]"}


#: Two pump cases: the shipped oil (completes) and a hundred times thinner one (the film closes at
#: about 54 deg: the hostile tests' weak pump, tests/hostile/test_outputs.py).
RUPTURE_STUDY = """
[study]
name = "rupture check"
run = "pump"
outputs = ["h_min", "flow_inlet", "friction_loss"]
objective = "h_min"
sense = "max"

[base]
kind = "pump"

[base.set]
mesh_size = 0.3
element = "P1"
start = "steady"

[grid]
"pump.viscosity" = [0.03, 0.0003]
"""


@pytest.mark.slow  # two pump revolutions in worker processes: about 5 s
def test_ruptured_cases_are_results_not_failures(tmp_path, capsys):
    import csv

    from bearingfe.cli import main

    (tmp_path / "s.toml").write_text(RUPTURE_STUDY)
    argv = ["sweep", str(tmp_path / "s.toml"), "--out", str(tmp_path / "out"), "--no-progress"]
    for run in range(2):  # first use and the cached rerun: both exit 0
        assert main(argv) == 0
        out = capsys.readouterr().out
        assert "2 cases: 1 completed, 1 ruptured (the film closed" in out and "0 failed" in out
        assert "best (max h_min): pump.viscosity [Pa s]=0.03, h_min [m]=" in out  # the best line with units
    with open(tmp_path / "out" / "results.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["status"] for r in rows] == ["completed", "ruptured"]
    assert rows[1]["error"].startswith("FilmRuptured: film ruptured") and rows[1]["h_min [m]"] == ""
    assert 1e-6 < float(rows[0]["h_min [m]"]) < 20e-6 and rows[0]["pump.viscosity [Pa s]"] == "0.03"
    assert json.loads((tmp_path / "out" / "best.json").read_text())["pump.viscosity"] == 0.03
