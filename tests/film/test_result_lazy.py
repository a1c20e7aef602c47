"""``build_result(..., lazy=True)``: flows, mass balance and friction computed on their first use.

The same values as the eager result (bit for bit: the same compiled outputs of the same field), for the
journal's Newton steps, which read only the force and the rupture set of their intermediate states.
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np

import bearingfe as bf
from bearingfe.cavitation.swift_stieber import obstacle_problem, warm_mask
from bearingfe.film import build_result, source_weights

SURFACE = bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(bf.Rectangle((0.05, 0.0), (0.48, 0.4)),))


def _lazy_and_eager():
    sup = bf.superpose(bf.mesh_surface(SURFACE, 0.2, order=2), bf.CosineFilm(0.7, 3.0), formulation="direct",
                       element="P2")
    w = source_weights(1.0, (0.1, -0.2), 2.0)
    fp = obstacle_problem(sup)
    sol = fp.problem.solve(fp.right_side(w), warm_mask(fp, sup, w, None))
    cavitated = np.zeros(sup.operators.n_dofs, bool)
    cavitated[fp.interior] = sol.active
    assert sol.active.any()  # a ruptured zone, whose sink flow the outputs carry
    u = sup.system.full(fp.unknowns(sol.u), w)
    made = [build_result(sup, u, w, None, cavitation="reynolds", cavitated=cavitated, lazy=lazy)
            for lazy in (True, False)]
    return made


def test_lazy_result_same_outputs_on_first_use():
    lazy, eager = _lazy_and_eager()
    assert "flows" not in lazy.__dict__  # not computed yet
    np.testing.assert_array_equal(lazy.pressure, eager.pressure)
    np.testing.assert_array_equal(lazy.force, eager.force)
    assert lazy.integral == eager.integral
    assert lazy.friction == eager.friction and lazy.mass_balance == eager.mass_balance
    assert dict(lazy.flows) == dict(eager.flows) and "cavitation" in lazy.flows
    assert "_outputs" not in lazy.__dict__


def test_lazy_result_copies_with_its_outputs():
    lazy2, eager = _lazy_and_eager()
    copied = copy.copy(lazy2)
    assert copied.mass_balance == eager.mass_balance and dict(copied.flows) == dict(eager.flows)
    lazy3, _ = _lazy_and_eager()
    noted = dataclasses.replace(lazy3, notes=("x",))
    assert noted.friction == eager.friction and noted.notes == ("x",)
    try:
        lazy3.nothing
    except AttributeError as exc:
        assert "nothing" in str(exc)
    else:
        raise AssertionError("an unknown attribute must raise AttributeError")
