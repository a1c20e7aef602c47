"""Changes of a design study: how one case differs from the base parameter object.

A change is named either by a dotted field path (``"surface.half_width"``,
``"scale.speed"``: applied with :func:`dataclasses.replace` down the path) or
by a *change builder* from :data:`CHANGES` (``"pocket_fraction"``,
``"pocket_position"``, ``"pocket_shape"``): a function
``(base, value) -> new base`` for parameters that are not one field.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from typing import Any, Callable, Iterable, Mapping

import numpy as np

from ..geometry.surface import Circle, Ellipse, Polygon, Rectangle, Slot, Surface
from ..core.limits import check_limit

__all__ = [
    "CHANGES", "POCKET_SHAPES", "apply_changes", "centroid", "check_change_name", "expand_cases", "get_field", "pocket_fraction",
    "pocket_position", "pocket_shape", "set_field",
]


def get_field(obj, path: str):
    """Value at a dotted field path (``""`` is the object itself)."""
    for part in filter(None, path.split(".")):
        if not hasattr(obj, part):
            raise ValueError(f"{type(obj).__name__} has no field {part!r} (in path {path!r})")
        obj = getattr(obj, part)
    return obj


def set_field(obj, path: str, value):
    """A copy of ``obj`` with the field at a dotted path replaced (``dataclasses.replace``)."""
    if not path:
        return value
    head, _, rest = path.partition(".")
    if not dataclasses.is_dataclass(obj) or head not in {f.name for f in dataclasses.fields(obj) if f.init}:
        raise ValueError(f"{type(obj).__name__} has no settable field {head!r} (in path {path!r})")
    return dataclasses.replace(obj, **{head: set_field(getattr(obj, head), rest, value)})


def _surface_path(base) -> str:
    if isinstance(base, Surface):
        return ""
    if isinstance(getattr(base, "surface", None), Surface):
        return "surface"
    if isinstance(getattr(getattr(base, "pump", None), "surface", None), Surface):
        return "pump.surface"
    raise ValueError(f"{type(base).__name__} carries no support surface (field 'surface' or 'pump.surface')")


def centroid(shape) -> tuple[float, float]:
    if isinstance(shape, Polygon):
        x, y = np.array(shape.points).T
        cross = x * np.roll(y, -1) - np.roll(x, -1) * y
        area = cross.sum() / 2
        return (float(((x + np.roll(x, -1)) * cross).sum() / (6 * area)),
                float(((y + np.roll(y, -1)) * cross).sum() / (6 * area)))
    return shape.center


def _transformed(shape, scale: float, shift: float):
    """The shape scaled by ``scale`` about its centroid and moved ``shift`` along phi."""
    cx, cy = centroid(shape)
    centre = (cx + shift, cy)
    if isinstance(shape, Circle):
        return Circle(centre, shape.radius * scale)
    if isinstance(shape, Ellipse):
        return Ellipse(centre, (shape.semi_axes[0] * scale, shape.semi_axes[1] * scale), shape.angle)
    if isinstance(shape, Slot):
        return Slot(centre, shape.length * scale, shape.width * scale, shape.angle)
    if isinstance(shape, Polygon):
        return Polygon(tuple((cx + shift + scale * (x - cx), cy + scale * (y - cy)) for x, y in shape.points))
    raise ValueError(f"cannot scale or move a pocket of type {type(shape).__name__}")


def _pocket_centre(surface: Surface) -> float:
    areas = np.array([s.area for s in surface.inlets])
    return float(np.array([centroid(s)[0] for s in surface.inlets]) @ areas / areas.sum())


def pocket_fraction(base, value):
    """Scale every pocket about its centroid so the pockets cover ``value`` of the surface.

    ``value`` in ``[0, 1)``; 0 removes the pockets. A base without pockets
    gets one circle at the middle of the surface.
    """
    value = float(value)
    if not (math.isfinite(value) and 0.0 <= value < 1.0):
        raise ValueError(f"pocket_fraction must be in [0, 1), got {value!r}")
    path = _surface_path(base)
    surface = get_field(base, path)
    if value == 0.0:
        return set_field(base, path, dataclasses.replace(surface, inlets=()))
    inlets = surface.inlets
    if not inlets:
        p1, p2, z1, z2 = surface.bounds
        inlets = (Circle(((p1 + p2) / 2, (z1 + z2) / 2), 0.1 * min(p2 - p1, z2 - z1)),)
    scale = math.sqrt(value * surface.area / sum(s.area for s in inlets))
    new = dataclasses.replace(surface, inlets=tuple(_transformed(s, scale, 0.0) for s in inlets))
    return set_field(base, path, new)


def pocket_position(base, value):
    """Move the pockets along the arc: their area centroid to ``alpha1 + value (alpha2 - alpha1)``.

    ``value`` in ``[0, 1]`` (0.5: middle of the arc); no-op without pockets.
    Pockets that would touch the outline raise ``ValueError`` (recorded as a
    failed case by :func:`sweep`).
    """
    value = float(value)
    if not (math.isfinite(value) and 0.0 <= value <= 1.0):
        raise ValueError(f"pocket_position must be in [0, 1], got {value!r}")
    path = _surface_path(base)
    surface = get_field(base, path)
    if not surface.inlets:
        return base
    p1, p2, _, _ = surface.bounds
    shift = p1 + value * (p2 - p1) - _pocket_centre(surface)
    new = dataclasses.replace(surface, inlets=tuple(_transformed(s, 1.0, shift) for s in surface.inlets))
    return set_field(base, path, new)


#: Pocket shapes of equal area ``A`` by name: ``(centre, A) -> shape``.
POCKET_SHAPES: dict[str, Callable[[tuple[float, float], float], Any]] = {
    "circle": lambda c, a: Circle(c, math.sqrt(a / math.pi)),
    "square": lambda c, a: Rectangle(c, (math.sqrt(a), math.sqrt(a))),
    "ellipse": lambda c, a: Ellipse(c, (math.sqrt(2 * a / math.pi), math.sqrt(a / (2 * math.pi)))),
    # length = 2 width: area = width^2 (2 + pi/4)
    "slot": lambda c, a: Slot(c, 2 * math.sqrt(a / (2 + math.pi / 4)), math.sqrt(a / (2 + math.pi / 4))),
}


def pocket_shape(base, value):
    """Replace every pocket by a shape of the same area and centroid (:data:`POCKET_SHAPES`)."""
    if value not in POCKET_SHAPES:
        raise ValueError(f"pocket_shape must be one of {sorted(POCKET_SHAPES)}, got {value!r}")
    path = _surface_path(base)
    surface = get_field(base, path)
    inlets = tuple(POCKET_SHAPES[value](centroid(s), s.area) for s in surface.inlets)
    return set_field(base, path, dataclasses.replace(surface, inlets=inlets))


#: Change builders by name: ``(base, value) -> new base``. Any other change
#: name is a dotted field path.
CHANGES: dict[str, Callable[[Any, Any], Any]] = {
    "pocket_fraction": pocket_fraction,
    "pocket_position": pocket_position,
    "pocket_shape": pocket_shape,
}


def check_change_name(base, name: str) -> None:
    """Raise ``ValueError`` unless ``name`` is a change builder or a settable field path of ``base``."""
    if name in CHANGES:
        return
    obj = base
    for part in name.split("."):
        if not dataclasses.is_dataclass(obj) or part not in {f.name for f in dataclasses.fields(obj) if f.init}:
            raise ValueError(f"change {name!r} is neither a change builder ({', '.join(CHANGES)}) "
                             f"nor a field path of {type(base).__name__} (no field {part!r})")
        obj = getattr(obj, part)


def apply_changes(base, changes: Mapping[str, Any]):
    """Apply named changes in order: builders from :data:`CHANGES`, else dotted field paths."""
    for name, value in changes.items():
        base = CHANGES[name](base, value) if name in CHANGES else set_field(base, name, value)
    return base


def expand_cases(changes, max_cases: int | None = None) -> list[dict[str, Any]]:
    """Cases from a grid ``{name: [values]}`` (Cartesian product, first name outermost)
    or from a list of ``{name: value}`` mappings.

    The number of cases is checked against ``max_cases`` (default: the
    ``cases`` limit of :mod:`bearingfe.core.limits`, 10000) before the grid is
    expanded; :class:`bearingfe.core.limits.LimitError` beyond it.
    """
    if isinstance(changes, Mapping):
        for name, values in changes.items():
            if isinstance(values, (str, bytes)) or not isinstance(values, Iterable):
                raise ValueError(f"grid values of {name!r} must be a list, got {values!r}")
        axes = {name: list(values) for name, values in changes.items()}
        for name, values in axes.items():
            if not values:
                raise ValueError(f"grid values of {name!r} must not be empty")
        check_limit("cases", math.prod(len(v) for v in axes.values()), max_cases, "max_cases")
        return [dict(zip(axes, combo)) for combo in itertools.product(*axes.values())]
    if hasattr(changes, "__len__"):
        check_limit("cases", len(changes), max_cases, "max_cases")
    cases = list(changes)
    for i, case in enumerate(cases):
        if not isinstance(case, Mapping):
            raise ValueError(f"changes[{i}] must be a mapping name -> value, got {case!r}")
    return [dict(case) for case in cases]
