#!/bin/sh
# `eqhb study --chart` draws the design chart (cli/plot_study.py, the drawing
# the benchmark's damper curves use too) and prints the smallest peak of each
# curve: friction-1d's peak falls, then rises again with the normal load.
# Usage: study_chart.sh EQHB SCENE
set -eu
eqhb=$1 scene=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$eqhb" study "$scene" --vary forcing[0].cos=10:20:2 --vary law.muN=0.5:40:6 --peak --from 0.3 --to 2.0 \
  --threads 1 --out "$dir/study" --chart "$dir/design" >"$dir/out.txt"
cat "$dir/out.txt"
test -s "$dir/design.png" && test -s "$dir/design.svg"
grep -q "chart: $dir/design.png" "$dir/out.txt"
# One table row per forcing level; its optimum strictly inside the load range.
/usr/bin/python3 - "$dir/out.txt" <<'PY'
import sys
rows = [l for l in open(sys.argv[1]) if l[:3] in ("| 1", "| 2")]
assert len(rows) == 2, rows
for r in rows:
    cells = [c.strip() for c in r.strip().strip("|").split("|")]
    optimum, at_low, at_high, peak = float(cells[1]), float(cells[4]), float(cells[5]), float(cells[2])
    assert 0.5 < optimum < 40 and peak < at_low and peak < at_high, cells
PY
