#!/bin/sh
# solve --refine shoot from a coarse H must report the exact orbit that
# `eqhb shoot` finds from the scene's H (max|x| per DOF to 1e-9), while the
# plain harmonic-balance peak at that coarse H is off by more than 1e-4.
# Usage: refine_matches_shoot.sh EQHB SCENE HARMONICS
set -eu
eqhb=$1 scene=$2 harmonics=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$eqhb" solve "$scene" --harmonics "$harmonics" --refine shoot --json >"$dir/refined.json"
"$eqhb" shoot "$scene" --json >"$dir/shoot.json"
python3 - "$dir/refined.json" "$dir/shoot.json" <<'PY'
import json, sys
refined, shoot = (json.load(open(p)) for p in sys.argv[1:3])
r = refined["refinement"]
assert r["converged"], r
exact = [d["max_abs"] for d in shoot["dofs"]]
reported = [d["max_abs"] for d in refined["dofs"]]
for got, want, plain in zip(reported, exact, r["hb_max_abs"]):
    assert abs(got / want - 1) < 1e-9, (got, want)
    assert abs(plain / want - 1) > 1e-4, (plain, want)
print("refined max|x| =", reported, "exact =", exact, "plain HB =", r["hb_max_abs"])
PY
