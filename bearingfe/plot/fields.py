"""Pictures of fields on the support surface (pyvista, off-screen).

The pressure or film thickness of a :class:`~bearingfe.ReynoldsResult` is
drawn either on the unwrapped plane ``(phi, z)`` or on the shoe's own
cylindrical surface ``(R0 cos phi, R0 sin phi, z)`` (optionally pushed
radially by the pressure). Pocket contours and the outline come from the
mesh's named boundaries (or from the :class:`~bearingfe.Surface` shapes
when given); the cavitation boundary is the ``p = 0`` contour.

pyvista is imported only inside these functions, with
``VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow`` set (if unset) so that
rendering works with no display (EGL on Mesa); importing :mod:`bearingfe`
never loads pyvista nor changes any display setting.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

__all__ = ["VIEWS", "field_grid", "outline_lines", "pocket_loops", "pocket_patches", "pressure_picture",
           "film_picture",
           "deflection_picture"]

VIEWS = ("unwrapped", "wrapped")


def _pyvista():
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista

    return pyvista


def _vertices(result) -> tuple[np.ndarray, np.ndarray]:
    """Vertex coordinates (2, nv) and triangles (3, nt) of the result's mesh."""
    m = result.basis.mesh
    nv = int(m.nvertices)
    t = np.asarray(m.t[:3])
    if t.max() >= nv:
        raise ValueError("mesh triangles refer to non-vertex nodes; cannot extract a P1 picture")
    return np.asarray(m.p[:, :nv], dtype=float), t


def _vertex_values(result, values) -> np.ndarray:
    nv = int(result.basis.mesh.nvertices)
    values = np.asarray(values, dtype=float)
    if values.shape[0] < nv:
        raise ValueError(f"values must have at least one entry per mesh vertex ({nv}), got {values.shape[0]}")
    # scikit-fem numbers vertex dofs first (P1 and P2 alike)
    return values[:nv]


def _embed(phi, z, view: str, radial=None) -> np.ndarray:
    """Points (n, 3) of the unwrapped plane or of the cylinder of radius 1 (+ radial)."""
    phi, z = np.asarray(phi, float), np.asarray(z, float)
    if view == "unwrapped":
        return np.column_stack([phi, z, np.zeros_like(phi)])
    r = 1.0 + (0.0 if radial is None else radial)
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def _check_view(view: str) -> None:
    if view not in VIEWS:
        raise ValueError(f"view must be one of {VIEWS}, got {view!r}")


def field_grid(result, values=None, *, name: str = "p", view: str = "unwrapped", warp: float = 0.0):
    """A pyvista UnstructuredGrid of the result's mesh carrying a vertex field.

    Parameters
    ----------
    result : ReynoldsResult
    values : ndarray, optional
        Dof values (default: ``result.pressure``); P2 results contribute
        their vertex values.
    name : str
        Name of the point-data array.
    view : {"unwrapped", "wrapped"}
        Plane ``(phi, z, 0)`` or cylinder ``(cos phi, sin phi, z)`` (unit radius ``R0``).
    warp : float
        Wrapped view only: radial displacement of the largest ``|value|``,
        as a fraction of ``R0`` (0 for none).
    """
    pv = _pyvista()
    _check_view(view)
    warp = float(warp)
    if not np.isfinite(warp) or warp < 0:
        raise ValueError(f"warp must be a finite number >= 0, got {warp!r}")
    xy, t = _vertices(result)
    v = _vertex_values(result, result.pressure if values is None else values)
    scale = np.abs(v).max()
    radial = warp * v / scale if (warp and scale > 0) else None
    points = _embed(xy[0], xy[1], view, radial)
    cells = np.hstack([np.full((t.shape[1], 1), 3), t.T]).ravel()
    grid = pv.UnstructuredGrid(cells, np.full(t.shape[1], pv.CellType.TRIANGLE, dtype=np.uint8), points)
    grid.point_data[name] = v
    return grid


def outline_lines(result, *, surface=None, boundary: str = "inlet", view: str = "unwrapped"):
    """Boundary curves as pyvista PolyData lines (None if there are none).

    From ``surface`` (exact shape polylines: ``"inlet"`` -> pockets,
    ``"outer"`` -> outline) when given, otherwise from the mesh facets of the
    named boundary.
    """
    pv = _pyvista()
    _check_view(view)
    lift = 1e-3  # keep lines just in front of (unwrapped) or outside (wrapped) the surface
    if surface is not None:
        shapes = surface.inlets if boundary == "inlet" else (surface.outline,)
        polys = []
        for shape in shapes:
            xy = shape.boundary(360)
            xy = np.hstack([xy, xy[:, :1]])
            pts = _embed(xy[0], xy[1], view, lift if view == "wrapped" else None)
            if view == "unwrapped":
                pts[:, 2] = lift
            polys.append(pv.lines_from_points(pts))
        return pv.merge(polys) if polys else None
    m = result.basis.mesh
    facets = (m.boundaries or {}).get(boundary)
    if facets is None or len(facets) == 0:
        return None
    ends = np.asarray(m.facets[:, facets])
    nodes, inverse = np.unique(ends, return_inverse=True)
    xy = m.p[:, nodes]
    pts = _embed(xy[0], xy[1], view, lift if view == "wrapped" else None)
    if view == "unwrapped":
        pts[:, 2] = lift
    lines = np.hstack([np.full((ends.shape[1], 1), 2), inverse.reshape(2, -1).T]).ravel()
    return pv.PolyData(pts, lines=lines)


def pocket_loops(result, surface=None) -> list[np.ndarray]:
    """Pocket contours as closed polylines (2, n) in ``(phi, z)``."""
    if surface is not None:
        return [shape.boundary(360) for shape in surface.inlets]
    m = result.basis.mesh
    bnd = m.boundaries or {}
    names = sorted(k for k in bnd if k.startswith("inlet_")) or (["inlet"] if "inlet" in bnd else [])
    loops = []
    for name in names:
        loops.extend(_chain(np.asarray(m.facets[:, bnd[name]])))
    return [m.p[:, loop] for loop in loops]


def _chain(edges: np.ndarray) -> list[np.ndarray]:
    """Order boundary edges (2, k) into closed loops of node indices."""
    neighbours: dict[int, list[int]] = {}
    for a, b in edges.T.tolist():
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)
    seen: set[int] = set()
    loops = []
    for start in neighbours:
        if start in seen:
            continue
        loop, prev, node = [start], None, start
        seen.add(start)
        while True:
            nxt = [n for n in neighbours[node] if n != prev and n not in seen]
            if not nxt:
                break
            prev, node = node, nxt[0]
            seen.add(node)
            loop.append(node)
        if len(loop) >= 3:
            loops.append(np.array(loop))
    return loops


def pocket_patches(result, *, surface=None, view: str = "unwrapped", value: float = 0.0, name: str = "p"):
    """The pockets (holes of the mesh) as filled pyvista patches carrying ``value``, or None."""
    pv = _pyvista()
    _check_view(view)
    patches = []
    for xy in pocket_loops(result, surface):
        n = xy.shape[1]
        flat = pv.PolyData(np.column_stack([xy[0], xy[1], np.zeros(n)]),
                           faces=np.hstack([[n], np.arange(n)])).triangulate()
        pts = np.asarray(flat.points)
        flat.points = _embed(pts[:, 0], pts[:, 1], view)
        flat.point_data[name] = np.full(flat.n_points, float(value))
        patches.append(flat)
    return pv.merge(patches) if patches else None


def _zero_contour(result, grid, name: str, values: np.ndarray):
    """The cavitation boundary: edge of ``result.cavitated`` if present, else the ``p = 0``
    line through the film (the outline, where ``p = 0`` by the boundary condition, left out)."""
    pv = _pyvista()
    mask = getattr(result, "cavitated", None)
    if mask is not None:
        flag = np.asarray(mask, dtype=float).ravel()
        if flag.size < grid.n_points or flag[: grid.n_points].min() == flag[: grid.n_points].max():
            return None
        probe = grid.copy()
        probe.point_data["cavitated"] = flag[: grid.n_points]
        line = probe.contour([0.5], scalars="cavitated")
        return line if line.n_points else None
    if not (values.min() < 0.0 < values.max()):
        return None
    line = grid.contour([0.0], scalars=name)
    if not line.n_points:
        return None
    on_outline = _on_outline(result, np.asarray(line.points)[:, :2])
    if on_outline is None:
        return line
    cells = line.lines.reshape(-1, 3)[:, 1:]
    keep = ~(on_outline[cells[:, 0]] & on_outline[cells[:, 1]])
    if not keep.any():
        return None
    kept = np.hstack([np.full((keep.sum(), 1), 2), cells[keep]]).ravel()
    return pv.PolyData(np.asarray(line.points), lines=kept).clean()


def _on_outline(result, xy: np.ndarray) -> np.ndarray | None:
    """Which points lie on the mesh's outer boundary (None if it is not named)."""
    m = result.basis.mesh
    facets = (m.boundaries or {}).get("outer")
    if facets is None:
        return None
    a, b = m.p[:, m.facets[0, facets]].T, m.p[:, m.facets[1, facets]].T
    d = b - a
    t = np.clip(np.einsum("pmk,mk->pm", xy[:, None, :] - a[None], d) / np.einsum("mk,mk->m", d, d), 0, 1)
    dist = np.linalg.norm(xy[:, None, :] - (a[None] + t[..., None] * d[None]), axis=-1).min(axis=1)
    return dist < 1e-9 * (1.0 + np.abs(m.p).max())


def _render(path, view, grid, name, title, cmap, overlays, window_size, pockets=None, pocket_color=None,
            heading=None):
    pv = _pyvista()
    path = Path(path)
    values = np.asarray(grid.point_data[name])
    clim = [float(values.min()), float(values.max())]
    if pockets is not None and pocket_color is None:
        pv_ = float(pockets.point_data[name][0])
        clim = [min(clim[0], pv_), max(clim[1], pv_)]
    if clim[0] == clim[1]:
        clim[1] = clim[0] + 1.0
    pl = pv.Plotter(off_screen=True, window_size=list(window_size))
    try:
        pl.set_background("white")
        # labels "%.3g" (no cut "127."), the bar clear of the right edge
        bar = dict(title=title, color="black", vertical=True, position_x=0.84, position_y=0.1,
                   height=0.75, width=0.05, fmt="%.3g", n_labels=5, title_font_size=16, label_font_size=14)
        shading = dict(smooth_shading=True, ambient=0.35) if view == "wrapped" else dict(lighting=False)
        pl.add_mesh(grid, scalars=name, cmap=cmap, clim=clim, scalar_bar_args=bar, **shading)
        if heading:
            pl.add_text(str(heading), position="upper_edge", color="black", font_size=10)
        if pockets is not None:
            if pocket_color is None:
                pl.add_mesh(pockets, scalars=name, cmap=cmap, clim=clim, show_scalar_bar=False, **shading)
            else:
                pl.add_mesh(pockets, color=pocket_color, **shading)
        legend = []
        for overlay in overlays:
            mesh, color, width = overlay[:3]
            if mesh is not None:
                pl.add_mesh(mesh, color=color, line_width=width)
                if len(overlay) > 3:
                    legend.append([overlay[3], color])
        if legend:  # the coloured curves say what they are
            pl.add_legend(legend, bcolor="white", size=(0.3, 0.06 * len(legend)), loc="lower left", face="-")
        if view == "unwrapped":
            pl.view_xy()
            pl.enable_parallel_projection()
            bounds = grid.bounds
            ratio = (bounds[3] - bounds[2]) / max(bounds[1] - bounds[0], 1e-12)
            pl.show_bounds(grid=False, location="outer", xtitle="phi [rad]", ytitle="z [R0]", color="black",
                           show_zaxis=False, font_size=12, n_ylabels=3 if ratio < 0.35 else 5, fmt="%.2g")
            pl.reset_camera()
            pl.camera.zoom(1.05)
        else:
            pl.view_vector((1.0, 0.35, 0.6))
            pl.reset_camera()
        from ..io.writers import atomic_path

        with atomic_path(path) as tmp:  # no half-written picture if rendering fails
            pl.screenshot(str(tmp))
    finally:
        pl.close()
    return path


def _check_scale(scale: float, unit: str) -> float:
    scale = float(scale)
    if not (math.isfinite(scale) and scale > 0):
        raise ValueError(f"scale must be a finite number > 0, got {scale!r}")
    if not isinstance(unit, str) or not unit:
        raise ValueError(f"unit must be a non-empty string, got {unit!r}")
    return scale


def pressure_picture(result, path, *, surface=None, view: str = "unwrapped", warp: float = 0.0,
                     cavitation: bool = True, cmap: str = "viridis", window_size=(1000, 600),
                     scale: float = 1.0, unit: str = "-", title: str | None = None) -> Path:
    """PNG of the pressure field with pocket outlines and the cavitation boundary.

    Parameters
    ----------
    result : ReynoldsResult
        Any result with ``basis`` and ``pressure`` (P1 or P2); the pockets
        are drawn filled at ``result.inlet_pressure``.
    path : str or Path
        PNG file to write.
    surface : Surface, optional
        Draw the exact pocket and outline curves instead of the mesh edges.
    view : {"unwrapped", "wrapped"}
        The unwrapped plane ``(phi, z)`` or the shoe's cylindrical surface.
    warp : float
        Wrapped view: radial displacement of the peak pressure [R0].
    cavitation : bool
        Draw the ``p = 0`` contour (red) where the pressure changes sign; for
        a result with a ``cavitated`` mask, the edge of the cavitated region.
    scale, unit : float, str
        Pressure shown as ``scale * p`` labelled ``p [unit]`` (e.g. the
        pressure scale in MPa and ``"MPa"``); default non-dimensional.
    title : str, optional
        Heading above the picture (e.g. the shaft angle).

    Returns
    -------
    Path
        The written file.
    """
    _check_view(view)
    scale = _check_scale(scale, unit)
    grid = field_grid(result, np.asarray(result.pressure, dtype=float) * scale, name="p", view=view, warp=warp)
    values = np.asarray(grid.point_data["p"])
    inlet = float(getattr(result, "inlet_pressure", 0.0)) * scale
    pockets = pocket_patches(result, surface=surface, view=view, value=inlet, name="p")
    if pockets is not None and warp and view == "wrapped":
        scale = np.abs(values).max()
        pts = np.asarray(pockets.points)
        phi = np.arctan2(pts[:, 1], pts[:, 0])
        pockets.points = _embed(phi, pts[:, 2], view, warp * inlet / scale if scale > 0 else None)
    overlays = [(outline_lines(result, surface=surface, boundary="outer", view=view), "black", 2),
                (outline_lines(result, surface=surface, boundary="inlet", view=view), "black", 2)]
    if cavitation:
        flat = grid if view == "unwrapped" else field_grid(result, name="p")
        zero = _zero_contour(result, flat, "p", np.asarray(flat.point_data["p"]))
        if zero is not None and view == "wrapped":
            pts = np.asarray(zero.points)
            zero.points = _embed(pts[:, 0], pts[:, 1], view, 2e-3)
        label = "film rupture boundary" if getattr(result, "cavitated", None) is not None else "p = 0"
        overlays.append((zero, "red", 3, label))
    return _render(path, view, grid, "p", f"p [{unit}]", cmap, overlays, window_size, pockets, heading=title)


def film_picture(result, path, *, film=None, surface=None, view: str = "unwrapped", cmap: str = "plasma",
                 window_size=(1000, 600), scale: float = 1.0, unit: str = "-", title: str | None = None) -> Path:
    """PNG of the film thickness ``h = H/c`` over the surface, pockets in grey.

    Parameters
    ----------
    result : ReynoldsResult
        Supplies the mesh (and the film, unless ``film`` is given).
    path : str or Path
        PNG file to write.
    film : Film, optional
        Film to draw (default ``result.film``).
    surface : Surface, optional
        Exact outlines instead of mesh edges.
    view : {"unwrapped", "wrapped"}
    scale, unit : float, str
        Film shown as ``scale * h`` labelled ``h [unit]`` (e.g. the clearance
        in um and ``"um"``); default non-dimensional.
    title : str, optional
        Heading above the picture.

    Returns
    -------
    Path
    """
    _check_view(view)
    scale = _check_scale(scale, unit)
    film = result.film if film is None else film
    xy, _ = _vertices(result)
    h = np.asarray(film.thickness(xy[0], xy[1]), dtype=float) * scale
    grid = field_grid(result, values=h, name="h", view=view)
    pockets = pocket_patches(result, surface=surface, view=view, name="h")
    overlays = [(outline_lines(result, surface=surface, boundary="outer", view=view), "black", 2),
                (outline_lines(result, surface=surface, boundary="inlet", view=view), "black", 2)]
    return _render(path, view, grid, "h", f"h [{unit}]", cmap, overlays, window_size, pockets, "lightgrey",
                   heading=title)


def deflection_picture(result, path, *, surface=None, view: str = "unwrapped", cmap: str = "cividis",
                       window_size=(1000, 600), scale: float = 1.0, unit: str = "-",
                       title: str | None = None) -> Path:
    """PNG of the film opening ``w`` by an elastic support (``result.deflection``), pockets in grey.

    Parameters
    ----------
    result : ReynoldsResult
        A solution on an elastic support (``solve_reynolds(..., elastic=...)``).
    path : str or Path
    surface : Surface, optional
    view : {"unwrapped", "wrapped"}
    scale, unit : float, str
        Shown as ``scale * w`` labelled ``w [unit]`` (e.g. the clearance in um).
    title : str, optional

    Returns
    -------
    Path
    """
    _check_view(view)
    scale = _check_scale(scale, unit)
    w = getattr(result, "deflection", None)
    if w is None:
        raise ValueError("result has no deflection: solve with an elastic support (elastic=...)")
    grid = field_grid(result, values=np.asarray(w, dtype=float) * scale, name="w", view=view)
    pockets = pocket_patches(result, surface=surface, view=view, name="w")
    overlays = [(outline_lines(result, surface=surface, boundary="outer", view=view), "black", 2),
                (outline_lines(result, surface=surface, boundary="inlet", view=view), "black", 2)]
    return _render(path, view, grid, "w", f"w [{unit}]", cmap, overlays, window_size, pockets, "lightgrey",
                   heading=title)
