#!/usr/bin/env bash
# Set up, then run the default scene end to end: results and pictures in out/.
#   bash scripts/run-main.sh                 # into out/
#   bash scripts/run-main.sh DIR             # into DIR
#   bash scripts/run-main.sh [DIR] --force   # any further arguments go to `bearingfe run` (--force, --no-progress, ...)
set -euo pipefail
cd "$(dirname "$0")/.."
out=out
if [[ $# -gt 0 && "$1" != -* ]]; then
    out="$1"
    shift
fi
bash scripts/setup.sh
export VTK_DEFAULT_OPENGL_WINDOW="${VTK_DEFAULT_OPENGL_WINDOW:-vtkEGLRenderWindow}"
export MPLBACKEND=Agg
exec .venv/bin/bearingfe run scenes/pump.toml --out "$out" "$@"
