#!/bin/sh
# solve --refine shoot --stability on a contact: the orbit reported is the
# elastic-impact one (the restitution the Signorini form approaches, e = 1 by
# default) and its stability is that orbit's own multipliers, equal to
# `eqhb shoot`'s, never Hill's verdict on the harmonic-balance start beside
# the exact orbit's amplitudes.
# Usage: refined_stability_is_the_orbits.sh EQHB SCENE
set -eu
eqhb=$1 scene=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$eqhb" solve "$scene" --harmonics 20 --refine shoot --stability --json >"$dir/refined.json"
"$eqhb" shoot "$scene" --json >"$dir/shoot.json"
"$eqhb" solve "$scene" --harmonics 20 --refine shoot --restitution 0 --stability --json >"$dir/plastic.json"
python3 - "$dir/refined.json" "$dir/shoot.json" "$dir/plastic.json" <<'PY'
import json, sys
refined, shoot, plastic = (json.load(open(p)) for p in sys.argv[1:4])
assert refined["refinement"]["converged"] and refined["refinement"]["restitution"] == 1, refined["refinement"]
assert shoot["restitution"] == 1, shoot["restitution"]
s = refined["stability"]
assert s["method"] == "shooting", s
assert abs(s["spectral_radius"] / shoot["spectral_radius"] - 1) < 1e-9, (s["spectral_radius"], shoot["spectral_radius"])
assert s["stable"] == shoot["stable"]
for got, want in zip((d["max_abs"] for d in refined["dofs"]), (d["max_abs"] for d in shoot["dofs"])):
    assert abs(got / want - 1) < 1e-9, (got, want)
# The plastic orbit is another one, with its own verdict.
p = plastic["stability"]
assert p["method"] == "shooting" and abs(p["spectral_radius"] - s["spectral_radius"]) > 0.1, (p, s)
print("elastic: radius", s["spectral_radius"], "stable", s["stable"], "| plastic: radius", p["spectral_radius"], "stable", p["stable"])
PY
