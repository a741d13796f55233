#!/usr/bin/env bash
# The outputs of every command on every shipped scene, with wall times
# removed, to diff two builds of the project: a change meant to keep
# behaviour must leave them identical.
#   bench/output_snapshot.sh BUILD_DIR OUT_DIR [REGEX]
#   diff -r OUT_BEFORE OUT_AFTER
# REGEX (optional) keeps the outputs whose name matches it (grep -E).
# Solves, stability and error estimates at each scene's own ω; sequential
# and arclength sweeps of the scenes whose sweep takes seconds (not
# beam-joint-large); shooting and the time reference on the small scenes.
# Stability along sweeps only on the shipped scenes (on the field's
# cantilevers Hill's method takes minutes a point).
# Exit codes are recorded beside each output. Takes a few minutes.
set -uo pipefail
build=${1:?usage: output_snapshot.sh BUILD_DIR OUT_DIR}
out=${2:?usage: output_snapshot.sh BUILD_DIR OUT_DIR}
only=${3:-.}
here=$(cd "$(dirname "$0")/.." && pwd)
eqhb="$(cd "$build" && pwd)/eqhb"
strip="$here/bench/strip_timings.py"
mkdir -p "$out"

# run NAME ARGS...: stdout (timings stripped) and exit code to OUT/NAME.
run() {
  local name=$1
  shift
  grep -qE "$only" <<<"$name" || return 0
  local raw status
  raw=$(mktemp)
  "$eqhb" "$@" >"$raw" 2>"$raw.err"
  status=$?
  /usr/bin/python3 "$strip" <"$raw" >"$out/$name.out"
  /usr/bin/python3 "$strip" <"$raw.err" >"$out/$name.stderr"
  echo "$status" >"$out/$name.rc"
  rm -f "$raw" "$raw.err"
}

# run_csv NAME ARGS...: as run, and the --out CSV written by the command.
run_csv() {
  local name=$1
  shift
  grep -qE "$only" <<<"$name" || return 0
  run "$name" "$@" --out "$out/$name.csv"
  # The curve, and the points that failed (written apart when there are any).
  for csv in "$out/$name.csv" "$out/$name.failed.csv"; do
    [ -f "$csv" ] && /usr/bin/python3 "$strip" --csv <"$csv" >"$csv.tmp" && mv "$csv.tmp" "$csv"
  done
}

scenes=()
for f in "$here"/problems/*.toml "$here"/problems/field/*.toml; do scenes+=("$f"); done
for f in "${scenes[@]}"; do
  n=$(basename "$(dirname "$f")")-$(basename "$f" .toml)
  run "$n.solve" solve "$f" --json
  run "$n.solve-text" solve "$f"
  case "$n" in *beam-joint-large*) continue ;; esac
  run "$n.solve-full" solve "$f" --full --json
  stability=(--stability)
  case "$n" in field-*) stability=() ;; esac
  run "$n.estimate" solve "$f" --json "${stability[@]}" --error-estimate
  grep -q '^\[sweep\]' "$f" || continue
  run_csv "$n.sweep" sweep "$f"
  run "$n.sweep-json" sweep "$f" --json "${stability[@]}"
  run_csv "$n.arclength" sweep "$f" --arclength
done
for s in friction-1d cubic contact coulomb-oscillator jenkins-1d duffing; do
  f="$here/problems/$s.toml"
  run "shoot-$s" shoot "$f" --json
  run "simulate-$s" simulate "$f" --json --periods 200
  run "compare-$s" compare "$f" --json --periods 200
done
echo "snapshot: $out ($(ls "$out" | wc -l) files)"
