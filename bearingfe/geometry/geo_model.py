"""Building a gmsh model through the gmsh API from the operations of :func:`bearingfe.geometry.geo_parser.parse_geo`.

Runs in the gmsh child process (:mod:`bearingfe.geometry.gmsh_worker` loads this file by its path), so it
imports only the standard library; ``gmsh`` is passed in. Every operation is a list whose first element is
its kind; numbers are in the file's units, angles in radians:

==================  ==============================================  =========================================
kind                fields                                          gmsh call
==================  ==============================================  =========================================
``point``           tag, x, y, z, size (0: none)                    ``addPoint``
``line``            tag, start, end                                 ``addLine``
``circle_arc``      tag, start, centre, end                         ``addCircleArc``
``circle``          tag, x, y, z, r, angle1, angle2                 ``occ.addCircle``
``ellipse_arc``     tag, start, centre, major-axis point, end       ``addEllipseArc``
``ellipse``         tag, x, y, z, r1, r2, angle1, angle2            ``occ.addEllipse``
``spline``          tag, [points]                                   ``addSpline``
``bspline``         tag, [points]                                   ``addBSpline``
``curve_loop``      tag, [curves, signed]                           ``addCurveLoop``
``plane_surface``   tag, [curve loops]                              ``addPlaneSurface``
``rotate``          [[dim, tag]...], ax, ay, az, x, y, z, angle     ``rotate``
``translate``       [[dim, tag]...], dx, dy, dz                     ``translate``
``dilate``          [[dim, tag]...], x, y, z, a, b, c               ``dilate``
``symmetry``        [[dim, tag]...], a, b, c, d                     ``mirror`` (plane a x + b y + c z + d = 0)
``physical``        dim, tag (-1: next free), name, [tags]          ``model.addPhysicalGroup``
``size``            [points], size                                  ``model.mesh.setSize``
``option``          name, value                                     ``option.setNumber``
``field``           tag, kind                                       ``model.mesh.field.add``
``field_number``    tag, option, value                              ``model.mesh.field.setNumber``
``field_numbers``   tag, option, [values]                           ``model.mesh.field.setNumbers``
``field_string``    tag, option, text                               ``model.mesh.field.setString``
``background``      tag                                             ``model.mesh.field.setAsBackgroundMesh``
==================  ==============================================  =========================================

Geometry calls go to the kernel the file chose (``gmsh.model.occ`` or ``gmsh.model.geo``); the kernel is
synchronized before the first model-level call that follows geometry and at the end.
"""

from __future__ import annotations

from typing import Any

__all__ = ["build"]


def _geometry(kernel: Any, op: list) -> None:
    kind, args = op[0], op[1:]
    if kind == "point":
        tag, x, y, z, size = args
        kernel.addPoint(x, y, z, size, tag)
    elif kind == "line":
        kernel.addLine(args[1], args[2], args[0])
    elif kind == "circle_arc":
        kernel.addCircleArc(args[1], args[2], args[3], args[0])
    elif kind == "circle":
        tag, x, y, z, r, a1, a2 = args
        kernel.addCircle(x, y, z, r, tag, a1, a2)
    elif kind == "ellipse_arc":
        kernel.addEllipseArc(args[1], args[2], args[3], args[4], args[0])
    elif kind == "ellipse":
        tag, x, y, z, r1, r2, a1, a2 = args
        kernel.addEllipse(x, y, z, r1, r2, tag, a1, a2)
    elif kind == "spline":
        kernel.addSpline(args[1], args[0])
    elif kind == "bspline":
        kernel.addBSpline(args[1], args[0])
    elif kind == "curve_loop":
        kernel.addCurveLoop(args[1], args[0])
    elif kind == "plane_surface":
        kernel.addPlaneSurface(args[1], args[0])
    elif kind == "rotate":
        entities, ax, ay, az, x, y, z, angle = args
        kernel.rotate([tuple(e) for e in entities], x, y, z, ax, ay, az, angle)
    elif kind == "translate":
        kernel.translate([tuple(e) for e in args[0]], *args[1:])
    elif kind == "dilate":
        kernel.dilate([tuple(e) for e in args[0]], *args[1:])
    elif kind == "symmetry":
        kernel.mirror([tuple(e) for e in args[0]], *args[1:])
    else:
        raise ValueError(f"unknown geometry operation {kind!r}")


_MODEL = frozenset({"physical", "size"})
_GEOMETRY = frozenset({"point", "line", "circle_arc", "circle", "ellipse_arc", "ellipse", "spline", "bspline",
                       "curve_loop", "plane_surface", "rotate", "translate", "dilate", "symmetry"})


def build(gmsh: Any, factory: str, ops: list) -> None:
    """Build the model of ``ops`` in gmsh's current model.

    Parameters
    ----------
    gmsh : module
        The initialized ``gmsh`` module.
    factory : {"occ", "geo"}
        The geometry kernel (OpenCASCADE or gmsh's built-in one).
    ops : list of list
        The operations (module table).
    """
    kernel = gmsh.model.occ if factory == "occ" else gmsh.model.geo
    field = gmsh.model.mesh.field
    dirty = False
    for op in ops:
        kind = op[0]
        if kind in _GEOMETRY:
            _geometry(kernel, op)
            dirty = True
            continue
        if kind in _MODEL and dirty:
            kernel.synchronize()
            dirty = False
        if kind == "physical":
            dim, tag, name, tags = op[1:]
            gmsh.model.addPhysicalGroup(dim, tags, tag, name)
        elif kind == "size":
            gmsh.model.mesh.setSize([(0, t) for t in op[1]], op[2])
        elif kind == "option":
            gmsh.option.setNumber(op[1], op[2])
        elif kind == "field":
            field.add(op[2], op[1])
        elif kind == "field_number":
            field.setNumber(op[1], op[2], op[3])
        elif kind == "field_numbers":
            field.setNumbers(op[1], op[2], op[3])
        elif kind == "field_string":
            field.setString(op[1], op[2], op[3])
        elif kind == "background":
            field.setAsBackgroundMesh(op[1])
        else:
            raise ValueError(f"unknown operation {kind!r}")
    kernel.synchronize()
