"""Hostile-but-fair inputs, round two: mesh readers that must not end the process, meshes no solver can
use, guards shared by every solver path, named errors that name the user's input, and signals.

Meshes are tiny (a unit square of four triangles, written as MSH 2.2 text here); solves use the coarse
shoe meshes of the other hostile tests. Where a test expects a number, the comment says where it comes from.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
import skfem

from bearingfe import SupportMesh, load_mesh
from bearingfe.geometry.geofiles import GeometryFileError, read_msh

#: A unit square cut into four triangles around its centre, its outline as the 'outer' curve.
SQUARE = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)]
FAN = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
OUTLINE = [(0, 1), (1, 2), (2, 3), (3, 0)]


def _msh(path: Path, points, triangles, lines) -> Path:
    """A minimal MSH 2.2 file: physical curve 1 'outer' (lines), surface 2 'film' (triangles);
    ``points`` are (x, y) or (x, y, z)."""
    rows = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", "2", '1 1 "outer"', '2 2 "film"',
            "$EndPhysicalNames", "$Nodes", str(len(points))]
    rows += [f"{k + 1} {' '.join(map(str, (tuple(p) + (0.0,))[:3]))}" for k, p in enumerate(points)]
    rows += ["$EndNodes", "$Elements", str(len(lines) + len(triangles))]
    for k, (a, b) in enumerate(lines):
        rows.append(f"{k + 1} 1 2 1 1 {a + 1} {b + 1}")
    for k, (a, b, c) in enumerate(triangles):
        rows.append(f"{len(lines) + k + 1} 2 2 2 1 {a + 1} {b + 1} {c + 1}")
    rows.append("$EndElements")
    path.write_text("\n".join(rows) + "\n")
    return path


# -- mesh reading never ends the process ---------------------------------------------------------------

def test_msh_that_meshio_answers_with_exit_is_a_named_error(tmp_path, capfd):
    # meshio's own reader calls sys.exit(1) on this file (checked with meshio.read: SystemExit(1))
    bad = tmp_path / "bad.msh"
    bad.write_text("$MeshFormat\n4.1 0 8\n$EndMeshFormat\nhello\n")
    with pytest.raises(GeometryFileError, match="bad.msh: not a readable gmsh mesh file"):
        load_mesh(bad)
    assert capfd.readouterr() == ("", "")  # library code prints nothing


def test_any_reader_exit_becomes_a_named_error(tmp_path, monkeypatch):
    import meshio.gmsh

    def exits(path):
        print("Error: gave up")
        sys.exit(1)

    monkeypatch.setattr(meshio.gmsh, "read", exits)
    with pytest.raises(GeometryFileError, match="ok.msh: not a readable gmsh mesh file \\(Error: gave up\\)"):
        read_msh(_msh(tmp_path / "ok.msh", SQUARE, FAN, OUTLINE))


# -- meshes no solver can use are refused by name --------------------------------------------------------

def test_msh_with_nodes_off_the_plane_is_refused(tmp_path):
    lifted = SQUARE[:4] + [(0.5, 0.5, 0.3)]  # the centre node 0.3 above the plane
    with pytest.raises(GeometryFileError, match="up.msh: node 4 lies off the plane \\(third coordinate 0.3\\)"):
        load_mesh(_msh(tmp_path / "up.msh", lifted, FAN, OUTLINE))
    rounded = SQUARE[:4] + [(0.5, 0.5, 1e-12)]  # round-off of a flat mesh: read
    assert load_mesh(_msh(tmp_path / "flat.msh", rounded, FAN, OUTLINE)).n_elements == 4


def test_detached_island_without_a_fixed_boundary_is_refused(tmp_path):
    # a second square two units to the right, its outline not in any physical curve
    island = [(x + 2.0, y) for x, y in SQUARE]
    fan = FAN + [(a + 5, b + 5, c + 5) for a, b, c in FAN]
    with pytest.raises(GeometryFileError, match="island.msh: 1 detached piece.*node at \\(2, 0\\)"):
        load_mesh(_msh(tmp_path / "island.msh", SQUARE + island, fan, OUTLINE))
    # with its outline named 'outer' too, each piece has its pressure fixed: read
    outline = OUTLINE + [(a + 5, b + 5) for a, b in OUTLINE]
    assert load_mesh(_msh(tmp_path / "two.msh", SQUARE + island, fan, outline)).n_elements == 8


def _square_mesh(points=SQUARE, triangles=FAN) -> skfem.MeshTri1:
    return skfem.MeshTri1(np.array(points, dtype=float).T, np.array(triangles).T)


def test_api_meshes_are_checked_like_files():
    good = _square_mesh()
    outer = good.boundary_facets()
    assert SupportMesh(good.with_boundaries({"outer": outer})).n_elements == 4
    with pytest.raises(GeometryFileError, match="no boundary named 'outer'"):
        SupportMesh(good)
    flat = _square_mesh(SQUARE + [(0.25, 0.25)], FAN + [(0, 5, 4)])  # node 5 on the segment 0-4
    with pytest.raises(GeometryFileError, match="1 degenerate \\(zero-area\\) triangle"):
        SupportMesh(flat.with_boundaries({"outer": flat.boundary_facets()}))
    island = _square_mesh(SQUARE + [(x + 2.0, y) for x, y in SQUARE], FAN + [(a + 5, b + 5, c + 5) for a, b, c in FAN])
    rim = island.boundary_facets()
    first = rim[(island.facets[:, rim] < 5).all(axis=0)]  # the outline of the first square only
    with pytest.raises(GeometryFileError, match="api: 1 detached piece"):
        SupportMesh(island.with_boundaries({"outer": first}), source="api")
    assert SupportMesh(island.with_boundaries({"outer": rim})).n_elements == 8
    with pytest.raises(GeometryFileError, match="must be a scikit-fem MeshTri1 or MeshTri2, got MeshQuad1"):
        SupportMesh(skfem.MeshQuad1())


# -- every exception that can escape is a public error of a family the command line reports ----------------

def test_transient_exceptions_are_runtime_errors():
    # the command line turns RuntimeError into "failed: ..." (exit 1); a bare Exception was a traceback
    from bearingfe.transient import FilmClosed, NoEquilibrium, TrialRejected

    assert all(issubclass(e, RuntimeError) for e in (TrialRejected, FilmClosed, NoEquilibrium))
