"""Errors of geometry files: a file that cannot be used, and a ``.geo`` construct refused as untrusted.

Both are :class:`ValueError`; :class:`UntrustedGeoError` is a :class:`GeometryFileError`. They live
here, below the ``.geo`` reader and the file loaders, so that both raise the same classes.
"""

from __future__ import annotations

__all__ = ["GeometryFileError", "UntrustedGeoError"]


class GeometryFileError(ValueError):
    """A geometry file cannot be used (not a mesh, not the ``.geo`` subset, gmsh failed, ended or ran out of time)."""


class UntrustedGeoError(GeometryFileError):
    """A ``.geo`` file uses a construct outside the geometry subset bearingfe reads (refused unless trusted)."""
