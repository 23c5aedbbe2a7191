"""Batches past one block: every member of a batch is its own single-state step (issue 26, item 2).

Block sizes (see the code): the numpy route cuts a batch into blocks of ``max(256, BLOCK_ELEMENTS // N)``
rows (:mod:`symbt.numeric.float64.rows`), the compiled block kernel into blocks of ``max(8, min(64, 2048 // N))``
states (``ensemble._block_rows``).  Each test below uses batches spanning several blocks of the route it
exercises, and compares every member with the single-state call through the same route: bit for bit,
and the same verdict (a member whose single step raises makes the batch raise, ``where`` naming exactly
the failing members).
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from symbt.numeric import NoRealMapError, NumericRangeError, bt_step
from symbt.numeric.core.step import BLOCK_ELEMENTS
from symbt.numeric.float64.jit import numba_available
from symbt.numeric.float64.orbit import _block_rows
from symbt.numeric.float64.step import _block_kernel_pays

P0 = np.array([-20.0, 10.0, 1.0])
Q0 = np.array([1.0, 0.0, 0.9])

needs_numba = pytest.mark.skipif(not numba_available(), reason="the block kernel needs numba")


def numpy_block(N: int) -> int:
    return max(256, BLOCK_ELEMENTS // N)


def single(p, q, lam0, mu, branch, backend, allow_complex=False):
    """The single-state call: ``(pt, qt, None)`` or ``(None, None, error)``."""
    try:
        pt, qt = bt_step(p, q, lam0, mu, branch=branch, backend=backend, allow_complex=allow_complex)
    except (NoRealMapError, NumericRangeError) as exc:
        return None, None, exc
    return pt, qt, None


@pytest.mark.parametrize("backend", ["auto", "numpy"])
def test_the_reported_batch_of_257_states_at_n_512_steps(backend):
    # 257 > 256 = the numpy block at N = 512: on main the second block was empty (a plain ValueError)
    assert numpy_block(512) == 256
    M, N = 257, 512
    pt, qt = bt_step(np.zeros((M, N)), np.zeros((M, N)), np.full(M, 50.0), 1.0, backend=backend)
    assert pt.shape == qt.shape == (M, N)
    p1, q1 = bt_step(np.zeros(N), np.zeros(N), 50.0, 1.0, backend=backend)
    for k in (0, 255, 256):
        np.testing.assert_array_equal(pt[k], p1)
        np.testing.assert_array_equal(qt[k], q1)


@pytest.mark.parametrize("backend", ["auto", "numba", "numpy"])
def test_per_state_mu_with_zeros_over_several_blocks(backend):
    if backend == "numba" and not numba_available():
        pytest.skip("numba not installed")
    N = 512
    M = 3 * numpy_block(N) + 7                # four numpy blocks; many kernel blocks
    rng = np.random.default_rng(26)
    p = np.tile(np.resize(P0, N), (M, 1)) * 0.0
    q = np.zeros((M, N))
    mu = rng.uniform(0.5, 1.5, M)
    mu[::3] = 0.0                             # on main: IndexError (lam0, mu sliced twice)
    lam0 = np.full(M, 50.0)
    pt, qt = bt_step(p, q, lam0, mu, backend=backend)
    idle = mu == 0
    np.testing.assert_array_equal(pt[idle], p[idle])
    np.testing.assert_array_equal(qt[idle], q[idle])
    for k in (1, 2, 256, 511, 512, 769, M - 1):
        p1, q1 = bt_step(p[k], q[k], lam0[k], mu[k], backend=backend)
        np.testing.assert_array_equal(pt[k], p1)
        np.testing.assert_array_equal(qt[k], q1)


def random_batch(M: int, seed: int):
    """States near the paper's example, a spread of lam0 and mu (some 0): many with a real map, many without,
    a few out of the float64 range (|q_{j+1} - q_j| ~ 800), and a few with |lam| ~ 1e52, where the block
    kernel gives the state back and the numpy route steps it."""
    rng = np.random.default_rng(seed)
    p = P0 + rng.normal(scale=3.0, size=(M, 3))
    q = Q0 + rng.normal(scale=1.0, size=(M, 3))
    lam0 = rng.uniform(-25.0, 25.0, M)
    mu = rng.uniform(-8.0, 8.0, M)
    mu[rng.random(M) < 0.1] = 0.0
    far = rng.random(M) < 0.003
    q[far, 1] += 800.0
    huge = rng.random(M) < 0.02               # |tr L| past 1e150: the kernel hands these back
    lam0[huge] *= 4e51
    mu[huge] *= 1e50
    return p, q, lam0, mu


def check_batch_against_singles(p, q, lam0, mu, branch, backend, allow_complex=False):
    M = p.shape[0]
    singles = [single(p[k], q[k], lam0[k], mu[k], branch, backend, allow_complex) for k in range(M)]
    nomap = [k for k in range(M) if isinstance(singles[k][2], NoRealMapError)]
    bad = [k for k in range(M) if singles[k][2] is not None]
    ok = [k for k in range(M) if singles[k][2] is None]
    if nomap:
        with pytest.raises(NoRealMapError) as info:
            bt_step(p, q, lam0, mu, branch=branch, backend=backend, allow_complex=allow_complex)
        assert info.value.where == tuple((k,) for k in nomap)
        assert info.value.condition == singles[nomap[0]][2].condition
    elif bad:
        with pytest.raises(NumericRangeError):
            bt_step(p, q, lam0, mu, branch=branch, backend=backend, allow_complex=allow_complex)
    # the members whose single step succeeds, as a batch of their own: equal bit for bit
    sel = np.array(ok)
    pt, qt = bt_step(p[sel], q[sel], lam0[sel], mu[sel], branch=branch, backend=backend,
                     allow_complex=allow_complex)
    for i, k in enumerate(ok):
        np.testing.assert_array_equal(pt[i], singles[k][0])
        np.testing.assert_array_equal(qt[i], singles[k][1])
    return len(ok), len(nomap), len(bad) - len(nomap)


@needs_numba
@pytest.mark.parametrize("branch", [1, -1])
def test_randomized_batches_through_the_block_kernel_equal_single_steps(branch):
    M = 3000                                  # < 4096: backend="auto" takes the block kernel at N = 3
    assert M > 10 * _block_rows(3)
    p, q, lam0, mu = random_batch(M, seed=2600 + branch)
    n_ok, n_nomap, n_range = check_batch_against_singles(p, q, lam0, mu, branch, "auto")
    assert n_ok > 300 and n_nomap > 300 and n_range > 0        # every verdict is exercised


@pytest.mark.parametrize("branch", [1, -1])
def test_randomized_batches_through_the_numpy_route_equal_single_steps(branch, monkeypatch):
    import symbt.numeric.float64.rows as rows

    monkeypatch.setattr(rows, "BLOCK_ELEMENTS", 1)            # blocks of 256 rows: 12 blocks at M = 3000
    M = 3000
    p, q, lam0, mu = random_batch(M, seed=2610 + branch)
    n_ok, n_nomap, n_range = check_batch_against_singles(p, q, lam0, mu, branch, "numpy")
    assert n_ok > 300 and n_nomap > 300 and n_range > 0


@needs_numba
def test_allow_complex_continues_exactly_the_members_without_a_real_map():
    M = 1500
    p, q, lam0, mu = random_batch(M, seed=2620)
    keep = np.abs(q[:, 1] - Q0[1]) < 100                      # leave out the out-of-range states
    p, q, lam0, mu = p[keep], q[keep], lam0[keep], mu[keep]
    pt, qt = bt_step(p, q, lam0, mu, allow_complex=True)
    assert pt.dtype == np.complex128
    n_complex = 0
    for k in range(p.shape[0]):
        p1, q1 = bt_step(p[k], q[k], lam0[k], mu[k], allow_complex=True)
        np.testing.assert_array_equal(pt[k], p1)
        np.testing.assert_array_equal(qt[k], q1)
        n_complex += np.iscomplexobj(p1)
    assert n_complex > 100


def test_where_names_failing_members_in_every_block_and_only_them():
    N = 512
    M = 2 * numpy_block(N) + 4               # three blocks; divisible by 3
    p, q = np.zeros((M, N)), np.zeros((M, N))
    lam0 = np.full(M, 50.0)
    lam0[[5, 300, M - 1]] = 0.0               # |tr L(+-1)| <= 2 at p = q = 0: inside a band
    with pytest.raises(NoRealMapError) as info:
        bt_step(p, q, lam0, 1.0, backend="numpy")
    assert info.value.where == ((5,), (300,), (M - 1,))
    with pytest.raises(NoRealMapError) as info:
        bt_step(p.reshape(3, -1, N), q.reshape(3, -1, N), lam0.reshape(3, -1), 1.0)
    assert info.value.where == tuple(np.unravel_index(k, (3, M // 3)) for k in (5, 300, M - 1))


def test_a_range_failure_does_not_hide_a_member_without_a_real_map():
    # a state out of the float64 range in the first block, one without a real map in a later block:
    # the batch reports the missing map (as the single step of that member does), naming only that member
    N = 512
    M = numpy_block(N) + 2
    p, q = np.zeros((M, N)), np.zeros((M, N))
    q[0, 1] = 800.0
    lam0 = np.full(M, 50.0)
    lam0[M - 1] = 0.0
    with pytest.raises(NumericRangeError):
        bt_step(p[0], q[0], 50.0, 1.0, backend="numpy")
    with pytest.raises(NoRealMapError) as info:
        bt_step(p, q, lam0, 1.0, backend="numpy")
    assert info.value.where == ((M - 1,),)


@needs_numba
def test_a_large_small_n_batch_on_the_numpy_route_is_within_the_bound_of_the_default_single_step():
    # >= 4096 states at N = 3: backend="auto" takes the numpy route for the batch, the single state the kernel;
    # documented (docs/numeric.md, "Batches"): within 8 a ulps of max(|p|, |q|, 1), a >= 1 the state's
    # amplification of a rounding of its input (measured on the exact map, below), existence alike away from edges.
    # The two routes round their exp/log differently (numpy's vectorised ones differ from libm in the last bit on
    # AVX-512 machines), and the map amplifies that as it amplifies input rounding: a state with a = 148 differs by
    # 9 ulps there.
    M = 7000
    p, q, lam0, mu = random_batch(M, seed=2630)
    ok, singles = [], {}
    for k in range(M):
        pt, qt, err = single(p[k], q[k], lam0[k], mu[k], 1, "auto")
        if err is None:
            ok.append(k)
            singles[k] = pt, qt
            continue
        with pytest.raises(type(err)):
            bt_step(p[k], q[k], lam0[k], mu[k], backend="numpy")
    sel = np.array(ok)
    assert not _block_kernel_pays(p[sel])        # the batch takes the numpy route
    pb, qb = bt_step(p[sel], q[sel], lam0[sel], mu[sel])
    rng = np.random.default_rng(7)
    worst = 0.0
    for i, k in enumerate(ok):
        p1, q1 = singles[k]
        scale = max(np.abs(p[k]).max(), np.abs(q[k]).max(), 1.0)
        ulps = max(np.abs(pb[i] - p1).max(), np.abs(qb[i] - q1).max()) / np.spacing(scale)
        if ulps > 8.0:          # beyond 8 ulps only as far as the exact map amplifies input rounding
            ulps /= amplification(p[k], q[k], lam0[k], mu[k], rng)
        worst = max(worst, ulps / 8.0)
    assert worst <= 1.0


def amplification(p, q, lam0, mu, rng, ulps=4, directions=4):
    """How many ulps of the state's scale the *exact* map moves per ulp of relative change of its input, at
    least 1: the mpmath step at 40 digits (no float64 route involved, so a worse kernel cannot widen the
    bound), the largest over ``directions`` random sign patterns of a relative change of ``ulps`` ulps."""
    scale = max(np.abs(p).max(), np.abs(q).max(), 1.0)
    with mpmath.workdps(40):
        exact = [mpmath.mpf(float(v)) for v in (*p, *q, lam0, mu)]
        n = p.size

        def step(xs):
            pt, qt = bt_step(xs[:n], xs[n:2 * n], xs[-2], xs[-1], backend="mpmath")
            return [*pt, *qt]

        base = step(exact)
        a = 1.0
        for _ in range(directions):
            sign = rng.choice([-1.0, 1.0], 2 * n + 2)
            moved = step([x * (1 + ulps * mpmath.mpf(2) ** -52 * s) for x, s in zip(exact, sign)])
            change = max(abs(u - v) for u, v in zip(moved, base))
            a = max(a, float(change) / np.spacing(scale) / ulps)
    return a
