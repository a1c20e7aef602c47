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
from typing import NoReturn, Sequence

__all__ = ["main", "command"]


def main(argv: Sequence[str] | None = None) -> int:
    """Import and run :func:`bearingfe.cli.main`; 130 with one line if interrupted while importing."""
    run = _load("main")
    return run(argv) if callable(run) else run


def command(argv: Sequence[str] | None = None) -> NoReturn:
    """The console script: import and run :func:`bearingfe.cli.command` (which ends the process with the
    exit code); 130 with one line if interrupted while importing."""
    run = _load("command")
    if not callable(run):
        sys.exit(run)
    run(argv)


def _load(name: str):
    """``bearingfe.cli.<name>``, or the exit code 130 if the import was interrupted."""
    def stop(signum, frame):
        raise KeyboardInterrupt

    before = signal.signal(signal.SIGTERM, stop) if hasattr(signal, "SIGTERM") else None
    try:
        from bearingfe import cli
    except KeyboardInterrupt:
        print("bearingfe: interrupted", file=sys.stderr)
        return 130
    finally:
        if before is not None:
            signal.signal(signal.SIGTERM, before)
    return getattr(cli, name)
