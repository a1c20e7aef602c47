"""The cost-saving paths of the JFO finite-volume solver (``bearingfe.film.finite_volume``) give the answers of
the paths they replace: the P1 integrals on the arrays against scikit-fem's assembly of the same forms, the
bounding-box recess depth against ``Surface.recess_depth``, the ordered factorization of the active-set
matrices against SuperLU's COLAMD, and the nested start of unstructured meshes against a cold start.

The references are the replaced computations themselves, so the tolerances are round-off (1e-12 relative on
the integrals; 1e-9 on a solve, whose matrices have condition numbers up to about 1e4).
"""

import numpy as np
import pytest

from benchmarks.jfo_gmsh import dimple, pocket_pad
from bearingfe import Circle, Ellipse, Polygon, Recess, Surface, UniformFilm, grid_mesh, mesh_surface
from bearingfe.film import finite_volume as fv
from bearingfe.film.forms import load, weighted_laplace
from bearingfe.film.mesh_operators import operators


def _options(case):
    return {k: v for k, v in case.options.items() if k != "cavitation"}


def test_p1_integrals_on_the_arrays_match_scikit_fem():
    mesh = mesh_surface(Surface(arc=(0.0, 1.0), half_width=0.5), 0.1)
    ops = operators(mesh, "P1")
    cells = fv._cells(mesh, ops)
    x = ops.x
    c = 1.0 + x[0] ** 2 + np.sin(3 * x[1])            # a coefficient that varies inside the triangles
    K = fv._stiffness(cells, c)
    K_ref = weighted_laplace.assemble(ops.basis, c=c)
    assert abs(K - K_ref).max() <= 1e-12 * abs(K_ref).max()
    f = np.cos(x[0]) * (1 + x[1])
    assert np.allclose(fv._load(cells, f), load.assemble(ops.basis, f=f), rtol=0, atol=1e-14)
    u = np.sin(2 * mesh.mesh.p[0]) + mesh.mesh.p[1] ** 2
    values, grad = fv._interpolate(cells, u)
    ref = ops.basis.interpolate(u)
    assert np.allclose(values, np.asarray(ref), rtol=0, atol=1e-14)
    assert np.allclose(grad, np.asarray(ref.grad)[:, :, 0], rtol=0, atol=1e-12)


def test_bounding_box_recess_depth_is_the_surfaces():
    shapes = [Circle((0.1 + 0.3 * i, -0.3 + 0.3 * j), 0.05) for i in range(3) for j in range(2)]
    shapes += [Ellipse((0.2, 0.35), (0.08, 0.03), 0.4), Polygon([(0.6, 0.25), (0.9, 0.3), (0.7, 0.45)])]
    surface = Surface(arc=(0.0, 1.0), half_width=0.5,
                      recesses=[Recess(s, 0.5 + 0.1 * k) for k, s in enumerate(shapes)])
    rng = np.random.default_rng(1)
    phi, z = rng.random((300, 40)), rng.random((300, 40)) - 0.5
    depth = fv._recess_depth(surface, phi, z)
    assert depth.shape == phi.shape and np.count_nonzero(depth) > 500
    assert np.array_equal(depth, surface.recess_depth(phi, z))


def test_ordered_factorization_gives_the_colamd_answer(monkeypatch):
    case = pocket_pad()
    mesh = mesh_surface(case.surface, 0.04)
    monkeypatch.setattr(fv, "ORDERED_FROM", 10**9)
    colamd = fv.solve_jfo(mesh, case.film, couette="streamline", **_options(case))
    monkeypatch.setattr(fv, "ORDERED_FROM", 0)
    ordered = fv.solve_jfo(mesh_surface(case.surface, 0.04), case.film, couette="streamline", **_options(case))
    assert ordered.iterations == colamd.iterations
    assert np.abs(ordered.pressure - colamd.pressure).max() <= 1e-9 * np.abs(colamd.pressure).max()
    assert np.abs(ordered.theta - colamd.theta).max() <= 1e-9
    assert abs(ordered.mass_balance) < 1e-12


def test_grid_factorizations_are_ordered_from_fewer_unknowns(monkeypatch):
    # on a grid_mesh the closed-form dissection order is taken from ORDERED_FROM_GRID unknowns (a 40 x 40 grid of
    # the dimple: 1,521 unknowns, below ORDERED_FROM): the same iterations and the COLAMD answer to round-off
    # (the banded LU that takes such small grids first is turned off: the ordered SuperLU is the path tested)
    from bearingfe.core.banded import BAND_LIMITS, BandLimits

    monkeypatch.setitem(BAND_LIMITS, "active_set_lu", BandLimits(kd_max=0, size_max=64**2))
    surface = Surface(arc=(0.0, 1.0), half_width=0.5, recesses=[Recess(Circle((0.5, 0.0), 0.25), 1.0)])
    options = dict(cavitation_pressure=-0.05, couette="grid")
    mesh = grid_mesh(surface, 1 / 40)
    unk = fv._unknowns(mesh, operators(mesh, "P1"))
    assert unk.on_grid and fv.ORDERED_FROM_GRID <= unk.rep.size < fv.ORDERED_FROM
    ordered = fv.solve_jfo(mesh, UniformFilm(1.0), **options)
    assert unk._order["order"].size == unk.rep.size   # the order was taken
    monkeypatch.setattr(fv, "ORDERED_FROM_GRID", 10**9)
    colamd = fv.solve_jfo(grid_mesh(surface, 1 / 40), UniformFilm(1.0), **options)
    assert ordered.iterations == colamd.iterations and np.array_equal(ordered.cavitated, colamd.cavitated)
    assert np.abs(ordered.pressure - colamd.pressure).max() <= 1e-9 * np.abs(colamd.pressure).max()
    assert np.abs(ordered.theta - colamd.theta).max() <= 1e-9
    assert abs(ordered.mass_balance) < 1e-12


def test_ordered_factorization_falls_back_on_an_inaccurate_solve():
    """A matrix whose diagonal pivots are tiny (the symmetric mode keeps them above the 0.01 threshold
    only by pivoting): the solve still returns the answer to round-off, by the COLAMD fallback if needed."""
    rng = np.random.default_rng(3)
    mesh = grid_mesh(Surface(arc=(0.0, 1.0), half_width=0.5), 1 / 9)
    unk = fv._unknowns(mesh, operators(mesh, "P1"))
    n = unk.rep.size
    import scipy.sparse as sp

    A = sp.random(n, n, density=0.2, random_state=4) + sp.diags(np.full(n, 1e-14))
    A = (A + sp.eye(n, k=1) * 3 + sp.eye(n, k=-1)).tocsc()
    old = fv.ORDERED_FROM
    try:
        fv.ORDERED_FROM = 0
        solve = fv._ordered_splu(unk, A, A)(A)
    finally:
        fv.ORDERED_FROM = old
    b = rng.random(n)
    x = solve(b)
    assert np.abs(A @ x - b).max() <= 1e-8 * np.abs(b).max()


@pytest.mark.parametrize("couette, fewer", [("streamline", True), ("median", False)])
def test_nested_start_on_gmsh_meshes_gives_the_cold_answer_in_fewer_fine_steps(monkeypatch, couette, fewer):
    case = pocket_pad()
    monkeypatch.setattr(fv, "NESTED_MIN_UNSTRUCTURED", 300)
    monkeypatch.setattr(fv, "NESTED_UNSTRUCTURED", False)
    cold = fv.solve_jfo(mesh_surface(case.surface, 0.03), case.film, couette=couette, **_options(case))
    monkeypatch.setattr(fv, "NESTED_UNSTRUCTURED", True)
    mesh = mesh_surface(case.surface, 0.03)
    nested = fv.solve_jfo(mesh, case.film, couette=couette, **_options(case))
    assert mesh.n_nodes > 1000 and cold.cost.get("nested_levels") is None
    assert nested.cost["nested_levels"] >= 1 and nested.cost["coarse_iterations"] >= 1
    assert nested.iterations < cold.iterations if fewer else nested.iterations <= cold.iterations
    assert np.abs(nested.pressure - cold.pressure).max() <= 1e-9 * np.abs(cold.pressure).max()
    assert np.abs(nested.theta - cold.theta).max() <= 1e-9


@pytest.mark.parametrize("make, cold_factorizations, nested_factorizations", [(pocket_pad, 3, 1), (dimple, 3, 2)])
def test_gmsh_meshes_of_about_1500_unknowns_take_the_nested_start(monkeypatch, make, cold_factorizations,
                                                                   nested_factorizations):
    # the uniform 0.025 meshes of docs/jfo_gmsh.md (1,936 and 1,964 nodes, 1,744 and 1,804 unknowns) are above
    # NESTED_MIN_UNSTRUCTURED: the nested start ends on the cold start's complementarity solution (to the
    # solver tolerance) in fewer fine factorizations (the counts measured: the pocket pad 1 against 3, the
    # dimple 2 against 3)
    case = make()
    mesh = mesh_surface(case.surface, 0.025, recess_size=0.025)
    nested = fv.solve_jfo(mesh, case.film, **_options(case))
    monkeypatch.setattr(fv, "NESTED_UNSTRUCTURED", False)
    cold = fv.solve_jfo(mesh, case.film, **_options(case))
    assert nested.cost["nested_levels"] == 1 and cold.cost.get("nested_levels") is None
    assert nested.cost["factorizations"] == nested_factorizations
    assert cold.cost["factorizations"] == cold_factorizations
    assert np.array_equal(nested.cavitated, cold.cavitated)
    assert np.abs(nested.pressure - cold.pressure).max() <= 1e-9 * np.abs(cold.pressure).max()
    assert np.abs(nested.theta - cold.theta).max() <= 1e-9


def test_no_nested_start_where_no_grid_fits():
    """A circular pocket cannot be a hole of a grid_mesh: the solve starts cold (and still converges)."""
    surface = Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[Circle((0.7, 0.0), 0.1)])
    mesh = mesh_surface(surface, 0.05)
    assert fv._grid_under(mesh) is None
    res = fv.solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05)
    assert res.cost.get("nested_levels") is None and abs(res.mass_balance) < 1e-10


def test_grid_under_an_unstructured_mesh_is_kept_on_it():
    """The nested start's grid under a gmsh mesh is built once per mesh: a second cold solve on the mesh takes
    the same grid object and gives the first solve's answers bit for bit (the same coarse level, so the same
    start and the same fine iterations)."""
    case = pocket_pad()
    mesh = mesh_surface(case.surface, 0.025, recess_size=0.025)   # 1,936 nodes: above NESTED_MIN_UNSTRUCTURED
    grid = fv._grid_under(mesh)
    assert grid is not None and fv._grid_under(mesh) is grid
    first = fv.solve_jfo(mesh, case.film, couette="streamline", **_options(case))
    again = fv.solve_jfo(mesh, case.film, couette="streamline", **_options(case))
    assert first.cost["nested_levels"] == again.cost["nested_levels"] == 1.0
    assert fv._grid_under(mesh) is grid
    assert np.array_equal(first.pressure, again.pressure) and np.array_equal(first.theta, again.theta)
    assert first.iterations == again.iterations and first.flows == again.flows
