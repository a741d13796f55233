"""A frequency sweep with stability and an accuracy check: the Duffing-like
cubic scene traced by arclength through its folds with Hill's stability along
the curve (command line, JSON read here), then friction-1d: the error
estimate of harmonic balance checked against the exact periodic orbit, and
the spectral radius by Hill's method, the monodromy and shooting."""
import json
import subprocess

import numpy as np

import eqhb
from _common import EQHB, ROOT, pyplot

# --- 1. the curve with its stability, from `eqhb sweep --arclength --stability --json`
scene = str(ROOT / "problems" / "cubic.toml")
run = subprocess.run([EQHB, "sweep", scene, "--arclength", "--stability", "--json"], capture_output=True, text=True)
assert run.returncode == 0, run.stderr
curve = json.loads(run.stdout)
points = curve["points"]
omega = np.array([p["omega"] for p in points])
amplitude = np.array([p["max_abs"][-1] for p in points])  # the last DOF, x2
stable = np.array([p["stable"] for p in points])
print(f"cubic: {len(points)} points, complete {curve['complete']}, "
      f"{int((~stable).sum())} unstable, folds {curve['folds']}")
for b in curve["bifurcations"]:
    print(f"  {b['kind']} at omega = {b['omega']:.4f}")

plt = pyplot()
fig, ax = plt.subplots(figsize=(6.5, 3.8))
# consecutive points of one kind drawn as one line: solid stable, dashed unstable
start = 0
for i in range(1, len(points) + 1):
    if i == len(points) or stable[i] != stable[start]:
        end = min(i + 1, len(points))
        ax.plot(omega[start:end], amplitude[start:end], "-" if stable[start] else "--", color="C0",
                label=None)
        start = i
ax.plot([], [], "-", color="C0", label="stable")
ax.plot([], [], "--", color="C0", label="unstable")
for b in curve["bifurcations"]:
    ax.axvline(b["omega"], color="0.7", lw=0.6)
ax.set_xlabel("omega")
ax.set_ylabel("max|x2|")
ax.legend(loc="upper left")
fig.savefig("cubic_stability.png")

# --- 2. accuracy: the estimate against the exact orbit on friction-1d at omega = 0.4
model = eqhb.load_scene(ROOT / "problems" / "friction-1d.toml")
exact = eqhb.shoot(model, omega=0.4)
exact_peak = max(d["max_abs"] for d in exact["dofs"])
print(f"\nfriction-1d, omega = 0.4: exact orbit max|x| = {exact_peak:.6f}, "
      f"multipliers |mu|max = {exact['spectral_radius']:.4f}, stable {exact['stable']}")
print(f"{'H':>4} {'max|x| (HB)':>12} {'true error':>11} {'estimate':>10} {'ratio':>6}")
rows = []
for H in (5, 10, 20, 40):
    r = eqhb.solve(model, omega=0.4, harmonics=H, error_estimate=True)
    peak = max(d["max_abs"] for d in r["dofs"])
    true_error = abs(peak - exact_peak) / exact_peak
    estimate = r["error_estimate"]["max_abs"]
    rows.append((H, true_error, estimate))
    print(f"{H:>4} {peak:>12.6f} {true_error:>11.2e} {estimate:>10.2e} {estimate / true_error:>6.2f}")
    assert r["converged"]

target = eqhb.solve(model, omega=0.4, accuracy=5e-3)
print(f"\nsolve(accuracy=5e-3): H = {target['harmonics']}, {target['accuracy']['test']} error "
      f"{target['accuracy']['error']:.2e}, "
      f"true error {abs(max(d['max_abs'] for d in target['dofs']) - exact_peak) / exact_peak:.2e}")

fig, ax = plt.subplots(figsize=(5.5, 3.6))
H = [r[0] for r in rows]
ax.loglog(H, [r[1] for r in rows], "o-", label="true error (against shooting)")
ax.loglog(H, [r[2] for r in rows], "s--", label="estimate (one solve at 2H)")
ax.set_xlabel("harmonics H")
ax.set_ylabel("relative error of max|x|")
ax.legend(loc="lower left")
fig.savefig("friction_accuracy.png")

# --- 3. who computes the multipliers: Hill's method, the monodromy, or shooting
print(f"\nfriction-1d, omega = 0.4: spectral radius by stability_method (exact orbit "
      f"{exact['spectral_radius']:.6f})")
print(f"{'H':>4} {'hill':>10} {'monodromy':>10} {'shooting':>10}")
for H in (5, 10, 20):
    radii = []
    for method in ("hill", "monodromy", "shooting"):
        r = eqhb.solve(model, omega=0.4, harmonics=H, stability=True, stability_method=method)
        assert r["stability"].get("method", "hill") == method, r["stability"]
        radii.append(r["stability"]["spectral_radius"])
    print(f"{H:>4} " + " ".join(f"{x:>10.6f}" for x in radii))
