#!/usr/bin/env bash
# Installs the Debian packages bssrdf needs to build and test; a quick no-op when all are present.
# Usage: tools/setup.sh            (as root, or with sudo available)
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libceres-dev libeigen3-dev libopenexr-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libstb-dev
  clang libclang-rt-14-dev
  python3-numpy  # tools/validation/advise_check.py
  libopenmpi-dev openmpi-bin  # MPI runs and their ctest checks (docs/mpi.md); optional for the build
)
# Blender (Cycles) for the export checks that run in the real renderer (tests/test_blender_export.cpp;
# skipped when absent). About 3 minutes and 170 MB; BSSRDF_SKIP_BLENDER=1 leaves it out.
if [ "${BSSRDF_SKIP_BLENDER:-0}" != "1" ]; then packages+=(blender); fi

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
