"""The numpy route with its condition estimate vectorised is bit for bit the route before (issue 22).

The oracle is the previous form of the estimate, kept here verbatim: the cheap tier's monodromy of the
``|a_j|`` on numpy arrays, the site loops of ``eigen_slopes`` and ``float_status``, ``np.select``, and the
sharp tier as the scalar :func:`~symbt.numeric.core.condition.sharp_trace_kappa` called row by row.  Each
test runs the same inputs once with the shipped code and once with the oracle patched in, and compares
the states (bits), the statuses, the escalated rows and the errors -- on a sweep across bands, gaps, band
edges (escalations) and the benchmark chains (the sharp tier), with batches of few rows (the float forms)
and of many (numpy over the rows).
"""
from __future__ import annotations

import numpy as np
import pytest

from symbt.benchmarks.cases import cases
from symbt.numeric import NoRealMapError, NumericRangeError, bt_orbit, bt_step, spectral_trace
from symbt.numeric.core import condition
from symbt.numeric.core import step as step_module
from symbt.numeric.core.condition import (
    FEW_ROWS,
    SIDE_BY_SIDE_ROWS,
    abs_trace_rows,
    sharp_trace_kappa,
    sharp_trace_kappa_rows,
)
from symbt.numeric.core.context import FLOAT
from symbt.numeric.core.limits import ILLCOND, KAPPA_MAX, OK, POSITIVITY, RANGE, TRACE1, TRACE2
from symbt.numeric.core.monodromy import monodromy
from symbt.numeric.float64 import orbit as orbit_module
from symbt.numeric.float64 import rows as rows_module

QUICK = {c.name: c for c in cases(quick=True)}


# --------------------------------------------------------------------------- the oracle: the forms before

def old_trace_kappa(a, r, t, disc, e, ka=1.0, two=2.0, absolute=None):
    with np.errstate(all="ignore"):
        Aa, _, _, Da, ea = monodromy(FLOAT, [np.abs(x) for x in a], [-x for x in r])
        return np.ldexp(Aa + Da, ea - e) * ((np.abs(t) + np.abs(two)) / np.abs(disc)) * ka


def old_sharpened(S, rows):
    P, r, lam, lo = S.inputs
    shape = np.shape(rows)
    out = np.full(shape, np.inf)
    with np.errstate(all="ignore"):
        pv = np.stack([np.broadcast_to(x, shape) for x in P], axis=-1).astype(float)
        rv = np.stack([np.broadcast_to(x, shape) for x in r], axis=-1).astype(float)
        lv, ov = np.broadcast_to(lam, shape), np.broadcast_to(lo, shape)
        for k in zip(*np.nonzero(rows)):
            out[k] = sharp_trace_kappa(pv[k], rv[k], float(lv[k]), float(ov[k]))
    return out


def old_float_status(aux, Pn, Qn):
    S1, S2 = aux["S1"], aux["S2"]
    k1, k2 = S1.kappa, S2.kappa
    with np.errstate(all="ignore"):
        t1, t2 = S1.trace_ok > 0, S2.trace_ok > 0
        opp = (S1.t < 0) != (S2.t < 0)
        xr, u, w = aux["xr"], aux["u"], aux["w"]

        def ill(k1, k2):
            kt = np.maximum(k1, k2)
            return ~(k1 <= KAPPA_MAX) | ~(k2 <= KAPPA_MAX), np.logical_or.reduce([
                ~(kt * (np.abs(u[j]) + np.abs(w[j])) * (np.abs(x + 1) + np.abs(x))
                  <= KAPPA_MAX * np.abs(u[j] - w[j]) * np.abs(x + 1)) for j, x in enumerate(xr)])

        ill_t, ill_p = ill(k1, k2)
        rows = np.broadcast_to(ill_t | ill_p, np.shape(k1))
        if np.any(rows):
            k1, k2 = np.fmin(k1, old_sharpened(S1, rows)), np.fmin(k2, old_sharpened(S2, rows))
            ill_t, ill_p = ill(k1, k2)
        pos = np.logical_and.reduce([x + 1 > 0 for x in xr])
        fin = np.isfinite(np.add.reduce(Pn) + np.add.reduce(Qn))
    conds = [np.broadcast_to(c, np.shape(fin)) for c in (ill_t, ~t1, ~t2, opp, ill_p, ~pos, ~fin)]
    codes = [ILLCOND, TRACE1, TRACE2, POSITIVITY, ILLCOND, POSITIVITY, RANGE]
    return np.select(conds, codes, OK).astype(np.int64)


def old_over_sites(fn, *lists):
    """The site loop: ``fn`` of one site at a time, the results stacked (as the list comprehensions were)."""
    per_site = [fn(*xs) for xs in zip(*lists)]

    def stack(parts):
        return tuple(stack(p) for p in zip(*parts)) if isinstance(parts[0], tuple) else np.array(parts)
    return stack(per_site)


def use_oracle(monkeypatch):
    monkeypatch.setattr(step_module, "trace_kappa", old_trace_kappa)
    monkeypatch.setattr(step_module, "monodromy_and_abs", lambda a, r: (monodromy(FLOAT, a, r), None))
    monkeypatch.setattr(step_module, "_over_sites", old_over_sites)
    for mod in (step_module, rows_module, orbit_module):
        monkeypatch.setattr(mod, "float_status", old_float_status)


# --------------------------------------------------------------------------- recording a run

def record(fn, monkeypatch):
    """``fn()``'s result (or its error: type, message, ``where``) and every row escalated to mpmath."""
    escalated = []
    for mod in (rows_module, orbit_module):
        real = mod.escalate_rows

        def spy(pa, qa, *args, _real=real, **kw):
            escalated.append((pa.copy(), qa.copy()))
            return _real(pa, qa, *args, **kw)
        monkeypatch.setattr(mod, "escalate_rows", spy)
    try:
        out = fn()
    except (NoRealMapError, NumericRangeError) as exc:
        out = (type(exc).__name__, str(exc), getattr(exc, "where", None))
    return out, escalated


def bits(x):
    if isinstance(x, tuple) and x and isinstance(x[0], str):
        return x
    if isinstance(x, (tuple, list)):
        return [bits(y) for y in x]
    return np.asarray(x).tobytes(), np.asarray(x).shape


def same_run(fn, monkeypatch):
    """Run ``fn`` with the shipped code, then with the oracle; both must agree bit for bit."""
    with monkeypatch.context() as m:
        new, esc_new = record(fn, m)
    with monkeypatch.context() as m:
        use_oracle(m)
        old, esc_old = record(fn, m)
    assert bits(new) == bits(old)
    assert bits(esc_new) == bits(esc_old)
    return new, esc_new


# --------------------------------------------------------------------------- the sweep

P3, Q3 = np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9])


def band_edges(p, q, lo=-40.0, hi=40.0, n=4001):
    """Points where ``|tr L(lam)| = 2`` (bisection of the literal trace on a grid)."""
    lam = np.linspace(lo, hi, n)
    f = np.array([abs(float(spectral_trace(x, p, q))) - 2.0 for x in lam])
    out = []
    for i in np.flatnonzero(np.sign(f[:-1]) != np.sign(f[1:])):
        a, b = lam[i], lam[i + 1]
        for _ in range(80):
            c = 0.5 * (a + b)
            if np.sign(abs(float(spectral_trace(c, p, q))) - 2.0) == np.sign(f[i]):
                a = c
            else:
                b = c
        out.append(0.5 * (a + b))
    return out


def sweep_batch(M, seed):
    """``M`` (>= 8) states of the paper's example (perturbed) at spectral parameters across bands and gaps;
    the first eight are the example itself: ``lam1`` then ``lam2`` inside each of two bands, and ``lam1``
    within 1e-9 .. 1e-12 of four band edges (ill-conditioned: escalated)."""
    rng = np.random.default_rng(seed)
    p = P3 + 0.05 * rng.normal(size=(M, 3))
    q = Q3 + 0.05 * rng.normal(size=(M, 3))
    lam0 = rng.uniform(-30, 30, M)
    mu = rng.choice([0.5, 2.0, 5.0, 12.0], M) * rng.choice([-1.0, 1.0], M)
    e = band_edges(P3, Q3)
    p[:8], q[:8], mu[:8] = P3, Q3, 1.0
    mids = [0.5 * (e[0] + e[1]), 0.5 * (e[2] + e[3])]
    lam0[:4] = [mids[0] - 1.0, mids[0] + 1.0, mids[1] - 1.0, mids[1] + 1.0]
    lam0[4:8] = [e[0] - 1.0 - 1e-9, e[1] - 1.0 + 1e-9, e[2] - 1.0 - 1e-12, e[3] - 1.0 + 1e-12]
    return p, q, lam0, mu


def statuses(p, q, lam0, mu, branch=1):
    with np.errstate(all="ignore"):
        Pn, Qn, aux = step_module.step_core(FLOAT, list(p.T.copy()), list(q.T.copy()), lam0, mu, branch,
                                            check_real=False)
    return step_module.float_status(aux, Pn, Qn)


@pytest.mark.parametrize("M", [FEW_ROWS - 3, 3 * FEW_ROWS, SIDE_BY_SIDE_ROWS + 100])
def test_a_batch_across_bands_gaps_and_edges_is_the_route_before(M, monkeypatch):
    p, q, lam0, mu = sweep_batch(M, seed=22 + M)
    st = statuses(p, q, lam0, mu)
    assert {OK, TRACE1, TRACE2, POSITIVITY} <= set(st.tolist()) and ILLCOND in st    # every verdict is met
    (pt, qt), escalated = same_run(lambda: bt_step(p, q, lam0, mu, backend="numpy", allow_complex=True),
                                   monkeypatch)
    assert escalated and sum(x[0].shape[0] for x in escalated) >= 2
    # and statuses one by one: float_status against the oracle's
    new = statuses(p, q, lam0, mu)
    with monkeypatch.context() as m:
        use_oracle(m)
        assert new.tolist() == statuses(p, q, lam0, mu).tolist()


def test_a_failing_batch_raises_the_same_error(monkeypatch):
    p, q, lam0, mu = sweep_batch(12, seed=5)
    out, _ = same_run(lambda: bt_step(p, q, lam0, mu, backend="numpy"), monkeypatch)
    assert out[0] == "NoRealMapError" and out[2]


@pytest.mark.parametrize("name", ["n64-chain", "n256-chain"])
@pytest.mark.parametrize("M", [1, FEW_ROWS + 4])
def test_the_chains_take_the_sharp_tier_as_before(name, M, monkeypatch):
    c = QUICK[name]
    rng = np.random.default_rng(M)
    p = np.array(c.p) + 1e-3 * rng.normal(size=(M, len(c.p)))
    q = np.tile(c.q, (M, 1))
    seen = []
    real = condition.sharp_trace_kappa_rows
    monkeypatch.setattr(step_module, "sharp_trace_kappa_rows", lambda *a: seen.append(a[0].shape) or real(*a))
    same_run(lambda: bt_step(p, q, c.lam0, c.mu, backend="numpy"), monkeypatch)
    assert seen and seen[0][0] == M                # the sharp tier decided every row


@pytest.mark.parametrize("name", ["paper-mu2", "n2-inner-gap", "n64-chain"])
def test_orbits_on_the_numpy_route_are_the_route_before(name, monkeypatch):
    c = QUICK[name]
    n = min(c.n, 40)
    same_run(lambda: bt_orbit(np.array(c.p), np.array(c.q), c.lam0, c.mu, n, branch=c.branch,
                              backend="numpy"), monkeypatch)


def test_an_orbit_through_a_band_edge_escalates_the_same_steps(monkeypatch):
    e = band_edges(P3, Q3)[1]
    _, escalated = same_run(lambda: bt_orbit(P3, Q3, e - 1.0 + 1e-11, 1.0, 3, backend="numpy"), monkeypatch)
    assert escalated


# --------------------------------------------------------------------------- the two forms, function by function

def _random_rows(rng, R, N):
    scale = float(rng.choice([1.0, 1e3, 1e60, 1e-100]))
    p = rng.normal(size=(R, N)) * scale
    with np.errstate(over="ignore"):
        r = np.exp(rng.normal(size=(R, N)) * float(rng.choice([0.1, 3.0, 50.0, 300.0])))
    lam = rng.normal(size=R) * scale
    return p, r, lam, rng.normal(size=R) * 1e-17 * np.abs(lam)


def _same_bits(x, y):
    x, y = np.asarray(x, float), np.asarray(y, float)    # NaNs compared as NaNs (their sign bit is not a result)
    return (np.array_equal(np.isnan(x), np.isnan(y))
            and np.where(np.isnan(x), 0.0, x).tobytes() == np.where(np.isnan(y), 0.0, y).tobytes())


def test_sharp_rows_equal_the_scalar_form_on_random_rows():
    rng = np.random.default_rng(2022)
    kinds = {"nan": 0, "inf": 0, "finite": 0}
    for _ in range(150):
        N, R = int(rng.choice([1, 2, 3, 8, 64])), int(rng.choice([1, FEW_ROWS, FEW_ROWS + 1, 40]))
        p, r, lam, lo = _random_rows(rng, R, N)
        with np.errstate(all="ignore"):
            ref = np.array([sharp_trace_kappa(p[k], r[k], float(lam[k]), float(lo[k])) for k in range(R)])
        assert _same_bits(sharp_trace_kappa_rows(p, r, lam, lo), ref)
        with np.errstate(all="ignore"):
            assert _same_bits(condition._sharp_over_rows(p, r, lam, lo), ref)     # the many-rows form at any R
        kinds["nan"] += int(np.isnan(ref).sum())
        kinds["inf"] += int(np.isinf(ref).sum())
        kinds["finite"] += int(np.isfinite(ref).sum())
    assert min(kinds.values()) > 10


def test_abs_trace_rows_equals_the_monodromy_of_the_absolute_values():
    rng = np.random.default_rng(2023)
    renormalised = 0
    for _ in range(150):
        N, R = int(rng.choice([1, 2, 3, 8, 64, 256])), int(rng.choice([1, 3, FEW_ROWS, FEW_ROWS + 1]))
        p, r, lam, _ = _random_rows(rng, R, N)
        a, rr = [lam + p[:, j] for j in range(N)], [r[:, j] for j in range(N)]
        with np.errstate(all="ignore"):
            Aa, _, _, Da, ea = monodromy(FLOAT, [np.abs(x) for x in a], [-x for x in rr])
            T, e = abs_trace_rows(a, rr)
        assert _same_bits(T, Aa + Da)
        assert np.broadcast_to(e, (R,)).tolist() == np.broadcast_to(ea, (R,)).tolist()
        renormalised += int(np.any(np.asarray(ea) != 0))
    assert renormalised > 10


def test_one_sweep_of_both_products_equals_the_two_products():
    from symbt.numeric.core.condition import monodromy_and_abs

    rng = np.random.default_rng(2024)
    seen = {"main renormalised": 0, "abs renormalised": 0, "abs only": 0}
    for _ in range(100):
        N, R = int(rng.choice([2, 3, 64, 300, 600])), int(rng.choice([1, 3, FEW_ROWS, FEW_ROWS + 1, 40]))
        p, r, lam, _ = _random_rows(rng, R, N)
        p[: R // 2] *= 1e-3 * N               # some rows near the spectrum, some far from it
        if N == 600:                          # inside a band: |M| bounded, the product of the |m_j| ~ 2.35**N
            p[::3], r[::3], lam[::3] = 0.0, 1.0, 1.9
        a, rr = [lam + p[:, j] for j in range(N)], [r[:, j] for j in range(N)]
        with np.errstate(all="ignore"):
            main, (T, e) = monodromy_and_abs(a, rr)
            ref = monodromy(FLOAT, a, rr)
            Aa, _, _, Da, ea = monodromy(FLOAT, [np.abs(x) for x in a], [-x for x in rr])
        for x, y in zip(main, ref):
            assert _same_bits(np.broadcast_to(x, (R,)), np.broadcast_to(y, (R,)))
            assert type(x) is type(y) and np.asarray(x).dtype == np.asarray(y).dtype
        assert _same_bits(T, Aa + Da) and np.broadcast_to(e, (R,)).tolist() == np.broadcast_to(ea, (R,)).tolist()
        em, eab = np.broadcast_to(ref[4], (R,)) != 0, np.broadcast_to(ea, (R,)) != 0     # per row
        seen["main renormalised"] += int(em.sum())
        seen["abs renormalised"] += int(eab.sum())
        seen["abs only"] += int((eab & ~em).sum())
    assert min(seen.values()) > 3


@pytest.mark.parametrize("N", [8, 128])
def test_wide_batches_far_from_the_spectrum_are_the_route_before(N, monkeypatch):
    rng = np.random.default_rng(N)                # the benchmark's bt_step rows: renormalised products
    p, q = rng.normal(size=(40, N)), 0.5 * rng.normal(size=(40, N))
    same_run(lambda: bt_step(p, q, 3.0 * N + 20.0, 2.0, backend="numpy"), monkeypatch)


def test_one_sweep_where_every_row_of_both_products_is_renormalised():
    from symbt.numeric.core.condition import monodromy_and_abs

    rng = np.random.default_rng(128)              # the benchmark's wide rows: far from the spectrum
    N, R = 128, 40
    p, q = rng.normal(size=(R, N)), 0.5 * rng.normal(size=(R, N))
    a = [3.0 * N + 20.0 + p[:, j] for j in range(N)]
    rr = [np.exp(q[:, (j + 1) % N] - q[:, j]) for j in range(N)]
    main, (T, e) = monodromy_and_abs(a, rr)
    ref = monodromy(FLOAT, a, rr)
    Aa, _, _, Da, ea = monodromy(FLOAT, [np.abs(x) for x in a], [-x for x in rr])
    assert np.all(ref[4] != 0) and np.all(ea != 0)         # the case: every row renormalised in both
    for x, y in zip(main, ref):
        assert _same_bits(x, y) and np.asarray(x).dtype == np.asarray(y).dtype
    assert _same_bits(T, Aa + Da) and np.asarray(e).tolist() == np.asarray(ea).tolist()
    assert np.asarray(e).dtype == np.asarray(ea).dtype
