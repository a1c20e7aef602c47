"""Crank-slider kinematics and inertia (bearingfe.mechanisms.crank) against independent routes and paper 000."""

import math

import numpy as np
import pytest

from bearingfe import crank
from bearingfe.core.machine import Drive
from bearingfe.mechanisms.machines import CrankMechanism, CrankSlider

PHI = np.linspace(0.0, 2 * np.pi, 721)


def _cs(lam=0.3):
    return CrankSlider(crank=lam, rod=1.0, rod_mass=2.0, rod_cg_from_crank_pin=0.3, rod_inertia=0.5,
                       slider_mass=1.0, crank_mass=3.0, crank_cg_radius=0.1)


def _ddphi(f, phi, h=1e-4):
    return (f(phi + h) - f(phi - h)) / (2 * h)


# --- exact kinematics vs numerical differentiation of the exact position -----------------


@pytest.mark.parametrize("lam", [0.065, 0.3, 0.6])
def test_slider_velocity_acceleration_match_numerical_derivatives(lam):
    cs, w = _cs(lam), 7.0
    # independent route: central differences of x(phi) = r cos phi + l cos beta, d/dt = w d/dphi
    v_num = w * _ddphi(lambda p: crank.slider_position(cs, p), PHI)
    a_num = w * _ddphi(lambda p: crank.slider_velocity(cs, w, p), PHI)
    assert np.max(np.abs(crank.slider_velocity(cs, w, PHI) - v_num)) < 1e-7 * cs.crank * w
    assert np.max(np.abs(crank.slider_acceleration(cs, w, PHI) - a_num)) < 1e-6 * cs.crank * w**2


def test_rod_centre_of_mass_and_rod_rates_match_numerical_derivatives():
    cs, w = _cs(0.35), 5.0
    vx, vy = crank.rod_cg_velocity(cs, w, PHI)
    ax, ay = crank.rod_cg_acceleration(cs, w, PHI)
    assert np.allclose(vx, w * _ddphi(lambda p: crank.rod_cg_position(cs, p)[0], PHI), atol=1e-7)
    assert np.allclose(vy, w * _ddphi(lambda p: crank.rod_cg_position(cs, p)[1], PHI), atol=1e-7)
    assert np.allclose(ax, w * _ddphi(lambda p: crank.rod_cg_velocity(cs, w, p)[0], PHI), atol=1e-5)
    assert np.allclose(ay, w * _ddphi(lambda p: crank.rod_cg_velocity(cs, w, p)[1], PHI), atol=1e-5)
    # rod angle beta(phi): d beta/dt and d^2 beta/dt^2
    om = crank.rod_angular_velocity(cs, w, PHI)
    assert np.allclose(om, w * _ddphi(lambda p: crank.rod_angle(cs, p), PHI), atol=1e-7)
    eps = crank.rod_angular_acceleration(cs, w, PHI)
    assert np.allclose(eps, w * _ddphi(lambda p: crank.rod_angular_velocity(cs, w, p), PHI), atol=1e-5)


def test_rod_centre_of_mass_lies_on_the_rod():
    # geometry: S = A + (l_a/l)(B - A)
    cs = _cs(0.4)
    xs, ys = crank.rod_cg_position(cs, PHI)
    ax_, ay_ = cs.crank * np.cos(PHI), cs.crank * np.sin(PHI)
    xb = crank.slider_position(cs, PHI)
    k = cs.rod_cg_from_crank_pin / cs.rod
    assert np.allclose(xs, ax_ + k * (xb - ax_), atol=1e-14)
    assert np.allclose(ys, ay_ * (1 - k), atol=1e-14)


# --- series vs exact ---------------------------------------------------------------------


@pytest.mark.parametrize("lam", [0.05, 0.1, 0.2])
def test_second_order_series_error_is_order_lambda_cubed(lam):
    # the series drops the lam^3 terms; for X the leading dropped term is r lam^3 sin^4(phi)/8
    # (expansion of (1 - cos beta)/lam), so max error / (r lam^3) -> 1/8 as lam -> 0
    cs, w = _cs(lam), 1.0
    scale = cs.crank * lam**3
    err_x = np.max(np.abs(crank.slider_displacement(cs, PHI) - crank.slider_displacement_series(cs, PHI)))
    err_v = np.max(np.abs(crank.slider_velocity(cs, w, PHI) - crank.slider_velocity_series(cs, w, PHI)))
    assert err_x / scale == pytest.approx(1 / 8, rel=0.03)
    assert err_v / scale < 0.17
    ax_e = crank.rod_cg_acceleration(cs, w, PHI)[0]
    ax_s = crank.rod_cg_acceleration_series(cs, w, PHI)[0]
    assert np.max(np.abs(ax_e - ax_s)) / scale < 0.16


@pytest.mark.parametrize("lam", [0.1, 0.25])
def test_sixth_order_acceleration_series_error_is_order_lambda_7(lam):
    cs = _cs(lam)
    err = np.max(np.abs(crank.slider_acceleration(cs, 1.0, PHI) - crank.slider_acceleration_series(cs, 1.0, PHI, 6)))
    err2 = np.max(np.abs(crank.slider_acceleration(cs, 1.0, PHI) - crank.slider_acceleration_series(cs, 1.0, PHI, 2)))
    # dropped terms start at lam^7 (A8 ~ lam^7 and the lam^7 parts of A2..A6)
    assert err < 2 * cs.crank * lam**7
    assert err < err2 / 50


@pytest.mark.parametrize("lam", [0.065, 0.2])
def test_rod_series_match_exact_to_order_lambda_7(lam):
    cs, w = _cs(lam), 3.0
    e1 = np.max(np.abs(crank.rod_angular_velocity(cs, w, PHI) - crank.rod_angular_velocity_series(cs, w, PHI)))
    e2 = np.max(np.abs(crank.rod_angular_acceleration(cs, w, PHI) - crank.rod_angular_acceleration_series(cs, w, PHI)))
    assert e1 < lam**7 * w
    assert e2 < 3 * lam**7 * w**2


def test_fourier_harmonics_match_closed_form_and_fix_paper_signs():
    # independent routes: FFT of the exact acceleration vs the closed-form A2, A4, A6
    lam = 0.25
    cs = _cs(lam)
    fft = crank.acceleration_harmonics(cs, 8)
    closed = crank.harmonic_coefficients_series(lam, 6)
    assert fft[1] == pytest.approx(1.0, abs=1e-12)
    for k in (2, 4, 6):
        assert fft[k] == pytest.approx(closed[k], abs=2 * lam**7)
    for k in (3, 5, 7):
        assert abs(fft[k]) < 1e-12
    # paper 000 eq. (1) prints "cos phi - A2 cos 2phi ..." and A4 = -lam^3/4 + ...: both wrong.
    assert fft[2] > 0 and fft[4] < 0 and fft[6] > 0


def test_fourier_harmonics_reconstruct_the_exact_acceleration():
    cs = _cs(0.45)
    h = crank.acceleration_harmonics(cs, 30)
    rebuilt = -cs.crank * sum(c * np.cos(k * PHI) for k, c in h.items())
    assert np.max(np.abs(rebuilt - crank.slider_acceleration(cs, 1.0, PHI))) < 1e-10


# --- masses, forces, resultants --------------------------------------------------------


def test_two_mass_replacement_keeps_mass_and_centre():
    cs = _cs()
    ma, mb = crank.two_mass_replacement(cs)
    assert ma + mb == pytest.approx(cs.rod_mass, rel=1e-15)
    # centre of mass of the two points measured from A equals l_a
    assert mb * cs.rod / (ma + mb) == pytest.approx(cs.rod_cg_from_crank_pin, rel=1e-14)
    # residual inertia: J_S minus the points' inertia about S
    la, lb = cs.rod_cg_from_crank_pin, cs.rod_cg_from_wrist_pin
    assert crank.residual_inertia(cs) == pytest.approx(cs.rod_inertia - (ma * la**2 + mb * lb**2), rel=1e-14)


def test_reciprocating_force_is_mass_times_acceleration_sampled():
    cs, w = _cs(0.3), 4.0
    p = crank.reciprocating_force(cs, w, PHI)
    a_num = w * _ddphi(lambda q: crank.slider_velocity(cs, w, q), PHI)
    assert np.allclose(p, -crank.reciprocating_mass(cs) * a_num, atol=1e-5)


def test_resultant_inertia_by_time_domain_sum():
    # independent route: add the force vectors of z cranks in time, take the Fourier amplitude per order
    cs = _cs(0.3)
    mech = CrankMechanism("t", Drive(10.0), cs, cylinders=3)
    n = 2048
    phi = 2 * np.pi * np.arange(n) / n
    fx = np.zeros(n)
    fy = np.zeros(n)
    for j in range(3):
        g = phi + 2 * np.pi * j / 3
        rx, ry = crank.rotating_force(cs, 10.0, g)
        fx += rx + crank.reciprocating_force(cs, 10.0, g)
        fy += ry
    z = np.fft.fft(fx + 1j * fy) / n
    res = crank.resultant_inertia(mech, max_order=6)
    for k in range(1, 7):
        amp = abs(z[k]) + abs(z[-k])  # forward + backward rotating parts
        assert res[k] == pytest.approx(amp, abs=1e-9 * (1 + amp))
    # z = 3: only orders divisible by 3 survive (order 6 from A6)
    assert res[1] == res[2] == res[4] == 0.0
    assert res[6] > 0


def test_single_crank_first_order_combines_rotating_and_reciprocating():
    cs = _cs(0.2)
    mech = CrankMechanism("t", Drive(3.0), cs, cylinders=1)
    base = cs.crank * 9.0
    # closed form: max |(m_B + m_n/2) e^{i phi} + (m_n/2) e^{-i phi}| = m_B + m_n
    expected = (crank.rotating_mass(cs) + crank.reciprocating_mass(cs)) * base
    assert crank.resultant_inertia(mech)[1] == pytest.approx(expected, rel=1e-12)


def test_resultant_moment_with_spacing():
    cs = _cs(0.2)
    mech = CrankMechanism("t", Drive(3.0), cs, cylinders=2, cylinder_spacing=0.5)
    # two cranks at 180 deg, planes 0 and 0.5 m: first-order moment = (m_B + m_n) r w^2 * 0.5
    m = crank.resultant_inertia_moment(mech)
    assert m[1] == pytest.approx((crank.rotating_mass(cs) + crank.reciprocating_mass(cs)) * cs.crank * 9 * 0.5, rel=1e-12)


# --- paper 000 numbers --------------------------------------------------------------------


def test_snt32_masses_flow_reproduce_paper(snt32):
    s = crank.analyze(snt32)
    # paper 000, text after Table 3: m_a = 15.5, m_b = 2.5, m1 = 9.77, m_B = 25.27, m_n = 17.79 kg (printed to 0.01)
    assert s.m_a == pytest.approx(15.5, abs=0.005)
    assert s.m_b == pytest.approx(2.5, abs=0.005)
    assert s.m_1 == pytest.approx(9.77, abs=0.005)
    assert s.m_rot == pytest.approx(25.27, abs=0.005)
    assert s.m_rec == pytest.approx(17.79, abs=0.005)
    # paper 000: Q_T = 105434 cm^3/min ~ 105.4 l/min; exact product is 105487 cm^3/min (paper's arithmetic off 0.05 %)
    assert s.flow_theoretical * 60e3 == pytest.approx(105.4, rel=1e-3)
    assert s.lam == pytest.approx(0.065, abs=5e-4)  # paper: lambda = 0.065


def test_snt32_kinematics_with_exact_omega_and_paper_rounding(snt32):
    s = crank.analyze(snt32)
    # closed forms: v_mean = 4 r n, a_max = r w^2 (1 + lam) at phi = 0, rod rates maxima lam w, ~lam w^2 sqrt-corrected
    assert s.v_mean == pytest.approx(4 * 0.0188 * 588 / 60, rel=1e-12)
    assert s.a_max == pytest.approx(0.0188 * s.omega**2 * (1 + s.lam), rel=1e-12)
    assert s.rod_omega_max == pytest.approx(s.lam * s.omega, rel=1e-9)
    # paper 000: v_max/v_mean = 1.57
    assert s.v_ratio == pytest.approx(1.57, abs=0.005)
    # paper 000 rounds omega to 62 1/s: v_max = 1.17 m/s reproduces with it (exact omega gives 1.160)
    s62 = crank.analyze(CrankMechanism("62", Drive(62.0), snt32.linkage, 3, 0.045))
    assert s62.v_max == pytest.approx(1.17, abs=0.005)
    # paper 000 Table 4: omega_max = 4.03 1/s, eps_max = 249.9 1/s^2 = 0.065*62 and 0.065*62^2 (rounded lambda and omega)
    assert 0.065 * 62 == pytest.approx(4.03, abs=0.005)
    assert s62.rod_omega_max == pytest.approx(4.03, rel=0.01)  # with lam = 0.06528: 4.047
    assert s62.rod_eps_max == pytest.approx(249.9, rel=0.01)
    # paper 000 a_max = 74.75 m/s^2 does NOT reproduce: r w^2 (1+lam) = 75.93 (exact w) / 76.98 (w = 62)
    assert abs(s.a_max - 74.75) > 1.0


def test_snt32_inertia_forces_and_moment(snt32):
    s = crank.analyze(snt32)
    s62 = crank.analyze(CrankMechanism("62", Drive(62.0), snt32.linkage, 3, 0.045))
    # paper 000: P_n1 = 17.79 * 0.0188 * 62^2 = 1286 N; P_n2 = 0.065 * 1286 = 84 N (omega rounded to 62)
    assert s62.P_rec1 == pytest.approx(1286, abs=1)
    assert s62.P_rec2 == pytest.approx(84, abs=1)
    # with the exact omega = 61.58 1/s: closed form m_n r w^2
    assert s.P_rec1 == pytest.approx(17.79 * 0.0188 * s.omega**2, rel=1e-12)
    # paper 000: dJ = 0.93 kg m^2 (from the implicit J_S = M3 l_b^2 stored in snt32.toml)
    assert s.delta_J == pytest.approx(0.93, abs=0.005)
    # paper 000 Table 5: M0_max = 232.37 N m = 0.93 * 249.86; exact motion at w = 62 gives dJ * eps_max
    assert s62.M0_max == pytest.approx(232.37, rel=0.01)
    # three cranks: rotating and first/second-order reciprocating forces balance (paper: "closed triangle")
    res = crank.resultant_inertia(snt32)
    assert res[1] == 0.0 and res[2] == 0.0


def test_paper_second_harmonic_sum_is_a_slip(snt32):
    # paper 000 eq. (10): P_n2^Sigma = lam (m_n + m_B) r w^2 = 202 N. The rotating force's x-projection
    # m_B r w^2 cos phi has no second harmonic, so the single-crank second order is lam m_n r w^2 only.
    cs = snt32.linkage
    one = CrankMechanism("one", Drive(62.0), cs, cylinders=1)
    res = crank.resultant_inertia(one)
    assert res[2] == pytest.approx(crank.reciprocating_mass(cs) * cs.crank * 62**2 * crank.acceleration_harmonics(cs, 2)[2], rel=1e-12)
    assert res[2] == pytest.approx(84, abs=1)


def test_table2_transmission_angle_and_acceleration_factor():
    # paper 000 Table 2: gamma_min = 84, 78.5, 72.5, 66.5, 60 deg for lam = 0.1 ... 0.5 (printed to 0.5 deg)
    for lam, gmin in [(0.1, 84.0), (0.2, 78.5), (0.3, 72.5), (0.4, 66.5), (0.5, 60.0)]:
        assert math.degrees(crank.min_transmission_angle(lam)) == pytest.approx(gmin, abs=0.3)
    # paper 000 Table 2: a_max = K r n^2 with K = 0.012, 0.013, 0.014, 0.0155, 0.0165; K = (pi/30)^2 (1 + lam)
    for lam, k in [(0.1, 0.012), (0.2, 0.013), (0.3, 0.014), (0.4, 0.0155), (0.5, 0.0165)]:
        cs = CrankSlider(crank=lam, rod=1.0)
        s = crank.analyze(CrankMechanism("t", Drive.from_rpm(100.0), cs))
        assert s.a_max / (cs.crank * 100.0**2) == pytest.approx(k, abs=0.0003)


def test_table2_velocity_ratio_partly_reproduces():
    # paper 000 Table 2, v_max/v_mean: 1.59 1.6 1.63 1.71 1.79 for lam = 0.1..0.5. Exact: 1.579 1.602 1.640 1.694 1.764.
    exact = {}
    for lam in (0.1, 0.2, 0.3, 0.4, 0.5):
        exact[lam] = crank.analyze(CrankMechanism("t", Drive(1.0), CrankSlider(lam, 1.0))).v_ratio
    assert exact[0.2] == pytest.approx(1.6, abs=0.005)
    assert exact[0.5] == pytest.approx(1.7643, abs=1e-3)  # paper's 1.79 is 1.5 % high (documented)


# --- bad input ------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, word",
    [
        (dict(crank=0.3, rod=0.2), "rod must be longer"),
        (dict(crank=0.1, rod=1.0, rod_mass=-1.0), "rod_mass"),
        (dict(crank=0.1, rod=1.0, slider_mass=-0.1), "slider_mass"),
        (dict(crank=0.1, rod=1.0, rod_cg_from_crank_pin=2.0), "rod_cg_from_crank_pin"),
        (dict(crank=0.0, rod=1.0), "crank"),
        (dict(crank=float("nan"), rod=1.0), "crank"),
    ],
)
def test_bad_linkage_raises(kwargs, word):
    with pytest.raises(ValueError, match=word):
        CrankSlider(**kwargs)


def test_zero_speed_and_missing_inertia_raise():
    with pytest.raises(ValueError, match="omega"):
        Drive(0.0)
    with pytest.raises(ValueError, match="speed_rpm"):
        Drive.from_rpm(-5)
    with pytest.raises(ValueError, match="omega"):
        crank.slider_velocity(_cs(), 0.0, PHI)
    with pytest.raises(ValueError, match="rod_inertia"):
        crank.residual_inertia(CrankSlider(0.1, 1.0))
    with pytest.raises(ValueError, match="plunger_diameter"):
        crank.theoretical_flow(CrankMechanism("t", Drive(1.0), CrankSlider(0.1, 1.0)))
    with pytest.raises(ValueError, match="cylinders"):
        CrankMechanism("t", Drive(1.0), CrankSlider(0.1, 1.0), cylinders=0)
