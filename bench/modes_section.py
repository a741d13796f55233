#!/usr/bin/env python3
"""Nonlinear modes in the benchmark: the backbone of each scene (omega and
damping ratio against modal amplitude) with its time, and, where the scene is
forced, the forced response the mode predicts against the forced sweep across
that resonance (`eqhb modes SCENE --synthesis --json`); then the same backbone
on the condensed mode system (`--condensed`) against it. Writes one chart per
scene (OUT/modes_NAME.png, .svg) and appends a section to the report.

    modes_section.py EQHB OUT REPORT.md [SCENE ...]

Without SCENE, the scenes listed below (problems/ relative to this file).
"""
import json
import pathlib
import resource
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENES = ["friction-1d", "jenkins-1d", "stribeck", "duffing", "cubic", "contact", "penalty-contact",
          "beam-damper-elastic", "beam-damper", "damper", "lap-joint", "field/nlvib-08-cantilever-friction-si",
          "field/tmdsimpy-sdof-jenkins-f33", "field/modes/nlvib-05-2dof-friction-modes"]


# Seconds for a condensed backbone: it factors every A_k at each new (ω, ξ),
# which the lap joint's 300-odd DOFs make far slower than its full system.
CONDENSED_TIME_LIMIT = 120


def run_modes(eqhb, scene, extra=None, time_limit=600):
    """The command's JSON (with the synthesis where the scene is forced, unless
    `extra` options are given), its exit code and CPU seconds of the child."""
    forced = "[[forcing]]" in scene.read_text()
    command = [eqhb, "modes", str(scene), "--json", "--quiet", "--backbone-time-limit", str(time_limit)]
    if extra:
        command += extra
    elif forced:
        command.append("--synthesis")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run = subprocess.run(command, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if run.returncode == 2 or not run.stdout.strip():
        return None, run.returncode, cpu, run.stderr.strip()
    return json.loads(run.stdout), run.returncode, cpu, run.stderr.strip()


def chart(result, name, out):
    converged = [p for p in result["points"] if p["converged"]]
    synthesis = result.get("synthesis")
    panels = 3 if synthesis and synthesis.get("forced") else 2
    fig, axes = plt.subplots(1, panels, figsize=(4.2 * panels, 3.6))
    a = [p["amplitude"] for p in converged]
    axes[0].semilogx(a, [p["omega"] for p in converged], ".-", ms=3)
    axes[0].set_xlabel("modal amplitude")
    axes[0].set_ylabel("ω (rad/s)")
    axes[1].semilogx(a, [p["damping_ratio"] for p in converged], ".-", ms=3, color="tab:red")
    axes[1].set_xlabel("modal amplitude")
    axes[1].set_ylabel("ζ")
    if panels == 3:
        dof = synthesis["dof"]
        forced = [(p["omega"], p["max_abs"]) for p in synthesis["forced"]["points"] if p["converged"]]
        points = synthesis["points"]
        axes[2].plot([p["omega"] for p in points], [p["max_abs"][dof - 1] for p in points], ".", ms=4,
                     color="tab:green", label="one-mode synthesis")
        axes[2].plot([w for w, _ in forced], [x for _, x in forced], "-", color="black", lw=1, label="forced sweep")
        if forced:
            axes[2].set_xlim(min(w for w, _ in forced), max(w for w, _ in forced))
        axes[2].set_xlabel("ω (rad/s)")
        axes[2].set_ylabel(f"max|x{dof}|")
        axes[2].legend(loc="best", fontsize=8)
    fig.suptitle(name, fontsize=10)
    fig.tight_layout()
    for suffix in (".png", ".svg"):
        fig.savefig(out / f"modes_{name}{suffix}", dpi=110)
    plt.close(fig)


def largest_difference(full, condensed, key):
    """The largest relative difference of `key` over the amplitudes both
    backbones reached (paired in the path's order), or None."""
    pairs = [(a[key], b[key]) for a, b in zip(full["points"], condensed["points"])
             if a["converged"] and b["converged"] and a["amplitude"] == b["amplitude"]]
    return max((abs(b - a) / max(abs(a), 1e-300) for a, b in pairs), default=None)


def condensed_row(eqhb, path, full):
    condensed, code, cpu, error = run_modes(eqhb, path, ["--condensed"], CONDENSED_TIME_LIMIT)
    if condensed is None:
        return f"| {path.stem} | – | – | – | {error.splitlines()[-1] if error else code} | |"
    stop = (condensed.get("stop") or {}).get("why", "")
    d_omega, d_zeta = largest_difference(full, condensed, "omega"), largest_difference(full, condensed, "damping_ratio")
    return (f"| {path.stem} | {len(condensed['points'])} | {condensed['failed_points']} | "
            f"{condensed['seconds']:.3g} (full {full['seconds']:.3g}) | "
            f"{'–' if d_omega is None else f'{d_omega:.1e}'} | {'–' if d_zeta is None else f'{d_zeta:.1e}'} |"
            + (f" {stop}" if stop else ""))


def percent(value):
    return "–" if value is None else f"{100.0 * value:+.2f} %"


def main():
    if len(sys.argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    eqhb, out, report = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    out.mkdir(parents=True, exist_ok=True)
    scenes = sys.argv[4:] or SCENES
    rows = ["| scene | points | failed | folds | backbone s (CPU s) | synthesis: peak | peak ω | "
            "band distance | forced sweep s |", "|---|---|---|---|---|---|---|---|---|"]
    condensed_rows = ["| scene | points | failed | backbone s (full s) | max Δω/ω | max Δζ/ζ |",
                      "|---|---|---|---|---|---|"]
    charts = []
    for name in scenes:
        path = pathlib.Path(name)
        if not path.exists():
            path = ROOT / "problems" / f"{name}.toml"
        result, code, cpu, error = run_modes(eqhb, path)
        label = path.stem
        if result is None:
            rows.append(f"| {label} | – | – | – | – | {error.splitlines()[-1] if error else code} | | | |")
            continue
        chart(result, label, out)
        charts.append(label)
        condensed_rows.append(condensed_row(eqhb, path, result))
        s = result.get("synthesis")
        peak = omega = band = forced_s = None
        note = ""
        if s and s.get("errors") and s.get("not_compared") is None:
            peak, omega, band = s["errors"]["peak_amplitude"], s["errors"]["peak_omega"], s["errors"]["band_distance"]
            forced_s = s["forced"]["seconds"]
        elif s:
            note = s.get("not_compared") or "no peak"
        else:
            note = "not forced"
        backbone_s = result["seconds"]
        rows.append(f"| {label} | {len(result['points'])} | {result['failed_points']} | {len(result['folds'])} | "
                    f"{backbone_s:.3g} ({cpu:.3g}) | {percent(peak) if not note else note} | {percent(omega)} | "
                    f"{'–' if band is None else f'{100 * band:.2f} %'} | "
                    f"{'–' if forced_s is None else f'{forced_s:.3g}'} |")
    text = ["", "## Nonlinear modes and one-mode synthesis", "",
            "`eqhb modes SCENE --synthesis --json` on defaults (mode 1, 50 amplitudes). Backbone seconds: the",
            "backbone's own wall time (the whole command's CPU time in brackets, synthesis and forced sweep",
            "included). Synthesis: the forced response the mode predicts (single nonlinear mode synthesis)",
            "against the forced arclength sweep across the same resonance, (synthesis − forced) / forced at the",
            "peak, and the largest distance from a forced point above half the peak to the synthesised curve,",
            "in units of the peak's height and the half-peak band's width.", ""] + rows + [""]
    text += [f"![modes {c}](modes_{c}.png)" for c in charts] + [""]
    text += ["Condensed mode system (`eqhb modes SCENE --condensed --json`, the law forces, ω and ξ as",
             f"unknowns, time limit {CONDENSED_TIME_LIMIT} s) against the full one above: the largest relative",
             "difference in ω and ζ over the amplitudes both reached. The full system's default tolerance is on",
             "forces of the size of K x, so near resonance its ζ can be the looser of the two.", ""]
    text += condensed_rows + [""]
    with open(report, "a") as f:
        f.write("\n".join(text) + "\n")
    print("\n".join(rows + [""] + condensed_rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
