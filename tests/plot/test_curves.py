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
    # films in um and flows in l/min (1 m^3/s = 6e4 l/min) from the SI arrays of a Trajectory
    np.testing.assert_allclose(axes[4].lines[1].get_ydata(), 6e4 * traj.flow_side)
    assert axes[4].get_ylabel() == "flow [l/min]" and axes[-1].get_xlabel() == "shaft angle beta [deg]"
    assert fig._suptitle.get_text() == "stand-in"
    # the marked minimum film is the smallest sample: 1 - 0.8 at beta = 90 deg, drawn in um
    marker = [ln for ln in axes[2].lines if ln.get_marker() == "o"][0]
    assert marker.get_xdata()[0] == pytest.approx(90.0)
    assert marker.get_ydata()[0] == pytest.approx(0.2e6)


def test_orbit_is_gamma_along_delta(tmp_path):
    traj = _trajectory()
    fig = orbit_plot(traj, tmp_path / "o.png")
    _check_png(tmp_path / "o.png")
    ax = fig.axes[0]
    orbit = ax.lines[1]  # after the unit circle
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


def test_both_designs_are_drawn_each_with_its_smallest_film(tmp_path):
    # two stand-in designs: the second's film is 1.5x thinner, its minimum at beta = 90 deg as well
    pocket = _trajectory()
    from dataclasses import replace

    plain = replace(pocket, h_min=pocket.h_min / 1.5, gamma=pocket.gamma * 1.1)
    fig = trajectory_plot({"pocket": pocket, "plain": plain}, tmp_path / "t.png", title="two designs")
    _check_png(tmp_path / "t.png")
    film = fig.axes[2]
    curves = [ln for ln in film.lines if ln.get_marker() in ("None", "")]
    markers = [ln for ln in film.lines if ln.get_marker() == "o"]
    assert [ln.get_label() for ln in curves] == ["pocket: h_min", "plain: h_min"]
    np.testing.assert_allclose(curves[1].get_ydata(), 1e6 * plain.h_min)
    assert [m.get_ydata()[0] for m in markers] == pytest.approx([0.2e6, 0.2e6 / 1.5])
    assert [m.get_xdata()[0] for m in markers] == pytest.approx([90.0, 90.0])
    assert markers[1].get_label() == "plain: min 1.33e+05 um at 90 deg"
    # legends: the designs' names in their colours on the top panel, the film's markers, the flows' styles
    top = fig.axes[0].get_legend()
    assert [t.get_text() for t in top.get_texts()] == ["pocket", "plain"]
    assert [h.get_color() for h in top.legend_handles] == ["tab:blue", "tab:orange"]
    assert fig.axes[2].get_legend() is not None and fig.axes[4].get_legend() is not None
    assert fig.axes[1].get_legend() is None and fig.axes[3].get_legend() is None
    assert len(fig.axes[0].lines) == 2 and len(fig.axes[4].lines) == 4
    assert {ln.get_color() for ln in fig.axes[0].lines} == {"tab:blue", "tab:orange"}


def test_orbit_of_both_designs_marks_start_and_smallest_film(tmp_path):
    pocket = _trajectory()
    from dataclasses import replace

    plain = replace(pocket, gamma=pocket.gamma * 1.1)
    fig = orbit_plot({"pocket": pocket, "plain": plain}, tmp_path / "o.png", title="two designs")
    _check_png(tmp_path / "o.png")
    ax = fig.axes[0]
    assert len(ax.lines) == 1 + 2 * 3  # the circle; per design the orbit, its start and its smallest film
    stars = [ln for ln in ax.lines if ln.get_marker() == "*"]
    k = 45  # beta = 90 deg at sample 45 of 181: the smallest film (1 - gamma) of both
    assert [s.get_xdata()[0] for s in stars] == pytest.approx(
        [g[k] * np.cos(pocket.delta[k]) for g in (pocket.gamma, plain.gamma)])
    assert len(fig.legends) == 1 and len(fig.legends[0].get_texts()) == 7
