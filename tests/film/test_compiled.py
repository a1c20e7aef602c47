"""The compiled film operator gives the reference scikit-fem assembly's numbers to round-off.

Reference: ``superpose(..., assembly="reference")``, which assembles every film with
scikit-fem forms (the code path the package used before the compiled maps). Both
solve the same discrete equations, so they agree to round-off: relative 1e-10
is ~100x the measured worst difference (1.2e-12, pressures, loads, flows and
friction over the cases below). Timing lives in benchmarks/operator_floor.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.film.forms import film_at
from bearingfe.film import film_outputs, operators
from bearingfe.film.reference import system_matrix

RTOL = 1e-10
SURFACE = bf.Surface(arc=(-1.2, 1.2), half_width=0.6, inlets=(bf.Circle((0.1, 0.05), 0.2),))
FILM = bf.CosineFilm(0.55, 2.6)
POINT = dict(wedge=1.0, squeeze=(0.3, -0.2), inlet_pressure=0.8)


@pytest.fixture(scope="module")
def meshes():
    return {"straight": bf.mesh_surface(SURFACE, 0.3), "curved": bf.mesh_surface(SURFACE, 0.35, order=2),
            "curved_fine": bf.mesh_surface(SURFACE, 0.1, order=2)}


def _close(a, b, scale=None):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = np.max(np.abs(b)) if scale is None else scale
    assert np.max(np.abs(a - b)) <= RTOL * scale


@pytest.mark.parametrize("geometry", ["straight", "curved"])
@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("formulation", ["pi", "direct"])
def test_compiled_superposition_and_result_match_the_reference(meshes, geometry, element, formulation, results_agree):
    mesh = meshes[geometry]
    comp = bf.superpose(mesh, FILM, formulation=formulation, element=element)
    ref = bf.superpose(mesh, FILM, formulation=formulation, element=element, assembly="reference")
    assert comp.assembly == "compiled" and ref.assembly == "reference"
    _close(comp.fields, ref.fields)
    _close(comp.forces, ref.forces)
    _close(comp.integrals, ref.integrals)
    _close(comp.system.rhs, ref.system.rhs)
    _close((comp.system.matrix - ref.system.matrix).toarray(), 0.0 * ref.system.matrix.toarray(),
           np.abs(ref.system.matrix).max())
    w = (POINT["wedge"], POINT["squeeze"], POINT["inlet_pressure"])
    results_agree(comp.combine(*w, sliding=0.7), ref.combine(*w, sliding=0.7), RTOL)


@pytest.mark.parametrize("model", ["reynolds", "gumbel"])
@pytest.mark.parametrize("element", ["P1", "P2"])
def test_cavitated_results_match_the_reference(meshes, model, element, results_agree):
    # the cavitation models add the flow handed to the ruptured zone and the ruptured-zone correction
    mesh = meshes["curved"]
    comp = bf.superpose(mesh, FILM, element=element)
    ref = bf.superpose(mesh, FILM, element=element, assembly="reference")
    args = (POINT["wedge"], POINT["squeeze"], POINT["inlet_pressure"])
    a = bf.cavitation.solve_cavitating(comp, *args, model=model)
    b = bf.cavitation.solve_cavitating(ref, *args, model=model)
    assert np.array_equal(a.cavitated, b.cavitated) and a.cavitated.any()
    assert "cavitation" in a.flows
    results_agree(a, b, RTOL)


def test_scatter_reproduces_the_assembled_matrices(meshes):
    # A.data = S @ c on the fixed pattern equals the scikit-fem matrices entry by entry
    ops = operators(meshes["curved"], "P2")
    co = ops.compiled
    at = film_at(FILM, ops.x)
    for formulation in ("direct", "pi"):
        ref = system_matrix(ops, at, formulation).toarray()
        mine = co.matrix(co.matrix_data(formulation, at.h.ravel(), at.D.ravel())).toarray()
        _close(mine, ref)


def test_batch_outputs_equal_one_state_at_a_time(meshes):
    # a trajectory's post-processing (film_outputs over many states) equals the results one by one
    mesh = meshes["curved"]
    films = [bf.CosineFilm(0.2 + 0.15 * k, 1.0 + 0.9 * k) for k in range(4)]
    sups = [bf.superpose(mesh, f, element="P2", formulation=("pi", "direct")[k % 2]) for k, f in enumerate(films)]
    weights = np.array([[1.0, 0.1 * k, -0.05 * k, 0.5 + 0.1 * k] for k in range(4)]).T
    sliding = np.array([1.0, 0.8, 1.2, 0.5])
    u = np.column_stack([s.fields @ weights[:, k] for k, s in enumerate(sups)])
    out = film_outputs(sups, u, weights, sliding)
    for k, s in enumerate(sups):
        res = s.combine(weights[0, k], weights[1:3, k], weights[3, k], sliding=sliding[k])
        scale = max(abs(v) for v in res.flows.values())
        for name, value in res.flows.items():
            _close(out.flows[name][k], value, scale)
        _close(out.friction[k], res.friction)
        _close(out.mass_balance[k], res.mass_balance, scale)


def test_a_kept_factorization_survives_the_next_film(meshes):
    # the compiled factorization refills one matrix object per mesh: an earlier film's solve must
    # still solve that film's system after a later film was factored
    mesh = meshes["straight"]
    first = bf.superpose(mesh, bf.CosineFilm(0.3, 0.5), formulation="direct")
    bf.superpose(mesh, bf.CosineFilm(0.7, 2.0), formulation="direct")
    again = first.system.solve(first.system.rhs)
    _close(first.system.matrix @ again, first.system.rhs)


def test_film_fields_from_precomputed_angles_equal_the_direct_evaluation():
    # the compiled path evaluates a CosineFilm from cos/sin of the quadrature angles computed once
    # per mesh (cos(phi - phi0) by the addition theorem); the reference path calls the film's own
    # methods: the fields agree to round-off, 1e-14 of the O(1) film fields, times |phi0| where the
    # reference's own phi - phi0 loses that many digits (measured 9e-14 relative at phi0 = 1e3)
    x = np.stack(np.meshgrid(np.linspace(-1.3, 1.3, 17), np.linspace(-0.6, 0.6, 5)))
    for film in (FILM, bf.CosineFilm(0.0, -4.0), bf.CosineFilm(0.97, 1e3)):
        fast = film_at(film, x, (np.cos(x[0]), np.sin(x[0])))
        ref = film_at(film, x)
        tol = 1e-14 * max(1.0, abs(film.phi0))
        for a, b in [(fast.h, ref.h), (fast.D, ref.D), *zip(fast.dh, ref.dh), *zip(fast.shapes, ref.shapes)]:
            assert a.shape == b.shape
            np.testing.assert_allclose(a, b, rtol=0, atol=tol * max(1.0, np.abs(b).max()))


@pytest.mark.parametrize("geometry, element, banded",
                         [("straight", "P1", True), ("curved", "P2", True), ("curved_fine", "P2", False)])
def test_condensed_factorization_banded_or_sparse_solves_the_system(meshes, geometry, element, banded):
    # small bands (half-bandwidth <= 64 in the reverse Cuthill-McKee order: the P1 test mesh has 11,
    # the curved P2 mesh 37) are factored by banded Cholesky, wider ones (the finer curved P2 mesh:
    # 85) by SuperLU; all give
    # scipy's sparse direct solution to round-off (1e-12 relative: backward-stable factorizations
    # of a matrix whose condition number is ~1e2 here)
    import scipy.sparse.linalg as spla

    ops = operators(meshes[geometry], element)
    co = ops.compiled
    at = film_at(FILM, ops.x)
    data = co.matrix_data("pi", at.h.ravel(), at.D.ravel())
    assert co.banded == banded
    b = np.random.default_rng(3).standard_normal((ops.interior.size, 4))
    reference = spla.spsolve(co.condensed(data).tocsc(), b)
    _close(co.factorize_condensed(data)(b), reference, np.abs(reference).max() * 1e-2)
    _close(co.factorize_condensed(data)(b[:, 0]), reference[:, 0], np.abs(reference).max() * 1e-2)
    # a matrix that is not positive definite (here negative definite) cannot take Cholesky: SuperLU
    _close(co.factorize_condensed(-data)(b), -reference, np.abs(reference).max() * 1e-2)


def test_assembly_choice_is_checked(meshes):
    with pytest.raises(ValueError, match="assembly must be one of"):
        bf.superpose(meshes["straight"], FILM, assembly="fast")


def test_journal_film_is_unchanged_by_the_compiled_path(results_agree):
    # the journal solves through the same superposition: a cavitated 360-degree L/D = 0.5 film at
    # eps = 0.6 (its load, flows and friction) is the same with either assembly to round-off
    mesh = bf.mesh_surface(bf.Surface(arc=(0.0, 2 * math.pi), half_width=0.5), 0.25)
    comp = bf.solve_reynolds(mesh, bf.CosineFilm(0.6, 0.0), formulation="direct", cavitation="reynolds")
    sup = bf.superpose(mesh, bf.CosineFilm(0.6, 0.0), formulation="direct", assembly="reference")
    ref = bf.cavitation.solve_cavitating(sup, 1.0)
    results_agree(comp, ref, RTOL)


def test_small_panels_leave_the_fill_reducing_order_unchanged():
    # the order-finding factorization of CompiledOperator.factorize_condensed uses SuperLU's small panels
    # (panel_size 1, relax 1) for speed; its column order must be the one of the default panels, or the
    # films' numbers would change (measured: identical on P1 and P2 meshes from 58 to 12282 unknowns)
    import scipy.sparse.linalg as spla
    from skfem import Basis, BilinearForm, ElementTriP2, asm
    from skfem.helpers import dot, grad

    @BilinearForm
    def weighted(u, v, w):
        return (1 + w.x[0] ** 2) * dot(grad(u), grad(v))

    basis = Basis(bf.mesh_surface(SURFACE, 0.15, order=2).mesh, ElementTriP2())
    interior = basis.complement_dofs(basis.get_dofs())
    A = asm(weighted, basis)[interior][:, interior].tocsc()
    options = dict(permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    default, small = spla.splu(A, **options), spla.splu(A, panel_size=1, relax=1, **options)
    np.testing.assert_array_equal(small.perm_c, default.perm_c)


def test_flow_maps_built_on_first_use_and_carried_by_a_pickled_copy():
    # the flow maps (group sums, corner facet data) are built on the first flow computed, not with the operator
    # (a Newton step reads no flows); a copy pickled before any flow was computed carries them built, the same
    # maps the original builds when its flows are first read (the reference: the original's own, built after)
    import pickle
    mesh = bf.mesh_surface(SURFACE, 0.3)  # fresh: no operator compiled yet
    sup = bf.superpose(mesh, FILM, formulation="direct", element="P2")
    co = sup.operators.compiled
    assert "flows" not in co._lazy and "flow_builder" in co._lazy
    copy = pickle.loads(pickle.dumps(co))
    assert "flows" in copy._lazy and "flow_builder" not in copy._lazy
    res = sup.combine(**POINT, sliding=0.7)  # the original builds its maps now
    assert "flows" in co._lazy and "flow_builder" not in co._lazy and res.flows
    for mine, theirs in zip(co.group_maps, copy.group_maps):
        assert mine.shape == theirs.shape and (mine != theirs).nnz == 0
    E, Gx, Gz, normals, x, parts = co.corners
    E2, Gx2, Gz2, normals2, x2, parts2 = copy.corners
    assert E.shape[0] > 0  # the pocket's corner dofs: facet data to compare
    for a, b in ((E, E2), (Gx, Gx2), (Gz, Gz2)):
        assert (a != b).nnz == 0
    assert np.array_equal(normals, normals2) and np.array_equal(x, x2) and parts.keys() == parts2.keys()
