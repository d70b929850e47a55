#!/usr/bin/env bash
# Runs the whole test suite as CI does: installs what is missing, builds with
# -Werror, runs every CTest label (cpu, gdal, gl, window, web) on the Release build,
# builds examples/raycast_depth and the installed-header check against the
# package installed into a fresh prefix, runs cpu and gdal again under
# AddressSanitizer + UndefinedBehaviorSanitizer (without the runs over large
# rasters and whole real DEMs that GTEST_FILTER in the asan test preset names:
# they took most of the sanitizer stage's test-minutes, the same code runs
# there on smaller inputs, and Release runs them all),
# and runs each libFuzzer
# harness briefly. Exits non-zero if anything fails, and if any test was
# skipped: CI has ../shared/data and may mount a tmpfs, so there a skipped
# test is one that silently did not run.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache keys on paths relative to the checkout, so a fresh clone elsewhere
# (CI) reuses what an earlier build on this machine compiled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
jobs=$(nproc)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Runs the tests of CTest preset $1 (CMakePresets.json), then fails naming
# every test that did not run: CTest reports a test as skipped when it exits
# with its SKIP_RETURN_CODE (tests/TestMain.cpp: a test called GTEST_SKIP and
# none failed), "notrun" in the JUnit report.
run_tests() {
  local junit="$scratch/$1.xml"
  ctest --preset "$1" -j"$jobs" --output-junit "$junit"
  local skipped
  skipped=$(sed -n 's/.*<testcase name="\([^"]*\)".*status="notrun".*/\1/p' "$junit")
  if [ -n "$skipped" ]; then
    echo "FAIL: tests did not run (\`ctest --preset $1 -V -R NAME\` shows why):" $skipped
    exit 1
  fi
}

# Each stage's wall time, so the command's 25-minute CI budget can be watched.
stage() { echo "== [$((SECONDS / 60))m$((SECONDS % 60))s] $*"; }

stage "install + Release build"
OVERFLIGHT_CMAKE_ARGS="-DOVERFLIGHT_WERROR=ON" bash scripts/setup.sh
stage "tests (Release): cpu gdal gl window web"
run_tests release

stage "installed package: examples/raycast_depth and tests/install from a fresh prefix"
cmake --install build/release --prefix "$scratch/prefix" >/dev/null
for project in examples/raycast_depth tests/install; do
  cmake -S "$project" -B "$scratch/build/$project" -G Ninja -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
  cmake --build "$scratch/build/$project" -j"$jobs"
done
"$scratch/build/examples/raycast_depth/raycast_depth"

stage "ASan+UBSan build (cpu and gdal tests only)"
cmake --preset asan >/dev/null
cmake --build --preset asan -j"$jobs"
stage "tests (ASan+UBSan): cpu gdal"
run_tests asan

if [ -f .ci/fuzz.sh ]; then
  stage "fuzzers"
  bash .ci/fuzz.sh "${OVERFLIGHT_FUZZ_SECONDS:-20}"
fi
stage "all tests passed"
