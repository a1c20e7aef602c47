"""An independent reference for the pump transient: paper 004's finite-difference scheme driving the
same quasi-static balance, integrated by an explicit Runge-Kutta method written here.

``bearingfe.simulate`` solves the film with finite elements (here P2 on a mesh of 0.1 R0), gets the
rates from its superposition (``transient._Model``) and integrates with LSODA. The reference shares none
of that: at every right-side evaluation it solves the five-point finite-difference Reynolds equation
(``bearingfe.solve_reynolds_fd``, the paper's scheme, a uniform grid) for the wedge/load part and for
unit squeeze rates, solves the 2x2 balance ``film force + plunger load = 0`` (paper eq. 13-14) for the
rates itself, and integrates with scipy's explicit RK45 (``solve_ivp``). Grid error is removed by
Richardson extrapolation of two grids (31 x 21 and 61 x 41 nodes; the scheme is second order).

Measured when this test was written (plain shoe of the shipped pump, one revolution from
gamma = 0.5, delta = pi, states every 45 deg): the Richardson value of the 31 x 21 / 61 x 41 pair
differs from that of the 61 x 41 / 121 x 81 pair by <= 2e-7 in gamma and <= 3e-6 rad in delta, and
the latter agrees with FEM P2 on 0.05 R0 to 1e-6 and 5e-6 rad: the two families converge to the same
trajectory. P2 on 0.1 R0 (used below) differs from P2 on 0.05 R0 by <= 5e-6 in gamma and <= 7e-5 rad
in delta; the tolerances below are three to four times that discretization error.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import bearingfe as bf

START = (0.5, math.pi)                       # (gamma, delta): off the periodic orbit, so the run has a transient
BETAS = np.radians(np.arange(0, 361, 30))    # states compared over one revolution (discharge and suction)
GRIDS = ((31, 21), (61, 41))                 # FD nodes (n_phi, n_z), spacing halved


def _fd_trajectory(pump, shape):
    """(gamma, delta) at BETAS from the FD film and the 2x2 balance, integrated by RK45."""

    def rates(beta, y):
        film = bf.CosineFilm(y[0], y[1])
        wedge = float(pump.wedge(beta))
        f0 = bf.solve_reynolds_fd(pump.surface, film, shape, wedge=wedge).force
        f_gamma = bf.solve_reynolds_fd(pump.surface, film, shape, wedge=0.0, squeeze=(1.0, 0.0)).force
        f_delta = bf.solve_reynolds_fd(pump.surface, film, shape, wedge=0.0, squeeze=(0.0, 1.0)).force
        return np.linalg.solve(np.column_stack([f_gamma, f_delta]), -(f0 + pump.load_vector(beta)))

    sol = solve_ivp(rates, (BETAS[0], BETAS[-1]), START, method="RK45", rtol=1e-8, atol=1e-10, t_eval=BETAS)
    assert sol.success, sol.message
    return sol.y.T


@pytest.mark.slow
def test_fem_lsoda_transient_matches_fd_runge_kutta_reference(plain_pump):
    coarse, fine = (_fd_trajectory(plain_pump, shape) for shape in GRIDS)
    reference = fine + (fine - coarse) / 3.0     # Richardson, second-order grid error
    assert np.max(np.abs(fine - coarse)) > 1e-4  # the grids do differ: the extrapolation is doing something

    mesh = bf.mesh_surface(plain_pump.surface, 0.1, order=2)
    tr = bf.simulate(plain_pump, mesh, 1.0, start=START, element="P2", rtol=1e-9, atol=1e-11,
                     points_per_revolution=360)
    assert tr.status == "completed"
    idx = np.rint(BETAS / (2 * math.pi) * 360).astype(int)
    np.testing.assert_allclose(tr.beta[idx], BETAS, atol=1e-12)
    np.testing.assert_allclose(tr.gamma[idx], reference[:, 0], rtol=0, atol=2e-5)
    np.testing.assert_allclose(tr.delta[idx], reference[:, 1], rtol=0, atol=2e-4)
    # the state moves by far more than the tolerances over the turn: the comparison has teeth
    assert np.ptp(reference[:, 0]) > 0.1 and np.ptp(reference[:, 1]) > 1.0
    # the smallest film over the arc at each compared state (a function of the state, brute force on the arc)
    psi = np.linspace(*plain_pump.surface.arc, 20001)
    h_ref = np.min(1 + reference[:, :1] * np.cos(psi[None, :] - reference[:, 1:]), axis=1) * plain_pump.clearance
    np.testing.assert_allclose(tr.h_min[idx], h_ref, rtol=1e-4)
