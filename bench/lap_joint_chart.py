#!/usr/bin/env python3
"""Lap-joint curves at several forcing levels: the harmonic-1 amplitude of
the forced DOF per unit force against omega, one curve per level, as a chart
(PREFIX.png, PREFIX.svg) and a table (peak omega, peak amplitude, the
half-power damping ratio where both half-power points are on the curve).

    lap_joint_chart.py PREFIX DOF FORCE=SWEEP.csv [FORCE=SWEEP.csv ...]

Each SWEEP.csv is an `eqhb sweep --out` curve of problems/lap-joint.toml at
forcing FORCE (N); DOF is the forced DOF's name, as the CSV's columns have it
("w20" in the scene: the upper beam's node 20, pair 11).
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def half_power_ratio(points, peak):
    """(omega_2 - omega_1) / (2 omega_peak) at amplitude peak / sqrt(2), or None."""
    level = peak[1] / math.sqrt(2.0)
    crossings = []
    for (w0, a0), (w1, a1) in zip(points, points[1:]):
        if (a0 - level) * (a1 - level) < 0.0:
            crossings.append(w0 + (level - a0) * (w1 - w0) / (a1 - a0))
    below = [w for w in crossings if w < peak[0]]
    above = [w for w in crossings if w > peak[0]]
    if not below or not above:
        return None
    return (min(above) - max(below)) / (2.0 * peak[0])


def main():
    if len(sys.argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    prefix, dof = sys.argv[1], sys.argv[2]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    lines = ["| forcing (N) | points | failed | peak ω (rad/s) | peak amplitude (m) | peak / force (m/N) | "
             "half-power ζ |", "|---|---|---|---|---|---|---|"]
    for spec in sys.argv[3:]:
        force_text, path = spec.split("=", 1)
        force = float(force_text)
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        points = sorted((float(r["omega"]), float(r["first_harmonic_" + dof])) for r in rows if r["converged"] == "true")
        failed = sum(1 for r in rows if r["converged"] != "true")
        peak = max(points, key=lambda p: p[1])
        zeta = half_power_ratio(points, peak)
        ax.plot([p[0] for p in points], [p[1] / force for p in points], label="%g N" % force)
        lines.append("| %g | %d | %d | %.1f | %.4g | %.4g | %s |" % (force, len(rows), failed, peak[0], peak[1],
                                                                    peak[1] / force,
                                                                    "%.4f" % zeta if zeta else "(off the curve)"))
    ax.set_xlabel("ω (rad/s)")
    ax.set_ylabel("harmonic-1 amplitude / force (m/N), DOF %s" % dof)
    ax.set_title("lap-joint: microslip to macroslip")
    ax.legend(title="forcing")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=120)
    fig.savefig(prefix + ".svg")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
