"""Line plots of a shoe's trajectory over the pump cycle (matplotlib object API).

The functions take any trajectory-like object with equal-length arrays
``beta`` (shaft angle [rad]), ``gamma`` (eccentricity [-]), ``delta``
(attitude angle of the line of centres in the shoe frame [rad]), ``h_min``
[m], ``friction_moment`` [N m], ``flow_inlet`` and ``flow_side`` [m^3/s]
(the SI arrays of :class:`bearingfe.Trajectory`; films are drawn in um and
flows in cm^3/s). They build a :class:`matplotlib.figure.Figure`
directly (no pyplot state), save it if ``path`` is given, and return it.
The mechanism plots live in :mod:`bearingfe.plot.mechanisms`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["TRAJECTORY_FIELDS", "trajectory_plot", "orbit_plot"]

#: Attributes a trajectory must have, in the order they are checked.
TRAJECTORY_FIELDS = ("beta", "gamma", "delta", "h_min", "friction_moment", "flow_inlet", "flow_side")


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


def _save(fig, path):
    if path is not None:
        fig.savefig(path, dpi=100)
    return fig


def trajectory_plot(traj, path=None, *, title: str | None = None):
    """Eccentricity, attitude, minimum film, friction moment and flows against shaft angle.

    Parameters
    ----------
    traj : Trajectory-like
        See the module docstring for the attributes used.
    path : str or Path, optional
        Save the figure here (format from the suffix).
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    d = _arrays(traj)
    deg = np.degrees(d["beta"])
    fig = Figure(figsize=(7.5, 9.0), layout="constrained")
    axes = fig.subplots(5, 1, sharex=True)
    panels = [
        (axes[0], [("gamma", d["gamma"])], "gamma [-]"),
        (axes[1], [("delta", np.degrees(d["delta"]))], "attitude delta [deg]"),
        (axes[2], [("h_min", 1e6 * d["h_min"])], "smallest film [um]"),
        (axes[3], [("friction", d["friction_moment"])], "friction moment\n[N m]"),
        (axes[4], [("inlet", 1e6 * d["flow_inlet"]), ("side", 1e6 * d["flow_side"])], "flow [cm^3/s]"),
    ]
    for ax, curves, label in panels:
        for name, y in curves:
            ax.plot(deg, y, label=name)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[2].axhline(0.0, color="k", lw=0.8)
    i = int(np.argmin(d["h_min"]))
    axes[2].plot(deg[i], 1e6 * d["h_min"][i], "o", color="tab:red",
                 label=f"min {1e6 * d['h_min'][i]:.3g} um at {deg[i]:.0f} deg")
    axes[2].legend(loc="best", fontsize="small")
    axes[4].legend(loc="best", fontsize="small")
    axes[-1].set_xlabel("shaft angle beta [deg]")
    if title:
        axes[0].set_title(title)
    return _save(fig, path)


def orbit_plot(traj, path=None, *, title: str | None = None):
    """Orbit of the shoe-bore centre relative to the eccentric: ``gamma (cos delta, sin delta)``.

    The unit circle (``gamma = 1``, contact of a full bearing) is drawn for
    scale; on a partial arc the orbit may cross it without contact.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    d = _arrays(traj, ("beta", "gamma", "delta"))
    x, y = d["gamma"] * np.cos(d["delta"]), d["gamma"] * np.sin(d["delta"])
    fig = Figure(figsize=(5.5, 5.5), layout="constrained")
    ax = fig.subplots()
    t = np.linspace(0, 2 * np.pi, 361)
    ax.plot(np.cos(t), np.sin(t), "--", color="0.5", lw=0.8, label="gamma = 1")
    points = ax.scatter(x, y, c=np.degrees(d["beta"]), s=8, cmap="viridis", zorder=3)
    ax.plot(x, y, color="0.3", lw=0.8)
    ax.plot(x[0], y[0], "s", color="k", label="start")
    fig.colorbar(points, ax=ax, label="shaft angle beta [deg]", shrink=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("gamma cos(delta) [-]")
    ax.set_ylabel("gamma sin(delta) [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize="small")
    if title:
        ax.set_title(title)
    return _save(fig, path)
