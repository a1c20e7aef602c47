"""Packages whose public names load their modules on first use (PEP 562).

A package table (``{module: (name, ...)}``) gives the package its module-level
``__getattr__`` and ``__dir__``: ``package.name`` imports ``package.module`` the
first time it is asked for and keeps the name, so a program that never asks for
a solver never pays for importing it (the main scene starts faster).
:func:`without_collections` keeps the garbage collector off while modules load.
"""

from __future__ import annotations

import contextlib
import gc
import importlib
from collections.abc import Callable, Iterator, Mapping


def lazy_names(package: str, table: Mapping[str, tuple[str, ...]],
               namespace: dict) -> tuple[Callable[[str], object], Callable[[], list[str]], list[str]]:
    """The ``__getattr__``, ``__dir__`` and ``__all__`` of a package that imports on first use.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    table : mapping of str to tuple of str
        Its public names by module (a module's name relative to the package).
    namespace : dict
        The package's ``globals()``: a name once imported is kept there.

    Returns
    -------
    getattr, dir : callables
        To be bound as the package's ``__getattr__`` and ``__dir__``.
    all : list of str
        Every public name, in the table's order.

    Raises
    ------
    ValueError
        If a name is listed under two modules.
    """
    origin: dict[str, str] = {}
    for module, names in table.items():
        for name in names:
            if name in origin:
                raise ValueError(f"{package}: {name!r} is listed under {origin[name]!r} and {module!r}")
            origin[name] = module

    def __getattr__(name: str):
        if name not in origin:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f"{package}.{origin[name]}"), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(origin))

    return __getattr__, __dir__, list(origin)


@contextlib.contextmanager
def without_collections() -> Iterator[None]:
    """No cyclic garbage collection inside the ``with`` block (the collector's state is restored after it).

    For imports: a module's objects live as long as the process, so the collector's passes over them while
    they load find nothing to free; on the main scene's start (numpy, scipy, scikit-fem, the scene's modules)
    they were a sixth of the imports' time (90 ms of 570).
    """
    collecting = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if collecting:
            gc.enable()
