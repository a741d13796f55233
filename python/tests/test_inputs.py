"""Inputs that must neither crash nor mislead: scipy.sparse matrices in
every legal layout (duplicates, unsorted indices) mean the matrix scipy
means; corrupt ones, non-real arrays, oversized arrays and arguments of the
wrong type raise eqhb.InputError naming the argument."""
import os
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest
import scipy.sparse

import eqhb

# friction-1d as arrays (see test_eqhb.py).
K = np.array([[2.0, -1.0], [-1.0, 1.0]])
M = np.eye(2)
LAWS = [{"type": "coulomb-1d", "dofs": [2], "muN": 7.2, "form": "minmax", "rho": 1.0}]
FORCING = [{"dof": 1, "harmonic": 1, "cos": 20.0}]


def friction_model(stiffness, mass=M):
    return eqhb.model(mass, stiffness, 0.02 * K, laws=LAWS, forcing=FORCING, harmonics=10, samples=1024, omega=0.4)


def max_x2(stiffness):
    result = eqhb.solve(friction_model(stiffness))
    assert result["converged"]
    return result["solution"]["max_abs_x"][1]


def run_isolated(code, timeout=60):
    """Runs `code` in a fresh interpreter (a crash there cannot take pytest
    down) and returns it; the caller checks returncode and output."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          timeout=timeout)


# K = [[2, -1], [-1, 1]] with K[0, 0] stored as 1 + 1 and K[0, 1] as -1 after K[1, 1].
DUPLICATES_CSC = scipy.sparse.csc_matrix(([1.0, 1.0, -1.0, -1.0, 1.0], [0, 0, 1, 0, 1], [0, 3, 5]), shape=(2, 2))


def test_duplicate_entries_are_summed_as_scipy_does():
    assert not DUPLICATES_CSC.has_canonical_format
    np.testing.assert_array_equal(DUPLICATES_CSC.toarray(), K)
    dense = max_x2(K)
    assert dense == pytest.approx(29.28, abs=0.01)
    csr = scipy.sparse.csr_matrix(([1.0, -1.0, 1.0, -1.0, 1.0], [0, 1, 0, 0, 1], [0, 3, 5]), shape=(2, 2))
    coo = scipy.sparse.coo_matrix(([1.5, -1.0, 0.5, -1.0, 1.0], ([0, 0, 0, 1, 1], [0, 1, 0, 0, 1])), shape=(2, 2))
    for stiffness in (DUPLICATES_CSC, csr, coo):
        assert not stiffness.has_canonical_format
        assert max_x2(stiffness) == pytest.approx(dense, rel=1e-9)
    np.testing.assert_array_equal(friction_model(DUPLICATES_CSC).stiffness, K)
    # Duplicates that cancel leave the sum, not one of them.
    cancelling = scipy.sparse.coo_matrix(([2.0, 5.0, -5.0], ([0, 1, 1], [0, 1, 1])), shape=(2, 2))
    np.testing.assert_array_equal(eqhb.model(np.eye(2), cancelling + 0.5 * scipy.sparse.eye(2), forcing=FORCING)
                                  .stiffness, [[2.5, 0.0], [0.0, 0.5]])


def test_unsorted_indices_of_a_symmetric_matrix_are_accepted():
    unsorted = scipy.sparse.csc_matrix(([-1.0, 2.0, 1.0, -1.0], [1, 0, 1, 0], [0, 2, 4]), shape=(2, 2))
    assert not unsorted.has_sorted_indices
    model = friction_model(unsorted)
    np.testing.assert_array_equal(model.stiffness, K)
    assert max_x2(unsorted) == pytest.approx(max_x2(K), rel=1e-9)


CORRUPT = {
    "row index out of range": "K.indices[1] = 1000000",
    "negative row index": "K.indices[0] = -3",
    "indptr decreasing": "K.indptr[1] = 3; K.indptr[2] = 1",
    "indptr past the data": "K.indptr[2] = 40",
    "csr column out of range": "K = K.tocsr(); K.indices[2] = 1000000",
    "coo row out of range": "K = K.tocoo(); K.row[0] = 1000000",
}


@pytest.mark.parametrize("corruption", CORRUPT.values(), ids=CORRUPT.keys())
def test_corrupt_sparse_arrays_raise_input_error_not_a_crash(corruption):
    # scipy lets these through attribute assignment; read unchecked they would
    # be out-of-bounds reads (the interpreter died of SIGSEGV).
    run = run_isolated(f"""
        import numpy as np, scipy.sparse, eqhb
        K = scipy.sparse.csc_matrix(np.array([[2.0, -1.0], [-1.0, 1.0]]))
        {corruption}
        try:
            eqhb.model(np.eye(2), K, forcing=[{{"dof": 1, "cos": 1.0}}])
            print("accepted")
        except eqhb.InputError as e:
            print("InputError:", e)
    """)
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith("InputError: stiffness:"), run.stdout


NOT_REAL = {
    "complex": K + 0.5j,
    "bool": K != 0,
    "str": K.astype(str),
    "object": K.astype(object),
}


@pytest.mark.parametrize("array", NOT_REAL.values(), ids=NOT_REAL.keys())
def test_non_real_arrays_are_refused_not_cast(array):
    with pytest.raises(eqhb.InputError, match=f"^stiffness: .*dtype {array.dtype}"):
        friction_model(array)
    if array.dtype.kind in "cb":
        with pytest.raises(eqhb.InputError, match="^damping: .*must be real numbers"):
            eqhb.model(M, K, scipy.sparse.csc_matrix(array), forcing=FORCING)
    with pytest.raises(eqhb.InputError, match="^initial: .*must be real numbers"):
        eqhb.solve(friction_model(K), initial=np.zeros(40, dtype=array.dtype))


def test_a_huge_broadcast_mass_is_refused_before_any_copy():
    # 30000 x 30000 views one number; a dense copy would be 7.2 GB. A
    # regression hangs or runs out of memory: the interpreter is a separate one.
    run = run_isolated("""
        import time, numpy as np, eqhb
        mass = np.broadcast_to(np.float64(1.0), (30000, 30000))
        start = time.perf_counter()
        try:
            eqhb.model(mass, mass, forcing=[{"dof": 1, "cos": 1.0}])
        except eqhb.InputError as e:
            print(f"{time.perf_counter() - start:.3f}", e)
    """, timeout=30)
    assert run.returncode == 0, run.stderr
    seconds, message = run.stdout.split(" ", 1)
    assert message.startswith("mass = 30000 x 30000: a dense array") and "GiB limit" in message
    assert float(seconds) < 1.0


def test_a_huge_sparse_matrix_is_refused_by_its_size():
    huge = scipy.sparse.csc_matrix((2**31, 2**31))
    started = time.perf_counter()
    with pytest.raises(eqhb.InputError, match="^mass: shape 2147483648 x 2147483648"):
        eqhb.model(huge, huge)
    with pytest.raises(eqhb.InputError, match="^mass = 2000000000 x 2000000000 .*GiB limit"):
        eqhb.model(scipy.sparse.csc_matrix((2 * 10**9, 2 * 10**9)), K)
    assert time.perf_counter() - started < 1.0


SCENE_MODEL = friction_model(K)

WRONG_TYPES = [
    (lambda: eqhb.solve("friction-1d"), "model"),
    (lambda: eqhb.solve(SCENE_MODEL, omega="0.4"), "omega"),
    (lambda: eqhb.solve(SCENE_MODEL, harmonics=2.5), "harmonics"),
    (lambda: eqhb.solve(SCENE_MODEL, samples=True), "samples"),
    (lambda: eqhb.solve(SCENE_MODEL, solver=None), "solver"),
    (lambda: eqhb.solve(SCENE_MODEL, max_iterations=2**40), "max_iterations"),
    (lambda: eqhb.solve(SCENE_MODEL, initial=[[1.0], [1.0, 2.0]]), "initial"),
    (lambda: eqhb.stability(SCENE_MODEL, {"converged": True}), "solution"),
    (lambda: eqhb.stability(SCENE_MODEL, np.array(["a", "b"])), "solution"),
    (lambda: eqhb.stability(SCENE_MODEL, np.zeros(3)), "solution"),
    (lambda: eqhb.stability(SCENE_MODEL, np.zeros(40), omega=[0.4]), "omega"),
    (lambda: eqhb.sweep(SCENE_MODEL, 0.3, 0.4, step="fine"), "step"),
    (lambda: eqhb.sweep(SCENE_MODEL, 0.3, 0.4, max_points=1e3), "max_points"),
    (lambda: eqhb.simulate(SCENE_MODEL, periods=1.5), "periods"),
    (lambda: eqhb.shoot(SCENE_MODEL, restitution="none"), "restitution"),
    (lambda: eqhb.load_scene(5), "path"),
    (lambda: eqhb.load_scene("friction-1d.toml", ["law[0].muN=1"]), "overrides"),
    (lambda: eqhb.model(M, K, forcing=5), "forcing"),
    (lambda: eqhb.model(M, K, laws=None), "laws"),
    (lambda: eqhb.model(M, object()), "stiffness"),
]


@pytest.mark.parametrize("call,argument", WRONG_TYPES, ids=[a for _, a in WRONG_TYPES])
def test_wrong_types_raise_input_error_naming_the_argument(call, argument):
    with pytest.raises(eqhb.InputError) as error:
        call()
    assert str(error.value).startswith(argument)


# A backend option the backend refuses is bad input before the sweep starts,
# as for solve: not a curve of invalid_options points.
@pytest.mark.parametrize("method", ["sequential", "arclength"])
def test_sweep_with_a_refused_backend_option_raises_naming_it(method):
    problems = os.environ.get("EQHB_PROBLEMS_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "problems"))
    scene = eqhb.load_scene(os.path.join(problems, "friction-1d.toml"))
    with pytest.raises(eqhb.InputError, match='factorisation = "bogus"'):
        eqhb.sweep(scene, method=method, options={"factorisation": "bogus"})
