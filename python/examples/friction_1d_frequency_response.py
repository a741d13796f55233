#!/usr/bin/env python3
"""The frequency response of the friction-1d scene (2-DOF chain, exact Coulomb
friction on DOF 2) from Python: a sequential sweep over the scene's range, the
resonance peak, and a chart of max|x| against omega.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/friction_1d_frequency_response.py \
        [--scene problems/friction-1d.toml] [--step 0.001] [--out friction-1d-frf] [--log-amplitude]

The same curve from the command line: eqhb sweep problems/friction-1d.toml --step 0.001 --chart friction-1d-frf
"""
import argparse
import pathlib
import time

import numpy as np

import eqhb


def main():
    here = pathlib.Path(__file__).resolve()
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(here.parents[2] / "problems" / "friction-1d.toml"))
    parser.add_argument("--step", type=float, default=0.001, help="grid step in omega")
    parser.add_argument("--solver", default="dogleg")
    parser.add_argument("--out", default="friction-1d-frf", help="chart prefix: PREFIX.png, PREFIX.svg")
    parser.add_argument("--log-amplitude", action="store_true")
    parser.add_argument("--no-chart", action="store_true", help="print the figures only")
    args = parser.parse_args()

    model = eqhb.load_scene(args.scene)
    start, stop = model.sweep_range
    began = time.perf_counter()
    curve = eqhb.sweep(model, start, stop, step=args.step, solver=args.solver)
    wall = time.perf_counter() - began

    ok = curve["converged"]
    amplitude = curve["max_abs"]  # points x DOFs
    peak = int(np.argmax(np.where(ok, amplitude[:, -1], -np.inf)))
    print(f"{model!r}")
    print(f"sweep {start} -> {stop}, step {args.step}, {curve['solver']}: {len(curve['omega'])} points, "
          f"{curve['failed_points']} failed, {curve['stop_reason']}")
    print(f"peak: omega = {curve['omega'][peak]:.6g}, max|x{model.dofs}| = {amplitude[peak, -1]:.6g}, "
          f"first harmonic {curve['first_harmonic'][peak, -1]:.6g}")
    print(f"time: {curve['seconds']:.3f} s in the library, {wall:.3f} s with the Python call")
    if args.no_chart:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for dof in range(model.dofs):
        ax.plot(curve["omega"][ok], amplitude[ok, dof], lw=1.2, label=f"max|x{dof + 1}|")
    if (~ok).any():
        ax.plot(curve["omega"][~ok], np.zeros((~ok).sum()), "r|", ms=12, label=f"{(~ok).sum()} failed")
    if args.log_amplitude:
        ax.set_yscale("log")
    ax.set_xlabel("forcing frequency ω")
    ax.set_ylabel("max |x| over one period")
    ax.set_title(f"{model.name}: frequency response (H = {model.harmonic_count} {model.harmonic_set})")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{args.out}.{ext}")
    print(f"chart: {args.out}.png, {args.out}.svg")


if __name__ == "__main__":
    main()
