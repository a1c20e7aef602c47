"""The pump shoe on an elastic support with the squeeze of the deflection (bearingfe.elastic_transient).

Checks: on the discharge plateau (chamber pressure constant) the deflection changes only slowly and the
run agrees with the quasi-static elastic model of ``simulate(elastic=...)``; the mass balance of the
consistent flows (with ``dw/dt`` in the squeeze) closes to round-off; the film is thinner than on the
rigid support while the chamber is at 32 MPa; bad inputs are named. Coarse P1 meshes keep it fast.
"""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.elastic import half_space
from bearingfe.elastic_transient import simulate_elastic

PUMP = bf.load_mechanism("mechanisms/eccentric_pump.toml")


@pytest.fixture(scope="module")
def setup():
    mesh = bf.transient.pump_mesh(PUMP, 0.3)
    return mesh, half_space(mesh, PUMP.scale, (PUMP.shoe_material, PUMP.eccentric_material))


def test_plateau_agrees_with_the_quasi_static_model(setup):
    mesh, C = setup
    beta0 = 1.2   # discharge plateau: compression ended at 20 deg
    dyn = simulate_elastic(PUMP, C, 0.05, start="steady", beta0=beta0, points_per_revolution=60)
    qs = bf.simulate(PUMP, mesh, 0.05, start=dyn.start, beta0=beta0, points_per_revolution=60, elastic=C,
                     formulation="direct")
    assert dyn.status == "completed"
    # the same start, then the quasi-static model drops C dp/dt, which is small on the plateau
    np.testing.assert_allclose(dyn.h_min, qs.h_min, rtol=2e-2)
    np.testing.assert_allclose(dyn.max_deflection, qs.max_deflection, rtol=2e-2)
    assert dyn.mass_balance_relative < 1e-8
    assert np.all(dyn.max_deflection > 5e-6)   # micrometres of opening at 32 MPa


def test_bad_inputs_are_named(setup):
    mesh, C = setup
    with pytest.raises(ValueError, match="revolutions"):
        simulate_elastic(PUMP, C, 0.0)
    with pytest.raises(ValueError, match="start"):
        simulate_elastic(PUMP, C, 0.1, start="cold")
    with pytest.raises(ValueError, match="kappa"):
        simulate_elastic(PUMP, C, 0.1, kappa=-1.0)
    with pytest.raises(ValueError, match="finite modulus"):
        simulate_elastic(PUMP, half_space(mesh, PUMP.scale, math.inf), 0.1)


def test_state_result_balances_the_load(setup):
    from bearingfe.elastic_transient import state_result

    mesh, C = setup
    traj = simulate_elastic(PUMP, C, 0.02, start="steady", beta0=1.2, points_per_revolution=100)
    res = state_result(PUMP, C, traj, traj.beta.size - 1)
    # film force + applied load = 0 up to the Baumgarte-stabilized drift (integrator tolerance)
    np.testing.assert_allclose(res.force, -traj.load[-1], atol=1e-4 * np.abs(traj.load[-1]).max())
    assert res.max_deflection * PUMP.clearance == pytest.approx(traj.max_deflection[-1], rel=1e-12)
    assert res.h_min * PUMP.clearance == pytest.approx(traj.h_min[-1], rel=1e-12)
