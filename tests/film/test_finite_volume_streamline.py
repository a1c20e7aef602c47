"""The streamline Couette flux of JFO on gmsh meshes (``solve_jfo(..., couette="streamline")``, the default on
``mesh_surface`` meshes): convergence on the cases of ``benchmarks/jfo_gmsh.py`` against their converged grid
references, full-film equality with the Galerkin flux, the recess-contour treatment and positivity.

Reference values are those of ``tests/film/test_finite_volume_pockets.py``: Richardson extrapolations of the
benchmark's three finest ``grid_mesh`` solutions (docs/jfo_gmsh.md), an independent and much finer solution
than the small gmsh meshes used here.
"""

import math

import numpy as np
import pytest

from benchmarks.jfo_gmsh import dimple, grooved_journal, pocket_pad, quantities
from bearingfe import CosineFilm, ProfileFilm, mesh_surface, solve_reynolds
from bearingfe.bearings.journal import JournalBearing
from bearingfe.film.finite_volume import RECESS_JFO_NOTE, UNSTRUCTURED_JFO_NOTE, solve_jfo
from tests.film.test_finite_volume_pockets import DIMPLE_LOAD, GROOVED_JOURNAL, POCKET_PAD


def _errors(case, sizes, reference, couette="streamline"):
    options = {k: v for k, v in case.options.items() if k != "cavitation"}
    rows, results = [], []
    for s in sizes:
        res = solve_jfo(mesh_surface(case.surface, s), case.film, couette=couette, **options)
        rows.append(quantities(res))
        results.append(res)
    return {k: [abs(q[k] / v - 1) for q in rows] for k, v in reference.items()}, results


def test_default_flux_on_gmsh_meshes_is_the_streamline_flux():
    case = pocket_pad()
    mesh = mesh_surface(case.surface, 0.1)
    options = {k: v for k, v in case.options.items() if k != "cavitation"}
    default = solve_reynolds(mesh, case.film, **case.options)
    streamline = solve_jfo(mesh, case.film, couette="streamline", **options)
    assert default.integral == streamline.integral and "upwinded_segments" in default.cost


def test_pocket_pad_flows_converge_above_first_order_without_smearing():
    """Measured errors (sizes 0.05, 0.025, 0.0125): inlet 2.2e-2, 8.0e-3, 3.1e-3; side 4.8e-3, 1.1e-3,
    2.9e-4; load within 1.4e-3 throughout. The median flux's side flow is 11 %, 5.5 %, 3.6 % off."""
    err, results = _errors(pocket_pad(), (0.05, 0.025, 0.0125), POCKET_PAD)
    for k in ("inlet", "side"):
        orders = [math.log2(a / b) for a, b in zip(err[k][:-1], err[k][1:])]
        assert min(orders) > 1.2, (k, err[k])
    assert max(err["load"]) < 2e-3
    assert max(e[-1] for e in err.values()) < 4e-3
    assert all(len(r.notes) == 1 and r.cost["upwinded_segments"] == 0 for r in results)
    assert all(abs(r.mass_balance) < 1e-10 for r in results)


def test_grooved_periodic_journal_side_flow_within_one_percent_from_6k_nodes():
    """Measured side-flow errors 2.8 % and 0.96 % at sizes 0.1 and 0.05 (1,520 and 5,839 nodes), where the
    median flux is 75 % and 45 % off; load within 3e-3."""
    err, results = _errors(grooved_journal(), (0.1, 0.05), GROOVED_JOURNAL)
    assert err["side"][0] < 0.035 and err["side"][1] < 0.011 and err["side"][1] < 0.5 * err["side"][0]
    assert max(err["load"]) < 3e-3
    res = results[-1]
    assert res.flows["inlet"] == pytest.approx(res.flows["side"], rel=1e-10)


def test_dimple_load_converges_at_first_order_and_is_noted():
    """Measured load errors 5.1 % and 2.3 % at sizes 0.04 and 0.02 (the contour nodes' theta referred to
    their deepest film; taking theta as is there gives 24 % and 11 %, the median flux 15 % and 7 %)."""
    err, results = _errors(dimple(), (0.04, 0.02), {"load": DIMPLE_LOAD})
    assert err["load"][1] < 0.03 and math.log2(err["load"][0] / err["load"][1]) > 0.9
    assert all(RECESS_JFO_NOTE in r.notes and UNSTRUCTURED_JFO_NOTE not in r.notes for r in results)


def test_without_rupture_the_streamline_flux_is_the_galerkin_flux():
    """With theta = 1 the foot weights sum to 1: the same Couette term as the median flux, to round-off."""
    case = pocket_pad()
    mesh = mesh_surface(case.surface, 0.1)
    film = ProfileFilm(((0.0, 2.0), (1.0, 1.0)))
    a = solve_jfo(mesh, film, inlet_pressure=1.0, couette="streamline")
    b = solve_jfo(mesh, film, inlet_pressure=1.0, couette="median")
    assert not np.any(a.theta < 1) and np.abs(a.pressure - b.pressure).max() < 1e-12
    assert len(a.notes) == 1


def test_squeeze_that_empties_the_film_is_upwinded_where_theta_would_fall_below_zero():
    """A journal closing fast (gamma_rate -0.5): the streamline flux alone ends with theta < 0 next to the
    cavity; the segments out of those nodes take the upwind value and theta stays in [0, 1] (measured 706
    segments upwinded, theta >= 0.0063), load within 1 % of the median flux's."""
    (surface,) = JournalBearing(1.0).surfaces()
    mesh = mesh_surface(surface, 0.1)
    res = solve_jfo(mesh, CosineFilm(0.6, 0.0), squeeze=(-0.5, 0.0))
    assert res.cost["upwinded_segments"] > 0 and res.theta.min() >= 0.0
    # the count is beside the times, not subtracted from the postprocess time as seconds (it was -706 s)
    assert res.cost["postprocess"] >= 0.0
    median = solve_jfo(mesh, CosineFilm(0.6, 0.0), squeeze=(-0.5, 0.0), couette="median")
    assert np.hypot(*res.force) == pytest.approx(np.hypot(*median.force), rel=1e-2)
    assert abs(res.mass_balance) < 1e-10



def test_streamline_matrices_summed_per_triangle_equal_the_segment_sums():
    # the flux matrices are summed per triangle (3 x 3 blocks) before the sort into CSR; reference: each
    # segment's outflow f_s sum_b w_b theta(foot node b) added to its two cells one by one (COO), with a
    # tenth of the segments upwinded (theta of their upwind node) and the recess contour's scaled operator
    import scipy.sparse as sp

    from bearingfe.film import finite_volume as fv

    case = dimple()
    mesh = mesh_surface(case.surface, 0.05)
    st = fv._assemble(fv.operators(mesh), mesh, case.film, 1.0, (0.0, 0.0), None, None, "streamline").reconstruction
    n, d = mesh.n_nodes, st.d
    upwinded = np.random.default_rng(3).random(st.up.size) < 0.1
    w = np.where(upwinded, 0.0, st.weights)
    w[0] += upwinded
    nodes = st.nodes.copy()
    nodes[0] = np.where(upwinded, st.up, nodes[0])
    scale = st.scale.copy()
    scale[0] = np.where(upwinded, st.up_scale, scale[0])

    def by_segment(weights):
        rows = np.concatenate([np.tile(d.i, 3), np.tile(d.j, 3)])
        vals = (st.flux * weights).ravel()
        return sp.csr_matrix((np.concatenate([vals, -vals]), (rows, np.concatenate([nodes.ravel()] * 2))), (n, n))

    C, C_cavity = st.matrices(n, upwinded)
    for new, ref in ((C, by_segment(w)), (C_cavity, by_segment(w * scale))):
        assert abs(new - ref).max() <= 1e-15 * abs(ref).max()
    assert st.scale is not None and upwinded.sum() > 50


def test_median_dual_equals_the_segment_by_segment_construction():
    # the three edge pairs of every triangle computed at once; reference: the construction pair by pair
    # (centroid g, edge midpoint m, normal (g - m) turned by 90 degrees towards the edge's second node,
    # segment midpoint (m + g) / 2), the same operations in the same order: equal bit for bit
    from bearingfe.film import finite_volume as fv

    m = mesh_surface(dimple().surface, 0.05).mesh
    p, t = m.p, m.t[:3]
    g = p[:, t].mean(axis=1)
    i, j, normal, mid = [], [], [], []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        edge = 0.5 * (p[:, t[a]] + p[:, t[b]])
        s = g - edge
        n = np.array([s[1], -s[0]])
        flip = np.sum(n * (p[:, t[b]] - p[:, t[a]]), axis=0) < 0
        n[:, flip] *= -1
        i.append(t[a]), j.append(t[b]), normal.append(n), mid.append(0.5 * (edge + g))
    d = fv.median_dual(m)
    assert np.array_equal(d.i, np.concatenate(i)) and np.array_equal(d.j, np.concatenate(j))
    assert np.array_equal(d.normal, np.hstack(normal)) and np.array_equal(d.midpoint, np.hstack(mid))
    # each segment's normal points from its first node to its second (positive along the edge)
    assert np.all(np.sum(d.normal * (p[:, d.j] - p[:, d.i]), axis=0) > 0)


@pytest.mark.parametrize("rotating", [False, True])
def test_streamline_feet_lie_upstream_on_their_triangles_edges(rotating):
    # the foot of each segment's streamline, sum_b w_b x(node b): on the line from the segment midpoint
    # against the sliding direction (cross product 0, dot product <= 0), on an edge of the segment's own
    # triangle (a barycentric weight 0, all >= 0, summing to 1): geometry, to round-off
    import bearingfe as bf
    from bearingfe.film import finite_volume as fv
    from bearingfe.geometry.runner import Rotating, velocity_at
    from tests.film.test_runner import SECTOR

    surface = bf.Surface(outer=SECTOR, runner=Rotating()) if rotating else dimple().surface
    mesh = mesh_surface(surface, 0.05)
    ops = fv.operators(mesh)
    d = fv.median_dual(mesh.mesh)
    u = velocity_at(mesh.runner, d.midpoint)
    direction = 1.0 if u is None else (u[0], u[1])
    nodes, w = fv._streamline_weights(mesh, d, direction, fv._cells(mesh, ops).grad)
    p = mesh.mesh.p
    foot = np.einsum("bs,dbs->ds", w, p[:, nodes])
    step = foot - d.midpoint
    ux, uy = (np.ones(d.i.size), np.zeros(d.i.size)) if u is None else u
    scale = np.hypot(*step) + 1e-300
    assert np.abs(step[0] * uy - step[1] * ux).max() <= 1e-12 * np.abs(p).max()
    assert np.all(step[0] * ux + step[1] * uy <= 1e-12 * np.abs(p).max() * scale)
    assert w.min() >= 0.0 and np.abs(w.sum(axis=0) - 1.0).max() <= 1e-14 and w.min(axis=0).max() <= 1e-14
    tri = np.arange(d.i.size) % mesh.mesh.t.shape[1]
    assert np.array_equal(nodes, mesh.mesh.t[:3][:, tri])


def test_contour_scales_are_the_deepest_film_at_the_node_over_the_film_on_the_triangles_side():
    # reference, node by node from the definition: the recess depth just inside each triangle at each of its
    # nodes (surface.recess_depth), the deepest over the node's triangles, scale = (h + deepest) / (h + depth);
    # per segment the scale of its triangle's nodes and of its upwind node; equal bit for bit
    from bearingfe.film import finite_volume as fv

    case = dimple()
    mesh = mesh_surface(case.surface, 0.05)
    d = fv.median_dual(mesh.mesh)
    f = np.random.default_rng(5).standard_normal(d.i.size)
    scale, up_scale = fv._contour_scales(mesh, case.film, d, f)
    p, t = mesh.mesh.p, mesh.mesh.t[:3]
    nt = t.shape[1]
    depth = np.zeros((3, nt))
    for k in range(nt):
        g = p[:, t[:, k]].mean(axis=1)
        for a in range(3):
            q = p[:, t[a, k]] + 1e-6 * (g - p[:, t[a, k]])
            depth[a, k] = case.surface.recess_depth(q[0], q[1])
    deepest = np.zeros(mesh.n_nodes)
    for a in range(3):
        for k in range(nt):
            deepest[t[a, k]] = max(deepest[t[a, k]], depth[a, k])
    h = case.film.thickness(p[0], p[1])[t]
    ref = (h + deepest[t]) / (h + depth)
    assert np.count_nonzero(ref != 1.0) > 50   # contour nodes of the dimple
    seg = np.arange(d.i.size)
    tri, pair = seg % nt, seg // nt
    up = np.where(f > 0, pair, (pair + 1) % 3)
    assert np.array_equal(scale, ref[:, tri]) and np.array_equal(up_scale, ref[up, tri])


def test_woodbury_steps_count_only_the_columns_not_solved_for_yet():
    # a step that adds a few switched unknowns to an earlier Woodbury step's reuses the kept columns: 22
    # switched (all new), then 25 (3 new) and 45 (20 new) stay on the first factorization; 60 in all (more
    # than twice LOW_RANK_SWITCHES) refactorize, and so do 26 new ones on that factorization. Each answer is
    # the set's system solved directly (spsolve of K diag(~cav) + G diag(cav)) to 1e-12 relative
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    from bearingfe.core.linalg import factorize_splu
    from bearingfe.film import finite_volume as fv

    rng = np.random.default_rng(7)
    m = 400
    K = (sp.random(m, m, density=0.01, random_state=1) + sp.eye(m) * 8.0).tocsr()
    G = (sp.random(m, m, density=0.01, random_state=2) + sp.eye(m) * 5.0).tocsr()
    solver = fv._SetSolver(K, G, factorize_splu)
    base = rng.random(m) < 0.3
    order = rng.permutation(m)

    def step(cav):
        rhs = rng.standard_normal(m)
        y = solver(cav, rhs)
        M = (K @ sp.diags((~cav).astype(float)) + G @ sp.diags(cav.astype(float))).tocsc()
        ref = spla.spsolve(M, rhs)
        assert np.abs(y - ref).max() <= 1e-12 * np.abs(ref).max()

    def switched(k):
        cav = base.copy()
        cav[order[:k]] = ~cav[order[:k]]
        return cav

    step(base)
    for k, factorizations in ((22, 1), (25, 1), (45, 1), (60, 2), (86, 3)):
        step(switched(k))
        assert solver.factorizations == factorizations, k


def test_corner_facet_triangles_found_without_the_inverse_map():
    # the flows' direct facet fluxes need the triangle of a few boundary facets: found among the triangles
    # with two nodes on them, the same as scikit-fem's facet-to-triangle map (built afterwards for the check)
    from bearingfe.film import finite_volume as fv
    from bearingfe.film.mesh_operators import boundary_facet_triangles

    mesh = mesh_surface(dimple().surface, 0.05)   # no pockets: nothing else builds the map
    fv.solve_jfo(mesh, dimple().film, cavitation_pressure=-0.05)
    assert not hasattr(mesh.mesh, "_f2t")
    facets = np.asarray(mesh.boundaries["outer"])
    found = boundary_facet_triangles(mesh.mesh, facets)
    assert np.array_equal(found, mesh.mesh.f2t[0, facets])


def test_nested_start_reads_the_fed_groove_as_full_film(monkeypatch):
    # the coarse grid's fixed dofs carry their own P = p - p_c into the carried sign: the nodes of a mesh
    # refined at a fed groove, between the last coarse cavity node and the groove's edge, start in the
    # full film (where the solution has them); read as 0 (a front) they started in the cavity and took
    # 7 active-set steps instead of 4 (measured); the same answer either way
    from benchmarks.jfo_gmsh import GRADED
    from bearingfe.film import finite_volume as fv

    case = grooved_journal()
    options = {k: v for k, v in case.options.items() if k != "cavitation"}

    def solve():
        mesh = mesh_surface(case.surface, 0.1, inlet_size=GRADED["inlet"] * 0.1,
                            grading_distance=GRADED["grading"] * 0.1)
        return solve_jfo(mesh, case.film, couette="streamline", **options)

    own = solve()
    monkeypatch.setattr(fv, "NESTED_FIXED_SIGN", False)
    zero = solve()
    assert own.cost["nested_levels"] == zero.cost["nested_levels"] == 1.0
    assert own.iterations < zero.iterations and own.cost["factorizations"] < zero.cost["factorizations"]
    assert np.array_equal(own.cavitated, zero.cavitated)
    assert np.abs(own.pressure - zero.pressure).max() <= 1e-12 * np.abs(zero.pressure).max()


def test_effective_operator_picks_each_entry_as_the_column_products_do(monkeypatch):
    # the flows' single Couette operator (cavitated columns from C_cavity) picked entry by entry on the two
    # operators' common pattern: the same entries and values, bit for bit, as the column products and their sum
    # (which keep each row's cavitated columns first), canonical; operators of two patterns take the products
    import dataclasses

    import scipy.sparse as sp

    from bearingfe.film import finite_volume as fv

    seen = {}
    effective = fv._effective
    monkeypatch.setattr(fv, "_effective", lambda system, unk, cavity: seen.setdefault(
        "args", (system, unk, cavity)) and effective(system, unk, cavity))
    case = dimple()
    solve_jfo(mesh_surface(case.surface, 0.05), case.film, cavitation_pressure=-0.05)
    system, unk, cavity = seen["args"]
    assert system.C_cavity is not None and cavity.any() and not cavity.all()
    cav = (unk.S @ cavity.astype(float)) > 0.5
    want = (system.C @ sp.diags((~cav).astype(float)) + system.C_cavity @ sp.diags(cav.astype(float))).tocsr()
    want.sort_indices()
    got = effective(system, unk, cavity)
    assert got.C_cavity is None and got.C.has_canonical_format
    assert np.array_equal(got.C.indptr, want.indptr) and np.array_equal(got.C.indices, want.indices)
    assert np.array_equal(got.C.data, want.data)
    assert (system.C != system.C_cavity).nnz > 0 and np.count_nonzero(system.C.data == 0.0) > 0   # a real pick
    other = dataclasses.replace(system, C_cavity=(system.C_cavity + sp.eye(system.C.shape[0], k=7)).tocsr())
    want = (system.C @ sp.diags((~cav).astype(float)) + other.C_cavity @ sp.diags(cav.astype(float))).tocsr()
    assert (effective(other, unk, cavity).C != want).nnz == 0


@pytest.mark.parametrize("upwind_every", [0, 5])
@pytest.mark.parametrize("on_pattern", [False, True])
def test_full_and_cavity_fluxes_sorted_at_once_are_each_sorted_alone(upwind_every, on_pattern):
    # the streamline flux of the full and of the cavitated nodes' theta (a surface with recesses), sorted into
    # CSR as one complex matrix: each part's indices, pointers and values are those of its own sort, bit for
    # bit, also with upwinded segments (their first weight moved to the upwind node's column); on the mesh's
    # P1 pattern (the default where the mesh has one) each the same as summed onto it alone
    import dataclasses

    from bearingfe.film import finite_volume as fv

    case = dimple()
    mesh = mesh_surface(case.surface, 0.05)
    ops = fv.operators(mesh)
    system = fv._assemble(ops, mesh, case.film, 1.0, (0.0, 0.0), None, None, "streamline")
    st = system.reconstruction
    assert st.pattern is not None
    if not on_pattern:
        st = dataclasses.replace(st, pattern=None)
    upwinded = np.zeros(st.up.size, bool)
    if upwind_every:
        upwinded[::upwind_every] = True
    C, C_cavity = st.matrices(ops.n_dofs, upwinded)
    # the same weights as matrices() gives them, each sorted alone
    w = np.where(upwinded, 0.0, st.weights)
    w[0] += np.where(upwinded, 1.0, 0.0)
    nt = st.nodes.shape[1] // 3
    first = None
    if upwinded.any():
        pair = np.arange(upwinded.size) // nt
        first = np.where(upwinded, np.where(st.up == st.d.i, pair, (pair + 1) % 3), 0)
    s = st.scale.copy()
    s[0] = np.where(upwinded, st.up_scale, s[0])
    t = st.nodes[:, :nt]
    for got, want in ((C, fv._streamline_flux(ops.n_dofs, t, st.flux, w, first, st.pattern)),
                      (C_cavity, fv._streamline_flux(ops.n_dofs, t, st.flux, w * s, first, st.pattern))):
        assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
        assert np.array_equal(got.data, want.data) and np.array_equal(np.signbit(got.data), np.signbit(want.data))
    assert (C != C_cavity).nnz > 0


def test_streamline_nested_start_takes_the_two_grid_band_without_recesses(monkeypatch):
    # the streamline flux's nested start (a grid_mesh a quarter of the nodes) also iterates its carried set on
    # the band around its fronts, corrected by the coarse level, before the first fine factorization, on a
    # surface without recesses: the global solves still decide convergence, so the answer is the plain start's
    # complementarity solution to the solver tolerance (a last Woodbury step is accepted at a 1e-11 residual),
    # in fewer fine factorizations (measured 1 against 2 on the pocket pad at 7,375 nodes)
    from bearingfe.film import finite_volume as fv

    case = pocket_pad()
    options = {k: v for k, v in case.options.items() if k != "cavitation"}
    mesh = mesh_surface(case.surface, 0.0125, recess_size=0.0125)
    calls = []
    two_grid = fv._two_grid_set
    monkeypatch.setattr(fv, "_two_grid_set", lambda *a: calls.append(1) or two_grid(*a))
    band = solve_jfo(mesh, case.film, couette="streamline", **options)
    monkeypatch.setattr(fv, "TWO_GRID_STREAMLINE", False)
    plain = solve_jfo(mesh, case.film, couette="streamline", **options)
    assert len(calls) == 1 and band.cost["nested_levels"] == plain.cost["nested_levels"] == 1.0
    assert plain.cavitated.any() and np.array_equal(band.cavitated, plain.cavitated)
    assert np.abs(band.pressure - plain.pressure).max() < 1e-10 * np.abs(plain.pressure).max()
    assert np.abs(band.theta - plain.theta).max() < 1e-10
    assert band.cost["factorizations"] < plain.cost["factorizations"]
    assert abs(band.mass_balance) < 1e-12 and band.cost["active_set_residual"] < 1e-11


def test_streamline_nested_start_on_a_recessed_surface_keeps_the_carried_set(monkeypatch):
    # on recess contours the streamline flux refers a cavitated node's theta to its deepest film; there the band's
    # start was measured to end on another complementarity solution (the dimple at 11,903 nodes: one node's set
    # and theta by 0.16), so a recessed surface's nested start factorizes the carried set as it is
    from benchmarks.jfo_gmsh import make_mesh
    from bearingfe.film import finite_volume as fv

    case = dimple()
    options = {k: v for k, v in case.options.items() if k != "cavitation"}
    mesh = make_mesh(case, "graded", 0.02)
    calls = []
    two_grid = fv._two_grid_set
    monkeypatch.setattr(fv, "_two_grid_set", lambda *a: calls.append(1) or two_grid(*a))
    res = solve_jfo(mesh, case.film, couette="streamline", **options)
    assert res.cost["nested_levels"] == 1.0 and res.cost["dofs"] >= fv.TWO_GRID_BANDED_FROM and calls == []
