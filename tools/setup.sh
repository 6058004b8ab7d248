#!/usr/bin/env bash
# Installs the Debian packages bssrdf needs; a quick no-op when all are present.
# Usage: tools/setup.sh           what building and running the tool needs (the quick start)
#        tools/setup.sh --tests   that plus what the test suite needs (tools/test.sh, CI)
# As root, or with sudo available. BSSRDF_SKIP_BLENDER=1 leaves Blender out of --tests.
set -euo pipefail

packages=(
  g++ make cmake pkg-config
  libceres-dev libeigen3-dev libopenexr-dev nlohmann-json3-dev libcli11-dev
  libstb-dev
  # The Python module's build dependencies are here, not with the tests: finding them turns on
  # position-independent library objects, and the test build must reuse the quick start's.
  pybind11-dev python3-dev
)
if [ "${1:-}" = "--tests" ]; then
  packages+=(
    libgtest-dev libgmock-dev libbenchmark-dev
    clang libclang-rt-14-dev  # tools/sanitize.sh: libFuzzer
    python3-numpy             # tools/validation/advise_check.py, the Python module
    python3-pytest python3-matplotlib  # the Python module's tests and examples/
    libopenmpi-dev openmpi-bin  # MPI runs and their ctest checks (docs/mpi.md); only the CLI's link changes
  )
  # Blender (Cycles) for the export checks that run in the real renderer (tests/test_blender_export.cpp;
  # skipped when absent). About 3 minutes and 170 MB.
  if [ "${BSSRDF_SKIP_BLENDER:-0}" != "1" ]; then packages+=(blender); fi
elif [ -n "${1:-}" ]; then
  echo "setup: unknown argument '$1' (give nothing, or --tests)" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
