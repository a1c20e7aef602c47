"""The pump shoe on an elastic support with the squeeze of the deflection (bearingfe.transient.elastic).

Checks: on the discharge plateau (chamber pressure constant) the deflection changes only slowly and the
run agrees with the quasi-static elastic model of ``simulate(elastic=...)``; the mass balance of the
consistent flows (with ``dw/dt`` in the squeeze) closes to round-off; the film is thinner than on the
rigid support while the chamber is at 32 MPa; bad inputs are named. Coarse P1 meshes keep it fast.
"""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.elastic import half_space
from bearingfe.transient import simulate_elastic
from tests.helpers import ROOT

PUMP = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")


@pytest.fixture(scope="module")
def setup():
    mesh = bf.transient.pump_mesh(PUMP, 0.3)
    return mesh, half_space(mesh, PUMP.scale, (PUMP.shoe_material, PUMP.eccentric_material))


def test_plateau_agrees_with_the_quasi_static_model(setup):
    mesh, C = setup
    beta0 = 1.2   # discharge plateau: compression ended at 20 deg
    dyn = simulate_elastic(PUMP, C, 0.05, start="steady", beta0=beta0, points_per_revolution=60)
    qs = bf.simulate(PUMP, mesh, 0.05, start=dyn.start, beta0=beta0, points_per_revolution=60, elastic=C,
                     formulation="direct")
    assert dyn.status == "completed"
    # the same start, then the quasi-static model drops C dp/dt, which is small on the plateau
    np.testing.assert_allclose(dyn.h_min, qs.h_min, rtol=2e-2)
    np.testing.assert_allclose(dyn.max_deflection, qs.max_deflection, rtol=2e-2)
    assert dyn.mass_balance_relative < 1e-8
    assert np.all(dyn.max_deflection > 5e-6)   # micrometres of opening at 32 MPa


def test_bad_inputs_are_named(setup):
    mesh, C = setup
    with pytest.raises(ValueError, match="revolutions"):
        simulate_elastic(PUMP, C, 0.0)
    with pytest.raises(ValueError, match="start"):
        simulate_elastic(PUMP, C, 0.1, start="cold")
    with pytest.raises(ValueError, match="kappa"):
        simulate_elastic(PUMP, C, 0.1, kappa=-1.0)
    with pytest.raises(ValueError, match="finite modulus"):
        simulate_elastic(PUMP, half_space(mesh, PUMP.scale, math.inf), 0.1)


def test_state_result_balances_the_load(setup):
    from bearingfe.transient import state_result

    mesh, C = setup
    traj = simulate_elastic(PUMP, C, 0.02, start="steady", beta0=1.2, points_per_revolution=100)
    res = state_result(PUMP, mesh, traj, traj.beta.size - 1, elastic=C)
    # film force + applied load = 0 up to the Baumgarte-stabilized drift (integrator tolerance)
    np.testing.assert_allclose(res.force, -traj.load[-1], atol=1e-4 * np.abs(traj.load[-1]).max())
    assert res.max_deflection * PUMP.clearance == pytest.approx(traj.max_deflection[-1], rel=1e-12)
    assert res.h_min * PUMP.clearance == pytest.approx(traj.h_min[-1], rel=1e-12)


# -- the fast path: defaults against a tight reference, continuation, stiff limit, guards --------

@pytest.fixture(scope="module")
def revolution(setup):
    """One revolution from the steady start at the defaults (BDF, rtol 1e-5, film opening to 1e-5 c) and
    at the tight reference (LSODA on the raw pressures, rtol 1e-8: the path before the fast defaults, tightened)."""
    mesh, C = setup
    fast = simulate_elastic(PUMP, C, 1.0, start="steady", points_per_revolution=72)
    ref = simulate_elastic(PUMP, C, 1.0, start="steady", points_per_revolution=72, method="LSODA", rtol=1e-8,
                           atol=1e-10, deflection_atol=1e-9)
    return fast, ref


def test_fast_defaults_agree_with_the_tight_reference(revolution):
    fast, ref = revolution
    c = PUMP.clearance
    assert fast.status == ref.status == "completed"
    # the documented accuracy of the defaults: the film within 1e-4 c over the whole revolution
    # (measured 2.0e-5 c on this mesh, 5e-5 c on the P2 0.15 R0 mesh of docs/elastic.md)
    assert np.max(np.abs(fast.h_min - ref.h_min)) < 1e-4 * c
    assert abs(fast.smallest_film - ref.smallest_film) < 1e-4 * c
    np.testing.assert_allclose(fast.max_deflection, ref.max_deflection, atol=1e-4 * c)
    # and it takes far fewer steps (measured 194 against 1185)
    assert fast.stats["steps"] < 0.3 * ref.stats["steps"]


def test_continuing_a_run_is_the_same_run(setup, revolution):
    mesh, C = setup
    fast, _ = revolution
    half = simulate_elastic(PUMP, C, 0.5, start="steady", points_per_revolution=72)
    rest = simulate_elastic(PUMP, C, 0.5, start=half, points_per_revolution=72)
    assert rest.beta[0] == pytest.approx(math.pi) and rest.beta[-1] == pytest.approx(2 * math.pi)
    assert rest.start == pytest.approx((half.gamma[-1], half.delta[-1]), rel=1e-12)
    # both halves together against the single revolution: the same trajectory to the integrator's accuracy
    np.testing.assert_allclose(np.r_[half.h_min, rest.h_min[1:]], fast.h_min, atol=1e-4 * PUMP.clearance)
    with pytest.raises(ValueError, match="simulate_elastic"):
        simulate_elastic(PUMP, C, 0.1, start=bf.simulate(PUMP, mesh, 0.02, start="steady"))


def test_a_stiff_support_gives_the_rigid_motion(setup):
    # E* x 1e6: the deflection is ~1e-6 of the steel one; at the start (the quasi-static state) the rates are
    # those of the rigid film in the same (direct) form, and a quarter turn follows the rigid motion
    mesh, _ = setup
    stiff = half_space(mesh, PUMP.scale, 1e6 * 115.4e9)
    el = simulate_elastic(PUMP, stiff, 0.25, start="steady", points_per_revolution=72)
    rigid = bf.simulate(PUMP, mesh, 0.25, start=el.start, points_per_revolution=72, formulation="direct",
                        element="P1", rtol=1e-8, atol=1e-11)
    # (measured 1e-4 relative apart on this coarse mesh: the elastic film is integrated from the compiled
    # maps, the rigid one assembled by its superposition; 1e-6 of it is the deflection)
    np.testing.assert_allclose([el.gamma_rate[0], el.delta_rate[0]], [rigid.gamma_rate[0], rigid.delta_rate[0]],
                               rtol=5e-4)
    assert np.max(el.max_deflection) < 1e-5 * PUMP.clearance
    # along the quarter turn: measured 2.7e-4 c apart at the defaults (1.2e-4 c at rtol 1e-8: the
    # Baumgarte-stabilized pressure state against the algebraic rigid balance on this coarse mesh)
    assert np.max(np.abs(el.h_min - rigid.h_min)) < 5e-4 * PUMP.clearance


def test_periodic_start_anderson_and_fixed_point_agree(setup):
    mesh, C = setup
    runs = {m: simulate_elastic(PUMP, C, 1.0, start="periodic", periodic_method=m, points_per_revolution=72)
            for m in ("anderson", "fixed-point")}
    a, f = runs["anderson"], runs["fixed-point"]
    assert a.periodic_residual < 1e-5 and f.periodic_residual < 1e-5
    assert a.periodic_iterations <= f.periodic_iterations
    # the same periodic revolution: the film within 1e-4 c (both meet periodic_tol = 1e-5 on gamma, delta)
    np.testing.assert_allclose(a.h_min, f.h_min, atol=1e-4 * PUMP.clearance)
    with pytest.raises(ValueError, match="periodic_method"):
        simulate_elastic(PUMP, C, 1.0, periodic_method="newton")
    with pytest.raises(ValueError, match="method must be one of"):  # explicit pairs: not for stiff modes
        simulate_elastic(PUMP, C, 1.0, method="RK23")


def test_dense_compliance_size_guard(setup, monkeypatch):
    from bearingfe.core.limits import LimitError

    mesh, C = setup
    monkeypatch.setenv("BEARINGFE_MAX_COMPLIANCE", "50")
    with pytest.raises(LimitError, match=r"compliance = 78 is above the limit of 50.*BEARINGFE_MAX_COMPLIANCE"):
        half_space(mesh, PUMP.scale, 115.4e9)
    with pytest.raises(LimitError, match="compliance = 78"):
        simulate_elastic(PUMP, C, 0.1)


def test_dense_threads_caps_and_restores():
    from threadpoolctl import threadpool_info

    from bearingfe.core.linalg import dense_threads

    before = [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]
    with dense_threads(1):
        assert all(i["num_threads"] == 1 for i in threadpool_info() if i["user_api"] == "blas")
    assert [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"] == before
    with pytest.raises(ValueError, match="limit must be an integer >= 1"):
        dense_threads(0)


def test_no_elastic_equilibrium_ends_the_run_with_a_status(setup):
    """Quasi-static elastic model on the plain shoe (no pocket): near 190 deg the rigid film would close
    (gamma > 1) and the coupled Newton finds no deflection carrying the load. The run stops there with
    status "no-equilibrium" and the reason, like a rupture, instead of raising mid-way (a scene then
    reports the other runs). The angle is the one this coarse mesh gives (190.5 deg, measured); the
    bound below only asserts it stopped on the discharge plateau, after the compression ended (20 deg)."""
    import dataclasses

    plain = dataclasses.replace(PUMP, surface=bf.Surface(arc=PUMP.surface.arc, half_width=PUMP.surface.half_width))
    mesh = bf.transient.pump_mesh(plain, 0.3)
    C = half_space(mesh, PUMP.scale, (PUMP.shoe_material, PUMP.eccentric_material))
    tr = bf.simulate(plain, mesh, 1.0, elastic=C, points_per_revolution=24)
    assert tr.status == "no-equilibrium"
    assert "no equilibrium of the elastic film at beta" in tr.message and "last accepted state" in tr.message
    assert math.radians(20) < tr.rupture_beta < math.radians(360) and tr.beta[-1] == pytest.approx(tr.rupture_beta)
    assert np.all(np.isfinite(tr.h_min)) and tr.smallest_film > 0


# -- a compliance held as its product: the matrix-free squeeze -------------------------------------

def _as_product(C):
    """The dense compliance ``C`` held as its product only: the same map, so the matrix-free path must give
    the dense path's run up to its inner solves (GMRES to 1e-9 relative for K, 1e-6 for the Newton matrix),
    far inside the integrator's rtol."""
    from bearingfe.elastic import Compliance

    return Compliance(mesh=C.mesh, element=C.element, model="dense-as-product", matrix=None, pocket=C.pocket,
                      modulus=C.modulus, scale=C.scale, seconds=0.0, operator=lambda p: C.matrix @ p)


def test_product_compliance_gives_the_dense_run(setup):
    """The matrix-free squeeze (K^-1 by GMRES, BDF's Newton by GMRES with the rank-4 correction) on the dense
    map held as its product: the same steps as the dense path (the Newton matrices are the same up to the
    inner tolerance), and gamma, delta, film [c] and deflection [c] within 5e-7 (measured 6e-8 over 0.2
    revolution across the compression, with the largest opening 0.44 c), against the integrator's rtol = 1e-5
    and deflection_atol = 1e-5 c; the pressures within 1e-6 of their largest (measured 1.4e-7)."""
    mesh, C = setup
    kw = dict(start="steady", beta0=5.8, points_per_revolution=60)
    dense = simulate_elastic(PUMP, C, 0.2, **kw)
    prod = simulate_elastic(PUMP, _as_product(C), 0.2, **kw)
    assert dense.status == prod.status == "completed"
    assert prod.stats["steps"] == dense.stats["steps"] and prod.stats["krylov_iterations"] > 0
    np.testing.assert_allclose(prod.gamma, dense.gamma, atol=5e-7)
    np.testing.assert_allclose(prod.delta, dense.delta, atol=5e-7)
    np.testing.assert_allclose(prod.h_min, dense.h_min, atol=5e-7 * PUMP.clearance)
    np.testing.assert_allclose(prod.max_deflection, dense.max_deflection, atol=5e-7 * PUMP.clearance)
    np.testing.assert_allclose(prod.pressures, dense.pressures, atol=1e-6 * np.abs(dense.pressures).max())
    assert prod.mass_balance_relative < 1e-8
    with pytest.raises(ValueError, match="method must be 'BDF'"):
        simulate_elastic(PUMP, _as_product(C), 0.1, method="LSODA")


def test_product_compliance_runs_above_the_dense_cap(setup, monkeypatch):
    """With the dense cap lowered below the mesh (78 dofs > 50) the dense squeeze model is refused, while
    the FFT half-space through its auxiliary grid (half_space_grid, held as its product) runs, the squeeze
    model and the quasi-static one (balance_load's Newton-Krylov: the dense-only chord is not taken). Its
    film is the dense one's within the grid's approximation (second order in its spacing: 1e-2 c here,
    measured 3.4e-3 c at the default spacing, half the median edge); at a spacing of half the nominal size
    (0.15: this small shoe's edges are near 0.12) some interior dof of this coarse mesh carries no grid node,
    K = 12 M C_I is singular, and the error says so."""
    from bearingfe.core.limits import LimitError
    from bearingfe.elastic import half_space_grid

    mesh, C = setup
    grid = half_space_grid(mesh, PUMP.scale, (PUMP.shoe_material, PUMP.eccentric_material))
    kw = dict(start="steady", beta0=1.2, points_per_revolution=60)
    dense = simulate_elastic(PUMP, C, 0.05, **kw)
    monkeypatch.setenv("BEARINGFE_MAX_COMPLIANCE", "50")
    with pytest.raises(LimitError, match="compliance = 78"):
        simulate_elastic(PUMP, C, 0.05, **kw)
    prod = simulate_elastic(PUMP, grid, 0.05, **kw)
    assert prod.status == "completed" and prod.stats["compliance_products"] > 0
    np.testing.assert_allclose(prod.h_min, dense.h_min, atol=1e-2 * PUMP.clearance)
    qs = bf.simulate(PUMP, mesh, 0.05, start=prod.start, beta0=1.2, points_per_revolution=60, elastic=grid,
                     formulation="direct")
    assert qs.status == "completed"
    # on the discharge plateau the two models agree (as the dense ones do above)
    np.testing.assert_allclose(prod.h_min, qs.h_min, rtol=2e-2)
    coarse = half_space_grid(mesh, PUMP.scale, (PUMP.shoe_material, PUMP.eccentric_material), spacing=0.15)
    with pytest.raises(bf.elastic.ElasticError, match="singular when some interior pressure opens no film"):
        simulate_elastic(PUMP, coarse, 0.05, **kw)


def test_scipy_bdf_has_the_internals_the_krylov_bdf_replaces():
    # The matrix-free deflection squeeze swaps scipy BDF's Newton matrix, factorization and solve
    # (bearingfe.transient.elastic._BDF_INTERNALS): a scipy release without them must fail here, loudly,
    # not integrate with scipy's own dense algebra on the sparse stand-in.
    import scipy.integrate as si

    from bearingfe.transient.elastic import _BDF_INTERNALS

    bdf = si.BDF(lambda t, y: -y, 0.0, np.ones(2), 1.0)
    assert all(hasattr(bdf, name) for name in _BDF_INTERNALS)


def test_K_preconditioner_solves_to_its_tolerance_in_few_iterations_flat_in_size():
    """K^-1 b of the product path (GMRES with the two-level preconditioner whose local level is the shifted
    film Laplacian, K_LOCAL_SHIFTS) against the dense solve of K = 12 M_I C_I on the dense half-space held as
    its product (pump_mesh 0.035, 781 interior dofs): the same solution to GMRES's tolerance (1e-9 relative
    residual; K's condition number on this mesh 3e2, measured 2e-9), in at most 20 iterations per right side
    and fewer than with the former local level (12 sigma M)^-1 (measured 14-16 against 24-27). On the grid
    half-space at pump_mesh 0.035 and 0.02 (781, 2,423 interior dofs) the count of a solve stays flat
    (measured 18 and 19; the former level with 256 patches 26 and 34)."""
    import scipy.sparse.linalg as spla

    from bearingfe.elastic import half_space_grid
    from bearingfe.elastic.krylov import gmres
    from bearingfe.film import operators
    from bearingfe.transient import elastic as te

    mats = (PUMP.shoe_material, PUMP.eccentric_material)
    mesh = bf.transient.pump_mesh(PUMP, 0.035)
    C = half_space(mesh, PUMP.scale, mats)
    ops = operators(mesh, "P1")
    pc = te._InteriorCompliance(_as_product(C), ops)
    I = ops.interior
    K = 12.0 * (ops.mass.tocsr()[I] @ C.matrix[:, I])
    rng = np.random.default_rng(1)
    rights = [12.0 * (pc.M_I @ C.matrix.sum(axis=1)), K @ rng.standard_normal(I.size),
              ops.compiled.sources @ np.cos(ops.compiled.x[0])]
    M12 = 12.0 * ops.mass.tocsr()[I][:, I]
    former = te._TwoLevel(pc.Z, 12.0 * (pc.M_I @ pc.CZ), spla.splu((pc.sigma * M12).tocsc()).solve)
    for b in rights:
        start = pc.iterations
        x = pc.solve_K(b)
        its = pc.iterations - start
        exact = np.linalg.solve(K, b)
        assert np.abs(x - exact).max() <= 1e-6 * np.abs(exact).max()
        _, old = gmres(pc.K, b, preconditioner=former, rtol=te.K_TOLERANCE, max_iterations=2000, what="K")
        assert its <= 20 and its < old
    counts = []
    for size in (0.035, 0.02):
        mesh = bf.transient.pump_mesh(PUMP, size)
        ops = operators(mesh, "P1")
        pc = te._InteriorCompliance(half_space_grid(mesh, PUMP.scale, mats), ops)
        b = ops.compiled.sources @ np.cos(ops.compiled.x[0])
        pc.solve_K(b)
        counts.append(pc.iterations)
    assert counts[1] <= counts[0] + 2 and max(counts) <= 22


def test_newton_matrix_preconditioner_solves_the_dense_system_in_fewer_iterations(monkeypatch):
    """The integrator's Newton matrix I - c J of the product path (_NewtonSolve: GMRES on K + c Jr with the
    two-level preconditioner around the sparse factors of K's shifted-Laplacian model plus c A_II) against
    the dense solve with the dense model's Jacobian at the same state (pump_mesh 0.035, the dense half-space
    held as its product, the state of a short run from 5.8 rad, c = 0.02 rad: about BDF's step there): the same
    solution to 1e-5 relative (GMRES to NEWTON_TOLERANCE 1e-6 relative residual; the Jacobians' columns in
    (gamma, delta) are central differences of different steps; measured 1e-7), in fewer GMRES iterations than
    with the former local level, the factors of c A_II + 12 sigma M_II (the four solves of the rank-4
    correction and one: measured 32 against 45; at c = 0.001-0.05 30-33 against 36-47)."""
    import scipy.sparse.linalg as spla

    from bearingfe.transient import elastic as te
    from bearingfe.transient.elastic import ElasticSqueeze

    mesh = bf.transient.pump_mesh(PUMP, 0.035)
    C = half_space(mesh, PUMP.scale, (PUMP.shoe_material, PUMP.eccentric_material))
    run = simulate_elastic(PUMP, C, 0.005, start="steady", beta0=5.8, points_per_revolution=720)
    assert run.status == "completed"
    dense, product = ElasticSqueeze(PUMP, C), ElasticSqueeze(PUMP, _as_product(C))
    beta = float(run.beta[-1])
    y = np.concatenate([[run.gamma[-1], run.delta[-1]], np.asarray(run.pressures[-1], float)[dense.I]])
    c = 0.02
    b = np.random.default_rng(2).standard_normal(y.size)
    exact = np.linalg.solve(np.eye(y.size) - c * dense.jacobian(beta, y), b)

    J = product.jacobian(beta, y)  # its central differences solve with K: counted before the Newton matrix's

    def iterations_and_solution():
        pc = product.product
        start = pc.iterations
        x = te._NewtonSolve(J, c).solve(b)
        return pc.iterations - start, x

    its, x = iterations_and_solution()
    assert np.abs(x - exact).max() <= 1e-5 * np.abs(exact).max()
    pc = product.product
    M12 = 12.0 * mesh_mass(pc)
    monkeypatch.setattr(te._ShiftedLaplacian, "newton",
                        lambda self, A, c: spla.splu((c * A + pc.sigma * M12).tocsc()).solve)
    former, x_former = iterations_and_solution()
    assert np.abs(x_former - exact).max() <= 1e-5 * np.abs(exact).max()
    assert its < former


def mesh_mass(pc):
    """The mass matrix on the interior dofs of a product path's compliance."""
    from bearingfe.film import operators

    I = pc.I
    return operators(pc.compliance.mesh, pc.compliance.element).mass.tocsr()[I][:, I]
