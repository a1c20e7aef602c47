"""The pump transient with the Swift-Stieber (Reynolds) cavitation condition.

Expected behaviour, from the model itself: with ``cavitation="reynolds"`` the
rates at every stored state come from the complementarity solve
(``bearingfe.cavitation.rates_for_load``), so the cavitated film force
balances the applied load (paper eq. 13-14) with ``p >= 0`` everywhere; where
the film never ruptures the trajectory is the uncavitated one.
"""

import dataclasses

import numpy as np
import pytest

import bearingfe as bf


def _wide(pump):
    """The shipped shoe widened to +-1.4 rad: its diverging ends rupture at low load."""
    return dataclasses.replace(pump, surface=bf.Surface(arc=(-1.4, 1.4), half_width=pump.surface.half_width))


def test_cavitated_states_balance_the_load_with_nonnegative_pressure(pump):
    wide = _wide(pump)
    mesh = bf.transient.pump_mesh(wide, 0.2)
    # the second half of the turn (suction, light load): the film ruptures from about 120 deg on
    run = dict(beta0=np.pi / 2, start="steady", points_per_revolution=24)
    traj = bf.simulate(wide, mesh, 0.5, cavitation="reynolds", **run)
    plain = bf.simulate(wide, mesh, 0.5, cavitation="none", **run)
    assert traj.status == "completed"
    model = bf.transient.Cavitating(wide, mesh, cavitation="reynolds", element="P1", solver="splu")
    ruptured = 0
    for k in range(0, traj.beta.size, 6):
        rates, res = model.balance(traj.beta[k], np.array([traj.gamma[k], traj.delta[k]]))
        # film force + applied load = 0 (Newton tolerance 1e-9 relative to the load)
        np.testing.assert_allclose(res.force, -traj.load[k], atol=1e-7 * np.abs(traj.load[k]).max())
        assert res.pressure.min() >= -1e-12
        ruptured += int(res.cavitated.sum())
    assert ruptured > 0, "the widened shoe should rupture during suction"
    # rupture changes the film: the trajectories differ by more than the integrator tolerance
    assert np.max(np.abs(traj.gamma - plain.gamma)) > 1e-4


def test_no_rupture_means_the_uncavitated_trajectory(pump):
    # the shipped shoe (+-0.6 rad) stays in full film at this load: both models agree to round-off
    mesh = bf.transient.pump_mesh(pump, 0.2)
    a = bf.simulate(pump, mesh, 0.25, start="steady", cavitation="none", points_per_revolution=24)
    b = bf.simulate(pump, mesh, 0.25, start="steady", cavitation="reynolds", points_per_revolution=24)
    np.testing.assert_allclose(b.h_min, a.h_min, rtol=1e-9)


def test_unknown_cavitation_model_is_named(pump):
    with pytest.raises(ValueError, match="cavitation must be one of"):
        bf.simulate(pump, None, 0.1, cavitation="swift")
