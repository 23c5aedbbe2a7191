"""The numpy route's cheaper forms (issue 22, "no ratio worse than before"): each the form before, bit for bit.

Each test compares a new form with the expression it replaced, kept here verbatim, on inputs that reach
every branch (NaN and infinite entries in each position, rows out of range), and checks
that the new path is the one taken.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from symbt.numeric.core import condition, monodromy
from symbt.numeric.core.context import FLOAT
from symbt.numeric.core.errors import NumericRangeError
from symbt.numeric.core.limits import MAX_DQ_FLOAT64
from symbt.numeric.float64 import rows as rows_module


def same_bits(x, y):
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    return x.shape == y.shape and x.tobytes() == y.tobytes()


def special_rows(rng, n):
    """``n`` values, mostly ordinary, with NaN, +-inf, huge and tiny ones sprinkled in."""
    x = rng.normal(size=n) * 10.0 ** rng.integers(-3, 4, n)
    k = rng.integers(0, n, 6)
    x[k] = [np.nan, np.inf, -np.inf, 2.0 ** 600, -(2.0 ** 700), 2.0 ** -600]
    return x


# ------------------------------------------------------------------ the two products' range test at once

def _in_range_before(half):
    """``FloatContext.out_of_range(*half)`` is the literal ``False`` (no row renormalised): the test before."""
    return FLOAT.out_of_range(*half) is False


@pytest.mark.parametrize("R", [condition.FEW_ROWS + 1, 200])
def test_both_in_range_is_the_range_test_of_each_half(R):
    rng = np.random.default_rng(R)
    decided = {True: 0, False: 0}
    for trial in range(400):
        X = [rng.normal(size=2 * R) * 10.0 ** rng.integers(-3, 4) for _ in range(4)]
        if trial % 2:                       # a special value at a random entry, half and row
            i, k = rng.integers(0, 4), rng.integers(0, 2 * R)
            X[i][k] = rng.choice([np.nan, np.inf, -np.inf, 2.0 ** 501, -(2.0 ** 600), 2.0 ** -501])
        want = _in_range_before([x[:R] for x in X]) and _in_range_before([x[R:] for x in X])
        assert condition._both_in_range(X, R) == want
        decided[want] += 1
    assert min(decided.values()) > 50


def test_a_nan_in_a_later_entry_passes_the_range_test_as_before():
    # out_of_range's whole-batch test is Python's max over the entries: a NaN span is kept only in first place
    R = 20
    X = [np.ones(2 * R) for _ in range(4)]
    X[2][3] = np.nan
    assert FLOAT.out_of_range(*[x[:R] for x in X]) is False
    assert condition._both_in_range(X, R)
    X[0][R + 1] = np.nan                    # in the first entry of the second half: that half is tested per row
    assert not condition._both_in_range(X, R)


def test_one_sweep_of_both_products_renormalises_as_before():
    rng = np.random.default_rng(7)
    for R in (condition.FEW_ROWS + 1, 300):
        for N in (2, 3, 40, 400):
            p = rng.normal(size=(N, R)) * 10.0 ** rng.integers(-2, 3)
            a = [20.0 + x for x in p]
            r = [np.exp(0.5 * rng.normal(size=R)) for _ in range(N)]
            main, (T, e) = condition.monodromy_and_abs(a, r)
            ref = monodromy.monodromy(FLOAT, a, r)
            Aa, _, _, Da, ea = monodromy.monodromy(FLOAT, [np.abs(x) for x in a], [-x for x in r])
            for x, y in zip(main, ref):
                assert same_bits(np.broadcast_to(x, (R,)), np.broadcast_to(y, (R,)))
                assert type(x) is type(y)
            assert same_bits(T, Aa + Da) and np.array_equal(np.broadcast_to(e, (R,)), np.broadcast_to(ea, (R,)))


# ------------------------------------------------------------------ the range test of neighbour differences

def _ratios_before(q):
    N = len(q)
    dq = [q[(j + 1) % N] - q[j] for j in range(N)]
    worst = max(float(max(np.max(d), -np.min(d))) if np.size(d) else 0.0 for d in np.real(dq))
    if worst > MAX_DQ_FLOAT64:
        raise NumericRangeError("too far")
    return [np.exp(d) for d in dq]


@pytest.mark.parametrize("case", ["plain", "far", "nan first", "nan later", "far after nan", "inf"])
def test_neighbour_ratios_refuses_exactly_as_before(case):
    rng = np.random.default_rng(3)
    q = [rng.normal(size=30) for _ in range(4)]
    if case == "far":
        q[2][5] = 800.0
    elif case == "nan first":
        q[1][0] = np.nan
    elif case == "nan later":
        q[3][0] = np.nan
    elif case == "far after nan":                           # site 0's span is NaN: Python's max keeps it
        q[0][0], q[2][7] = np.nan, 900.0
    elif case == "inf":
        q[2][1] = np.inf
    outcomes = []
    for fn in (_ratios_before, lambda q: monodromy.neighbour_ratios(FLOAT, q)):
        with np.errstate(all="ignore"):
            try:
                outcomes.append([x.tobytes() for x in fn(q)])
            except NumericRangeError:
                outcomes.append("refused")
    assert outcomes[0] == outcomes[1]
    assert (outcomes[0] == "refused") == (case in ("far", "inf"))


# ------------------------------------------------------------------ the rows' largest neighbour step

@pytest.mark.parametrize("N", [1, 2, 3, 8, 9, 64])
def test_largest_step_is_the_rolled_difference(N):
    rng = np.random.default_rng(N)
    q = special_rows(rng, 500 * N).reshape(500, N)
    with np.errstate(all="ignore"):
        before = np.abs(np.roll(q, -1, axis=1) - q).max(axis=1)
        got = rows_module._largest_step(q)
    assert same_bits(got, before)
    assert N == 1 or (np.isnan(before).any() and (before > MAX_DQ_FLOAT64).any())


def test_float_rows_step_refuses_the_far_rows_as_before():
    rng = np.random.default_rng(5)
    p, q = rng.normal(size=(12, 3)), rng.normal(size=(12, 3))
    q[4, 1], q[9, 2] = 750.0, math.nan
    with pytest.raises(NumericRangeError) as err:
        rows_module.float_rows_step(p, q, 20.0, 1.0, 1, False, (12,))
    assert "(4,)" in str(err.value) and "(9,)" in str(err.value)


# ------------------------------------------------------------------ the plain-Python step's sharp tier on floats

def test_the_plain_python_step_calls_the_sharp_tier_on_floats():
    from symbt.numeric.float64 import kernels

    step_globals = kernels.python_kernels()["step"].__globals__
    assert condition.SHARP_ON_FLOATS in step_globals.values()
    assert condition.sharp_trace_kappa not in step_globals.values()
    dev = kernels.python_orbit_with({})                       # the measuring device too
    assert condition.SHARP_ON_FLOATS in dev.__globals__["_orbit_on_rows"].__globals__["step"].__globals__.values()


def test_the_sharp_tier_on_floats_is_the_array_form_bit_for_bit():
    # the n64/n256 chains' states (the sharp tier every step) and random rows, renormalised ones included
    from symbt.benchmarks.cases import cases

    rng = np.random.default_rng(64)
    states = [(np.array(c.p), np.exp(np.roll(np.array(c.q), -1) - np.array(c.q)), c.lam0 + s * c.mu)
              for c in cases(quick=True) for s in (1.0, -1.0)]
    for N in (2, 3, 40, 300):
        states += [(rng.normal(size=N) * 10.0 ** rng.integers(-1, 3), np.exp(rng.normal(size=N)), float(rng.normal()))
                   for _ in range(10)]
    for p, r, lam in states:
        with np.errstate(all="ignore"):
            a = condition.sharp_trace_kappa(p, r, lam, 0.0)
        b = condition.SHARP_ON_FLOATS(condition._Sites(p.tolist()), condition._Sites(r.tolist()), lam, 0.0)
        assert same_bits(a, b) or (np.isnan(a) and np.isnan(b))
