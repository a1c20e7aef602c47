"""Child process in which gmsh meshes: one ``.geo`` file (:func:`bearingfe.geometry.geofiles.run_geo`) or the shoe
body from its dimensions (``task = "shoe"``, :func:`bearingfe.elastic.shoe.mesh_shoe`).

An untrusted ``.geo`` file arrives already read by :mod:`bearingfe.geometry.geo_parser` as operations
(``model``), built through the gmsh API by :mod:`bearingfe.geometry.geo_model`; only a trusted one (``geo``,
a path) is opened by gmsh's script interpreter.

Run as a file (``runpy.run_path``) with the request file as its argument; it
imports only gmsh and the standard library, so a script that loops, crashes
gmsh or calls ``Exit`` affects this process only. It confines itself before
gmsh starts: CPU time (the parent's limit plus 5 s), address space
(:data:`bearingfe.geometry.geofiles.GEO_MEMORY`) and, on Linux, death with its parent. It writes the mesh (msh
4.1, physical groups only) and a small JSON result; the parent reads both.
The element count is estimated twice before the surface is meshed: from the
size options and the points' sizes, then from the meshed boundary curves.

The shoe task builds the body with the OpenCASCADE kernel from numbers only
(no script): the annular or flat-backed section between the bore ``r = 1``
over the arc ``psi in [a1, a2]`` (``x = r sin psi``, ``y = r cos psi``) and
the back, extruded over ``|z| <= half_width``; an optional lining (the layer
``r <= 1 + lining``) as its own volume; the seat split off the back by the
cylinder ``x^2 + z^2 <= seat^2`` about the plunger axis ``y``. The tetrahedra
are graded from ``film_size`` on the bore and on the seat's rim to ``size``. Physical groups:
volumes ``backing`` and ``lining``, surfaces ``film`` (the bore) and ``seat``.
It writes the nodes and elements as JSON (``out``).
"""

from __future__ import annotations

import json
import math
import os
import sys

_EQUILATERAL = math.sqrt(3.0) / 4.0


def _area(gmsh) -> float:
    """Area of the 2D entities (OCC mass if available, else their bounding boxes)."""
    total = 0.0
    for dim, tag in gmsh.model.getEntities(2):
        try:
            total += gmsh.model.occ.getMass(dim, tag)
            continue
        except Exception:  # noqa: BLE001 - built-in kernel: bounding box
            pass
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(dim, tag)
        total += max(x1 - x0, 0.0) * max(y1 - y0, 0.0)
    return total


def _size_bound(gmsh) -> float:
    """Largest element size gmsh may use here (before any meshing)."""
    opt = gmsh.option.getNumber
    largest = opt("Mesh.MeshSizeMax")
    if opt("Mesh.MeshSizeFromPoints"):
        try:
            sizes = [s for s in gmsh.model.mesh.getSizes(gmsh.model.getEntities(0)) if s > 0]
        except Exception:  # noqa: BLE001
            sizes = []
        if sizes:
            largest = min(largest, max(sizes))
    return max(largest, opt("Mesh.MeshSizeMin")) * opt("Mesh.MeshSizeFactor")


def _boundary_size(gmsh) -> float:
    """Mean edge length of the meshed curves (after ``generate(1)``)."""
    total, count = 0.0, 0
    for dim, tag in gmsh.model.getEntities(1):
        _, coords, _ = gmsh.model.mesh.getNodes(dim, tag, includeBoundary=True)
        n = len(coords) // 3
        if n < 2:
            continue
        length = gmsh.model.occ.getMass(dim, tag) if _is_occ(gmsh, dim, tag) else _polyline(coords)
        total += length
        count += n - 1
    return total / count if count else math.inf


def _is_occ(gmsh, dim, tag) -> bool:
    try:
        gmsh.model.occ.getMass(dim, tag)
        return True
    except Exception:  # noqa: BLE001
        return False


def _polyline(coords) -> float:
    pts = [coords[k:k + 3] for k in range(0, len(coords), 3)]
    return sum(math.dist(a, b) for a, b in zip(pts, pts[1:]))


def _geo_model() -> dict:
    """The namespace of ``geo_model.py`` beside this file (loaded by path: the child imports no package)."""
    import runpy

    return runpy.run_path(os.path.join(os.path.dirname(os.path.abspath(__file__)), "geo_model.py"))


def _run(request: dict, result: dict) -> None:
    import gmsh

    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.logger.start()
    try:
        if "model" in request:  # an untrusted file, read by bearingfe: built through the API, never interpreted
            gmsh.model.add("geo")
            _geo_model()["build"](gmsh, request["factory"], request["model"])
        else:  # a trusted script: gmsh's own interpreter
            gmsh.open(request["geo"])
        if request.get("size") is not None:
            gmsh.option.setNumber("Mesh.MeshSizeMax", float(request["size"]))
        if not gmsh.model.getPhysicalGroups(1):
            result["error"] = "no physical curve groups (need at least 'outer')"
            return
        area, limit = _area(gmsh), request["max_elements"]
        estimate = area / (_EQUILATERAL * _size_bound(gmsh) ** 2)
        if estimate <= limit:
            gmsh.model.mesh.generate(1)
            estimate = max(estimate, area / (_EQUILATERAL * min(_boundary_size(gmsh), _size_bound(gmsh)) ** 2))
        result["estimate"] = estimate
        if not estimate <= limit:
            result.update(kind="too_many", error=f"about {estimate:.3g} triangles")
            return
        gmsh.model.mesh.generate(2)
        if int(request.get("order", 1)) == 2:
            gmsh.model.mesh.setOrder(2)
        result["elements"] = int(sum(len(t) for t in gmsh.model.mesh.getElements(2)[1]))
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        gmsh.option.setNumber("Mesh.SaveAll", 0)  # elements of physical groups only, names kept
        gmsh.write(request["out"])
    except Exception as exc:  # noqa: BLE001 - reported to the parent
        errors = [m for m in gmsh.logger.get() if m.startswith("Error")]
        result["error"] = " ".join((errors[-1] if errors else str(exc)).split())[:300]
    finally:
        gmsh.finalize()


def _point_on(gmsh, dim: int, tag: int) -> tuple:
    """A point inside the entity (the image of the middle of its parameter box)."""
    lo, hi = gmsh.model.getParametrizationBounds(dim, tag)
    mid = [(a + b) / 2 for a, b in zip(lo, hi)]
    return tuple(gmsh.model.getValue(dim, tag, mid))


def _shoe_geometry(gmsh, g: dict) -> None:
    """The shoe volumes (OCC) from the numbers of ``g``; synchronized, fragments conformal."""
    occ = gmsh.model.occ
    a1, a2, hw, t = float(g["a1"]), float(g["a2"]), float(g["half_width"]), float(g["thickness"])
    plane = g.get("face") == "plane"
    if plane:  # a flat block under a flat film (x = psi): the body the tensor-mesh model solves
        body = [(3, occ.addBox(a1, 1, -hw, a2 - a1, t, 2 * hw))]
    else:
        centre = occ.addPoint(0, 0, -hw)
        p = lambda x, y: occ.addPoint(x, y, -hw)  # noqa: E731
        A1, A2 = p(math.sin(a1), math.cos(a1)), p(math.sin(a2), math.cos(a2))
        bore = occ.addCircleArc(A2, centre, A1)
        if g["back"] == "flat":
            B1, B2 = p(math.sin(a1), 1 + t), p(math.sin(a2), 1 + t)
            back = occ.addLine(B1, B2)
        else:
            B1 = p((1 + t) * math.sin(a1), (1 + t) * math.cos(a1))
            B2 = p((1 + t) * math.sin(a2), (1 + t) * math.cos(a2))
            back = occ.addCircleArc(B1, centre, B2)
        loop = occ.addCurveLoop([bore, occ.addLine(A1, B1), back, occ.addLine(B2, A2)])
        section = occ.addPlaneSurface([loop])
        body = [e for e in occ.extrude([(2, section)], 0, 0, 2 * hw) if e[0] == 3]
    lining = float(g.get("lining", 0.0))
    volumes = {"backing": body, "lining": []}
    if lining > 0:
        tube = occ.addCylinder(0, 0, -hw - 1, 0, 0, 2 * hw + 2, 1 + lining)
        inner = occ.intersect(body, [(3, tube)], removeObject=False, removeTool=True)[0]
        outer = occ.cut(body, inner, removeObject=True, removeTool=False)[0]
        volumes = {"backing": outer, "lining": inner}
    seat = float(g["seat"])  # 0: the whole back
    objects = volumes["backing"] + volumes["lining"]
    kept = volumes
    if seat > 0:
        tool = occ.addCylinder(0, -1, 0, 0, 4 + 2 * t, 0, seat)
        _, children = occ.fragment(objects, [(3, tool)])
        kept = {name: [c for k, o in enumerate(objects) if o in ents for c in children[k]]
                for name, ents in volumes.items()}
        mine = {c for cs in kept.values() for c in cs}
        stray = [c for c in children[len(objects)] if c not in mine]
        if stray:
            occ.remove(stray, recursive=True)
    elif volumes["lining"]:  # make the interface conformal
        nb = len(volumes["backing"])
        _, children = occ.fragment(volumes["backing"], volumes["lining"])
        kept = {"backing": [c for cs in children[:nb] for c in cs], "lining": [c for cs in children[nb:] for c in cs]}
    occ.synchronize()
    for name, ents in kept.items():
        if ents:
            gmsh.model.addPhysicalGroup(3, [e[1] for e in ents], name=name)
    faces = gmsh.model.getBoundary([e for ents in kept.values() for e in ents], combined=True, oriented=False)
    film, seats = [], []
    for _, tag in faces:
        tag = abs(tag)
        x, y, _ = _point_on(gmsh, 2, tag)  # on the face's underlying surface (plane or cylinder)
        x0, _, z0, x1, _, z1 = gmsh.model.getBoundingBox(2, tag)
        r = math.hypot(x, y)
        on_film = abs(y - 1) < 1e-7 if plane else abs(r - 1) < 1e-7
        on_back = abs(y - 1 - t) < 1e-7 if (plane or g["back"] == "flat") else abs(r - 1 - t) < 1e-7
        if z1 - z0 > 1e-9 and on_film:
            film.append(tag)
        elif on_back and (seat == 0 or max(abs(x0), abs(x1), abs(z0), abs(z1)) <= 1.05 * seat):  # loose OCC boxes
            seats.append(tag)
    if not film or not seats:
        raise ValueError(f"the shoe's film face ({len(film)}) or seat ({len(seats)}) was not found")
    gmsh.model.addPhysicalGroup(2, film, name="film")
    gmsh.model.addPhysicalGroup(2, seats, name="seat")
    fields = []
    # graded from film_size on the film face, and on the seat's rim (where the hold's stresses concentrate)
    rims = [abs(c) for _, c in gmsh.model.getBoundary([(2, k) for k in seats], combined=True, oriented=False)]
    for dim, tags in ((2, film), (1, rims if seat > 0 else [])):
        if not tags:
            continue
        distance = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(distance, "SurfacesList" if dim == 2 else "CurvesList", tags)
        threshold = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(threshold, "InField", distance)
        gmsh.model.mesh.field.setNumber(threshold, "SizeMin", float(g["film_size"]))
        gmsh.model.mesh.field.setNumber(threshold, "SizeMax", float(g["size"]))
        gmsh.model.mesh.field.setNumber(threshold, "DistMin", 0.0)
        gmsh.model.mesh.field.setNumber(threshold, "DistMax", float(g["grading"]))
        fields.append(threshold)
    smallest = gmsh.model.mesh.field.add("Min")
    gmsh.model.mesh.field.setNumbers(smallest, "FieldsList", fields)
    gmsh.model.mesh.field.setAsBackgroundMesh(smallest)
    for name in ("Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature", "Mesh.MeshSizeExtendFromBoundary"):
        gmsh.option.setNumber(name, 0)
    gmsh.option.setNumber("Mesh.MeshSizeMax", float(g["size"]))


def _group_elements(gmsh, dim: int, name: str, etype: int) -> list:
    """Node tags of the elements (of gmsh type ``etype``) of the physical group ``name``, flat."""
    out = []
    for d, tag in gmsh.model.getPhysicalGroups(dim):
        if gmsh.model.getPhysicalName(d, tag) != name:
            continue
        for entity in gmsh.model.getEntitiesForPhysicalGroup(d, tag):
            types, _, nodes = gmsh.model.mesh.getElements(d, entity)
            for ty, nd in zip(types, nodes):
                if ty == etype:
                    out.extend(int(n) for n in nd)
    return out


def _shoe(request: dict, result: dict) -> None:
    import gmsh

    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.logger.start()
    try:
        gmsh.model.add("shoe")
        _shoe_geometry(gmsh, request["geometry"])
        gmsh.model.mesh.generate(3)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        mesh = {"tags": [int(k) for k in tags], "coords": [float(c) for c in coords],
                "backing": _group_elements(gmsh, 3, "backing", 4), "lining": _group_elements(gmsh, 3, "lining", 4),
                "film": _group_elements(gmsh, 2, "film", 2), "seat": _group_elements(gmsh, 2, "seat", 2)}
        result["elements"] = (len(mesh["backing"]) + len(mesh["lining"])) // 4
        with open(request["out"], "w") as f:
            json.dump(mesh, f)
    except Exception as exc:  # noqa: BLE001 - reported to the parent
        errors = [m for m in gmsh.logger.get() if m.startswith("Error")]
        result["error"] = " ".join((errors[-1] if errors else str(exc)).split())[:300]
    finally:
        gmsh.finalize()


def _confine(request: dict) -> None:
    """Limits that hold even if the parent dies: CPU seconds, address space, death with the parent (Linux)."""
    try:
        import resource

        cpu = int(math.ceil(request["seconds"])) + 5
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 5))
        memory = int(request["memory"])
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    except (ImportError, ValueError, OSError):  # not on this platform: the parent's time limit remains
        pass
    if sys.platform.startswith("linux"):
        try:
            import ctypes
            import signal

            ctypes.CDLL(None).prctl(1, int(signal.SIGKILL))  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass
    if os.getppid() != request["parent"]:  # the parent ended before the line above
        sys.exit(3)


def main(argv: list[str]) -> int:
    with open(argv[0]) as f:
        request = json.load(f)
    _confine(request)
    result: dict = {}
    (_shoe if request.get("task") == "shoe" else _run)(request, result)
    with open(request["result"], "w") as f:
        json.dump(result, f)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
