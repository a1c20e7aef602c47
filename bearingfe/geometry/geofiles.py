"""Geometry files from users: ``.geo`` files read by bearingfe and meshed apart, ``.msh`` read as data.

A gmsh ``.geo`` file is a program: besides points and curves it can run
shell commands (``SystemCall``), write files (``Printf(...) > "f"``,
``Save``), read other files (``Include``, ``Merge``, ``ShapeFromFile``) and
end the process that reads it (``Exit``). bearingfe therefore treats
geometry files as untrusted data by default (docs: README, "Safety"):

* ``.msh`` files are read by a data parser (meshio), never by gmsh's script
  interpreter, and only if their content starts with ``$MeshFormat`` (a
  ``.geo`` script renamed to ``x.msh`` is refused, not run);
* an untrusted ``.geo`` file never reaches gmsh's script interpreter: bearingfe
  reads the geometry subset it documents with its own parser
  (:mod:`bearingfe.geometry.geo_parser`, :func:`read_geo`) and the gmsh child
  builds the model through the gmsh API (:mod:`bearingfe.geometry.geo_model`);
  anything else is refused with :class:`UntrustedGeoError` naming file, line
  and construct. Only a trusted file (``trusted=True``, ``--trust-geo``) is
  run by gmsh's interpreter;
* reading and meshing share one time limit (:data:`DEFAULT_GEO_TIMEOUT`):
  the parser counts its work against it and a budget, gmsh meshes in a
  separate process that is killed with everything it started when the rest
  of the time is up; a loop that never ends or an ``Exit;`` in a trusted
  script cannot hang or end the caller;
* the child process is confined: its own session (killed as a whole), an
  empty environment, CPU time, :data:`GEO_MEMORY` of address space, and on
  Linux it dies with its parent;
* the element count is estimated before meshing and refused beyond
  ``max_elements`` (:data:`DEFAULT_MAX_ELEMENTS`, environment variable
  ``BEARINGFE_MAX_ELEMENTS``).
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.limits import DEFAULT_LIMITS, LimitError, limit
from .errors import GeometryFileError, UntrustedGeoError
from .geo_parser import MAX_GEO_BYTES, GeoModel, Work, parse_geo

__all__ = [
    "GeometryFileError",
    "UntrustedGeoError",
    "MeshSizeError",
    "DEFAULT_MAX_ELEMENTS",
    "DEFAULT_GEO_TIMEOUT",
    "MeshData",
    "max_elements_limit",
    "geo_timeout_limit",
    "check_element_count",
    "estimate_triangles",
    "read_geo",
    "read_msh",
    "run_geo",
    "run_gmsh_worker",
]

#: Largest number of triangles a mesh may have unless the caller raises the limit
#: (``max_elements=``, ``--max-elements`` or the environment variable ``BEARINGFE_MAX_ELEMENTS``).
DEFAULT_MAX_ELEMENTS = int(DEFAULT_LIMITS["elements"])

#: Seconds gmsh may spend parsing and meshing a ``.geo`` script (``timeout=``, ``--geo-timeout``,
#: environment variable ``BEARINGFE_GEO_TIMEOUT``).
DEFAULT_GEO_TIMEOUT = 120.0

#: Address space of the gmsh child process [bytes] (a script that allocates without end fails, not the machine).
GEO_MEMORY = 4 * 1024**3

MAX_ELEMENTS_ENV = "BEARINGFE_MAX_ELEMENTS"
GEO_TIMEOUT_ENV = "BEARINGFE_GEO_TIMEOUT"

#: Area of an equilateral triangle of unit edge: element counts are estimated as area / (this * h^2).
_EQUILATERAL = math.sqrt(3.0) / 4.0


class MeshSizeError(LimitError):
    """The mesh asked for would have more elements than the limit allows."""


# -- limits ------------------------------------------------------------------------

def max_elements_limit(value: int | None = None) -> int:
    """The element-count limit: ``value`` if given, else ``$BEARINGFE_MAX_ELEMENTS``, else the default
    (the ``elements`` limit of :mod:`bearingfe.core.limits`).

    Raises
    ------
    ValueError
        If the value is not an integer >= 1 (or the environment variable not a number > 0).
    """
    if value is None:
        return int(limit("elements"))
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"max_elements (--max-elements) must be an integer >= 1, got {value!r}") from None
    if not (math.isfinite(number) and number >= 1 and number == int(number)):
        raise ValueError(f"max_elements (--max-elements) must be an integer >= 1, got {value!r}")
    return int(number)


def geo_timeout_limit(value: float | None = None) -> float:
    """The ``.geo`` time limit [s]: ``value``, else ``$BEARINGFE_GEO_TIMEOUT``, else the default."""
    source = "timeout (--geo-timeout)"
    if value is None:
        env = os.environ.get(GEO_TIMEOUT_ENV)
        if env is None:
            return DEFAULT_GEO_TIMEOUT
        value, source = env, GEO_TIMEOUT_ENV
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{source} must be a number of seconds > 0, got {value!r}") from None
    if not (math.isfinite(number) and number > 0):
        raise ValueError(f"{source} must be a finite number of seconds > 0, got {value!r}")
    return number


def estimate_triangles(area: float, size: float) -> float:
    """Triangles of edge ``size`` needed to cover ``area`` (a lower bound for sizes up to ``size``)."""
    return float(area) / (_EQUILATERAL * float(size) ** 2)


def check_element_count(estimate: float, max_elements: int | None = None, *, what: str = "the mesh") -> None:
    """Refuse an estimated element count beyond the limit.

    Parameters
    ----------
    estimate : float
        Estimated number of triangles.
    max_elements : int, optional
        The limit; default :func:`max_elements_limit` (environment or
        :data:`DEFAULT_MAX_ELEMENTS`).
    what : str
        What is being meshed, for the message (e.g. ``"size = 0.0001"``).

    Raises
    ------
    MeshSizeError
        Naming the estimate, the limit and how to raise it.
    """
    limit = max_elements_limit(max_elements)
    if not estimate <= limit:  # also NaN
        raise MeshSizeError(
            f"{what} would need about {estimate:.3g} triangles, more than max_elements = {limit}: use a "
            f"larger element size, or raise the limit (max_elements= argument, --max-elements on the "
            f"command line, or the environment variable {MAX_ELEMENTS_ENV})")


# -- .msh as data --------------------------------------------------------------------

@dataclass(frozen=True)
class MeshData:
    """A triangle mesh as plain arrays (read from a file, not yet a scikit-fem mesh).

    Attributes
    ----------
    points : ndarray, shape (2, n)
        Node coordinates ``(phi, z)``.
    triangles : ndarray, shape (3 or 6, m)
        Node indices of each triangle (6: gmsh's second-order node order).
    curves : dict of str to ndarray, shape (2, k)
        For each named physical curve group, the end nodes of its edges.
    """

    points: np.ndarray
    triangles: np.ndarray
    curves: dict


def read_msh(path: str | Path) -> MeshData:
    """Read a gmsh ``.msh`` file (formats 2.2, 4.0, 4.1; text or binary) as data.

    The file is parsed by meshio, never by gmsh's script interpreter, and
    only if it starts with ``$MeshFormat``.

    Raises
    ------
    GeometryFileError
        Not a gmsh mesh file (e.g. a ``.geo`` script named ``.msh``), a file
        meshio cannot parse, or one without triangles.
    """
    path = Path(path)
    with open(path, "rb") as f:
        head = f.read(64).lstrip()
    if not head.startswith(b"$MeshFormat"):
        raise GeometryFileError(
            f"{path.name} is not a gmsh mesh file (it does not start with $MeshFormat); a .geo script must "
            f"be named .geo to be meshed (and it is checked before it runs)")
    import meshio

    try:
        m = meshio.read(path, file_format="gmsh")
    except Exception as exc:  # noqa: BLE001 - any parser failure is a bad file
        raise GeometryFileError(f"{path.name}: not a readable gmsh mesh file ({_short(exc)})") from None
    points = np.asarray(m.points, dtype=float)
    if points.ndim != 2 or points.shape[0] == 0 or not np.all(np.isfinite(points)):
        raise GeometryFileError(f"{path.name}: node coordinates missing or not finite")
    tri = [(k, c.data) for k, c in enumerate(m.cells) if c.type in ("triangle", "triangle6")]
    kinds = {m.cells[k].type for k, _ in tri}
    if not tri:
        raise GeometryFileError(f"{path.name}: no triangles (is there a physical surface?)")
    if len(kinds) > 1:
        raise GeometryFileError(f"{path.name}: mixes straight and curved triangles")
    triangles = np.vstack([d for _, d in tri]).T.astype(np.int64)
    curves = _named_curves(m)
    n = points.shape[0]
    for arr in (triangles, *curves.values()):
        if arr.size and (arr.min() < 0 or arr.max() >= n):
            raise GeometryFileError(f"{path.name}: elements refer to nodes that do not exist")
    return MeshData(points=np.ascontiguousarray(points[:, :2].T), triangles=triangles, curves=curves)


def _named_curves(m) -> dict:
    """End nodes of the line elements of each named physical curve group."""
    lines = {k: c.data[:, :2] for k, c in enumerate(m.cells) if c.type in ("line", "line3")}
    names = {str(name): (int(v[0]), int(v[1])) for name, v in (m.field_data or {}).items() if len(v) >= 2}
    out: dict[str, list] = {}
    sets = {k: v for k, v in (m.cell_sets or {}).items() if k in names and names[k][1] == 1}
    if sets:  # msh 4: an element can belong to several groups
        for name, per_block in sets.items():
            for k, idx in enumerate(per_block):
                if k in lines and idx is not None and len(idx):
                    out.setdefault(name, []).append(lines[k][np.asarray(idx, dtype=np.int64)])
    else:  # msh 2: one physical tag per element, elements repeated per group
        physical = (m.cell_data or {}).get("gmsh:physical")
        by_tag = {tag: name for name, (tag, dim) in names.items() if dim == 1}
        for k, edges in lines.items():
            if physical is None:
                break
            tags = np.asarray(physical[k])
            for tag, name in by_tag.items():
                sel = edges[tags == tag]
                if len(sel):
                    out.setdefault(name, []).append(sel)
    return {name: np.vstack(parts).T.astype(np.int64) for name, parts in out.items()}


def _short(exc: BaseException) -> str:
    return " ".join(str(exc).split())[:200] or type(exc).__name__


# -- .geo in a separate process ------------------------------------------------------------

def read_geo(path: str | Path, *, timeout: float | None = None, clock=time.monotonic) -> GeoModel:
    """Read an untrusted ``.geo`` file with bearingfe's parser (:func:`bearingfe.geometry.geo_parser.parse_geo`).

    Parameters
    ----------
    path : str or Path
        The file (UTF-8 text of at most :data:`bearingfe.geometry.geo_parser.MAX_GEO_BYTES` bytes).
    timeout : float, optional
        Seconds the read may take [s]; default :func:`geo_timeout_limit`.
    clock : callable
        Seconds now [s] (``time.monotonic``; a test may count instead).

    Returns
    -------
    GeoModel
        The kernel and the geometry operations for the gmsh API.

    Raises
    ------
    UntrustedGeoError
        A construct outside the subset, named with file and line.
    GeometryFileError
        Not a regular file, too large, not UTF-8 text, not valid ``.geo``, or beyond the work budget or the
        time limit.
    """
    path = Path(path)
    seconds = geo_timeout_limit(timeout)
    deadline = clock() + seconds
    if not path.is_file():  # a pipe or a device would be read without end
        raise GeometryFileError(f"{path.name} is not a regular file")
    with open(path, "rb") as f:
        data = f.read(MAX_GEO_BYTES + 1)
    if len(data) > MAX_GEO_BYTES:
        raise GeometryFileError(f"{path.name} is larger than the {MAX_GEO_BYTES} bytes a .geo file may have "
                                f"(MAX_GEO_BYTES)")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise GeometryFileError(f"{path.name} line {line}: not UTF-8 text (a .geo file is text)") from None
    return parse_geo(text, path.name, work=Work(deadline=deadline, seconds=seconds, clock=clock))


def run_geo(path: str | Path, out_msh: str | Path, *, size: float | None = None, order: int = 1,
            trusted: bool = False, timeout: float | None = None, max_elements: int | None = None) -> dict:
    """Mesh a ``.geo`` file with gmsh in a separate process and write a ``.msh`` 4.1 file.

    Untrusted (the default), the file is read by bearingfe's parser (:func:`read_geo`) and the child builds
    the model through the gmsh API; gmsh's script interpreter never sees it. Trusted, gmsh's interpreter
    runs the script in the child. Reading and meshing share the time limit.

    Parameters
    ----------
    path : str or Path
        The ``.geo`` file.
    out_msh : str or Path
        Where the mesh is written (physical groups only, names kept).
    size : float, optional
        Largest element size [-] (gmsh's ``Mesh.MeshSizeMax``).
    order : {1, 2}
        Geometry order.
    trusted : bool
        Run the script in gmsh's own interpreter (every command of gmsh's language, shell and files
        included: only for files you trust); still in the child process with the time limit.
    timeout : float, optional
        Seconds for reading and meshing [s]; default :func:`geo_timeout_limit`.
    max_elements : int, optional
        Element-count limit checked before the surface is meshed; default
        :func:`max_elements_limit`.

    Returns
    -------
    dict
        ``estimate`` (the element-count estimate) and ``elements``.

    Raises
    ------
    UntrustedGeoError, GeometryFileError, MeshSizeError
    """
    path = Path(path)
    limit = max_elements_limit(max_elements)
    seconds = geo_timeout_limit(timeout)
    deadline = time.monotonic() + seconds
    request = dict(out=str(Path(out_msh).resolve()), size=size, order=int(order), max_elements=limit)
    if trusted:
        request["geo"] = str(path.resolve())
    else:
        model = read_geo(path, timeout=seconds)
        request.update(model=model.ops, factory=model.factory)
    with tempfile.TemporaryDirectory(prefix="bearingfe-geo-") as work:
        result = run_gmsh_worker(request, work, seconds, path.name,
                                 slow="a loop that does not end, or a very fine mesh?",
                                 how="timeout= (load_mesh), --geo-timeout (bearingfe mesh)",
                                 ended="an Exit or Abort in the script?", deadline=deadline)
    if result.get("kind") == "too_many":
        check_element_count(result["estimate"], limit, what=f"{path.name}"
                            + (f" with size = {size:g}" if size is not None else ""))
    if "error" in result:
        raise GeometryFileError(f"{path.name}: gmsh failed: {result['error']}")
    return result


def run_gmsh_worker(request: dict, work: str | Path, seconds: float, name: str, *, slow: str, how: str,
                    ended: str, deadline: float | None = None) -> dict:
    """Run one request in the gmsh child process (:mod:`bearingfe.geometry.gmsh_worker`) and return its result.

    The child is confined (its own session, an empty environment, CPU
    ``seconds`` + 5, :data:`GEO_MEMORY` of address space, death with its
    parent) and its whole session is killed when it is done or after
    ``seconds`` of wall time (or at ``deadline``).

    Parameters
    ----------
    request : dict
        The task (plain JSON data: never a command); the limits, the parent's
        id and the result file are added here.
    work : str or Path
        A private temporary folder for the request and result files.
    seconds : float
        Wall-time limit [s].
    name : str
        What is meshed, first in every message.
    slow, how, ended : str
        The likely cause of a time-out, how to raise the limit, and the
        likely cause of an early end without a result (for the messages).
    deadline : float, optional
        ``time.monotonic()`` [s] at which the time limit ends, when part of
        ``seconds`` was spent before (reading the file).

    Raises
    ------
    GeometryFileError
        Time-out, or the child ended without writing its result.
    """
    worker = Path(__file__).with_name("gmsh_worker.py")
    request = dict(request, result=str(Path(work) / "result.json"), seconds=seconds, memory=GEO_MEMORY,
                   parent=os.getpid())
    req_file = Path(work) / "request.json"
    req_file.write_text(json.dumps(request))
    code = "import runpy, sys; sys.argv = sys.argv[1:]; runpy.run_path(sys.argv[0], run_name='__main__')"
    proc = subprocess.Popen([sys.executable, "-I", "-c", code, str(worker), str(req_file)], cwd=work,
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            start_new_session=True, env={})
    left = seconds if deadline is None else max(deadline - time.monotonic(), 0.0)
    try:
        output, _ = proc.communicate(timeout=left)
    except subprocess.TimeoutExpired:
        _kill(proc)
        raise GeometryFileError(
            f"{name}: gmsh did not finish within {seconds:g} s ({slow}); raise the limit with {how} or "
            f"the environment variable {GEO_TIMEOUT_ENV}") from None
    finally:
        _kill(proc)  # a trusted script may have started children in the worker's session
    result_file = Path(request["result"])
    if not result_file.is_file():
        tail = " ".join(output.decode("utf-8", "replace").split())[-200:]
        raise GeometryFileError(
            f"{name}: gmsh ended (exit status {proc.returncode}) before it made a mesh"
            + (f" ({ended})" if proc.returncode in (0, 1) else
               f" (out of its {GEO_MEMORY / 1024**3:g} GiB of memory or CPU time, or a crash?)")
            + (f": {tail}" if tail else ""))
    return json.loads(result_file.read_text())


def _kill(proc: subprocess.Popen) -> None:
    """End the worker's process group (the worker and anything it started)."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    proc.wait()
