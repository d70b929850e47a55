#!/usr/bin/env bash
# Builds the web page's engine (web/CMakeLists.txt) with Emscripten into
# build/web: overflight_engine.{js,wasm} (SIMD128) and
# overflight_engine_scalar.{js,wasm}. Needs Debian's `emscripten` package.
#   bash scripts/build_web.sh
#   OVERFLIGHT_WEB_BUILD_DIR=DIR ...   # another build folder
#   OVERFLIGHT_JOBS=N ...              # parallel jobs (default: all cores)
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
# Debian's emscripten runs its JavaScript tools with `node` and finds their
# modules (acorn) among Debian's node packages; a Node installed from
# elsewhere does not look there by itself.
if [ -d /usr/share/nodejs ]; then
  export NODE_PATH="/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}"
fi
command -v emcmake >/dev/null || { echo "build_web: emcmake not found (apt-get install emscripten)" >&2; exit 1; }

build_dir=${OVERFLIGHT_WEB_BUILD_DIR:-build/web}
emcmake cmake -S web -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j"${OVERFLIGHT_JOBS:-$(nproc)}"
