#!/usr/bin/env bash
# README command 2: install what is missing, build, and run the whole test suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh -DBSSRDF_WERROR=ON  # CI: warnings are errors here, not in a user's build
cd build
ctest --output-on-failure -j "$(nproc)"
