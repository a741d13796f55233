"""Your own structure: a 6-DOF chain written as numpy arrays, a friction
damper on its last mass, one solve and a frequency sweep; then the same
structure as Matrix Market files in a scene file, solved by the command line
and by Python, which must agree."""
import json
import subprocess

import numpy as np
import scipy.io
import scipy.sparse

import eqhb
from _common import EQHB, pyplot

# --- the structure: 6 masses in a row, clamped at the left, free at the right
n = 6
m, k = 1.0, 100.0
M = m * np.eye(n)
K = np.zeros((n, n))
for i in range(n):  # spring i joins mass i to mass i-1 (the clamp for i = 0)
    K[i, i] += k
    if i > 0:
        K[i - 1, i - 1] += k
        K[i - 1, i] -= k
        K[i, i - 1] -= k
eigenvalues = np.linalg.eigvalsh(np.linalg.solve(M, K))
omega_1 = float(np.sqrt(eigenvalues[0]))
C = 0.002 * K  # stiffness-proportional damping

# --- the nonlinear part: Coulomb friction on DOF 6 (numbered from 1), the
# load on DOF 6 too; the keys are those of a scene file's [[law]] and [[forcing]]
laws = [{"type": "coulomb-1d", "dofs": [6], "muN": 2.0}]
forcing = [{"dof": 6, "cos": 3.0}]
model = eqhb.model(M, K, C, laws=laws, forcing=forcing, harmonics=10, omega=omega_1)
print(f"model: {n} DOFs, first eigenfrequency {omega_1:.4f} rad/s")

r = eqhb.solve(model, omega=omega_1)
print(f"solve at omega_1: converged {r['converged']} in {r['iterations']} iterations, "
      f"max|x6| = {r['dofs'][-1]['max_abs']:.5f}")

# --- a frequency sweep around the first mode, and the linear response for scale
curve = eqhb.sweep(model, 0.6 * omega_1, 1.4 * omega_1, step=0.005 * omega_1)
print(f"sweep: {len(curve['omega'])} points converged, {curve['failed_points']} failed, "
      f"complete {curve['complete']}")
peak = int(np.argmax(curve["max_abs"][:, -1]))
print(f"peak of x6: {curve['max_abs'][peak, -1]:.5f} at omega = {curve['omega'][peak]:.4f}")

def linear_amplitude(w):
    A = K - w**2 * M + 1j * w * C
    f = np.zeros(n)
    f[5] = 3.0
    return abs(np.linalg.solve(A, f)[5])

plt = pyplot()
fig, ax = plt.subplots(figsize=(6.5, 3.8))
ax.plot(curve["omega"], curve["max_abs"][:, -1], label="with friction (eqhb)")
w = np.linspace(0.6 * omega_1, 1.4 * omega_1, 400)
ax.plot(w, [linear_amplitude(x) for x in w], "--", lw=0.8, label="without friction (linear)")
ax.set_yscale("log")
ax.set_xlabel("omega (rad/s)")
ax.set_ylabel("max|x6|")
ax.legend(loc="upper right")
fig.savefig("frf.png")

# --- the same structure from Matrix Market files, as a finite-element code
# would export it; the scene file names them relative to itself
scipy.io.mmwrite("M.mtx", scipy.sparse.coo_matrix(M), symmetry="symmetric")
scipy.io.mmwrite("K.mtx", scipy.sparse.coo_matrix(K), symmetry="symmetric")
scene = f"""name = "chain-6"

[structure]
type = "matrix-market"
mass = "M.mtx"
stiffness = "K.mtx"
rayleigh = [0.0, 0.002]   # C = 0 M + 0.002 K

[[forcing]]
dof = 6
cos = 3.0

[[law]]
type = "coulomb-1d"
dofs = [6]
muN = 2.0

[harmonic_balance]
harmonics = 10
set = "odd"
samples = 256
omega = {omega_1!r}
"""
with open("chain-6.toml", "w") as f:
    f.write(scene)
print("chain-6.toml:\n" + scene)

cli = json.loads(subprocess.run([EQHB, "solve", "chain-6.toml", "--json"], check=True, capture_output=True,
                                text=True).stdout)
from_file = eqhb.solve(eqhb.load_scene("chain-6.toml"))
print(f"eqhb solve chain-6.toml: max|x6| = {cli['dofs'][-1]['max_abs']:.5f}")
print(f"eqhb.load_scene + solve: max|x6| = {from_file['dofs'][-1]['max_abs']:.5f}")
assert abs(cli["dofs"][-1]["max_abs"] - r["dofs"][-1]["max_abs"]) < 1e-8 * r["dofs"][-1]["max_abs"]
assert abs(from_file["dofs"][-1]["max_abs"] - r["dofs"][-1]["max_abs"]) < 1e-8 * r["dofs"][-1]["max_abs"]
print("arrays, Matrix Market with the command line and Matrix Market from Python agree")
