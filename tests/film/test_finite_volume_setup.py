"""The per-mesh set-up of the JFO solver: recess integrals of the grid faces, facets kept by the meshers, caches."""

import numpy as np
import skfem

from bearingfe import Circle, Recess, Surface, grid_mesh, mesh_surface
from bearingfe.core.compressed import csc_of, csr_sum, csr_transposed, sorted_entries
from bearingfe.film import finite_volume as fv
from bearingfe.film.finite_volume import solve_jfo
from bearingfe.film.thickness import UniformFilm


def _dimpled():
    """Four circular dimples of two depths on a unit slider (at least four: the bucketed recess test)."""
    centres = [(0.3, -0.2), (0.7, -0.2), (0.3, 0.2), (0.7, 0.2)]
    return Surface(arc=(0.0, 1.0), half_width=0.5,
                   recesses=[Recess(Circle(c, 0.15), 0.5 + 0.5 * (k % 2)) for k, c in enumerate(centres)])


def test_line_recess_meets_the_chord_lengths():
    """``int depth dz`` along lines ``phi = x`` through circular dimples: depth times the chord
    ``2 sqrt(r^2 - (x - cx)^2)`` (closed form). Each contour crossing is located to ``2**-30`` of a
    sub-interval (an eighth of the segment), so the integrals agree to 1e-9 of the segment length. The lines
    cross the dimples within 0.1 of their centres: chords of 0.22 or more, longer than a sub-interval (the
    method's stated condition: at most one crossing per sub-interval)."""
    surface = _dimpled()
    x = np.concatenate([np.linspace(0.2, 0.4, 21), np.linspace(0.6, 0.8, 21)])
    lo, hi = np.full(x.size, -0.5), np.full(x.size, 0.5)
    got = fv._line_recess(surface, x, lo, hi)
    expected = np.zeros(x.size)
    for r in surface.recesses:
        (cx, _), radius = r.shape.center, r.shape.radius
        expected += r.depth * 2.0 * np.sqrt(np.clip(radius**2 - (x - cx) ** 2, 0.0, None))
    assert np.abs(got - expected).max() < 1e-9


def test_face_recess_lines_near_their_faces_recesses_are_the_lines_own_test():
    """The recess part of the grid faces' film, each face's lines taken near the recesses the face is near (the
    faces' overlaps found once): bit for bit the midpoint rule written out with each line's own overlap test
    (:func:`_line_circles` by default), the middle line where the outer and middle lines agree, else all 8."""
    surface = _dimpled()
    g = fv._grid_faces(grid_mesh(surface, 1 / 29))
    got = fv._face_recess(surface, g.x0, g.x1, g.lo, g.hi)
    lines = np.array([fv._line_circles(surface, g.x0 + (k + 0.5) / 8 * (g.x1 - g.x0), g.lo, g.hi) for k in range(8)])
    cut = (lines[0] != lines[4]) | (lines[4] != lines[7])
    others = lines[[1, 2, 3, 5, 6]].sum(axis=0)
    expected = np.where(cut, (others + lines[0] + lines[4] + lines[7]) / 8, lines[4])
    assert np.count_nonzero(cut) > 50 and np.count_nonzero(expected) > 200
    assert np.array_equal(got, expected)


def test_line_circles_at_once_are_the_chords_added_circle_by_circle():
    """All line-circle pairs at once (summed by ``bincount``) give bit for bit the chords added circle by circle
    in the circles' order (the previous loop, written out), lines crossing two dimples among them."""
    surface = _dimpled()
    rng = np.random.default_rng(7)
    x = rng.uniform(0.0, 1.0, 400)
    lo = rng.uniform(-0.5, 0.0, 400)
    hi = lo + rng.uniform(0.0, 0.8, 400)
    expected = np.zeros(x.size)
    for r, near in zip(surface.recesses, fv._overlaps(surface, x, x, lo, hi)):
        (cx, cz), radius = r.shape.center, r.shape.radius
        half = np.sqrt(np.maximum(radius * radius - (x[near] - cx) ** 2, 0.0))
        expected[near] += r.depth * np.maximum(np.minimum(hi[near], cz + half) - np.maximum(lo[near], cz - half), 0.0)
    got = fv._line_circles(surface, x, lo, hi)
    assert np.count_nonzero(expected) > 100 and np.array_equal(got, expected)
    assert np.array_equal(fv._line_circles(surface, x[:0], lo[:0], hi[:0]), np.zeros(0))


def test_line_pairs_are_each_recesses_lines_concatenated():
    """The (line, recess) pairs of the face lines built at once (:func:`_line_pairs`) are the previous path's:
    per recess its places shifted to each line (``place + j n``, line by line), concatenated in the recesses'
    order, the recess of each pair repeated alike; with recesses near no rectangle and none at all."""
    rng = np.random.default_rng(13)
    for n, lines in ((40, 3), (40, 5), (7, 1), (0, 3)):
        places = [np.sort(rng.choice(n, size, replace=False)).astype(np.int64) if n else np.zeros(0, np.int64)
                  for size in rng.integers(0, n + 1, 6)]
        places[2] = np.zeros(0, np.int64)
        rows = [(w[None, :] + n * np.arange(lines)[:, None]).ravel() for w in places]
        idx, which = fv._line_pairs(places, lines, n)
        assert idx.dtype == np.int64 and np.array_equal(idx, np.concatenate(rows))
        assert np.array_equal(which, np.repeat(np.arange(len(rows)), [r.size for r in rows]))
    idx, which = fv._line_pairs([], 3, 10)
    assert idx.size == 0 and which.size == 0


def test_tensor_overlaps_are_the_rectangles_own_test():
    """The rectangles of a tensor grid near each recess found from the lines (:func:`_tensor_overlaps`, one and two
    copies: a grid's two triangles per cell) are those of each rectangle's own overlap test (:func:`_overlaps`),
    on uneven cells and on the nodes (zero-width rectangles)."""
    mesh = grid_mesh(_dimpled(), 1 / 17, size_z=1 / 9)
    xs, zs = fv.tensor_lines(mesh)
    for (x_lo, x_hi), (z_lo, z_hi) in (((xs[:-1], xs[1:]), (zs[:-1], zs[1:])), ((xs, xs), (zs, zs))):
        nx, nz = x_lo.size, z_lo.size
        x0, x1 = np.repeat(x_lo, nz), np.repeat(x_hi, nz)
        z0, z1 = np.tile(z_lo, nx), np.tile(z_hi, nx)
        want = fv._overlaps(mesh.surface, x0, x1, z0, z1)
        got = fv._tensor_overlaps(mesh.surface, (x_lo, x_hi), (z_lo, z_hi))
        assert len(got) == 4 and all(r.size > 0 for r in got)
        assert all(np.array_equal(a, b) for a, b in zip(got, want))
        two = fv._tensor_overlaps(mesh.surface, (x_lo, x_hi), (z_lo, z_hi), copies=2)
        assert all(np.array_equal(a, np.concatenate([b, b + nx * nz])) for a, b in zip(two, want))


def test_subcentroids_are_the_sub_triangles_centroids():
    """The barycentric coordinates of the cut cells' points (:func:`_subcentroids`): ``n^2`` rows summing to 1,
    the centroids of the ``n(n+1)/2`` upright sub-triangles (corners ``(i, j), (i+1, j), (i, j+1)`` over ``n``)
    then of the ``n(n-1)/2`` inverted ones, kept read-only per ``n``."""
    for n in (1, 3, 8):
        lam = fv._subcentroids(n)
        assert lam.shape == (n * n, 3) and not lam.flags.writeable and fv._subcentroids(n) is lam
        assert np.allclose(lam.sum(axis=1), 1.0, rtol=0, atol=1e-15)
        up = [((3 * i + 1) / (3 * n), (3 * j + 1) / (3 * n)) for i in range(n) for j in range(n - i)]
        down = [((3 * i + 2) / (3 * n), (3 * j + 2) / (3 * n)) for i in range(n - 1) for j in range(n - 1 - i)]
        assert np.allclose(lam[:, 1:], np.array(up + down).reshape(-1, 2), rtol=0, atol=1e-15)


def test_line_recess_on_part_of_a_chord():
    """Segments ending inside a dimple: depth times the part of the chord in ``[lo, hi]`` (closed form)."""
    surface = _dimpled()
    x = np.full(5, 0.3)
    lo = np.array([-0.5, -0.3, -0.25, -0.1, 0.0])
    hi = np.array([-0.2, -0.1, 0.0, 0.3, 0.5])
    half = 0.15   # the chord through the centres of the two dimples at phi = 0.3 (depth 0.5, at z = -0.2 and 0.2)
    expected = sum(d * np.clip(np.minimum(hi, c + half) - np.maximum(lo, c - half), 0.0, None)
                   for c, d in ((-0.2, 0.5), (0.2, 0.5)))
    assert np.allclose(fv._line_recess(surface, x, lo, hi), expected, rtol=0.0, atol=1e-9)


def test_all_circle_lines_take_the_chords_as_the_sampled_crossings_do(monkeypatch):
    """Where every recess is a circle, :func:`_line_recess` takes each chord's overlap with the segment
    directly (:func:`_line_circles`); the sampled path (every contour crossing located to ``2**-30`` of an
    eighth of the segment, forced here by hiding the Circle type) gives the same integrals to that
    resolution: at most two crossings a line, each weighing a depth of 1, 2 * (1/8) * 2**-30 = 2.3e-10,
    on segments inside, across and away from the dimples."""
    surface = _dimpled()
    rng = np.random.default_rng(5)
    x = rng.uniform(0.0, 1.0, 300)
    lo = rng.uniform(-0.5, 0.3, 300)
    hi = lo + rng.uniform(0.0, 0.5, 300)
    direct = fv._line_recess(surface, x, lo, hi)

    class NotACircle:   # every recess sampled and bisected
        pass

    monkeypatch.setattr(fv, "Circle", NotACircle)
    sampled = fv._line_recess(surface, x, lo, hi)
    assert np.count_nonzero(direct) > 100 and np.abs(direct - sampled).max() <= 2.3e-10


def test_facet_fluxes_of_named_groups_in_one_pass_equal_one_call_each():
    """The boundary facet fluxes of several named groups in one pass (their triangles and films found once)
    equal, bit for bit, those of one call per group: the same half-facet terms summed in each group's order
    (a dimpled grid: recess depth at the facets' quarter points; an empty group gives zeros)."""
    mesh = grid_mesh(_dimpled(), 1 / 12)
    ops = fv.operators(mesh, "P1")
    rng = np.random.default_rng(2)
    grad_p = rng.normal(size=(2, mesh.mesh.t.shape[1]))
    theta = rng.uniform(0.2, 1.0, mesh.mesh.nvertices)
    groups = {k: ops.facet_groups[k] for k in ("arc_start", "arc_end", "side")}
    groups["none"] = np.zeros(0, np.int64)
    together = fv._facet_flux(mesh, UniformFilm(1.0), 1.0, grad_p, theta, groups)
    for k, facets in groups.items():
        assert np.array_equal(together[k], fv._facet_flux(mesh, UniformFilm(1.0), 1.0, grad_p, theta, facets))
    assert all(np.count_nonzero(together[k]) > 0 for k in ("arc_start", "arc_end", "side"))


def test_condensed_selection_equals_the_products_with_the_unknowns_map():
    """Without a periodic seam the unknowns are a selection of the dofs: the condensed matrices taken by
    indexing equal ``S^T A S`` (the products, which drop stored zeros) in pattern and values, bit for bit, and so
    does the fixed part of the residual."""
    import scipy.sparse as sp

    mesh = grid_mesh(_dimpled(), 1 / 14)
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    unk = fv._unknowns(mesh, ops)
    p_fixed = fv._pocket_values(mesh, ops, 0.0)
    K, G, b = fv._condensed(system, unk, p_fixed, -0.05)
    St = unk.S.T.tocsr()
    A = (system.C + sp.diags(system.storage)).tocsr()
    p0 = np.full(p_fixed.size, -0.05)
    p0[unk.fixed] = p_fixed[unk.fixed]
    theta0 = np.zeros(p_fixed.size)
    theta0[unk.fixed] = 1.0
    for got, want in ((K, (St @ system.K @ unk.S).tocsr()), (G, (St @ A @ unk.S).tocsr())):
        want.sort_indices()
        assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
        assert np.array_equal(got.data, want.data)
    assert np.array_equal(b, St @ (system.K @ p0 + A @ theta0 + system.source))
    # a stored zero (as a stiffness assembled cell by cell has on the cells' diagonals): the products drop it,
    # and so does the selection
    zeroed = system.K.copy()
    r = int(unk.rep[5])   # the diagonal entry of an unknown's row
    zeroed.data[zeroed.indptr[r] + np.flatnonzero(zeroed.indices[zeroed.indptr[r]:zeroed.indptr[r + 1]] == r)] = 0.0
    want = (St @ zeroed @ unk.S).tocsr()
    want.sort_indices()
    got = fv._selected(zeroed, unk.rep)
    assert np.count_nonzero(zeroed.data == 0.0) == 1 and got.nnz == want.nnz < zeroed[unk.rep][:, unk.rep].nnz
    assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
    assert np.array_equal(got.data, want.data)


def test_boxed_depth_is_the_surfaces_own_recess_depth():
    """:func:`_boxed_depth` (each recess tests only the rectangles near it) and :func:`_rows_depth` give exactly the surface's
    ``recess_depth`` of the same points: recesses of two shapes and three depths, rectangles inside, across
    and away from the contours, 16 points in each."""
    from bearingfe import Rectangle

    surface = Surface(arc=(0.0, 1.0), half_width=0.5,
                      recesses=[Recess(Circle((0.3, 0.0), 0.2), 0.3), Recess(Rectangle((0.65, 0.25), (0.2, 0.15)), 0.7),
                                Recess(Circle((0.8, -0.3), 0.1), 1.1)])
    rng = np.random.default_rng(3)
    x0, z0 = rng.uniform(0.0, 0.95, 400), rng.uniform(-0.5, 0.45, 400)
    x1, z1 = x0 + rng.uniform(0.0, 0.1, 400), z0 + rng.uniform(0.0, 0.1, 400)
    s = rng.uniform(0.0, 1.0, (2, 400, 16))
    X, Z = x0[:, None] + (x1 - x0)[:, None] * s[0], z0[:, None] + (z1 - z0)[:, None] * s[1]
    got = fv._boxed_depth(surface, x0, x1, z0, z1, X, Z)
    assert np.array_equal(got, surface.recess_depth(X, Z))
    assert np.array_equal(fv._rows_depth(surface, X, Z), got)   # the rows' own bounding boxes
    assert all(np.any(got == r.depth) for r in surface.recesses) and np.any(got == 0.0)


def test_grid_and_gmsh_meshes_keep_the_facets_they_named():
    """The meshers' copies with named boundaries carry the facets they were named on: the same as
    scikit-fem builds from the triangles afresh, so the boundary facet indices stay valid."""
    for mesh in (grid_mesh(_dimpled(), 0.1), mesh_surface(_dimpled(), 0.2)):
        m = mesh.mesh
        assert "_facets" in m.__dict__
        fresh = skfem.MeshTri1(m.p, m.t)
        assert np.array_equal(m.facets, fresh.facets) and np.array_equal(m.t2f, fresh.t2f)
        outer = m.facets[:, mesh.boundaries["outer"]]
        assert np.all(np.isin(outer, fresh.boundary_nodes()))


def test_a_second_solve_on_a_mesh_repeats_the_first():
    """The second solve reads the per-mesh set-up (recess integrals of the faces and at the quadrature
    points, cut cells, unknowns) from the caches: the same answer as the first, to round-off."""
    film = UniformFilm(1.0)
    for couette, mesh in (("grid", grid_mesh(_dimpled(), 0.05)), ("streamline", mesh_surface(_dimpled(), 0.1))):
        first = solve_jfo(mesh, film, cavitation_pressure=-0.05, couette=couette)
        again = solve_jfo(mesh, film, cavitation_pressure=-0.05, couette=couette)
        assert first.cavitated_fraction > 0.01   # a cavity: the JFO path with its fill fraction
        assert np.allclose(again.pressure, first.pressure, rtol=0.0, atol=1e-12 * np.abs(first.pressure).max())
        assert np.allclose(again.theta, first.theta, rtol=0.0, atol=1e-12)
        assert abs(again.friction - first.friction) <= 1e-12 * abs(first.friction)


def test_box_fill_in_blocks_sums_the_same_integrals(monkeypatch):
    """The cavity's shear deficit and emptied area integrated block by block of boxes equal the one-block
    sums to round-off (the same midpoint values, summed in another grouping: 1e-13 relative), on a dimpled
    grid whose cavities span many boxes; and the area is within the pad."""
    mesh = grid_mesh(_dimpled(), 1.0 / 40)
    captured = []
    real = fv._box_fill

    def keep(*args, **kwargs):
        captured.append((args, kwargs))
        return real(*args, **kwargs)

    monkeypatch.setattr(fv, "_box_fill", keep)
    solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05, couette="grid")
    args, kwargs = captured[0]
    theta = args[3]
    assert np.count_nonzero(theta < 1.0 - 1e-12) > 50  # enough emptied boxes for several blocks below
    monkeypatch.setattr(fv, "BOX_FILL_CHUNK", 10**9)
    whole = real(*args, **kwargs)
    monkeypatch.setattr(fv, "BOX_FILL_CHUNK", 7)
    blocks = real(*args, **kwargs)
    assert whole[0] > 0.0 and 0.0 < whole[1] < 1.0   # a deficit, and an area within the unit pad
    assert np.allclose(blocks, whole, rtol=1e-13, atol=0.0)


def test_grid_box_cells_reach_midway_to_the_neighbouring_grid_lines():
    """Each node's box cell spans from midway to the previous grid line to midway to the next (the outline's
    lines: to the line itself) in ``phi`` and in ``z``, every node with a finite box, on a grid with lines
    through the edges of a pocket (a hole of whole cells): the formula written out node by node (the same
    before and after the boxes were written without the node-to-grid map)."""
    from bearingfe import Rectangle

    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[Rectangle((0.5, 0.0), (0.1, 0.1))],
                      recesses=_dimpled().recesses)
    mesh = grid_mesh(surface, 1.0 / 17)
    p = mesh.mesh.p
    box = fv._grid_faces(mesh).box
    assert box.shape == (4, p.shape[1]) and np.all(np.isfinite(box))
    for axis, rows in ((0, (0, 1)), (1, (2, 3))):
        lines = np.unique(p[axis])
        k = np.searchsorted(lines, p[axis])
        below = np.where(k > 0, 0.5 * (lines[np.maximum(k - 1, 0)] + lines[k]), lines[k])
        above = np.where(k < lines.size - 1, 0.5 * (lines[k] + lines[np.minimum(k + 1, lines.size - 1)]), lines[k])
        assert np.array_equal(box[rows[0]], below) and np.array_equal(box[rows[1]], above)


def test_box_fill_block_is_its_formula_with_boxes_without_a_downstream_face():
    """The fill of an emptied box is ``min(1, theta hbar / h)`` at its sample points, its deficit ``int (1 -
    fill) / h`` and its emptied area ``int [fill < 1]`` (midpoint rule); a box without a downstream face (no
    ``hbar``) takes its own mean film instead: equal bit for bit to the formula written out on the points, on a
    dimpled grid's boxes with every third emptied box's face removed."""
    mesh = grid_mesh(_dimpled(), 1.0 / 20)
    film = UniformFilm(1.0)
    box = fv._grid_faces(mesh).box
    rng = np.random.default_rng(5)
    n = box.shape[1]
    theta = rng.uniform(0.2, 1.0, n)
    hbar = rng.uniform(1.0, 3.0, n)
    emptied = np.flatnonzero(np.isfinite(box[0]))[::2]
    hbar[emptied[::3]] = np.nan   # no downstream face
    samples = 8
    b = box[:, emptied]
    t = (np.arange(samples) + 0.5) / samples
    X = (b[0][:, None] + (b[1] - b[0])[:, None] * t).repeat(samples, axis=1)
    Z = np.tile(b[2][:, None] + (b[3] - b[2])[:, None] * t, (1, samples))
    h = 1.0 + fv._recess_depth(mesh.surface, X, Z)
    c = theta[emptied] * hbar[emptied]
    cc = np.where(np.isfinite(c), c, theta[emptied] * h.mean(axis=1))[:, None]
    fill = np.minimum(1.0, cc / h)
    w = ((b[1] - b[0]) * (b[3] - b[2]) / samples**2)[:, None]
    want = (float(np.sum(w * (1.0 - fill) / h)), float(np.sum(w * (fill < 1.0 - 1e-12))))
    assert np.any(h > 1.0) and np.any(fill < 1.0) and np.any(fill == 1.0)   # dimples, emptied and full points
    assert fv._box_fill_block(mesh, film, box, theta, hbar, emptied, samples) == want


def test_the_full_film_first_guess_is_counted():
    """A cold solve guesses its cavity from one full-film factorization, reported beside the active set's
    own count: on its own grid below the nested sizes, on the coarsest grid of a nested start above; a warm
    start makes none."""
    small = solve_jfo(grid_mesh(_dimpled(), 0.05), UniformFilm(1.0), cavitation_pressure=-0.05, couette="grid")
    assert small.cost["first_guess_factorizations"] == 1.0 and small.cost["factorizations"] >= 1.0
    warm = solve_jfo(grid_mesh(_dimpled(), 0.05), UniformFilm(1.0), cavitation_pressure=-0.05, couette="grid",
                     warm_start=small)
    assert "first_guess_factorizations" not in warm.cost
    nested = solve_jfo(grid_mesh(_dimpled(), 1.0 / fv.NESTED_MIN ** 0.5 * 0.9), UniformFilm(1.0),
                       cavitation_pressure=-0.05, couette="grid")
    assert nested.cost["nested_levels"] >= 1.0 and nested.cost["first_guess_factorizations"] == 1.0


def test_facet_to_triangle_map_is_scikit_fems():
    """The facet-to-triangle map given to a mesh before its pocket moments (one stable sort) is the array
    scikit-fem's ``Mesh.build_inverse`` makes (two unique sorts), element for element and in its dtype,
    on a gmsh mesh with a pocket and on a grid."""
    from bearingfe import Rectangle
    from bearingfe.geometry.meshing import give_facet_triangles

    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[Rectangle((0.7, 0.0), (0.2, 0.2))])
    for mesh in (mesh_surface(surface, 0.1), grid_mesh(surface, 1 / 10)):
        m = mesh.mesh   # built here: its map may be replaced
        want = skfem.Mesh.build_inverse(m.t, m.t2f)
        if hasattr(m, "_f2t"):
            del m._f2t
        give_facet_triangles(m)
        assert m._f2t.dtype == want.dtype and np.array_equal(m._f2t, want)
        assert np.count_nonzero(want[1] == -1) > 0   # boundary facets (pocket and outline) in it


def test_the_complementarity_solve_runs_with_one_blas_thread(monkeypatch):
    """SuperLU's solves call BLAS, whose threads wait for each other on a busy machine: the complementarity
    solve (active sets, factorizations, Woodbury block solves) runs with every BLAS library capped at one
    thread, and the caller's thread counts are back afterwards."""
    from threadpoolctl import threadpool_info, threadpool_limits

    def counts():
        return [p["num_threads"] for p in threadpool_info() if p["user_api"] == "blas"]

    seen = []
    inner = fv._complementarity

    def spy(*args, **kwargs):
        seen.append(counts())
        return inner(*args, **kwargs)

    monkeypatch.setattr(fv, "_complementarity", spy)
    with threadpool_limits(limits=2, user_api="blas"):   # a caller with two BLAS threads
        before = counts()
        solve_jfo(grid_mesh(_dimpled(), 1 / 12), UniformFilm(1.0), cavitation_pressure=-0.05)
        after = counts()
    assert before and all(n == 2 for n in before)
    assert seen and all(n == 1 for n in seen[0])
    assert after == before


def test_full_film_first_guess_by_banded_cholesky(monkeypatch):
    """The full-film first guess on a small grid solves the symmetric positive definite Poiseuille system by
    banded Cholesky: the pressures equal SuperLU's (COLAMD, partial pivoting) to 1e-12 of the largest (both
    backward stable, the matrix of 14 x 14 cells well conditioned: round-off), hence the same guessed cavity; the
    band plan kept on the unknowns for the next film is the one built afresh from the matrix's pattern. A
    non-symmetric matrix, or a band wider than the ``full_film_guess`` limit, is left to SuperLU (None)."""
    import scipy.sparse as sp

    from bearingfe.core.linalg import factorize_splu
    from bearingfe.core.banded import BAND_LIMITS, BandLimits, band_plan

    mesh = grid_mesh(_dimpled(), 1 / 14)
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    unk = fv._unknowns(mesh, ops)
    K, G, b = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
    rhs = -b - G @ np.ones(b.size)
    want = factorize_splu(K.tocsc())(rhs)
    got = fv._full_film_banded(unk, K, rhs)
    assert np.abs(got - want).max() <= 1e-12 * np.abs(want).max()
    assert np.array_equal(got < 0, want < 0) and np.count_nonzero(want < 0) > 0
    kept = unk._order["band"][2]
    fresh = band_plan(np.arange(K.nnz), K.indices, K.indptr, K.shape[0], kind="full_film_guess")
    assert kept.kd == fresh.kd and kept.n == fresh.n
    for name in ("perm", "inverse", "flat", "take"):
        assert np.array_equal(getattr(kept, name), getattr(fresh, name))
    assert np.array_equal(fv._full_film_banded(unk, K, rhs), got) and unk._order["band"][2] is kept   # reused
    skew = K + sp.csr_matrix(([1e-3], ([0], [1])), shape=K.shape)
    assert fv._full_film_banded(unk, skew, rhs) is None
    monkeypatch.setitem(BAND_LIMITS, "full_film_guess", BandLimits(kd_max=1, size_max=96**2))
    unk._order.pop("band")
    assert fv._full_film_banded(unk, K, rhs) is None


def _dimpled_set_solver():
    """The reduced ``K``, ``G``, right side and the active-set solver of the dimpled grid (14 cells per side,
    cavity pressure -0.05): a banded set solver."""
    mesh = grid_mesh(_dimpled(), 1 / 14)
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    unk = fv._unknowns(mesh, ops)
    K, G, b = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
    return K, G, b, fv._SetSolver(K, G, fv.factorize_splu, unk)


def test_banded_set_values_are_the_set_matrix_in_band_storage(monkeypatch):
    """A banded set factorization takes ``K``'s columns outside the set and ``G``'s inside straight into LAPACK's
    band storage (:meth:`_SetSolver._band_values`, no union pattern): the same storage, bit for bit, as the set's
    sparse matrix (:meth:`_SetSolver.matrix`) placed there, for several sets, whether that matrix is picked on
    the union pattern or built by the sparse products (above ``CHOICE_UP_TO``); a ``K`` with its entries stored
    twice as halves (not canonical: summed first) gives the same storage."""
    import scipy.sparse as sp

    K, G, b, solver = _dimpled_set_solver()
    banded = solver.factorize
    assert isinstance(banded, fv._BandedLU)

    def storage(values, places):
        ab = np.zeros((3 * banded.kd + 1) * b.size)
        ab[places] = values
        return ab

    def placed(M):
        A = sp.coo_matrix(M)
        return storage(A.data, banded.places(A.row, A.col))

    rng = np.random.default_rng(3)
    sets = [np.zeros(b.size, bool), np.ones(b.size, bool)] + [rng.random(b.size) < q for q in (0.2, 0.5, 0.8)]
    for cav in sets:
        assert np.array_equal(storage(*solver._band_values(cav)), placed(solver.matrix(cav)))
    monkeypatch.setattr(fv, "CHOICE_UP_TO", 0)   # the set matrices by the sparse products
    for cav in sets:
        assert np.array_equal(storage(*solver._band_values(cav)), placed(solver.matrix(cav)))
    other = fv._SetSolver(K, G, banded)   # each entry of K stored twice, as two halves (exact)
    Kc = other.K
    other.K = sp.csc_matrix((np.repeat(0.5 * Kc.data, 2), np.repeat(Kc.indices, 2), 2 * Kc.indptr), shape=Kc.shape)
    assert not other.K.has_canonical_format
    for cav in sets:
        assert np.array_equal(storage(*other._band_values(cav)), storage(*solver._band_values(cav)))


def test_banded_storage_serves_again_once_its_solve_is_gone():
    """A banded factorization's band storage is kept for the next one only once its solve is gone: while a solve
    lives, a new factorization takes new storage and the old solve still solves its own matrix (bit for bit as
    before); once dropped, the next factorization reuses its storage (zeroed first) and solves exactly as one
    on new storage."""
    import gc

    import scipy.sparse as sp

    K, G, b, solver = _dimpled_set_solver()
    perm, kd = solver.factorize.perm, solver.factorize.kd
    rhs = np.random.default_rng(4).standard_normal(b.size)
    a, c = np.zeros(b.size, bool), np.ones(b.size, bool)
    a[::3] = True
    want_a = fv._factorize_banded(perm, kd)(solver.matrix(a))(rhs)   # each on its own new storage
    want_c = fv._factorize_banded(perm, kd)(solver.matrix(c))(rhs)
    banded = fv._factorize_banded(perm, kd)
    solve_a = banded(solver.matrix(a))
    solve_c = banded(solver.matrix(c))   # solve_a lives: new storage
    assert banded._spare == []
    assert np.array_equal(solve_a(rhs), want_a) and np.array_equal(solve_c(rhs), want_c)
    del solve_a
    gc.collect()
    assert len(banded._spare) == 1
    kept = banded._spare[0]
    solve_c2 = banded(sp.csc_matrix(solver.matrix(c)))   # a's storage, zeroed and filled with c's matrix
    assert banded._spare == [] and np.array_equal(solve_c2(rhs), want_c)
    del solve_c2
    gc.collect()
    assert banded._spare[-1] is kept
    solver._refactorize(a)   # the set solver drops its last solve before factorizing: one storage serves all
    solver._refactorize(c)
    solver._refactorize(a)
    assert np.array_equal(solver.solve(rhs), want_a) and solver.factorize._spare == []   # none left over
    solver.solve = None
    gc.collect()
    assert len(solver.factorize._spare) == 1


def test_banded_low_rank_limit_reaches_the_same_set_as_refactorizing(monkeypatch):
    """A banded set factorization of half-bandwidth ``kd`` takes at most ``kd // BANDED_KD_PER_COLUMN`` new
    columns by a low-rank update (SuperLU's: ``LOW_RANK_SWITCHES``). On the dimpled slider of docs/jfo_gmsh.md
    at grid size 0.04 (676 nodes, all sets banded) the low-rank route with the plain limit (24), the default
    and refactorizing at almost every change (limit 1) end on the same cavity, with pressures and fill
    fractions equal to 1e-12 (round-off of the Sherman-Morrison-Woodbury steps); fewer low-rank columns take
    more factorizations (measured 2, 4 and 5)."""
    surface = Surface(arc=(0.0, 1.0), half_width=0.5, recesses=[Recess(Circle((0.5, 0.0), 0.25), 1.0)])
    results = {}
    for share in (1e-9, fv.BANDED_KD_PER_COLUMN, 1e9):
        monkeypatch.setattr(fv, "BANDED_KD_PER_COLUMN", share)
        results[share] = solve_jfo(grid_mesh(surface, 0.04), UniformFilm(1.0), cavitation_pressure=-0.05,
                                   couette="grid")
    plain = results[1e-9]
    for res in results.values():
        assert np.array_equal(res.cavitated, plain.cavitated)
        assert np.abs(res.pressure - plain.pressure).max() <= 1e-12 * np.abs(plain.pressure).max()
        assert np.abs(res.theta - plain.theta).max() <= 1e-12
    counts = [results[k].cost["factorizations"] for k in sorted(results)]
    assert counts[0] <= counts[1] <= counts[2] and counts[0] < counts[2]
    mesh = grid_mesh(_dimpled(), 1 / 14)   # the limit itself: kd // 3, at least 1, at most LOW_RANK_SWITCHES
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    unk = fv._unknowns(mesh, ops)
    K, G, _ = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
    monkeypatch.setattr(fv, "BANDED_KD_PER_COLUMN", 3)
    perm = np.arange(K.shape[0])
    assert [fv._SetSolver(K, G, fv._factorize_banded(perm, kd))._low_rank_limit() for kd in (2, 18, 49, 90)] == \
        [1, 6, 16, fv.LOW_RANK_SWITCHES]
    assert fv._SetSolver(K, G, fv._factorize_in_order(perm))._low_rank_limit() == fv.LOW_RANK_SWITCHES


def test_small_active_set_matrices_by_banded_lu(monkeypatch):
    """Up to the ``active_set_lu`` band limit the active-set matrices are factored by banded LU with partial
    pivoting: the solution of a set's system equals SuperLU's (COLAMD, partial pivoting) to 1e-12 of the largest (both
    backward stable, a well-conditioned matrix of 14 x 14 cells: round-off); the order kept on the unknowns
    is the one found afresh; an exactly singular matrix falls back to SuperLU (which then refuses it as
    singular, as before); a wider band is left to SuperLU (None). The reverse Cuthill-McKee order (a grid's own
    line order switched off: its test below)."""
    import pytest
    import scipy.sparse as sp
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    from bearingfe.core.banded import BAND_LIMITS, BandLimits
    from bearingfe.core.linalg import factorize_splu

    monkeypatch.setattr(fv, "GRID_BAND_ORDER", False)
    mesh = grid_mesh(_dimpled(), 1 / 14)
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    unk = fv._unknowns(mesh, ops)
    K, G, b = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
    cav = np.zeros(b.size, bool)
    cav[::3] = True
    solver = fv._SetSolver(K, G, fv.factorize_splu, unk)
    M = solver.matrix(cav)
    rhs = np.random.default_rng(1).standard_normal(b.size)
    want = factorize_splu(M)(rhs)
    got = solver.factorize(M)(rhs)
    assert np.abs(got - want).max() <= 1e-12 * np.abs(want).max()
    perm, kd = unk._order["set_band"][2]
    pattern = (abs(K) + abs(G)).tocsr()
    pattern = (pattern + pattern.T).tocsr()
    assert np.array_equal(perm, reverse_cuthill_mckee(pattern, symmetric_mode=True))
    assert 0 < kd <= BAND_LIMITS["active_set_lu"].kd_max == 64
    # the set solver's own factorization takes the picked values straight into the band storage: the same
    # band matrix as the sparse one, so the same factors and solution, bit for bit
    solver._refactorize(cav)
    assert isinstance(solver.factorize, fv._BandedLU) and solver.factorizations == 1
    assert np.array_equal(solver.solve(rhs), got)
    other = ~cav   # another set: the kept band places serve every set of the pattern
    solver._refactorize(other)
    assert np.array_equal(solver.solve(rhs), solver.factorize(solver.matrix(other))(rhs))
    singular = M.tolil()
    singular[:, 0] = 0.0
    with pytest.raises(RuntimeError, match="singular"):
        fv._factorize_banded(perm, kd)(sp.csc_matrix(singular))
    monkeypatch.setitem(BAND_LIMITS, "active_set_lu", BandLimits(kd_max=kd - 1, size_max=64**2))
    unk._order.pop("set_band")
    assert fv._set_band(unk, K, G) is None


def test_vertex_depth_kept_per_mesh_is_the_pointwise_depth():
    """The recess depth at the vertices, found once per mesh, is what the per-triangle test of the vertices
    (the cut cells' check) and the plain thickness at the dofs (the result's h_min) took: the same values,
    bit for bit, with circles and a rectangle (a bisected contour shape) among the recesses."""
    from bearingfe import Rectangle

    surface = Surface(arc=(0.0, 1.0), half_width=0.5,
                      recesses=[*_dimpled().recesses, Recess(Rectangle((0.5, 0.0), (0.2, 0.1)), 0.7)])
    mesh = grid_mesh(surface, 1 / 23)
    t = mesh.mesh.t[:3]
    px, pz = mesh.mesh.p[0, t], mesh.mesh.p[1, t]
    depth = fv._vertex_depth(mesh)
    assert fv._vertex_depth(mesh) is depth and np.count_nonzero(depth) > 20
    assert np.array_equal(depth[t], fv._rows_depth(surface, px.T, pz.T).T)
    film = UniformFilm(1.0)
    doflocs = np.asarray(fv.operators(mesh).basis.doflocs)
    assert np.array_equal(fv._dof_thickness(mesh, film, doflocs), fv._thickness(mesh, film, *doflocs))
    assert fv._vertex_depth(grid_mesh(Surface(arc=(0.0, 1.0), half_width=0.5), 0.1)) is None


def test_triangle_recesses_give_the_previous_quadrature_depth_and_cut_cells():
    """The triangles near each recess (their corners' boxes, found once per mesh) serve the quadrature depth and
    the cut cells: the same values, bit for bit, as the previous computation (the quadrature points' own boxes,
    :func:`_rows_depth`, equal to the surface's plain test; the cut cells' boxes, :func:`_boxed_depth`), with
    circles and a rectangle among the recesses, and on a quadratic mesh (its own boxes: no shared lists)."""
    from bearingfe import Rectangle

    surface = Surface(arc=(0.0, 1.0), half_width=0.5,
                      recesses=[*_dimpled().recesses, Recess(Rectangle((0.5, 0.0), (0.2, 0.1)), 0.7)])
    mesh = grid_mesh(surface, 1 / 23)
    x = fv.operators(mesh).x
    over = fv._triangle_recesses(mesh)
    assert len(over) == 5 and all(np.all(np.diff(rows) > 0) for rows in over)
    depth = fv._quadrature_depth(mesh, x)
    assert np.count_nonzero(depth) > 100
    assert np.array_equal(depth, fv._rows_depth(surface, x[0], x[1]))
    assert np.array_equal(depth, surface.recess_depth(x[0], x[1]))
    cut, pts, cut_depth = fv._cut_cells(mesh, x, 8)
    t = mesh.mesh.t[:3, cut]
    px, pz = mesh.mesh.p[0, t], mesh.mesh.p[1, t]
    assert cut.size > 50
    assert np.array_equal(cut_depth, fv._boxed_depth(surface, px.min(axis=0), px.max(axis=0), pz.min(axis=0),
                                                     pz.max(axis=0), pts[0], pts[1]))
    assert np.array_equal(cut_depth, surface.recess_depth(pts[0], pts[1]))
    curved = mesh_surface(surface, 0.1, order=2)
    assert fv._triangle_recesses(curved) is None


def test_band_subproblem_factored_by_banded_lu_where_thin(monkeypatch):
    """The band subproblem of a nested start (:func:`_band_set`) is factored by banded LU in its reverse
    Cuthill-McKee order where the band pays (the ``front_band_lu`` limits: half-bandwidth and work): its
    solution equals SuperLU's in the same order to 1e-12 of the largest (both backward stable; a
    well-conditioned set matrix of the 14 x 14 dimple grid's unknowns, round-off); a wider band keeps SuperLU."""
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    from bearingfe.core.banded import BAND_LIMITS, BandLimits

    mesh = grid_mesh(_dimpled(), 1 / 14)
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    unk = fv._unknowns(mesh, ops)
    K, G, b = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
    pattern = (abs(K) + abs(G)).tocsr()
    order = np.asarray(reverse_cuthill_mckee(pattern, symmetric_mode=True))
    banded = fv._band_factorize(pattern, order)
    assert isinstance(banded, fv._BandedLU) and np.array_equal(banded.perm, order)
    cav = np.zeros(b.size, bool)
    cav[1::3] = True
    M = fv._SetSolver(K, G, banded).matrix(cav)
    rhs = np.random.default_rng(2).standard_normal(b.size)
    want = fv._factorize_in_order(order)(M)(rhs)
    got = banded(M)(rhs)
    assert np.abs(got - want).max() <= 1e-12 * np.abs(want).max()
    monkeypatch.setitem(BAND_LIMITS, "front_band_lu", BandLimits(kd_max=banded.kd - 1, work_max=2e7))
    wide = fv._band_factorize(pattern, order)
    assert not isinstance(wide, fv._BandedLU)
    assert np.abs(wide(M)(rhs) - want).max() == 0.0
    n = pattern.shape[0]   # a long band (work n kd^2 above the cap) keeps SuperLU too
    monkeypatch.setitem(BAND_LIMITS, "front_band_lu", BandLimits(kd_max=64, work_max=n * banded.kd**2 - 1))
    wide = fv._band_factorize(pattern, order)
    assert not isinstance(wide, fv._BandedLU)
    assert np.abs(wide(M)(rhs) - want).max() == 0.0


def test_union_pattern_read_from_compressed_arrays_is_the_sum_of_the_matrices():
    """The set matrices' symmetric union pattern read from the CSC (or CSR) arrays equals the sums
    ``|K| + |G|`` plus its transpose made through CSR (indices, pointers and values, bit for bit), also with
    entries that cancel (an explicit zero) and for mixed or non-canonical formats (those take the sums)."""
    import scipy.sparse as sp

    mesh = grid_mesh(_dimpled(), 1 / 9)
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "median")
    unk = fv._unknowns(mesh, ops)
    K, G, _ = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
    K = K.tocsr()
    assert K[0, 60] == 0 and K[3, 40] == 0 and K[40, 3] == 0
    # an entry outside K's pattern (one of the union and of its transpose) and an explicit zero where K has
    # no entry (no entry of the union: scipy's sums drop it)
    G = (G.tocsr() + sp.csr_matrix(([1.5, 1.0], ([3, 0], [40, 60])), shape=G.shape)).tocsr()
    G.data[G.indptr[0] + np.flatnonzero(G.indices[G.indptr[0]:G.indptr[1]] == 60)] = 0.0
    assert G.has_canonical_format and G[0, 60] == 0 and 60 in G.indices[G.indptr[0]:G.indptr[1]]
    want = (abs(sp.csr_matrix(K)) + abs(sp.csr_matrix(G))).tocsr()
    want = (want + want.T).tocsr()
    want.sort_indices()
    for k, g in ((K.tocsc(), G.tocsc()), (K.tocsr(), G.tocsr()), (K.tocsr(), G.tocsc()), (K.tocoo(), G)):
        got = fv._union_pattern(k, g)
        assert got.format == "csr" and got.has_sorted_indices
        assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
        assert np.array_equal(got.data, want.data)
    assert want[3, 40] == want[40, 3] == 1.5 and want[0, 60] == 0 and 60 not in want.indices[:want.indptr[1]]



def test_union_pattern_kernels_are_scipys_sums_and_transpose():
    """csr_sum and csr_transposed (scipy's kernels on int32 arrays, no checks between) give the arrays of scipy's
    ``A + B`` and ``A.T.tocsr()`` bit for bit, entries that cancel dropped, on random canonical matrices of
    several shapes; and the union pattern of int64-indexed matrices (scipy's sums) equals the int32 one's."""
    import scipy.sparse as sp

    rng = np.random.default_rng(5)
    for k in range(12):
        n, m = (int(x) for x in rng.integers(1, 40, size=2))
        A = sp.random(n, m, density=0.2, random_state=k, format="csr")
        B = sp.random(n, m, density=0.2, random_state=k + 50, format="csr")
        A.data -= 0.5
        B = (B - B.multiply(A != 0)).tocsr()   # no entry where A has one ...
        cut = sp.csr_matrix(A, copy=True)
        cut.data[3:] = 0.0
        cut.eliminate_zeros()
        B = (B - cut).tocsr()                  # ... but minus A's first three: they cancel in A + B
        B.sum_duplicates()
        for x in (A, B):
            assert x.indices.dtype == np.int32 and x.has_canonical_format
        want, got = A + B, csr_sum(A, B)
        assert A.nnz < 3 or want.nnz == A.nnz + B.nnz - 6   # three shared entries, which cancel
        for name in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(got, name), getattr(want, name))
        assert got.shape == want.shape and got.has_canonical_format
        want_t, got_t = A.T.tocsr(), csr_transposed(A)
        for name in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(got_t, name), getattr(want_t, name))
        assert got_t.shape == (m, n)
        want_c, got_c = A.tocsc(), csc_of(A)
        assert got_c.format == "csc" and got_c.shape == (n, m) and got_c.has_canonical_format
        for name in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(got_c, name), getattr(want_c, name))
        twice = sp.csr_matrix(([1.0, 2.0, 3.0, 4.0], [0, 1, 1, 0], [0, 1, 3, 4]), shape=(3, 2))   # (1, 1) twice
        assert not twice.has_canonical_format   # a repeated entry: scipy's conversion; the transpose keeps it
        assert csc_of(twice).nnz == 4 and np.array_equal(csc_of(twice).toarray(), twice.toarray())
        assert not csr_transposed(twice).has_canonical_format
        assert np.array_equal(csr_transposed(twice).toarray(), twice.T.toarray())
        assert fv._symmetric(A + A.T) if n == m else not fv._symmetric(A)
        if n == m:
            wide = [sp.csr_matrix(x) for x in (A, B)]
            for x in wide:
                x.indices, x.indptr = x.indices.astype(np.int64), x.indptr.astype(np.int64)
            P, Q = fv._union_pattern(A, B), fv._union_pattern(*wide)
            for name in ("indptr", "indices", "data"):
                assert np.array_equal(getattr(P, name), getattr(Q, name))

def test_whole_grids_find_triangles_and_faces_from_their_lines():
    """A whole grid_mesh (no pockets) keeps its lines (tensor_lines): the triangles and the box faces near each
    recess (_tensor_overlaps, two binary searches per axis) and the box faces themselves come from them, the same
    arrays, bit for bit, as the tests per rectangle (_overlaps of the triangles' corners' boxes and of the faces)
    and the faces found from the nodes (_grid_numbering), and the recess depth at the nodes (each recess testing
    the nodes in its box) equals the surface's test; on square and uneven lines (size_z), one cell wider than a recess. A grid with a
    pocket, and a mesh that travelled through pickle, keep no lines (the general paths)."""
    import pickle

    from bearingfe import Rectangle
    from bearingfe.geometry.meshing import tensor_lines

    surface = Surface(arc=(0.0, 1.0), half_width=0.5,
                      recesses=[*_dimpled().recesses, Recess(Circle((0.88, 0.38), 0.1), 0.3)])
    for size, size_z in ((1 / 23, None), (1 / 17, 1 / 9), (0.5, None)):
        mesh = grid_mesh(surface, size, size_z=size_z)
        xs, zs = tensor_lines(mesh)
        assert np.array_equal(xs, np.unique(mesh.mesh.p[0])) and np.array_equal(zs, np.unique(mesh.mesh.p[1]))
        t = mesh.mesh.t[:3]
        px, pz = mesh.mesh.p[0, t], mesh.mesh.p[1, t]
        tested = fv._overlaps(surface, px.min(axis=0), px.max(axis=0), pz.min(axis=0), pz.max(axis=0))
        ours = fv._triangle_recesses(mesh)
        assert len(ours) == 5 and sum(r.size for r in ours) > 0
        assert all(np.array_equal(a, b) and a.dtype == b.dtype for a, b in zip(ours, tested))
        faces = fv._build_grid_faces(mesh)
        found = fv._faces_on_grid(mesh.mesh.p, *fv._grid_numbering(mesh.mesh))
        for name in ("i", "j", "x0", "x1", "lo", "hi", "box"):
            assert np.array_equal(getattr(faces, name), getattr(found, name))
            assert getattr(faces, name).dtype == getattr(found, name).dtype
        tested = fv._overlaps(surface, faces.x0, faces.x1, faces.lo, faces.hi)
        ours = fv._face_overlaps(mesh, faces)
        assert len(ours) == 5 and sum(r.size for r in ours) > 0
        assert all(np.array_equal(a, b) and a.dtype == b.dtype for a, b in zip(ours, tested))
        depth = fv._vertex_depth(mesh)
        assert depth.shape == (mesh.n_nodes,) and (np.count_nonzero(depth) > 0 or mesh.n_nodes < 10)
        assert np.array_equal(depth, fv._recess_depth(surface, mesh.mesh.p[0], mesh.mesh.p[1]))
    pocketed = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[Rectangle((0.5, 0.0), (0.1, 0.1))])
    assert tensor_lines(grid_mesh(pocketed, 1 / 10)) is None
    assert tensor_lines(pickle.loads(pickle.dumps(grid_mesh(surface, 1 / 10)))) is None


def test_selection_by_mask_equals_scipys_indexing():
    """:func:`_selected` of a canonical CSR matrix (picked by a mask over the stored entries) equals scipy's
    ``A[rows][:, rows]`` with its explicit zeros dropped and indices sorted, bit for bit: random matrices with
    stored zeros and random increasing rows, the empty selection and all rows; a matrix with unsorted indices
    takes scipy's path, with the same answer."""
    import scipy.sparse as sp

    def indexed(A, rows):
        B = A[rows][:, rows].tocsr()
        B.eliminate_zeros()
        B.sort_indices()
        return B

    rng = np.random.default_rng(7)
    for trial in range(60):
        n = int(rng.integers(1, 40))
        A = sp.random(n, n, density=float(rng.uniform(0.05, 0.5)), random_state=trial, format="csr")
        A.data[rng.uniform(size=A.nnz) < 0.2] = 0.0   # stored zeros
        for rows in (np.flatnonzero(rng.uniform(size=n) < 0.6), np.zeros(0, np.int64), np.arange(n)):
            got, want = fv._selected(A, rows), indexed(A, rows)
            assert got.shape == want.shape and got.has_canonical_format
            assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
            assert np.array_equal(got.data, want.data)
    A = sp.csr_matrix(np.array([[1.0, 2.0, 0.0], [0.0, 3.0, 4.0], [5.0, 0.0, 6.0]]))
    A.indices[:2], A.data[:2] = A.indices[:2][::-1].copy(), A.data[:2][::-1].copy()   # row 0 unsorted
    A.has_sorted_indices = False
    got = fv._selected(A, np.array([0, 2]))
    assert np.array_equal(got.toarray(), np.array([[1.0, 0.0], [5.0, 6.0]]))


def test_couette_operator_plus_zero_storage_is_scipys_sum():
    """:func:`_with_storage` without storage (a copy of the canonical operator without its zeros) equals scipy's
    ``C + diag(0)`` bit for bit, stored zeros (also ``-0.0``) dropped; with storage it is scipy's sum."""
    import scipy.sparse as sp

    rng = np.random.default_rng(3)
    C = sp.random(30, 30, density=0.2, random_state=4, format="csr")
    C.data -= 0.5
    C.data[:3] = [0.0, -0.0, 0.0]
    for storage in (np.zeros(30), rng.uniform(0.0, 1.0, 30)):
        got, want = fv._with_storage(C, storage), (C + sp.diags(storage)).tocsr()
        assert got.nnz == want.nnz < C.nnz + (30 if storage.any() else 0)
        assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
        assert np.array_equal(got.data, want.data)
    assert C.data[0] == 0.0   # the operator itself is left as it was


def test_facet_geometry_is_kept_on_the_mesh_with_the_same_fluxes():
    """The boundary facets' geometry of the facet fluxes is built once per mesh and facet list: a second call
    takes the same frame and gives the first call's fluxes bit for bit, which equal those on a fresh copy of the
    mesh (a gmsh mesh with a pocket; the flows' three groups in one pass)."""
    from bearingfe import Rectangle

    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[Rectangle((0.7, 0.0), (0.2, 0.2))])
    film = UniformFilm(1.0)
    fluxes = []
    for mesh in (mesh_surface(surface, 0.1), mesh_surface(surface, 0.1)):
        ops = fv.operators(mesh, "P1")
        rng = np.random.default_rng(5)
        grad_p = rng.normal(size=(2, mesh.mesh.t.shape[1]))
        theta = rng.uniform(0.2, 1.0, mesh.mesh.nvertices)
        groups = {k: ops.facet_groups[k] for k in ("arc_start", "arc_end", "side")}
        first = fv._facet_flux(mesh, film, 1.0, grad_p, theta, groups)
        every = np.concatenate([np.asarray(f, np.int64) for f in groups.values()])
        frame = fv._facet_frame(mesh, every)
        again = fv._facet_flux(mesh, film, 1.0, grad_p, theta, groups)
        assert fv._facet_frame(mesh, every) is frame and not frame.normal.flags.writeable
        assert all(np.array_equal(first[k], again[k]) for k in groups)
        fluxes.append(first)
    assert all(np.array_equal(fluxes[0][k], fluxes[1][k]) for k in fluxes[0])


def _sparse_stiffness(cells, w):
    """The stiffness of the cell integrals ``w`` by scipy's sparse sums, the path the P1 pattern replaces: ``U``
    by the COO conversion, ``U + U^T``, the rows' sums on the diagonal."""
    import scipy.sparse as sp

    g, t = cells.grad, cells.t
    a, b = [0, 1, 2], [1, 2, 0]
    vals = (w * (g[0][a] * g[0][b] + g[1][a] * g[1][b])).ravel()
    U = sp.csr_matrix((vals, (t[a].ravel(), t[b].ravel())), shape=(cells.n, cells.n))
    A = U + U.T
    return (A - sp.diags(np.asarray(A.sum(axis=1)).ravel())).tocsr()


def _stiffness_meshes():
    """A gmsh mesh with a pocket, a periodic gmsh mesh and a grid (whose diagonals' entries sum to exactly zero)."""
    from benchmarks.jfo_gmsh import grooved_journal
    from bearingfe import Rectangle

    pad = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[Rectangle((0.7, 0.0), (0.2, 0.2))])
    return mesh_surface(pad, 0.08), mesh_surface(grooved_journal().surface, 0.3), grid_mesh(_dimpled(), 1 / 10)


def test_stiffness_on_the_pattern_found_at_the_second_call_equals_scipys_sums():
    """Without a streamline flux to share it, a mesh's first stiffness is scipy's sparse sums and from its
    second on it is summed on the P1 pattern (:func:`_stiffness_pattern`): scikit-fem's edges' where they are at
    hand, else the triangles' own (the same arrays). The stiffness equals, bit for bit, the sparse sums (``U`` by
    the COO conversion, ``U + U^T``, the rows' sums on the diagonal) for random cell integrals, on a gmsh mesh with
    a pocket, a periodic gmsh mesh and a grid (whose diagonals' entries sum to exactly zero and are left out); with
    the streamline flux the pattern of scikit-fem's edges serves from the first stiffness."""
    import copy

    rng = np.random.default_rng(11)
    for mesh in _stiffness_meshes():
        skfem = fv._p1_pattern(mesh)
        assert fv._stiffness_pattern(mesh, flux=True) is skfem
        for edges in (True, False):
            copied = copy.deepcopy(mesh)
            copied._cache.clear()
            cells = fv._cells(copied, fv.operators(copied, "P1"))
            if not edges:   # (after the operators: the pocket's moments use scikit-fem's facet map, which finds them)
                copied.mesh.__dict__.pop("_t2f", None)
            for call in range(4):   # scipy's sums, then the pattern found at the second call
                pattern = fv._stiffness_pattern(copied)
                assert (pattern is None) == (call == 0)
                w = rng.uniform(0.5, 2.0, cells.t.shape[1])
                got, want = fv._stiffness_of(cells, w, pattern), _sparse_stiffness(cells, w)
                assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
                assert np.array_equal(got.data, want.data)
            assert (fv._p1_pattern(copied) is pattern) == edges
            for name in ("indptr", "indices", "take", "diagonal", "off", "edge", "block_slot"):
                assert np.array_equal(getattr(pattern, name), getattr(skfem, name))
            if mesh.source == "grid":
                assert want.nnz < pattern.indices.size   # the zero entries left out


def test_stiffness_on_a_grids_pattern_drops_its_zeros_as_scipys_sums(monkeypatch):
    """On a grid's P1 pattern (its diagonals' entries sum to exactly zero, and some cell integrals are zero here, so
    whole rows of off-diagonal entries and diagonals vanish) the stiffness drops the zeros by scipy's kernel
    (:func:`~bearingfe.core.compressed.csr_without_zeros`) or, with the kernels declared unusable, by scipy's
    ``eliminate_zeros``: bit for bit scipy's sparse sums (reference: ``U`` by the COO conversion, ``U + U^T``, the
    rows' sums on the diagonal) either way."""
    from bearingfe.core import compressed as cm

    mesh = grid_mesh(_dimpled(), 1 / 10)
    cells = fv._cells(mesh, fv.operators(mesh, "P1"))
    pattern = fv._p1_pattern(mesh)
    rng = np.random.default_rng(5)
    w = rng.uniform(0.5, 2.0, cells.t.shape[1])
    w[: w.size // 4] = 0.0   # a corner of cells without terms: nodes whose rows are empty
    want = _sparse_stiffness(cells, w)
    assert want.nnz < pattern.indices.size and np.all(want.data)
    kept = pattern.indices.copy(), pattern.indptr.copy()
    for usable in (True, False):
        monkeypatch.setattr(cm, "kernels_usable", lambda: usable)
        got = fv._stiffness_on(pattern, fv._edge_terms(cells, w))
        for name in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(got, name), getattr(want, name)), (usable, name)
    assert np.array_equal(pattern.indices, kept[0]) and np.array_equal(pattern.indptr, kept[1])   # left as they were


def test_first_stiffness_is_scipys_sums_on_any_triangles(monkeypatch):
    """A mesh's first stiffness (no pattern: :func:`_stiffness_converted`, scipy's kernels on the arrays) equals
    scipy's sparse sums bit for bit (reference: ``U`` by the COO conversion, ``U + U^T``, ``A - diag(A 1)``) also
    where the arrays are not a mesh's: an edge in four triangles (a triangle repeated), a triangle with a node twice,
    terms that cancel and zero terms; on the kernels and with them declared unusable (scipy's own operations)."""
    import scipy.sparse as sp
    from bearingfe.core import compressed as cm

    rng = np.random.default_rng(29)
    n = 12
    t = np.sort(rng.choice(n, size=(40, 3), replace=True), axis=1).T   # some triangles with a node twice
    t = np.concatenate([t, t[:, :3]], axis=1)                          # repeated triangles: edges in 3-4 of them
    vals = rng.normal(size=3 * t.shape[1])
    vals[::5] = 0.0
    vals[1::7] = -vals[2::7][: vals[1::7].size]
    a, b = [0, 1, 2], [1, 2, 0]
    U = sp.csr_matrix((vals, (t[a].ravel(), t[b].ravel())), shape=(n, n))
    A = U + U.T
    want = (A - sp.diags(np.asarray(A.sum(axis=1)).ravel())).tocsr()
    for usable in (True, False):
        monkeypatch.setattr(cm, "kernels_usable", lambda: usable)
        got = fv._stiffness_converted(t, vals, n)
        for name in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(got, name), getattr(want, name)), (usable, name)


def test_band_set_with_the_callers_pattern_proposes_the_same_set():
    """:func:`_band_set` given the caller's ``|K| + |Gc|`` (as :func:`_two_grid_set` passes the one it found its
    fronts on) proposes the same set as when it builds that pattern itself (the same pattern: the same band, the
    same arithmetic), with and without a global correction, on the 14 x 14 dimple grid's unknowns."""
    mesh = grid_mesh(_dimpled(), 1 / 14)
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    unk = fv._unknowns(mesh, ops)
    K, G, b = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
    Gc = G
    pattern = (abs(K) + abs(Gc)).tocsr()
    cav = np.zeros(b.size, bool)
    cav[b.size // 3: b.size // 2] = True
    new = cav.copy()
    new[b.size // 2: b.size // 2 + 5] = True
    solve = fv._SetSolver(K, G, fv.factorize_splu).matrix(cav)
    correct = fv.factorize_splu(solve)
    y = correct(-b)
    for kwargs in ({}, dict(solve=correct), dict(solve=correct, converge=True, passes=3)):
        want = fv._band_set(K, Gc, G, b, cav, y, new, 1e-10, 1e-10, **kwargs)
        got = fv._band_set(K, Gc, G, b, cav, y, new, 1e-10, 1e-10, pattern=pattern, **kwargs)
        assert np.array_equal(got, want)
    assert not np.array_equal(want, new)   # the band's iteration moved the set: a case that tests something


def test_edge_terms_in_blocks_are_the_products_at_once(monkeypatch):
    """The stiffness's edge terms written block by block (:func:`_edge_terms`, several blocks and a partial last
    one) equal, bit for bit, the products of the gathered gradient rows computed at once (the previous formula)."""
    mesh = grid_mesh(_dimpled(), 1 / 12)
    cells = fv._cells(mesh, fv.operators(mesh, "P1"))
    w = np.random.default_rng(5).uniform(0.5, 2.0, cells.t.shape[1])
    g, a, b = cells.grad, [0, 1, 2], [1, 2, 0]
    want = (w * (g[0][a] * g[0][b] + g[1][a] * g[1][b])).ravel()
    monkeypatch.setattr(fv, "BLOCK", 37)   # read at call time
    assert cells.t.shape[1] % 37 and cells.t.shape[1] > 3 * 37
    assert np.array_equal(fv._edge_terms(cells, w), want)


def test_load_direction_on_grid_columns_is_the_pointwise_cos_and_sin(monkeypatch):
    """:func:`_phi_trig` on a whole grid (each column's cos and sin once, repeated along z) gives the pointwise
    ``np.cos`` and ``np.sin`` of phi at every quadrature point bit for bit, on square and uneven lines; a grid
    with a pocket (no lines kept) takes the pointwise path; and a JFO solve's load and integral are the same
    numbers as with the pointwise functions (the previous path)."""
    from bearingfe import Rectangle
    from bearingfe.geometry.meshing import tensor_lines

    for size, size_z in ((1 / 23, None), (1 / 17, 1 / 9), (0.5, None)):
        mesh = grid_mesh(_dimpled(), size, size_z=size_z)
        assert tensor_lines(mesh) is not None
        x0 = fv.operators(mesh, "P1").x[0]
        c, s = fv._phi_trig(mesh, x0)
        assert np.array_equal(c, np.cos(x0)) and np.array_equal(s, np.sin(x0))
    pocketed = grid_mesh(Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[Rectangle((0.5, 0.0), (0.1, 0.1))]), 1 / 10)
    x0 = fv.operators(pocketed, "P1").x[0]
    c, s = fv._phi_trig(pocketed, x0)
    assert np.array_equal(c, np.cos(x0)) and np.array_equal(s, np.sin(x0))
    fast = solve_jfo(grid_mesh(_dimpled(), 1 / 40), UniformFilm(1.0), cavitation_pressure=-0.05)
    monkeypatch.setattr(fv, "_phi_trig", lambda mesh, x0: (np.cos(x0), np.sin(x0)))
    plain = solve_jfo(grid_mesh(_dimpled(), 1 / 40), UniformFilm(1.0), cavitation_pressure=-0.05)
    assert fast.cavitated.any()
    assert np.array_equal(fast.force, plain.force) and fast.integral == plain.integral


def test_grid_line_band_order_gives_the_reverse_cuthill_mckee_band_and_answers(monkeypatch):
    """On a grid without a seam the active set's banded LU takes the grid's line order (:func:`_grid_band_order`,
    line by line across the axis with more lines, each line from its largest coordinate down): a permutation of
    the unknowns whose half-bandwidth of ``|K| + |G|`` equals reverse Cuthill-McKee's on square cells (narrower on
    uneven ones: 8 against 9 at 17 x 9 cells), a set matrix's solution within 1e-12 of the largest of that in
    reverse Cuthill-McKee order, and the same cold JFO solution (cavity, factorizations) as the reverse
    Cuthill-McKee order (the previous path) with pressures and fill within 1e-11 (both banded LU with partial
    pivoting, backward stable: orders that differ in rounding only, well-conditioned grids of 9 to 30 cells); a
    periodic grid (a seam: not on_grid) keeps reverse Cuthill-McKee."""
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    from bearingfe.core.banded import half_bandwidth

    for size, size_z in ((1 / 14, None), (1 / 30, None), (1 / 17, 1 / 9), (1 / 9, 1 / 17)):
        mesh = grid_mesh(_dimpled(), size, size_z=size_z)
        ops = fv.operators(mesh, "P1")
        system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
        unk = fv._unknowns(mesh, ops)
        K, G, b = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
        order = fv._grid_band_order(unk)
        assert unk.on_grid and np.array_equal(np.sort(order), np.arange(b.size))
        pattern = (abs(K) + abs(G)).tocsr()
        pattern = (pattern + pattern.T).tocsr()
        rcm = reverse_cuthill_mckee(pattern, symmetric_mode=True)
        assert half_bandwidth(pattern, order) <= half_bandwidth(pattern, rcm)
        if size_z is None:   # square cells: the same band
            assert half_bandwidth(pattern, order) == half_bandwidth(pattern, rcm)
        perm, kd = fv._set_band(unk, K.tocsc(), G.tocsc())
        assert perm is order and kd == half_bandwidth(pattern, order) and "set_band" not in unk._order
        cav = np.zeros(b.size, bool)
        cav[::3] = True
        M = fv._SetSolver(K, G, fv.factorize_splu, unk).matrix(cav)
        rhs = np.random.default_rng(2).standard_normal(b.size)
        lines = fv._factorize_banded(perm, kd)(M)(rhs)
        monkeypatch.setattr(fv, "GRID_BAND_ORDER", False)
        graph = fv._factorize_banded(*fv._set_band(unk, K.tocsc(), G.tocsc()))(M)(rhs)
        assert not np.array_equal(unk._order["set_band"][2][0], order)
        assert np.abs(lines - graph).max() <= 1e-12 * np.abs(graph).max()
        plain = solve_jfo(grid_mesh(_dimpled(), size, size_z=size_z), UniformFilm(1.0), cavitation_pressure=-0.05)
        monkeypatch.setattr(fv, "GRID_BAND_ORDER", True)
        ours = solve_jfo(grid_mesh(_dimpled(), size, size_z=size_z), UniformFilm(1.0), cavitation_pressure=-0.05)
        assert ours.cavitated.any() and np.array_equal(ours.cavitated, plain.cavitated)
        assert ours.cost["factorizations"] == plain.cost["factorizations"]
        assert np.abs(ours.pressure - plain.pressure).max() <= 1e-11 * np.abs(plain.pressure).max()
        assert np.abs(ours.theta - plain.theta).max() <= 1e-11
    periodic = grid_mesh(Surface(arc=(0.0, 2 * np.pi), half_width=0.5, periodic=True), 0.2)
    seamed = fv._unknowns(periodic, fv.operators(periodic, "P1"))
    assert not seamed.on_grid and fv._grid_band_order(seamed) is None


def test_distinct_count_is_the_size_of_numpys_unique():
    """:func:`_distinct_count` (the grid line order's comparison of its coordinates' counts) equals
    ``np.unique(values).size`` (the previous path) on sorted and unsorted values with repeats, signed zeros (one
    value), one value and none, and on a grid's unknowns' coordinates in both directions."""
    rng = np.random.default_rng(3)
    values = rng.integers(-5, 6, 200) * 0.1
    cases = [values, np.sort(values), np.array([0.0, -0.0, 0.0, 1.0, -0.0]), np.array([-0.0, 0.0]), np.array([2.5]),
             np.zeros(0), rng.random(50)]
    mesh = grid_mesh(_dimpled(), 1 / 17, size_z=1 / 9)
    unk = fv._unknowns(mesh, fv.operators(mesh, "P1"))
    cases += list(unk.coordinates)
    for v in cases:
        assert fv._distinct_count(v) == np.unique(v).size
        assert fv._distinct_count(v[::-1]) == np.unique(v).size


def test_band_just_below_lapacks_block_size_is_factored_as_that_block(monkeypatch):
    """A banded LU of half-bandwidth from ``BAND_PAD_FROM`` up to ``BAND_BLOCK`` (32) is stored and factored as
    one of ``BAND_BLOCK`` (LAPACK's blocked path; zero extra diagonals, the same pivots): its solution equals the
    unwidened factorization's and SuperLU's (COLAMD, partial pivoting) to 1e-12 of the largest on random
    nonsymmetric band matrices (well conditioned, shuffled unknowns); other widths are stored as they are."""
    import scipy.sparse as sp

    from bearingfe.core.linalg import factorize_splu

    rng = np.random.default_rng(5)
    n = 700
    for kd in (27, 28, 31, 32, 40):
        offsets = np.arange(-kd, kd + 1)
        M = sp.diags([rng.standard_normal(n - abs(k)) for k in offsets], offsets, format="csc")
        M = (M + 3.0 * kd * sp.identity(n)).tocsc()
        perm = rng.permutation(n)   # the band order of a shuffled numbering
        inverse = np.argsort(perm)
        A = M[inverse][:, inverse].tocsc()   # unknown perm[k] at band position k
        rhs = rng.standard_normal(n)
        banded = fv._factorize_banded(perm, kd)
        assert banded.kd == kd and banded.width == (32 if 28 <= kd < 32 else kd)
        got = banded(A)(rhs)
        want = factorize_splu(A)(rhs)
        assert np.abs(got - want).max() <= 1e-12 * np.abs(want).max()
        monkeypatch.setattr(fv, "BAND_PAD_FROM", 10**9)
        plain = fv._factorize_banded(perm, kd)
        assert plain.width == kd
        assert np.abs(plain(A)(rhs) - got).max() <= 1e-12 * np.abs(want).max()
        monkeypatch.setattr(fv, "BAND_PAD_FROM", 28)


def test_stiffness_and_streamline_flux_on_the_p1_pattern_equal_the_sparse_sums():
    """On the mesh's P1 pattern (:func:`_p1_pattern`, from scikit-fem's edges of the triangles) the stiffness
    equals the sparse sums bit for bit (the previous path: ``U`` by the COO conversion, ``U + U^T``, the rows'
    sums on the diagonal) for random cell integrals, on a gmsh mesh with a pocket, a periodic gmsh mesh and a
    grid (whose entries that sum to exactly zero are left out). The triangles' 3 x 3 blocks summed onto it
    (:func:`_on_pattern`) have the pattern of their conversion into CSR, explicit zeros kept, the off-diagonal
    entries (two terms) bit for bit and the diagonal to round-off (1e-15 of the largest entry: another order)."""
    import scipy.sparse as sp

    rng = np.random.default_rng(12)
    for mesh in _stiffness_meshes():
        cells = fv._cells(mesh, fv.operators(mesh, "P1"))
        pattern = fv._p1_pattern(mesh)
        assert pattern is not None
        w = rng.uniform(0.5, 2.0, cells.t.shape[1])
        got, want = fv._stiffness_of(cells, w, pattern), _sparse_stiffness(cells, w)
        assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
        assert np.array_equal(got.data, want.data)
        assert (want.nnz < pattern.indices.size) == (mesh.source == "grid")   # the zero entries left out
        blocks = rng.standard_normal(9 * cells.t.shape[1])
        blocks[::11] = 0.0
        rows, cols = fv._block_places(cells.t)
        ref = sp.csr_matrix((blocks, (rows, cols)), shape=(cells.n, cells.n))
        on = fv._on_pattern(pattern, blocks)
        assert np.array_equal(on.indptr, ref.indptr) and np.array_equal(on.indices, ref.indices)
        off = on.indices != np.repeat(np.arange(cells.n), np.diff(on.indptr))
        assert np.array_equal(on.data[off], ref.data[off])
        assert np.abs(on.data - ref.data).max() <= 1e-15 * np.abs(ref.data).max()


def test_p1_pattern_needs_the_meshs_edges_of_the_triangles():
    """Without scikit-fem's edges of the triangles at hand (``t2f``) or with triangles that do not match them,
    no pattern: the solve keeps the sparse sums (and the same answers to round-off)."""
    import copy

    mesh = mesh_surface(Surface(arc=(0.0, 1.0), half_width=0.5), 0.2)
    bare = copy.deepcopy(mesh)
    bare._cache.clear()
    bare.mesh.__dict__.pop("_t2f", None)
    assert fv._p1_pattern(bare) is None and not hasattr(bare.mesh, "_t2f")
    shuffled = copy.deepcopy(mesh)
    shuffled._cache.clear()
    shuffled.mesh.t = shuffled.mesh.t[[1, 2, 0]]   # the same triangles, their nodes in another order
    assert fv._p1_pattern(shuffled) is None
    assert fv._stiffness_pattern(shuffled) is None and fv._stiffness_pattern(shuffled) is None   # first, second


def test_symmetric_compares_a_matrix_with_its_transpose():
    """:func:`_symmetric` (the full-film guess's test before banded Cholesky) agrees with ``(K != K^T).nnz == 0``
    on the pocket pad's full-film matrix and on changed copies: a value off its mirror, an entry without its
    mirror; an explicit zero without its mirror counts as a difference (a conservative no: SuperLU then)."""
    import scipy.sparse as sp

    from bearingfe import Rectangle

    pad = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[Rectangle((0.7, 0.0), (0.2, 0.2))])
    mesh = mesh_surface(pad, 0.08)
    ops = fv.operators(mesh, "P1")
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "streamline")
    unk = fv._unknowns(mesh, ops)
    K = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.5), 0.0)[0]
    assert fv._symmetric(K) and (K != K.T).nnz == 0
    changed = K.copy()
    changed.data[1] *= 1.0 + 1e-15   # an off-diagonal entry (the first is the diagonal of row 0)
    assert changed.indices[1] != 0 and not fv._symmetric(changed) and (changed != changed.T).nnz > 0
    lower = sp.tril(K).tocsr()
    lower.sort_indices()
    assert not fv._symmetric(lower) and (lower != lower.T).nnz > 0
    zero = sp.csr_matrix((np.array([1.0, 0.0, 1.0]), np.array([0, 1, 1]), np.array([0, 2, 3])), shape=(2, 2))
    assert not fv._symmetric(zero)
    assert not fv._symmetric(sp.csr_matrix(np.ones((2, 3))))


def test_circle_depth_at_once_is_the_loop_over_recesses():
    """Circular recesses tested all at once (:func:`_circle_depth`, from the surface's recess table) give bit for
    bit the loop over recesses it replaces (each recess's rows, ``out[rows] += depth * contains``, in order) and the
    surface's own ``recess_depth``: rows in two recesses' lists (boxes across two dimples' boxes, added by
    ``np.add.at``) and rows in one only, points of 16 per row and of one; a surface with a rectangle keeps the loop."""
    from bearingfe import Rectangle

    rng = np.random.default_rng(11)
    x0, z0 = rng.uniform(0.0, 0.9, 600), rng.uniform(-0.5, 0.4, 600)
    x1, z1 = x0 + rng.uniform(0.0, 0.5, 600), z0 + rng.uniform(0.0, 0.5, 600)
    s = rng.uniform(0.0, 1.0, (2, 600, 16))
    X, Z = x0[:, None] + (x1 - x0)[:, None] * s[0], z0[:, None] + (z1 - z0)[:, None] * s[1]
    mixed = Surface(arc=(0.0, 1.0), half_width=0.5,
                    recesses=[Recess(Circle((0.3, 0.0), 0.2), 0.3), Recess(Rectangle((0.75, 0.25), (0.2, 0.15)), 0.7)])
    for surface in (_dimpled(), mixed):
        rows = fv._overlaps(surface, x0, x1, z0, z1)
        for xs, zs in ((X, Z), (X[:, :1], Z[:, :1])):
            expected = np.zeros(xs.shape)
            for r, idx in zip(surface.recesses, rows):
                expected[idx] += r.depth * r.shape.contains(xs[idx], zs[idx])
            got = fv._depth_on_rows(surface, rows, xs, zs)
            assert np.array_equal(got, expected) and np.array_equal(got, surface.recess_depth(xs, zs))
        shared = np.bincount(np.concatenate(rows), minlength=600)
        assert np.count_nonzero(shared > 1) > 10 and np.count_nonzero(shared == 1) > 100
    assert fv._recess_table(_dimpled()).centre is not None and fv._recess_table(mixed).centre is None
    small = (x0, x0 + 0.05 * (x1 - x0), z0, z0 + 0.05 * (z1 - z0))   # boxes within 0.025: each row near one dimple
    Xs = small[0][:, None] + (small[1] - small[0])[:, None] * s[0]
    Zs = small[2][:, None] + (small[3] - small[2])[:, None] * s[1]
    rows = fv._overlaps(_dimpled(), *small)
    assert np.bincount(np.concatenate(rows)).max() == 1 and sum(r.size for r in rows) > 100
    assert np.array_equal(fv._depth_on_rows(_dimpled(), rows, Xs, Zs), _dimpled().recess_depth(Xs, Zs))


def test_tensor_overlaps_numbered_at_once_are_the_rectangles_own_test():
    """:func:`_tensor_overlaps` numbers every box's cells at once: the same increasing indices as testing each
    rectangle of the tensor product against each recess box (:func:`_recess_boxes`), with and without a copy of
    the rectangles, on lines so sparse that some boxes meet no node (empty lists) and on dense ones."""
    surface = _dimpled()
    boxes = fv._recess_boxes(surface)
    sparse_lines = (np.array([0.0, 0.25, 0.5, 1.0]), np.linspace(-0.5, 0.5, 6))   # no node in two dimples' boxes
    for xs, zs in (sparse_lines,
                   (np.linspace(0.0, 1.0, 41), np.sort(np.random.default_rng(5).uniform(-0.5, 0.5, 37)))):
        for x, z in (((xs[:-1], xs[1:]), (zs[:-1], zs[1:])), ((xs, xs), (zs, zs))):
            X0, Z0 = np.meshgrid(x[0], z[0], indexing="ij")
            X1, Z1 = np.meshgrid(x[1], z[1], indexing="ij")
            X0, X1, Z0, Z1 = X0.ravel(), X1.ravel(), Z0.ravel(), Z1.ravel()
            expected = [np.flatnonzero((X1 >= lo[0]) & (X0 <= hi[0]) & (Z1 >= lo[1]) & (Z0 <= hi[1]))
                        for lo, hi in boxes]
            for copies in (1, 2):
                got = fv._tensor_overlaps(surface, x, z, copies=copies)
                want = [np.concatenate([e + k * X0.size for k in range(copies)]) for e in expected]
                assert len(got) == len(want) and all(np.array_equal(g, w) for g, w in zip(got, want))
    sparse = fv._tensor_overlaps(surface, (sparse_lines[0],) * 2, (sparse_lines[1],) * 2)
    assert any(r.size == 0 for r in sparse) and any(r.size for r in sparse)


def test_circle_depth_from_boxes_is_the_points_own_test():
    """Circular recesses take a rectangle wholly inside or outside a circle from its box (:func:`_circle_depth`
    with ``boxes``): the same values, bit for bit, as the surface's ``recess_depth`` of its points, on rectangles
    inside the dimples, across their contours, just outside them and away; and the grid triangles' boxes
    (:func:`_triangle_boxes`, their cells') are their corners' own, so the quadrature depth of a grid is its points'."""
    surface = _dimpled()
    rng = np.random.default_rng(13)
    centres = np.array([r.shape.center for r in surface.recesses])[rng.integers(0, 4, 900)]
    angle, radius = rng.uniform(0.0, 2 * np.pi, 900), 0.15 * rng.uniform(0.0, 1.3, 900)
    x0, z0 = centres[:, 0] + radius * np.cos(angle), centres[:, 1] + radius * np.sin(angle)
    size = rng.uniform(0.0, 0.05, (2, 900))
    x1, z1 = x0 + size[0], z0 + size[1]
    s = rng.uniform(0.0, 1.0, (2, 900, 16))
    X, Z = x0[:, None] + (x1 - x0)[:, None] * s[0], z0[:, None] + (z1 - z0)[:, None] * s[1]
    got = fv._boxed_depth(surface, x0, x1, z0, z1, X, Z)
    assert np.array_equal(got, surface.recess_depth(X, Z))
    whole = np.all(got == got[:, :1], axis=1)
    assert np.count_nonzero(whole & (got[:, 0] > 0)) > 100 and np.count_nonzero(~whole) > 100
    mesh = grid_mesh(surface, 1 / 23)
    t, p = mesh.mesh.t, mesh.mesh.p
    boxes = fv._triangle_boxes(mesh)
    assert all(np.array_equal(b, f(p[k, t], axis=0)) for b, k, f in zip(boxes, (0, 0, 1, 1), (np.min, np.max) * 2))
    x = fv.operators(mesh, "P1").basis.mapping.F(np.array([[1 / 6, 2 / 3, 1 / 6], [1 / 6, 1 / 6, 2 / 3]]))
    assert np.array_equal(fv._quadrature_depth(mesh, x), surface.recess_depth(x[0], x[1]))


def test_unknowns_selection_is_scipys_conversion():
    """A mesh without a periodic seam takes its unknowns' selection S from _selection (its CSR arrays written
    directly): the same arrays, dtypes and canonical flag as scipy's conversion of the entries (ones at
    (I[k], k)), noted as a selection for _selects; a periodic mesh keeps the conversion and _selects finds it
    is none. Also at the edges: no rows, every row, the last row only."""
    import scipy.sparse as sp

    for rows, n in ((np.array([2, 3, 7, 8, 11]), 13), (np.zeros(0, np.int64), 4), (np.arange(6), 6),
                    (np.array([5]), 6)):
        want = sp.csr_matrix((np.ones(rows.size), (rows, np.arange(rows.size))), shape=(n, rows.size))
        got = fv._selection(rows, n)
        assert got.shape == want.shape and got.has_canonical_format
        for name in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(got, name), getattr(want, name))
            assert getattr(got, name).dtype == getattr(want, name).dtype
    mesh = mesh_surface(_dimpled(), 0.2)
    ops = fv.operators(mesh, "P1")
    unk = fv._unknowns(mesh, ops)
    want = sp.csr_matrix((np.ones(ops.interior.size), (ops.interior, np.arange(ops.interior.size))),
                         shape=(ops.n_dofs, ops.interior.size))
    assert np.array_equal(unk.S.indptr, want.indptr) and np.array_equal(unk.S.indices, want.indices)
    assert unk._order["selects"] is True and fv._selects(fv.FVUnknowns(S=want, rep=unk.rep, fixed=unk.fixed))
    import math

    from bearingfe.bearings.journal import Groove, JournalBearing
    (surface,) = JournalBearing(1.0, periodic=True, grooves=(Groove(math.pi / 2, math.radians(20.0), 0.8),)).surfaces()
    seam = mesh_surface(surface, 0.5)
    unk = fv._unknowns(seam, fv.operators(seam, "P1"))
    assert "selects" not in unk._order and not fv._selects(unk) and unk._order["selects"] is False


def test_sorted_entries_are_scipys_conversion():
    """sorted_entries (scipy's coo_tocsr and csr_sort_indices kernels) gives scipy's conversion of the entries
    with sorted indices, bit for bit (arrays and dtypes), on random places in random order; places given twice
    take scipy's conversion (their entries summed); and the P1 pattern of a gmsh mesh is the one built through
    scipy's conversion (its take, the entries' slots, included)."""
    import scipy.sparse as sp

    rng = np.random.default_rng(11)
    for n in (1, 7, 40):
        places = rng.permutation(n * n)[: max(1, n * n // 3)]
        rows, cols = places // n, places % n
        values = rng.normal(size=places.size)
        want = sp.csr_matrix((values, (rows, cols)), shape=(n, n))
        want.sort_indices()
        got = sorted_entries(rows, cols, values, n)
        assert got.has_canonical_format and got.shape == (n, n)
        for name in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(got, name), getattr(want, name))
            assert getattr(got, name).dtype == getattr(want, name).dtype
    twice = sorted_entries(np.array([0, 1, 0]), np.array([1, 0, 1]), np.array([1.0, 2.0, 3.0]), 2)
    assert twice.nnz == 2 and twice[0, 1] == 4.0
    mesh = mesh_surface(Surface(arc=(0.0, 1.0), half_width=0.5, recesses=[Recess(Circle((0.5, 0.0), 0.2), 1.0)]), 0.1)
    m = mesh.mesh
    t, n, facets, edge = m.t, int(m.nvertices), np.asarray(m.facets), np.asarray(m.t2f)
    pattern = fv._pattern_of(t, n, facets, edge)
    nodes = np.arange(n)
    rows, cols = np.concatenate([facets[0], facets[1], nodes]), np.concatenate([facets[1], facets[0], nodes])
    P = sp.csr_matrix((np.arange(rows.size, dtype=float), (rows, cols)), shape=(n, n))
    P.sort_indices()
    assert np.array_equal(pattern.indptr, P.indptr) and np.array_equal(pattern.indices, P.indices)
    assert np.array_equal(pattern.take, P.data.astype(np.int64))


def test_set_band_takes_the_full_film_order_of_the_same_pattern(monkeypatch):
    """On a fresh gmsh mesh the active-set matrices' union pattern is the full-film matrix's own: the set band
    takes the reverse Cuthill-McKee order the full-film guess's band plan found (the same array), which is
    scipy's order of the union pattern; a solve that searches the order again gives the same answer bit for
    bit (pocket pad of docs/jfo_gmsh.md, streamline flux, size 0.05: 529 nodes)."""
    import pickle

    from scipy.sparse.csgraph import reverse_cuthill_mckee

    from benchmarks.jfo_gmsh import KINDS, make_mesh, pocket_pad

    case = pocket_pad()
    options = {k: v for k, v in case.options.items() if k != "cavitation"}
    blob = pickle.dumps(make_mesh(case, "streamline", 0.05))
    mesh = pickle.loads(blob)
    got = solve_jfo(mesh, case.film, couette=KINDS["streamline"][1], **options)
    ops = fv.operators(mesh, "P1")
    unk = fv._unknowns(mesh, ops)
    plan = unk._order["band"][2]
    perm, _ = unk._order["set_band"][2]
    assert perm is plan.perm
    system = fv._assemble(ops, mesh, case.film, 1.0, (0.0, 0.0), None, None, "streamline")
    K, G, _ = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.02)
    pattern = fv._union_pattern(K.tocsc(), G.tocsc())
    assert np.array_equal(perm, reverse_cuthill_mckee(pattern, symmetric_mode=True))
    assert fv._full_film_order(unk, pattern) is plan.perm
    other = pattern.copy()
    other.indices = other.indices.copy()
    other.indices[[0, 1]] = other.indices[[1, 0]]
    assert fv._full_film_order(unk, other) is None
    monkeypatch.setattr(fv, "_full_film_order", lambda unk, pattern: None)
    again = solve_jfo(pickle.loads(blob), case.film, couette=KINDS["streamline"][1], **options)
    assert np.array_equal(got.pressure, again.pressure) and np.array_equal(got.theta, again.theta)
    assert got.iterations == again.iterations
