#!/usr/bin/env python3
"""Field suite: the problems of problems/field/ swept on eqhb's defaults.

A thin client of the eqhb command-line tool. Per scene and per backend it runs
a sequential sweep and an arclength sweep (`eqhb sweep SCENE --json
[--arclength] --solver S`, nothing else changed) and records the points
converged / asked, the points of the curve, whether the whole range was
covered and why it stopped, the wall time, and the points that needed a
fallback. Where `eqhb shoot SCENE --omega W --json` finds the exact periodic
orbit, max|x| of the curve is compared with it at three frequencies of the
range.

    /usr/bin/python3 bench/field_suite.py --eqhb build/eqhb --out results
    /usr/bin/python3 bench/field_suite.py --quick      # dogleg only (CI)

Writes OUT/field-suite.md and OUT/field-suite.json.
"""

import argparse
import glob
import json
import math
import os
import subprocess
import sys
import time
import tomllib

BACKENDS = ["dogleg", "dogleg-newton", "minpack", "ceres-lm", "ipopt-ls"]
METHODS = ["sequential", "arclength"]
DEFAULT_STEP = 0.01  # eqhb sweep's default --step (omega)
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(cmd, timeout):
    """Runs cmd; returns (exit code or None on timeout, stdout, stderr, seconds)."""
    start = time.monotonic()
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=timeout)
        return p.returncode, p.stdout, p.stderr, time.monotonic() - start
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
        err = e.stderr.decode() if isinstance(e.stderr, bytes) else (e.stderr or "")
        return None, out, err, time.monotonic() - start


def listed_backends(eqhb):
    code, out, err, _ = run([eqhb, "solvers"], 60)
    if code != 0:
        sys.exit(f"field_suite: `{eqhb} solvers` failed: {err.strip()}")
    names = set()
    for line in out.splitlines():
        words = line.replace(",", " ").replace(":", " ").split()
        names.update(words[:1])
    return [b for b in BACKENDS if b in names]


def last_line(text):
    lines = [l.strip() for l in text.strip().splitlines() if l.strip()]
    return lines[-1] if lines else ""


def max_abs(entry):
    """max|x| over the DOFs of a point (sweep) or an orbit (shoot)."""
    values = entry.get("max_abs")
    if isinstance(values, (int, float)):
        return [float(values)]
    if isinstance(values, list):
        return [float(v) for v in values]
    dofs = entry.get("dofs")
    if isinstance(dofs, list):
        return [float(d["max_abs"]) for d in dofs if isinstance(d, dict) and "max_abs" in d]
    return None


def relative_difference(a, b):
    if a is None or b is None or len(a) != len(b) or not b:
        return None
    scale = max(abs(v) for v in b)
    if scale == 0.0:
        return None
    return max(abs(x - y) for x, y in zip(a, b)) / scale


def curve_max_abs_at(points, omega):
    """max|x| of the curve at omega: the point there (sequential grid), else
    interpolated between two consecutive converged points that bracket it;
    where several branches pass omega (folds), every candidate is returned."""
    candidates = []
    for p in points:
        if p.get("converged") and abs(p["omega"] - omega) <= 1e-9 * max(1.0, abs(omega)):
            a = max_abs(p)
            if a is not None:
                candidates.append(a)
    if candidates:
        return candidates
    for p, q in zip(points, points[1:]):
        if not (p.get("converged") and q.get("converged")):
            continue
        w0, w1 = p["omega"], q["omega"]
        if w0 == w1 or not (min(w0, w1) <= omega <= max(w0, w1)):
            continue
        a, b = max_abs(p), max_abs(q)
        if a is None or b is None or len(a) != len(b):
            continue
        t = (omega - w0) / (w1 - w0)
        candidates.append([x + t * (y - x) for x, y in zip(a, b)])
    return candidates


def grid_points(lo, hi, step):
    if not all(isinstance(v, (int, float)) for v in (lo, hi, step)) or step <= 0:
        return None
    return int(math.floor(abs(hi - lo) / step + 1e-9)) + 1


def sweep(eqhb, scene, backend, method, timeout, span):
    cmd = [eqhb, "sweep", scene, "--json", "--solver", backend, "--quiet"]
    if method == "arclength":
        cmd.append("--arclength")
    code, out, err, seconds = run(cmd, timeout)
    row = {"backend": backend, "method": method, "exit": code, "seconds": round(seconds, 3)}
    data = None
    if out.strip():
        try:
            data = json.loads(out)
        except json.JSONDecodeError:
            data = None
    if code is None:
        row["stop_reason"] = f"timeout after {timeout:g} s"
    if data is None:
        asked = grid_points(span[0], span[1], DEFAULT_STEP) if method == "sequential" else None
        row.update({"converged": 0, "asked": asked, "points": 0, "complete": False, "fallbacks": 0})
        row.setdefault("stop_reason", last_line(err) or "no JSON output")
        return row, []
    # "points" holds the converged points, "failed" the grid points of a
    # sequential sweep that did not converge: merged back in grid order, so
    # that no interpolation bridges a failed point (an arclength curve, whose
    # ω turns at folds, has none).
    points = data.get("points", [])
    failed = [dict(f, converged=False) for f in data.get("failed", [])]
    if failed:
        points = sorted(points + failed, key=lambda p: p["omega"], reverse=data.get("from", 0) > data.get("to", 0))
    converged = sum(1 for p in points if p.get("converged"))
    asked = len(points)
    if method == "sequential":
        grid = grid_points(data.get("from"), data.get("to"), data.get("step"))
        if grid is not None and grid >= asked:
            asked = grid
    row.update({
        "converged": converged,
        "asked": asked,
        "points": len(points),
        "complete": bool(data.get("complete")) and code == 0,
        "stop_reason": data.get("stop_reason") or row.get("stop_reason") or "",
        "fallbacks": sum(1 for p in points if p.get("fallback")),
        "folds": len(data.get("folds", []) or []),
    })
    if code is None:
        row["stop_reason"] = f"timeout after {timeout:g} s"
    return row, points


def shoot_references(eqhb, scene, lo, hi, timeout):
    """Exact orbits at 25, 50 and 75 % of the range (on the 0.01 grid of the
    sequential sweep), or the reason there are none."""
    refs = []
    for fraction in (0.25, 0.5, 0.75):
        omega = lo + fraction * (hi - lo)
        omega = lo + round((omega - lo) / 0.01) * 0.01
        omega = float(f"{omega:.10g}")
        code, out, err, seconds = run([eqhb, "shoot", scene, "--omega", repr(omega), "--json", "--quiet"], timeout)
        ref = {"omega": omega, "seconds": round(seconds, 3)}
        try:
            data = json.loads(out) if code == 0 and out.strip() else None
        except json.JSONDecodeError:
            data = None
        if data is None:
            ref["error"] = f"timeout after {timeout:g} s" if code is None else (last_line(err) or f"exit {code}")
        else:
            ref["max_abs"] = max_abs(data)
            if ref["max_abs"] is None:
                ref["error"] = "no max_abs in the shoot output"
        refs.append(ref)
    return refs


def compare(points, refs):
    out = []
    for ref in refs:
        if "max_abs" not in ref:
            out.append(None)
            continue
        diffs = [relative_difference(c, ref["max_abs"]) for c in curve_max_abs_at(points, ref["omega"])]
        diffs = [d for d in diffs if d is not None]
        out.append(min(diffs) if diffs else None)
    return out


def fmt(v, digits=3):
    if v is None:
        return "–"
    if isinstance(v, float):
        if v == 0.0:
            return "0"
        return f"{v:.{digits}g}" if abs(v) < 1e4 else f"{v:.3e}"
    return str(v)


def markdown(results, backends, quick, eqhb):
    lines = ["# Field suite", "",
             f"Problems of `problems/field/` swept with `{os.path.basename(eqhb)} sweep SCENE --json "
             "[--arclength] --solver S` on eqhb's defaults (grid step 0.01 in omega, scale-free rho, "
             "default fallbacks); backends: " + ", ".join(backends) + (" (--quick)" if quick else "") + ".",
             "`conv/asked`: points converged / points of the grid (sequential) or of the curve "
             "(arclength). `fb`: points that needed a fallback. `|dx| vs shoot`: relative "
             "difference of max|x| between the curve and the exact orbit (`eqhb shoot`) at 25, 50 "
             "and 75 % of the range (– where no orbit or no curve point).", "",
             "| scene | backend | method | conv/asked | points | complete | stop reason | s/curve | fb | |dx| vs shoot |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for scene in results:
        for row in scene["runs"]:
            asked = row["asked"] if row["asked"] is not None else "–"
            diffs = " / ".join(fmt(d, 2) for d in row.get("shoot_rel_diff", [])) or "–"
            reason = (row.get("stop_reason") or "").replace("|", "/")
            if len(reason) > 90:
                reason = reason[:87] + "..."
            lines.append(f"| {scene['scene']} | {row['backend']} | {row['method']} | {row['converged']}/{asked} | "
                         f"{row['points']} | {'yes' if row['complete'] else 'no'} | {reason} | "
                         f"{row['seconds']:.2f} | {row.get('fallbacks', 0)} | {diffs} |")
    lines += ["", "Exact orbits (`eqhb shoot --omega W`):", ""]
    for scene in results:
        refs = scene.get("shoot", [])
        if not refs:
            continue
        parts = []
        for r in refs:
            if "max_abs" in r:
                parts.append(f"ω = {r['omega']:g}: max|x| = {fmt(max(r['max_abs']))} ({r['seconds']:.1f} s)")
            else:
                parts.append(f"ω = {r['omega']:g}: none ({r['error'][:80]})")
        lines.append(f"- {scene['scene']}: " + "; ".join(parts))
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--eqhb", default=os.path.join(ROOT, "build", "eqhb"), help="the eqhb binary")
    ap.add_argument("--out", default=os.path.join(ROOT, "results"), help="folder for field-suite.md/.json")
    ap.add_argument("--quick", action="store_true", help="dogleg only (sequential and arclength), no shoot")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds per run (sweep or shoot)")
    ap.add_argument("--scenes", default=os.path.join(ROOT, "problems", "field"), help="folder of scenes")
    ap.add_argument("--only", action="append", default=[], help="run only scenes whose name contains this")
    args = ap.parse_args()

    eqhb = os.path.abspath(args.eqhb)
    backends = ["dogleg"] if args.quick else listed_backends(eqhb)
    scenes = sorted(glob.glob(os.path.join(args.scenes, "*.toml")))
    if args.only:
        scenes = [s for s in scenes if any(o in os.path.basename(s) for o in args.only)]
    if not scenes:
        sys.exit(f"field_suite: no scenes in {args.scenes}")
    os.makedirs(args.out, exist_ok=True)

    results = []
    for scene in scenes:
        with open(scene, "rb") as f:
            spec = tomllib.load(f)
        name = spec.get("name", os.path.splitext(os.path.basename(scene))[0])
        lo, hi = sorted((spec["sweep"]["from"], spec["sweep"]["to"]))
        laws = [law["type"] for law in spec.get("law", [])]
        entry = {"scene": name, "file": os.path.relpath(scene, ROOT), "laws": laws,
                 "range": [spec["sweep"]["from"], spec["sweep"]["to"]], "runs": []}
        refs = [] if args.quick else shoot_references(eqhb, scene, lo, hi, args.timeout)
        entry["shoot"] = refs
        for backend in backends:
            for method in METHODS:
                row, points = sweep(eqhb, scene, backend, method, args.timeout, (lo, hi))
                if refs:
                    row["shoot_rel_diff"] = compare(points, refs)
                entry["runs"].append(row)
                print(f"{name:40s} {backend:14s} {method:10s} {row['converged']}/{row['asked']} "
                      f"complete={row['complete']} {row['seconds']:.1f}s fb={row.get('fallbacks', 0)} "
                      f"{row.get('stop_reason', '')[:60]}", flush=True)
        results.append(entry)

    with open(os.path.join(args.out, "field-suite.json"), "w") as f:
        json.dump({"eqhb": eqhb, "backends": backends, "quick": args.quick, "timeout": args.timeout,
                   "scenes": results}, f, indent=1)
    with open(os.path.join(args.out, "field-suite.md"), "w") as f:
        f.write(markdown(results, backends, args.quick, eqhb))
    print(f"field suite: {os.path.join(args.out, 'field-suite.md')}")


if __name__ == "__main__":
    main()
