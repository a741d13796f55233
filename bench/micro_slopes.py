#!/usr/bin/env python3
"""Log-log slopes of the micro-benchmark times vs H (and N), from Google
Benchmark's JSON output. Usage: micro_slopes.py micro.json micro.md"""
import json
import math
import sys
from collections import defaultdict


def slope(points):
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(y) for _, y in points]
    n = len(xs)
    if n < 2:
        return math.nan
    mx, my = sum(xs) / n, sum(ys) / n
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main(source, target):
    data = json.load(open(source))
    series = defaultdict(list)
    for b in data["benchmarks"]:
        parts = b["name"].split("/")
        name, args = parts[0], [int(p) for p in parts[1:] if p.isdigit()]
        key = (name, b.get("label", ""))
        series[key].append((args[-1], b["real_time"], b["time_unit"]))
    lines = ["| benchmark | law | sizes | time at smallest | time at largest | log-log slope |",
             "|---|---|---|---|---|---|"]
    for (name, label), pts in sorted(series.items()):
        pts.sort()
        s = slope([(x, t) for x, t, _ in pts])
        size = "N" if name == "ResidualVsSamples" else "H"
        lines.append(f"| {name} | {label} | {size} = {pts[0][0]}..{pts[-1][0]} | {pts[0][1]:.3g} {pts[0][2]} | "
                     f"{pts[-1][1]:.3g} {pts[-1][2]} | {s:.2f} |")
    text = "\n".join(lines) + "\n"
    open(target, "w").write("# Micro-benchmarks of the hot path\n\nSlope of log(time) vs log(size); "
                            "N grows with H (N = smallest power of two >= 8(2H+1)).\n\n" + text)
    print(text)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
