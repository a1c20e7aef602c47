r"""The half-space compliance on a uniform grid, applied by FFT convolution (no dense matrix).

On a mesh of :func:`bearingfe.geometry.meshing.grid_mesh` with uniform grid lines
(spacings ``dphi``, ``dz``) every triangle is a translate of one of a few
reference triangles (two for the tensor split), so the Boussinesq influence of
:mod:`bearingfe.elastic.half_space`

    w_i = kappa sum_T sum_k int_T lambda_k(y) / |x_i - y| dA(y) p(dof_k(T))

is, for each reference triangle ``s`` and each of its vertices ``k``, a discrete
convolution over the cells: ``w = kappa sum_(s,k) K_(s,k) * q_(s,k)`` with the kernel
``K_(s,k)(m) = int_(T_s) lambda_k(y) / |m h - y| dA`` (the same exact integrals as the
dense matrix, ``m`` the grid offset) and ``q_(s,k)(c) = p(c + o_k)`` on the cells ``c``
that carry a triangle of shape ``s`` (none in a pocket: the holes are handled
exactly, and so is the edge of the film, where a node's hat is cut). The
convolutions are linear (zero-padded to twice the grid), by real FFTs:
``O(N log N)`` time and ``O(N)`` memory per product instead of the dense
``O(N^2)``, and the same numbers as the dense product to round-off. The pocket
term (pressure ``p_s`` over the holes) is the dense model's contour integral at
each node, ``O(N x pocket facets)``.

P1 elements only (the deflection is collocated at the grid nodes).

Any other mesh (gmsh, curved P2): :func:`half_space_grid` transfers the pressure to an
auxiliary uniform grid over the surface (the film pressure interpolated at the grid
nodes in the film, ``p_s`` in the pockets, zero outside: a continuous field), convolves
there by the same FFT and interpolates the deflection back to the film dofs. This is
an approximation of the dense map, not the same numbers: its error falls like
``spacing^2`` (on a 0.05 R0 gmsh mesh of the pump shoe with its 32 MPa pocket, P1: the
deflection within 1.3 % of the dense one at ``spacing = size``, 0.35 % at the default
``size/2``, 0.1 % at ``size/4``; the film force 3.4e-4 apart at the default).
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.fft as sfft
import scipy.sparse as sp
import skfem

from .compliance import Compliance, contact_modulus
from .half_space import element_integrals, pocket_integrals
from ..core.scales import Scale
from ..film import operators
from ..geometry.meshing import SupportMesh

__all__ = ["GridConvolution", "grid_convolution", "half_space_fft", "half_space_grid"]


def _uniform_index(values: np.ndarray, what: str) -> tuple[np.ndarray, float, float, int]:
    """Grid index of each coordinate on uniform lines: ``values = origin + index * step``."""
    lines = np.unique(np.round(values, 12))
    if lines.size < 2:
        raise ValueError(f"the mesh has a single grid line along {what}: not a grid")
    steps = np.diff(lines)
    step = float(lines[-1] - lines[0]) / (lines.size - 1)
    if np.max(np.abs(steps - step)) > 1e-9 * max(step, 1e-300) * lines.size:
        raise ValueError(f"the FFT half-space needs uniform grid lines along {what} (grid_mesh without pockets "
                         f"off the grid); spacings range {steps.min():.6g} .. {steps.max():.6g}: use "
                         f"the dense half_space on this mesh")
    index = np.rint((values - lines[0]) / step).astype(np.int64)
    if np.max(np.abs(lines[0] + index * step - values)) > 1e-9 * step * lines.size:
        raise ValueError(f"mesh nodes off the uniform grid lines along {what}: use the dense half_space")
    return index, float(lines[0]), step, int(lines.size)


#: Largest value on a grid's edge rows, relative to the field's largest, that the one-kernel product treats
#: as zero (its error is of this order relative to the product).
EDGE_ROUND_OFF = 1e-12


class GridConvolution:
    """The geometric influence ``G p = sum_j int phi_j / |x_i - y| dA p_j`` [R0] at the nodes of a uniform grid mesh.

    Built once per mesh (the kernels of the reference triangles, exact
    integrals); :meth:`__call__` applies it to a nodal field by FFT.

    Parameters
    ----------
    mesh : SupportMesh or skfem.MeshTri1
        A triangular (P1) mesh whose nodes lie on uniform grid lines and
        whose triangles are half-cells of that grid, e.g.
        :func:`bearingfe.geometry.meshing.grid_mesh` of a plain surface.

    Raises
    ------
    ValueError
        A mesh off a uniform grid (non-uniform lines, curved or other triangles).
    """

    def __init__(self, mesh: SupportMesh | skfem.MeshTri1):
        m = mesh.mesh if isinstance(mesh, SupportMesh) else mesh
        if not isinstance(m, skfem.MeshTri1):
            raise ValueError(f"the FFT half-space needs a straight P1 triangle mesh (grid_mesh), "
                             f"got {type(m).__name__}")
        ix, x0, hx, nx = _uniform_index(m.p[0], "phi")
        iz, z0, hz, nz = _uniform_index(m.p[1], "z")
        self.n_nodes = m.p.shape[1]
        self.shape = (nx, nz)                                # grid nodes along phi and z
        self.step = (hx, hz)
        self.origin = (x0, z0)
        self.flat = ix * nz + iz                             # grid position of each node
        tx, tz = ix[m.t], iz[m.t]                            # (3, n_elements)
        cx, cz = tx.min(axis=0), tz.min(axis=0)              # the cell of each triangle
        ox, oz = tx - cx, tz - cz
        if ox.max() > 1 or oz.max() > 1:
            raise ValueError("the FFT half-space needs triangles that are half-cells of the grid (grid_mesh)")
        code = (ox * 2 + oz)                                 # vertex offsets as 0..3, shape (3, n_elements)
        shapes, which = _shape_classes(code)
        ncx, ncz = nx - 1, nz - 1
        # zero-padded to at least n + (n - 1) - 1 (linear, not circular, convolution), at a fast FFT length
        px, pz = sfft.next_fast_len(2 * nx - 2, real=True), sfft.next_fast_len(2 * nz - 2, real=True)
        self._pad = (px, pz)
        # offsets m = i - c of node i from cell c, i in [0, n), c in [0, n - 1): m in [-(n - 2), n - 1]
        mx = np.arange(-(ncx - 1), nx)
        mz = np.arange(-(ncz - 1), nz)
        MX, MZ = np.meshgrid(mx, mz, indexing="ij")
        pts = np.array([MX.ravel() * hx, MZ.ravel() * hz])
        # terms (cells mask, node offset) -> kernel; triangles of different shapes on the same cells (the two
        # halves of every cell) share the masked window of a vertex offset: their kernels add up
        masks, kernels, whole_parts = [], {}, []
        for s, shape in enumerate(shapes):
            offs = [(int(c) // 2, int(c) % 2) for c in shape]
            v = np.array([[o[0] * hx for o in offs], [o[1] * hz for o in offs]])[:, :, None]  # (2, 3, 1)
            K = element_integrals(pts, v, "P1")[:, :, 0]   # (3, n_offsets)
            whole_parts.append(K)
            mask = np.zeros((ncx, ncz), bool)
            sel = which == s
            mask[cx[sel], cz[sel]] = True
            m_id = next((i for i, other in enumerate(masks) if np.array_equal(other, mask)), None)
            if m_id is None:
                masks.append(mask)
                m_id = len(masks) - 1
            for k in range(3):
                key = (m_id, offs[k])
                if key not in kernels:
                    kernels[key] = np.zeros((px, pz))
                # kernel[m mod pad] = K(m): negative offsets wrap to the end of the padded array
                kernels[key][np.mod(MX, px), np.mod(MZ, pz)] += K[k].reshape(MX.shape)
        # the cells with no triangle (the holes: pockets of a grid mesh) and the kernel of a whole cell
        self._holes = ~np.logical_or.reduce(masks)
        self._whole_shapes = _halves(shapes)
        if self._whole_shapes:  # the two reference triangles tile the cell: its kernel is the sum of theirs
            whole = sum(kernel.sum(axis=0) for kernel in whole_parts)
        else:
            cell = np.array([[0.0, hx, hx, 0.0, hx, 0.0], [0.0, 0.0, hz, 0.0, hz, hz]]).reshape(2, 2, 3).transpose(0, 2, 1)
            whole = element_integrals(pts, cell, "P1").sum(axis=(0, 2))  # sum of the barycentric weights: 1
        self._cell_kernel = np.zeros((px, pz))
        self._cell_kernel[np.mod(MX, px), np.mod(MZ, pz)] = whole.reshape(MX.shape)
        self._masks = [None if m.all() else m.astype(float) for m in masks]
        self._keys = list(kernels)
        self._kernels = sfft.rfft2(np.array([kernels[key] for key in self._keys]), axes=(1, 2))
        self._node_kernel = None
        if all(mask is None for mask in self._masks):
            # every cell carries its triangles: for a field that vanishes on the grid's edge rows every node
            # with p != 0 has all its cells, and sum_o K_o * p(. + o) is one convolution with the node kernel
            # sum_o K_o(m + o) (see __call__)
            node = sum(np.roll(kernels[key], (-key[1][0], -key[1][1]), axis=(0, 1)) for key in self._keys)
            self._node_kernel = sfft.rfft2(node)
        self._ncells = (ncx, ncz)
        self._p, self._t = m.p, m.t
        self._cell_triangles = np.argsort(cx * ncz + cz, kind="stable")  # two per cell where no hole

    def __call__(self, p: np.ndarray) -> np.ndarray:
        """``G p`` at the nodes [R0] for the nodal values ``p`` (shape ``(n_nodes,)`` or ``(n_nodes, k)``)."""
        p = np.asarray(p, float)
        if p.shape[0] != self.n_nodes:
            raise ValueError(f"p must have one value per node ({self.n_nodes}), got shape {p.shape}")
        if p.ndim == 2:
            return np.column_stack([self(p[:, j]) for j in range(p.shape[1])])
        nx, nz = self.shape
        ncx, ncz = self._ncells
        grid = np.zeros((nx, nz))
        grid.ravel()[self.flat] = p
        if self._node_kernel is not None and self._edges_vanish(grid):
            # one convolution (the same sum to round-off): the offsets i - j of the nodes that carry p span
            # less than the padding, and the two that alias (i or j on an edge row) meet p = 0
            w = sfft.irfft2(self._node_kernel * sfft.rfft2(grid, s=self._pad), s=self._pad)
            return w[:nx, :nz].ravel()[self.flat]
        q = np.zeros((len(self._keys), *self._pad))
        for t, (m_id, (ox, oz)) in enumerate(self._keys):
            window = grid[ox:ox + ncx, oz:oz + ncz]
            mask = self._masks[m_id]
            q[t, :ncx, :ncz] = window if mask is None else mask * window
        total = np.einsum("tij,tij->ij", self._kernels, sfft.rfft2(q, axes=(1, 2)))
        w = sfft.irfft2(total, s=self._pad)
        # (K * q)(i) = sum_c K(i - c) q(c): node i sits at index i of the padded result
        return w[:nx, :nz].ravel()[self.flat]


    @staticmethod
    def _edges_vanish(grid: np.ndarray) -> bool:
        """Whether the field is zero on the grid's edge rows, to round-off (``EDGE_ROUND_OFF`` of its largest
        value: a film's zero boundary value interpolated by a curved P2 element is ~1e-13, not 0)."""
        edge = max(np.abs(grid[0]).max(), np.abs(grid[-1]).max(), np.abs(grid[:, 0]).max(), np.abs(grid[:, -1]).max())
        return edge <= EDGE_ROUND_OFF * np.abs(grid).max()

    def probes(self, x: np.ndarray) -> sp.csr_matrix:
        """P1 interpolation ``(n, n_nodes)`` from the grid's nodes to the points ``x`` (2, n) [R0].

        The cell of each point by index arithmetic on the uniform lines (no search), then the half of it that
        holds the point; points off the grid's box (round-off at its edge) take its nearest cell, extrapolated.
        Needs a grid without holes (every cell carries its two triangles)."""
        if self._holes.any() or self._t.shape[1] != 2 * self._ncells[0] * self._ncells[1]:
            raise ValueError("GridConvolution.probes needs a grid whose every cell carries two triangles "
                             "(no pockets): locate the points with bearingfe.geometry.locate instead")
        from ..geometry.locate import INSIDE_TOLERANCE, barycentric

        x = np.asarray(x, float)
        ncx, ncz = self._ncells
        i = np.clip(np.floor((x[0] - self.origin[0]) / self.step[0]).astype(np.int64), 0, ncx - 1)
        k = np.clip(np.floor((x[1] - self.origin[1]) / self.step[1]).astype(np.int64), 0, ncz - 1)
        pair = self._cell_triangles.reshape(-1, 2)[i * ncz + k]          # (n, 2): the cell's two triangles
        first, second = (barycentric(self._p, self._t, pair[:, j], x) for j in range(2))
        # the half where the point's smallest barycentric coordinate is largest (inside: >= -tolerance)
        worst = [np.minimum(np.minimum(l1, l2), 1.0 - l1 - l2) for l1, l2 in (first, second)]
        use_second = worst[1] > np.maximum(worst[0], -INSIDE_TOLERANCE)
        cells = np.where(use_second, pair[:, 1], pair[:, 0])
        l1, l2 = (np.where(use_second, b, a) for a, b in zip(first, second))
        n = x.shape[1]
        rows = np.tile(np.arange(n), 3)
        cols = self._t[:, cells].ravel()
        return sp.csr_matrix((np.concatenate([1.0 - l1 - l2, l1, l2]), (rows, cols)), shape=(n, self.n_nodes))

    def holes(self) -> np.ndarray:
        """``int_holes 1/|x_i - y| dA`` [R0] at the nodes: the cells of the grid that carry no triangle."""
        nx, nz = self.shape
        ncx, ncz = self._ncells
        if not self._holes.any():
            return np.zeros(self.n_nodes)
        w = sfft.irfft2(sfft.rfft2(self._cell_kernel) * sfft.rfft2(self._holes.astype(float), s=self._pad),
                        s=self._pad)
        return w[:nx, :nz].ravel()[self.flat]


def grid_convolution(mesh: SupportMesh) -> GridConvolution:
    """The :class:`GridConvolution` of ``mesh``, cached on the mesh (built once per mesh)."""
    return mesh.cached("half_space_fft", lambda: GridConvolution(mesh))


def _pockets(conv: GridConvolution, mesh: SupportMesh) -> np.ndarray:
    """``int_pockets 1/|x_i - y| dA`` at the nodes: by FFT over the holes of the grid when they are the pockets.

    The dense model integrates along the contours of the ``inlet`` boundary
    (:func:`bearingfe.elastic.half_space.pocket_integrals`, ``O(N x facets)``);
    on a grid mesh the pockets are whole cells left out, so the same integral is
    one convolution. Checked at a few nodes against the contour integral; where
    they differ (holes that are not pockets), the contour integral is used.
    """
    m, facets = mesh.mesh, mesh.boundaries.get("inlet")
    if facets is None or len(facets) == 0:
        return np.zeros(conv.n_nodes)
    fast = conv.holes()
    probe = np.unique(np.linspace(0, conv.n_nodes - 1, 9).astype(int))
    exact = pocket_integrals(m.p[:, probe], m, facets)
    if np.max(np.abs(fast[probe] - exact)) <= 1e-9 * np.max(np.abs(exact)):
        return fast
    return pocket_integrals(m.p, m, facets)


def half_space_fft(mesh: SupportMesh, scale: Scale, modulus, element: str = "P1") -> Compliance:
    """Compliance of two elastic half-spaces under the film, applied by FFT on a uniform grid mesh.

    The same map as :func:`bearingfe.elastic.half_space` (exact influence
    coefficients, collocated at the nodes) without its dense matrix:
    :attr:`Compliance.matrix` is None and :meth:`Compliance.apply` convolves
    by FFT, ``O(N log N)``; the size limit of the dense compliance does not
    apply, and the coupled solves take the matrix-free Newton-Krylov path.

    Parameters
    ----------
    mesh : SupportMesh
        A P1 grid mesh with uniform lines (:func:`bearingfe.grid_mesh`) [R0].
    scale : Scale
    modulus : float, Material or (Material, Material)
        As in :func:`bearingfe.elastic.half_space`.
    element : {"P1"}

    Returns
    -------
    Compliance
        ``model="half-space-fft"``, ``matrix=None``.
    """
    if not isinstance(scale, Scale):
        raise ValueError(f"scale must be a bearingfe.Scale, got {type(scale).__name__}")
    if element != "P1":
        raise ValueError(f"the FFT half-space is built for element 'P1' (nodes on the grid), got {element!r}; "
                         "use the dense half_space for P2")
    e_star = contact_modulus(modulus)
    start = time.perf_counter()
    conv = grid_convolution(mesh)
    basis = operators(mesh, element).basis
    if basis.N != conv.n_nodes:
        raise ValueError("the FFT half-space needs the P1 dofs to be the mesh nodes")
    kappa = 0.0 if math.isinf(e_star) else scale.pressure * scale.radius / (math.pi * e_star * scale.clearance)
    pocket = kappa * _pockets(conv, mesh)

    def apply(p: np.ndarray) -> np.ndarray:
        return kappa * conv(p) if kappa else np.zeros(np.shape(p))

    return Compliance(mesh=mesh, element=element, model="half-space-fft", matrix=None, pocket=pocket,
                      modulus=e_star, scale=scale, seconds=time.perf_counter() - start, operator=apply)


def _shape_classes(code: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct rows of the vertex codes (3, n_elements), sorted, and each triangle's row: what
    ``np.unique(code.T, axis=0, return_inverse=True)`` gives, by counting the 64 possible keys (no sort)."""
    key = code[0] * 16 + code[1] * 4 + code[2]
    present = np.flatnonzero(np.bincount(key, minlength=64))
    lookup = np.full(64, -1)
    lookup[present] = np.arange(present.size)
    return np.array([present // 16, present // 4 % 4, present % 4]).T, lookup[key]


def _halves(shapes: np.ndarray) -> bool:
    """Whether the reference triangles (rows of vertex codes ``2 ox + oz`` in 0..3) are the two halves of the
    cell cut along one diagonal."""
    found = {frozenset(int(c) for c in shape) for shape in shapes}
    return found in ({frozenset((0, 1, 3)), frozenset((0, 2, 3))}, {frozenset((0, 1, 2)), frozenset((1, 2, 3))})


def _median_edge(m) -> float:
    """The median length of the triangles' straight edges (vertex to vertex) [R0]."""
    t, p = m.t[:3], m.p
    return float(np.median(np.concatenate([np.hypot(*(p[:, t[i]] - p[:, t[j]]))
                                           for i, j in ((0, 1), (1, 2), (2, 0))])))


def half_space_grid(mesh: SupportMesh, scale: Scale, modulus, element: str = "P1", *,
                    spacing: float | None = None) -> Compliance:
    """Compliance of two elastic half-spaces on any film mesh, through an auxiliary uniform grid (FFT).

    Approximate (see the module notes): the pressure is interpolated to a
    uniform grid over the mesh's bounding box (``p_s`` in the pockets of
    ``mesh.surface``, zero outside the film), convolved there with the exact
    cell kernels of :class:`GridConvolution` and interpolated back to the dofs.
    ``O(G log G)`` per product for ``G`` grid nodes, no dense matrix, no size
    limit; the error against :func:`bearingfe.elastic.half_space` falls like
    ``spacing^2``.

    Parameters
    ----------
    mesh : SupportMesh
        Any film mesh (gmsh, curved) [R0]; with pockets it needs its ``surface``.
    scale : Scale
    modulus : float, Material or (Material, Material)
        As in :func:`bearingfe.elastic.half_space`.
    element : {"P1", "P2"}
    spacing : float, optional
        Grid spacing [R0], > 0; default half the median edge of the mesh's
        triangles (not its nominal size: a small surface or a graded mesh has
        edges well below it, and a grid coarser than the dofs makes ``C``
        singular on them; a mesh read from a file has no nominal size).

    Returns
    -------
    Compliance
        ``model="half-space-grid"``, ``matrix=None``.
    """
    from ..geometry.locate import lattice_cells, probe_matrices

    if not isinstance(scale, Scale):
        raise ValueError(f"scale must be a bearingfe.Scale, got {type(scale).__name__}")
    if not isinstance(mesh, SupportMesh):
        raise ValueError(f"mesh must be a bearingfe SupportMesh, got {type(mesh).__name__}")
    e_star = contact_modulus(modulus)
    start = time.perf_counter()
    h = 0.5 * _median_edge(mesh.mesh) if spacing is None else spacing
    if not (isinstance(h, (int, float)) and math.isfinite(h) and h > 0):
        raise ValueError(f"spacing must be a grid spacing in R0, > 0, got {spacing!r}")
    m = mesh.mesh
    lo, hi = m.p.min(axis=1), m.p.max(axis=1)
    n = np.maximum(2, np.ceil((hi - lo) / h).astype(int) + 1)
    if n[0] * n[1] > 50 * max(m.p.shape[1], 1000):
        raise ValueError(f"spacing = {h:g} R0 makes a grid of {n[0] * n[1]} nodes for a mesh of {m.p.shape[1]}: "
                         "choose a spacing near the mesh size")
    lines = (np.linspace(lo[0], hi[0], n[0]), np.linspace(lo[1], hi[1], n[1]))
    steps = ((hi[0] - lo[0]) / (n[0] - 1), (hi[1] - lo[1]) / (n[1] - 1))
    grid = skfem.MeshTri1.init_tensor(*lines)
    conv = GridConvolution(grid)
    basis = operators(mesh, element).basis
    X = grid.p
    lattice = lattice_cells(m.p, m.t, lo, steps, n)
    cells = lattice[np.rint((X[0] - lo[0]) / steps[0]).astype(np.int64),
                    np.rint((X[1] - lo[1]) / steps[1]).astype(np.int64)]
    inside = cells >= 0
    pockets = np.zeros(X.shape[1], bool)
    if len(mesh.boundaries.get("inlet", ())):
        if mesh.surface is None:
            raise ValueError("half_space_grid needs mesh.surface to know its pockets (a mesh read from a file "
                             "has none): use the dense half_space")
        for shape in mesh.surface.inlets:
            pockets |= np.asarray(shape.contains(X[0], X[1]), bool)
    # by the exact shapes, not the straight triangles: a curved mesh's chords cut slivers of pocket and outline
    inside &= ~pockets
    if mesh.surface is not None and not mesh.surface.is_rectangular:
        inside &= np.asarray(mesh.surface.outline.contains(X[0], X[1]), bool)  # on it: p = 0 anyway
    rows = np.flatnonzero(inside)
    T = probe_matrices(basis, X[:, rows], cells[rows])[0].tocoo()
    to_grid = sp.csr_matrix((T.data, (rows[T.row], T.col)), shape=(X.shape[1], basis.N))
    back = conv.probes(basis.doflocs)
    kappa = 0.0 if math.isinf(e_star) else scale.pressure * scale.radius / (math.pi * e_star * scale.clearance)
    pocket = kappa * (back @ conv(pockets.astype(float)))

    def apply(p: np.ndarray) -> np.ndarray:
        return kappa * (back @ conv(to_grid @ p)) if kappa else np.zeros(np.shape(p))

    return Compliance(mesh=mesh, element=element, model="half-space-grid", matrix=None, pocket=pocket,
                      modulus=e_star, scale=scale, seconds=time.perf_counter() - start, operator=apply)
