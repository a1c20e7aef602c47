"""The support surface and its meshes: outlines and pockets, gmsh meshing, untrusted geometry files.

================  ============================================================
module            what it does
================  ============================================================
``surface``       Support-surface geometry in unwrapped non-dimensional coordinates.
``geofiles``      Geometry files from users: ``.geo`` scripts checked and run apart, ``.msh`` read as data.
``gmsh_worker``   Child process in which gmsh meshes: one ``.geo`` script (:func:`bearingfe.geometry.geofiles.run_geo`
``locate``        Points on a triangle mesh: the cell that holds a point, field values there, cell sizes.
``meshing``       Meshing support surfaces with gmsh and reading meshes into scikit-fem.
================  ============================================================
"""

from __future__ import annotations

from .surface import Circle, Ellipse, Polygon, Recess, Rectangle, Shape, Slot, Surface
from .geofiles import GeometryFileError, MeshSizeError, UntrustedGeoError
from .meshing import SupportMesh, grid_mesh, load_mesh, mesh_surface, refine_uniformly

__all__ = ["Circle", "Ellipse", "Polygon", "Recess", "Rectangle", "Shape", "Slot", "Surface", "GeometryFileError",
           "MeshSizeError", "UntrustedGeoError", "SupportMesh", "grid_mesh", "load_mesh", "mesh_surface",
           "refine_uniformly"]
