#!/usr/bin/env bash
# A --peak study resumed from a journal cut in mid-block gives the rows of an
# uninterrupted run, bit for bit: the cut block is computed again from its
# cold first sample to rebuild the warm starts. (Resumed with a cold start
# at the first missing sample instead, friction-1d at forcing 20 followed the
# fading first resonance at muN = 9 to 10.5: peaks of 87 down to 13 where
# the largest, near omega = 1.62, is 111 down to 102.)
#   study_resume_peak_test.sh EQHB SCENE WORKDIR
set -euo pipefail
eqhb=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
args=(study "$scene" --set forcing[0].cos=20 --vary law.muN=6.5:14:16 --peak --from 0.3 --to 2.0 --threads 1)
total=16
"$eqhb" "${args[@]}" --out "$work/fresh" >/dev/null
for kept in 1 5; do
  mkdir -p "$work/cut$kept"
  cp "$work/fresh/plan.txt" "$work/cut$kept/"
  # The plan's fingerprint and the CSV header, then the first rows.
  lines=$(($(grep -c '^#' "$work/fresh/journal.csv" || true) + 1 + kept))
  head -n "$lines" "$work/fresh/journal.csv" >"$work/cut$kept/journal.csv"
  "$eqhb" "${args[@]}" --out "$work/cut$kept" | tee "$work/cut$kept.txt"
  grep -q "$((total - kept)) computed now" "$work/cut$kept.txt"
  /usr/bin/python3 "$(dirname "$0")/compare_studies.py" "$work/cut$kept/study.csv" "$work/fresh/study.csv" 0 "$total"
  # Rows already in the journal are not written twice.
  [ "$(($(wc -l <"$work/cut$kept/journal.csv") - lines))" -eq "$((total - kept))" ]
done
