#!/usr/bin/env python3
"""Frequency-response chart of an `eqhb sweep` CSV: max|x| per DOF vs omega,
folds marked, failed points shown.
Usage: plot_curve.py CSV PREFIX [TITLE] [--log-amplitude]"""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("prefix", help="writes PREFIX.png and PREFIX.svg")
    parser.add_argument("title", nargs="?", default="")
    parser.add_argument("--log-amplitude", action="store_true", help="logarithmic amplitude axis")
    args = parser.parse_args()
    rows = list(csv.DictReader(open(args.csv)))
    if not rows:
        parser.exit(1, f"{args.csv}: no points to plot\n")
    dofs = sorted(k for k in rows[0] if k.startswith("max_abs_x"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key in dofs:
        ok = [(float(r["omega"]), float(r[key])) for r in rows if r["converged"] == "true"]
        ax.plot([p[0] for p in ok], [p[1] for p in ok], "-", lw=1.2, label=key.replace("max_abs_", "max|") + "|")
        folds = [(float(r["omega"]), float(r[key])) for r in rows if r["fold"] == "true" and r["converged"] == "true"]
        if folds:
            ax.plot([p[0] for p in folds], [p[1] for p in folds], "kx", ms=8)
    failed = [float(r["omega"]) for r in rows if r["converged"] != "true"]
    if args.log_amplitude:
        ax.set_yscale("log")
    if failed:
        # On a log axis zero cannot be drawn: failed points sit at the bottom.
        bottom = ax.get_ylim()[0] if args.log_amplitude else 0.0
        ax.plot(failed, [bottom] * len(failed), "r|", ms=12, label=f"{len(failed)} failed")
    ax.set_xlabel("forcing frequency ω")
    ax.set_ylabel("max |x| over one period" + (" (log scale)" if args.log_amplitude else ""))
    has_folds = any(r["fold"] == "true" for r in rows)
    ax.set_title(f"{args.title}: frequency response" + (" (x: folds)" if has_folds else ""))
    ax.grid(True, alpha=0.3, which="both" if args.log_amplitude else "major")
    ax.legend()
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{args.prefix}.{ext}")


if __name__ == "__main__":
    main()
