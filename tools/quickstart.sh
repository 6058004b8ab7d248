#!/usr/bin/env bash
# README command 1: install what the tool needs, build the tool, and write Skin1's tables into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
mkdir -p out
./build/bssrdf lut --material Skin1 --kind radial -o out/skin1-radial.exr
./build/bssrdf lut --material Skin1 --kind separable --taps 25 -q -o out/skin1-kernel.hlsl
./build/bssrdf lut --material Skin1 --preview out/skin1.png
