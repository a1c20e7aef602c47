"""Line plots for the machine models (matplotlib object API, no pyplot state).

Each function takes parameters (or a result), an optional ``ax`` to draw into
and an optional ``path`` to save to, and returns the Figure.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

__all__ = ["plot_crank_kinematics", "plot_efficiency", "plot_natural_frequencies"]


def _figure(ax, nrows: int = 1, size=(7.0, 4.5)):
    if ax is not None:
        return ax.figure, [ax] * nrows
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, layout="constrained")
    axes = fig.subplots(nrows, 1, sharex=True, squeeze=False)[:, 0]
    return fig, list(axes)


def _finish(fig, path):
    from .figures import save

    return save(fig, path)


def plot_crank_kinematics(mech, ax=None, path=None):
    """Slider displacement, velocity and acceleration over one revolution, exact vs series.

    Parameters
    ----------
    mech : CrankMechanism
    ax : matplotlib Axes, optional
        Draw all three curves (normalised by r, r w, r w^2) into this Axes.
    path : str or Path, optional
        Save the figure here.
    """
    from bearingfe import crank

    cs, w = mech.linkage, mech.drive.omega
    phi = np.linspace(0, 2 * np.pi, 721)
    deg = np.degrees(phi)
    curves = [
        ("X [m]", crank.slider_displacement(cs, phi), crank.slider_displacement_series(cs, phi), cs.crank),
        ("v [m/s]", crank.slider_velocity(cs, w, phi), crank.slider_velocity_series(cs, w, phi), cs.crank * w),
        ("a [m/s$^2$]", crank.slider_acceleration(cs, w, phi),
         crank.slider_acceleration_series(cs, w, phi, 2), cs.crank * w**2),
    ]
    fig, axes = _figure(ax, 3, (7.0, 7.0))
    for axis, (label, exact, series, scale) in zip(axes, curves):
        k = scale if ax is not None else 1.0
        name = label.split()[0]
        axis.plot(deg, exact / k, label=f"{name} exact")
        axis.plot(deg, series / k, "--", label=f"{name} series")
        if ax is None:
            axis.set_ylabel(label)
        axis.grid(True, alpha=0.3)
        axis.legend(loc="best", fontsize="small")
    axes[-1].set_xlabel("crank angle phi [deg]")
    axes[0].set_title(f"{mech.name}: lambda = {cs.lam:.4f}, omega = {w:.2f} 1/s")
    return _finish(fig, path)


def plot_efficiency(mill, rods=None, ax=None, path=None):
    """Instantaneous efficiency against crank angle for several rod lengths.

    Each curve is labelled by the smallest transmission angle in the working
    zones and the cycle efficiency, showing paper 003's conclusion: the
    closer the transmission angle stays to 90 deg, the higher the efficiency.
    Idle zones (no rolling) are shaded.

    Parameters
    ----------
    mill : MillDrive
    rods : sequence of float, optional
        Rod lengths [m]; default 1.5, 2.5, 4, 8 crank radii and the mill's own.
    """
    from bearingfe import efficiency as eff

    link = mill.linkage
    rods = sorted(set(rods if rods is not None else [k * link.crank for k in (1.5, 2.5, 4.0, 8.0)] + [link.rod]))
    theta = np.linspace(0, 2 * np.pi, 721)
    fig, (axis,) = _figure(ax)
    for rod in rods:
        variant = replace(mill, linkage=replace(link, rod=rod))
        res = eff.cycle(variant, samples=801)
        eta = eff.efficiency(variant.linkage, theta)
        eta = np.where(eff.working_mask(theta, mill.idle_zone), eta, np.nan)
        axis.plot(np.degrees(theta), eta,
                  label=f"l/r = {rod / link.crank:.2f}: psi_min = {np.degrees(res.min_transmission_angle):.1f} deg, "
                        f"eta_cycle = {res.efficiency:.3f}")
    half = np.degrees(mill.idle_zone / 2)
    for a, b in ((0, half), (180 - half, 180 + half), (360 - half, 360)):
        axis.axvspan(a, b, color="0.85", zorder=0)
    axis.set_xlabel("crank angle theta from the outer dead centre [deg]")
    axis.set_ylabel("instantaneous efficiency [-]")
    axis.set_title(f"{mill.name}")
    axis.grid(True, alpha=0.3)
    axis.legend(loc="lower center", fontsize="small")
    return _finish(fig, path)


def plot_natural_frequencies(system, critical_speeds=None, ax=None, path=None, band=(0.9, 1.1)):
    """Natural frequencies p1, p2 against column height for each section, with the exclusion bands.

    Parameters
    ----------
    system : RotorFrame
    critical_speeds : sequence of float, optional
        Default: natural frequencies of the reference design.
    """
    from bearingfe import rotor

    if critical_speeds is None:
        critical_speeds = rotor.natural_frequencies(system.rotor, rotor.frame_for(system))
    heights = np.linspace(*system.height_range, 600)
    fig, (axis,) = _figure(ax)
    for sec in system.sections or (system.section,):
        p1, p2 = rotor.natural_frequency_curves(system, sec, heights)
        (line,) = axis.plot(heights, p2, label=f"No. {sec.name}")
        axis.plot(heights, p1, ":", color=line.get_color())
    for wc in critical_speeds:
        axis.axhline(wc, color="k", lw=0.8)
        axis.axhspan(band[0] * wc, band[1] * wc, color="tab:red", alpha=0.15)
    axis.set_ylim(0.0, 1.6 * band[1] * max(critical_speeds))
    axis.set_xlabel("column height L [m]")
    axis.set_ylabel("natural frequency p [rad/s] (solid p2, dotted p1)")
    axis.set_title(f"{system.name}: excluded bands {band[0]}..{band[1]} w_cr")
    axis.grid(True, alpha=0.3)
    axis.legend(loc="upper right", fontsize="small")
    return _finish(fig, path)
