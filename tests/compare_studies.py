#!/usr/bin/env python3
"""Checks that two study.csv files hold the same samples with the same
results: same ids, parameters and status; peak omega and amplitudes equal
within a relative tolerance. Exit 0 if so, 1 with the differences if not."""
import csv
import math
import sys


def rows(path):
    with open(path, newline="") as f:
        return {int(r["sample"]): r for r in csv.DictReader(f)}


def main():
    if len(sys.argv) < 3:
        print("usage: compare_studies.py A.csv B.csv [relative tolerance] [expected samples]", file=sys.stderr)
        return 2
    a, b = rows(sys.argv[1]), rows(sys.argv[2])
    tolerance = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-6
    expected = int(sys.argv[4]) if len(sys.argv) > 4 else None
    problems = []
    if expected is not None and (len(a) != expected or sorted(a) != list(range(expected))):
        problems.append(f"{sys.argv[1]}: {len(a)} samples, expected 0..{expected - 1}")
    if sorted(a) != sorted(b):
        problems.append(f"different samples: {sorted(set(a) ^ set(b))}")
    columns = [c for c in next(iter(a.values())).keys()
               if c == "peak_omega" or c.startswith("first_harmonic_") or c.startswith("max_abs_")]
    exact = [c for c in next(iter(a.values())).keys()
             if c not in columns and c not in ("start", "solves", "iterations", "seconds", "worker")]
    for i in sorted(set(a) & set(b)):
        for c in exact:
            if a[i][c] != b[i][c]:
                problems.append(f"sample {i} {c}: {a[i][c]!r} != {b[i][c]!r}")
        for c in columns:
            x, y = float(a[i][c]), float(b[i][c])
            if math.isnan(x) and math.isnan(y):
                continue
            if not abs(x - y) <= tolerance * max(abs(x), abs(y)):
                problems.append(f"sample {i} {c}: {x} != {y}")
    for p in problems[:20]:
        print(p)
    print(f"{len(a)} samples compared, {len(problems)} difference(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
