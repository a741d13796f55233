#!/usr/bin/env python3
"""Work-precision charts against the exact periodic orbits, from the
precision.csv that eqhb-precision writes, and the report section.

    precision_charts.py FOLDER [REPORT.md]

Per scene, precision_SCENE.png/.svg: sup error against the exact orbit vs
median time per solve (log-log), one line per curve (H grows along it), the
Pareto front over every curve drawn in black, failed solves as crosses on a
band above the converged points (each where its time lies). With REPORT.md
the section "Work-precision against the exact orbits" is appended: charts,
the curves on each Pareto front and the rates table (FOLDER/precision.md).
"""
import csv
import os
import re
import sys
from collections import OrderedDict, defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def slug(scene):
    return re.sub(r"[^A-Za-z0-9.]+", "-", scene.replace("ω", "w")).strip("-")


def read(folder):
    scenes = OrderedDict()
    with open(os.path.join(folder, "precision.csv")) as f:
        for row in csv.DictReader(f):
            row["harmonics"] = int(row["harmonics"])
            row["seconds"] = float(row["seconds"])
            row["converged"] = row["converged"] == "1" and row["sup_error"] != ""
            row["sup_error"] = float(row["sup_error"]) if row["sup_error"] else None
            row["max_abs_error"] = float(row["max_abs_error"]) if row["max_abs_error"] else None
            scenes.setdefault(row["scene"], OrderedDict()).setdefault(row["curve"], []).append(row)
    return scenes


def pareto(points):
    """Points (seconds, error, row) not beaten in both time and error, fastest first."""
    front, best = [], float("inf")
    for p in sorted(points, key=lambda p: (p[0], p[1])):
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def chart(folder, scene, curves):
    fig, ax = plt.subplots(figsize=(10, 6))
    cmap = plt.get_cmap("tab20")
    converged = [(r["seconds"], r["sup_error"], r) for rows in curves.values() for r in rows if r["converged"]]
    if not converged:
        plt.close(fig)
        return None, []
    top = max(e for _, e, _ in converged) * 4
    for i, (name, rows) in enumerate(curves.items()):
        color = cmap(i % 20)
        style = {"hb+shooting": "--", "hb0+shooting": ":"}.get(rows[0]["variant"], "-")
        ok = [r for r in rows if r["converged"]]
        ax.plot([r["seconds"] for r in ok], [r["sup_error"] for r in ok], style, marker="o", ms=3, lw=1,
                color=color, label=name)
        bad = [r for r in rows if not r["converged"]]
        if bad:
            ax.plot([r["seconds"] for r in bad], [top] * len(bad), "x", color=color, ms=7, mew=1.5)
    front = pareto(converged)
    ax.plot([p[0] for p in front], [p[1] for p in front], "-", color="black", lw=2.5, alpha=0.35,
            drawstyle="steps-post", label="Pareto front")
    ax.plot([p[0] for p in front], [p[1] for p in front], "o", mfc="none", mec="black", ms=8)
    if any(not r["converged"] for rows in curves.values() for r in rows):
        ax.axhline(top, color="grey", lw=0.5, ls=":")
        ax.text(0.01, top, " failed solves (x)", transform=ax.get_yaxis_transform(), va="bottom", fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("median seconds per solve (H grows along each curve)")
    ax.set_ylabel("sup |x − x_exact| / max|x_exact|")
    ax.set_title(f"{scene}: error against the exact orbit vs time")
    ax.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.01, 0.5))
    ax.grid(True, which="both", alpha=0.2)
    name = f"precision_{slug(scene)}"
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(folder, f"{name}.{ext}"), dpi=110)
    plt.close(fig)
    return name, front


def front_summary(front):
    """The curves on a Pareto front, each with the H and error range it covers there."""
    members = OrderedDict()
    for seconds, error, row in front:
        members.setdefault(row["curve"], []).append((row["harmonics"], error, seconds))
    lines = []
    for curve, pts in members.items():
        hs = sorted(h for h, _, _ in pts)
        errors = [e for _, e, _ in pts]
        times = [t for _, _, t in pts]
        lines.append(f"{curve} (H {hs[0]}–{hs[-1]}: error {max(errors):.2g} → {min(errors):.2g}, "
                     f"{min(times):.2g}–{max(times):.2g} s)")
    return lines


VARIANTS = {"hb+shooting": "HB + shooting", "hb0+shooting": "HB at H0 + shooting"}


def variant_rows(scene, curves, front):
    """Where each shooting variant takes over from plain HB on one scene."""
    return [row for row in (variant_row(scene, curves, front, v) for v in VARIANTS) if row]


def variant_row(scene, curves, front, variant):
    points = [(r["seconds"], r["sup_error"], r) for rows in curves.values() for r in rows if r["converged"]]
    hb = [p for p in points if p[2]["variant"] == "hb"]
    shoot = [p for p in points if p[2]["variant"] == variant]
    if not hb or not shoot:
        return None
    best_hb = min(hb, key=lambda p: (p[1], p[0]))
    on_front = [p for p in front if p[2]["variant"] == variant]
    takes_over = f"{max(p[1] for p in on_front):.2g}" if on_front else "never"
    reaching = [p for p in shoot if p[1] <= best_hb[1]]
    if reaching:
        t = min(p[0] for p in reaching)
        cost = f"{t:.2g} s ({t / best_hb[0]:.2g}× HB's)"
    else:
        cost = "not reached"
    best_shoot = min(p[1] for p in shoot)
    return (f"| {scene} | {VARIANTS[variant]} | {best_hb[2]['curve']} (H = {best_hb[2]['harmonics']}) | {best_hb[1]:.2g} | "
            f"{best_hb[0]:.2g} | {takes_over} | {cost} | {best_shoot:.2g} |")


def main(folder, report=None):
    scenes = read(folder)
    md = ["## Work–precision against the exact orbits\n",
          "eqhb-precision: per scene where shooting applies, the error of each solution against the exact "
          "periodic orbit (sup over the period and DOFs, relative to max|x|) vs the median time per solve, "
          "H growing along each curve (N following H); solves by continuation in H from H = 5. Curves: every "
          "exact law form × ρ policy (fixed: the scene's ρ; scaled: ρ·5/H; adaptive: ρ balancing the law's "
          "two arguments on the H = 5 solution) on the own dogleg, the first form on the other backends and "
          "systems, harmonic balance followed by shooting (dashed) and harmonic balance at H = 5 followed by "
          "shooting, the orbit projected on each H (dotted). Black: the Pareto front over all curves; "
          "crosses on the dotted line: failed solves at their time. Data: precision.csv, precision.json.\n"]
    wins = defaultdict(int)
    variants = []
    for scene, curves in scenes.items():
        name, front = chart(folder, scene, curves)
        md.append(f"### {scene}\n")
        if name is None:
            md.append("no converged solve\n")
            continue
        md.append(f"![{scene}]({name}.png)\n")
        failed = sum(1 for rows in curves.values() for r in rows if not r["converged"])
        md.append(f"Pareto front ({failed} failed solves drawn as crosses):\n")
        md.extend(f"- {line}" for line in front_summary(front))
        md.append("")
        for _, _, row in front:
            wins[row["variant"]] += 1
        variants.extend(variant_rows(scene, curves, front))
    md.append("Points on the Pareto fronts by variant: " +
              ", ".join(f"{v} {n}" for v, n in sorted(wins.items())) + "\n")
    md.append("### Where each variant wins\n")
    md.append("Per shooting variant: plain HB's most accurate point over all its curves, the largest error at which "
              "the variant is on the Pareto front (below it, it wins), the time it takes to reach plain HB's best "
              "error, and its own best error.\n")
    md.append("| scene | variant | plain HB's best curve | its error | its s | variant wins below | variant's time "
              "to that error | variant's best error |")
    md.append("|---|---|---|---|---|---|---|---|")
    md.extend(variants)
    md.append("")
    rates = os.path.join(folder, "precision.md")
    if os.path.exists(rates):
        md.append(open(rates).read())
    text = "\n".join(md) + "\n"
    if report:
        with open(report, "a") as f:
            f.write("\n" + text)
    print(text)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else None)
