"""The chord iteration of the quasi-static elastic film (bearingfe.elastic.coupled.ChordBalance) against the damped
Newton of balance_load, which it replaces inside a run of nearby states (simulate(elastic=...)).

Expected values: balance_load without reuse (Newton on the deflection with a fresh superposition per
iterate, converged to 1e-8 c) at the same state; the chord answer must agree to that tolerance.
Coarse P1 mesh of the shipped pump, steel on steel.
"""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.elastic import ChordBalance, ElasticError, balance_load, half_space
from tests.helpers import ROOT

PUMP = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")


@pytest.fixture(scope="module")
def setup():
    mesh = bf.transient.pump_mesh(PUMP, 0.3)
    C = half_space(mesh, PUMP.scale, (PUMP.shoe_material, PUMP.eccentric_material))
    gamma, delta = bf.transient.steady_state(PUMP, mesh, 0.0, element="P1")
    return mesh, C, gamma, delta


def _args(beta):
    return dict(wedge=float(PUMP.wedge(beta)), inlet_pressure=float(PUMP.inlet_pressure(beta)))


def test_chord_answer_is_the_newton_answer_at_a_nearby_state(setup):
    mesh, C, gamma, delta = setup
    reuse = {}
    first = balance_load(mesh, bf.CosineFilm(gamma, delta), C, PUMP.load_vector(0.2), reuse=reuse, **_args(0.2))
    assert isinstance(reuse["chord"], ChordBalance) and reuse["chord"].state is not None
    film = bf.CosineFilm(gamma * 1.01, delta + 0.02)
    fast = balance_load(mesh, film, C, PUMP.load_vector(0.25), reuse=reuse, **_args(0.25))
    ref = balance_load(mesh, film, C, PUMP.load_vector(0.25), **_args(0.25))
    # a dense Jacobian or two (rebuilt when a chord step does not shrink tenfold), a few residuals, no Reynolds solve
    assert fast.jacobians <= 2 and fast.iterations <= 8
    np.testing.assert_allclose(fast.rates, ref.rates, rtol=1e-7)
    assert np.max(np.abs(fast.deflection - ref.deflection)) < 1e-8 * 10   # both converged to 1e-8 c
    np.testing.assert_allclose(fast.result.force, ref.result.force, rtol=1e-7, atol=1e-9 * abs(ref.result.force[0]))
    assert first.result is not None and fast.deflection.max() > 0.01  # a fraction of a micrometre at this load


def test_chord_falls_back_far_from_its_state(setup):
    mesh, C, gamma, delta = setup
    reuse = {}
    balance_load(mesh, bf.CosineFilm(gamma, delta), C, PUMP.load_vector(0.2), reuse=reuse, **_args(0.2))
    # the suction phase half a turn later: another film, a tenth of the load
    film, beta = bf.CosineFilm(0.3, delta), math.pi + 0.5
    fast = balance_load(mesh, film, C, PUMP.load_vector(beta), reuse=reuse, **_args(beta))
    ref = balance_load(mesh, film, C, PUMP.load_vector(beta), **_args(beta))
    np.testing.assert_allclose(fast.rates, ref.rates, rtol=1e-7)


def test_chord_bad_inputs(setup):
    mesh, C, gamma, delta = setup
    with pytest.raises(ValueError, match="state is None"):
        ChordBalance(C).solve(bf.CosineFilm(gamma, delta), PUMP.load_vector(0.0), 1.0, 0.0)
    with pytest.raises(ValueError, match="tol must be in"):
        ChordBalance(C, tol=0.0)
    with pytest.raises(ValueError, match="compliance must be"):
        ChordBalance(np.eye(3))
    reuse = {}
    balance_load(mesh, bf.CosineFilm(gamma, delta), C, PUMP.load_vector(0.2), reuse=reuse, **_args(0.2))
    chord = ChordBalance(C, max_iterations=1)
    chord.state = reuse["chord"].state
    with pytest.raises(ElasticError, match="did not converge in 1 residuals"):  # a state elsewhere, one residual
        chord.solve(bf.CosineFilm(gamma * 1.01, delta), PUMP.load_vector(0.25), **_args(0.25))


def test_chord_on_a_rigid_support_gives_the_rigid_rates(setup):
    # E* = inf: the compliance is zero, the coupled film is the rigid one; the chord answer (seeded at
    # another state) equals the rigid superposition's rates in the same (direct) form to round-off
    mesh, _, gamma, delta = setup
    rigid_c = half_space(mesh, PUMP.scale, math.inf)
    reuse = {}
    balance_load(mesh, bf.CosineFilm(gamma, delta), rigid_c, PUMP.load_vector(0.2), reuse=reuse, **_args(0.2))
    film = bf.CosineFilm(gamma * 1.02, delta - 0.03)
    fast = balance_load(mesh, film, rigid_c, PUMP.load_vector(0.3), reuse=reuse, **_args(0.3))
    sup = bf.superpose(mesh, film, formulation="direct", element="P1")
    a = _args(0.3)
    np.testing.assert_allclose(fast.rates, sup.rates_for_load(PUMP.load_vector(0.3), a["wedge"], a["inlet_pressure"]),
                               rtol=1e-9)
    assert np.all(fast.deflection == 0.0)


def test_no_useful_low_rank_compliance():
    # docs/elastic.md's reason for keeping the compliance dense, recomputed on the coarsest mesh of its
    # table: singular values above 1 % of the largest are every one of them (276 of 276), above 10 % a few
    # dozen (30)
    import json

    rows = json.loads((ROOT / "docs" / "elastic.json").read_text())["dense"]
    row = next(r for r in rows if r["size"] == 0.3)
    mesh = bf.transient.pump_mesh(PUMP, 0.3, order=2)
    C = half_space(mesh, PUMP.scale, (PUMP.shoe_material, PUMP.eccentric_material), "P2")
    sv = np.linalg.svd(C.matrix, compute_uv=False)
    assert C.n_dofs == row["dofs"]
    for tol, rank in row["ranks"].items():
        assert int(np.sum(sv >= float(tol) * sv[0])) == rank
    assert row["ranks"]["0.01"] == C.n_dofs
