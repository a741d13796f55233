"""A bolted lap joint from microslip to macroslip: problems/lap-joint.toml (two
frame beams bolted over a lap, 21 node pairs with a penalty contact and an
elastic dry-friction element each, pressed by the bolt's preload) swept across
its first bending mode at three forcing levels on the scene's defaults. The
benchmark's chart script (bench/lap_joint_chart.py) draws the receptance of
the forced point and tabulates the peaks; this script then checks the trend
friction in a joint gives (asserted: the page fails if it goes)."""
import csv
import subprocess
import sys

from _common import EQHB, ROOT

DOF = "w20"  # the forced point: the upper beam's node 20, over the lap
FORCES = (3, 15, 50)


def shown(command):
    return "$ " + " ".join("python3" if c == sys.executable else c.replace(str(ROOT) + "/", "") for c in command)


for force in FORCES:
    command = [EQHB, "sweep", str(ROOT / "problems" / "lap-joint.toml"), "--set", f"forcing[0].cos={force}",
               "--show", DOF, "--out", f"lap-joint-{force}.csv"]
    print(shown(command))
    run = subprocess.run(command, capture_output=True, text=True)
    print(run.stdout.strip())
    assert run.returncode == 0, run.stderr

chart = [sys.executable, str(ROOT / "bench" / "lap_joint_chart.py"), "lap_joint", DOF] + \
        [f"{force}=lap-joint-{force}.csv" for force in FORCES]
print(shown(chart))
run = subprocess.run(chart, capture_output=True, text=True)
print(run.stdout.strip())
assert run.returncode == 0, run.stderr

peaks = {}
for force in FORCES:
    with open(f"lap-joint-{force}.csv") as f:
        peaks[force] = max(((float(r["omega"]), float(r["first_harmonic_" + DOF])) for r in csv.DictReader(f)
                            if r["converged"] == "true"), key=lambda p: p[1])
# The resonance softens as more of the interface slides, and microslip damps it.
assert peaks[3][0] > peaks[15][0] > peaks[50][0], peaks
assert peaks[15][1] / 15 < 0.5 * peaks[3][1] / 3, peaks
