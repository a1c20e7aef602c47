"""The half-space compliance applied by FFT on a uniform grid, and the matrix-free (Newton-Krylov) coupled film.

Expected values: the dense half-space compliance of the same mesh (exact influence
integrals; the FFT sums the same integrals, so the products agree to round-off);
Love's closed form for a uniform pressure on a rectangle (Johnson, Contact Mechanics,
eq. 3.25; P1 reproduces a constant exactly, so at the nodes the only error is
round-off); the dense-path coupled answer on the same mesh (both converged to
1e-11 c, so they agree to 1e-8); and above the dense cap the fixed point's own
definition ``w = C p`` at the answer plus the coarse dense answer (mesh convergence). The grid
transfer for other meshes is an approximation: its error against the dense map is checked to fall
like the grid spacing squared, and its coupled force against the converged reference of
tests/elastic/test_coupled.py (REFERENCE_FORCE, Richardson limit of the dense path on curved P2 meshes).
"""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.core.limits import LimitError
from bearingfe.elastic import (COMPLIANCES, ChordBalance, balance_load, combined_modulus, compliance_of,
                               compliance_on, half_space, half_space_fft, half_space_grid, influence_matrix, rectangle_deflection,
                               solve_elastic)
from bearingfe.elastic.convolution import grid_convolution
from bearingfe.reynolds import operators
from tests.helpers import ROOT

SCALE = bf.Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=157.08)   # the shipped pump
STEEL = bf.Material("steel", 210e9, poisson_ratio=0.3)
PLAIN = bf.Surface(arc=(-0.6, 0.6), half_width=0.4)
# a square recess whose edges lie on the uniform grid lines of the sizes used here (0.05, 0.01)
RECESS = bf.Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[bf.Rectangle((0.0, 0.0), (0.2, 0.2))])
FILM = bf.CosineFilm(0.6, math.pi)


@pytest.mark.parametrize("surface, size, size_z", [(PLAIN, 0.1, 0.08), (RECESS, 0.05, None)])
def test_fft_product_is_the_dense_product(surface, size, size_z):
    # the same exact element integrals, summed by FFT instead of a matrix: round-off apart
    mesh = bf.grid_mesh(surface, size, size_z=size_z)
    dense = half_space(mesh, SCALE, (STEEL, STEEL))
    fft = half_space_fft(mesh, SCALE, (STEEL, STEEL))
    assert fft.matrix is None and not fft.dense and fft.model == "half-space-fft"
    p = np.random.default_rng(1).standard_normal((dense.n_dofs, 3))
    ref = dense.matrix @ p
    assert np.max(np.abs(fft.apply(p) - ref)) <= 1e-10 * np.max(np.abs(ref))
    assert np.max(np.abs(fft.pocket - dense.pocket)) <= 1e-12 * max(1.0, np.max(np.abs(dense.pocket)))
    assert np.max(np.abs(fft.to_dense() - dense.matrix)) <= 1e-10 * np.max(dense.matrix)
    # the pockets by FFT over the holes of the grid against the dense model's contour integral
    holes, (_, pocket) = grid_convolution(mesh).holes(), influence_matrix(mesh)
    assert np.max(np.abs(holes - pocket)) <= 1e-12 * max(1.0, np.max(pocket))
    assert (np.max(pocket) > 0.1) == (surface is RECESS)


def test_one_kernel_product_is_the_dense_product():
    # PLAIN grid (every cell carries its triangles): a field zero on the edge rows takes the one-kernel
    # product; against the dense matrix, round-off apart; with a non-zero edge value it takes the per-shape
    # sums, also the dense product; a grid with a pocket hole has no node kernel
    mesh = bf.grid_mesh(PLAIN, 0.1, size_z=0.08)
    dense = half_space(mesh, SCALE, (STEEL, STEEL))
    fft = half_space_fft(mesh, SCALE, (STEEL, STEEL))
    conv = grid_convolution(mesh)
    assert conv._node_kernel is not None
    p = np.random.default_rng(2).standard_normal(dense.n_dofs)
    edge = (np.abs(mesh.mesh.p[0]) > 0.6 - 1e-9) | (np.abs(mesh.mesh.p[1]) > 0.4 - 1e-9)
    for values in (np.where(edge, 0.0, p), p):
        grid = np.zeros(conv.shape)
        grid.ravel()[conv.flat] = values
        assert conv._edges_vanish(grid) == (values is not p)
        ref = dense.matrix @ values
        assert np.max(np.abs(fft.apply(values) - ref)) <= 1e-10 * np.max(np.abs(ref))
    assert grid_convolution(bf.grid_mesh(RECESS, 0.05))._node_kernel is None


def test_uniform_pressure_on_rectangle_against_love():
    # 32 MPa on the whole 60 x 40 mm shoe: Love's corner formula at every node (corners, edges, centre)
    mesh = bf.grid_mesh(PLAIN, 0.025)
    C = half_space_fft(mesh, SCALE, (STEEL, STEEL))
    d = operators(mesh, "P1").basis.doflocs
    w = C.deflection(np.full(C.n_dofs, SCALE.from_pressure(32e6))) * SCALE.clearance  # [m]
    love = 32e6 / (math.pi * combined_modulus(STEEL, STEEL)) * rectangle_deflection(
        d[0] * SCALE.radius, d[1] * SCALE.radius, 0.6 * SCALE.radius, 0.4 * SCALE.radius)
    assert np.max(np.abs(w - love) / love) < 1e-11
    assert 5e-6 < w.max() < 20e-6  # micrometres: the order of the film


def test_table_row_rebuild_and_refusals():
    mesh = bf.grid_mesh(PLAIN, 0.1)
    C = compliance_of("half-space-fft", mesh, SCALE, STEEL, counterpart=STEEL)
    assert "half-space-fft" in COMPLIANCES and C.modulus == combined_modulus(STEEL, STEEL)
    fine = compliance_on(C, mesh.refinement())
    assert fine.model == "half-space-fft" and fine.n_dofs > C.n_dofs
    with pytest.raises(ValueError, match="P1"):
        half_space_fft(mesh, SCALE, STEEL, "P2")
    graded = bf.grid_mesh(PLAIN, 0.1, column_width=lambda phi: 0.02 + 0.08 * np.abs(phi))
    with pytest.raises(ValueError, match="uniform grid lines"):
        half_space_fft(graded, SCALE, STEEL)
    with pytest.raises(ValueError, match="dense compliance"):
        ChordBalance(C)


@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_matrix_free_newton_is_the_dense_newton(cavitation):
    # pump conditions (32 MPa recess, steel on steel, max opening 0.4 c): both paths to 1e-11 c
    mesh = bf.grid_mesh(RECESS, 0.05)
    ps = SCALE.from_pressure(32e6)
    dense = solve_elastic(mesh, FILM, half_space(mesh, SCALE, (STEEL, STEEL)), inlet_pressure=ps,
                          cavitation=cavitation, tol=1e-11)
    free = solve_elastic(mesh, FILM, half_space_fft(mesh, SCALE, (STEEL, STEEL)), inlet_pressure=ps,
                         cavitation=cavitation, tol=1e-11)
    assert dense.krylov_iterations == 0 < free.krylov_iterations
    assert dense.max_deflection > 0.3
    assert np.max(np.abs(free.deflection - dense.deflection)) <= 1e-8 * dense.max_deflection
    assert np.max(np.abs(free.result.pressure - dense.result.pressure)) <= 1e-8 * dense.result.pressure.max()
    assert free.result.force == pytest.approx(dense.result.force, rel=1e-8)


def test_matrix_free_load_balance_is_the_dense_one():
    # the transient's right side: rates that balance a load with w = C p, damped Newton on both paths
    mesh = bf.grid_mesh(RECESS, 0.05)
    ps = SCALE.from_pressure(32e6)
    load = (-0.3, 0.05)
    kw = dict(wedge=1.0, inlet_pressure=ps, tol=1e-11)
    dense = balance_load(mesh, FILM, half_space(mesh, SCALE, (STEEL, STEEL)), load, **kw)
    free = balance_load(mesh, FILM, half_space_fft(mesh, SCALE, (STEEL, STEEL)), load, reuse={}, **kw)
    assert np.allclose(free.rates, dense.rates, rtol=1e-8, atol=1e-10)
    assert np.max(np.abs(free.deflection - dense.deflection)) <= 1e-8 * np.max(np.abs(dense.deflection))


def test_above_the_dense_cap():
    # 23,936 film unknowns (the dense compliance stops at 4,000): the fixed point w = C p holds at the answer,
    # and the answer continues the dense one of a coarse mesh of the same case: the largest opening
    # converges from above under refinement (0.4030 c at 416 unknowns, dense), so the fine one lies
    # below the coarse one by less than the coarse mesh's error (under 1 %)
    ps = SCALE.from_pressure(32e6)
    coarse_mesh = bf.grid_mesh(RECESS, 0.05)
    coarse = solve_elastic(coarse_mesh, FILM, half_space(coarse_mesh, SCALE, (STEEL, STEEL)), inlet_pressure=ps)
    mesh = bf.grid_mesh(RECESS, 0.00625)
    with pytest.raises(LimitError):
        half_space(mesh, SCALE, (STEEL, STEEL))
    C = half_space_fft(mesh, SCALE, (STEEL, STEEL))
    assert C.n_dofs > 20_000
    sol = solve_elastic(mesh, FILM, C, inlet_pressure=ps, tol=1e-9)
    assert np.max(np.abs(C.deflection(sol.result.pressure, ps) - sol.deflection)) <= 1e-9
    assert 0 < coarse.max_deflection - sol.max_deflection < 0.01 * coarse.max_deflection
    assert sol.result.h_min > sol.rigid_h_min
    # the deflection squeeze takes it too (matrix-free: tests/transient/test_elastic.py), with BDF only
    with pytest.raises(ValueError, match="method must be 'BDF'"):
        bf.transient.simulate_elastic(bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml"), C,
                                      method="LSODA")


POCKET = bf.Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[bf.Circle((0.0, 0.0), 0.1748)])


def test_grid_transfer_on_a_gmsh_mesh_converges_to_the_dense_map():
    # the coupled answer's pressure (32 MPa pocket) through the dense map and through grids of spacing
    # size and size/2: measured 1.3 % and 0.35 % of the largest deflection (second order)
    mesh = bf.mesh_surface(POCKET, 0.05)
    ps = SCALE.from_pressure(32e6)
    dense = half_space(mesh, SCALE, (STEEL, STEEL))
    p = solve_elastic(mesh, FILM, dense, inlet_pressure=ps).result.pressure
    ref = dense.deflection(p, ps)
    errors = [np.max(np.abs(half_space_grid(mesh, SCALE, (STEEL, STEEL), spacing=f * mesh.size).deflection(p, ps)
                            - ref)) / ref.max() for f in (1.0, 0.5)]
    assert errors[1] < 5e-3 and errors[0] / errors[1] > 3.0
    C = compliance_of("half-space-grid", mesh, SCALE, STEEL, counterpart=STEEL)
    assert C.model == "half-space-grid" and not C.dense
    with pytest.raises(ValueError, match="spacing"):
        half_space_grid(mesh, SCALE, STEEL, spacing=-1.0)


def test_grid_transfer_above_the_dense_cap_on_curved_p2():
    # curved P2, 0.03 R0: 4781 dofs (above the dense limit); Swift-Stieber; the force against the converged
    # reference 0.4176956 of the dense path (tests/elastic/test_coupled.py): within 3e-4 (measured 1.7e-4)
    mesh = bf.mesh_surface(POCKET, 0.03, order=2)
    ps = SCALE.from_pressure(32e6)
    C = half_space_grid(mesh, SCALE, (STEEL, STEEL), "P2")
    assert C.n_dofs > 4000
    sol = solve_elastic(mesh, FILM, C, inlet_pressure=ps, element="P2", cavitation="reynolds")
    assert abs(sol.result.force[0] - 0.4176956) / 0.4176956 < 3e-4
    assert np.max(np.abs(C.deflection(sol.result.pressure, ps) - sol.deflection)) <= 1e-8


def test_quasi_static_pump_transient_takes_the_grid_transfer():
    # simulate(elastic=...) balances the load with balance_load at every step: with a compliance held as its
    # product it runs the Newton-Krylov there (no chord factors). Expected: the dense run on the same coarse
    # mesh; the grid transfer is an approximation, measured 4e-4 apart on the smallest film
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    mesh = bf.transient.pump_mesh(pump, 0.3)
    mats = (pump.shoe_material, pump.eccentric_material)
    runs = [bf.simulate(pump, mesh, revolutions=0.25, elastic=build(mesh, pump.scale, mats), element="P1")
            for build in (half_space, half_space_grid)]
    dense, grid = (float(np.min(r.h_min)) for r in runs)
    assert grid == pytest.approx(dense, rel=2e-3)


def test_grid_probes_and_cell_kernel_equal_the_searched_ones():
    # GridConvolution.probes (cells by index arithmetic) against the k-d tree search of
    # bearingfe.geometry.locate on the same grid; the whole-cell kernel summed from the two halves' kernels
    # against its direct integral (GridConvolution's holes); both to round-off. Points: a curved P2 mesh's
    # dofs (some a hair outside the box of its vertices) and points on grid lines and the diagonal.
    import skfem

    from bearingfe.elastic.convolution import GridConvolution
    from bearingfe.elastic.half_space import element_integrals
    from bearingfe.geometry.locate import probe_matrices

    mesh = bf.mesh_surface(POCKET, 0.1, order=2)
    basis = operators(mesh, "P2").basis
    lo, hi = mesh.mesh.p.min(axis=1), mesh.mesh.p.max(axis=1)
    grid = skfem.MeshTri1.init_tensor(np.linspace(lo[0], hi[0], 27), np.linspace(lo[1], hi[1], 19))
    conv = GridConvolution(grid)
    edges = np.array([[lo[0], hi[0], 0.5 * (lo[0] + hi[0]), grid.p[0, 40]], [lo[1], hi[1], grid.p[1, 40], grid.p[1, 40]]])
    points = np.hstack([basis.doflocs, grid.p[:, ::7], edges])
    searched = probe_matrices(skfem.Basis(grid, skfem.ElementTriP1()), points)[0]
    field = np.sin(3.0 * grid.p[0]) * np.cos(2.0 * grid.p[1]) + grid.p[0] * grid.p[1]
    assert np.abs(conv.probes(points) @ field - searched @ field).max() <= 1e-12
    hx, hz = conv.step
    cell = np.array([[0.0, hx, hx, 0.0, hx, 0.0], [0.0, 0.0, hz, 0.0, hz, hz]]).reshape(2, 2, 3).transpose(0, 2, 1)
    m = np.arange(-3, 4)  # grid offsets along the cells' diagonal
    direct = element_integrals(np.array([m * hx, m * hz]), cell, "P1").sum(axis=(0, 2))
    assert conv._whole_shapes
    summed = conv._cell_kernel[np.mod(m, conv._pad[0]), np.mod(m, conv._pad[1])]
    assert np.abs(summed - direct).max() <= 1e-13 * np.abs(direct).max()
    with pytest.raises(ValueError, match="two triangles"):
        GridConvolution(bf.grid_mesh(bf.Surface(arc=(-0.6, 0.6), half_width=0.4,
                                                inlets=[bf.Rectangle((0.0, 0.0), (0.2, 0.2))]), 0.1)).probes(points)


@pytest.mark.parametrize("rates_balance", [False, True])
def test_sensitivity_from_the_cavitation_factors_is_the_fresh_one(rates_balance):
    # dp/dw v with A_FF solved by the Swift-Stieber problem's factors (the active-set iteration's own of the
    # final set, and a new one of another set, kept in its cache) against a fresh SuperLU factorization of
    # A_FF from the sensitivity's own assembly: the same products to 1e-10 of their largest (round-off of
    # two assemblies of the same matrix)
    from bearingfe.cavitation import ModelOptions, solve_model
    from bearingfe.cavitation.swift_stieber import cached_problem
    from bearingfe.elastic.coupled import sensitivity_operator

    mesh = bf.grid_mesh(PLAIN, 0.05)
    sup = bf.superpose(mesh, FILM, formulation="direct", element="P1")
    res = solve_model(sup, np.array([1.0, 0.0, 0.0, 0.0]), "reynolds", ModelOptions())
    fp = cached_problem(sup)
    ops = operators(mesh, "P1")
    interior = np.zeros(ops.basis.N, bool)
    interior[ops.interior] = True
    V = np.random.default_rng(0).standard_normal((ops.basis.N, 3))
    args = (res.basis, res.film, res.pressure, res.wedge)
    made = fp.problem.factorization_count
    for free, new in ((interior & ~res.cavitated, 0), (interior & ~res.cavitated & (ops.basis.doflocs[0] > -0.2), 1)):
        assert res.cavitated.any() and free.sum() < interior.sum()
        fresh = sensitivity_operator(*args, free, rates_balance=rates_balance)(V)
        reused = sensitivity_operator(*args, free, rates_balance=rates_balance, problem=fp)(V)
        assert fp.problem.factorization_count == made + new  # the final set's from the cache, the other made
        made = fp.problem.factorization_count
        assert np.abs(fresh).max() > 0
        np.testing.assert_allclose(reused, fresh, rtol=0, atol=1e-10 * np.abs(fresh).max())


def test_cold_and_warm_starts_of_the_rupture_set_give_the_same_film(monkeypatch):
    # solve_elastic starts a state's Swift-Stieber set cold once the deflection moved more than WARM_MOVE since
    # the last cavitated state: always cold (0), always warm (inf) and the default reach the same film, to the
    # Newton tolerance (1e-11 c) with margin: deflection within 1e-9 c, pressure 1e-8 of its largest, same set
    from bearingfe.elastic import coupled

    # the film of benchmarks/solver_kinds.py's 'elastic P1' kind, coarser: Newton moves of 0.17 c and less
    mesh = bf.grid_mesh(bf.Surface(arc=(-1.0, 1.0), half_width=0.5), 0.05)
    C = half_space_fft(mesh, SCALE, (STEEL, STEEL))
    runs = []
    for move in (0.0, math.inf, coupled.WARM_MOVE):
        monkeypatch.setattr(coupled, "WARM_MOVE", move)
        runs.append(solve_elastic(mesh, bf.CosineFilm(0.6, math.pi + 0.3), C, cavitation="reynolds", tol=1e-11))
    ref = runs[0]
    assert ref.max_deflection > 0.2 and ref.result.cavitated.any()
    for sol in runs[1:]:
        np.testing.assert_array_equal(sol.result.cavitated, ref.result.cavitated)
        assert np.max(np.abs(sol.deflection - ref.deflection)) <= 1e-9
        assert np.max(np.abs(sol.result.pressure - ref.result.pressure)) <= 1e-8 * ref.result.pressure.max()
