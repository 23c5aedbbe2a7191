"""Large N far from the spectrum (issue 26, item 5): ``|tr L| >> 1e150`` stays in the fused kernels.

The kernels carry the monodromy as ``sc * [[A, B], [C, D]]`` with ``sc`` a power of two (exact
rescaling; the eigenvector slopes only need ratios), so a state at N = 128 or 256 with ``|tr L|`` up to
``1e512`` is stepped by the kernel instead of the general numpy path (about 2000x slower at N = 256).
Each test compares with an independent route: the mpmath step at 40 digits (``symbt.numeric.bt_step`` on
mpf, its own scaled monodromy with a separate exponent), and checks which route was taken.
"""
from __future__ import annotations

import mpmath
import numpy as np
import pytest

from symbt.benchmarks.cases import chain
from symbt.numeric import bt_orbit, bt_step, spectral_trace
from symbt.numeric.float64 import orbit as E
from symbt.numeric.float64.jit import numba_available
from symbt.numeric.float64.orbit import kernel_batch_step, kernel_step

EPS = 2.0**-52
# the kernel's one-step bound against the 40-digit step, in ulps of the state's scale
# max(|p|, |q|, |lam0| + |mu|): the increments are mu times ratios of slopes ~ lam + p_j
ULPS = 8.0

needs_numba = pytest.mark.skipif(not numba_available(), reason="numba not installed")
BACKENDS = [pytest.param("numba", marks=needs_numba), "python"]


def _state(N):
    p, q = chain(N, N, 0.5, 0.25)
    return np.array(p), np.array(q)


def _mp_step(p, q, lam0, mu, branch=1):
    with mpmath.workdps(40):
        P, Q = bt_step([mpmath.mpf(float(x)) for x in p], [mpmath.mpf(float(x)) for x in q],
                       mpmath.mpf(lam0), mpmath.mpf(mu), branch=branch)
        return np.array([float(x) for x in P]), np.array([float(x) for x in Q])


def _scale(p, q, lam0, mu):
    return max(np.abs(p).max(), np.abs(q).max(), abs(lam0) + abs(mu), 1.0)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("N,lam0,mu,branch", [(128, 100.0, 5.0, 1), (256, 10.0, 1.0, 1), (256, -60.0, 2.0, -1)])
def test_one_step_past_1e150_by_the_kernel_within_the_bound(N, lam0, mu, branch, backend):
    p, q = _state(N)
    tr = spectral_trace(mpmath.mpf(lam0 + mu), [mpmath.mpf(float(x)) for x in p], [mpmath.mpf(float(x)) for x in q])
    assert abs(tr) > mpmath.mpf(10) ** 200            # far past the old limit |tr L| ~ 1e150
    out = kernel_step(p, q, lam0, mu, branch, backend)
    assert out is not None                            # the fused kernel finished it (before: handed back)
    rp, rq = _mp_step(p, q, lam0, mu, branch)
    err = max(np.abs(out[0] - rp).max(), np.abs(out[1] - rq).max())
    assert err <= ULPS * EPS * _scale(p, q, lam0, mu), err / (EPS * _scale(p, q, lam0, mu))
    assert err > 0 or backend == "python"             # a float64 step, not the reference itself


@needs_numba
def test_the_block_kernel_equals_the_single_kernel_bit_for_bit_past_1e150():
    N, lam0, mu = 128, 100.0, 5.0
    p, q = _state(N)
    rng = np.random.default_rng(5)
    pa = p + 0.1 * rng.normal(size=(20, N))           # several blocks of the block kernel
    qa = q + 0.1 * rng.normal(size=(20, N))
    bp, bq = kernel_batch_step(pa, qa, lam0, mu, 1, False, (20,))
    for m in range(20):
        sp, sq = kernel_step(pa[m], qa[m], lam0, mu, 1, "numba")
        assert np.array_equal(bp[m], sp) and np.array_equal(bq[m], sq), m


@needs_numba
def test_single_state_orbit_at_n256_past_1e150_never_takes_the_general_path(monkeypatch):
    N, lam0, mu, n = 256, 10.0, 1.0, 5
    p, q = _state(N)

    def refuse(*args, **kw):
        raise AssertionError("the general path was taken")

    monkeypatch.setattr(E, "general_orbit", refuse)
    P, Q = bt_orbit(p, q, lam0, mu, n)
    # independent route: n steps of the 40-digit step (state kept at 40 digits)
    with mpmath.workdps(40):
        xp = [mpmath.mpf(float(x)) for x in p]
        xq = [mpmath.mpf(float(x)) for x in q]
        for _ in range(n):
            xp, xq = bt_step(xp, xq, mpmath.mpf(lam0), mpmath.mpf(mu))
        rp = np.array([float(x) for x in xp])
        rq = np.array([float(x) for x in xq])
    err = max(np.abs(P[-1] - rp).max(), np.abs(Q[-1] - rq).max())
    assert err <= n * ULPS * EPS * _scale(P[-1], Q[-1], lam0, mu)


@pytest.mark.parametrize("lam0,mu", [(10.0, 1.0), (3.0 * 256 + 20, 2.0)])
def test_bt_step_at_n256_past_1e150_takes_the_kernel_single_and_batch(lam0, mu, monkeypatch):
    # issue 26, item 5 follow-up: `bt_step` used to route N log(|lam0| + |mu|) > log(1e150) + 10 to the numpy
    # general path at once (~2000x slower); now the single state and every batch member stay in the kernel
    from symbt.numeric.float64 import step as S

    N = 256
    p, q = _state(N)
    tr = spectral_trace(mpmath.mpf(lam0 + mu), [mpmath.mpf(float(x)) for x in p], [mpmath.mpf(float(x)) for x in q])
    assert abs(tr) > mpmath.mpf(10) ** 200

    def refuse(*args, **kw):
        raise AssertionError("the general (numpy) path was taken")

    monkeypatch.setattr(S, "float_rows_step", refuse)
    monkeypatch.setattr(E, "float_rows_step", refuse)
    pt, qt = bt_step(p, q, lam0, mu)
    rp, rq = _mp_step(p, q, lam0, mu)
    bound = ULPS * EPS * _scale(p, q, lam0, mu)
    err = max(np.abs(pt - rp).max(), np.abs(qt - rq).max())
    assert err <= bound, err / (EPS * _scale(p, q, lam0, mu))
    assert err > 0                                    # a float64 step, not the reference itself
    if not numba_available():
        return                                        # without numba a batch takes the numpy route by design
    rng = np.random.default_rng(7)
    pa = p + 0.1 * rng.normal(size=(3, N))
    qa = q + 0.1 * rng.normal(size=(3, N))
    bp, bq = bt_step(pa, qa, lam0, mu)
    for m in range(3):
        rp, rq = _mp_step(pa[m], qa[m], lam0, mu)
        err = max(np.abs(bp[m] - rp).max(), np.abs(bq[m] - rq).max())
        assert err <= ULPS * EPS * _scale(pa[m], qa[m], lam0, mu), (m, err)
