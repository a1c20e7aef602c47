"""Geometry files from users: ``.geo`` scripts checked and run apart, ``.msh`` read as data.

A gmsh ``.geo`` file is a program: besides points and curves it can run
shell commands (``SystemCall``), write files (``Printf(...) > "f"``,
``Save``), read other files (``Include``, ``Merge``, ``ShapeFromFile``) and
end the process that reads it (``Exit``). bearingfe therefore treats
geometry files as untrusted data by default (docs: README, "Safety"):

* ``.msh`` files are read by a data parser (meshio), never by gmsh's script
  interpreter, and only if their content starts with ``$MeshFormat`` (a
  ``.geo`` script renamed to ``x.msh`` is refused, not run);
* ``.geo`` scripts are checked against an allow-list (:func:`check_geo_script`):
  geometry, mesh-size and physical-group statements, arithmetic, loops,
  ``Mesh.*`` / ``Geometry.*`` numeric options, numeric ``DefineConstant``
  parameters; anything else (shell, files, other option groups, other
  onelab commands, plugins, environment, ``Exit``) is
  refused with :class:`UntrustedGeoError` naming the command and line,
  unless the caller trusts the file (``trusted=True``, ``--trust-geo``);
* trusted or not, gmsh parses and meshes the script in a separate process
  with a time limit (:data:`DEFAULT_GEO_TIMEOUT`): a loop that never ends
  or an ``Exit;`` cannot hang or end the caller;
* the child process is confined: CPU time, :data:`GEO_MEMORY` of address
  space, and on Linux it dies with its parent;
* the element count is estimated before meshing and refused beyond
  ``max_elements`` (:data:`DEFAULT_MAX_ELEMENTS`, environment variable
  ``BEARINGFE_MAX_ELEMENTS``).
"""

from __future__ import annotations

import json
import math
import os
import re
import signal
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.tempdirs import private_tempdir
from ..core.limits import DEFAULT_LIMITS, LimitError, limit

__all__ = [
    "GeometryFileError",
    "UntrustedGeoError",
    "MeshSizeError",
    "DEFAULT_MAX_ELEMENTS",
    "DEFAULT_GEO_TIMEOUT",
    "MeshData",
    "max_elements_limit",
    "geo_timeout_limit",
    "check_element_count",
    "estimate_triangles",
    "check_geo_script",
    "read_msh",
    "run_geo",
    "run_gmsh_worker",
]

#: Largest number of triangles a mesh may have unless the caller raises the limit
#: (``max_elements=``, ``--max-elements`` or the environment variable ``BEARINGFE_MAX_ELEMENTS``).
DEFAULT_MAX_ELEMENTS = int(DEFAULT_LIMITS["elements"])

#: Seconds gmsh may spend parsing and meshing a ``.geo`` script (``timeout=``, ``--geo-timeout``,
#: environment variable ``BEARINGFE_GEO_TIMEOUT``).
DEFAULT_GEO_TIMEOUT = 120.0

#: Address space of the gmsh child process [bytes] (a script that allocates without end fails, not the machine).
GEO_MEMORY = 4 * 1024**3

MAX_ELEMENTS_ENV = "BEARINGFE_MAX_ELEMENTS"
GEO_TIMEOUT_ENV = "BEARINGFE_GEO_TIMEOUT"

#: Area of an equilateral triangle of unit edge: element counts are estimated as area / (this * h^2).
_EQUILATERAL = math.sqrt(3.0) / 4.0


class GeometryFileError(ValueError):
    """A geometry file cannot be used (not a mesh, gmsh failed, ended or ran out of time)."""


class UntrustedGeoError(GeometryFileError):
    """A ``.geo`` script uses a command that reaches outside the geometry (refused unless trusted)."""


class MeshSizeError(LimitError):
    """The mesh asked for would have more elements than the limit allows."""


# -- limits ------------------------------------------------------------------------

def max_elements_limit(value: int | None = None) -> int:
    """The element-count limit: ``value`` if given, else ``$BEARINGFE_MAX_ELEMENTS``, else the default
    (the ``elements`` limit of :mod:`bearingfe.core.limits`).

    Raises
    ------
    ValueError
        If the value is not an integer >= 1 (or the environment variable not a number > 0).
    """
    if value is None:
        return int(limit("elements"))
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"max_elements (--max-elements) must be an integer >= 1, got {value!r}") from None
    if not (math.isfinite(number) and number >= 1 and number == int(number)):
        raise ValueError(f"max_elements (--max-elements) must be an integer >= 1, got {value!r}")
    return int(number)


def geo_timeout_limit(value: float | None = None) -> float:
    """The ``.geo`` time limit [s]: ``value``, else ``$BEARINGFE_GEO_TIMEOUT``, else the default."""
    source = "timeout (--geo-timeout)"
    if value is None:
        env = os.environ.get(GEO_TIMEOUT_ENV)
        if env is None:
            return DEFAULT_GEO_TIMEOUT
        value, source = env, GEO_TIMEOUT_ENV
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{source} must be a number of seconds > 0, got {value!r}") from None
    if not (math.isfinite(number) and number > 0):
        raise ValueError(f"{source} must be a finite number of seconds > 0, got {value!r}")
    return number


def estimate_triangles(area: float, size: float) -> float:
    """Triangles of edge ``size`` needed to cover ``area`` (a lower bound for sizes up to ``size``)."""
    return float(area) / (_EQUILATERAL * float(size) ** 2)


def check_element_count(estimate: float, max_elements: int | None = None, *, what: str = "the mesh") -> None:
    """Refuse an estimated element count beyond the limit.

    Parameters
    ----------
    estimate : float
        Estimated number of triangles.
    max_elements : int, optional
        The limit; default :func:`max_elements_limit` (environment or
        :data:`DEFAULT_MAX_ELEMENTS`).
    what : str
        What is being meshed, for the message (e.g. ``"size = 0.0001"``).

    Raises
    ------
    MeshSizeError
        Naming the estimate, the limit and how to raise it.
    """
    limit = max_elements_limit(max_elements)
    if not estimate <= limit:  # also NaN
        raise MeshSizeError(
            f"{what} would need about {estimate:.3g} triangles, more than max_elements = {limit}: use a "
            f"larger element size, or raise the limit (max_elements= argument, --max-elements on the "
            f"command line, or the environment variable {MAX_ELEMENTS_ENV})")


# -- the .geo allow-list -------------------------------------------------------------

_TOKEN = re.compile(r"""
    (?P<space>[ \t\r\f]+|\n)
  | (?P<comment>//[^\n]*|/\*.*?(?:\*/|\Z))
  | (?P<string>"[^"]*(?:"|\Z)|'[^']*(?:'|\Z))
  | (?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z_0-9]*)
  | (?P<op>\.\.\.|::|\|\||&&|\+\+|--|==|!=|<=|>=|>>|<<|\+=|-=|\*=|/=|.)
""", re.VERBOSE | re.DOTALL)

#: gmsh .geo keywords an untrusted script may use: geometry, sizes, groups, arithmetic, loops, strings.
_ALLOWED_KEYWORDS = frozenset("""
    Abs Acos ArcCos ArcSin ArcTan ArcTan2 Asin Atan Atan2 Ceil Cos Cosh Exp Fabs Floor Fmod Hypot Log Log10
    Modulo Round Sin Sinh Sqrt Tan Tanh Pi Min Max Step Rand LinSpace LogSpace Unique List Exists Find
    Str StrCat Sprintf StrCmp StrLen StrSub StrReplace StrPrefix StrFind StrChoice UpperCase LowerCase
    LowerCaseIn NameToString N2S StringToName S2N
    newreg newp newl newc newll newcl news newsl newv newf
    Point Curve Line Circle Ellipse Ellipsis Spline CatmullRom BSpline Bezier Nurbs Knots Order Surface
    Plane Ruled Physical Rectangle Disk Compound Wire In Using Parametric
    BooleanCoherence BooleanCommon BooleanCut BooleanDifference BooleanFragments BooleanFuse
    BooleanIntersection BooleanSection BooleanUnion Fillet Chamfer
    Rotate Translate Symmetry Dilate Affine Extrude Layers Recombine Transfinite Field Characteristic
    MeshSize MeshAlgorithm MeshSizeFromBoundary Periodic Reverse ReverseMesh Smoother Coherence
    Delete Recursive Hide Show Color RefineMesh Hole
    For EndFor If ElseIf Else EndIf Macro Function Call Return
    SetFactory Printf Error Warning
""".split())

#: Every other gmsh .geo keyword (gmsh's lexer), refused when untrusted; the reason if it is a known hazard.
_REFUSED_KEYWORDS = {
    "Exit": "ends the program that reads the file",
    "Abort": "ends the program that reads the file",
    "OnelabRun": "runs an external program",
    "OnelabAction": "drives an external (onelab) client",
    "ShapeFromFile": "reads another file",
    "ListFromFile": "reads another file",
    "FileExists": "looks at the file system",
    "AbsolutePath": "looks at the file system",
    "CurrentDir": "looks at the file system",
    "CurrentDirectory": "looks at the file system",
    "CurrentFileName": "looks at the file system",
    "DirName": "looks at the file system",
    "FixRelativePath": "looks at the file system",
    "StrRelative": "looks at the file system",
    "GetEnv": "reads the environment",
    "GetValue": "waits for keyboard input",
    "GetString": "reads onelab parameters",
    "GetStringValue": "waits for keyboard input",
    "GetNumber": "reads onelab parameters",
    "GetForced": "reads onelab parameters",
    "GetForcedStr": "reads onelab parameters",
    "SetNumber": "sets onelab parameters",
    "SetString": "sets onelab parameters",
    "DefineNumber": "defines onelab parameters",
    "DefineString": "defines onelab parameters",
    "UndefineConstant": "changes onelab parameters",
    "Plugin": "runs a gmsh plugin (plugins read and write files)",
    "NewModel": "replaces the model",
    "GmshExecutableName": "looks at the installation",
}

#: Words of the .geo grammar that are not lexer keywords but are safe where they appear.
_GRAMMAR_WORDS = frozenset("""
    Loop Duplicata Progression Bump Beta Left Right Alternate AlternateLeft AlternateRight
    Model Physicals Variables Meshes Options
    Distance Threshold MathEval MathEvalAniso Box Ball Frustum Cylinder Restrict Constant Mean Laplacian
    Gradient Curvature Param Extend BoundaryLayer AttractorAnisoCurve Attractor MaxEigenHessian Octree
    AutomaticMeshSizeField Cylinder
""".split())

#: Non-keyword command words of gmsh (``Word argument;``) and why they are refused.
_COMMANDS = {
    "SystemCall": "runs a shell command",
    "System": "runs a shell command",
    "NonBlockingSystemCall": "runs a shell command",
    "Include": "includes another file",
    "Merge": "merges another file",
    "MergeWithBoundingBox": "merges another file",
    "Save": "writes a file",
    "Print": "writes a file",
    "CreateDir": "creates a directory",
    "Sleep": "waits",
    "SetName": "renames the model",
    "Exit": "ends the program that reads the file",
    "ExternalProcess": "is a size field that runs an external program",
    "Structured": "is a size field that reads a file",
    "PostView": "is a size field that reads post-processing views",
}

#: ``DefineConstant[ name = {value, Attribute value, ...} ]``: the onelab attributes an untrusted script may
#: give a numeric constant (labels and ranges for a GUI; gmsh run by bearingfe has none). Text attributes take
#: one string, number attributes a numeric expression, ``Choices`` a list of numbers optionally labelled.
_CONSTANT_TEXT_ATTRIBUTES = frozenset({"Name", "Label", "Help", "Units", "Highlight"})
_CONSTANT_NUMBER_ATTRIBUTES = frozenset({"Min", "Max", "Step", "Visible", "ReadOnly", "Closed", "ReadOnlyRange"})
_CONSTANT_LIST_ATTRIBUTES = frozenset({"Choices"})

#: Option groups an untrusted script may set (numbers only): the others hold paths and programs.
_OPTION_GROUPS = frozenset({"Mesh", "Geometry"})

_ASSIGN = frozenset({"=", "+=", "-=", "*=", "/=", "++", "--", "[", "(", "."})


@dataclass(frozen=True)
class _Tok:
    kind: str
    text: str
    line: int


def _tokens(text: str) -> list[_Tok]:
    out, line = [], 1
    for m in _TOKEN.finditer(text):
        kind, value = m.lastgroup, m.group()
        if kind not in ("space", "comment"):
            out.append(_Tok(kind, value, line))
        line += value.count("\n")
    return out


def _refuse(name: str, tok: _Tok, reason: str) -> UntrustedGeoError:
    return UntrustedGeoError(
        f"{name} line {tok.line}: '{tok.text}' {reason}; untrusted .geo scripts may only describe geometry, "
        f"mesh sizes and physical groups. If you trust this file, pass trusted=True (load_mesh) or "
        f"--trust-geo (bearingfe mesh)")


def check_geo_script(text: str, name: str = "<geo>") -> None:
    """Refuse a ``.geo`` script that reaches outside its own geometry.

    The check is an allow-list on the script's words (it never runs the
    script): gmsh keywords must be geometry, mesh-size, physical-group,
    arithmetic, string or loop keywords; an option assignment must be a
    number into the ``Mesh.`` or ``Geometry.`` group; every other word must
    be a variable the script assigns itself. Refused, among others:
    ``SystemCall``, ``NonBlockingSystemCall``, ``OnelabRun``, ``Include``,
    ``Merge``, ``ShapeFromFile``, ``Save``, ``Print``, ``CreateDir``,
    ``Printf(...) > "file"``, ``Exit``, ``Abort``, ``GetEnv``, ``GetValue``,
    ``Plugin``, the ``ExternalProcess``/``Structured``/``PostView`` size
    fields and the ``General.``/``Solver.``/``Print.`` option groups.

    Parameters
    ----------
    text : str
        The script.
    name : str
        File name for the messages.

    Raises
    ------
    UntrustedGeoError
        Naming the first refused word, its line and how to trust the file.
    """
    toks = _constants_as_assignments(_tokens(text), name)
    defined = _defined_names(toks)
    for i, tok in enumerate(toks):
        prev = toks[i - 1] if i else None
        nxt = toks[i + 1] if i + 1 < len(toks) else None
        if tok.kind == "string" and prev is not None and prev.kind == "name" and prev.text not in _ALLOWED_KEYWORDS:
            raise _refuse(name, prev, _COMMANDS.get(prev.text, "is a command that takes a file name or text"))
        if tok.text in ("Printf", "Error", "Warning") and _redirected(toks, i):
            raise _refuse(name, tok, "writes to a file (> or >> after the message)")
        if tok.kind == "name" and prev is not None and prev.text == ".":
            if nxt is not None and nxt.kind in ("name", "number", "string"):
                raise _refuse(name, tok, "is used as a command")
            continue  # an option or field member: checked at its group
        if tok.kind != "name":
            continue
        word = tok.text
        if word in _ALLOWED_KEYWORDS:
            continue
        if word in _REFUSED_KEYWORDS:
            raise _refuse(name, tok, _REFUSED_KEYWORDS[word])
        if word in _COMMANDS and (nxt is None or nxt.text not in _ASSIGN - {"."}):
            raise _refuse(name, tok, _COMMANDS[word])
        if nxt is not None and nxt.text == ".":
            if word not in _OPTION_GROUPS:
                raise _refuse(name, tok, f"sets options of the {word}. group (only Mesh. and Geometry. "
                                         f"numeric options are accepted)")
            _check_option_value(toks, i, name)
            continue
        if word == "Mesh" and nxt is not None and nxt.kind == "number":
            continue  # "Mesh 2;": mesh now
        if word in _GRAMMAR_WORDS:
            continue
        if word in defined:
            if prev is not None and prev.text in ("For", "Macro", "Function", "Call"):
                continue
            if nxt is not None and nxt.kind in ("number", "string", "name"):
                raise _refuse(name, tok, "is used as a command")
            continue
        raise _refuse(name, tok, "is not a geometry command or a variable assigned in the script")


def _constants_as_assignments(toks: list[_Tok], name: str) -> list[_Tok]:
    """Each ``DefineConstant[ ... ];`` checked and replaced by plain assignments for the allow-list.

    ``DefineConstant[ a = 1, b = {2, Min 0, Max 5, Name "Parameters/b"} ];`` defines ``a`` and ``b``
    unless already defined (gmsh's onelab parameters; in batch mode only the values matter). Accepted:
    numeric values (expressions) with the attributes of :data:`_CONSTANT_TEXT_ATTRIBUTES` (one string),
    :data:`_CONSTANT_NUMBER_ATTRIBUTES` (an expression) and ``Choices{v, v = "label", ...}``; anything else
    in the brackets is refused. The values and number attributes become ``name = expression;`` so that the
    rest of the check sees every word they use; the strings and labels are dropped (they are only text).
    """
    out, i = [], 0
    while i < len(toks):
        tok = toks[i]
        if tok.text != "DefineConstant":
            out.append(tok)
            i += 1
            continue
        if i + 1 >= len(toks) or toks[i + 1].text != "[":
            raise _refuse(name, tok, "must be followed by [ name = value, ... ]")
        end = _closing(toks, i + 1, name)
        for entry in _split_top(toks[i + 2:end], ","):
            out += _constant_entry(entry, tok, name)
        i = end + 1
        if i < len(toks) and toks[i].text == ";":
            i += 1
    return out


def _closing(toks: list[_Tok], i: int, name: str) -> int:
    """Index of the bracket closing the one at ``i`` (``[``/``{``/``(`` nest)."""
    depth = 0
    for j in range(i, len(toks)):
        if toks[j].text in ("[", "{", "("):
            depth += 1
        elif toks[j].text in ("]", "}", ")"):
            depth -= 1
            if depth == 0:
                return j
    raise _refuse(name, toks[i], "is not closed")


def _split_top(toks: list[_Tok], sep: str) -> list[list[_Tok]]:
    """``toks`` split at ``sep`` outside any bracket (empty pieces dropped)."""
    pieces, piece, depth = [], [], 0
    for tok in toks:
        if tok.text in ("[", "{", "("):
            depth += 1
        elif tok.text in ("]", "}", ")"):
            depth -= 1
        if tok.text == sep and depth == 0:
            pieces.append(piece)
            piece = []
        else:
            piece.append(tok)
    return [p for p in pieces + [piece] if p]


def _constant_entry(entry: list[_Tok], where: _Tok, name: str) -> list[_Tok]:
    """One ``name = value`` or ``name = {value, attributes}`` of a DefineConstant, as assignments."""
    if len(entry) < 3 or entry[0].kind != "name" or entry[1].text != "=":
        raise _refuse(name, entry[0] if entry else where, "in DefineConstant[...] must be 'name = value'")
    target, value = entry[0], entry[2:]
    if value[0].text != "{":
        return _assignment(target, value, name)
    if _closing(value, 0, name) != len(value) - 1:
        raise _refuse(name, value[0], "in DefineConstant[...]: nothing may follow the closing brace")
    parts = _split_top(value[1:-1], ",")
    if not parts:
        raise _refuse(name, value[0], "in DefineConstant[...] has no value")
    out = _assignment(target, parts[0], name)
    for part in parts[1:]:
        attribute, rest = part[0], part[1:]
        if attribute.text in _CONSTANT_TEXT_ATTRIBUTES and len(rest) == 1 and rest[0].kind == "string":
            continue
        if attribute.text in _CONSTANT_NUMBER_ATTRIBUTES and rest:
            out += _assignment(target, rest, name)
        elif attribute.text in _CONSTANT_LIST_ATTRIBUTES and rest and rest[0].text == "{" \
                and _closing(rest, 0, name) == len(rest) - 1:
            for choice in _split_top(rest[1:-1], ","):
                label = next((k for k, t in enumerate(choice) if t.text == "="), None)
                if label is not None and not (label == len(choice) - 2 and choice[-1].kind == "string"):
                    raise _refuse(name, choice[0], "in Choices{...} must be 'number' or 'number = \"label\"'")
                out += _assignment(target, choice[:label], name)
        else:
            raise _refuse(name, attribute, "is not an accepted DefineConstant attribute (accepted: "
                          + ", ".join(sorted(_CONSTANT_TEXT_ATTRIBUTES | _CONSTANT_NUMBER_ATTRIBUTES
                                             | _CONSTANT_LIST_ATTRIBUTES)) + ")")
    return out


def _assignment(target: _Tok, value: list[_Tok], name: str) -> list[_Tok]:
    """``target = value;`` as tokens; a DefineConstant value must be a numeric expression (no text)."""
    if not value:
        raise _refuse(name, target, "in DefineConstant[...] has an empty value")
    for tok in value:
        if tok.kind == "string":
            raise _refuse(name, tok, "is a text value in DefineConstant[...] (only numbers are accepted)")
    line = target.line
    return [target, _Tok("op", "=", line), *value, _Tok("op", ";", value[-1].line)]


def _redirected(toks: list[_Tok], i: int) -> bool:
    """``Printf(...) > file``: the token after the closing parenthesis is ``>`` or ``>>``."""
    depth = 0
    for j in range(i + 1, len(toks)):
        if toks[j].text == "(":
            depth += 1
        elif toks[j].text == ")":
            depth -= 1
            if depth == 0:
                return j + 1 < len(toks) and toks[j + 1].text in (">", ">>")
        elif toks[j].text == ";":
            return False
    return False


def _defined_names(toks: list[_Tok]) -> set[str]:
    """Variables, loop variables and macro names the script defines itself (anywhere in it)."""
    names = set()
    for i, tok in enumerate(toks):
        if tok.kind != "name" or tok.text in _ALLOWED_KEYWORDS or tok.text in _REFUSED_KEYWORDS:
            continue
        prev = toks[i - 1].text if i else ";"
        nxt = toks[i + 1].text if i + 1 < len(toks) else ""
        if prev in ("For", "Macro", "Function"):
            names.add(tok.text)
        elif prev != "." and tok.text not in _COMMANDS:
            if nxt in ("=", "+=", "-=", "*=", "/=", "++", "--") or (nxt in ("[", "(") and _assigned_list(toks, i + 1)):
                names.add(tok.text)
    return names


def _assigned_list(toks: list[_Tok], i: int) -> bool:
    """``x[] = ...`` / ``x(2) = ...``: the bracket at ``i`` closes and is followed by an assignment."""
    depth = 0
    for j in range(i, len(toks)):
        if toks[j].text in ("[", "("):
            depth += 1
        elif toks[j].text in ("]", ")"):
            depth -= 1
            if depth == 0:
                return j + 1 < len(toks) and toks[j + 1].text in ("=", "+=", "-=", "*=", "/=")
        elif toks[j].text == ";":
            return False
    return False


def _check_option_value(toks: list[_Tok], i: int, name: str) -> None:
    """``Mesh.X = <numeric expression>;``: no strings in the value."""
    for tok in toks[i:]:
        if tok.text == ";":
            return
        if tok.kind == "string":
            raise _refuse(name, tok, f"is a text value for a {toks[i].text}. option (only numbers are accepted)")


# -- .msh as data --------------------------------------------------------------------

@dataclass(frozen=True)
class MeshData:
    """A triangle mesh as plain arrays (read from a file, not yet a scikit-fem mesh).

    Attributes
    ----------
    points : ndarray, shape (2, n)
        Node coordinates ``(phi, z)``.
    triangles : ndarray, shape (3 or 6, m)
        Node indices of each triangle (6: gmsh's second-order node order).
    curves : dict of str to ndarray, shape (2, k)
        For each named physical curve group, the end nodes of its edges.
    """

    points: np.ndarray
    triangles: np.ndarray
    curves: dict


def read_msh(path: str | Path) -> MeshData:
    """Read a gmsh ``.msh`` file (formats 2.2, 4.0, 4.1; text or binary) as data.

    The file is parsed by meshio, never by gmsh's script interpreter, and
    only if it starts with ``$MeshFormat``.

    Raises
    ------
    GeometryFileError
        Not a gmsh mesh file (e.g. a ``.geo`` script named ``.msh``), a file
        meshio cannot parse, or one without triangles.
    """
    path = Path(path)
    with open(path, "rb") as f:
        head = f.read(64).lstrip()
    if not head.startswith(b"$MeshFormat"):
        raise GeometryFileError(
            f"{path.name} is not a gmsh mesh file (it does not start with $MeshFormat); a .geo script must "
            f"be named .geo to be meshed (and it is checked before it runs)")
    m = _meshio_read(path)
    points = np.asarray(m.points, dtype=float)
    if points.ndim != 2 or points.shape[0] == 0 or not np.all(np.isfinite(points)):
        raise GeometryFileError(f"{path.name}: node coordinates missing or not finite")
    _check_planar(points, path.name)
    tri = [(k, c.data) for k, c in enumerate(m.cells) if c.type in ("triangle", "triangle6")]
    kinds = {m.cells[k].type for k, _ in tri}
    if not tri:
        raise GeometryFileError(f"{path.name}: no triangles (is there a physical surface?)")
    if len(kinds) > 1:
        raise GeometryFileError(f"{path.name}: mixes straight and curved triangles")
    triangles = np.vstack([d for _, d in tri]).T.astype(np.int64)
    curves = _named_curves(m)
    n = points.shape[0]
    for arr in (triangles, *curves.values()):
        if arr.size and (arr.min() < 0 or arr.max() >= n):
            raise GeometryFileError(f"{path.name}: elements refer to nodes that do not exist")
    return MeshData(points=np.ascontiguousarray(points[:, :2].T), triangles=triangles, curves=curves)


def _meshio_read(path: Path):
    """meshio's gmsh reader, its failures (exceptions, ``sys.exit``, messages on the terminal) as one error.

    meshio answers some malformed files with ``sys.exit(1)`` after printing;
    that must not end the caller's process, and library code prints nothing.
    """
    import contextlib
    import io

    import meshio.gmsh

    said = io.StringIO()
    try:
        with contextlib.redirect_stdout(said), contextlib.redirect_stderr(said):
            return meshio.gmsh.read(str(path))
    except (Exception, SystemExit) as exc:  # noqa: BLE001 - any parser failure is a bad file
        detail = _short(exc) if not isinstance(exc, SystemExit) else (_short(said.getvalue()) or "parse error")
        raise GeometryFileError(f"{path.name}: not a readable gmsh mesh file ({detail})") from None


def _check_planar(points: np.ndarray, name: str) -> None:
    """Refuse nodes off the plane z = 0: a support surface is the flat ``(phi, z)`` plane.

    ``points`` has shape (n, 2 or 3); the third coordinate may differ from 0
    by round-off only (1e-9 of the mesh's extent).
    """
    if points.shape[1] < 3:
        return
    extent = max(1.0, float(np.ptp(points[:, :2])))
    off = np.abs(points[:, 2])
    if off.max() > 1e-9 * extent:
        k = int(np.argmax(off))
        raise GeometryFileError(f"{name}: node {k} lies off the plane (third coordinate {points[k, 2]:.6g}); "
                                f"a support-surface mesh is flat, (phi, z) with the third coordinate 0")


def _named_curves(m) -> dict:
    """End nodes of the line elements of each named physical curve group."""
    lines = {k: c.data[:, :2] for k, c in enumerate(m.cells) if c.type in ("line", "line3")}
    names = {str(name): (int(v[0]), int(v[1])) for name, v in (m.field_data or {}).items() if len(v) >= 2}
    out: dict[str, list] = {}
    sets = {k: v for k, v in (m.cell_sets or {}).items() if k in names and names[k][1] == 1}
    if sets:  # msh 4: an element can belong to several groups
        for name, per_block in sets.items():
            for k, idx in enumerate(per_block):
                if k in lines and idx is not None and len(idx):
                    out.setdefault(name, []).append(lines[k][np.asarray(idx, dtype=np.int64)])
    else:  # msh 2: one physical tag per element, elements repeated per group
        physical = (m.cell_data or {}).get("gmsh:physical")
        by_tag = {tag: name for name, (tag, dim) in names.items() if dim == 1}
        for k, edges in lines.items():
            if physical is None:
                break
            tags = np.asarray(physical[k])
            for tag, name in by_tag.items():
                sel = edges[tags == tag]
                if len(sel):
                    out.setdefault(name, []).append(sel)
    return {name: np.vstack(parts).T.astype(np.int64) for name, parts in out.items()}


def _short(exc: BaseException) -> str:
    return " ".join(str(exc).split())[:200] or type(exc).__name__


# -- .geo in a separate process ------------------------------------------------------------

def run_geo(path: str | Path, out_msh: str | Path, *, size: float | None = None, order: int = 1,
            trusted: bool = False, timeout: float | None = None, max_elements: int | None = None) -> dict:
    """Mesh a ``.geo`` script with gmsh in a separate process and write a ``.msh`` 4.1 file.

    Parameters
    ----------
    path : str or Path
        The script.
    out_msh : str or Path
        Where the mesh is written (physical groups only, names kept).
    size : float, optional
        Largest element size [-] (gmsh's ``Mesh.MeshSizeMax``).
    order : {1, 2}
        Geometry order.
    trusted : bool
        Skip the allow-list (:func:`check_geo_script`); the script still
        runs in a separate process with the time limit.
    timeout : float, optional
        Seconds for parsing and meshing; default :func:`geo_timeout_limit`.
    max_elements : int, optional
        Element-count limit checked before the surface is meshed; default
        :func:`max_elements_limit`.

    Returns
    -------
    dict
        ``estimate`` (the element-count estimate) and ``elements``.

    Raises
    ------
    UntrustedGeoError, GeometryFileError, MeshSizeError
    """
    path = Path(path)
    limit = max_elements_limit(max_elements)
    seconds = geo_timeout_limit(timeout)
    if not trusted:
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            raise GeometryFileError(f"{path.name} is not a text (UTF-8) .geo script") from None
        check_geo_script(text, path.name)
    with private_tempdir("geo") as work:
        request = dict(geo=str(path.resolve()), out=str(Path(out_msh).resolve()), size=size, order=int(order),
                       max_elements=limit)
        result = run_gmsh_worker(request, work, seconds, path.name,
                                 slow="a loop that does not end, or a very fine mesh?",
                                 how="timeout= (load_mesh), --geo-timeout (bearingfe mesh)",
                                 ended="an Exit or Abort in the script?")
    if result.get("kind") == "too_many":
        check_element_count(result["estimate"], limit, what=f"{path.name}"
                            + (f" with size = {size:g}" if size is not None else ""))
    if "error" in result:
        raise GeometryFileError(f"{path.name}: gmsh failed: {result['error']}")
    return result


def run_gmsh_worker(request: dict, work: str | Path, seconds: float, name: str, *, slow: str, how: str,
                    ended: str) -> dict:
    """Run one request in the gmsh child process (:mod:`bearingfe.geometry.gmsh_worker`) and return its result.

    The child is confined (CPU ``seconds`` + 5, :data:`GEO_MEMORY` of address
    space, death with its parent) and killed with everything it started when
    it is done or after ``seconds`` of wall time.

    Parameters
    ----------
    request : dict
        The task (plain JSON data: never a command); the limits, the parent's
        id and the result file are added here.
    work : str or Path
        A private temporary folder for the request and result files.
    seconds : float
        Wall-time limit [s].
    name : str
        What is meshed, first in every message.
    slow, how, ended : str
        The likely cause of a time-out, how to raise the limit, and the
        likely cause of an early end without a result (for the messages).

    Raises
    ------
    GeometryFileError
        Time-out, or the child ended without writing its result.
    """
    worker = Path(__file__).with_name("gmsh_worker.py")
    request = dict(request, result=str(Path(work) / "result.json"), seconds=seconds, memory=GEO_MEMORY,
                   parent=os.getpid())
    req_file = Path(work) / "request.json"
    req_file.write_text(json.dumps(request))
    code = "import runpy, sys; sys.argv = sys.argv[1:]; runpy.run_path(sys.argv[0], run_name='__main__')"
    proc = subprocess.Popen([sys.executable, "-I", "-c", code, str(worker), str(req_file)], cwd=work,
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            start_new_session=True)
    try:
        output, _ = proc.communicate(timeout=seconds)
    except subprocess.TimeoutExpired:
        _kill(proc)
        raise GeometryFileError(
            f"{name}: gmsh did not finish within {seconds:g} s ({slow}); raise the limit with {how} or "
            f"the environment variable {GEO_TIMEOUT_ENV}") from None
    finally:
        _kill(proc)  # a trusted script may have started children in the worker's session
    result_file = Path(request["result"])
    if not result_file.is_file():
        tail = " ".join(output.decode("utf-8", "replace").split())[-200:]
        raise GeometryFileError(
            f"{name}: gmsh ended (exit status {proc.returncode}) before it made a mesh"
            + (f" ({ended})" if proc.returncode in (0, 1) else
               f" (out of its {GEO_MEMORY / 1024**3:g} GiB of memory or CPU time, or a crash?)")
            + (f": {tail}" if tail else ""))
    return json.loads(result_file.read_text())


def _kill(proc: subprocess.Popen) -> None:
    """End the worker's process group (the worker and anything it started)."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    proc.wait()
