"""Line plots of a shoe's trajectory over the pump cycle (matplotlib object API).

The functions take one trajectory-like object, or a mapping ``{design name:
trajectory}`` to draw several designs on the same axes (one colour per
design, the smallest film of each marked). A trajectory has equal-length
arrays ``beta`` (shaft angle [rad]), ``gamma`` (eccentricity [-]),
``delta`` (attitude angle of the line of centres in the shoe frame [rad]),
``h_min`` [m], ``friction_moment`` [N m], ``flow_inlet`` and ``flow_side``
[m^3/s] (the SI arrays of :class:`bearingfe.Trajectory`); angles are drawn
in degrees, films in um and flows in l/min. The functions build a
:class:`matplotlib.figure.Figure` directly (no pyplot state), save it if
``path`` is given, and return it. The mechanism plots live in
:mod:`bearingfe.plot.mechanisms`.
"""

from __future__ import annotations

import textwrap
from typing import Mapping

import numpy as np

from .figures import frame, save, title as set_title

__all__ = ["TRAJECTORY_FIELDS", "DESIGN_COLORS", "designs_of", "trajectory_plot", "orbit_plot", "pocket_plot"]

#: Attributes a trajectory must have, in the order they are checked.
TRAJECTORY_FIELDS = ("beta", "gamma", "delta", "h_min", "friction_moment", "flow_inlet", "flow_side")

#: Colours of the designs, in the order they are given.
DESIGN_COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink")

#: m^3/s -> l/min.
LITRES_PER_MINUTE = 6e4


def designs_of(trajs) -> dict:
    """``{name: trajectory}``: a mapping as given, a single trajectory as ``{"": traj}``."""
    if isinstance(trajs, Mapping):
        if not trajs:
            raise ValueError("no trajectory to draw: the mapping of designs is empty")
        return dict(trajs)
    return {"": trajs}


def _arrays(traj, names=TRAJECTORY_FIELDS) -> dict[str, np.ndarray]:
    out = {}
    for name in names:
        if not hasattr(traj, name):
            raise ValueError(f"trajectory has no attribute {name!r}; needed: {', '.join(names)}")
        out[name] = np.asarray(getattr(traj, name), dtype=float).ravel()
    n = out[names[0]].size
    bad = [k for k, v in out.items() if v.size != n]
    if bad:
        raise ValueError(f"trajectory arrays must all have the length of {names[0]} ({n}); differ: {bad}")
    if n < 2:
        raise ValueError(f"trajectory needs at least 2 samples, got {n}")
    return out


def _label(design: str, what: str) -> str:
    return f"{design}: {what}" if design else what


def trajectory_plot(trajs, path=None, *, title: str | None = None):
    """Eccentricity, attitude, smallest film, friction moment and flows against shaft angle.

    Parameters
    ----------
    trajs : Trajectory-like or mapping of them
        One trajectory, or ``{design name: trajectory}`` drawn together (see the module docstring).
    path : str or Path, optional
        Save the figure here (format from the suffix).
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        Five axes; on each, one line per design (the flow panel: inlet solid, side dashed), and on
        the film panel one ``"o"`` marker per design at its smallest film. Legends: the film and flow
        panels', and with several designs their names and colours on the top panel.
    """
    from matplotlib.figure import Figure

    designs = {name: _arrays(t) for name, t in designs_of(trajs).items()}
    fig = Figure(figsize=(7.5, 9.5))
    axes = frame(fig, nrows=5, top=0.75 if title else 0.2, bottom=0.55, left=1.05, right=0.2,
                 hgap=0.12).subplots(sharex=True)
    for (design, d), color in zip(designs.items(), DESIGN_COLORS):
        deg = np.degrees(d["beta"])
        axes[0].plot(deg, d["gamma"], color=color, label=_label(design, "gamma"))
        axes[1].plot(deg, np.degrees(d["delta"]), color=color, label=_label(design, "delta"))
        axes[2].plot(deg, 1e6 * d["h_min"], color=color, label=_label(design, "h_min"))
        axes[3].plot(deg, d["friction_moment"], color=color, label=_label(design, "friction"))
        axes[4].plot(deg, LITRES_PER_MINUTE * d["flow_inlet"], color=color, label=_label(design, "pocket inflow"))
        axes[4].plot(deg, LITRES_PER_MINUTE * d["flow_side"], "--", color=color, label=_label(design, "side flow"))
        i = int(np.argmin(d["h_min"]))
        axes[2].plot(deg[i], 1e6 * d["h_min"][i], "o", color=color, markeredgecolor="k",
                     label=_label(design, f"min {1e6 * d['h_min'][i]:.3g} um at {deg[i]:.0f} deg"))
    labels = ("eccentricity gamma [-]", "attitude delta [deg]", "smallest film [um]", "friction moment\n[N m]",
              "flow [l/min]")
    for ax, label in zip(axes, labels):
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[2].set_ylim(bottom=0.0)
    for ax in (axes[2], axes[4]):  # the smallest films marked; the flows' line styles
        ax.legend(loc="best", fontsize="small")
    if len(designs) > 1:  # the designs' colours once, on the top panel (a legend costs ~10 ms to draw)
        axes[0].legend(axes[0].lines, list(designs), loc="best", fontsize="small")
    return _over_the_cycle(fig, axes, title, path)


def _over_the_cycle(fig, axes, title: str | None, path):
    """The shaft-angle axis of stacked curves over a revolution, the title, and the file."""
    axes[-1].set_xlabel("shaft angle beta [deg]")
    axes[-1].set_xticks(np.arange(0, 361, 45))
    if title:
        fig.suptitle(textwrap.fill(title, 80))
    return save(fig, path)


def pocket_plot(trajs, scale, omega: float, path=None, *, title: str | None = None):
    """The pocket over the cycle: its pressure, the leakage and the power lost, against shaft angle.

    Three axes: pressure [MPa] (the chamber's dashed black, then each design's pocket pressure),
    flow [l/min] (per design the pocket's outflow into the film solid, the side flow dashed and,
    where the pocket is fed through a restrictor, the restrictor's flow dash-dotted) and power
    [W] (per design friction solid, pumping dashed: :func:`bearingfe.transient.trajectory.power_columns`).
    A design without a pocket (its ``flow_inlet`` zero throughout, no restrictor) has no pocket lines.

    Parameters
    ----------
    trajs : Trajectory or mapping of them
        :class:`bearingfe.Trajectory` (the pocket pressure and the powers need its columns).
    scale : Scale
        The runs' scales (the non-dimensional pocket pressure to Pa).
    omega : float
        Shaft speed [rad/s].
    path : str or Path, optional
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    from ..transient.trajectory import power_columns

    designs = designs_of(trajs)
    fig = Figure(figsize=(7.5, 7.0))
    axes = frame(fig, nrows=3, top=0.75 if title else 0.2, bottom=0.55, left=1.05, right=0.2,
                 hgap=0.12).subplots(sharex=True)
    first = next(iter(designs.values()))
    _arrays(first)
    axes[0].plot(np.degrees(first.beta), np.asarray(first.chamber_pressure) / 1e6, "--", color="k", label="chamber")
    for (design, traj), color in zip(designs.items(), DESIGN_COLORS):
        deg = np.degrees(_arrays(traj)["beta"])
        power = power_columns(traj, scale, omega)
        if np.any(np.asarray(traj.flow_inlet) != 0) or traj.flow_restrictor is not None:  # it has a pocket
            axes[0].plot(deg, scale.to_pressure(np.asarray(traj.inlet_pressure, float)) / 1e6, color=color,
                         label=_label(design, "pocket"))
            axes[1].plot(deg, LITRES_PER_MINUTE * np.asarray(traj.flow_inlet), color=color,
                         label=_label(design, "pocket into the film"))
        axes[1].plot(deg, LITRES_PER_MINUTE * np.asarray(traj.flow_side), "--", color=color,
                     label=_label(design, "side"))
        if traj.flow_restrictor is not None:
            axes[1].plot(deg, LITRES_PER_MINUTE * np.asarray(traj.flow_restrictor), "-.", color=color,
                         label=_label(design, "restrictor"))
        axes[2].plot(deg, power["friction_power"], color=color, label=_label(design, "friction"))
        axes[2].plot(deg, power["pumping_power"], "--", color=color, label=_label(design, "pumping"))
    for ax, label in zip(axes, ("pressure [MPa]", "flow [l/min]", "power [W]")):
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize="small")
    return _over_the_cycle(fig, axes, title, path)


def orbit_plot(trajs, path=None, *, title: str | None = None):
    """Orbit of the shoe-bore centre relative to the eccentric: ``gamma (cos delta, sin delta)``.

    One line per design, its start (square) and its smallest film (star) marked; the unit circle
    (``gamma = 1``, contact of a full bearing) is drawn for scale (on a partial arc the orbit may
    cross it without contact). The lines are ``ax.lines``: the circle first, then per design the
    orbit, the start and the smallest-film marker.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.0, 7.2))
    ax = frame(fig, top=0.95 if title else 0.4, bottom=1.75, left=0.85, right=0.2).subplots()
    t = np.linspace(0, 2 * np.pi, 361)
    ax.plot(np.cos(t), np.sin(t), "--", color="0.5", lw=0.8, label="gamma = 1")
    for (design, traj), color in zip(designs_of(trajs).items(), DESIGN_COLORS):
        d = _arrays(traj, ("beta", "gamma", "delta", "h_min"))
        x, y = d["gamma"] * np.cos(d["delta"]), d["gamma"] * np.sin(d["delta"])
        ax.plot(x, y, color=color, lw=1.2, label=_label(design, "orbit"))
        ax.plot(x[0], y[0], "s", color=color, markeredgecolor="k",
                label=_label(design, f"start, beta = {np.degrees(d['beta'][0]) % 360:.0f} deg"))
        i = int(np.argmin(d["h_min"]))
        ax.plot(x[i], y[i], "*", ms=12, color=color, markeredgecolor="k",
                label=_label(design, f"smallest film {1e6 * d['h_min'][i]:.3g} um at "
                                     f"{np.degrees(d['beta'][i]) % 360:.0f} deg"))
    ax.set_aspect("equal")
    ax.set_xlabel("gamma cos(delta) [-]")
    ax.set_ylabel("gamma sin(delta) [-]")
    ax.grid(True, alpha=0.3)
    fig.legend(*ax.get_legend_handles_labels(), loc="lower center", ncols=2, fontsize="small")
    set_title(ax, "orbit of the shoe-bore centre", fontsize="medium")
    if title:
        fig.suptitle(textwrap.fill(title, 60))
    return save(fig, path)
