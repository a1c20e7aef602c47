"""The ``bearingfe`` console script's entry point, outside the package it starts.

Importing :mod:`bearingfe` takes a second or more (numpy, scipy, scikit-fem,
gmsh); a Ctrl-C (or SIGTERM) in that time raised KeyboardInterrupt inside
the console script's own import line, before :func:`bearingfe.cli.main` and
its one-line messages existed, and Python printed a traceback. This module
imports nothing heavy: it imports the command line inside a ``try`` and ends
an interrupted start like an interrupted command (exit 130, one line).
"""

from __future__ import annotations

import signal
import sys
from typing import Sequence

__all__ = ["main"]


def main(argv: Sequence[str] | None = None) -> int:
    """Import and run :func:`bearingfe.cli.main`; 130 with one line if interrupted while importing."""
    def stop(signum, frame):
        raise KeyboardInterrupt

    before = signal.signal(signal.SIGTERM, stop) if hasattr(signal, "SIGTERM") else None
    try:
        from bearingfe.cli import main as run
    except KeyboardInterrupt:
        print("bearingfe: interrupted", file=sys.stderr)
        return 130
    finally:
        if before is not None:
            signal.signal(signal.SIGTERM, before)
    return run(argv)
