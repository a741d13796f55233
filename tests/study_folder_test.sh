#!/usr/bin/env bash
# A study folder holds one study. A journal is checked against the plan,
# with or without plan.txt, and row by row (sample id in range and not
# truncated, the plan's values for that id, finite results on ok rows); a
# second study on a folder in use is refused at once.
#   study_folder_test.sh EQHB SCENE WORKDIR
set -euo pipefail
eqhb=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
args=(study "$scene" --harmonics 5 --samples 128 --vary law.muN=1:6:6 --peak --from 0.3 --to 1.2 --threads 1)
other=(study "$scene" --harmonics 5 --samples 128 --vary law.muN=1:7:6 --peak --from 0.3 --to 1.2 --threads 1)

source "$(dirname "$0")/expect.sh"
# edit FOLDER LINE COLUMN VALUE: one field of one journal line (1-based).
edit() {
  /usr/bin/python3 - "$1/journal.csv" "$2" "$3" "$4" <<'PY'
import sys
path, line, column, value = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
lines = open(path).read().split("\n")
fields = lines[line - 1].split(",")
fields[column - 1] = value
lines[line - 1] = ",".join(fields)
open(path, "w").write("\n".join(lines))
PY
}

"$eqhb" "${args[@]}" --out "$work/a" >/dev/null
cp -r "$work/a" "$work/kept"
# Another study in the folder: refused, naming the folder and the first
# line of plan.txt that differs.
expect 2 "--out = $work/a: holds another study \(its plan.txt differs from this command's: line [0-9]+ is '2' there, '2.2[0-9]*' for" \
  "$eqhb" "${other[@]}" --out "$work/a"
# Without plan.txt the journal still knows its study.
rm "$work/a/plan.txt"
expect 2 "--out = $work/a: holds another study: journal.csv has plan fingerprint [0-9a-f]{16}, this command's is [0-9a-f]{16} \(plan.txt, which would say what differs, is missing\)" \
  "$eqhb" "${other[@]}" --out "$work/a"
[ ! -e "$work/a/plan.txt" ] || { echo "plan.txt written for a refused study"; exit 1; }
# The same study resumes (nothing left to compute) and writes plan.txt again.
expect 0 " 0 computed now" "$eqhb" "${args[@]}" --out "$work/a"
cmp "$work/a/plan.txt" "$work/kept/plan.txt"

# Rows (line 3 is sample 0's: plan fingerprint, header, rows).
row=3
sed -n "${row}p" "$work/kept/journal.csv" | grep -q '^0,1,ok,' || { echo "line $row is not sample 0's"; exit 1; }
check_row() {  # COLUMN VALUE REGEX
  rm -rf "$work/b" && cp -r "$work/kept" "$work/b"
  edit "$work/b" "$row" "$1" "$2"
  expect 2 "$3" "$eqhb" "${args[@]}" --out "$work/b"
}
# 4294967301 = 2^32 + 5 is not sample 5.
check_row 1 4294967301 "$work/b/journal.csv:$row sample = '4294967301': must be an integer in \[0, 2147483647\]"
check_row 1 6 "$work/b/journal.csv:$row sample = 6: this study has samples 0 to 5"
check_row 2 1.5 "$work/b/journal.csv:$row law.muN = 1.5: sample 0 of this study has 1"
check_row 2 1.0000000000000002 "$work/b/journal.csv:$row law.muN = 1.0000000000000002: sample 0 of this study has 1"
check_row 5 nan "$work/b/journal.csv:$row sample = 0: is ok but has a non-finite peak_omega"
check_row 6 inf "$work/b/journal.csv:$row sample = 0: is ok but has a non-finite"
check_row 14 -3 "$work/b/journal.csv:$row worker = '-3': must be an integer"
# A row twice.
rm -rf "$work/b" && cp -r "$work/kept" "$work/b"
sed -n "${row}p" "$work/kept/journal.csv" >>"$work/b/journal.csv"
expect 2 "$work/b/journal.csv:9 sample = 0: is already on line $row" "$eqhb" "${args[@]}" --out "$work/b"
# A journal from before the fingerprint (header first).
rm -rf "$work/b" && cp -r "$work/kept" "$work/b"
sed -i 1d "$work/b/journal.csv"
expect 2 "$work/b/journal.csv:1 = sample,law.muN,.*: is not the first line of an eqhb study journal" \
  "$eqhb" "${args[@]}" --out "$work/b"

# One study at a time: a second one on a folder in use exits at once.
long=(study "$scene" --harmonics 5 --samples 128 --vary law.muN=1:8:4000 --peak --from 0.3 --to 1.2 --threads 1)
"$eqhb" "${long[@]}" --out "$work/c" >/dev/null 2>&1 &
first=$!
for _ in $(seq 1 1000); do
  [ "$({ wc -l <"$work/c/journal.csv"; } 2>/dev/null || echo 0)" -ge 4 ] && break
  sleep 0.01
done
started=$(date +%s%N)
expect 2 "--out = $work/c: is in use by another study \(process $first on [^ ]+ holds $work/c/lock\)" \
  timeout 60 "$eqhb" "${long[@]}" --out "$work/c"
elapsed_ms=$((($(date +%s%N) - started) / 1000000))
kill "$first"
wait "$first" 2>/dev/null || true
echo "second study refused in $elapsed_ms ms"
[ "$elapsed_ms" -lt 20000 ] || { echo "the second study took $elapsed_ms ms to be refused"; exit 1; }
# The lock goes with its process: past it, the next study meets the plan.
expect 2 "--out = $work/c: holds another study \(its plan.txt differs" "$eqhb" "${other[@]}" --out "$work/c"
echo "study folder checks passed"
