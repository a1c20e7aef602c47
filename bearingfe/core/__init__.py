"""The layer every other one stands on: input schema, size limits, argument checks, scales, parameter objects and sparse linear algebra.

================  ============================================================
module            what it does
================  ============================================================
``schema``        One schema for every input file: scene, mechanism and study files.
``limits``        Size limits: guards against runaway work, checked before the work starts.
``checks``        Checks that keep answers honest: ranges of solver inputs and the mesh resolution of the thin film.
``scales``        Conversion between the non-dimensional Reynolds problem and SI units.
``machine``       The drive and the materials every machine shares (SI, frozen, validated).
``parameters``    Parameter objects for arguments that travel together: the operating point and the discretization.
``linalg``        Pluggable sparse linear solvers for the condensed Reynolds systems.
``compressed``    Sparse matrices from arrays at hand: scipy's own kernels without its objects' checks, checked once.
``banded``        Banded Cholesky of sparse symmetric positive definite matrices, and the rule for when a band pays.
``ordering``      Fill-reducing orderings found from the sparsity pattern alone (nested dissection).
``blocks``        Blocks of consecutive indices: long vectorized passes cut into pieces that stay in cache.
``pages``         Large arrays on ordinary memory pages while a solve runs (no wait for huge-page compaction).
``tempdirs``      Private temporary folders that a killed process does not leave behind for good.
``parallel``      Independent jobs of one run shared with forked processes when more than one core is free.
``lazy``          Packages whose public names load their modules on first use (PEP 562).
================  ============================================================
"""

from __future__ import annotations

from .limits import LimitError, check_limit
from .checks import ResolutionWarning, check_resolution
from .scales import Scale
from .machine import Drive, Material
from .parameters import Discretization, OperatingPoint
from .linalg import DEFAULT_SOLVER, LINEAR_SOLVERS

__all__ = ["LimitError", "check_limit", "ResolutionWarning", "check_resolution", "Scale", "Drive", "Material",
           "Discretization", "OperatingPoint", "DEFAULT_SOLVER", "LINEAR_SOLVERS"]
