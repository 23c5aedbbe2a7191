"""Ensembles: bt_orbit on (M, N) float64 arrays (fused block kernel / numpy general path), per-state
errors, every=, and the dask recipe.

Each ensemble state is checked against its own 50-digit orbit (``reference_step``) and against the
single-state orbit (bit for bit: the block kernel performs the single kernel's arithmetic).
"""

import mpmath
import numpy as np
import pytest

from symbt.benchmarks.numeric_cases import random_gap_case, state_error
from symbt.numeric import NoRealMapError, NumericRangeError, bt_orbit, bt_step
from symbt.numeric.float64.jit import numba_available
from symbt.numeric.float64.kernels import stored_steps
from symbt.reference.literal import reference_step

P0 = np.array([-20.0, 10.0, 1.0])
Q0 = np.array([1.0, 0.0, 0.9])
BACKENDS = ["auto", "numpy"] + (["numba"] if numba_available() else [])


def gap_ensemble(N, M, seed):
    rng = np.random.default_rng(seed)
    cases = [random_gap_case(rng, N) for _ in range(M)]
    return (np.array([c[0] for c in cases]), np.array([c[1] for c in cases]),
            np.array([c[2] for c in cases]), np.array([c[3] for c in cases]))


@pytest.mark.parametrize("N", [2, 3, 5, 8])
@pytest.mark.parametrize("backend", BACKENDS)
def test_ensemble_rows_against_50_digits_and_single_orbits(N, backend):
    p, q, lam0, mu = gap_ensemble(N, 6, 7 * N)
    n = 30
    P, Q = bt_orbit(p, q, lam0, mu, n, every=10, backend=backend)
    assert P.shape == Q.shape == (4, 6, N)
    for i in range(6):
        with mpmath.workdps(50):
            a, b = [mpmath.mpf(v) for v in p[i]], [mpmath.mpf(v) for v in q[i]]
            for k in range(1, n + 1):
                a, b = reference_step(a, b, lam0[i], mu[i])
                if k % 10 == 0:
                    assert state_error(P[k // 10, i], Q[k // 10, i], a, b) <= 1e-12   # measured <= 2e-14
        single = bt_orbit(p[i], q[i], lam0[i], mu[i], n, every=10, backend="numba" if backend == "numba" else
                          ("numpy" if backend == "numpy" else "auto"))
        if backend == "numpy":   # same general path; numpy's SIMD exp may round differently by array length
            np.testing.assert_allclose(P[:, i], single[0], rtol=1e-12, atol=1e-12)
        elif numba_available():
            assert np.array_equal(P[:, i], single[0]) and np.array_equal(Q[:, i], single[1])


@pytest.mark.skipif(not numba_available(), reason="numba is not installed")
def test_numba_ensemble_at_block_edges():
    # batches of one block - 1, one block and one block + 1 states (blocks of 64 at N = 3): each row the bits of the
    # distinct states' batch, in the compiled kernel (paths.many_rows checks the plain-Python one).  Seed 18's
    # kernels_block:338 (`nb = (M + block + 1) // block`: one block past M, of negative length) passed both: the
    # block count is now a ceiling division, whose mutants give no blocks at all
    from symbt.numeric.float64.orbit import _block_rows

    p, q, lam0, mu = gap_ensemble(3, 5, 338)
    block = _block_rows(3)
    Pd, Qd = bt_orbit(p, q, lam0, mu, 3, backend="numba")
    for M in (block - 1, block, block + 1):
        idx = np.arange(M) % 5
        P, Q = bt_orbit(p[idx], q[idx], lam0[idx], mu[idx], 3, backend="numba")
        assert np.array_equal(P, Pd[:, idx]) and np.array_equal(Q, Qd[:, idx])


def test_ensemble_shapes_every_and_mu_zero_rows():
    p = np.broadcast_to(P0, (2, 3, 3)) + 0.001 * np.arange(6).reshape(2, 3, 1)
    q = np.broadcast_to(Q0, (2, 3, 3)).copy()
    mu = np.array([[5.0, 0.0, 5.0], [0.0, 5.0, 5.0]])
    P, Q = bt_orbit(p, q, 10.0, mu, 25, every=10)
    assert P.shape == (len(stored_steps(25, 10)), 2, 3, 3)
    assert np.array_equal(P[:, 0, 1], np.broadcast_to(p[0, 1], (4, 3)))    # mu = 0: identity
    full, _ = bt_orbit(p, q, 10.0, mu, 25)
    assert np.array_equal(P, full[stored_steps(25, 10)])
    Pn, _ = bt_orbit(p, q, 10.0, mu, 25, every=10, backend="numpy")
    np.testing.assert_allclose(P, Pn, rtol=1e-12, atol=1e-12)
    E, _ = bt_orbit(np.zeros((0, 3)), np.zeros((0, 3)), 10.0, 5.0, 4)
    assert E.shape == (5, 0, 3)


@pytest.mark.parametrize("backend", BACKENDS)
def test_per_state_errors_list_every_offending_index(backend):
    M = 7
    p = np.tile(P0, (M, 1))
    q = np.tile(Q0, (M, 1))
    lam0 = np.full(M, 10.0)
    mu = np.full(M, 5.0)
    lam0[2], mu[2] = 22.5, 17.5       # lam1, lam2 in different gaps -> positivity
    lam0[5], mu[5] = -10.278, 0.002   # both inside a band -> trace
    mu[1] = 0.0                        # identity row in a failing batch
    with pytest.raises(NoRealMapError) as info:
        bt_orbit(p, q, lam0, mu, 20, backend=backend)
    assert info.value.where == ((2,), (5,))
    assert info.value.condition == "positivity"          # that of the first offending state
    # a 2-d batch keeps 2-d indices
    with pytest.raises(NoRealMapError) as info:
        bt_orbit(p[:6].reshape(2, 3, 3), q[:6].reshape(2, 3, 3), lam0[:6].reshape(2, 3), mu[:6].reshape(2, 3), 3,
                 backend=backend)
    assert info.value.where == ((0, 2), (1, 2))
    # range problems only -> NumericRangeError
    q2 = q.copy()
    q2[3] = [0.0, 900.0, 0.0]
    with pytest.raises(NumericRangeError):
        bt_orbit(p, q2, 10.0, 5.0, 3, backend=backend)


def test_bt_step_batch_where_keeps_indices_with_zero_mu():
    p = np.tile(P0, (4, 1))
    q = np.tile(Q0, (4, 1))
    with pytest.raises(NoRealMapError) as info:
        bt_step(p, q, np.array([10.0, 10.0, 22.5, 10.0]), np.array([0.0, 5.0, 17.5, 0.0]))
    assert info.value.where == ((2,),)
    assert "batch index (2,)" in str(info.value)


def test_kernel_failures_recomputed_by_general_path():
    # one state needs the renormalised monodromy (huge lam): the kernel hands it to the general path
    rng = np.random.default_rng(1)
    p = np.vstack([np.tile([1.0, -2.0, 0.5], 20)] * 3) + 0.01 * rng.normal(size=(3, 60))
    q = np.zeros((3, 60))
    lam0 = np.array([1e15, 300.0, 1e15])
    mu = np.array([1e14, 10.0, 1e14])
    P, Q = bt_orbit(p, q, lam0, mu, 3)
    Pn, Qn = bt_orbit(p, q, lam0, mu, 3, backend="numpy")
    np.testing.assert_allclose(P, Pn, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(Q, Qn, rtol=1e-13, atol=1e-13)


# --------------------------------------------------------------------------- dask recipe

def test_dask_orbit_matches_in_memory():
    da = pytest.importorskip("dask.array")
    from symbt.numeric import dask_orbit

    p, q, lam0, mu = gap_ensemble(3, 10, 99)
    P, Q = dask_orbit(p, q, lam0, mu, 40, chunks=3, every=8)
    assert isinstance(P, da.Array) and P.chunks[1] == (3, 3, 3, 1)
    Pm, Qm = bt_orbit(p, q, lam0, mu, 40, every=8)
    assert np.array_equal(P.compute(), Pm) and np.array_equal(Q.compute(), Qm)
    # dask input keeps its chunks; a reduction without materialising the orbit
    P2, Q2 = dask_orbit(da.from_array(p, chunks=(5, 3)), da.from_array(q, chunks=(5, 3)), lam0, mu, 40, every=40)
    # (dask sums chunk by chunk: the mean agrees to round-off, the orbit itself bit for bit)
    assert np.array_equal(Q2[-1].compute(), Qm[-1])
    np.testing.assert_allclose(Q2[-1].mean(axis=0).compute(), Qm[-1].mean(axis=0), rtol=1e-14)


def test_dask_orbit_errors_carry_global_indices():
    pytest.importorskip("dask.array")
    from symbt.numeric import dask_orbit

    p = np.tile(P0, (8, 1))
    q = np.tile(Q0, (8, 1))
    lam0 = np.full(8, 10.0)
    mu = np.full(8, 5.0)
    lam0[6], mu[6] = 22.5, 17.5
    P, _ = dask_orbit(p, q, lam0, mu, 5, chunks=4)
    with pytest.raises(NoRealMapError) as info:
        P.compute()
    assert info.value.where == ((6,),)


def test_dask_orbit_without_dask_is_an_import_error(monkeypatch):
    import builtins

    from symbt.numeric import MissingDependencyError, dask_orbit

    real = builtins.__import__

    def fake(name, *a, **k):
        if name.startswith("dask"):
            raise ImportError("no dask here")
        return real(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", fake)
    with pytest.raises(ImportError, match="pip install") as info:
        dask_orbit(np.tile(P0, (2, 1)), np.tile(Q0, (2, 1)), 10.0, 5.0, 3)
    assert isinstance(info.value, MissingDependencyError)
