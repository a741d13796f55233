#!/usr/bin/env bash
# A full disk stops a study at the first failed write, with exit code 3 (I/O
# failure, not bad input) and a message naming the file; the journal left
# behind is whole up to that row, and the study resumes once there is room.
# Needs a 16 KiB tmpfs (root); skipped (77) where it cannot be mounted.
#   study_full_disk_test.sh EQHB SCENE WORKDIR
set -euo pipefail
eqhb=$1 scene=$2 work=$3
disk=$work/disk
umount "$disk" 2>/dev/null || true
rm -rf "$work" && mkdir -p "$disk"
mount -t tmpfs -o size=16k tmpfs "$disk" 2>/dev/null || { echo "cannot mount a tmpfs here: skipped"; exit 77; }
trap 'umount "$disk" 2>/dev/null || true' EXIT

source "$(dirname "$0")/expect.sh"

# 300 rows of ~160 bytes do not fit in 16 KiB: the journal's write fails.
total=300
args=(study "$scene" --harmonics 5 --samples 128 --vary law.muN=1:8:$total --peak --from 0.3 --to 1.2 --threads 2)
expect 3 "I/O error: $disk/peak/journal.csv: cannot write \([0-9]+ of [0-9]+ bytes written\) \(No space left on device\)" \
  "$eqhb" "${args[@]}" --out "$disk/peak"
[ ! -e "$disk/peak/study.csv" ] || { echo "study.csv written after a failed write"; exit 1; }
rows=$(($(wc -l <"$disk/peak/journal.csv") - 2))
echo "$rows of $total rows in the journal at the failed write"
[ "$rows" -gt 0 ] && [ "$rows" -lt "$total" ] || exit 1
# Room again: the study resumes from every whole row and computes the rest.
mount -o remount,size=8m "$disk"
expect 0 "$total samples \(peak\), $((total - rows)) computed now .*, 0 failed" "$eqhb" "${args[@]}" --out "$disk/peak"
[ "$(($(wc -l <"$disk/peak/study.csv") - 1))" -eq "$total" ]

# A sweep's curve files fill the disk: the study stops there too.
rm -rf "${disk:?}"/*
mount -o remount,size=16k "$disk"
sweep=(study "$scene" --harmonics 5 --samples 128 --vary law.muN=1:8:40 --sweep --step 0.005 --threads 1)
expect 3 "I/O error: $disk/curves/curves/sample_[0-9]{6}.csv: cannot (write|create) the curve file" \
  "$eqhb" "${sweep[@]}" --out "$disk/curves"
echo "full disk checks passed"
