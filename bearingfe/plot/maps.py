"""Field maps of film results drawn with matplotlib, for comparisons side by side.

A film result's field (pressure, film thickness, deflection) is sampled on a
refined display mesh (:func:`sampled`): every triangle is split ``nrefs``
times and the P1 or P2 field evaluated at the new points through its own
basis (``CellBasis.refinterp``), so a P2 field on a coarse curved mesh is
drawn with its quadratic variation instead of facets. The film is evaluated
exactly at the display points. :func:`field_axes` draws one field into an
axes (Gouraud shading, pockets filled, pocket and outline curves, the
cavitation line ``p = 0``, a colour bar with its unit); :func:`field_panels`
lays out a grid of them and saves it.

Coordinates are drawn in SI-derived units a designer reads: the angle
``phi`` in degrees and the axial position ``z`` in mm (``z R0``), with the
aspect of the real surface (arc length ``R0 phi`` against ``R0 z``).
Nothing here touches pyplot's global state.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from .figures import frame, save, title as set_title

__all__ = ["FIELDS", "DISPLAY_TRIANGLES", "MAP_TICKS", "TICK_STEPS", "Panel", "refinements", "sampled", "gouraud",
           "field_axes", "field_panels"]

#: Field kind -> (symbol, colour map, pocket colour or None: the pockets carry the inlet pressure).
FIELDS = {"pressure": ("p", "viridis", None), "film": ("h", "plasma", "lightgrey"),
          "deflection": ("w", "cividis", "lightgrey")}


@dataclass(frozen=True)
class Panel:
    """One field map: ``kind`` of ``result`` shown as ``scale * value`` in ``unit``, titled ``title``.

    ``radius`` is the eccentric radius ``R0`` [m] (axes in deg and mm; ``None``: a non-dimensional
    result, ``z`` in units of ``R0``); ``surface`` gives the exact
    pocket and outline curves; ``offset_deg`` is added to the angle (e.g. a pad's place in the
    bearing frame); ``true_aspect``: draw arc length and width to the same scale (a full journal
    bearing, far longer round than wide, reads better stretched: ``False``); ``plane``: the result lives on
    a plane (a thrust pad: ``x``, ``y`` in units of ``R0``), both axes drawn in mm.
    """

    result: Any
    kind: str
    scale: float
    unit: str
    radius: float | None
    title: str = ""
    surface: Any = None
    offset_deg: float = 0.0
    true_aspect: bool = True
    plane: bool = False


#: Most intervals between the ticks of a map's axes and colour bar (matplotlib's ``MaxNLocator``), at the
#: :data:`TICK_STEPS` multiples (the defaults draw about seven per axis; every tick is drawn and costs about 1 ms).
MAP_TICKS = 4
#: Tick spacings a map's axes may take, times a power of ten.
TICK_STEPS = (1, 2, 2.5, 5, 10)

#: Display triangles aimed at: a P2 field is refined while its display mesh stays below this.
DISPLAY_TRIANGLES = 20000


def refinements(result) -> int:
    """How often to split the triangles for display: 0 for P1 (linear: nothing to gain), for P2 as
    often as keeps the display mesh under :data:`DISPLAY_TRIANGLES` (at least once)."""
    basis = result.basis
    if basis.N <= basis.mesh.nvertices:  # P1: one dof per vertex
        return 0
    nt, k = basis.mesh.t.shape[1], 1
    while k < 3 and nt * 4 ** (k + 1) <= DISPLAY_TRIANGLES:
        k += 1
    return k


def sampled(result, values: np.ndarray | None = None, *, kind: str = "pressure", nrefs: int | None = None):
    """Display points (2, n) ``(phi, z)`` [-], triangles (3, m) and field values (n,) [-] of a result.

    ``nrefs``: splits of every triangle (default :func:`refinements`).

    ``values``: dofs of the result's basis (default: the pressure, or the deflection for
    ``kind="deflection"``); ``kind="film"``: the film thickness, evaluated exactly at the points.
    """
    basis = result.basis
    nrefs = refinements(result) if nrefs is None else int(nrefs)
    if kind == "film":
        mesh, _ = basis.refinterp(np.zeros(basis.N), nrefs=nrefs)
        xy = np.asarray(mesh.p, dtype=float)
        return xy, np.asarray(mesh.t), np.asarray(result.film.thickness(xy[0], xy[1]), dtype=float)
    if values is None:
        values = result.deflection if kind == "deflection" else result.pressure
        if values is None:
            raise ValueError("result has no deflection: solve with an elastic support (elastic=...)")
    mesh, z = basis.refinterp(np.asarray(values, dtype=float), nrefs=nrefs)
    return np.asarray(mesh.p, dtype=float), np.asarray(mesh.t), np.asarray(z, dtype=float)


def gouraud(ax, tri, values: np.ndarray, cmap, lo: float, hi: float):
    """``values`` at the points of the triangulation ``tri`` drawn into ``ax`` with Gouraud shading, colours
    ``lo``..``hi`` of ``cmap`` (rasterized); returns the ``TriMesh``.

    What ``ax.tripcolor(tri, values, shading="gouraud", ...)`` draws, with the axes' data limits taken from the
    points' box: matplotlib before 3.11 also measured every triangle as a path of its own (a tenth of a second
    for the four maps of a picture)."""
    from matplotlib.collections import TriMesh

    mesh = TriMesh(tri, array=np.asarray(values, dtype=float), cmap=cmap, rasterized=True)
    mesh.set_clim(lo, hi)
    ax.grid(False)
    ax.update_datalim([(float(tri.x.min()), float(tri.y.min())), (float(tri.x.max()), float(tri.y.max()))])
    ax.autoscale_view()
    ax.add_collection(mesh, autolim=False)
    return mesh


def field_axes(ax, panel: Panel, *, nrefs: int | None = None, colorbar: bool = True):
    """Draw ``panel`` into ``ax``; returns the mappable (a ``TriMesh``/``PolyCollection``).

    The colour bar (:func:`bearingfe.plot.colour_bars.colour_bar`, also ``mappable.colorbar``) is labelled
    ``"<symbol> [<unit>]"``; the pockets are
    filled with the inlet pressure (pressure) or grey (film, deflection) and outlined in black; the
    ``p = 0`` line of a pressure that changes sign is drawn in red.
    """
    from matplotlib.tri import Triangulation

    if panel.kind not in FIELDS:
        raise ValueError(f"kind must be one of {tuple(FIELDS)}, got {panel.kind!r}")
    symbol, cmap, pocket_color = FIELDS[panel.kind]
    xy, t, v = sampled(panel.result, kind=panel.kind, nrefs=nrefs)
    v = v * panel.scale
    to_mm = 1.0 if panel.radius is None else panel.radius * 1e3
    def to_axes(u, w):
        return (u * to_mm, w * to_mm) if panel.plane else (np.degrees(u) + panel.offset_deg, w * to_mm)

    x, y = to_axes(xy[0], xy[1])
    tri = Triangulation(x, y, t.T)
    lo, hi = float(v.min()), float(v.max())
    inlet = float(getattr(panel.result, "inlet_pressure", 0.0)) * panel.scale
    from .fields import pocket_loops  # pure numpy: no pyvista import

    loops = pocket_loops(panel.result, panel.surface)
    if pocket_color is None and loops:
        lo, hi = min(lo, inlet), max(hi, inlet)
    if hi <= lo:
        hi = lo + (abs(lo) or 1.0) * 1e-6
    mappable = gouraud(ax, tri, v, cmap, lo, hi)
    for loop in loops:
        px, py = to_axes(loop[0], loop[1])
        if pocket_color is None:
            ax.fill(px, py, color=mappable.cmap(mappable.norm(inlet)), zorder=2)
        else:
            ax.fill(px, py, color=pocket_color, zorder=2)
        ax.plot(np.append(px, px[0]), np.append(py, py[0]), color="k", lw=1.0, zorder=3)
    if panel.surface is not None:
        out = panel.surface.outline.boundary(360)
        ox, oy = to_axes(np.append(out[0], out[0, 0]), np.append(out[1], out[1, 0]))
        ax.plot(ox, oy, color="k", lw=1.0)
    ruptured = getattr(panel.result, "cavitated", None)
    limits = ax.get_xlim(), ax.get_ylim()  # a contour autoscales its axes tight: this panel keeps the others'
    if panel.kind == "pressure" and ruptured is not None and np.size(ruptured) == panel.result.basis.N:
        _, _, flag = sampled(panel.result, np.asarray(ruptured, dtype=float).ravel(), nrefs=nrefs)
        if flag.min() < 0.5 < flag.max():
            ax.tricontour(tri, flag, levels=[0.5], colors="red", linewidths=1.2)
            ax.plot([], [], color="red", label="film rupture boundary")
    elif panel.kind == "pressure" and v.min() < 0.0 < v.max():
        ax.tricontour(tri, v, levels=[0.0], colors="red", linewidths=1.2)
        ax.plot([], [], color="red", label="p = 0")
    ax.set_xlim(limits[0])
    ax.set_ylim(limits[1])
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper right", fontsize="small")
    unit = "R0" if panel.radius is None else "mm"
    if panel.plane:
        ax.set_aspect(1.0)
        ax.set_xlabel(f"x [{unit}]")
        ax.set_ylabel(f"y [{unit}]")
    else:
        if panel.true_aspect:
            ax.set_aspect(1.0 / (np.pi / 180 * to_mm))  # 1 deg of arc is R0 pi/180 long
        ax.set_xlabel("phi [deg]")
        ax.set_ylabel(f"z [{unit}]")
    if panel.title:
        set_title(ax, panel.title, fontsize="medium")
    from matplotlib.ticker import MaxNLocator

    for axis in (ax.xaxis, ax.yaxis):  # a map is read by its colours: a few ticks place it (each costs ~1 ms)
        axis.set_major_locator(MaxNLocator(MAP_TICKS, steps=TICK_STEPS))
    if colorbar:
        from .colour_bars import colour_bar

        colour_bar(ax, mappable, f"{symbol} [{panel.unit}]", MaxNLocator(MAP_TICKS, steps=TICK_STEPS))
    return mappable


def field_panels(panels: Sequence[Sequence[Panel | None]], path=None, *, title: str | None = None,
                 nrefs: int | None = None, panel_size=(5.2, 3.4)):
    """A grid of field maps (rows of :class:`Panel`, ``None`` leaves a cell empty); saved if ``path``.

    Returns
    -------
    matplotlib.figure.Figure
        One axes per panel (empty cells removed); each panel's colour bar is an artist of the figure
        (:class:`bearingfe.plot.colour_bars.ColourBar`, in ``fig.artists``).
    """
    from matplotlib.figure import Figure

    rows = [list(r) for r in panels]
    if not rows or not any(p is not None for r in rows for p in r):
        raise ValueError("no panel to draw")
    ncols = max(len(r) for r in rows)
    fig = Figure(figsize=(panel_size[0] * ncols, panel_size[1] * len(rows) + (0.4 if title else 0.0)))
    # fixed margins [in]: two-line panel titles above, tick and axis labels left and below, the colour
    # bar's label right of every panel (its bar takes a share of the panel's own width)
    grid = frame(fig, nrows=len(rows), ncols=ncols, top=0.55 + (0.4 if title else 0.0), bottom=0.5, left=0.75,
                 right=0.35, wgap=0.95, hgap=1.0)
    axes = np.atleast_2d(grid.subplots(squeeze=False))
    for i, row in enumerate(rows):
        for j in range(ncols):
            panel = row[j] if j < len(row) else None
            if panel is None:
                fig.delaxes(axes[i, j])
            else:
                field_axes(axes[i, j], panel, nrefs=nrefs)
    if title:
        fig.suptitle(title)
    return save(fig, path)
