"""Stability of a rigid rotor on two bearings: damped eigenvalues, logarithmic decrement, Lund's threshold.

References: Lund's closed-form threshold of a rigid rotor on frequency-independent coefficients
(J. W. Lund, "Review of the concept of dynamic coefficients for fluid film journal bearings", ASME J.
Tribology 109 (1987) 37-41), checked against the eigenvalues, which share no formula with it; the
classic half-frequency whirl of a lightly loaded plain bearing (whirl ratio -> 1/2, Newkirk's oil whip)
and its stability at every speed above eps ~ 0.75; the tilting-pad bearing with massless pads, whose
reduced coefficients have no cross-coupled stiffness, is stable.
"""

import math

import numpy as np
import pytest

from bearingfe.bearings import journal
from bearingfe.bearings.stability import lund_threshold, rotor_modes
from bearingfe.bearings.tilting_pad import (TiltingPadGeometry, pad_assembly_coefficients, tilting_pad_equilibrium,
                                            tilting_pad_meshes)


@pytest.fixture(scope="module")
def plain():
    b = journal.JournalBearing(0.5)
    return {w: journal.dynamic_coefficients(journal.equilibrium(b, (0.0, -w), size=0.1)) for w in (0.02, 0.2, 1.0, 5.0)}


@pytest.mark.parametrize("w", [0.02, 0.2, 1.0])
def test_eigenvalues_cross_the_axis_at_lunds_threshold(plain, w):
    c = plain[w]
    m_crit, gamma = lund_threshold(c)
    below, above = rotor_modes(c, 0.999 * m_crit), rotor_modes(c, 1.001 * m_crit)
    assert below.stable and not above.stable
    assert below.log_decrements[0] > 0 > above.log_decrements[0]
    # the mode crossing the axis whirls at Lund's ratio
    assert above.eigenvalues[0].imag == pytest.approx(gamma, rel=1e-3)


def test_plain_bearing_whirls_at_half_speed_when_lightly_loaded(plain):
    # eps 0.03: the onset of oil whirl at half the running speed
    c = plain[0.02]
    assert c.eps < 0.05
    assert lund_threshold(c)[1] == pytest.approx(0.5, abs=0.005)


def test_plain_bearing_is_stable_at_every_speed_when_heavily_loaded(plain):
    c = plain[5.0]
    assert c.eps > 0.8
    assert lund_threshold(c)[0] == math.inf
    for m in (1.0, 10.0, 1000.0):
        assert rotor_modes(c, m).stable


@pytest.mark.parametrize("on_pad", [False, True])
def test_tilting_pads_without_inertia_are_stable(on_pad):
    g = TiltingPadGeometry(0.5, n_pads=5, arc=math.radians(60), load_on_pad=on_pad)
    full = pad_assembly_coefficients(tilting_pad_equilibrium(g, (0.0, -0.5), meshes=tilting_pad_meshes(g, 0.1)))
    for m in (0.1, 1.0, 10.0, 100.0, 1e4):
        modes = rotor_modes(full, m)
        assert modes.stable and np.all(modes.log_decrements > 0)
        # the synchronous reduced coefficients agree: no cross-coupled stiffness, so Lund's threshold is infinite
    assert lund_threshold(full.reduced()) [0] == math.inf


def test_the_pad_freedoms_are_the_reduction_at_the_eigenvalue():
    # with heavy pads, an eigenvalue of the full model makes the reduced impedance at that (complex)
    # frequency singular: det(Z_red(lambda) + M lambda^2) = 0
    g = TiltingPadGeometry(0.5, n_pads=5, arc=math.radians(60))
    full = pad_assembly_coefficients(tilting_pad_equilibrium(g, (0.0, -0.5), meshes=tilting_pad_meshes(g, 0.1)))
    m, pad_mass = 2.0, 0.3
    keep = np.concatenate([[True, True], full.active])
    K, C = full.K[np.ix_(keep, keep)], full.C[np.ix_(keep, keep)]
    for lam in rotor_modes(full, m, pad_mass=pad_mass).eigenvalues:
        Z = K + lam * C
        Z[2:, 2:] += lam**2 * pad_mass / full.load * np.eye(K.shape[0] - 2)
        reduced = Z[:2, :2] - Z[:2, 2:] @ np.linalg.solve(Z[2:, 2:], Z[2:, :2]) + m * lam**2 * np.eye(2)
        assert abs(np.linalg.det(reduced)) <= 1e-9 * np.abs(reduced).max() ** 2


def test_checks():
    c = journal.DynamicCoefficients(K=np.eye(2), C=np.eye(2), load=1.0, eps=0.5, attitude=0.0, method="given")
    with pytest.raises(ValueError):
        rotor_modes(c, 0.0)
    with pytest.raises(ValueError):
        rotor_modes(c, 1.0, pad_mass=1.0)


def test_isotropic_supports_have_the_damped_oscillator_eigenvalues():
    k, c, m = 3.0, 0.4, 2.0
    modes = rotor_modes(journal.DynamicCoefficients(K=k * np.eye(2), C=c * np.eye(2), load=1.0, eps=0.0,
                                                     attitude=0.0, method="given"), m)
    expected = complex(-c / (2 * m), math.sqrt(k / m - (c / (2 * m)) ** 2))
    np.testing.assert_allclose(modes.eigenvalues, [expected, expected], rtol=1e-12)
    assert modes.log_decrements[0] == pytest.approx(-2 * math.pi * expected.real / expected.imag)


@pytest.mark.slow
def test_threshold_speed_of_a_rotor_on_plain_bearings():
    # a 50 kg rigid rotor on two plain bearings (R 25 mm, L/D 0.5, c 50 um, oil 0.02 Pa s): the speed at
    # which the sampled stability map turns negative agrees with the root of Lund's condition
    # c omega^2 / g = M_crit(S(omega)) found by bisection on the same bearing model
    R, c, mu, m, g = 0.025, 50e-6, 0.02, 50.0, 9.81
    bearing = journal.JournalBearing(0.5)
    cache = {}

    def coefficients(speed):
        if speed not in cache:
            w = (m * g / 2) * c**2 / (mu * speed * R**4)
            cache[speed] = journal.dynamic_coefficients(journal.equilibrium(bearing, (0.0, -w), size=0.1))
        return cache[speed]

    from bearingfe.bearings.stability import log_decrement_map, threshold_speed
    speeds = np.linspace(200.0, 1600.0, 15)
    delta = log_decrement_map(speeds, coefficients, lambda s: c * s**2 / g)
    sampled = threshold_speed(speeds, delta)
    lo, hi = 200.0, 1600.0
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if c * mid**2 / g < lund_threshold(coefficients(mid))[0] else (lo, mid)
    assert math.isfinite(sampled) and delta[0] > 0 > delta[-1]
    assert sampled == pytest.approx(0.5 * (lo + hi), rel=0.02)  # linear interpolation over 100 rad/s steps
