#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/*.cpp) with clang in their own build
# directory and runs each for SECONDS (default 20) from a seed corpus written
# here and the one under fuzz/corpus/HARNESS/ when there is one, failing on
# the first crash, leak, sanitizer report or timeout.
#
#   .ci/fuzz.sh [SECONDS]        env: FUZZ_BUILD (default build-fuzz), JOBS (default 1)
set -euo pipefail

seconds="${1:-20}"
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${FUZZ_BUILD:-$root/build-fuzz}"
harnesses=(fuzz_pgm fuzz_ppm fuzz_map fuzz_flight_record)

# Everything is instrumented for coverage (fuzzer-no-link), not only the
# harnesses: the parsers under test live in overflight_io.
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DOVERFLIGHT_FUZZ=ON -DOVERFLIGHT_TESTS=OFF -DOVERFLIGHT_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" \
  >"$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" --target "${harnesses[@]}" -j"${JOBS:-1}"

seeds="$build/seeds"
rm -rf "$seeds"
mkdir -p "$seeds/fuzz_pgm" "$seeds/fuzz_ppm" "$seeds/fuzz_map"
printf 'P5\n3 2\n255\n\x00\x01\x02\xfd\xfe\xff' >"$seeds/fuzz_pgm/8bit"
printf 'P5\n# comment\n2 2\n65535\n\x01\x02\xff\xff\x80\x00\x00\xff' >"$seeds/fuzz_pgm/16bit"
printf 'P5 1 1 256\n\x01\x00' >"$seeds/fuzz_pgm/maxval256"
printf 'P6\n2 1\n255\n\x01\x02\x03\xff\x00\x80' >"$seeds/fuzz_ppm/8bit"
printf 'P6\n1 1\n65535\n\xff\xff\x80\x80\x00\x00' >"$seeds/fuzz_ppm/16bit"
cat >"$seeds/fuzz_map/full" <<'MAP'
h_scale = 10.0
v_scale = 0.1
y_offset = -5
sun_dir = [0.3, 0.8, 0.5]
sun_color = [1.0, 0.96, 0.9]
fog_density = 0.0002
fog_color = [0.72, 0.8, 0.9]
[vehicle]
x = 100.0
z = 200.0
heading = 90.0
[[object]]
kind = "box"
x = 4890.0
z = 13800.0
width = 60.0
height = 120.0
depth = 60.0
color = [200, 40, 40]
[[object]]
kind = "model"
x = 1
z = 2
file = "tree.obj"
[[line]]
points = [[1000.0, 2000.0], [1400.0, 2100.0]]
height = 40.0
sag = 4.0
MAP
printf 'h_scale = 1\nv_scale = 1\n' >"$seeds/fuzz_map/minimal"
printf 'h_scale = 1\nv_scale = 1\nsun_dir = [3e38, 0, 1]\nfog_density = 3.4e38\n' >"$seeds/fuzz_map/float_range"

status=0
for h in "${harnesses[@]}"; do
  corpus="$build/corpus/$h"
  mkdir -p "$corpus" "$seeds/$h"
  stored=()
  [ -d "$root/fuzz/corpus/$h" ] && stored=("$root/fuzz/corpus/$h")
  echo "== $h for ${seconds}s"
  # The fuzzer writes crash-* reproducers into the build directory on failure.
  if ! (cd "$build" && "$build/fuzz/$h" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
        -rss_limit_mb=2048 -print_final_stats=1 "$corpus" "$seeds/$h" "${stored[@]}" 2>"$build/$h.log"); then
    tail -n 40 "$build/$h.log"
    echo "FAIL: $h crashed (reproducer in $build)"
    status=1
  else
    grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "$build/$h.log" || true
  fi
done
exit "$status"
