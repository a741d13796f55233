#!/bin/sh
# What a beam's outputs show: by default the deflection of four nodes (w15,
# w30, w45, w60 of 60) in the CSV and the chart, the tip deflection w60
# defining the sweep's peak (not the tip rotation theta60, the last DOF);
# --show and --peak-dof choose others by name or number; the text of a solve
# lists the chosen DOFs only; the chart's legend is in numeric order.
# Usage: beam_outputs.sh EQHB PROBLEMS_DIR PLOT_CURVE
set -eu
eqhb=$1 problems=$2 plot=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
beam="$problems/beam-damper.toml"
"$eqhb" sweep "$beam" --from 3.3 --to 3.7 --step 0.05 --out "$dir/default.csv" --chart "$dir/default" >"$dir/default.txt"
cat "$dir/default.txt"
head -1 "$dir/default.csv" | grep -q ',seconds,max_abs_w15,max_abs_w30,max_abs_w45,max_abs_w60,first_harmonic_w15,'
grep -q 'peak: omega = 3.5, max|w60| = 2\.3' "$dir/default.txt"
test -s "$dir/default.png"
"$eqhb" sweep "$beam" --from 3.3 --to 3.7 --step 0.05 --show 120,w1 --peak-dof theta60 --out "$dir/chosen.csv" >"$dir/chosen.txt"
head -1 "$dir/chosen.csv" | grep -q ',seconds,max_abs_theta60,max_abs_w1,first_harmonic_theta60,first_harmonic_w1,energy'
grep -q 'peak: omega = 3.5, max|theta60| = 3\.2' "$dir/chosen.txt"
"$eqhb" solve "$beam" >"$dir/solve.txt"
test "$(grep -c '  max|\(w\|theta\|x\)[0-9]*|' "$dir/solve.txt")" -eq 4
grep -q '  max|w60| = ' "$dir/solve.txt"
# Numeric order of the legend: x2 before x10, theta5 and w5 before w10.
/usr/bin/python3 - "$plot" <<'PY'
import importlib.util, sys
spec = importlib.util.spec_from_file_location("plot_curve", sys.argv[1])
plot = importlib.util.module_from_spec(spec)
spec.loader.exec_module(plot)
got = sorted(["x10", "x2", "x1", "w10", "theta5", "w5"], key=plot.numeric_order)
assert got == ["x1", "x2", "theta5", "w5", "w10", "x10"], got
PY
echo "beam outputs: default and chosen DOFs, peaks and legend order as expected"
