#!/usr/bin/env bash
# Set up (as scripts/setup.sh, plus the docs extra), then build the documentation site into
# docs/_build/html with every warning an error. The example gallery runs every example while building.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/python -m pip install -q -e ".[docs]"
export VTK_DEFAULT_OPENGL_WINDOW="${VTK_DEFAULT_OPENGL_WINDOW:-vtkEGLRenderWindow}"
export MPLBACKEND=Agg
.venv/bin/python -m sphinx -W --keep-going -q -b html docs docs/_build/html "$@"
echo "docs: docs/_build/html/index.html"
