"""Thrust bearings (bearingfe.bearings.thrust): sector pads on a rotating collar, fixed and tilting.

References: the 1-D Reynolds solution of the inclined slider (closed form, integrated by quadrature to
1e-12) for the centre of pressure of a wide tilting pad; the exact similarity of the rigid isoviscous
film (h, pitch and roll scale as load^-1/2, power as load^1/2, stiffness as load^3/2, damping as
load^3/2 at a frequency scaled with them: here the reduction is at a fixed frequency, so only the
fixed-geometry damping, c ~ h^-3, is checked); finite differences along the equilibrium curve for the
stiffness; the full-film limit in which Swift-Stieber and JFO must agree.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from bearingfe.bearings.thrust import (SliderPad, ThrustError, ThrustPad, axial_coefficients, pad_for_load,
                                       solve_pad, tilting_equilibrium)
from bearingfe.core.scales import Scale

SCALE = Scale(radius=0.1, clearance=20e-6, viscosity=0.03, speed=2 * math.pi * 3000 / 60)
PAD = ThrustPad(0.05, 0.1, math.radians(40), n_pads=6, pivot_offset=0.6)


@pytest.fixture(scope="module")
def mesh():
    return PAD.mesh(0.05)


def _centre_of_pressure(K: float) -> float:
    """1-D inclined slider, film h = K + (1 - K) x on [0, 1]: centre of pressure from the leading edge."""
    def h(x):
        return K + (1 - K) * x
    h_star = quad(lambda x: h(x) ** -2, 0, 1, epsabs=1e-14)[0] / quad(lambda x: h(x) ** -3, 0, 1, epsabs=1e-14)[0]

    def p(x):
        return 6 * quad(lambda s: (h(s) - h_star) / h(s) ** 3, 0, x, epsabs=1e-14)[0]
    return quad(lambda x: p(x) * x, 0, 1, epsabs=1e-13)[0] / quad(p, 0, 1, epsabs=1e-13)[0]


def test_wide_tilting_pad_settles_at_the_one_dimensional_film_ratio():
    """A wide pad pivoted at the 1-D centre of pressure of K = 2 (0.56869) tilts to K = 2 (Richardson of two
    meshes, 1e-3; the P1 error falls at order 2)."""
    pivot = _centre_of_pressure(2.0)
    assert pivot == pytest.approx(0.568688, abs=1e-6)
    pad = SliderPad(1.0, pivot_offset=pivot)
    ratios = []
    for size in (0.1, 0.05):
        perf = tilting_equilibrium(pad, pad.mesh(size), SCALE, 1000.0, pivot="line")
        q = perf.pad.state
        ratios.append((q[0] + q[1] * pivot) / (q[0] - q[1] * (1 - pivot)))
    assert ratios[1] + (ratios[1] - ratios[0]) / 3 == pytest.approx(2.0, abs=1e-3)
    assert math.log2(abs(ratios[0] - 2) / abs(ratios[1] - 2)) == pytest.approx(2.0, abs=0.4)


def test_tilting_pad_equilibrium_and_similarity(mesh):
    """Point pivot: the load is carried through the pivot (moments ~0) and the solution follows the exact
    similarity of the rigid isoviscous film when the load doubles (warm-started)."""
    a = tilting_equilibrium(PAD, mesh, SCALE, 5e3)
    b = tilting_equilibrium(PAD, mesh, SCALE, 1e4, start=(a.h_pivot, a.pitch, a.roll))
    assert a.load == pytest.approx(5e3, rel=1e-8)
    lever = PAD.lever * a.pad.load
    assert np.max(np.abs(a.pad.moments)) < 1e-8 * lever
    root2 = math.sqrt(2.0)
    for name in ("h_pivot", "pitch", "roll", "h_min"):
        assert getattr(b, name) == pytest.approx(getattr(a, name) / root2, rel=1e-6), name
    assert b.power == pytest.approx(a.power * root2, rel=1e-6)
    assert b.p_max == pytest.approx(a.p_max * 2, rel=1e-6)
    assert a.roll > 0  # the faster outer rim lifts the outer side
    flows = a.flows   # the oil entering at the leading edges leaves through the other three edges, up to the
    # (pi form's) discrete mass balance the result reports
    imbalance = flows["leading"] - (flows["trailing"] + flows["inner"] + flows["outer"])
    reported = PAD.n_pads * SCALE.to_flow(a.pad.result.mass_balance)
    assert imbalance == pytest.approx(reported, abs=1e-9 * flows["leading"])
    assert abs(imbalance) < 2e-3 * flows["leading"]


def test_line_pivot_holds_the_roll(mesh):
    """A rocker line along the radius: the pad pitches only (roll stays 0) and the pitch moment vanishes."""
    perf = tilting_equilibrium(PAD, mesh, SCALE, 1e4, pivot="line")
    assert perf.roll == 0.0
    assert abs(perf.pad.moments[0]) < 1e-8 * PAD.lever * perf.pad.load
    assert abs(perf.pad.moments[1]) > 1e-4 * PAD.lever * perf.pad.load  # the roll moment is carried by the line


def test_swift_stieber_and_jfo_agree_where_nothing_ruptures(mesh):
    """A converging tilting pad has no rupture: both cavitation models find the same equilibrium, to the
    difference of their discretizations (Galerkin and finite volume: 1.4e-4 in the roll on this mesh)."""
    ss = tilting_equilibrium(PAD, mesh, SCALE, 2e4, cavitation="reynolds", formulation="direct")
    jfo = tilting_equilibrium(PAD, mesh, SCALE, 2e4, start=(ss.h_pivot, ss.pitch, ss.roll), cavitation="jfo")
    assert ss.pad.result.cavitated_fraction == 0.0 and jfo.pad.result.cavitated_fraction == 0.0
    for name in ("h_pivot", "pitch", "roll"):
        assert getattr(jfo, name) == pytest.approx(getattr(ss, name), rel=5e-4), name


def test_stiffness_is_the_slope_of_the_equilibrium_curve(mesh):
    """k_zz of massless tilting pads at a low frequency equals -dW/dh along the equilibrium curve (central
    differences of two equilibria, 1e-3); fixed-geometry pads are stiffer; damping is positive."""
    mid = tilting_equilibrium(PAD, mesh, SCALE, 1e4)
    start = (mid.h_pivot, mid.pitch, mid.roll)
    lo, hi = (tilting_equilibrium(PAD, mesh, SCALE, w, start=start) for w in (0.99e4, 1.01e4))
    slope = (hi.load - lo.load) / (lo.h_pivot - hi.h_pivot)
    tilting = axial_coefficients(PAD, mesh, SCALE, mid, frequency=1e-6 * SCALE.speed)
    assert tilting.k_zz == pytest.approx(slope, rel=1e-3)
    fixed = axial_coefficients(PAD, mesh, SCALE, mid, pivot=None)
    assert fixed.k_zz > tilting.k_zz > 0 and fixed.c_zz > 0


def test_parallel_pad_damping_scales_as_film_cubed(mesh):
    """A parallel (untilted) pad has no wedge load, and its squeeze damping goes as h^-3 exactly."""
    perf = []
    for h in (20e-6, 40e-6):
        q = PAD.state(SCALE, h)
        sol = solve_pad(PAD, mesh, q, scale=SCALE)
        assert abs(sol.load) < 1e-12
        from bearingfe.bearings.thrust import performance
        perf.append(axial_coefficients(PAD, mesh, SCALE, performance(PAD, SCALE, sol), pivot=None))
    assert perf[0].c_zz / perf[1].c_zz == pytest.approx(8.0, rel=1e-6)


def test_fixed_taper_land_pad_for_load(mesh):
    """A taper-land pad (taper over 70 % of the angle, 20 um deep) carries its load by Newton on the film;
    a heavier load runs on a thinner film."""
    pad = ThrustPad(0.05, 0.1, math.radians(40), n_pads=6, profile=((0.0, 20e-6), (0.7, 0.0), (1.0, 0.0)))
    mesh = pad.mesh(0.05)
    light = pad_for_load(pad, mesh, SCALE, 5e3)
    heavy = pad_for_load(pad, mesh, SCALE, 1e4, h_guess=light.h_pivot)
    assert light.load == pytest.approx(5e3, rel=1e-8) and heavy.load == pytest.approx(1e4, rel=1e-8)
    assert heavy.h_min < light.h_min
    assert heavy.power > light.power > 0


def test_bad_inputs_are_named():
    with pytest.raises(ValueError, match="ThrustPad.extent"):
        ThrustPad(0.05, 0.1, 1.2, n_pads=6)
    with pytest.raises(ValueError, match="pivot_offset"):
        ThrustPad(0.05, 0.1, 0.5, pivot_offset=1.0)
    with pytest.raises(ValueError, match="load"):
        tilting_equilibrium(PAD, None, SCALE, -1.0)
    with pytest.raises(ValueError, match="pivot"):
        tilting_equilibrium(PAD, None, SCALE, 1.0, pivot="ball")


def test_a_load_no_film_carries_is_reported(mesh):
    """A flat untilted pad carries no load at any film: Newton reports that it cannot, it does not hang."""
    with pytest.raises(ThrustError, match="pad_for_load"):
        pad_for_load(PAD, mesh, SCALE, 1e3, max_iterations=8)


def test_user_film_addition_is_added(mesh):
    """A user film added to the pad (a uniform 0.5 h_ref) is the same pad at a film 0.5 h_ref thicker at the
    pivot: equal loads to round-off."""
    import bearingfe as bf

    thicker = ThrustPad(0.05, 0.1, math.radians(40), n_pads=6, pivot_offset=0.6, addition=bf.UniformFilm(0.5))
    q = PAD.state(SCALE, 30e-6, 5e-4, 1e-4)
    a = solve_pad(thicker, mesh, q, scale=SCALE, formulation="direct")
    b = solve_pad(PAD, mesh, q + np.array([0.5, 0.0, 0.0]), scale=SCALE, formulation="direct")
    assert a.load == pytest.approx(b.load, rel=1e-12)
    with pytest.raises(ValueError, match="addition"):
        ThrustPad(0.05, 0.1, 0.5, addition=0.5)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_pocket_moments_are_the_pockets_area_and_first_moments(element):
    """``int 1``, ``int x``, ``int y`` over a pad's pockets from their contours: a rectangle's closed form
    (area 0.02, centroid c; 1e-13 relative: the Gauss rule is exact on straight edges), and on a circle the
    same numbers, bit for bit, as the facet basis's points, normals and weights (the path they replace);
    the P2 circle's curved edges give pi r^2 to 1e-3."""
    from bearingfe.bearings.thrust import _pocket_moments
    from bearingfe.film import operators
    from bearingfe.film.mesh_operators import facet_basis
    from bearingfe import Circle, Rectangle

    c = (0.75 * math.cos(0.35), 0.75 * math.sin(0.35))
    order = 2 if element == "P2" else 1
    for pocket, exact in [(Rectangle(c, (0.2, 0.1)), 0.02), (Circle(c, 0.08), math.pi * 0.08**2)]:
        pad = ThrustPad(0.05, 0.1, math.radians(40), n_pads=6, pockets=(pocket,))
        basis = operators(pad.mesh(0.05, order=order), element).basis
        got = _pocket_moments(basis)
        fb = facet_basis(basis, basis.mesh.boundaries["inlet"], 8)
        x, n, dx = np.asarray(fb.global_coordinates()), np.asarray(fb.normals), np.asarray(fb.dx)
        assert got == (float(-np.sum(x[0] * n[0] * dx)), float(-np.sum(0.5 * x[0] ** 2 * n[0] * dx)),
                       float(-np.sum(0.5 * x[1] ** 2 * n[1] * dx)))
        if isinstance(pocket, Circle) and element == "P1":
            continue  # a polygon inscribed in the circle (5 % less area at this mesh size)
        rtol = 1e-3 if isinstance(pocket, Circle) else 1e-13
        np.testing.assert_allclose(got, (exact, exact * c[0], exact * c[1]), rtol=rtol)
