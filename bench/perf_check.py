#!/usr/bin/env python3
"""CI performance tracking: compare a fresh `eqhb-bench --quick` run with the
committed baseline (bench/baseline.json).

Fails (exit 1) when
  - a deterministic figure changed: converged, termination, iterations,
    residual and Jacobian evaluations (exact), accuracy vs the references
    (relative 1e-6), or a case appeared / disappeared;
  - timings regressed beyond noise: a case whose median is over RATIO times
    its baseline and over FLOOR seconds slower, or the geometric mean of all
    time ratios over MEAN_RATIO.
A case that stopped on the wall-clock limit in one run only is a timing: its
time there is at least the limit, and it fails as a regression only when that
is over RATIO times the other run's (a case converging near the limit, as
elastic-friction-3d's full dogleg-newton at 1.5 s against 2 s, stops on it on
a loaded machine). Stopped on it in both runs: compared on `converged` only.
Update the baseline on purpose: ./run.sh baseline
Usage: perf_check.py BASELINE FRESH"""
import json
import math
import sys

RATIO, FLOOR, MEAN_RATIO = 10.0, 0.02, 3.0
EXACT = ("converged", "termination", "iterations", "residual_evaluations", "jacobian_evaluations")
CLOSE = ("error_reference", "error_high_h")


def key(case):
    return (case["study"], case["scene"], case["solver"], case["system"], case["form"], case["harmonics"])


def close(a, b):
    if a is None or b is None:
        return a is None and b is None
    return abs(a - b) <= 1e-6 * max(abs(a), abs(b)) + 1e-14


def load(path):
    """(metadata, cases): bench.json is {"metadata", "cases"}; older files are the bare case list."""
    data = json.load(open(path))
    return (data.get("metadata", {}), data["cases"]) if isinstance(data, dict) else ({}, data)


def describe(metadata):
    if not metadata:
        return "no metadata"
    return (f"commit {metadata.get('commit', '?')[:10]}, {metadata.get('date', '?')}, {metadata.get('cpu', '?')}, "
            f"{metadata.get('compiler', '?')}")


def main(baseline_path, fresh_path):
    baseline_metadata, baseline_cases = load(baseline_path)
    fresh_metadata, fresh_cases = load(fresh_path)
    print(f"baseline: {describe(baseline_metadata)}\nthis run: {describe(fresh_metadata)}")
    baseline = {key(c): c for c in baseline_cases}
    fresh = {key(c): c for c in fresh_cases}
    problems, ratios = [], []
    for k in sorted(set(baseline) | set(fresh), key=str):
        if k not in fresh or k not in baseline:
            problems.append(f"{'/'.join(map(str, k))}: case {'missing' if k not in fresh else 'new'}")
            continue
        b, f = baseline[k], fresh[k]
        timed_out = "time_limit" in (b["termination"], f["termination"])
        both_timed_out = b["termination"] == f["termination"] == "time_limit"
        for field in ("converged",) if both_timed_out else () if timed_out else EXACT:
            if b[field] != f[field]:
                problems.append(f"{'/'.join(map(str, k))}: {field} {b[field]} -> {f[field]}")
        if not timed_out:
            for field in CLOSE:
                if not close(b.get(field), f.get(field)):
                    problems.append(f"{'/'.join(map(str, k))}: {field} {b.get(field)} -> {f.get(field)}")
        tb, tf = b.get("median_seconds"), f.get("median_seconds")
        if tb and tf and not both_timed_out:
            ratios.append(tf / tb)
            if tf > RATIO * tb and tf - tb > FLOOR:
                problems.append(f"{'/'.join(map(str, k))}: time {tb:.3g} s -> {tf:.3g} s ({tf / tb:.1f}x)")
    mean = math.exp(sum(math.log(r) for r in ratios) / len(ratios)) if ratios else 1.0
    print(f"perf check: {len(fresh)} cases, geometric mean time ratio {mean:.2f} "
          f"(fails above {MEAN_RATIO}), per-case limit {RATIO}x and +{FLOOR * 1e3:.0f} ms")
    if mean > MEAN_RATIO:
        problems.append(f"geometric mean time ratio {mean:.2f} > {MEAN_RATIO}")
    for p in problems:
        print("  CHANGED: " + p)
    print(f"{len(fresh) - len(problems) if len(problems) < len(fresh) else 0} passed, {len(problems)} failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
