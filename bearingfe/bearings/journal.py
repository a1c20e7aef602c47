r"""Journal bearings with the same Reynolds machinery: performance, equilibrium, dynamic coefficients.

Coordinates and scales are the package's (``phi`` along the bore, ``z = Z/R``,
``h = H/c``, ``p = P c^2/(mu omega R^2)``, forces in ``mu omega R^4/c^2``).
A bearing of length ``L`` and diameter ``D = 2R`` has the half width
``a = L/(2R) = L/D`` in ``z``.

The journal centre sits at ``(x, y)`` (units of c) from the bore centre, so
the film is ``h = 1 - x cos(phi) - y sin(phi)`` = ``CosineFilm(eps, phi0)``
with ``eps = |(x, y)|`` and ``phi0`` (the line of largest film) opposite
the journal displacement. The journal surface moves towards ``+phi``
(``wedge = 1``).

Full bearing (``JournalBearing(pads=None)``): the Raimondi-Boyd 360-degree
bearing, with ``p = 0`` at the axial edges and along the line of largest
film, Swift-Stieber cavitation elsewhere. It is meshed once in the frame of
the line of centres (arc ``(0, 2 pi)`` from the largest film), where the
answer depends on ``eps`` only (by gmsh, or as a tensor-product mesh of the
unwrapped film, :func:`structured_journal_mesh`, which :func:`equilibrium`
can refine locally at the rupture front: ``rupture_size``, since the
dynamic coefficients' error comes from there). Partial arcs and several pads
(``pads=((start, end), ...)``) are meshed in the bearing frame, with axial
supply grooves as pockets at the supply pressure.

Chart variables (Raimondi & Boyd 1958), with ``W`` the load,
``P = W/(L D)``, ``N`` the speed [rev/s]:

- Sommerfeld number ``S = (R/c)^2 mu N / P = 2 a / (pi w)``, with ``w`` the
  non-dimensional load;
- attitude angle: between the load line and the line of centres;
- friction variable ``(R/c) f = friction / w``: the shear on the journal
  with the full-film Couette term over the whole clearance (as Petroff and
  Raimondi-Boyd count it), pressure term where the film is full;
- flow variable ``Q/(R c N L) = pi q / a`` with ``q`` the flow into the
  leading edge of the film, side-flow ratio ``Q_s/Q``;
- maximum-pressure ratio ``P/p_max = w / (4 a p_max)``.

Dynamic coefficients: ``K_ij = -d f_i/d x_j``, ``C_ij = -d f_i/d xdot_j``
with ``f`` the film force on the journal, by linearization of the discrete
Reynolds equation on the converged rupture set (direct form: the derivative
of ``int h^3 grad p . grad v`` is ``int 3 h^2 h_x grad p . grad v``, one
back-substitution per coefficient column with the factorization already
made) and, as a check, by central finite differences of the full nonlinear
solution. Non-dimensional as Lund's ``K c / W``, ``C c omega / W``.
"""

from __future__ import annotations

import itertools
import math
import threading
import time
import warnings
import weakref
from contextlib import nullcontext
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
import scipy.sparse as sp
import skfem
from scipy.spatial import cKDTree

from ..core.checks import ResolutionWarning
from ..cavitation import CavitationError, ObstacleProblem, obstacle, obstacle_problem, solve_cavitating
from ..cavitation.coarse import NESTED_MIN
from ..cavitation.swift_stieber import cold_mask, warm_mask
from ..core.compressed import compressed, csr_of, matvec
from ..core.linalg import SMALL_PANELS_UP_TO, dense_threads
from ..film import build_result
from ..film.superposition import source_weights
from ..film.thickness import CosineFilm
from ..geometry.surface import Rectangle, Surface
from ..film.finite_volume import solve_jfo
from ..geometry.geofiles import check_element_count
from ..geometry.locate import cell_diameters, values_in_cells
from ..geometry.meshing import (SupportMesh, give_facet_triangles, give_facets, grid_mesh, mesh_surface, split_parents,
                                name_surface_boundaries, refine_marked, refine_uniformly, with_named_boundaries)
from ..core.parameters import Discretization, takes
from ..film import forms
from ..core.parameters import ELEMENTS
from ..film import ReynoldsResult, load_error, load_order, operators, superpose

__all__ = [
    "Groove",
    "JournalBearing",
    "JournalPerformance",
    "DynamicCoefficients",
    "ResolutionWarning",
    "film_graded_size",
    "journal_mesh",
    "structured_journal_mesh",
    "structured_meshes",
    "performance",
    "equilibrium",
    "dynamic_coefficients",
    "short_bearing_force",
    "position_state",
    "force_derivatives",
    "EQUILIBRIUM_CAVITATION",
]

#: Cavitation models of :func:`equilibrium` (and so of its dynamic coefficients).
EQUILIBRIUM_CAVITATION = ("reynolds", "none", "jfo")

#: Eccentricity ratios beyond this are refused (contact in all but name).
EPS_MAX = 0.995


@dataclass(frozen=True)
class Groove:
    """Axial supply groove: a pocket at the supply pressure.

    Parameters
    ----------
    angle : float
        Centre angle in the bearing frame [rad].
    width : float
        Angular width [rad], > 0.
    length_fraction : float
        Groove length over bearing length, in (0, 1) (a groove must stay
        inside the film to be a pocket).
    """

    angle: float
    width: float
    length_fraction: float = 0.8

    def __post_init__(self) -> None:
        if not math.isfinite(self.angle):
            raise ValueError(f"Groove.angle must be finite, got {self.angle!r}")
        if not (math.isfinite(self.width) and 0 < self.width < math.pi):
            raise ValueError(f"Groove.width must be in (0, pi) rad, got {self.width!r}")
        if not (0 < self.length_fraction < 1):
            raise ValueError(f"Groove.length_fraction must be in (0, 1), got {self.length_fraction!r}")


@dataclass(frozen=True)
class JournalBearing:
    """Geometry of a plain journal bearing (non-dimensional).

    Parameters
    ----------
    length_ratio : float
        ``L/D`` [-], in [0.001, 4].
    pads : tuple of (float, float) or None
        ``None``: full 360-degree film starting at the line of largest film
        (Raimondi-Boyd). Otherwise arcs ``(start, end)`` [rad] in the
        bearing frame (a partial arc, or several pads; a 360-degree arc with
        its edges at a fixed axial groove line).
    grooves : tuple of Groove
        Supply grooves inside the pads (with ``pads``) or inside the periodic
        film (with ``periodic``).
    supply_pressure : float
        Groove pressure [-] (``P c^2/(mu omega R^2)``), >= 0.
    periodic : bool
        A full 360-degree film with no edge along the bore (``pads=None``):
        oil enters only through the grooves (at least one), partial-length
        pockets at ``supply_pressure``. Solved by the finite-volume scheme
        (``cavitation="jfo"``, or ``"reynolds"``/``"none"`` on the same
        discretization), meshed in the bearing frame like pads.
    """

    length_ratio: float
    pads: tuple | None = None
    grooves: tuple = ()
    supply_pressure: float = 0.0
    periodic: bool = False

    def __post_init__(self) -> None:
        if not (math.isfinite(self.length_ratio) and 1e-3 <= self.length_ratio <= 4):
            raise ValueError(f"length_ratio (L/D) must be in [0.001, 4] (shorter films are the short-bearing limit; "
                             f"1e-300 made a degenerate outline), got {self.length_ratio!r}")
        if self.pads is not None:
            pads = tuple((float(a), float(b)) for a, b in self.pads)
            for a, b in pads:
                if not a < b <= a + 2 * math.pi + 1e-12:
                    raise ValueError(f"pads: each arc needs start < end <= start + 2 pi, got {(a, b)}")
            object.__setattr__(self, "pads", pads)
        elif self.grooves and not self.periodic:
            raise ValueError("grooves need explicit pads or periodic=True (the Raimondi-Boyd full bearing has none)")
        if not isinstance(self.periodic, bool):
            raise ValueError(f"periodic must be True or False, got {self.periodic!r}")
        if self.periodic and (self.pads is not None or not self.grooves):
            raise ValueError("periodic=True needs pads=None and at least one groove (the only oil supply "
                             "of a film without edges along the bore)")
        if not (math.isfinite(self.supply_pressure) and self.supply_pressure >= 0):
            raise ValueError(f"supply_pressure must be >= 0, got {self.supply_pressure!r}")
        object.__setattr__(self, "grooves", tuple(self.grooves))

    @property
    def half_width(self) -> float:
        """``a = L/D`` (z is scaled by the radius) [-]."""
        return float(self.length_ratio)

    @property
    def raimondi_boyd(self) -> bool:
        """The full bearing cut at the line of largest film (``pads=None``, not periodic),
        meshed in the frame of the line of centres."""
        return self.pads is None and not self.periodic

    def _seam(self) -> float:
        """Angle of the periodic film's seam: the middle of the widest gap between grooves."""
        angles = np.sort(np.mod([g.angle for g in self.grooves], 2 * math.pi))
        gaps = np.diff(np.append(angles, angles[0] + 2 * math.pi))
        k = int(np.argmax(gaps))
        return float(angles[k] + gaps[k] / 2)

    def surfaces(self) -> tuple[Surface, ...]:
        """Support surfaces of the pads in the bearing frame (full bearing: one
        arc ``(0, 2 pi)`` in the frame of the line of largest film).

        Made once per bearing (cached): checking a surface's layout costs
        milliseconds, and the structured path meshes the pads at every remesh."""
        return _surfaces(self)


@lru_cache(maxsize=64)
def _surfaces(bearing: JournalBearing) -> tuple[Surface, ...]:
    """:meth:`JournalBearing.surfaces` (the bearing is frozen and hashable)."""
    a = bearing.half_width
    if bearing.periodic:
        seam = bearing._seam()
        pockets = tuple(Rectangle((_wrap_into(g.angle, seam), 0.0), (g.width, 2 * a * g.length_fraction))
                        for g in bearing.grooves)
        return (Surface(arc=(seam, seam + 2 * math.pi), half_width=a, inlets=pockets, periodic=True),)
    if bearing.pads is None:
        return (Surface(arc=(0.0, 2 * math.pi), half_width=a),)
    out = []
    for start, end in bearing.pads:
        pockets = tuple(Rectangle((_wrap_into(g.angle, start), 0.0), (g.width, 2 * a * g.length_fraction))
                        for g in bearing.grooves if start < _wrap_into(g.angle, start) < end)
        out.append(Surface(arc=(start, end), half_width=a, inlets=pockets))
    return tuple(out)


def _wrap_into(angle: float, start: float) -> float:
    return start + (angle - start) % (2 * math.pi)


# -- meshes ---------------------------------------------------------------------

def film_graded_size(film, size: float, min_size: float, exponent: float = 0.5):
    """Element-size function ``s(phi, z)`` for :func:`bearingfe.mesh_surface` driven by the film.

    ``s = clip(size * h^exponent, min_size, size)``: the thin-film pressure
    spike of a journal at eccentricity ``eps`` has a width of order
    ``sqrt(h_min)`` around the thinnest line, so ``exponent = 1/2`` keeps the
    number of elements across it fixed as ``eps -> 1``.

    Parameters
    ----------
    film : Film
    size, min_size : float
        Largest and smallest element size [-], ``0 < min_size <= size``.
    exponent : float
        In (0, 2].
    """
    if not (math.isfinite(size) and size > 0 and math.isfinite(min_size) and 0 < min_size <= size):
        raise ValueError(f"need 0 < min_size <= size, got size={size!r}, min_size={min_size!r}")
    if not (0 < exponent <= 2):
        raise ValueError(f"exponent must be in (0, 2], got {exponent!r}")

    def size_function(phi, z):
        h = np.asarray(film.thickness(np.asarray(phi, float), np.asarray(z, float)), float)
        return np.clip(size * np.maximum(h, 0.0) ** exponent, min_size, size)

    return size_function


def _cosine_graded_size(eps: float, phi0: float, size: float, min_size: float):
    """:func:`film_graded_size` of ``CosineFilm(eps, phi0)`` with exponent 1/2 in scalar arithmetic:
    gmsh calls it once per point (numpy's per-call overhead made it half the meshing time)."""
    CosineFilm(eps, phi0)  # the same argument checks

    def size_function(phi, z):
        h = 1.0 + eps * math.cos(float(phi) - phi0)
        return min(max(size * math.sqrt(max(h, 0.0)), min_size), size)

    return size_function


#: Digits to which a mesh's grading position (eccentricity ratio and line of largest film) is rounded
#: (:func:`grading_position`).
GRADING_DIGITS = 9


def grading_position(eps: float, phi0: float) -> tuple[float, float]:
    """The eccentricity ratio ``eps`` [-] and line of largest film ``phi0`` [rad] a mesh is graded for, rounded to
    :data:`GRADING_DIGITS` digits: the grading needs them to a few digits only, and a journal position that
    differs by round-off (another iteration path, another factorization order) then grades the same mesh to the
    last bit. Structured meshes need that: the refinement splits the longest edge of a triangle, and the
    isosceles halves of a split right triangle have two edges of one length, the longer of which round-off
    picks; loads 1e-14 apart (as another factorization order) gave the supply groove of part ``journal_pads``
    other refined meshes (size 0.2, rupture_size 0.05: 2,006 to 2,024 nodes, eps and the coefficients 1.5e-5
    apart)."""
    return round(float(eps), GRADING_DIGITS), round(float(phi0), GRADING_DIGITS)


@lru_cache(maxsize=32)
def _mesh(surface: Surface, size: float, min_size: float, eps: float, phi0: float, order: int) -> SupportMesh:
    graded = _cosine_graded_size(eps, phi0, size, min_size) if min_size < size else None
    return mesh_surface(surface, size, size_function=graded, min_size=min(min_size, size), order=order)


def journal_mesh(bearing: JournalBearing, size: float, *, min_size: float | None = None,
                 eps: float = 0.0, phi0: float = 0.0, order: int = 1) -> tuple[SupportMesh, ...]:
    """Meshes of the pads, graded towards the thinnest film of ``CosineFilm(eps, phi0)``.

    Meshes are cached on their arguments (the transient and the Newton
    iterations reuse them).

    Parameters
    ----------
    order : {1, 2}
        Geometry order (2: curved ``MeshTri2`` edges, for P2 on pads with
        curved pockets; the plain bore and rectangular grooves are exact with 1).
    """
    min_size = size if min_size is None else float(min_size)
    _check_order(order)
    # round-off in eps and phi0 (e.g. a load direction of cos(-pi/2) = 6e-17) gives the same (cached) mesh
    # instead of another gmsh mesh
    eps, phi0 = grading_position(eps, phi0)
    return tuple(_mesh(s, float(size), min_size, eps, phi0, int(order)) for s in bearing.surfaces())


def _check_order(order) -> None:
    if order not in (1, 2):
        raise ValueError(f"order (mesh geometry order) must be 1 or 2, got {order!r}")


def _check_element(element) -> None:
    if element not in ELEMENTS:
        raise ValueError(f"element must be one of {list(ELEMENTS)}, got {element!r}")


def _refined(bearing: JournalBearing, mesh: SupportMesh, size: float, min_size: float, eps: float,
             order: int) -> SupportMesh:
    """The error-estimate mesh: the uniform refinement (straight meshes) or a remesh at half the sizes."""
    if order == 1:
        return refine_uniformly(mesh)
    (fine,) = journal_mesh(bearing, size / 2, min_size=min_size / 2, eps=eps, order=order)
    return fine


def default_min_size(size: float, eps: float) -> float:
    """Smallest element size used by default: ``size * sqrt(1 - eps)`` (see :func:`film_graded_size`)."""
    return float(size * math.sqrt(max(1.0 - eps, 1e-4)))


# -- structured meshes of the full bearing ----------------------------------------------

def structured_journal_mesh(bearing: JournalBearing, size: float, *, min_size: float | None = None,
                            eps: float = 0.0) -> SupportMesh:
    """Tensor-product mesh of the unwrapped film of the full bearing (no gmsh).

    The rectangle ``(0, 2 pi) x (-a, a)`` of :meth:`JournalBearing.surfaces`
    (frame of the line of largest film, ``pads=None``) is cut into columns
    along ``phi`` and rows along ``z``, each rectangle into two triangles.
    Column widths follow :func:`film_graded_size` of ``CosineFilm(eps, 0)``
    (``size sqrt(h)`` clipped to ``[min_size, size]``); the rows are
    uniform, about ``size`` high. The straight edges are exact for the
    rectangle. Building it costs milliseconds where gmsh costs a tenth of a
    second or more; :func:`equilibrium` refines it locally at the rupture
    front (``rupture_size``).

    Parameters
    ----------
    bearing : JournalBearing
        With ``pads=None`` (not periodic).
    size : float
        Largest element size [-], in (0, 1].
    min_size : float, optional
        Smallest column width [-], in (0, size]; default
        :func:`default_min_size`.
    eps : float
        Eccentricity ratio of the grading, in ``[0, 0.995]``.

    Returns
    -------
    SupportMesh
        Boundaries ``outer``, ``arc_start``, ``arc_end``, ``side``; ``source = "structured"``.
    """
    if not bearing.raimondi_boyd:
        raise ValueError("structured meshes are for the full Raimondi-Boyd bearing (pads=None, not periodic)")
    if not (isinstance(size, (int, float)) and math.isfinite(size) and 0 < size <= 1):
        raise ValueError(f"size must be in (0, 1], got {size!r}")
    eps = _check_eps(eps)
    min_size = default_min_size(size, eps) if min_size is None else float(min_size)
    if not (math.isfinite(min_size) and 0 < min_size <= size):
        raise ValueError(f"min_size must be in (0, size = {size}], got {min_size!r}")
    a = bearing.half_width
    rows = max(2, math.ceil(2 * a / size - 1e-9))
    phis = _graded_columns(2 * math.pi, size, min_size, eps, rows)
    zs = np.linspace(-a, a, rows + 1)
    return _named_rectangle(skfem.MeshTri1.init_tensor(phis, zs), bearing.surfaces()[0], (0.0, 2 * math.pi), a)


def _graded_columns(length: float, size: float, min_size: float, eps: float, rows: int = 1) -> np.ndarray:
    """Column edges on ``[0, length]`` with widths about ``clip(size sqrt(1 + eps cos phi), min_size, size)``:
    equidistribution of the width function (its inverse integrated on a fine grid, then split evenly).
    The ``2 columns rows`` triangles are checked against the element limit before any is made."""
    x = np.linspace(0.0, length, 4097)
    width = np.clip(size * np.sqrt(np.maximum(1.0 + eps * np.cos(x), 0.0)), min_size, size)
    count = np.concatenate([[0.0], np.cumsum(0.5 * (1 / width[1:] + 1 / width[:-1]) * np.diff(x))])
    check_element_count(2.0 * count[-1] * rows, what=f"a structured journal mesh of size = {size:g}, "
                                                     f"min_size = {min_size:g}")
    n = max(2, math.ceil(count[-1] - 1e-9))
    phis = np.interp(np.linspace(0.0, count[-1], n + 1), count, x)
    phis[0], phis[-1] = 0.0, length
    return phis


def structured_meshes(bearing: JournalBearing, size: float, *, min_size: float | None = None, eps: float = 0.0,
                      phi0: float = 0.0) -> tuple[SupportMesh, ...]:
    """Tensor-product meshes of every film of ``bearing`` (no gmsh): the structured counterpart of
    :func:`journal_mesh`.

    The full Raimondi-Boyd bearing: :func:`structured_journal_mesh` (frame of the line of largest film,
    ``phi0`` unused). Pads, partial arcs and periodic films (bearing frame): :func:`bearingfe.grid_mesh`
    of each surface of :meth:`JournalBearing.surfaces`, with the axial grooves as rectangular pockets
    (their edges on grid lines) and, on a periodic film, the seam; the columns are graded towards the
    thinnest film of ``CosineFilm(eps, phi0)`` as :func:`film_graded_size` grades (``size sqrt(h)``
    clipped to ``[min_size, size]``), the rows uniform, about ``size`` high. Straight edges are exact
    for these rectangles, and on a tensor grid the finite-volume (JFO) solver carries the Couette flux
    along the grid lines (``couette="auto"`` of :func:`bearingfe.solve_jfo`).

    Parameters
    ----------
    bearing : JournalBearing
    size : float
        Largest element size [-], in (0, 1].
    min_size : float, optional
        Smallest column width [-], in (0, size]; default :func:`default_min_size`.
    eps, phi0 : float
        Eccentricity ratio in ``[0, 0.995]`` and line of largest film [rad] (bearing frame) of the grading.

    Returns
    -------
    tuple of SupportMesh
        One per pad (one for the full or periodic film).
    """
    if not (isinstance(size, (int, float)) and math.isfinite(size) and 0 < size <= 1):
        raise ValueError(f"size must be in (0, 1], got {size!r}")
    if bearing.raimondi_boyd:
        return (structured_journal_mesh(bearing, size, min_size=min_size, eps=eps),)
    eps = _check_eps(eps)
    if not math.isfinite(phi0):
        raise ValueError(f"phi0 must be finite, got {phi0!r}")
    min_size = default_min_size(size, eps) if min_size is None else float(min_size)
    if not (math.isfinite(min_size) and 0 < min_size <= size):
        raise ValueError(f"min_size must be in (0, size = {size}], got {min_size!r}")

    def width(phi):
        return np.clip(size * np.sqrt(np.maximum(1.0 + eps * np.cos(phi - phi0), 0.0)), min_size, size)
    return tuple(grid_mesh(s, size, column_width=width) for s in bearing.surfaces())


def _named_rectangle(m: skfem.MeshTri1, surface: Surface, phis: tuple[float, float], a: float,
                     cells_checked: bool = False, connected: bool = False) -> SupportMesh:
    """A mesh of the rectangle ``phis x (-a, a)`` with the boundaries of :func:`structured_journal_mesh`;
    ``cells_checked``, ``connected``: its triangles are valid, its pieces touch the outline by construction (see
    :func:`~bearingfe.geometry.meshing.name_surface_boundaries`). Its facets and their triangles are built as
    meshing builds them (scikit-fem's arrays: a counting sort and one stable sort instead of scikit-fem's
    ``np.unique`` calls), or taken from the mesh (:func:`~bearingfe.geometry.meshing.refine_marked` built them)."""
    give_facets(m)
    give_facet_triangles(m)
    facets = m.boundary_facets()
    mid = m.p[:, m.facets[:, facets]].mean(axis=1)
    tol = 1e-9 * (phis[1] - phis[0])
    bnd = {"arc_start": facets[np.abs(mid[0] - phis[0]) < tol], "arc_end": facets[np.abs(mid[0] - phis[1]) < tol],
           "side": facets[np.abs(np.abs(mid[1]) - a) < tol]}
    bnd["outer"] = np.sort(np.concatenate(list(bnd.values())))
    return SupportMesh(mesh=with_named_boundaries(m, bnd), surface=surface, size=float(cell_diameters(m).max()),
                       source="structured", cells_checked=cells_checked, connected=connected)


def _reformation_elements(res: ReynoldsResult, front: np.ndarray) -> np.ndarray:
    """The elements of ``front`` (:func:`_front_elements`) on a boundary where the film forms again (a full film
    fed from a supply pocket or a pad's trailing part, downstream of a ruptured zone), not where it ruptures: the
    ruptured dofs within :data:`REFORMATION_REACH` element diameters lie upstream of the others there (their
    mean ``phi`` is smaller; the journal surface moves towards ``+phi``)."""
    out = np.zeros_like(front)
    if not front.any():
        return out
    mesh = res.basis.mesh
    centres = mesh.p[:, mesh.t].mean(axis=1)[:, front].T
    hits = _dof_tree(res.basis).query_ball_point(centres, REFORMATION_REACH * cell_diameters(mesh)[front])
    owner = np.repeat(np.arange(len(hits)), [len(h) for h in hits])
    dofs = np.concatenate([np.asarray(h, int) for h in hits])
    ruptured = np.asarray(res.cavitated, bool)[dofs]
    phi = np.asarray(res.basis.doflocs)[0][dofs]

    def mean_phi(mask):  # per front element: the mean phi of its dofs in mask, and their number
        count = np.bincount(owner[mask], minlength=len(hits))
        return np.bincount(owner[mask], weights=phi[mask], minlength=len(hits)) / np.maximum(count, 1), count
    (phi_r, n_r), (phi_f, n_f) = mean_phi(ruptured), mean_phi(~ruptured)
    out[front] = (n_r > 0) & (n_f > 0) & (phi_r < phi_f)
    return out


def _front_elements(res: ReynoldsResult) -> np.ndarray:
    """Elements holding the discrete rupture front: a ruptured dof and a positive pressure, with a vertex
    shared with a full-film element (a positive pressure and no ruptured dof). P2 leaves isolated small
    positive values (of order 1e-5 of the largest pressure) behind the front, among ruptured dofs only;
    the last condition skips them."""
    dofs = res.basis.element_dofs
    positive = np.any(np.asarray(res.pressure)[dofs] > 0, axis=0)
    ruptured = np.any(res.cavitated[dofs], axis=0)
    t = res.basis.mesh.t[:3]
    full = np.zeros(res.basis.mesh.nvertices, bool)
    full[t[:, positive & ~ruptured].ravel()] = True
    return ruptured & positive & np.any(full[t], axis=0)


# -- one journal position --------------------------------------------------------

@dataclass(frozen=True, eq=False)
class _State:
    """Solutions of all pads at one journal position (bearing frame)."""

    results: tuple[ReynoldsResult, ...]
    sups: tuple
    force: np.ndarray          # on the shoe/bore = applied load on the journal at equilibrium
    rotation: float            # mesh frame -> bearing frame angle
    joined: "_Joined | None" = None  # the films' joined obstacle problem, when they were solved as one
    #: per film, the derivatives of its interior unknowns in the journal's (x, y, xdot, ydot) on its rupture set
    #: (columns; (x, y) alone after a Newton step's linearization), once :func:`_linearized` made them: the next
    #: Newton position's rupture set is predicted from them
    perturbations: list = field(default_factory=list)


def _check_eps(eps: float) -> float:
    eps = float(eps)
    if not (math.isfinite(eps) and 0 <= eps <= EPS_MAX):
        raise ValueError(f"eccentricity ratio must be in [0, {EPS_MAX}], got {eps!r} "
                         "(beyond it the film is thinner than any mesh resolves; the journal touches)")
    return eps


def _rot(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def _solve_state(bearing: JournalBearing, meshes, x: float, y: float, cavitation: str,
                 squeeze_xy=(0.0, 0.0), rotation: float = 0.0, warm_start=None, element: str = "P1") -> _State:
    """Solve all pads for a journal at ``(x, y)`` in the frame of the meshes, moving at ``squeeze_xy``;
    ``warm_start``: a previous state (its results, one per pad, on any mesh) or one start per pad (a result
    or a rupture mask of all dofs) to start the rupture sets from."""
    eps = math.hypot(x, y)
    phi0 = math.atan2(-y, -x) if eps > 0 else 0.0
    film = CosineFilm(eps, phi0)
    xd, yd = squeeze_xy
    # dh/dt = -xd cos phi - yd sin phi = gamma_rate cos(phi - phi0) + gamma phi0_rate sin(phi - phi0)
    gamma_rate = -(xd * math.cos(phi0) + yd * math.sin(phi0))
    phi0_rate = (xd * math.sin(phi0) - yd * math.cos(phi0)) / eps if eps > 0 else 0.0
    if eps == 0 and (xd or yd):
        raise ValueError("squeeze velocities at eps = 0 need a finite eccentricity (use eps >= 1e-6)")
    results, sups, force = [], [], np.zeros(2)
    warm = ((None,) * len(meshes) if warm_start is None else
            warm_start.results if isinstance(warm_start, _State) else tuple(warm_start))
    squeeze = (gamma_rate, phi0_rate)
    notes = ()
    if cavitation == "reynolds" and not any(m.needs_finite_volumes for m in meshes):
        # the Galerkin films (the full bearing's one, or the pads') from rupture sets, or small ones from none (the
        # cold start of solve_cavitating below NESTED_MIN unknowns): one active-set iteration over all of them,
        # with lazy results (a Newton step reads the force and the rupture sets; the flows are built when read)
        sups = [superpose(mesh, film, formulation="direct", element=element, lazy=True) for mesh in meshes]
        if not all(w is not None or sup.system.interior.size < NESTED_MIN for w, sup in zip(warm, sups)):
            sups = None
    if sups:
        try:
            results, joined = _solve_joined(sups, [source_weights(1.0, squeeze, bearing.supply_pressure
                                                                  if m.has_inlet else 0.0) for m in meshes], warm)
        except CavitationError as exc:  # pad by pad, each with the fallbacks of solve_cavitating
            notes = (f"cavitation: the pads' joined active-set iteration failed ({exc}); solved pad by pad",)
        else:
            force = np.sum([res.force for res in results], axis=0)
            return _State(results=tuple(results), sups=tuple(sups), force=_rot(rotation) @ force,
                          rotation=rotation, joined=joined)
    sups = []
    for mesh, previous in zip(meshes, warm):
        ps = bearing.supply_pressure if mesh.has_inlet else 0.0
        if cavitation == "jfo" or mesh.needs_finite_volumes:  # finite volumes: no Galerkin system
            res = solve_jfo(mesh, film, wedge=1.0, squeeze=squeeze, inlet_pressure=ps,
                            cavitation=cavitation, warm_start=previous)
            results.append(res)
            sups.append(None)
            force += res.force
            continue
        sup = superpose(mesh, film, formulation="direct", element=element, lazy=True)
        if cavitation == "none":
            res = sup.combine(1.0, squeeze, ps)
        else:
            res = solve_cavitating(sup, 1.0, squeeze, ps, model=cavitation, warm_start=previous)
        if notes:
            res = replace(res, notes=res.notes + notes)
        results.append(res)
        sups.append(sup)
        force += res.force
    return _State(results=tuple(results), sups=tuple(sups), force=_rot(rotation) @ force, rotation=rotation)


@dataclass(frozen=True, eq=False)
class _Joined:
    """The obstacle problems of several films as one block-diagonal problem (:func:`_solve_joined`)."""

    problem: ObstacleProblem
    films: tuple  # the films' FilmProblem, in the order of the blocks
    offsets: np.ndarray  # block k holds the unknowns offsets[k]:offsets[k + 1]

    def split(self, v: np.ndarray) -> list[np.ndarray]:
        return [v[a:b] for a, b in zip(self.offsets[:-1], self.offsets[1:])]

    def solve_fixed(self, rhs: list[np.ndarray], active: list[np.ndarray]) -> list[np.ndarray]:
        """:meth:`FilmProblem.solve_fixed` of every film at once (one factorization of the joined free set):
        the interior nodal unknowns per film."""
        b = np.concatenate([r if fp.change is None else matvec(fp.change_transposed, r)
                            for fp, r in zip(self.films, rhs)])
        v = self.problem.solve_fixed(b, np.concatenate(active))
        return [fp.unknowns(x) for fp, x in zip(self.films, self.split(v))]


def _block_diagonal(blocks) -> sp.csr_matrix:
    """The block-diagonal CSR matrix of square CSR blocks, by concatenating their arrays (``sp.block_diag``
    goes through COO and costs about a millisecond more per Newton step at a few hundred unknowns), made by
    :func:`~bearingfe.core.compressed.compressed` on ``int32`` indices (the index type scipy's constructor
    chooses for them) without scipy's checks."""
    blocks = [csr_of(b) for b in blocks]
    sizes = np.array([b.shape[0] for b in blocks])
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    nnz = np.concatenate([[0], np.cumsum([b.nnz for b in blocks])])
    n = int(offsets[-1])
    index = np.int32 if max(n, int(nnz[-1])) < 2**31 - 1 else np.int64
    indptr = np.concatenate([np.zeros(1, index)] + [b.indptr[1:] + z for b, z in zip(blocks, nnz[:-1])],
                            dtype=index)
    indices = np.concatenate([b.indices + o for b, o in zip(blocks, offsets[:-1])], dtype=index)
    data = np.concatenate([b.data for b in blocks])
    return compressed(data, indices, indptr, (n, n))


#: The last few joined patterns of :func:`_joined_pattern`: ``(weak references to the films' patterns' index
#: arrays, joined pattern)``, newest last.
_JOINED_PATTERNS: list = []
_JOINED_LOCK = threading.Lock()
#: Joined patterns kept (the film states of one set of meshes share one; an equilibrium's refinement levels are
#: a few sets).
JOINED_PATTERNS_KEPT = 4


def _joined_pattern(patterns) -> sp.csr_matrix:
    """The block diagonal of the films' patterns (:func:`_block_diagonal`), which orders the joined problem's
    factorizations by its sparsity pattern alone: kept for the last :data:`JOINED_PATTERNS_KEPT` sets of
    patterns, found again when every film's pattern holds the same index arrays (the film states of a mesh hold
    its compiled operator's, see :meth:`~bearingfe.film.compiled.CompiledOperator.condensed`). Its values are
    those of the first film state it was made for. Up to :data:`~bearingfe.cavitation.obstacle.BLOCKS_UP_TO`
    unknowns, as the orders found from it are kept (above, each state's problem finds its own order, and a kept
    pattern would hold memory for nothing)."""
    if sum(p.shape[0] for p in patterns) > obstacle.BLOCKS_UP_TO:
        return _block_diagonal(patterns)
    arrays = [a for p in patterns for a in (p.indptr, p.indices)]
    with _JOINED_LOCK:  # film states solved in threads share the list
        for refs, joined in _JOINED_PATTERNS:
            if len(refs) == len(arrays) and all(r() is a for r, a in zip(refs, arrays)):
                return joined
    joined = _block_diagonal(patterns)
    with _JOINED_LOCK:
        _JOINED_PATTERNS.append(([weakref.ref(a) for a in arrays], joined))
        del _JOINED_PATTERNS[:-JOINED_PATTERNS_KEPT]
    return joined


def _solve_joined(sups, weights, warm) -> tuple[list[ReynoldsResult], _Joined]:
    """Swift-Stieber solutions of several films (pads of one bearing) by one primal-dual active-set iteration on
    their block-diagonal system: one factorization of the joined free set per iteration and one count of
    iterations (the largest any film needs, not their sum); one :class:`ReynoldsResult` per film.

    ``warm``: one warm start per film (a result on any mesh of its surface, or a rupture mask of its dofs), or
    None for the cold start of :func:`~bearingfe.cavitation.swift_stieber.cold_mask` (films below
    :data:`~bearingfe.cavitation.coarse.NESTED_MIN` unknowns; the results are then lazy too, where
    ``solve_cavitating`` builds the flows of every film); the full-film start of every film is its
    superposition's own factorization (as for one film)."""
    t0 = time.perf_counter()
    films = tuple(obstacle_problem(sup) for sup in sups)
    sizes = [fp.problem.n for fp in films]
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    orders = [fp.problem.order for fp in films]
    order = (np.concatenate([o + a for o, a in zip(orders, offsets)]) if all(o is not None for o in orders)
             else None)
    one = len(films) == 1  # the film's own matrix and pattern (a block diagonal of one block copies them)
    problem = ObstacleProblem(films[0].problem.A if one else _block_diagonal([fp.problem.A for fp in films]),
                              films[0].problem.factorize, tol=films[0].problem.tol,
                              max_iterations=films[0].problem.max_iterations, order=order,
                              factor_settled=True,  # every state is linearized on its rupture sets
                              pattern=films[0].problem.pattern if one else
                              _joined_pattern([fp.problem.pattern for fp in films]))
    joined = _Joined(problem=problem, films=films, offsets=offsets)

    def full_film(b, joined=joined):
        return np.concatenate([fp.problem.solve_fixed(x, np.zeros(x.shape[0], bool))
                               for fp, x in zip(films, joined.split(b))])

    problem.add_factorization(np.ones(problem.n, bool), full_film)
    b = np.concatenate([fp.right_side(w) for fp, w in zip(films, weights)])
    start = np.concatenate([cold_mask(fp, sup, w) if s is None else warm_mask(fp, sup, w, s)
                            for fp, sup, w, s in zip(films, sups, weights, warm)])
    with dense_threads(1) if problem.n <= SMALL_PANELS_UP_TO else nullcontext():
        sol = problem.solve(b, start)
    cost = {"cavitation": time.perf_counter() - t0, "cavitation_factorizations": float(sol.factorizations)}
    results = []
    for fp, sup, w, v, active in zip(films, sups, weights, joined.split(sol.u), joined.split(sol.active)):
        cavitated = np.zeros(sup.operators.n_dofs, bool)
        cavitated[fp.interior] = active
        results.append(build_result(sup, sup.system.full(fp.unknowns(v), w), w, None, cavitation="reynolds",
                                    iterations=sol.iterations, cavitated=cavitated, extra_cost=cost, lazy=True))
    return results, joined


def position_state(bearing: JournalBearing, meshes, x: float, y: float, cavitation: str, *,
                   velocity=(0.0, 0.0), warm_start=None, element: str = "P1") -> _State:
    """The films of ``meshes`` (pads of ``bearing``) with the journal at ``(x, y)`` [c] moving at
    ``velocity`` [c omega], in the bearing frame: the one film solve every journal result is built on.

    Returns the state whose ``force`` [mu omega R^4/c^2] is the film force on the bore and whose
    ``results`` hold one :class:`~bearingfe.film.ReynoldsResult` per mesh; ``warm_start``: a previous
    state to start the rupture sets from. Films of other bearings that are a journal at an effective
    position (a tilted or preloaded pad) are solved through it.
    """
    if cavitation not in EQUILIBRIUM_CAVITATION:
        raise ValueError(f"cavitation must be one of {EQUILIBRIUM_CAVITATION}, got {cavitation!r}")
    _check_element(element)
    return _solve_state(bearing, meshes, float(x), float(y), cavitation, squeeze_xy=tuple(velocity),
                        warm_start=warm_start, element=element)


def force_derivatives(state: _State) -> tuple[np.ndarray, np.ndarray]:
    """``dF/d(x, y)`` [mu omega R^4/c^3] and ``dF/d(xdot, ydot)`` of the film force on the bore of a
    :func:`position_state` (bearing frame), linearized on its rupture sets; Galerkin solves only
    (``cavitation`` ``"reynolds"`` or ``"none"``, no finite-volume surface)."""
    if any(sup is None for sup in state.sups):
        raise ValueError("force_derivatives needs the Galerkin system; finite-volume solutions "
                         "(cavitation='jfo', periodic or recessed surfaces) have none")
    dFx, dFv = _linearized(state)
    R = _rot(state.rotation)
    return R @ dFx @ R.T, R @ dFv @ R.T


def _stiffness(bearing: JournalBearing, meshes, state: _State, xy, cavitation: str,
               step: float = 1e-6) -> np.ndarray:
    """``dF/d(x, y)`` in the mesh frame: linearized on the rupture sets, or (finite-volume solves,
    which keep no Galerkin system) by forward differences warm-started from ``state``."""
    if all(sup is not None for sup in state.sups):
        return _linearized(state, velocity=False)[0]
    K = np.zeros((2, 2))
    base = state.force
    for j in range(2):
        d = np.zeros(2)
        d[j] = step
        moved = _solve_state(bearing, meshes, *(np.asarray(xy, float) + d), cavitation, rotation=state.rotation,
                             warm_start=state)
        K[:, j] = _rot(-state.rotation) @ (moved.force - base) / step
    return K


def _lumped_area(res: ReynoldsResult) -> np.ndarray:
    return forms.load.assemble(res.basis, f=np.ones_like(res.basis.dx))


_POSITION_SOURCES: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def _position_sources(co) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """What :func:`_linearized` needs of a mesh alone (its compiled operator ``co``), kept per operator:
    ``dh/d(x, y) = (-cos phi, -sin phi)`` at the quadrature points ``(2, n_q)`` (from the operator's own cosines
    and sines, the same numbers as ``cos`` of its points) and the derivatives of the sources in the journal
    position, ``int 6 dh/d(x, y) dv/dphi`` and ``-int 12 dh/d(x, y) v`` ``(n_dofs, 2)`` each: they depend on the
    film's shape only through ``h``'s position derivatives, which do not depend on the position. A mesh is
    linearized one to three times in an equilibrium (its coarse Newton steps, a refinement level's step, the
    last Newton step and the coefficients): 0.64 ms a call at 2,159 P2 dofs (two_groove's refined pads; CPU
    time, 300 repetitions) for the sources, 0.28 ms for the cosines and sines of the points."""
    kept = _POSITION_SOURCES.get(co)
    if kept is None:
        cos, sin = co.angles
        slopes = -np.stack([np.ravel(cos), np.ravel(sin)])
        dx = co.dx
        kept = (slopes, co.maps.integrate_gradient((6.0 * dx * slopes).T, 0),
                co.maps.integrate_value((-12.0 * dx * slopes).T))
        for a in kept:  # shared by every film state of the mesh
            a.flags.writeable = False
        _POSITION_SOURCES[co] = kept
    return kept


def _linearized(state: _State, velocity: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
    """``dF/d(x, y)`` and ``dF/d(xdot, ydot)`` of the force on the bore by
    differentiating the discrete equation on the fixed rupture sets; ``velocity=False``: ``dF/d(x, y)`` alone
    (and None), the stiffness of a Newton step, whose two squeeze perturbations are then neither solved nor
    integrated (:attr:`_State.perturbations` get the two position columns, all that :func:`_predicted_rupture`
    reads). Each column is solved and integrated on its own, so the position derivatives are the same numbers
    either way.

    By the per-element maps of the mesh (:mod:`bearingfe.film.compiled`): the derivative
    matrices applied to ``p``, the source integrals and the loads are mat-vecs at the
    quadrature points; no matrix is assembled per Newton step.
    """
    dF = np.zeros((2, 4))
    systems = []
    for res, sup in zip(state.results, state.sups):
        if res.cavitation == "gumbel":
            raise ValueError("linearization is defined for cavitation='reynolds' or 'none'")
        co = sup.operators.compiled
        m, dx = co.maps, co.dx
        h = np.asarray(sup.at.h, float).reshape(-1)
        slopes, wedge, squeeze = _position_sources(co)
        p = res.pressure
        # A(h) p = int 6 h dv/dphi - int 12 dh/dt v (the wedge in conservative form); differentiate in
        # x, y, xdot, ydot. dA/dx p = int 3 h^2 dh/dx grad p . grad v; the wedge source's derivative is
        # -int 6 (dh/dx) dv/dphi. All by the per-element maps (mat-vecs, no matrix assembled)
        grad_p = (m.gradient(p, 0).ravel(), m.gradient(p, 1).ravel())
        weights = (3.0 * dx * h**2) * slopes  # (2, n_q): dx 3 h^2 dh/d(x, y)
        dA_p = m.integrate_gradient((weights * grad_p[0]).T, 0) + m.integrate_gradient((weights * grad_p[1]).T, 1)
        fp = obstacle_problem(sup)
        rhs = (np.column_stack([wedge - dA_p, squeeze]) if velocity else wedge - dA_p)[fp.interior]
        active = res.cavitated[fp.interior] if res.cavitated is not None else np.zeros(fp.interior.size, bool)
        systems.append((co, fp, rhs, active))
    if state.joined is not None:  # the films' perturbations on one factorization of the joined free set
        solved = state.joined.solve_fixed([r for _, _, r, _ in systems], [a for _, _, _, a in systems])
    else:
        solved = [fp.solve_fixed(rhs, active) for _, fp, rhs, active in systems]
    state.perturbations[:] = solved
    for (co, fp, _, _), U in zip(systems, solved):
        u = np.zeros((co.n_dofs, U.shape[1]))
        u[fp.interior] = U
        # int p' (cos phi, sin phi) of the four (or two) perturbations (einsum's loops: no threaded BLAS wait)
        dF[:, :U.shape[1]] += np.einsum("kq,qs->ks", co.loads[:2], co.maps.values(u))
    return dF[:, :2], (dF[:, 2:] if velocity else None)


# -- results ------------------------------------------------------------------

@dataclass(frozen=True)
class JournalPerformance:
    """Raimondi-Boyd chart variables of a full journal bearing at one eccentricity.

    Attributes
    ----------
    eps : float
        Eccentricity ratio [-].
    sommerfeld : float
        ``S = (R/c)^2 mu N / P`` [-] (``inf`` at ``eps = 0``).
    attitude : float
        Attitude angle [deg] (at ``eps = 0`` its limit ``eps -> 0``).
    friction_variable : float
        ``(R/c) f`` [-].
    flow_variable : float
        ``Q / (R c N L)`` [-].
    side_flow_ratio : float
        ``Q_s / Q`` [-].
    max_pressure_ratio : float
        ``P / p_max`` [-].
    load : float
        Non-dimensional load ``w`` [mu omega R^4 / c^2].
    max_pressure : float
        Largest film pressure [mu omega R^2 / c^2].
    h_min : float
        Smallest film thickness [c].
    cavitated_fraction : float
        Area of the ruptured region over the film area [-] (lumped nodal
        areas): the free boundary's convergence measure.
    iterations : int
        Active-set iterations of the cavitation solve.
    n_nodes : int
        Mesh nodes (of the finest mesh used).
    error_estimate : float
        Relative change of the load between the mesh and its uniform
        refinement (NaN if not estimated); the reported values are those
        of the refined mesh, whose error it overstates by about ``2^k - 1``
        (3 for P1).
    load_error : float
        Estimated relative error of the reported (refined) load: the change
        Richardson-scaled at the known order
        (:attr:`bearingfe.film.estimate.LoadError.refined_relative`; NaN if
        not estimated). Estimate over true error 0.99 to 1.01 on the
        journals of docs/validation.md.
    attitude_error : float
        Change of the attitude angle under the refinement [deg].
    seconds : float
        Wall time [s].
    """

    eps: float
    sommerfeld: float
    attitude: float
    friction_variable: float
    flow_variable: float
    side_flow_ratio: float
    max_pressure_ratio: float
    load: float
    max_pressure: float
    h_min: float
    cavitated_fraction: float
    iterations: int
    n_nodes: int
    error_estimate: float = math.nan
    attitude_error: float = math.nan
    seconds: float = 0.0
    load_error: float = math.nan


def _chart(bearing: JournalBearing, res: ReynoldsResult, eps: float, n_nodes: int) -> JournalPerformance:
    a = bearing.half_width
    F = res.force
    w = float(np.hypot(*F))
    # journal displaced towards phi = pi (frame of the largest film at phi = 0): line of centres (-1, 0)
    attitude = math.degrees(math.atan2(abs(F[1]), -F[0]))
    q_in = -res.flows["arc_start"]
    pressure = res.pressure
    rupture = 0.0
    if res.cavitated is not None and res.cavitated.any():
        lumped = _lumped_area(res)
        rupture = float(lumped[res.cavitated].sum() / lumped.sum())
    pmax = float(pressure.max())
    return JournalPerformance(
        eps=eps, sommerfeld=2 * a / (math.pi * w) if w > 0 else math.inf, attitude=attitude,
        friction_variable=res.friction / w if w > 0 else math.inf,
        flow_variable=math.pi * q_in / a, side_flow_ratio=res.flows["side"] / q_in,
        max_pressure_ratio=w / (4 * a * pmax) if pmax > 0 else math.nan, load=w, max_pressure=pmax,
        h_min=res.h_min, cavitated_fraction=rupture, iterations=res.iterations, n_nodes=n_nodes)


@takes(Discretization, rename={"mesh_size": "size"})
def performance(bearing: JournalBearing, eps: float, *, size: float = 0.08, min_size: float | None = None,
                cavitation: str = "reynolds", estimate_error: bool = False,
                error_tolerance: float = 0.02, element: str = "P1", order: int = 1) -> JournalPerformance:
    """Chart variables of a full (Raimondi-Boyd) bearing at eccentricity ``eps``.

    Parameters
    ----------
    bearing : JournalBearing
        With ``pads=None``.
    eps : float
        Eccentricity ratio in ``[0, 0.995]``. At ``eps = 0`` the load is zero
        (``S = inf``) and the attitude is its limit, evaluated at ``eps = 1e-6``
        (the pressure is linear in ``eps`` there).
    size, min_size : float
        Element sizes [-]; by default ``min_size = size sqrt(1 - eps)`` at the
        thinnest film (:func:`film_graded_size`). Or ``discretization=`` a
        :class:`bearingfe.core.parameters.Discretization` with ``mesh_size`` and
        ``min_size`` (its other fields stay at their defaults: the journal
        solves choose their own element, form and solver).
    cavitation : {"reynolds", "gumbel", "none", "jfo"}
        ``"jfo"``: mass-conserving cavitation (:mod:`bearingfe.film.finite_volume`); its
        friction counts the Couette shear on the oil fraction ``theta`` only.
    estimate_error : bool
        Also solve on the uniformly refined mesh and report the relative
        change of the load (values returned are the refined ones). The
        refined solve starts from the coarse rupture set (nested iteration),
        so it needs a few active-set iterations whatever the mesh.
    error_tolerance : float
        With ``estimate_error``: a :class:`ResolutionWarning` is issued if
        the estimate exceeds it.
    element : {"P1", "P2"}
        Finite element (P2: third-order load error on smooth films, see
        docs/benchmarks.md).
    order : {1, 2}
        Mesh geometry order (:func:`journal_mesh`); the error estimate of an
        order-2 mesh remeshes at half the sizes instead of splitting it.
    """
    if not bearing.raimondi_boyd:
        raise ValueError("performance() is for the full Raimondi-Boyd bearing (pads=None, not periodic); "
                         "use equilibrium() for pads and partial arcs")
    eps = _check_eps(eps)
    if cavitation not in ("reynolds", "gumbel", "none", "jfo"):
        raise ValueError(f"cavitation must be 'reynolds', 'gumbel', 'none' or 'jfo', got {cavitation!r}")
    _check_element(element)
    _check_order(order)
    start = time.perf_counter()
    e = max(eps, 1e-6)
    min_size = default_min_size(size, e) if min_size is None else float(min_size)
    (mesh,) = journal_mesh(bearing, size, min_size=min_size, eps=e, order=order)
    state = _solve_state(bearing, (mesh,), -e, 0.0, cavitation, element=element)
    res = state.results[0]
    perf = _chart(bearing, res, e, mesh.n_nodes)
    extra = {}
    if estimate_error:
        fine = _refined(bearing, mesh, size, min_size, e, order)
        # nested iteration: the coarse rupture set starts the fine one (bounded active-set count)
        warm = state if cavitation in ("reynolds", "jfo") else None
        res_f = _solve_state(bearing, (fine,), -e, 0.0, cavitation, warm_start=warm, element=element).results[0]
        perf_f = _chart(bearing, res_f, e, fine.n_nodes)
        err = abs(perf_f.load - perf.load) / perf_f.load
        scheme = "finite-volume" if cavitation == "jfo" else "finite-element"
        estimate = load_error(res, res_f, order=load_order(scheme, element))
        extra = dict(error_estimate=err, attitude_error=abs(perf_f.attitude - perf.attitude),
                     load_error=estimate.refined_relative)
        perf = perf_f
        if err > error_tolerance:
            warnings.warn(ResolutionWarning(
                f"eps = {eps:.4g}: the load changes by {100 * err:.2g} % under mesh refinement "
                f"(h_min = {1 - e:.3g}, smallest element {min_size:.3g}): the thin-film pressure peak "
                f"is not resolved; use a smaller min_size"), stacklevel=2)
    if eps == 0:
        extra.update(sommerfeld=math.inf, load=0.0, max_pressure=0.0, friction_variable=math.inf, eps=0.0,
                     max_pressure_ratio=math.nan)
    return JournalPerformance(**{**perf.__dict__, **extra, "seconds": time.perf_counter() - start})


# -- equilibrium -------------------------------------------------------------------

@dataclass(frozen=True)
class Equilibrium:
    """Static equilibrium of the journal under a load.

    Attributes
    ----------
    eps : float
        Eccentricity ratio [-].
    attitude : float
        Angle from the load line to the line of centres [deg].
    position : ndarray, shape (2,)
        Journal centre in the bearing frame [c].
    force : ndarray, shape (2,)
        Film force on the bore (= applied load on the journal) [mu omega R^4/c^2].
    newton_iterations : int
    residual : float
        ``|force - load| / |load|``.
    active_set_iterations : int
        Cavitation active-set iterations summed over all film solves of the
        Newton iteration (each one a sparse factorization at most).
    element : str
        Finite element of the solution.
    """

    eps: float
    attitude: float
    position: np.ndarray
    force: np.ndarray
    newton_iterations: int
    residual: float
    active_set_iterations: int = 0
    element: str = "P1"
    state: _State = field(repr=False, compare=False, default=None)
    meshes: tuple = field(repr=False, compare=False, default=())
    bearing: JournalBearing | None = field(repr=False, compare=False, default=None)


def _short_force(eps: float, a: float) -> np.ndarray:
    """:func:`short_bearing_force` at zero velocity in closed form (the first guesses need it a dozen times;
    the quadrature costs a millisecond each): ``int_0^pi sin cos / h^3 = -2 eps / (1 - eps^2)^2`` and
    ``int_0^pi sin^2 / h^3 = pi / (2 (1 - eps^2)^(3/2))`` give ``(-8 a^3 eps^2 / (1 - eps^2)^2,
    2 pi a^3 eps / (1 - eps^2)^(3/2))``."""
    q = 1.0 - eps * eps
    return np.array([-8.0 * a**3 * eps * eps / q**2, 2.0 * math.pi * a**3 * eps / q**1.5])


def _short_force_and_stiffness(xy: np.ndarray, a: float) -> tuple[np.ndarray, np.ndarray]:
    """The short bearing's force on the bore [mu omega R^4/c^2] and its stiffness ``dF/d(x, y)`` [per c] with the
    journal at ``xy`` (any frame, ``0 < |xy| < 1``): :func:`_short_force` turned with the line of centres, and its
    derivative along the line of centres (``dF/deps`` of the closed form) and across it (the force turning with
    it, ``J F / eps``)."""
    e = float(np.hypot(*xy))
    q = 1.0 - e * e
    u = np.asarray(xy, float) / e  # the journal's displacement direction
    R = np.array([[-u[0], u[1]], [-u[1], -u[0]]])  # the mesh frame (journal at (-eps, 0)) -> this frame
    F = R @ _short_force(e, a)
    dF = R @ np.array([-16.0 * a**3 * e * (1.0 + e * e) / q**3, 2.0 * math.pi * a**3 * (1.0 + 2.0 * e * e) / q**2.5])
    turned = np.array([-F[1], F[0]]) / e
    return F, np.outer(dF, u) + np.outer(turned, [-u[1], u[0]])


def _short_guess(load: np.ndarray, a: float) -> np.ndarray:
    """Journal position [c] at which the short (Ocvirk) bearing carries ``load`` (eps kept in [0.05, 0.95]): the
    first guess of the structured paths (:func:`_short_eps` in closed form, the force turned onto the load)."""
    e = min(max(_short_eps(float(np.hypot(*load)), a), 0.05), 0.95)
    F = _short_force(e, a)
    return _rot(math.atan2(load[1], load[0]) - math.atan2(F[1], F[0])) @ np.array([-e, 0.0])


def _calibrated_guess(xy: np.ndarray, force: np.ndarray, K: np.ndarray, load: np.ndarray,
                      a: float) -> np.ndarray | None:
    """A first guess corrected by one film solve: the position where the short bearing, scaled and offset to
    match that solve, carries ``load`` (None if the fit or its inversion fails).

    The film force is modelled as ``c F_short(x, y) + F_0``: ``c`` [-] fits the solve's stiffness ``K`` to the
    short bearing's (least squares over the four entries), ``F_0`` is the force the scaled short bearing leaves
    unexplained at ``xy`` (a supply pocket's push, the pressure lost at a pad edge); the model is then inverted
    in closed form (:func:`_short_guess` of ``(load - F_0) / c``). It keeps the short bearing's growth of the
    load with eps, which a Newton step from a guess far below the answer lacks: on the supply groove of part
    ``journal_pads`` (pocket fed at 0.5 over a 360-degree pad cut at -60 degrees) the guess moves from eps 0.556
    to 0.725 (answer 0.761), where a Newton step reaches 0.671."""
    F_short, K_short = _short_force_and_stiffness(xy, a)
    c = float(np.sum(K * K_short) / np.sum(K_short * K_short))
    if not (math.isfinite(c) and c > 0):
        return None
    target = (np.asarray(load, float) - (np.asarray(force, float) - c * F_short)) / c
    try:
        return _short_guess(target, a)
    except ValueError:  # the model asks for more than the short bearing carries (or nothing at all)
        return None


def _short_eps(load: float, a: float, closed_form: bool = True) -> float:
    """Eccentricity of the short (Ocvirk) bearing under a non-dimensional load: first guess. ``closed_form``:
    from :func:`_short_force`, else from the quadrature of :func:`short_bearing_force` (the gmsh path's guess
    as it was: see :func:`_eps_step`)."""
    from scipy.optimize import brentq

    def f(e):
        return float(np.hypot(*(_short_force(e, a) if closed_form else short_bearing_force(e, a)))) - load
    if f(0.99) < 0:
        capacity = load + f(EPS_MAX)
        if load > 2.0 * capacity:  # the short bearing overestimates a finite one: this load needs eps > EPS_MAX
            raise ValueError(f"load: magnitude {load:.3g} (non-dimensional) is more than twice what the short-bearing "
                             f"estimate carries at eccentricity {EPS_MAX} ({capacity:.3g}): the film would close; "
                             f"give a smaller load (or a larger speed, viscosity or bearing)")
        return 0.99
    if f(1e-9) >= 0:  # brentq would answer "f(a) and f(b) must have different signs"
        raise ValueError(f"load: magnitude {load:.3g} (non-dimensional) is below what the bearing carries at "
                         f"eccentricity 1e-9 ({load + f(1e-9):.3g}): the journal sits centred to round-off; "
                         f"give a larger load")
    return float(brentq(f, 1e-9, 0.99))


@takes(Discretization, rename={"mesh_size": "size"})
def equilibrium(bearing: JournalBearing, load, *, size: float = 0.08, min_size: float | None = None,
                cavitation: str = "reynolds", tol: float = 1e-8, max_newton: int = 40, element: str = "P1",
                order: int = 1, warm_start: bool = True, structured: bool = False,
                rupture_size: float | None = None) -> Equilibrium:
    """Journal position that carries a load, by Newton's method with the linearized stiffness.

    Parameters
    ----------
    bearing : JournalBearing
    load : (float, float)
        Applied load on the journal in the bearing frame [mu omega R^4/c^2];
        for the full bearing only its magnitude and direction matter.
    size, min_size : float
        Element sizes (the mesh is graded for the first guess and regenerated
        once if the answer moved by more than 0.02 in eps; a structured mesh
        if that changes its smallest element size by more than 10 %); or
        ``discretization=`` as in :func:`performance`.
    cavitation : {"reynolds", "none", "jfo"}
        With ``"jfo"`` (and for periodic bearings) the stiffness of the
        Newton steps comes from forward differences of warm-started solves.
    tol : float
        Relative tolerance on the force balance.
    max_newton : int
    element : {"P1", "P2"}
    order : {1, 2}
        Mesh geometry order (:func:`journal_mesh`).
    warm_start : bool
        Start each cavitation solve from the rupture set of the previous
        Newton step (and, after a remesh, from the previous mesh's, carried
        over): the active-set iteration then only corrects the free boundary
        by the step's motion. ``False`` starts every solve afresh (where the
        linear solution is negative); the answers agree to the active-set
        tolerance. The Galerkin films (the full bearing's, or the pads') are
        solved as one (one active-set iteration on their block-diagonal
        system), with one result per film whose flows are built when read.
    structured : bool
        Mesh with :func:`structured_meshes` (graded tensor-product meshes,
        no gmsh) instead of :func:`journal_mesh`: the full bearing's
        unwrapped film (:func:`structured_journal_mesh`), or
        :func:`bearingfe.grid_mesh` of every pad with the axial grooves as
        rectangular pockets (pads and partial arcs: Newton in ``(x, y)``,
        the meshes graded for the first guess, remeshed once if the answer's
        thinnest film moved), or of the periodic film with its seam (solved
        by finite volumes with the grid Couette flux).
    rupture_size : float, optional
        ``structured=True``, ``cavitation="reynolds"``, not periodic:
        element size [-] at the rupture front, in ``(0, size]``. After
        Newton on the structured meshes (to ``max(tol, COARSE_TOL)``), the
        elements near the discrete rupture front of every film are split
        (conforming red-green-blue refinement), one level at a time, each
        level solved once at that position from the previous level's
        rupture sets, until the front lies in elements no longer than
        ``rupture_size`` (on a pad whose largest pressure is a fraction
        ``f`` of the bearing's largest, ``rupture_size min(1/f, 5)``: a
        lightly loaded pad's front weighs less on the coefficients; where the
        film forms again, e.g. upstream of a supply pocket, ``5 rupture_size``
        at least; a front closer than 0.75 behind its zone's pressure peak
        smaller, and a full film running into a pad's downstream edge gets
        a refined band there: :func:`zone_ends`), each
        level solved at a Newton step on from the level before; then Newton
        to ``tol`` on those meshes (the returned ``meshes``, which
        :func:`dynamic_coefficients` reuses). The coefficients are
        linearized on the converged rupture set; their error is set by how
        well the mesh resolves the front (the pressure gradient has a kink
        there), while that of the position is set by ``size``. Use it with
        ``element="P2"``: ``size = 0.2, rupture_size = 0.04`` put eps and
        the eight coefficients within 5e-4 of converged references on plain
        bearings of L/D 0.25 and 0.5 at eps 0.3 to 0.8, many times faster
        than a uniform mesh of that accuracy (docs/benchmarks.md, part
        ``journal``: errors and times of other settings there), and within
        1e-3 on two-groove bearings, a partial arc and a pad with a supply
        groove (part ``journal_pads``).

    Raises
    ------
    RuntimeError
        If Newton does not converge, or the load needs ``eps > 0.995``.
    """
    load = np.asarray(load, float)
    if load.shape != (2,) or not np.all(np.isfinite(load)) or not np.hypot(*load) > 0:
        raise ValueError(f"load must be a finite non-zero pair, got {load!r}")
    if cavitation not in EQUILIBRIUM_CAVITATION:
        raise ValueError(f"cavitation must be one of {EQUILIBRIUM_CAVITATION}, got {cavitation!r}")
    _check_element(element)
    _check_order(order)
    _check_structured(bearing, structured, rupture_size, size, cavitation, order)
    opts = _Solves(cavitation=cavitation, element=element,
                   warm=bool(warm_start) and cavitation in ("reynolds", "jfo"))
    w = float(np.hypot(*load))
    eps = min(max(_short_eps(w, bearing.half_width, closed_form=structured), 0.05), 0.95)
    theta_load = math.atan2(load[1], load[0])
    if bearing.raimondi_boyd:
        mesher = _Mesher(bearing, size, min_size, order, structured)
        return _equilibrium_full(bearing, w, theta_load, eps, mesher, opts, tol, max_newton, rupture_size)
    xy = eps * np.array([math.cos(theta_load), math.sin(theta_load)])
    if structured:
        xy, state, k, res, meshes = _equilibrium_structured(bearing, load, size, min_size, opts, tol,
                                                            max_newton, rupture_size)
    else:
        for _ in range(2):
            ms = default_min_size(size, np.hypot(*xy)) if min_size is None else min_size
            meshes = journal_mesh(bearing, size, min_size=ms, eps=float(np.hypot(*xy)),
                                  phi0=math.atan2(-xy[1], -xy[0]), order=order)
            xy, state, k, res = _newton_xy(bearing, meshes, xy, load, opts, tol, max_newton)
            if min_size is not None:
                break
    e = float(np.hypot(*xy))
    att = math.degrees(abs(_angle_between(theta_load, math.atan2(xy[1], xy[0]))))
    return Equilibrium(eps=e, attitude=att, position=xy, force=state.force, newton_iterations=k,
                       residual=res, active_set_iterations=opts.iterations, element=element, state=state,
                       meshes=meshes, bearing=bearing)


@dataclass
class _Solves:
    """Film solves of one equilibrium: options, the warm start and the active-set count."""

    cavitation: str
    element: str
    warm: bool
    previous: _State | None = None
    iterations: int = 0
    at: tuple | None = None  # the journal position of ``previous`` (mesh frame)

    def solve(self, bearing: JournalBearing, meshes, x: float, y: float, start=None) -> _State:
        """``start``: rupture masks (one per pad) to start from instead of the previous state. The previous
        state's rupture sets are turned with the line of centres (:func:`_turn`) when it turned and, once it was
        linearized (a Newton step's stiffness), joined by the dofs its linearization predicts ruptured at
        ``(x, y)`` (:func:`_predicted_rupture`)."""
        warm = start if start is not None else self.previous if self.warm else None
        if start is None and warm is not None and self.at is not None and self.cavitation == "reynolds":
            turn = _turn(self.at, (x, y))
            same = all(r.basis.mesh is m.mesh for r, m in zip(warm.results, meshes))
            previous = warm
            if turn and same:
                warm = tuple(_turned_in_place(r, turn) for r in warm.results)
            step = np.array([x - self.at[0], y - self.at[1]])
            if same and previous.perturbations and np.hypot(*step) <= PREDICTED_STEP * (1 - np.hypot(*self.at)):
                warm = _predicted_rupture(previous, warm.results if isinstance(warm, _State) else warm, step)
        state = _solve_state(bearing, meshes, x, y, self.cavitation, element=self.element, warm_start=warm)
        # solved as one (joined): one active-set iteration for all films, each result carries its count
        self.iterations += state.results[0].iterations if state.joined else sum(r.iterations for r in state.results)
        self.previous, self.at = state, (float(x), float(y))
        return state


def _turn(old, new) -> float:
    """Angle [rad] by which the line of centres turned from the journal position ``old`` to ``new`` (mesh
    frame; 0 if either is centred). Pads are solved in the bearing frame, where the ruptured zone turns with
    the line of centres: a rupture set carried over turned by it starts the active-set iteration nearer the
    answer (on two_groove's coarse Newton steps, 1 or 2 iterations instead of 2 or 3); the full bearing's mesh
    frame turns with it already (its turn is 0)."""
    if not (np.hypot(*old) > 0 and np.hypot(*new) > 0):
        return 0.0
    return _angle_between(math.atan2(-old[1], -old[0]), math.atan2(-new[1], -new[0]))


def _angle_between(a: float, b: float) -> float:
    return (b - a + math.pi) % (2 * math.pi) - math.pi


#: Pads' structured meshes are remeshed after the first Newton when the answer's ``sqrt(1 - eps)`` (the smallest
#: column width's scale) moved by more than this fraction from the first guess's (or the line of centres by more
#: than ``0.5 sqrt(1 - eps)``). 0.1 remeshed two_groove_ld1 (the short-bearing guess 0.35 against eps 0.49:
#: 11.4 %), one more coarse solve and two more compiled meshes, 1.13x the full bearing's time; with 0.15 its
#: errors in part ``journal_pads`` stay within 4.6e-4 at sizes 0.2 to 0.3 (rupture_size 0.05 and below), the
#: other cases' meshes are unchanged (their guesses moved 6-7 %; the supply groove's 27 % still remeshes).
PAD_REMESH = 0.15


def _regrade(xy_mesh, xy, fraction: float = 1.0) -> bool:
    """Whether pads' structured meshes graded for the journal at ``xy_mesh`` are remeshed for the position ``xy``
    (:data:`PAD_REMESH`); ``fraction`` [-]: whether ``xy`` moved from ``xy_mesh`` by more than that fraction of
    the remeshing threshold."""
    e, e_new = float(np.hypot(*xy_mesh)), float(np.hypot(*xy))
    moved = abs(_angle_between(math.atan2(-xy_mesh[1], -xy_mesh[0]), math.atan2(-xy[1], -xy[0])))
    return (abs(math.sqrt(1 - e_new) / math.sqrt(1 - e) - 1) > fraction * PAD_REMESH
            or moved > fraction * 0.5 * math.sqrt(1 - e_new))


#: Newton on meshes that will be remeshed (:func:`_regrade`) stops before solving at a position its step moved by
#: less than this fraction of the remeshing threshold: the meshes are remeshed there and Newton goes on from it on
#: them, whose first solve it needed anyway. On the supply groove of part ``journal_pads`` (the first guess's
#: meshes graded at eps 0.556, the answer 0.761) the last step on them moves sqrt(1 - eps) by 1.3 %
#: (0.7675 -> 0.7612): one coarse solve fewer, the same remeshed meshes and answers (the step before moved it 8 %).
#: Its coarse meshes then take 4 solves (at eps 0.556, 0.725 and 0.768 on the first meshes, 0.761 on the remeshed
#: ones; 11 active-set iterations) against the full bearing's 2 (3), about 22 of its 209 ms CPU at size 0.2,
#: rupture_size 0.05 with two mesh builds (9 ms); its refined levels' solves (31, 73 ms) and the last Newton step's
#: (24 ms) cost what their meshes' size (2,020 nodes against 749) and one more active-set iteration a level ask
#: (:data:`LEVEL_START_TOL`). A second calibrated guess on the first meshes (eps 0.759, 1.4 degrees off) remeshed at
#: once left the first solve on the new meshes above :data:`COARSE_TOL`: the same 4 coarse solves, 2 more
#: active-set iterations and the error against the part's reference 7.5e-4 instead of 5.8e-4.
REGRADE_SETTLED = 1.0 / 3.0


def _equilibrium_structured(bearing, load, size, min_size, opts: _Solves, tol, max_newton, rupture_size):
    """Pads, partial arcs and periodic films on :func:`structured_meshes`: Newton in ``(x, y)`` on meshes graded
    for the first guess (remeshed once if the answer's thinnest film moved), then, with ``rupture_size``, the
    rupture refinement of every pad and Newton to ``tol`` on the refined meshes. Returns
    ``(xy, state, newton_steps, residual, meshes)``.

    The first guess is the short bearing's (its force turned onto the load, not the load line itself). Galerkin
    films are solved there once; if the guess corrected by that solve (:func:`_calibrated_guess`) would regrade
    the meshes (:func:`_regrade`: the guess is far off), the first step goes there instead of a Newton step's
    way, else Newton goes on from that solve (the same iteration as without the check). Newton on meshes that
    will be remeshed stops, unsolved, at a position its step moved by little (:data:`REGRADE_SETTLED`)."""
    first_tol = tol if rupture_size is None else max(tol, COARSE_TOL)
    xy = _short_guess(load, bearing.half_width)
    k_total = 0
    for rounds in range(3):
        xy_mesh = xy
        e, phi0 = grading_position(np.hypot(*xy), math.atan2(-xy[1], -xy[0]))
        ms = default_min_size(size, e) if min_size is None else min_size
        meshes = structured_meshes(bearing, size, min_size=ms, eps=e, phi0=phi0)
        first = stiffness = None
        if rounds == 0 and min_size is None and opts.cavitation != "jfo":
            first = opts.solve(bearing, meshes, *xy)
            if all(sup is not None for sup in first.sups):
                stiffness = _linearized(first, velocity=False)[0]
                guess = _calibrated_guess(xy, first.force, stiffness, load, bearing.half_width)
                if guess is not None and _regrade(xy, guess):
                    xy, first, stiffness, k_total = guess, None, None, 1
        settled = None if min_size is not None or rounds == 2 else (
            lambda old, new, xy_mesh=xy_mesh: _regrade(xy_mesh, new) and not _regrade(old, new, REGRADE_SETTLED))
        xy, state, k, res = _newton_xy(bearing, meshes, xy, load, opts, first_tol, max_newton, first=first,
                                       polar=True, first_stiffness=stiffness, settled=settled)
        k_total += k
        if min_size is not None or not _regrade(xy_mesh, xy):
            break
    if rupture_size is not None:
        def step(state, at):
            R = state.force - load
            if np.hypot(*R) <= tol * np.hypot(*load):
                return None
            return tuple(_polar_step(np.asarray(at), state.force, _linearized(state, velocity=False)[0], load))
        meshes, state, at, k = _refine_rupture(bearing, meshes, state, tuple(xy), rupture_size, opts, step)
        xy = np.asarray(at)
        k_total += k
        xy, state, k, res = _newton_xy(bearing, meshes, xy, load, opts, tol, max_newton, first=state, polar=True)
        k_total += k
    return xy, state, k_total, res, meshes


def _newton_xy(bearing, meshes, xy, load, opts: _Solves, tol, max_newton, first: _State | None = None,
               polar: bool = False, first_stiffness: np.ndarray | None = None, settled=None):
    """Newton on ``F(x, y) = load`` on fixed meshes; ``first``: the solution at ``xy`` on them if already made
    (``first_stiffness``: its stiffness, if already linearized); ``polar``: :func:`_polar_step` steps, else plain
    ones (see :func:`_eps_step`). ``settled(old, new)``: True if the step from ``old`` to ``new`` ends the iteration
    before the solve at ``new`` (the meshes are to be remade there); the state returned is then None and the
    residual that before the step."""
    w = np.hypot(*load)
    for k in range(max_newton + 1):
        e = float(np.hypot(*xy))
        if e > EPS_MAX:
            raise RuntimeError(f"equilibrium needs eps > {EPS_MAX}: the load is too large for this bearing")
        state = first if k == 0 and first is not None else opts.solve(bearing, meshes, xy[0], xy[1])
        R = state.force - load
        res = float(np.hypot(*R) / w)
        if res <= tol:
            return xy, state, k, res
        K = (first_stiffness if k == 0 and first is not None and first_stiffness is not None
             else _stiffness(bearing, meshes, state, xy, opts.cavitation))
        old, xy = xy, _polar_step(xy, state.force, K, load, plain=not polar)
        if settled is not None and settled(old, xy):
            return xy, None, k + 1, res
    raise RuntimeError(f"journal equilibrium: Newton did not converge in {max_newton} steps "
                       f"(relative force residual {res:.3g}); can the pads carry a load in this direction?")


def _check_structured(bearing: JournalBearing, structured, rupture_size, size, cavitation: str, order) -> None:
    if not isinstance(structured, bool):
        raise ValueError(f"structured must be True or False, got {structured!r}")
    if structured and order != 1:
        raise ValueError("structured meshes are straight-sided (exact for the unwrapped film): use order=1")
    if rupture_size is None:
        return
    if not structured or cavitation != "reynolds":
        raise ValueError("rupture_size needs structured=True and cavitation='reynolds' (it refines a "
                         "structured mesh around the Swift-Stieber rupture front)")
    if bearing.periodic:
        raise ValueError("rupture_size is for Galerkin solves: a periodic film is solved by finite volumes on "
                         "its grid (structured=True without rupture_size)")
    if not (isinstance(rupture_size, (int, float)) and not isinstance(rupture_size, bool)
            and math.isfinite(rupture_size) and 0 < rupture_size <= size):
        raise ValueError(f"rupture_size must be in (0, size = {size}], got {rupture_size!r}")
    # the refined band along the front (about the bearing's width 2a long): each level of element size d adds
    # a band about 1.5 d wide of 2.31 / d^2 triangles per unit area, 7 a / d; the levels sum to about 14 a / d
    check_element_count(14.0 * bearing.half_width / rupture_size, what=f"rupture_size = {rupture_size:g}")


@dataclass(frozen=True)
class _Mesher:
    """How :func:`equilibrium` meshes the full bearing at an eccentricity."""

    bearing: JournalBearing
    size: float
    min_size: float | None
    order: int
    structured: bool

    def remesh(self, eps_mesh: float, eps: float) -> bool:
        """Whether the answer ``eps`` moved too far from the mesh's ``eps_mesh``: by 0.02 (gmsh meshes), or
        (structured meshes, which are graded in one direction only) enough to change the smallest element
        size by more than 10 %."""
        if not self.structured:
            return abs(eps - eps_mesh) >= 0.02
        return abs(math.sqrt(1 - eps) / math.sqrt(1 - eps_mesh) - 1) > 0.1

    def __call__(self, eps: float) -> tuple[SupportMesh, ...]:
        eps = grading_position(eps, 0.0)[0]  # an answer that differs by round-off grades the same mesh
        ms = default_min_size(self.size, eps) if self.min_size is None else self.min_size
        if self.structured:
            return (structured_journal_mesh(self.bearing, self.size, min_size=ms, eps=eps),)
        return journal_mesh(self.bearing, self.size, min_size=ms, eps=eps, order=self.order)


#: Force-balance tolerance of the Newton iteration on the mesh that :func:`equilibrium` then refines
#: around the rupture front (each refinement level takes a Newton step before its solve and the finest
#: meshes' Newton goes on to ``tol``: the coarse position only has to put the front within the refinement's
#: reach; 5e-2 instead of 1e-3 saved two coarse steps on pads and left the plain cases' errors unchanged).
COARSE_TOL = 5e-2


def _newton_eps(bearing, meshes, eps: float, w: float, opts: "_Solves", tol: float, max_newton: int,
                first: "_State | None" = None, log: bool = False):
    """Newton on ``|F|(eps) = w`` on fixed meshes: ``(eps, state, steps, residual)``; ``first``: the solution
    at ``eps`` on these meshes if already made."""
    for k in range(max_newton + 1):
        state = first if k == 0 and first is not None else opts.solve(bearing, meshes, -eps, 0.0)
        F = state.force
        wf = float(np.hypot(*F))
        res = abs(wf - w) / w
        if res <= tol:
            return eps, state, k, res
        eps = _eps_step(eps, F, _stiffness(bearing, meshes, state, (-eps, 0.0), opts.cavitation), w, log)
    raise RuntimeError(f"journal equilibrium: Newton did not converge in {max_newton} steps "
                       f"(relative load residual {res:.3g})")


def _eps_step(eps: float, F: np.ndarray, K: np.ndarray, w: float, log: bool = True) -> float:
    """One Newton step on ``log |F|(eps) = log w`` (full bearing, mesh frame; the magnitude part of
    :func:`_polar_step`), or on ``|F|(eps) = w`` (``log=False``), with the stiffness ``K = dF/d(x, y)``, kept
    within half the way to ``EPS_MAX`` and to half ``eps``.

    The gmsh paths keep the plain steps and the first guess by quadrature: their meshes are graded at the
    converged eccentricity rounded to 9 digits, so another iteration path (the same root to 1e-9) gives other
    gmsh meshes and moves their results by the mesh-to-mesh scatter (up to 5e-4 on the recorded
    coefficients of part ``journal``); the structured paths take the log (polar) steps and the closed-form
    guess."""
    wf = float(np.hypot(*F))
    dw = float(F @ (-K[:, 0])) / wf  # journal moves along -x as eps grows
    new = eps - (math.log(wf / w) * wf if log else wf - w) / dw
    return float(min(max(new, 0.5 * eps), 0.5 * (eps + EPS_MAX)))


def _polar_step(xy: np.ndarray, F: np.ndarray, K: np.ndarray, load: np.ndarray, plain: bool = False) -> np.ndarray:
    """One Newton step on the force balance ``F(x, y) = load`` in polar form, ``log |F| = log |load|`` and
    ``arg F = arg load`` (the same root; Jacobian from the stiffness ``K = dF/d(x, y)``), kept inside the
    clearance: at most half way to the eccentricity limit. The load grows about as ``eps / (1 - eps^2)^2``,
    far from linear in ``(x, y)``: from the short-bearing guess the plain step overshot (two_groove_ld1:
    1.84 -> 3.72 -> 3.10 -> 3.0016 against a load of 3), the polar one does not (1.84 -> 3.09 -> 3.0001).
    ``plain``: the plain step on ``F - load`` (see :func:`_eps_step`)."""
    if plain:
        step = -np.linalg.solve(K, F - load)
    else:
        f2 = float(F @ F)
        J = np.vstack([F @ K, F[0] * K[1] - F[1] * K[0]]) / f2
        R = np.array([math.log(math.sqrt(f2) / float(np.hypot(*load))),
                      _angle_between(math.atan2(load[1], load[0]), math.atan2(F[1], F[0]))])
        step = -np.linalg.solve(J, R)
    e = float(np.hypot(*xy))
    t = 1.0
    while np.hypot(*(xy + t * step)) > max(e, 0.5 * (e + EPS_MAX)):
        t *= 0.5
    return xy + t * step


#: Rupture refinement: elements within this many front-element diameters of the front are split ...
RUPTURE_REACH = 0.75
#: ... this many times per level (one solve per level).
RUPTURE_SPLITS = 2
#: A film whose largest pressure is a fraction f of the bearing's has its front refined to
#: ``rupture_size * min(1 / f, RUPTURE_LIGHT)``: the lightly loaded pad of a two-groove bearing (f = 0.01)
#: then gets one level instead of all (not refining it at all left errors up to 1e-3 in its coefficients, on
#: two_groove_ld1 at sizes 0.2-0.25). 5 rather than 4: the light pad of a mesh of size 0.3 (front elements 0.42
#: across) is split once to 0.21, not twice because 0.21 exceeds 4 x 0.05 (two_groove_ld1: 172 nodes instead
#: of 399, error 3.8e-4 instead of 4.6e-4); the errors of every other setting of part ``journal_pads`` unchanged.
RUPTURE_LIGHT = 5.0
#: Where the film forms again (:func:`_reformation_elements`: the boundary of a full film fed from a supply pocket
#: or a pad's trailing part, downstream of a ruptured zone) the front is refined to ``rupture_size`` times this
#: (or the film's own size, if larger): the coefficients hardly depend on it. On the supply groove of part
#: ``journal_pads`` (a pocket-fed zone behind the ruptured one) it held a third of the refined elements; at this
#: size the errors against the part's references at size 0.2 are 7.9e-4, 5.5e-4, 4.4e-4 at rupture sizes 0.05,
#: 0.04, 0.02 (5.8e-4, 5.8e-4, 4.3e-4 with the whole front at rupture_size), on 1,151 nodes instead of 1,654 at
#: 0.05. A light pad's film already had this size (:data:`RUPTURE_LIGHT`): two_groove, two_groove_ld1 and
#: partial_arc keep their meshes.
REFORMATION_SIZE = 5.0
#: ... telling such a boundary from a rupture front by the dofs within this many element diameters of a front
#: element (one element's own dofs misread a few elements where a rupture front bends towards the bearing's edge).
REFORMATION_REACH = 2.0
#: Supply pockets: elements within this many of their diameters of a pocket corner are split (0.75: every
#: element touching the corner, whose centroid lies within 2/3 of a median of it, and few others; 1.5 split a
#: ring of neighbours too: on the supply groove of part ``journal_pads`` 15 % more nodes at sizes 0.2 to 0.3
#: for the same errors to 1e-5, at eps 0.76 and 0.86) ...
CORNER_REACH = 0.75
#: ... until they are no longer than this times ``rupture_size`` (graded towards the corner). The corners hold
#: 220 of the supply groove's 2,020 nodes (size 0.2, rupture_size 0.05; without them its error is 1.8e-3); 1.5 (and
#: 2, the same meshes there) saved 80 nodes at that setting and 4 % over the grading sweep of
#: :data:`FRONT_PEAK_DISTANCE`, but left 10.4e-4 at grading 0.788 (8.9e-4 with 1) and an active-set iteration more.
CORNER_SIZE = 1.0


def _refine_rupture(bearing: JournalBearing, meshes: tuple, state: "_State", at, rupture_size: float,
                    opts: "_Solves", step=None) -> tuple[tuple, "_State", tuple, int]:
    """Refine the elements near the rupture front of every film (conforming red-green-blue splits) until the
    front lies in elements no longer than ``rupture_size`` on the film with the largest pressure, and no
    longer than ``rupture_size min(1 / f, RUPTURE_LIGHT)`` on a film whose largest pressure is a fraction
    ``f`` of that (the coefficients' error from a front grows with the pressures around it); where the film forms
    again (:func:`_reformation_elements`) no longer than ``rupture_size REFORMATION_SIZE`` (or the film's size,
    if larger). A front closer than :data:`FRONT_PEAK_DISTANCE` behind its zone's pressure peak is refined further
    in proportion (in a narrower band, :data:`FRONT_PEAK_REACH`), and a zone running into the film's downstream
    edge has a band along that edge refined to :data:`EDGE_SIZE` times the front's size (:func:`zone_ends`). Per
    level: the elements within
    :data:`RUPTURE_REACH` diameters of a front element
    are split :data:`RUPTURE_SPLITS` times, then one solve with the journal at ``at`` (mesh frame) started
    from the previous level's rupture sets (nested iteration, :func:`_level_start`).

    ``step(state, at)``: the next position (a Newton step of the equilibrium on the level's mesh) or None if
    ``state`` is in equilibrium to the tolerance; each level is then solved at the position stepped from the
    previous level's solution, so that the last level's is in equilibrium but for that level's change (the
    Newton that follows on the finest meshes starts there, one refined solve closer). Returns the refined
    meshes, their solution, its position and the number of steps taken."""
    levels = 8 + 2 * math.ceil(math.log2(max(max(m.size for m in meshes) / rupture_size, 1.0)))
    steps = 0
    for _ in range(levels):
        peaks = [max(float(np.max(res.pressure)), 0.0) for res in state.results]
        sizes = [rupture_size * min(max(peaks) / peak, RUPTURE_LIGHT) if peak > 0 else math.inf for peak in peaks]
        refined = [_refined_at_front(bearing, mesh, res, size, CORNER_SIZE * rupture_size,
                                     max(size, REFORMATION_SIZE * rupture_size),
                                     EDGE_SIZE * rupture_size * max(peaks) / peak if peak > 0 else math.inf)
                   for mesh, res, size, peak in zip(meshes, state.results, sizes, peaks)]
        if all(r is None for r in refined):
            return meshes, state, at, steps
        moved = step(state, at) if step is not None else None
        if moved is not None:
            at, steps = moved, steps + 1
        meshes = tuple(mesh if r is None else r for mesh, r in zip(meshes, refined))
        # not turned with the line of centres (as a Newton step's start is, :meth:`_Solves.solve`): the front
        # moves with the refinement more than with the level's step, and the turned set started the pads of
        # part ``journal_pads`` further from their answer (two_groove at size 0.3, rupture_size 0.05: 14
        # active-set iterations instead of 13); a film not refined at this level keeps its set as it is
        start = tuple(res.cavitated if r is None else _level_start(res, operators(mesh, opts.element).basis)
                      for mesh, res, r in zip(meshes, state.results, refined))
        state = opts.solve(bearing, meshes, *at, start=start)
    raise RuntimeError(f"journal equilibrium: the rupture front still crosses elements longer than rupture_size = "
                       f"{rupture_size:g} after {levels} refinement levels (it moves as the mesh is refined)")


#: A rupture front closer than this [-] (in units of the journal radius, along ``phi``) behind the pressure peak
#: of its full-film zone (:func:`zone_ends`) has its elements refined to ``rupture_size`` times the square of its
#: distance over this. The plain pads of part ``journal_pads`` have their fronts 0.72-0.86 behind the peak on the
#: coarse mesh (0.81-1.1 refined; their meshes are unchanged); the supply groove's front, 20 degrees behind a
#: steep peak (0.30-0.40), then lies in elements of about 0.01 instead of 0.035 at rupture_size 0.05. The plain
#: ratio (no square: elements of 0.018) left errors up to 11.9e-4 at size 0.2 and 15-19e-4 at sizes 0.25 and 0.3
#: over the grading sweep below (step 0.004 from 0.72 to 0.8; the square: 9.0e-4, 11.9e-4, 7.0e-4). Shorter
#: distances save nodes, not accuracy: 0.7, 0.65 and 0.6 gave 1,970, 1,838 and 1,773 nodes on average over the
#: sweep at size 0.2, rupture_size 0.05 (2,199 with 0.75; 6.05-6.10 Newton steps against 6.48, the third refinement
#: level of the gradings below 0.76 saved) but 11.6e-4, 10.7e-4 and 10.7e-4 at grading 0.756 (3.0e-4 with 0.75) ...
FRONT_PEAK_DISTANCE = 0.75
#: ... but not below this fraction of it (a tiny full-film zone, a few dofs from peak to front, would otherwise ask
#: for elements without bound; the supply groove's factor is 0.16-0.28) ...
FRONT_PEAK_FLOOR = 0.1
#: ... in a band narrower than the front's own: the elements within this many front-element diameters of a front
#: element go below ``rupture_size``, those within :data:`RUPTURE_REACH` to it. On the supply groove of part
#: ``journal_pads`` (size 0.2, rupture_size 0.05) the band of :data:`RUPTURE_REACH` held 1,787 of the 2,556 nodes
#: (a front whose ``phi`` varies by 0.1 along the bearing); with 0.4 the meshes have 2,009 nodes and eps, K and C
#: move by 1.4e-7 of their largest values, the Newton steps and active-set iterations the same. Over the grading
#: sweep of :data:`EDGE_SIZE` (12 gradings from 0.72 to 0.8) the errors against the part's reference rise by 1.7e-5
#: at most (the largest, 8.8e-4 at 0.788, unchanged) on 2,000-2,450 nodes instead of 2,460-3,360; 0.35 left 9.4e-4
#: at 0.788, 0.3 took an extra Newton step at half the gradings and 11.6e-4 at 0.788, 0.25 an extra refinement
#: level. Fronts not close behind their peak (factor 1: the plain pads of the part) are not affected; the full
#: bearing's front comes within FRONT_PEAK_DISTANCE of its peak from eps 0.84 (L/D 0.5, load 5; 0.33 at eps 0.94):
#: there 23-29 % fewer nodes at sizes 0.2-0.3, rupture_size 0.05, eps, K and C within 5.1e-6 of the wide band's.
FRONT_PEAK_REACH = 0.4
#: ... and a full-film zone that runs into the film's downstream edge (``p = 0`` there: the pocket-fed zone of the
#: supply groove, cut at an axial line 17 degrees behind its peak of 1.9) has the elements within this many
#: peak-to-edge distances of the edge ...
EDGE_REACH = 2.0
#: ... refined to this times ``rupture_size / f`` (the pressure falls from its peak to zero there; ``f`` as for
#: :data:`RUPTURE_LIGHT`, but not capped: the light pad of two_groove, f = 0.01, reaches its trailing edge in full
#: film, and the cap split its elements there at rupture_size 0.02, 2 % more nodes). Neither alone made the
#: supply groove robust: with the grading eccentricity fixed at 0.74-0.78, its errors at size 0.2, rupture_size
#: 0.05 were 5.2e-4 to 36e-4; the front alone 4.0e-4 to 11.5e-4 (even rupture_size 0.02 everywhere: 3.3e-4 to
#: 11.2e-4); both (the plain ratio) 2.1e-4 to 7.5e-4 on 2,130-2,260 nodes (7.8e-4 at most with 4, 10.6e-4 with
#: 5; with 2 the same errors on 12 % more nodes; EDGE_REACH 1 instead of 2 left 9.7e-4 at size 0.3); with the
#: square 1.6e-4 to 9.0e-4 over 0.72-0.8 on 2,450-3,400 nodes (main: 4.6e-4 to 36e-4 on 1,090-1,170). With the
#: narrower band of :data:`FRONT_PEAK_REACH`, 4 saves 1 % of the nodes over that sweep (2,172 against 2,199 on
#: average) for 9.0e-4 at grading 0.788 (8.9e-4 with 3).
EDGE_SIZE = 3.0


def front_size_factor(distance: float) -> float:
    """Factor on the front's element size for a rupture front ``distance`` [-] behind its zone's pressure peak
    (:func:`zone_ends`): ``(distance / FRONT_PEAK_DISTANCE)^2`` within ``[FRONT_PEAK_FLOOR, 1]``."""
    return max(min(1.0, distance / FRONT_PEAK_DISTANCE) ** 2, FRONT_PEAK_FLOOR)


def zone_ends(res: ReynoldsResult) -> tuple[float, float]:
    """Shortest distances [-] (along ``phi``, on the row of dofs nearest the mid-plane ``z = 0``) from the largest
    pressure of a full-film zone forward to where the zone ends: ``(front, edge)``, the first over zones ending at
    a rupture front, the second over a zone ending at the film's downstream edge (``inf`` where there is none). A
    zone that ends close behind a steep peak needs smaller elements there than one far behind a flat one."""
    x = np.asarray(res.basis.doflocs)
    row = np.flatnonzero(np.abs(x[1]) <= np.min(np.abs(x[1])) + 1e-9)
    row = row[np.argsort(x[0, row])]
    phi, p, cavitated = x[0, row], np.asarray(res.pressure)[row], np.asarray(res.cavitated, bool)[row]
    change = np.diff(np.concatenate([[0], (~cavitated & (p > 0)).astype(np.int8), [0]]))
    front = edge = math.inf
    last = len(row) - 1
    for start, end in zip(np.flatnonzero(change == 1), np.flatnonzero(change == -1)):  # zone: dofs start..end-1
        end = min(end, last)  # the first dof after the zone (the edge's, if the zone reaches it)
        if cavitated[end] or end == last:
            distance = float(phi[end] - phi[start + int(np.argmax(p[start:end]))])
            front, edge = (min(front, distance), edge) if cavitated[end] else (front, distance)
    return front, edge


def _corners(shape) -> list[tuple[float, float]]:
    """The four corners of an axis-aligned rectangular pocket."""
    xy = shape.boundary()
    (x0, z0), (x1, z1) = xy.min(axis=1), xy.max(axis=1)
    return [(x0, z0), (x1, z0), (x0, z1), (x1, z1)]


def _refined_at_front(bearing: JournalBearing, mesh: SupportMesh, res: ReynoldsResult,
                      rupture_size: float, corner_size: float = 0.0,
                      reformation_size: float | None = None, edge_size: float = math.inf) -> SupportMesh | None:
    """One level of :func:`_refine_rupture` on one film, or None if its front already lies in elements no
    longer than ``rupture_size`` (those where the film forms again, :func:`_reformation_elements`: no longer
    than ``reformation_size``, default ``rupture_size``), or it has no front. ``rupture_size`` is scaled down for a
    front close behind its peak (within :data:`FRONT_PEAK_REACH` element diameters of the front; within
    :data:`RUPTURE_REACH` to ``rupture_size`` itself), and a loaded downstream edge gets a band of elements no longer
    than ``edge_size`` (:func:`zone_ends`, :data:`FRONT_PEAK_DISTANCE`, :data:`EDGE_REACH`)."""
    m = mesh.mesh  # refine_marked drops the named boundaries and splits on the facets the mesh has built
    changed = False
    front = _front_elements(res)
    diameters = cell_diameters(m)
    to_front, to_edge = zone_ends(res)
    plain_size, rupture_size = rupture_size, rupture_size * front_size_factor(to_front)
    phi = m.p[0, m.t].mean(axis=0)
    edge = (phi > phi.max() - EDGE_REACH * to_edge if math.isfinite(to_edge) and math.isfinite(edge_size)
            else np.zeros_like(front))
    # told apart only where it matters: among the front elements longer than rupture_size (reformation_size is not
    # smaller; each element is told apart by the dofs around it alone), and for all of them if some is to be split
    # (unless they are all long: then that is the verdict for all of them already; the supply groove's first two
    # levels, two_groove's first)
    long = front & (diameters > rupture_size * (1 + 1e-9))
    reformation = np.zeros_like(front)
    if reformation_size is not None and long.any():
        reformation = _reformation_elements(res, long)
        if not np.array_equal(long, front) and (
                np.any(long & ~reformation) or np.any(diameters[reformation] > reformation_size * (1 + 1e-9))):
            reformation = _reformation_elements(res, front)
    rupture = front & ~reformation
    # (mask, size, reach in diameters): a front close behind its peak is split to plain_size as any front, and
    # further down to its own size in a narrower band (FRONT_PEAK_REACH)
    fronts = ([(rupture, plain_size, RUPTURE_REACH), (rupture, rupture_size, FRONT_PEAK_REACH)]
              if rupture_size < plain_size else [(rupture, rupture_size, RUPTURE_REACH)])
    groups = [(mask, size, reach) for mask, size, reach in fronts + [(reformation, reformation_size, RUPTURE_REACH),
                                                                     (edge, edge_size, RUPTURE_REACH)]
              if mask.any() and math.isfinite(size) and diameters[mask].max() > size * (1 + 1e-9)]
    d, centroids = diameters, m.p[:, m.t].mean(axis=1)  # of m, made afresh after each split
    if groups:
        centres = [(centroids[:, mask].T, reach * diameters[mask], size) for mask, size, reach in groups]
        for _ in range(RUPTURE_SPLITS):
            tree = cKDTree(centroids.T)
            marked = np.zeros(m.nelements, bool)
            for points, reach, size in centres:
                near = np.zeros(m.nelements, bool)
                near[np.fromiter(itertools.chain.from_iterable(tree.query_ball_point(points, reach)), np.intp)] = True
                marked |= near & (d > size * (1 + 1e-9))
            marked = np.flatnonzero(marked)
            if not marked.size:
                break
            m = refine_marked(m, marked)
            d, centroids = cell_diameters(m), m.p[:, m.t].mean(axis=1)
            changed = True
    # the corners of the supply pockets (the pressure gradient is singular there): graded down to corner_size
    corners = np.array([(x, z) for g in mesh.surface.inlets for x, z in _corners(g)]) if corner_size else np.zeros((0, 2))
    for _ in range(64 if corners.size else 0):
        gap = np.min(np.hypot(*(centroids[:, :, None] - corners.T[:, None, :])), axis=1)
        marked = np.flatnonzero((gap < CORNER_REACH * d) & (d > corner_size * (1 + 1e-9)))
        if not marked.size:
            break
        m = refine_marked(m, marked)
        d, centroids = cell_diameters(m), m.p[:, m.t].mean(axis=1)
        changed = True
    if not changed:
        return None
    check_element_count(m.nelements, what=f"rupture_size = {rupture_size:g}")
    # conforming splits of the checked mesh's triangles: valid, and its pieces (on the same outline), by construction
    if bearing.raimondi_boyd:
        return _named_rectangle(m, mesh.surface, (0.0, 2 * math.pi), bearing.half_width, cells_checked=True,
                                connected=True)
    return name_surface_boundaries(m, mesh.surface, source="structured", cells_checked=True, connected=True)


_DOF_TREES: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def _dof_tree(basis) -> cKDTree:
    """The k-d tree of a basis' dof locations, kept per basis: the Newton steps on a mesh carry its rupture set
    over (turned) at every solve (a refinement level takes its start from the old elements instead,
    :func:`_level_start`)."""
    tree = _DOF_TREES.get(basis)
    if tree is None:
        tree = _DOF_TREES[basis] = cKDTree(np.asarray(basis.doflocs).T)
    return tree


#: Relative slack of the search radius of a rupture set turned on its own mesh (:meth:`_Solves.solve`): the turned
#: dof's distance to its own dof is ``|turn|`` but for the rounding of the subtraction.
TURN_REACH_SLACK = 1e-6


#: A Newton step's start is predicted from the previous state's linearization (:func:`_predicted_rupture`) when the
#: journal moves by at most this fraction of the previous thinnest film ``1 - eps`` [c]: the first-order change of
#: the film is then within a tenth of it. Larger steps (the first ones from the short-bearing guess, 0.2-1.3 of
#: it) overshoot: on gmsh meshes of size 0.1 they put 50-800 dofs in the start that were not ruptured, and
#: two_groove took 27 active-set iterations instead of 23; the steps near the answer move 1e-2 of it and less.
PREDICTED_STEP = 0.1


def _predicted_rupture(previous: _State, starts, step: np.ndarray) -> tuple[np.ndarray, ...]:
    """Rupture masks to start the films of ``previous`` (on its meshes) from, with the journal moved by ``step``
    [c] (mesh frame): ``starts`` (one per film: a result or a mask of its dofs) with the dofs added whose constrained
    unknown the linearization of ``previous`` (:attr:`_State.perturbations`) predicts below zero there,
    ``v = T (u + du/d(x, y) step) < -tol max |v|`` (the active-set iteration's own test). The front moves with
    the journal; the first-order step puts the dofs it passes over in the start (a Newton step on the refined pads
    of two_groove_ld1 had one dof to rupture, which took one more active-set iteration of 3,182 unknowns)."""
    masks = []
    for res, sup, du, start in zip(previous.results, previous.sups, previous.perturbations, starts):
        fp = obstacle_problem(sup)
        mask = np.array(start.cavitated if isinstance(start, ReynoldsResult) else start, bool)
        v = fp.coefficients(np.asarray(res.pressure)[fp.interior] + du[:, :2] @ step)
        mask[fp.interior] |= v < -fp.problem.tol * float(np.abs(v).max(initial=0.0))
        masks.append(mask)
    return tuple(masks)


def _turned_in_place(res: ReynoldsResult, turn: float) -> np.ndarray:
    """The rupture mask of ``res`` turned by ``turn`` [rad] on its own mesh: :func:`_nearest_rupture` of its
    dofs searched within ``|turn|`` (each turned dof's own dof is that far). When no two dofs lie within twice
    that reach, every turned dof's nearest dof is its own (any other is farther than the reach from it), so the
    mask is returned as it is, without the search: the Newton steps near the answer turn by 1e-5 to 1e-4 rad
    against a dof spacing of 1e-2 (a pair search within the tiny radius costs half the bounded search,
    0.20 against 0.42 ms at 1,823 P2 dofs; CPU time, 500 repetitions). The cell hash of :func:`_points_apart`
    decides first, the k-d tree's pair search only where it cannot."""
    reach = abs(turn) * (1 + TURN_REACH_SLACK)
    cavitated = np.asarray(res.cavitated, bool)
    dofs = np.asarray(res.basis.doflocs)
    edge = res.basis.element_dofs[:2, 0]  # two dofs of an element: within twice the reach, no pair search
    if 2 * reach < float(np.hypot(*(dofs[:, edge[0]] - dofs[:, edge[1]]))) \
            and (_points_apart(dofs, 2 * reach)
                 or not _dof_tree(res.basis).query_pairs(2 * reach, output_type="ndarray").size):
        return cavitated.copy()
    return _nearest_rupture(res, dofs, turn, reach)


def _points_apart(points: np.ndarray, distance: float) -> bool:
    """Whether no two of ``points`` (shape (2, n)) lie within ``distance`` [same units] of each other, by hashing
    them into square cells a little wider than ``distance`` (two points within it share a cell or lie in
    neighbouring ones): True only if every cell holds one point and no two occupied cells touch. False means
    only that some two points are that close to touching cells (:func:`_turned_in_place` then asks the k-d tree's
    exact pair search). Spares the tree of a mesh whose rupture set is turned once and never searched (the
    refined pads' last Newton solve): 0.16 against 0.51 ms for the tree and its pair search at 1,823 P2 dofs
    (CPU time, 500 repetitions). Cells narrower than ``1e-9`` of the points' extent are not made (the
    integer cell numbers stay far inside int64): a tinier ``distance`` is tested at that width, which implies
    it."""
    points = np.asarray(points, float)
    if points.ndim != 2 or points.shape[0] != 2:
        raise ValueError(f"points must have shape (2, n), got {points.shape}")
    if not (math.isfinite(distance) and distance >= 0):
        raise ValueError(f"distance must be finite and >= 0, got {distance!r}")
    if points.shape[1] < 2:
        return True
    low = points.min(axis=1, keepdims=True)
    extent = float(np.max(points.max(axis=1) - low[:, 0]))
    cell = max(distance, 1e-9 * extent) * (1 + 1e-6)
    if cell == 0:  # all points at one place
        return False
    ij = np.floor((points - low) / cell).astype(np.int64)
    width = int(ij[1].max()) + 3  # a column of cells and a spare cell below and above: no neighbour wraps
    keys = np.sort(ij[0] * width + ij[1] + 1)
    if np.any(keys[1:] == keys[:-1]):
        return False
    last = keys.size - 1
    for offset in (1, width - 1, width, width + 1):  # the neighbour above, and the three in the next column
        shifted = keys + offset
        if np.any(keys[np.minimum(np.searchsorted(keys, shifted), last)] == shifted):
            return False
    return True


def _nearest_rupture(res: ReynoldsResult, points: np.ndarray, turn: float = 0.0,
                     reach: float | None = None) -> np.ndarray:
    """Rupture mask at ``points`` (shape (2, n)): the state of the nearest dof of ``res`` (its front is
    then off by at most half the dof spacing); ``turn``: that of ``res`` turned by this angle along ``phi``
    (the state at ``phi - turn``). ``reach`` [same units as the coordinates]: a distance within which every
    turned point is known to have a dof (the k-d tree then searches only that far: a third less time for a
    rupture set turned on its own mesh, 0.42 against 0.62 ms at 1,823 P2 dofs); points without a dof within
    it are searched without the bound, so the answer is the nearest dof's either way."""
    tree = _dof_tree(res.basis)
    shifted = (points - np.array([[turn], [0.0]])).T
    if reach is None:
        nearest = tree.query(shifted)[1]
    else:
        nearest = tree.query(shifted, distance_upper_bound=reach)[1]
        missed = nearest >= tree.n
        if missed.any():
            nearest[missed] = tree.query(shifted[missed])[1]
    return np.asarray(res.cavitated, bool)[nearest]


#: A refinement level starts its rupture set from the previous level's solution (:func:`_level_start`): a new dof
#: in an old element with both ruptured and full-film dofs starts ruptured where the nearest of that element's dofs
#: (all of the equally nearest) were ruptured and the old pressure there is at most this fraction of the film's
#: largest. Over the 36 runs of part ``journal_pads`` (its six settings; its four cases and the two full bearings)
#: the active-set iterations were 617, 608, 599, 591, 578, 575, 578, 579, 576, 588, 589 at 0, 1e-5, 1e-4, 3e-4,
#: 1e-3, 2e-3, 3e-3, 5e-3, 1e-2, 3e-2, 0.1 (589 without the pressure's test; 625 with the nearest old dof's state
#: alone, the previous start), with the same converged sets, answers and meshes: 3e-3, the middle of the plateau.
#: The variants below were measured before the meshes were graded for the rounded journal position
#: (:func:`grading_position`; then 617 for the previous start, within 1 of the above from 1e-4 up). Taking the
#: first of equally nearest dofs (a vertex before an edge's middle; new dofs a quarter along an old edge are as
#: near to its end as to its middle) left 586-588 over 1e-3 to 5e-3, any of them ruptured 591-595.
#: Starting from the old pressure's sign alone (ruptured where it is at most the fraction, whatever the dofs
#: around) left 615, 611, 598, 611, 733 at 0, 1e-6, 1e-4, 1e-3, 1e-2; with the old field's Bernstein coefficient
#: at the new dof in place of its value (and the nearest old dof's state), 614, 591, 585, 589 at 0, 1e-4, 1e-3,
#: 1e-2. On the supply groove the front moves downstream as it is refined (close behind its steep peak: by about an
#: old dof spacing from level to level), so its levels start with a band of dofs ruptured that the active-set
#: iteration frees a layer or two at a time (size 0.2, rupture_size 0.05: 4 and 5 iterations, 235, 176, 52 and 4 dofs
#: freed at the second level; the full bearing 3 and 4). Measured against 578 and not taken: the old elements next
#: to a front element started free throughout, one or two layers, 615 and 640 (the free solve goes negative over
#: the freed band, which is ruptured again at once and freed as before); the pads' Dirichlet dofs (p = 0 at their
#: edges) counted as ruptured-compatible, 574, the supply groove unchanged; the new dofs of front elements started
#: free where sqrt(p), extended from the nearest full-film old element's field, is still positive (the front's
#: p ~ d^2: it puts the second level's start within a dof of its front along the mid-plane), 571, and with that
#: extension read 1.2 times as far from the element's centroid, 559, but two_groove_ld1 up by 1 to 4 and the
#: supply groove's CPU time at size 0.2, rupture_size 0.05 down by 0.5 % only (median of 15 interleaved ratios).
LEVEL_START_TOL = 3e-3


def _level_start(res: ReynoldsResult, basis) -> np.ndarray:
    """Rupture mask at the dofs of ``basis`` (P1 or P2 on a mesh split from that of ``res`` by
    :func:`~bearingfe.geometry.meshing.refine_marked`) to start its solve from: each dof as the element of the
    old mesh holding it (:func:`~bearingfe.geometry.meshing.split_parents`) says. Ruptured where all that
    element's dofs were, free where none was; in an element with both (the front), ruptured where the nearest
    of its dofs were (all of the equally near ones) and the old pressure, evaluated there (exact on the nested
    mesh), is at most :data:`LEVEL_START_TOL` of the film's largest (a new dof in the full film next to the front
    starts free). Without a record of the split, the state of the nearest old dof (:func:`_nearest_rupture`).

    The old element's dofs replace the k-d tree search of every new dof among all old ones: on two_groove of
    part ``journal_pads`` (size 0.3, rupture_size 0.05; levels of 336, 1,044 and 1,823 P2 dofs) 0.47 against
    1.08 ms a run, two_groove_ld1 (646, 1,405, 2,768) 0.74 against 1.63, the supply groove (3,826, 6,778, 8,302)
    1.5 against 7.3 ms (CPU time, best of 2 x 300 repetitions; the old dofs' k-d tree already built)."""
    old = res.basis
    parents = split_parents(old.mesh, basis.mesh)
    if parents is None or res.cavitated is None:
        return _nearest_rupture(res, np.asarray(basis.doflocs))
    ruptured = np.asarray(res.cavitated, bool)[old.element_dofs]  # (dofs per element, old elements)
    count = ruptured.sum(axis=0)
    owner = np.empty(basis.N, dtype=np.int64)  # an element holding each dof, and its old element
    owner[basis.element_dofs] = np.arange(basis.element_dofs.shape[1])
    cells = parents[owner]
    mask = count[cells] == ruptured.shape[0]
    front = np.flatnonzero((count[cells] > 0) & ~mask)
    cells, points = cells[front], np.asarray(basis.doflocs)[:, front]
    gaps = np.sum((np.asarray(old.doflocs)[:, old.element_dofs[:, cells]] - points[:, None, :]) ** 2, axis=0)
    peak = max(float(np.max(res.pressure)), 0.0)
    nearest = gaps <= gaps.min(axis=0) * (1 + 1e-9)  # equal distances but for rounding
    mask[front] = (np.all(ruptured[:, cells] | ~nearest, axis=0)
                   & (values_in_cells(old, np.asarray(res.pressure), points, cells) <= LEVEL_START_TOL * peak))
    return mask


def _equilibrium_full(bearing, w, theta_load, eps, mesher: _Mesher, opts: _Solves, tol, max_newton,
                      rupture_size: float | None = None):
    """Full bearing: the answer depends on eps only; Newton on |F|(eps) = w."""
    k_total = 0
    first_tol = tol if rupture_size is None else max(tol, COARSE_TOL)
    for _ in range(3):
        meshes = mesher(eps)
        eps_start = eps
        eps, state, k, res = _newton_eps(bearing, meshes, eps, w, opts, first_tol, max_newton, log=mesher.structured)
        k_total += k
        if mesher.min_size is not None or not mesher.remesh(eps_start, eps):
            break
        if eps >= EPS_MAX * 0.999:
            raise RuntimeError(f"equilibrium needs eps > {EPS_MAX}: the load is too large for this bearing")
    if rupture_size is not None:
        def step(state, at):
            if abs(float(np.hypot(*state.force)) - w) <= tol * w:
                return None
            return (-_eps_step(-at[0], state.force, _linearized(state, velocity=False)[0], w), 0.0)
        meshes, state, at, k = _refine_rupture(bearing, meshes, state, (-eps, 0.0), rupture_size, opts, step)
        eps = -at[0]
        k_total += k
        eps, state, k, res = _newton_eps(bearing, meshes, eps, w, opts, tol, max_newton, first=state,
                                         log=mesher.structured)
        k_total += k
    F = state.force
    # mesh frame -> bearing frame: rotate so that F points along the load
    rotation = theta_load - math.atan2(F[1], F[0])
    xy = _rot(rotation) @ np.array([-eps, 0.0])
    att = math.degrees(math.atan2(abs(F[1]), -F[0]))
    # the joined problem kept: the coefficients' linearization reuses the factorization of the final rupture set
    state = replace(state, force=_rot(rotation) @ F, rotation=rotation)
    return Equilibrium(eps=eps, attitude=att, position=xy, force=state.force, newton_iterations=k_total,
                       residual=res, active_set_iterations=opts.iterations, element=opts.element, state=state,
                       meshes=meshes, bearing=bearing)


# -- dynamic coefficients --------------------------------------------------------------

@dataclass(frozen=True)
class DynamicCoefficients:
    """Stiffness and damping of the film at a static equilibrium.

    Attributes
    ----------
    K, C : ndarray, shape (2, 2)
        Non-dimensional ``K c / W`` and ``C c omega / W`` in the ROSS frame:
        ``x`` horizontal, ``y`` vertical, the static load on the journal
        along ``-y`` (gravity), rotation from ``+x`` to ``+y``.
    load : float
        Non-dimensional load ``w`` [mu omega R^4 / c^2].
    eps, attitude : float
        Equilibrium eccentricity [-] and attitude [deg].
    method : str
        ``"linearized"`` or ``"finite-difference"``.
    """

    K: np.ndarray
    C: np.ndarray
    load: float
    eps: float
    attitude: float
    method: str

    def to_si(self, *, viscosity: float, speed: float, radius: float, clearance: float) -> tuple[np.ndarray, np.ndarray]:
        """Stiffness [N/m] and damping [N s/m] for ``mu`` [Pa s], ``omega`` [rad/s], ``R``, ``c`` [m]."""
        for name, v in (("viscosity", viscosity), ("speed", speed), ("radius", radius), ("clearance", clearance)):
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
        W = viscosity * speed * radius**4 / clearance**2 * self.load
        return self.K * W / clearance, self.C * W / (clearance * speed)

    def to_ross_kwargs(self, *, viscosity: float, speed: float, radius: float, clearance: float) -> dict:
        """Keywords for ``ross.BearingElement(n=..., **kwargs)`` (ROSS is not imported).

        Returns ``kxx, kxy, kyx, kyy`` [N/m], ``cxx, cxy, cyx, cyy`` [N s/m] and
        ``frequency`` [rad/s] (one-element lists: the coefficients at this speed).
        """
        K, C = self.to_si(viscosity=viscosity, speed=speed, radius=radius, clearance=clearance)
        out = {f"k{a}{b}": [float(K[i, j])] for i, a in enumerate("xy") for j, b in enumerate("xy")}
        out.update({f"c{a}{b}": [float(C[i, j])] for i, a in enumerate("xy") for j, b in enumerate("xy")})
        out["frequency"] = [float(speed)]
        return out


def _to_ross_frame(force_dir: float, K: np.ndarray) -> np.ndarray:
    # rotate so that the static load on the journal (= film force on the bore direction) is along -y
    Q = _rot(-math.pi / 2 - force_dir)
    return Q @ K @ Q.T


def dynamic_coefficients(eq: Equilibrium, *, method: str = "linearized", step: float = 1e-5) -> DynamicCoefficients:
    """The eight film coefficients at a static equilibrium.

    Parameters
    ----------
    eq : Equilibrium
        From :func:`equilibrium` (its meshes and solution are reused).
    method : {"linearized", "finite-difference"}
        Linearization of the discrete Reynolds equation on the rupture set,
        or central differences of the nonlinear (cavitated) force with
        ``step`` in position [c] and velocity [c omega].

    Notes
    -----
    Both methods keep the meshes fixed, so for the full bearing the
    ``p = 0`` line stays where the static line of largest film is (as an
    axial groove would), rather than following the perturbed line of centres.
    """
    if method not in ("linearized", "finite-difference"):
        raise ValueError(f"method must be 'linearized' or 'finite-difference', got {method!r}")
    if not (0 < step < 1e-2):
        raise ValueError(f"step must be in (0, 1e-2), got {step!r}")
    state = eq.state
    cav = state.results[0].cavitation
    if cav == "gumbel":
        raise ValueError("dynamic coefficients need cavitation='reynolds' or 'none'")
    rot = state.rotation
    if method == "linearized":
        if any(sup is None for sup in state.sups):
            raise ValueError("method='linearized' needs the Galerkin system; finite-volume solutions "
                             "(cavitation='jfo', periodic or recessed surfaces) take method='finite-difference'")
        dFx, dFv = _linearized(state)
    else:
        # journal position in the mesh frame
        R = _rot(-rot)
        xy = R @ eq.position
        dFx, dFv = np.zeros((2, 2)), np.zeros((2, 2))
        element = state.sups[0].operators.element if state.sups[0] is not None else "P1"
        # every perturbed solve starts from the equilibrium's rupture set (a step of 1e-5 moves it little)
        warm = state if cav in ("reynolds", "jfo") else None

        def force(at, squeeze=(0.0, 0.0)):
            return _solve_state(_bearing_of(eq), eq.meshes, *at, cav, squeeze_xy=squeeze, element=element,
                                warm_start=warm).force
        for j in range(2):
            d = np.zeros(2)
            d[j] = step
            dFx[:, j] = (force(xy + d) - force(xy - d)) / (2 * step)
            dFv[:, j] = (force(xy, d) - force(xy, -d)) / (2 * step)
    # K_ij = -d f_journal,i / d x_j = d F_bore,i / d x_j ; from the mesh frame to the bearing frame
    Rm = _rot(rot)
    K = Rm @ dFx @ Rm.T
    C = Rm @ dFv @ Rm.T
    w = float(np.hypot(*eq.force))
    direction = math.atan2(eq.force[1], eq.force[0])
    return DynamicCoefficients(K=_to_ross_frame(direction, K) / w, C=_to_ross_frame(direction, C) / w,
                               load=w, eps=eq.eps, attitude=eq.attitude, method=method)


def _bearing_of(eq: Equilibrium) -> JournalBearing:
    if eq.bearing is None:
        raise ValueError("the Equilibrium carries no bearing (build it with equilibrium())")
    return eq.bearing


# -- closed forms -------------------------------------------------------------------------

def short_bearing_force(eps: float, half_width: float, velocity=(0.0, 0.0), wedge: float = 1.0,
                        n: int = 4000) -> np.ndarray:
    """Force on the bore of the short (Ocvirk) bearing with a half (pi) film, in the frame of the
    line of largest film (journal displaced along ``-x``), moving at ``velocity`` [c omega].

    ``p = s (z^2 - a^2) / (2 h^3)`` with ``s = 6 dh/dphi + 12 dh/dt`` where ``s < 0``, else 0;
    the force ``-(2 a^3/3) int_{s<0} s/h^3 (cos, sin) dphi`` is integrated by the midpoint rule
    with ``n`` points. At zero velocity its magnitude is Ocvirk's
    ``W = mu U L^3/(4 c^2) eps/(1-eps^2)^2 sqrt(pi^2 (1-eps^2) + 16 eps^2)``, i.e.
    ``w = 2 a^3 eps/(1-eps^2)^2 sqrt(pi^2 (1-eps^2) + 16 eps^2)`` in package units.
    """
    phi = (np.arange(n) + 0.5) * 2 * np.pi / n
    h = 1 + eps * np.cos(phi)
    s = 6 * wedge * (-eps * np.sin(phi)) + 12 * (-velocity[0] * np.cos(phi) - velocity[1] * np.sin(phi))
    g = np.where(s < 0, s / h**3, 0.0) * (-(2 * half_width**3) / 3) * (2 * np.pi / n)
    return np.array([np.sum(g * np.cos(phi)), np.sum(g * np.sin(phi))])
