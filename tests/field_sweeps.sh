#!/bin/sh
# Runs the sequential sweep of each field scene on eqhb's defaults (own
# dogleg, the scene's [sweep] range) and passes when every one covers its
# whole range with every point converged (exit 0).
# Usage: field_sweeps.sh EQHB SCENE...
eqhb=$1
shift
failed=0
for scene in "$@"; do
  if "$eqhb" sweep "$scene" --quiet >/dev/null 2>"${TMPDIR:-/tmp}/field_sweep.$$"; then
    echo "complete: $scene"
  else
    echo "NOT complete (exit $?): $scene" >&2
    tail -n 3 "${TMPDIR:-/tmp}/field_sweep.$$" >&2
    failed=1
  fi
done
rm -f "${TMPDIR:-/tmp}/field_sweep.$$"
exit "$failed"
