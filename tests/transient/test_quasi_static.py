"""The shoe transient: equilibrium at stored states, tolerance convergence,
mass balance, the steady partial-arc limit, rupture and lift-off.

Coarse meshes (size 0.15 R0, ~60 nodes) keep the file fast; tolerances are
stated with their reason at each assertion.
"""

import dataclasses
import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.bearings.pump import PressureCycle
from bearingfe.transient import LiftOffError, pump_mesh

SIZE = 0.15  # the shared pump meshes of conftest.py (pocket_mesh, plain_mesh) have this size


@pytest.fixture(scope="module")
def pocket_run(pump, pocket_mesh):
    return bf.simulate(pump, pocket_mesh, 1.0, points_per_revolution=36)


def test_run_completes_without_nan(pocket_run, pump):
    tr = pocket_run
    assert tr.status == "completed" and "completed" in tr.message
    for name, col in tr.columns().items():
        assert np.all(np.isfinite(col)), name
    assert tr.beta[0] == 0.0 and tr.beta[-1] == pytest.approx(2 * math.pi)
    assert tr.t[-1] == pytest.approx(2 * math.pi / pump.drive.omega)
    np.testing.assert_allclose(tr.wedge, bf.pump.shoe_wedge(tr.beta, pump.e2))


def test_film_force_balances_the_load_at_stored_states(pocket_run, pocket_mesh, pump):
    # re-solve each stored state from scratch with the stored rates: the
    # superposition is exact in exact arithmetic, so the balance holds to round-off
    tr = pocket_run
    for i in (0, 5, 12, 20, 30):
        res = bf.solve_reynolds(pocket_mesh, bf.CosineFilm(tr.gamma[i], tr.delta[i]), wedge=tr.wedge[i],
                                squeeze=(tr.gamma_rate[i], tr.delta_rate[i]), inlet_pressure=tr.inlet_pressure[i])
        np.testing.assert_allclose(res.force + tr.load[i], 0.0, atol=1e-8 * abs(tr.load[i, 0]))
        assert res.h_min * pump.clearance == pytest.approx(tr.h_min[i], rel=1e-12)


def test_mass_balance(pocket_run):
    # the solver's consistent boundary fluxes close the balance up to the
    # corner-splitting error of the coarse mesh; measured ~1e-4 of the flows
    assert pocket_run.mass_balance_relative < 2e-3
    assert np.max(np.abs(pocket_run.flow_inlet)) > 0  # the pocket does feed the film


def test_integrator_tolerance_study_converges(plain_mesh, plain_pump):
    # smallest film over a turn against a tight reference: the error falls
    # with rtol and is below 0.1 % at rtol = 1e-5
    ref = bf.simulate(plain_pump, plain_mesh, 1.0, rtol=1e-8, atol=1e-11, points_per_revolution=90).smallest_film
    errs = [abs(bf.simulate(plain_pump, plain_mesh, 1.0, rtol=r, atol=1e-3 * r, points_per_revolution=90).smallest_film
                - ref) / ref for r in (1e-2, 1e-3, 1e-5)]
    assert errs[2] < errs[0]
    assert errs[2] < 1e-3
    assert errs[1] < 1e-2


@pytest.mark.parametrize("method", ["RK23", "RK45"])
def test_explicit_runge_kutta_pairs_integrate_the_same_motion(plain_mesh, plain_pump, method):
    # the explicit pairs integrate the same ODE: at rtol 1e-6 the smallest film and the state at
    # the end of the turn agree with a tight LSODA run (rtol 1e-9) to the integration error,
    # measured 2.6e-6 (RK23) and 1.0e-5 (RK45) relative on this mesh (LSODA at rtol 1e-6: 7e-7);
    # 5e-5 leaves a margin of 5
    ref = bf.simulate(plain_pump, plain_mesh, 1.0, rtol=1e-9, atol=1e-12, points_per_revolution=90)
    run = bf.simulate(plain_pump, plain_mesh, 1.0, method=method, rtol=1e-6, points_per_revolution=90)
    assert run.status == "completed"
    assert run.smallest_film == pytest.approx(ref.smallest_film, rel=5e-5)
    np.testing.assert_allclose([run.gamma[-1], run.delta[-1]], [ref.gamma[-1], ref.delta[-1]], rtol=5e-5)


def test_constant_load_without_swing_is_the_steady_partial_arc_bearing(plain_pump):
    # e2 -> infinity removes the swing (wedge -> 1) and equal pressures remove the
    # load cycle: the state must stay at the steady partial-arc solution, whose
    # force is checked against the independent finite-difference solver.
    pump = dataclasses.replace(plain_pump, pivot_distance=1e7 * plain_pump.eccentricity,
                               cycle=PressureCycle(10e6, 10e6))
    mesh = pump_mesh(pump, 0.1)
    tr = bf.simulate(pump, mesh, 0.5, points_per_revolution=24)
    np.testing.assert_allclose(tr.gamma, tr.gamma[0], atol=1e-6)  # integrator error of a rest state
    np.testing.assert_allclose(tr.delta, tr.delta[0], atol=1e-6)
    assert np.max(np.abs(tr.gamma_rate)) < 1e-5
    a1, a2 = pump.surface.arc
    fd = bf.solve_reynolds_fd(pump.surface, bf.CosineFilm(tr.gamma[0], tr.delta[0]), shape=(121, 81),
                              wedge=float(tr.wedge[0]))
    # FE mesh 0.1 vs FD grid 0.01: both second order, discretization gap measured < 1 %
    assert fd.force[0] == pytest.approx(-tr.load[0, 0], rel=2e-2)
    assert abs(fd.force[1]) < 2e-2 * abs(tr.load[0, 0])
    psi = np.linspace(a1, a2, 200001)  # smallest film over the arc by brute force (grid error ~1e-11)
    h = 1 + tr.gamma[0] * np.cos(psi - tr.delta[0])
    assert tr.h_min[0] == pytest.approx(plain_pump.clearance * h.min(), rel=1e-9)


def test_periodic_start(plain_mesh, plain_pump):
    tr = bf.simulate(plain_pump, plain_mesh, 1.0, start="periodic", periodic_tol=1e-6, points_per_revolution=36)
    assert 1 <= tr.periodic_iterations <= 10 and tr.periodic_residual < 1e-6
    assert tr.gamma[-1] == pytest.approx(tr.gamma[0], abs=1e-5)  # tol + dense-output error
    assert (tr.delta[-1] - tr.delta[0]) == pytest.approx(0.0, abs=1e-5)


def test_rupture_event_gives_a_clear_result(plain_pump):
    # ten times the viscosity-speed load factor: at 60 % of the clearance as the bound, the film "ruptures"
    pump = dataclasses.replace(plain_pump, viscosity=0.003)
    tr = bf.simulate(pump, pump_mesh(pump, SIZE), 1.0, min_film=0.6 * pump.clearance, points_per_revolution=36)
    assert tr.status == "ruptured"
    assert "ruptured" in tr.message and "beta" in tr.message
    assert 0 < tr.rupture_beta < 2 * math.pi
    assert tr.beta[-1] == pytest.approx(tr.rupture_beta)
    assert tr.h_min[-1] == pytest.approx(0.6 * pump.clearance, rel=1e-6)  # bisection on the dense output
    for name, col in tr.columns().items():
        assert np.all(np.isfinite(col)), name


def test_lift_off_is_detected_before_integrating(pump):
    big = bf.Surface(arc=pump.surface.arc, half_width=pump.surface.half_width, inlets=(bf.Circle((0, 0), 0.3),))
    lifted = dataclasses.replace(pump, surface=big)
    mesh = pump_mesh(lifted, SIZE)
    assert bf.balance_ratio(lifted, mesh) > 1
    with pytest.raises(LiftOffError, match="balance ratio"):
        bf.simulate(lifted, mesh)


def test_missing_steady_state_is_reported_with_its_cause(pump):
    # A 12 % pocket placed upstream (35 % along the arc) during discharge: its hydrostatic force has a
    # component the wedge cannot balance. Measured: over gamma in [0.02, 0.98] x delta in [0, 2 pi)
    # (25 x 73 grid, P1) the smallest relative force residual is 0.05, at gamma = 0.94 -- no steady
    # state short of contact, so the error is physical, not the solver's. The message says so.
    from bearingfe.sweep import pocket_fraction, pocket_position
    from bearingfe.transient import steady_state
    upstream = dataclasses.replace(pump, surface=pocket_position(pocket_fraction(pump.surface, 0.12), 0.35))
    with pytest.raises(RuntimeError, match="no steady state.*cannot carry this load.*periodic"):
        steady_state(upstream, pump_mesh(upstream, SIZE), beta=math.pi / 2)


def test_balance_ratio_of_the_shipped_pump(pocket_mesh, pump, plain_pump):
    # pocket 10 %: hydrostatic lift a little below the plunger force (the TOML's design note)
    assert 0.8 < bf.balance_ratio(pump, pocket_mesh) < 0.95
    assert bf.balance_ratio(plain_pump) == 0.0


def test_bad_options_raise_value_errors(plain_mesh, plain_pump):
    with pytest.raises(ValueError, match="cavitation"):
        bf.simulate(plain_pump, plain_mesh, cavitation="bogus")
    with pytest.raises(ValueError, match="revolutions"):
        bf.simulate(plain_pump, plain_mesh, revolutions=0)
    with pytest.raises(ValueError, match="method"):
        bf.simulate(plain_pump, plain_mesh, method="Euler")
    with pytest.raises(ValueError, match="start"):
        bf.simulate(plain_pump, plain_mesh, start=(0.5, "x"))
    # gamma = 0 is the concentric shoe: delta undefined, squeeze rates singular; refused before any step
    with pytest.raises(ValueError, match=r"start gamma must be > 0"):
        bf.simulate(plain_pump, plain_mesh, start=(0.0, 0.3))
    with pytest.raises(ValueError, match=r"start \(gamma, delta\) must be two finite numbers"):
        bf.simulate(plain_pump, plain_mesh, start=(math.nan, 0.3))
    # h = 1 + gamma cos(phi - delta): gamma = 1.5 with delta at the arc's middle plus pi leaves a negative film there
    middle = float(np.mean(plain_mesh.mesh.p[0][[plain_mesh.mesh.p[0].argmin(), plain_mesh.mesh.p[0].argmax()]]))
    with pytest.raises(ValueError, match=r"min_film"):
        bf.simulate(plain_pump, plain_mesh, start=(1.5, middle + math.pi))
