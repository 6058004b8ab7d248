#!/usr/bin/env bash
# MPI runs (docs/mpi.md), under `mpirun -np 2 --oversubscribe` on any machine:
#   identity  bssrdf reference at 1 process, 2 and 3 ranks: the same tallies, bitwise (JSON less
#             the timing and rank fields), for one and three channels
#   killed    a rank killed mid-run: non-zero status, one line of ours on stderr, no output file
#   exact     generate_exact_table run at 1 process and 2 ranks: the same state files, byte for byte
#             but for the recorded wall time, and a 2-rank run resuming a 1-process state reaches them too
#
#   bash tests/mpi/mpi_runs.sh identity|killed|exact BSSRDF GENERATE_EXACT_TABLE
set -euo pipefail
what=$1 bin=$2 generator=$3
py=/usr/bin/python3
mpi=(mpirun --oversubscribe --allow-run-as-root --quiet)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# The tallies of a reference JSON without what legitimately differs (time, threads, ranks).
tallies() {
  "$py" -c 'import json,sys
d = json.load(open(sys.argv[1]))
for k in ("seconds", "photons_per_second", "threads", "ranks", "communication_bytes", "communication_seconds"):
    d.pop(k, None)
print(json.dumps(d, sort_keys=True))' "$1"
}

case $what in
identity)
  # 600000 photons: 147 batches of 4096 = 3 chunks per channel, dealt unevenly to the ranks.
  for medium in "--sigma-a 0.05 --sigma-s 4 --g 0.8 --eta 1.4" "--material skin1 --unit mm"; do
    args=(reference $medium --photons 600000 --bins 50 --depth-bins 10 -f json)
    "$bin" "${args[@]}" --threads 2 -o "$work/one.json" >/dev/null
    timeout 300 "${mpi[@]}" -np 2 "$bin" "${args[@]}" --threads 2 -o "$work/two.json" >/dev/null
    timeout 300 "${mpi[@]}" -np 3 "$bin" "${args[@]}" --threads 1 -o "$work/three.json" >/dev/null
    [ "$(tallies "$work/one.json")" = "$(tallies "$work/two.json")" ] || fail "1 and 2 ranks differ ($medium)"
    [ "$(tallies "$work/one.json")" = "$(tallies "$work/three.json")" ] || fail "1 and 3 ranks differ ($medium)"
    "$py" -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["ranks"] == 2 and d["communication_bytes"] > 0, d' \
      "$work/two.json" || fail "2-rank JSON lacks ranks or communication_bytes"
    if "$py" -c 'import json,sys; sys.exit("ranks" in json.load(open(sys.argv[1])))' "$work/one.json"; then :; else
      fail "1-process JSON names ranks"
    fi
  done
  echo "identity: 1, 2 and 3 ranks give the same tallies"
  ;;
killed)
  # Rank 1 is killed two seconds into a run of minutes (on a loaded machine maybe before MPI_Init).
  set +e
  timeout 120 "${mpi[@]}" -np 2 sh -c 'if [ "$OMPI_COMM_WORLD_RANK" = 1 ]; then (sleep 2; kill -9 $$) & fi
    exec "$0" reference --sigma-a 0.01 --sigma-s 10 --photons 2000000000 --threads 1 -f json -o "$1"' \
    "$bin" "$work/out.json" >"$work/stdout" 2>"$work/stderr"
  status=$?
  set -e
  cat "$work/stderr"
  [ "$status" -ne 0 ] || fail "status 0 after a rank was killed"
  [ "$status" -ne 124 ] || fail "the run hung after a rank was killed"
  [ ! -e "$work/out.json" ] || fail "output written after a rank was killed"
  [ "$(grep -c '^bssrdf: error: MPI run stopped' "$work/stderr")" = 1 ] || fail "not exactly one line of ours"
  [ "$(grep -c '^bssrdf' "$work/stderr")" = 1 ] || fail "more than one line of ours"
  echo "killed: status $status, one line, no output"
  ;;
exact)
  focus=(--runs 0.01 --g-max 0.1 --eta-max 1.15 --chunk 1000)
  "$generator" run --state "$work/one" --photons 3000 "${focus[@]}" 2>/dev/null
  timeout 300 "${mpi[@]}" -np 2 "$generator" run --state "$work/two" --photons 3000 "${focus[@]}" 2>/dev/null
  "$generator" run --state "$work/resumed" --photons 1000 "${focus[@]}" 2>/dev/null
  timeout 300 "${mpi[@]}" -np 2 "$generator" run --state "$work/resumed" --photons 3000 "${focus[@]}" 2>/dev/null
  n=$(ls "$work/one" | wc -l)
  [ "$n" -ge 3 ] || fail "only $n state files"
  for d in two resumed; do
    [ "$(ls "$work/$d" | wc -l)" = "$n" ] || fail "$d: $(ls "$work/$d" | wc -l) state files, not $n"
    for f in "$work/one"/*; do
      # Bytes 32-39 hold the node's wall time (NodeSums::seconds); everything else must match.
      "$py" -c 'import sys; a, b = (open(p, "rb").read() for p in sys.argv[1:]); sys.exit(a[:32] + a[40:] != b[:32] + b[40:])' \
        "$f" "$work/$d/$(basename "$f")" || fail "$d/$(basename "$f") differs"
    done
  done
  echo "exact: $n state files identical at 1 process, 2 ranks, and resumed under 2 ranks"
  ;;
*) fail "unknown test $what" ;;
esac
