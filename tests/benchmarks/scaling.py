#!/usr/bin/python3
"""Scaling exponents from the Google Benchmark output of `make bench` (results/benchmarks/*.json).

For each family (the forward run against N, and against Nbar; a cost evaluation against Nbar) the exponent p of
time ~ size^p is the least-squares slope of log(median time) on log(size) over the sizes given, and the exponent between
each pair of neighbouring sizes is listed beside it, so that a change of regime (the eigen-decomposition taking over
from the per-sample sums) shows. Written to results/benchmarks/scaling.json and printed.
"""
import json
import math
import os
import re
import sys

FAMILIES = [
    ("forward run against N (Nbar = 4096)", "forward_model.json", r"^BM_SimulateFast/(\d+)_median$"),
    ("state-space modes against N", "forward_model.json", r"^BM_StateSpaceModes/(\d+)_median$"),
    ("forward run against Nbar (N = 16)", "forward_model.json", r"^BM_SimulateFastSamples/(\d+)_median$"),
    ("time cost against Nbar (N = 16)", "identification.json", r"^BM_CostSamples/time/(\d+)_median$"),
    ("spike-smooth cost against Nbar (N = 16)", "identification.json", r"^BM_CostSamples/spike_smooth/(\d+)_median$"),
]
UNIT = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def slope(points):
    xs = [math.log(s) for s, _ in points]
    ys = [math.log(t) for _, t in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "results/benchmarks"
    out = {}
    for title, file, pattern in FAMILIES:
        path = os.path.join(folder, file)
        if not os.path.exists(path):
            continue
        points = []
        for b in json.load(open(path))["benchmarks"]:
            m = re.match(pattern, b["name"])
            if m:
                points.append((int(m.group(1)), b["real_time"] * UNIT[b["time_unit"]]))
        points.sort()
        if len(points) < 2:
            continue
        pairs = [{"from": a[0], "to": b[0], "exponent": round(slope([a, b]), 2)} for a, b in zip(points, points[1:])]
        out[title] = {"sizes": [p[0] for p in points], "median_s": [p[1] for p in points],
                      "exponent": round(slope(points), 2), "neighbour_exponents": pairs}
        print(f"{title}: time ~ size^{slope(points):.2f} over {points[0][0]}..{points[-1][0]} "
              f"(neighbours: {', '.join(str(p['exponent']) for p in pairs)})")
    with open(os.path.join(folder, "scaling.json"), "w") as f:
        json.dump(out, f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    main()
