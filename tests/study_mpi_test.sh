#!/usr/bin/env bash
# The study on MPI ranks gives the serial results: 2 ranks (one worker),
# then 3 ranks (two workers, dynamic distribution) resuming a journal that
# already holds some samples; a killed mpirun leaves no rank writing.
#   study_mpi_test.sh MPIEXEC EQHB SCENE WORKDIR
set -euo pipefail
mpiexec=$1 eqhb=$2 scene=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
compare="/usr/bin/python3 $(dirname "$0")/compare_studies.py"
launcher=("$mpiexec")
# Open MPI: as root in containers (it refuses root otherwise, even for
# --version), and more ranks than cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$mpiexec" --version 2>/dev/null | grep -qiE "open ?mpi|openrte|open-mpi" && launcher+=(--oversubscribe)
args=(study "$scene" --harmonics 5 --samples 128 --vary forcing[0].cos=10:20:2 --vary law.muN=0.5:3:20
  --peak --from 0.3 --to 1.2)
total=40

"$eqhb" "${args[@]}" --threads 1 --out "$work/serial" >/dev/null
"${launcher[@]}" -np 2 "$eqhb" "${args[@]}" --out "$work/two" | tee "$work/two.txt"
grep -q "on 2 MPI ranks" "$work/two.txt"
$compare "$work/two/study.csv" "$work/serial/study.csv" 1e-6 "$total"

# A journal with the first 5 samples (as a killed run leaves it: the plan's
# fingerprint, the header, 5 rows), resumed on 3 ranks.
mkdir -p "$work/three"
cp "$work/serial/plan.txt" "$work/three/"
head -n 7 "$work/serial/journal.csv" >"$work/three/journal.csv"
"${launcher[@]}" -np 3 "$eqhb" "${args[@]}" --out "$work/three" | tee "$work/three.txt"
grep -q "$((total - 5)) computed now on 3 MPI ranks" "$work/three.txt"
$compare "$work/three/study.csv" "$work/serial/study.csv" 1e-6 "$total"
# Both workers took part.
column=$(sed -n 2p "$work/three/journal.csv" | tr ',' '\n' | grep -n '^worker$' | cut -d: -f1)
[ "$(cut -d, -f"$column" "$work/three/journal.csv" | tail -n +8 | sort -u | tr '\n' ' ')" = "1 2 " ]

# A rippled, stick-dominated resonance top, where a peak depends on where its
# search starts: 3 ranks give the serial rows exactly (whole warm-start blocks).
rippled=(study "$scene" --set forcing[0].cos=20 --vary law.muN=36:40:40 --peak --from 1.3 --to 1.7)
"$eqhb" "${rippled[@]}" --threads 1 --out "$work/rippled-serial" --quiet
"${launcher[@]}" -np 3 "$eqhb" "${rippled[@]}" --out "$work/rippled-three" --quiet
$compare "$work/rippled-three/study.csv" "$work/rippled-serial/study.csv" 1e-13 40

# mpirun killed (SIGKILL) mid-study: its orphaned ranks stop writing at once
# (they used to append rows for more than a second) and the folder is free.
long=(study "$scene" --harmonics 5 --samples 128 --vary law.muN=1:8:20000 --peak --from 0.3 --to 1.2)
"${launcher[@]}" -np 3 "$eqhb" "${long[@]}" --out "$work/killed" --quiet >/dev/null 2>&1 &
job=$!
for _ in $(seq 1 1000); do
  [ "$({ wc -l <"$work/killed/journal.csv"; } 2>/dev/null || echo 0)" -ge 20 ] && break
  sleep 0.01
done
kill -9 "$job"
wait "$job" 2>/dev/null || true
sleep 0.2  # a row being written at the kill lands
at_kill=$(wc -l <"$work/killed/journal.csv")
sleep 1.5
after=$(wc -l <"$work/killed/journal.csv")
echo "journal lines 0.2 s after killing mpirun: $at_kill, 1.7 s after: $after"
[ "$after" -eq "$at_kill" ] || { echo "orphaned ranks kept writing"; exit 1; }
# Past the lock (released): this other study meets the folder's plan.
refused=$("$eqhb" study "$scene" --vary law.muN=1:2:2 --peak --out "$work/killed" 2>&1 || true)
grep -q "holds another study" <<<"$refused"
