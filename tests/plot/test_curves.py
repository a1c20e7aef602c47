"""Trajectory and orbit plots from a trajectory-like object (frozen stand-in for the transient's result)."""

from dataclasses import dataclass

import numpy as np
import pytest

from bearingfe.plot.curves import orbit_plot, trajectory_plot


@dataclass(frozen=True)
class FakeTrajectory:
    beta: np.ndarray
    gamma: np.ndarray
    delta: np.ndarray
    h_min: np.ndarray
    friction_moment: np.ndarray
    flow_inlet: np.ndarray
    flow_side: np.ndarray


def _trajectory(n=181):
    beta = np.linspace(0, 2 * np.pi, n)
    gamma = 0.6 + 0.2 * np.sin(beta)
    return FakeTrajectory(beta, gamma, 0.3 * np.cos(beta), 1 - gamma, 0.4 + 0.1 * np.cos(2 * beta),
                          2 + np.sin(beta), 1 + 0.5 * np.sin(beta))


def _check_png(path):
    import matplotlib.image as mpimg

    img = mpimg.imread(path)[..., :3]
    assert np.ptp(img) > 0.5 and len(np.unique(img.reshape(-1, 3), axis=0)) > 20


def test_trajectory_plot_draws_every_quantity(tmp_path):
    traj = _trajectory()
    fig = trajectory_plot(traj, tmp_path / "t.png", title="stand-in")
    _check_png(tmp_path / "t.png")
    axes = fig.axes
    assert len(axes) == 5
    # first line of each panel is the data against beta in degrees
    np.testing.assert_allclose(axes[0].lines[0].get_xdata(), np.degrees(traj.beta))
    np.testing.assert_allclose(axes[0].lines[0].get_ydata(), traj.gamma)
    np.testing.assert_allclose(axes[1].lines[0].get_ydata(), np.degrees(traj.delta))
    # films in um and flows in cm^3/s from the SI arrays of a Trajectory
    np.testing.assert_allclose(axes[4].lines[1].get_ydata(), 1e6 * traj.flow_side)
    # the marked minimum film is the smallest sample: 1 - 0.8 at beta = 90 deg, drawn in um
    marker = [ln for ln in axes[2].lines if ln.get_marker() == "o"][0]
    assert marker.get_xdata()[0] == pytest.approx(90.0)
    assert marker.get_ydata()[0] == pytest.approx(0.2e6)


def test_orbit_is_gamma_along_delta(tmp_path):
    traj = _trajectory()
    fig = orbit_plot(traj, tmp_path / "o.png")
    _check_png(tmp_path / "o.png")
    ax = fig.axes[0]
    orbit = ax.lines[1]
    np.testing.assert_allclose(orbit.get_xdata(), traj.gamma * np.cos(traj.delta))
    np.testing.assert_allclose(orbit.get_ydata(), traj.gamma * np.sin(traj.delta))


def test_missing_or_ragged_arrays_are_named():
    t = _trajectory()

    @dataclass(frozen=True)
    class NoFlows:
        beta: np.ndarray
        gamma: np.ndarray

    with pytest.raises(ValueError, match="'delta'"):
        trajectory_plot(NoFlows(t.beta, t.gamma))
    from dataclasses import replace

    with pytest.raises(ValueError, match="h_min"):
        trajectory_plot(replace(t, h_min=t.h_min[:-1]))
