"""Files users open elsewhere: VTU/PVD for ParaView, CSV trajectories, JSON summaries.

Every writer is atomic: it writes a temporary file next to the target and
renames it into place only when complete, so a failure never leaves a
half-written file behind (an existing file stays as it was). Written files
get the mode the process umask gives (``0o666 & ~umask``), as ``open`` would.
"""

from __future__ import annotations

import base64
import contextlib
import csv
import json
import math
import os
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Iterator, Mapping, Sequence
from xml.sax.saxutils import escape

import numpy as np

from ..core.limits import check_limit

__all__ = ["atomic_path", "umask", "vtu_fields", "write_vtu", "vtu_document", "write_pvd", "read_pvd", "write_csv",
           "write_json", "ROSS_COEFFICIENTS", "write_ross_bearings", "read_ross_bearing"]

#: Trajectory columns written by :func:`write_csv` when present, in this order.
CSV_FIELDS = ("beta", "gamma", "delta", "phi0", "h_min", "friction_moment", "flow_inlet", "flow_side",
              "flow_arc_start", "flow_arc_end", "flow_squeeze", "inlet_pressure", "load")


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; rename it onto ``path`` on success, remove it on failure."""
    path = Path(path)
    if not path.parent.is_dir():
        raise FileNotFoundError(f"directory does not exist: {path.parent}")
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    tmp = Path(tmp)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~umask())  # mkstemp made it 0600
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def umask() -> int:
    """The process umask (read without changing it where ``/proc`` allows)."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("Umask:"):
                return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)  # elsewhere: set and restore at once
    os.umask(mask)
    return mask


def vtu_fields(result, scale=None) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Points (n, 3), triangles (m, 3) and point data of a result's VTU file.

    With ``scale`` (:class:`bearingfe.core.scales.Scale`) the points are the
    unwrapped surface in metres ``(R0 phi, R0 z, 0)`` and the fields SI:
    ``pressure_Pa``, ``film_thickness_m`` (and ``deflection_m`` on an elastic
    support), the solver's values kept as ``pressure_nondimensional``,
    ``film_thickness_nondimensional`` (``deflection_nondimensional``). Without
    it only the non-dimensional fields, on the points ``(phi, z, 0)`` [R0].
    P2 results give their vertex values.
    """
    m = result.basis.mesh
    nv = int(m.nvertices)
    t = np.asarray(m.t[:3]).T
    xy = np.asarray(m.p[:, :nv], dtype=float)
    nd = {"pressure": np.asarray(result.pressure, dtype=float)[:nv],
          "film_thickness": np.asarray(result.film.thickness(xy[0], xy[1]), dtype=float)}
    deflection = getattr(result, "deflection", None)
    if deflection is not None:
        nd["deflection"] = np.asarray(deflection, dtype=float)[:nv]
    data = {f"{k}_nondimensional": v for k, v in nd.items()}
    if scale is None:
        return np.column_stack([xy[0], xy[1], np.zeros(nv)]), t, data
    si = {"pressure_Pa": nd["pressure"] * scale.pressure, "film_thickness_m": nd["film_thickness"] * scale.clearance}
    if "deflection" in nd:
        si["deflection_m"] = nd["deflection"] * scale.clearance
    points = np.column_stack([xy[0] * scale.radius, xy[1] * scale.radius, np.zeros(nv)])
    return points, t, {**si, **data}


def write_vtu(result, path: str | Path, scale=None, *, field_data: Mapping[str, float] | None = None) -> Path:
    """Write a result's mesh and fields as VTU (see :func:`vtu_fields` for the arrays and units).

    Parameters
    ----------
    result : ReynoldsResult
    path : str or Path
        Target ``.vtu`` file.
    scale : Scale, optional
        Write SI fields on a mesh in metres besides the non-dimensional ones.
    field_data : mapping, optional
        Named numbers of the whole frame (e.g. ``shaft_angle_deg``), written as VTK field data.

    Returns
    -------
    Path
    """
    path = Path(path)
    if path.suffix != ".vtu":
        raise ValueError(f"path must end in .vtu, got {path.name}")
    points, t, data = vtu_fields(result, scale)
    with atomic_path(path) as tmp:
        tmp.write_bytes(vtu_document(points, t, data, field_data))
    return path


#: VTK's cell type of a linear triangle.
VTK_TRIANGLE = 5
#: Quotes escaped in an XML attribute.
_QUOTE = {'"': "&quot;"}


def _binary(values: np.ndarray) -> str:
    """A VTK XML ``binary`` data array: base64 of its byte count (UInt64) and its little-endian bytes."""
    raw = np.ascontiguousarray(values).astype(values.dtype.newbyteorder("<"), copy=False).tobytes()
    return base64.b64encode(np.uint64(len(raw)).astype("<u8").tobytes() + raw).decode("ascii")


def vtu_document(points: np.ndarray, triangles: np.ndarray, point_data: Mapping[str, np.ndarray],
                 field_data: Mapping[str, float] | None = None) -> bytes:
    """A VTK XML unstructured grid of triangles (the ``.vtu`` format ParaView and VTK read).

    Parameters
    ----------
    points : ndarray, shape (n, 3)
        Point coordinates (as given: [m] or [R0]).
    triangles : ndarray, shape (m, 3)
        Point indices of each triangle.
    point_data : mapping
        Named arrays of ``n`` values each (Float64).
    field_data : mapping, optional
        Named numbers of the whole grid (one Float64 each, written in ASCII).

    Returns
    -------
    bytes
        The document: arrays base64-encoded (``format="binary"``, a UInt64 byte count before each), little-endian.
    """
    points = np.asarray(points, dtype=np.float64)
    cells = np.asarray(triangles, dtype=np.int64)
    n, m = points.shape[0], cells.shape[0]
    if points.shape != (n, 3) or cells.shape != (m, 3):
        raise ValueError(f"points must be (n, 3) and triangles (m, 3), got {points.shape} and {cells.shape}")
    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">',
             "<UnstructuredGrid>"]
    if field_data:
        lines.append("<FieldData>")
        lines += [f'<DataArray type="Float64" Name="{escape(name, _QUOTE)}" NumberOfTuples="1" format="ascii">'
                  f"{float(value)!r}</DataArray>" for name, value in field_data.items()]
        lines.append("</FieldData>")
    lines += [f'<Piece NumberOfPoints="{n}" NumberOfCells="{m}">',
              "<PointData>"]
    for name, values in point_data.items():
        values = np.asarray(values, dtype=np.float64)
        if values.shape != (n,):
            raise ValueError(f"point data {name!r} must hold {n} values, got shape {values.shape}")
        lines.append(f'<DataArray type="Float64" Name="{escape(name, _QUOTE)}" format="binary">'
                     f"{_binary(values)}</DataArray>")
    lines += ["</PointData>", "<Points>",
              f'<DataArray type="Float64" NumberOfComponents="3" format="binary">{_binary(points)}</DataArray>',
              "</Points>", "<Cells>",
              f'<DataArray type="Int64" Name="connectivity" format="binary">{_binary(cells)}</DataArray>',
              f'<DataArray type="Int64" Name="offsets" format="binary">'
              f"{_binary(np.arange(3, 3 * m + 1, 3, dtype=np.int64))}</DataArray>",
              f'<DataArray type="UInt8" Name="types" format="binary">'
              f"{_binary(np.full(m, VTK_TRIANGLE, dtype=np.uint8))}</DataArray>",
              "</Cells>", "</Piece>", "</UnstructuredGrid>", "</VTKFile>", ""]
    return "\n".join(lines).encode("utf-8")


def write_pvd(results_or_paths: Sequence, times: Sequence[float], path: str | Path, *,
              max_frames: int | None = None, scale=None, angles: Sequence[float] | None = None) -> Path:
    """Write a ParaView time series (``.pvd``) referencing one VTU per time.

    Parameters
    ----------
    results_or_paths : sequence
        Either results (each written as ``<stem>_<k>.vtu`` next to ``path``)
        or paths of existing ``.vtu`` files.
    times : sequence of float
        Time value of each entry (e.g. the time from the start [s]), strictly increasing.
    path : str or Path
        Target ``.pvd`` file.
    max_frames : int, optional
        Most entries accepted; default the ``frames`` limit of
        :mod:`bearingfe.core.limits` (1000).
    scale : Scale, optional
        Results are written with SI fields (:func:`write_vtu`).
    angles : sequence of float, optional
        Shaft angle of each entry [deg], written into its VTU as field data ``shaft_angle_deg``.

    Returns
    -------
    Path
    """
    path = Path(path)
    if path.suffix != ".pvd":
        raise ValueError(f"path must end in .pvd, got {path.name}")
    if hasattr(results_or_paths, "__len__"):  # before a generator is drawn out
        check_limit("frames", len(results_or_paths), max_frames, "max_frames")
    items = list(results_or_paths)
    check_limit("frames", len(items), max_frames, "max_frames")
    times = np.asarray(times, dtype=float).ravel()
    if times.size != len(items) or not items:
        raise ValueError(f"times must have one value per entry ({len(items)}), got {times.size}")
    if not (np.all(np.isfinite(times)) and np.all(np.diff(times) > 0)):
        raise ValueError("times must be finite and strictly increasing")
    angles = None if angles is None else np.asarray(angles, dtype=float).ravel()
    if angles is not None and angles.size != len(items):
        raise ValueError(f"angles must have one value per entry ({len(items)}), got {angles.size}")
    files = []
    for k, item in enumerate(items):
        if isinstance(item, (str, Path)):
            f = Path(item)
            if not f.is_file():
                raise FileNotFoundError(f"VTU file not found: {f}")
        else:
            extra = {"time_s": times[k]} if scale is not None else {}
            if angles is not None:
                extra["shaft_angle_deg"] = angles[k]
            f = write_vtu(item, path.with_name(f"{path.stem}_{k:04d}.vtu"), scale, field_data=extra)
        files.append(os.path.relpath(f.resolve(), path.parent.resolve()))
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    coll = ET.SubElement(root, "Collection")
    for t, f in zip(times, files):
        ET.SubElement(coll, "DataSet", timestep=repr(float(t)), group="", part="0", file=Path(f).as_posix())
    ET.indent(root)
    with atomic_path(path) as tmp:
        ET.ElementTree(root).write(tmp, encoding="utf-8", xml_declaration=True)
    return path


def read_pvd(path: str | Path) -> list[tuple[float, Path]]:
    """``(time, vtu path)`` pairs of a ``.pvd`` file (paths resolved against its directory)."""
    path = Path(path)
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), path.parent / d.get("file")) for d in root.iter("DataSet")]


def _column(traj, name):
    value = traj[name] if isinstance(traj, Mapping) else getattr(traj, name, None)
    if value is None:
        return None
    arr = np.asarray(value, dtype=float)
    return arr if arr.ndim == 1 else None


def write_csv(traj, path: str | Path, fields: Sequence[str] | None = None) -> Path:
    """Write a trajectory's 1-D arrays as CSV columns.

    Parameters
    ----------
    traj : Trajectory-like or mapping
        Object (or dict) with equal-length 1-D arrays.
    path : str or Path
    fields : sequence of str, optional
        Columns to write (all must exist); default: those of
        :data:`CSV_FIELDS` present (``beta`` required).
    """
    path = Path(path)
    names = list(fields) if fields is not None else [f for f in CSV_FIELDS if _has(traj, f)]
    if fields is None and "beta" not in names:
        raise ValueError("trajectory has no 'beta' array (shaft angle)")
    cols = {}
    for name in names:
        col = _column(traj, name) if _has(traj, name) else None
        if col is None:
            raise ValueError(f"trajectory has no 1-D array {name!r}")
        cols[name] = col
    n = {c.size for c in cols.values()}
    if len(n) != 1:
        raise ValueError(f"trajectory columns differ in length: { {k: v.size for k, v in cols.items()} }")
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(names)
        for row in zip(*cols.values()):
            writer.writerow([repr(float(v)) for v in row])
    return path


def _has(traj, name) -> bool:
    return name in traj if isinstance(traj, Mapping) else hasattr(traj, name)


def _jsonable(value):
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return [_jsonable(v) for v in value.tolist()]
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        value = float(value)
        if not math.isfinite(value):
            return None  # JSON has no NaN/inf
        return value
    if isinstance(value, Path):
        return str(value)
    if value is None or isinstance(value, (bool, int, str)):
        return value
    raise ValueError(f"cannot write {type(value).__name__} to JSON: {value!r}")


def write_json(summary: Mapping, path: str | Path) -> Path:
    """Write a summary mapping as indented JSON (numpy scalars and arrays converted, NaN -> null)."""
    path = Path(path)
    if not isinstance(summary, Mapping):
        raise ValueError(f"summary must be a mapping, got {type(summary).__name__}")
    text = json.dumps(_jsonable(summary), indent=2, sort_keys=False)
    with atomic_path(path) as tmp:
        tmp.write_text(text + "\n")
    return path


# -- ROSS bearing files ---------------------------------------------------------------------------

#: Coefficients of a ``ross.BearingElement`` file and their units: stiffness [N/m], damping [N s/m].
ROSS_COEFFICIENTS = {"kxx": "N/m", "kxy": "N/m", "kyx": "N/m", "kyy": "N/m",
                     "cxx": "N s/m", "cxy": "N s/m", "cyx": "N s/m", "cyy": "N s/m"}


def _toml_value(v) -> str:
    if isinstance(v, str):
        return json.dumps(v)  # a TOML basic string is a JSON string
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    f = float(v)
    if not math.isfinite(f):
        raise ValueError(f"a ROSS bearing file holds finite numbers only, got {v!r}")
    return repr(f)


def write_ross_bearings(table: Mapping, folder: str | Path, *, n: int = 0, tag: str = "bearing") -> list[Path]:
    """Write coefficients over (rotor speed, whirl frequency) as ROSS bearing files, one per speed.

    ROSS (up to its 2.4 release) keeps a bearing's coefficients as functions of one frequency: a
    ``BearingElement`` has 1-D ``kxx ... cyy`` over ``frequency`` [rad/s], and ``BearingElement.save``
    writes them as a TOML table ``[BearingElement_<tag>]`` holding its constructor's keywords, which
    ``ross.BearingElement.load(file)`` reads back. A table over speed and frequency is therefore
    written as one such file per rotor speed, ``<tag>_<speed>rpm.toml`` (the speed to 6 digits, a
    decimal point written ``p``), each with the coefficients of
    that speed over the whirl frequencies; ``speed`` [rad/s] is kept in each file too (an extra key,
    which ``load`` passes on as a keyword ROSS ignores).

    Parameters
    ----------
    table : mapping
        ``speed`` (m,) and ``frequency`` (f,) [rad/s] and the coefficients of :data:`ROSS_COEFFICIENTS`
        as arrays (m, f) (as :func:`bearingfe.bearings.tilting_pad.ross_table` returns).
    folder : str or Path
        Existing folder for the files.
    n : int
        The rotor node of the bearing (``BearingElement(n=...)``).
    tag : str
        Element tag: letters, digits, ``_`` and ``-``.

    Returns
    -------
    list of Path
        The files, in the order of the speeds.
    """
    if not (isinstance(tag, str) and tag and all(ch.isalnum() or ch in "_-" for ch in tag)):
        raise ValueError(f"tag must be letters, digits, '_' or '-', got {tag!r}")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise ValueError(f"n must be a node number >= 0, got {n!r}")
    speeds, freqs = np.asarray(table["speed"], float), np.asarray(table["frequency"], float)
    if speeds.ndim != 1 or freqs.ndim != 1 or not speeds.size or not freqs.size:
        raise ValueError("speed and frequency must be non-empty 1-D arrays")
    values = {}
    for name in ROSS_COEFFICIENTS:
        v = np.asarray(table[name], float)
        if v.shape != (speeds.size, freqs.size):
            raise ValueError(f"{name} must have the shape (speeds, frequencies) = {(speeds.size, freqs.size)}, "
                             f"got {v.shape}")
        values[name] = v
    rpm = speeds * 30.0 / math.pi
    labels = [f"{tag}_{r:.6g}rpm".replace(".", "p") for r in rpm]  # no dot: it splits a TOML key
    names = [f"{label}.toml" for label in labels]
    if len(set(names)) != len(names):
        raise ValueError("two speeds give the same file name: speeds must differ by more than 1e-6 relative")
    out = []
    for i, name in enumerate(names):
        fields = {"n": int(n), "tag": labels[i], "scale_factor": 1,
                  **{k: v[i] for k, v in values.items()}, "frequency": freqs, "speed": float(speeds[i])}
        text = f'["BearingElement_{labels[i]}"]\n' + "".join(f"{k} = {_toml_value(v)}\n" for k, v in fields.items())
        path = Path(folder) / name
        with atomic_path(path) as tmp:
            tmp.write_text(text)
        out.append(path)
    return out


#: Every coefficient table of a ROSS 3.x ``BearingElement``: stiffness [N/m], damping [N s/m], mass [kg];
#: ``BearingElement.save`` writes them all, over both axes, with ``kyy``, ``cyy``, ``myy`` given.
ROSS3_COEFFICIENTS = {**{f"k{a}": "N/m" for a in ("xx", "yy", "xy", "yx", "zz")},
                      **{f"c{a}": "N s/m" for a in ("xx", "yy", "xy", "yx", "zz")},
                      **{f"m{a}": "kg" for a in ("xx", "yy", "xy", "yx", "zz")}}

#: The interpolations a ROSS 3.x table takes along each axis.
ROSS3_INTERPOLATION = ("pchip", "linear")


def write_ross3_bearing(table: Mapping, path: str | Path, *, n: int = 0, tag: str = "bearing",
                        interpolation: str = "pchip", color: str = "#355d7a") -> Path:
    """Write coefficients over (rotor speed, whirl frequency) as one ROSS 3.x bearing file.

    ROSS 3.x keeps a ``BearingElement``'s coefficients as a two-dimensional table: given both axes
    ``speed`` and ``frequency`` [rad/s], each of ``kxx ... mzz`` has the shape ``(len(speed),
    len(frequency))`` and is interpolated along the speed first, then the frequency. Its ``save``
    writes a TOML table ``[BearingElement_<tag>]`` with the keys in sorted order: ``color``, the
    fifteen coefficient tables (:data:`ROSS3_COEFFICIENTS`), ``frequency``, ``interpolation``, ``n``,
    ``scale_factor``, ``speed``, ``tag`` (``n_link`` and ``radial_clearance`` left out when absent);
    ``ross.BearingElement.load(path)`` builds the element from it. This writes exactly that: the table's
    ``kxx ... cyy``, the axial and mass tables zero.

    Parameters
    ----------
    table : mapping
        ``speed`` (m,) and ``frequency`` (f,) [rad/s], each increasing, and the coefficients of
        :data:`ROSS_COEFFICIENTS` as arrays (m, f) (as :func:`bearingfe.bearings.tilting_pad.ross_table`
        returns).
    path : str or Path
        The file (``.toml``); its folder must exist.
    n : int
        The rotor node of the bearing (``BearingElement(n=...)``).
    tag : str
        Element tag: letters, digits, ``_`` and ``-``.
    interpolation : {"pchip", "linear"}
        ROSS's interpolation along each axis.
    color : str
        ROSS's drawing colour.

    Returns
    -------
    Path
    """
    if not (isinstance(tag, str) and tag and all(ch.isalnum() or ch in "_-" for ch in tag)):
        raise ValueError(f"tag must be letters, digits, '_' or '-', got {tag!r}")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise ValueError(f"n must be a node number >= 0, got {n!r}")
    if interpolation not in ROSS3_INTERPOLATION:
        raise ValueError(f"interpolation must be one of {ROSS3_INTERPOLATION}, got {interpolation!r}")
    path = Path(path)
    if path.suffix != ".toml":
        raise ValueError(f"path must end in .toml, got {str(path)!r}")
    speeds, freqs = np.asarray(table["speed"], float), np.asarray(table["frequency"], float)
    for name, axis in (("speed", speeds), ("frequency", freqs)):
        if axis.ndim != 1 or not axis.size or not np.all(np.diff(axis) > 0):
            raise ValueError(f"{name} must be a non-empty increasing 1-D array, got {axis!r}")
    fields = {"color": color}
    for name in sorted(ROSS3_COEFFICIENTS):
        v = np.asarray(table[name], float) if name in ROSS_COEFFICIENTS else np.zeros((speeds.size, freqs.size))
        if v.shape != (speeds.size, freqs.size):
            raise ValueError(f"{name} must have the shape (speeds, frequencies) = {(speeds.size, freqs.size)}, "
                             f"got {v.shape}")
        fields[name] = v
    fields.update(frequency=freqs, interpolation=interpolation, n=int(n), scale_factor=1, speed=speeds, tag=tag)
    fields = dict(sorted(fields.items()))
    text = f'["BearingElement_{tag}"]\n' + "".join(f"{k} = {_toml_value(v)}\n" for k, v in fields.items())
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return path


def read_ross_bearing(path: str | Path) -> dict:
    """The keywords of the one ``ross.BearingElement`` in a ROSS bearing file (TOML or JSON), as
    ``BearingElement.load`` reads them: the first table's fields, coefficient lists as arrays (2-D over
    speed and frequency in a ROSS 3.x file, :func:`write_ross3_bearing`)."""
    import tomllib

    path = Path(path)
    data = json.loads(path.read_text()) if path.suffix == ".json" else tomllib.loads(path.read_text())
    if not data:
        raise ValueError(f"{path}: no element in the file")
    fields = dict(next(iter(data.values())))
    return {k: (np.asarray(v, float) if isinstance(v, list) else v) for k, v in fields.items()}
