"""Choosing and comparing backends: the C++ program backends.cpp (built with
the project as eqhb-tutorial-backends) solves friction-1d from rest with
every backend; then the same comparison from Python, where eqhb.solve runs
what `eqhb solve` runs (coarse start and fallbacks on), once with the
default path and once with the backend alone (cold_start="zero",
fallback="none")."""
import subprocess

import numpy as np

import eqhb
from _common import BUILD, ROOT, pyplot

print("C++ (docs/tutorials/backends.cpp):")
cpp = subprocess.run([str(BUILD / "docs" / "eqhb-tutorial-backends")], check=True, capture_output=True, text=True)
print(cpp.stdout)

model = eqhb.load_scene(ROOT / "problems" / "friction-1d.toml")
names = [s["name"] for s in eqhb.solvers()]
print("Python, friction-1d at omega = 0.4, backend alone (zero start, no fallback):")
print(f"{'backend':<22} {'termination':<16} {'iter':>5} {'max|x2|':>10} {'ms (median of 5)':>17}")
alone = {}
for name in names:
    r = eqhb.solve(model, 0.4, solver=name, cold_start="zero", fallback="none", repeat=5)
    alone[name] = r
    peak = r["dofs"][1]["max_abs"]
    print(f"{name:<22} {r['termination']:<16} {r['iterations']:>5} {peak:>10.5f} {1e3 * r['seconds']:>17.3f}")

converged = [n for n in names if alone[n]["converged"]]
peaks = np.array([alone[n]["dofs"][1]["max_abs"] for n in converged])
print(f"\n{len(converged)} of {len(names)} backends converge alone; their max|x2| agree to "
      f"{(peaks.max() - peaks.min()) / peaks.max():.1e} (relative)")

# The default path: a backend that fails alone is rescued by the fallback steps.
for name in names:
    if not alone[name]["converged"]:
        r = eqhb.solve(model, 0.4, solver=name)
        tried = [f"{a['step']} ({a['solver']}): {a['termination']}" for a in r.get("fallback", {}).get("attempts", [])]
        print(f"{name}: alone {alone[name]['termination']}; with the default path converged {r['converged']}"
              + (f", after the fallback steps {'; '.join(tried)}" if tried else ""))

plt = pyplot()
fig, ax = plt.subplots(figsize=(6.5, 3.6))
times = [1e3 * alone[n]["seconds"] for n in names]
colors = ["C0" if alone[n]["converged"] else "C3" for n in names]
ax.barh(names, times, color=colors)
ax.set_xscale("log")
ax.set_xlabel("ms per solve (median of 5), red: did not converge")
ax.invert_yaxis()
fig.savefig("backends.png")
