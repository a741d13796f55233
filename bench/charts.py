#!/usr/bin/env python3
"""Charts of the eqhb benchmark (matplotlib, PNG and SVG), from the CSV files
that eqhb-bench and eqhb-convergence write into one folder:
  work_precision_SCENE   median time vs error against the time reference
  performance_profile    Dolan-More profile over every scene/form/system case
  failure_map_SCENE      success rate of each backend over each grid
  curve_SCENE_*          frequency-response curves (via cli/plot_curve.py;
                         --log-amplitude for a logarithmic amplitude axis)
  convergence_*          HB error vs harmonics, reference error vs step
  scale                  scale study: time per solve, per residual + Jacobian
                         and peak memory against the unknowns (log-log)
"""
import argparse
import csv
import glob
import math
import os
import subprocess
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def label(ax, xlabel, ylabel, title, legend_size=None):
    """Axis labels, title, the grid of both tick kinds and the legend of one chart."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=legend_size)


def save(fig, folder, name):
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{folder}/{name}.{ext}")
    plt.close(fig)


def number(text):
    try:
        value = float(text)
    except ValueError:
        return math.nan
    return value


def solved(row):
    """A case solved its problem: converged and agrees with a reference (the
    verdict eqhb-bench writes); a converged answer that disagrees is a failure. Older
    files without a verdict fall back on convergence."""
    return row.get("verdict", "solved" if row["converged"] == "true" else "failed") == "solved"


def work_precision(folder, rows):
    by_scene = defaultdict(list)
    for r in rows:
        if r["study"] == "scenes":
            by_scene[r["scene"]].append(r)
    for scene, cases in by_scene.items():
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for solver in sorted({c["solver"] for c in cases}):
            pts = [(number(c["median_seconds"]), number(c["error_reference"])) for c in cases
                   if c["solver"] == solver and solved(c)]
            pts = [p for p in pts if not math.isnan(p[1])]
            if pts:
                ax.scatter([p[0] for p in pts], [max(p[1], 1e-16) for p in pts], label=solver, alpha=0.75)
        failed = sum(not solved(c) for c in cases)
        ax.set_xscale("log")
        ax.set_yscale("log")
        label(ax, "median time per solve [s]", "L2 error of x vs time-domain reference",
              f"{scene}: work-precision ({failed} of {len(cases)} cases failed)", 7)
        save(fig, folder, f"work_precision_{scene}")


def performance_profile(folder, rows):
    cases = defaultdict(dict)
    unchecked = set()
    for r in rows:
        if r["study"] != "scenes":
            continue
        key = (r["scene"], r["form"], r["system"])
        if r.get("verdict") == "unchecked":
            unchecked.add(key)
        t = number(r["median_seconds"]) if solved(r) else math.inf
        cases[key][r["solver"]] = t
    # A case no answer could be checked on says nothing of who solves it.
    for key in unchecked:
        if all(math.isinf(t) for t in cases[key].values()):
            del cases[key]
    solvers = sorted({s for c in cases.values() for s in c})
    ratios = defaultdict(list)
    for times in cases.values():
        best = min(times.values())
        for s in solvers:
            t = times.get(s, math.inf)
            ratios[s].append(t / best if math.isfinite(best) and math.isfinite(t) else math.inf)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    taus = [1.0 * (1.05 ** i) for i in range(0, 160)]
    for s in solvers:
        rs = ratios[s]
        ax.step(taus, [sum(r <= tau for r in rs) / len(rs) for tau in taus], where="post", label=s)
    ax.set_xscale("log")
    ax.set_xlabel("tau (time / best time on the case)")
    ax.set_ylabel("fraction of cases solved within tau")
    ax.set_title(f"performance profile over {len(cases)} cases (scene x form x system)\n"
                 f"solved = converged and agrees with a reference", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, folder, "performance_profile")


# What each failure-map grid varies, as the axis label.
GRID_LABELS = {
    "start": "start: perturbation σ of the solution (× its rms; cold = zero start)",
    "harmonics": "harmonics H (cold start)",
    "rho": "law scaling ρ (cold start)",
    "forcing": "forcing (× the scene's loads, cold start)",
}


def failure_maps(folder):
    path = f"{folder}/failure_maps.csv"
    if not os.path.exists(path):
        return
    rows = list(csv.DictReader(open(path)))
    for scene in sorted({r["scene"] for r in rows}):
        grids = [g for g in ("start", "harmonics", "rho", "forcing") if any(r["grid"] == g and r["scene"] == scene for r in rows)]
        fig, axes = plt.subplots(1, len(grids), figsize=(4 * len(grids), 3.6), squeeze=False)
        for ax, grid in zip(axes[0], grids):
            sub = [r for r in rows if r["scene"] == scene and r["grid"] == grid]
            solvers = sorted({r["solver"] for r in sub})
            values = []
            for r in sub:
                if r["value"] not in values:
                    values.append(r["value"])
            matrix = []
            for s in solvers:
                line = []
                for v in values:
                    cell = [r for r in sub if r["solver"] == s and r["value"] == v]
                    line.append(sum(r["converged"] == "true" for r in cell) / len(cell) if cell else math.nan)
                matrix.append(line)
            ax.imshow(matrix, cmap="RdYlGn", vmin=0, vmax=1, aspect="auto")
            ax.set_xticks(range(len(values)), values, rotation=45, fontsize=7)
            ax.set_yticks(range(len(solvers)), solvers, fontsize=7)
            ax.set_title(f"{grid}", fontsize=9)
            ax.set_xlabel(GRID_LABELS.get(grid, grid), fontsize=8)
            ax.set_ylabel("backend", fontsize=8)
            for i, line in enumerate(matrix):
                for j, value in enumerate(line):
                    if not math.isnan(value):
                        ax.text(j, i, f"{value:.0%}", ha="center", va="center", fontsize=6)
        fig.suptitle(f"{scene}: share of solves converged per backend (green 100 %, red 0 %)")
        save(fig, folder, f"failure_map_{scene}")


def curves(folder, log_amplitude):
    for path in sorted(glob.glob(f"{folder}/curve_*.csv")):
        prefix = path[:-4]
        name = os.path.basename(prefix)[len("curve_"):]
        command = [sys.executable, os.path.join(HERE, "..", "cli", "plot_curve.py"), path, prefix, name]
        subprocess.run(command + (["--log-amplitude"] if log_amplitude else []), check=False)


def convergence_charts(folder):
    path = f"{folder}/convergence.csv"
    if not os.path.exists(path):
        return
    rows = [r for r in csv.DictReader(open(path)) if r["converged"] in ("1", "true")]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for omega in sorted({r["omega"] for r in rows}):
        pts = [(int(r["harmonics"]), number(r["l2_x2"]), number(r["error_max_abs_x2"])) for r in rows if r["omega"] == omega]
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"L2 error of x2, w = {omega}")
        ax.loglog([p[0] for p in pts], [max(p[2], 1e-16) for p in pts], "s--", alpha=0.6,
                  label=f"error of max|x2|, w = {omega}")
    label(ax, "harmonics H", "relative error vs time-domain reference",
          "harmonic balance: error vs number of harmonics", 8)
    save(fig, folder, "convergence_harmonics")
    files = sorted(glob.glob(f"{folder}/reference_*.csv"))
    if files:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for f in files:
            rs = list(csv.DictReader(open(f)))
            ax.loglog([number(r["step"]) for r in rs], [number(r["l2_error_vs_finest"]) for r in rs], "o-",
                      label="w = " + os.path.basename(f)[len("reference_"):-4])
        label(ax, "time step h", "relative L2 error vs finest step", "time-domain reference: error vs step")
        save(fig, folder, "convergence_step")


def scale_chart(folder):
    path = f"{folder}/scale.csv"
    if not os.path.exists(path):
        return
    rows = [r for r in csv.DictReader(open(path)) if r["converged"] == "true"]
    studies = [("full", "full system (5 contacts)"), ("condensed", "condensed system (200 DOFs)")]

    def by_solver(study):
        """The study's rows per solver, each by increasing unknowns."""
        rows_of = defaultdict(list)
        for r in rows:
            if r["study"] == study:
                rows_of[r["solver"]].append(r)
        for rs in rows_of.values():
            rs.sort(key=lambda r: int(r["unknowns"]))
        return sorted(rows_of.items())

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    for ax, (study, title) in zip(axes[:2], studies):
        for solver, rs in by_solver(study):
            x = [int(r["unknowns"]) for r in rs]
            line, = ax.loglog(x, [number(r["solve_seconds"]) for r in rs], "o-", label=f"{solver} solve")
            ax.loglog(x, [number(r["residual_jacobian_seconds"]) for r in rs], "s--", color=line.get_color(),
                      label=f"{solver} residual+Jacobian")
        label(ax, "unknowns", "seconds", title, 6)
    ax = axes[2]
    for study, _ in studies:
        for solver, rs in by_solver(study):
            ax.loglog([int(r["unknowns"]) for r in rs], [number(r["peak_mib"]) for r in rs], "o-",
                      label=f"{study} {solver}")
    label(ax, "unknowns", "peak memory (MiB)", "peak memory per case", 6)
    save(fig, folder, "scale")


def main(folder, log_amplitude=False):
    if os.path.exists(f"{folder}/bench.csv"):
        rows = list(csv.DictReader(open(f"{folder}/bench.csv")))
        work_precision(folder, rows)
        performance_profile(folder, rows)
    failure_maps(folder)
    curves(folder, log_amplitude)
    convergence_charts(folder)
    scale_chart(folder)
    print(f"charts written to {folder}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="Charts of the eqhb benchmark")
    parser.add_argument("folder", nargs="?", default="results")
    parser.add_argument("--log-amplitude", action="store_true", help="frequency responses on a log amplitude axis")
    arguments = parser.parse_args()
    main(arguments.folder, arguments.log_amplitude)
