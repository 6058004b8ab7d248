#!/usr/bin/env bash
# Configures and builds bssrdf in ./build (Release). Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
# The Python module for Debian's interpreter (the one Blender runs and python3-numpy serves), not
# whichever python3 comes first on PATH.
python=()
[ -x /usr/bin/python3 ] && python=(-DPython_EXECUTABLE=/usr/bin/python3)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${python[@]}" "$@" >/dev/null
cmake --build build -j "$(nproc)"
