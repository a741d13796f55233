"""The Python module against the library's own answers: a scene file and
the same model from arrays (dense and scipy.sparse) agree, a sweep agrees
with single solves, the time reference agrees with harmonic balance, and
every bad input raises eqhb.InputError naming the field."""
import math
import os
import pathlib
import signal
import threading

import numpy as np
import pytest
import scipy.sparse

import eqhb

PROBLEMS = pathlib.Path(os.environ.get("EQHB_PROBLEMS_DIR", pathlib.Path(__file__).parents[2] / "problems"))
SCENE = PROBLEMS / "friction-1d.toml"

# friction-1d (formulation spec section 4): 2-DOF chain, m = k = 1, d = 0.02,
# Coulomb friction muN = 7.2 on DOF 2, forcing 20 cos(wt) on DOF 1.
K = np.array([[2.0, -1.0], [-1.0, 1.0]])
M = np.eye(2)
C = 0.02 * K
LAWS = [{"type": "coulomb-1d", "dofs": [2], "muN": 7.2, "form": "minmax", "rho": 1.0}]
FORCING = [{"dof": 1, "harmonic": 1, "cos": 20.0}]


def arrays_model(mass=M, stiffness=K, damping=C, **kw):
    settings = dict(laws=LAWS, forcing=FORCING, harmonics=10, samples=1024, omega=0.4)
    settings.update(kw)
    return eqhb.model(mass, stiffness, damping, **settings)


def test_coarse_cold_start_finds_the_zero_starts_solution():
    model = eqhb.load_scene(SCENE)
    coarse, zero = eqhb.solve(model), eqhb.solve(model, cold_start="zero")
    assert coarse["converged"] and zero["converged"]
    assert coarse["cold_start"]["kind"] == "coarse" and zero["cold_start"]["kind"] == "zero"
    # H = 10 odd: the rung has 3 harmonics; the fine solve needs fewer iterations from it.
    assert coarse["cold_start"]["harmonics"] == 3 and coarse["cold_start"]["converged"]
    assert coarse["iterations"] < zero["iterations"]
    np.testing.assert_allclose(coarse["solution"]["full"], zero["solution"]["full"],
                               atol=1e-8 * np.max(np.abs(zero["solution"]["full"])))
    # A given initial guess is used as given.
    again = eqhb.solve(model, initial=zero["solution"]["full"])
    assert again["cold_start"]["kind"] == "given" and again["iterations"] == 0


def test_version_and_backends():
    assert eqhb.__version__.count(".") == 2
    names = [s["name"] for s in eqhb.solvers()]
    assert "dogleg" in names and "dogleg-newton" in names


def test_scene_solve_is_physical():
    model = eqhb.load_scene(SCENE)
    assert (model.dofs, model.harmonic_count, model.samples, model.omega) == (2, 10, 1024, 0.4)
    assert list(model.harmonics) == list(range(1, 20, 2))
    r = eqhb.solve(model)
    assert r["converged"] and r["termination"] == "converged"
    assert r["residual_norm"] <= 1e-10
    s = r["solution"]
    assert s["x_cos"].shape == (2, 10) and s["lambda_cos"].shape == (1, 10)
    assert s["x"].shape == (2, 1024) and s["t"].shape == (1024,)
    # The truncated series of the friction force oscillates around muN = 7.2
    # (Gibbs) but its level is that of the law.
    assert 7.2 * 0.9 < np.max(np.abs(s["lambda"])) < 7.2 * 1.2
    assert [i["type"] for i in s["invariants"]] == ["coulomb-1d"]
    # max|x| is the largest sampled value of x.
    np.testing.assert_allclose(s["max_abs_x"], np.max(np.abs(s["x"]), axis=1), rtol=1e-12)
    # The time samples are the Fourier series with these coefficients.
    t, w = s["t"], model.omega
    x1 = sum(s["x_cos"][0, j] * np.cos(k * w * t) + s["x_sin"][0, j] * np.sin(k * w * t)
             for j, k in enumerate(s["harmonics"]))
    np.testing.assert_allclose(x1, s["x"][0], atol=1e-9 * np.max(np.abs(x1)))


def test_arrays_dense_and_sparse_match_the_scene():
    scene = eqhb.solve(eqhb.load_scene(SCENE))["solution"]
    dense = eqhb.solve(arrays_model())["solution"]
    sparse = eqhb.solve(arrays_model(scipy.sparse.csr_matrix(M), scipy.sparse.csc_matrix(K),
                                     scipy.sparse.coo_matrix(C)))["solution"]
    for other in (dense, sparse):
        np.testing.assert_allclose(other["full"], scene["full"], rtol=0, atol=1e-9)


def test_overrides_and_settings_change_the_answer():
    base = eqhb.solve(eqhb.load_scene(SCENE))["solution"]["max_abs_x"]
    stuck = eqhb.solve(eqhb.load_scene(SCENE, {"law[0].muN": 1e3}))["solution"]
    # Friction far above the load: DOF 2 sticks.
    assert stuck["max_abs_x"][1] < 1e-8 < base[1]
    r = eqhb.solve(eqhb.load_scene(SCENE), omega=0.3, harmonics=5, samples=256)
    assert r["omega"] == 0.3 and len(r["solution"]["harmonics"]) == 5


def test_backends_by_name_agree_and_initial_restarts():
    model = eqhb.load_scene(SCENE)
    dogleg = eqhb.solve(model, solver="dogleg")
    newton = eqhb.solve(model, solver="dogleg-newton", system="full")
    assert newton["converged"] and newton["system"] == "full"
    np.testing.assert_allclose(newton["solution"]["full"], dogleg["solution"]["full"], atol=1e-8)
    again = eqhb.solve(model, initial=dogleg["solution"]["full"])
    assert again["converged"] and again["iterations"] <= 1 < dogleg["iterations"]


def test_sweep_points_are_the_single_solves():
    model = eqhb.load_scene(SCENE)
    curve = eqhb.sweep(model, 0.3, 0.4, step=0.02, harmonics=5, samples=256)
    np.testing.assert_allclose(curve["omega"], np.linspace(0.3, 0.4, 6), atol=1e-12)
    assert curve["converged"].all() and curve["complete"] and curve["failed_points"] == 0
    assert curve["max_abs"].shape == (6, 2) and curve["x_cos"].shape == (6, 2, 5)
    single = eqhb.solve(model, omega=curve["omega"][3], harmonics=5, samples=256)["solution"]
    np.testing.assert_allclose(curve["max_abs"][3], single["max_abs_x"], rtol=1e-6)
    np.testing.assert_allclose(curve["x_cos"][3], single["x_cos"], atol=1e-6 * np.max(single["max_abs_x"]))


def test_a_curve_time_limit_keeps_the_points_found():
    model = eqhb.load_scene(SCENE)
    curve = eqhb.sweep(model, 0.3, 0.4, step=0.02, harmonics=5, samples=256, curve_time_limit=1e-9, stability=True)
    # The first point is solved, then the limit stops the curve; stability has no time left.
    assert list(curve["omega"]) == [0.3] and curve["converged"].all()
    assert not curve["complete"] and curve["failed_points"] == 0
    assert "curve_time_limit of 1e-09 s reached" in curve["stop_reason"]
    assert curve["stability_time_limited"] and curve["stability_points_analysed"] == 0
    with pytest.raises(eqhb.InputError, match="^curve_time_limit = -1: must be finite and >= 0"):
        eqhb.sweep(model, 0.3, 0.4, curve_time_limit=-1)


def test_sweep_progress_sees_each_point_and_ctrl_c_keeps_them():
    model = eqhb.load_scene(SCENE)
    seen = []
    curve = eqhb.sweep(model, 0.3, 0.4, step=0.02, harmonics=5, samples=256, progress=seen.append)
    assert [p["index"] for p in seen] == list(range(6)) and all(p["converged"] for p in seen)
    np.testing.assert_allclose([p["omega"] for p in seen], curve["omega"], atol=0)

    # Ctrl-C during the third point: the curve stops there with three points.
    def interrupt_at_third(point):
        if point["index"] == 2:
            signal.raise_signal(signal.SIGINT)
    stopped = eqhb.sweep(model, 0.3, 0.4, step=0.02, harmonics=5, samples=256, progress=interrupt_at_third)
    assert len(stopped["omega"]) == 3 and not stopped["complete"]
    assert "stopped on request" in stopped["stop_reason"]

    # An exception of the callable stops the sweep and reaches the caller.
    def fail_at_second(point):
        if point["index"] == 1:
            raise RuntimeError("enough")
    with pytest.raises(RuntimeError, match="enough"):
        eqhb.sweep(model, 0.3, 0.4, step=0.02, harmonics=5, samples=256, progress=fail_at_second)
    with pytest.raises(eqhb.InputError, match="^progress = 3: must be callable"):
        eqhb.sweep(model, 0.3, 0.4, progress=3)


def test_ctrl_c_while_the_library_runs_stops_the_sweep_keeping_its_points():
    # No callable: the signal comes while the sweep runs without the GIL
    # (15001 points of ~30 ms: far from done after 1 s; the time limit only
    # bounds the test if the signal were missed).
    model = eqhb.load_scene(PROBLEMS / "lap-joint.toml")
    timer = threading.Timer(1.0, signal.raise_signal, (signal.SIGINT,))
    timer.start()
    try:
        curve = eqhb.sweep(model, 1450, 1600, step=0.01, curve_time_limit=60)
    finally:
        timer.cancel()
    assert "stopped on request" in curve["stop_reason"] and not curve["complete"]
    assert len(curve["omega"]) >= 1 and curve["converged"].all()


def test_arclength_sweep_uses_the_scene_range():
    model = eqhb.load_scene(PROBLEMS / "cubic.toml")
    curve = eqhb.sweep(model, method="arclength", harmonics=3, samples=64)
    start, stop = model.sweep_range
    assert curve["method"] == "arclength" and curve["complete"]
    # The last point lies on the end of the range, not past it.
    assert curve["omega"][0] == start and curve["omega"][-1] == stop


def test_simulate_agrees_with_harmonic_balance():
    model = eqhb.load_scene(SCENE)
    hb = eqhb.solve(model, omega=0.3, harmonics=20, samples=2048)["solution"]
    ref = eqhb.simulate(model, omega=0.3, step=2e-3, initial=None)
    assert ref["periodic"] and ref["x"].shape[0] == 2 and ref["x"].shape == ref["v"].shape
    np.testing.assert_allclose(ref["max_abs_x"], hb["max_abs_x"], rtol=0.02)


def test_shoot_finds_the_exact_orbit_near_harmonic_balance():
    model = eqhb.load_scene(SCENE)
    orbit = eqhb.shoot(model, omega=0.308)
    assert orbit["converged"] and orbit["period_residual"] <= 1e-11
    # Stick-slip at this frequency: two stick and two slip phases per period.
    assert orbit["events"] == {"slip": 2, "stick": 2}
    assert orbit["stable"] and orbit["spectral_radius"] == pytest.approx(np.max(np.abs(orbit["multipliers"])))
    assert orbit["x"].shape == (2, model.samples)
    hb = eqhb.solve(model, omega=0.308)["solution"]
    np.testing.assert_allclose(orbit["max_abs_x"], hb["max_abs_x"], rtol=0.05)


def test_shoot_stops_at_its_time_limit_without_multipliers():
    # At omega = 0.8 the start without its fallbacks does not converge, and
    # Newton on the period map from it runs for minutes.
    orbit = eqhb.shoot(eqhb.load_scene(PROBLEMS / "cubic.toml"), omega=0.8, time_limit=1.0, fallback="none")
    assert not orbit["from_hb"]["converged"] and "did not converge" in orbit["warnings"][0]
    assert not orbit["converged"] and "time limit reached" in orbit["failure"]
    assert orbit["multipliers"] is None and orbit["spectral_radius"] is None and orbit["stable"] is None


def test_stability_by_hill_matches_the_shooting_multipliers_on_cubic():
    model = eqhb.load_scene(PROBLEMS / "cubic.toml")
    result = eqhb.solve(model, omega=0.5, system="full")
    hill = eqhb.stability(model, result)
    orbit = eqhb.shoot(model, omega=0.5)
    assert hill["stable"] and orbit["stable"] and hill["failure"] == ""
    assert hill["spectral_radius"] == pytest.approx(orbit["spectral_radius"], rel=1e-5)
    exact = sorted(orbit["multipliers"], key=lambda z: (round(abs(z), 6), z.imag))
    found = sorted(hill["multipliers"], key=lambda z: (round(abs(z), 6), z.imag))
    np.testing.assert_allclose(found, exact, atol=1e-5)
    with pytest.raises(eqhb.InputError, match="full"):
        eqhb.stability(model, np.zeros(3), omega=0.5)


BAD = [
    (lambda: arrays_model(laws=[dict(LAWS[0], muN=-1.0)]), "law[0].muN"),
    (lambda: arrays_model(laws=[dict(LAWS[0], muN=float("nan"))]), "law[0].muN"),
    (lambda: arrays_model(laws=[dict(LAWS[0], dofs=[3])]), "law[0].dofs"),
    (lambda: arrays_model(laws=[dict(LAWS[0], muN=object())]), "law[0].muN"),
    (lambda: arrays_model(forcing=[{"dof": 1, "cos": "x"}]), "forcing[0].cos"),
    (lambda: arrays_model(stiffness=np.ones((3, 3))), "stiffness"),
    (lambda: arrays_model(mass=np.diag([1.0, -1.0])), "mass"),
    (lambda: arrays_model(damping=np.array([[np.inf, 0], [0, 0]])), "damping"),
    (lambda: arrays_model(mass="not a matrix"), "mass"),
    (lambda: arrays_model(samples=8), "harmonic_balance.samples"),
    (lambda: arrays_model(omega=0.0), "harmonic_balance.omega"),
    (lambda: eqhb.load_scene(PROBLEMS / "missing.toml"), "missing.toml"),
    (lambda: eqhb.load_scene(SCENE, {"law[0].form": "bogus"}), "law[0].form"),
    (lambda: eqhb.solve(eqhb.load_scene(SCENE), omega=-1.0), "omega"),
    (lambda: eqhb.solve(eqhb.load_scene(SCENE), solver="nope"), "solver"),
    (lambda: eqhb.solve(eqhb.load_scene(SCENE), system="dense"), "system"),
    (lambda: eqhb.solve(eqhb.load_scene(SCENE), tolerance=-1.0), "tolerance"),
    (lambda: eqhb.solve(eqhb.load_scene(SCENE), options={"bogus": 1}), "bogus"),
    (lambda: eqhb.solve(eqhb.load_scene(SCENE), initial=[0.0, 1.0]), "initial"),
    (lambda: eqhb.solve(eqhb.load_scene(SCENE), cold_start="warm"), "cold_start"),
    (lambda: eqhb.sweep(eqhb.load_scene(SCENE), method="newton"), "method"),
    (lambda: eqhb.sweep(eqhb.load_scene(SCENE), 0.1, 0.2, step=0.0), "step"),
    (lambda: eqhb.simulate(eqhb.load_scene(SCENE), theta=2.0), "theta"),
    (lambda: eqhb.shoot(eqhb.load_scene(SCENE), restitution=2.0), "restitution"),
    (lambda: eqhb.shoot(eqhb.load_scene(PROBLEMS / "contact-friction-2d.toml")), "law"),
]


@pytest.mark.parametrize("call,field", BAD, ids=[f for _, f in BAD])
def test_bad_input_raises_naming_the_field(call, field):
    with pytest.raises(eqhb.InputError) as error:
        call()
    assert field in str(error.value)
    assert isinstance(error.value, ValueError)


def test_a_sweep_point_lost_past_a_fold_is_found_by_the_fallback_chain():
    # Duffing's upper branch ends at its fold: from the previous point the
    # dogleg stalls; the default path's cold start finds the lower branch.
    duffing = eqhb.load_scene(PROBLEMS / "duffing.toml")
    plain = eqhb.sweep(duffing, fallback="none")
    assert not plain["complete"] and plain["failed_points"] > 0
    rescued = eqhb.sweep(duffing)
    assert rescued["complete"] and rescued["failed_points"] == 0 and rescued["failed"] == []
    assert "cold" in rescued["fallback"]
    # The lost points are listed apart, not as NaN rows: the arrays hold the
    # converged points, and with the failed ones they make the whole grid.
    failed = plain["failed"]
    assert len(failed) == plain["failed_points"]
    assert plain["converged"].all() and np.isfinite(plain["max_abs"]).all() and np.isfinite(plain["x_cos"]).all()
    assert all(f["termination"] and f["termination"] != "converged" and f["iterations"] > 0 for f in failed)
    np.testing.assert_allclose(np.sort(np.concatenate([plain["omega"], [f["omega"] for f in failed]])),
                               rescued["omega"], atol=1e-12)
    kept = np.isin(rescued["omega"], plain["omega"])
    assert all(step == "" for step in np.asarray(rescued["fallback"])[kept])


def test_a_failed_solve_reports_each_fallback_attempt():
    cubic = eqhb.load_scene(PROBLEMS / "cubic.toml")
    alone = eqhb.solve(cubic, 0.8, fallback="none")
    assert not alone["converged"] and "fallback" not in alone
    chained = eqhb.solve(cubic, 0.8, fallback="full,dogleg-newton")
    assert [a["step"] for a in chained["fallback"]["attempts"]] == ["full", "dogleg-newton"]
    assert chained["converged"] == (chained["fallback"]["taken"] is not None)
    with pytest.raises(eqhb.InputError, match="fallback = cold,nope: has an unknown step nope"):
        eqhb.solve(cubic, 0.8, fallback="cold,nope")



def test_a_solve_below_a_hardening_peak_is_found_by_continuation_in_omega():
    # penalty-contact at omega = 0.7: every step of the default path before
    # "omega" stalls; continuation in omega reaches the sweep's point there.
    penalty = eqhb.load_scene(PROBLEMS / "penalty-contact.toml")
    without = eqhb.solve(penalty, 0.7, fallback="cold,full,condensed,forcing")
    assert not without["converged"]
    rescued = eqhb.solve(penalty, 0.7)
    assert rescued["converged"] and rescued["fallback"]["taken"] == "omega"
    assert "from omega = " in rescued["fallback"]["attempts"][-1]["note"]
    curve = eqhb.sweep(penalty, 0.3, 0.7, step=0.004)
    assert curve["complete"] and abs(curve["omega"][-1] - 0.7) < 1e-12
    np.testing.assert_allclose(rescued["solution"]["max_abs_x"], curve["max_abs"][-1], rtol=1e-8)

def test_an_element_between_two_nodes_acts_equally_and_oppositely():
    # Four identical DOFs on unit springs to the ground, grouped in two 2-DOF
    # nodes, a cubic spring between them along n = (0.6, 0.8): node 2 feels
    # -n lambda where node 1 feels +n lambda.
    k = np.eye(4)
    law = {"type": "cubic", "between": [1, 2], "normal": [0.6, 0.8], "epsilon": 0.5}
    m = eqhb.model(np.eye(4), k, 0.05 * k, laws=[law], forcing=[{"dof": 1, "cos": 0.2}, {"dof": 2, "cos": 0.1}],
                   harmonics=5, omega=0.9, node_table=[[1, 2], [3, 4]])
    r = eqhb.solve(m)
    assert r["converged"]
    for part in ("x_cos", "x_sin"):
        x = np.array(r["solution"][part])  # dofs x harmonics (1, 3, 5, ...)
        assert np.abs(0.8 * x[2] - 0.6 * x[3]).max() < 1e-9  # unloaded node 2 moves along n
        assert np.abs(x[:2, 1:] + x[2:, 1:]).max() < 1e-9  # above harmonic 1 (no load): opposite
    assert np.abs(np.array(r["solution"]["x_cos"])[2:, 1:]).max() > 1e-6  # the spring acts there
    reads = r["laws"][0]["components"][0]["reads"]
    assert [(d["dof"], d["weight"]) for d in reads] == [(1, 0.6), (2, 0.8), (3, -0.6), (4, -0.8)]
    with pytest.raises(eqhb.InputError, match=r"law\[0\]\.normal = \[0, 0\]: must be a nonzero"):
        eqhb.model(np.eye(4), k, laws=[dict(law, normal=[0.0, 0.0])], node_table=[[1, 2], [3, 4]])


def test_a_preload_is_solved_statically_first_and_reported():
    # Two unit masses on springs K = [[2, -1], [-1, 2]], DOF 1 against a wall
    # at gap 0. Pressed into it by 2 N the contact closes and carries all of
    # it (x = 0, normal force 2); pulled away by 2 N it opens by K⁻¹₁₁ 2 = 4/3.
    k = np.array([[2.0, -1.0], [-1.0, 2.0]])
    wall = [{"type": "signorini", "dofs": [1], "gap": 0.0}]
    states = {}
    for force in (2.0, -2.0):
        m = eqhb.model(np.eye(2), k, 0.05 * k, laws=wall, forcing=[{"dof": 2, "cos": 0.3}],
                       preload=[{"dof": 1, "force": force}], harmonics=3, harmonic_set="all", omega=0.5)
        r = eqhb.solve(m)
        assert r["converged"] and r["preload"]["converged"]
        states[force] = r["preload"]["elements"][0]
    assert states[2.0]["state"] == "closed" and abs(states[2.0]["normal_force"] - 2.0) < 1e-9
    assert states[-2.0]["state"] == "open" and abs(states[-2.0]["gap"] - 4.0 / 3.0) < 1e-9
    with pytest.raises(eqhb.InputError, match=r"preload\[0\]\.force = nan: must be finite"):
        eqhb.model(np.eye(2), k, preload=[{"dof": 1, "force": float("nan")}])
    with pytest.raises(eqhb.InputError, match=r"preload\[0\]\.dof = 3: no such DOF"):
        eqhb.solve(eqhb.model(np.eye(2), k, preload=[{"dof": 3, "force": 1.0}]))
