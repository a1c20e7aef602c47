"""gmsh meshing: named boundaries, curved edges, nesting, gmsh state, file input.

Expected lengths and areas are those of the exact geometry (perimeters and
areas of rectangles and circles); the tolerances are the chord error of a
polygonal boundary, ``1 - sin(t)/t`` with ``t = size / (2 r)`` per edge.
"""

import math

import gmsh
import numpy as np
import pytest
import skfem

import bearingfe as bf
from bearingfe import Circle, Rectangle, Surface, load_mesh, mesh_surface, refine_uniformly
from bearingfe.geometry.meshing import refine_once
from bearingfe.geometry.meshing import SupportMesh
from tests.helpers import ROOT

MESHES = ROOT / "meshes"

TWO_POCKETS = Surface(arc=(-0.5, 0.5), half_width=0.4,
                      inlets=(Circle((-0.2, 0.0), 0.1), Rectangle((0.25, 0.05), (0.15, 0.2))))


def facet_lengths(mesh: skfem.Mesh, facets: np.ndarray) -> np.ndarray:
    p, f = mesh.p, mesh.facets[:, facets]
    return np.linalg.norm(p[:, f[0]] - p[:, f[1]], axis=0)


def film_area(sm: SupportMesh) -> float:
    basis = skfem.Basis(sm.mesh, skfem.ElementTriP1(), intorder=4)
    return float(basis.dx.sum())


def test_named_boundaries_of_a_rectangle_with_two_pockets():
    sm = mesh_surface(TWO_POCKETS, 0.05)
    b = sm.boundaries
    assert {"outer", "inlet", "inlet_0", "inlet_1", "arc_start", "arc_end", "side"} <= set(b)
    m = sm.mesh
    # straight edges are meshed exactly: lengths 2a = 0.8 and 2 x arc length 1.0
    assert facet_lengths(m, b["arc_start"]).sum() == pytest.approx(0.8, rel=1e-12)
    assert facet_lengths(m, b["arc_end"]).sum() == pytest.approx(0.8, rel=1e-12)
    assert facet_lengths(m, b["side"]).sum() == pytest.approx(2.0, rel=1e-12)
    assert facet_lengths(m, b["outer"]).sum() == pytest.approx(3.6, rel=1e-12)
    # edges in the right places
    x = m.p[:, m.facets[:, b["arc_start"]]]
    assert np.allclose(x[0], -0.5)
    x = m.p[:, m.facets[:, b["side"]]]
    assert np.allclose(np.abs(x[1]), 0.4)
    # pocket contours: inscribed polygon of the circle (chord error < 1e-2 at size/r = 0.5),
    # rectangle perimeter exactly
    assert facet_lengths(m, b["inlet_0"]).sum() == pytest.approx(2 * math.pi * 0.1, rel=1.1e-2)
    assert facet_lengths(m, b["inlet_1"]).sum() == pytest.approx(0.7, rel=1e-12)
    assert np.array_equal(np.sort(b["inlet"]), np.union1d(b["inlet_0"], b["inlet_1"]))
    # all named facets are boundary facets; outer and inlet partition the boundary
    boundary = m.boundary_facets()
    assert np.array_equal(np.union1d(b["outer"], b["inlet"]), np.sort(boundary))
    assert np.intersect1d(b["outer"], b["inlet"]).size == 0
    # film area = outline - pockets; the pocket polygon is inscribed in the circle, so the film
    # is larger by the chord deficit pi r^2 (1 - sin(2t)/(2t)) ~ pi r^2 (2t)^2/6 with
    # t = size/(2r) = 0.25, i.e. at most 4.1 % of the circle
    exact = 0.8 - math.pi * 0.01 - 0.03
    assert exact < film_area(sm) < exact + 0.05 * math.pi * 0.01
    assert sm.has_inlet and sm.geometry_order == 1 and sm.n_nodes == m.nvertices


def test_non_rectangular_outline_has_only_outer_and_inlet():
    sm = mesh_surface(Surface(outer=Circle((0, 0), 0.5), inlets=(Circle((0.1, 0), 0.1),)), 0.1)
    assert set(sm.boundaries) == {"outer", "inlet", "inlet_0"}


def test_order_two_puts_edge_midpoints_on_the_curves():
    sm = mesh_surface(Surface(outer=Circle((0, 0), 0.5), inlets=(Circle((0.05, 0.0), 0.15),)), 0.1, order=2)
    m = sm.mesh
    assert isinstance(m, skfem.MeshTri2) and sm.geometry_order == 2
    # the P2 dofs on a facet are its two ends and its midpoint node: all on the circle
    basis = skfem.Basis(m, skfem.ElementTriP2())
    for name, centre, r in (("outer", (0, 0), 0.5), ("inlet", (0.05, 0.0), 0.15)):
        dofs = basis.get_dofs(sm.boundaries[name]).all()
        x = basis.doflocs[:, dofs]
        assert np.hypot(x[0] - centre[0], x[1] - centre[1]) == pytest.approx(r, abs=1e-9)
    # curved (isoparametric) triangles reproduce the annulus area far better than chords:
    # exact 0.25 pi - 0.0225 pi; straight chords miss ~ (2t)^2/6 of each circle (the outer and
    # pocket deficits partly cancel: measured 6.7e-4 vs 2.8e-5 curved)
    exact = math.pi * (0.25 - 0.0225)
    curved = abs(film_area(sm) / exact - 1)
    assert curved < 1e-4
    assert abs(film_area(mesh_surface(sm.surface, 0.1)) / exact - 1) > 10 * curved


def test_refine_gives_nested_meshes_with_new_nodes_on_the_curves():
    surface = Surface(inlets=(Circle((0, 0), 0.2),))
    coarse, fine = (mesh_surface(surface, 0.1, refine=k) for k in (0, 1))
    assert fine.mesh.nelements == 4 * coarse.mesh.nelements
    assert fine.size == pytest.approx(0.05)
    # every coarse vertex is a fine vertex
    from scipy.spatial import cKDTree

    d, _ = cKDTree(fine.mesh.p.T).query(coarse.mesh.p.T)
    assert d.max() < 1e-12
    # new pocket nodes were snapped to the circle, not left on the chords
    x = fine.mesh.p[:, np.unique(fine.mesh.facets[:, fine.boundaries["inlet"]])]
    assert np.hypot(*x) == pytest.approx(0.2, abs=1e-9)


def test_inlet_and_corner_sizes_grade_the_mesh():
    sm = mesh_surface(TWO_POCKETS, 0.1, inlet_size=0.02, grading_distance=0.2)
    edges = facet_lengths(sm.mesh, sm.boundaries["inlet"])
    assert edges.max() < 0.02 * 1.5  # gmsh keeps edges within about its size field
    assert facet_lengths(sm.mesh, sm.boundaries["side"]).max() > 0.06


def test_size_function_refines_where_asked():
    fine_left = lambda x, y: np.where(x < 0.0, 0.02, 0.1)  # noqa: E731
    sm = mesh_surface(Surface(), 0.1, size_function=fine_left)
    centroids = sm.mesh.p[:, sm.mesh.t].mean(axis=1)
    left = np.count_nonzero(centroids[0] < -0.1)
    right = np.count_nonzero(centroids[0] > 0.1)
    assert left > 10 * right  # element density ~ (0.1/0.02)^2 = 25 times higher


def test_refine_uniformly_on_straight_meshes_only():
    sm = mesh_surface(Surface(), 0.2)
    assert refine_uniformly(sm, 2).mesh.nelements == 16 * sm.mesh.nelements
    with pytest.raises(ValueError, match="straight-sided"):
        refine_uniformly(mesh_surface(Surface(), 0.2, order=2))


# -- gmsh global state ---------------------------------------------------------

def _signature(sm: SupportMesh):
    return sm.mesh.p.copy(), sm.mesh.t.copy(), {k: v.copy() for k, v in sm.boundaries.items()}


def test_meshing_repeatedly_in_one_process_gives_identical_meshes():
    surface = Surface(inlets=(Circle((0.1, 0.0), 0.1),))
    first = _signature(mesh_surface(surface, 0.1))
    assert not gmsh.isInitialized()  # the session was closed
    # other calls in between with different options, order, callback and geometry
    mesh_surface(TWO_POCKETS, 0.05, inlet_size=0.01, corner_size=0.005, order=2, algorithm=5)
    mesh_surface(Surface(), 0.1, size_function=lambda x, y: 0.03 + 0 * x)
    load_mesh(MESHES / "plain_shoe.geo", size=0.3)
    again = _signature(mesh_surface(surface, 0.1))
    assert np.array_equal(first[0], again[0]) and np.array_equal(first[1], again[1])
    assert first[2].keys() == again[2].keys()
    assert all(np.array_equal(first[2][k], again[2][k]) for k in first[2])
    assert not gmsh.isInitialized()


def test_gmsh_is_finalized_after_an_error_inside_the_session():
    def broken(x, y):
        raise RuntimeError("size function failed")

    with pytest.raises(ValueError, match="size_function failed"):
        mesh_surface(Surface(), 0.1, size_function=broken)
    assert not gmsh.isInitialized()
    for bad in (0.0, -0.1, math.nan):  # never a silent clamp
        with pytest.raises(ValueError, match="size_function"):
            mesh_surface(Surface(), 0.1, size_function=lambda x, y, bad=bad: bad + 0 * x)
    assert mesh_surface(Surface(), 0.25).n_nodes > 0


def test_a_callers_gmsh_session_is_left_as_it_was():
    # meshing inside a caller's own gmsh session: the session stays open, the caller's model and its
    # entities stay current, the options this package sets come back, and the mesh is the same as
    # from a private session
    private = _signature(mesh_surface(Surface(inlets=(Circle((0.1, 0.0), 0.1),)), 0.1))
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("mine")
        gmsh.model.occ.addPoint(0.3, 0.2, 0.0)
        gmsh.model.occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", 7.0)
        gmsh.option.setNumber("Mesh.Algorithm", 8)
        nested = _signature(mesh_surface(Surface(inlets=(Circle((0.1, 0.0), 0.1),)), 0.1,
                                         size_function=lambda x, y: 0.1 + 0 * x))
        load_mesh(MESHES / "plain_shoe.geo", size=0.3)
        assert gmsh.isInitialized()
        assert gmsh.model.getCurrent() == "mine" and gmsh.model.list() == ["", "mine"]
        assert gmsh.model.getEntities(0) == [(0, 1)]
        assert gmsh.option.getNumber("Mesh.MeshSizeMax") == 7.0 and gmsh.option.getNumber("Mesh.Algorithm") == 8
    finally:
        gmsh.finalize()
    assert np.array_equal(private[0], nested[0]) and np.array_equal(private[1], nested[1])


# -- files ---------------------------------------------------------------------

def test_load_mesh_geo_and_msh_agree(tmp_path):
    geo = MESHES / "central_pocket_10pct.geo"
    from_geo = load_mesh(geo, size=0.05)
    # write the .msh with gmsh directly (an independent route to the file)
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(geo))
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.05)
        gmsh.model.mesh.generate(2)
        msh = tmp_path / "pocket.msh"
        gmsh.write(str(msh))
    finally:
        gmsh.finalize()
    from_msh = load_mesh(msh)
    assert from_msh.source == str(msh)
    for sm in (from_geo, from_msh):
        assert {"outer", "inlet", "arc_start", "arc_end", "side"} <= set(sm.boundaries)
        # outline 0.8 minus the pocket 0.08 (10 %) plus the chord deficit of the inscribed
        # pocket polygon, < (2t)^2/6 = 1.7 % of 0.08 at t = 0.05/(2 * 0.1596)
        assert 0.72 < film_area(sm) < 0.72 + 0.017 * 0.08
    assert from_geo.n_nodes == from_msh.n_nodes
    assert film_area(from_geo) == pytest.approx(film_area(from_msh), rel=1e-12)


def test_load_mesh_geo_order_two():
    sm = load_mesh(MESHES / "central_pocket_10pct.geo", size=0.1, order=2)
    assert sm.geometry_order == 2
    assert film_area(sm) == pytest.approx(0.72, rel=1e-4)  # curved edges; measured 2.4e-5


def test_load_mesh_errors(tmp_path):
    with pytest.raises(FileNotFoundError):
        load_mesh(tmp_path / "missing.msh")
    wrong = tmp_path / "mesh.txt"
    wrong.write_text("x")
    with pytest.raises(ValueError, match=".geo or .msh"):
        load_mesh(wrong)
    nameless = tmp_path / "nameless.geo"
    nameless.write_text('SetFactory("OpenCASCADE");\nFor k In {1:4}\n  Point(k) = {(k == 2 || k == 3), k > 2, 0};\n'
                        'EndFor\nFor k In {1:4}\n  Line(k) = {k, k % 4 + 1};\nEndFor\nCurve Loop(1) = {1:4};\n'
                        'Plane Surface(1) = {1};\nPhysical Curve("edge") = {1, 2, 3, 4};\n'
                        'Physical Surface("film") = {1};\n')
    with pytest.raises(ValueError, match="outer"):
        load_mesh(nameless, size=0.5)
    assert not gmsh.isInitialized()


@pytest.mark.parametrize("kwargs, words", [
    (dict(size=0.0), "size"),
    (dict(size=-0.1), "size"),
    (dict(size=math.nan), "size"),
    (dict(size=0.1, inlet_size=0.0), "inlet_size"),
    (dict(size=0.1, corner_size=-1.0), "corner_size"),
    (dict(size=0.1, grading_distance=math.inf), "grading_distance"),
    (dict(size=0.1, order=3), "order"),
    (dict(size=0.1, refine=-1), "refine"),
    (dict(size=0.1, refine=1.5), "refine"),
])
def test_mesh_surface_rejects_bad_sizes_and_options(kwargs, words):
    with pytest.raises(ValueError, match=words):
        mesh_surface(TWO_POCKETS, **kwargs)


def test_mesh_surface_needs_a_surface():
    with pytest.raises(ValueError, match="surface"):
        mesh_surface("shoe", 0.1)


def test_size_function_requests_below_a_quarter_of_size_are_honoured():
    # gmsh's MeshSizeMin used to raise them to size/4 without a word (a silent clamp): with a size
    # function and no min_size there is no floor; an explicit min_size is one
    m = mesh_surface(Surface(), 0.2, size_function=lambda x, y: 0.02 + 0 * x)
    edges = m.mesh.p[:, m.mesh.facets[0]] - m.mesh.p[:, m.mesh.facets[1]]
    assert np.median(np.hypot(*edges)) < 0.03  # requested 0.02; the old floor was 0.05
    floored = mesh_surface(Surface(), 0.2, size_function=lambda x, y: 0.02 + 0 * x, min_size=0.05)
    assert floored.n_nodes < m.n_nodes / 3


def test_refining_a_grid_with_a_pocket_splits_every_cell_and_keeps_the_pocket_edges():
    """refine_once of a grid with an axis-aligned pocket: every cell split in two each way (4x the
    triangles, exactly), the film area and the pocket contour's length unchanged (exact: both are
    unions of grid cells and grid edges)."""
    surface = bf.Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[bf.Rectangle((0.3, 0.1), (0.2, 0.3))])
    coarse = bf.grid_mesh(surface, 0.07)
    fine = refine_once(coarse)
    assert fine.mesh.t.shape[1] == 4 * coarse.mesh.t.shape[1]

    def area(m):
        p = m.mesh.p[:, m.mesh.t]
        return 0.5 * np.abs((p[0, 1] - p[0, 0]) * (p[1, 2] - p[1, 0]) - (p[0, 2] - p[0, 0]) * (p[1, 1] - p[1, 0])).sum()

    def inlet_length(m):
        f = m.mesh.facets[:, m.mesh.boundaries["inlet"]]
        return np.linalg.norm(m.mesh.p[:, f[0]] - m.mesh.p[:, f[1]], axis=0).sum()

    assert area(fine) == pytest.approx(1.0 - 0.2 * 0.3, rel=1e-12)
    assert inlet_length(coarse) == pytest.approx(2 * (0.2 + 0.3), rel=1e-12)
    assert inlet_length(fine) == pytest.approx(2 * (0.2 + 0.3), rel=1e-12)
    assert fine.refinement is not None


def test_recess_contours_are_refined_by_default():
    """A surface with a recess: mesh_surface's default refines the recess contour to size / 8 (edges on the
    contour about that long), recess_size=size turns it off, and the refined mesh is the one remeshed by
    refine_once (its recipe keeps the setting)."""
    import numpy as np

    import bearingfe as bf
    from bearingfe.geometry.meshing import RECESS_REFINEMENT, refine_once

    surface = bf.Surface(arc=(-0.5, 0.5), half_width=0.5, recesses=[bf.Recess(bf.Circle((0.0, 0.0), 0.2), 1.0)])
    default, uniform = bf.mesh_surface(surface, 0.08), bf.mesh_surface(surface, 0.08, recess_size=0.08)

    def contour_edges(mesh):
        p, f = mesh.mesh.p, mesh.mesh.facets
        on = (np.abs(np.hypot(*p[:, f[0]]) - 0.2) < 1e-9) & (np.abs(np.hypot(*p[:, f[1]]) - 0.2) < 1e-9)
        return np.linalg.norm(p[:, f[0]] - p[:, f[1]], axis=0)[on]

    assert np.median(contour_edges(default)) == pytest.approx(RECESS_REFINEMENT * 0.08, rel=0.3)
    assert np.median(contour_edges(uniform)) == pytest.approx(0.08, rel=0.3)
    assert default.n_nodes > 2 * uniform.n_nodes
    finer = refine_once(default)
    assert finer.n_nodes > 3 * default.n_nodes


def test_grid_cells_checked_on_the_lines_agree_with_the_per_triangle_check(monkeypatch):
    """grid_mesh skips check_triangles when its grid lines prove every triangle valid; the line test
    (_grid_cells_valid) must accept exactly the grids check_triangles accepts: here an ordinary grid, and an
    elongated one whose half cells fall below check_triangles' area bound (1e-10 x longest edge squared)."""
    from bearingfe.geometry import meshing
    from bearingfe.geometry.geofiles import GeometryFileError

    ok_x, ok_z = np.linspace(0.0, 1.0, 5), np.linspace(-0.5, 0.5, 4)
    assert meshing._grid_cells_valid(ok_x, ok_z)
    m = skfem.MeshTri1.init_tensor(ok_x, ok_z)
    meshing.check_triangles(m.p, m.t)   # passes: the line test agrees
    thin_x = np.array([0.0, 1e-11, 1.0])   # a column 1e-11 wide: area / diagonal^2 ~ 5e-12 < 1e-10
    assert not meshing._grid_cells_valid(thin_x, ok_z)
    m = skfem.MeshTri1.init_tensor(thin_x, ok_z)
    with pytest.raises(GeometryFileError, match="degenerate"):
        meshing.check_triangles(m.p, m.t)
    assert not meshing._grid_cells_valid(np.array([0.0, 0.5, 0.5, 1.0]), ok_z)   # a repeated line
    # grid_mesh itself no longer runs the per-triangle check, any other support mesh still does
    calls = []
    monkeypatch.setattr(meshing, "check_triangles", lambda *a, **k: calls.append(1))
    grid = bf.grid_mesh(Surface(arc=(0.0, 1.0), half_width=0.5), 0.25)
    assert calls == [] and "cells_checked" not in vars(grid)   # an init-only flag, not stored
    SupportMesh(mesh=grid.mesh, surface=grid.surface, source="grid")
    assert calls == [1]


def test_gmsh_meshes_check_their_triangles_once(monkeypatch):
    """mesh_surface checks the triangles as it reads gmsh's mesh (mesh_from_data, which load_mesh shares): the
    support mesh it returns does not check them again, one made elsewhere still does; a bad file still fails on
    mesh_from_data's check (tests/hostile)."""
    from bearingfe.geometry import meshing

    calls = []
    real = meshing.check_triangles
    monkeypatch.setattr(meshing, "check_triangles", lambda *a, **k: calls.append(1) or real(*a, **k))
    mesh = bf.mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4), 0.2)
    assert calls == [1] and "cells_checked" not in vars(mesh)
    calls.clear()
    SupportMesh(mesh=mesh.mesh, surface=mesh.surface, source="user")  # a mesh from elsewhere: checked
    assert calls == [1]


@pytest.mark.parametrize("order", [1, 2])
def test_gmsh_meshes_have_scikit_fems_own_facets_and_boundaries(order):
    """mesh_from_data builds the facets by the counting sort and finds the named curves' facets by their codes:
    the facets, the triangle-to-facet map and every boundary equal what scikit-fem builds from the same triangles
    (reference: a fresh scikit-fem mesh of the same nodes and triangles, its boundaries by the curves' node pairs)."""
    shoe = Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[bf.Circle((0.0, 0.0), 0.16)])
    m = bf.mesh_surface(shoe, 0.08, order=order).mesh
    fresh = type(m)(m.doflocs if order == 2 else m.p, m.t if order == 1 else np.vstack([m.t, m.t2f + m.nvertices]))
    np.testing.assert_array_equal(m.facets, fresh.facets)
    np.testing.assert_array_equal(m.t2f, fresh.t2f)
    pairs = {tuple(f): k for k, f in enumerate(fresh.facets.T.tolist())}
    for name, facets in m.boundaries.items():
        ends = np.sort(m.facets[:, facets], axis=0)
        assert [pairs[tuple(e)] for e in ends.T.tolist()] == facets.tolist()


def test_grid_facets_are_the_ones_scikit_fem_builds():
    """grid_mesh builds its facets itself (a sparse counting sort); they must be scikit-fem's own arrays
    (Mesh.facets, Mesh.t2f, f2t): the same pairs in the same order, on a grid with a pocket cut out."""
    pocket = bf.Rectangle((0.3, 0.1), (0.2, 0.3))
    grid = bf.grid_mesh(Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[pocket]), 0.1)
    fresh = skfem.MeshTri1(grid.mesh.p, grid.mesh.t)   # nothing built yet: scikit-fem sorts the facets itself
    assert np.array_equal(grid.mesh.facets, fresh.facets) and grid.mesh.facets.dtype == fresh.facets.dtype
    assert np.array_equal(grid.mesh.t2f, fresh.t2f)
    assert np.array_equal(grid.mesh.f2t, fresh.f2t)


def test_refine_marked_is_scikit_fems_local_refinement():
    """refine_marked (the rupture front's refinement levels) gives the mesh of scikit-fem's own
    ``refined(marked)`` to the last index (nodes, triangles and their dtype), level after level, on a grid with a
    pocket; bad input is refused naming the parameter."""
    from bearingfe.geometry.meshing import name_surface_boundaries, refine_marked

    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[bf.Rectangle((0.3, 0.1), (0.2, 0.3))])
    ours = theirs = skfem.MeshTri1(bf.grid_mesh(surface, 0.1).mesh.p, bf.grid_mesh(surface, 0.1).mesh.t)
    rng = np.random.default_rng(3)
    for _ in range(3):
        marked = np.sort(rng.choice(theirs.nelements, theirs.nelements // 5, replace=False))
        ours, theirs = refine_marked(ours, marked), theirs.refined(marked)
        assert np.array_equal(ours.p, theirs.p)
        assert np.array_equal(ours.t, theirs.t) and ours.t.dtype == theirs.t.dtype
    # valid by construction: naming it without the triangle check gives the checked mesh's boundaries
    named = name_surface_boundaries(skfem.MeshTri1(ours.p, ours.t), surface, cells_checked=True)
    checked = name_surface_boundaries(skfem.MeshTri1(ours.p, ours.t), surface)
    assert named.boundaries.keys() == checked.boundaries.keys()
    assert all(np.array_equal(named.boundaries[k], checked.boundaries[k]) for k in checked.boundaries)
    with pytest.raises(ValueError, match="marked"):
        refine_marked(ours, np.array([ours.nelements]))
    with pytest.raises(ValueError, match="marked"):
        refine_marked(ours, np.array([0.5]))
    with pytest.raises(ValueError, match="MeshTri1"):
        refine_marked(skfem.MeshQuad1(), np.array([0]))


def test_refine_marked_builds_scikit_fems_facets_of_the_refined_mesh():
    """refine_marked builds the refined mesh's facets and triangle-to-facet map from the split (unsplit facets,
    halves, inner edges, one sort): the arrays (values and dtypes) scikit-fem sorts out of the refined triangles
    itself, level after level, whether the mesh it splits has its facets already (a named mesh, the previous
    split) or not; the nodes and triangles are scikit-fem's ``refined``'s, also for a mesh with subdomains
    (scikit-fem's own split then)."""
    from bearingfe.geometry.meshing import refine_marked

    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[bf.Rectangle((0.3, 0.1), (0.2, 0.3))])
    grid = bf.grid_mesh(surface, 0.1).mesh   # has its facets
    rng = np.random.default_rng(11)
    for start in (grid, skfem.MeshTri1(grid.p, grid.t), skfem.MeshTri1.init_symmetric().refined(2)):
        ours, theirs = start, skfem.MeshTri1(start.p, start.t)
        for level in range(4):
            marked = rng.choice(theirs.nelements, max(1, theirs.nelements // (3 + level)), replace=False)
            ours, theirs = refine_marked(ours, marked), theirs.refined(marked)
            assert np.array_equal(ours.p, theirs.p) and np.array_equal(ours.t, theirs.t)
            assert ours.t.dtype == theirs.t.dtype and ours.sort_t == theirs.sort_t
            fresh = skfem.MeshTri1(ours.p, ours.t)   # nothing built: scikit-fem sorts the facets itself
            assert np.array_equal(ours._facets, fresh.facets) and ours._facets.dtype == fresh.facets.dtype
            assert np.array_equal(ours._t2f, fresh.t2f) and ours._t2f.dtype == fresh.t2f.dtype
        assert np.array_equal(refine_marked(ours, np.array([], int)).t, ours.t)   # nothing marked: the same mesh
    parts = skfem.MeshTri1.init_symmetric().refined(2)
    parts = parts.with_subdomains({"left": lambda x: x[0] < 0.5})
    marked = np.array([0, 5, 9])
    ours, theirs = refine_marked(parts, marked), parts.refined(marked)
    assert np.array_equal(ours.p, theirs.p) and np.array_equal(ours.t, theirs.t)
    assert np.array_equal(ours.subdomains["left"], theirs.subdomains["left"])


def test_refine_marked_records_each_triangles_parent():
    """refine_marked records the triangle of the mesh it split (and of the meshes that one was split from, while
    alive) holding each new triangle (split_parents), through several splits and a named copy: every new
    triangle's centroid lies inside its parent (barycentric coordinates >= -1e-12), the new triangles of a parent
    cover its area (to 1e-12 relative), a P2 field of a quadratic function evaluated at the new dofs from the
    parents (locate.values_in_cells) equals the function there to 1e-12 (P2 reproduces it); a mesh not split from
    the other has no record (None)."""
    from bearingfe.geometry.locate import barycentric, values_in_cells
    from bearingfe.geometry.meshing import refine_marked, split_parents, with_named_boundaries

    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[bf.Rectangle((0.3, 0.1), (0.2, 0.3))])
    start = bf.grid_mesh(surface, 0.1).mesh
    rng = np.random.default_rng(7)
    meshes = [start]
    for level in range(4):
        m = refine_marked(meshes[-1], rng.choice(meshes[-1].nelements, 25, replace=False))
        meshes.append(with_named_boundaries(m, {"some": np.array([0])}) if level == 1 else m)

    def area(m):
        p = m.p[:, m.t]
        return 0.5 * np.abs((p[0, 1] - p[0, 0]) * (p[1, 2] - p[1, 0]) - (p[1, 1] - p[1, 0]) * (p[0, 2] - p[0, 0]))

    def quadratic(x):
        return 1.0 + 2.0 * x[0] - x[1] + 3.0 * x[0] ** 2 - 2.0 * x[0] * x[1] + 0.5 * x[1] ** 2
    fine = meshes[-1]
    fine_basis = skfem.Basis(fine, skfem.ElementTriP2())
    for coarse in meshes[:-1]:
        parents = split_parents(coarse, fine)
        assert parents.shape == (fine.nelements,)
        l1, l2 = barycentric(coarse.p, coarse.t, parents, fine.p[:, fine.t].mean(axis=1))
        assert min(l1.min(), l2.min(), (1 - l1 - l2).min()) >= -1e-12
        covered = np.bincount(parents, area(fine), minlength=coarse.nelements)
        assert np.abs(covered - area(coarse)).max() <= 1e-12 * area(coarse).max()
        basis = skfem.Basis(coarse, skfem.ElementTriP2())
        owner = np.empty(fine_basis.N, dtype=np.int64)
        owner[fine_basis.element_dofs] = np.arange(fine.nelements)
        x = np.asarray(fine_basis.doflocs)
        values = values_in_cells(basis, quadratic(np.asarray(basis.doflocs)), x, parents[owner])
        assert np.abs(values - quadratic(x)).max() <= 1e-12
    assert np.array_equal(split_parents(fine, fine), np.arange(fine.nelements))
    assert split_parents(fine, start) is None
    assert split_parents(skfem.MeshTri1(start.p, start.t), fine) is None  # an equal mesh, not the one split


def test_sorting_networks_are_numpys_column_sorts():
    """The facets' node pairs and a refined mesh's triangles are put in order by elementwise minima and maxima
    instead of ``np.sort(..., axis=0)`` (a call per column): the same arrays and dtypes, ties included."""
    from bearingfe.geometry import meshing

    rng = np.random.default_rng(2)
    for n, high in ((1, 3), (50, 4), (5000, 10**6)):
        t = rng.integers(0, high, (3, n)).astype(np.int32)
        assert np.array_equal(meshing._sorted_columns(t), np.sort(t, axis=0))
        assert meshing._sorted_columns(t).dtype == t.dtype
        assert np.array_equal(meshing._in_order(t[0], t[2]), np.sort(t[[0, 2]], axis=0))
    m = skfem.MeshTri1.init_symmetric().refined(3)
    expected = np.sort(np.hstack([m.t[ix] for ix in m.elem.refdom.facets]), axis=0)
    assert np.array_equal(meshing._facet_pairs(m), expected) and meshing._facet_pairs(m).dtype == expected.dtype


def test_refined_meshes_named_as_connected_skip_the_component_search(monkeypatch):
    """name_surface_boundaries(connected=True) (the rupture front's splits of a checked support mesh: the same
    pieces on the same outline) does not search the connected components again; by default it does, and the
    boundaries are the same either way."""
    from bearingfe.geometry import meshing

    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[bf.Rectangle((0.3, 0.1), (0.2, 0.3))])
    grid = bf.grid_mesh(surface, 0.1).mesh
    m = meshing.refine_marked(grid, np.arange(0, grid.nelements, 7))
    calls = []
    real = meshing._check_components
    monkeypatch.setattr(meshing, "_check_components", lambda *a, **k: calls.append(1) or real(*a, **k))
    known = meshing.name_surface_boundaries(m, surface, cells_checked=True, connected=True)
    assert calls == []
    searched = meshing.name_surface_boundaries(m, surface, cells_checked=True)
    assert calls == [1]
    assert all(np.array_equal(known.boundaries[k], searched.boundaries[k]) for k in searched.boundaries)


def test_named_locally_refined_meshes_have_scikit_fems_own_facets():
    """name_surface_boundaries (a grid refined locally by scikit-fem, e.g. at a journal's rupture front) builds
    the facets by the same counting sort as grid_mesh: scikit-fem's own arrays, and the same named boundaries as
    when scikit-fem sorts them."""
    from bearingfe.geometry.meshing import name_surface_boundaries

    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[bf.Rectangle((0.3, 0.1), (0.2, 0.3))])
    grid = bf.grid_mesh(surface, 0.1)
    refined = grid.mesh.refined(np.arange(0, grid.n_elements, 3))
    named = name_surface_boundaries(skfem.MeshTri1(refined.p, refined.t), surface)
    sorted_by_skfem = skfem.MeshTri1(refined.p, refined.t)
    assert np.array_equal(named.mesh.facets, sorted_by_skfem.facets)
    assert np.array_equal(named.mesh.t2f, sorted_by_skfem.t2f)
    facets = sorted_by_skfem.boundary_facets()
    assert set(named.boundaries) >= {"outer", "inlet", "arc_start", "arc_end", "side"}
    assert all(np.isin(f, facets).all() for f in named.boundaries.values())
    assert np.array_equal(np.sort(named.boundaries["outer"]),
                          np.sort(facets[~np.isin(facets, named.boundaries["inlet"])]))


def test_per_mesh_structures_are_built_once_per_key_and_kept_per_mesh():
    """SupportMesh.cached is the one home of per-mesh structures: built once per key, kept per mesh (the
    operators and the finite-volume structures all go through it). A mesh solved on still pickles: its
    structures stay behind (scikit-fem bases do not pickle) and are rebuilt in the copy, to the same answer."""
    import pickle

    from bearingfe.film.finite_volume import solve_jfo
    from bearingfe.film.thickness import UniformFilm
    from bearingfe.geometry import meshing

    def dimpled():   # one dimple on a parallel slider: it cavitates (the JFO caches are all exercised)
        shape = Surface(arc=(0.0, 1.0), half_width=0.5, recesses=[bf.Recess(Circle((0.5, 0.0), 0.2), 0.8)])
        return bf.grid_mesh(shape, 1.0 / 24)

    def solve(m):
        return solve_jfo(m, UniformFilm(1.0), cavitation_pressure=-0.02, couette="grid")

    mesh, calls = dimpled(), []
    first = mesh.cached(("probe", 1), lambda: calls.append(1) or np.arange(3.0))
    again = mesh.cached(("probe", 1), lambda: calls.append(2) or np.zeros(3))
    other = mesh.cached(("probe", 2), lambda: calls.append(3) or np.ones(3))
    assert again is first and calls == [1, 3] and np.array_equal(other, np.ones(3))
    fresh = dimpled()   # not shared between meshes (a new grid holds only the lines grid_mesh keeps, tensor_lines)
    assert fresh._cache is not mesh._cache and set(fresh._cache) == {meshing.TENSOR_LINES}
    res = solve(mesh)
    assert res.cavitated_fraction > 0.01
    kept = {k if isinstance(k, str) else k[0] for k in mesh._cache}
    assert {"finite_volume.grid_faces", "finite_volume.cells", "finite_volume.unknowns",
            "finite_volume.vertex_depth", "finite_volume.cut_cells"} <= kept
    # the kept structures give the same answer as a fresh mesh, bit for bit; so does a pickled copy
    assert np.array_equal(solve(mesh).pressure, res.pressure)
    assert np.array_equal(solve(dimpled()).pressure, res.pressure)
    copy = pickle.loads(pickle.dumps(mesh))
    assert copy._cache == {} and mesh._cache
    assert np.array_equal(solve(copy).pressure, res.pressure)


def test_tensor_facets_in_closed_form_are_scikit_fems_own():
    """A grid without pockets gets its facets and triangle-to-facet map in closed form (_tensor_facets): the
    same arrays (values and dtypes) as the counting sort (_init_facets) and as scikit-fem's own sort, on
    uneven lines of several shapes, down to one cell."""
    from bearingfe.geometry import meshing

    rng = np.random.default_rng(5)
    for nx, nz in ((2, 2), (3, 7), (9, 2), (36, 36), (40, 13)):
        xs, zs = np.sort(rng.random(nx)), np.sort(rng.random(nz))
        ours = skfem.MeshTri1.init_tensor(xs, zs)
        meshing._tensor_facets(ours, nx, nz)
        sorted_ = skfem.MeshTri1.init_tensor(xs, zs)
        meshing._init_facets(sorted_)
        theirs = skfem.MeshTri1.init_tensor(xs, zs)
        for ref in (sorted_._facets, theirs.facets):
            assert np.array_equal(ours._facets, ref) and ours._facets.dtype == ref.dtype
        for ref in (sorted_._t2f, theirs.t2f):
            assert np.array_equal(ours._t2f, ref) and ours._t2f.dtype == ref.dtype


def test_whole_grids_skip_the_component_search_pocketed_ones_do_not(monkeypatch):
    """A grid without pockets is one piece touching ``outer`` by construction: grid_mesh (and the nested
    start's coarser grids, made the same way) skip the connected-component search; a grid with a pocket (a
    hole that could cut it in pieces) and a support mesh made elsewhere still search."""
    from bearingfe.geometry import meshing

    calls = []
    real = meshing._check_components
    monkeypatch.setattr(meshing, "_check_components", lambda *a, **k: calls.append(1) or real(*a, **k))
    whole = bf.grid_mesh(Surface(arc=(0.0, 1.0), half_width=0.5), 0.1)
    assert calls == [] and "connected" not in vars(whole)   # an init-only flag, not stored
    bf.grid_mesh(Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[bf.Rectangle((0.5, 0.0), (0.2, 0.2))]), 0.1)
    assert calls == [1]
    SupportMesh(mesh=whole.mesh, surface=whole.surface, source="grid")
    assert calls == [1, 1]
