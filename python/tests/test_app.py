"""eqhb.solve, shoot, simulate and compare run what the eqhb command runs
(the application layer): on the same scene and options they return what
`eqhb solve/shoot/simulate/compare --json` prints, with the same labels."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import eqhb

PROBLEMS = pathlib.Path(os.environ.get("EQHB_PROBLEMS_DIR", pathlib.Path(__file__).parents[2] / "problems"))
SCENE = PROBLEMS / "friction-1d.toml"


def cli_json(*args, expect=(0,)):
    """`eqhb ARGS --json` as a dict (exit code checked)."""
    path = os.environ.get("EQHB_CLI")
    if not path:
        pytest.skip("EQHB_CLI is not set: built without the eqhb command (tests/CMakeLists.txt sets it)")
    run = subprocess.run([path, *map(str, args), "--json", "--quiet"], capture_output=True, text=True)
    assert run.returncode in expect, run.stderr
    return json.loads(run.stdout)


def max_abs(result):
    return [d["max_abs"] for d in result["dofs"]]


# Keys that measure the run (time, memory), not its answer.
TIMES = {"seconds", "seconds_min", "seconds_max", "setup_seconds", "peak_rss_mib", "seconds_per_orbit", "test_seconds"}


def same_answer(cli, py, path=""):
    """Every key of the command's JSON is in Python's dict with the same value
    (numbers to 1e-9; times and memory excepted)."""
    for key, value in cli.items():
        where = f"{path}.{key}"
        assert key in py, f"{where} missing from the Python result"
        if key in TIMES:
            continue
        mine = py[key]
        if isinstance(value, dict):
            same_answer(value, mine, where)
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            assert len(value) == len(mine), where
            for i, (a, b) in enumerate(zip(value, mine)):
                same_answer(a, b, f"{where}[{i}]")
        elif isinstance(value, list) and value and not isinstance(value[0], str):
            # Arrays: numbers, or complex numbers as [re, im] pairs.
            expected = np.asarray(value, dtype=float)
            mine = np.asarray(mine)
            if np.iscomplexobj(mine):
                expected = expected[:, 0] + 1j * expected[:, 1]
            np.testing.assert_allclose(mine, expected, rtol=1e-9, atol=1e-12, err_msg=where)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            assert mine == pytest.approx(value, rel=1e-9, abs=1e-12), where
        else:
            assert mine == value, where


def test_solve_with_stability_and_error_estimate_is_eqhb_solve():
    cli = cli_json("solve", SCENE, "--omega", 0.4, "--stability", "--error-estimate")
    py = eqhb.solve(eqhb.load_scene(SCENE), 0.4, stability=True, error_estimate=True)
    assert "stability" in py and "error_estimate" in py
    stability = cli.pop("stability")
    same_answer(cli, py)
    assert py["stability"]["spectral_radius"] == pytest.approx(stability["spectral_radius"], rel=1e-9)
    assert py["stability"]["stable"] == stability["stable"]
    multipliers = [complex(re, im) for re, im in stability["multipliers"]]
    np.testing.assert_allclose(py["stability"]["multipliers"], multipliers, rtol=1e-9, atol=1e-12)
    assert py["solution"]["max_abs_x"].tolist() == pytest.approx(max_abs(cli), rel=1e-12)


def test_accuracy_target_chooses_what_eqhb_solve_chooses():
    cli = cli_json("solve", SCENE, "--omega", 0.4, "--accuracy", 0.02, "--max-harmonics", 40)
    py = eqhb.solve(eqhb.load_scene(SCENE), 0.4, accuracy=0.02, max_harmonics=40)
    assert py["accuracy"]["reached"] and py["accuracy"]["test"] == "exact-orbit" and py["accuracy"]["error"] <= 0.02
    same_answer(cli, py)
    with pytest.raises(eqhb.InputError, match="accuracy = 2"):
        eqhb.solve(eqhb.load_scene(SCENE), 0.4, accuracy=2.0)
    with pytest.raises(eqhb.InputError, match="max_harmonics = 0"):
        eqhb.solve(eqhb.load_scene(SCENE), 0.4, accuracy=0.01, max_harmonics=0)


def test_accuracy_test_is_eqhb_solves():
    # friction-1d at omega = 0.35: tested against the exact orbit (H = 80),
    # or by the estimate times its safety factor.
    # (on rho = 1 the estimate's test climbs to max_harmonics without a claim: exit 1).
    for test, code in (("auto", 0), ("estimate", 1)):
        cli = cli_json("solve", SCENE, "--omega", 0.35, "--accuracy", 1e-3, "--rho", 1, "--accuracy-test", test,
                       expect=(code,))
        py = eqhb.solve(eqhb.load_scene(SCENE), 0.35, accuracy=1e-3, rho=1, accuracy_test=test)
        assert py["accuracy"]["test"] == ("exact-orbit" if test == "auto" else "estimate")
        assert py["harmonics"] == cli["harmonics"] and (test != "auto" or py["harmonics"] == 80)
        assert py["accuracy"]["error"] == pytest.approx(cli["accuracy"]["error"], rel=1e-9)
        assert py["accuracy"]["reached"] == (test == "auto") and (test != "auto" or py["accuracy"]["error"] <= 1e-3)
        same_answer(cli, py)
    with pytest.raises(eqhb.InputError, match="accuracy_test = \"exact\""):
        eqhb.solve(eqhb.load_scene(SCENE), 0.35, accuracy=1e-3, accuracy_test="exact")


def test_refine_by_shooting_is_eqhb_solve_refine():
    cli = cli_json("solve", SCENE, "--omega", 0.308, "--refine", "shoot", "--refine-harmonics", 15)
    py = eqhb.solve(eqhb.load_scene(SCENE), 0.308, refine="shoot", refine_harmonics=15)
    assert py["refinement"]["converged"] and py["refinement"]["harmonics"] == 15
    assert len(py["solution"]["harmonics"]) == 15
    # max|x| reported is the exact orbit's, not the harmonic balance's.
    assert py["solution"]["max_abs_x"].tolist() == pytest.approx(py["refinement"]["max_abs"], rel=1e-12)
    same_answer(cli, py)
    with pytest.raises(eqhb.InputError, match="refine_harmonics = 15: needs refine"):
        eqhb.solve(eqhb.load_scene(SCENE), 0.308, refine_harmonics=15)


def test_starts_and_repeats_are_eqhb_solves():
    model = eqhb.load_scene(SCENE)
    seeded = eqhb.solve(model, 0.4, harmonics=20, from_harmonics=5)
    assert seeded["cold_start"] == {"kind": "from-harmonics"}
    same_answer(cli_json("solve", SCENE, "--omega", 0.4, "--harmonics", 20, "--from-harmonics", 5), seeded)
    zero = eqhb.solve(model, 0.4, cold_start="zero", repeat=3)
    assert zero["cold_start"] == {"kind": "zero"} and zero["repeats"] == 3
    same_answer(cli_json("solve", SCENE, "--omega", 0.4, "--cold-start", "zero", "--repeat", 3), zero)
    dense = eqhb.solve(model, 0.4, linear_algebra="dense", form="projection", rho=0.5)
    same_answer(cli_json("solve", SCENE, "--omega", 0.4, "--linear-algebra", "dense", "--form", "projection",
                         "--rho", 0.5), dense)
    with pytest.raises(eqhb.InputError, match="from_harmonics = 20"):
        eqhb.solve(model, 0.4, harmonics=20, from_harmonics=20)
    with pytest.raises(eqhb.InputError, match="repeat = 0"):
        eqhb.solve(model, 0.4, repeat=0)


def test_formulation_is_eqhb_solves_formulation():
    scene = PROBLEMS / "jenkins-1d.toml"
    aft = eqhb.solve(eqhb.load_scene(scene), formulation="aft")
    same_answer(cli_json("solve", scene, "--formulation", "aft"), aft)
    equality = eqhb.solve(eqhb.load_scene(scene), formulation="equality")
    assert aft["solution"]["max_abs_x"] != pytest.approx(equality["solution"]["max_abs_x"], rel=1e-6)
    with pytest.raises(eqhb.InputError, match="formulation = aft: no law of the scene has this formulation"):
        eqhb.solve(eqhb.load_scene(SCENE), formulation="aft")


def test_shoot_starts_from_the_solve_that_eqhb_shoot_starts_from():
    cli = cli_json("shoot", SCENE, "--omega", 0.308, "--trajectory")
    py = eqhb.shoot(eqhb.load_scene(SCENE), 0.308)
    # The start is a solve of the scene (coarse start, fallbacks), not a solve from zero.
    assert py["from_hb"]["cold_start"]["kind"] == "coarse"
    trajectory = cli.pop("trajectory")
    same_answer(cli, py)
    np.testing.assert_allclose(py["x"][1], trajectory["x2"], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(py["lambda"][0], trajectory["law1.lambda"], rtol=1e-9, atol=1e-9)
    assert py["lambda_labels"] == ["law1.lambda"]


def test_a_planar_law_is_labelled_alike_in_solve_and_shoot():
    scene = PROBLEMS / "friction-2d.toml"
    solve = cli_json("solve", scene, "--harmonics", 5, "--trajectory")
    shoot = cli_json("shoot", scene, "--harmonics", 5, "--trajectory", expect=(0, 1))
    labels = ["law1.lambda1", "law1.lambda2"]
    assert all(label in solve["trajectory"] for label in labels)
    if shoot["converged"]:
        assert all(label in shoot["trajectory"] for label in labels)
    assert eqhb.solve(eqhb.load_scene(scene), harmonics=5)["solution"]["lambda_labels"] == labels


def test_simulate_takes_the_scene_time_defaults_as_eqhb_simulate():
    scene = PROBLEMS / "stribeck.toml"  # [time_reference] step = 1e-3
    cli = cli_json("simulate", scene, "--periods", 3, expect=(0, 1))
    py = eqhb.simulate(eqhb.load_scene(scene), periods=3)
    assert py["step"] == pytest.approx(cli["step"], rel=1e-15) and py["step"] > 5e-4
    same_answer(cli, py)
    assert [f["label"] for f in py["law_forces"]] == ["law1.lambda"]
    from_hb = eqhb.simulate(eqhb.load_scene(SCENE), 0.4, step=0.02, periods=20, from_hb=True)
    same_answer(cli_json("simulate", SCENE, "--omega", 0.4, "--step", 0.02, "--periods", 20, "--from-hb",
                         expect=(0, 1)), from_hb)
    assert from_hb["from_hb"]["converged"]


def test_compare_is_eqhb_compare():
    cli = cli_json("compare", SCENE, "--omega", 0.4, "--step", 0.02, "--periods", 200, expect=(0, 1))
    py = eqhb.compare(eqhb.load_scene(SCENE), 0.4, step=0.02, periods=200)
    same_answer(cli, py)
    assert [e["channel"] for e in py["errors"]] == ["x1", "x2", "law1.lambda"]
    # The errors sample the solution on the reference's instants.
    assert py["solution"]["max_abs_x"].tolist() == pytest.approx(
        [e["max_abs_hb"] for e in py["errors"][:2]], rel=1e-4)


# Per-point keys of `eqhb sweep --json` and their names in Python's arrays.
POINT_KEYS = {"omega": "omega", "max_abs": "max_abs", "first_harmonic": "first_harmonic", "energy": "energy",
              "fold": "fold", "iterations": "iterations", "stable": "stable", "bifurcation": "bifurcation",
              "spectral_radius": "spectral_radius", "multipliers": "multipliers",
              "error_estimate": "error_estimate", "harmonics": "point_harmonics", "samples": "point_samples",
              "accuracy_met": "accuracy_met", "accuracy_failure": "accuracy_failure"}


def same_curve(cli, py):
    """The curve's settings and every converged point's values as `eqhb sweep --json` has them."""
    points = cli.pop("points")
    cli.pop("harmonics")  # H; Python's "harmonics" lists the harmonics of the basis
    for key in ("stability_seconds", "solve_seconds"):
        cli.pop(key, None)
    same_answer(cli, py)
    assert len(py["omega"]) == len(points)
    for key, name in POINT_KEYS.items():
        given = [p.get(key) for p in points]
        if all(v is None for v in given):
            assert name not in py or all(v is None or v == "" for v in py[name]), name
            continue
        for i, (a, b) in enumerate(zip(given, py[name])):
            where = f"points[{i}].{key}"
            if a is None:
                assert b is None or b == "", where
            elif key == "multipliers":
                np.testing.assert_allclose(b, [complex(re, im) for re, im in a], rtol=1e-9, atol=1e-12, err_msg=where)
            elif isinstance(a, (list, float)):
                np.testing.assert_allclose(np.asarray(b, dtype=float), a, rtol=1e-9, atol=1e-12, err_msg=where)
            else:
                assert b == a, where


def test_sweep_with_stability_and_error_estimates_is_eqhb_sweep():
    args = ("--from", 0.3, "--to", 0.4, "--step", 0.02, "--harmonics", 5)
    cli = cli_json("sweep", SCENE, *args, "--stability", "--error-estimate")
    py = eqhb.sweep(eqhb.load_scene(SCENE), 0.3, 0.4, step=0.02, harmonics=5, stability=True, error_estimate=True)
    assert len(py["stable"]) == 6 and all(s in (True, False) for s in py["stable"])
    assert all(e is not None and 0 < e < 1 for e in py["error_estimate"])
    assert py["bifurcations"] == cli["bifurcations"]
    same_curve(cli, py)


@pytest.mark.parametrize("method", ["hill", "monodromy", "shooting"])
def test_sweep_stability_by_each_method_is_eqhb_sweeps(method):
    """The stability column by the method asked is the command's, verdicts and radii; the two methods agree."""
    args = ("--from", 0.3, "--to", 0.56, "--step", 0.02, "--harmonics", 10)
    cli = cli_json("sweep", SCENE, *args, "--stability", "--stability-method", method)
    py = eqhb.sweep(eqhb.load_scene(SCENE), 0.3, 0.56, step=0.02, harmonics=10, stability=True,
                    stability_method=method)
    same_curve(cli, py)
    other = eqhb.sweep(eqhb.load_scene(SCENE), 0.3, 0.56, step=0.02, harmonics=10, stability=True,
                       stability_method="monodromy" if method == "hill" else "hill")
    assert py["stable"] == other["stable"] and all(s in (True, False) for s in py["stable"])
    # The radii differ by method (0.78 against 0.71 at 0.3): the choice reached the analysis.
    assert max(abs(a - b) for a, b in zip(py["spectral_radius"], other["spectral_radius"])) > 0.01


def test_a_sweeps_stability_stops_at_its_time_limit():
    full = eqhb.sweep(eqhb.load_scene(SCENE), 0.3, 0.4, step=0.02, harmonics=5, stability=True)
    assert not full["stability_time_limited"] and full["stability_points_analysed"] == 6
    cut = eqhb.sweep(eqhb.load_scene(SCENE), 0.3, 0.4, step=0.02, harmonics=5, stability=True,
                     stability_time_limit=1e-9)
    assert cut["stability_time_limited"] and cut["stability_points_analysed"] < 6
    assert sum(s is not None for s in cut["stable"]) == cut["stability_points_analysed"]
    with pytest.raises(eqhb.InputError, match="stability_time_limit"):
        eqhb.sweep(eqhb.load_scene(SCENE), 0.3, 0.4, stability=True, stability_time_limit=-1.0)


def test_arclength_sweep_with_stability_finds_the_folds_eqhb_sweep_finds():
    scene = PROBLEMS / "duffing.toml"
    cli = cli_json("sweep", scene, "--arclength", "--harmonics", 3, "--samples", 64, "--stability",
                   "--max-step", 0.05, "--min-step", 1e-5, expect=(0, 1))
    py = eqhb.sweep(eqhb.load_scene(scene), method="arclength", harmonics=3, samples=64, stability=True,
                    max_step=0.05, min_step=1e-5)
    assert py["method"] == "arclength" and py["step"] == 0.01
    same_curve(cli, py)


def test_accuracy_sweep_is_eqhb_sweep_accuracy():
    args = ("--from", 0.3, "--to", 0.4, "--step", 0.05, "--accuracy", 0.05, "--max-harmonics", 20)
    cli = cli_json("sweep", SCENE, *args, expect=(0, 1))
    py = eqhb.sweep(eqhb.load_scene(SCENE), 0.3, 0.4, step=0.05, accuracy=0.05, max_harmonics=20)
    assert "accuracy" in py and "rho" in py and len(py["accuracy_met"]) == len(py["omega"])
    same_curve(cli, py)
    with pytest.raises(eqhb.InputError, match="stability = \\(set\\): not with accuracy"):
        eqhb.sweep(eqhb.load_scene(SCENE), 0.3, 0.4, accuracy=0.05, stability=True)


def test_sweep_options_are_named_as_python_names_them():
    model = eqhb.model(np.eye(1), np.eye(1), forcing=[{"dof": 1, "cos": 1.0}])
    with pytest.raises(eqhb.InputError, match="^start = \\(missing\\).*give start and stop"):
        eqhb.sweep(model)
    with pytest.raises(eqhb.InputError, match="^stop = 0.5: must differ from from"):
        eqhb.sweep(model, 0.5, 0.5)
    with pytest.raises(eqhb.InputError, match="^min_step = 0.5: min_step = 0.5 must be <= max_step = 0.1"):
        eqhb.sweep(model, 0.5, 0.6, min_step=0.5, max_step=0.1, method="arclength")


def test_study_is_eqhb_study(tmp_path):
    args = ("--harmonics", 5, "--samples", 128, "--vary", "law.muN=0.5:3:3", "--peak", "--from", 0.3, "--to", 1.2,
            "--threads", 1)
    path = os.environ.get("EQHB_CLI")
    if not path:
        pytest.skip("EQHB_CLI is not set")
    run = subprocess.run([path, "study", SCENE, *map(str, args), "--out", tmp_path / "cli"], capture_output=True,
                         text=True)
    assert run.returncode == 0, run.stderr
    cli = json.loads((tmp_path / "cli" / "study.json").read_text())
    py = eqhb.study(eqhb.load_scene(SCENE), "law.muN=0.5:3:3", out=str(tmp_path / "py"), mode="peak", harmonics=5,
                    samples=128, start=0.3, stop=1.2, threads=1)
    assert py["succeeded"] and py["total"] == py["computed"] == 3 and py["failed"] == 0
    assert json.loads((tmp_path / "py" / "study.json").read_text())["samples"][2]["peak_omega"] == pytest.approx(
        py["samples"][2]["peak_omega"], rel=1e-15)
    for sample in cli["samples"] + py["samples"]:
        sample.pop("worker")
    same_answer(cli, py)
    again = eqhb.study(eqhb.load_scene(SCENE), ["law.muN=0.5:3:3"], out=str(tmp_path / "py"), harmonics=5,
                       samples=128, start=0.3, stop=1.2)
    assert again["computed"] == 0 and again["succeeded"]
    with pytest.raises(eqhb.InputError, match="^model = \\(in memory\\)"):
        eqhb.study(eqhb.model(np.eye(1), np.eye(1)), "law.muN=1:2:2", out=str(tmp_path / "m"))
    with pytest.raises(eqhb.InputError, match="^mode = \"both\""):
        eqhb.study(eqhb.load_scene(SCENE), "law.muN=1:2:2", out=str(tmp_path / "m"), mode="both")


def test_study_fallback_reaches_every_sample(tmp_path):
    duffing = eqhb.load_scene(PROBLEMS / "field" / "nlvib-01-duffing.toml")
    bare = eqhb.study(duffing, "law[0].epsilon=0.1:0.1:1", out=str(tmp_path / "none"), mode="sweep", fallback="none")
    assert bare["failed"] == 1 and "grid point" in bare["samples"][0]["reason"]
    helped = eqhb.study(duffing, "law[0].epsilon=0.1:0.1:1", out=str(tmp_path / "default"), mode="sweep")
    assert helped["succeeded"] and helped["failed"] == 0
    with pytest.raises(eqhb.InputError, match="^fallback = bogus: has an unknown step bogus"):
        eqhb.study(duffing, "law[0].epsilon=0.1:0.1:1", out=str(tmp_path / "bad"), mode="sweep", fallback="bogus")


PRELOADED = """name = "preloaded"
[structure]
type = "chain"
dofs = 1
m = 1.0
k = 1.0
d = 0.02
[[law]]
type = "penalty-contact"
dofs = [1]
stiffness = 10.0
gap = 0.5
[[preload]]
dof = 1
force = 2.0
[[forcing]]
dof = 1
cos = 0.01
[harmonic_balance]
harmonics = 5
set = "all"
samples = 64
omega = 1.5
"""


def test_preload_static_state_is_eqhb_solves(tmp_path):
    scene = tmp_path / "preloaded.toml"
    scene.write_text(PRELOADED)
    cli = cli_json("solve", scene)
    py = eqhb.solve(eqhb.load_scene(scene))
    same_answer(cli, py)
    element = py["preload"]["elements"][0]
    assert element["state"] == "closed"
    # Pressed on the wall: x = (F + k_n g0)/(k + k_n) = 7/11, p = k_n (x − g0).
    assert py["preload"]["displacement"][0] == pytest.approx(7 / 11, rel=1e-12)
    assert element["normal_force"] == pytest.approx(10 * (7 / 11 - 0.5), rel=1e-12)


def test_a_beams_dofs_are_named_and_its_tip_deflection_defines_the_peak():
    beam = eqhb.load_scene(PROBLEMS / "beam-damper.toml")
    curve = eqhb.sweep(beam, 3.4, 3.6, step=0.1)
    assert curve["dof_labels"][:2] == ["w1", "theta1"] and curve["dof_labels"][-1] == "theta60"
    assert curve["peak_dof"] == "w60"
    chosen = eqhb.sweep(beam, 3.4, 3.6, step=0.1, peak_dof="theta60")
    assert chosen["peak_dof"] == "theta60"
    assert eqhb.sweep(beam, 3.4, 3.6, step=0.1, peak_dof=119)["peak_dof"] == "w60"
    with pytest.raises(eqhb.InputError, match=r"peak_dof = \"w61\": no DOF of the structure is named so"):
        eqhb.sweep(beam, 3.4, 3.6, step=0.1, peak_dof="w61")
    with pytest.raises(eqhb.InputError, match="peak_dof"):
        eqhb.sweep(beam, 3.4, 3.6, step=0.1, peak_dof=1.5)


def test_show_chooses_the_dofs_shown_in_solve_sweep_and_study(tmp_path):
    beam = eqhb.load_scene(PROBLEMS / "beam-damper.toml")
    solved = eqhb.solve(beam, omega=3.5)
    assert solved["shown"] == ["w15", "w30", "w45", "w60"]
    assert [d["name"] for d in solved["dofs"]][118:] == ["w60", "theta60"]
    assert eqhb.solve(beam, omega=3.5, show=["theta60", 1])["shown"] == ["theta60", "w1"]
    assert eqhb.solve(beam, omega=3.5, show="w10")["shown"] == ["w10"]
    curve = eqhb.sweep(beam, 3.4, 3.6, step=0.1, show=[119, "w30"])
    assert curve["shown"] == ["w60", "w30"] and curve["max_abs"].shape[1] == 120  # the arrays keep every DOF
    study = eqhb.study(beam, "forcing[0].cos=1:2:2", out=str(tmp_path / "s"),
                       start=3.3, stop=3.7, coarse_points=9, threads=1, dof="w60", show=["w30"])
    assert study["dof"] == 119 and study["dof_label"] == "w60" and study["shown"] == ["w30", "w60"]
    header = (tmp_path / "s" / "study.csv").read_text().splitlines()[0]
    assert ",peak_omega,first_harmonic_w30,first_harmonic_w60,max_abs_w30,max_abs_w60,peaks," in header
    with pytest.raises(eqhb.InputError, match=r"show\[1\] = \"w61\": no DOF of the structure is named so"):
        eqhb.solve(beam, omega=3.5, show=["w60", "w61"])
    with pytest.raises(eqhb.InputError, match=r"show\[0\] = 1.5: must be a DOF number"):
        eqhb.sweep(beam, 3.4, 3.6, step=0.1, show=[1.5])
    with pytest.raises(eqhb.InputError, match=r"dof = \"w61\": no DOF of the structure is named so"):
        eqhb.study(beam, "forcing[0].cos=1:2:2", out=str(tmp_path / "bad"), dof="w61")
