#!/bin/sh
# The Brake–Reuss-sized chain (481 DOFs, 122 friction contacts, harmonics
# 0..3, N = 128) under a static force at its tip, as the field solves a bolted
# joint: the static state first, then harmonic balance about it. Passes when
# both converge on the defaults.
# Usage: preloaded_chain_test.sh EQHB WORK_DIR [eqhb generate options...]
set -e
eqhb=$1
work=$2
shift 2
mkdir -p "$work"
"$eqhb" generate --dofs 481 --contacts 122 --harmonics 3 --set all --samples 128 --omega 0.3 --preload 2.0 "$@" \
  --out "$work/scene.toml"
status=0
output=$("$eqhb" solve "$work/scene.toml" 2>&1) || status=$?
printf '%s\n' "$output"
[ "$status" -eq 0 ] || { echo "eqhb solve exited $status" >&2; exit 1; }
printf '%s\n' "$output" | grep -Eq '^[a-z-]+: converged' || { echo "the dynamic solve did not converge" >&2; exit 1; }
printf '%s\n' "$output" | grep -Eq '^static state under the preload: [a-z-]+ in [0-9]+ iterations.*[0-9]+ stuck' ||
  { echo "no static state reported" >&2; exit 1; }
