#!/usr/bin/env bash
# Set up, then run the default scene end to end: results and pictures in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export VTK_DEFAULT_OPENGL_WINDOW="${VTK_DEFAULT_OPENGL_WINDOW:-vtkEGLRenderWindow}"
export MPLBACKEND=Agg
.venv/bin/bearingfe run scenes/pump.toml --out "${1:-out}"
