"""The support surface and its meshes: outlines and pockets, gmsh meshing, untrusted geometry files.

================  ============================================================
module            what it does
================  ============================================================
``surface``       Support-surface geometry in unwrapped non-dimensional coordinates.
``runner``        How the runner (the moving surface facing the support) slides over the support's plane.
``errors``        Errors of geometry files: a file that cannot be used, a ``.geo`` construct refused as untrusted.
``geofiles``      Geometry files from users: ``.geo`` files read by bearingfe and meshed apart, ``.msh`` read as data.
``geo_parser``    Reader of the ``.geo`` subset bearingfe meshes from untrusted files: text in, geometry operations out.
``geo_model``     Building a gmsh model through the gmsh API from the operations of ``geo_parser`` (in the child).
``gmsh_worker``   Child process in which gmsh meshes: a ``.geo`` file (built, or trusted: interpreted), the shoe body.
``locate``        Points on a triangle mesh: the cell that holds a point, field values there, cell sizes.
``meshing``       Meshing support surfaces with gmsh and reading meshes into scikit-fem.
================  ============================================================
"""

from __future__ import annotations

from .runner import Rotating, Runner, Translating
from .surface import AnnularSector, Circle, Ellipse, Polygon, Recess, Rectangle, Shape, Slot, Surface
from .errors import GeometryFileError, UntrustedGeoError
from .geofiles import MeshSizeError
from .meshing import SupportMesh, grid_mesh, load_mesh, mesh_surface, refine_uniformly

__all__ = ["AnnularSector", "Rotating", "Runner", "Translating", "Circle", "Ellipse", "Polygon", "Recess", "Rectangle", "Shape", "Slot", "Surface", "GeometryFileError",
           "MeshSizeError", "UntrustedGeoError", "SupportMesh", "grid_mesh", "load_mesh", "mesh_surface",
           "refine_uniformly"]
