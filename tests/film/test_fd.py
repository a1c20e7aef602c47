"""Finite-difference reference solver (bearingfe.film.fd) against closed forms and itself.

Closed forms used:
* gamma = 0 (h = 1), wedge = 0, squeeze (gamma_rate, phi0_rate) = (1, 0):
  ``Laplace p = 12 cos(phi)`` on ``[-1/2, 1/2] x [-a, a]``, p = 0 on the
  outline. Separation of variables gives
  ``p = g(phi) + sum_n c_n cos(k_n phi) cosh(k_n z) / cosh(k_n a)``, with
  ``g = 12 (cos(1/2) - cos(phi))`` (the 1-D solution), ``k_n = (2n+1) pi`` and
  ``c_n = -2 int g cos(k_n phi) dphi`` (Fourier cosine series of -g on the
  arc of length 1). All integrals of p needed below follow term by term.
* gamma = 0 and a long pocket strip across a very long shoe: the mid-line
  pressure is the 1-D harmonic (linear) ramp from the pocket to the arc edge.
"""

import math

import numpy as np
import pytest

from bearingfe.film.fd import FDResult, solve_reynolds_fd
from bearingfe.film.thickness import CosineFilm
from bearingfe.geometry.surface import Circle, Ellipse, Rectangle, Surface

SHOE = Surface(arc=(-0.5, 0.5), half_width=0.4)  # the default 1.0 x 0.8 shoe
POCKET = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=(Circle((0.0, 0.0), math.sqrt(0.08 / math.pi)),))
SMOOTH = dict(wedge=1.0, squeeze=(0.5, -0.3))
FILM = CosineFilm(0.6, 0.3)


# -- closed form of the gamma = 0 squeeze problem ------------------------------

A = 0.4
K = (2 * np.arange(4000) + 1) * np.pi
I_COS_K = 2 * np.sin(K / 2) / K  # int_{-1/2}^{1/2} cos(k phi) dphi
I_COS_COS_K = np.sin((K - 1) / 2) / (K - 1) + np.sin((K + 1) / 2) / (K + 1)  # int cos(phi) cos(k phi)
C = -2 * 12 * (math.cos(0.5) * I_COS_K - I_COS_COS_K)  # c_n


def series_pressure(phi, z):
    """p(phi, z) of the squeeze problem (module docstring); cosh ratio written with exponentials."""
    P, Z = np.meshgrid(phi, z)
    p = 12 * (math.cos(0.5) - np.cos(P))
    for k, c in zip(K[:400], C[:400]):
        p += c * np.cos(k * P) * np.exp(k * (np.abs(Z) - A)) * (1 + np.exp(-2 * k * np.abs(Z))) / (1 + np.exp(-2 * k * A))
    return p


def series_integrals():
    """(int p, int p cos(phi), outflow through phi = -1/2): term-by-term integrals of the series."""
    tanh_int = 2 * np.tanh(K * A) / K  # int_{-a}^{a} cosh(kz)/cosh(ka) dz
    integral = 2 * A * 12 * (math.cos(0.5) - 2 * math.sin(0.5)) + np.sum(C * I_COS_K * tanh_int)
    fx = 2 * A * 12 * (2 * math.cos(0.5) * math.sin(0.5) - (0.5 + math.sin(1) / 2)) + np.sum(C * I_COS_COS_K * tanh_int)
    # out through phi = -1/2 is -q_phi = (1/12) dp/dphi integrated over z
    arc_start = (2 * A * 12 * math.sin(-0.5) + np.sum(C * K * np.sin(K / 2) * tanh_int)) / 12
    return integral, fx, arc_start


@pytest.mark.parametrize("formulation", ["pi", "direct"])
def test_squeeze_closed_form_second_order(formulation):
    # nodal error against the series; halving the step divides it by 4 (second order).
    # Observed max error: 1.45e-3 at (21, 17), 3.64e-4 at (41, 33) on a peak |p| of 0.675.
    errors = []
    for shape in [(21, 17), (41, 33)]:
        r = solve_reynolds_fd(SHOE, CosineFilm(0.0), shape, wedge=0.0, squeeze=(1.0, 0.0), formulation=formulation)
        errors.append(np.abs(r.pressure - series_pressure(r.phi, r.z)).max())
    assert errors[1] < 4e-4
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.05)


def test_squeeze_closed_form_integrals_and_flows():
    r = solve_reynolds_fd(SHOE, CosineFilm(0.0), (81, 65), wedge=0.0, squeeze=(1.0, 0.0))
    integral, fx, arc_start = series_integrals()
    # series values: integral -0.25680, force_x -0.25007, arc_start -0.157520;
    # trapezoid + FD errors are O(dphi^2) = O(1.6e-4) (observed 1.6e-4, 1.5e-4, 3.8e-5)
    assert r.integral == pytest.approx(integral, abs=3e-4)
    assert r.force[0] == pytest.approx(fx, abs=3e-4)
    assert r.force[1] == pytest.approx(0.0, abs=1e-12)  # p is even in phi, sin(phi) odd
    assert r.flows["arc_start"] == pytest.approx(arc_start, abs=1e-4)
    assert r.flows["arc_end"] == pytest.approx(arc_start, abs=1e-4)  # mirror symmetry in phi
    # squeeze = int cos(phi) dphi dz = 2a * 2 sin(1/2) = 0.767018; trapezoid error O(dphi^2)
    assert r.flows["squeeze"] == pytest.approx(4 * A * math.sin(0.5), abs=1e-4)
    # no pocket: nothing enters, the film volume change leaves through the edges
    assert r.flows["inlet"] == 0.0
    assert abs(r.flows["balance"]) < 1e-12  # h = 1: the scheme conserves exactly (module docs)


@pytest.mark.parametrize("formulation", ["pi", "direct"])
def test_pocket_strip_gives_linear_ramp(formulation):
    # gamma = 0, no wedge/squeeze source: p is harmonic. A pocket strip |phi| <= 0.1 across
    # a shoe 10 long in z: far from the z ends p = p_s (0.5 - |phi|) / 0.4 (1-D closed form).
    # The five-point scheme is exact on linear functions; the end effect at z = 0 decays
    # like exp(-pi 4.9 / 0.8) ~ 5e-9 relative.
    n_phi = 41  # dphi = 0.025: nodes at phi = +-0.1 lie inside the strip of half-length 0.1125
    strip = Rectangle((0.0, 0.0), (0.225, 9.8))
    surface = Surface(arc=(-0.5, 0.5), half_width=5.0, inlets=(strip,))
    r = solve_reynolds_fd(surface, CosineFilm(0.0), (n_phi, 101), wedge=0.0, inlet_pressure=3.0,
                          formulation=formulation)
    mid = r.pressure[50]
    assert r.z[50] == pytest.approx(0.0, abs=1e-12)
    expected = np.minimum(3.0, 3.0 * (0.5 - np.abs(r.phi)) / 0.4)
    np.testing.assert_allclose(mid, expected, atol=1e-7)


def _convergence(formulation):
    """Load p_x on dphi = dz = 0.1/k for k = 2, 4, 8, 16 (smooth film, no pocket)."""
    ks = [2, 4, 8, 16]
    loads = [solve_reynolds_fd(SHOE, FILM, (10 * k + 1, 8 * k + 1), formulation=formulation, **SMOOTH).force[0]
             for k in ks]
    return np.array(ks), np.array(loads)


@pytest.mark.parametrize("formulation", ["pi", "direct"])
def test_load_converges_at_second_order(formulation):
    ks, loads = _convergence(formulation)
    reference = loads[-1] + (loads[-1] - loads[-2]) / 3  # Richardson extrapolation, order 2
    errors = np.abs(loads[:-1] - reference)
    slope = np.polyfit(np.log(0.1 / ks[:-1]), np.log(errors), 1)[0]
    assert 1.8 < slope < 2.2  # five-point scheme: O(step^2) truncation on smooth data (observed 1.994)


def test_pi_and_direct_forms_agree_as_grid_is_refined():
    _, pi_loads = _convergence("pi")
    _, direct_loads = _convergence("direct")
    gaps = np.abs(pi_loads - direct_loads)
    # both are O(step^2) approximations of one load: their gap shrinks ~4x per halving
    assert np.all(gaps[1:] / gaps[:-1] < 0.3)
    assert gaps[-1] < 1e-4 * abs(direct_loads[-1])  # observed 2.2e-6 relative at dphi = 1/160


@pytest.mark.parametrize("formulation", ["pi", "direct"])
@pytest.mark.parametrize("omega", [1.0, 1.6])
def test_seidel_agrees_with_sparse_solve(formulation, omega):
    kw = dict(formulation=formulation, inlet_pressure=2.0, **SMOOTH)
    direct = solve_reynolds_fd(POCKET, FILM, (21, 17), **kw)
    tol = 1e-11
    seidel = solve_reynolds_fd(POCKET, FILM, (21, 17), method="seidel", tol=tol, omega_relax=omega, **kw)
    assert seidel.iterations > 10 and direct.iterations == 0
    # error <= change * rho / (1 - rho); for this grid's Laplacian rho_GS = ((cos(pi/20) + cos(pi/16))/2)^2
    # = 0.969 -> factor 31; x10 margin for the h^3 weights and the l1 -> max-norm step
    # (observed error 1.2e-10 with omega = 1 against a bound of 6.2e-9)
    rho = ((math.cos(math.pi / 20) + math.cos(math.pi / 16)) / 2) ** 2
    bound = 10 * tol * rho / (1 - rho) * np.abs(direct.pressure).max()
    np.testing.assert_allclose(seidel.pressure, direct.pressure, rtol=0, atol=bound)
    np.testing.assert_allclose(seidel.force, direct.force, rtol=0, atol=bound)


def test_sor_needs_fewer_sweeps_than_seidel():
    kw = dict(method="seidel", tol=1e-9, inlet_pressure=2.0, **SMOOTH)
    plain = solve_reynolds_fd(POCKET, FILM, (41, 33), **kw)
    sor = solve_reynolds_fd(POCKET, FILM, (41, 33), omega_relax=1.85, **kw)
    # near-optimal SOR cuts the sweeps from O(n^2) to O(n) (observed 693 vs 126)
    assert sor.iterations < plain.iterations / 4


def test_seidel_cap_raises():
    with pytest.raises(RuntimeError, match=r"max_iter = 5 sweeps.*relative change"):
        solve_reynolds_fd(POCKET, FILM, (21, 17), method="seidel", max_iter=5, inlet_pressure=1.0)


def test_mass_balance_residual_small_and_shrinking():
    kw = dict(formulation="pi", inlet_pressure=2.0, **SMOOTH)
    results = [solve_reynolds_fd(POCKET, FILM, shape, **kw) for shape in [(21, 17), (41, 33), (81, 65)]]
    residuals = np.array([abs(r.flows["balance"]) for r in results])
    inlet = results[-1].flows["inlet"]
    assert inlet > 1.0  # pocket at p_s = 2 feeds the film (observed 3.71)
    # residual = truncation of the flux balance, O(step^2): ~4x smaller per halving
    # (observed pi: 2.2e-4, 5.7e-5, 1.5e-5)
    assert np.all(residuals[1:] / residuals[:-1] < 0.35)
    assert residuals[-1] < 1e-5 * inlet


def test_direct_scheme_conserves_mass_exactly():
    # the direct scheme's wedge term is the difference of the Couette fluxes h/2 at the same half-points the
    # balance adds up (a conservative scheme), so the dual cells balance to round-off on every grid
    # (before it took the nodal dh/dphi: 5.5e-6, 1.5e-6, 3.9e-7 of the same inlet flow)
    kw = dict(formulation="direct", inlet_pressure=2.0, **SMOOTH)
    for shape in [(21, 17), (41, 33), (81, 65)]:
        r = solve_reynolds_fd(POCKET, FILM, shape, **kw)
        assert r.flows["inlet"] > 1.0
        assert abs(r.flows["balance"]) < 1e-12 * r.flows["inlet"]


def test_hydrostatic_flows_balance_exactly():
    # gamma = 0, no wedge, no squeeze: the direct scheme has no source, every cell conserves
    # exactly, so inlet = side + arc_start + arc_end to rounding; the pocket is centred, so
    # the two arc flows are equal (mirror symmetry in phi).
    r = solve_reynolds_fd(POCKET, CosineFilm(0.0), (41, 33), wedge=0.0, inlet_pressure=1.0, formulation="direct")
    f = r.flows
    assert f["squeeze"] == 0.0
    assert abs(f["balance"]) < 1e-13
    assert f["inlet"] == pytest.approx(f["side"] + f["arc_start"] + f["arc_end"], abs=1e-13)
    assert f["arc_start"] == pytest.approx(f["arc_end"], rel=1e-10)
    assert np.all((r.pressure >= -1e-14) & (r.pressure <= 1.0 + 1e-14))  # maximum principle


def test_couette_flow_of_uniform_film():
    # h = 1, no pocket, no squeeze: p = 0 and the flux is the Couette flow wedge h / 2 e_phi:
    # 0.5 * 0.8 = 0.4 enters at phi = alpha1 and leaves at phi = alpha2, none through the sides.
    r = solve_reynolds_fd(SHOE, CosineFilm(0.0), (21, 17), wedge=1.0)
    assert np.all(r.pressure == 0.0)
    assert r.flows["arc_start"] == pytest.approx(-0.4, abs=1e-14)
    assert r.flows["arc_end"] == pytest.approx(0.4, abs=1e-14)
    assert r.flows["side"] == pytest.approx(0.0, abs=1e-14)


def test_mirror_symmetry_in_z():
    # the film does not depend on z, so mirroring the pocket in z mirrors the pressure
    upper = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=(Ellipse((0.1, 0.13), (0.12, 0.07), 0.5),))
    lower = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=(Ellipse((0.1, -0.13), (0.12, 0.07), -0.5),))
    kw = dict(inlet_pressure=2.0, **SMOOTH)
    a = solve_reynolds_fd(upper, FILM, (41, 33), **kw)
    b = solve_reynolds_fd(lower, FILM, (41, 33), **kw)
    np.testing.assert_allclose(a.pressure, b.pressure[::-1], atol=1e-12)
    centred = solve_reynolds_fd(POCKET, FILM, (41, 33), **kw)
    np.testing.assert_allclose(centred.pressure, centred.pressure[::-1], atol=1e-12)


def test_result_fields():
    r = solve_reynolds_fd(POCKET, FILM, (21, 17), inlet_pressure=2.0, **SMOOTH)
    assert isinstance(r, FDResult)
    assert r.pressure.shape == (17, 21) and r.phi.shape == (21,) and r.z.shape == (17,)
    assert r.force.shape == (2,) and r.seconds > 0 and r.iterations == 0
    assert (r.formulation, r.method) == ("pi", "direct")
    # pocket nodes carry p_s (node (0, 0) is inside the centred circle), outline nodes 0
    assert r.pressure[8, 10] == pytest.approx(2.0, rel=1e-14)
    assert np.all(r.pressure[[0, -1]] == 0) and np.all(r.pressure[:, [0, -1]] == 0)
    # h_min: line of centres at 0.3 rad, thinnest point 0.3 + pi is off the arc, so the
    # minimum is at phi = -0.5: 1 + 0.6 cos(-0.8) = 1.41802
    assert r.h_min == pytest.approx(1 + 0.6 * math.cos(0.8), rel=1e-14)


@pytest.mark.parametrize("kwargs, match", [
    (dict(shape=(2, 17)), "n_phi"),
    (dict(shape=(21, 17.0)), "n_z"),
    (dict(shape=21), "shape"),
    (dict(tol=0.0), "tol"),
    (dict(max_iter=0), "max_iter"),
    (dict(omega_relax=2.0), "omega_relax"),
    (dict(formulation="galerkin"), "formulation.*'pi', 'direct'"),
    (dict(method="cg"), "method.*'direct', 'seidel'"),
    (dict(squeeze=(1.0,)), "squeeze"),
    (dict(wedge=math.nan), "wedge"),
    (dict(inlet_pressure="high"), "inlet_pressure"),
])
def test_invalid_inputs_name_the_parameter(kwargs, match):
    kw = dict(shape=(21, 17)) | kwargs
    with pytest.raises(ValueError, match=match):
        solve_reynolds_fd(POCKET, FILM, **kw)


def test_non_positive_film_is_rejected():
    # h = 1 - 1.5 cos(phi) < 0 near phi = 0
    with pytest.raises(ValueError, match=r"gamma = 1.5.*h_min = -0.5"):
        solve_reynolds_fd(SHOE, CosineFilm(1.5, math.pi), (21, 17))


def test_non_rectangular_outline_is_rejected():
    oval = Surface(outer=Ellipse((0.0, 0.0), (0.5, 0.4)))
    with pytest.raises(ValueError, match="outer"):
        solve_reynolds_fd(oval, FILM, (21, 17))


def test_projected_sor_rupture_is_a_complementarity_solution():
    # Christopherson's projected SOR: p >= 0; where p > 0 the discrete Reynolds equation holds (its
    # residual vanishes there to the iteration tolerance); it needs the Seidel method
    surface = Surface(arc=(0.0, 2 * math.pi), half_width=0.5)
    film = CosineFilm(0.6, 0.0)
    r = solve_reynolds_fd(surface, film, (127, 21), formulation="direct", method="seidel",
                          cavitation="reynolds", omega_relax=1.8, tol=1e-14)
    linear = solve_reynolds_fd(surface, film, (127, 21), formulation="direct")
    assert r.pressure.min() == 0.0 and linear.pressure.min() < 0
    ruptured = r.pressure == 0
    assert 0.2 < ruptured[1:-1, 1:-1].mean() < 0.6
    # residual of the five-point equations cP p + sum c_nb p_nb = f = 6 (h_e - h_w)/dphi (the direct scheme's
    # conservative wedge term): zero where p > 0, and <= 0 where p = 0 (there it is -f < 0 in the divergent
    # film, i.e. a multiplier >= 0)
    from bearingfe.film.fd import _conservative_rhs, _direct_stencil, _make_grid
    grid = _make_grid(surface, 127, 21)
    st = _direct_stencil(film, grid, _conservative_rhs(film, grid, 1.0, (0.0, 0.0)), 0.0)
    x, c = r.pressure, (slice(1, -1), slice(1, -1))
    res = (st.cP[c] * x[c] + st.cE[c] * x[1:-1, 2:] + st.cW[c] * x[1:-1, :-2] + st.cN[c] * x[2:, 1:-1]
           + st.cS[c] * x[:-2, 1:-1] - st.b[c])
    scale = np.abs(st.b).max()
    assert np.abs(res[~ruptured[c]]).max() < 1e-8 * scale
    assert res[ruptured[c]].max() < 1e-8 * scale
    with pytest.raises(ValueError, match="projected SOR"):
        solve_reynolds_fd(surface, film, (31, 11), cavitation="reynolds")
    with pytest.raises(ValueError, match="cavitation"):
        solve_reynolds_fd(surface, film, (31, 11), method="seidel", cavitation="gumbel")

