"""A contact between two nodes: two oscillators that strike each other across
a gap (an impact pair), the contact an element between the two nodes
(`between = [1, 2]`: it reads x1 - x2 and pushes them apart equally and
oppositely). Then a 120-DOF beam swept with the deflections of chosen nodes
shown (--show), the tip deflection defining the peak."""
import csv
import json
import subprocess

from _common import EQHB, ROOT

SCENE = """
name = "impact-pair"
description = "a forced oscillator strikes a second one across a gap of 0.3"

[structure]
type = "matrices"
mass = [[1.0, 0.0], [0.0, 0.5]]
stiffness = [[1.0, 0.0], [0.0, 1.0]]
damping = [[0.02, 0.0], [0.0, 0.02]]

[[forcing]]
dof = 1
cos = 0.1

[[law]]
type = "signorini"
between = [1, 2]       # the gap closes when x1 - x2 reaches 0.3
gap = 0.3
form = "fischer-burmeister"
rho = 1.0

[harmonic_balance]
harmonics = 20         # all harmonics 0..20: an impact's force has a mean
set = "all"
samples = 1024
omega = 1.0

[sweep]
from = 0.6
to = 1.6
"""
with open("impact-pair.toml", "w") as f:
    f.write(SCENE)


def eqhb(*args):
    run = subprocess.run([EQHB, *args], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return run.stdout


# --- 1. one solve: the text output names each invariant and what it measures
print(eqhb("solve", "impact-pair.toml"))

# --- 2. the sweep, both masses' amplitudes and the contact force in one chart
summary = eqhb("sweep", "impact-pair.toml", "--arclength", "--out", "impact.csv", "--chart", "impact_pair")
print(summary)
rows = list(csv.DictReader(open("impact.csv")))
peak = max(rows, key=lambda r: float(r["max_abs_x1"]))
print(f"{len(rows)} points; the largest max|x1| = {float(peak['max_abs_x1']):.4f} at omega = "
      f"{float(peak['omega']):.4f}, near sqrt(2 / 1.5) = {(2 / 1.5) ** 0.5:.4f}, the two masses moving together")
assert all(r["converged"] == "true" for r in rows)
# Without the contact the primary's peak would be 0.1 / 0.02 = 5 at omega = 1.
assert float(peak["max_abs_x1"]) < 2.5 and abs(float(peak["omega"]) - (2 / 1.5) ** 0.5) < 0.02

# --- 3. a 120-DOF beam: the deflection of nodes 20, 40 and 60 (the tip)
beam = str(ROOT / "problems" / "beam-damper.toml")
print(eqhb("sweep", beam, "--show", "w20,w40,w60", "--out", "beam.csv", "--chart", "beam_nodes"))
with open("beam.csv") as f:
    header = next(csv.reader(f))
print("CSV columns:", ", ".join(c for c in header if c.startswith("max_abs_")))
assert [c for c in header if c.startswith("max_abs_")] == ["max_abs_w20", "max_abs_w40", "max_abs_w60"]
# The JSON labels every DOF; the peak is the tip deflection's, not the tip rotation's.
curve = json.loads(eqhb("sweep", beam, "--from", "3.4", "--to", "3.6", "--step", "0.1", "--json"))
print("dof_labels:", curve["dof_labels"][:4], "...", curve["dof_labels"][-2:], " peak_dof:", curve["peak_dof"])
