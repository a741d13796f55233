#!/usr/bin/env python3
"""Design chart of an `eqhb study` folder: the resonance peak (the largest
first-harmonic amplitude of one DOF) against the last varied value, one curve
per value of the others, the smallest peak of each curve starred (a damper's
optimum normal load), on a logarithmic amplitude axis.
Usage: plot_study.py STUDY_DIR PREFIX [--dof DOF] [--x PATH] [--title TITLE]
(DOF: its name in study.csv's columns, "w60", or its number from 1)
writes PREFIX.png and PREFIX.svg and prints a Markdown table of the optima."""
import argparse
import csv
import json
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_study(folder):
    """study.csv's rows and the varied columns (those between `sample` and `status`)."""
    with open(os.path.join(folder, "study.csv"), newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        fields = reader.fieldnames or []
    varied = fields[1:fields.index("status")] if "status" in fields else []
    return rows, varied


def dof_name(folder, dof):
    """The name of DOF `dof` (a name, or a number from 1 looked up in the
    folder's study.json, whose dof_labels name every DOF; "x<number>" without it)."""
    dof = str(dof)
    if not dof.isdigit():
        return dof
    try:
        with open(os.path.join(folder, "study.json")) as f:
            labels = json.load(f).get("dof_labels", [])
    except OSError:
        labels = []
    return labels[int(dof) - 1] if 0 < int(dof) <= len(labels) else f"x{dof}"


def draw(rows, varied, dof, prefix, title, x_path=None, x_label=None, group_label=None):
    """The chart (PREFIX.png, .svg); returns the table lines and the failed rows.
    dof: the DOF's name as study.csv's columns have it ("w60", "x3").
    x_label, group_label: words for the axis and the curves (default: the paths)."""
    if not varied:
        raise SystemExit("plot_study.py: the study varies nothing")
    x_path = x_path or varied[-1]
    if x_path not in varied:
        raise SystemExit(f"plot_study.py: --x {x_path} is not a varied value ({', '.join(varied)})")
    others = [v for v in varied if v != x_path]
    column = f"first_harmonic_{dof}"
    curves, failed = defaultdict(list), []
    for r in rows:
        if r["status"] != "ok":
            failed.append(r)
            continue
        key = tuple(float(r[o]) for o in others)
        curves[key].append((float(r[x_path]), float(r[column]), float(r["peak_omega"])))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    x_label = x_label or x_path
    head = group_label or (" | ".join(others) if others else "curve")
    lines = [f"| {head} | optimum {x_label} | peak amplitude there | peak ω there | "
             "amplitude at the lowest value | at the highest |", "|---|---|---|---|---|---|"]
    for key in sorted(curves):
        points = sorted(curves[key])
        best = min(points, key=lambda p: p[1])
        name = (f"{group_label} " + ", ".join(f"{v:g}" for v in key) if group_label and key
                else ", ".join(f"{o} {v:g}" for o, v in zip(others, key)) or "peak")
        ax.plot([p[0] for p in points], [p[1] for p in points], marker=".", label=name)
        ax.plot([best[0]], [best[1]], "k*", ms=9)
        values = " | ".join(f"{v:g}" for v in key) if key else "all"
        lines.append(f"| {values} | {best[0]:.4g} | {best[1]:.4g} | {best[2]:.4g} | {points[0][1]:.4g} | "
                     f"{points[-1][1]:.4g} |")
    if failed:
        ax.plot([float(r[x_path]) for r in failed], [ax.get_ylim()[0]] * len(failed), "r|", ms=12,
                label=f"{len(failed)} failed")
    ax.set_xlabel(x_label)
    ax.set_ylabel(f"peak first-harmonic amplitude of {dof}")
    ax.set_yscale("log")
    what = f"resonance peak vs {x_label} (★ smallest)"
    ax.set_title(f"{title}: {what}" if title else what)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    for ext in ("png", "svg"):
        fig.savefig(f"{prefix}.{ext}", dpi=120, bbox_inches="tight")
    plt.close(fig)
    return lines, failed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("prefix", help="writes PREFIX.png and PREFIX.svg")
    parser.add_argument("--dof", default="1", help="the study's --dof: its name (\"w60\") or number from 1")
    parser.add_argument("--x", dest="x_path", help="the varied value along the axis (default: the last)")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    rows, varied = read_study(args.folder)
    lines, _ = draw(rows, varied, dof_name(args.folder, args.dof), args.prefix, args.title, args.x_path)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
