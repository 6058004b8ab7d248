#!/usr/bin/env bash
# Coverage-guided fuzzing (libFuzzer) of every file format in tests/fuzz/fuzz_targets.hpp, each on
# its seed corpus tests/fuzz/corpus/<format>/, for SECONDS each. New interesting inputs go to
# fuzz-out/<format>/ (not the repository); a crash leaves fuzz-out/<format>/crash-* and fails the
# script: copy it to tests/fuzz/regressions/<format>/ with the fix, so test_fuzz_mutations replays it.
# Usage: tools/fuzz.sh [SECONDS] [BUILD_DIR]     (CI: 20 s per format; a real campaign: 3600 or more)
# The build dir must be configured with clang and -DBSSRDF_FUZZ=ON (tools/sanitize.sh does this).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
build="${2:-build-sanitize}"
driver="$build/tests/fuzz/fuzz_parser"
if [ ! -x "$driver" ]; then
  echo "fuzz: $driver not found; run tools/sanitize.sh first (needs clang and libclang-rt-dev)" >&2
  exit 2
fi
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for corpus in tests/fuzz/corpus/*/; do
  format=$(basename "$corpus")
  out="fuzz-out/$format"
  mkdir -p "$out"
  # -rss_limit_mb and -timeout make a memory blow-up or a hang (> 10 s for one input) a finding too.
  if ! BSSRDF_FUZZ_FORMAT="$format" "$driver" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -max_len=65536 -artifact_prefix="$out/" -print_final_stats=1 "$out" "$corpus" >"$out/log.txt" 2>&1; then
    echo "fuzz: $format FAILED, see $out/log.txt and $out/crash-*" >&2
    tail -40 "$out/log.txt" >&2
    status=1
  else
    echo "fuzz: $format: $(grep -o 'stat::number_of_executed_units: *[0-9]*' "$out/log.txt" | grep -o '[0-9]*$') inputs in ${seconds} s, no finding"
  fi
done
exit $status
