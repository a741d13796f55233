#!/usr/bin/env python3
"""Damper curves from an `eqhb study --peak` over a forcing level and the
normal load: peak amplitude vs normal load, one curve per forcing level, the
optimum load of each (the smallest peak), as a chart and a report section.

    damper_chart.py STUDY_DIR REPORT.md [FORCING_PATH LOAD_PATH DOF [SCENE_NAME]]

LOAD_PATH may be the linked form of `--vary A,B,...` (the study's column).
"""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    folder, report = sys.argv[1], sys.argv[2]
    forcing = sys.argv[3] if len(sys.argv) > 3 else "forcing[0].cos"
    load = sys.argv[4] if len(sys.argv) > 4 else "law.muN"
    dof = sys.argv[5] if len(sys.argv) > 5 else "1"
    name = sys.argv[6] if len(sys.argv) > 6 else "friction-1d"
    with open(os.path.join(folder, "study.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    curves = defaultdict(list)
    failed = []
    for r in rows:
        if r["status"] != "ok":
            failed.append(r)
            continue
        curves[float(r[forcing])].append((float(r[load]), float(r["first_harmonic_x" + dof]), float(r["peak_omega"])))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    lines = ["| forcing | optimum normal load | peak amplitude there | peak ω there | "
             "amplitude at the lowest load | at the highest |", "|---|---|---|---|---|---|"]
    for level in sorted(curves):
        points = sorted(curves[level])
        loads = [p[0] for p in points]
        amplitudes = [p[1] for p in points]
        best = min(points, key=lambda p: p[1])
        ax.plot(loads, amplitudes, marker=".", label=f"forcing {level:g}")
        ax.plot([best[0]], [best[1]], "k*")
        lines.append(f"| {level:g} | {best[0]:.4g} | {best[1]:.4g} | {best[2]:.4g} | {points[0][1]:.4g} | "
                     f"{points[-1][1]:.4g} |")
    ax.set_xlabel("normal load μN" + (" (every damper)" if "," in load else ""))
    ax.set_ylabel(f"peak first-harmonic amplitude of x{dof}")
    ax.set_yscale("log")
    ax.set_title(f"{name}: resonance peak vs normal load (★ optimum)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(os.path.dirname(report) or ".", f"damper_{name}.{ext}"), dpi=120,
                    bbox_inches="tight")
    section = ["", f"## Damper curves ({name})", "",
               "Resonance peak (largest maximum over ω of the first-harmonic amplitude of x" + dof +
               ") vs the normal load, per forcing level, by `eqhb study --peak` (peaks followed along the load; "
               f"{len(rows)} samples, {len(failed)} failed). Too little load and the damper slides freely, too much "
               "and it sticks; the optimum lies between.", "", *lines, "",
               f"![damper curves](damper_{name}.png)", ""]
    for r in failed:
        section.insert(-2, f"- failed: {forcing} = {r[forcing]}, {load} = {r[load]}: {r['reason']}")
    with open(report, "a") as f:
        f.write("\n".join(section) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
