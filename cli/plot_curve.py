#!/usr/bin/env python3
"""Frequency-response chart of an `eqhb sweep` CSV: max|x| per DOF shown vs omega
(the CSV's max_abs_<label> columns: x3, a beam's w10; legend in numeric order, inside the axes),
folds marked, failed points (the companion CSV.failed.csv) shown; with a `stable` column (sweep --stability)
stable branches solid, unstable ones dashed, bifurcations marked by kind.
Usage: plot_curve.py CSV PREFIX [TITLE] [--log-amplitude]"""
import argparse
import csv
import math
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


# Marker per bifurcation kind (sweep --stability).
MARKERS = {"fold": ("kx", "fold"), "branch-point": ("k+", "branch point (real +1)"),
           "period-doubling": ("rs", "period doubling"), "neimark-sacker": ("m^", "Neimark-Sacker")}
labelled_kinds = set()


def numeric_order(label):
    """x2 before x10, theta5 and w5 before w10: by the number, then the name."""
    match = re.match(r"([^0-9]*)([0-9]+)$", label)
    return (int(match.group(2)), match.group(1)) if match else (math.inf, label)


def draw_by_stability(ax, rows, key, label):
    """One DOF's curve: runs of equal stability, solid if stable, dashed if
    not (a run ends at a failed point), bifurcations marked."""
    color = None
    run, run_stable = [], None

    def flush():
        nonlocal color
        if len(run) >= 1:
            line, = ax.plot([p[0] for p in run], [p[1] for p in run], "-" if run_stable else "--", lw=1.2,
                            color=color, label=label if color is None else None)
            color = line.get_color()

    for r in rows:
        if r["converged"] != "true" or r["stable"] == "":
            flush()
            run, run_stable = [], None
            continue
        point = (float(r["omega"]), float(r[key]))
        stable = r["stable"] == "1"
        if run_stable is not None and stable != run_stable:
            run.append(point)  # join the two runs at the change
            flush()
            run = [point]
        else:
            run.append(point)
        run_stable = stable
        kind = r.get("bifurcation", "")
        if kind in MARKERS:
            style, name = MARKERS[kind]
            ax.plot([point[0]], [point[1]], style, ms=8, label=None if kind in labelled_kinds else name)
            labelled_kinds.add(kind)
    flush()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("prefix", help="writes PREFIX.png and PREFIX.svg")
    parser.add_argument("title", nargs="?", default="")
    parser.add_argument("--log-amplitude", action="store_true", help="logarithmic amplitude axis")
    args = parser.parse_args()
    rows = list(csv.DictReader(open(args.csv)))
    failed_csv = (args.csv[:-4] if args.csv.endswith(".csv") else args.csv) + ".failed.csv"
    failed = [float(r["omega"]) for r in csv.DictReader(open(failed_csv))] if os.path.exists(failed_csv) else []
    if not rows:
        parser.exit(1, f"{args.csv}: no points to plot\n")
    dofs = sorted((k for k in rows[0] if k.startswith("max_abs_")), key=lambda k: numeric_order(k[len("max_abs_"):]))
    with_stability = "stable" in rows[0]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key in dofs:
        label = key.replace("max_abs_", "max|") + "|"
        if with_stability:
            draw_by_stability(ax, rows, key, label)
            continue
        ok = [(float(r["omega"]), float(r[key])) for r in rows if r["converged"] == "true"]
        ax.plot([p[0] for p in ok], [p[1] for p in ok], "-", lw=1.2, label=label)
        folds = [(float(r["omega"]), float(r[key])) for r in rows if r["fold"] == "true" and r["converged"] == "true"]
        if folds:
            ax.plot([p[0] for p in folds], [p[1] for p in folds], "kx", ms=8)
    if args.log_amplitude:
        ax.set_yscale("log")
    if failed:
        # On a log axis zero cannot be drawn: failed points sit at the bottom.
        bottom = ax.get_ylim()[0] if args.log_amplitude else 0.0
        ax.plot(failed, [bottom] * len(failed), "r|", ms=12, label=f"{len(failed)} failed")
    ax.set_xlabel("forcing frequency ω")
    ax.set_ylabel("max over one period of |DOF|" + (" (log scale)" if args.log_amplitude else ""))
    has_folds = any(r["fold"] == "true" for r in rows)
    if with_stability:
        ax.set_title(f"{args.title}: frequency response (solid: stable, dashed: unstable)")
    else:
        ax.set_title(f"{args.title}: frequency response" + (" (x: folds)" if has_folds else ""))
    ax.grid(True, alpha=0.3, which="both" if args.log_amplitude else "major")
    # Inside the axes; in columns of at most 12 entries when many DOFs are shown.
    entries = len(ax.get_legend_handles_labels()[0])
    ax.legend(loc="best", fontsize="small" if entries > 6 else None, ncol=max(1, math.ceil(entries / 12)))
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{args.prefix}.{ext}")


if __name__ == "__main__":
    main()
