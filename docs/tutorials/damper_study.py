"""A damper design study: how the resonance peak of friction-1d depends on
the friction damper's normal load (μN) at three forcing levels. `eqhb study
--peak` follows the resonance peak along each line of the grid (threads
here; the same command runs on MPI ranks under mpirun or srun), writes
study.csv, and this script draws the design chart from it."""
import csv
import subprocess

import numpy as np

from _common import EQHB, ROOT, pyplot

command = [EQHB, "study", str(ROOT / "problems" / "friction-1d.toml"), "--vary", "forcing[0].cos=10:30:3",
           "--vary", "law.muN=0.5:50:40", "--peak", "--from", "0.3", "--to", "2.0", "--out", "damper",
           "--threads", "2", "--quiet"]
print("$ " + " ".join(c if not c.startswith(str(ROOT)) else c.replace(str(ROOT) + "/", "") for c in command))
run = subprocess.run(command, capture_output=True, text=True)
print(run.stdout.strip())
assert run.returncode in (0, 1), run.stderr  # 1: some samples failed (listed)

with open("damper/study.csv") as f:
    rows = list(csv.DictReader(f))
print(f"study.csv: {len(rows)} rows, columns {', '.join(list(rows[0])[:8])}, ...")
ok = [r for r in rows if r["status"] == "ok"]
print(f"{len(ok)} samples ok, {len(rows) - len(ok)} failed")

plt = pyplot()
fig, ax = plt.subplots(figsize=(6.5, 3.8))
for level in sorted({float(r["forcing[0].cos"]) for r in ok}):
    line = sorted((float(r["law.muN"]), float(r["first_harmonic_x1"])) for r in ok
                  if float(r["forcing[0].cos"]) == level)
    mu_n, peak = np.array(line).T
    best = int(np.argmin(peak))
    ax.plot(mu_n, peak, label=f"f = {level:g}")
    ax.plot(mu_n[best], peak[best], "k.", ms=8)
    print(f"f = {level:g}: smallest peak {peak[best]:.3f} at muN = {mu_n[best]:.3g} "
          f"(muN/f = {mu_n[best] / level:.3f}); stuck damper (muN = 50): {peak[-1]:.3f}")
ax.set_xlabel("normal load muN")
ax.set_ylabel("resonance peak of x1 (first harmonic)")
ax.set_yscale("log")
ax.legend(loc="upper right", title="forcing")
fig.savefig("damper.png")
