"""Observed convergence orders of the load on a smooth case.

Smooth case: rectangle [-0.5, 0.5] x [-0.4, 0.4], CosineFilm(0.6, 0.3)
(h in [0.47, 1.45]), wedge 1, squeeze (0.5, -0.3), no pocket. Nested meshes
from ``mesh_surface(..., refine=k)``. Reference: P2 (direct form) on the
mesh refined four times (size 0.0125); its error is ~2e-9, below 1 % of the
smallest error used in the fits (measured by comparison with refine=5:
P2 errors fall by 2^3.8 per halving).

Expected: the load is a smooth functional of the solution, so its error is
of order h^(2k) for Pk (P1: 2, P2: 4); the 90-degree corners of the
rectangle limit the regularity slightly (measured P2 slopes 3.67, 3.74,
3.79 per level, rising toward 4). Measured fitted slopes: P1 1.98 (direct
and pi), P2 3.70 (direct) and 3.69 (pi). The bands below would catch a
regression to a lower order (e.g. a load quadrature or a source term
computed to first order).
"""

import numpy as np
import pytest

from bearingfe import CosineFilm, Surface, mesh_surface, solve_reynolds

SURFACE = Surface(arc=(-0.5, 0.5), half_width=0.4)
FILM = CosineFilm(0.6, 0.3)
OPERATING = dict(wedge=1.0, squeeze=(0.5, -0.3))


@pytest.fixture(scope="module")
def meshes():
    return [mesh_surface(SURFACE, 0.2, refine=k) for k in range(5)]


@pytest.fixture(scope="module")
def reference(meshes):
    return solve_reynolds(meshes[4], FILM, element="P2", formulation="direct", **OPERATING)


def slope(sizes, errors) -> float:
    return float(np.polyfit(np.log(sizes), np.log(errors), 1)[0])


def load_errors(meshes, levels, element, formulation, reference):
    sizes, errors = [], []
    for k in levels:
        res = solve_reynolds(meshes[k], FILM, element=element, formulation=formulation, **OPERATING)
        sizes.append(meshes[k].size)
        errors.append(np.hypot(*(res.force - reference.force)))
    return np.array(sizes), np.array(errors)


@pytest.mark.parametrize("formulation", ["direct", "pi"])
def test_p1_load_converges_at_second_order(meshes, reference, formulation):
    sizes, errors = load_errors(meshes, range(1, 5), "P1", formulation, reference)
    assert 1.85 < slope(sizes, errors) < 2.2
    # and the error is small in absolute terms (load ~0.042; measured 1.3e-5 at size 0.0125)
    assert errors[-1] < 3e-5


@pytest.mark.parametrize("formulation", ["direct", "pi"])
def test_p2_load_converges_at_nearly_fourth_order(meshes, reference, formulation):
    sizes, errors = load_errors(meshes, range(0, 3), "P2", formulation, reference)
    assert 3.4 < slope(sizes, errors) < 4.3
    assert errors[-1] < 1e-6  # measured 4e-7 at size 0.05


def test_reference_is_converged(meshes, reference):
    # the reference differs from the next-coarser P2 solution by the latter's error (~3e-8),
    # so the reference itself is at least ten times better than anything fitted above
    coarser = solve_reynolds(meshes[3], FILM, element="P2", formulation="direct", **OPERATING)
    assert np.hypot(*(coarser.force - reference.force)) < 1e-7
    assert abs(coarser.integral - reference.integral) < 1e-7


@pytest.mark.parametrize("element, levels, rate", [("P1", (2, 3, 4), 2.0), ("P2", (0, 1, 2), 3.5)])
def test_pi_and_direct_agree_to_discretization_error(meshes, reference, element, levels, rate):
    # both discretize the same equation: their difference is bounded by the discretization
    # error and shrinks at least about as fast as it (measured P1 difference 3e-6 vs error 2e-4)
    diffs = []
    for k in levels:
        pi = solve_reynolds(meshes[k], FILM, element=element, formulation="pi", **OPERATING)
        direct = solve_reynolds(meshes[k], FILM, element=element, formulation="direct", **OPERATING)
        diff = np.hypot(*(pi.force - direct.force))
        error = np.hypot(*(direct.force - reference.force))
        assert diff < error
        assert pi.formulation == "pi" and not any("direct form" in n for n in pi.notes)  # no fallback happened
        diffs.append(diff)
    sizes = [meshes[k].size for k in levels]
    assert slope(sizes, diffs) > rate - 0.3


def test_mass_balance_vanishes_with_refinement(meshes):
    direct, pi = [], []
    for k in range(4):
        direct.append(solve_reynolds(meshes[k], FILM, formulation="direct", **OPERATING).mass_balance)
        pi.append(solve_reynolds(meshes[k], FILM, formulation="pi", **OPERATING).mass_balance)
    # direct form: the residual is the discrete equation itself, zero up to quadrature of the
    # non-polynomial coefficients (measured 1.2e-11 on the coarsest mesh, then ~1e-15)
    assert np.abs(direct).max() < 1e-9
    # pi form: the flux of p = h^-3/2 Pi is not the discrete conservative flux; its imbalance is
    # a discretization error (measured 1.0e-4, 1.4e-5, 7.9e-7, -2.7e-7)
    assert abs(pi[3]) < 1e-6
    assert abs(pi[0]) > 10 * abs(pi[3])
