"""Hostile geometry and solver inputs: refused with a named one-line error, nothing run or written.

Every .geo below starts from the shipped plain shoe and adds one statement that
reaches outside the geometry. A "marker" file is what the statement would
create if it ran: the tests check it is NOT there. Untrusted, bearingfe's own
parser reads the file (gmsh's interpreter never sees it) and refuses the
statement by name; the fuzz test feeds it random and mutated files. Meshes are
small (size 0.2).
"""

from __future__ import annotations

import math
import os
import re
from pathlib import Path

import numpy as np
import pytest

from bearingfe import Circle, CosineFilm, Rectangle, Slot, Surface, load_mesh, mesh_surface
from bearingfe.cli import main
from bearingfe.geometry.geofiles import (DEFAULT_MAX_ELEMENTS, GeometryFileError, MeshSizeError, UntrustedGeoError,
                                max_elements_limit)
from bearingfe.geometry.geo_parser import parse_geo
from tests.helpers import ROOT

PLAIN = (ROOT / "meshes" / "plain_shoe.geo").read_text()


def _geo(tmp_path: Path, extra: str, name: str = "hostile.geo") -> Path:
    path = tmp_path / name
    path.write_text(PLAIN + "\n" + extra + "\n")
    return path


# -- .geo commands that reach outside: refused before anything runs ----------------------------

HOSTILE = {
    "SystemCall": ('SystemCall "touch {marker}";', "runs a shell command"),
    "SystemCall Sprintf": ('SystemCall Sprintf("touch %s", "{marker}");', "runs a shell command"),
    "NonBlockingSystemCall": ('NonBlockingSystemCall "touch {marker}";', "runs a shell command"),
    "System (old alias)": ('System "touch {marker}";', "runs a shell command"),
    "lower-case command": ('systemcall "touch {marker}";', "not a geometry command"),
    "Save View": ('Save View[0] "{marker}";', "writes a file"),
    "OnelabRun": ('OnelabRun("x", "touch {marker}");', "runs an external program"),
    "Printf >": ('Printf("x") > "{marker}";', "writes to a file"),
    "Printf >> in If": ('If (1)\n Printf("x %g", lc) >> "{marker}";\nEndIf', "writes to a file"),
    "Save": ('Save "{marker}";', "writes a file"),
    "Print": ('Print "{marker}";', "writes a file"),
    "CreateDir": ('CreateDir "{marker}";', "creates a directory"),
    "Include": ('Include "{marker}";', "includes another file"),
    "Merge": ('Merge "{marker}";', "merges another file"),
    "ShapeFromFile": ('v() = ShapeFromFile("{marker}");', "reads another file"),
    "Exit": ("Exit;", "ends the program"),
    "Abort": ("Abort;", "ends the program"),
    "GetEnv": ('home = GetEnv("HOME");', "reads the environment"),
    "GetValue": ('x = GetValue("size?", 0.1);', "keyboard"),
    "Solver option": ('Solver.Executable0 = "touch {marker}";', "Solver. group"),
    "General option": ("General.Terminal = 1;", "General. group"),
    "text Mesh option": ('Mesh.Format = "{marker}";', "text value"),
    "ExternalProcess field": ("Field[1] = ExternalProcess;", "runs an external program"),
    "Plugin": ("Plugin(Crack).Run;", "plugin"),
    "GetEnv in DefineConstant": ('DefineConstant[ h = GetEnv("HOME") ];', "reads the environment"),
    "Exit in DefineConstant": ('DefineConstant[ h = {{Exit, Name "h"}} ];', "ends the program"),
    "unknown in DefineConstant": ('DefineConstant[ h = {{1, Name "h", Min Frobnicate}} ];',
                                  "not a variable given a value above"),
    "text DefineConstant": ('DefineConstant[ f = {{"{marker}", Name "x"}} ];', "text value in DefineConstant"),
    "DefineConstant attribute": ('DefineConstant[ f = {{1, Name "f", Macro "{marker}"}} ];',
                                 "not an accepted DefineConstant"),
    "DefineConstant call": ('DefineConstant[ f = {{1, Name "a"}} SystemCall "touch {marker}" ];',
                            "nothing may follow"),
    "DefineString": ('DefineString[ f = {{"{marker}"}} ];', "onelab"),
    "SetNumber": ('SetNumber("x", 1);', "onelab"),
    "Sleep": ("Sleep 1000;", "waits"),
    "unknown command": ("Frobnicate;", "not a geometry command"),
    "unknown function": ('x = StrCat("a", "b");', "not a geometry command"),
    "unknown variable": ("Point(99) = {{Frobnicate, 0, 0}};", "not a variable given a value above"),
    "Duplicata": ("Rotate {{{{0, 0, 1}}, {{0, 0, 0}}, Pi/2}} {{ Duplicata {{ Curve{{1}}; }} }}", "Duplicata"),
    "other shapes": ("Rectangle(2) = {{0, 0, 0, 1, 1}};", "not a geometry command"),
    "other options": ("Mesh.SaveAll = 1;", "not an accepted option"),
    "text field option": ('Field[1] = Box;\nField[1].VIn = "{marker}";', "text value"),
    "Physical Volume": ('Physical Volume("v") = {{1}};', "not a physical group of a 2-D geometry"),
    "SetFactory after geometry": ('SetFactory("Built-in");', "SetFactory' after geometry"),
}


@pytest.mark.parametrize("label", sorted(HOSTILE))
def test_hostile_geo_is_refused_and_nothing_runs(tmp_path, label):
    statement, reason = HOSTILE[label]
    marker = tmp_path / "marker"
    geo = _geo(tmp_path, statement.format(marker=marker))
    with pytest.raises(UntrustedGeoError, match=reason) as info:
        load_mesh(geo, size=0.2)
    message = str(info.value)
    # the statement is on line 26 (27 for the two-line ones): the plain shoe has 24 lines, then a blank one
    assert re.search(r"hostile.geo line 2[67]: ", message) and "trusted=True" in message and "--trust-geo" in message
    assert not marker.exists()


def test_cli_mesh_refuses_hostile_geo_in_one_line(tmp_path, capsys):
    marker, out = tmp_path / "marker", tmp_path / "m.msh"
    geo = _geo(tmp_path, f'SystemCall "touch {marker}";')
    assert main(["mesh", str(geo), "--size", "0.2", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "SystemCall" in err and "--trust-geo" in err and "Traceback" not in err
    assert not marker.exists() and not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == ["hostile.geo"]  # no temporary file left behind


def test_shipped_geo_files_are_read_by_the_parser():
    """Every shipped .geo is in the subset: OpenCASCADE, one plane surface, the named groups bearingfe reads."""
    for geo in sorted((ROOT / "meshes").glob("*.geo")):
        model = parse_geo(geo.read_text(), geo.name)  # raises if refused
        names = {op[3] for op in model.ops if op[0] == "physical"}
        assert model.factory == "occ" and {"outer", "arc_start", "arc_end", "side", "film"} <= names


def test_ordinary_geo_constructs_are_accepted():
    text = PLAIN + """
    Macro Grow
      k += 1;
    Return
    k = 0;
    For i In {1:3}
      Call Grow;
    EndFor
    If (k == 3)
      Printf("k = %g", k);
    EndIf
    pts[] = {};
    pts[] += newp;
    Mesh.ElementOrder = 1;
    Geometry.Tolerance = 1e-9;
    Field[1] = Distance;
    Field[1].CurvesList = {1};
    Background Field = 1;
    Rotate {{0, 0, 1}, {0, 0, 0}, Pi/2} { Curve{1}; }
    """
    ops = parse_geo(text, "ok.geo").ops
    # the loop ran the macro three times (k = 3), so the If's Printf ran: Printf is accepted and ignored
    assert ["option", "Mesh.ElementOrder", 1.0] in ops and ["field_numbers", 1, "CurvesList", [1.0]] in ops
    assert ["background", 1] in ops and ["rotate", [[1, 1]], 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, math.pi / 2] in ops


def test_numeric_define_constant_is_accepted_and_meshes_like_an_assignment(tmp_path):
    # gmsh's onelab parameters with numbers only: the mesh equals the one of the plain assignment lc = 0.05
    # (same script, same gmsh: node for node)
    parametrised = PLAIN.replace("lc = 0.05;", 'DefineConstant[ lc = {0.05, Min 0.01, Max 0.2, Step 0.01, '
                                 'Name "Parameters/element size", Units "-", Choices{0.05 = "fine", 0.1 = "coarse"}}, '
                                 'unused = 2 * Pi ];')
    assert parametrised != PLAIN
    plain = load_mesh(_geo(tmp_path, "", "plain.geo"))
    defined = load_mesh(_write(tmp_path / "defined.geo", parametrised))
    assert defined.n_nodes == plain.n_nodes
    np.testing.assert_allclose(defined.mesh.p, plain.mesh.p, atol=1e-12)


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


def test_trusted_geo_runs_in_a_child_that_exit_cannot_end(tmp_path):
    """``Exit;`` ends gmsh's process, not the caller: a named error, and this test keeps running."""
    geo = _geo(tmp_path, "Exit;")
    with pytest.raises(GeometryFileError, match="ended .* before it made a mesh"):
        load_mesh(geo, size=0.2, trusted=True)


def test_trusted_geo_may_write_files(tmp_path):
    """The trust flag is the documented way to run a script that writes (here: a Printf to a file)."""
    marker = tmp_path / "marker"
    geo = _geo(tmp_path, f'Printf("written") > "{marker}";')
    mesh = load_mesh(geo, size=0.2, trusted=True)
    assert marker.read_text().strip() == "written" and "outer" in mesh.boundaries


def test_trusted_geo_loop_that_does_not_end_hits_the_time_limit(tmp_path):
    geo = _geo(tmp_path, "For i In {1:3000}\nFor j In {1:3000}\nx = i + j;\nEndFor\nEndFor")
    with pytest.raises(GeometryFileError, match=r"did not finish within 1 s.*timeout=.*--geo-timeout"):
        load_mesh(geo, size=0.2, trusted=True, timeout=1)


def test_untrusted_geo_loop_stops_at_the_work_budget(tmp_path):
    """3000 x 3000 passes of a statement are more than MAX_GEO_STEPS = 2e6 steps: refused while reading,
    before gmsh starts (each pass counts at least one step: the budget is reached in 2e6 / 3000 < 667 outer passes)."""
    geo = _geo(tmp_path, "For i In {1:3000}\nFor j In {1:3000}\nx = i + j;\nEndFor\nEndFor")
    with pytest.raises(GeometryFileError, match=r"hostile.geo: reading the geometry takes more than 2000000 steps "
                                                 r"\(MAX_GEO_STEPS"):
        load_mesh(geo, size=0.2)


def test_untrusted_geo_reading_keeps_to_the_time_limit(tmp_path):
    """The parser checks the meshing time limit as it works. Time-free: a clock that advances 1 s at each look
    passes the 5 s limit at its sixth look, after about 6 x 1024 steps (it looks every 1024)."""
    from bearingfe.geometry.geofiles import read_geo

    looks = []

    def clock():
        looks.append(1)
        return float(len(looks))

    geo = _geo(tmp_path, "For i In {1:3000}\nFor j In {1:3000}\nx = i + j;\nEndFor\nEndFor")
    with pytest.raises(GeometryFileError, match=r"hostile.geo: reading the geometry did not finish within 5 s "
                                                 r".*timeout=.*--geo-timeout.*BEARINGFE_GEO_TIMEOUT"):
        read_geo(geo, timeout=5, clock=clock)
    assert len(looks) == 7  # the deadline (1 + 5) and six looks


def test_geo_time_limit_from_the_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("BEARINGFE_GEO_TIMEOUT", "nonsense")
    with pytest.raises(ValueError, match="BEARINGFE_GEO_TIMEOUT must be a number"):
        load_mesh(ROOT / "meshes" / "plain_shoe.geo", size=0.2)


def test_gmsh_error_is_a_one_line_error(tmp_path, capsys):
    geo = _geo(tmp_path, "Curve Loop(7) = {1, 3};\nPlane Surface(7) = {7};")  # parsed, but not a closed loop
    with pytest.raises(GeometryFileError, match="gmsh failed"):
        load_mesh(geo, size=0.2)
    out = tmp_path / "m.msh"
    assert main(["mesh", str(geo), "--size", "0.2", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "gmsh failed" in err and not out.exists()


# -- .msh files are data -------------------------------------------------------------------------

def test_msh_holding_a_geo_script_is_not_run(tmp_path):
    marker = tmp_path / "marker"
    fake = tmp_path / "x.msh"
    fake.write_text(PLAIN + f'\nSystemCall "touch {marker}";\n')
    with pytest.raises(GeometryFileError, match=r"x.msh is not a gmsh mesh file .*\$MeshFormat"):
        load_mesh(fake)
    assert not marker.exists()


def test_truncated_msh_is_a_named_error(tmp_path):
    good = tmp_path / "good.msh"
    assert main(["mesh", str(ROOT / "meshes" / "plain_shoe.geo"), "--size", "0.3", "--out", str(good)]) == 0
    bad = tmp_path / "bad.msh"
    bad.write_text(good.read_text()[: len(good.read_text()) // 2])
    with pytest.raises(GeometryFileError, match="bad.msh: not a readable gmsh mesh file"):
        load_mesh(bad)


def _msh_v2(path: Path, points, triangles, lines) -> Path:
    """A minimal MSH 2.2 file: physical curve 1 'outer' (lines), surface 2 'film' (triangles)."""
    rows = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", "2", '1 1 "outer"', '2 2 "film"',
            "$EndPhysicalNames", "$Nodes", str(len(points))]
    rows += [f"{k + 1} {x} {y} 0" for k, (x, y) in enumerate(points)]
    rows += ["$EndNodes", "$Elements", str(len(lines) + len(triangles))]
    k = 0
    for a, b in lines:
        k += 1
        rows.append(f"{k} 1 2 1 1 {a + 1} {b + 1}")
    for a, b, c in triangles:
        k += 1
        rows.append(f"{k} 2 2 2 1 {a + 1} {b + 1} {c + 1}")
    rows.append("$EndElements")
    path.write_text("\n".join(rows) + "\n")
    return path


SQUARE = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)]
FAN = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
OUTLINE = [(0, 1), (1, 2), (2, 3), (3, 0)]


def test_valid_msh_v2_reads(tmp_path):
    mesh = load_mesh(_msh_v2(tmp_path / "ok.msh", SQUARE, FAN, OUTLINE))
    assert mesh.n_elements == 4 and len(mesh.boundaries["outer"]) == 4
    assert float(np.sum(mesh.mesh.p[0])) == pytest.approx(2.5)  # 0+1+1+0+0.5: all five nodes kept


def test_duplicated_triangles_are_refused(tmp_path):
    path = _msh_v2(tmp_path / "dup.msh", SQUARE, FAN + [(4, 2, 1)], OUTLINE)  # (1, 2, 4) again, reordered
    with pytest.raises(GeometryFileError, match="dup.msh: 1 duplicated triangle"):
        load_mesh(path)


def test_degenerate_triangles_are_refused(tmp_path):
    points = SQUARE + [(0.25, 0.25)]  # on the segment from node 0 to node 4
    path = _msh_v2(tmp_path / "flat.msh", points, FAN + [(0, 5, 4)], OUTLINE)
    with pytest.raises(GeometryFileError, match="flat.msh: 1 degenerate \\(zero-area\\) triangle"):
        load_mesh(path)


def test_overlapping_triangles_are_refused(tmp_path):
    points = SQUARE + [(0.5, 0.2)]
    path = _msh_v2(tmp_path / "fold.msh", points, FAN + [(0, 1, 5)], OUTLINE)  # lies on top of (0, 1, 4)
    with pytest.raises(GeometryFileError, match="fold.msh: 1 inner edge.*same side"):
        load_mesh(path)
    points = SQUARE + [(0.5, 0.2), (0.5, 0.1)]
    path = _msh_v2(tmp_path / "three.msh", points, FAN + [(0, 1, 5), (0, 1, 6)], OUTLINE)
    with pytest.raises(GeometryFileError, match="three.msh: .*shared by more than two triangles"):
        load_mesh(path)


def test_msh_with_huge_element_count_is_refused(tmp_path):
    path = _msh_v2(tmp_path / "ok.msh", SQUARE, FAN, OUTLINE)
    with pytest.raises(MeshSizeError, match="max_elements = 3"):
        load_mesh(path, max_elements=3)


# -- element-count limit before meshing -------------------------------------------------------

def test_geo_with_tiny_size_is_refused_before_meshing(tmp_path, capsys):
    """``mesh --size 1e-4`` needs 0.8 / (sqrt(3)/4 * 1e-8) = 1.85e8 triangles on the 1 x 0.8 shoe."""
    with pytest.raises(MeshSizeError, match=r"about 1.85e\+08 triangles, more than max_elements = 1000000"):
        load_mesh(ROOT / "meshes" / "plain_shoe.geo", size=1e-4)
    out = tmp_path / "m.msh"
    assert main(["mesh", str(ROOT / "meshes" / "plain_shoe.geo"), "--size", "1e-4", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--max-elements" in err and "BEARINGFE_MAX_ELEMENTS" in err and err.count("\n") == 1


def test_geo_with_tiny_point_sizes_is_refused_before_meshing(tmp_path):
    """Sizes set on the points (no size option): 0.8 / (sqrt(3)/4 * 1e-8) triangles again."""
    geo = tmp_path / "fine.geo"
    geo.write_text(PLAIN.replace("lc = 0.05;", "lc = 1e-4;").replace("Mesh.MeshSizeMax = lc;", ""))
    with pytest.raises(MeshSizeError, match=r"about 1.8\de\+08 triangles"):
        load_mesh(geo)


def test_element_limit_can_be_raised_or_lowered(tmp_path, monkeypatch):
    geo = ROOT / "meshes" / "plain_shoe.geo"
    with pytest.raises(MeshSizeError, match="max_elements = 100"):
        load_mesh(geo, size=0.2, max_elements=100)  # 0.8 / (sqrt(3)/4 0.04) = 46 is the lower bound; gmsh > 100
    monkeypatch.setenv("BEARINGFE_MAX_ELEMENTS", "50")
    assert max_elements_limit() == 50
    with pytest.raises(MeshSizeError, match="max_elements = 50"):
        mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4), 0.1)  # 0.8 / (sqrt(3)/4 0.01) = 185
    monkeypatch.setenv("BEARINGFE_MAX_ELEMENTS", "many")
    with pytest.raises(ValueError, match="BEARINGFE_MAX_ELEMENTS must be a number > 0"):
        max_elements_limit()
    monkeypatch.delenv("BEARINGFE_MAX_ELEMENTS")
    assert max_elements_limit() == DEFAULT_MAX_ELEMENTS


def test_mesh_surface_with_tiny_size_is_refused_before_meshing():
    with pytest.raises(MeshSizeError, match=r"size = 0.0001 would need about 1.8\de\+08 triangles"):
        mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4), 1e-4)


def test_mesh_surface_element_estimate_is_close():
    """The estimate (film area / equilateral triangle of the size) against what gmsh makes: within 20 %."""
    from bearingfe.geometry.meshing import _estimated_triangles  # noqa: PLC2701 - white-box check of the estimate

    surface = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Circle((0.0, 0.0), 0.1)])
    mesh = mesh_surface(surface, 0.05)
    estimate = _estimated_triangles(surface, 0.05, 0.0125, 0.05, 0.2, None)
    assert estimate == pytest.approx(mesh.n_elements, rel=0.2)


# -- pockets too small to resolve ------------------------------------------------------------------

def test_pocket_too_small_is_refused():
    with pytest.raises(ValueError, match=r"Surface.inlets\[0\] \(Circle\) is 2e-09 across.*pocket size >= 0.0001"):
        Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Circle((0.0, 0.0), 1e-9)])
    with pytest.raises(ValueError, match=r"Surface.inlets\[0\] \(Polygon\)"):
        Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Rectangle((0.0, 0.0), (0.4, 1e-6))])
    # the sliver that gave "KeyError (-1, -1)" (its contour edges were not edges of the triangles)
    from bearingfe import Ellipse, Polygon

    with pytest.raises(ValueError, match=r"Surface.inlets\[0\] \(Polygon\) is .* across"):
        Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Polygon(((0.0, 0.0), (0.3, 0.0), (0.15, 1e-8)))])
    with pytest.raises(ValueError, match=r"Surface.inlets\[0\] \(Ellipse\) is .* across"):
        Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Ellipse((0.0, 0.0), (0.3, 1e-8))])


def test_scene_with_a_tiny_pocket_is_one_line(tmp_path, capsys, scene_file):
    scene = scene_file("reynolds", title="tiny pocket", surface={"inlets": {0: {"radius": 1e-9}}}, film={"phi0": None},
                       solver={"size": 0.2, "inlet_size": None, "element": None, "linear_solver": None},
                       output={"pictures": []})
    assert main(["run", str(scene), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "inlets[0] (Circle) is 2e-09 across" in err


def test_small_pocket_is_resolved_by_the_mesh():
    """A pocket of radius r at pressure 1 in a plain film: the inlet flow follows the radial
    log law, flow ~ 1 / ln(R / r), so r = 1e-3 -> 1e-2 raises it by about ln(R/1e-3) / ln(R/1e-2)
    (R ~ 0.4: 5.99 / 3.69 = 1.62). Before the pocket sizes capped the element size, both pockets
    were a single node of the mesh and the flows differed by 3 %."""
    from bearingfe import solve_reynolds

    flows = []
    for r in (1e-3, 1e-2):
        surface = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Circle((0.0, 0.0), r)])
        res = solve_reynolds(mesh_surface(surface, 0.1), CosineFilm(0.0), wedge=0.0, inlet_pressure=1.0)
        flows.append(res.flows["inlet"])
    assert flows[1] / flows[0] == pytest.approx(math.log(0.4 / 1e-3) / math.log(0.4 / 1e-2), rel=0.1)


def test_thin_slot_pocket_meshes_with_named_boundaries():
    """A slot 100 x thinner than the default size: the pocket contour stays an edge set of the mesh,
    with edges no longer than the slot's hydraulic diameter 4 area / perimeter (about 2e-3)."""
    surface = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Slot((0.0, 0.0), 0.3, 1e-3)])
    mesh = mesh_surface(surface, 0.1)
    width = surface.inlet_widths()[0]
    assert width == pytest.approx(2e-3, rel=0.01)
    # contour length 0.6 + pi 1e-3; gmsh's edges come out up to ~1.25 x the size asked for
    assert len(mesh.boundaries["inlet"]) >= 0.8 * 0.6 / width


# -- solver inputs: silly numbers are refused with the parameter and its range --------------------

@pytest.mark.parametrize("kwargs, match", [
    (dict(gamma=0.5, phi0=1e300), r"CosineFilm.phi0 must be an angle \[rad\] with \|CosineFilm.phi0\| <= 1e\+06"),
    (dict(gamma=0.5, phi0=-1e20), r"CosineFilm.phi0 must be an angle"),
    (dict(gamma=0.5, phi0=math.nan), r"CosineFilm.phi0 must be an angle"),
    (dict(gamma=1e300), r"CosineFilm.gamma must be a number in \[0, 1000\]"),
    (dict(gamma=-0.1), r"CosineFilm.gamma must be a number in \[0, 1000\]"),
])
def test_film_parameters_out_of_range(kwargs, match):
    with pytest.raises(ValueError, match=match):
        CosineFilm(**kwargs)


def test_film_angle_at_the_limit_keeps_its_digits():
    """At |phi0| = 1e6 rad (the limit) cos(phi - phi0) still agrees with the reduced angle to 1e-9:
    the spacing of doubles near 1e6 is 1.2e-10."""
    far = CosineFilm(0.5, 1e6)
    near = CosineFilm(0.5, math.remainder(1e6, 2 * math.pi))
    phi = np.linspace(-0.5, 0.5, 11)
    assert np.allclose(far.thickness(phi, 0 * phi), near.thickness(phi, 0 * phi), rtol=0, atol=1e-9)


@pytest.mark.parametrize("name, kwargs", [
    ("inlet_pressure", dict(inlet_pressure=1e308)),
    ("inlet_pressure", dict(inlet_pressure=-1e13)),
    ("wedge", dict(wedge=1e308)),
    (r"squeeze\[0\]", dict(squeeze=(1e308, 0.0))),
])
def test_fd_operating_point_out_of_range(name, kwargs):
    from bearingfe import solve_reynolds_fd

    surface = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Circle((0.0, 0.0), 0.1)])
    with pytest.raises(ValueError, match=rf"{name} must be a finite number with \|{name}\| <= 1e\+12"):
        solve_reynolds_fd(surface, CosineFilm(0.5), (21, 17), **kwargs)


def test_pump_rtol_out_of_range_is_named():
    from bearingfe import load_mechanism, simulate

    pump = load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    with pytest.raises(ValueError, match=r"rtol must be in \(0, 1\)"):
        simulate(pump, revolutions=0.1, rtol=10)


def test_pump_scene_with_rtol_10_is_one_line(tmp_path, capsys, scene_file):
    """``rtol = 10`` in a pump scene once leaked the private ``_FilmClosed`` as a traceback."""
    scene = scene_file("pump", run={"rtol": 10})  # the shipped scene, whatever rtol it uses, with rtol 10
    assert main(["run", str(scene), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "rtol must be in (0, 1)" in err and "_FilmClosed" not in err


def test_mesh_surface_algorithm_is_checked():
    with pytest.raises(ValueError, match="algorithm must be one of gmsh's 2D algorithms"):
        mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4), 0.2, algorithm=10)


# -- the thin-film resolution check -------------------------------------------------------------

def _one_triangle(points):
    """A SupportMesh-like holder of a single straight triangle (only ``.mesh`` is read)."""
    import skfem

    class Holder:
        mesh = skfem.MeshTri1(np.array(points, dtype=float).T, np.array([[0], [1], [2]]))

    return Holder()


def test_film_variation_closed_form():
    """One triangle with vertices at phi = pi (thinnest point of h = 1 + gamma cos phi) and pi + s:
    (h(pi + s) - h(pi)) / h(pi) = gamma (1 - cos s) / (1 - gamma), exactly (the corner at pi + s is the
    thickest vertex)."""
    from bearingfe.core.checks import film_variation

    gamma, s = 0.99, 0.1
    holder = _one_triangle([(math.pi, 0.0), (math.pi + s, 0.0), (math.pi, s)])
    variation, h_min, size = film_variation(holder, CosineFilm(gamma))
    assert variation == pytest.approx(gamma * (1 - math.cos(s)) / (1 - gamma), rel=1e-12)
    assert h_min == pytest.approx(1 - gamma, rel=1e-12) and size == pytest.approx(s * math.sqrt(2), rel=1e-12)


def test_resolution_check_warns_near_contact_only():
    """gamma = 1 - 1e-6 on a 0.05 mesh: across an element at the thinnest film h grows by about
    gamma s^2 / 2 / 1e-6 ~ 1e3 x h_min (limit 1). gamma = 0.5 on the same mesh changes by < 0.1."""
    from bearingfe import ResolutionWarning, check_resolution

    mesh = mesh_surface(Surface(arc=(2.0, 4.2), half_width=0.5), 0.05)
    with pytest.warns(ResolutionWarning, match=r"thin film is not resolved: .* where h = 1e-06"):
        message = check_resolution(mesh, CosineFilm(1 - 1e-6))
    assert "film_graded_size" in message
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", ResolutionWarning)
        assert check_resolution(mesh, CosineFilm(0.5)) is None


def test_gmsh_child_dies_with_its_parent(tmp_path):
    """A caller killed by SIGKILL (no chance to clean up) does not leave gmsh looping: the child
    process asked the kernel to kill it with its parent (Linux PR_SET_PDEATHSIG)."""
    import signal
    import subprocess
    import sys
    import time

    geo = _geo(tmp_path, "For i In {1:3000}\nFor j In {1:3000}\nx = i + j;\nEndFor\nEndFor")
    # trusted: gmsh's interpreter runs the loop in the child (untrusted, the parser would refuse it first)
    code = f"from bearingfe import load_mesh; load_mesh({str(geo)!r}, size=0.2, timeout=600, trusted=True)"
    parent = subprocess.Popen([sys.executable, "-c", code], cwd=ROOT)
    children = Path(f"/proc/{parent.pid}/task/{parent.pid}/children")
    child = None
    for _ in range(300):  # the child appears once bearingfe is imported (a few seconds at most)
        text = children.read_text().split() if children.exists() else []
        if text:
            child = int(text[0])
            break
        time.sleep(0.05)
    assert child is not None
    time.sleep(1.0)  # let it reach gmsh's loop
    parent.send_signal(signal.SIGKILL)
    parent.wait()
    for _ in range(100):
        if not Path(f"/proc/{child}").exists() or "Z" in Path(f"/proc/{child}/stat").read_text().split()[2]:
            break
        time.sleep(0.05)
    else:
        os.kill(child, signal.SIGKILL)  # the child this test started (through its parent)
        pytest.fail("the gmsh child outlived its killed parent")


@pytest.mark.parametrize("name, kwargs", [
    ("inlet_pressure", dict(inlet_pressure=1e308)),
    ("wedge", dict(wedge=-1e300)),
    (r"squeeze\[1\]", dict(squeeze=(0.0, 1e13))),
])
def test_solve_reynolds_operating_point_out_of_range(name, kwargs):
    from bearingfe import solve_reynolds

    mesh = mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[Circle((0.0, 0.0), 0.1)]), 0.2)
    with pytest.raises(ValueError, match=rf"{name} must be a finite number with \|{name}\| <= 1e\+12"):
        solve_reynolds(mesh, CosineFilm(0.5), **kwargs)


def test_near_contact_solve_warns_and_notes():
    """At gamma = 1 - 1e-6 the peak pressure changed 400 x with the mesh and nothing said so.
    Now every solve_reynolds warns and records it in the result's notes; a resolved film (gamma = 0.5
    on the same mesh: h changes by < 0.1 x h across any element) gets neither."""
    import warnings

    from bearingfe import ResolutionWarning, solve_reynolds

    mesh = mesh_surface(Surface(arc=(2.0, 4.2), half_width=0.5), 0.1)
    with pytest.warns(ResolutionWarning, match="thin film is not resolved") as record:
        res = solve_reynolds(mesh, CosineFilm(1 - 1e-6), cavitation="reynolds")
    assert record[0].filename == __file__  # the warning points at the caller's line
    assert any("thin film is not resolved" in note for note in res.notes)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ResolutionWarning)
        res = solve_reynolds(mesh, CosineFilm(0.5), cavitation="reynolds")
    assert not any("not resolved" in note for note in res.notes)


def test_command_hidden_behind_a_dot_is_refused():
    with pytest.raises(UntrustedGeoError, match="dot.geo line 26: 'Sleep' is not an accepted option"):
        parse_geo(PLAIN + "\nGeometry. Sleep 5;\n", "dot.geo")
    with pytest.raises(UntrustedGeoError, match="dot.geo line 26: 'SystemCall' is not an accepted option"):
        parse_geo(PLAIN + '\nMesh. SystemCall Sprintf("touch x");\n', "dot.geo")


def test_scene_with_tiny_mesh_size_is_one_line(tmp_path, capsys, scene_file):
    """``size = 1e-4`` in a scene: 0.8 / (sqrt(3)/4 1e-8) = 1.85e8 triangles, refused before gmsh starts."""
    scene = scene_file("reynolds", title="too fine", surface={"inlets": None}, film={"phi0": None},
                       operating={"inlet_pressure": None},
                       solver={"size": 1e-4, "inlet_size": None, "element": None, "linear_solver": None},
                       output={"pictures": []})
    assert main(["run", str(scene), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "1.85e+08 triangles" in err and "BEARINGFE_MAX_ELEMENTS" in err


def test_mesh_command_killed_while_meshing_leaves_nothing_beside_out(tmp_path):
    """``bearingfe mesh`` killed by SIGKILL while gmsh works (no chance to clean up): gmsh wrote into a
    private temporary folder, so the --out folder holds only what was there before (the .geo)."""
    import signal
    import subprocess
    import sys
    import time

    geo = _geo(tmp_path, "For i In {1:3000}\nFor j In {1:3000}\nx = i + j;\nEndFor\nEndFor")
    out = tmp_path / "m.msh"
    parent = subprocess.Popen([sys.executable, "-m", "bearingfe.cli", "mesh", str(geo), "--size", "0.2",
                               "--out", str(out), "--geo-timeout", "600", "--trust-geo"], cwd=ROOT)
    children = Path(f"/proc/{parent.pid}/task/{parent.pid}/children")
    for _ in range(300):  # gmsh's child appears once bearingfe is imported (a few seconds at most)
        if children.exists() and children.read_text().split():
            break
        time.sleep(0.05)
    else:
        parent.kill()
        pytest.fail("the gmsh child never started")
    time.sleep(1.0)  # let it reach gmsh's loop
    parent.send_signal(signal.SIGKILL)
    assert parent.wait() == -signal.SIGKILL
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hostile.geo"]


# -- untrusted .geo text: lexer corners, size, linear work, fuzz -------------------------------------

def test_nul_in_a_comment_hides_no_command(tmp_path, capsys):
    """The reported reproduction: gmsh's lexer ends a // comment at NUL, so a command after it ran. bearingfe's
    parser refuses control characters anywhere, comments included, naming the line; nothing runs."""
    marker, out = tmp_path / "pwned", tmp_path / "o.msh"
    evil = tmp_path / "evil.geo"
    evil.write_bytes(b'// note\x00SystemCall "touch ' + str(marker).encode() + b'";\n' + PLAIN.encode())
    assert main(["mesh", str(evil), "--size", "0.2", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "evil.geo line 1: control character U+0000" in err and "Traceback" not in err
    with pytest.raises(GeometryFileError, match=r"evil.geo line 1: control character U\+0000"):
        load_mesh(evil, size=0.2)
    assert not marker.exists() and not out.exists()


CORNERS = {  # where a checker's lexer could differ from gmsh's: each either refused or harmless comment/text
    "carriage return in //": b"// note\rSystemCall \"touch {marker}\";\n",
    "form feed in //": b"// note\x0cSystemCall \"touch {marker}\";\n",
    "vertical tab in //": b"// note\x0bSystemCall \"touch {marker}\";\n",
    "NUL in /* */": b"/* note\x00 */ SystemCall \"touch {marker}\";\n",
    "backslash line end in //": b"// note \\\nSystemCall \"touch {marker}\";\n",
    "1023-character string": b"Physical Curve(\"" + b"a" * 1023 + b"\") = {1}; SystemCall \"touch {marker}\";\n",
    "string across a line": b"Printf(\"a\nSystemCall \"touch {marker}\";\n\");\n",
    "DEL character": b"x = 1;\x7fSystemCall \"touch {marker}\";\n",
    "UTF-8 line separator": "// note\u2028SystemCall \"touch {marker}\";\n".encode(),
    "not UTF-8": b"// note \xff\xfe\nSystemCall \"touch {marker}\";\n",
}


@pytest.mark.parametrize("label", sorted(CORNERS))
def test_lexer_corners_hide_no_command(tmp_path, label):
    """The refusals name the line; the one file accepted (the command inside a comment, as its text says)
    meshes the plain shoe. Either way the marker is never written."""
    marker = tmp_path / "marker"
    geo = tmp_path / "corner.geo"
    geo.write_bytes(CORNERS[label].replace(b"{marker}", str(marker).encode()) + PLAIN.encode())
    try:
        mesh = load_mesh(geo, size=0.2)
    except GeometryFileError as exc:
        assert re.match(r"corner.geo line \d+: ", str(exc)), str(exc)
    else:
        assert label in ("carriage return in //", "form feed in //", "UTF-8 line separator") and mesh.n_nodes == 415
    assert not marker.exists()


def test_geo_file_size_is_capped(tmp_path):
    """MAX_GEO_BYTES = 1e6: one byte more (a long comment) is refused before it is parsed."""
    from bearingfe.geometry.geo_parser import MAX_GEO_BYTES

    geo = tmp_path / "big.geo"
    geo.write_text("//" + "x" * (MAX_GEO_BYTES - 2 - len(PLAIN) - 1) + "\n" + PLAIN)
    assert geo.stat().st_size == MAX_GEO_BYTES
    assert load_mesh(geo, size=0.3).n_nodes > 0  # exactly at the limit: read
    geo.write_text("//" + "x" * (MAX_GEO_BYTES - 2 - len(PLAIN)) + "\n" + PLAIN)
    with pytest.raises(GeometryFileError, match=r"big.geo is larger than the 1000000 bytes a .geo file may have "
                                                 r"\(MAX_GEO_BYTES\)"):
        load_mesh(geo, size=0.3)


def _steps(text: str) -> tuple[int, str]:
    """The parser's operation count for ``text`` and how the read ended."""
    from bearingfe.geometry.geo_parser import Work

    work = Work()
    try:
        parse_geo(text, "steps.geo", work=work)
        outcome = "read"
    except GeometryFileError as exc:
        outcome = str(exc)
    return work.steps, outcome


def test_reading_x_paren_is_linear():
    """The reported quadratic case: 'x(' repeated 8,000 times took the allow-list 16 s. The parser lexes each
    token once and refuses at nesting 40: its step count grows by exactly 2 per 'x(' (two tokens), so from
    4,000 to 8,000 to 16,000 the differences double exactly (no term in n^2)."""
    runs = [_steps("x(" * n) for n in (4000, 8000, 16000)]
    assert all("nested more than 40 deep (MAX_NESTING)" in outcome for _, outcome in runs)
    (s1, _), (s2, _), (s4, _) = runs
    assert s2 - s1 == 2 * 4000 and s4 - s2 == 2 * 8000


def test_reading_a_geometry_is_linear_in_its_size():
    """k copies of a block (points, lines, a loop, expressions, a bounded loop) after the plain shoe: every copy
    costs the same number of steps, so the differences between k = 50, 100, 200 double exactly."""
    block = ("p = newp; Point(p) = {{0.1 + {k} * 1e-3, 0.2, 0, lc / 2}};\n"
             "Point(p + 1) = {{0.1, 0.2 + Sqrt({k}) * 1e-3, 0}};\n"
             "Line(newl) = {{p, p + 1}}; s = 0; For i In {{1:5}} s += i^2 % 3; EndFor\n"
             "If (s > 3) x[] = {{1:4}}; ElseIf (s < 0) x[] = {{}}; Else x[] = {{}}; EndIf\n")
    counts = []
    for k in (50, 100, 200):
        steps, outcome = _steps(PLAIN + "".join(block.format(k=j) for j in range(k)))
        assert outcome == "read"
        counts.append(steps)
    assert counts[2] - counts[1] == 2 * (counts[1] - counts[0]) > 0


def test_trusted_geo_runs_in_its_own_session_with_an_empty_environment(tmp_path, monkeypatch):
    """--trust-geo keeps gmsh's interpreter, in a child that leads its own session (killed as a whole) and
    gets none of the caller's environment (a variable set here is not there; shell built-ins only: no PATH)."""
    monkeypatch.setenv("BEARINGFE_PROBE", "secret")
    env, sid = tmp_path / "env.txt", tmp_path / "sid.txt"
    geo = _geo(tmp_path, f'SystemCall "export -p > {env}; read -r a b c d e s rest < /proc/$$/stat; '
                         f'echo $s > {sid}";')
    load_mesh(geo, size=0.3, trusted=True)
    exported = env.read_text()
    assert "BEARINGFE_PROBE" not in exported and "HOME=" not in exported and "PYTHONPATH='" + str(ROOT) not in exported
    assert int(sid.read_text()) != os.getsid(0)


# the fuzz test: random bytes, token soups and mutated shipped files; every input is either read into the
# geometry operations below or refused with a GeometryFileError, within the work budget, touching no file,
# process or environment on the way

#: Operation kinds of the gmsh model builder (bearingfe/geometry/geo_model.py, its module table).
OPERATIONS = {"point", "line", "circle_arc", "circle", "ellipse_arc", "ellipse", "spline", "bspline", "curve_loop",
              "plane_surface", "rotate", "translate", "dilate", "symmetry", "physical", "size", "option", "field",
              "field_number", "field_numbers", "field_string", "background"}

FUZZ_WORDS = (
    "Point Line Circle Ellipse Spline BSpline Curve Loop Plane Surface Physical Characteristic Length MeshSize "
    "Rotate Translate Dilate Symmetry Field Background Mesh Geometry SetFactory DefineConstant For In EndFor If "
    "ElseIf Else EndIf Macro Function Return Call Printf Name Min Max Choices Pi newp newl news newreg Sqrt Cos "
    "SystemCall System NonBlockingSystemCall OnelabRun Include Merge Save Print Exit Abort GetEnv GetValue Sleep "
    "Plugin Delete CreateDir ShapeFromFile Sprintf StrCat Duplicata Rectangle ExternalProcess Structured "
    "General Solver MeshSizeMax Algorithm Distance Threshold MathEval CurvesList InField lc x i p "
    "( ) [ ] {{ }} , ; = += -= ++ -- . : ? ! ^ % # + - * / < > == && || // /* */ \\ \" ' "
    "0 1 2 -1 0.5 1e9 1e-9 1e308 1e999 2147483648 .5 1.e3"
).split()
CONTROL = [chr(c) for c in range(32) if c not in (9, 10)] + ["\x7f", "\u2028", "\ufeff"]


def _mutations(rng, count):
    """``count`` shipped files, their comments removed, with a few edits: insert a word or character, delete or
    repeat a span."""
    shipped = [re.sub(r"//[^\n]*", "", p.read_text()) for p in sorted((ROOT / "meshes").glob("*.geo"))]
    for _ in range(count):
        text = rng.choice(shipped)
        for _ in range(rng.randrange(1, 4)):
            k = rng.randrange(len(text))
            edit = rng.randrange(4)
            if edit == 0:
                text = text[:k] + " " + rng.choice(FUZZ_WORDS).replace("{{", "{") + " " + text[k:]
            elif edit == 1:
                text = text[:k] + rng.choice(CONTROL + list("(){}[];,=\"/*\n")) + text[k:]
            elif edit == 2:
                text = text[:k] + text[k + rng.randrange(1, 30):]
            else:
                text = text[:k] + text[k:k + rng.randrange(1, 60)] * rng.randrange(2, 6) + text[k:]
        yield text


def _fuzz_texts(rng):
    for _ in range(300):  # random bytes, read as Latin-1: every byte value, NUL and controls included
        yield bytes(rng.randrange(256) for _ in range(rng.randrange(1, 400))).decode("latin-1")
    for _ in range(400):  # token soups, with control characters now and then
        words = [rng.choice(FUZZ_WORDS if rng.random() < 0.97 else CONTROL) for _ in range(rng.randrange(1, 80))]
        yield rng.choice(["", PLAIN + "\n"]) + " ".join(words).replace("{{", "{").replace("}}", "}")
    yield from _mutations(rng, 500)
    for n in (10, 39, 40, 41, 500, 2000):  # nesting of every kind, at and past MAX_NESTING = 40
        yield "x = " + "(" * n + "1" + ")" * n + ";\n" + PLAIN
        yield "x[] = " + "{" * n + "1" + "}" * n + ";\n" + PLAIN
        yield "x = " + "-" * n + "1;\n" + PLAIN
        yield "x = " + "2^" * n + "1;\n" + PLAIN
        yield "x = " + "1 ? " * n + "1" + " : 0" * n + ";\n" + PLAIN
        yield "For i In {1:1}\n" * n + "x = 1;\n" + "EndFor\n" * n + PLAIN
        yield "If (1)\n" * n + "x = 1;\n" + "EndIf\n" * n + PLAIN
        yield "x = Sqrt(" * n + "1" + ")" * n + ";\n" + PLAIN
        yield "x = 1" + " + 1" * n + ";\n" + PLAIN  # a long flat sum: no nesting, read
    for n in (1023, 1024, 5000, 20000):  # long strings, comments, names, numbers
        yield f'Physical Curve("{"a" * n}") = {{1}};\n' + PLAIN
        yield "// " + "x" * n + "\n" + PLAIN
        yield "/* " + "*" * n + " */\n" + PLAIN
        yield "/* " + "x" * n + "\n" + PLAIN
        yield "a" * n + " = 1;\n" + PLAIN
        yield "x = " + "9" * n + ";\n" + PLAIN
        yield '"' * n + PLAIN
    yield "Macro M\nCall M;\nReturn\nCall M;\n" + PLAIN  # a macro that calls itself
    yield "For i In {1:1e12}\nEndFor\n" + PLAIN  # a loop of 1e12 passes
    yield "x[] = {1:3e6};\n" + PLAIN  # a list of 3e6 values


def _only_geometry(model) -> None:
    """Every operation is one the builder knows, with plain numbers and short printable names only."""
    from bearingfe.geometry.geo_parser import FIELD_KINDS, OPTIONS

    def plain(value):
        if isinstance(value, list):
            return all(plain(v) for v in value)
        if isinstance(value, str):
            return value.isprintable() and len(value) <= 256 and '"' not in value
        return isinstance(value, (int, float)) and math.isfinite(value)

    assert model.factory in ("occ", "geo")
    for op in model.ops:
        assert op[0] in OPERATIONS and plain(op[1:]), op
        if op[0] == "option":
            assert op[1] in OPTIONS
        if op[0] == "field":
            assert op[2] in FIELD_KINDS
        if op[0] == "field_string":
            assert op[2] == "F"


def test_fuzz_reads_geometry_or_refuses_by_name(monkeypatch):
    """1,285 inputs from a fixed seed: each one is read into geometry operations (checked above) or
    refused with a GeometryFileError, within MAX_GEO_STEPS; no other exception, and no file opened, process
    started, environment read or exit on the way (those calls fail the test while the parser runs)."""
    import builtins
    import random
    import subprocess
    import sys

    from bearingfe.geometry.geo_parser import MAX_GEO_STEPS, Work

    def forbidden(*args, **kwargs):
        raise AssertionError(f"the parser reached outside: {args!r}")

    rng = random.Random(20261128)
    texts = list(_fuzz_texts(rng))
    outcomes = {"read": 0, "refused": 0}
    with monkeypatch.context() as m:
        for target, name in ((builtins, "open"), (os, "open"), (os, "system"), (os, "getenv"), (os, "execv"),
                             (os, "fork"), (subprocess, "Popen"), (sys, "exit"), (os, "_exit")):
            m.setattr(target, name, forbidden)
        for text in texts:
            work = Work()
            try:
                model = parse_geo(text, "fuzz.geo", work=work)
            except GeometryFileError as exc:
                assert str(exc).startswith("fuzz.geo"), str(exc)
                outcomes["refused"] += 1
            else:
                _only_geometry(model)
                outcomes["read"] += 1
            assert work.steps <= MAX_GEO_STEPS
    assert len(texts) == 1285 and outcomes["read"] >= 30 and outcomes["refused"] > 1000, outcomes


def test_fuzzed_files_that_read_mesh_or_fail_by_name(tmp_path):
    """Some of the mutated files the parser reads, meshed for real: a mesh or a GeometryFileError (gmsh's own
    error, the element limit), never another exception; a marker the hazards would write never appears."""
    import random

    from bearingfe.geometry.geofiles import MeshSizeError

    shipped = {re.sub(r"//[^\n]*", "", p.read_text()) for p in (ROOT / "meshes").glob("*.geo")}
    meshed = 0
    for text in _mutations(random.Random(7), 2000):
        if meshed == 4:
            break
        try:
            parse_geo(text, "fuzz.geo")
        except GeometryFileError:
            continue
        if text in shipped:
            continue  # an edit that changed nothing
        geo = tmp_path / f"fuzz{meshed}.geo"
        geo.write_text(text)
        meshed += 1
        try:
            load_mesh(geo, size=0.2, max_elements=20000)
        except (GeometryFileError, MeshSizeError, ValueError) as exc:
            assert "Traceback" not in str(exc)
    assert meshed == 4
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"fuzz{k}.geo" for k in range(4)]


def test_geo_that_is_not_a_regular_file_is_not_read(tmp_path):
    """A named pipe called x.geo would block the reader for ever (no time limit covers a blocked open)."""
    from bearingfe.geometry.geofiles import read_geo

    pipe = tmp_path / "x.geo"
    os.mkfifo(pipe)
    with pytest.raises(GeometryFileError, match="x.geo is not a regular file"):
        read_geo(pipe)
