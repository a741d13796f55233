#!/usr/bin/env python3
"""Backbone chart of an `eqhb modes --csv` file: the nonlinear mode's frequency
omega and damping ratio zeta against the modal amplitude (logarithmic axis),
one panel each; points that did not converge are left out.
Usage: plot_backbone.py CSV OUTPUT.png [TITLE]"""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("output")
    parser.add_argument("title", nargs="?", default="")
    args = parser.parse_args()
    with open(args.csv, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["converged"] == "1"]
    amplitude = [float(r["amplitude"]) for r in rows]
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0))
    top.semilogx(amplitude, [float(r["omega"]) for r in rows], "o-", ms=3)
    top.set_ylabel("omega")
    bottom.semilogx(amplitude, [float(r["damping_ratio"]) for r in rows], "o-", ms=3, color="C3")
    bottom.set_ylabel("damping ratio zeta")
    bottom.set_xlabel("modal amplitude")
    for ax in (top, bottom):
        ax.grid(True, which="both", alpha=0.3)
    if args.title:
        top.set_title(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)


if __name__ == "__main__":
    main()
