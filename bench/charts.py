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
    print(f"charts written to {folder}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results")
