r"""The shoe as a 3-D elastic block held at its back, condensed to a compliance on the film dofs.

The half-space ignores the finite shoe (its thickness, how it is held); a
block clamped at its back is stiffer. :func:`block_compliance` models the shoe as
such a block: 3-D linear elasticity (P1 tetrahedra, scikit-fem) solved once
per film pressure basis function and condensed to a dense compliance on the
film dofs, with the eccentric as a half-space on top.
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem

from .compliance import Compliance, check_dense_size, combined_modulus
from ..core.limits import LimitError, check_limit
from .half_space import half_space
from ..core.machine import Material
from ..core.scales import Scale
from ..film import operators
from ..geometry.locate import barycentric, nearest_cells
from ..geometry.meshing import SupportMesh

__all__ = ["block_compliance", "body_compliance"]


def _graded(length: float, size: float, top_size: float) -> np.ndarray:
    """Coordinates from ``-length`` to 0 with spacing ``top_size`` at 0 growing geometrically to ``size``."""
    z, step = [0.0], top_size
    while z[-1] > -length:
        z.append(z[-1] - step)
        step = min(size, step * 1.4)
    z[-1] = -length
    if len(z) > 2 and z[-2] - z[-1] < 0.3 * step:
        z.pop(-2)
    return np.array(z[::-1])


def block_compliance(mesh: SupportMesh, scale: Scale, shoe: Material, thickness: float, *,
              counterpart: Material | None = None, element: str = "P1", margin: float = 0.0,
              size: float | None = None) -> Compliance:
    """Compliance of the shoe as a 3-D elastic block held at its back, condensed to the film dofs.

    The shoe is the block over the film's bounding box (widened by ``margin``
    on each side) of depth ``thickness``, flat (the arc's curvature is left
    out), clamped on its back face (seated on the plunger), free on its sides.
    Linear elasticity with P1 tetrahedra on a tensor mesh graded towards the
    film face is solved once for each film pressure basis function
    (``int phi_j n . v`` on the film face; the pockets load it with ``p_s``)
    and the normal displacement of the film face is read at the film dofs:
    a dense compliance on the film dofs, like :func:`half_space`. The other
    surface (the eccentric), if given, adds its own half-space compliance.

    Parameters
    ----------
    mesh : SupportMesh
    scale : Scale
    shoe : Material
    thickness : float
        Depth of the shoe body [m], > 0.
    counterpart : Material, optional
        The eccentric (a half-space); default rigid.
    element : {"P1", "P2"}
        Of the film (the pressure basis).
    margin : float
        Extra width of the body beyond the film on every side [m], >= 0.
    size : float, optional
        Element size of the body away from the film face [R0] (default the
        film mesh size).
    """
    if not isinstance(scale, Scale):
        raise ValueError(f"scale must be a bearingfe.Scale, got {type(scale).__name__}")
    if not isinstance(shoe, Material):
        raise ValueError(f"shoe must be a bearingfe.Material, got {type(shoe).__name__}")
    if not (math.isfinite(thickness) and thickness > 0):
        raise ValueError(f"thickness must be a finite number > 0 [m], got {thickness!r}")
    if not (math.isfinite(margin) and margin >= 0):
        raise ValueError(f"margin must be a finite number >= 0 [m], got {margin!r}")
    start = time.perf_counter()
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    basis2 = operators(mesh, element).basis
    check_dense_size(basis2.N)
    h = float(size if size is not None else mesh.size)
    if not (math.isfinite(h) and h > 0):
        raise ValueError(f"size must be a finite element size > 0 [R0], got {size!r}")
    lo, hi = mesh.mesh.p.min(axis=1) - margin / scale.radius, mesh.mesh.p.max(axis=1) + margin / scale.radius
    counts = [max(2, int(math.ceil((hi[k] - lo[k]) / h))) for k in range(2)]
    _check_body_size(counts, thickness / scale.radius, h, basis2.N)
    axes = [np.linspace(lo[k], hi[k], counts[k] + 1) for k in range(2)]
    zs = _graded(thickness / scale.radius, 2 * h, h / 2)
    body = skfem.MeshTet.init_tensor(axes[0], axes[1], zs)
    lam, mu = lame_parameters(1.0, shoe.poisson_ratio)  # E = 1: displacements scale with 1/E
    vb = skfem.Basis(body, skfem.ElementVector(skfem.ElementTetP1()))
    K = linear_elasticity(lam, mu).assemble(vb).tocsr()
    top = body.facets_satisfying(lambda x: np.isclose(x[2], 0.0))
    back = body.facets_satisfying(lambda x: np.isclose(x[2], zs[0]))
    fb = skfem.FacetBasis(body, vb.elem, facets=top, intorder=4)
    xq = np.array(fb.global_coordinates())  # (3, n_facets, n_q)
    pts = xq[:2].reshape(2, -1)
    P, film_mask, pocket_mask = _film_face_probe(basis2, mesh, pts)
    dx = np.asarray(fb.dx).ravel()
    Nz = _normal_component_values(fb)  # (n_q_total, vb.N): z-component of the vector basis at the points
    F = (Nz.T @ sp.diags(-dx)) @ P        # pressure pushes into the body (-z): (vb.N, n_film)
    f_pocket = Nz.T @ (-dx * pocket_mask)
    fixed = vb.get_dofs(back).all()
    free = np.setdiff1d(np.arange(vb.N), fixed)
    lu = spla.splu(sp.csc_matrix(K[free][:, free]))
    U = np.zeros((vb.N, P.shape[1] + 1))
    rhs = np.column_stack([np.asarray(F[free].todense()), f_pocket[free]])
    U[free] = lu.solve(rhs)
    d = basis2.doflocs
    probe = vb.probes(np.vstack([d, np.zeros(d.shape[1])]))  # displacement components at the film dofs
    uz = probe @ U  # rows: the dofs' ux, uy, uz stacked by component
    n = d.shape[1]
    opening = -np.asarray(uz)[2 * n:3 * n] if uz.shape[0] == 3 * n else -np.asarray(uz)
    return body_compliance(mesh, scale, shoe, opening[:, :-1], opening[:, -1], model="body", element=element,
                           counterpart=counterpart, start=start)


def _check_body_size(counts: list[int], depth: float, h: float, n_film: int) -> None:
    """Refuse a block body too large to build, before any of it is made.

    ``counts`` are its cells along phi and z, ``depth`` its thickness [R0]
    (layers about ``2 h`` thick, :func:`_graded`), ``n_film`` the film dofs.
    The body has 6 tetrahedra per cell (the ``elements`` limit of
    :mod:`bearingfe.core.limits`) and a dense block of ``3 nodes x (n_film + 1)``
    displacements (at most ``16 x compliance^2`` numbers: 2 GB at the default).
    """
    layers = depth / (2 * h) + 8  # the geometric start from h / 2 adds a few layers
    cells = float(counts[0]) * float(counts[1]) * layers
    try:
        check_limit("elements", 6 * cells)
        dense = 3.0 * (counts[0] + 1) * (counts[1] + 1) * (layers + 1) * (n_film + 1)
        check_limit("compliance", math.sqrt(dense / 16.0))
    except LimitError as exc:
        raise LimitError(f"the block body ({counts[0]} x {counts[1]} x {layers:.3g} cells of size {h:.3g} R0, "
                         f"thickness {depth:.3g} R0; {n_film} film dofs): {exc}") from None


def _film_face_probe(basis2, mesh: SupportMesh, pts: np.ndarray):
    """Film basis values at points of the film face; which points lie in the film, which in a pocket."""
    m = mesh.mesh
    cells = nearest_cells(m.p, m.t, pts)
    l1, l2 = barycentric(m.p, m.t, cells, pts)
    inside = (l1 >= -1e-9) & (l2 >= -1e-9) & (l1 + l2 <= 1 + 1e-9)
    # basis values from the barycentric coordinates of the straight triangles (exact on straight
    # meshes; on curved ones the film face is loaded as if the pocket edges were their chords)
    lam = np.array([1.0 - l1 - l2, l1, l2])[:, inside]
    if basis2.Nbfun == 3:
        vals = lam
    else:  # scikit-fem's P2 order: vertices, then edges 01, 12, 02
        vals = np.array([lam[0] * (2 * lam[0] - 1), lam[1] * (2 * lam[1] - 1), lam[2] * (2 * lam[2] - 1),
                         4 * lam[0] * lam[1], 4 * lam[1] * lam[2], 4 * lam[0] * lam[2]])
    rows = np.tile(np.flatnonzero(inside), vals.shape[0])
    cols = basis2.element_dofs[:, cells[inside]].ravel()
    P = sp.coo_matrix((vals.ravel(), (rows, cols)), shape=(pts.shape[1], basis2.N))
    # the surface is the rectangle arc x (-a, a): its points outside the film elements are pocket points
    (a1, a2), half = mesh.surface.arc, mesh.surface.half_width
    in_box = (pts[0] >= a1) & (pts[0] <= a2) & (np.abs(pts[1]) <= half)
    pocket = (~inside & in_box).astype(float)
    return sp.csr_matrix(P), inside, pocket


def _normal_component_values(fb) -> sp.csr_matrix:
    """Values of the z-component of each vector basis function at the facet quadrature points."""
    n_f, n_q = np.asarray(fb.dx).shape
    rows, cols, vals = [], [], []
    dofs = fb.element_dofs  # (Nbfun, n_facets)
    for k in range(fb.Nbfun):
        v = np.asarray(fb.basis[k][0])  # (3, n_f, n_q) vector values
        comp = v[2]
        r = np.arange(n_f * n_q).reshape(n_f, n_q)
        rows.append(r.ravel())
        cols.append(np.repeat(dofs[k], n_q))
        vals.append(comp.ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n_f * n_q, fb.N))


def body_compliance(mesh: SupportMesh, scale: Scale, shoe: Material, opening: np.ndarray, pocket: np.ndarray, *,
                    model: str, element: str, counterpart: Material | None = None,
                    start: float | None = None) -> Compliance:
    """The :class:`Compliance` of an elastic body from its film openings under unit loads.

    Parameters
    ----------
    mesh, scale, element
        The film mesh, its scales and element.
    shoe : Material
        The body's material; ``opening`` was computed with Young's modulus 1
        and pressures in units of ``scale.pressure``.
    opening : ndarray, shape (n, n)
        Film opening at each film dof under the unit load of each film dof,
        from the body solved with Young's modulus 1, lengths in R0 and
        pressures in units of ``scale.pressure`` [R0]; the factor
        ``p_scale R0 / (E c)`` makes it clearances per unit pressure.
    pocket : ndarray, shape (n,)
        The opening under a unit pressure over the pockets (same units).
    model : str
        Name of the body model (``"body"``, ``"shoe"``).
    counterpart : Material, optional
        The other surface, an elastic half-space added in series.
    start : float, optional
        ``time.perf_counter()`` when the build began (for ``seconds``).
    """
    factor = scale.pressure * scale.radius / (shoe.youngs_modulus * scale.clearance)
    matrix, pocket = factor * np.asarray(opening), factor * np.asarray(pocket)
    e_star = shoe.youngs_modulus / (1 - shoe.poisson_ratio**2)
    if counterpart is not None:
        other = half_space(mesh, scale, counterpart, element)
        matrix, pocket = matrix + other.matrix, pocket + other.pocket
        e_star = combined_modulus(shoe, counterpart)
    seconds = math.nan if start is None else time.perf_counter() - start
    return Compliance(mesh=mesh, element=element, model=model, matrix=matrix, pocket=pocket, modulus=e_star,
                      scale=scale, seconds=seconds)
