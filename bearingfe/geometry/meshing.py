"""Meshing support surfaces with gmsh and reading meshes into scikit-fem.

Every call opens and closes its own gmsh session (gmsh keeps global state),
so meshing works repeatedly in one process and nothing leaks between calls.
Boundaries come out named: ``outer`` (the outline), ``inlet`` (all pocket
contours) and ``inlet_0``, ``inlet_1``, ... per pocket; on the default
rectangular outline also ``arc_start`` (phi = alpha1), ``arc_end``
(phi = alpha2) and ``side`` (z = +-a). A periodic surface has no arc edges:
``outer`` = ``side``, and the seam is named ``periodic_start`` /
``periodic_end`` (matching nodes, see :func:`periodic_pairs`).
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import math
import pickle
import threading
import weakref
from dataclasses import InitVar, dataclass, field
from pathlib import Path
from typing import Callable, Hashable, Iterator, TypeVar

import numpy as np
import skfem

from .geofiles import (GeometryFileError, MeshData, check_element_count, estimate_triangles, max_elements_limit,
                       read_msh, run_geo)
from .surface import Surface
from .runner import ALONG_PHI
from ..core.tempdirs import private_tempdir

T = TypeVar("T")

__all__ = ["SupportMesh", "mesh_surface", "load_mesh", "refine_uniformly", "refine_marked", "refine_once",
           "mesh_from_data", "check_triangles", "check_support_mesh",
           "strip_mesh", "grid_mesh", "name_surface_boundaries", "with_named_boundaries", "periodic_pairs",
           "give_facets", "give_facet_triangles", "tensor_lines", "split_parents"]

_GMSH_LOCK = threading.Lock()

#: gmsh's 2D meshing algorithms (Mesh.Algorithm): MeshAdapt, Automatic, Initial mesh only, Delaunay,
#: Frontal-Delaunay, BAMG, Frontal-Delaunay for quads, Packing of parallelograms, Quasi-structured quad.
ALGORITHMS_2D = (1, 2, 3, 5, 6, 7, 8, 9, 11)

#: gmsh element type codes: triangle (3 and 6 nodes), line (2 and 3 nodes).
_TRI = {1: 2, 2: 9}
_LINE = {1: 1, 2: 8}


@dataclass(frozen=True, eq=False)
class SupportMesh:
    """A triangular mesh of a support surface with named boundaries.

    Attributes
    ----------
    mesh : skfem.MeshTri1 or skfem.MeshTri2
        The scikit-fem mesh in ``(phi, z)``; ``MeshTri2`` carries curved
        (second-order) element edges.
    surface : Surface or None
        The geometry it was meshed from (None for a mesh read from a file).
    size : float
        Nominal element size [-] (longest requested edge).
    source : str
        Where the mesh came from (``"gmsh"`` or the file path).
    refinement : callable or None
        Makes this mesh refined once (every triangle split in four, new
        boundary nodes on the exact outline), as the function that made it
        would: set by :func:`mesh_surface`, :func:`strip_mesh` and
        :func:`grid_mesh`; None for meshes read from files (see
        :func:`refine_once`).

    Other Parameters
    ----------------
    cells_checked : bool
        The maker already proved every triangle valid (:func:`mesh_from_data`
        checks them, a grid's lines prove them): only the boundaries are
        checked here. Not stored.
    connected : bool
        The maker already proved the mesh one connected piece that touches
        ``outer`` (a tensor grid without holes): the connected components are
        not searched (:func:`check_support_mesh`). Not stored.
    """

    mesh: skfem.Mesh
    surface: Surface | None = None
    size: float = math.nan
    source: str = "gmsh"
    refinement: Callable[[], "SupportMesh"] | None = field(default=None, repr=False, compare=False)
    _cache: dict = field(default_factory=dict, repr=False, compare=False)
    cells_checked: InitVar[bool] = False
    connected: InitVar[bool] = False

    def __post_init__(self, cells_checked: bool, connected: bool) -> None:
        check_support_mesh(self.mesh, self.source, triangles=not cells_checked, components=not connected)

    def __getstate__(self) -> dict:
        # a mesh made with a local size function (e.g. film_graded_size's) still pickles, without its recipe:
        # in another process refine_once then splits its triangles
        state = dict(self.__dict__)
        state["_cache"] = {}   # the per-mesh structures are rebuilt where they are needed (some hold
        try:                   # scikit-fem objects that do not pickle)
            pickle.dumps(state["refinement"])
        except (pickle.PicklingError, AttributeError, TypeError):
            state["refinement"] = None
        return state

    def cached(self, key: Hashable, build: Callable[[], T]) -> T:
        """What ``build()`` returns, built once per mesh and kept on it under ``key``.

        The one home of per-mesh structures (operators, finite-volume duals and faces, FFT kernels, ...):
        they live as long as the mesh (a pickled mesh travels without them: they are rebuilt where they
        are needed). ``key`` names the structure: a string, or a tuple of a string and what the structure
        depends on besides the mesh.

        Structures that belong to an object derived from a mesh rather than to the mesh itself (a compiled
        operator, a superposition, an assembled system, a finite-volume system's cells) are kept by their module
        in a ``weakref.WeakKeyDictionary`` keyed by that object, so that they go when it goes (e.g.
        ``finite_volume._REDUCED``, ``journal._POSITION_SOURCES``, the ``swift_stieber`` chains): a key
        of this cache could not name such an object without keeping it alive as long as the mesh.
        """
        try:
            return self._cache[key]
        except KeyError:
            value = self._cache[key] = build()
            return value

    @property
    def boundaries(self) -> dict[str, np.ndarray]:
        """Boundary facet indices by name."""
        return dict(self.mesh.boundaries or {})

    @property
    def n_nodes(self) -> int:
        return int(self.mesh.nvertices)

    @property
    def n_elements(self) -> int:
        return int(self.mesh.nelements)

    @property
    def geometry_order(self) -> int:
        """1 for straight-sided triangles, 2 for curved (MeshTri2)."""
        return 2 if isinstance(self.mesh, skfem.MeshTri2) else 1

    @property
    def has_inlet(self) -> bool:
        return "inlet" in self.boundaries and len(self.boundaries["inlet"]) > 0

    @property
    def needs_finite_volumes(self) -> bool:
        """True for surfaces with recesses (film steps) or a periodic seam: only the
        finite-volume solver (:mod:`bearingfe.film.finite_volume`) takes them."""
        surface = self.surface
        return surface is not None and (bool(surface.recesses) or surface.periodic)

    @property
    def runner(self):
        """How the runner slides over the surface (:mod:`bearingfe.geometry.runner`): the surface's,
        or uniformly along ``phi`` for a mesh without one."""
        return self.surface.runner if self.surface is not None else ALONG_PHI

    @property
    def max_edge(self) -> float:
        """Longest element edge [-]."""
        p, f = self.mesh.p, self.mesh.facets
        return float(np.linalg.norm(p[:, f[0]] - p[:, f[1]], axis=0).max())


#: Numeric gmsh options this package sets; saved and restored around a session nested in a caller's.
_TOUCHED_OPTIONS = ("General.Terminal", "General.Verbosity", "Mesh.Algorithm", "Mesh.MeshSizeMax",
                    "Mesh.MeshSizeMin", "Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature",
                    "Mesh.MeshSizeExtendFromBoundary", "Mesh.ElementOrder", "Mesh.MshFileVersion")


@contextlib.contextmanager
def gmsh_session(verbose: bool = False) -> Iterator[object]:
    """A private gmsh session: yield the gmsh module, leave gmsh as it was found.

    If gmsh is not initialized, it is initialized here and finalized on exit.
    If the caller already has a gmsh session, it is left open: the models
    created inside are removed on exit, the caller's current model is made
    current again and the options this package sets are restored.
    """
    import gmsh

    with _GMSH_LOCK:
        if not gmsh.isInitialized():
            gmsh.initialize(interruptible=False)
            _reinstall_signal_handlers()
            try:
                _quiet(gmsh, verbose)
                yield gmsh
            finally:
                gmsh.finalize()
            return
        current, before = gmsh.model.getCurrent(), set(gmsh.model.list())
        saved = {name: gmsh.option.getNumber(name) for name in _TOUCHED_OPTIONS}
        try:
            _quiet(gmsh, verbose)
            yield gmsh
        finally:
            for name in [m for m in gmsh.model.list() if m not in before]:
                gmsh.model.setCurrent(name)
                gmsh.model.remove()
            if current in gmsh.model.list():
                gmsh.model.setCurrent(current)
            for name, value in saved.items():
                gmsh.option.setNumber(name, value)


def _reinstall_signal_handlers() -> None:
    """Put Python's handlers of SIGTERM, SIGINT and SIGHUP back at the C level.

    ``gmsh.initialize()`` sets SIGTERM to its default action behind Python's
    back, so a SIGTERM after meshing killed the process (exit 143) instead of
    running the caller's handler (the command line's clean-up, exit 130).
    Setting the handler Python already holds installs it again. Only the main
    thread may set handlers (elsewhere there is nothing of Python's to restore).
    """
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return
    for name in ("SIGTERM", "SIGINT", "SIGHUP"):
        sig = getattr(signal, name, None)
        handler = signal.getsignal(sig) if sig is not None else None
        if handler is not None:
            signal.signal(sig, handler)


def _quiet(gmsh, verbose: bool) -> None:
    gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
    gmsh.option.setNumber("General.Verbosity", 5 if verbose else 0)


def mesh_surface(
    surface: Surface,
    size: float,
    *,
    inlet_size: float | None = None,
    corner_size: float | None = None,
    grading_distance: float | None = None,
    recess_size: float | None = None,
    size_function: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
    min_size: float | None = None,
    order: int = 1,
    refine: int = 0,
    algorithm: int = 6,
    verbose: bool = False,
    max_elements: int | None = None,
) -> SupportMesh:
    """Mesh a support surface with gmsh.

    Parameters
    ----------
    surface : Surface
        Outline and pockets in ``(phi, z)``.
    size : float
        Element size away from refinement zones [-], > 0.
    inlet_size : float, optional
        Element size on the pocket contours; grows linearly to ``size`` over
        ``grading_distance``. Default: ``size`` (no grading), but never
        larger than half the narrowest gap between a pocket and the outline.
    corner_size : float, optional
        Element size at the sharp corners of pockets (rectangles, polygons),
        where the pressure gradient is singular. Default: ``inlet_size``.
    grading_distance : float, optional
        Distance over which refined sizes grow back to ``size`` [-].
        Default: ``4 * size``.
    recess_size : float, optional
        Element size on the recess contours (the film's steps) [-], growing to ``size`` over
        ``2 * size``. Default: ``size / 8`` (:data:`RECESS_REFINEMENT`): a step carries the
        mass-conserving flux's first-order error along its contour, so refining there pays most
        (measured on a slider with one dimple: within 1 % of the converged load from 6k nodes, against
        47k nodes without). ``recess_size = size`` turns it off.
    size_function : callable, optional
        ``f(phi, z) -> size`` for any other refinement (e.g. where the film
        is thinnest: see :func:`bearingfe.film_graded_size`); the smallest of
        all requested sizes wins.
    min_size : float, optional
        Smallest element size gmsh may use [-], > 0 (sizes asked for below
        it are raised to it). Default: with a ``size_function``, none (its
        requests are honoured as asked); without, a quarter of the smallest
        of ``size``, ``inlet_size`` and ``corner_size``.
    order : {1, 2}
        Geometry order: 2 gives curved edges on curved pockets (``MeshTri2``),
        which P2 elements need to keep their convergence rate.
    refine : int
        Number of uniform refinements (each splits every triangle in four),
        done by gmsh after meshing so new nodes stay on curved boundaries.
    algorithm : int
        gmsh 2D algorithm (6: Frontal-Delaunay), one of :data:`ALGORITHMS_2D`.
    verbose : bool
        Let gmsh print its log.
    max_elements : int, optional
        Largest number of triangles: the count is estimated from the film
        area and the requested sizes before gmsh starts, and refused beyond
        it (:class:`bearingfe.geometry.geofiles.MeshSizeError`). Default
        :data:`bearingfe.geometry.geofiles.DEFAULT_MAX_ELEMENTS` or the environment
        variable ``BEARINGFE_MAX_ELEMENTS``.

    Returns
    -------
    SupportMesh
    """
    if not isinstance(surface, Surface):
        raise ValueError(f"surface must be a bearingfe.Surface, got {type(surface).__name__}")
    size = _checked_size(size, "size")
    gap = surface.min_gap() if surface.inlets else math.inf
    widest = min(surface.inlet_widths()) if surface.inlets else math.inf  # the mesh must resolve every pocket
    inlet_size = min(_checked_size(inlet_size, "inlet_size") if inlet_size is not None else size, gap / 2, widest)
    corner_size = _checked_size(corner_size, "corner_size") if corner_size is not None else inlet_size
    grading = _checked_size(grading_distance, "grading_distance") if grading_distance is not None else 4 * size
    recess_size = min(_checked_size(recess_size, "recess_size") if recess_size is not None
                      else RECESS_REFINEMENT * size, size) if surface.recesses else size
    if min_size is not None:
        floor = _checked_size(min_size, "min_size")
    else:  # a size function's requests are not raised silently (gmsh's MeshSizeMin 0 = no floor)
        floor = 0.0 if size_function is not None else min(size, inlet_size, corner_size, recess_size) / 4
    if order not in (1, 2):
        raise ValueError(f"order must be 1 or 2, got {order!r}")
    if not (isinstance(refine, int) and 0 <= refine <= 6):
        raise ValueError(f"refine must be an integer in 0..6, got {refine!r}")
    if algorithm not in ALGORITHMS_2D:
        raise ValueError(f"algorithm must be one of gmsh's 2D algorithms {ALGORITHMS_2D}, got {algorithm!r}")
    estimate = 4**refine * _estimated_triangles(surface, size, floor, inlet_size, grading, size_function,
                                                recess_size)
    check_element_count(estimate, max_elements,
                        what=f"size = {size:g}" + (f" with refine = {refine}" if refine else "")
                        + (" and the size_function" if size_function is not None else ""))

    try:
        with gmsh_session(verbose) as gmsh:
            gmsh.model.add("support")
            groups = _build_geometry(gmsh, surface)
            errors = _set_sizes(gmsh, groups, size, floor, inlet_size, corner_size, grading, size_function, surface,
                                recess_size)
            gmsh.option.setNumber("Mesh.Algorithm", algorithm)
            gmsh.model.mesh.generate(2)
            if errors:  # gmsh swallows exceptions raised in its size callback
                raise ValueError(f"size_function failed: {errors[0]}") from errors[0]
            for _ in range(refine):
                gmsh.model.mesh.refine()
            if order == 2:
                gmsh.model.mesh.setOrder(2)
            mesh = _read_gmsh_model(gmsh, order)
    except Exception as exc:
        if type(exc) is Exception:  # gmsh's API raises a bare Exception carrying its last error
            raise RuntimeError(f"gmsh could not mesh the surface: {' '.join(str(exc).split())}") from None
        raise
    again = functools.partial(mesh_surface, surface, size, inlet_size=inlet_size, corner_size=corner_size,
                              grading_distance=grading_distance, recess_size=recess_size,
                              size_function=size_function, min_size=min_size,
                              order=order, refine=refine + 1, algorithm=algorithm, verbose=verbose,
                              max_elements=max_elements)
    # mesh_from_data checked the triangles (_read_gmsh_model): the mesh need not check them again
    return SupportMesh(mesh=mesh, surface=surface, size=size / 2**refine, source="gmsh", refinement=again,
                       cells_checked=True)


def load_mesh(path: str | Path, *, size: float | None = None, order: int = 1, trusted: bool = False,
              timeout: float | None = None, max_elements: int | None = None) -> SupportMesh:
    """Read a support-surface mesh from a gmsh ``.geo`` or ``.msh`` file.

    The file must define physical curve groups named ``outer`` and
    (optionally) ``inlet`` and a physical surface; ``arc_start``,
    ``arc_end`` and ``side`` are used for flow splits when present.

    Geometry files are data unless the caller says otherwise
    (:mod:`bearingfe.geometry.geofiles`): a ``.msh`` file is parsed as data (meshio)
    and must start with ``$MeshFormat``; a ``.geo`` file is read by
    bearingfe's parser of the documented geometry subset (no shell
    commands, file writes, includes, merges, ``Exit``...: those are refused
    by name) and built and meshed through the gmsh API in a separate
    process with a time limit. Degenerate (zero-area) and duplicated
    triangles are refused.

    Parameters
    ----------
    path : str or Path
        ``.geo`` (meshed here) or ``.msh`` (read as is).
    size : float, optional
        For ``.geo``: maximum element size [-] (overrides the file's sizes).
    order : {1, 2}
        For ``.geo``: geometry order of the generated mesh.
    trusted : bool
        For ``.geo``: hand the script to gmsh's own interpreter, every
        command of gmsh's language included (only for files you wrote or
        trust). It still runs in a separate process with the time limit.
    timeout : float, optional
        For ``.geo``: seconds reading and meshing may take [s]; default
        :data:`bearingfe.geometry.geofiles.DEFAULT_GEO_TIMEOUT` or the environment
        variable ``BEARINGFE_GEO_TIMEOUT``.
    max_elements : int, optional
        Largest number of triangles (estimated before meshing a ``.geo``);
        default :data:`bearingfe.geometry.geofiles.DEFAULT_MAX_ELEMENTS` or the
        environment variable ``BEARINGFE_MAX_ELEMENTS``.

    Raises
    ------
    FileNotFoundError
        No such file.
    ValueError
        Wrong suffix or argument; :class:`bearingfe.geometry.geofiles.UntrustedGeoError`
        (a refused command), :class:`bearingfe.geometry.geofiles.GeometryFileError`
        (not a mesh, gmsh failed or timed out, bad elements) and
        :class:`bearingfe.geometry.geofiles.MeshSizeError` (too many elements) are
        ValueErrors.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"mesh file not found: {path}")
    if path.suffix not in (".geo", ".msh"):
        raise ValueError(f"mesh file must be .geo or .msh, got {path.name}")
    limit = max_elements_limit(max_elements)
    if path.suffix == ".geo":
        if size is not None:
            size = _checked_size(size, "size")
        if order not in (1, 2):
            raise ValueError(f"order must be 1 or 2, got {order!r}")
        with private_tempdir("mesh") as work:
            msh = Path(work) / "mesh.msh"
            run_geo(path, msh, size=size, order=order, trusted=trusted, timeout=timeout, max_elements=limit)
            data = read_msh(msh)
    else:
        data = read_msh(path)
    check_element_count(data.triangles.shape[1], limit, what=path.name)
    mesh = mesh_from_data(data, path.name)
    if "outer" not in (mesh.boundaries or {}):
        raise ValueError(f"{path.name}: no physical curve group named 'outer'")
    return SupportMesh(mesh=mesh, surface=None, size=size if size is not None else math.nan, source=str(path),
                       cells_checked=True)  # mesh_from_data checked the triangles


def refine_uniformly(mesh: SupportMesh, times: int = 1) -> SupportMesh:
    """Split every triangle in four ``times`` times (straight edges only)."""
    m = mesh.mesh
    if isinstance(m, skfem.MeshTri2):
        raise ValueError("refine_uniformly works on straight-sided meshes; remesh with refine= for curved ones")
    return SupportMesh(mesh=m.refined(times), surface=mesh.surface, size=mesh.size / 2**times, source=mesh.source)


def refine_marked(m: skfem.MeshTri1, marked: np.ndarray) -> skfem.MeshTri1:
    """``m.refined(marked)``: scikit-fem's conforming red-green-blue refinement of the triangles ``marked``,
    the same mesh (nodes and triangles, to the last index), split by index tables (one gather per kind of
    split instead of scikit-fem's sixty stacks), with the facets of ``m`` taken from it where it has them
    (a named mesh, or the previous split's result) and the refined mesh's facets and triangle-to-facet map
    (scikit-fem's arrays) built from the split itself: each unsplit facet stays, each split one gives two
    halves, each split triangle its inner edges; one sort of their codes orders them as scikit-fem would.
    A rupture front's refinement levels split a few hundred triangles several times per level, and the
    next split and the naming of the boundaries use those facets. The refined mesh records the triangle of
    ``m`` (and of the meshes ``m`` was split from) holding each of its triangles: :func:`split_parents`.

    Parameters
    ----------
    m : skfem.MeshTri1
        Straight triangles; named boundaries are dropped (as by ``refined``): name them again, e.g. with
        :func:`name_surface_boundaries`.
    marked : numpy.ndarray of int
        Indices of the triangles to split (their neighbours are split too where conformity needs it).

    Returns
    -------
    skfem.MeshTri1
        With its facets and triangle-to-facet map built (unless ``m`` has subdomains: then scikit-fem's
        own split, facets built on first use).
    """
    if type(m) is not skfem.MeshTri1:
        raise ValueError(f"m must be a scikit-fem MeshTri1 (straight triangles), got {type(m).__name__}")
    marked = np.asarray(marked)
    if marked.ndim != 1 or not np.issubdtype(marked.dtype, np.integer) or (
            marked.size and (marked.min() < 0 or marked.max() >= m.t.shape[1])):
        raise ValueError(f"marked must be a 1-D array of triangle indices in [0, {m.t.shape[1]}), got {marked!r}")
    give_facets(m)
    t, t2f = _longest_edge_first(m.p, m.t, m._t2f)
    split = _closed_split(t2f, m._facets.shape[1], marked)
    if m._subdomains is not None:  # MeshTri1._adaptive's own split, which carries the subdomains
        sorted_mesh = dataclasses.replace(m, t=t, sort_t=False)
        sorted_mesh._facets, sorted_mesh._t2f = m._facets, t2f
        doflocs, t, subdomains = m._adaptive_split_elements(sorted_mesh, split.astype(np.int32), m._subdomains)
        return dataclasses.replace(m, doflocs=doflocs, t=t, _boundaries=None, _subdomains=subdomains)
    nv = m.p.shape[1]
    new = np.full(split.size, -1, dtype=np.int64)
    new[split] = np.arange(nv, nv + np.count_nonzero(split))
    mid = new[t2f]   # (3, triangles): the new node on each local facet, -1 if it is not split
    cut = mid >= 0
    rest = ~cut[2]   # the closure splits facet 2 (the longest) of every triangle with a split facet
    kinds = (cut[0] & cut[1], ~cut[0] & cut[1] & cut[2], cut[0] & ~cut[1] & cut[2], ~cut[0] & ~cut[1] & cut[2])
    nodes = np.vstack([t, mid])  # rows 0-2 the vertices, 3-5 the new nodes on facets 0-2
    parts = [nodes[:, kind] for kind in kinds]
    ends = m._facets[:, split]
    doflocs = np.hstack((m.p, .5 * (m.p[:, ends[0]] + m.p[:, ends[1]])))
    triangles = np.hstack([t[:, rest]] + [part[table.T].reshape(3, -1) for part, table in zip(parts, _SPLITS)])
    if m.sort_t:   # what the mesh's __post_init__ would do (np.sort(t, axis=0)), by a sorting network
        triangles = _sorted_columns(triangles)
    refined = dataclasses.replace(m, doflocs=doflocs, t=triangles, sort_t=False, _boundaries=None, _subdomains=None)
    refined.sort_t = m.sort_t
    # the triangle of m each new one lies in: the columns above, in their order (a kind's part[table.T] holds
    # its first piece of every triangle of the kind, then its second...)
    _keep_parents(refined, m, np.concatenate([np.flatnonzero(rest)] + [np.tile(np.flatnonzero(kind), len(table))
                                                                       for kind, table in zip(kinds, _SPLITS)]))
    pairs = np.hstack([m._facets[:, ~split], np.vstack([ends[0], new[split]]), np.vstack([ends[1], new[split]])]
                      + [_in_order(part[i], part[j]) for part, edges in zip(parts, _INNER_EDGES) for i, j in edges])
    _set_facets(refined, np.sort(pairs[0].astype(np.int64) * doflocs.shape[1] + pairs[1]))
    return refined


#: How :func:`refine_marked` splits a triangle (vertices 0-2 longest facet 2 = (0, 2), new nodes 3-5 on facets
#: (0, 1), (1, 2), (0, 2)): the rows of its new triangles, per kind (scikit-fem's ``_adaptive_split_elements``:
#: red, blue with facet 0 whole, blue with facet 1 whole, green), in scikit-fem's order.
_SPLITS = (np.array([(0, 3, 5), (1, 3, 4), (2, 4, 5), (4, 5, 3)]), np.array([(1, 0, 5), (1, 4, 5), (2, 5, 4)]),
           np.array([(0, 3, 5), (5, 3, 1), (2, 5, 1)]), np.array([(1, 5, 0), (2, 5, 1)]))
#: ... and the new edges inside it (the pairs of rows), per kind.
_INNER_EDGES = (((3, 4), (4, 5), (3, 5)), ((1, 5), (4, 5)), ((3, 5), (1, 5)), ((1, 5),))


#: Attribute of a mesh made by :func:`refine_marked` (and of its named copies, :func:`with_named_boundaries`):
#: ``((weakref to an earlier mesh, index of its triangle holding each of this mesh's triangles), ...)``, for the
#: mesh it was split from and, composed, for that mesh's own such meshes still alive (:func:`split_parents`).
_PARENTS = "_split_parents"


def _keep_parents(refined: skfem.MeshTri1, m: skfem.MeshTri1, parents: np.ndarray) -> None:
    """Record on ``refined``, split from ``m``, the triangle of ``m`` holding each of its triangles
    (``parents``), and through ``m``'s own record those of the earlier meshes ``m`` was split from that are still
    alive (the mesh a level of splits started from, e.g. the one a solution lives on)."""
    earlier = tuple((ref, p[parents]) for ref, p in vars(m).get(_PARENTS, ()) if ref() is not None)
    setattr(refined, _PARENTS, ((weakref.ref(m), parents),) + earlier)


def split_parents(coarse: skfem.Mesh, fine: skfem.Mesh) -> np.ndarray | None:
    """The triangle of ``coarse`` holding each triangle of ``fine``, if ``fine`` was made from ``coarse`` by
    :func:`refine_marked` (one or several splits; a copy named by :func:`with_named_boundaries` keeps the
    record of the mesh it copies), else None. Every triangle of ``fine`` lies inside its parent (the splits are
    nested), so a field of ``coarse`` is evaluated exactly at a point of ``fine`` from the parent's vertices
    alone (:func:`~bearingfe.geometry.locate.values_in_cells`).

    Parameters
    ----------
    coarse, fine : skfem.Mesh

    Returns
    -------
    numpy.ndarray of int or None
        Shape ``(fine.nelements,)``: indices into ``coarse.t``'s columns; ``arange`` if ``fine`` is ``coarse``.
    """
    if fine is coarse:
        return np.arange(coarse.t.shape[1])
    for ref, parents in vars(fine).get(_PARENTS, ()):
        if ref() is coarse:
            return parents
    return None


def _longest_edge_first(p: np.ndarray, t: np.ndarray, t2f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """scikit-fem's ``MeshTri1._adaptive_sort_mesh`` (each triangle's vertices turned so that its facet 2,
    ``(0, 2)``, is the strictly longest where one is; the same lengths and comparisons, from one gather of the
    vertices) and the triangle-to-facet map turned alike (the facets do not change): where vertices 1 and 2
    are swapped (facet 0 longest), facets 0 and 2 are; where vertices 0 and 1 (facet 1 longest), facets 1 and 2."""
    q = p[:, t]
    l01, l12, l02 = (np.sqrt(np.sum((q[:, i] - q[:, j]) ** 2, axis=0)) for i, j in ((0, 1), (1, 2), (0, 2)))
    turned, t2f = t.copy(), t2f.copy()
    for (i, j), k, swapped in (((1, 2), 0, (l01 > l02) & (l01 > l12)), ((0, 1), 1, (l12 > l01) & (l12 > l02))):
        turned[i, swapped], turned[j, swapped] = t[j, swapped], t[i, swapped]
        t2f[k, swapped], t2f[2, swapped] = t2f[2, swapped], t2f[k, swapped]
    return turned, t2f


def _closed_split(t2f: np.ndarray, n_facets: int, marked: np.ndarray) -> np.ndarray:
    """scikit-fem's ``MeshTri1._adaptive_find_facets`` as a mask: the facets of the ``marked`` triangles, and
    the longest facet (2) of every triangle with a split facet, until no more are added (conformity)."""
    split = np.zeros(n_facets, dtype=bool)
    split[t2f[:, marked]] = True
    count = -1
    while (now := np.count_nonzero(split)) > count:
        count = now
        split[t2f[2, split[t2f[0]] | split[t2f[1]]]] = True
    return split


def refine_once(mesh: SupportMesh) -> SupportMesh:
    """``mesh`` with every triangle split in four: the mesh of a once-refined comparison.

    The function that made the mesh makes it again one level finer
    (``mesh.refinement``): gmsh refines its own mesh, so new nodes on curved
    outlines and pockets lie on them and curved (order-2) meshes stay curved;
    strips and grids get twice the cells each way. A straight-sided mesh
    without that record (read from a file) is split by
    :func:`refine_uniformly`: its outline stays the polygon of the file.

    Raises
    ------
    ValueError
        For a curved (``MeshTri2``) mesh read from a file (no geometry to put new nodes on).
    """
    if mesh.refinement is not None:
        return mesh.refinement()
    return refine_uniformly(mesh)


def _estimated_triangles(surface: Surface, size: float, floor: float, inlet_size: float, grading: float,
                         size_function, recess_size: float | None = None) -> float:
    """Triangles needed for the film at the requested sizes (corner grading left out: a lower bound).

    The sizes are sampled on a 120 x 120 grid over the outline's bounding box;
    the band around the pockets where the size grows linearly from
    ``inlet_size`` to ``size`` over ``grading`` adds
    ``perimeter * grading / (size - inlet_size) * (1/inlet_size - 1/size)``
    equilateral-triangle areas.
    """
    x0, x1, y0, y1 = surface.bounds
    n = 120
    phi, z = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    inside = surface.outline.contains(phi, z) & ~surface.in_pocket(phi, z)
    local = np.full(phi.shape, size)
    if size_function is not None:
        try:
            with np.errstate(all="ignore"):
                asked = np.broadcast_to(np.asarray(size_function(phi, z), dtype=float), phi.shape)
            local = np.where(np.isfinite(asked) & (asked > 0), np.minimum(local, asked), local)
        except Exception:  # noqa: BLE001 - scalar-only functions: estimate from size alone
            pass
    local = np.maximum(local, floor) if floor > 0 else local
    cell = (x1 - x0) * (y1 - y0) / n**2
    sampled = float(np.sum(inside / local**2)) * cell / (math.sqrt(3.0) / 4.0)
    def band(shapes, small: float, distance: float) -> float:
        s0 = max(small, floor)
        if not shapes or s0 >= size:
            return 0.0
        perimeter = sum(float(np.sum(np.linalg.norm(np.roll(xy, -1, axis=1) - xy, axis=0)))
                        for xy in (shape.boundary() for shape in shapes))
        return perimeter * distance / (size - s0) * (1 / s0 - 1 / size) / (math.sqrt(3.0) / 4.0)

    sampled += band(surface.inlets, inlet_size, grading)
    if recess_size is not None:
        sampled += band([r.shape for r in surface.recesses], recess_size, RECESS_GRADING * size)
    return max(sampled, estimate_triangles(surface.film_area, size))


#: Range of element sizes [R0] (the surfaces are of order 1): beyond it the size estimates under- or overflow
#: (1e-300 gave "float division by zero", 1e300 "Numerical result out of range"); sizes far inside it are
#: refused by the element-count limit already.
SIZE_RANGE = (1e-12, 1e6)


def _checked_size(value: float, name: str) -> float:
    """``float(value)`` if it is an element size in :data:`SIZE_RANGE` [R0], else a ValueError naming ``name``."""
    value = float(value)
    if not (math.isfinite(value) and SIZE_RANGE[0] <= value <= SIZE_RANGE[1]):
        raise ValueError(f"{name} must be a finite element size in [{SIZE_RANGE[0]:g}, {SIZE_RANGE[1]:g}] "
                         f"(units of R0), got {value!r}")
    return value


def _build_geometry(gmsh, surface: Surface) -> dict[str, list[int]]:
    occ = gmsh.model.occ
    outline = surface.outline
    outer_curves = outline.add_to_gmsh(occ)
    inlet_curves = [shape.add_to_gmsh(occ) for shape in surface.inlets]
    loops = [occ.addCurveLoop(outer_curves)] + [occ.addCurveLoop(c) for c in inlet_curves]
    face = occ.addPlaneSurface(loops)
    recess_curves = [r.shape.add_to_gmsh(occ) for r in surface.recesses]
    occ.synchronize()
    if recess_curves:  # recess contours on element edges: the film step is meshed conformally
        gmsh.model.mesh.embed(1, [c for cs in recess_curves for c in cs], 2, face)
    groups = {"outer": outer_curves, "inlet": [c for cs in inlet_curves for c in cs]}
    for k, cs in enumerate(inlet_curves):
        groups[f"inlet_{k}"] = cs
    if surface.periodic:
        # the arc ends are one line of the film: matching nodes, no pressure condition there
        bottom, right, top, left = outer_curves
        period = surface.arc[1] - surface.arc[0]
        gmsh.model.mesh.setPeriodic(1, [right], [left], [1, 0, 0, period, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
        groups.update(outer=[bottom, top], side=[bottom, top], periodic_start=[left], periodic_end=[right])
    elif surface.is_rectangular:
        # Rectangle vertices are stored counter-clockwise starting at (alpha1, -a):
        # edges bottom (side), right (arc_end), top (side), left (arc_start).
        bottom, right, top, left = outer_curves
        groups.update(arc_start=[left], arc_end=[right], side=[bottom, top])
    elif hasattr(outline, "edge_groups"):  # an outline that names its edges (AnnularSector)
        groups.update({name: [outer_curves[i] for i in idx] for name, idx in outline.edge_groups().items()})
    for name, curves in groups.items():
        if curves:
            gmsh.model.addPhysicalGroup(1, curves, name=name)
    gmsh.model.addPhysicalGroup(2, [face], name="film")
    groups["recess"] = [c for cs in recess_curves for c in cs]
    return groups


#: Default element size on recess contours over ``size``, and the distance (in ``size``) over which it grows back.
RECESS_REFINEMENT = 0.125
RECESS_GRADING = 2.0


def _set_sizes(gmsh, groups, size, floor, inlet_size, corner_size, grading, size_function, surface,
               recess_size=None) -> list:
    opt = gmsh.option
    opt.setNumber("Mesh.MeshSizeMax", size)
    opt.setNumber("Mesh.MeshSizeMin", floor)
    opt.setNumber("Mesh.MeshSizeFromPoints", 0)
    opt.setNumber("Mesh.MeshSizeFromCurvature", 0)
    opt.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    fields = []
    errors: list[Exception] = []
    mf = gmsh.model.mesh.field
    edges = groups["inlet"] + groups.get("recess", [])
    if edges and inlet_size < size:
        fields.append(_threshold(mf, "CurvesList", edges, inlet_size, size, grading))
    recess = groups.get("recess", [])
    if recess and recess_size is not None and recess_size < min(size, inlet_size):
        fields.append(_threshold(mf, "CurvesList", recess, recess_size, size, RECESS_GRADING * size))
    shapes = list(surface.inlets) + [r.shape for r in surface.recesses]
    corners = np.hstack([s.corners() for s in shapes]) if shapes else np.zeros((2, 0))
    if corners.shape[1] and corner_size < size:
        pts = _points_at(gmsh, corners)
        fields.append(_threshold(mf, "PointsList", pts, corner_size, size, grading))
    if fields:
        fmin = mf.add("Min")
        mf.setNumbers(fmin, "FieldsList", fields)
        mf.setAsBackgroundMesh(fmin)
    if size_function is not None:
        def callback(dim, tag, x, y, z, lc):
            try:
                value = float(size_function(np.array(x), np.array(y)))
                if not (math.isfinite(value) and value > 0):
                    raise ValueError(f"it must return a finite size > 0, got {value!r} at ({x}, {y})")
            except Exception as exc:  # noqa: BLE001 - re-raised after meshing
                errors.append(exc)
                return lc
            return min(lc, value)
        gmsh.model.mesh.setSizeCallback(callback)
    return errors


def _points_at(gmsh, xy: np.ndarray) -> list[int]:
    """Tags of the geometry points (already on pocket contours) at the given corners."""
    tags = [tag for _, tag in gmsh.model.getEntities(0)]
    where = np.array([gmsh.model.getValue(0, tag, [])[:2] for tag in tags]).T
    near = np.hypot(where[0][:, None] - xy[0], where[1][:, None] - xy[1]) < 1e-9 * (1 + np.abs(xy).max())
    return [tags[i] for i in np.nonzero(near.any(axis=1))[0]]


def _threshold(mf, kind: str, entities: list[int], small: float, large: float, distance: float) -> int:
    dist = mf.add("Distance")
    mf.setNumbers(dist, kind, entities)
    mf.setNumber(dist, "Sampling", 200)
    thr = mf.add("Threshold")
    mf.setNumber(thr, "InField", dist)
    mf.setNumber(thr, "SizeMin", small)
    mf.setNumber(thr, "SizeMax", large)
    mf.setNumber(thr, "DistMin", 0.0)
    mf.setNumber(thr, "DistMax", distance)
    return thr


def _read_gmsh_model(gmsh, order: int) -> skfem.Mesh:
    """Convert gmsh's current 2D mesh to scikit-fem with named boundaries."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xy = coords.reshape(-1, 3)[:, :2].T
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(tags.size)
    _, node_tags = gmsh.model.mesh.getElementsByType(_TRI[order])
    if node_tags.size == 0:
        raise ValueError("gmsh produced no triangles (is there a physical surface?)")
    t = index[node_tags.astype(np.int64)].reshape(-1, 3 * order).T
    curves: dict[str, list] = {}
    for dim, tag in gmsh.model.getPhysicalGroups(1):
        name = gmsh.model.getPhysicalName(dim, tag)
        for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            for etype, _, enodes in zip(*gmsh.model.mesh.getElements(1, entity)):
                nper = gmsh.model.mesh.getElementProperties(etype)[3]
                curves.setdefault(name, []).append(index[enodes.astype(np.int64)].reshape(-1, nper)[:, :2])
    named = {k: np.vstack(v).T for k, v in curves.items() if k}
    return mesh_from_data(MeshData(points=xy, triangles=t, curves=named), "gmsh mesh")


def mesh_from_data(data: MeshData, name: str = "mesh") -> skfem.Mesh:
    """A scikit-fem mesh with named boundaries from plain arrays, after checking the triangles.

    Parameters
    ----------
    data : bearingfe.geometry.geofiles.MeshData
        Nodes, triangles (3 or 6 nodes) and named curves.
    name : str
        For the messages (e.g. the file name).

    Raises
    ------
    bearingfe.geometry.geofiles.GeometryFileError
        Degenerate (zero-area) or duplicated triangles, triangles that
        overlap (an edge shared by more than two), or a named curve whose
        edges are not edges of the triangles (e.g. a pocket too thin for the
        element size).
    """
    t_all = np.asarray(data.triangles, dtype=np.int64)
    order = 1 if t_all.shape[0] == 3 else 2
    used = _used(t_all, data.points.shape[1])
    compact = np.full(data.points.shape[1], -1, dtype=np.int64)
    compact[used] = np.arange(used.size)
    xy = np.ascontiguousarray(data.points[:, used], dtype=float)
    t = compact[t_all]
    check_triangles(xy, t[:3], name)
    vertices = _used(t[:3], xy.shape[1])
    renumber = np.full(xy.shape[1], -1, dtype=np.int64)
    renumber[vertices] = np.arange(vertices.size)  # scikit-fem's own vertex numbering
    if order == 1:
        mesh = skfem.MeshTri1(np.ascontiguousarray(xy[:, vertices]), np.ascontiguousarray(renumber[t]))
    else:
        mesh = skfem.MeshTri2(xy, np.ascontiguousarray(t))
    _init_facets(mesh)
    nv = int(mesh.nvertices)
    codes = mesh.facets[0].astype(np.int64) * nv + mesh.facets[1]  # ascending: the facets are sorted pairs
    boundaries = {}
    for label, ends in data.curves.items():
        ends = renumber[compact[np.asarray(ends, dtype=np.int64)]]
        ends = _in_order(ends[0], ends[1])
        wanted = ends[0] * nv + ends[1]
        at = np.minimum(np.searchsorted(codes, wanted), codes.size - 1)
        missing = int(np.count_nonzero((codes[at] != wanted) | (ends[0] < 0)))
        if missing:
            raise GeometryFileError(
                f"{name}: {missing} edge(s) of the physical curve '{label}' are not edges of the triangles "
                f"(a pocket or gap too thin for the element size, or curves not in the meshed surface)")
        boundaries[label] = np.unique(at).astype(np.int64)
    return with_named_boundaries(mesh, boundaries) if boundaries else mesh


def _used(indices: np.ndarray, n: int) -> np.ndarray:
    """The sorted distinct values of ``indices`` (all in ``0 .. n - 1``): ``np.unique`` by a mask, no sort."""
    mask = np.zeros(n, dtype=bool)
    mask[indices.ravel()] = True
    return np.flatnonzero(mask)


def with_named_boundaries(m: skfem.Mesh, boundaries: dict) -> skfem.Mesh:
    """``m.with_boundaries(boundaries)`` keeping the facets (and their maps) ``m`` has built already: the copy
    has the same triangles, and scikit-fem would sort them into facets again on its first use of them; and
    the record of the meshes ``m`` was split from (:func:`split_parents`).

    Parameters
    ----------
    m : skfem.Mesh
    boundaries : dict
        Boundary name -> facet indices of ``m`` (added to ``m``'s own).

    Returns
    -------
    skfem.Mesh
        The copy with the named boundaries.
    """
    new = m.with_boundaries(boundaries)
    if np.array_equal(new.t, m.t):
        for name in ("_facets", "_t2f", "_f2t", _PARENTS):
            if name in m.__dict__:
                setattr(new, name, m.__dict__[name])
    return new


def _init_facets(m: skfem.Mesh) -> None:
    """Give ``m`` the facets and triangle-to-facet map scikit-fem's ``Mesh._init_facets`` would build (the same
    arrays: the sorted unique node pairs in lexicographic order), found by a sparse matrix's counting sort by
    first node instead of scikit-fem's sort of structured rows (about twice as fast on a large grid)."""
    from scipy.sparse import csr_matrix

    pairs = _facet_pairs(m)
    nv = int(m.nvertices)
    graph = csr_matrix((np.ones(pairs.shape[1]), (pairs[0], pairs[1])), shape=(nv, nv))
    graph.sum_duplicates()   # rows then columns sorted, each pair once: the lexicographic unique pairs
    first = np.repeat(np.arange(nv, dtype=np.int64), np.diff(graph.indptr))
    _set_facets(m, first * nv + graph.indices, pairs)


def _set_facets(m: skfem.Mesh, code: np.ndarray, pairs: np.ndarray | None = None) -> None:
    """Give ``m`` its facets and triangle-to-facet map from the codes ``first * nvertices + second`` of all its
    facets (node pairs ``first < second``), sorted and each once: scikit-fem's arrays (values and dtypes).
    ``pairs``: the sorted node pairs of every triangle's facets, facet by facet (made here if not given)."""
    pairs = _facet_pairs(m) if pairs is None else pairs
    nv = int(m.nvertices)
    m._facets = np.ascontiguousarray(np.vstack(np.divmod(code, nv)).astype(m.t.dtype))
    m._t2f = np.searchsorted(code, pairs[0].astype(np.int64) * nv + pairs[1]).reshape(-1, m.t.shape[1])


def _facet_pairs(m: skfem.Mesh) -> np.ndarray:
    """The node pairs (smaller first) of every triangle's facets, facet 0 of all triangles first: scikit-fem's
    ``np.sort(..., axis=0)`` of them, by an elementwise minimum and maximum (a sort of two-element columns
    costs a call per column)."""
    local = m.elem.refdom.facets
    return np.hstack([_in_order(m.t[i], m.t[j]) for i, j in local])


def _sorted_columns(t: np.ndarray) -> np.ndarray:
    """``np.sort(t, axis=0)`` of three rows, by a sorting network of elementwise minima and maxima."""
    low, high = np.minimum(t[0], t[1]), np.maximum(t[0], t[1])
    first, rest = np.minimum(low, t[2]), np.maximum(low, t[2])
    return np.vstack([first, np.minimum(high, rest), np.maximum(high, rest)])


def _in_order(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The pairs ``(a, b)`` as rows ``(min, max)``: ``np.sort(np.vstack([a, b]), axis=0)``, elementwise."""
    return np.vstack([np.minimum(a, b), np.maximum(a, b)])


def give_facets(m: skfem.Mesh) -> None:
    """Give ``m`` scikit-fem's facets and triangle-to-facet map (``Mesh.facets``, ``Mesh.t2f``: the same arrays)
    unless it has them: built by the counting sort of the node pairs instead of scikit-fem's ``np.unique`` of
    structured rows (a mesh from :func:`grid_mesh`, :func:`refine_marked` or a named copy of one has them)."""
    if "_facets" not in vars(m) or "_t2f" not in vars(m):
        _init_facets(m)


def give_facet_triangles(m: skfem.Mesh) -> None:
    """Give ``m`` scikit-fem's facet-to-triangle map (``Mesh.f2t``: per facet its first and last triangle in
    the order of ``t2f.flatten()``, -1 for the second of a boundary facet) unless it has it: the same array as
    ``Mesh.build_inverse`` makes, from one stable sort of the facet numbers instead of two ``np.unique``
    (2.8 against 6.0 ms at 7,375 nodes, 13 against 25 at 28,947)."""
    if hasattr(m, "_f2t"):
        return
    e = m.t2f.flatten(order="C")
    tix = np.tile(np.arange(m.t.shape[1]), m.t.shape[0])
    order = np.argsort(e, kind="stable")
    se = e[order]
    new = np.empty(se.size, bool)
    new[0] = True
    np.not_equal(se[1:], se[:-1], out=new[1:])
    starts = np.flatnonzero(new)
    ends = np.append(starts[1:], se.size) - 1
    inverse = np.zeros((2, int(se[-1]) + 1), dtype=np.int32)
    inverse[0, se[starts]] = tix[order[starts]]
    inverse[1, se[starts]] = tix[order[ends]]
    inverse[1, np.nonzero(inverse[0] == inverse[1])[0]] = -1
    m._f2t = inverse


def _unique_columns(key: np.ndarray, n: int, inverse: bool = False):
    """``np.unique(key, axis=1, return_counts=True)`` (and ``return_inverse``) for columns of node indices
    below ``n``, on one integer per column (sorting a structured view is several times slower)."""
    rows = key.shape[0]
    if n ** rows >= 2 ** 62:
        return np.unique(key, axis=1, return_inverse=inverse, return_counts=True)
    code = np.zeros(key.shape[1], np.int64)
    for r in range(rows):
        code = code * n + key[r].astype(np.int64)
    out = np.unique(code, return_inverse=inverse, return_counts=True)
    cols, rest = out[0], out[1:]
    unique = np.empty((rows, cols.size), dtype=key.dtype)
    for r in range(rows - 1, -1, -1):
        cols, unique[r] = np.divmod(cols, n)
    return (unique, *rest)


def check_triangles(points: np.ndarray, triangles: np.ndarray, name: str = "mesh") -> None:
    """Refuse degenerate, duplicated and overlapping triangles.

    Parameters
    ----------
    points : ndarray, shape (2, n)
    triangles : ndarray, shape (3, m)
        Vertex indices.
    name : str
        For the messages.

    Raises
    ------
    bearingfe.geometry.geofiles.GeometryFileError
        A triangle of zero area (relative to its longest edge squared,
        below 1e-10), the same three vertices used twice, or an edge shared
        by more than two triangles.
    """
    a, b, c = (points[:, triangles[k]] for k in range(3))
    area = 0.5 * np.abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    longest = np.max([np.hypot(*(b - a)), np.hypot(*(c - b)), np.hypot(*(a - c))], axis=0)
    flat = np.nonzero(~(area > 1e-10 * longest**2))[0]
    if flat.size:
        k = int(flat[0])
        raise GeometryFileError(
            f"{name}: {flat.size} degenerate (zero-area) triangle(s), e.g. triangle {k} at "
            f"({a[0, k]:.6g}, {a[1, k]:.6g}); remesh the surface")
    key = _sorted_columns(triangles)
    unique, counts = _unique_columns(key, points.shape[1])
    if np.any(counts > 1):
        k = int(np.argmax(counts > 1))
        raise GeometryFileError(
            f"{name}: {int(np.sum(counts - 1))} duplicated triangle(s) (same three nodes), e.g. nodes "
            f"{unique[:, k].tolist()}; a mesh must cover each point of the surface once")
    edges = np.hstack([_in_order(triangles[i], triangles[j]) for i, j in ((0, 1), (1, 2), (2, 0))])
    opposite = np.concatenate([triangles[2], triangles[0], triangles[1]])
    _, inverse, shared = _unique_columns(edges, points.shape[1], inverse=True)
    if np.any(shared > 2):
        raise GeometryFileError(
            f"{name}: {int(np.sum(shared > 2))} edge(s) shared by more than two triangles (overlapping "
            f"triangles); a mesh must cover each point of the surface once")
    # the two triangles on an inner edge lie on opposite sides of it (else they overlap)
    p0, p1, pc = points[:, edges[0]], points[:, edges[1]], points[:, opposite]
    side = np.sign((p1[0] - p0[0]) * (pc[1] - p0[1]) - (p1[1] - p0[1]) * (pc[0] - p0[0]))
    inverse = np.ravel(inverse)
    order = np.argsort(inverse, kind="stable")
    pairs = shared[inverse[order]] == 2
    first = order[pairs][0::2]
    second = order[pairs][1::2]
    folded = int(np.sum(side[first] * side[second] > 0))
    if folded:
        raise GeometryFileError(
            f"{name}: {folded} inner edge(s) with both triangles on the same side (folded or overlapping "
            f"triangles); a mesh must cover each point of the surface once")


#: Boundaries where the pressure is fixed (Dirichlet): the outline and the pockets.
DIRICHLET = ("outer", "inlet")


def check_support_mesh(mesh: skfem.Mesh, name: str = "mesh", *, triangles: bool = True,
                       components: bool = True) -> None:
    """Refuse a mesh no solver can use, whoever built it (a file, gmsh, the API).

    Parameters
    ----------
    mesh : skfem.MeshTri1 or skfem.MeshTri2
        Nodes in the flat ``(phi, z)`` plane [-], with a boundary named ``outer``.
    name : str
        For the messages.
    triangles : bool
        Run :func:`check_triangles` (default). False only for a mesh valid
        by construction whose cells were checked otherwise (a tensor grid on
        increasing grid lines, :func:`grid_mesh`): the per-triangle check
        sorts every edge, half the time of meshing a large grid.
    components : bool
        Search the connected components (default). False only for a mesh
        connected by construction whose every piece touches ``outer`` (a
        tensor grid without holes, :func:`grid_mesh`).

    Raises
    ------
    bearingfe.geometry.geofiles.GeometryFileError
        Not a triangle mesh, coordinates not 2-D or not finite, degenerate,
        duplicated or overlapping triangles (:func:`check_triangles`), no
        boundary named ``outer``, or a piece of the mesh (a connected
        component) that touches no Dirichlet boundary (``outer``, ``inlet``):
        its pressure would be fixed by round-off only.
    """
    if not isinstance(mesh, (skfem.MeshTri1, skfem.MeshTri2)):
        raise GeometryFileError(f"{name}: a support mesh must be a scikit-fem MeshTri1 or MeshTri2, "
                                f"got {type(mesh).__name__}")
    p = np.asarray(mesh.p)
    if p.ndim != 2 or p.shape[0] != 2:
        raise GeometryFileError(f"{name}: node coordinates must be 2-D (phi, z), got shape {p.shape}")
    if not np.all(np.isfinite(p)):
        raise GeometryFileError(f"{name}: node coordinates are not finite")
    nv = int(mesh.nvertices)
    t = np.asarray(mesh.t[:3], dtype=np.int64)
    if triangles:
        check_triangles(p[:, :nv], t, name)
    boundaries = mesh.boundaries or {}
    if "outer" not in boundaries:
        raise GeometryFileError(f"{name}: no boundary named 'outer' (the outline, where the pressure is fixed)")
    if components:
        _check_components(mesh, t, nv, boundaries, name)


def _check_components(mesh: skfem.Mesh, t: np.ndarray, nv: int, boundaries: dict, name: str) -> None:
    """Every connected piece of the mesh must touch a Dirichlet boundary (:data:`DIRICHLET`)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    rows = np.concatenate([t[0], t[1], t[2]])
    cols = np.concatenate([t[1], t[2], t[0]])
    graph = coo_matrix((np.ones(rows.size), (rows, cols)), shape=(nv, nv))
    count, label = connected_components(graph, directed=False)
    if count == 1:
        return
    facets = np.concatenate([np.asarray(boundaries[b], dtype=np.int64) for b in DIRICHLET if b in boundaries])
    fixed = np.unique(label[np.asarray(mesh.facets)[:, facets].ravel()]) if facets.size else np.zeros(0, int)
    free = np.setdiff1d(np.unique(label[np.unique(t)]), fixed)
    if free.size:
        k = int(np.flatnonzero(label == free[0])[0])
        raise GeometryFileError(
            f"{name}: {free.size} detached piece(s) of the mesh touch no boundary where the pressure is fixed "
            f"({' or '.join(DIRICHLET)}), e.g. the one with the node at ({mesh.p[0, k]:.6g}, {mesh.p[1, k]:.6g}); "
            f"their pressure would be set by round-off: remove them or name their outline")


def strip_mesh(n: int, *, length: float = 1.0, width: float | None = None, rows: int = 2) -> SupportMesh:
    """A structured strip ``[0, length] x [-width/2, width/2]`` for 1-D film problems on the 2-D solvers.

    Only the two ends carry fixed pressure (``outer`` = ``arc_start`` + ``arc_end``);
    the long sides are left free, i.e. closed to flow (the natural condition
    ``q . n = 0``), so a film that varies along ``phi`` only gives the 1-D
    solution. Nodes sit at ``phi = k length / n``, so steps of the film at such
    abscissae lie on element edges.

    Parameters
    ----------
    n : int
        Number of cells along the strip, >= 2.
    length : float
        Strip length along ``phi`` [-], > 0.
    width : float, optional
        Strip width [-], > 0; default ``rows * length / n`` (square cells).
    rows : int
        Number of cells across, >= 1.
    """
    if not (isinstance(n, int) and n >= 2):
        raise ValueError(f"n must be an integer >= 2, got {n!r}")
    if not (isinstance(rows, int) and rows >= 1):
        raise ValueError(f"rows must be an integer >= 1, got {rows!r}")
    length = _checked_size(length, "length")
    width = rows * length / n if width is None else _checked_size(width, "width")
    m = skfem.MeshTri1.init_tensor(np.linspace(0.0, length, n + 1), np.linspace(-width / 2, width / 2, rows + 1))
    facets = m.boundary_facets()
    x = m.p[0, m.facets[:, facets]].mean(axis=0)
    tol = 1e-9 * length
    bnd = {"arc_start": facets[np.abs(x) < tol], "arc_end": facets[np.abs(x - length) < tol]}
    bnd["outer"] = np.concatenate([bnd["arc_start"], bnd["arc_end"]])
    again = functools.partial(strip_mesh, 2 * n, length=length, width=width, rows=2 * rows)
    return SupportMesh(mesh=with_named_boundaries(m, bnd), surface=None, size=length / n, source="strip",
                       refinement=again)


def grid_mesh(surface: Surface, size: float, *, size_z: float | None = None,
              max_elements: int | None = None, column_width: Callable | None = None) -> SupportMesh:
    """A structured mesh of a rectangular surface, aligned with the sliding direction ``phi``.

    Cells of at most ``size`` along ``phi`` and ``size_z`` along ``z``, each
    split into two triangles. The grid lines pass through the edges of the
    pockets, which must be rectangles aligned with the axes (axial grooves,
    hydrostatic recesses fed at their pressure): between consecutive pocket
    edges the lines are uniform, and the cells inside a pocket are left out
    (a hole, as in :func:`mesh_surface`). Recess contours are NOT on element
    edges: the film is integrated exactly over the cells and faces they cut
    (see ``couette="grid"`` in :func:`bearingfe.film.finite_volume.solve_jfo`,
    where the mass-conserving solver carries the Couette flux along the grid
    lines, free of crosswind smearing). Boundaries are named as by
    :func:`mesh_surface`: ``arc_start``, ``arc_end``, ``side``, ``outer`` and
    ``inlet``, ``inlet_0``, ... on the pocket contours, or on a periodic
    surface ``side`` = ``outer`` and the seam ``periodic_start`` /
    ``periodic_end``. Meshing takes milliseconds (no gmsh). Recesses should be
    wider than a cell: a contour is located exactly along each cell face
    only where it crosses an eighth of the face at most once.

    Parameters
    ----------
    surface : Surface
        Default rectangular outline; pockets (``inlets``) axis-aligned
        rectangles (their contours must lie on element edges to carry their
        pressure; other pocket shapes: use :func:`mesh_surface`).
    size : float
        Largest cell length along ``phi`` [-], > 0.
    size_z : float, optional
        Largest cell length along ``z`` [-], > 0; default ``size``.
    max_elements : int, optional
        Largest number of triangles (as in :func:`mesh_surface`).
    column_width : callable, optional
        Graded columns: ``column_width(phi)`` (vectorized) is the wanted
        column width [-] along ``phi``, in ``(0, size]``; between consecutive
        pocket edges the columns equidistribute it (e.g. narrow where a
        journal's film is thin). Default: uniform columns of at most ``size``.

    Returns
    -------
    SupportMesh
        ``source="grid"``.
    """
    if not isinstance(surface, Surface):
        raise ValueError(f"surface must be a bearingfe.Surface, got {type(surface).__name__}")
    if not surface.is_rectangular:
        raise ValueError("grid_mesh needs the default rectangular outline (Surface(outer=None)); "
                         "use mesh_surface for other outlines")
    pockets = [_axis_rectangle(shape, k) for k, shape in enumerate(surface.inlets)]
    size = _checked_size(size, "size")
    size_z = size if size_z is None else _checked_size(size_z, "size_z")
    a1, a2 = surface.arc
    a = surface.half_width
    if column_width is None:
        xs = _grid_lines([a1, a2] + [x for r in pockets for x in r[:2]], size)
    else:
        xs = _graded_lines([a1, a2] + [x for r in pockets for x in r[:2]], size, column_width, max_elements)
    if xs.size < 3:   # at least two cells along phi
        xs = np.linspace(a1, a2, 3)
    zs = _grid_lines([-a, a] + [z for r in pockets for z in r[2:]], size_z)
    check_element_count(2.0 * (xs.size - 1) * (zs.size - 1), max_elements,
                        what=f"grid_mesh with size = {size:g}, size_z = {size_z:g}")
    return _grid_on_lines(surface, xs, zs, tuple(pockets), max_elements)


def _halved(lines: np.ndarray) -> np.ndarray:
    """Grid coordinates with the midpoint of every interval added: each cell split in two."""
    return np.sort(np.concatenate([lines, 0.5 * (lines[:-1] + lines[1:])]))


def _grid_on_lines(surface: Surface, xs: np.ndarray, zs: np.ndarray, pockets: tuple,
                   max_elements: int | None) -> SupportMesh:
    """The grid mesh of :func:`grid_mesh` on the grid lines ``xs`` (phi) and ``zs`` (z), pockets left out.

    Its ``refinement`` is the same grid with every cell split in two along each axis (the pocket
    edges stay on grid lines), for the once-refined load-error estimate.
    """
    check_element_count(2.0 * (xs.size - 1) * (zs.size - 1), max_elements, what="grid_mesh refined")
    m = skfem.MeshTri1.init_tensor(xs, zs)
    if pockets:
        m = _without_pockets(m, pockets)
        _init_facets(m)
    else:
        _tensor_facets(m, xs.size, zs.size)
    bnd = _surface_boundaries(m, surface, pockets)
    again = functools.partial(_grid_on_lines, surface, _halved(xs), _halved(zs), pockets, max_elements)
    valid = _grid_cells_valid(xs, zs)   # else check_triangles names the fault
    grid = SupportMesh(mesh=with_named_boundaries(m, bnd), surface=surface,
                       size=float(max(np.diff(xs).max(), np.diff(zs).max())), source="grid", refinement=again,
                       cells_checked=valid, connected=valid and not pockets)   # a whole grid is one piece
    if valid and not pockets:
        lines = (np.array(xs, float), np.array(zs, float))
        grid.cached(TENSOR_LINES, lambda: lines)
    return grid


#: Key of :func:`tensor_lines` in a grid mesh's cache (:meth:`SupportMesh.cached`).
TENSOR_LINES = "meshing.tensor_lines"


def tensor_lines(mesh: SupportMesh) -> tuple[np.ndarray, np.ndarray] | None:
    """The grid lines ``(phi, z)`` (increasing, read-only by convention) of a whole tensor grid made by
    :func:`grid_mesh` without pockets, kept on it where it was made; None for any other mesh (pockets, another
    maker, a mesh that travelled through pickle: its cache stays behind).

    On such a grid of ``nx`` by ``nz`` lines, node ``iz + nz ix`` lies at ``(phi[ix], z[iz])`` and the cell
    ``c = iz + (nz - 1) ix`` is split into the triangles ``c`` and ``c + (nx - 1)(nz - 1)``
    (``skfem.MeshTri1.init_tensor``'s numbering), each of whose corners span the whole cell."""
    return mesh._cache.get(TENSOR_LINES)


def _tensor_facets(m: skfem.MeshTri1, nx: int, nz: int) -> None:
    """Give the tensor mesh ``m`` (``skfem.MeshTri1.init_tensor`` on ``nx`` by ``nz`` lines, nothing removed)
    the facets and triangle-to-facet map of :func:`_init_facets` (the same arrays), in closed form: node
    ``k = iz + nz ix`` starts the facets to ``k + 1`` (up), ``k + nz`` (right) and ``k + nz + 1`` (the
    diagonal), in this lexicographic order, those that exist. No sort: 0.8 against 1.9 ms CPU at 71 x 71 lines,
    5.6 against 23 ms at 201 x 201 (mean of 20)."""
    nv = nx * nz
    k = np.arange(nv, dtype=np.int64)
    up, right = k % nz < nz - 1, k // nz < nx - 1
    has = np.stack([up, right, up & right], axis=1)             # (nv, 3): the facets node k starts
    second = np.stack([k + 1, k + nz, k + nz + 1], axis=1)[has]
    first = np.repeat(k, has.sum(axis=1))
    start = np.cumsum(has.sum(axis=1)) - has.sum(axis=1)        # the first facet node k starts
    t = m.t
    local = m.elem.refdom.facets
    a = np.hstack([t[i] for i, _ in local]).astype(np.int64)
    b = np.hstack([t[j] for _, j in local]).astype(np.int64)
    lo, step = np.minimum(a, b), np.abs(a - b)
    place = start[lo] + np.where(step == 1, 0, np.where(step == nz, up[lo], up[lo] + right[lo].astype(np.int64)))
    m._facets = np.ascontiguousarray(np.vstack([first, second]).astype(t.dtype))
    m._t2f = place.reshape(len(local), t.shape[1])


def _grid_cells_valid(xs: np.ndarray, zs: np.ndarray) -> bool:
    """Whether every triangle of the tensor grid on the lines ``xs``, ``zs`` (each cell split in two, pockets
    cut out whole cells) passes :func:`check_triangles`: lines strictly increasing (no duplicated or overlapping
    triangles) and each half cell's area above ``1e-10`` times its longest edge (the diagonal) squared."""
    dx, dz = np.diff(xs), np.diff(zs)
    if not (np.all(np.isfinite(dx)) and np.all(np.isfinite(dz)) and np.all(dx > 0) and np.all(dz > 0)):
        return False
    # 0.5 dx dz > 1e-10 (dx^2 + dz^2) is worst at the most elongated cell: check the extreme ratios
    ratio = max(dx.max() / dz.min(), dz.max() / dx.min())
    return bool(0.5 > 1e-10 * (ratio + 1.0 / ratio))


def _surface_boundaries(m: skfem.MeshTri1, surface: Surface, pockets) -> dict[str, np.ndarray]:
    """The boundary facets of a straight mesh of a rectangular surface, named by where they lie (as
    :func:`grid_mesh` names them); ``pockets``: the ``(phi_lo, phi_hi, z_lo, z_hi)`` of the holes."""
    a1, a2 = surface.arc
    a = surface.half_width
    give_facet_triangles(m)   # the map boundary_facets reads, without scikit-fem's two np.unique
    facets = m.boundary_facets()
    mid = m.p[:, m.facets[:, facets]].mean(axis=1)
    tol = 1e-9 * max(a2 - a1, 2 * a)
    start, end = facets[np.abs(mid[0] - a1) < tol], facets[np.abs(mid[0] - a2) < tol]
    side = facets[np.abs(np.abs(mid[1]) - a) < tol]
    if surface.periodic:
        bnd = {"outer": side, "side": side, "periodic_start": start, "periodic_end": end}
    else:
        bnd = {"outer": np.concatenate([start, end, side]), "arc_start": start, "arc_end": end, "side": side}
    if pockets:
        edge = [facets[_on_rectangle(mid, r, tol)] for r in pockets]
        bnd["inlet"] = np.concatenate(edge)
        bnd.update({f"inlet_{k}": e for k, e in enumerate(edge)})
    return bnd


def name_surface_boundaries(m: skfem.MeshTri1, surface: Surface, *, source: str = "grid",
                            cells_checked: bool = False, connected: bool = False) -> SupportMesh:
    """A straight triangle mesh of a rectangular surface (e.g. a :func:`grid_mesh` refined locally by
    scikit-fem, which drops the named boundaries) with its boundaries named as :func:`grid_mesh` names them.

    Parameters
    ----------
    m : skfem.MeshTri1
        Covers the surface's rectangle with its axis-aligned rectangular pockets left out.
    surface : Surface
        Default rectangular outline, pockets axis-aligned rectangles.
    source : str
        Recorded as ``SupportMesh.source``.
    cells_checked : bool
        The triangles are valid by construction (e.g. :func:`refine_marked` of a checked mesh: conforming
        splits of valid triangles), so :func:`check_triangles` is skipped (as for :func:`grid_mesh`); the
        boundaries are checked as always.
    connected : bool
        Every connected piece of the mesh is known to touch a fixed-pressure boundary (e.g. :func:`refine_marked`
        of a support mesh that passed :func:`check_support_mesh`: the splits keep its pieces, on the same
        outline), so the connected components are not searched again.
    """
    if not surface.is_rectangular:
        raise ValueError("name_surface_boundaries needs the default rectangular outline (Surface(outer=None))")
    pockets = tuple(_axis_rectangle(shape, k) for k, shape in enumerate(surface.inlets))
    give_facets(m)  # scikit-fem's facets by the counting sort (the same arrays, a third of the time)
    p = m.p[:, m.t]
    edges = np.max([np.hypot(*(p[:, i] - p[:, j])) for i, j in ((0, 1), (1, 2), (2, 0))], axis=0)
    return SupportMesh(mesh=with_named_boundaries(m, _surface_boundaries(m, surface, pockets)), surface=surface,
                       size=float(edges.max()), source=source, cells_checked=bool(cells_checked),
                       connected=bool(connected))


def _graded_lines(breaks: list[float], size: float, width: Callable, max_elements: int | None) -> np.ndarray:
    """Grid coordinates through every break point with spacings about ``clip(width(x), 0, size)``:
    between consecutive breaks, the integral of ``1 / width`` (trapezoidal on a fine sampling) split evenly."""
    b = np.unique(np.asarray(breaks, float))
    span = b[-1] - b[0]
    b = b[np.concatenate([[True], np.diff(b) > 1e-9 * span])]
    pieces = []
    for x0, x1 in zip(b[:-1], b[1:]):
        x = np.linspace(x0, x1, max(65, math.ceil(4096 * (x1 - x0) / span)))
        w = np.minimum(np.asarray(width(x), float), size)
        if w.shape != x.shape or not np.all(np.isfinite(w) & (w > 0)):
            raise ValueError("column_width must return finite widths > 0 at every phi of the surface")
        count = np.concatenate([[0.0], np.cumsum(0.5 * (1 / w[1:] + 1 / w[:-1]) * np.diff(x))])
        check_element_count(2.0 * count[-1], max_elements, what="grid_mesh columns")
        n = max(1, math.ceil(count[-1] - 1e-9))
        pieces.append(np.interp(np.linspace(0.0, count[-1], n + 1), count, x)[:-1])
    return np.concatenate(pieces + [b[-1:]])


def _axis_rectangle(shape, k: int) -> tuple[float, float, float, float]:
    """``(phi_lo, phi_hi, z_lo, z_hi)`` of a pocket that is an axis-aligned rectangle.

    Raises
    ------
    ValueError
        For any other pocket shape (its contour would not lie on grid lines).
    """
    xy = shape.boundary()
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    scale = float(np.max(hi - lo))
    on_edge = np.minimum(np.abs(xy - lo[:, None]), np.abs(xy - hi[:, None])).min(axis=0)
    box = float(np.prod(hi - lo))
    if np.any(on_edge > 1e-9 * scale) or abs(shape.area - box) > 1e-9 * box:
        raise ValueError(f"grid_mesh takes pockets that are rectangles aligned with phi and z only "
                         f"(Surface.inlets[{k}] is {type(shape).__name__} {shape!r}): their edges lie on grid "
                         "lines; use mesh_surface for other pocket shapes")
    return float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1])


def _grid_lines(breaks: list[float], size: float) -> np.ndarray:
    """Grid coordinates through every break point, uniform between consecutive ones, spacing <= ``size``."""
    b = np.unique(np.asarray(breaks, float))
    span = b[-1] - b[0]
    b = b[np.concatenate([[True], np.diff(b) > 1e-9 * span])]
    pieces = [np.linspace(x0, x1, max(1, math.ceil((x1 - x0) / size - 1e-9)) + 1)[:-1] for x0, x1 in zip(b[:-1], b[1:])]
    return np.concatenate(pieces + [b[-1:]])


def _without_pockets(m: skfem.MeshTri1, pockets: list) -> skfem.MeshTri1:
    """The tensor mesh with the triangles inside the pockets removed (and their orphaned nodes)."""
    g = m.p[:, m.t].mean(axis=1)
    inside = np.zeros(m.t.shape[1], bool)
    for x0, x1, z0, z1 in pockets:
        inside |= (g[0] > x0) & (g[0] < x1) & (g[1] > z0) & (g[1] < z1)
    t = m.t[:, ~inside]
    used = np.unique(t)
    index = np.full(m.p.shape[1], -1, dtype=np.int64)
    index[used] = np.arange(used.size)
    return skfem.MeshTri1(np.ascontiguousarray(m.p[:, used]), np.ascontiguousarray(index[t]))


def _on_rectangle(mid: np.ndarray, rect: tuple[float, float, float, float], tol: float) -> np.ndarray:
    """Mask of the facet midpoints on the contour of the rectangle ``(phi_lo, phi_hi, z_lo, z_hi)``."""
    x0, x1, z0, z1 = rect
    in_x = (mid[0] > x0 - tol) & (mid[0] < x1 + tol)
    in_z = (mid[1] > z0 - tol) & (mid[1] < z1 + tol)
    return ((in_x & ((np.abs(mid[1] - z0) < tol) | (np.abs(mid[1] - z1) < tol)))
            | (in_z & ((np.abs(mid[0] - x0) < tol) | (np.abs(mid[0] - x1) < tol))))


def periodic_pairs(mesh: SupportMesh) -> tuple[np.ndarray, np.ndarray]:
    """Matching vertex pairs ``(start, end)`` across the seam of a periodic surface's mesh.

    Empty arrays for a mesh without the ``periodic_start``/``periodic_end`` boundaries.

    Raises
    ------
    ValueError
        If the seam nodes do not match one to one (same ``z``, ``phi`` one period apart).
    """
    bnd = mesh.boundaries
    if "periodic_start" not in bnd or "periodic_end" not in bnd:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    m = mesh.mesh
    start = np.unique(m.facets[:, bnd["periodic_start"]])
    end = np.unique(m.facets[:, bnd["periodic_end"]])
    start = start[np.argsort(m.p[1, start])]
    end = end[np.argsort(m.p[1, end])]
    tol = 1e-9 * max(1.0, float(np.ptp(m.p[0])))
    if start.size != end.size or np.abs(m.p[1, start] - m.p[1, end]).max(initial=0.0) > tol:
        raise ValueError("the periodic seam's nodes do not match one to one (the mesh is not periodic)")
    return start, end
