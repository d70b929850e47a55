#!/usr/bin/env bash
# Runs the whole test suite as CI does: installs what is missing, builds with
# -Werror, runs every CTest label (cpu, gdal, gl, window) on the Release build,
# runs cpu and gdal again under AddressSanitizer + UndefinedBehaviorSanitizer,
# and runs each libFuzzer harness briefly. Exits non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

OVERFLIGHT_CMAKE_ARGS="-DOVERFLIGHT_WERROR=ON" bash scripts/setup.sh
echo "== tests (Release): cpu gdal gl window"
ctest --test-dir build/release --output-on-failure -j"$jobs"

echo "== tests (ASan+UBSan): cpu gdal"
OVERFLIGHT_SKIP_INSTALL=1 OVERFLIGHT_BUILD_DIR=build/sanitize \
  OVERFLIGHT_CMAKE_ARGS="-DOVERFLIGHT_WERROR=ON -DOVERFLIGHT_SANITIZE=ON -DOVERFLIGHT_BENCH=OFF" bash scripts/setup.sh
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/sanitize --output-on-failure -j"$jobs" -L 'cpu|gdal'

if [ -f .ci/fuzz.sh ]; then
  echo "== fuzzers"
  bash .ci/fuzz.sh "${OVERFLIGHT_FUZZ_SECONDS:-20}"
fi
echo "== all tests passed"
