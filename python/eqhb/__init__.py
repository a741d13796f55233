"""eqhb: periodic vibrations of structures with dry friction and unilateral
contact by an equality-based harmonic balance.

    import eqhb
    model = eqhb.load_scene("problems/friction-1d.toml")
    result = eqhb.solve(model, omega=0.4, solver="dogleg")
    curve = eqhb.sweep(model, 0.1, 0.8, step=0.005)
    reference = eqhb.simulate(model, omega=0.3, step=1e-3)
    orbit = eqhb.shoot(model, omega=0.3)                   # exact orbit, Floquet multipliers
    errors = eqhb.compare(model, omega=0.3)                # harmonic balance against the reference

A model comes from a scene file (`load_scene`) or from arrays (`model`: numpy
or scipy.sparse M, C, K, laws and loads as dicts with the scene file's keys).
Results are plain dicts of numpy arrays and numbers. Bad input raises
`eqhb.InputError` (a ValueError) whose message names the field.
"""
import math
import numbers
import os

from ._eqhb import InputError, Model, __version__, solvers
from ._eqhb import _compare, _modes, _shoot, _simulate, _solve, _stability, _study, _sweep

__all__ = ["InputError", "Model", "__version__", "compare", "load_scene", "model", "modes", "shoot", "simulate", "solve", "solvers", "stability",
           "study", "sweep"]


def load_scene(path, overrides=None):
    """The model of a scene file (a .toml file, as in problems/). `overrides` maps a dotted
    path to a value, as `eqhb --set`: {"law[0].muN": 5, "harmonic_balance.omega": 0.3}."""
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"path = {path!r}: must be a file path (str or pathlib.Path)")
    overrides = _dict(overrides, "overrides")
    return Model.from_scene(os.fspath(path), [f"{_text(k, 'overrides')}={_toml_value(v, k)}" for k, v in overrides.items()])


def model(mass, stiffness, damping=None, *, laws=(), forcing=(), preload=(), harmonics=10, harmonic_set="odd",
          samples=None, omega=1.0, sweep=None, name="model", node_table=None):
    """A model from arrays.

    mass, stiffness, damping: n x n numpy arrays or scipy.sparse matrices
    (damping None: no damping).

    laws: dicts with the scene file's keys, DOFs numbered from 1, e.g.
    {"type": "coulomb-1d", "dofs": [2], "muN": 7.2}, or an element between
    two nodes: {"type": "cubic", "between": [1, 2], "epsilon": 0.1} (with
    "normal" and "tangents" on nodes of several DOFs).

    forcing: dicts {"dof": 1, "harmonic": 1, "cos": 20.0, "sin": 0.0}.

    preload: static loads, dicts {"dof": 1, "force": -500.0} (or "node"
    with a node_table), as a scene's [[preload]] tables: the static state
    under them is solved first and harmonic balance runs about it.

    harmonics, harmonic_set ("odd" or "all"), samples (default: a power of
    two >= 4 (2 k_max + 1), at least 64), omega: the harmonic-balance settings.

    sweep: an optional (start, stop) frequency range used by `sweep`.

    node_table: node i's DOFs (from 1) per row, e.g. [[1, 2, 3], [4, 5, 6]],
    for elements that name nodes; without it a node is a DOF.
    """
    dofs = _square_size(mass, "mass")
    if isinstance(harmonics, bool) or not isinstance(harmonics, numbers.Integral):
        raise InputError(f"harmonics = {harmonics!r}: must be an integer")
    if samples is None:
        k_max = 2 * int(harmonics) - 1 if harmonic_set == "odd" else int(harmonics)
        samples = max(64, 1 << math.ceil(math.log2(4 * (2 * max(k_max, 0) + 1))))
    lines = [f"name = {_toml_value(name, 'name')}", "", "[structure]", 'type = "chain"', f"dofs = {dofs}",
             "m = 1.0", "k = 1.0", "d = 0.0"]
    if node_table is not None:
        lines.append(f"node_table = {_toml_value(node_table, 'node_table')}")
    for i, load in enumerate(_sequence(forcing, "forcing")):
        lines += ["", "[[forcing]]"] + _toml_table(load, f"forcing[{i}]")
    for i, load in enumerate(_sequence(preload, "preload")):
        lines += ["", "[[preload]]"] + _toml_table(load, f"preload[{i}]")
    for i, law in enumerate(_sequence(laws, "laws")):
        lines += ["", "[[law]]"] + _toml_table(law, f"law[{i}]")
    settings = {"harmonics": harmonics, "set": harmonic_set, "samples": samples, "omega": omega}
    lines += ["", "[harmonic_balance]"] + _toml_table(settings, "harmonic_balance")
    if sweep is not None:
        try:
            start, stop = sweep
        except (TypeError, ValueError):
            raise InputError(f"sweep = {sweep!r}: must be a pair (start, stop)") from None
        lines += ["", "[sweep]"] + _toml_table({"from": start, "to": stop}, "sweep")
    return Model._from_arrays("\n".join(lines) + "\n", mass, stiffness, damping)


def solve(model, omega=None, *, harmonics=None, samples=None, form=None, rho=None, formulation=None, solver="dogleg",
          system="condensed", tolerance=1e-10, max_iterations=1000, max_evaluations=10000, time_limit=0.0,
          options=None, linear_algebra="auto", initial=None, cold_start="coarse", fallback="default",
          from_harmonics=None, repeat=1, stability=False, stability_method="auto", stability_time_limit=0.0,
          error_estimate=False,
          accuracy=None, max_harmonics=320, accuracy_test="auto", refine=None, restitution=1.0, refine_harmonics=None,
          show=None):
    """One harmonic-balance solve, as `eqhb solve` runs it. Returns a dict
    with every key of `eqhb solve --json` (converged, termination, iterations,
    residual/jacobian evaluations, residual_norm, seconds, cold_start,
    fallback, "dofs" and "laws", invariants, ...) and "solution" (harmonics,
    x_cos/x_sin and lambda_cos/lambda_sin per channel, one period sampled: t,
    x, lambda; max_abs_x, and "full", the coefficient vector to pass as
    `initial` to a later solve). Each of "dofs" has its number from 1
    ("dof") and name ("name": "x1", a beam's "w1", "theta1"); "shown" names
    the DOFs the outputs show: show (DOF numbers from 1 or names, as
    `eqhb --show`), else the model's [output] dofs, else its default (a few
    deflections on beams, four DOFs spread over a model of more than 8).

    The start: `initial` (a "full" vector), else the solutions at
    from_harmonics, 2 from_harmonics, ... below H (continuation in H), else a
    coarse harmonic balance (about H/3 harmonics on few samples;
    cold_start="zero": from zero). A solve that fails gets the `fallback`
    steps in order ("cold", "full", "condensed", "forcing", "omega", a backend
    name; comma-separated, or "none"; "default": cold, full, condensed, then
    Ipopt's least squares, else ceres-lm, then forcing: the dynamic loads
    raised from a quarter to the whole, each solve from the last, then omega:
    continuation in omega from omega/2 up, else from 2 omega down; each
    attempt's "note" says where it started).
    form and rho apply to every law that has them, and formulation
    ("equality" or "aft": the force in time from the displacement, projected)
    to every law that has that formulation. linear_algebra: "auto",
    "dense" or "sparse". repeat: solves timed (the median is "seconds").

    On the answer: stability (Floquet multipliers: the "stability" dict, as
    eqhb.stability; stability_method "hill", "monodromy" (grounded Coulomb
    1D and Signorini laws: the monodromy over the solution with saltation at
    the switching instants; above 20 DOFs on the law DOFs and the slow or
    weakly damped modes), "shooting" (grounded laws with an exact flow: the
    exact multipliers of the periodic orbit shot from the solution, which do
    not depend on H; where shooting fails or reaches another orbit the
    monodromy, else Hill, answers and the dict's "note" says why) or "auto"
    (the default: the monodromy where it applies, else Hill)), error_estimate (one more solve at
    2H: "error_estimate"), accuracy (a relative error in (0, 1): the cheapest
    H, doubling from `harmonics` or 5 up to max_harmonics, and unless rho is
    given the rho among each law's times 1, 0.1, 0.01, whose error of max|x|
    is <= accuracy: "accuracy" and "rho"; accuracy_test "auto" tests each H
    against the exact orbit shot from it where every law has an exact flow
    and the structure has at most 12 DOFs, else, and with "estimate", by the
    error estimate times its safety factor; "accuracy" names the test that
    decided, "test", and its value, "error"), refine="shoot" (the exact
    periodic orbit replaces the answer, on refine_harmonics harmonics if
    given, restitution e of contact laws: "refinement")."""
    args = _scene_args(omega, harmonics, samples, form, rho, formulation)
    args.update(_hb_args(solver, system, tolerance, max_iterations, max_evaluations, time_limit, options,
                         linear_algebra, cold_start, fallback))
    args.update(initial=_vector(initial, "initial"), from_harmonics=_integer(from_harmonics, "from_harmonics", True),
                repeat=_integer(repeat, "repeat"), stability=_flag(stability, "stability"),
                stability_method=_text(stability_method, "stability_method"),
                stability_time_limit=_real(stability_time_limit, "stability_time_limit"),
                error_estimate=_flag(error_estimate, "error_estimate"), accuracy=_real(accuracy, "accuracy", True),
                max_harmonics=_integer(max_harmonics, "max_harmonics"),
                accuracy_test=_text(accuracy_test, "accuracy_test"),
                refine=None if refine is None else _text(refine, "refine"), restitution=_real(restitution, "restitution"),
                refine_harmonics=_integer(refine_harmonics, "refine_harmonics", True), show=_dofs(show, "show"))
    return _solve(_model(model), args)


def stability(model, solution, *, omega=None, harmonics=None, samples=None):
    """Stability of a harmonic-balance solution by Hill's method on the full
    system's weak Jacobian. `solution` is what solve returned (its omega is
    used), its "solution" dict, or the "full" coefficient vector; give the
    harmonics/samples (and omega) it was solved with. Returns a dict: stable,
    spectral_radius, multipliers and exponents (complex, largest modulus
    first), pencil_size, seconds, failure (empty when computed)."""
    if isinstance(solution, dict) and "solution" in solution:
        omega = solution.get("omega") if omega is None else omega
        solution = solution["solution"]
    if isinstance(solution, dict):
        if "full" not in solution:
            raise InputError("solution: a dict must be what solve returned or its \"solution\" (it has no \"full\")")
        solution = solution["full"]
    return _stability(_model(model), _vector(solution, "solution"), _real(omega, "omega", True),
                      _integer(harmonics, "harmonics", True), _integer(samples, "samples", True))


def sweep(model, start=None, stop=None, *, step=None, method="sequential", harmonics=None, samples=None, form=None,
          rho=None, formulation=None, solver="dogleg", system="condensed", tolerance=1e-10, max_iterations=1000, max_evaluations=10000,
          time_limit=0.0, options=None, linear_algebra="auto", max_points=20000, fallback="default", min_step=None,
          max_step=None, stability=False, stability_method="auto", stability_time_limit=0.0, error_estimate=False,
          accuracy=None, curve_time_limit=0.0, progress=None,
          max_harmonics=320, accuracy_test="auto", peak_dof=None, show=None):
    """A frequency-response curve by continuation in omega, as `eqhb sweep`
    runs it ("sequential" on a grid of `step`, by default a hundredth of the
    range, or "arclength", which passes turning points, from a scaled step
    of 0.01). start and stop default to the model's sweep range; min_step
    (default min(1e-6, step)) and max_step (arclength, default max(0.1,
    step)) bound the step; curve_time_limit (seconds, 0 none) bounds the
    whole sweep: the curve stops between two points, keeping those found
    (complete False, stop_reason saying where), and stability gets what is
    left. progress, a callable, is told of each point as it is found
    (a dict: index, omega, converged); if it raises, the sweep stops and the
    exception propagates. Ctrl-C (KeyboardInterrupt) stops the curve between
    two points and returns those found (complete False, the stop reason
    "stopped on request"), as SIGINT does to `eqhb sweep`. Returns a dict of arrays over the converged
    points: omega, converged, max_abs (points x dofs), first_harmonic,
    energy, fold, x_cos/x_sin (points x dofs x harmonics), and folds,
    stop_reason, complete, failed_points, seconds and the settings of `eqhb
    sweep --json` (scene, solver, method, from, to, step, system,
    harmonic_set, samples), "dof_labels" (each DOF's name, the columns of
    max_abs: "x1", ..., a beam's "w1", "theta1", ...) and "peak_dof" (the
    label of the DOF whose maximum defines the peak: peak_dof, by number from
    1 or name, else the model's [output] peak, on a beam its tip deflection,
    else the last DOF) and "shown" (the labels of the DOFs `eqhb sweep`'s CSV
    and chart show: show, as solve's, else the model's choice; the arrays
    keep every DOF); "fallback" per point names the step that
    converged a point that failed from the previous one (see solve). The
    grid points that did not converge are in "failed", a list of dicts
    (omega, termination, iterations, residual_evaluations,
    jacobian_evaluations, residual_norm, seconds), never rows of NaN.

    On the points: stability (stability_method at every converged point,
    "hill", "monodromy", "shooting" or "auto" as for solve; stability_time_limit seconds
    for the whole curve, 0 none: the points not reached have None, and
    "stability_time_limited" and "stability_points_analysed" say so:
    per point "stable", "spectral_radius", "multipliers" (the leading four,
    complex), "stability_method" (who answered), "stability_note" (why not
    the method asked, if so) and "bifurcation"; "bifurcations", a list of dicts omega, kind,
    point; the folds confirmed by the multipliers), error_estimate (one more
    solve at 2H per point: "error_estimate"), accuracy (a relative error in
    (0, 1): H, and rho unless given, chosen at the first point as solve
    does, raised per point up to max_harmonics where its test (accuracy_test,
    as solve's) fails: per point "error_estimate", "point_harmonics",
    "point_samples", "accuracy_met", "accuracy_seconds", "accuracy_failure",
    "accuracy_test", "accuracy_error", and "accuracy" and "rho"). Per-point lists hold None where a point has no value.
    form and rho apply to every law that has them."""
    args = _scene_args(None, harmonics, samples, form, rho, formulation)
    args.update(_hb_args(solver, system, tolerance, max_iterations, max_evaluations, time_limit, options,
                         linear_algebra, "coarse", fallback))
    args.update(start=_real(start, "start", True), stop=_real(stop, "stop", True), step=_real(step, "step", True),
                method=_text(method, "method"), max_points=_integer(max_points, "max_points"),
                curve_time_limit=_real(curve_time_limit, "curve_time_limit"),
                progress=_callable(progress, "progress"),
                min_step=_real(min_step, "min_step", True), max_step=_real(max_step, "max_step", True),
                stability=_flag(stability, "stability"), stability_method=_text(stability_method, "stability_method"),
                stability_time_limit=_real(stability_time_limit, "stability_time_limit"),
                error_estimate=_flag(error_estimate, "error_estimate"),
                accuracy=_real(accuracy, "accuracy", True), max_harmonics=_integer(max_harmonics, "max_harmonics"),
                accuracy_test=_text(accuracy_test, "accuracy_test"), peak_dof=_dof(peak_dof, "peak_dof"), show=_dofs(show, "show"))
    return _sweep(_model(model), args)


def study(model, vary, *, out, mode="peak", lhs=None, seed=1, start=None, stop=None, step=0.01, dof=1,
          coarse_points=41, max_peaks=4, threads=0, harmonics=None, samples=None, form=None, rho=None, formulation=None,
          solver="dogleg", system="condensed", tolerance=1e-10, max_iterations=1000, max_evaluations=10000,
          time_limit=0.0, options=None, linear_algebra="auto", fallback="default", show=None):
    """A parameter study, as `eqhb study` runs it on threads: over a grid of
    the scene values `vary` ("PATH=FROM:TO:COUNT" strings, PATH as for
    load_scene's overrides, or "A,B,..." set together) or, with lhs=N, a
    Latin hypercube of N samples ("PATH=FROM:TO", reproducible from seed),
    each sample's resonance peak (mode="peak": the first-harmonic amplitude
    of DOF `dof`, by number from 1 or name ("w60"), tracked from sample to sample, up to max_peaks
    resonances, a cold start from a sweep of coarse_points) or frequency
    response (mode="sweep", a grid of `step` in omega) over [start, stop]
    (default: the model's sweep range). The model must come from a scene
    file (load_scene): samples reload it. `out` is the study folder
    (study.csv, study.json, journal.csv, plan.txt; a folder of the same
    study is resumed, its samples not computed again). A failed point of a
    sample's sweeps gets the `fallback` steps, as in sweep. Returns study.json
    as a dict (scene, mode, dof, dof_label, dof_labels, shown: the DOFs of
    study.csv's columns, show as solve's, and `dof`; range, parameters, samples: per sample its
    values, status, reason, start, peak_omega, first_harmonic, max_abs,
    peaks, solves, iterations, seconds, worker, curve) with total,
    computed, failed, succeeded, seconds and threads of this run."""
    if isinstance(vary, str):
        vary = [vary]
    args = _scene_args(None, harmonics, samples, form, rho, formulation)
    args.update(_hb_args(solver, system, tolerance, max_iterations, max_evaluations, time_limit, options,
                         linear_algebra, "coarse", fallback))
    if not isinstance(vary, (list, tuple)):
        raise InputError(f"vary = {vary!r}: must be a string or a list of strings")
    args.update(vary=[_text(v, "vary") for v in vary], out=_text(out, "out"),
                mode=_text(mode, "mode"), lhs=_integer(lhs, "lhs", True), seed=_integer(seed, "seed"),
                start=_real(start, "start", True), stop=_real(stop, "stop", True), step=_real(step, "step"),
                dof=_dof(dof, "dof"), show=_dofs(show, "show"), coarse_points=_integer(coarse_points, "coarse_points"),
                max_peaks=_integer(max_peaks, "max_peaks"), threads=_integer(threads, "threads"))
    if args["seed"] < 0:
        raise InputError(f"seed = {seed!r}: must be >= 0")
    return _study(_model(model), args)


def simulate(model, omega=None, *, step=None, periods=None, theta=None, periodic_tolerance=None, max_seconds=0.0,
             restitution=0.0, initial=None, from_hb=False, harmonics=None, samples=None, form=None, rho=None,
             formulation=None,
             solver="dogleg", system="condensed", tolerance=1e-10, max_iterations=1000, max_evaluations=10000,
             time_limit=0.0, options=None, linear_algebra="auto", cold_start="coarse", fallback="default"):
    """The time-domain reference, as `eqhb simulate`: Moreau-Jean integration
    to the periodic steady state. step, periods, theta and
    periodic_tolerance left None take the scene's [time_reference], else
    1e-4, 5000, 0.5 and 1e-9; max_seconds stops an unsettled run (0: none).
    It starts from rest, from `initial` (a "full" vector) or, with from_hb,
    from the harmonic-balance solution (solved as by solve, with the solver
    arguments). Returns periodic, timed_out, periods, step, steps_per_period,
    periodicity_error, seconds, the last period (t, x, v, lambda: one row per
    DOF or law component), max_abs_x, "dofs" and "law_forces" (as `eqhb
    simulate --json`) and the Fourier "coefficients"."""
    args = _scene_args(omega, harmonics, samples, form, rho, formulation)
    args.update(_time_args(step, periods, theta, periodic_tolerance, max_seconds, restitution))
    args.update(_hb_args(solver, system, tolerance, max_iterations, max_evaluations, time_limit, options,
                         linear_algebra, cold_start, fallback))
    args.update(initial=_vector(initial, "initial"), from_hb=_flag(from_hb, "from_hb"))
    return _simulate(_model(model), args)


def compare(model, omega=None, *, harmonics=None, samples=None, form=None, rho=None, formulation=None, step=None,
            periods=None,
            theta=None, periodic_tolerance=None, max_seconds=0.0, restitution=0.0, from_rest=False,
            solver="dogleg", system="condensed", tolerance=1e-10, max_iterations=1000, max_evaluations=10000,
            time_limit=0.0, options=None, linear_algebra="auto", cold_start="coarse", fallback="default"):
    """A harmonic-balance solve against the time-domain reference started
    from it (from rest with from_rest), as `eqhb compare`. Returns scene,
    omega, harmonics, "hb" (converged, termination, residual_norm, seconds,
    solver), "solution" (as solve's), "reference" (as simulate's) and
    "errors": per channel (x1.., law1.lambda..) relative_l2,
    relative_l2_velocity, relative_max_abs, first_harmonic_error, max_abs_hb,
    max_abs_reference. The time settings are simulate's."""
    args = _scene_args(omega, harmonics, samples, form, rho, formulation)
    args.update(_time_args(step, periods, theta, periodic_tolerance, max_seconds, restitution))
    args.update(_hb_args(solver, system, tolerance, max_iterations, max_evaluations, time_limit, options,
                         linear_algebra, cold_start, fallback))
    args.update(from_rest=_flag(from_rest, "from_rest"))
    return _compare(_model(model), args)


def shoot(model, omega=None, *, harmonics=None, samples=None, form=None, rho=None, formulation=None, from_hb=None,
          solver="dogleg",
          fallback="default", restitution=1.0, tolerance=1e-11, max_iterations=40, time_limit=0.0):
    """The exact periodic orbit by shooting, as `eqhb shoot` (Coulomb 1D,
    Jenkins on one DOF and Signorini laws in closed form, cubic, planar
    Coulomb with stick-slip and Stribeck by Gauss-Legendre phases with
    located events; Newton on the period map with saltation matrices),
    started from the harmonic-balance solution of the scene (solved as by
    solve: coarse start, `fallback` steps; at from_hb harmonics if given).
    Returns converged, failure, period_residual, tolerance, iterations,
    flow_evaluations, state (y(t0) = [x; v]), monodromy, multipliers
    (complex, largest modulus first), spectral_radius, stable (these three
    None when no orbit was found), events per period, max_abs_x, "dofs",
    "from_hb" (the start's solver report, harmonics, cold_start), and one
    period sampled (t, x, v, lambda: one row per DOF or law component,
    lambda_labels). tolerance and max_iterations are shooting's (relative
    period residual, Newton steps). time_limit: seconds for the whole call
    (0: none); shooting that runs out of it returns converged False, a
    harmonic-balance start that does raises."""
    args = _scene_args(omega, harmonics, samples, form, rho, formulation)
    args.update(_hb_args(solver, "condensed", 1e-10, 1000, 10000, time_limit, None, "auto", "coarse", fallback))
    args.update(from_hb=_integer(from_hb, "from_hb", True), restitution=_real(restitution, "restitution"),
                shooting_tolerance=_real(tolerance, "tolerance"),
                shooting_max_iterations=_integer(max_iterations, "max_iterations"))
    return _shoot(_model(model), args)


def modes(model, mode=1, *, branch="auto", start=None, stop=None, points=50, harmonics=None, samples=None, form=None, rho=None,
          formulation=None,
          solver="dogleg", system="full", tolerance=1e-10, max_iterations=1000, max_evaluations=10000, time_limit=0.0,
          options=None, linear_algebra="auto", backbone_time_limit=0.0, synthesis=False):
    """The nonlinear mode `mode` (K, from 1, of the structure linearised about
    rest) by the extended periodic motion concept, as `eqhb modes`. `branch`
    ("auto", "held", "sliding", as `eqhb modes --branch`): held starts from
    the structure with sticking friction holding its DOFs and goes up in
    amplitude; sliding starts from the structure without its laws at `stop`
    and goes down; auto is sliding when the scene's sweep range holds the
    free mode K and not the held one. The held branch is: the
    unforced structure with an added damping -xi M x' that makes the motion
    periodic, continued in pseudo-arclength (past the folds where it turns
    back in amplitude) and reported at `points` modal amplitudes phi^T M x1
    evenly spaced in log from `start` to `stop` (`eqhb modes --from/--to`;
    None: 1e-2 and 1e3 of the slip onset, else of the scene's length scale;
    about a preload, `stop` no further than where a pressed contact would
    open on the linear mode, nor below 10 times the onset),
    at every crossing of the path in its order; a preloaded scene's mode is
    taken about its static state. Returns the keys of `eqhb modes --json`:
    mode, from, to, linear_mode (omega, damping_ratio, shape), complete,
    failed_points, folds (amplitude, omega, damping_ratio at each turn),
    stop (None, or why and where the path stopped), seconds and points, each
    with amplitude, omega,
    xi, damping_ratio (xi / 2 omega), dissipated_energy (per cycle), max_abs
    (per DOF), the solve's counts and "channels" (every DOF's and law
    force's Fourier coefficients). `time_limit` bounds each solve,
    `backbone_time_limit` the whole backbone (0: none): the path stops there,
    saying so in `stop`, and the amplitudes not reached are failed points.
    With `synthesis`, the key "synthesis" also holds the forced response the
    mode predicts under the scene's forcing (`eqhb modes --synthesis`): its
    points (omega, amplitude, branch, max_abs), peak, and the forced sweep
    across that resonance (forced) with their differences (errors).
    `system` ("full" or "condensed", as `eqhb modes --condensed`): the
    condensed mode system has the law forces alone as unknowns and factors
    every A_k at each new (omega, xi); it needs a law and a regular K."""
    start, stop = _real(start, "start", True), _real(stop, "stop", True)
    for value, field in ((start, "start"), (stop, "stop")):
        if value is not None and not (math.isfinite(value) and value > 0.0):
            raise InputError(f"{field} = {value!r}: must be finite and > 0 (a modal amplitude)")
    if start is not None and stop is not None and not stop > start:
        raise InputError(f"stop = {stop!r}: must be > start ({start!r})")
    args = _scene_args(None, harmonics, samples, form, rho, formulation)
    args.update(mode=_integer(mode, "mode"), branch=_text(branch, "branch"), points=_integer(points, "points"), **{"from": start, "to": stop},
                backbone_time_limit=_real(backbone_time_limit, "backbone_time_limit"),
                synthesis=_flag(synthesis, "synthesis"))
    args.update(_hb_args(solver, system, tolerance, max_iterations, max_evaluations, time_limit, options,
                         linear_algebra, "coarse", "none"))
    return _modes(_model(model), args)


def _scene_args(omega, harmonics, samples, form, rho, formulation):
    return {"omega": _real(omega, "omega", True), "harmonics": _integer(harmonics, "harmonics", True),
            "samples": _integer(samples, "samples", True), "form": None if form is None else _text(form, "form"),
            "rho": _real(rho, "rho", True),
            "formulation": None if formulation is None else _text(formulation, "formulation")}


def _hb_args(solver, system, tolerance, max_iterations, max_evaluations, time_limit, options, linear_algebra,
             cold_start, fallback):
    return {"solver": _text(solver, "solver"), "system": _text(system, "system"),
            "tolerance": _real(tolerance, "tolerance"), "max_iterations": _integer(max_iterations, "max_iterations"),
            "max_evaluations": _integer(max_evaluations, "max_evaluations"),
            "time_limit": _real(time_limit, "time_limit"), "options": _options(options),
            "linear_algebra": _text(linear_algebra, "linear_algebra"), "cold_start": _text(cold_start, "cold_start"),
            "fallback": _text(fallback, "fallback")}


def _time_args(step, periods, theta, periodic_tolerance, max_seconds, restitution):
    return {"step": _real(step, "step", True), "periods": _integer(periods, "periods", True),
            "theta": _real(theta, "theta", True),
            "periodic_tolerance": _real(periodic_tolerance, "periodic_tolerance", True),
            "max_seconds": _real(max_seconds, "max_seconds"), "restitution": _real(restitution, "restitution")}


def _flag(value, field):
    if not isinstance(value, bool):
        raise InputError(f"{field} = {value!r}: must be True or False")
    return value


def _square_size(matrix, field):
    shape = getattr(matrix, "shape", None)
    if shape is None or len(shape) != 2:
        raise InputError(f"{field}: must be a 2-D numpy array or a scipy.sparse matrix")
    if shape[0] != shape[1] or shape[0] < 1:
        raise InputError(f"{field}: must be square and non-empty (got {shape[0]} x {shape[1]})")
    return int(shape[0])


# The arguments' types are checked here so that a wrong one raises
# InputError naming it, not the binding's TypeError listing signatures.

def _model(value):
    if not isinstance(value, Model):
        raise InputError(f"model: must be an eqhb.Model (from load_scene or model), not {type(value).__name__}")
    return value


def _real(value, field, optional=False):
    if value is None and optional:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"{field} = {value!r}: must be a real number")
    return float(value)


def _callable(value, field):
    if value is not None and not callable(value):
        raise InputError(f"{field} = {value!r}: must be callable (told of each point) or None")
    return value


_INT_RANGE = (-2**31, 2**31 - 1)  # the C++ int the bindings take


def _integer(value, field, optional=False):
    if value is None and optional:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InputError(f"{field} = {value!r}: must be an integer")
    if not _INT_RANGE[0] <= int(value) <= _INT_RANGE[1]:
        raise InputError(f"{field} = {value!r}: out of range of a 32-bit integer")
    return int(value)


def _dof(value, field):
    """A DOF by number from 1 or name ("w60"), as text; None stays None."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, str)):
        raise InputError(f"{field} = {value!r}: must be a DOF number (from 1) or name such as \"w60\"")
    return str(value)


def _dofs(value, field):
    """DOFs by number from 1 or name: one, or a list of them; None stays None."""
    if value is None:
        return None
    if isinstance(value, (str, numbers.Integral)) and not isinstance(value, bool):
        return [_dof(value, field)]
    if not isinstance(value, (list, tuple)):
        raise InputError(f"{field} = {value!r}: must be a DOF number (from 1) or name, or a list of them")
    return [_dof(v, f"{field}[{i}]") for i, v in enumerate(value)]


def _text(value, field):
    if not isinstance(value, str):
        raise InputError(f"{field} = {value!r}: must be a string")
    return value


def _dict(value, field):
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise InputError(f"{field} = {value!r}: must be a dict")
    return value


def _sequence(value, field):
    if not isinstance(value, (list, tuple)):
        raise InputError(f"{field} = {value!r}: must be a list of dicts")
    return value


def _options(options):
    if options is None:
        return {}
    if not isinstance(options, dict):
        raise InputError(f"options = {options!r}: must be a dict NAME -> value")
    return {str(k): str(v) for k, v in options.items()}


def _vector(values, field):
    """A 1-D float array; complex, boolean, string and object arrays are
    refused rather than cast (a cast would drop the imaginary part or parse
    text)."""
    if values is None:
        return None
    import numpy

    try:
        array = numpy.asarray(values)
    except ValueError:
        raise InputError(f"{field}: must be a 1-D array of real numbers (got a ragged sequence)") from None
    if array.dtype.kind not in "fiu":
        raise InputError(f"{field}: must be real numbers, not dtype {array.dtype}")
    if array.ndim != 1:
        raise InputError(f"{field}: must be a 1-D array (got {array.ndim}-D)")
    return array.astype(float)


def _toml_table(entries, field):
    if not isinstance(entries, dict):
        raise InputError(f"{field} = {entries!r}: must be a dict")
    lines = []
    for key, value in entries.items():
        if not isinstance(key, str) or not key.replace("_", "").isalnum():
            raise InputError(f"{field}: key {key!r} must be a name of letters, digits and '_'")
        lines.append(f"{key} = {_toml_value(value, f'{field}.{key}')}")
    return lines


def _toml_value(value, field):
    """One value in TOML; numpy scalars and arrays are accepted."""
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"')
        if any(ord(c) < 32 for c in escaped):
            raise InputError(f"{field} = {value!r}: control characters are not allowed")
        return f'"{escaped}"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v, f"{field}[{i}]") for i, v in enumerate(value)) + "]"
    raise InputError(f"{field} = {value!r}: must be a number, a string, a boolean or a list of them")
