"""The .geo subset read by bearingfe's own parser and built through the gmsh API.

Expected values come from gmsh itself: the same file meshed by gmsh's own
script interpreter (the trusted path, ``trusted=True``) must give the same mesh
node for node (counts, coordinates, boundary edges per named group, area), and
the parser's arithmetic must give the numbers gmsh's interpreter gives for the
same expressions (read back from gmsh's model). Error cases name the line and
construct; the message texts are the package's.
"""


import re

import gmsh
import numpy as np
import pytest

from bearingfe import load_mesh
from bearingfe.geometry.errors import GeometryFileError, UntrustedGeoError
from bearingfe.geometry.geo_parser import parse_geo
from tests.helpers import ROOT

MESHES = ROOT / "meshes"

#: The built-in kernel with what the shipped files do not use: quarter ellipse arcs, a spline and a B-spline
#: through points made by a macro in a loop, lists and ranges, DefineConstant, ?:, Translate, and size fields
#: (a graded distance, a MathEval formula, their minimum).
BUILT_IN = """// built-in kernel
SetFactory("Built-in");
DefineConstant[ lc = {0.08, Min 0.01, Max 0.2, Name "Parameters/size"}, a = 0.4 ];
Mesh.MeshSizeMax = lc;
Mesh.Algorithm = 6;
c[] = {-0.5, -a, 0.5, a};
Point(1) = {c[0], c[1], 0, lc};
Point(2) = {c[2], c[1], 0, lc};
Point(3) = {c[2], c[3], 0, lc};
Point(4) = {c[0], c[3], 0, lc};
For k In {1:4}
  Line(k) = {k, k % 4 + 1};
EndFor
Curve Loop(1) = {1:4};
Point(10) = {-0.2, 0, 0, lc/2};
Point(11) = {-0.2 + 0.1, 0, 0, lc/2};
Point(12) = {-0.2, 0.06, 0, lc/2};
Point(13) = {-0.2 - 0.1, 0, 0, lc/2};
Point(14) = {-0.2, -0.06, 0, lc/2};
Ellipse(10) = {11, 10, 11, 12};
Ellipse(11) = {12, 10, 11, 13};
Ellipse(12) = {13, 10, 11, 14};
Ellipse(13) = {14, 10, 11, 11};
Curve Loop(2) = {10:13};
n = 6; r = 0.08; cy = 0;
pts[] = {};
Macro Ring
  For i In {0:n-1}
    p = newp;
    Point(p) = {0.2 + r * Cos(2*Pi*i/n), cy + r * Sin(2*Pi*i/n) * (i % 2 == 0 ? 1 : 0.8), 0, lc/2};
    pts[] += p;
  EndFor
Return
Call Ring;
Spline(20) = {pts[], pts[0]};
Curve Loop(3) = {20};
pts[] = {}; cy = -0.25;
Call Ring;
BSpline(21) = {pts[], pts[0]};
Curve Loop(4) = {21};
Plane Surface(1) = {1, 2, 3, 4};
Translate {0.01, 0, 0} { Point{10:14}; Curve{10:13}; }
Field[1] = Distance;
Field[1].CurvesList = {10:13, 20, 21};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = lc / 3;
Field[2].SizeMax = lc;
Field[2].DistMin = 0.02;
Field[2].DistMax = 0.2;
Field[3] = MathEval;
Field[3].F = "0.05 + 0.1 * x * x";
Field[4] = Min;
Field[4].FieldsList = {2, 3};
Background Field = 4;
Physical Curve("outer") = {1:4};
Physical Curve("arc_start") = {4};
Physical Curve("arc_end") = {2};
Physical Curve("side") = {1, 3};
Physical Curve("inlet") = {10:13, 20, 21};
Physical Surface("film") = {1};
"""

#: OpenCASCADE with a full circle and ellipse (newp after them counts the vertex OpenCASCADE gives each),
#: Rotate, Dilate, Symmetry, point sizes, an old option name and a numbered physical group.
OPENCASCADE = """SetFactory("OpenCASCADE");
lc = 0.06;
Mesh.CharacteristicLengthMax = lc;
Point(1) = {-0.5, -0.4, 0};
Point(2) = { 0.5, -0.4, 0};
Point(3) = { 0.5,  0.4, 0};
Point(4) = {-0.5,  0.4, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Circle(5) = {-0.25, 0, 0, 0.08};
Curve Loop(2) = {5};
Ellipse(6) = {0.2, 0.15, 0, 0.1, 0.05};
Rotate {{0, 0, 1}, {0.2, 0.15, 0}, Pi/4} { Curve{6}; }
Curve Loop(3) = {6};
q = newp;
Point(q) = {0.1, -0.25, 0};
Point(q + 1) = {0.3, -0.25, 0};
Point(q + 2) = {0.2, -0.15, 0};
Line(7) = {q, q + 1};
Line(8) = {q + 1, q + 2};
Line(9) = {q + 2, q};
Dilate {{0.2, -0.2, 0}, 1.2} { Curve{7:9}; }
Symmetry {1, 0, 0, 0} { Curve{7:9}; }
Curve Loop(4) = {7, 8, 9};
Plane Surface(1) = {1, 2, 3, 4};
Characteristic Length {1, 2} = lc / 2;
MeshSize {q:q+2} = lc / 3;
Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("side", 40) = {1, 3};
Physical Curve("inlet") = {5, 6, 7, 8, 9};
Physical Surface("film") = {1};
"""


def _area(sm) -> float:
    p, t = sm.mesh.p, sm.mesh.t
    u, v = p[:, t[1]] - p[:, t[0]], p[:, t[2]] - p[:, t[0]]
    return float(np.sum(np.abs(u[0] * v[1] - u[1] * v[0])) / 2)


def _same_mesh(ours, gmsh_own) -> None:
    assert ours.n_nodes == gmsh_own.n_nodes and ours.n_elements == gmsh_own.n_elements
    np.testing.assert_allclose(ours.mesh.p, gmsh_own.mesh.p, rtol=0, atol=1e-12)
    assert {k: len(v) for k, v in ours.boundaries.items()} == {k: len(v) for k, v in gmsh_own.boundaries.items()}
    assert _area(ours) == pytest.approx(_area(gmsh_own), rel=1e-12)


@pytest.mark.parametrize("name", sorted(p.name for p in MESHES.glob("*.geo")))
def test_shipped_geo_files_mesh_as_with_gmsh_interpreter(name):
    """Untrusted (parser + API) and trusted (gmsh's interpreter): the same mesh, at the file's size and at 0.2."""
    for size in (None, 0.2):
        _same_mesh(load_mesh(MESHES / name, size=size), load_mesh(MESHES / name, size=size, trusted=True))


@pytest.mark.parametrize("text", [BUILT_IN, OPENCASCADE], ids=["built-in", "opencascade"])
def test_the_subset_meshes_as_with_gmsh_interpreter(tmp_path, text):
    path = tmp_path / "subset.geo"
    path.write_text(text)
    ours, theirs = load_mesh(path), load_mesh(path, trusted=True)
    _same_mesh(ours, theirs)
    assert {"outer", "side", "inlet"} <= set(ours.boundaries) and ours.n_nodes > 400  # 657 and 441 nodes


def test_the_builder_knows_every_operation_the_parser_makes():
    """The two files above and the shipped slot (circle arcs) use every operation kind of the builder's table
    (bearingfe/geometry/geo_model.py), so the equality tests above build each one."""
    from bearingfe.geometry import geo_model

    table = set(re.findall(r"^``([a-z_]+)``\s", geo_model.__doc__, flags=re.MULTILINE))
    texts = (BUILT_IN, OPENCASCADE, (MESHES / "slot_pocket.geo").read_text())
    made = {op[0] for text in texts for op in parse_geo(text, "all.geo").ops}
    assert made == table and len(table) == 22


EXPRESSIONS = ["2^3^2", "-2^2", "2^-1", "7 % 3", "-7 % 3", "1 + 2 * 3 - 4 / 8", "(1 < 2) + (2 <= 2) + (3 > 4)",
               "(1 == 1) + 2 * (1 != 1) + 4 * (2 >= 3)", "1 && 0 || 1", "!0 + !3", "0 ? 2 : 3", "#c[] + c[2]",
               "Sqrt(16) + Atan2(1, 1)", "Fmod(7.5, 2) + Modulo(-7.5, 2)", "Floor(-1.5) + Ceil(1.2)",
               "Round(2.5) + 10 * Round(-2.5)", "Hypot(3, 4) + Min(3, 1) + Max(2, 5)", "Exp(1) * Log(2) + Log10(1000)",
               "Sin(Pi/6) + Cos(Pi/3) + Tan(Pi/4)", "Asin(1) + Acos(0) + Atan(1)", "Sinh(1) + Cosh(1) + Tanh(1)",
               "Fabs(-2) + Abs(-3)", "c[1] * newp", "1e-3 * .5e3 + 2.", "- - 3 + +2"]


def test_expressions_give_the_numbers_of_gmsh_interpreter(tmp_path):
    """Each expression becomes the x of a point: gmsh's interpreter (gmsh.open, in this process) and the parser
    must agree to 1e-12."""
    lines = ['SetFactory("Built-in");', "c[] = {1.5, 2, 3};", "x = 1;"]
    lines += [f"Point({k + 1}) = {{{e}, 0, 0}};" for k, e in enumerate(EXPRESSIONS)]
    n = len(EXPRESSIONS)
    lines += [f"Point({n + 1}) = {{0, 1, 0}};", f"Point({n + 2}) = {{1, 1, 0}};",
              f"Line(1) = {{1, 2}};", f"Line(2) = {{2, {n + 2}}};", f"Line(3) = {{{n + 2}, {n + 1}}};",
              f"Line(4) = {{{n + 1}, 1}};", "Curve Loop(1) = {1:4};", "Plane Surface(1) = {1};"]
    text = "\n".join(lines) + "\n"
    ours = {op[1]: op[2] for op in parse_geo(text, "expressions.geo").ops if op[0] == "point"}
    path = tmp_path / "expressions.geo"
    path.write_text(text)
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(path))
        theirs = {tag: gmsh.model.getValue(0, tag, [])[0] for _, tag in gmsh.model.getEntities(0)}
    finally:
        gmsh.finalize()
    for k, expression in enumerate(EXPRESSIONS):
        assert ours[k + 1] == pytest.approx(theirs[k + 1], rel=1e-12, abs=1e-12), expression


PLAIN = (MESHES / "plain_shoe.geo").read_text()  # 24 lines: a statement appended after "\n" is on line 26


@pytest.mark.parametrize("extra, error, match", [
    ("For i In {1:3}\nx = i;", GeometryFileError, r"line 28: the block is not closed \(expected EndFor\)"),
    ("EndIf", GeometryFileError, r"line 26: 'EndIf' without the For, If or Macro that opens it"),
    ("/* a comment that never ends", GeometryFileError, r"line 26: a /\* comment is not closed"),
    ('Physical Curve("open) = {1};', GeometryFileError, r"line 26: a string is not closed on its line"),
    ("x = 1\ny = 2;", GeometryFileError, r"line 27: expected ';' at the end of the statement, found 'y'"),
    ("Line(9) = {1, 99};", GeometryFileError, r"line 26: Line uses point 99, which is not defined above"),
    ("Point(1) = {0, 0, 0};", GeometryFileError, r"line 26: Point 1 is defined twice"),
    ("Point(0) = {0, 0, 0};", GeometryFileError, r"line 26: 0 is not an entity number"),
    ("Point(1.5) = {0, 0, 0};", GeometryFileError, r"line 26: 1.5 is not an entity number"),
    ("Point(9) = {0, 0};", GeometryFileError, r"line 26: Point\(9\) takes \{x, y, z\} or \{x, y, z, size\}, got 2"),
    ("x = {1:5:0};", GeometryFileError, r"line 26: a range with step 0 never ends"),
    ("x = Sqrt(-1);", GeometryFileError, r"line 26: Sqrt\(-1\) is not defined"),
    ("x = 1 / 0;", GeometryFileError, r"line 26: 1 / 0 is not defined"),
    ("x = 10^400;", GeometryFileError, r"line 26: 10\^400 is not defined"),
    ("x = 1e999;", GeometryFileError, r"line 26: '1e999' is not a finite number"),
    ("x[] = {1, 2};\ny = x[2];", GeometryFileError, r"line 27: x\[2\]: the index must be an integer in \[0, 1\]"),
    ("x[] = {1, 2};\ny = x + 1;", GeometryFileError, r"line 27: a list of 2 numbers where one number is expected"),
    ("Macro M\nCall M;\nReturn\nCall M;", GeometryFileError, r"line 27: macro calls nested more than 16 deep"),
    ("Mesh.ElementOrder = 5;", GeometryFileError, r"line 26: Mesh.ElementOrder = 5 is outside \[1, 2\]"),
    ("Characteristic Length {1} = 0;", GeometryFileError, r"line 26: a mesh size must be > 0, got 0"),
    ('SetFactory("OpenCASCADE");', UntrustedGeoError, r"line 26: 'SetFactory' after geometry"),
    ("Field[3].SizeMin = 1;", GeometryFileError, r"line 26: Field\[3\] is not defined above"),
    ("x = 1 @ 2;", GeometryFileError, r"line 26: unexpected character '@'"),
    ("x = 1;\n\n\t\x1b", GeometryFileError, r"line 28: control character U\+001B"),
])
def test_errors_name_the_line_and_the_construct(extra, error, match):
    with pytest.raises(error, match=r"^bad.geo " + match):
        parse_geo(PLAIN + "\n" + extra + "\n", "bad.geo")


def test_built_in_circle_needs_three_points():
    text = PLAIN.replace('SetFactory("OpenCASCADE");', 'SetFactory("Built-in");').replace(
        "Plane Surface(1) = {1};", "Circle(5) = {0, 0, 0, 0.1};\nPlane Surface(1) = {1};")
    with pytest.raises(GeometryFileError, match=r"Circle\(5\) takes the points \{start, centre, end\} or, with "
                                                r"SetFactory\(\"OpenCASCADE\"\), \{x, y, z, radius\[, angles\]\}; "
                                                r"got 4 numbers"):
        parse_geo(text, "circle.geo")


def test_a_file_without_a_plane_surface_is_refused():
    with pytest.raises(GeometryFileError, match=r"^empty.geo: no Plane Surface"):
        parse_geo("// nothing but a comment\n", "empty.geo")


def test_physical_groups_of_one_name_are_one_group():
    """gmsh merges statements that name the same group; the parser gives one operation with both curves."""
    ops = parse_geo(PLAIN + '\nPhysical Curve("edge") = {1};\nPhysical Curve("edge") = {2, 1};\n', "g.geo").ops
    assert [op for op in ops if op[0] == "physical" and op[3] == "edge"] == [["physical", 1, -1, "edge", [1, 2]]]
