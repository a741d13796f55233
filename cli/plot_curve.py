#!/usr/bin/env python3
"""Frequency-response chart of an `eqhb sweep` CSV: max|x| per DOF vs omega,
folds marked, failed points shown. Usage: plot_curve.py CSV PREFIX TITLE"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(path, prefix, title):
    rows = list(csv.DictReader(open(path)))
    if not rows:
        sys.exit(f"{path}: no points to plot")
    dofs = sorted(k for k in rows[0] if k.startswith("max_abs_x"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key in dofs:
        ok = [(float(r["omega"]), float(r[key])) for r in rows if r["converged"] == "true"]
        ax.plot([p[0] for p in ok], [p[1] for p in ok], "-", lw=1.2, label=key.replace("max_abs_", "max|") + "|")
        folds = [(float(r["omega"]), float(r[key])) for r in rows if r["fold"] == "true" and r["converged"] == "true"]
        if folds:
            ax.plot([p[0] for p in folds], [p[1] for p in folds], "kx", ms=8)
    failed = [float(r["omega"]) for r in rows if r["converged"] != "true"]
    if failed:
        ax.plot(failed, [0.0] * len(failed), "r|", ms=12, label=f"{len(failed)} failed")
    ax.set_xlabel("omega")
    ax.set_ylabel("max |x| over one period")
    ax.set_title(f"{title}: frequency response" + (" (x: folds)" if any(r["fold"] == "true" for r in rows) else ""))
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{prefix}.{ext}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else "")
