"""The one stepping loop of the pump transient: every model, every integrator, one loop.

:func:`integrate` steps a model's integrator (:meth:`bearingfe.transient.base.Model.stepper`,
a scipy :class:`~scipy.integrate.OdeSolver`) one accepted step at a time:

* a trial state that closes the film (:class:`~bearingfe.transient.base.FilmClosed`
  raised inside ``step()``), or any trial step the model cannot take
  (:class:`~bearingfe.transient.base.TrialRejected`: the JFO step's Newton
  that does not converge) rejects the trial: the integrator is restarted
  from the last accepted state with its first and largest step half as
  long as the last step it accepted, halved again at every further
  rejection; after :data:`CALM_STEPS` accepted steps without one it is
  restarted with the settings' ``max_step`` again. Below the floor
  ``min_step`` the run stops as ``"stalled"`` with the angle and the
  reason in its message;
* after each accepted step the film-rupture event
  (:func:`bearingfe.transient.events.film_rupture`) is evaluated; when it
  has happened its angle is located on the step's dense output and the
  run ends there as ``"ruptured"``;
* a trial state without equilibrium (:class:`~bearingfe.transient.base.NoEquilibrium`)
  ends the run at the last accepted state as ``"no-equilibrium"``; an
  integrator that fails (its own step size underflows) as ``"stalled"``.

:func:`states_at` evaluates the dense output of a run at the sample angles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .base import FilmClosed, NoEquilibrium, TrialRejected
from .events import crossed, film_rupture, locate

__all__ = ["Run", "integrate", "states_at", "CALM_STEPS"]

#: Accepted steps after a rejected trial before the integrator may take steps of ``max_step`` again.
CALM_STEPS = 8


@dataclass
class Run:
    """One integration of a model from ``segments[0][0]`` (or its start) to ``end``.

    Attributes
    ----------
    segments : list of (float, float, callable)
        Accepted steps ``(beta_from, beta_to, dense output)`` [rad]; the last
        one of a ruptured run ends at the located angle.
    end : float
        Angle where the run ended [rad].
    y_end : ndarray
        State there.
    status, message : str
        As :attr:`bearingfe.Trajectory.status` and its message.
    rupture_beta : float
        ``end`` unless the run completed (NaN).
    steps : int
        Accepted steps.
    factorizations : int
        LU decompositions of the integrators' Newton matrices (implicit methods).
    retakes : int
        Rejected trial steps (their state closed the film, or the model's own
        solver failed) taken again shorter.
    """

    segments: list = field(default_factory=list)
    end: float = math.nan
    y_end: np.ndarray | None = None
    status: str = "completed"
    message: str = ""
    rupture_beta: float = math.nan
    steps: int = 0
    factorizations: int = 0
    retakes: int = 0

    def stop(self, status: str, beta: float, y: np.ndarray, message: str) -> Run:
        """End the run at ``(beta, y)`` with ``status`` (not ``"completed"``)."""
        self.status, self.end, self.y_end, self.message = status, float(beta), np.asarray(y, float), message
        self.rupture_beta = float(beta)
        return self


def _degrees(beta: float) -> str:
    return f"beta = {beta:.4f} rad ({math.degrees(beta) % 360:.1f} deg)"


def _shorter(stepper, retaken: float | None, settings) -> float:
    """Length of the step to retake after a rejected trial [rad]: half the last step this integrator
    accepted; if it accepted none, half the step it tried (``h_abs``, as scipy's integrators name the
    next step; LSODA does not say), else half the previous retaken step, else half of ``max_step``."""
    base = stepper.step_size
    if base is None:
        known = settings.max_step if retaken is None else retaken
        tried = getattr(stepper, "h_abs", None)
        base = known if tried is None else min(float(tried), known)
    return 0.5 * float(base)


def integrate(model, y0, angles: np.ndarray, settings) -> Run:
    """Integrate ``model`` from ``(angles[0], y0)`` to ``angles[-1]`` (see the module docstring).

    Parameters
    ----------
    model : bearingfe.transient.base.Model
    y0 : array_like
        Initial state.
    angles : ndarray
        The run's sample angles [rad], increasing (a fixed-step model steps on them).
    settings : bearingfe.transient.settings.Integration
    """
    beta0 = float(angles[0])
    y0 = np.asarray(y0, float)
    run = Run()
    event = film_rupture(model, settings.min_film)
    model.begin(beta0, y0)
    before = event(beta0, y0)
    if before <= 0:
        model.end(run.stop("ruptured", beta0, y0, f"film ruptured: the start's smallest film is below "
                                                  f"{settings.min_film:.4g} c at {_degrees(beta0)}"))
        return run
    stepper = model.stepper(beta0, y0, angles, settings, None, None)
    retaken, calm = None, 0  # the last retaken step [rad] and the accepted steps since
    while stepper is not None and stepper.status == "running":
        beta_old, y_old = float(stepper.t), np.array(stepper.y, float)
        try:
            note = stepper.step()
        except TrialRejected as exc:
            retaken = _shorter(stepper, retaken, settings)
            run.factorizations += int(stepper.nlu)
            if retaken < settings.min_step:
                why = "closed the film (h <= 0)" if isinstance(exc, FilmClosed) else f"was rejected ({exc})"
                run.stop("stalled", beta_old, y_old,
                         f"every trial step after {_degrees(beta_old)} down to the floor min_step = "
                         f"{settings.min_step:g} rad {why}; stopped at the last accepted state "
                         f"(smallest film {model.smallest_film(beta_old, y_old):.4g} c)")
                stepper = None  # its factorizations are counted
                break
            run.retakes += 1
            stepper = model.stepper(beta_old, y_old, angles, settings, retaken, retaken)
            calm = 0
            continue
        except NoEquilibrium as exc:
            run.stop("no-equilibrium", beta_old, y_old, f"{exc}; stopped at the last accepted state "
                                                       f"(beta = {beta_old:.4f} rad)")
            break
        if stepper.status == "failed":
            run.stop("stalled", beta_old, y_old, f"integrator {settings.method} failed at {_degrees(beta_old)}: "
                                                 f"{_integrator_failure(note, settings)}; stopped at the last "
                                                 f"accepted state")
            break
        run.steps += 1
        dense = stepper.dense_output()
        beta, y = float(stepper.t), np.asarray(stepper.y, float)
        after = event(beta, y)
        if crossed(event, before, after):
            hit = locate(event, dense, beta_old, beta)
            run.segments.append((beta_old, hit, dense))
            run.stop("ruptured", hit, dense(hit), f"film ruptured: smallest film reached {settings.min_film:.4g} c "
                                                   f"at {_degrees(hit)}")
            break
        before = after
        run.segments.append((beta_old, beta, dense))
        if retaken is not None:
            calm += 1
            if calm >= CALM_STEPS and stepper.status == "running":  # trouble passed: the full max_step again
                run.factorizations += int(stepper.nlu)
                stepper = model.stepper(beta, y, angles, settings, stepper.step_size, None)
                retaken, calm = None, 0
    if run.status == "completed":
        run.end, run.y_end = float(stepper.t), np.asarray(stepper.y, float)
        run.message = f"completed {(run.end - beta0) / (2 * math.pi):.4g} revolutions"
    if stepper is not None:
        run.factorizations += int(stepper.nlu)
    model.end(run)
    return run


def states_at(run: Run, angles: np.ndarray, y0) -> tuple[np.ndarray, np.ndarray]:
    """The sample angles the run reached (and its end, if it stopped early) and the states there.

    Each state comes from the dense output of the accepted step that holds
    its angle (the first one, at a step's end).
    """
    betas = np.asarray(angles, float)
    betas = betas[betas <= run.end + 1e-12]
    if run.status != "completed" and (betas.size == 0 or betas[-1] < run.end):
        betas = np.append(betas, run.end)
    states = np.empty((betas.size, np.size(y0)))
    k = 0
    for i, b in enumerate(betas):
        if not run.segments:
            states[i] = y0
            continue
        while k < len(run.segments) - 1 and b > run.segments[k][1]:
            k += 1
        start, stop, dense = run.segments[k]
        states[i] = dense(min(max(b, start), stop))
    return betas, states


def _integrator_failure(note, settings) -> str:
    """The integrator's failure in the user's terms (scipy's text kept in brackets)."""
    what = " ".join(str(note or "").split()) or "no reason given"
    return (f"it could not take a step that meets rtol = {settings.rtol:g} (scipy: {what}); the run's inputs may "
            f"be extreme (pressures, speeds, a very soft support), or try another method "
            f"(method='BDF' or 'Radau'), a smaller max_step or a looser rtol")

