#!/usr/bin/env bash
# The whole materials database in every table kind through the command line, as users run it
# (`bssrdf lut --all --kind K`, files written to a temporary directory): median wall time of RUNS
# runs per kind with one thread and with all threads, and the sum over kinds.
#
#   bash tools/bench/lut_all_kinds.sh [RUNS=5]        (after tools/build.sh; BSSRDF=path overrides build/bssrdf)
#
# BASELINE=path/to/other/bssrdf: runs it side by side (alternating with the build's binary, so both see
# the same machine load), prints both medians and their ratio, and compares the two binaries' tables of
# every kind and material (tools/bench/lut_compare.py: how far any value moved; accuracy is kept when
# nothing moves beyond rounding).
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${BSSRDF:-build/bssrdf}
baseline=${BASELINE:-}
runs=${1:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median_ms() {  # median of the arguments
  printf '%s\n' "$@" | sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'
}
run_ms() {  # BINARY KIND THREADS: wall time of one run in ms
  rm -rf "${out:?}"/*
  local start=$(date +%s%N)
  "$1" lut --all --kind "$2" --threads "$3" --output-dir "$out" -q 2>/dev/null
  echo $((($(date +%s%N) - start) / 1000000))
}

echo "bssrdf lut --all: $("$bin" materials list | wc -l) materials, $(nproc) cores, median of $runs runs (ms)"
if [ -z "$baseline" ]; then
  printf '  %-14s %10s %10s\n' kind "1 thread" "all"
else
  printf '  %-14s %10s %10s %10s %10s %8s\n' kind "base 1 th" "new 1 th" "base all" "new all" "all/base"
fi
total1=0; totalN=0; base1=0; baseN=0
for kind in radial albedo-radius transmission preintegrated penumbra separable gaussians; do
  for threads in 1 0; do
    times=(); base_times=()
    for ((i = 0; i < runs; i++)); do
      [ -n "$baseline" ] && base_times+=($(run_ms "$baseline" "$kind" "$threads"))
      times+=($(run_ms "$bin" "$kind" "$threads"))
    done
    m=$(median_ms "${times[@]}")
    b=$([ -n "$baseline" ] && median_ms "${base_times[@]}" || echo 0)
    if [ "$threads" = 1 ]; then t1=$m; b1=$b; total1=$((total1 + m)); base1=$((base1 + b)); else
      tN=$m; bN=$b; totalN=$((totalN + m)); baseN=$((baseN + b)); fi
  done
  if [ -z "$baseline" ]; then
    printf '  %-14s %10s %10s\n' "$kind" "$t1" "$tN"
  else
    printf '  %-14s %10s %10s %10s %10s %8s\n' "$kind" "$b1" "$t1" "$bN" "$tN" "$(awk "BEGIN {printf \"%.2f\", $tN / $bN}")"
  fi
done
if [ -z "$baseline" ]; then
  printf '  %-14s %10s %10s\n' "all kinds" "$total1" "$totalN"
  exit 0
fi
printf '  %-14s %10s %10s %10s %10s %8s\n' "all kinds" "$base1" "$total1" "$baseN" "$totalN" \
  "$(awk "BEGIN {printf \"%.2f\", $totalN / $baseN}")"
echo "tables, new against baseline (every material, JSON):"
for kind in radial albedo-radius transmission preintegrated penumbra separable gaussians; do
  mkdir -p "$out/base_$kind" "$out/new_$kind"
  "$baseline" lut --all --kind "$kind" -f json --output-dir "$out/base_$kind" -q 2>/dev/null
  "$bin" lut --all --kind "$kind" -f json --output-dir "$out/new_$kind" -q 2>/dev/null
  printf '  %-14s %s\n' "$kind" "$(/usr/bin/python3 tools/bench/lut_compare.py "$out/base_$kind" "$out/new_$kind")"
done
