#!/bin/sh
# `eqhb compare` succeeds (exit 0: the solve converged and the reference
# settled) and no displacement's relative L2 error reaches BOUND; prints
# the comparison either way.
# Usage: compare_within.sh BOUND EQHB compare SCENE [OPTIONS...]
set -eu
bound=$1
shift
out=$(mktemp)
trap 'rm -f "$out"' EXIT
status=0
"$@" >"$out" 2>&1 || status=$?
cat "$out"
[ "$status" -eq 0 ] || { echo "FAILED: exit code $status" >&2; exit 1; }
# Lines "  x1: L2 0.00123, ...": the largest such error against the bound.
awk -v bound="$bound" '
  $1 ~ /^x[0-9]+:$/ && $2 == "L2" { e = $3 + 0; n++; if (e > worst) worst = e }
  END {
    if (n == 0) { print "FAILED: no displacement errors in the output" > "/dev/stderr"; exit 1 }
    if (!(worst < bound)) { printf "FAILED: largest x L2 error %g >= %g\n", worst, bound > "/dev/stderr"; exit 1 }
    printf "largest x L2 error %g < %g over %d DOFs\n", worst, bound, n
  }' "$out"
