"""The block kernel on lists of Python floats (``symbt.numeric.float64.block_python``) is the block kernel.

Judged against the numba instance of the same source (the same statuses, the same bits for every member it
finishes) and against the source run as it is on numpy scalars with IEEE semantics (``errstate`` ignore:
every output, failing members' included, bit for bit), on a sweep of the benchmark cases perturbed across
bands and gaps, with band-edge members (``ILLCOND``), members past the float64 range (``RANGE``) and the
chains (the sharp tier).
"""
from __future__ import annotations

import numpy as np
import pytest
from test_numeric_rows_identity import band_edges  # the literal trace's |tr| = 2 points

from symbt.benchmarks.cases import cases
from symbt.numeric import bt_orbit
from symbt.numeric.core.limits import ILLCOND, OK, POSITIVITY, RANGE, TRACE1, TRACE2
from symbt.numeric.float64 import block_python as BP
from symbt.numeric.float64 import kernels_block as KB
from symbt.numeric.float64.jit import kernel, numba_available
from symbt.numeric.float64.kernels import ANCHOR, orbit_rows

CASES = cases(quick=True)


def run(fn, P0, Q0, lam0, mu, branch, n, every):
    M, N = P0.shape
    rows = orbit_rows(n, every)
    P, Q, st = np.full((rows, M, N), 7.0), np.full((rows, M, 2 * N), 7.0), np.zeros(M, np.int64)
    with np.errstate(all="ignore"):
        fn(P0, Q0, lam0 + mu, lam0 - mu, 2.0 * mu, branch, n, every, ANCHOR, 8, P, Q, st)
    return P, Q, st


def sweep(seed):
    """Members of every quick case, perturbed; some at a band edge of the paper's example, some past range."""
    rng = np.random.default_rng(seed)
    for i, c in enumerate(CASES):
        M, N = 24, len(c.p)
        P0 = np.array(c.p) + 0.05 * (i % 3) * rng.normal(size=(M, N))
        Q0 = np.array(c.q) + 0.05 * rng.normal(size=(M, N))
        lam0 = c.lam0 + 3.0 * (i % 4) * rng.normal(size=M)
        mu = c.mu * rng.choice([1.0, -1.0, 0.3], M)
        if N == 3:                     # lam1 within 1e-12 of a band edge of the member's state
            e = band_edges(P0[0], Q0[0])[0]
            lam0[:2], mu[:2], P0[1], Q0[1] = e - 1.0 + 1e-12, 1.0, P0[0], Q0[0]
        Q0[-1, 0] += 705.0              # |q_2 - q_1| > 700: out of the float64 formulation's range
        yield c, P0, Q0, lam0, mu, min(c.n, 12)


def test_the_float_form_equals_the_source_on_numpy_scalars():
    seen = set()
    for c, P0, Q0, lam0, mu, n in sweep(1):
        a = run(BP.ensemble, P0, Q0, lam0, mu, c.branch, n, 5)
        b = run(KB.ensemble, P0, Q0, lam0, mu, c.branch, n, 5)
        assert a[2].tolist() == b[2].tolist()
        assert a[0].tobytes() == b[0].tobytes() and a[1].tobytes() == b[1].tobytes()
        seen |= set(a[2].tolist())
    assert {OK, TRACE1, TRACE2, POSITIVITY, RANGE, ILLCOND} <= seen


@pytest.mark.skipif(not numba_available(), reason="numba not installed")
def test_the_float_form_equals_the_numba_kernel():
    numba_ensemble = kernel("ensemble", "numba")[0]
    for c, P0, Q0, lam0, mu, n in sweep(2):
        a = run(BP.ensemble, P0, Q0, lam0, mu, c.branch, n, 5)
        b = run(numba_ensemble, P0, Q0, lam0, mu, c.branch, n, 5)
        ok = b[2] == OK
        assert a[2].tolist() == b[2].tolist() and ok.sum() > 3
        assert a[0][:, ok].tobytes() == b[0][:, ok].tobytes() and a[1][:, ok].tobytes() == b[1][:, ok].tobytes()


def test_backend_python_runs_the_float_form_and_a_planted_change_reaches_it(monkeypatch):
    assert kernel("ensemble", "python")[0] is BP.ensemble
    c = CASES[0]
    P0, Q0 = np.tile(c.p, (3, 1)), np.tile(c.q, (3, 1))
    P1, _ = bt_orbit(P0, Q0, c.lam0, c.mu, 4, backend="python")
    monkeypatch.setattr(KB, "KAPPA_MAX", 0.0)     # the tests' planted bugs patch kernels_block's globals
    assert kernel("ensemble", "python")[0] is KB.ensemble
    st = run(kernel("ensemble", "python")[0], P0, Q0, np.full(3, c.lam0), np.full(3, c.mu), c.branch, 2, 1)[2]
    assert st.tolist() == [ILLCOND] * 3
    P2, _ = bt_orbit(P0, Q0, c.lam0, c.mu, 4, backend="python")   # handed back: the numpy route finishes
    np.testing.assert_allclose(P2, P1, rtol=0, atol=1e-12)
