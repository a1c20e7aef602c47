"""Pump parameters, chamber-pressure cycle and swinging-plunger kinematics.

Expected values come from the geometry itself: positions of O2, the pivot B
and material points, differentiated by central finite differences.
"""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.bearings.pump import (EccentricPump, PressureCycle, attitude, pivot_ratio, pivot_ratio_rate, plunger_stroke,
                            shoe_wedge, swing_angle, swing_rate)
from tests.helpers import ROOT

E, E2, R0 = 0.008, 0.05, 0.03  # e2 = 6.25: strong swing, so sign errors show
BETAS = np.linspace(-3.0, 9.0, 37)
STEP = 1e-5


def positions(beta):
    """Eccentric centre O2 and pivot B in the fixed frame (O1 at the origin)."""
    return np.array([E * math.cos(beta), E * math.sin(beta)]), np.array([-E2, 0.0])


def fd(fun, beta):
    return (fun(beta + STEP) - fun(beta - STEP)) / (2 * STEP)


def axis_angle(beta):
    o2, b = positions(beta)
    return math.atan2(*(o2 - b)[::-1])


def test_swing_angle_and_pivot_ratio_from_positions():
    for beta in BETAS:
        o2, b = positions(beta)
        assert swing_angle(beta, E2 / E) == pytest.approx(axis_angle(beta), abs=1e-12)
        assert pivot_ratio(beta, E2 / E) == pytest.approx(np.linalg.norm(o2 - b) / E, rel=1e-12)


def test_rates_against_finite_differences_of_positions():
    # central differences: truncation ~ STEP^2 ~ 1e-10, round-off ~ 1e-16/STEP ~ 1e-11
    for beta in BETAS:
        unwrapped = lambda b: np.unwrap([axis_angle(beta), axis_angle(b)])[1]  # noqa: E731
        assert swing_rate(beta, E2 / E) == pytest.approx(fd(unwrapped, beta), abs=1e-8)
        lam = lambda b: np.linalg.norm(np.subtract(*positions(b))) / E  # noqa: E731
        assert pivot_ratio_rate(beta, E2 / E) == pytest.approx(fd(lam, beta), abs=1e-8)


def test_stroke_and_discharge_half_turn():
    # lam = e2 + 1 at beta = 0 (outer dead centre), e2 - 1 at pi: stroke 2 E
    assert plunger_stroke(0.0, 6.25) == pytest.approx(0.0, abs=1e-14)
    assert plunger_stroke(math.pi, 6.25) == pytest.approx(2.0, abs=1e-14)
    b = np.linspace(0.01, math.pi - 0.01, 50)
    assert np.all(pivot_ratio_rate(b, 6.25) < 0)  # chamber compressed on (0, pi)


def test_wedge_is_the_sliding_speed_of_eccentric_points_in_the_shoe_frame():
    # A material point of the eccentric at body angle theta0 is at fixed-frame
    # angle theta0 + beta about O2; its shoe angle is psi = phi - phi2 - pi.
    theta0 = 0.7
    for beta in BETAS:
        psi = lambda b: theta0 + b - axis_angle(b) - math.pi  # noqa: E731
        rate = (np.unwrap([psi(beta - STEP), psi(beta + STEP)]) @ [-1, 1]) / (2 * STEP)
        assert shoe_wedge(beta, E2 / E) == pytest.approx(rate, abs=1e-8)


def gap(beta, psi, gamma, delta, c):
    """Film thickness [m] at the shoe point psi from world positions of a rigid bore.

    The bore centre C sits at gamma c from O2 in the shoe-frame direction
    delta; the shoe point lies on the bore circle (radius R0 + c) at the
    shoe angle psi. H = |P - O2| - R0 (exact geometry).
    """
    o2, _ = positions(beta)
    frame = axis_angle(beta) + math.pi
    centre = o2 + gamma * c * np.array([math.cos(delta + frame), math.sin(delta + frame)])
    point = centre + (R0 + c) * np.array([math.cos(psi + frame), math.sin(psi + frame)])
    return np.linalg.norm(point - o2) - R0


def test_film_and_squeeze_in_the_shoe_frame_from_positions():
    # h = 1 + gamma cos(psi - delta) to O(c/R0) = 3e-7, and the squeeze at a
    # fixed shoe point is gamma' cos(psi - delta) + gamma delta' sin(psi - delta):
    # the solver's "phi0_rate" is delta' (no phi2' term) in the shoe frame.
    c = 1e-8
    g = lambda b: 0.6 + 0.2 * math.sin(b)  # noqa: E731
    d = lambda b: 3.3 + 0.4 * math.cos(2 * b)  # noqa: E731
    for beta in BETAS[::4]:
        for psi in (-0.5, 0.0, 0.4):
            h = gap(beta, psi, g(beta), d(beta), c) / c
            assert h == pytest.approx(1 + g(beta) * math.cos(psi - d(beta)), abs=1e-5)
            rate = fd(lambda b: gap(b, psi, g(b), d(b), c) / c, beta)
            expect = fd(g, beta) * math.cos(psi - d(beta)) + g(beta) * fd(d, beta) * math.sin(psi - d(beta))
            assert rate == pytest.approx(expect, abs=2e-4)  # FD of a 1e-8 m gap: round-off ~1e-5


def test_attitude_is_phi0_minus_swing_minus_pi():
    assert attitude(1.0 + swing_angle(0.4, 6.25) + math.pi, 0.4, 6.25) == pytest.approx(1.0, abs=1e-14)


def test_pressure_cycle_levels_and_smooth_ramps():
    cyc = PressureCycle(32e6, 0.3e6, math.radians(20), math.radians(30))
    assert cyc.pressure(0.0) == pytest.approx(0.3e6)
    assert cyc.pressure(math.radians(10)) == pytest.approx(0.3e6 + 0.5 * 31.7e6)  # raised-cosine midpoint
    assert cyc.pressure(math.radians(90)) == pytest.approx(32e6)
    assert cyc.pressure(math.pi + math.radians(15)) == pytest.approx(0.3e6 + 0.5 * 31.7e6)
    assert cyc.pressure(math.radians(270)) == pytest.approx(0.3e6)
    b = np.linspace(-1, 7, 20001)
    jumps = np.abs(np.diff(cyc.pressure(b)))
    # max slope of a raised cosine over 20 deg: (pi/2) dp/ramp; step 8/20000 rad
    assert jumps.max() <= 1.01 * math.pi / 2 * 31.7e6 / math.radians(20) * 8 / 20000


def test_pressure_fraction_of_one_angle_equals_the_array_formula():
    # an integrator asks for one float angle at a time, which takes a path without arrays: the same
    # formula, so the values agree to round-off (measured: identical) at every angle, ramps included
    cycle = PressureCycle(discharge=32e6, suction=0.3e6, compression=0.4, decompression=0.3)
    betas = np.linspace(-7.0, 14.0, 4001)
    one_by_one = np.array([cycle.fraction(float(b)) for b in betas])
    np.testing.assert_allclose(one_by_one, cycle.fraction(betas), rtol=0, atol=1e-15)
    assert isinstance(cycle.fraction(0.1), np.floating)


def test_pump_validation_names_the_parameter(tmp_path):
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    import dataclasses
    with pytest.raises(ValueError, match="pivot_distance"):
        dataclasses.replace(pump, pivot_distance=0.05)
    with pytest.raises(ValueError, match="clearance"):
        dataclasses.replace(pump, clearance=1e-3)
    with pytest.raises(ValueError, match="arc"):
        dataclasses.replace(pump, surface=bf.Surface(arc=(-2.0, 0.5), half_width=0.4))
    with pytest.raises(ValueError, match="suction"):
        dataclasses.replace(pump, cycle=PressureCycle(1e6, 0.0), preload=0.0)
    with pytest.raises(ValueError, match="compression"):
        PressureCycle(1e6, 0.0, compression=4.0)


def test_mechanism_file_and_load_scale():
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    assert isinstance(pump, EccentricPump)
    assert pump.surface.inlet_fraction == pytest.approx(0.10, abs=1e-3)  # the paper's 10 % pocket
    assert pump.e2 == pytest.approx(25.0)
    beta = 1.5  # mid discharge: F = 32 MPa * pi d^2/4 + preload
    force = 32e6 * math.pi * 0.035**2 / 4 + 200.0
    assert pump.plunger_force(beta) == pytest.approx(force, rel=1e-12)
    assert pump.load_vector(beta) == pytest.approx([-force * 20e-6**2 / (0.03 * pump.drive.omega * 0.05**4), 0.0])


def test_mechanism_file_bad_shape(tmp_path):
    text = (ROOT / "mechanisms" / "eccentric_pump.toml").read_text().replace('shape = "circle"', 'shape = "star"')
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=r"surface.inlets.0.*shape"):
        bf.load_mechanism(path)
