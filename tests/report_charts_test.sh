#!/bin/sh
# bench/report_charts.py embeds in report.md every chart of the folder that
# it does not show yet, once, and a second run replaces its own section.
# Usage: report_charts_test.sh REPORT_CHARTS_PY
set -eu
script=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf '# report\n\n![profile](performance_profile.png)\n' >"$dir/report.md"
for chart in performance_profile curve_duffing_sequential curve_duffing_arclength scale damper_friction-1d; do
  : >"$dir/$chart.png"
done
/usr/bin/python3 "$script" "$dir" | grep -q '4 charts embedded now, 1 shown already, 5 in all'
/usr/bin/python3 "$script" "$dir" | grep -q '4 charts embedded now, 1 shown already, 5 in all'
cat "$dir/report.md"
for chart in performance_profile curve_duffing_sequential curve_duffing_arclength scale damper_friction-1d; do
  test "$(grep -c "($chart.png)" "$dir/report.md")" -eq 1
done
test "$(grep -c '^## Every other chart' "$dir/report.md")" -eq 1
grep -q '^### curve' "$dir/report.md"
