#!/usr/bin/env bash
# The frame rate of `overflight web`'s page at 1280x720 in headless Chromium
# (software WebGL2 through SwiftShader, one thread): writes a site for
# TERRAIN (default: the demo island) into a scratch folder, serves it on
# 127.0.0.1, flies forward and counts frames over BENCH_SECONDS (default 10), for
# the WebAssembly ray caster's view and for the ROAM view (Tab). A
# benchmark, not a test: the numbers depend on the machine and its load,
# printed beside them.
#
#   bash bench/web_fps.sh [TERRAIN [overflight web options...]]
# Environment: OVERFLIGHT (the binary, default build/release/apps/overflight),
# SIZE (default 1280x720), BENCH_SECONDS (default 10).
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${OVERFLIGHT:-build/release/apps/overflight}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
terrain=${1:-demo}
shift || true
"$exe" web "$terrain" "$@" -o "$scratch/site" >/dev/null
echo "site: $(du -sb "$scratch/site" | cut -f1) bytes; load: $(uptime | sed 's/.*load average/load average/')"
node bench/web_fps.mjs "$scratch/site" "${SIZE:-1280x720}" "${BENCH_SECONDS:-10}"
echo "after: $(uptime | sed 's/.*load average/load average/')"
