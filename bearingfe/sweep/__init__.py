"""Design studies: parameter sweeps on one machine or on a Dask cluster.

A *case* is a base parameter object plus a mapping of changes. A change is
named either by a dotted field path (``"surface.half_width"``,
``"scale.speed"``: applied with :func:`dataclasses.replace` down the path) or
by a *change builder* from :data:`CHANGES` (``"pocket_fraction"``,
``"pocket_position"``, ``"pocket_shape"``): a function
``(base, value) -> new base`` for parameters that are not one field.

Each case runs in its own process (gmsh and the sparse factorizations are
not thread-safe): local ``spawn`` processes by default, or the workers of a
``dask.distributed`` client (a ``LocalCluster`` or any scheduler address).
The worker function :func:`run_case` is pure: parameter object in, plain
record out; the parent process alone reads and writes the on-disk cache, so
workers on other machines need no shared file system.

The table is a :class:`pandas.DataFrame` (one row per case, in the order of
the cases): its columns mix floats (outputs), strings (errors, categorical
inputs such as a pocket shape) and booleans, it must hold ragged lists of
cases and failed rows as well as full grids, and it writes straight to CSV;
a pivot turns a grid back into a 2-D array for contour plots. (An
``xarray.Dataset`` fits only full grids of numeric inputs.)

Modules
-------
``cases``     parameter objects and run functions (ShoeCase, PumpCase, RUNS, BASES)
``outputs``   named reductions of a result to one float (OUTPUTS), their units and SI columns
``changes``   field paths and change builders (CHANGES, apply_changes, expand_cases)
``execute``   processes / Dask, the resumable cache, the table (sweep, run_case, case_key)
``workers``   local worker processes: per-case time limit, no worker outlives its parent
``studies``   TOML study files (Study, read_study)

Every name is re-exported here: ``from bearingfe.sweep import ...`` is the
public path (cache keys name this package's functions by it, too).
"""

from __future__ import annotations

# Names outside __all__ (POCKET_SHAPES, get_field, centroid, ...) are re-exported as the one module had them.
from .cases import BASES, RUNS, FilmRuptured, PumpCase, PumpOutcome, ShoeCase, run_pump, run_shoe
from .changes import (CHANGES, POCKET_SHAPES, apply_changes, centroid, check_change_name, expand_cases, get_field,
                      pocket_fraction, pocket_position, pocket_shape, set_field)
from .execute import (CACHE_FILES, CacheWarning, best_design, case_key, case_status, estimated_elements, run_case,
                      sweep)
from .outputs import OUTPUT_UNITS, OUTPUTS, SI_OUTPUTS, STANDARD_OUTPUTS, csv_headers, si_columns
from .studies import Study, read_study

__all__ = [
    "CACHE_FILES", "CacheWarning", "estimated_elements", "FilmRuptured", "case_status", "csv_headers", "OUTPUT_UNITS",
    "CHANGES", "OUTPUTS", "RUNS", "BASES", "PumpCase", "PumpOutcome", "ShoeCase", "Study", "apply_changes", "best_design",
    "case_key", "expand_cases", "read_study", "run_case", "run_pump", "run_shoe", "set_field", "sweep",
    "SI_OUTPUTS", "si_columns",
]
