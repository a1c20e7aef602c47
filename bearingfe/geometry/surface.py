"""Support-surface geometry in unwrapped non-dimensional coordinates.

The shoe surface is described in the plane ``(phi, z)``: ``phi`` [rad] is the
angle along the arc and ``z = Z / R0`` the axial coordinate scaled by the
eccentric radius, so that the Reynolds operator is isotropic in this plane.
The film domain is an outer contour (by default the rectangle
``[alpha1, alpha2] x [-a, a]``) minus any number of inlet pockets of any shape.

Every shape is a frozen dataclass that knows its area, a fine polyline of its
boundary (used to validate the layout before gmsh is called), a point-inside
test (used by the finite-difference reference) and how to draw itself with
gmsh's OpenCASCADE kernel.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol, Sequence, runtime_checkable

import numpy as np

from ..core.checks import check_depth
from ..core.schema import positive
from .runner import ALONG_PHI, Runner

__all__ = [
    "Shape",
    "Circle",
    "Ellipse",
    "Rectangle",
    "Polygon",
    "Slot",
    "Recess",
    "Surface",
]

#: Number of points used to sample a curved boundary for layout checks.
_SAMPLES = 720


@runtime_checkable
class Shape(Protocol):
    """A closed planar region in the ``(phi, z)`` plane."""

    @property
    def area(self) -> float: ...

    def boundary(self, n: int = _SAMPLES) -> np.ndarray:
        """Counter-clockwise boundary polyline, shape ``(2, m)`` (not closed)."""

    def contains(self, phi: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Boolean mask of points strictly inside the shape."""

    def corners(self) -> np.ndarray:
        """Sharp corners, shape ``(2, k)`` (k may be 0)."""

    def add_to_gmsh(self, occ) -> list[int]:
        """Add the boundary curves to gmsh's OCC kernel, return their tags in loop order."""


def _pair(value, name: str) -> tuple[float, float]:
    try:
        x, y = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair of numbers, got {value!r}") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return x, y


@dataclass(frozen=True)
class Circle:
    """Circular pocket.

    Parameters
    ----------
    center : (float, float)
        Centre ``(phi, z)`` [rad, -].
    radius : float
        Radius in the unwrapped plane [-] (units of R0), > 0.
    """

    center: tuple[float, float]
    radius: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "center", _pair(self.center, "Circle.center"))
        object.__setattr__(self, "radius", positive("Circle.radius", self.radius))

    @property
    def area(self) -> float:
        return math.pi * self.radius**2

    def boundary(self, n: int = _SAMPLES) -> np.ndarray:
        t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
        return np.array(self.center)[:, None] + self.radius * np.array([np.cos(t), np.sin(t)])

    def contains(self, phi, z):
        return (np.asarray(phi) - self.center[0]) ** 2 + (np.asarray(z) - self.center[1]) ** 2 < self.radius**2

    def corners(self) -> np.ndarray:
        return np.zeros((2, 0))

    def add_to_gmsh(self, occ) -> list[int]:
        return [occ.addCircle(self.center[0], self.center[1], 0.0, self.radius)]


@dataclass(frozen=True)
class Ellipse:
    """Elliptical pocket.

    Parameters
    ----------
    center : (float, float)
        Centre ``(phi, z)``.
    semi_axes : (float, float)
        Semi-axes along the (rotated) phi and z directions, both > 0.
    angle : float
        Rotation of the first semi-axis from the phi direction [rad].
    """

    center: tuple[float, float]
    semi_axes: tuple[float, float]
    angle: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "center", _pair(self.center, "Ellipse.center"))
        a, b = _pair(self.semi_axes, "Ellipse.semi_axes")
        positive("Ellipse.semi_axes[0]", a)
        positive("Ellipse.semi_axes[1]", b)
        object.__setattr__(self, "semi_axes", (a, b))
        if not math.isfinite(float(self.angle)):
            raise ValueError(f"Ellipse.angle must be finite, got {self.angle!r}")
        object.__setattr__(self, "angle", float(self.angle))

    @property
    def area(self) -> float:
        return math.pi * self.semi_axes[0] * self.semi_axes[1]

    def _local(self, phi, z):
        c, s = math.cos(self.angle), math.sin(self.angle)
        dx, dy = np.asarray(phi) - self.center[0], np.asarray(z) - self.center[1]
        return c * dx + s * dy, -s * dx + c * dy

    def boundary(self, n: int = _SAMPLES) -> np.ndarray:
        t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
        u, v = self.semi_axes[0] * np.cos(t), self.semi_axes[1] * np.sin(t)
        c, s = math.cos(self.angle), math.sin(self.angle)
        return np.array([self.center[0] + c * u - s * v, self.center[1] + s * u + c * v])

    def contains(self, phi, z):
        u, v = self._local(phi, z)
        return (u / self.semi_axes[0]) ** 2 + (v / self.semi_axes[1]) ** 2 < 1.0

    def corners(self) -> np.ndarray:
        return np.zeros((2, 0))

    def add_to_gmsh(self, occ) -> list[int]:
        a, b = self.semi_axes
        angle = self.angle
        if a < b:  # gmsh wants the major radius first
            a, b, angle = b, a, angle + math.pi / 2
        x_axis = [math.cos(angle), math.sin(angle), 0.0]
        return [occ.addEllipse(self.center[0], self.center[1], 0.0, a, b, zAxis=[0, 0, 1], xAxis=x_axis)]


@dataclass(frozen=True)
class Polygon:
    """Polygonal region with straight edges and sharp corners.

    Parameters
    ----------
    points : sequence of (float, float)
        Vertices ``(phi, z)`` in order (either orientation); at least three,
        no repeated vertex, no self-intersection, non-zero area.
    """

    points: tuple[tuple[float, float], ...]

    def __post_init__(self) -> None:
        try:
            pts = tuple(_pair(p, "Polygon.points[i]") for p in self.points)
        except TypeError:
            raise ValueError(f"Polygon.points must be a sequence of pairs, got {self.points!r}") from None
        if len(pts) < 3:
            raise ValueError(f"Polygon.points needs at least 3 vertices, got {len(pts)}")
        xy = np.array(pts).T
        if _signed_area(xy) < 0:  # store counter-clockwise
            pts = pts[::-1]
            xy = xy[:, ::-1]
        scale = float(np.ptp(xy, axis=1).max())
        edge = np.linalg.norm(np.roll(xy, -1, axis=1) - xy, axis=0)
        if scale == 0.0 or edge.min() <= 1e-12 * scale:
            raise ValueError("Polygon.points has repeated (coincident) vertices")
        if _self_intersects(xy):
            raise ValueError("Polygon.points describes a self-intersecting polygon")
        if abs(_signed_area(xy)) <= 1e-12 * scale**2:
            raise ValueError("Polygon.points encloses zero area (degenerate polygon)")
        object.__setattr__(self, "points", pts)

    @property
    def area(self) -> float:
        return abs(_signed_area(np.array(self.points).T))

    def boundary(self, n: int = _SAMPLES) -> np.ndarray:
        xy = np.array(self.points).T
        per_edge = max(2, n // len(self.points))
        out = []
        for a, b in zip(xy.T, np.roll(xy, -1, axis=1).T):
            t = np.linspace(0.0, 1.0, per_edge, endpoint=False)
            out.append(a[:, None] + (b - a)[:, None] * t)
        return np.hstack(out)

    def contains(self, phi, z):
        return _points_in_polygon(np.array(self.points).T, np.asarray(phi, float), np.asarray(z, float))

    def corners(self) -> np.ndarray:
        return np.array(self.points).T

    def add_to_gmsh(self, occ) -> list[int]:
        tags = [occ.addPoint(x, y, 0.0) for x, y in self.points]
        return [occ.addLine(tags[i], tags[(i + 1) % len(tags)]) for i in range(len(tags))]


def Rectangle(center: Sequence[float], size: Sequence[float], angle: float = 0.0) -> Polygon:
    """Rectangular recess with sharp corners.

    Parameters
    ----------
    center : (float, float)
        Centre ``(phi, z)``.
    size : (float, float)
        Full lengths along phi and z (before rotation), both > 0.
    angle : float
        Rotation [rad].
    """
    cx, cy = _pair(center, "Rectangle.center")
    w, h = _pair(size, "Rectangle.size")
    positive("Rectangle.size[0]", w)
    positive("Rectangle.size[1]", h)
    c, s = math.cos(angle), math.sin(angle)
    local = [(-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)]
    return Polygon(tuple((cx + c * u - s * v, cy + s * u + c * v) for u, v in local))


@dataclass(frozen=True)
class AnnularSector:
    """An annular sector: the outline of a thrust pad in the plane of its runner.

    Parameters
    ----------
    inner_radius, outer_radius : float
        Radii of the inner and outer rims [-] (units of the reference radius), ``0 < inner < outer``.
    start : float
        Angle of the edge at the sector's start (the leading edge under a counter-clockwise runner),
        from the ``+x`` axis [rad].
    extent : float
        Angular extent of the sector [rad], ``0 < extent < 2 pi``; the sector runs counter-clockwise from
        ``start``.
    centre : (float, float)
        Centre of the rims [-] (the runner's axis for a thrust bearing).

    Notes
    -----
    Its edges are named for the flows (:meth:`edge_groups`): ``arc_start`` (the radial edge at ``start``),
    ``outer_rim``, ``arc_end`` (the radial edge at ``start + extent``) and ``inner_rim``; the rims are
    exact circular arcs in gmsh.
    """

    inner_radius: float
    outer_radius: float
    start: float = 0.0
    extent: float = math.pi / 4
    centre: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        ri = positive("AnnularSector.inner_radius", self.inner_radius)
        ro = positive("AnnularSector.outer_radius", self.outer_radius)
        if not ro > ri:
            raise ValueError(f"AnnularSector.outer_radius must exceed inner_radius ({ri!r}), got {ro!r}")
        start, extent = float(self.start), float(self.extent)
        if not (math.isfinite(start) and abs(start) <= 1e3):
            raise ValueError(f"AnnularSector.start must be a finite angle [rad] with |start| <= 1e3, got {self.start!r}")
        if not (math.isfinite(extent) and 0.0 < extent < 2 * math.pi):
            raise ValueError(f"AnnularSector.extent must be in (0, 2 pi) [rad], got {self.extent!r}")
        object.__setattr__(self, "inner_radius", ri)
        object.__setattr__(self, "outer_radius", ro)
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "extent", extent)
        object.__setattr__(self, "centre", _pair(self.centre, "AnnularSector.centre"))

    @property
    def area(self) -> float:
        return 0.5 * self.extent * (self.outer_radius**2 - self.inner_radius**2)

    def _point(self, r, angle) -> np.ndarray:
        return np.array([self.centre[0] + r * np.cos(angle), self.centre[1] + r * np.sin(angle)])

    def boundary(self, n: int = _SAMPLES) -> np.ndarray:
        ri, ro, a1 = self.inner_radius, self.outer_radius, self.start
        a2 = a1 + self.extent
        lengths = np.array([ro - ri, ro * self.extent, ro - ri, ri * self.extent])
        counts = np.maximum(2, np.round(n * lengths / lengths.sum()).astype(int))
        t = [np.linspace(0.0, 1.0, k, endpoint=False) for k in counts]
        return np.hstack([self._point(ri + (ro - ri) * t[0], a1 + 0 * t[0]),
                          self._point(ro + 0 * t[1], a1 + self.extent * t[1]),
                          self._point(ro - (ro - ri) * t[2], a2 + 0 * t[2]),
                          self._point(ri + 0 * t[3], a2 - self.extent * t[3])])

    def polar(self, x, y) -> tuple[np.ndarray, np.ndarray]:
        """Radius and angle from ``start`` (in ``[0, 2 pi)``) of points about the centre."""
        dx, dy = np.asarray(x, float) - self.centre[0], np.asarray(y, float) - self.centre[1]
        return np.hypot(dx, dy), np.mod(np.arctan2(dy, dx) - self.start, 2 * math.pi)

    def contains(self, phi, z):
        r, angle = self.polar(phi, z)
        return (r > self.inner_radius) & (r < self.outer_radius) & (angle > 0.0) & (angle < self.extent)

    def corners(self) -> np.ndarray:
        a1, a2 = self.start, self.start + self.extent
        return np.column_stack([self._point(self.inner_radius, a1), self._point(self.outer_radius, a1),
                                self._point(self.outer_radius, a2), self._point(self.inner_radius, a2)])

    def _arc_pieces(self) -> int:
        return int(math.ceil(self.extent / (math.pi / 2)))  # each gmsh arc well below pi

    def add_to_gmsh(self, occ) -> list[int]:
        k = self._arc_pieces()
        angles = self.start + self.extent * np.arange(k + 1) / k
        centre = occ.addPoint(self.centre[0], self.centre[1], 0.0)
        outer = [occ.addPoint(*self._point(self.outer_radius, a), 0.0) for a in angles]
        inner = [occ.addPoint(*self._point(self.inner_radius, a), 0.0) for a in angles]
        curves = [occ.addLine(inner[0], outer[0])]
        curves += [occ.addCircleArc(outer[i], centre, outer[i + 1]) for i in range(k)]
        curves.append(occ.addLine(outer[k], inner[k]))
        curves += [occ.addCircleArc(inner[i + 1], centre, inner[i]) for i in reversed(range(k))]
        return curves

    def edge_groups(self) -> dict[str, list[int]]:
        """Positions of each named edge's curves in :meth:`add_to_gmsh`'s list."""
        k = self._arc_pieces()
        return {"arc_start": [0], "outer_rim": list(range(1, k + 1)), "arc_end": [k + 1],
                "inner_rim": list(range(k + 2, 2 * k + 2))}


@dataclass(frozen=True)
class Slot:
    """Slot (stadium, kidney-like) pocket: a rectangle with semicircular ends.

    Parameters
    ----------
    center : (float, float)
        Centre ``(phi, z)``.
    length : float
        Distance between the centres of the two end circles, > 0.
    width : float
        Full width (twice the end radius), > 0.
    angle : float
        Direction of the slot axis from the phi direction [rad].
    """

    center: tuple[float, float]
    length: float
    width: float
    angle: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "center", _pair(self.center, "Slot.center"))
        object.__setattr__(self, "length", positive("Slot.length", self.length))
        object.__setattr__(self, "width", positive("Slot.width", self.width))
        if not math.isfinite(float(self.angle)):
            raise ValueError(f"Slot.angle must be finite, got {self.angle!r}")
        object.__setattr__(self, "angle", float(self.angle))

    @property
    def area(self) -> float:
        r = self.width / 2
        return self.length * self.width + math.pi * r**2

    def _ends(self) -> tuple[np.ndarray, np.ndarray]:
        d = 0.5 * self.length * np.array([math.cos(self.angle), math.sin(self.angle)])
        c = np.array(self.center)
        return c - d, c + d

    def boundary(self, n: int = _SAMPLES) -> np.ndarray:
        r = self.width / 2
        p0, p1 = self._ends()
        m = n // 4
        t = np.linspace(-np.pi / 2, np.pi / 2, m) + self.angle
        cap1 = p1[:, None] + r * np.array([np.cos(t), np.sin(t)])
        cap0 = p0[:, None] + r * np.array([np.cos(t + np.pi), np.sin(t + np.pi)])
        s = np.linspace(0, 1, m, endpoint=False)[1:]
        top = cap1[:, -1:] + (cap0[:, :1] - cap1[:, -1:]) * s
        bottom = cap0[:, -1:] + (cap1[:, :1] - cap0[:, -1:]) * s
        return np.hstack([cap1, top, cap0, bottom])

    def contains(self, phi, z):
        p0, p1 = self._ends()
        phi, z = np.asarray(phi, float), np.asarray(z, float)
        d = p1 - p0
        t = np.clip(((phi - p0[0]) * d[0] + (z - p0[1]) * d[1]) / (d @ d), 0.0, 1.0)
        return (phi - p0[0] - t * d[0]) ** 2 + (z - p0[1] - t * d[1]) ** 2 < (self.width / 2) ** 2

    def corners(self) -> np.ndarray:
        return np.zeros((2, 0))

    def add_to_gmsh(self, occ) -> list[int]:
        r = self.width / 2
        p0, p1 = self._ends()
        n = np.array([-math.sin(self.angle), math.cos(self.angle)])
        a0, a1 = p0 - r * n, p1 - r * n  # bottom edge
        b1, b0 = p1 + r * n, p0 + r * n  # top edge
        axis = np.array([math.cos(self.angle), math.sin(self.angle)])
        tip1, tip0 = p1 + r * axis, p0 - r * axis
        pt = {k: occ.addPoint(*v, 0.0) for k, v in dict(a0=a0, a1=a1, t1=tip1, b1=b1, b0=b0, t0=tip0).items()}
        c0, c1 = occ.addPoint(*p0, 0.0), occ.addPoint(*p1, 0.0)
        # each end as two quarter arcs: a half circle from three points is ambiguous for gmsh
        return [
            occ.addLine(pt["a0"], pt["a1"]),
            occ.addCircleArc(pt["a1"], c1, pt["t1"]),
            occ.addCircleArc(pt["t1"], c1, pt["b1"]),
            occ.addLine(pt["b1"], pt["b0"]),
            occ.addCircleArc(pt["b0"], c0, pt["t0"]),
            occ.addCircleArc(pt["t0"], c0, pt["a0"]),
        ]


@dataclass(frozen=True)
class Recess:
    """A blind region where the film is deeper (dimple, step, relief groove).

    Unlike an inlet pocket it is not fed: the film runs through it with the
    extra ``depth``. ``mesh_surface`` meshes it conformally (its contour lies
    on element edges); ``grid_mesh`` cuts it through the cells, whose film is
    then integrated exactly. Either way the mass-conserving solver crosses the
    film step with the exact flux.

    Parameters
    ----------
    shape : Shape
        The region in ``(phi, z)``, strictly inside the outline.
    depth : float
        Extra film thickness inside [-] (units of the clearance c), in
        ``(0, 1e3]`` (:data:`bearingfe.core.checks.MAX_DEPTH`).
    """

    shape: Shape
    depth: float

    def __post_init__(self) -> None:
        if not isinstance(self.shape, Shape):
            raise ValueError(f"Recess.shape must be a shape (Circle, Ellipse, Polygon, Slot), got {self.shape!r}")
        object.__setattr__(self, "depth", check_depth(self.depth, "Recess.depth"))


@dataclass(frozen=True)
class Surface:
    """A shoe support surface with its inlet pockets.

    Parameters
    ----------
    arc : (float, float)
        Arc limits ``(alpha1, alpha2)`` [rad] of the default rectangular
        outline, ``alpha1 < alpha2 <= alpha1 + 2 pi``.
    half_width : float
        Half width ``a = b / (2 R0)`` [-] of the default outline, > 0.
    inlets : sequence of Shape
        High-pressure inlet pockets; each strictly inside the outline, none
        touching or overlapping another.
    outer : Shape or None
        Any closed outline replacing the rectangle ``arc x [-a, a]``.
    recesses : sequence of Recess
        Blind deeper regions of the film; each strictly inside the outline,
        none touching a pocket or another recess.
    periodic : bool
        A full 360-degree film with no edge at the arc ends: ``arc`` must span
        exactly ``2 pi`` (default outline only); the mesh matches its nodes
        across the seam ``phi = alpha1 ~ alpha2`` and the solver identifies
        them. Pockets (e.g. axial grooves of partial length) stay strictly
        inside the arc: choose ``alpha1`` away from them.
    runner : Runner
        How the facing surface slides over this one (:mod:`bearingfe.geometry.runner`): uniformly
        along ``phi`` (the default, every journal and slider) or rotating about an axis (a thrust
        collar over a pad in the plane).
    """

    arc: tuple[float, float] = (-0.5, 0.5)
    half_width: float = 0.5
    inlets: tuple = ()
    outer: Shape | None = None
    recesses: tuple = ()
    periodic: bool = False
    runner: Runner = ALONG_PHI
    _outline: Shape = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        a1, a2 = _pair(self.arc, "Surface.arc")
        if not a1 < a2 <= a1 + 2 * math.pi + 1e-12:
            raise ValueError(f"Surface.arc must satisfy alpha1 < alpha2 <= alpha1 + 2*pi, got {self.arc!r}")
        object.__setattr__(self, "arc", (a1, a2))
        object.__setattr__(self, "half_width", positive("Surface.half_width", self.half_width))
        inlets = (self.inlets,) if isinstance(self.inlets, Shape) else tuple(self.inlets)
        for i, shape in enumerate(inlets):
            if not isinstance(shape, Shape):
                raise ValueError(f"Surface.inlets[{i}] must be a shape (Circle, Ellipse, Polygon, Slot), got {shape!r}")
        object.__setattr__(self, "inlets", inlets)
        if self.outer is not None and not isinstance(self.outer, Shape):
            raise ValueError(f"Surface.outer must be a shape or None, got {self.outer!r}")
        outline = self.outer if self.outer is not None else Rectangle(
            ((a1 + a2) / 2, 0.0), (a2 - a1, 2 * self.half_width))
        object.__setattr__(self, "_outline", outline)
        _check_layout(outline, inlets)
        recesses = (self.recesses,) if isinstance(self.recesses, Recess) else tuple(self.recesses)
        for i, r in enumerate(recesses):
            if not isinstance(r, Recess):
                raise ValueError(f"Surface.recesses[{i}] must be a Recess(shape, depth), got {r!r}")
        object.__setattr__(self, "recesses", recesses)
        if not isinstance(self.runner, Runner):
            raise ValueError(f"Surface.runner must be a runner (Translating or Rotating), got {self.runner!r}")
        if not isinstance(self.periodic, bool):
            raise ValueError(f"Surface.periodic must be True or False, got {self.periodic!r}")
        if self.periodic and (self.outer is not None or abs(a2 - a1 - 2 * math.pi) > 1e-9):
            raise ValueError(f"Surface.periodic needs the default outline with an arc of exactly 2 pi "
                             f"(alpha2 = alpha1 + 2 pi), got arc={self.arc!r}, outer={self.outer!r}")
        if recesses:
            _check_layout(outline, inlets + tuple(r.shape for r in recesses), names=(
                [f"Surface.inlets[{i}]" for i in range(len(inlets))]
                + [f"Surface.recesses[{i}]" for i in range(len(recesses))]))

    def recess_depth(self, phi, z) -> np.ndarray:
        """Extra film depth of the recesses at the points [-] (0 outside them)."""
        out = np.zeros(np.broadcast(np.asarray(phi), np.asarray(z)).shape)
        for r in self.recesses:
            out = out + r.depth * r.shape.contains(phi, z)
        return out

    @property
    def outline(self) -> Shape:
        """The outer contour as a shape (the rectangle unless ``outer`` was given)."""
        return self._outline

    @property
    def is_rectangular(self) -> bool:
        """True for the default ``arc x [-a, a]`` outline (named edges exist)."""
        return self.outer is None

    @property
    def area(self) -> float:
        """Area inside the outer contour, pockets included [-]."""
        return self._outline.area

    @property
    def inlet_area(self) -> float:
        """Total pocket area [-]."""
        return float(sum(s.area for s in self.inlets))

    @property
    def inlet_fraction(self) -> float:
        """Pocket area as a fraction of the whole surface."""
        return self.inlet_area / self.area

    @property
    def film_area(self) -> float:
        """Area wetted by the thin film (outline minus pockets)."""
        return self.area - self.inlet_area

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """``(phi_min, phi_max, z_min, z_max)`` of the outline."""
        xy = self._outline.boundary()
        return float(xy[0].min()), float(xy[0].max()), float(xy[1].min()), float(xy[1].max())

    def in_pocket(self, phi, z) -> np.ndarray:
        """Boolean mask of points inside any inlet pocket."""
        mask = np.zeros(np.broadcast(np.asarray(phi), np.asarray(z)).shape, dtype=bool)
        for shape in self.inlets:
            mask |= shape.contains(phi, z)
        return mask

    def inlet_widths(self) -> tuple[float, ...]:
        """Size of each pocket as its hydraulic diameter ``4 area / perimeter`` [-]
        (the diameter of a circle, about twice the width of a thin slot)."""
        return tuple(_hydraulic_diameter(s) for s in self.inlets)

    def min_gap(self) -> float:
        """Smallest distance between a pocket and the outline or another pocket."""
        curves = [self._outline.boundary()] + [s.boundary() for s in self.inlets]
        gaps = [_polyline_distance(curves[i], curves[j])
                for i in range(len(curves)) for j in range(i + 1, len(curves))]
        return float(min(gaps)) if gaps else math.inf


# -- layout checks ---------------------------------------------------------

#: Smallest pocket size and pocket gap, relative to the outline's extent: below, gmsh cannot resolve them.
MIN_FEATURE = 1e-4


def _hydraulic_diameter(shape: Shape) -> float:
    xy = shape.boundary()
    perimeter = float(np.sum(np.linalg.norm(np.roll(xy, -1, axis=1) - xy, axis=0)))
    return 4.0 * abs(_signed_area(xy)) / perimeter


def _check_layout(outline: Shape, inlets: tuple, names=None) -> None:
    outer_xy = outline.boundary()
    scale = float(np.ptp(outer_xy, axis=1).max())
    tol = MIN_FEATURE * scale
    names = names or [f"Surface.inlets[{i}]" for i in range(len(inlets))]
    for i, shape in enumerate(inlets):
        width = _hydraulic_diameter(shape)
        if not width >= tol:
            raise ValueError(
                f"{names[i]} ({type(shape).__name__}) is {width:.3g} across (4 area / perimeter), "
                f"smaller than {MIN_FEATURE:g} x the outline ({scale:.3g}): too small to mesh or resolve; "
                f"allowed: pocket size >= {tol:.3g}")
        xy = shape.boundary()
        if _polylines_cross(xy, outer_xy) or not outline.contains(*xy).all():
            raise ValueError(f"{names[i]} ({type(shape).__name__}) is not inside the outer contour")
        gap = _polyline_distance(xy, outer_xy)
        if gap < tol:
            raise ValueError(
                f"{names[i]} ({type(shape).__name__}) touches the outer contour "
                f"(gap {gap:.3g} < {tol:.3g}); keep pockets and recesses strictly inside")
        for j in range(i):
            other = inlets[j].boundary()
            if _box_gap(xy, other) >= tol:  # boxes apart by tol: no crossing, containment or contact
                continue
            if (_polylines_cross(xy, other) or inlets[j].contains(*xy).any()
                    or shape.contains(*other).any() or _polyline_distance(xy, other) < tol):
                raise ValueError(f"{names[i]} and {names[j]} overlap or touch")


def _box_gap(p: np.ndarray, q: np.ndarray) -> float:
    """Distance between the bounding boxes of two polylines along the axis that separates them most
    (<= 0 if the boxes overlap); a lower bound of the polylines' distance."""
    return float(np.max(np.maximum(p.min(axis=1) - q.max(axis=1), q.min(axis=1) - p.max(axis=1))))


def _signed_area(xy: np.ndarray) -> float:
    x, y = xy
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _segments(xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return xy, np.roll(xy, -1, axis=1)


def _cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _crossing_matrix(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Proper crossings between the edges of closed polylines p and q."""
    p0, p1 = _segments(p)
    q0, q1 = _segments(q)
    P0, P1 = p0[:, :, None], p1[:, :, None]
    Q0, Q1 = q0[:, None, :], q1[:, None, :]
    d1, d2 = _cross(P0, P1, Q0), _cross(P0, P1, Q1)
    d3, d4 = _cross(Q0, Q1, P0), _cross(Q0, Q1, P1)
    return (d1 * d2 < 0) & (d3 * d4 < 0)


def _polylines_cross(p: np.ndarray, q: np.ndarray) -> bool:
    """Whether an edge of closed polyline ``p`` properly crosses one of ``q``: :func:`_crossing_matrix`
    on the pairs of edges whose bounding circles meet (the only ones that can cross; the same test on
    each pair, so the same answer without the full matrix of fine outlines)."""
    if p.shape[1] * q.shape[1] <= _DENSE_PAIRS:
        return bool(_crossing_matrix(p, q).any())
    (pm, ph), (qm, qh) = _edge_circles(p), _edge_circles(q)
    i, j = _close_pairs(qm, pm, (ph + qh.max()) * (1.0 + 1e-9))
    if i.size == 0:
        return False
    p0, p1 = _segments(p)
    q0, q1 = _segments(q)
    P0, P1, Q0, Q1 = p0[:, i], p1[:, i], q0[:, j], q1[:, j]
    d1, d2 = _cross(P0, P1, Q0), _cross(P0, P1, Q1)
    d3, d4 = _cross(Q0, Q1, P0), _cross(Q0, Q1, P1)
    return bool(np.any((d1 * d2 < 0) & (d3 * d4 < 0)))


#: Point-edge or edge-edge pairs up to which the layout checks take every pair (a dense array), beyond
#: which they first keep the pairs that can matter (a k-d tree): the same numbers, much less work.
_DENSE_PAIRS = 4096


def _edge_circles(xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Midpoints ``(2, n)`` and half lengths ``(n,)`` of the edges of a closed polyline."""
    a, b = _segments(xy)
    return 0.5 * (a + b), 0.5 * np.hypot(b[0] - a[0], b[1] - a[1])


def _close_pairs(points: np.ndarray, centres: np.ndarray, radii) -> tuple[np.ndarray, np.ndarray]:
    """Indices ``(i, j)`` of every centre ``i`` and point ``j`` at most ``radii[i]`` apart (``radii``
    a number or one per centre)."""
    from scipy.spatial import cKDTree

    lists = cKDTree(points.T).query_ball_point(centres.T, np.broadcast_to(radii, centres.shape[1:]))
    counts = np.fromiter((len(v) for v in lists), dtype=np.intp, count=len(lists))
    i = np.repeat(np.arange(len(lists)), counts)
    j = np.fromiter((k for v in lists for k in v), dtype=np.intp, count=int(counts.sum()))
    return i, j


def _self_intersects(xy: np.ndarray) -> bool:
    n = xy.shape[1]
    m = _crossing_matrix(xy, xy)
    idx = np.arange(n)
    for k in (-1, 0, 1):  # neighbouring edges share a vertex
        m[idx, (idx + k) % n] = False
    return bool(m.any())


def _points_to_segments(points: np.ndarray, xy: np.ndarray) -> np.ndarray:
    a, b = _segments(xy)
    d = b - a
    pa = points[:, :, None] - a[:, None, :]
    t = np.clip((pa[0] * d[0] + pa[1] * d[1]) / np.maximum((d * d).sum(0), 1e-300), 0.0, 1.0)
    dist = np.hypot(pa[0] - t * d[0], pa[1] - t * d[1])
    return dist.min(axis=1)


def _nearest_to_segments(points: np.ndarray, xy: np.ndarray) -> float:
    """``_points_to_segments(points, xy).min()``, evaluated on the point-edge pairs that can hold it.

    Any point is at most ``bound`` (the distance from the edges' start vertices to the nearest point) from
    some edge, and a point within ``bound`` of an edge is within ``bound + half length`` of its midpoint:
    only those pairs are evaluated, with the same arithmetic as :func:`_points_to_segments`, so the
    smallest distance is the same number."""
    if points.shape[1] * xy.shape[1] <= _DENSE_PAIRS:
        return float(_points_to_segments(points, xy).min())
    from scipy.spatial import cKDTree

    a, b = _segments(xy)
    bound = float(cKDTree(points.T).query(a.T)[0].min())
    mid, half = _edge_circles(xy)
    seg, pts = _close_pairs(points, mid, (bound + half) * (1.0 + 1e-9) + 1e-300)
    d = (b - a)[:, seg]
    pa = points[:, pts] - a[:, seg]
    t = np.clip((pa[0] * d[0] + pa[1] * d[1]) / np.maximum((d * d).sum(0), 1e-300), 0.0, 1.0)
    return float(np.hypot(pa[0] - t * d[0], pa[1] - t * d[1]).min())


def _polyline_distance(p: np.ndarray, q: np.ndarray) -> float:
    return float(min(_nearest_to_segments(p, q), _nearest_to_segments(q, p)))


def _points_in_polygon(xy: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Even-odd rule, vectorized over points."""
    x, y = np.broadcast_arrays(x, y)
    inside = np.zeros(x.shape, dtype=bool)
    xs, ys = xy
    for i in range(xs.size):
        x0, y0, x1, y1 = xs[i - 1], ys[i - 1], xs[i], ys[i]
        crosses = (y0 > y) != (y1 > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            xint = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
        inside ^= crosses & (x < xint)
    return inside
