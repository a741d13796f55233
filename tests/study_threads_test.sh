#!/usr/bin/env bash
# On a rippled, stick-dominated resonance top (friction-1d, forcing 20,
# muN 36..40) a peak depends on where its search starts. The study hands
# out whole warm-start blocks, so 2 threads give the serial rows exactly.
#   study_threads_test.sh EQHB SCENE WORKDIR
set -euo pipefail
eqhb=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
args=(study "$scene" --set forcing[0].cos=20 --vary law.muN=36:40:40 --peak --from 1.3 --to 1.7)
"$eqhb" "${args[@]}" --threads 1 --out "$work/serial" --quiet
"$eqhb" "${args[@]}" --threads 2 --out "$work/two" --quiet
/usr/bin/python3 "$(dirname "$0")/compare_studies.py" "$work/two/study.csv" "$work/serial/study.csv" 1e-13 40
