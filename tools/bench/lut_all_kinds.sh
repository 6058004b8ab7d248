#!/usr/bin/env bash
# The whole materials database in every table kind through the command line, as users run it
# (`bssrdf lut --all --kind K`, files written to a temporary directory): median wall time of RUNS
# runs per kind with one thread and with all threads, and the sum over kinds.
#
#   bash tools/bench/lut_all_kinds.sh [RUNS=5]        (after tools/build.sh; BSSRDF=path overrides build/bssrdf)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${BSSRDF:-build/bssrdf}
runs=${1:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median_ms() {  # median of the arguments
  printf '%s\n' "$@" | sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'
}

echo "bssrdf lut --all: $("$bin" materials list | wc -l) materials, $(nproc) cores, median of $runs runs (ms)"
printf '  %-14s %10s %10s\n' kind "1 thread" "all"
total1=0; totalN=0
for kind in radial albedo-radius transmission preintegrated penumbra separable gaussians; do
  for threads in 1 0; do
    times=()
    for ((i = 0; i < runs; i++)); do
      rm -rf "$out"/*
      start=$(date +%s%N)
      "$bin" lut --all --kind "$kind" --threads "$threads" --output-dir "$out" -q 2>/dev/null
      times+=($(( ($(date +%s%N) - start) / 1000000 )))
    done
    m=$(median_ms "${times[@]}")
    if [ "$threads" = 1 ]; then t1=$m; total1=$((total1 + m)); else tN=$m; totalN=$((totalN + m)); fi
  done
  printf '  %-14s %10s %10s\n' "$kind" "$t1" "$tN"
done
printf '  %-14s %10s %10s\n' "all kinds" "$total1" "$totalN"
