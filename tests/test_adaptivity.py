"""Error indicators and adaptive remeshing (bearingfe.adaptivity).

Expected values: closed forms (a linear pressure ramp, the 1-D Reynolds
solution of a film that varies along phi only), the converged loads
documented in docs/adaptivity.md (benchmarks/adaptivity.py) and
bearingfe.bearings.journal.performance on a fine graded mesh.
"""

import math
import warnings

import numpy as np
import pytest
import skfem
from scipy.integrate import quad

import bearingfe as bf
from bearingfe.adaptivity import AdaptivityError, adapt, error_indicators, load_indicators
from bearingfe.film.flows import ruptured_elements
from bearingfe.bearings.journal import ResolutionWarning, performance
from bearingfe.geometry.meshing import SupportMesh

# -- (a) indicators of exact and of smooth solutions ----------------------------------------

P_S = 3.0
ARC = (0.1, 0.5)  # the film right of a pocket strip |phi| <= 0.1 that spans the whole shoe


def strip_mesh(size, order):
    """The film beside a pocket strip across the whole shoe width (the 1-D case of
    tests/film/test_fd.py::test_pocket_strip_gives_linear_ramp without its end effects): the
    strip edge phi = 0.1 is the 'inlet', phi = 0.5 the 'outer' edge, and the shoe's
    sides z = +-0.5 are sealed (natural condition h^3 dp/dz = 0), so the pressure
    depends on phi only. An unstructured gmsh mesh, so that edges cross the ramp at
    every angle."""
    m = bf.mesh_surface(bf.Surface(arc=ARC, half_width=0.5), size, order=order)
    b = m.boundaries
    return SupportMesh(m.mesh.with_boundaries({"inlet": b["arc_start"], "outer": b["arc_end"]}), surface=None)


@pytest.mark.parametrize("element,order", [("P1", 1), ("P2", 2)])
@pytest.mark.parametrize("formulation", ["pi", "direct"])
def test_indicators_vanish_on_an_exact_linear_ramp(element, order, formulation):
    # h = 1, no wedge or squeeze: p = p_s (0.5 - phi) / 0.4 (closed form), which P1 and P2
    # represent exactly, so both residuals (div q = 0 inside, [q.n] = 0 across edges) and
    # the sealed-side flux dp/dz vanish up to round-off
    mesh = strip_mesh(0.1, order)
    r = bf.solve_reynolds(mesh, bf.CosineFilm(0.0), wedge=0.0, inlet_pressure=P_S, formulation=formulation,
                          element=element)
    exact = P_S * (0.5 - r.basis.doflocs[0]) / 0.4
    np.testing.assert_allclose(r.pressure, exact, atol=1e-12)
    flux_scale = P_S / 0.4 / 12.0 * 0.1  # |q| times an element size
    for norm in ("flux", "energy"):
        assert error_indicators(r, norm=norm).max() < 1e-12 * flux_scale  # measured ~1e-15
    # the same mesh with a varying film and a wedge: the indicators do see an error
    r = bf.solve_reynolds(mesh, bf.CosineFilm(0.3, 1.0), wedge=1.0, inlet_pressure=P_S,
                          formulation=formulation, element=element)
    assert error_indicators(r).max() > 1e-6 * flux_scale


def exact_1d(film):
    """Closed form of the 1-D problem of strip_mesh with wedge 1: (h^3 p')' = 6 h', so
    h^3 p' = 6 h + C with C from p(0.1) = p_s, p(0.5) = 0."""
    i2 = quad(lambda s: film.thickness(s, 0.0) ** -2, *ARC)[0]
    i3 = quad(lambda s: film.thickness(s, 0.0) ** -3, *ARC)[0]
    c = (-P_S - 6.0 * i2) / i3
    return lambda phi: (6.0 * film.thickness(phi, 0.0) + c) / film.thickness(phi, 0.0) ** 3  # p'


@pytest.mark.parametrize("element,order", [("P1", 1), ("P2", 2)])
def test_energy_indicator_is_reliable_and_efficient(element, order):
    # sum eta^2 (norm="energy") against the true energy error int h^3/12 |grad(p - p_h)|^2 of the
    # closed-form 1-D solution: the ratio (efficiency index) must lie above 1 (reliable with
    # constant 1), below a fixed constant and not drift under refinement (the estimator and the
    # error converge at the same rate). Measured on sizes 0.1, 0.05, 0.025 and three films:
    # P1 5.4-5.7, P2 9.0-9.9, pi and direct alike (typical of the diameter-weighted estimator).
    film = bf.CosineFilm(0.5, 2.0)
    dp_exact = exact_1d(film)
    ratios = {}
    for size in (0.1, 0.05):
        mesh = strip_mesh(size, order)
        for formulation in ("pi", "direct"):
            r = bf.solve_reynolds(mesh, film, wedge=1.0, inlet_pressure=P_S, formulation=formulation,
                                  element=element)
            x = np.array(r.basis.global_coordinates())
            u = r.pressure if formulation == "direct" else r.pressure * film.thickness(*r.basis.doflocs) ** 1.5
            field = r.basis.interpolate(u)
            h = film.thickness(x[0], x[1])
            if formulation == "direct":
                dp = np.array(field.grad)
            else:  # p = h^(-3/2) Pi
                dh = np.array(film.gradient(x[0], x[1]))
                dp = h**-1.5 * np.array(field.grad) - 1.5 * h**-2.5 * np.array(field) * dh
            error = math.sqrt(np.sum(h**3 / 12 * ((dp[0] - dp_exact(x[0])) ** 2 + dp[1] ** 2) * r.basis.dx))
            estimate = math.sqrt(np.sum(error_indicators(r, norm="energy") ** 2))
            ratios[size, formulation] = estimate / error
            assert 1.0 < estimate / error < 12.0, (element, size, formulation, estimate / error)
    for formulation in ("pi", "direct"):
        assert ratios[0.05, formulation] == pytest.approx(ratios[0.1, formulation], rel=0.15)


# -- cavitation: no indicator where the film has ruptured -------------------------------------

def test_ruptured_elements_get_zero():
    mesh = bf.mesh_surface(bf.Surface(arc=(0, 2 * math.pi), half_width=0.5), 0.2)
    r = bf.solve_reynolds(mesh, bf.CosineFilm(0.9, 0.0), formulation="direct", cavitation="reynolds")
    ruptured = ruptured_elements(r.basis.element_dofs, r.pressure, r.cavitated)
    assert 0.2 < ruptured.mean() < 0.6  # about half the bearing ruptures (Swift-Stieber)
    for eta in (error_indicators(r), error_indicators(r, norm="energy"), load_indicators(r)):
        assert np.all(eta[ruptured] == 0.0)
        assert np.all(eta >= 0.0)
        assert np.mean(eta[~ruptured] > 0) > 0.99  # the full film has residuals everywhere


def test_curved_mesh_with_tiny_elements_solves():
    # regression: scikit-fem's inverse isoparametric mapping (Newton to 1e-12 in reference
    # coordinates) never stopped on curved elements of 2e-5 at 0.3 from the origin, so the
    # pocket moments of a finely graded P2 mesh failed; bearingfe.reynolds stops at 1e-9
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(bf.Rectangle((0.3, 0.2), (0.2, 0.1)),))
    mesh = bf.mesh_surface(surface, 0.1, corner_size=2e-5, min_size=1e-5, grading_distance=0.05, order=2)
    with pytest.raises(Exception, match="Newton"):  # the default mapping: the failure this guards
        skfem.FacetBasis(mesh.mesh, skfem.ElementTriP1(), facets=mesh.boundaries["inlet"], intorder=8)
    r = bf.solve_reynolds(mesh, bf.CosineFilm(0.3), inlet_pressure=10.0, element="P2")
    graded = bf.solve_reynolds(bf.mesh_surface(surface, 0.1, corner_size=1e-3, grading_distance=0.05, order=2),
                               bf.CosineFilm(0.3), inlet_pressure=10.0, element="P2")
    # the same mesh away from the corners with corner elements of 1e-3 (which the default
    # mapping handles): the loads differ by that mesh's corner error (measured 8.2e-4 relative)
    assert np.linalg.norm(r.force - graded.force) < 2e-3 * np.linalg.norm(r.force)
    assert np.all(error_indicators(r) >= 0)


# -- (b) sharp rectangular recess: fewer nodes than uniform meshes ------------------------

EPS = 1e-9  # benchmarks/work_precision.py case (b): pocket edges a hair off the FD grid lines
RECESS = bf.Surface(arc=(-0.6, 0.6), half_width=0.5,
                    inlets=(bf.Rectangle((0.0, 0.0), (0.48 + 2 * EPS, 0.4 + 2 * EPS)),))
RECESS_FILM = bf.CosineFilm(0.5, math.pi)
# Converged load of case (b): docs/adaptivity.md (benchmarks/adaptivity.py), Richardson extrapolation
# of the adaptive P2 levels at 7173, 21404, 61175 nodes, 508.7498089, uncertainty 1.8e-6 (an
# independent corner-graded P2 family extrapolates to 1.8e-6 below it, the FD LU Richardson value of
# docs/benchmarks.md, 508.74994, is 2.6e-7 above). The tests below resolve errors of 1e-3.
RECESS_LOAD = 508.74981


def test_recess_adaptive_beats_uniform():
    run = adapt(RECESS, RECESS_FILM, size=0.1, tol=5e-3, inlet_pressure=1000.0, element="P1")
    assert run.converged and run.reason == "converged"
    err = abs(run.load / RECESS_LOAD - 1)
    assert err < run.error_estimate  # the load change overestimates the error (measured 1.1e-3 < 3.3e-3)
    n_adaptive = run.levels[-1].n_nodes
    nodes, errors = [], []
    for size in (0.05, 0.025, 0.0125):  # uniform P1 (errors measured 6.7e-3, 2.6e-3, 1.0e-3)
        mesh = bf.mesh_surface(RECESS, size)
        r = bf.solve_reynolds(mesh, RECESS_FILM, inlet_pressure=1000.0, formulation="direct")
        nodes.append(mesh.n_nodes)
        errors.append(abs(np.linalg.norm(r.force) / RECESS_LOAD - 1))
    # nodes a uniform mesh needs for the adaptive error (log-log interpolation of its sweep)
    slope, intercept = np.polyfit(np.log(errors), np.log(nodes), 1)
    n_uniform = math.exp(intercept + slope * math.log(err))
    assert n_uniform > 3 * n_adaptive  # measured 4.3x (1634 vs ~7100 nodes)
    # the levels are nested refinements: nodes grow, the estimate falls
    assert all(b.n_nodes > a.n_nodes for a, b in zip(run.levels, run.levels[1:]))
    assert np.all(np.diff([lv.estimate for lv in run.levels[1:]]) < 0)


# -- (c) cavitated full journal -------------------------------------------------------------

# Converged load of CosineFilm(0.9) on arc (0, 2 pi), half-width 0.5, Swift-Stieber: docs/adaptivity.md
# case (c), Richardson extrapolation of graded P2 (film_graded_size, sizes 0.1, 0.05, 0.025),
# 10.18884358, and of adaptive P2 levels, 10.18884581 (they differ by 2.2e-7).
JOURNAL_LOAD = 10.188844


def test_cavitated_journal_converges_and_agrees_with_performance():
    run = adapt(bf.Surface(arc=(0, 2 * math.pi), half_width=0.5), bf.CosineFilm(0.9, 0.0), size=0.3, tol=1e-3,
                element="P2", cavitation="reynolds", formulation="direct")
    assert run.converged
    assert run.result.cavitation == "reynolds" and run.result.cavitated.any()
    assert run.error_estimate < 1e-3
    # within its own estimate of the converged value (measured error 3.1e-5, estimate 4.1e-5)
    assert abs(run.load / JOURNAL_LOAD - 1) < run.error_estimate
    # bearingfe.bearings.journal.performance: graded mesh, refined once, with its own refinement estimate
    # (measured: 10.17945, estimate 2.8e-3; difference 8.9e-4)
    perf = performance(bf.JournalBearing(0.5), 0.9, size=0.08, estimate_error=True)
    assert abs(run.load - perf.load) / perf.load < perf.error_estimate + run.error_estimate


def test_remeshing_keeps_curved_pockets_and_named_boundaries():
    # every level is meshed by gmsh from the surface: pocket nodes lie on the exact circle and the
    # named boundaries survive (the pocket of radius 0.1 at (0.1, 0.05) is 'inlet' and 'inlet_0')
    surface = bf.Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=(bf.Circle((0.1, 0.05), 0.1),))
    run = adapt(surface, bf.CosineFilm(0.4, 2.5), size=0.1, tol=1e-2, inlet_pressure=50.0, element="P2")
    mesh = run.mesh
    assert len(run.levels) >= 2 and run.levels[-1].n_nodes > run.levels[0].n_nodes
    assert {"outer", "inlet", "inlet_0", "arc_start", "arc_end", "side"} <= set(mesh.boundaries)
    facets = mesh.mesh.facets[:, mesh.boundaries["inlet"]]
    xy = mesh.mesh.p[:, np.unique(facets)]
    np.testing.assert_allclose(np.hypot(xy[0] - 0.1, xy[1] - 0.05), 0.1, atol=1e-12)
    assert mesh.geometry_order == 2  # P2 runs on curved (order-2) geometry


# -- (d) bad inputs and stopping without convergence --------------------------------------

@pytest.mark.parametrize("kwargs,name", [
    ({"size": -0.1}, "size"), ({"size": math.nan}, "size"), ({"tol": 0.0}, "tol"), ({"tol": 1.5}, "tol"),
    ({"max_levels": 1}, "max_levels"), ({"max_levels": 2.5}, "max_levels"), ({"min_size": 0.2}, "min_size"),
    ({"min_size": -1.0}, "min_size"), ({"growth": 1.0}, "growth"), ({"growth": 100}, "growth"),
    ({"max_nodes": 10}, "max_nodes"), ({"element": "P3"}, "element"), ({"formulation": "fd"}, "formulation"),
    ({"cavitation": "elrod"}, "cavitation"), ({"indicator": "hessian"}, "indicator"),
    ({"on_unconverged": "ignore"}, "on_unconverged"),
])
def test_bad_inputs_raise_value_error_naming_the_parameter(kwargs, name):
    args = dict(size=0.1) | kwargs
    with pytest.raises(ValueError, match=name):
        adapt(RECESS, RECESS_FILM, inlet_pressure=1000.0, **args)


def test_bad_surface_film_and_result():
    with pytest.raises(ValueError, match="surface"):
        adapt("shoe", RECESS_FILM, size=0.1)
    with pytest.raises(ValueError, match="film"):
        adapt(RECESS, 0.5, size=0.1)
    with pytest.raises(ValueError, match="result"):
        error_indicators(np.zeros(3))
    r = bf.solve_reynolds(strip_mesh(0.1, 1), bf.CosineFilm(0.0), wedge=0.0, inlet_pressure=1.0)
    with pytest.raises(ValueError, match="norm"):
        error_indicators(r, norm="l2")
    with pytest.raises(ValueError, match="max_nodes"):  # the first mesh is already too big
        adapt(RECESS, RECESS_FILM, size=0.01, max_nodes=1000, inlet_pressure=1000.0)
    with pytest.raises(ValueError, match="load"):  # no film force: a relative load change is undefined
        adapt(bf.Surface(), bf.CosineFilm(0.0), size=0.2)


def test_max_levels_without_convergence_warns_or_raises_with_the_cause():
    with pytest.warns(ResolutionWarning, match="max_levels=2"):
        run = adapt(RECESS, RECESS_FILM, size=0.1, tol=1e-6, max_levels=2, inlet_pressure=1000.0)
    assert not run.converged and "max_levels=2" in run.reason
    assert len(run.levels) == 2 and run.levels[-1].estimate >= 1e-6
    with pytest.raises(AdaptivityError, match="max_levels=2"):
        adapt(RECESS, RECESS_FILM, size=0.1, tol=1e-6, max_levels=2, inlet_pressure=1000.0,
              on_unconverged="raise")


def test_min_size_that_stops_the_refinement_is_named():
    # min_size = size/2: the corner elements cannot refine as asked (h/4 < min_size)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = adapt(RECESS, RECESS_FILM, size=0.1, tol=1e-6, max_levels=3, min_size=0.05, inlet_pressure=1000.0)
    assert "min_size=0.05" in run.reason
    assert any("min_size=0.05" in str(w.message) for w in caught)
    assert run.levels[-1].smallest_size > 0.03  # gmsh honours the floor (edges ~ size within 40 %)
