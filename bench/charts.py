#!/usr/bin/env python3
"""Charts for eqhb-bench (matplotlib): work-precision (median time vs
accuracy, one marker per backend) and time per backend, PNG and SVG."""
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(folder):
    import os
    if not os.path.exists(f"{folder}/bench.csv"):
        convergence_charts(folder)
        return
    rows = list(csv.DictReader(open(f"{folder}/bench.csv")))
    by_scene = defaultdict(list)
    for r in rows:
        by_scene[r["scene"]].append(r)
    for scene, cases in by_scene.items():
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for solver in sorted({c["solver"] for c in cases}):
            pts = [(float(c["median_seconds"]), float(c["relative_error_max_abs"]), c)
                   for c in cases if c["solver"] == solver and c["converged"] == "true"
                   and not math.isnan(float(c["relative_error_max_abs"]))]
            if pts:
                ax.scatter([p[0] for p in pts], [max(p[1], 1e-16) for p in pts], label=solver, alpha=0.8)
        failed = [c for c in cases if c["converged"] != "true"]
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("median time per solve [s]")
        ax.set_ylabel("relative error of max|x| vs highest-H solution")
        ax.set_title(f"{scene}: work-precision ({len(failed)} of {len(cases)} cases did not converge)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        fig.tight_layout()
        for ext in ("png", "svg"):
            fig.savefig(f"{folder}/work_precision_{scene}.{ext}")
        plt.close(fig)
    convergence_charts(folder)
    print(f"charts written to {folder}")


def convergence_charts(folder):
    """Error of the harmonic balance vs H, and of the reference vs h."""
    import glob
    import os
    path = f"{folder}/convergence.csv"
    if not os.path.exists(path):
        return
    rows = [r for r in csv.DictReader(open(path)) if r["converged"] in ("1", "true")]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for omega in sorted({r["omega"] for r in rows}):
        pts = [(int(r["harmonics"]), float(r["l2_x2"]), float(r["error_max_abs_x2"])) for r in rows if r["omega"] == omega]
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"L2 error of x2, w = {omega}")
        ax.loglog([p[0] for p in pts], [max(p[2], 1e-16) for p in pts], "s--", alpha=0.6,
                  label=f"error of max|x2|, w = {omega}")
    ax.set_xlabel("harmonics H")
    ax.set_ylabel("relative error vs time-domain reference")
    ax.set_title("harmonic balance: error vs number of harmonics")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{folder}/convergence_harmonics.{ext}")
    plt.close(fig)
    files = sorted(glob.glob(f"{folder}/reference_*.csv"))
    if files:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for f in files:
            rs = list(csv.DictReader(open(f)))
            ax.loglog([float(r["step"]) for r in rs], [float(r["l2_error_vs_finest"]) for r in rs], "o-",
                      label=os.path.basename(f)[len("reference_"):-4])
        ax.set_xlabel("time step h")
        ax.set_ylabel("relative L2 error vs finest step")
        ax.set_title("time-domain reference: error vs step (w in legend)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        fig.tight_layout()
        for ext in ("png", "svg"):
            fig.savefig(f"{folder}/convergence_step.{ext}")
        plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results")
