#!/bin/sh
# The HDF5 files of `eqhb sweep --hdf5`, `eqhb study --hdf5` and `eqhb modes
# --hdf5`, read back
# with h5py (Debian's /usr/bin/python3), hold the JSON output's numbers:
# every point's ω, max|x| and first-harmonic amplitude per DOF, the failed
# points, the labels and the peak DOF; every sample's parameters, status,
# peak ω and amplitudes; every backbone point's amplitude, ω, ζ, energy,
# max|x| and Fourier coefficients per DOF. A beam scene checks the DOF labels
# (w, theta).
# Usage: hdf5_matches_json.sh EQHB PROBLEMS_DIR
set -eu
eqhb=$1 problems=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$eqhb" sweep "$problems/duffing.toml" --stability --json --hdf5 "$dir/duffing.h5" >"$dir/duffing.json" 2>/dev/null
"$eqhb" sweep "$problems/beam-damper.toml" --from 3 --to 3.6 --step 0.3 --json --hdf5 "$dir/beam.h5" \
  >"$dir/beam.json" 2>/dev/null
"$eqhb" modes "$problems/friction-1d.toml" --points 12 --json --hdf5 "$dir/modes.h5" >"$dir/modes.json" 2>/dev/null
"$eqhb" study "$problems/friction-1d.toml" --vary forcing[0].cos=10:20:2 --vary law.muN=1:5:3 --peak --from 0.3 \
  --to 2.0 --threads 1 --out "$dir/study" --hdf5 "$dir/study.h5" >/dev/null
/usr/bin/python3 - "$dir" <<'PY'
import json, math, sys
import h5py
import numpy as np

d = sys.argv[1]
for name in ("duffing", "beam"):
    curve = json.load(open(f"{d}/{name}.json"))
    with h5py.File(f"{d}/{name}.h5", "r") as f:
        points = curve["points"]
        assert len(points) > 2, name
        np.testing.assert_array_equal(f["points/omega"][()], [p["omega"] for p in points])
        np.testing.assert_array_equal(f["points/max_abs"][()], [p["max_abs"] for p in points])
        np.testing.assert_array_equal(f["points/first_harmonic"][()], [p["first_harmonic"] for p in points])
        np.testing.assert_array_equal(f["points/iterations"][()], [p["iterations"] for p in points])
        np.testing.assert_array_equal(f["points/fold"][()], [int(p["fold"]) for p in points])
        np.testing.assert_array_equal(f["failed/omega"][()], [p["omega"] for p in curve["failed"]])
        np.testing.assert_array_equal(f["folds"][()], curve["folds"])
        labels = [s.decode() for s in f["dof_labels"][()]]
        assert labels == curve["dof_labels"], (labels, curve["dof_labels"])
        assert f.attrs["peak_dof"] == curve["peak_dof"], (f.attrs["peak_dof"], curve["peak_dof"])
        assert f.attrs["scene"] == curve["scene"] and f.attrs["harmonics"] == curve["harmonics"]
        if "bifurcations" in curve:
            stable = [-1 if p["stable"] is None else int(p["stable"]) for p in points]
            np.testing.assert_array_equal(f["points/stable"][()], stable)
        print(name, len(points), "points,", len(curve["failed"]), "failed, labels", labels[:2], "... peak",
              curve["peak_dof"])
beam = json.load(open(f"{d}/beam.json"))
assert beam["dof_labels"][:2] == ["w1", "theta1"] and beam["peak_dof"] == "w60", beam["peak_dof"]

study = json.load(open(f"{d}/study/study.json"))
with h5py.File(f"{d}/study.h5", "r") as f:
    samples = study["samples"]
    assert len(samples) == 6
    assert [s.decode() for s in f["parameters"][()]] == study["parameters"]
    np.testing.assert_array_equal(f["samples/sample"][()], [s["sample"] for s in samples])
    values = [[s["parameters"][p] for p in study["parameters"]] for s in samples]
    np.testing.assert_array_equal(f["samples/values"][()], values)
    assert [s.decode() for s in f["samples/status"][()]] == [s["status"] for s in samples]
    nan = lambda v: math.nan if v is None else v
    np.testing.assert_array_equal(f["samples/peak_omega"][()], [nan(s["peak_omega"]) for s in samples])
    np.testing.assert_array_equal(f["samples/first_harmonic"][()],
                                  [[nan(v) for v in s["first_harmonic"]] for s in samples])
    assert f.attrs["mode"] == "peak" and f.attrs["dof"] == study["dof"]
    print("study:", len(samples), "samples match")

modes = json.load(open(f"{d}/modes.json"))
with h5py.File(f"{d}/modes.h5", "r") as f:
    points = modes["points"]
    assert len(points) == 12 and any(p["converged"] for p in points)
    nan = lambda p, key: p[key] if p["converged"] else math.nan
    np.testing.assert_array_equal(f["points/amplitude"][()], [p["amplitude"] for p in points])
    np.testing.assert_array_equal(f["points/converged"][()], [int(p["converged"]) for p in points])
    np.testing.assert_array_equal(f["points/iterations"][()], [p["iterations"] for p in points])
    assert [s.decode() for s in f["points/termination"][()]] == [p["termination"] for p in points]
    for key in ("omega", "xi", "damping_ratio", "dissipated_energy"):
        np.testing.assert_array_equal(f["points/" + key][()], [nan(p, key) for p in points])
    n = len(modes["dof_labels"])
    np.testing.assert_array_equal(f["points/max_abs"][()],
                                  [p["max_abs"] if p["converged"] else [math.nan] * n for p in points])
    h = len(f["harmonics"][()])
    for part in ("cos", "sin"):
        expected = [[d["coefficients"][part] for d in p["channels"]["dofs"]] if p["converged"]
                    else [[math.nan] * h] * n for p in points]
        np.testing.assert_array_equal(f["points/" + part][()], expected)
    converged = next(p for p in points if p["converged"])
    np.testing.assert_array_equal(f["harmonics"][()], converged["channels"]["dofs"][0]["coefficients"]["harmonics"])
    assert [s.decode() for s in f["dof_labels"][()]] == modes["dof_labels"]
    np.testing.assert_array_equal(f["linear_shape"][()], modes["linear_mode"]["shape"])
    np.testing.assert_array_equal(f["folds/amplitude"][()], [x["amplitude"] for x in modes["folds"]])
    assert f.attrs["linear_omega"] == modes["linear_mode"]["omega"] and f.attrs["mode"] == modes["mode"]
    assert f.attrs["scene"] == modes["scene"] and f.attrs["failed_points"] == modes["failed_points"]
    assert f.attrs["from"] == modes["from"] and f.attrs["to"] == modes["to"]
    print("modes:", len(points), "points match, shape", f["points/cos"].shape)
PY
