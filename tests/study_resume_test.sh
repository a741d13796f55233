#!/usr/bin/env bash
# A study killed (SIGKILL) part-way resumes from its journal and ends with
# the same study.csv as an uninterrupted run.
#   study_resume_test.sh EQHB SCENE WORKDIR
set -euo pipefail
eqhb=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
args=(study "$scene" --harmonics 5 --samples 128 --vary law.muN=1:8:40 --sweep --step 0.005 --threads 1)
total=40

"$eqhb" "${args[@]}" --out "$work/killed" >/dev/null &
pid=$!
# Kill once a few rows are on disk (journal: the plan's fingerprint, the header, rows).
for _ in $(seq 1 500); do
  rows=$(($({ wc -l <"$work/killed/journal.csv"; } 2>/dev/null || echo 2) - 2))
  [ "$rows" -ge 5 ] && break
  sleep 0.01
done
kill -9 "$pid"
wait "$pid" 2>/dev/null || true
before=$(($(wc -l <"$work/killed/journal.csv") - 2))
echo "killed with $before of $total samples in the journal"
[ "$before" -ge 5 ] && [ "$before" -lt "$total" ] || { echo "the kill did not land mid-study"; exit 1; }
[ ! -e "$work/killed/study.csv" ] || { echo "study.csv written before the end"; exit 1; }

"$eqhb" "${args[@]}" --out "$work/killed" | tee "$work/resumed.txt"
grep -q "$((total - before)) computed now" "$work/resumed.txt" || { echo "the resumed run recomputed finished samples"; exit 1; }
"$eqhb" "${args[@]}" --out "$work/reference" >/dev/null
/usr/bin/python3 "$(dirname "$0")/compare_studies.py" "$work/killed/study.csv" "$work/reference/study.csv" 1e-12 "$total"
# A finished study run again computes nothing.
"$eqhb" "${args[@]}" --out "$work/killed" | grep -q " 0 computed now"
