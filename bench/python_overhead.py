#!/usr/bin/env python3
"""What a render called from Python costs over the same render in the C++
benchmark, measured in one run: `overflight bench TERRAIN --json --methods M
--frames N/R --size WxH` (median ms per frame of the method's session, no
depth read back) against a Python loop of N/R `overflight.render(...,
depth=False)` calls for the same camera (bench's default view, far 2048
samples), after one warm-up call each, in R interleaved rounds so that both
see the same machine load. A `voxel` view from Python shows the terrain's
objects (as `render` does), so on a terrain with objects (the demo) it is
timed against bench's `voxel+objects`, the same render. Prints one JSON
object: per method the bench row compared, the medians over all frames, the
median of the rounds' ratios and, less sensitive to a shared machine's load,
the ratio of the fastest frames.

    PYTHONPATH=build/release/python python3 bench/python_overhead.py \\
        --exe build/release/apps/overflight --terrain ../shared/data/srtm/mt_rainier_90m.tif
"""
import argparse
import json
import statistics
import subprocess
import time

import overflight


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--exe", default="overflight")
    p.add_argument("--terrain", default="demo")
    p.add_argument("--methods", default="voxel,mesh")
    p.add_argument("--frames", type=int, default=100)
    p.add_argument("--rounds", type=int, default=4)
    p.add_argument("--size", default="1920x1080")
    a = p.parse_args()
    terrain = overflight.load(a.terrain)
    far = 2048.0 * terrain.cell_size
    size = tuple(int(v) for v in a.size.split("x"))
    per_round = max(1, a.frames // a.rounds)
    info = terrain.info()
    has_objects = info["objects"] + info["lines"] > 0
    out = {"terrain": a.terrain, "frames": per_round * a.rounds, "rounds": a.rounds, "size": a.size, "runs": []}
    for method in a.methods.split(","):
        row = "voxel+objects" if method == "voxel" and has_objects else method
        bench_ms, bench_min, python_ms, ratios = [], [], [], []
        overflight.render(terrain, method, size, far=far, depth=False)  # warm-up, as bench's
        for _ in range(a.rounds):
            bench = json.loads(subprocess.run([a.exe, "bench", a.terrain, "--json", "--methods", row, "--frames",
                                               str(per_round), "--size", a.size], check=True, capture_output=True,
                                              text=True).stdout)
            run = next(r for r in bench["runs"] if r["method"] == row)
            ms = []
            for _ in range(per_round):
                t0 = time.perf_counter()
                overflight.render(terrain, method, size, far=far, depth=False)
                ms.append((time.perf_counter() - t0) * 1000.0)
            bench_ms.append(run["ms_median"])
            bench_min.append(run["ms_min"])
            python_ms += ms
            ratios.append(statistics.median(ms) / run["ms_median"])
        out["runs"].append({"method": method, "bench_method": row, "bench_ms_median": statistics.median(bench_ms),
                            "python_ms_median": statistics.median(python_ms),
                            "python_over_bench": statistics.median(ratios), "round_ratios": ratios,
                            "bench_ms_min": min(bench_min), "python_ms_min": min(python_ms),
                            "python_over_bench_min": min(python_ms) / min(bench_min)})
    print(json.dumps(out))


if __name__ == "__main__":
    main()
