#!/usr/bin/env bash
# Configures bssrdf in ./build (Release, warnings as errors) and builds it.
# Usage: tools/build.sh           the tool only (build/bssrdf): the quick start
#        tools/build.sh --tests   the tool, the tests, benchmarks and validation drivers: tools/test.sh
# One configuration for both: the compile flags of the library never differ between them, so the
# test build reuses every object the quick start compiled (switching the tests on adds targets, it
# changes no flag). Extra arguments after the first go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-}"
if [ $# -gt 0 ]; then shift; fi
case "$mode" in
  "") tests=OFF targets=(--target bssrdf-cli) ;;
  --tests) tests=ON targets=() ;;
  *) echo "build: unknown argument '$mode' (give nothing, or --tests)" >&2; exit 2 ;;
esac
# The Python module for Debian's interpreter (the one Blender runs and python3-numpy serves), not
# whichever python3 comes first on PATH.
python=()
if [ -x /usr/bin/python3 ]; then python=(-DPython_EXECUTABLE=/usr/bin/python3); fi
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBSSRDF_WERROR=ON -DBSSRDF_UNITY=ON -DBSSRDF_BUILD_TESTS="$tests" \
  -DBSSRDF_BUILD_BENCHMARKS="$tests" "${launcher[@]}" "${python[@]}" "$@" >/dev/null
cmake --build build -j "$(nproc)" "${targets[@]}"
