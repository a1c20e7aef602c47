"""The FEM Reynolds solver: symmetry, flows, superposition, invalid inputs, scales.

Expected values are exact consequences of the equation (mirror symmetry of
the data, the divergence theorem for flows, linearity for superposition) or
closed forms stated at each test; tolerances are measured discretization
errors with margin.
"""

import math

import numpy as np
import pytest

from bearingfe import Circle, CosineFilm, Ellipse, Rectangle, Scale, Slot, Surface, mesh_surface, solve_reynolds, superpose
from bearingfe.reynolds import CoercivityError  # noqa: F401  (public name, exported)


@pytest.fixture(scope="module")
def z_symmetric():
    # pockets centred on z = 0 (and one mirrored pair): the surface is symmetric in z
    surface = Surface(arc=(-0.6, 0.6), half_width=0.4,
                      inlets=(Circle((-0.25, 0.0), 0.1), Ellipse((0.2, 0.2), (0.1, 0.05)),
                              Ellipse((0.2, -0.2), (0.1, 0.05))))
    return mesh_surface(surface, 0.06, inlet_size=0.02, grading_distance=0.1, order=2)


@pytest.fixture(scope="module")
def phi_symmetric():
    # arc centred on phi = 0.3, pockets mirrored about phi = 0.3
    surface = Surface(arc=(-0.3, 0.9), half_width=0.4,
                      inlets=(Slot((0.05, 0.1), 0.1, 0.08, angle=0.5), Slot((0.55, 0.1), 0.1, 0.08, angle=-0.5),
                              Rectangle((0.3, -0.2), (0.2, 0.08))))
    return mesh_surface(surface, 0.06, inlet_size=0.02, grading_distance=0.1, order=2)


def probe_points(phi_c, half_span, a):
    s = np.linspace(0.02, half_span - 0.02, 9)
    z = np.linspace(-a + 0.02, a - 0.02, 9)
    return np.meshgrid(s, z)


def in_film(surface, phi, z, margin=0.02):
    """Points that are in the film and at least `margin` from every pocket (probes must be in the mesh)."""
    near = np.zeros(phi.shape, dtype=bool)
    for dphi in (-margin, 0, margin):
        for dz in (-margin, 0, margin):
            near |= surface.in_pocket(phi + dphi, z + dz)
    return ~near


def test_z_mirror_symmetry(z_symmetric):
    res = solve_reynolds(z_symmetric, CosineFilm(0.6, 0.4), wedge=1.0, squeeze=(0.3, 0.2),
                         inlet_pressure=1.5, element="P2")
    phi, z = np.meshgrid(np.linspace(-0.58, 0.58, 25), np.linspace(0.01, 0.38, 12))
    ok = in_film(z_symmetric.surface, phi, z) & in_film(z_symmetric.surface, phi, -z)
    upper, lower = res.interpolate(phi[ok], z[ok]), res.interpolate(phi[ok], -z[ok])
    # the mesh is not symmetric, so symmetry holds to the pointwise P2 error at size 0.06
    # (measured 9.5e-4 of max |p|; 4e-3 without the pocket grading; a sign slip would be O(1))
    assert np.abs(upper - lower).max() < 3e-3 * np.abs(upper).max()
    assert np.abs(upper).max() > 0.1  # a non-trivial field


def test_phi_mirror_symmetry_and_antisymmetry(phi_symmetric):
    surface, phi0 = phi_symmetric.surface, 0.3
    film = CosineFilm(0.5, phi0)  # h symmetric about phi0
    s, z = np.meshgrid(np.linspace(0.01, 0.58, 20), np.linspace(-0.38, 0.38, 15))
    ok = in_film(surface, phi0 + s, z) & in_film(surface, phi0 - s, z)
    sup = superpose(phi_symmetric, film, element="P2")
    # gamma_rate source 12 cos(phi - phi0) and the inlet pressure are even about phi0
    even = sup.combine(wedge=0.0, squeeze=(1.0, 0.0), inlet_pressure=2.0)
    right, left = even.interpolate(phi0 + s[ok], z[ok]), even.interpolate(phi0 - s[ok], z[ok])
    assert np.abs(right - left).max() < 3e-3 * np.abs(right).max()  # measured 9.8e-4
    # the wedge source 6 dh/dphi = -6 gamma sin(phi - phi0) and phi0_rate are odd: p is odd
    odd = sup.combine(wedge=1.0, squeeze=(0.0, 0.7), inlet_pressure=0.0)
    right, left = odd.interpolate(phi0 + s[ok], z[ok]), odd.interpolate(phi0 - s[ok], z[ok])
    assert np.abs(right + left).max() < 3e-3 * np.abs(right).max()  # measured 1.5e-3
    # an odd field has no load along the symmetry line: int p cos(phi - phi0) = 0
    # (measured 3e-7 against 0.7 for the even field)
    fx = math.cos(phi0) * odd.force[0] + math.sin(phi0) * odd.force[1]
    assert abs(fx) < 1e-5 * np.hypot(*even.force)


# -- flows ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def pocket_mesh():
    return mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4,
                                inlets=(Circle((0.1, 0.05), 0.12), Rectangle((-0.25, -0.1), (0.12, 0.15)))),
                        0.05, order=2)


@pytest.mark.parametrize("formulation, element, tol", [
    ("direct", "P2", 1e-10), ("direct", "P1", 1e-10),  # measured <= 7e-12 absolute
    ("pi", "P2", 2e-4), ("pi", "P1", 5e-3),  # measured 2.4e-5 and 6.6e-4 relative to the inlet flow
])
def test_flows_balance(pocket_mesh, formulation, element, tol):
    film = CosineFilm(0.7, 2.5)
    res = solve_reynolds(pocket_mesh, film, wedge=1.0, squeeze=(0.4, -0.6), inlet_pressure=3.0,
                         formulation=formulation, element=element)
    f = res.flows
    assert set(f) == {"inlet", "side", "arc_start", "arc_end", "squeeze"}
    # int dh/dt over the film = int over the outline - int over the pockets, all closed forms
    # of int (0.4 cos(phi - phi0) - 0.6 g sin(phi - phi0)):
    # rectangle [x1, x2] x [z1, z2]: (z2 - z1)(0.4 [sin(x - phi0)] + 0.6 g [cos(x - phi0)]) from x1 to x2;
    # disc of radius r at phi_c: 2 pi r J1(r) (0.4 cos(phi_c - phi0) - 0.6 g sin(phi_c - phi0))
    from scipy.special import j1

    phi0, g = 2.5, 0.7

    def box(x1, x2, height):
        return height * (0.4 * (math.sin(x2 - phi0) - math.sin(x1 - phi0))
                         + 0.6 * g * (math.cos(x2 - phi0) - math.cos(x1 - phi0)))

    disc = 2 * math.pi * 0.12 * j1(0.12) * (0.4 * math.cos(0.1 - phi0) - 0.6 * g * math.sin(0.1 - phi0))
    exact = box(-0.5, 0.5, 0.8) - box(-0.31, -0.19, 0.15) - disc
    assert f["squeeze"] == pytest.approx(exact, rel=1e-6)  # curved mesh: quadrature of the exact disc
    outflow = f["side"] + f["arc_start"] + f["arc_end"]
    assert f["inlet"] - outflow - f["squeeze"] == pytest.approx(res.mass_balance, abs=1e-14)
    assert abs(res.mass_balance) < tol * abs(f["inlet"])
    assert f["inlet"] > 0 and f["side"] > 0  # pockets at p_s = 3 feed the film, oil leaves at the sides


def test_squeeze_flow_is_the_integral_of_dh_dt_without_pockets():
    mesh = mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4), 0.1)
    res = solve_reynolds(mesh, CosineFilm(0.7, 2.5), wedge=0.0, squeeze=(0.4, -0.6), element="P2",
                         formulation="direct")
    a1, a2, a, phi0, g = -0.5, 0.5, 0.4, 2.5, 0.7
    exact = 2 * a * (0.4 * (math.sin(a2 - phi0) - math.sin(a1 - phi0))
                     - 0.6 * g * (-math.cos(a2 - phi0) + math.cos(a1 - phi0)))
    assert res.flows["squeeze"] == pytest.approx(exact, rel=1e-10)
    assert res.flows["inlet"] == 0.0
    assert res.flows["side"] + res.flows["arc_start"] + res.flows["arc_end"] == pytest.approx(-exact, rel=1e-10)


def test_pure_couette_flow_and_friction():
    # h = 1 (gamma = 0), no pocket: p = 0, flux wedge h/2 along phi: in at arc_start, out at arc_end,
    # each 1/2 x 2a; shear on the journal int sliding / h = sliding x area
    mesh = mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4), 0.2)
    res = solve_reynolds(mesh, CosineFilm(0.0), wedge=1.0, sliding=2.0, element="P1")
    assert np.abs(res.pressure).max() < 1e-14
    assert res.flows["arc_start"] == pytest.approx(-0.4, rel=1e-12)
    assert res.flows["arc_end"] == pytest.approx(0.4, rel=1e-12)
    assert res.flows["side"] == pytest.approx(0.0, abs=1e-14)
    assert res.friction == pytest.approx(2.0 * 0.8, rel=1e-12)


def test_corner_flows_are_split_by_edge_not_shared_blindly():
    # wedge-only flow through a rectangle with h = 1 + gamma cos(phi): the side outflow must
    # converge (no O(1) share of the corner dofs' arc flow leaking into 'side')
    values = []
    for size in (0.1, 0.05):
        mesh = mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4), size)
        values.append(solve_reynolds(mesh, CosineFilm(0.4, 0.2), element="P2").flows["side"])
    assert values[0] == pytest.approx(values[1], rel=1e-3)


# -- superposition -------------------------------------------------------------------

def test_combine_equals_a_direct_solve(pocket_mesh):
    film = CosineFilm(0.55, 1.0)
    point = dict(wedge=0.8, squeeze=(-0.3, 0.45), inlet_pressure=2.5)
    for formulation in ("pi", "direct"):
        sup = superpose(pocket_mesh, film, formulation=formulation, element="P2")
        combined = sup.combine(**point)
        direct = solve_reynolds(pocket_mesh, film, formulation=formulation, element="P2", **point)
        scale = np.abs(direct.pressure).max()
        assert np.abs(combined.pressure - direct.pressure).max() < 1e-12 * scale
        assert combined.force == pytest.approx(direct.force, rel=1e-12, abs=1e-14)
        assert combined.integral == pytest.approx(direct.integral, rel=1e-12)
        assert combined.friction == pytest.approx(direct.friction, rel=1e-12)
        for name in direct.flows:
            assert combined.flows[name] == pytest.approx(direct.flows[name], rel=1e-10, abs=1e-13)
        assert sup.force(**point) == pytest.approx(direct.force, rel=1e-12, abs=1e-14)
        # the paper's coefficients: force = (a1, b1) gamma_rate + (a2, b2) phi0_rate + (a3, b3)
        c = sup.coefficients(point["wedge"], point["inlet_pressure"])
        assert c @ np.array([*point["squeeze"], 1.0]) == pytest.approx(direct.force, rel=1e-12, abs=1e-14)


def test_rates_for_load_balance_the_load(pocket_mesh):
    film = CosineFilm(0.55, 1.0)
    sup = superpose(pocket_mesh, film, element="P2")
    load = np.array([-1.2, 0.4])
    rates = sup.rates_for_load(load, wedge=1.0, inlet_pressure=2.0)
    res = solve_reynolds(pocket_mesh, film, wedge=1.0, squeeze=tuple(rates), inlet_pressure=2.0, element="P2")
    # film force + applied load = 0 (paper eq. 14)
    assert res.force + load == pytest.approx(np.zeros(2), abs=1e-10)
    # gamma = 0: the phi0_rate column vanishes and the system is singular: said so
    with pytest.raises(np.linalg.LinAlgError, match="singular"):
        superpose(pocket_mesh, CosineFilm(0.0)).rates_for_load(load)
    with pytest.raises(ValueError, match="load"):
        sup.rates_for_load([math.nan, 0.0])
    with pytest.raises(ValueError, match="load"):
        sup.rates_for_load([1.0, 2.0, 3.0])


def test_pocket_force_uses_the_pocket_area():
    # h = 1, no wedge, pocket at p_s: film force = film pressure moments + pocket moments;
    # with a tiny film ring the load tends to p_s x pocket area from above
    surface = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=(Rectangle((0.0, 0.0), (0.9, 0.7)),))
    res = solve_reynolds(mesh_surface(surface, 0.02), CosineFilm(0.0), wedge=0.0, inlet_pressure=1.0,
                         element="P2")
    pocket = 0.9 * 0.7
    assert pocket < res.integral < 0.8
    # exact pocket moment int cos(phi) over the rectangle: 0.7 x 2 sin(0.45)
    assert res.force[0] > 0.7 * 2 * math.sin(0.45)


# -- invalid inputs ---------------------------------------------------------------------

@pytest.fixture(scope="module")
def plain():
    return mesh_surface(Surface(), 0.2)


class NotAFilm:
    pass


@pytest.mark.parametrize("kwargs, error, words", [
    (dict(formulation="fd"), ValueError, "formulation"),
    (dict(element="P3"), ValueError, "element"),
    (dict(cavitation="half-sommerfeld"), ValueError, "cavitation"),
    (dict(wedge=math.nan), ValueError, "finite"),
    (dict(wedge=math.inf), ValueError, "finite"),
    (dict(squeeze=(math.nan, 0.0)), ValueError, "finite"),
    (dict(squeeze=(0.0, -math.inf)), ValueError, "finite"),
    (dict(squeeze=(1.0, 2.0, 3.0)), ValueError, "squeeze"),
    (dict(squeeze=1.0), ValueError, "squeeze"),
    (dict(inlet_pressure=1.0), ValueError, "no pocket"),
    (dict(sliding=math.nan), ValueError, "sliding"),
    (dict(solver="umfpack"), ValueError, "solver"),
    (dict(on_indefinite="ignore"), ValueError, "on_indefinite"),
])
def test_solver_rejects_invalid_inputs(plain, kwargs, error, words):
    with pytest.raises(error, match=words):
        solve_reynolds(plain, CosineFilm(0.5), **kwargs)


def test_solver_rejects_bad_mesh_film_and_contact(plain):
    with pytest.raises(ValueError, match="mesh"):
        solve_reynolds("mesh", CosineFilm(0.5))
    with pytest.raises(ValueError, match="film"):
        solve_reynolds(plain, NotAFilm())
    # arc [-0.5, 0.5]: h = 1 + 1.2 cos(phi - pi) < 0 at phi = 0 and h = 0 exactly at the
    # thinnest point of gamma = 1 (interior and at an arc end)
    for film in (CosineFilm(1.2, math.pi), CosineFilm(1.0, math.pi), CosineFilm(1.0, math.pi + 0.5)):
        with pytest.raises(ValueError, match="h_min"):
            solve_reynolds(plain, film)
    # gamma > 1 is fine on a partial arc where h stays positive: with phi0 = 0,
    # h >= 1 + 1.5 cos(0.5) on [-0.5, 0.5] (the thinnest point is at the arc ends)
    res = solve_reynolds(plain, CosineFilm(1.5, 0.0))
    assert res.h_min == pytest.approx(1 + 1.5 * math.cos(0.5), rel=1e-12)


def test_custom_film_without_exact_minimum_is_checked_on_the_mesh(plain):
    class Tilted:
        """h = 1 + k phi (a tilted flat shoe); no exact minimum."""

        def __init__(self, k):
            self.k = k

        def thickness(self, phi, z):
            return 1.0 + self.k * np.asarray(phi) + 0 * np.asarray(z)

        def gradient(self, phi, z):
            return self.k + 0 * np.asarray(phi), 0 * np.asarray(z)

        def laplacian(self, phi, z):
            return 0 * np.asarray(phi)

        def rate_shapes(self, phi, z):
            return 0 * np.asarray(phi), 0 * np.asarray(phi)

        def minimum(self, phi_range):
            return None

    res = solve_reynolds(plain, Tilted(-0.5), formulation="direct")
    assert res.h_min == pytest.approx(0.75, rel=1e-12)  # at phi = 0.5
    assert res.force[0] > 0  # converging wedge in the direction of motion builds pressure
    with pytest.raises(ValueError, match="h_min"):
        solve_reynolds(plain, Tilted(-2.0))  # h = 0 at phi = 0.5


def test_superposition_rejects_invalid_operating_points(plain):
    sup = superpose(plain, CosineFilm(0.5))
    with pytest.raises(ValueError, match="no pocket"):
        sup.combine(inlet_pressure=1.0)
    with pytest.raises(ValueError, match="no pocket"):
        sup.force(inlet_pressure=1.0)
    with pytest.raises(ValueError, match="finite"):
        sup.combine(squeeze=(math.nan, 0.0))
    with pytest.raises(ValueError, match="sliding"):
        sup.combine(sliding=math.inf)


# -- scales ------------------------------------------------------------------------------

def test_scale_conversions():
    # R0 = 10 mm, c = 10 um, mu = 0.05 Pa s, omega = 100 rad/s, by hand:
    # P = mu omega R0^2 / c^2 = 0.05 * 100 * 1e-4 / 1e-10 = 5e6 Pa; F = P R0^2 = 500 N;
    # Q = omega R0^2 c = 1e-7 m^3/s; M = mu omega R0^4 / c = 5e-3 N m; power = M omega = 0.5 W
    s = Scale(radius=0.01, clearance=1e-5, viscosity=0.05, speed=100.0)
    assert s.pressure == pytest.approx(5e6, rel=1e-12)
    assert s.force == pytest.approx(500.0, rel=1e-12)
    assert s.flow == pytest.approx(1e-7, rel=1e-12)
    assert s.moment == pytest.approx(5e-3, rel=1e-12)
    assert s.power == pytest.approx(0.5, rel=1e-12)
    assert s.to_pressure(0.2) == pytest.approx(1e6, rel=1e-12)
    assert s.from_pressure(s.to_pressure(0.37)) == pytest.approx(0.37, rel=1e-14)
    assert s.from_force(s.to_force(1.7)) == pytest.approx(1.7, rel=1e-14)
    assert s.to_flow(2.0) == pytest.approx(2e-7, rel=1e-12)
    assert s.to_moment(3.0) == pytest.approx(1.5e-2, rel=1e-12)
    assert s.to_thickness(0.5) == pytest.approx(5e-6, rel=1e-12)


@pytest.mark.parametrize("kwargs, words", [
    (dict(radius=0.0), "radius"), (dict(clearance=-1e-5), "clearance"), (dict(viscosity=math.nan), "viscosity"),
    (dict(speed=math.inf), "speed"), (dict(clearance=0.02), "clearance must be smaller"),
])
def test_scale_rejects_invalid_parameters(kwargs, words):
    base = dict(radius=0.01, clearance=1e-5, viscosity=0.05, speed=100.0)
    with pytest.raises(ValueError, match=words):
        Scale(**{**base, **kwargs})
