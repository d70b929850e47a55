#!/usr/bin/env bash
# The renderer's speed goals, measured in one run and printed as one table:
# each figure beside its goal and the factor still missing (> 1: short of it).
#
#   bench/speed_targets.sh
#
# 1. The exact ray caster at 1920x1080, far 2048 cells, on the 4097² demo
#    (`bench --compare`): ns per sample per core counting every column x slice,
#    and its lead on `voxel-literal` and on the classic Voxel Space loop.
# 2. The distance LOD at 3840x2160 with a 16384-cell view: fps, and its
#    silhouette agreement with the exact cast at 1080p (LodAccuracy).
# 3. Split-only ROAM at 65536 and 262144 triangles (`bench_roam`, Mt Rainier
#    or the 1025² demo without the shared data, and the 4097² demo):
#    M triangles/s; beside it the split loop's floor (BM_RoamSplitFloor: the
#    same priorities and queue without keeping the mesh conforming), also at
#    16384 triangles on the 257² demo, where everything stays in the caches;
#    and a 240-frame flight (BM_RoamFlight), each frame from the previous
#    frame's order-free threshold, with the share of frames refined again.
# 4. The flight window against the headless composite of the same path
#    (`fly --frames N` under xvfb-run when there is no display, then
#    `fly --replay`), voxel method at 1280x720 and 1920x1080: the window's
#    share.
# Absolute times swing with the machine (2-3x between days on a shared VM);
# the load average is printed beside each step and under the table, and goals
# are best judged on an idle machine. With ROUNDS=N every measurement runs N
# times, one round after the other, and the table gives each figure's median
# and range over the rounds (the factor from the median). Environment: BUILD
# (default build/release), FRAMES (bench frames, default 15), FLY_FRAMES
# (default 200), ROUNDS (default 1), OUT (scratch folder).
set -euo pipefail

build=${BUILD:-build/release}
bin=$build/apps/overflight
frames=${FRAMES:-15}
fly_frames=${FLY_FRAMES:-200}
rounds=${ROUNDS:-1}
out=${OUT:-/tmp/overflight-speed-targets}
load() { uptime | sed 's/.*load average: //'; }
# Prints the step to stderr and keeps the 1-minute load average for the table.
step() {
    echo "round $r/$rounds: $1 (load $(load))" >&2
    uptime | sed 's/.*load average: //; s/,.*//' >>"$out/$r/load.txt"
}

for r in $(seq "$rounds"); do
    rm -rf "${out:?}/$r"
    mkdir -p "$out/$r"
    step "exact 1080p and --compare"
    "$bin" bench demo --demo-size 4097 --size 1920x1080 --methods voxel --compare --frames "$frames" --json \
        >"$out/$r/exact.json"
    step "LOD 4K"
    "$bin" bench demo --demo-size 4097 --size 3840x2160 --far 163840 --methods voxel --lod --frames "$frames" \
        --json >"$out/$r/lod.json"
    step "ROAM"
    roam_cases='BM_Roam(Frame|SplitFloor|Flight)/([01]/(65536|262144)|2/16384)(/iterations:240)?$'
    "$build/bench/bench_roam" --benchmark_filter="$roam_cases" \
        --benchmark_repetitions=3 \
        --benchmark_report_aggregates_only=true --benchmark_format=json >"$out/$r/roam.json" 2>/dev/null
    for size in 1280x720 1920x1080; do
        step "fly window and replay, $size"
        xvfb=()
        if [[ -z "${DISPLAY:-}" ]]; then xvfb=(xvfb-run -a -s "-screen 0 ${size}x24"); fi
        "${xvfb[@]}" "$bin" fly demo --method voxel --size "$size" --frames "$fly_frames" --no-hud \
            --press "accelerate:0-$fly_frames" "left:$((fly_frames / 3))-$((2 * fly_frames / 3))" \
            --record "$out/$r/fly-$size.csv" >"$out/$r/window-$size.csv"
        "$bin" fly demo --method voxel --size "$size" --replay "$out/$r/fly-$size.csv" --out "$out/$r/replay-$size" \
            >"$out/$r/replay-$size.csv"
    done
done

python3 - "$out" "$rounds" <<'EOF'
import csv, json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])

def fly_fps(path):
    with open(path) as f:
        return float(next(csv.DictReader(f))["fps"])

def measure(d):
    """One round's figures: {what: (value, goal text, goal value, higher is better, format)}."""
    exact = json.load(open(f"{d}/exact.json"))
    lod = json.load(open(f"{d}/lod.json"))
    roam = json.load(open(f"{d}/roam.json"))
    runs = {r["method"]: r for r in exact["runs"]}
    voxel = runs["voxel"]
    m = {}
    m["exact cast 1920x1080: ns / sample / core"] = (voxel["ns_per_sample"] * exact["threads"], "<= 1.7", 1.7,
                                                      False, "{:.2f}")
    m["exact cast 1920x1080: fps"] = (voxel["fps"], ">= 300", 300, True, "{:.1f}")
    for name, r in runs.items():
        if name != "voxel":
            m[f"lead on {name}: frame time"] = (r["ms_median"] / voxel["ms_median"], "-", None, True, "{:.1f}x")
            m[f"lead on {name}: time per sample"] = (r["ns_per_sample"] / voxel["ns_per_sample"], "-", None, True,
                                                     "{:.1f}x")
    l = lod["runs"][0]
    acc = l.get("lod_accuracy", {})
    m["LOD 3840x2160, far 16384 cells: fps"] = (l["fps"], ">= 120", 120, True, "{:.1f}")
    m["LOD silhouette within 1 px (1080p columns), %"] = (100 * acc.get("silhouette_within_1px", 0), ">= 98", 98,
                                                          True, "{:.3f}")
    m["LOD sky mask agreement (1080p pixels), %"] = (100 * acc.get("sky_mask_agreement", 0), "-", None, True,
                                                     "{:.3f}")
    names = {"0": "Rainier (or 1025² demo)", "1": "4097² demo", "2": "257² demo (in cache)"}
    for b in roam["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        bench, which, budget = b["run_name"].split("/")[:3]
        if bench == "BM_RoamFlight":
            m[f"ROAM flight (camera moving), {budget}, {names[which]}: M triangles/s"] = (
                b["items_per_second"] / 1e6, "-", None, True, "{:.1f}")
            m[f"ROAM flight, {budget}, {names[which]}: frames refined again in order, %"] = (
                100 * b["refined_again"], "-", None, False, "{:.1f}")
            continue
        if bench == "BM_RoamSplitFloor":
            m[f"ROAM's split floor (not conforming), {budget}, {names[which]}: M triangles/s"] = (
                b["items_per_second"] / 1e6, "-", None, True, "{:.1f}")
            continue
        goal = 15.0 if budget == "262144" else None
        m[f"ROAM {budget} triangles, {names[which]}: M triangles/s"] = (
            b["items_per_second"] / 1e6, ">= 15" if goal else "-", goal, True, "{:.1f}")
    for size in ("1280x720", "1920x1080"):
        window, replay = fly_fps(f"{d}/window-{size}.csv"), fly_fps(f"{d}/replay-{size}.csv")
        m[f"fly voxel {size}: window fps"] = (window, "-", None, True, "{:.1f}")
        m[f"fly voxel {size}: replay fps"] = (replay, "-", None, True, "{:.1f}")
        m[f"fly voxel {size}: window / replay"] = (window / replay, ">= 0.85", 0.85, True, "{:.2f}")
    return m

per_round = [measure(f"{out}/{r}") for r in range(1, rounds + 1)]
print("| measure | measured | goal | factor to the goal |")
print("|---|---:|---:|---:|")
for what, (_, goal_text, goal, higher, fmt) in per_round[0].items():
    values = [m[what][0] for m in per_round]
    med = statistics.median(values)
    shown = fmt.format(med)
    if rounds > 1:
        shown += f" ({fmt.format(min(values))}-{fmt.format(max(values))})"
    factor = "-"
    if goal is not None:
        f = goal / med if higher else med / goal
        factor = "met" if f <= 1 else f"{f:.2f}"
    print(f"| {what} | {shown} | {goal_text} | {factor} |")
loads = [float(x) for r in range(1, rounds + 1) for x in open(f"{out}/{r}/load.txt")]
print(f"\n{rounds} round(s); 1-minute load average at the steps: {min(loads):.2f}-{max(loads):.2f}")
EOF
