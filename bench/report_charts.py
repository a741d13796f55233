#!/usr/bin/env python3
"""Embeds in report.md every chart of its folder that it does not show yet:
the charts the benchmark's steps make (charts.py, damper_chart.py, ...) are
named in report.md by some steps and only listed by others. Appends one
section, "## Every other chart", grouped by the chart's kind (the part of its
name before the first underscore), each chart under its name.

    report_charts.py FOLDER [REPORT]     (REPORT default FOLDER/report.md)

Prints the number of charts embedded now and the number already shown."""
import os
import re
import sys
from collections import defaultdict

SECTION = "## Every other chart"


def shown_in(text):
    """The PNG files a Markdown text embeds (![...](NAME.png))."""
    return {os.path.basename(m) for m in re.findall(r"!\[[^\]]*\]\(([^)\s]+\.png)\)", text)}


def section(missing):
    """The appended section: per kind, each chart with its name as caption."""
    kinds = defaultdict(list)
    for name in sorted(missing):
        kinds[name.split("_")[0].removesuffix(".png")].append(name)
    lines = ["", SECTION, "",
             "Every chart the run made that the sections above do not show (PNG; SVG beside each).", ""]
    for kind in sorted(kinds):
        lines += [f"### {kind}", ""]
        for name in kinds[kind]:
            lines += [f"![{name[:-4]}]({name})", ""]
    return lines


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    folder = argv[1]
    report = argv[2] if len(argv) > 2 else os.path.join(folder, "report.md")
    text = open(report).read() if os.path.exists(report) else ""
    if SECTION in text:  # a second run replaces its own section
        text = text[:text.index(SECTION)].rstrip("\n") + "\n"
    charts = {n for n in os.listdir(folder) if n.endswith(".png")}
    shown = shown_in(text) & charts
    missing = charts - shown
    if missing:
        text += "\n".join(section(missing)) + "\n"
    with open(report, "w") as f:
        f.write(text)
    print(f"report_charts: {len(missing)} charts embedded now, {len(shown)} shown already, {len(charts)} in all")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
