"""The fused float64 kernel behind bt_orbit / bt_step: agreement, bit identities, fallbacks, laziness.

References: the general path (``backend="numpy"``: ``step_core`` on numpy arrays,
the pre-kernel implementation) and the paper's literal route at 50 digits
(``reference_step``).  Orbit-level accuracy (3500 steps) is in
``test_numeric_orbit.py``.
"""

import subprocess
import sys

import mpmath
import numpy as np
import pytest

from symbt.benchmarks.numeric_cases import random_gap_case, state_error
from symbt.numeric import InvalidInputError, NoRealMapError, NumericRangeError, bt_orbit, bt_step
from symbt.numeric.float64.jit import kernel, numba_available
from symbt.numeric.float64.kernels import ANCHOR, orbit_rows, stored_steps
from symbt.reference.literal import reference_step

P0 = np.array([-20.0, 10.0, 1.0])
Q0 = np.array([1.0, 0.0, 0.9])
needs_numba = pytest.mark.skipif(not numba_available(), reason="numba not installed")


def ref_orbit(p, q, lam0, mu, n, branch=1):
    out = []
    with mpmath.workdps(50):
        a, b = [mpmath.mpf(float(v)) for v in p], [mpmath.mpf(float(v)) for v in q]
        for _ in range(n):
            a, b = reference_step(a, b, float(lam0), float(mu), branch=branch)
            out.append((a, b))
    return out


@pytest.mark.parametrize("N", [2, 3, 5, 8, 16])
@pytest.mark.parametrize("branch", [1, -1])
def test_kernel_orbit_matches_general_path_and_50_digits(N, branch):
    rng = np.random.default_rng(10 * N + (branch > 0))
    p, q, lam0, mu = random_gap_case(rng, N)
    n = 40
    Pk, Qk = bt_orbit(p, q, lam0, mu, n, branch=branch)                  # fused kernel
    Pg, Qg = bt_orbit(p, q, lam0, mu, n, branch=branch, backend="numpy")  # general path
    refs = ref_orbit(p, q, lam0, mu, n, branch)
    for i in (1, 2, 5, 10, 20, 40):
        ek = state_error(Pk[i], Qk[i], *refs[i - 1])
        eg = state_error(Pg[i], Qg[i], *refs[i - 1])
        # one step: a few ulps (the one-step bound of test_numeric_step); later the orbit's own growth,
        # for which the general path's error (times 10, plus 20 ulps) is the yardstick
        assert ek <= (1e-13 if i == 1 else 10 * eg + 5e-15), (i, ek, eg)
    assert state_error(Pk[1], Qk[1], Pg[1], Qg[1]) <= 2e-15       # same formulas after one step


def test_bt_step_single_state_uses_kernel_same_formula():
    rng = np.random.default_rng(3)
    for N in (2, 3, 7):
        p, q, lam0, mu = random_gap_case(rng, N)
        for branch in (1, -1):
            a = bt_step(p, q, lam0, mu, branch=branch)
            b = bt_step(p, q, lam0, mu, branch=branch, backend="numpy")
            ref = reference_step([float(v) for v in p], [float(v) for v in q], lam0, mu, branch=branch)
            assert state_error(*a, *ref) <= 1e-13
            # identical formulas; only libm vs numpy exp/log1p may differ in the last bit
            np.testing.assert_allclose(a[0], b[0], rtol=4e-15, atol=4e-15 * np.abs(b[0]).max())
            np.testing.assert_allclose(a[1], b[1], rtol=4e-15, atol=4e-15 * np.abs(b[1]).max())


@needs_numba
def test_numba_and_python_kernels_bit_identical():
    Pn, Qn = bt_orbit(P0, Q0, 10.0, 5.0, 300, every=7, backend="numba")
    Pp, Qp = bt_orbit(P0, Q0, 10.0, 5.0, 300, every=7, backend="python")
    assert np.array_equal(Pn, Pp) and np.array_equal(Qn, Qp)
    # the block (ensemble) kernel: numba and plain Python, and against the single-orbit kernel
    rng = np.random.default_rng(4)
    p = P0 + 0.01 * rng.normal(size=(5, 3))
    q = Q0 + 0.01 * rng.normal(size=(5, 3))
    Pe, Qe = bt_orbit(p, q, 10.0, 5.0, 60, backend="numba")
    Pb, Qb = bt_orbit(p, q, 10.0, 5.0, 60, backend="python")
    assert np.array_equal(Pe, Pb) and np.array_equal(Qe, Qb)
    for i in range(5):
        Ps, Qs = bt_orbit(p[i], q[i], 10.0, 5.0, 60)
        assert np.array_equal(Ps, Pe[:, i]) and np.array_equal(Qs, Qe[:, i])


def test_every_subsamples_the_same_orbit():
    P, Q = bt_orbit(P0, Q0, 10.0, 5.0, 100)
    for every in (1, 3, 16, 33, 100, 250):
        Ps, Qs = bt_orbit(P0, Q0, 10.0, 5.0, 100, every=every)
        idx = stored_steps(100, every)
        assert Ps.shape == (orbit_rows(100, every), 3) == (len(idx), 3)
        assert np.array_equal(Ps, P[idx]) and np.array_equal(Qs, Q[idx])   # bit for bit
    with pytest.raises(InvalidInputError):
        bt_orbit(P0, Q0, 10.0, 5.0, 10, every=0)


def _outcome(fn, *a, **k):
    try:
        return "ok", fn(*a, **k)
    except (NoRealMapError, NumericRangeError, InvalidInputError) as e:
        return type(e).__name__, getattr(e, "condition", None)


FALLBACK = {
    "lam1 in a band": (P0, Q0, -10.278, 0.002),
    "gaps two apart": (P0, Q0, 22.5, 17.5),
    "|q_{j+1} - q_j| > 700": (P0, np.array([0.0, 900.0, 0.0]), 10.0, 5.0),
    "huge lam: renormalised monodromy": (np.array([1.0, -2.0, 0.5] * 20), np.zeros(60), 1e15, 1e14),
    "degenerate eigenvector (lam2 + p_2 = 0)": (np.array([-3.0, 0.0]), np.array([0.0, 1.0]), 1.0, 1.0),
    "lam0 + mu overflows": (P0, Q0, 1e308, 1e308),
}


@pytest.mark.parametrize("name", sorted(FALLBACK))
def test_fallback_same_outcome_as_general_path(name):
    p, q, lam0, mu = FALLBACK[name]
    for n in (1, 3):
        fast = _outcome(bt_orbit, p, q, lam0, mu, n)
        slow = _outcome(bt_orbit, p, q, lam0, mu, n, backend="numpy")
        assert fast[0] == slow[0], (fast, slow)
        if fast[0] == "ok":
            assert np.allclose(fast[1][0], slow[1][0], rtol=1e-13, atol=1e-13)
        else:
            assert fast[1] == slow[1]
        py = _outcome(bt_orbit, p, q, lam0, mu, n, backend="python")
        assert py[0] == slow[0]
    fast = _outcome(bt_step, p, q, lam0, mu)
    slow = _outcome(bt_step, p, q, lam0, mu, backend="numpy")
    assert fast[0] == slow[0] and (fast[0] == "ok" or fast[1] == slow[1])


def test_degenerate_eigenvector_float_limit_via_kernel():
    # lam2 + p_2 = 0: the backward-transported slope passes through infinity; the float step returns
    # the limit (checked against reference_step at mu -> 1 in test_numeric_corner.py)
    pt, qt = bt_orbit(np.array([-3.0, 0.0]), np.array([0.0, 1.0]), 1.0, 1.0, 1)
    assert np.all(np.isfinite(pt)) and np.all(np.isfinite(qt))
    np.testing.assert_allclose(pt[1], [-1.0, -2.0], atol=1e-14)


def test_kernel_backend_names_and_errors():
    fn, name = kernel("orbit", "python")
    assert name == "python" and callable(fn)
    with pytest.raises(InvalidInputError):
        kernel("orbit", "fortran")
    with pytest.raises(InvalidInputError):
        bt_orbit(P0, Q0, 10.0, 5.0, 3, backend="fortran")
    with pytest.raises(InvalidInputError):
        bt_orbit(P0, Q0, 10.0, 5.0, 3, backend="flint")      # an mpmath backend for float input


def test_python_kernel_direct_call():
    fn, _ = kernel("orbit", "python")
    P = np.empty((orbit_rows(5, 1), 3))
    Q = np.empty_like(P)
    with np.errstate(all="raise"):
        st = fn(P0, Q0, 15.0, 5.0, 10.0, 1, 5, 1, ANCHOR, P, Q)
    assert st == 0
    np.testing.assert_allclose(P, bt_orbit(P0, Q0, 10.0, 5.0, 5)[0], rtol=0, atol=0)


def test_import_is_lazy_about_numba_flint_dask():
    code = ("import sys, numpy as np, symbt.numeric as sn; "
            "sn.bt_step(np.array([-20.0, 10, 1]), np.array([1.0, 0, 0.9]), 10.0, 5.0, backend='numpy'); "
            "print(','.join(m for m in ('numba', 'flint', 'dask', 'sympy', 'scipy') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", out.stdout


def test_no_numba_environment_falls_back_cleanly():
    code = ("import numpy as np, sys; from symbt.numeric import bt_orbit; "
            "from symbt.numeric.float64.jit import numba_available; "
            "P, Q = bt_orbit(np.array([-20.0, 10, 1]), np.array([1.0, 0, 0.9]), 10.0, 5.0, 50); "
            "Pe, Qe = bt_orbit(np.tile([-20.0, 10, 1], (4, 1)), np.tile([1.0, 0, 0.9], (4, 1)), 10.0, 5.0, 50); "
            "print(numba_available(), 'numba' in sys.modules, float(abs(Pe[:, 2] - P).max()) < 1e-11)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**__import__("os").environ, "SYMBT_NO_NUMBA": "1"})
    assert out.stdout.split() == ["False", "False", "True"], out.stdout


@pytest.mark.parametrize("backend", ["auto", "python"])
def test_kernel_leaves_when_tr_squared_overflows(backend):
    """|tr L| ~ 1e154: (tr - 2)(tr + 2) overflows, so the kernel must hand over to the rescaling general path
    (found by the fuzz suite: the kernel returned p~ = 2e-230 instead of 9.9e75)."""
    import mpmath as mp

    from symbt.reference.literal import reference_step

    p, q, l0, m = [0.0, 0.0], [0.0, -352.0], 1.0911609275242446e+77, 5.455804637621223e+76
    with mp.workdps(60):
        rp, rq = reference_step([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m), branch=-1)
    ref = np.array([float(v) for v in rp + rq])
    P, Q = bt_orbit(np.array(p), np.array(q), l0, m, 1, branch=-1, backend=backend)
    got = np.r_[P[1], Q[1]]
    assert np.allclose(got, ref, rtol=1e-12, atol=0)
    PB, QB = bt_orbit(np.tile(p, (3, 1)), np.tile(q, (3, 1)), l0, m, 1, branch=-1)   # the block kernel too
    assert np.allclose(np.c_[PB[1], QB[1]], ref, rtol=1e-12, atol=0)
