"""The pieces every pump-transient model shares: settings, events, the model table, the periodic methods,
the trajectory builder and state_result.

Expected values come from the definitions themselves (a field's allowed range, an event's attributes,
the zero of a linear function); the rigid Anderson start is compared with Newton shooting on the same
mesh (both meet ``periodic_tol``, the return map contracts about 20x per revolution, so their starts
agree to about the tolerance).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe import transient
from bearingfe.transient.events import crossed, film_rupture, locate


@pytest.mark.parametrize("field, value, message", [
    ("revolutions", 0.0, r"revolutions must be a finite number > 0, got 0.0"),
    ("revolutions", math.inf, r"revolutions must be a finite number > 0"),
    ("method", "Euler", r"method must be one of \['Radau', 'BDF', 'LSODA', 'RK23', 'RK45'\], got 'Euler'"),
    ("rtol", 1.0, r"rtol must be in \(0, 1\)"),
    ("rtol", -1e-6, r"rtol must be a finite number > 0"),
    ("atol", 0.0, r"atol must be a finite number > 0"),
    ("max_step", math.nan, r"max_step must be a finite number > 0"),
    ("min_film", 1.0, r"min_film must be in \(0, 1\) clearances, got 1.0"),
    ("points_per_revolution", 7, r"points_per_revolution must be an integer >= 8, got 7"),
    ("points_per_revolution", 36.5, r"points_per_revolution must be an integer >= 8"),
    ("periodic_method", "secant", r"periodic_method must be one of \('newton', 'fixed-point', 'anderson', "
                                  r"'one-revolution'\), got 'secant'"),
    ("periodic_tol", 0.0, r"periodic_tol must be a finite number > 0"),
    ("periodic_max_iter", 0, r"periodic_max_iter must be an integer >= 1, got 0"),
    ("start", "cold", r"start must be 'steady', 'periodic', \(gamma, delta\) or a Trajectory"),
    ("start", (0.0, 1.0), r"start gamma must be > 0"),
    ("start", (0.5, math.nan), r"start \(gamma, delta\) must be two finite numbers"),
    ("beta0", math.inf, r"beta0 must be a finite angle"),
])
def test_integration_settings_name_the_field_and_its_range(field, value, message):
    with pytest.raises(ValueError, match=message):
        transient.Integration(**{field: value})


def test_integration_settings_are_frozen_and_checked_once():
    settings = transient.Integration(start=[0.4, 3], points_per_revolution=36.0)
    assert settings.start == (0.4, 3.0) and settings.points_per_revolution == 36
    assert settings.absolute_tolerance == pytest.approx(1e-3 * settings.rtol)
    with pytest.raises(AttributeError):
        settings.rtol = 1e-3
    with pytest.raises(bf.LimitError, match="max_revolutions"):
        transient.Integration(revolutions=3.0, max_revolutions=2.0)
    # the output samples: points_per_revolution a turn, both ends included
    angles = transient.Integration(revolutions=0.5, points_per_revolution=36).output_angles(1.0)
    assert angles.size == 19 and angles[0] == 1.0 and angles[-1] == pytest.approx(1.0 + math.pi)


def test_film_rupture_is_a_scipy_style_event():
    class Film:
        def smallest_film(self, beta, y):
            return 1.0 - beta  # closes linearly: reaches 0.25 at beta = 0.75

    event = film_rupture(Film(), 0.25)
    assert event.terminal is True and event.direction == -1
    assert event(0.5, None) == pytest.approx(0.25)
    assert crossed(event, 0.1, 0.0) and crossed(event, 0.1, -0.2)
    assert not crossed(event, -0.1, 0.2) and not crossed(event, 0.2, 0.1)
    # located on a dense output by bisection: 2^-60 of the step is below the round-off of the angle
    assert locate(event, lambda beta: None, 0.5, 1.0) == pytest.approx(0.75, abs=1e-15)


def test_every_model_of_the_table_keeps_the_contract():
    assert set(transient.MODELS) == {"rigid", "cavitating", "jfo", "quasi-static elastic", "elastic", "fed",
                                     "fed cavitating", "fed jfo", "fed quasi-static elastic"}
    for name, model in transient.MODELS.items():
        assert issubclass(model, transient.Model) and model.name == name
        assert model.periodic_default in model.periodic_methods
        assert set(model.periodic_methods) <= set(transient.PERIODIC_METHODS)
    # Newton shooting needs the monodromy of a (gamma, delta) state: not for the pressure state, nor the JFO history
    assert transient.MODELS["rigid"].periodic_default == "newton"
    assert transient.MODELS["elastic"].periodic_default == "anderson"
    assert transient.MODELS["jfo"].periodic_default == "one-revolution"
    assert transient.MODELS["fed"].periodic_default == transient.MODELS["fed cavitating"].periodic_default == \
        transient.MODELS["fed quasi-static elastic"].periodic_default == "anderson"
    assert transient.MODELS["fed jfo"].periodic_default == "one-revolution"
    for name in ("elastic", "jfo", "fed", "fed cavitating", "fed jfo", "fed quasi-static elastic"):
        with pytest.raises(ValueError, match=f"periodic_method must be one of .* for the {name} model"):
            transient.MODELS[name].check(transient.Integration(start="periodic", periodic_method="newton"))
    with pytest.raises(ValueError, match="method must be one of .* for the elastic model"):
        transient.MODELS["elastic"].check(transient.Integration(method="RK45"))
    with pytest.raises(ValueError, match="start must be 'periodic', 'steady' or a Trajectory"):
        transient.MODELS["elastic"].check(transient.Integration(start=(0.5, 3.0)))


def test_the_trajectory_builder_refuses_what_it_cannot_build(pump):
    betas = np.array([0.0, 0.1])
    columns = {name: np.zeros(2) for name in transient.trajectory.SAMPLE_COLUMNS}
    common = dict(message="", rupture_beta=math.nan, start=(0.5, 3.0), periodic_iterations=0,
                  periodic_residual=math.nan, element="P1", stats={})
    traj = transient.trajectory.make_trajectory(pump, 0.0, betas, np.ones((2, 2)), columns, status="completed",
                                                **common)
    assert traj.t[-1] == pytest.approx(0.1 / pump.drive.omega) and traj.max_deflection is None
    with pytest.raises(ValueError, match="status must be one of"):
        transient.trajectory.make_trajectory(pump, 0.0, betas, np.ones((2, 2)), columns, status="done", **common)
    with pytest.raises(ValueError, match=r"columns: missing \['h_min'\]"):
        transient.trajectory.make_trajectory(pump, 0.0, betas, np.ones((2, 2)),
                                             {k: v for k, v in columns.items() if k != "h_min"},
                                             status="completed", **common)


def test_jfo_does_not_take_an_elastic_support(pump, pocket_mesh):
    # before the one driver, simulate(cavitation="jfo", elastic=C) ran the rigid JFO film and ignored C
    C = bf.elastic.half_space(pocket_mesh, pump.scale, (pump.shoe_material, pump.eccentric_material))
    with pytest.raises(ValueError, match="cavitation='jfo' does not take elastic="):
        bf.simulate(pump, pocket_mesh, 0.1, cavitation="jfo", elastic=C)


def test_state_result_of_a_pressure_state_needs_its_compliance(pump):
    mesh = transient.pump_mesh(pump, 0.3)
    C = bf.elastic.half_space(mesh, pump.scale, (pump.shoe_material, pump.eccentric_material))
    traj = transient.simulate_elastic(pump, C, 0.01, start="steady", points_per_revolution=36)
    with pytest.raises(ValueError, match="pass its Compliance"):
        transient.state_result(pump, mesh, traj, 0)
    res = transient.state_result(pump, mesh, traj, 0, elastic=C)
    # the run's own pressure: the result's pressure is the trajectory's (no solve)
    np.testing.assert_array_equal(res.pressure, traj.pressures[0])
