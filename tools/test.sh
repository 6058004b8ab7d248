#!/usr/bin/env bash
# README command 2: add the test dependencies, build the tests on the quick start's build (nothing of
# the library is compiled again), and run the whole suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh --tests
bash tools/build.sh --tests
cd build
ctest --output-on-failure -j "$(nproc)"
