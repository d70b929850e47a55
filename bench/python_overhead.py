#!/usr/bin/env python3
"""What a render called from Python costs over the same render in the C++
benchmark, measured in one run: `overflight bench TERRAIN --json --methods M
--frames N` (median ms per frame of the method's session, no depth read back)
against a Python loop of N `overflight.render(..., depth=False)` calls for
the same camera (bench's: the default view, 1920x1080, far 2048 samples),
after one warm-up call each. Prints one JSON object with the ratios.

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
    a = p.parse_args()
    bench = json.loads(subprocess.run([a.exe, "bench", a.terrain, "--json", "--methods", a.methods,
                                       "--frames", str(a.frames)], check=True, capture_output=True,
                                      text=True).stdout)
    terrain = overflight.load(a.terrain)
    far = 2048.0 * terrain.cell_size
    out = {"terrain": a.terrain, "frames": a.frames, "runs": []}
    for run in bench["runs"]:
        method = run["method"]
        if "+" in method:
            continue
        size = (run["width"], run["height"])
        overflight.render(terrain, method, size, far=far, depth=False)  # warm-up, as bench
        ms = []
        for _ in range(a.frames):
            t0 = time.perf_counter()
            overflight.render(terrain, method, size, far=far, depth=False)
            ms.append((time.perf_counter() - t0) * 1000.0)
        py = statistics.median(ms)
        out["runs"].append({"method": method, "bench_ms_median": run["ms_median"], "python_ms_median": py,
                            "python_over_bench": py / run["ms_median"]})
    print(json.dumps(out))


if __name__ == "__main__":
    main()
