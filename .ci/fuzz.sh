#!/usr/bin/env bash
# Builds every libFuzzer harness (fuzz/NAME.cpp) with clang in its own build
# directory and runs each for SECONDS (default 20), starting from its seed
# corpus fuzz/corpus/NAME/ (kept in the repository, read only here), failing
# on the first crash, leak, sanitizer report or timeout. A new harness is one
# fuzz/NAME.cpp plus one fuzz/corpus/NAME/ folder of seeds.
#
#   .ci/fuzz.sh [SECONDS]        env: FUZZ_BUILD (default build-fuzz), JOBS (default 1)
set -euo pipefail

seconds="${1:-20}"
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${FUZZ_BUILD:-$root/build-fuzz}"
harnesses=()
for src in "$root"/fuzz/*.cpp; do
  harnesses+=("$(basename "$src" .cpp)")
done
[ ${#harnesses[@]} -gt 0 ] || { echo "no harness in $root/fuzz"; exit 1; }

# Everything is instrumented for coverage (fuzzer-no-link), not only the
# harnesses: the parsers under test live in overflight_io.
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DOVERFLIGHT_FUZZ=ON -DOVERFLIGHT_TESTS=OFF -DOVERFLIGHT_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" \
  >"$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" --target "${harnesses[@]}" -j"${JOBS:-1}"

status=0
for h in "${harnesses[@]}"; do
  seeds="$root/fuzz/corpus/$h"
  if [ ! -d "$seeds" ] || [ -z "$(ls -A "$seeds")" ]; then
    echo "FAIL: $h has no seed corpus in fuzz/corpus/$h"
    status=1
    continue
  fi
  # New inputs go to the first folder (the build's working corpus), never into the repository.
  corpus="$build/corpus/$h"
  mkdir -p "$corpus"
  echo "== $h for ${seconds}s"
  # The seeds run first and on their own, so a regression seed fails at once
  # with its name; then the fuzzer runs from them. Reproducers land in $build.
  if ! (cd "$build" && "$build/fuzz/$h" -runs=0 "$seeds" >"$build/$h.seeds.log" 2>&1); then
    tail -n 40 "$build/$h.seeds.log"
    echo "FAIL: $h fails on a seed of fuzz/corpus/$h"
    status=1
    continue
  fi
  if ! (cd "$build" && "$build/fuzz/$h" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
        -rss_limit_mb=2048 -print_final_stats=1 "$corpus" "$seeds" 2>"$build/$h.log"); then
    tail -n 40 "$build/$h.log"
    echo "FAIL: $h crashed (reproducer in $build)"
    status=1
  else
    grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "$build/$h.log" || true
  fi
done
exit "$status"
