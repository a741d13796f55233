#!/usr/bin/env python3
"""Damper curves from an `eqhb study --peak` over a forcing level and the
normal load: peak amplitude vs normal load, one curve per forcing level, the
optimum load of each (the smallest peak), as a chart and a report section.
The chart is drawn by cli/plot_study.py, the drawing of `eqhb study --chart`.

    damper_chart.py STUDY_DIR REPORT.md [FORCING_PATH LOAD_PATH DOF [SCENE_NAME]]

DOF: the study's --dof, by name ("w60") or number from 1.

LOAD_PATH may be the linked form of `--vary A,B,...` (the study's column).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import plot_study  # noqa: E402


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    folder, report = sys.argv[1], sys.argv[2]
    forcing = sys.argv[3] if len(sys.argv) > 3 else "forcing[0].cos"
    load = sys.argv[4] if len(sys.argv) > 4 else "law.muN"
    dof = sys.argv[5] if len(sys.argv) > 5 else "1"
    name = sys.argv[6] if len(sys.argv) > 6 else "friction-1d"
    rows, varied = plot_study.read_study(folder)
    dof = plot_study.dof_name(folder, dof)
    prefix = os.path.join(os.path.dirname(report) or ".", f"damper_{name}")
    lines, failed = plot_study.draw(rows, varied, dof, prefix, name, x_path=load,
                                    x_label="normal load μN" + (" (every damper)" if "," in load else ""),
                                    group_label="forcing")
    section = ["", f"## Damper curves ({name})", "",
               "Resonance peak (largest maximum over ω of the first-harmonic amplitude of " + dof +
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
