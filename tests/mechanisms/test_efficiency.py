"""Crank-slider efficiency with friction (bearingfe.mechanisms.efficiency) against energy balance and paper 003."""

import math
from dataclasses import replace

import numpy as np
import pytest

from bearingfe import efficiency as E
from bearingfe.mechanisms.efficiency import Linkage
from bearingfe.core.machine import Drive
from bearingfe.mechanisms.machines import MillDrive

THETA = np.linspace(0.0, 2 * np.pi, 361)


@pytest.mark.parametrize("rod_factor", [1.6, 4.68, 10.0])
def test_free_body_equilibrium_satisfies_energy_balance(mill, rod_factor):
    # independent route: driving power from crank moment equilibrium must equal useful power plus the
    # friction power computed from joint loads and relative velocities (virtual work of a quasi-static mechanism)
    link = replace(mill.linkage, rod=rod_factor * mill.linkage.crank)
    jf = E.joint_forces(link, THETA, mill.load, mill.drive.omega)
    balance = jf.drive_power - jf.useful_power - jf.friction_power
    assert np.max(np.abs(balance)) < 1e-10 * mill.load * link.crank * mill.drive.omega
    assert np.allclose(E.loss_coefficient(link, THETA) + E.efficiency(link, THETA), 1.0, atol=1e-12)


def test_slider_equilibrium(mill):
    # guide: P_x = sgn(v)(T + mu4 |N|), normal N = -P_y
    jf = E.joint_forces(mill.linkage, THETA[1:180], mill.load)
    mu4 = mill.linkage.guide_friction
    assert np.allclose(np.abs(jf.px), mill.load + mu4 * jf.normal, rtol=1e-12)


def test_frictionless_is_ideal():
    link = Linkage(0.3, 1.2)
    th = np.linspace(0.1, 3.0, 50)
    assert np.allclose(E.efficiency(link, th), 1.0, atol=1e-12)
    # frictionless driving moment = T * (instantaneous lever |dx/dtheta|) (virtual work)
    jf = E.joint_forces(link, th, 1000.0)
    lever = 0.3 * np.abs(np.sin(th) + np.cos(th) * np.tan(np.arcsin(0.25 * np.sin(th))))
    assert np.allclose(jf.drive_moment, 1000.0 * lever, rtol=1e-12)


def test_first_order_loss_agrees_to_order_mu_squared(mill):
    # loss_first_order uses the frictionless joint loads F = T/sin(psi); the exact loss differs by O(mu^2)
    th = np.linspace(0.4, 2.7, 40)
    errs = []
    for s in (1.0, 0.5, 0.25):
        link = replace(mill.linkage, pin_friction=tuple(s * m for m in mill.linkage.pin_friction),
                       guide_friction=s * mill.linkage.guide_friction)
        errs.append(np.max(np.abs(E.loss_coefficient(link, th) - E.loss_first_order(link, th))))
    # halving friction divides the discrepancy by ~4
    assert errs[0] / errs[1] == pytest.approx(4.0, rel=0.15)
    assert errs[1] / errs[2] == pytest.approx(4.0, rel=0.15)


def test_efficiency_independent_of_load(mill):
    a = E.joint_forces(mill.linkage, THETA[5:170], 10.0)
    b = E.joint_forces(mill.linkage, THETA[5:170], 1e6)
    assert np.allclose(a.useful_power / a.drive_power, b.useful_power / b.drive_power, rtol=1e-12)


def test_dead_centres_give_zero_efficiency_not_nan(mill):
    eta = E.efficiency(mill.linkage, np.array([0.0, np.pi, 2 * np.pi]))
    assert np.all(np.isfinite(eta)) and np.allclose(eta, 0.0, atol=1e-12)


def test_cycle_work_equals_integral_of_powers(mill):
    res = E.cycle(mill)
    # energy balance per revolution, and useful work = T * (path length in the working zones)
    assert res.drive_work == pytest.approx(res.useful_work + res.friction_work, rel=1e-10)
    link = mill.linkage
    half = mill.idle_zone / 2
    x = lambda t: link.crank * np.cos(t) + link.rod * np.cos(np.arcsin(link.lam * np.sin(t)))  # noqa: E731
    path = 2 * abs(x(half) - x(np.pi - half))
    assert res.useful_work == pytest.approx(mill.load * path, rel=1e-6)


def test_efficiency_rises_as_transmission_angle_nears_90_deg(mill):
    # paper 003 conclusion: efficiency grows as the pressure (transmission) angle in the working zone nears 90 deg
    psi, eta = [], []
    for k in (1.6, 2.5, 4.0, 8.0, 20.0):
        r = E.cycle(replace(mill, linkage=replace(mill.linkage, rod=k * mill.linkage.crank)), samples=801)
        psi.append(r.min_transmission_angle)
        eta.append(r.efficiency)
    assert np.all(np.diff(psi) > 0)
    assert np.all(np.diff(eta) > 0)
    assert math.degrees(psi[-1]) > 87


def test_working_mask(mill):
    th = np.radians([0, 14, 16, 90, 164, 180, 194, 196, 346])
    assert list(E.working_mask(th, mill.idle_zone)) == [False, False, True, True, True, False, False, True, False]


def test_bad_linkage_raises():
    with pytest.raises(ValueError, match="rod must be longer"):
        Linkage(1.0, 0.5)
    with pytest.raises(ValueError, match="pin_friction"):
        Linkage(0.3, 1.0, pin_friction=(0.1, -0.1, 0.0))
    with pytest.raises(ValueError, match="guide_friction"):
        Linkage(0.3, 1.0, guide_friction=1.5)
    with pytest.raises(ValueError, match="pin_diameters"):
        Linkage(0.3, 1.0, pin_diameters=(0.1, 0.1))
    with pytest.raises(ValueError, match="load"):
        E.joint_forces(Linkage(0.3, 1.0), 0.5, load=0.0)
    with pytest.raises(ValueError, match="idle_zone"):
        MillDrive("m", Drive(1.0), Linkage(0.3, 1.0), 1.0, idle_zone=4.0)
