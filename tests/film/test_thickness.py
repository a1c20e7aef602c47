"""Film models with tapers and steps, and the wedge source that takes a step exactly.

Expected values come from closed forms of the 1-D and the finite-width slider
(:mod:`bearingfe.validation`: the piecewise-constant film, the inclined slider,
the Rayleigh step and its Fourier series), whose own optima are checked against
the published ones (Hamrock, Schmid & Jacobson, ch. 8-9: 0.16024 at
h_in/h_out = 2.1887; 0.20627 at H = 1.8660, alpha = 0.7182).
"""

import math

import numpy as np
import pytest
from scipy.optimize import minimize

import bearingfe as bf
from bearingfe.geometry.meshing import grid_mesh, strip_mesh
from bearingfe.validation import (PocketSlider, film_steps, inclined_slider_load, rayleigh_step, rayleigh_step_load,
                                  stepped_slider)

RAYLEIGH = dict(h1=1.866, h2=1.0, a=0.7)


def rayleigh_film(h1: float, h2: float, a: float) -> bf.ProfileFilm:
    return bf.ProfileFilm(((0.0, h1), (a, h1), (a, h2), (1.0, h2)))


def test_the_closed_forms_have_the_published_optima():
    best = minimize(lambda x: -inclined_slider_load(x[0], 1.0), [2.0], method="Nelder-Mead",
                    options={"xatol": 1e-8, "fatol": 1e-14})
    assert best.x[0] == pytest.approx(2.1887, abs=1e-4) and -best.fun == pytest.approx(0.16024, abs=5e-6)
    best = minimize(lambda x: -stepped_slider(h1=x[0], h2=1.0, a=x[1])[1], [1.8, 0.7], method="Nelder-Mead",
                    options={"xatol": 1e-8, "fatol": 1e-14})
    assert best.x == pytest.approx([1.8660, 0.7182], abs=1e-4)
    assert -best.fun == pytest.approx(0.20627, abs=5e-6)


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("formulation", ["direct", "pi"])
def test_rayleigh_step_on_a_strip_is_exact(element, formulation):
    # the step on an element edge, lands of uniform film: p is piecewise linear, so P1 and P2 are exact; the
    # pi form is not defined for a step, so the solver takes the direct form and says so
    mesh = strip_mesh(50, rows=1)
    width = float(np.ptp(mesh.mesh.p[1]))
    res = bf.solve_reynolds(mesh, rayleigh_film(**RAYLEIGH), element=element, formulation=formulation)
    flow, load = stepped_slider(**RAYLEIGH)
    assert res.formulation == "direct"
    assert (formulation == "pi") == any("kink or a step" in n for n in res.notes)
    assert res.integral / width == pytest.approx(load, rel=1e-10)
    assert res.flows["arc_end"] / width == pytest.approx(flow, rel=1e-10)
    assert abs(res.mass_balance) < 1e-10 * flow * width


def test_pocket_slider_film_on_the_galerkin_path():
    # validation.PocketSlider's film (a deeper pocket between two lands) without cavitation: three lands of
    # uniform film, exact piecewise-linear pressure (film_steps); the old pointwise dh/dphi source missed both
    # steps and gave zero pressure everywhere
    case = PocketSlider()
    L = case.length
    lands = [case.start / L, (case.end - case.start) / L, 1.0 - case.end / L]
    films = [1.0, case.h_in / case.h_out, 1.0]
    flow, pressures, load = film_steps(lands, films)
    mesh = strip_mesh(100, rows=1)
    width = float(np.ptp(mesh.mesh.p[1]))
    for element in ("P1", "P2"):
        res = bf.solve_reynolds(mesh, case.film(), element=element)
        assert res.integral / width == pytest.approx(load, rel=1e-9)
        assert float(res.interpolate(case.end / L, 0.0)) == pytest.approx(pressures[2], rel=1e-9)
        assert res.flows["arc_end"] / width == pytest.approx(flow, rel=1e-9)


def test_inclined_slider_converges_to_its_closed_form():
    film = bf.TaperFilm(h_in=2.1887, h_out=1.0, start=0.0, end=1.0)
    errors = []
    for n in (10, 20, 40):
        mesh = strip_mesh(n, rows=1)
        width = float(np.ptp(mesh.mesh.p[1]))
        res = bf.solve_reynolds(mesh, film, element="P2")
        errors.append(abs(res.integral / width / inclined_slider_load(2.1887, 1.0) - 1))
    assert res.formulation == "pi"  # the plane is smooth: the pi form is kept
    order = math.log2(errors[0] / errors[1]), math.log2(errors[1] / errors[2])
    assert min(order) > 3.5  # P2: the load converges at order 4 (observed 3.99, 4.00)
    assert errors[-1] < 1e-6
    assert res.integral / width == pytest.approx(0.16024, abs=1e-5)  # the optimum, to the table's digits


def test_rayleigh_step_at_its_optimum():
    # the step at alpha = 3591/5000 = 0.7182 on an element edge: the optimum coefficient to its five digits
    mesh = strip_mesh(5000, rows=1)
    width = float(np.ptp(mesh.mesh.p[1]))
    res = bf.solve_reynolds(mesh, rayleigh_film(1.8660, 1.0, 3591 / 5000), formulation="direct")
    assert res.integral / width == pytest.approx(0.20627, abs=5e-6)


def test_finite_width_rayleigh_step_converges_to_its_series():
    # p = 0 on the sides too: the Fourier series of validation.rayleigh_step_load; the step line on grid edges
    surface = bf.Surface(arc=(0.0, 1.0), half_width=0.5)
    exact = rayleigh_step_load(1.866, 1.0, 0.7, 1.0, 1.0)
    assert exact == pytest.approx(rayleigh_step_load(1.866, 1.0, 0.7, 1.0, 1.0, terms=8001), rel=1e-11)
    for element, sizes, order in (("P1", (0.05, 0.025), 1.9), ("P2", (0.1, 0.05), 3.5)):
        err = [abs(bf.solve_reynolds(grid_mesh(surface, s), rayleigh_film(**RAYLEIGH), formulation="direct",
                                     element=element).integral / exact - 1) for s in sizes]
        # observed P1: 4.5e-3, 1.1e-3 (order 2.0); P2: 1.3e-5, 7.2e-7 (order 4.2)
        assert math.log2(err[0] / err[1]) > order
    assert rayleigh_step(quick=True)[0].passed


def test_film_models_have_their_fields():
    phi = np.array([-0.2, 0.0, 0.3, 0.5, 0.8, 1.2])
    z = np.zeros_like(phi)
    taper = bf.TaperFilm(h_in=2.0, h_out=1.0, start=0.0, end=1.0)
    assert taper.thickness(phi, z) == pytest.approx(2.0 - phi) and taper.smooth
    assert taper.gradient(phi, z)[0] == pytest.approx(-np.ones_like(phi))
    assert taper.minimum((0.0, 1.0)) == 1.0
    land = bf.TaperLandFilm(h_land=1.0, depth=0.5, start=0.0, land_start=0.5)
    assert land.thickness(phi, z) == pytest.approx([1.5, 1.5, 1.2, 1.0, 1.0, 1.0]) and not land.smooth
    step = rayleigh_film(2.0, 1.0, 0.5)
    assert step.thickness(phi, z) == pytest.approx([2.0, 2.0, 2.0, 1.0, 1.0, 1.0])  # right-continuous at the step
    assert not step.smooth and step.minimum((0.0, 1.0)) == 1.0
    across = bf.ProfileFilm(((0.0, 2.0), (0.1, 1.0)), direction=math.pi / 2)  # varies along z only
    assert across.thickness(np.zeros(3), np.array([0.0, 0.05, 0.2])) == pytest.approx([2.0, 1.5, 1.0])
    assert across.minimum((0.0, 1.0)) is None
    region = bf.StepFilm(bf.Rectangle((0.5, 0.0), (0.2, 0.2)), 0.5, base=bf.UniformFilm(1.0))
    assert region.thickness(np.array([0.5, 0.0]), np.zeros(2)) == pytest.approx([1.5, 1.0])
    total = bf.CosineFilm(0.5) + land
    assert isinstance(total, bf.SumFilm) and not total.smooth
    assert total.thickness(phi, z) == pytest.approx(1 + 0.5 * np.cos(phi) + land.thickness(phi, z))
    assert total.rate_shapes(phi, z)[0] == pytest.approx(np.cos(phi))  # the base film's squeeze shapes


def test_bad_film_parameters_are_named():
    with pytest.raises(ValueError, match="TaperFilm.h_out must be a finite film thickness > 0"):
        bf.TaperFilm(h_in=2.0, h_out=0.0)
    with pytest.raises(ValueError, match="TaperFilm: abscissae must be strictly increasing"):
        bf.TaperFilm(h_in=2.0, h_out=1.0, start=1.0, end=1.0)
    with pytest.raises(ValueError, match="TaperLandFilm.depth must be a finite number >= 0"):
        bf.TaperLandFilm(h_land=1.0, depth=-1.0)
    with pytest.raises(ValueError, match="ProfileFilm: abscissae must be non-decreasing"):
        bf.ProfileFilm(((0.0, 1.0), (0.5, 1.0), (0.2, 1.0)))
    with pytest.raises(ValueError, match="ProfileFilm.points must have at least 2 points"):
        bf.ProfileFilm(((0.0, 1.0),))
    with pytest.raises(ValueError, match="StepFilm.region must be a bearingfe shape"):
        bf.StepFilm("square", 0.5, bf.UniformFilm(1.0))
    with pytest.raises(ValueError, match="SumFilm terms must be films"):
        bf.SumFilm(bf.UniformFilm(1.0), (2.0,))


class UndeclaredStep:
    """A user's film with a step that does not say so (no ``smooth`` attribute)."""

    def thickness(self, phi, z):
        return 1.0 + 1.0 * (np.asarray(phi) < 0.7) + 0.0 * np.asarray(z)

    def gradient(self, phi, z):
        zero = 0.0 * np.asarray(phi) + 0.0 * np.asarray(z)
        return zero, zero

    def laplacian(self, phi, z):
        return 0.0 * np.asarray(phi) + 0.0 * np.asarray(z)

    def rate_shapes(self, phi, z):
        zero = 0.0 * np.asarray(phi) + 0.0 * np.asarray(z)
        return zero + 1.0, zero

    def minimum(self, phi_range):
        return 1.0


def test_a_film_with_an_undeclared_step_is_caught():
    # its derivatives (zero) disagree with its thickness (a step): the pi form, which would put the step
    # into Pi = p h^(3/2) and lose it, is refused; the direct form gives the exact Rayleigh step
    mesh = strip_mesh(50, rows=1)
    width = float(np.ptp(mesh.mesh.p[1]))
    res = bf.solve_reynolds(mesh, UndeclaredStep())
    assert res.formulation == "direct" and any("kink or a step" in n for n in res.notes)
    assert res.integral / width == pytest.approx(stepped_slider(h1=2.0, h2=1.0, a=0.7)[1], rel=1e-10)
    smooth = bf.solve_reynolds(mesh, bf.TaperFilm(2.0, 1.0, 0.0, 1.0))
    assert smooth.formulation == "pi" and smooth.notes == ()


def test_a_uniform_film_has_no_wedge_source():
    # the conservative source of a uniform film vanishes exactly (not to round-off): no pressure, no load
    res = bf.solve_reynolds(bf.mesh_surface(bf.Surface(), 0.2), bf.UniformFilm(1.3), element="P2")
    assert np.all(res.pressure == 0.0) and res.integral == 0.0


def test_finite_differences_take_the_step_too():
    # the FD reference's direct scheme takes the wedge as a difference of half-point films: the strip's
    # Rayleigh step (step between nodes) converges to the closed form; the pi form refuses a step film
    surface = bf.Surface(arc=(0.0, 1.0), half_width=2.0)
    film = rayleigh_film(**RAYLEIGH)
    exact = rayleigh_step_load(1.866, 1.0, 0.7, 1.0, 4.0)
    err = [abs(bf.solve_reynolds_fd(surface, film, shape, formulation="direct").integral / exact - 1)
           for shape in ((101, 17), (201, 33))]
    assert err[1] < err[0] / 3 and err[1] < 3e-3  # observed 1.0e-2, 2.2e-3
    with pytest.raises(ValueError, match="formulation='pi' needs a smooth film"):
        bf.solve_reynolds_fd(surface, film, (101, 9))


def _profile_by_definition(x: float, s: list[float], h: list[float]) -> float:
    """A piecewise-linear profile at one point, by its definition: constant beyond the ends, right-continuous at a
    step (the piece that holds ``x`` is the last with a start ``<= x`` and a positive length), in each piece
    ``h_k + (h_{k+1} - h_k) (x - s_k) / (s_{k+1} - s_k)`` (the formula's own order of operations)."""
    if x < s[0]:
        return h[0]
    if x >= s[-1]:
        return h[-1]
    k = max(j for j in range(len(s) - 1) if s[j] <= x and s[j + 1] > s[j])
    return h[k] + (h[k + 1] - h[k]) * (x - s[k]) / (s[k + 1] - s[k])


@pytest.mark.parametrize("compared, block", [(8, 16384), (0, 16384), (8, 7)])   # pieces found by comparisons or
# by binary search; the points in one block or in blocks of 7
@pytest.mark.parametrize("points", [((0.0, 2.0), (0.5, 1.0), (1.0, 2.0)),
                                    ((0.0, 1.866), (0.7, 1.866), (0.7, 1.0), (1.0, 1.0)),
                                    ((0.0, 1.0), (0.2, 2.0), (0.2, 3.0), (0.2, 4.0), (0.5, 5.0), (0.5, 6.0)),
                                    tuple((k / 11, 1.0 + (k % 3) / 7) for k in range(12))])
def test_profile_film_interpolates_by_its_definition(points, compared, block, monkeypatch):
    """``ProfileFilm.thickness`` equals the definition bit for bit (steps, repeated knots, points at and next
    to the knots, beyond the ends), with its pieces found by comparisons and by binary search, in one block of
    points or in several (a two-dimensional, non-contiguous array of points keeps its shape)."""
    from bearingfe.film import thickness

    monkeypatch.setattr(thickness, "COMPARED_KNOTS", compared)
    monkeypatch.setattr(thickness, "INTERPOLATE_BLOCK", block)
    film = bf.ProfileFilm(points)
    s, h = [p[0] for p in points], [p[1] for p in points]
    knots = np.array(s)
    x = np.concatenate([np.random.default_rng(3).uniform(-0.3, 1.3, 500), knots, np.nextafter(knots, 2.0),
                        np.nextafter(knots, -1.0)])
    got = film.thickness(x, np.zeros_like(x))
    assert np.array_equal(got, [_profile_by_definition(v, s, h) for v in x])
    grid = x[:-(x.size % 6) or None].reshape(6, -1).T   # (n, 6), not contiguous
    assert np.array_equal(film.thickness(grid, np.zeros(grid.shape)), got[:grid.size].reshape(6, -1).T)


def test_profile_pieces_are_found_once_per_knots(monkeypatch):
    """The pieces of a profile's knots (:func:`_pieces`) are kept per knots (their bytes): the second evaluation
    takes the same read-only arrays, equal to those found afresh; other knots (one abscissa moved by one ulp) get
    their own; past ``PIECES_KEPT`` knots the table starts again. The films' values are the definition's either way
    (reference: :func:`_profile_by_definition`)."""
    from bearingfe.film import thickness

    monkeypatch.setattr(thickness, "_PIECES", {})
    monkeypatch.setattr(thickness, "PIECES_KEPT", 2)
    points = ((0.0, 1.866), (0.7, 1.866), (0.7, 1.0), (1.0, 1.0))
    moved = ((0.0, 1.866), (0.7, 1.866), (float(np.nextafter(0.7, 1.0)), 1.0), (1.0, 1.0))
    x = np.linspace(-0.2, 1.2, 57)
    for pts in (points, moved, points, ((0.0, 2.0), (0.5, 1.0), (1.0, 2.0)), points):
        s, h = (np.array([p[k] for p in pts]) for k in (0, 1))
        got = bf.ProfileFilm(pts).thickness(x, np.zeros_like(x))
        assert np.array_equal(got, [_profile_by_definition(v, list(s), list(h)) for v in x])
        kept = thickness._pieces_kept(s, h)
        assert kept is thickness._pieces_kept(s.copy(), h.copy()) and len(thickness._PIECES) <= 2
        assert all(not a.flags.writeable and np.array_equal(a, b) for a, b in zip(kept, thickness._pieces(s, h)))
    knots = [tuple(np.array([p[k] for p in pts]) for k in (0, 1)) for pts in (points, moved)]
    assert [int(thickness._pieces_kept(*k)[0][1]) for k in knots] == [2, 1]   # the step's piece moved on, or its own
