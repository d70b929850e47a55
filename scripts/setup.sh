#!/usr/bin/env bash
# Installs the Debian 12 packages Overflight needs (only those missing), then
# configures and builds a Release `overflight` in build/release.
#   bash scripts/setup.sh            # install + build
#   OVERFLIGHT_SKIP_INSTALL=1 ...    # build only
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache keys on paths relative to the checkout, so a fresh clone elsewhere
# (CI) reuses what an earlier build on this machine compiled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"

packages=(
  build-essential cmake ninja-build pkg-config ccache clang libclang-rt-14-dev
  libgdal-dev gdal-bin libglfw3-dev libepoxy-dev libegl-dev libgl1-mesa-dri libegl-mesa0
  libglm-dev libtbb-dev libcli11-dev libtomlplusplus-dev libstb-dev libtinyobjloader-dev
  libtinygltf-dev libimgui-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev xvfb xauth
  ffmpeg parallel pybind11-dev python3-dev python3-pybind11 python3-numpy python3-pytest python3-gdal
  emscripten nodejs chromium
)

if [ "${OVERFLIGHT_SKIP_INSTALL:-0}" != 1 ]; then
  missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing ${missing[*]}"
    sudo_cmd=""
    [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
    $sudo_cmd apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
fi

build_dir=${OVERFLIGHT_BUILD_DIR:-build/release}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release ${OVERFLIGHT_CMAKE_ARGS:-} >/dev/null
cmake --build "$build_dir" -j"$(nproc)" ${OVERFLIGHT_TARGETS:+--target $OVERFLIGHT_TARGETS}
