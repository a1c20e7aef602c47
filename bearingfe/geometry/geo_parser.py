"""Reader of the ``.geo`` subset bearingfe meshes from untrusted files: text in, plain geometry operations out.

gmsh's ``.geo`` language is a program (shell commands, file reads and writes,
``Exit``); an untrusted file never reaches gmsh's interpreter. This module
reads the geometry subset below with its own lexer and parser and turns it
into a list of operations (plain JSON data) that
:mod:`bearingfe.geometry.geo_model` builds through the gmsh API in the child
process. Anything else is refused by name (:class:`UntrustedGeoError`, naming
file, line and construct); text that is not valid ``.geo`` is a
:class:`GeometryFileError`. No other exception escapes :func:`parse_geo`.

The subset (docs/geometry_files.md)
-----------------------------------
* ``SetFactory("OpenCASCADE")`` or ``SetFactory("Built-in")``, before any geometry;
* ``Point``, ``Line``, ``Circle`` (three points; with OpenCASCADE also centre and
  radius), ``Ellipse`` (four points; with OpenCASCADE also centre and radii),
  ``Spline``, ``BSpline``, ``Curve Loop`` / ``Line Loop``, ``Plane Surface``;
* ``Rotate``, ``Translate``, ``Dilate``, ``Symmetry`` of ``Point``/``Curve``/``Line``/``Surface`` lists;
* ``Physical Point``/``Curve``/``Line``/``Surface`` with a name and/or a number;
* ``Characteristic Length {points} = size;`` and ``MeshSize {points} = size;``;
* size fields ``Field[n] = Kind;`` of the kinds :data:`FIELD_KINDS`, ``Field[n].Option = value;``
  and ``Background Field = n;``; numeric options :data:`OPTIONS` (``Mesh.MeshSizeMax = 0.05;``);
* numeric variables and lists (``x = 1;``, ``p[] = {1, 2};``, ``p[] += {3};``, ``p[1]``, ``#p[]``,
  ``{1:5:2}``), ``newp``-style tags, arithmetic, comparisons and the functions of :data:`FUNCTIONS`;
  ``DefineConstant[...]`` with numeric values;
* ``For ... EndFor`` over a finite range, ``If ... ElseIf ... Else ... EndIf``,
  ``Macro``/``Function`` ... ``Return`` and ``Call``; ``Printf("...", ...);`` (ignored), ``Mesh 2;`` (ignored).

Limits
------
:data:`MAX_GEO_BYTES` of text, :data:`MAX_NESTING` levels of brackets and blocks, :data:`MAX_CALL_DEPTH`
macro calls, and :data:`MAX_GEO_STEPS` steps of work (tokens read, statements run, values computed) under
the caller's deadline (:class:`Work`): lexing and parsing are linear in the file size, and loops stop at the
budget, so reading a file is bounded whatever it holds.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass
from typing import Callable

from .errors import GeometryFileError, UntrustedGeoError

__all__ = ["MAX_GEO_BYTES", "MAX_GEO_STEPS", "MAX_NESTING", "MAX_CALL_DEPTH", "FUNCTIONS", "OPTIONS",
           "FIELD_KINDS", "Work", "GeoModel", "parse_geo"]

#: Largest ``.geo`` file read [bytes] (the shipped ones are about 1.5 kB).
MAX_GEO_BYTES = 1_000_000

#: Work budget of one file [steps]: tokens read, statements run, values computed and list elements made.
MAX_GEO_STEPS = 2_000_000

#: Deepest nesting of brackets, operators and blocks (``For``/``If``/``Macro`` bodies).
MAX_NESTING = 40

#: Deepest chain of macro calls (a macro that calls itself stops here).
MAX_CALL_DEPTH = 16

#: Longest string (a physical group name, a Printf format, a MathEval formula) [characters].
MAX_STRING = 256

#: Longest number literal or name [characters].
MAX_WORD = 100

#: The functions of expressions and their number of arguments.
FUNCTIONS: dict[str, tuple[int, Callable[..., float]]] = {
    "Sqrt": (1, math.sqrt), "Exp": (1, math.exp), "Log": (1, math.log), "Log10": (1, math.log10),
    "Sin": (1, math.sin), "Cos": (1, math.cos), "Tan": (1, math.tan), "Asin": (1, math.asin),
    "ArcSin": (1, math.asin), "Acos": (1, math.acos), "ArcCos": (1, math.acos), "Atan": (1, math.atan),
    "ArcTan": (1, math.atan), "Atan2": (2, math.atan2), "ArcTan2": (2, math.atan2), "Sinh": (1, math.sinh),
    "Cosh": (1, math.cosh), "Tanh": (1, math.tanh), "Fabs": (1, abs), "Abs": (1, abs),
    "Floor": (1, lambda x: float(math.floor(x))), "Ceil": (1, lambda x: float(math.ceil(x))),
    "Round": (1, lambda x: float(math.floor(x + 0.5))), "Fmod": (2, math.fmod), "Modulo": (2, math.fmod),
    "Hypot": (2, math.hypot), "Min": (2, min), "Max": (2, max),
}

#: Numeric options a file may set, with the accepted range of each (gmsh's names; old aliases map to them).
OPTIONS: dict[str, tuple[float, float]] = {
    "Mesh.MeshSizeMax": (1e-12, 1e22), "Mesh.MeshSizeMin": (0.0, 1e22), "Mesh.MeshSizeFactor": (1e-6, 1e6),
    "Mesh.MeshSizeFromPoints": (0, 1), "Mesh.MeshSizeFromCurvature": (0, 1000),
    "Mesh.MeshSizeExtendFromBoundary": (-3, 3), "Mesh.Algorithm": (1, 11), "Mesh.ElementOrder": (1, 2),
    "Mesh.MinimumCirclePoints": (0, 1000), "Mesh.MinimumCurvePoints": (0, 1000),
    "Mesh.MinimumElementsPerTwoPi": (0, 1000), "Mesh.Smoothing": (0, 100), "Mesh.Optimize": (0, 1),
    "Mesh.RandomFactor": (0, 1), "Mesh.SecondOrderLinear": (0, 1), "Mesh.AngleToleranceFacetOverlap": (0, 1),
    "Geometry.Tolerance": (0, 1), "Geometry.ToleranceBoolean": (0, 1), "Geometry.AutoCoherence": (0, 2),
    "Geometry.OCCFixDegenerated": (0, 1), "Geometry.OCCFixSmallEdges": (0, 1), "Geometry.OCCFixSmallFaces": (0, 1),
}

_OPTION_ALIASES = {
    "Mesh.CharacteristicLengthMax": "Mesh.MeshSizeMax", "Mesh.CharacteristicLengthMin": "Mesh.MeshSizeMin",
    "Mesh.CharacteristicLengthFactor": "Mesh.MeshSizeFactor",
    "Mesh.CharacteristicLengthFromPoints": "Mesh.MeshSizeFromPoints",
    "Mesh.CharacteristicLengthFromCurvature": "Mesh.MeshSizeFromCurvature",
    "Mesh.CharacteristicLengthExtendFromBoundary": "Mesh.MeshSizeExtendFromBoundary",
}

#: Size-field kinds a file may create (they compute sizes from the geometry and numbers only).
FIELD_KINDS = frozenset({"Attractor", "Ball", "Box", "Constant", "Cylinder", "Distance", "Frustum", "MathEval",
                         "Max", "Min", "Restrict", "Threshold"})

#: Words of gmsh's language that are refused, and why (the others are refused as "not in the subset").
_HAZARDS = {
    "SystemCall": "runs a shell command", "System": "runs a shell command",
    "NonBlockingSystemCall": "runs a shell command", "OnelabRun": "runs an external program",
    "OnelabAction": "drives an external (onelab) client", "ExternalProcess": "runs an external program",
    "Include": "includes another file", "Merge": "merges another file", "MergeWithBoundingBox": "merges another file",
    "ShapeFromFile": "reads another file", "ListFromFile": "reads another file", "Structured": "reads a file",
    "PostView": "reads post-processing views", "Save": "writes a file", "Print": "writes a file",
    "CreateDir": "creates a directory", "Delete": "deletes", "Exit": "ends the program that reads the file",
    "Abort": "ends the program that reads the file", "GetEnv": "reads the environment",
    "FileExists": "looks at the file system", "AbsolutePath": "looks at the file system",
    "CurrentDir": "looks at the file system", "CurrentDirectory": "looks at the file system",
    "CurrentFileName": "looks at the file system", "DirName": "looks at the file system",
    "GetValue": "waits for keyboard input", "GetStringValue": "waits for keyboard input", "Sleep": "waits",
    "DefineNumber": "drives onelab parameters", "DefineString": "drives onelab parameters",
    "GetNumber": "drives onelab parameters", "GetString": "drives onelab parameters",
    "SetNumber": "drives onelab parameters", "SetString": "drives onelab parameters",
    "UndefineConstant": "drives onelab parameters", "Plugin": "runs a gmsh plugin (plugins read and write files)",
    "NewModel": "replaces the model", "SetName": "renames the model",
}

#: Other words of gmsh's language (commands, shapes, meshing constraints, string functions): not in the subset.
_GMSH_WORDS = frozenset("""
    Affine Bezier Box BooleanCoherence BooleanCommon BooleanCut BooleanDifference BooleanFragments BooleanFuse
    BooleanIntersection BooleanSection BooleanUnion CatmullRom Chamfer Coherence Color Compound Cone Cylinder Disk
    Duplicata Ellipsis Error Extrude Fillet Hide Hole In Knots Layers LinSpace List LogSpace LowerCase Nurbs Order
    Parametric Periodic Recombine Rectangle RefineMesh Recursive Reverse ReverseMesh Ruled Show Smoother Sphere Step
    Str StrCat StrChoice StrCmp StrFind StrLen StrPrefix StrRelative StrReplace StrSub Sprintf Surface ThruSections
    Torus Transfinite Unique UpperCase Using Volume Warning Wedge Wire Rand Exists Find NameToString StringToName
    N2S S2N GetForced GetForcedStr FixRelativePath GmshExecutableName Loop Alternate Progression Bump Beta
""".split())

_STATEMENTS = ("Point, Line, Circle, Ellipse, Spline, BSpline, Curve Loop, Plane Surface, Physical, Characteristic "
               "Length, MeshSize, Rotate, Translate, Dilate, Symmetry, Field, Background Field, Mesh./Geometry. "
               "options, SetFactory, DefineConstant, variables, For, If, Macro, Call, Printf")

_TRUST = ("If you trust this file, pass trusted=True (load_mesh) or --trust-geo (bearingfe mesh) to run it in "
          "gmsh's own interpreter")

_CONTROL = re.compile(r"[\x00-\x08\x0b\x0e-\x1f\x7f]")
_TOKEN = re.compile(r"""
    (?P<space>[ \t\r\f]+|\n)
  | (?P<comment>//[^\n]*|/\*(?:[^*]|\*(?!/))*\*/)
  | (?P<badcomment>/\*)
  | (?P<str>"[^"\n]*")
  | (?P<badstr>")
  | (?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z_0-9]*)
  | (?P<op>\+\+|--|\+=|-=|\*=|/=|==|!=|<=|>=|&&|\|\||[-+*/%^(){}\[\],;=<>!?:.\#])
  | (?P<bad>.)
""", re.VERBOSE)

#: Binary operators by precedence (gmsh's): higher binds tighter; ``^`` is right-associative (handled apart).
_BINARY = {"||": 1, "&&": 2, "==": 3, "!=": 3, "<": 4, ">": 4, "<=": 4, ">=": 4, "+": 5, "-": 5, "*": 6, "/": 6,
           "%": 6}

_NEW = {"newp": "point", "newl": "curve", "newc": "curve", "newll": "loop", "newcl": "loop", "news": "surface",
        "newreg": "any", "newf": "field"}

_DIMS = {"Point": 0, "Curve": 1, "Line": 1, "Surface": 2}


@dataclass
class Work:
    """The operation count of one read, its budget and its deadline.

    Attributes
    ----------
    limit : int
        Largest number of steps [-] (:data:`MAX_GEO_STEPS`).
    deadline : float, optional
        Value of ``clock()`` [s] after which reading stops (the time limit of meshing).
    seconds : float, optional
        The time limit [s], for the message.
    clock : callable
        Seconds now [s] (``time.monotonic``).
    steps : int
        Steps counted so far.
    name : str
        The file's name, first in the messages (set by :func:`parse_geo`).
    """

    limit: int = MAX_GEO_STEPS
    deadline: float | None = None
    seconds: float | None = None
    clock: Callable[[], float] = time.monotonic
    steps: int = 0
    name: str = "<geo>"
    _next_check: int = 1024

    def tick(self, n: int = 1) -> None:
        """Count ``n`` steps; past the budget or the deadline, raise :class:`GeometryFileError`."""
        self.steps += n
        if self.steps > self.limit:
            raise GeometryFileError(
                f"{self.name}: reading the geometry takes more than {self.limit} steps (MAX_GEO_STEPS: a loop "
                f"or list too long for a geometry file?)")
        if self.deadline is not None and self.steps >= self._next_check:
            self._next_check = self.steps + 1024
            if self.clock() > self.deadline:
                within = "the time limit" if self.seconds is None else f"{self.seconds:g} s"
                raise GeometryFileError(
                    f"{self.name}: reading the geometry did not finish within {within} (a loop that "
                    f"does not end?); raise the limit with timeout= (load_mesh), --geo-timeout (bearingfe mesh) "
                    f"or the environment variable BEARINGFE_GEO_TIMEOUT")


@dataclass
class GeoModel:
    """What a ``.geo`` file describes, as operations for :func:`bearingfe.geometry.geo_model.build`.

    Attributes
    ----------
    factory : str
        ``"occ"`` (OpenCASCADE) or ``"geo"`` (gmsh's built-in kernel).
    ops : list of list
        The operations in file order (plain JSON data; the first element of each is its kind).
    steps : int
        Steps of work the read took (:class:`Work`).
    """

    factory: str
    ops: list
    steps: int = 0


@dataclass(frozen=True)
class _Tok:
    kind: str
    text: str
    line: int


def _show(text: str) -> str:
    """The user's text for a message: printable and at most 40 characters."""
    text = text if len(text) <= 40 else text[:37] + "..."
    return "".join(c if c.isprintable() else f"\\x{ord(c):02x}" for c in text)


class _Reader:
    """Lexer and recursive-descent parser: tokens to a tree of statements (nothing is evaluated)."""

    def __init__(self, text: str, name: str, work: Work):
        self.name, self.work = name, work
        self.toks = self._lex(text)
        self.pos, self.depth = 0, 0

    # -- errors ------------------------------------------------------------------------------------

    def error(self, tok: _Tok, what: str) -> GeometryFileError:
        return GeometryFileError(f"{self.name} line {tok.line}: {what}")

    def refuse(self, tok: _Tok, what: str | None = None) -> UntrustedGeoError:
        word = _show(tok.text)
        reason = what or _HAZARDS.get(tok.text) or "is not a geometry command of the subset bearingfe reads"
        return UntrustedGeoError(
            f"{self.name} line {tok.line}: '{word}' {reason}; an untrusted .geo file may only use: {_STATEMENTS}. "
            f"{_TRUST}")

    # -- lexer ---------------------------------------------------------------------------------------

    def _lex(self, text: str) -> list[_Tok]:
        bad = _CONTROL.search(text)
        if bad:
            line = text.count("\n", 0, bad.start()) + 1
            raise GeometryFileError(
                f"{self.name} line {line}: control character U+{ord(bad.group()):04X} (a .geo file is text: only "
                f"tabs, line ends and printable characters are accepted, also in comments)")
        out, line = [], 1
        for m in _TOKEN.finditer(text):
            kind, value = m.lastgroup, m.group()
            if kind == "space" or kind == "comment":
                line += value.count("\n")
                continue
            tok = _Tok(kind, value, line)
            if kind == "badcomment":
                raise self.error(tok, "a /* comment is not closed")
            if kind == "badstr":
                raise self.error(tok, "a string is not closed on its line")
            if kind == "bad":
                raise self.error(tok, f"unexpected character '{_show(value)}'")
            if kind == "str" and len(value) - 2 > MAX_STRING:
                raise self.error(tok, f"a string longer than {MAX_STRING} characters (MAX_STRING)")
            if kind in ("num", "name") and len(value) > MAX_WORD:
                raise self.error(tok, f"'{_show(value)}' is longer than {MAX_WORD} characters")
            out.append(tok)
            if len(out) % 1024 == 0:  # the deadline holds while lexing too
                self.work.tick(1024)
        self.work.tick(len(out) % 1024 + 1)
        out.append(_Tok("end", "end of file", line))
        return out

    # -- token access --------------------------------------------------------------------------------

    @property
    def tok(self) -> _Tok:
        return self.toks[self.pos]

    def peek(self, k: int = 1) -> _Tok:
        return self.toks[min(self.pos + k, len(self.toks) - 1)]

    def next(self) -> _Tok:
        tok = self.toks[self.pos]
        if tok.kind != "end":
            self.pos += 1
        self.work.tick()
        return tok

    def at(self, *texts: str) -> bool:
        return self.tok.kind in ("op", "name") and self.tok.text in texts

    def expect(self, text: str, after: str = "") -> _Tok:
        if not self.at(text):
            raise self.error(self.tok, f"expected '{text}'{' ' + after if after else ''}, found "
                                       f"'{_show(self.tok.text)}'")
        return self.next()

    def word(self) -> _Tok:
        if self.tok.kind != "name":
            raise self.error(self.tok, f"expected a name, found '{_show(self.tok.text)}'")
        return self.next()

    def string(self) -> str:
        if self.tok.kind != "str":
            raise self.error(self.tok, f"expected a string in double quotes, found '{_show(self.tok.text)}'")
        return self.next().text[1:-1]

    def enter(self) -> None:
        self.depth += 1
        if self.depth > MAX_NESTING:
            raise self.error(self.tok, f"brackets, operators or blocks nested more than {MAX_NESTING} deep "
                                       f"(MAX_NESTING)")

    def leave(self) -> None:
        self.depth -= 1

    # -- statements ----------------------------------------------------------------------------------

    def program(self) -> list:
        body = self.block(())
        if self.tok.kind != "end":
            raise self.error(self.tok, f"'{_show(self.tok.text)}' without the statement that opens it")
        return body

    def block(self, ends: tuple[str, ...]) -> list:
        body = []
        while self.tok.kind != "end" and not (self.tok.kind == "name" and self.tok.text in ends):
            if self.at(";"):
                self.next()
                continue
            body.append(self.statement())
        return body

    def statement(self) -> tuple:
        tok = self.tok
        if tok.kind != "name":
            raise self.error(tok, f"a statement cannot start with '{_show(tok.text)}'")
        handler = getattr(self, "s_" + tok.text, None)
        if handler is not None and tok.text[0].isupper():
            return handler()
        if tok.text in ("EndFor", "EndIf", "Else", "ElseIf", "Return"):
            raise self.error(tok, f"'{tok.text}' without the For, If or Macro that opens it")
        if tok.text in _HAZARDS or tok.text in _GMSH_WORDS:
            raise self.refuse(tok)
        if self.peek().text == ".":
            raise self.refuse(tok, f"sets options of the {_show(tok.text)}. group (only the numeric Mesh. and "
                                   f"Geometry. options of the subset are accepted)")
        if self.peek().text in ("=", "+=", "-=", "*=", "/=", "++", "--", "[") or (
                self.peek().text == "(" and not tok.text[0].isupper()):
            return self.assignment()
        raise self.refuse(tok)

    def end(self) -> None:
        self.expect(";", "at the end of the statement")

    def s_SetFactory(self) -> tuple:
        tok = self.next()
        self.expect("(")
        kind = self.string()
        self.expect(")")
        self.end()
        kinds = {"OpenCASCADE": "occ", "Built-in": "geo", "Geo": "geo"}
        if kind not in kinds:
            raise self.refuse(tok, f"with \"{_show(kind)}\" names no kernel (accepted: \"OpenCASCADE\", \"Built-in\")")
        return ("factory", tok, kinds[kind])

    def _entity(self, kind: str, tok: _Tok) -> tuple:
        if self.at("{"):
            raise self.refuse(tok, f"with {{...}} (a list of entities: In, embedding, Delete) is not in the subset; "
                                   f"define entities with {tok.text}(tag) = {{...}}")
        self.expect("(")
        tag = self.expr()
        self.expect(")")
        self.expect("=")
        items = self.braces()
        self.end()
        return ("entity", tok, kind, tag, items)

    def s_Point(self) -> tuple:
        return self._entity("point", self.next())

    def s_Line(self) -> tuple:
        tok = self.next()
        if self.at("Loop"):
            self.next()
            return self._entity("curve_loop", tok)
        return self._entity("line", tok)

    def s_Curve(self) -> tuple:
        tok = self.next()
        if not self.at("Loop"):
            raise self.refuse(tok, "is only accepted as 'Curve Loop' (curves are Line, Circle, Ellipse, Spline)")
        self.next()
        return self._entity("curve_loop", tok)

    def s_Circle(self) -> tuple:
        return self._entity("circle", self.next())

    def s_Ellipse(self) -> tuple:
        return self._entity("ellipse", self.next())

    def s_Spline(self) -> tuple:
        return self._entity("spline", self.next())

    def s_BSpline(self) -> tuple:
        return self._entity("bspline", self.next())

    def s_Plane(self) -> tuple:
        tok = self.next()
        if not self.at("Surface"):
            raise self.refuse(tok, "is only accepted as 'Plane Surface'")
        self.next()
        return self._entity("plane_surface", tok)

    def s_Physical(self) -> tuple:
        tok = self.next()
        kind = self.tok
        if kind.text not in _DIMS:
            raise self.refuse(kind, "is not a physical group of a 2-D geometry (Point, Curve, Line, Surface)")
        self.next()
        self.expect("(")
        label, number = None, None
        if self.tok.kind == "str":
            label = self.string()
            if self.at(","):
                self.next()
                number = self.expr()
        else:
            number = self.expr()
        self.expect(")")
        self.expect("=")
        items = self.braces()
        self.end()
        return ("physical", tok, _DIMS[kind.text], label, number, items)

    def s_Characteristic(self) -> tuple:
        tok = self.next()
        self.expect("Length", "after 'Characteristic'")
        return self._size(tok)

    def s_MeshSize(self) -> tuple:
        return self._size(self.next())

    def _size(self, tok: _Tok) -> tuple:
        items = self.braces()
        self.expect("=")
        value = self.expr()
        self.end()
        return ("size", tok, items, value)

    def _transform(self, kind: str) -> tuple:
        tok = self.next()
        args = self.braces()
        self.expect("{")
        shapes = []
        while not self.at("}"):
            word = self.tok
            if word.text == "Duplicata":
                raise self.refuse(word, "is not in the subset (copies need tags from the model; write the "
                                        "copied entities out)")
            if word.text not in _DIMS:
                raise self.refuse(word, "is not a shape list of the subset (Point{...}, Curve{...}, Line{...}, "
                                        "Surface{...})")
            self.next()
            shapes.append((_DIMS[word.text], self.braces()))
            self.end()
        self.next()
        if self.at(";"):
            self.next()
        return ("transform", tok, kind, args, shapes)

    def s_Rotate(self) -> tuple:
        return self._transform("rotate")

    def s_Translate(self) -> tuple:
        return self._transform("translate")

    def s_Dilate(self) -> tuple:
        return self._transform("dilate")

    def s_Symmetry(self) -> tuple:
        return self._transform("symmetry")

    def s_Field(self) -> tuple:
        tok = self.next()
        self.expect("[")
        tag = self.expr()
        self.expect("]")
        if self.at("="):
            self.next()
            kind = self.word()
            if kind.text not in FIELD_KINDS:
                raise self.refuse(kind, (f"is a size field that {_HAZARDS[kind.text]}" if kind.text in _HAZARDS
                                         else "is not a size field of the subset")
                                  + f" (accepted: {', '.join(sorted(FIELD_KINDS))})")
            self.end()
            return ("field", tok, tag, kind.text)
        self.expect(".", "or '=' after Field[...]")
        option = self.word()
        self.expect("=")
        if self.tok.kind == "str":
            value = ("str", self.string())
        elif self.at("{"):
            value = ("list", self.braces())
        else:
            value = ("expr", self.expr())
        self.end()
        return ("field_option", tok, tag, option.text, value)

    def s_Background(self) -> tuple:
        tok = self.next()
        self.expect("Field", "after 'Background'")
        self.expect("=")
        value = self.expr()
        self.end()
        return ("background", tok, value)

    def s_Mesh(self) -> tuple:
        if self.peek().text == ".":
            return self._option()
        tok = self.next()
        self.expr()  # Mesh 2; meshes now in gmsh: bearingfe meshes after reading the file
        self.end()
        return ("nop", tok)

    def s_Geometry(self) -> tuple:
        return self._option()

    def _option(self) -> tuple:
        group = self.next()
        self.expect(".")
        option = self.word()
        full = f"{group.text}.{option.text}"
        if self.at("=") and self.peek().kind == "str":
            raise self.refuse(self.peek(), f"is a text value for the option {full} (only numbers are accepted)")
        full = _OPTION_ALIASES.get(full, full)
        if full not in OPTIONS:
            raise self.refuse(option, f"is not an accepted option (the numeric options accepted: "
                                      f"{', '.join(sorted(OPTIONS))})")
        self.expect("=")
        value = self.expr()
        self.end()
        return ("option", group, full, value)

    def s_Printf(self) -> tuple:
        tok = self.next()
        self.expect("(")
        self.string()
        while self.at(","):
            self.next()
            self.expr()
        self.expect(")")
        if self.at(">", ">>"):
            raise self.refuse(tok, "writes to a file (> or >> after the message)")
        self.end()
        return ("nop", tok)

    def s_DefineConstant(self) -> tuple:
        tok = self.next()
        self.expect("[")
        entries = []
        while True:
            target = self.word()
            self.expect("=")
            if self.at("{"):
                entries.append((target, self._constant_braces()))
            elif self.tok.kind == "str":
                raise self.refuse(self.tok, "is a text value in DefineConstant[...] (only numbers are accepted)")
            else:
                entries.append((target, ("constant", self.expr(), [])))
            if not self.at(",", "]"):
                raise self.refuse(self.tok, "in DefineConstant[...]: nothing may follow a value but ',' or ']'")
            if not self.at(","):
                break
            self.next()
        self.expect("]", "closing DefineConstant[")
        self.end()
        return ("constants", tok, entries)

    def _constant_braces(self) -> tuple:
        """``{value, Name "...", Min 0, Choices{1, 2 = "label"}, ...}``: the value; the attributes are checked."""
        self.next()
        if self.tok.kind == "str":
            raise self.refuse(self.tok, "is a text value in DefineConstant[...] (only numbers are accepted)")
        value = self.expr()
        checked = []
        while self.at(","):
            self.next()
            attribute = self.tok
            if attribute.text in ("Name", "Label", "Help", "Units", "Highlight"):
                self.next()
                self.string()
            elif attribute.text in ("Min", "Max", "Step", "Visible", "ReadOnly", "Closed", "ReadOnlyRange"):
                self.next()
                checked.append(self.expr())
            elif attribute.text == "Choices":
                self.next()
                self.expect("{")
                while not self.at("}"):
                    checked.append(self.expr())
                    if self.at("="):
                        self.next()
                        self.string()
                    if not self.at(","):
                        break
                    self.next()
                self.expect("}")
            else:
                raise self.refuse(attribute, "is not an accepted DefineConstant attribute (accepted: Name, Label, "
                                             "Help, Units, Highlight, Min, Max, Step, Visible, ReadOnly, Closed, "
                                             "ReadOnlyRange, Choices)")
        if not self.at("}"):
            raise self.refuse(self.tok, "in DefineConstant[...]: nothing may follow the value and its attributes")
        self.next()
        return ("constant", value, checked)

    def s_For(self) -> tuple:
        tok = self.next()
        var = None
        if self.at("("):
            self.next()
            items = self._range(")")
        else:
            var = self.word().text
            self.expect("In", "after the loop variable")
            self.expect("{")
            items = self._range("}")
        body = self._body(("EndFor",))
        self.expect("EndFor")
        return ("for", tok, var, items, body)

    def _range(self, close: str) -> list:
        start = self.expr()
        self.expect(":", "in a loop range (For i In {a:b} or {a:b:step})")
        stop = self.expr()
        step = None
        if self.at(":"):
            self.next()
            step = self.expr()
        self.expect(close)
        return [("range", start, stop, step)]

    def _body(self, ends: tuple[str, ...]) -> list:
        self.enter()
        body = self.block(ends)
        self.leave()
        if self.tok.kind == "end":
            raise self.error(self.tok, f"the block is not closed (expected {' or '.join(ends)})")
        return body

    def s_If(self) -> tuple:
        tok = self.next()
        branches = [(self._condition(), self._body(("ElseIf", "Else", "EndIf")))]
        otherwise: list = []
        while self.at("ElseIf"):
            self.next()
            branches.append((self._condition(), self._body(("ElseIf", "Else", "EndIf"))))
        if self.at("Else"):
            self.next()
            otherwise = self._body(("EndIf",))
        self.expect("EndIf")
        return ("if", tok, branches, otherwise)

    def _condition(self) -> tuple:
        self.expect("(")
        cond = self.expr()
        self.expect(")")
        return cond

    def s_Macro(self) -> tuple:
        tok = self.next()
        if self.tok.kind == "str":
            label = self.string()
        else:
            label = self.word().text
        body = self._body(("Return",))
        self.expect("Return")
        return ("macro", tok, label, body)

    s_Function = s_Macro

    def s_Call(self) -> tuple:
        tok = self.next()
        label = self.string() if self.tok.kind == "str" else self.word().text
        self.end()
        return ("call", tok, label)

    def assignment(self) -> tuple:
        target = self.next()
        index, whole = None, False
        if self.at("[", "("):
            close = "]" if self.next().text == "[" else ")"
            if self.at(close):
                whole = True
            else:
                index = self.expr()
            self.expect(close)
        op = self.tok
        if op.text in ("++", "--") and index is None and not whole:
            self.next()
            self.end()
            return ("incr", target, 1.0 if op.text == "++" else -1.0)
        if op.text not in ("=", "+=", "-=", "*=", "/="):
            raise self.error(op, f"expected '=' after '{_show(target.text)}', found '{_show(op.text)}'")
        self.next()
        if self.tok.kind == "str":
            raise self.refuse(self.tok, "is a text value (variables hold numbers only)")
        value = ("list", self.braces()) if self.at("{") else ("expr", self.expr())
        self.end()
        return ("assign", target, index, whole, op.text, value)

    # -- lists and expressions -----------------------------------------------------------------------

    def braces(self) -> list:
        """``{item, ...}``: expressions, ranges ``a:b[:step]``, whole lists ``p[]`` and nested braces."""
        self.expect("{")
        self.enter()
        items: list = []
        while not self.at("}"):
            if self.at("{"):
                items.append(("braces", self.braces()))
            elif self.tok.kind == "name" and self.peek().text in ("[", "(") and self.peek(2).text in ("]", ")") \
                    and self.tok.text not in FUNCTIONS:
                items.append(("whole", self.next()))
                self.next()
                self.next()
            else:
                first = self.expr()
                if self.at(":"):
                    self.next()
                    stop = self.expr()
                    step = None
                    if self.at(":"):
                        self.next()
                        step = self.expr()
                    items.append(("range", first, stop, step))
                else:
                    items.append(("expr", first))
            if not self.at(","):
                break
            self.next()
        self.expect("}", "closing the list")
        self.leave()
        return items

    def expr(self) -> tuple:
        self.enter()
        cond = self.binary(1)
        if self.at("?"):
            tok = self.next()
            yes = self.expr()
            self.expect(":", "in a ?: expression")
            no = self.expr()
            cond = ("if", tok, cond, yes, no)
        self.leave()
        return cond

    def binary(self, level: int) -> tuple:
        """Operators of precedence >= ``level``; the operators of one level form one flat chain, so that a
        long sum is a list, not a deep tree."""
        if level > 6:
            return self.unary()
        ops, chain = [], [self.binary(level + 1)]
        while self.tok.kind == "op" and _BINARY.get(self.tok.text) == level:
            ops.append(self.next())
            chain.append(self.binary(level + 1))
        return ("chain", ops, chain) if ops else chain[0]

    def unary(self) -> tuple:
        if self.at("-", "+", "!"):
            tok = self.next()
            self.enter()
            operand = self.unary()
            self.leave()
            return ("unary", tok, operand)
        return self.power()

    def power(self) -> tuple:
        base = self.primary()
        if self.at("^"):
            tok = self.next()
            self.enter()
            exponent = self.unary()  # right-associative: 2^-1, 2^3^2 = 2^9
            self.leave()
            return ("pow", tok, base, exponent)
        return base

    def primary(self) -> tuple:
        tok = self.tok
        if tok.kind == "num":
            self.next()
            value = float(tok.text)
            if not math.isfinite(value):
                raise self.error(tok, f"'{_show(tok.text)}' is not a finite number")
            return ("num", value, tok)
        if self.at("("):
            self.next()
            inner = self.expr()
            self.expect(")")
            return inner
        if self.at("#"):
            self.next()
            name = self.word()
            close = "]" if self.at("[") else ")"
            self.expect("[" if close == "]" else "(")
            self.expect(close)
            return ("len", name)
        if tok.kind != "name":
            raise self.error(tok, f"expected a number, a variable or '(', found '{_show(tok.text)}'")
        self.next()
        if tok.text == "Pi":
            return ("num", math.pi, tok)
        if tok.text in _NEW:
            return ("new", tok, _NEW[tok.text])
        if tok.text in FUNCTIONS:
            return self._function(tok)
        if tok.text in _HAZARDS or tok.text in _GMSH_WORDS or (self.at("(", "[") and self.peek().kind == "str"):
            raise self.refuse(tok)
        if self.at("[", "("):
            close = "]" if self.next().text == "[" else ")"
            self.enter()
            index = self.expr()
            self.leave()
            self.expect(close)
            return ("item", tok, index)
        return ("var", tok)

    def _function(self, tok: _Tok) -> tuple:
        close = {"[": "]", "(": ")"}.get(self.tok.text)
        if close is None:
            raise self.error(self.tok, f"expected '[' or '(' after the function {tok.text}")
        self.next()
        args = [self.expr()]
        while self.at(","):
            self.next()
            args.append(self.expr())
        self.expect(close)
        count = FUNCTIONS[tok.text][0]
        if len(args) != count:
            raise self.error(tok, f"{tok.text} takes {count} argument{'s' if count > 1 else ''}, got {len(args)}")
        return ("call", tok, args)


class _Runner:
    """Runs the statement tree: variables, loops and macros, and records the geometry operations."""

    def __init__(self, name: str, work: Work):
        self.name, self.work = name, work
        self.vars: dict[str, list[float]] = {}
        self.macros: dict[str, list] = {}
        self.ops: list = []
        self.factory: str | None = None
        self.tags: dict[str, set[int]] = {"point": set(), "curve": set(), "loop": set(), "surface": set(),
                                          "field": set()}
        self.top = dict.fromkeys(self.tags, 0)  # largest tag of each kind (newp & co. without a search)
        self.physicals: dict[tuple, tuple[list, set]] = {}
        self.calls = 0
        self.depth = 0

    def error(self, tok: _Tok, what: str) -> GeometryFileError:
        return GeometryFileError(f"{self.name} line {tok.line}: {what}")

    # -- statements ----------------------------------------------------------------------------------

    def run(self, body: list) -> None:
        self.depth += 1
        if self.depth > MAX_NESTING:  # blocks inside macros called from blocks
            raise GeometryFileError(f"{self.name}: blocks and macro calls nested more than {MAX_NESTING} deep "
                                    f"(MAX_NESTING)")
        for statement in body:
            self.work.tick()
            getattr(self, "r_" + statement[0])(*statement[1:])
        self.depth -= 1

    def r_nop(self, tok: _Tok) -> None:
        pass

    def r_factory(self, tok: _Tok, kind: str) -> None:
        if any(self.tags[k] for k in ("point", "curve", "loop", "surface")):
            raise UntrustedGeoError(f"{self.name} line {tok.line}: 'SetFactory' after geometry is not in the subset "
                                    f"(one kernel per file, chosen before the first entity). {_TRUST}")
        self.factory = kind

    def r_assign(self, target: _Tok, index, whole: bool, op: str, value: tuple) -> None:
        values = self.items(value[1]) if value[0] == "list" else [self.num(value[1])]
        name = target.text
        if index is not None:
            if len(values) != 1:
                raise self.error(target, f"{name}[...] takes one number, got a list of {len(values)}")
            current = self._list(target)
            k = self.index(index, len(current) + (op == "="), target)
            if k == len(current):
                current.append(values[0])
            else:
                current[k] = values[0] if op == "=" else self._combine(current[k], values[0], op, target)
            return
        if op == "=":
            self.vars[name] = values
            return
        current = self._list(target)
        if whole and op in ("+=", "-="):
            if op == "+=":
                current.extend(values)
            else:
                drop = set(values)
                self.work.tick(len(current))
                current[:] = [v for v in current if v not in drop]
            return
        if len(values) != 1 or len(current) != 1:
            raise self.error(target, f"'{op}' needs one number on each side ({name} has {len(current)})")
        current[0] = self._combine(current[0], values[0], op, target)

    def _combine(self, old: float, new: float, op: str, tok: _Tok) -> float:
        return self.finite(_arith(op[0], old, new, lambda what: self.error(tok, what)), tok)

    def _list(self, target: _Tok) -> list[float]:
        if target.text not in self.vars:
            raise UntrustedGeoError(
                f"{self.name} line {target.line}: '{_show(target.text)}' is not a variable given a value above, nor "
                f"a word of the geometry subset bearingfe reads (docs/geometry_files.md). {_TRUST}")
        return self.vars[target.text]

    def r_incr(self, target: _Tok, delta: float) -> None:
        current = self._list(target)
        if len(current) != 1:
            raise self.error(target, f"'{target.text}' is a list of {len(current)}, not one number")
        current[0] += delta

    def r_constants(self, tok: _Tok, entries: list) -> None:
        for target, (_, value, checked) in entries:
            number = self.num(value)
            for attribute in checked:  # labels and ranges for a GUI: unused, but their words must be known
                self.num(attribute)
            self.vars.setdefault(target.text, [number])  # a value given before (e.g. -setnumber) wins

    def r_for(self, tok: _Tok, var: str | None, items: list, body: list) -> None:
        _, start, stop, step = items[0]
        first, last, delta = self.num(start), self.num(stop), 1.0 if step is None else self.num(step)
        count = _range_count(first, last, delta, lambda what: self.error(tok, what))
        self.work.tick(count)
        for k in range(count):
            if var is not None:
                self.vars[var] = [first + k * delta]
            self.run(body)

    def r_if(self, tok: _Tok, branches: list, otherwise: list) -> None:
        for cond, body in branches:
            if self.num(cond) != 0:
                self.run(body)
                return
        self.run(otherwise)

    def r_macro(self, tok: _Tok, label: str, body: list) -> None:
        self.macros[label] = body

    def r_call(self, tok: _Tok, label: str) -> None:
        if label not in self.macros:
            raise self.error(tok, f"Call {_show(label)}: no macro of that name is defined above")
        self.calls += 1
        if self.calls > MAX_CALL_DEPTH:
            raise self.error(tok, f"macro calls nested more than {MAX_CALL_DEPTH} deep (MAX_CALL_DEPTH: a macro "
                                  f"that calls itself?)")
        self.run(self.macros[label])
        self.calls -= 1

    # -- geometry ------------------------------------------------------------------------------------

    def kernel(self) -> str:
        if self.factory is None:
            self.factory = "geo"
        return self.factory

    def r_entity(self, tok: _Tok, kind: str, tag_expr: tuple, items: list) -> None:
        tag = self.tag(tag_expr, tok)
        values = self.items(items)
        occ = self.kernel() == "occ"
        store = {"point": "point", "curve_loop": "loop", "plane_surface": "surface"}.get(kind, "curve")
        if tag in self.tags[store]:
            raise self.error(tok, f"{tok.text} {tag} is defined twice")
        n = len(values)
        if kind == "point":
            if n not in (3, 4):
                raise self.error(tok, f"Point({tag}) takes {{x, y, z}} or {{x, y, z, size}}, got {n} numbers")
            self.ops.append(["point", tag, *values[:3], values[3] if n == 4 else 0.0])
        elif kind == "line":
            self._need(tok, values, 2, 2, "Line", "{start, end} point")
            self.ops.append(["line", tag, *self.refs(values, "point", tok)])
        elif kind in ("circle", "ellipse"):
            arc, radii = (3, 1) if kind == "circle" else (4, 2)
            if n == arc:
                self.ops.append([kind + "_arc", tag, *self.refs(values, "point", tok)])
            elif occ and 3 + radii <= n <= 5 + radii:
                rest = values[3 + radii:]
                angles = [0.0, 2 * math.pi] if not rest else [0.0, rest[0]] if len(rest) == 1 else rest
                self.ops.append([kind, tag, *values[:3 + radii], *angles])
                self._add("point", self._new("point"))  # OpenCASCADE gives the closed curve a vertex
            else:
                points = "{start, centre, end}" if kind == "circle" else "{start, centre, major-axis point, end}"
                shape = "{x, y, z, radius[, angles]}" if kind == "circle" else "{x, y, z, r1, r2[, angles]}"
                raise self.error(tok, f"{tok.text}({tag}) takes the points {points} or, with "
                                      f"SetFactory(\"OpenCASCADE\"), {shape}; got {n} numbers")
        elif kind in ("spline", "bspline"):
            if n < 2:
                raise self.error(tok, f"{tok.text}({tag}) needs at least 2 points, got {n}")
            self.ops.append([kind, tag, self.refs(values, "point", tok)])
        elif kind == "curve_loop":
            if n < 1:
                raise self.error(tok, f"Curve Loop({tag}) needs at least one curve")
            self.ops.append(["curve_loop", tag, self.refs(values, "curve", tok, signed=True)])
        else:
            if n < 1:
                raise self.error(tok, f"Plane Surface({tag}) needs at least one curve loop")
            self.ops.append(["plane_surface", tag, self.refs(values, "loop", tok, signed=True)])
        self._add(store, tag)

    def _add(self, store: str, tag: int) -> None:
        self.tags[store].add(tag)
        self.top[store] = max(self.top[store], tag)

    def _need(self, tok: _Tok, values: list, low: int, high: int, what: str, form: str) -> None:
        if not low <= len(values) <= high:
            raise self.error(tok, f"{what} takes {form}, got {len(values)} numbers")

    def refs(self, values: list[float], kind: str, tok: _Tok, signed: bool = False) -> list[int]:
        """Tags of entities defined above (``signed``: a minus sign reverses a curve or loop)."""
        out = []
        for value in values:
            tag = _as_tag(value, signed, lambda what: self.error(tok, what))
            if abs(tag) not in self.tags[kind]:
                raise self.error(tok, f"{tok.text} uses {'curve loop' if kind == 'loop' else kind} {abs(tag)}, "
                                      f"which is not defined above")
            out.append(tag)
        return out

    def r_physical(self, tok: _Tok, dim: int, label: str | None, number, items: list) -> None:
        tags = [abs(_as_tag(v, True, lambda what: self.error(tok, what))) for v in self.items(items)]
        if label is not None and not label.isprintable():
            raise self.error(tok, "a physical group name must be printable text")
        tag = -1 if number is None else self.tag(number, tok)
        key = (dim, label if label is not None else tag)
        if key not in self.physicals:
            op = ["physical", dim, tag, label or "", []]
            self.physicals[key] = (op, set())
            self.ops.append(op)
        op, seen = self.physicals[key]
        for t in tags:
            if t not in seen:
                seen.add(t)
                op[4].append(t)

    def r_size(self, tok: _Tok, items: list, value: tuple) -> None:
        points = self.refs(self.items(items), "point", tok)
        size = self.num(value)
        if not size > 0:
            raise self.error(tok, f"a mesh size must be > 0, got {size:g}")
        self.ops.append(["size", points, size])

    def r_transform(self, tok: _Tok, kind: str, args: list, shapes: list) -> None:
        shape = [self._flat(a, tok) for a in args]
        forms = {"rotate": ([3, 3, 1], "{{axis x, y, z}, {point x, y, z}, angle}"),
                 "translate": ([1, 1, 1], "{dx, dy, dz}"),
                 "dilate": ([3, 1], "{{centre x, y, z}, factor}"), "symmetry": ([1, 1, 1, 1], "{a, b, c, d}")}
        sizes, form = forms[kind]
        if kind == "dilate" and [len(s) for s in shape] == [3, 3]:
            sizes = [3, 3]
        if [len(s) for s in shape] != sizes:
            raise self.error(tok, f"{tok.text} takes {form}")
        numbers = [x for s in shape for x in s]
        if kind == "dilate" and len(numbers) == 4:
            numbers += numbers[3:] * 2
        entities = []
        for dim, items in shapes:
            store = ("point", "curve", "surface")[dim]
            entities += [[dim, abs(t)] for t in self.refs(self.items(items), store, tok)]
        self.ops.append([kind, entities, *numbers])

    def _flat(self, item: tuple, tok: _Tok) -> list[float]:
        if item[0] == "braces":
            return self.items(item[1])
        return self.items([item])

    def r_field(self, tok: _Tok, tag_expr: tuple, kind: str) -> None:
        tag = self.tag(tag_expr, tok)
        self._add("field", tag)
        self.ops.append(["field", tag, kind])

    def r_field_option(self, tok: _Tok, tag_expr: tuple, option: str, value: tuple) -> None:
        tag = self.tag(tag_expr, tok)
        if tag not in self.tags["field"]:
            raise self.error(tok, f"Field[{tag}] is not defined above")
        if value[0] == "str":
            if option != "F":
                raise UntrustedGeoError(f"{self.name} line {tok.line}: 'Field[{tag}].{_show(option)}' takes a "
                                        f"text value, which the subset accepts only for F (a MathEval formula). "
                                        f"{_TRUST}")
            self.ops.append(["field_string", tag, option, value[1]])
        elif value[0] == "list":
            self.ops.append(["field_numbers", tag, option, self.items(value[1])])
        else:
            self.ops.append(["field_number", tag, option, self.num(value[1])])

    def r_background(self, tok: _Tok, value: tuple) -> None:
        tag = self.tag(value, tok)
        if tag not in self.tags["field"]:
            raise self.error(tok, f"Background Field = {tag}: no field {tag} is defined above")
        self.ops.append(["background", tag])

    def r_option(self, tok: _Tok, option: str, value: tuple) -> None:
        number = self.num(value)
        low, high = OPTIONS[option]
        if not low <= number <= high:
            raise self.error(tok, f"{option} = {number:g} is outside [{low:g}, {high:g}]")
        self.ops.append(["option", option, number])

    # -- values --------------------------------------------------------------------------------------

    def tag(self, expr: tuple, tok: _Tok) -> int:
        return _as_tag(self.num(expr), False, lambda what: self.error(tok, what))

    def num(self, expr: tuple) -> float:
        values = self.value(expr)
        if len(values) != 1:
            raise GeometryFileError(f"{self.name} line {_line(expr)}: a list of {len(values)} numbers where one "
                                    f"number is expected")
        return values[0]

    def finite(self, value: float, tok: _Tok) -> float:
        if not math.isfinite(value):
            raise self.error(tok, f"'{_show(tok.text)}' gives a number that is not finite")
        return value

    def items(self, items: list) -> list[float]:
        out: list[float] = []
        for item in items:
            kind = item[0]
            if kind == "expr":
                out += self.value(item[1])
            elif kind == "braces":
                out += self.items(item[1])
            elif kind == "whole":
                whole = self._list(item[1])
                self.work.tick(len(whole))
                out += whole
            else:
                first, last = self.num(item[1]), self.num(item[2])
                delta = 1.0 if item[3] is None else self.num(item[3])
                count = _range_count(first, last, delta,
                                     lambda what: GeometryFileError(f"{self.name} line {_line(item[1])}: {what}"))
                self.work.tick(count)
                out += [first + k * delta for k in range(count)]
            self.work.tick()
        return out

    def value(self, expr: tuple) -> list[float]:
        """The value of an expression: a list of numbers (one for a number, several for a whole list)."""
        self.work.tick()
        kind = expr[0]
        if kind == "num":
            return [expr[1]]
        if kind == "var":
            whole = self._list(expr[1])
            self.work.tick(len(whole))
            return list(whole)
        if kind == "item":
            current = self._list(expr[1])
            return [current[self.index(expr[2], len(current), expr[1])]]
        if kind == "len":
            return [float(len(self._list(expr[1])))]
        if kind == "new":
            return [float(self._new(expr[2]))]
        if kind == "call":
            tok, args = expr[1], [self.num(a) for a in expr[2]]
            try:
                return [self.finite(float(FUNCTIONS[tok.text][1](*args)), tok)]
            except (ArithmeticError, ValueError):
                raise self.error(tok, f"{tok.text}({', '.join(f'{a:g}' for a in args)}) is not defined") from None
        if kind == "unary":
            tok, x = expr[1], self.num(expr[2])
            return [-x if tok.text == "-" else x if tok.text == "+" else float(x == 0)]
        if kind == "pow":
            tok, base, exponent = expr[1], self.num(expr[2]), self.num(expr[3])
            try:
                return [self.finite(math.pow(base, exponent), tok)]
            except (ArithmeticError, ValueError):
                raise self.error(tok, f"{base:g}^{exponent:g} is not defined") from None
        if kind == "if":
            return [self.num(expr[3]) if self.num(expr[2]) != 0 else self.num(expr[4])]
        _, ops, chain = expr  # "chain"
        result = self.num(chain[0])
        for tok, operand in zip(ops, chain[1:]):
            result = self.finite(_arith(tok.text, result, self.num(operand), lambda what: self.error(tok, what)),
                                 tok)
        return [result]

    def index(self, expr: tuple, size: int, tok: _Tok) -> int:
        number = self.num(expr)
        if not (number == int(number) and 0 <= number < size):
            raise self.error(tok, f"{tok.text}[{number:g}]: the index must be an integer in [0, {size - 1}]")
        return int(number)

    def _new(self, kind: str) -> int:
        stores = ("point", "curve", "loop", "surface") if kind == "any" else (kind,)
        return max(self.top[s] for s in stores) + 1


def _line(expr: tuple) -> int | str:
    """The line of an expression (its first token), for messages."""
    for part in expr[1:]:
        parts = part if isinstance(part, list) else [part]
        for piece in parts:
            if isinstance(piece, _Tok):
                return piece.line
            if isinstance(piece, tuple) and piece:
                line = _line(piece)
                if line != "?":
                    return line
    return "?"


def _arith(op: str, a: float, b: float, error: Callable[[str], Exception] | None = None) -> float:
    """``a op b`` for the binary operators of expressions (comparisons give 1 or 0)."""
    try:
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        if op == "/":
            return a / b
        if op == "%":
            return math.fmod(a, b)
    except (ArithmeticError, ValueError):
        if error is None:
            raise GeometryFileError(f"{a:g} {op} {b:g} is not defined") from None
        raise error(f"{a:g} {op} {b:g} is not defined") from None
    return float({"==": a == b, "!=": a != b, "<": a < b, ">": a > b, "<=": a <= b, ">=": a >= b,
                  "&&": a != 0 and b != 0, "||": a != 0 or b != 0}[op])


def _range_count(first: float, last: float, step: float, error: Callable[[str], Exception]) -> int:
    """Number of values of ``first:last:step`` (gmsh's rule: up to ``last`` inclusive, within rounding)."""
    if step == 0:
        raise error("a range with step 0 never ends")
    span = (last - first) / step
    if span < -1e-10:
        return 0
    if span > MAX_GEO_STEPS:
        raise error(f"a range of more than {MAX_GEO_STEPS} values (MAX_GEO_STEPS)")
    return int(math.floor(span + 1e-10)) + 1


def _as_tag(value: float, signed: bool, error: Callable[[str], Exception]) -> int:
    """An entity tag: an integer in [1, 2^31 - 1] (``signed``: or its negative, a reversed orientation)."""
    magnitude = abs(value) if signed else value
    if not (magnitude == int(magnitude) and 1 <= magnitude <= 2**31 - 1):
        raise error(f"{value:g} is not an entity number (an integer from 1 to 2147483647)")
    return int(value)


def parse_geo(text: str, name: str = "<geo>", *, work: Work | None = None) -> GeoModel:
    """Read a ``.geo`` file of the geometry subset into operations for the gmsh API.

    Parameters
    ----------
    text : str
        The file's text (at most :data:`MAX_GEO_BYTES` characters).
    name : str
        The file's name, first in every message.
    work : Work, optional
        Budget and deadline of the read (default: :data:`MAX_GEO_STEPS`, no deadline); its ``steps``
        count the work done.

    Returns
    -------
    GeoModel
        The kernel and the operations, in file order.

    Raises
    ------
    UntrustedGeoError
        A construct outside the subset, named with its line (e.g. ``SystemCall``, ``Include``, ``Exit``).
    GeometryFileError
        Text that is not valid ``.geo``, a value out of range, a file or work beyond the limits.
    """
    work = Work() if work is None else work
    work.name = name
    if len(text) > MAX_GEO_BYTES:
        raise GeometryFileError(f"{name} has {len(text)} characters, more than the {MAX_GEO_BYTES} a .geo file "
                                f"may have (MAX_GEO_BYTES)")
    try:
        reader = _Reader(text, name, work)
        program = reader.program()
        runner = _Runner(name, work)
        runner.run(program)
    except RecursionError:  # a guard above should stop first; the interpreter's stack is the last line
        raise GeometryFileError(f"{name}: nested too deeply to read (MAX_NESTING)") from None
    factory = runner.factory or "geo"
    ops = runner.ops
    if not any(op[0] == "plane_surface" for op in ops):
        raise GeometryFileError(f"{name}: no Plane Surface (a support surface needs one)")
    return GeoModel(factory=factory, ops=ops, steps=work.steps)
