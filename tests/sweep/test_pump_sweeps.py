"""Design sweeps over the pump transient (``run="pump"``).

Expected values come from the transient itself: a swept case must report
exactly what :func:`bearingfe.simulate` gives for the same design (smallest
film over the cycle, mean inlet flow, mean friction moment times shaft speed),
and a pocket change must act on ``pump.surface``.
"""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.sweep import PumpCase, apply_changes, sweep


@pytest.fixture(scope="module")
def base():
    return PumpCase(mesh_size=0.3, element="P1", start="steady")


def test_pump_sweep_reports_what_simulate_gives(base, tmp_path):
    table = sweep(base, [{"pocket_fraction": 0.06}], ["h_min", "flow_inlet", "friction_loss", "balance_ratio"],
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


def test_pump_case_validation_names_the_field():
    with pytest.raises(ValueError, match="PumpCase.element"):
        PumpCase(element="P3")
    with pytest.raises(ValueError, match="PumpCase.mesh_size"):
        PumpCase(mesh_size=0.0)
    with pytest.raises(ValueError, match="PumpCase.pump"):
        PumpCase(pump="not a pump")
