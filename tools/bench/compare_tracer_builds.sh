#!/usr/bin/env bash
# Two builds of the Monte Carlo tracer side by side, for a change that must not change a result:
# fixed-seed `bssrdf reference` runs (implicit capture and analog absorption, half-space, slab, layer
# stack, depth bins, MCML's roulette; every BSSRDF_MC_SIMD path: default, avx2, sse2, nofma, where a build
# that does not know a value takes its default) must be bitwise identical in every number but the
# timings; then one-thread CPU time of both, alternating, median of RUNS each and the ratio after/before.
#
#   bash tools/bench/compare_tracer_builds.sh BEFORE_BINARY AFTER_BINARY [RUNS=7]
set -euo pipefail
cd "$(dirname "$0")/../.."
before=$1 after=$2 runs=${3:-7}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cases=(
  "--material Skin1 --photons 200000 --seed 1"
  "--material Skin1 --photons 200000 --seed 1 --depth-bins 50"
  "--material marble --photons 100000 --seed 7 --absorption analog --depth-bins 20"
  "--sigma-a 0.1 --sigma-s 5 --g 0.8 --eta 1.4 --thickness 0.7 --photons 100000 --seed 2 --bin-spacing log"
  "--layers tests/data/two_layer_skin.json --photons 100000 --seed 3"
  "--material Skin1 --photons 50000 --seed 5 --roulette-threshold 1e-4 --roulette-survival 0.1"
)
# Every number of the JSON report but the run's own timings.
results() { python3 -c '
import json, sys
def strip(o):
    if isinstance(o, dict): return {k: strip(v) for k, v in o.items() if k not in ("seconds", "photons_per_second")}
    if isinstance(o, list): return [strip(v) for v in o]
    return o
print(json.dumps(strip(json.load(open(sys.argv[1]))), sort_keys=True))' "$1"; }
differ=0
for simd in default avx2 sse2 nofma; do
  for c in "${cases[@]}"; do
    for side in before after; do
      bin=$before; [ $side = after ] && bin=$after
      # shellcheck disable=SC2086
      BSSRDF_MC_SIMD=$simd "$bin" reference $c -j 2 -f json -q -o "$out/$side.json"
    done
    if [ "$(results "$out/before.json")" != "$(results "$out/after.json")" ]; then
      echo "DIFFERENT ($simd): reference $c"
      differ=1
    fi
  done
done
[ $differ = 0 ] && echo "identical: ${#cases[@]} cases x 4 SIMD paths"

cpu_seconds() {  # user CPU seconds of one run on one thread (robust on a shared machine)
  local TIMEFORMAT=%U
  { time "$@" -j 1 -f json -q -o "$out/t.json" 2>/dev/null; } 2>&1
}
median() { printf '%s\n' "$@" | sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
for c in "--material Skin1 --photons 1000000" "--material marble --photons 300000 --absorption analog"; do
  b=() a=()
  for ((i = 1; i <= runs; i++)); do
    # shellcheck disable=SC2086
    b+=($(cpu_seconds "$before" reference $c --seed $i))
    # shellcheck disable=SC2086
    a+=($(cpu_seconds "$after" reference $c --seed $i))
  done
  mb=$(median "${b[@]}") ma=$(median "${a[@]}")
  echo "reference $c, 1 thread, CPU s (median of $runs): before $mb, after $ma, after/before $(python3 -c "print(f'{$ma / $mb:.3f}')")"
done
exit $differ
