"""eqhb.modes runs what `eqhb modes` runs: the same backbone on the same scene,
a linear structure's modal frequency and damping ratio at every amplitude,
and bad input named by the Python argument."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import eqhb

PROBLEMS = pathlib.Path(os.environ.get("EQHB_PROBLEMS_DIR", pathlib.Path(__file__).parents[2] / "problems"))
SCENE = PROBLEMS / "friction-1d.toml"


def rayleigh_chain():
    mass = np.diag([1.0, 2.0])
    stiffness = np.array([[3.0, -1.0], [-1.0, 1.0]])
    return eqhb.model(mass, stiffness, 0.01 * mass + 0.004 * stiffness, harmonics=3), mass, stiffness


def test_linear_structure_keeps_its_modal_frequency_and_damping_ratio():
    model, mass, stiffness = rayleigh_chain()
    eigenvalues = np.sort(np.linalg.eigvals(np.linalg.solve(mass, stiffness)).real)
    for mode in (1, 2):
        omega = np.sqrt(eigenvalues[mode - 1])
        zeta = 0.5 * (0.01 / omega + 0.004 * omega)
        result = eqhb.modes(model, mode, start=1e-2, stop=1e2, points=5)
        assert result["complete"] and len(result["points"]) == 5
        for p in result["points"]:
            assert abs(p["omega"] - omega) < 1e-10 * omega
            assert abs(p["damping_ratio"] - zeta) < 1e-10 * zeta


def test_same_backbone_as_the_command():
    path = os.environ.get("EQHB_CLI")
    if not path:
        pytest.skip("EQHB_CLI is not set: built without the eqhb command (tests/CMakeLists.txt sets it)")
    run = subprocess.run([path, "modes", str(SCENE), "--from", "0.5", "--to", "50", "--points", "4", "--json"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    command = json.loads(run.stdout)
    python = eqhb.modes(eqhb.load_scene(SCENE), 1, start=0.5, stop=50, points=4)
    for a, b in zip(command["points"], python["points"]):
        for key in ("amplitude", "omega", "damping_ratio", "dissipated_energy"):
            assert a[key] == pytest.approx(b[key], rel=1e-12)


@pytest.mark.parametrize("kwargs, message", [
    ({"mode": 3}, "mode = 3"),
    ({"start": 0.0}, "start = 0.0"),
    ({"stop": float("nan")}, "stop = nan"),
    ({"start": 2.0, "stop": 1.0}, "stop = 1.0: must be > start"),
    ({"backbone_time_limit": -1.0}, "backbone_time_limit = -1"),
    ({"synthesis": True}, "forcing = none at harmonic 1"),
])
def test_bad_input_names_the_argument(kwargs, message):
    model, _, _ = rayleigh_chain()
    with pytest.raises(eqhb.InputError, match=message):
        eqhb.modes(model, **kwargs)


def test_synthesis_beside_the_forced_sweep():
    """The forced response the mode predicts, beside the forced sweep across
    the resonance (as `eqhb modes --synthesis`): on exact Coulomb friction
    one mode carries the resonance and the two agree within about 1 %
    (the held branch: the sweep's default, auto, is the sliding one)."""
    result = eqhb.modes(eqhb.load_scene(SCENE), 1, branch="held", synthesis=True)
    s = result["synthesis"]
    assert s["closed"] and s["not_compared"] is None and s["refinement_points"] > 0
    assert s["dof"] == 1 and s["forced"]["failed_points"] == 0
    assert abs(s["errors"]["peak_amplitude"]) < 0.01
    assert abs(s["forced"]["peak"]["max_abs"] - s["peak"]["max_abs"][0]) < 0.01 * s["forced"]["peak"]["max_abs"]
    lower = [p for p in s["points"] if p["branch"] == "lower"]
    upper = [p for p in s["points"] if p["branch"] == "upper"]
    assert lower and upper and max(p["omega"] for p in lower) <= min(p["omega"] for p in upper)


def test_condensed_system_gives_the_full_systems_backbone():
    scene = eqhb.load_scene(SCENE)
    full = eqhb.modes(scene, 1, start=0.5, stop=50, points=6)
    condensed = eqhb.modes(scene, 1, start=0.5, stop=50, points=6, system="condensed")
    assert full["system"] == "full" and condensed["system"] == "condensed"
    assert condensed["complete"]
    for a, b in zip(full["points"], condensed["points"]):
        assert b["omega"] == pytest.approx(a["omega"], rel=1e-8)
        assert b["damping_ratio"] == pytest.approx(a["damping_ratio"], rel=1e-7)
    with pytest.raises(eqhb.InputError, match="system"):
        eqhb.modes(rayleigh_chain()[0], 1, system="condensed")  # no law to condense to
    with pytest.raises(eqhb.InputError, match="system"):
        eqhb.modes(scene, 1, system="reduced")
