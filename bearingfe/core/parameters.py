"""Parameter objects for arguments that travel together: the operating point and the discretization.

:class:`OperatingPoint` (wedge, squeeze rates, pocket pressure, sliding speed)
and :class:`Discretization` (element, formulation, linear solver, mesh sizes)
are frozen dataclasses that check their values when made, so a bad value is
named where it is written. The solver functions take them as ``operating=``
and ``discretization=`` besides their loose keywords (which keep working)::

    op = OperatingPoint(wedge=1.0, squeeze=(0.0, 0.2), inlet_pressure=2.0)
    fine = Discretization(element="P2", formulation="direct")
    solve_reynolds(mesh, film, operating=op, discretization=fine)
    # the same as solve_reynolds(mesh, film, wedge=1.0, squeeze=(0.0, 0.2), inlet_pressure=2.0,
    #                            element="P2", formulation="direct")

:func:`takes` adds the two keywords to a function: each field of an object
is passed as the function's keyword of the same name (or a renamed one,
``mesh_size`` -> ``size``). Giving a field both ways, or a field the
function has no use for (``mesh_size`` to a function that takes a mesh), is
an error that names it.

This module owns the choice lists of the discretization (:data:`ELEMENTS`,
:data:`FORMULATIONS`); the linear solvers are those of
:data:`bearingfe.core.linalg.LINEAR_SOLVERS`.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, Mapping

import numpy as np
import skfem

from .linalg import DEFAULT_SOLVER, LINEAR_SOLVERS
from .schema import finite, one_of, positive

__all__ = ["ELEMENTS", "FORMULATIONS", "Discretization", "OperatingPoint", "takes"]

#: Finite elements by name: triangles of order 1 and 2 (P2 also curves the mesh's geometry).
ELEMENTS: Mapping[str, type] = MappingProxyType({"P1": skfem.ElementTriP1, "P2": skfem.ElementTriP2})
#: Forms of the Reynolds equation: the substitution ``Pi = p h^(3/2)`` or ``div(h^3 grad p)``
#: (``docs/formulations.md``).
FORMULATIONS = ("pi", "direct")


@dataclass(frozen=True)
class OperatingPoint:
    """Where a film state is solved: the source terms of the Reynolds equation (non-dimensional).

    Parameters
    ----------
    wedge : float
        Entrainment factor of the wedge term ``6 wedge dh/dphi`` [-] (1 for
        a journal turning under a fixed shoe); finite.
    squeeze : (float, float)
        ``(gamma_rate, phi0_rate)`` per radian of shaft turn; finite.
    inlet_pressure : float or tuple of float
        Pocket pressure ``p_s`` [-]; finite (non-zero needs pockets). A tuple holds each pocket at its
        own pressure, in the order of :func:`bearingfe.film.pockets.pocket_names` (the front door,
        :func:`bearingfe.solve_reynolds`, makes it from a sequence or a mapping ``name -> value``).
    sliding : float, optional
        Sliding speed for the Couette shear [-]; default ``wedge``.

    Raises
    ------
    ValueError
        A value is not a finite number; the message names the field.
    """

    wedge: float = 1.0
    squeeze: tuple[float, float] = (0.0, 0.0)
    inlet_pressure: float | tuple[float, ...] = 0.0
    sliding: float | None = None

    def __post_init__(self) -> None:
        own = type(self).__name__
        object.__setattr__(self, "wedge", finite(f"{own}.wedge", self.wedge))
        try:
            rates = tuple(self.squeeze)
        except TypeError:
            rates = ()
        if len(rates) != 2:
            raise ValueError(f"{own}.squeeze must be a pair (gamma_rate, phi0_rate) of finite numbers, "
                             f"got {self.squeeze!r}")
        object.__setattr__(self, "squeeze", tuple(finite(f"{own}.squeeze[{k}]", r) for k, r in enumerate(rates)))
        if isinstance(self.inlet_pressure, tuple):  # one pressure per pocket
            object.__setattr__(self, "inlet_pressure", tuple(finite(f"{own}.inlet_pressure[{k}]", v)
                                                             for k, v in enumerate(self.inlet_pressure)))
        else:
            object.__setattr__(self, "inlet_pressure", finite(f"{own}.inlet_pressure", self.inlet_pressure))
        if self.sliding is not None:
            object.__setattr__(self, "sliding", finite(f"{own}.sliding", self.sliding))

    @property
    def weights(self) -> np.ndarray:
        """Weights of the unit sources ``(wedge, gamma_rate, phi0_rate, inlet)``; with one pressure per pocket
        the inlet column holds the pockets at their pressures (weight 1)."""
        if isinstance(self.inlet_pressure, tuple):
            return np.array([self.wedge, *self.squeeze, 1.0])
        return np.array([self.wedge, *self.squeeze, self.inlet_pressure])


@dataclass(frozen=True)
class Discretization:
    """How a film is discretized and solved.

    Parameters
    ----------
    element : str
        A key of :data:`ELEMENTS` (``"P1"``, ``"P2"``).
    formulation : str
        One of :data:`FORMULATIONS` (``"pi"``, ``"direct"``).
    solver : str or callable
        A key of :data:`bearingfe.core.linalg.LINEAR_SOLVERS`, or a factorization
        ``A -> solve``.
    mesh_size : float, optional
        Element size of a mesh the function makes itself [-], > 0; ``None``:
        the function's default (functions given a mesh take none).
    min_size : float, optional
        Smallest element size of a graded or adapted mesh [-], in
        ``(0, mesh_size]``; ``None``: the function's default.

    Raises
    ------
    ValueError
        A value outside its choices or range; the message names the field.
    """

    element: str = "P1"
    formulation: str = "pi"
    solver: str | Callable = DEFAULT_SOLVER
    mesh_size: float | None = None
    min_size: float | None = None

    def __post_init__(self) -> None:
        own = type(self).__name__
        one_of(f"{own}.element", self.element, ELEMENTS)
        one_of(f"{own}.formulation", self.formulation, FORMULATIONS)
        if not callable(self.solver):
            one_of(f"{own}.solver", self.solver, LINEAR_SOLVERS)
        for name in ("mesh_size", "min_size"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, positive(f"{own}.{name}", getattr(self, name)))
        if self.mesh_size is not None and self.min_size is not None and self.min_size > self.mesh_size:
            raise ValueError(f"{own}.min_size must be in (0, mesh_size = {self.mesh_size:g}], "
                             f"got {self.min_size!r}")


#: Keyword under which each parameter object is passed.
_KEYWORDS = {OperatingPoint: "operating", Discretization: "discretization"}


def takes(*classes: type, rename: Mapping[str, str] | None = None) -> Callable[[Callable], Callable]:
    """Decorator: the function also accepts ``operating=`` and/or ``discretization=`` objects.

    Each field of a given object is passed as the function's keyword of the
    same name (``rename`` maps a field to another keyword, e.g.
    ``{"mesh_size": "size"}``); a field left at ``None`` is not passed. The
    old keyword calls are unchanged.

    Raises (from the decorated function)
    ------------------------------------
    ValueError
        The object is of the wrong type; a field is given both in the object
        and as a keyword; or the function has no keyword for a field that is
        not at its default (it would be ignored).
    """
    rename = dict(rename or {})

    def decorate(func: Callable) -> Callable:
        sig = inspect.signature(func)
        keywords = {cls: _KEYWORDS[cls] for cls in classes}

        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            given = {cls: kwargs.pop(kw, None) for cls, kw in keywords.items()}
            if all(obj is None for obj in given.values()):
                return func(*args, **kwargs)
            try:
                explicit = set(sig.bind_partial(*args, **kwargs).arguments)
            except TypeError:  # a call that does not fit the signature: the function's own error
                return func(*args, **kwargs)
            for cls, obj in given.items():
                if obj is not None:
                    kwargs.update(_expand(func.__name__, sig, cls, obj, keywords[cls], rename, explicit))
            return func(*args, **kwargs)

        extra = [inspect.Parameter(kw, inspect.Parameter.KEYWORD_ONLY, default=None, annotation=f"{cls.__name__} | None")
                 for cls, kw in keywords.items()]
        params = list(sig.parameters.values())
        tail = [p for p in params if p.kind is inspect.Parameter.VAR_KEYWORD]
        wrapper.__signature__ = sig.replace(parameters=[p for p in params if p not in tail] + extra + tail)
        return wrapper
    return decorate


def _expand(name: str, sig: inspect.Signature, cls: type, obj, keyword: str, rename: Mapping[str, str],
            explicit: set) -> dict:
    """The keywords that stand for the fields of ``obj`` in a call of function ``name``."""
    if not isinstance(obj, cls):
        raise ValueError(f"{keyword} must be a bearingfe.{cls.__name__}, got {type(obj).__name__}")
    out = {}
    default = cls()
    for f in dataclasses.fields(cls):
        value = getattr(obj, f.name)
        target = rename.get(f.name, f.name)
        if target not in sig.parameters:
            if value is not None and not _same(value, getattr(default, f.name)):
                raise ValueError(f"{name}() has no use for {cls.__name__}.{f.name} = {value!r}; leave it at "
                                 f"{getattr(default, f.name)!r}")
            continue
        if value is None:
            continue
        if target in explicit:
            raise ValueError(f"{name}(): {target} given both as a keyword and in {keyword}= "
                             f"({cls.__name__}.{f.name}); give it once")
        out[target] = value
    return out


def _same(a, b) -> bool:
    try:
        return bool(a == b)
    except (TypeError, ValueError):
        return a is b
