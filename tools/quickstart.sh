#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the main job on a bundled material.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
mkdir -p out
./build/bssrdf lut --material Skin1 --kind radial -o out/skin1-radial.exr
./build/bssrdf lut --material Skin1 --kind separable --taps 25 -q -o out/skin1-kernel.hlsl
./build/bssrdf lut --material Skin1 --preview out/skin1.png
