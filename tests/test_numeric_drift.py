"""Drift at the round-off limit (issue 26, item 6): the measure, the measuring device, the compensated carry.

The long measurement (1e7 steps, N = 3, 64, 256, heyoka alongside) is ``python -m symbt.benchmarks.drift``
(BENCHMARKS.md, "Drift at the round-off limit"); these tests check its parts cheaply:

* the windowed-RMS exponent recovers 0.5 for random walks and 1 for linear drift (synthetic data);
* the modular read-out used to see the orbit's own drift is the kernel's orbit (momenta bit for bit,
  position differences within the rounding of the absolute rows);
* the stored absolute positions round ``q_{j+1} - q_j`` at ``ulp(|q|)``, and ``|q|`` grows linearly with
  the centre of mass: after 1e5 steps the drift of the invariants measured on the absolute rows exceeds
  that of the same orbit read out modulo 64 -- the linear term of the issue's measurement;
* the double-double carry of the positions (``_dd_add``) loses nothing against exact rational sums.
"""
from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symbt.benchmarks.drift import drift_case, modular_orbit, unwrap, windowed_rms
from symbt.numeric import invariants
from symbt.numeric.float64.jit import kernel, numba_available
from symbt.numeric.float64.kernels import ANCHOR, _dd_add, orbit_rows, stored_steps

needs_numba = pytest.mark.skipif(not numba_available(), reason="numba not installed")


def test_windowed_exponent_of_random_walks_and_of_linear_drift():
    rng = np.random.default_rng(3)
    n = 2 * 10**4
    walk = np.cumsum(rng.normal(size=(n, 400)), axis=0)[:, :, None]
    steps = np.arange(1, n + 1)
    assert 0.44 < windowed_rms(steps, walk, nwin=8)[2] < 0.56
    bias = walk + 0.5 * steps[:, None, None]          # a bias of 0.5 sigma per step dominates late
    assert windowed_rms(steps, bias, nwin=8)[2] > 0.8
    assert abs(windowed_rms(steps, 1e-16 * steps[:, None, None].astype(float), nwin=8)[2] - 1.0) < 0.01


def test_dd_add_carries_increments_exactly():
    rng = np.random.default_rng(7)
    hi, lo, exact = 1234.5, 0.0, Fraction(1234.5)
    for s in rng.normal(scale=1e-3, size=20000):
        hi, lo = _dd_add(hi, lo, float(s))
        exact += Fraction(float(s))
    err = abs(Fraction(hi) + Fraction(lo) - exact)
    assert float(err) <= 20000 * 2.0**-104 * 1300     # double-double rounding per add, far below one ulp of hi
    assert float(err) < 2.0**-52 * 1234.5 / 1e3


def _h50(p, q):
    with mpmath.workdps(50):
        return invariants([mpmath.mpf(float(a)) for a in p], [mpmath.mpf(float(b)) for b in q])


def _drift(P, Q, rows, H0):
    with mpmath.workdps(50):
        return np.array([[float((a - b) / abs(b)) for a, b in zip(_h50(P[r], Q[r]), H0)] for r in rows])


@needs_numba
def test_modular_read_out_is_the_kernel_orbit_and_absolute_rows_add_the_centre_rounding():
    p, q, lam0, mu = drift_case(3)
    n, every = 10**5, 1000
    rows = orbit_rows(n, every)
    Pa, Qa, Pm, Qm = (np.empty((rows, 3)) for _ in range(4))
    args = (p, q, lam0 + mu, lam0 - mu, 2 * mu, 1, n, every, ANCHOR)
    assert kernel("orbit", "numba")[0](*args, Pa, Qa) == 0
    assert modular_orbit()(*args, Pm, Qm) == 0
    assert np.array_equal(Pa, Pm)                                 # the same orbit: momenta bit for bit
    Qm = unwrap(Qm)
    big = np.abs(Qa).max(axis=1)
    assert big[-1] > 1e4                                          # the centre of mass has moved ~0.15 per step
    da, dm = np.diff(Qa, axis=1), np.diff(Qm, axis=1)
    # the absolute rows round each position once at |q|: differences within one ulp of |q| of the modular ones
    assert np.all(np.abs(da - dm) <= 2 * np.spacing(big)[:, None] + 1e-13)
    last = np.flatnonzero(np.array(stored_steps(n, every)) > n // 2)
    H0 = _h50(p, q)
    ra, rm = _drift(Pa, Qa, last, H0), _drift(Pm, Qm, last, H0)
    rms_a, rms_m = np.sqrt(np.mean(ra**2)), np.sqrt(np.mean(rm**2))
    # the absolute rows' extra drift is the rounding of the differences at ulp(|q|) ~ 1.8e-12 here
    assert rms_a > 2 * rms_m, (rms_a, rms_m)
    assert rms_m < 1e-12 and rms_a < 1e-10


@needs_numba
def test_no_linear_drift_when_two_mu_differs_from_lam1_minus_lam2():
    """``n64-chain``'s state at lam0 = 5.1, mu = 1.3: ``2.0 * mu`` is an ulp off ``fl(lam0 + mu) - fl(lam0 - mu)``.
    Before the repair each step was the map of parameters an ulp inconsistent with its read-out -- the same
    bias in every step: the traces drifted linearly, 6.2e-13, 1.2e-12, 1.7e-12, 2.3e-12 at 5e3 ... 2e4 steps
    (this test failed); now 5e-15 ... 1.5e-14, a random walk of the per-step rounding.  The kernels take
    the slopes at ``fl(lam0 +- mu)`` plus the low parts of
    :func:`~symbt.numeric.core.spectral_sum.lam_split` (their difference exactly ``2 mu``), each
    ``lam + p_j`` rounded once (two-sum), in every route alike."""
    from fractions import Fraction

    from symbt.numeric import spectral_trace

    p, q, _, _ = drift_case(64)
    lam0, mu, N = 5.1, 1.3, 64
    assert Fraction(lam0 + mu) - Fraction(lam0 - mu) != Fraction(2 * mu)
    n, every = 2 * 10**4, 5 * 10**3
    rows = orbit_rows(n, every)
    P, Q = np.empty((rows, N)), np.empty((rows, N))
    assert modular_orbit()(p, q, lam0 + mu, lam0 - mu, 2 * mu, 1, n, every, ANCHOR, P, Q) == 0
    Q = unwrap(Q)
    with mpmath.workdps(50):
        def traces(pp, qq):
            return [spectral_trace(mpmath.mpf(lam), [mpmath.mpf(float(a)) for a in pp],
                                   [mpmath.mpf(float(b)) for b in qq]) for lam in (lam0 - mu, lam0, lam0 + mu)]
        T0 = traces(p, q)
        rel = np.array([[float((a - b) / abs(b)) for a, b in zip(traces(P[r], Q[r]), T0)] for r in range(1, rows)])
    # a tenth of the biased drift at 2e4 steps, ten times the random walk measured
    assert np.abs(rel).max() < 2e-13, np.abs(rel).max(axis=1)


@needs_numba
def test_q_low_leaves_the_positions_bit_identical_and_removes_the_rounding_at_ulp_q():
    """``bt_orbit(..., q_low=True)``: ``Q`` is the default output bit for bit; ``Q + Q_low`` gives
    differences ``q_{j+1} - q_j`` that agree with the modular read-out of the same kernel orbit (rounded
    at |q| < 64) within a few ulps of 64, where the plain ``Q`` is off by up to ``ulp(|q|) ~ 2e-12``."""
    from symbt.numeric import bt_orbit

    p, q, lam0, mu = drift_case(3)
    n, every = 10**5, 10**4
    P0, Q0 = bt_orbit(p, q, lam0, mu, n, every=every)
    P1, Q1, L1 = bt_orbit(p, q, lam0, mu, n, every=every, q_low=True)
    assert np.array_equal(P0, P1) and np.array_equal(Q0, Q1)
    assert np.all(np.abs(L1) <= np.spacing(np.abs(Q1)) / 2)
    rows = orbit_rows(n, every)
    Pm, Qm = np.empty((rows, 3)), np.empty((rows, 3))
    assert modular_orbit()(p, q, lam0 + mu, lam0 - mu, 2 * mu, 1, n, every, ANCHOR, Pm, Qm) == 0
    dm = np.diff(unwrap(Qm), axis=1)
    d_low = np.diff(Q1, axis=1) + np.diff(L1, axis=1)
    d_plain = np.diff(Q1, axis=1)
    assert np.abs(d_low - dm).max() <= 4 * np.spacing(64.0)
    # what q_low removes: roundings at ulp(|q|) ~ 1.8e-12 (|q| ~ 1.5e4), of 20 differences the largest is 8.9e-13
    # here (over 1.4e-12 before the slope was rounded once: the orbit differs in its last bits)
    assert np.abs(d_plain - dm).max() > 30 * np.spacing(64.0)


@needs_numba
@pytest.mark.parametrize("backend", ["auto", "numpy"])
def test_q_low_on_ensembles_and_the_general_path(backend):
    from symbt.numeric import bt_orbit

    rng = np.random.default_rng(2)
    p = np.array([-20.0, 10, 1]) + 1e-3 * rng.normal(size=(5, 3))
    q = np.array([1.0, 0, 0.9]) + 1e-3 * rng.normal(size=(5, 3)) + 1e4          # far from 0: ulp(q) ~ 2e-12
    mu = np.array([5.0, 5.0, 0.0, 5.0, 5.0])                                      # one idle member
    P0, Q0 = bt_orbit(p, q, 10.0, mu, 300, every=100, backend=backend)
    P1, Q1, L1 = bt_orbit(p, q, 10.0, mu, 300, every=100, backend=backend, q_low=True)
    assert Q1.shape == L1.shape == (4, 5, 3)
    assert np.array_equal(P0, P1) and np.array_equal(Q0, Q1)
    assert np.all(np.abs(L1) <= np.spacing(np.abs(Q1)) / 2) and np.all(L1[:, 2] == 0) and np.all(L1[0] == 0)
    assert np.any(L1[1:, [0, 1, 3, 4]] != 0)                  # the carried positions have more bits than Q


def test_q_low_refuses_what_it_does_not_apply_to():
    import mpmath

    from symbt.numeric import bt_orbit
    from symbt.numeric.core.errors import InvalidInputError

    with pytest.raises(InvalidInputError, match="float64"):
        bt_orbit([mpmath.mpf(-20), mpmath.mpf(10), mpmath.mpf(1)], [mpmath.mpf(1), mpmath.mpf(0), mpmath.mpf("0.9")],
                 10, 5, 2, q_low=True)
    with pytest.raises(InvalidInputError, match="certified"):
        bt_orbit([-20.0, 10, 1], [1.0, 0, 0.9], 10.0, 5.0, 2, certified=True, q_low=True)


# four orbits of the paper's example, its state perturbed by ~1e-9 (drift.kernel_drift's members 1, 10, 12, 15)
_NEAR_PAPER = [
    ([-19.99999999987427, 9.999999999867896, 1.0000000006404226],
     [1.0000000001049, -5.35669373161111e-10, 0.9000000003615951]),
    ([-20.000000001288363, 10.000000000395122, 1.0000000004298637],
     [1.0000000006960428, -1.184117966757189e-09, 0.8999999993382974]),
    ([-19.999999998416527, 10.00000000132036, 1.0000000006333527],
     [0.9999999977964901, 5.202897425988651e-11, 0.9000000006836862]),
    ([-20.00000000127768, 10.000000000630411, 1.0000000005811658],
     [1.000000001294559, -7.546057912599311e-10, 0.9000000016891074]),
]


def _h0_linear_part(orbit, p, q, n=2 * 10**5, rows=50):
    """Least-squares linear part (through 0) at step n of the relative drift of H_0 (50 digits, positions
    with their low parts): what grows like n."""
    every = n // rows
    P, Q = np.empty((orbit_rows(n, every), 3)), np.empty((orbit_rows(n, every), 6))
    assert orbit(np.array(p), np.array(q), 15.0, 5.0, 10.0, 1, n, every, ANCHOR, P, Q) == 0
    steps = np.array(stored_steps(n, every), dtype=float)
    with mpmath.workdps(50):
        h0 = _h50(p, q)[0]
        rel = np.array([float((invariants([mpmath.mpf(float(a)) for a in P[i]],
                                          [mpmath.mpf(float(b)) + mpmath.mpf(float(c))
                                           for b, c in zip(Q[i, :3], Q[i, 3:])])[0] - h0) / abs(h0))
                        for i in range(len(steps))])
    return float((rel * steps).sum() / (steps**2).sum() * n)


def _k_rounded(A, D, dl, g, B, C, two, plus, wantk):
    """The slope at site 1 as it was computed before: ``k = dl +- g`` rounded, then divided."""
    k = dl + g if plus else dl - g
    return k / (2.0 * B) if wantk else (-2.0 * C) / k


@needs_numba
def test_no_per_orbit_linear_drift_of_the_papers_example():
    """The paper's example drifted linearly with a sign of its own per orbit (0.05 ulp of H_0 per step,
    exponent 0.80 over 1e7 steps): ``k = dl +- sqrt(t**2 - 4)`` is about ``2 (A - v)`` with ``v`` an
    eigenvalue -- constant on the orbit -- and ``A`` a double, so rounding ``k`` dropped the same bits of
    ``v`` in every step (and the root of the few doubles ``t`` takes repeated its rounding); orbits 1e-11
    apart drift alike, 1e-9 apart not.  Now the slope at site 1 is rounded once
    (:func:`~symbt.numeric.core.spectral_sum.root_slope`).  Measured on four orbits over 2e5 steps: the
    linear part of the H_0 drift was 1.7e-12 ... 2.1e-12 with the rounded ``k`` (asserted below, the same
    kernel with that one hook replaced) and is 0.5e-13 ... 3.8e-13 now, the random walk of the round-off."""
    from symbt.numeric.float64.jit import orbit_with

    now = [_h0_linear_part(kernel("orbit", "numba")[0], p, q) for p, q in _NEAR_PAPER]
    before = [_h0_linear_part(orbit_with({"root_slope": _k_rounded}), p, q) for p, q in _NEAR_PAPER]
    rms_now, rms_before = np.sqrt(np.mean(np.square(now))), np.sqrt(np.mean(np.square(before)))
    assert min(np.abs(before)) > 1.2e-12, before              # the bias, one sign per orbit
    assert rms_now < 6e-13 and rms_now < rms_before / 3, (now, before)
    assert rms_now > 1e-15                                     # round-off is there: a random walk, not zero


def test_root_slope_is_rounded_once_and_the_rows_form_equals_it():
    """:func:`~symbt.numeric.core.spectral_sum.root_slope` against the 60-digit slope of its inputs (``A``,
    ``D``, ``B``, ``C`` as given, ``A + D``, ``A - D`` and the root exact) on random monodromies near and far
    from the band edge: within half an ulp (correctly rounded) away from it, where ``k`` rounded and then
    divided is not; :func:`~symbt.numeric.core.spectral_sum.root_slope_rows` equals it element for element."""
    import math

    from symbt.numeric.core.spectral_sum import root_slope, root_slope_rows

    rng = np.random.default_rng(26)
    m = 1500
    t = rng.choice([-1.0, 1.0], m) * 10.0 ** rng.uniform(np.log10(2.0) + 1e-9, 6, m)
    t[:100] = rng.choice([-1.0, 1.0], 100) * (2.0 + 10.0 ** rng.uniform(-12, -2, 100))   # near the band edge
    A = rng.uniform(-2, 2, m) * np.abs(t)
    D = t - A
    keep = np.abs(A + D) > 2.0
    A, D = A[keep], D[keep]
    m = A.size
    t, dl = A + D, A - D
    B = rng.uniform(-3, 3, m) * 10.0 ** rng.uniform(-3, 3, m)
    C = rng.uniform(-3, 3, m)
    g = np.sqrt((t - 2.0) * (t + 2.0))
    plus, wantk = dl >= 0, rng.random(m) < 0.5
    rows = root_slope_rows(A, D, dl, g, B, C, 2.0, plus, wantk)
    worst_once = worst_twice = worst_far = 0.0
    with mpmath.workdps(60):
        for i in range(m):
            args = (A[i], D[i], dl[i], g[i], B[i], C[i], 2.0, bool(plus[i]), bool(wantk[i]))
            u = root_slope(*args)
            assert u == rows[i]
            a, d = mpmath.mpf(A[i]), mpmath.mpf(D[i])
            G = mpmath.sqrt((a + d) ** 2 - 4)
            k = (a - d) + (G if plus[i] else -G)
            exact = k / (2 * mpmath.mpf(B[i])) if wantk[i] else -2 * mpmath.mpf(C[i]) / k
            worst_once = max(worst_once, float(abs(u - exact)) / math.ulp(u))
            if abs(t[i]) > 3.0:
                worst_far = max(worst_far, float(abs(u - exact)) / math.ulp(u))
            twice = _k_rounded(*args)
            worst_twice = max(worst_twice, float(abs(twice - exact)) / math.ulp(twice))
    # correctly rounded away from the band edge; near it (|t| - 2 down to 1e-12, where fl(A + D) moves the
    # root by a large relative amount) the one Newton correction of the root leaves a few ulps, where the
    # root of fl(A + D) was off by 1e5 ulps and more
    assert m > 1400 and worst_far <= 0.5 + 1e-9 and worst_once <= 32 and worst_twice > 1e3, (
        m, worst_far, worst_once, worst_twice)


def test_root_slope_rows_few_rows_path_is_the_array_path(monkeypatch):
    """Up to ``_FEW_ROWS`` rows :func:`root_slope_rows` calls the scalar form per row (speed); every element
    must be the array form's bits, including zero denominators (IEEE inf/NaN: the array form takes over),
    cancelling traces and a scalar ``two``."""
    import symbt.numeric.core.spectral_sum as ss

    rng = np.random.default_rng(3)
    fallbacks = 0
    for trial in range(600):
        n = int(rng.integers(1, ss._FEW_ROWS + 1))
        A = rng.normal(0, 10, n) * 10.0 ** rng.integers(-3, 8, n)
        D = -A + rng.normal(0, 1e-3, n) if trial % 7 == 0 else rng.normal(0, 10, n) * 10.0 ** rng.integers(-3, 8, n)
        t, dl = A + D, A - D
        two = 2.0 if trial % 2 else np.full(n, 2.0)
        with np.errstate(all="ignore"):
            g = np.sqrt((t - 2) * (t + 2))
        B, C = rng.normal(0, 3, n), rng.normal(0, 3, n)
        wantk = rng.random(n) < 0.5
        if trial % 5 == 0:
            B[0], wantk[0] = 0.0, True
            fallbacks += 1
        args = (A, D, dl, g, B, C, two, dl >= 0, wantk)
        few = ss.root_slope_rows(*args)
        monkeypatch.setattr(ss, "_FEW_ROWS", -1)
        full = ss.root_slope_rows(*args)
        monkeypatch.setattr(ss, "_FEW_ROWS", 16)
        assert np.array_equal(few.view(np.int64), full.view(np.int64)), trial
    assert fallbacks > 0
