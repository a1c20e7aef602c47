"""Parameter objects (bearingfe.core.parameters): OperatingPoint and Discretization.

Their checks name the field and the allowed range; the solver functions take them as
``operating=`` / ``discretization=`` and give bit-for-bit the result of the old keyword call
(the objects only carry the same numbers to the same code, so equality is exact, no tolerance).
"""

import inspect
import math
import warnings

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.cavitation import rates_for_load, solve_cavitating
from bearingfe.bearings.journal import JournalBearing, equilibrium, performance
from bearingfe.core.parameters import Discretization, OperatingPoint
from tests.helpers import ROOT

SURFACE = bf.Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=(bf.Circle((0.0, 0.0), 0.1),))
FILM = bf.CosineFilm(0.6, 0.3)
OLD_OP = dict(wedge=1.0, squeeze=(0.1, -0.2), inlet_pressure=2.0, sliding=0.5)
OP = OperatingPoint(wedge=1.0, squeeze=(0.1, -0.2), inlet_pressure=2.0, sliding=0.5)


@pytest.fixture(scope="module")
def mesh():
    return bf.mesh_surface(SURFACE, 0.12)


@pytest.mark.parametrize("make, message", [
    (lambda: OperatingPoint(wedge=math.nan), "OperatingPoint.wedge must be a finite number, got nan"),
    (lambda: OperatingPoint(squeeze=(0.0,)), "OperatingPoint.squeeze must be a pair (gamma_rate, phi0_rate)"),
    (lambda: OperatingPoint(squeeze=3.0), "OperatingPoint.squeeze must be a pair"),
    (lambda: OperatingPoint(squeeze=(0.0, math.inf)), "OperatingPoint.squeeze[1] must be a finite number, got inf"),
    (lambda: OperatingPoint(inlet_pressure="2"), "OperatingPoint.inlet_pressure must be a finite number, got '2'"),
    (lambda: OperatingPoint(sliding=math.nan), "OperatingPoint.sliding must be a finite number, got nan"),
    (lambda: Discretization(element="P3"), "Discretization.element must be one of 'P1', 'P2', got 'P3'"),
    (lambda: Discretization(formulation="mixed"),
     "Discretization.formulation must be one of 'pi', 'direct', got 'mixed'"),
    (lambda: Discretization(solver="magic"), "Discretization.solver must be one of 'splu"),
    (lambda: Discretization(mesh_size=0.0), "Discretization.mesh_size must be > 0, got 0.0"),
    (lambda: Discretization(min_size=-1), "Discretization.min_size must be > 0, got -1"),
    (lambda: Discretization(mesh_size=0.1, min_size=0.2), "Discretization.min_size must be in (0, mesh_size = 0.1]"),
])
def test_objects_name_the_field_and_the_range(make, message):
    with pytest.raises(ValueError) as info:
        make()
    assert str(info.value).startswith(message)


def test_objects_are_frozen_and_normalized():
    op = OperatingPoint(wedge=1, squeeze=[0, 1], inlet_pressure=np.float32(0.5))
    assert op.squeeze == (0.0, 1.0) and type(op.wedge) is float and type(op.inlet_pressure) is float
    np.testing.assert_array_equal(op.weights, [1.0, 0.0, 1.0, 0.5])  # the order of Superposition.fields
    with pytest.raises(AttributeError):
        op.wedge = 2.0
    assert Discretization(solver=lambda A: None).solver is not None  # a factorization callable is accepted


def _same(a, b):
    np.testing.assert_array_equal(a.pressure, b.pressure)
    np.testing.assert_array_equal(a.force, b.force)
    assert a.friction == b.friction and dict(a.flows) == dict(b.flows)


@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_solve_reynolds_old_and_new_calls_agree(mesh, cavitation):
    old = bf.solve_reynolds(mesh, FILM, **OLD_OP, element="P1", formulation="direct", cavitation=cavitation)
    new = bf.solve_reynolds(mesh, FILM, operating=OP, discretization=Discretization(formulation="direct"),
                            cavitation=cavitation)
    _same(old, new)
    # mixing: one object plus the other group as keywords
    _same(old, bf.solve_reynolds(mesh, FILM, operating=OP, formulation="direct", cavitation=cavitation))


def test_superpose_and_combine_old_and_new_calls_agree(mesh):
    sup_old = bf.superpose(mesh, FILM, formulation="direct")
    sup_new = bf.superpose(mesh, FILM, discretization=Discretization(formulation="direct"))
    np.testing.assert_array_equal(sup_old.fields, sup_new.fields)
    _same(sup_old.combine(**OLD_OP), sup_new.combine(operating=OP))
    _same(sup_old.combine(1.0, (0.1, -0.2), 2.0, 0.5), sup_new.combine(operating=OP))  # positional old call
    np.testing.assert_array_equal(sup_old.force(1.0, (0.1, -0.2), 2.0),
                                  sup_new.force(operating=OperatingPoint(1.0, (0.1, -0.2), 2.0)))


def test_cavitation_functions_take_the_operating_point(mesh):
    sup = bf.superpose(mesh, FILM)
    _same(solve_cavitating(sup, **OLD_OP), solve_cavitating(sup, operating=OP))
    load = np.array([-0.3, 0.05])
    old = rates_for_load(sup, load, 1.0, 2.0)
    new = rates_for_load(sup, load, operating=OperatingPoint(wedge=1.0, inlet_pressure=2.0))
    np.testing.assert_array_equal(old.rates, new.rates)


def test_adapt_old_and_new_calls_agree():
    kw = dict(tol=1e-2, max_levels=2)
    with warnings.catch_warnings():  # two levels rarely meet tol = 1 %; the comparison is the point
        warnings.simplefilter("ignore")
        old = bf.adapt(SURFACE, FILM, size=0.2, wedge=1.0, squeeze=(0.1, -0.2), inlet_pressure=2.0,
                       element="P1", formulation="direct", **kw)
        new = bf.adapt(SURFACE, FILM, operating=OperatingPoint(1.0, (0.1, -0.2), 2.0),
                       discretization=Discretization(formulation="direct", mesh_size=0.2), **kw)
    _same(old.result, new.result)
    assert [lv.n_nodes for lv in old.levels] == [lv.n_nodes for lv in new.levels]


def test_simulate_old_and_new_calls_agree():
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    kw = dict(start="steady", points_per_revolution=40)
    old = bf.simulate(pump, None, 0.05, mesh_size=0.25, element="P1", formulation="pi", **kw)
    new = bf.simulate(pump, None, 0.05, discretization=Discretization(mesh_size=0.25), **kw)
    np.testing.assert_array_equal(old.h_min, new.h_min)
    np.testing.assert_array_equal(old.gamma, new.gamma)


def test_journal_functions_take_the_mesh_sizes():
    full = JournalBearing(length_ratio=0.5)
    old = performance(full, 0.6, size=0.25, min_size=0.2, cavitation="none")
    new = performance(full, 0.6, discretization=Discretization(mesh_size=0.25, min_size=0.2), cavitation="none")
    assert (old.sommerfeld, old.attitude, old.friction_variable) == (new.sommerfeld, new.attitude,
                                                                     new.friction_variable)
    load = np.array([0.0, -2.0])
    a = equilibrium(full, load, size=0.3, cavitation="none")
    b = equilibrium(full, load, discretization=Discretization(mesh_size=0.3), cavitation="none")
    assert (a.eps, a.attitude) == (b.eps, b.attitude)


@pytest.mark.parametrize("call, message", [
    (lambda m: bf.solve_reynolds(m, FILM, wedge=2.0, operating=OP),
     "solve_reynolds(): wedge given both as a keyword and in operating= (OperatingPoint.wedge); give it once"),
    (lambda m: bf.solve_reynolds(m, FILM, discretization=Discretization(mesh_size=0.1)),
     "solve_reynolds() has no use for Discretization.mesh_size = 0.1; leave it at None"),
    (lambda m: bf.solve_reynolds(m, FILM, operating=(1.0, (0, 0), 0.0)),
     "operating must be a bearingfe.OperatingPoint, got tuple"),
    (lambda m: bf.superpose(m, FILM).force(operating=OP),
     "force() has no use for OperatingPoint.sliding = 0.5; leave it at None"),
    (lambda m: rates_for_load(bf.superpose(m, FILM), (0.0, -1.0), operating=OperatingPoint(squeeze=(0.1, 0.0))),
     "rates_for_load() has no use for OperatingPoint.squeeze = (0.1, 0.0); leave it at (0.0, 0.0)"),
    (lambda m: performance(JournalBearing(length_ratio=0.5), 0.5, discretization=Discretization(formulation="direct")),
     "performance() has no use for Discretization.formulation = 'direct'; leave it at 'pi'"),
    (lambda m: bf.superpose(m, FILM, "pi", discretization=Discretization()), "takes 2 positional arguments"),
])
def test_conflicting_or_unused_fields_are_named(mesh, call, message):
    with pytest.raises((ValueError, TypeError)) as info:
        call(mesh)
    assert message in str(info.value)


@pytest.mark.parametrize("func, keywords", [
    (bf.solve_reynolds, {"operating", "discretization"}), (bf.superpose, {"discretization"}),
    (bf.Superposition.combine, {"operating"}), (bf.simulate, {"discretization"}),
    (bf.adapt, {"operating", "discretization"}), (performance, {"discretization"}),
    (equilibrium, {"discretization"}), (solve_cavitating, {"operating"}),
])
def test_signatures_show_the_new_keywords(func, keywords):
    params = inspect.signature(func).parameters
    assert keywords <= set(params) and all(params[k].kind is inspect.Parameter.KEYWORD_ONLY for k in keywords)


def test_fd_reference_and_superposition_methods_take_the_operating_point(mesh):
    from bearingfe.film.fd import solve_reynolds_fd

    old = solve_reynolds_fd(SURFACE, FILM, (21, 17), wedge=1.0, squeeze=(0.1, -0.2), inlet_pressure=2.0,
                            formulation="direct")
    new = solve_reynolds_fd(SURFACE, FILM, (21, 17), operating=OperatingPoint(1.0, (0.1, -0.2), 2.0),
                            discretization=Discretization(formulation="direct"))
    np.testing.assert_array_equal(old.pressure, new.pressure)
    sup = bf.superpose(mesh, FILM)
    op = OperatingPoint(wedge=1.0, inlet_pressure=2.0)
    np.testing.assert_array_equal(sup.coefficients(1.0, 2.0), sup.coefficients(operating=op))
    np.testing.assert_array_equal(sup.rates_for_load(np.array([-0.3, 0.05]), 1.0, 2.0),
                                  sup.rates_for_load(np.array([-0.3, 0.05]), operating=op))
