"""Hard cases of the FEM Reynolds solver, at fast sizes.

Each case either converges, with an error estimate that the test bounds, or
fails with a clear message; none may return NaN. Error estimates are the
difference between two independent discretizations (pi vs direct form,
or two meshes); where a closed form or a converged reference exists it is
named in the comment.
"""

import math
import warnings
from dataclasses import dataclass

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.reynolds import operators


def _finite(res):
    assert np.all(np.isfinite(res.pressure)) and np.all(np.isfinite(res.force))
    assert all(math.isfinite(v) for v in res.flows.values()) and math.isfinite(res.mass_balance)


def _rel(a, b):
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b)) / np.linalg.norm(b))


# -- eccentricity 0.99 and 0.995 (no cavitation) ------------------------------------------

@pytest.mark.parametrize("gamma", [0.99, 0.995])
@pytest.mark.parametrize("arc", [(-1.0, 1.0), (0.0, 2 * math.pi)], ids=["partial", "full"])
def test_high_eccentricity_converges(gamma, arc):
    thin = 0.5 * (arc[0] + arc[1])  # thinnest film in the middle of the arc
    film = bf.CosineFilm(gamma, thin + math.pi)
    h_min = 1.0 - gamma
    size = 0.1

    def graded(phi, z):  # element size ~ the film-thickness length scale sqrt(h) near the gap
        return size * np.clip(np.sqrt(0.25 * (phi - thin) ** 2 + h_min) / 0.5, 0.02, 1.0)

    mesh = bf.mesh_surface(bf.Surface(arc=arc, half_width=0.5), size, order=2, size_function=graded)
    pi = bf.solve_reynolds(mesh, film, element="P2", formulation="pi")
    direct = bf.solve_reynolds(mesh, film, element="P2", formulation="direct")
    for r in (pi, direct):
        _finite(r)
        assert r.h_min == pytest.approx(h_min, rel=1e-12)  # exact minimum of the cosine film on the arc
    # error estimate: two discretizations of the same problem agree (measured 4e-5 .. 7e-5 at this size;
    # on the mesh twice as fine they agree to 3e-6 and move < 2e-5 from these)
    assert _rel(pi.force, direct.force) < 3e-4
    # peak pressure ~ 1/h_min^2 scale: it must be large, not clipped or blown up (measured 908 and 2593)
    assert 5e2 < direct.max_pressure < 5e3
    # direct form: the flux balance closes to rounding (consistent fluxes)
    assert abs(direct.mass_balance) < 1e-10 * max(1.0, abs(direct.flows["arc_start"]))


def test_contact_is_a_clear_error_not_nan():
    mesh = bf.mesh_surface(bf.Surface(arc=(0.0, 2 * math.pi), half_width=0.5), 0.3)
    with pytest.raises(ValueError, match="h_min"):
        bf.solve_reynolds(mesh, bf.CosineFilm(1.0, 0.0))


# -- tiny pocket, pocket near the edge, very high inlet pressure --------------------------

def test_pocket_of_a_thousandth_of_the_area_converges():
    area = 2.0  # arc (-1, 1) x (-0.5, 0.5)
    r0 = math.sqrt(1e-3 * area / math.pi)
    surface = bf.Surface(arc=(-1.0, 1.0), half_width=0.5, inlets=(bf.Circle((0.0, 0.0), r0),))
    assert surface.inlet_fraction == pytest.approx(1e-3, rel=1e-12)
    film = bf.CosineFilm(0.4, math.pi)
    loads = []
    for size, inlet in ((0.1, 0.004), (0.05, 0.002)):
        mesh = bf.mesh_surface(surface, size, inlet_size=inlet, grading_distance=0.2, order=2)
        res = bf.solve_reynolds(mesh, film, element="P2", inlet_pressure=100.0)
        _finite(res)
        loads.append(res.integral)
    # The pocket's hydrostatic load is a log-capacity effect: ~ p_s * 2 pi / ln(R/r0) * (domain factor),
    # well above the pocket's own area times p_s (0.2) -> check it is carried and converged.
    assert loads[1] > 10 * 100.0 * 1e-3 * area
    assert abs(loads[0] - loads[1]) / abs(loads[1]) < 2e-3  # error estimate between the two meshes


def test_pocket_one_percent_of_the_width_from_the_edge():
    a = 0.5
    gap = 0.01 * 2 * a
    pocket = bf.Rectangle((0.0, a - gap - 0.1), (0.4, 0.2))  # upper edge at z = a - gap
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=a, inlets=(pocket,))
    assert surface.min_gap() == pytest.approx(gap, rel=1e-9)
    film = bf.CosineFilm(0.5, math.pi)
    out = []
    for size in (0.1, 0.05):
        mesh = bf.mesh_surface(surface, size, corner_size=size / 4)
        res = bf.solve_reynolds(mesh, film, element="P2", formulation="direct", inlet_pressure=100.0)
        _finite(res)
        out.append(res)
    # the thin land leaks: side flow ~ h^3/12 * p_s / gap * length; with h ~ 0.5-1 that is O(10..80)
    side = out[1].flows["side"]
    assert 10 < side < 200
    assert abs(out[1].mass_balance) < 1e-10 * side  # consistent flux balance of the direct form
    assert abs(out[0].flows["inlet"] / out[1].flows["inlet"] - 1) < 0.02  # mesh error estimate of the flow
    assert _rel(out[0].force, out[1].force) < 2e-3


def test_inlet_pressure_ten_thousand_times_the_hydrodynamic_scale():
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(bf.Circle((0.0, 0.0), 0.15),))
    mesh = bf.mesh_surface(surface, 0.08, order=2)
    film = bf.CosineFilm(0.5, math.pi)
    sup = bf.superpose(mesh, film, element="P2")
    wedge_only = sup.combine(1.0, (0.0, 0.0), 0.0)
    ps = 1e4 * max(1.0, wedge_only.max_pressure)  # 10^4 times the hydrodynamic pressure scale
    res = bf.solve_reynolds(mesh, film, element="P2", inlet_pressure=ps)
    _finite(res)
    assert res.max_pressure == pytest.approx(ps, rel=1e-12)
    # p stays within [min of the wedge field, p_s] up to the wedge field itself (maximum principle)
    assert res.pressure.min() > wedge_only.pressure.min() - 1e-9 * ps
    # linearity survives the 1e4 scale ratio: the wedge part is recovered from the difference to rounding
    unit = sup.combine(0.0, (0.0, 0.0), 1.0)
    recovered = res.force - ps * unit.force
    assert np.allclose(recovered, wedge_only.force, rtol=0, atol=1e-10 * ps * np.abs(unit.force).max())
    # pi form: the flux balance is its discretization error, not rounding (measured 4.6e-5 of the inlet flow)
    assert abs(res.mass_balance) < 1e-3 * res.flows["inlet"]


# -- long domain: the pi operator's coercivity check --------------------------------------

def test_long_domain_pi_operator_bound_fails_exact_check_passes():
    # Lead's analysis: int |grad Pi|^2 - D Pi^2 = int h^3 |grad(Pi h^-3/2)|^2 > 0, so the continuous pi
    # operator is always coercive; only the cheap sufficient bound pi^2 (1/L^2 + 1/W^2) > max D fails on a
    # long, wide domain. Here L = 2 pi, W = 6: bound 0.524 < max D ~ 0.71 (gamma = 0.9).
    surface = bf.Surface(arc=(-math.pi, math.pi), half_width=3.0)
    film = bf.CosineFilm(0.9, math.pi)
    for size, element, tol in ((0.6, "P1", None), (0.3, "P2", 5e-3)):
        mesh = bf.mesh_surface(surface, size, order=2 if element == "P2" else 1)
        ops = operators(mesh, element)
        x = ops.x
        h = film.thickness(x[0], x[1])
        d_max = float(np.max(0.75 * (3 * h**2 - 4 * h + 1 - film.gamma**2) / h**2))  # D of the cosine film, docs/formulations.md
        assert ops.eigen_bound < d_max  # the cheap bound cannot decide
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            pi = bf.solve_reynolds(mesh, film, element=element, formulation="pi", on_indefinite="raise")
        # the 0.6 P1 mesh is deliberately coarse: the film changes by ~2 h across an element where h = 0.136
        # (bearingfe.core.checks limit: 1 h), so the solve must say so; the 0.3 mesh is within the limit
        coarse = any(issubclass(w.category, bf.ResolutionWarning) for w in caught)
        assert coarse == (size == 0.6)
        _finite(pi)
        assert pi.formulation == "pi" and not any("direct form" in n for n in pi.notes)  # no fallback
        assert pi.coercivity > 0.1  # exact smallest eigenvalue (measured 1.9: far from indefinite)
        if tol is not None:  # pi and direct forms converge to the same load (measured 1.7e-3 here)
            direct = bf.solve_reynolds(mesh, film, element=element, formulation="direct")
            assert _rel(pi.force, direct.force) < tol


@dataclass(frozen=True)
class _InconsistentFilm:
    """h = 1 but a Laplacian of -20: D = 15 makes -Laplace - D indefinite on a 2 x 1 domain
    (first Dirichlet eigenvalue pi^2 (1/4 + 1) = 12.3 < 15). It declares itself smooth: a film that does
    not is measured first, and this one's Laplacian disagrees with its thickness, which sends it to the
    direct form before the coercivity test (tests/test_films.py)."""

    smooth = True

    def thickness(self, phi, z):
        return np.ones(np.broadcast(phi, z).shape)

    def gradient(self, phi, z):
        zero = np.zeros(np.broadcast(phi, z).shape)
        return zero, zero

    def laplacian(self, phi, z):
        return -20.0 * np.ones(np.broadcast(phi, z).shape)

    def rate_shapes(self, phi, z):
        one = np.ones(np.broadcast(phi, z).shape)
        return one, 0 * one

    def minimum(self, phi_range):
        return 1.0


def test_indefinite_pi_operator_is_detected():
    mesh = bf.mesh_surface(bf.Surface(arc=(-1.0, 1.0), half_width=0.5), 0.1)
    with pytest.raises(bf.CoercivityError, match="not positive definite"):
        bf.solve_reynolds(mesh, _InconsistentFilm(), squeeze=(1.0, 0.0), formulation="pi", on_indefinite="raise")
    res = bf.solve_reynolds(mesh, _InconsistentFilm(), squeeze=(1.0, 0.0), formulation="pi")
    _finite(res)
    assert res.formulation == "direct" and "direct form" in res.notes[0]
    assert res.coercivity < 0


# -- rectangular recess corners --------------------------------------------------------------

def test_recess_corner_refinement_converges():
    eps = 1e-9
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.5,
                         inlets=(bf.Rectangle((0.0, 0.0), (0.48 + 2 * eps, 0.4 + 2 * eps)),))
    film = bf.CosineFilm(0.5, math.pi)
    # converged reference from benchmarks/work_precision.py case (b) (P2 direct, curved, graded):
    # load x-component 508.7522 at p_s = 1000 (2e5 dofs; moved 9e-6 from the mesh twice as coarse)
    reference = 508.7522
    errors = []
    for corner in (0.05, 0.0125, 0.003125):
        mesh = bf.mesh_surface(surface, 0.05, corner_size=corner, grading_distance=0.15)
        res = bf.solve_reynolds(mesh, film, element="P1", inlet_pressure=1000.0)
        _finite(res)
        errors.append(abs(res.force[0] / reference - 1))
    # corner refinement alone (same element size elsewhere) removes most of the singular error
    assert errors[1] < 0.5 * errors[0] and errors[2] < 0.7 * errors[1]
    assert errors[2] < 2e-3


# -- P2 on curved pocket boundaries ----------------------------------------------------------

def test_p2_needs_curved_geometry_on_curved_pockets():
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(bf.Circle((0.0, 0.0), 0.2),))
    film = bf.CosineFilm(0.0)  # h = 1: Laplace equation, the load is a pure geometry-and-element question
    ref_mesh = bf.mesh_surface(surface, 0.0125, order=2)  # converged reference: P2, curved, fine mesh
    reference = bf.solve_reynolds(ref_mesh, film, element="P2", wedge=0.0, inlet_pressure=1.0).integral
    sizes = (0.1, 0.05, 0.025)
    slopes = {}
    for order in (1, 2):
        errs = []
        for size in sizes:
            mesh = bf.mesh_surface(surface, size, order=order)
            res = bf.solve_reynolds(mesh, film, element="P2", wedge=0.0, inlet_pressure=1.0)
            _finite(res)
            errs.append(abs(res.integral / reference - 1))
        slopes[order] = np.polyfit(np.log(sizes), np.log(errs), 1)[0]
    # straight-sided triangles: the polygonal pocket costs O(h^2) in the load; curved edges restore
    # a higher rate (P2 theory: O(h^4) for a smooth functional; measured values in docs/benchmarks.md)
    assert 1.5 < slopes[1] < 2.6
    assert slopes[2] > slopes[1] + 1.0
