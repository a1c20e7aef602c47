#!/usr/bin/env bash
# Set up bearingfe on a fresh Debian machine with nothing but Python:
# system libraries that gmsh and VTK load at run time, a virtual environment
# in .venv, and the package with its test extras from PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."

# gmsh's wheel links libGLU/libGL/X11; VTK renders off-screen through EGL (shared/PLATFORM.md).
SYSTEM_PACKAGES="libglu1-mesa libgl1 libxrender1 libxcursor1 libxft2 libxinerama1 libgomp1 libegl1 libegl-mesa0"

missing=""
if command -v dpkg-query >/dev/null 2>&1; then
  for pkg in $SYSTEM_PACKAGES; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "ok installed" || missing="$missing $pkg"
  done
fi
apt_install() {
  if [ "$(id -u)" = 0 ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@"
  elif command -v sudo >/dev/null 2>&1; then
    sudo apt-get update -qq && sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@"
  else
    echo "setup: please install these Debian packages first:$*" >&2; exit 1
  fi
}
if [ -n "$missing" ]; then
  echo "setup: installing system libraries:$missing"
  apt_install $missing >/dev/null
fi

PYTHON="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
  if ! "$PYTHON" -m venv .venv >/dev/null 2>&1; then
    rm -rf .venv
    apt_install python3-venv >/dev/null
    "$PYTHON" -m venv .venv
  fi
fi
.venv/bin/python -m pip install -q --upgrade pip >/dev/null
.venv/bin/python -m pip install -q -e ".[test]"
