"""The two-tier float64 condition estimate (issue: n64-chain / n256-chain escalated to mpmath every step).

The cheap trace condition ``T |t| / |t**2 - 4|`` (``T`` = trace of the product of the entrywise absolute
values) stays where it passes; where it would escalate, the sharp first-order scale of
:func:`symbt.numeric.core.condition.sharp_trace_kappa` decides.  Judged here against routes that do not share its
derivation: finite differences of the literal trace (:mod:`symbt.reference`) at 60 digits for the trace's
actual sensitivity, and the 50-digit literal step for the documented accuracy bound ``32 N eps kappa rho s``.
"""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from symbt.benchmarks.cases import cases
from symbt.numeric import bt_orbit, bt_step
from symbt.numeric.core.condition import sharp_trace_kappa
from symbt.numeric.core.context import FLOAT
from symbt.numeric.core.limits import KAPPA_MAX, OK
from symbt.numeric.core.monodromy import neighbour_ratios
from symbt.numeric.core.spectral_sum import lam_add, lam_split
from symbt.numeric.core.step import float_status, sharpened, step_core
from symbt.reference.literal import reference_step

EPS = 2.0 ** -52
QUICK = {c.name: c for c in cases(quick=True)}
STEPS = {"n64-chain": 20, "n256-chain": 2}       # the quick cases' step counts (BENCHMARKS.md)


def _case(name):
    c = QUICK[name]
    return np.array(c.p, float), np.array(c.q, float), float(c.lam0), float(c.mu)


def _states(name):
    """The quick case's float64 orbit (its states are what every step of the benchmark starts from)."""
    p, q, lam0, mu = _case(name)
    P, Q = bt_orbit(p, q, lam0, mu, STEPS[name], backend="numpy")
    return [(P[i], Q[i]) for i in range(P.shape[0])], lam0, mu


def _kernel_status(p, q, lam0, mu, n, backend):
    from symbt.numeric.float64.orbit import _single

    return _single(p, q, lam0, mu, 1, n, 1, backend)[2]


def _block_status(p, q, lam0, mu, n, backend):
    from symbt.numeric.float64.orbit import _ensemble

    M = 2
    P = np.empty((n + 1, M, p.size))
    Q = np.empty((n + 1, M, p.size))
    st = np.zeros(M, np.int64)
    _ensemble(np.array([p, p]), np.array([q, q]), lam0, mu, 1, n, 1, backend, np.arange(M), P, Q, st)
    return st.tolist()


def _numpy_status(states, lam0, mu):
    P = np.array([s[0] for s in states])
    Q = np.array([s[1] for s in states])
    with np.errstate(all="ignore"):
        Pn, Qn, aux = step_core(FLOAT, list(P.T.copy()), list(Q.T.copy()), lam0, mu, 1, check_real=False)
    return float_status(aux, Pn, Qn).tolist(), aux


@pytest.mark.parametrize("name", sorted(STEPS))
@pytest.mark.parametrize("backend", ["python", "numba"])
def test_quick_cases_run_without_escalation_in_the_fused_kernel(name, backend):
    pytest.importorskip("numba") if backend == "numba" else None
    p, q, lam0, mu = _case(name)
    assert _kernel_status(p, q, lam0, mu, STEPS[name], backend) == OK        # was ILLCOND (5)


@pytest.mark.parametrize("name", sorted(STEPS))
@pytest.mark.parametrize("backend", ["python", "numba"])
def test_quick_cases_run_without_escalation_in_the_block_kernel(name, backend):
    pytest.importorskip("numba") if backend == "numba" else None
    p, q, lam0, mu = _case(name)
    assert _block_status(p, q, lam0, mu, STEPS[name], backend) == [OK, OK]


@pytest.mark.parametrize("name", sorted(STEPS))
def test_quick_cases_run_without_escalation_in_the_numpy_rows(name, monkeypatch):
    import symbt.numeric.float64.rows as rows

    def refuse(*args, **kw):
        raise AssertionError("escalated to mpmath")

    states, lam0, mu = _states(name)
    st, _ = _numpy_status(states, lam0, mu)
    assert st == [OK] * len(states)
    monkeypatch.setattr(rows, "escalate_rows", refuse)
    p, q = states[0]
    bt_step(np.array([p, p]), np.array([q, q]), lam0, mu, backend="numpy")


def _trace_fd_sensitivity(p, q, lam):
    """``sum_j`` over the nonzero entries ``e`` of ``m_j`` of ``|e dt/de|``: the first-order change of ``tr M``
    under relative perturbations of every entry, by finite differences of the product at 60 digits (the
    exact product of the rounded float64 inputs)."""
    with mp.workdps(60):
        N = len(p)
        a = [mp.mpf(float(x)) for x in p]
        lam_m = mp.mpf(lam)
        r = [mp.exp(mp.mpf(float(q[(j + 1) % N])) - mp.mpf(float(q[j]))) for j in range(N)]
        ms = [mp.matrix([[lam_m + a[j], -1], [r[j], 0]]) for j in range(N)]

        def tr(mats):
            M = mp.eye(2)
            for m in mats:
                M = m * M
            return M[0, 0] + M[1, 1]

        t = tr(ms)
        h = mp.mpf(10) ** -25
        sens = mp.mpf(0)
        for j in range(N):
            for (i, k) in ((0, 0), (0, 1), (1, 0)):
                m2 = ms[j].copy()
                m2[i, k] *= 1 + h
                sens += abs(tr(ms[:j] + [m2] + ms[j + 1:]) - t) / h
        return float(sens), float(t)


@pytest.mark.parametrize("name", ["n64-chain"])
def test_sharp_scale_lies_between_the_actual_sensitivity_and_the_cheap_bound(name):
    """``sens / N <= Ts <= T`` per trace: the sharp scale bounds the actual first-order sensitivity
    (finite differences, not the prefix/suffix sum) and never exceeds the cheap scale; and it is far below it."""
    p, q, lam0, mu = _case(name)
    N = p.size
    r = np.array([float(x) for x in neighbour_ratios(FLOAT, [np.array(x) for x in q])])
    lo1, lo2 = lam_split(lam0 + mu, lam0 - mu, 2 * mu)
    for lam, lo in ((lam0 + mu, lo1), (lam0 - mu, lo2)):
        sens, t = _trace_fd_sensitivity(p, q, lam)
        ks = sharp_trace_kappa(p, r, lam, lo)
        a = np.array([lam_add(lam, lo, x) for x in p])
        ka = float(np.max((abs(lam) + np.abs(p)) / np.abs(a)))
        Ts = ks / ka * abs(t * t - 4) / abs(t)
        T = np.trace(np.linalg.multi_dot([np.abs(np.array([[x, -1.0], [rj, 0.0]])) for x, rj in
                                          zip(a[::-1], r[::-1])]))
        assert sens / N <= Ts * (1 + 1e-9), (sens / N, Ts)
        assert Ts <= T * (1 + 1e-9)
    # the numbers: at lam = 3.5 the cheap T / |t| ~ 2.4e6, the sharp one O(1)
    lam = lam0 - mu
    ks = sharp_trace_kappa(p, r, lam, lo2)
    assert 1.0 <= ks <= 100.0, ks


def _bound_check(p, q, lam0, mu, route):
    """``max |x - x_ref| <= 32 N eps kappa rho s`` with ``kappa`` the two-tier estimate (the numpy rows' aux),
    the reference the literal step at 50 digits; returns ``(err, bound, kappa)``."""
    _, aux = _numpy_status([(p, q)], lam0, mu)
    S1, S2 = aux["S1"], aux["S2"]
    rows = np.array([True])
    k1 = np.fmin(S1.kappa, sharpened(S1, rows))[0]
    k2 = np.fmin(S2.kappa, sharpened(S2, rows))[0]
    kt = max(k1, k2)
    u, w, xr = aux["u"], aux["w"], aux["xr"]
    kappa = max(float(kt * (abs(u[j][0]) + abs(w[j][0])) / abs(u[j][0] - w[j][0])
                      * (1 + abs(xr[j][0]) / abs(1 + xr[j][0]))) for j in range(p.size))
    pt, qt = route(p, q, lam0, mu)
    with mp.workdps(50):
        rp, rq = reference_step([mp.mpf(float(x)) for x in p], [mp.mpf(float(x)) for x in q], mp.mpf(lam0),
                                mp.mpf(mu), branch=1)
    ref = np.array([float(x) for x in list(rp) + list(rq)])
    got = np.concatenate([pt, qt])
    err = float(np.max(np.abs(got - ref)))
    rho = 1 + float(np.max(np.abs(np.roll(q, -1) - q)))
    s = max(float(np.max(np.abs(np.concatenate([p, q, got])))), abs(lam0) + abs(mu))
    return err, 32 * p.size * EPS * kappa * rho * s, kappa


ROUTES = {"kernel": lambda p, q, l, m: bt_step(p, q, l, m, backend="python"),
          "numpy": lambda p, q, l, m: bt_step(p, q, l, m, backend="numpy")}


@pytest.mark.parametrize("route", sorted(ROUTES))
@pytest.mark.parametrize("name,index", [("n64-chain", 0), ("n64-chain", 10), ("n64-chain", 20),
                                        ("n256-chain", 0), ("n256-chain", 2)])
def test_accuracy_bound_holds_with_the_sharp_kappa_on_the_quick_cases(name, index, route):
    states, lam0, mu = _states(name)
    p, q = states[index]
    err, bound, kappa = _bound_check(p, q, lam0, mu, ROUTES[route])
    assert kappa <= KAPPA_MAX                   # decided in float64 (the premise: no escalation)
    assert err <= bound, (err, bound, kappa)
    assert bound <= 1e-8 * max(np.max(np.abs(p)), 1.0)      # and the guarantee says something


# near-closed gaps (tests/test_numeric_existence.py's GAP, less closed): tr L(lam_i) close to -2
GAPS = [(np.array([0, d, 0, 0, 0, 0]), np.array([0, d, 0, 0, 0, 0]), -2.5754513054971884e-08 * (d / 1.192092896e-07),
         -2.859114757386928e-08 * (d / 1.192092896e-07)) for d in (1e-4, 1e-3, 1e-2)]


@pytest.mark.parametrize("route", sorted(ROUTES))
@pytest.mark.parametrize("case", range(len(GAPS)))
def test_accuracy_bound_holds_near_closed_gaps(case, route):
    p, q, lam0, mu = GAPS[case]
    err, bound, kappa = _bound_check(p, q, lam0, mu, ROUTES[route])
    if kappa <= KAPPA_MAX:
        assert err <= bound, (err, bound, kappa)
    else:                                       # escalated: rounded from the higher-precision step
        assert err <= 4 * EPS * max(1.0, float(np.max(np.abs(np.concatenate([p, q])))))
