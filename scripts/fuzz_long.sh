#!/usr/bin/env bash
# Long fuzzing runs (not part of CI): every harness fuzz/NAME.cpp for RUNS
# executions (default 10 million) from its seed corpus fuzz/corpus/NAME/, in a
# build optimised for throughput: libFuzzer's coverage without AddressSanitizer
# and UBSan (CI runs every harness briefly with both, .ci/fuzz.sh). Prints one
# line per harness: executions done, seconds, and OK or the failure.
#
#   scripts/fuzz_long.sh [RUNS] [HARNESS ...]     env: FUZZ_LONG_BUILD (default build-fuzz-long)
set -euo pipefail
runs="${1:-10000000}"
shift || true
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${FUZZ_LONG_BUILD:-$root/build-fuzz-long}"
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then
  for src in "$root"/fuzz/*.cpp; do harnesses+=("$(basename "$src" .cpp)"); done
fi
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DOVERFLIGHT_FUZZ=ON \
  -DOVERFLIGHT_FUZZ_SANITIZE= -DOVERFLIGHT_TESTS=OFF -DOVERFLIGHT_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" >"$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" --target "${harnesses[@]}" >/dev/null
status=0
for h in "${harnesses[@]}"; do
  corpus="$build/corpus/$h"
  mkdir -p "$corpus"
  start=$(date +%s)
  if (cd "$build" && "$build/fuzz/$h" -runs="$runs" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 "$corpus" "$root/fuzz/corpus/$h" >"$build/$h.log" 2>&1); then
    result=OK
  else
    result="FAILED (reproducer and log in $build)"
    status=1
  fi
  execs=$(grep -E '^stat::number_of_executed_units' "$build/$h.log" | awk '{print $2}')
  echo "$h: ${execs:-?} executions in $(( $(date +%s) - start )) s: $result"
done
exit "$status"
