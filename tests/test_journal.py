"""Journal bearings: Raimondi-Boyd tables, short-bearing limits, equilibrium, dynamic coefficients.

Published reference: A. A. Raimondi and J. Boyd, "A solution for the finite journal bearing and its
application to analysis and design: III", ASLE Transactions 1 (1958) 194-209, full 360-degree bearing
with Reynolds (Swift-Stieber) conditions, as reproduced in Shigley's Mechanical Engineering Design
(Table 12-x / charts) and Hamrock, Schmid & Jacobson, Fundamentals of Fluid Film Lubrication. The values
below agree with an independent public transcription of the Shigley tables (not with a scan of
the 1958 paper); the tests allow 1.5 % on S (the published
tables print 3 significant figures and are themselves a 1958 relaxation solution) and 0.3 degree on
the attitude angle, on deliberately coarse meshes; docs/validation.md has the converged comparison.
"""

import math
import warnings

import numpy as np
import pytest

from bearingfe.journal import (EPS_MAX, Groove, JournalBearing, ResolutionWarning, dynamic_coefficients,
                               equilibrium, film_graded_size, performance, short_bearing_force)
from bearingfe import CosineFilm

# (L/D, eps, S, attitude [deg], (R/c) f, Q/(R c N L)) -- Raimondi & Boyd (1958), full bearing
RAIMONDI_BOYD = [
    (1.0, 0.1, 1.33, 79.5, 26.4, 3.37),
    (1.0, 0.6, 0.121, 50.58, 3.22, 4.33),
    (1.0, 0.9, 0.0188, 26.45, 1.05, 4.74),
    (0.5, 0.6, 0.319, 48.14, 8.10, 4.85),
    (0.25, 0.6, 1.07, 46.72, 26.7, 4.99),
]


@pytest.mark.parametrize("ld,eps,S,att,fric,flow", RAIMONDI_BOYD)
def test_full_bearing_against_raimondi_boyd(ld, eps, S, att, fric, flow):
    p = performance(JournalBearing(ld), eps, size=min(0.12, ld / 5))
    assert abs(p.sommerfeld / S - 1) < 0.015
    assert abs(p.attitude - att) < 0.3
    assert abs(p.friction_variable / fric - 1) < 0.015
    assert abs(p.flow_variable / flow - 1) < 0.015


def test_zero_eccentricity_limit():
    # eps -> 0: S -> inf, Raimondi & Boyd list the attitude limit 85 deg for L/D = 1 and flow variable pi
    p = performance(JournalBearing(1.0), 0.0, size=0.15)
    assert p.sommerfeld == math.inf and p.load == 0.0
    assert abs(p.attitude - 85.0) < 0.3
    assert abs(p.flow_variable - math.pi) < 1e-3


def test_short_bearing_closed_form_and_limit():
    # Ocvirk: w = 2 a^3 eps/(1-eps^2)^2 sqrt(pi^2 (1-eps^2) + 16 eps^2), tan(att) = pi sqrt(1-eps^2)/(4 eps)
    eps, a = 0.5, 1.0 / 16
    F = short_bearing_force(eps, a)
    w = 2 * a**3 * eps / (1 - eps**2) ** 2 * math.sqrt(math.pi**2 * (1 - eps**2) + 16 * eps**2)
    assert abs(np.hypot(*F) / w - 1) < 1e-6
    assert abs(math.degrees(math.atan2(abs(F[1]), -F[0]))
               - math.degrees(math.atan(math.pi * math.sqrt(1 - eps**2) / (4 * eps)))) < 1e-4
    # the finite bearing tends to it as L/D -> 0 (measured 0.935, 0.974, 0.985 at L/D = 1/4, 1/8, 1/16)
    p = performance(JournalBearing(a), eps, size=a / 4)
    assert abs(p.load / w - 1) < 0.025


def test_high_eccentricity_converges_and_reports_error():
    # eps = 0.99: the load changes by < 1 % under uniform refinement of the h-graded mesh
    p = performance(JournalBearing(1.0), 0.99, size=0.1, estimate_error=True)
    assert p.error_estimate < 0.01
    assert np.isfinite([p.sommerfeld, p.attitude, p.friction_variable, p.flow_variable]).all()
    assert 5 < p.attitude < 15  # R&B: 15.47 deg at 0.97 and 0 at 1; monotone in between
    # an unresolved peak warns, naming the cause
    with pytest.warns(ResolutionWarning, match="not resolved"):
        performance(JournalBearing(1.0), 0.995, size=0.4, min_size=0.4, estimate_error=True,
                    error_tolerance=0.001)
    with pytest.raises(ValueError, match="eccentricity ratio"):
        performance(JournalBearing(1.0), 0.996)


def test_no_nan_over_the_range():
    for eps in (0.0, 0.3, 0.95, EPS_MAX):
        p = performance(JournalBearing(0.5), eps, size=0.3)
        assert not any(isinstance(v, float) and math.isnan(v) for v in
                       (p.attitude, p.flow_variable, p.side_flow_ratio, p.friction_variable))


def test_equilibrium_by_newton_matches_performance():
    b = JournalBearing(0.5)
    p = performance(b, 0.6, size=0.15)
    eq = equilibrium(b, (0.0, -p.load), size=0.15, min_size=0.15 * math.sqrt(0.4))
    assert eq.residual < 1e-8
    assert abs(eq.eps - 0.6) < 2e-3  # graded for its own first guess: a slightly different mesh
    assert abs(eq.attitude - p.attitude) < 0.2
    assert eq.newton_iterations <= 8


def test_dynamic_coefficients_linearized_vs_finite_difference():
    eq = equilibrium(JournalBearing(0.5), (0.0, -5.0), size=0.15)
    lin = dynamic_coefficients(eq)
    fd = dynamic_coefficients(eq, method="finite-difference", step=1e-5)
    np.testing.assert_allclose(lin.K, fd.K, rtol=1e-5, atol=1e-6 * np.abs(lin.K).max())
    np.testing.assert_allclose(lin.C, fd.C, rtol=1e-5, atol=1e-6 * np.abs(lin.C).max())
    np.testing.assert_allclose(lin.C, lin.C.T, atol=1e-10 * np.abs(lin.C).max())  # damping is symmetric


def test_dynamic_coefficients_short_bearing_limit():
    # short-bearing (Ocvirk, pi film) coefficients by differentiating the closed-form pressure
    # (its force integral evaluated by quadrature); the finite bearing at L/D = 1/16 is within 4 %
    a, eps = 1.0 / 16, 0.5
    w = np.hypot(*short_bearing_force(eps, a))
    eq = equilibrium(JournalBearing(a), (0.0, -w), size=a / 4)
    lin = dynamic_coefficients(eq)
    d = 1e-6
    K = np.zeros((2, 2)); C = np.zeros((2, 2))
    for j in range(2):
        e = np.zeros(2); e[j] = d
        # journal at (-eps, 0) in the frame of the largest film; perturb position and velocity
        fp = short_bearing_force_xy(-eps + e[0], e[1], a, (0, 0)); fm = short_bearing_force_xy(-eps - e[0], -e[1], a, (0, 0))
        K[:, j] = (fp - fm) / (2 * d)
        fp = short_bearing_force_xy(-eps, 0.0, a, e); fm = short_bearing_force_xy(-eps, 0.0, a, -e)
        C[:, j] = (fp - fm) / (2 * d)
    F = short_bearing_force(eps, a)
    from bearingfe.journal import _to_ross_frame
    direction = math.atan2(F[1], F[0])
    Ks, Cs = _to_ross_frame(direction, K) / w, _to_ross_frame(direction, C) / w
    scale_k, scale_c = np.abs(Ks).max(), np.abs(Cs).max()
    assert np.abs(lin.K - Ks).max() < 0.06 * scale_k
    assert np.abs(lin.C - Cs).max() < 0.06 * scale_c


def short_bearing_force_xy(x, y, a, velocity):
    """Short-bearing force with the journal at (x, y): rotate into the frame of the largest film."""
    eps = math.hypot(x, y)
    phi0 = math.atan2(-y, -x)
    R = np.array([[math.cos(phi0), -math.sin(phi0)], [math.sin(phi0), math.cos(phi0)]])
    v = R.T @ np.asarray(velocity, float)
    return R @ short_bearing_force(eps, a, velocity=tuple(v), n=20000)


def test_pads_grooves_and_ross_export():
    bp = JournalBearing(0.5, pads=((math.radians(-150), math.radians(-30)),))
    eq = equilibrium(bp, (0.0, -2.0), size=0.1)
    assert eq.residual < 1e-8 and 0 < eq.eps < 1
    grooved = JournalBearing(0.5, pads=((math.radians(-60), math.radians(300)),),
                             grooves=(Groove(math.radians(120), 0.2, 0.8),), supply_pressure=0.5)
    eqg = equilibrium(grooved, (0.0, -3.0), size=0.12)
    assert eqg.state.results[0].flows["inlet"] > 0  # the groove feeds the film
    kw = dynamic_coefficients(eq).to_ross_kwargs(viscosity=0.02, speed=300.0, radius=0.05, clearance=5e-5)
    assert set(kw) == {"kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "frequency"}
    # SI scale: K = w mu omega R^4 / c^3 * Kbar
    dc = dynamic_coefficients(eq)
    scale = 0.02 * 300.0 * 0.05**4 / 5e-5**3 * dc.load
    assert abs(kw["kyy"][0] - scale * dc.K[1, 1]) < 1e-9 * abs(kw["kyy"][0])
    with pytest.raises(ValueError, match="grooves need explicit pads"):
        JournalBearing(0.5, grooves=(Groove(0.0, 0.2),))
    with pytest.raises(ValueError, match="length_ratio"):
        JournalBearing(0.0)


def test_film_graded_size():
    f = film_graded_size(CosineFilm(0.99, 0.0), 0.2, 0.01)
    s = f(np.array([0.0, math.pi]), np.zeros(2))
    assert s[0] == pytest.approx(0.2) and s[1] == pytest.approx(0.2 * math.sqrt(0.01))
    with pytest.raises(ValueError, match="min_size"):
        film_graded_size(CosineFilm(0.5), 0.1, 0.2)
