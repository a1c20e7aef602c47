"""A tilting-pad bearing's reduced coefficients over (rotor speed, whirl frequency), loaded by ROSS 3.x.

:func:`bearingfe.io.writers.write_ross3_bearing` writes the table of
:func:`bearingfe.bearings.tilting_pad.ross_table` as one ROSS 3.x ``BearingElement`` file (2-D
coefficient tables over ``speed`` and ``frequency``). ROSS is not a dependency of this package: this
script runs ROSS 3.x (``ross-rotordynamics`` >= 3.0, Python >= 3.12 for 3.0 and >= 3.13 for 3.1) in its
own interpreter, given by ``--ross-python`` or the environment variable ``ROSS3_PYTHON``, which loads
the file with ``ross.BearingElement.load`` and evaluates ``K(frequency, speed)`` and ``C(frequency,
speed)`` at every tabulated (speed, frequency) point. Every one must equal this package's coefficient to
``1e-12`` relative (of the largest entry of its matrix); the script exits with status 1 otherwise.

The bearing is the five-pad one of ``scenes/journal_tilting.toml`` (D 100 mm, L 50 mm, C_p 80 um, 60-degree
pads, pivots at 60 %, preload 0.25, 3924 N between two pads, 0.015 Pa s) on 5e8 N/m pivots, at five
speeds from 3000 to 9000 rpm and five whirl frequencies of 0.5 to 2.0 times the lowest speed
(ROSS 3.x asks for at least 5 points per axis).

    python -m benchmarks.tilting_pad_ross3 --ross-python /path/to/ross3-venv/bin/python [--out DIR]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from bearingfe.bearings.tilting_pad import TiltingPadBearing, ross_table
from bearingfe.io.writers import write_ross3_bearing

#: The scene's bearing (scenes/journal_tilting.toml) on soft pivots.
BEARING = dict(radius=0.05, length=0.05, pad_clearance=80e-6, n_pads=5, arc=math.radians(60.0), offset=0.6,
               preload=0.25, load_on_pad=False, pad_inertia=2e-5, pad_thickness=0.012, pivot_stiffness=5e8)
LOAD, VISCOSITY = 3924.0, 0.015
RPM = (3000.0, 4500.0, 6000.0, 7500.0, 9000.0)
FREQUENCY_RATIOS = (0.5, 0.875, 1.25, 1.625, 2.0)  # of the lowest speed
TOLERANCE = 1e-12

ROSS_SCRIPT = r"""
import json, sys, warnings
warnings.filterwarnings("ignore")
import numpy as np
import ross
path, points = sys.argv[1], json.loads(sys.argv[2])
b = ross.BearingElement.load(path)
out = [dict(speed=s, frequency=f, K=np.asarray(b.K(frequency=f, speed=s))[:2, :2].tolist(),
            C=np.asarray(b.C(frequency=f, speed=s))[:2, :2].tolist()) for s, f in points]
print("RESULT " + json.dumps(dict(version=ross.__version__, points=out)))
"""


def run(ross_python: str, out: Path, size: float = 0.15, log=print) -> dict:
    """The table, its file, ROSS's coefficients at every tabulated point and the largest relative difference."""
    load_start = list(os.getloadavg())
    bearing = TiltingPadBearing(**BEARING)
    speeds = [r * math.pi / 30 for r in RPM]
    frequencies = [x * speeds[0] for x in FREQUENCY_RATIOS]
    t = time.perf_counter()
    table = ross_table(bearing, LOAD, VISCOSITY, speeds, frequencies, size=size)
    seconds = time.perf_counter() - t
    path = write_ross3_bearing(table, out / "tilting_pad_ross3.toml", n=0, tag="tilting_pad")
    log(f"tilting_pad_ross3: table of {len(speeds)} x {len(frequencies)} in {seconds:.1f} s, {path}")
    points = [(s, f) for s in speeds for f in frequencies]
    r = subprocess.run([ross_python, "-c", ROSS_SCRIPT, str(path), json.dumps(points)], capture_output=True,
                       text=True, timeout=1800)
    line = next((l for l in r.stdout.splitlines() if l.startswith("RESULT ")), None)
    if line is None:
        raise RuntimeError(f"ROSS run failed: {(r.stderr or r.stdout).strip().splitlines()[-3:]}")
    ross = json.loads(line[len("RESULT "):])
    worst, rows = 0.0, []
    for p in ross["points"]:
        i, j = speeds.index(p["speed"]), frequencies.index(p["frequency"])
        ours_K = np.array([[table[f"k{a}{b}"][i][j] for b in "xy"] for a in "xy"])
        ours_C = np.array([[table[f"c{a}{b}"][i][j] for b in "xy"] for a in "xy"])
        err = max(float(np.abs(np.array(p["K"]) - ours_K).max() / np.abs(ours_K).max()),
                  float(np.abs(np.array(p["C"]) - ours_C).max() / np.abs(ours_C).max()))
        worst = max(worst, err)
        rows.append(dict(speed=p["speed"], frequency=p["frequency"], relative_difference=err,
                         kxx=ours_K[0, 0], kyy=ours_K[1, 1], cxx=ours_C[0, 0], cyy=ours_C[1, 1]))
    res = dict(ross_version=ross["version"], file=str(path), points=rows, worst=worst, tolerance=TOLERANCE,
               table_seconds=seconds, load=load_start + list(os.getloadavg()))
    (out / "tilting_pad_ross3.json").write_text(json.dumps(res, indent=1) + "\n")
    return res


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ross-python", default=os.environ.get("ROSS3_PYTHON"),
                        help="interpreter with ROSS 3.x (default: $ROSS3_PYTHON)")
    parser.add_argument("--out", default=None, help="folder for the file and the result (default: a new temporary one)")
    parser.add_argument("--size", type=float, default=0.15, help="element size of the pad meshes [R]")
    args = parser.parse_args(argv)
    if not args.ross_python:
        parser.error("give --ross-python or ROSS3_PYTHON (ROSS 3.x is not a dependency of this package)")
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="tilting_pad_ross3_"))
    out.mkdir(parents=True, exist_ok=True)
    res = run(args.ross_python, out, size=args.size)
    for p in res["points"]:
        print(f"speed {p['speed']:9.3f} rad/s  frequency {p['frequency']:9.3f} rad/s  kxx {p['kxx']:.6e} N/m  "
              f"cyy {p['cyy']:.6e} N s/m  relative difference {p['relative_difference']:.2e}")
    ok = res["worst"] <= TOLERANCE
    print(f"ROSS {res['ross_version']} loads {res['file']}: largest relative difference {res['worst']:.2e} "
          f"({'within' if ok else 'NOT within'} {TOLERANCE:g}); load average {res['load']}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
