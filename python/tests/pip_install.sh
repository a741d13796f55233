#!/usr/bin/env bash
# pip install of the module, as the documentation says it: a venv from
# Debian's Python with the system's packages, `pip install
# --no-build-isolation .` offline (--no-index: nothing is downloaded), then
# `import eqhb` and a solve from that venv, outside the source tree. Then the
# wheel: `pip wheel` and the wheel installed into a second venv.
#   python/tests/pip_install.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$(cd "$1" && pwd)
work=$2
rm -rf "$work"
mkdir -p "$work"
cd "$work"

check() {  # VENV: the installed module imports from the venv and solves
  "$1/bin/python" - "$src/problems/friction-1d.toml" <<'PY'
import pathlib, sys
import numpy as np
import eqhb
where = pathlib.Path(eqhb.__file__).resolve()
assert pathlib.Path(sys.prefix).resolve() in where.parents, f"eqhb imported from {where}, not from {sys.prefix}"
K = np.array([[2.0, -1.0], [-1.0, 1.0]])
model = eqhb.model(np.eye(2), K, 0.02 * K, laws=[{"type": "coulomb-1d", "dofs": [2], "muN": 7.2, "rho": 1.0}],
                   forcing=[{"dof": 1, "cos": 20.0}], harmonics=10, samples=1024, omega=0.4)
r = eqhb.solve(model, 0.4)
scene = eqhb.solve(eqhb.load_scene(sys.argv[1]), 0.4)
assert r["converged"] and scene["converged"], (r["termination"], scene["termination"])
assert abs(r["dofs"][1]["max_abs"] - scene["dofs"][1]["max_abs"]) < 1e-9 * scene["dofs"][1]["max_abs"]
print(f"eqhb {eqhb.__version__} from {where.parent}: converged in {r['iterations']} iterations, "
      f"max|x2| = {r['dofs'][1]['max_abs']:.6f}")
PY
}

/usr/bin/python3 -m venv --system-site-packages venv
venv/bin/pip install --no-build-isolation --no-index "$src" 2>&1 | tee pip-install.log | grep -E "^(Processing|Building|Successfully|ERROR)|eqhb: cmake" || true
grep -q "^Successfully installed eqhb" pip-install.log || { tail -n 40 pip-install.log; exit 1; }
check venv

venv/bin/pip wheel --no-build-isolation --no-index --no-deps -w wheels "$src" > pip-wheel.log 2>&1 || { tail -n 40 pip-wheel.log; exit 1; }
wheel=$(ls wheels/eqhb-*.whl)
echo "wheel: $(basename "$wheel")"
/usr/bin/python3 -m venv --system-site-packages venv-wheel
venv-wheel/bin/pip install --no-index "$wheel" > pip-wheel-install.log 2>&1 || { tail -n 40 pip-wheel-install.log; exit 1; }
check venv-wheel
