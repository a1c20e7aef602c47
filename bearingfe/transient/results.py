"""The film of one sample of a pump transient, re-solved for pictures and fields: :func:`state_result`."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..bearings.pump import EccentricPump
from ..elastic import Compliance, DeflectedFilm
from ..film import CosineFilm, ReynoldsResult, operators, source_weights, superpose
from ..film import build_result
from ..geometry import SupportMesh
from ..reynolds import solve_reynolds
from .trajectory import Trajectory

__all__ = ["state_result"]


def state_result(pump: EccentricPump, mesh: SupportMesh, traj: Trajectory, k: int, cavitation: str = "none",
                 element: str | None = None, elastic: Compliance | None = None) -> ReynoldsResult:
    """Re-solve the film of sample ``k`` of a trajectory (shoe frame): pressure field, flows, friction.

    The same film state, rates and pocket pressure that the run balanced, so
    the film force equals ``-traj.load[k]``; use it for pictures, fields and
    peak pressures (``Trajectory`` keeps only the reduced arrays). The film
    is solved by the front door :func:`bearingfe.reynolds.solve_reynolds`
    with the run's ``cavitation`` and ``elastic`` support (the steady JFO
    film of that state under ``"jfo"``: the run's history is not replayed).
    Where the pressure is itself a state of the run
    (:func:`bearingfe.transient.elastic.simulate_elastic`: ``traj.pressures``),
    the result is built from the run's pressure: force and friction are the
    run's, the flows leave out the deflection's squeeze (``traj`` has the
    complete ones).

    Parameters
    ----------
    pump : EccentricPump
    mesh : SupportMesh
        The run's mesh.
    traj : Trajectory
    k : int
        Index of the sample.
    cavitation : str
        The run's cavitation model (:data:`bearingfe.cavitation.MODELS`).
    element : {"P1", "P2"}, optional
        Default the run's (``traj.element``).
    elastic : Compliance, optional
        The run's elastic support (needed when the run's pressure is a state).
    """
    film = CosineFilm(float(traj.gamma[k]), float(traj.delta[k]))
    element = traj.element if element is None else element
    rates = (float(traj.gamma_rate[k]), float(traj.delta_rate[k]))
    if traj.pressures is not None:
        return _pressure_state(mesh, traj, k, film, rates, elastic)
    p_s = float(traj.inlet_pressure[k]) if mesh.has_inlet else 0.0
    return solve_reynolds(mesh, film, wedge=float(traj.wedge[k]), squeeze=rates, inlet_pressure=p_s,
                          formulation="pi" if elastic is None else "direct", element=element, cavitation=cavitation,
                          elastic=elastic)


def _pressure_state(mesh: SupportMesh, traj: Trajectory, k: int, film: CosineFilm, rates: tuple[float, float],
                    compliance: Compliance | None) -> ReynoldsResult:
    """The result of the run's own pressure on the film it deflects (through the film layer, no solve)."""
    if not isinstance(compliance, Compliance):
        raise ValueError("elastic: the run's pressure is a state (simulate_elastic): pass its Compliance, got "
                         f"{type(compliance).__name__}")
    if compliance.mesh is not mesh:
        raise ValueError("elastic: the compliance was built on another mesh than `mesh`")
    p = np.asarray(traj.pressures[k], float)
    ps = float(traj.inlet_pressure[k])
    w = compliance.deflection(p, ps)
    basis = operators(compliance.mesh, compliance.element).basis
    deflected = DeflectedFilm(film, basis, w)
    sup = superpose(compliance.mesh, deflected, formulation="direct", element=compliance.element)
    weights = source_weights(float(traj.wedge[k]), rates, ps)
    res = build_result(sup, p, weights, cavitated=np.zeros(p.size, bool))
    return dataclasses.replace(res, deflection=w)
