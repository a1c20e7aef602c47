"""Child process that lets gmsh parse and mesh one ``.geo`` script (run by :func:`bearingfe.geofiles.run_geo`).

Run as a file (``runpy.run_path``) with the request file as its argument; it
imports only gmsh and the standard library, so a script that loops, crashes
gmsh or calls ``Exit`` affects this process only. It confines itself before
gmsh starts: CPU time (the parent's limit plus 5 s), address space
(:data:`bearingfe.geofiles.GEO_MEMORY`) and, on Linux, death with its parent. It writes the mesh (msh
4.1, physical groups only) and a small JSON result; the parent reads both.
The element count is estimated twice before the surface is meshed: from the
size options and the points' sizes, then from the meshed boundary curves.
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


def _run(request: dict, result: dict) -> None:
    import gmsh

    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.logger.start()
    try:
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
    _run(request, result)
    with open(request["result"], "w") as f:
        json.dump(result, f)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
