#!/usr/bin/env bash
# The flight window against the headless composite, on one camera path and at
# one size: what a user flies against what the benchmark measures.
#
#   bench/fly_replay.sh [TERRAIN [extra options for fly and bench ...]]
#
# 1. `fly --frames N` in a real window (under xvfb-run when there is no
#    display) flies a scripted path with the voxel method and records it;
#    its fps is the window's.
# 2. `fly --replay` renders the recorded cameras headless through the same
#    compositor (objects and the vehicle, images read back): the headless
#    composite on the same path; its fps counts the frames, not the PNG writes.
# 3. `bench --methods voxel,voxel+objects` at the same size, on bench's own
#    camera, for the Szenberg Table 1 steps.
# Each runs twice: with the data set's looks, then with every stage-2 effect
# (--lighting sun --shadows --water --atmosphere; give --color FILE for
# imagery). The machine's load is printed beside the numbers; compare ratios
# within one run. Environment: OVERFLIGHT (the binary), FRAMES (default 300),
# SIZE (default 1280x720), OUT (scratch folder, default /tmp/overflight-fly-replay).
set -euo pipefail

bin=${OVERFLIGHT:-build/release/apps/overflight}
frames=${FRAMES:-300}
size=${SIZE:-1280x720}
out=${OUT:-/tmp/overflight-fly-replay}
terrain=${1:-demo}
shift || true
extra=("$@")

xvfb=()
if [[ -z "${DISPLAY:-}" ]]; then xvfb=(xvfb-run -a -s "-screen 0 ${size}x24"); fi
mkdir -p "$out"

# A path that accelerates, turns left, then right, through the whole run.
third=$((frames / 3))
press=(--press "accelerate:0-${frames}" "left:${third}-$((2 * third))" "right:$((2 * third))-${frames}")

# Prints "label: method fps steps" from fly's CSV (method,frames,fps,...).
fly_row() {
    awk -F, -v label="$1" 'NR > 1 { printf "%-34s %-14s %8.1f fps   %s\n", label, $1, $3, $6 }'
}

run() {
    local name=$1
    shift
    local looks=("$@")
    echo "== $name: ${looks[*]:-(the looks of the data set)}   load: $(uptime | sed 's/.*load average: //')"
    "${xvfb[@]}" "$bin" fly "$terrain" --method voxel --size "$size" --frames "$frames" --no-hud "${press[@]}" \
        --record "$out/$name.csv" --screenshot "$out/$name-window.png" "${looks[@]}" "${extra[@]}" |
        fly_row "fly --frames $frames (window)"
    rm -rf "$out/$name-replay"
    "$bin" fly "$terrain" --method voxel --size "$size" --replay "$out/$name.csv" --out "$out/$name-replay" \
        "${looks[@]}" "${extra[@]}" | fly_row "fly --replay (headless composite)"
    "$bin" bench "$terrain" --size "$size" --frames 30 --methods voxel,voxel+objects --json "${looks[@]}" "${extra[@]}" |
        python3 -c '
import json, sys
d = json.load(sys.stdin)
for r in d["runs"]:
    steps = ";".join("%s:%.2f" % kv for kv in r.get("steps_ms", {}).items())
    print("%-34s %-14s %8.1f fps   %s" % ("bench (overview camera)", r["method"], r["fps"], steps))
'
}

run plain
run effects --lighting sun --shadows --water --atmosphere
echo "frames and paths in $out; load after: $(uptime | sed 's/.*load average: //')"
