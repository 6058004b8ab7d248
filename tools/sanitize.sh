#!/usr/bin/env bash
# CI's second stage: the library, the tool and the test suite built with AddressSanitizer +
# UndefinedBehaviorSanitizer (-O1) in build-sanitize/, the whole ctest suite run there (any sanitizer
# report aborts its test, so the stage fails), then a short libFuzzer run of every file format.
# With clang (Debian: clang, libclang-rt-14-dev) the build is also instrumented for libFuzzer;
# without it, gcc's sanitizers and the deterministic mutation test (test_fuzz_mutations) still run.
# Usage: tools/sanitize.sh [SECONDS_PER_FORMAT]   (fuzzing time per format, default 20; 0: skip)
set -euo pipefail
cd "$(dirname "$0")/.."
fuzz_seconds="${1:-20}"
start=$(date +%s)

compiler=()
fuzz=OFF
if command -v clang++ >/dev/null && echo 'int main(){}' | clang++ -x c++ -fsanitize=fuzzer-no-link,address - -o /dev/null 2>/dev/null; then
  compiler=(-DCMAKE_CXX_COMPILER=clang++)
  fuzz=ON
fi
# No Python module here: loading it would need the sanitizer runtimes preloaded into python3.
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1" "${compiler[@]}" "${launcher[@]}" \
  -DBSSRDF_SANITIZE=ON -DBSSRDF_FUZZ="$fuzz" -DBSSRDF_BUILD_BENCHMARKS=OFF \
  -DBSSRDF_PYTHON=OFF >/dev/null

# Only what the stage runs: the tool, the table generator (its state-file test), validate_exact (its
# rescore test), the test binaries and the fuzz driver (no benchmarks, no other validation drivers).
# Every executable a ctest names must be here, or its test fails on a missing file.
targets=(bssrdf-cli generate_exact_table validate_exact)
for t in tests/test_*.cpp; do targets+=("$(basename "$t" .cpp)"); done
if [ "$fuzz" = ON ]; then targets+=(fuzz_parser); fi
cmake --build build-sanitize -j "$(nproc)" --target "${targets[@]}"
built=$(date +%s)

# Leaks are reported too; a report exits the process with an error, which ctest counts as a failure.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)"
tested=$(date +%s)

if [ "$fuzz" = ON ] && [ "$fuzz_seconds" -gt 0 ]; then
  bash tools/fuzz.sh "$fuzz_seconds" build-sanitize
fi
echo "sanitize: build $((built - start)) s, tests $((tested - built)) s, fuzzing $(($(date +%s) - tested)) s (compiler: ${compiler[*]:-default})"
