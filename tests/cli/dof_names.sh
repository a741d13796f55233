#!/bin/sh
# DOFs by name across the outputs: a solve's JSON names each DOF and each DOF
# a law reads ("name", "dof_name") and lists the shown ones; a Matrix Market
# model of 40 DOFs shows four of them by default in the text and the CSV and
# says so, with how to pick others; a study's CSV is headed by the names and
# has the shown DOFs' columns and --dof's, which takes a name; an unknown
# name exits 2 naming the option.
# Usage: dof_names.sh EQHB PROBLEMS_DIR
set -eu
eqhb=$1 problems=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
beam="$problems/beam-damper.toml"

"$eqhb" solve "$beam" --json >"$dir/beam.json"
/usr/bin/python3 - "$dir/beam.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
names = [d["name"] for d in s["dofs"]]
assert names[:2] == ["w1", "theta1"] and names[-1] == "theta60" and len(names) == 120, names[:4]
assert [d["dof"] for d in s["dofs"]][:2] == [1, 2]
assert s["shown"] == ["w15", "w30", "w45", "w60"], s["shown"]
read = [c.get("dof_name") or [r["name"] for r in c["reads"]] for law in s["laws"] for c in law["components"]]
assert read and all(read), read
print("solve JSON: DOF names", names[:2], "... laws read", read)
PY

"$eqhb" generate --dofs 40 --contacts 2 --matrix-market "$dir/market" >/dev/null
"$eqhb" solve "$dir/market/scene.toml" >"$dir/market.txt"
cat "$dir/market.txt"
grep -q '  x10, x20, x30, x40 of 40 DOFs shown; others by --show or \[output\] dofs, by number or name' "$dir/market.txt"
test "$(grep -c '  max|x[0-9]*|' "$dir/market.txt")" -eq 4
"$eqhb" solve "$dir/market/scene.toml" --show 7 >"$dir/one.txt"
test "$(grep -c '  max|x[0-9]*|' "$dir/one.txt")" -eq 1 && grep -q '  max|x7|' "$dir/one.txt"
"$eqhb" sweep "$dir/market/scene.toml" --from 0.030 --to 0.032 --step 0.001 --out "$dir/market.csv" >"$dir/sweep.txt"
grep -q '  CSV: x10, x20, x30, x40 of 40 DOFs shown' "$dir/sweep.txt"
head -1 "$dir/market.csv" | grep -q ',seconds,max_abs_x10,max_abs_x20,max_abs_x30,max_abs_x40,first_harmonic_x10,'

"$eqhb" study "$beam" --vary forcing[0].cos=1:2:2 --peak --dof w60 --from 3.3 --to 3.7 --coarse-points 9 --threads 1 \
  --out "$dir/study" >/dev/null
head -1 "$dir/study/study.csv" | grep -q ',peak_omega,first_harmonic_w15,first_harmonic_w30,first_harmonic_w45,first_harmonic_w60,max_abs_w15,max_abs_w30,max_abs_w45,max_abs_w60,peaks,'
/usr/bin/python3 - "$dir/study/study.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
assert s["dof"] == 119 and s["dof_label"] == "w60" and s["shown"] == ["w15", "w30", "w45", "w60"], s["shown"]
assert s["dof_labels"][118] == "w60" and len(s["samples"][0]["first_harmonic"]) == 120
PY
# --show picks study.csv's DOFs; --dof's is added when not among them.
"$eqhb" study "$beam" --vary forcing[0].cos=1:2:2 --peak --dof 119 --show theta60 --from 3.3 --to 3.7 \
  --coarse-points 9 --threads 1 --out "$dir/study2" >/dev/null
head -1 "$dir/study2/study.csv" | grep -q ',peak_omega,first_harmonic_theta60,first_harmonic_w60,max_abs_theta60,max_abs_w60,peaks,'

status=0
"$eqhb" study "$beam" --vary forcing[0].cos=1:2:2 --peak --dof w61 --out "$dir/bad" >"$dir/bad.txt" 2>&1 || status=$?
cat "$dir/bad.txt"
test "$status" -eq 2 && grep -q -- '--dof = "w61": no DOF of the structure is named so' "$dir/bad.txt"
echo "DOF names: solve JSON, Matrix Market defaults, study CSV and --dof as expected"
