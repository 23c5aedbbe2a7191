"""Existence decided alike on every numeric route, and accuracy near closed gaps (issue 21, issue 26 item 3).

The judge is the literal map of :mod:`symbt.reference` at 60 digits (a complex result: no real map).
"""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from symbt.numeric import NoRealMapError, bt_orbit, bt_step
from symbt.numeric.core.limits import ILLCOND, KAPPA_MAX
from symbt.numeric.float64.rows import escalate_rows
from symbt.reference.literal import literal_trace, reference_step

EPS = 2.0 ** -52

# lam1, lam2 in different gaps with traces of opposite signs (tr1 ~ -1.4e11, tr2 ~ +4.1e15), found by the fuzz:
# the rounded Etilde_j came out positive, and every float64 route returned a finite state
ACROSS = (np.array([0.28719213289277035, -0.5354112941976452]), np.array([-50.273358751315875, -95.54491846658226]),
          -6770238226.469732, 150674.52529335022, -1)
# the issue's examples (traces of opposite signs; decided by the positivity test already)
ISSUE = [(np.zeros(2), np.array([0.0, 19.0]), float(np.exp(9.5)), 0.3 * float(np.exp(9.5)), 1),
         (np.zeros(2), np.array([0.0, 200.0]), 2.5e43, 0.5e43, 1)]
# a nearly closed gap: tr L(lam_i) = -2 - 7e-15 and -2 - 1.3e-14 (issue 26 item 3): relative error 8.3e-4 before
GAP = (np.array([0, 1.192092896e-07, 0, 0, 0, 0]), np.array([0, 1.192092896e-07, 0, 0, 0, 0]),
       -2.5754513054971884e-08, -2.859114757386928e-08, 1)

FLOAT_ROUTES = {
    "kernel": lambda p, q, l, m, b: bt_step(p, q, l, m, branch=b),
    "python": lambda p, q, l, m, b: bt_step(p, q, l, m, branch=b, backend="python"),
    "numpy": lambda p, q, l, m, b: bt_step(p, q, l, m, branch=b, backend="numpy"),
    "block": lambda p, q, l, m, b: tuple(x[1] for x in bt_step(np.array([p, p]), np.array([q, q]), l, m, branch=b,
                                                              backend="numba")),
    "rows": lambda p, q, l, m, b: tuple(x[1] for x in bt_step(np.array([p, p]), np.array([q, q]), l, m, branch=b,
                                                             backend="numpy")),
    "orbit": lambda p, q, l, m, b: tuple(x[1] for x in bt_orbit(p, q, l, m, 1, branch=b)),
    "orbit-numpy": lambda p, q, l, m, b: tuple(x[1] for x in bt_orbit(p, q, l, m, 1, branch=b, backend="numpy")),
    "ensemble": lambda p, q, l, m, b: tuple(x[1, 1] for x in bt_orbit(np.array([p, p]), np.array([q, q]), l, m, 1,
                                                                      branch=b)),
}
MP_BACKENDS = ("qd", "flint", "mpmath")


def _literal(case):
    p, q, lam0, mu, b = case
    with mp.workdps(60):
        pt, qt = reference_step([mp.mpf(float(x)) for x in p], [mp.mpf(float(x)) for x in q], mp.mpf(lam0),
                                mp.mpf(mu), branch=b)
    return list(pt) + list(qt)


def _traces(case):
    p, q, lam0, mu, _ = case
    with mp.workdps(40):
        P, Q = [mp.mpf(float(x)) for x in p], [mp.mpf(float(x)) for x in q]
        return [literal_trace(mp.mpf(lam0) + s * mp.mpf(mu), P, Q) for s in (1, -1)]


@pytest.mark.parametrize("route", sorted(FLOAT_ROUTES))
@pytest.mark.parametrize("case", [ACROSS] + ISSUE, ids=["fuzz-found", "issue-q19", "issue-q200"])
def test_no_real_map_across_gaps_on_every_float_route(route, case):
    t1, t2 = _traces(case)
    assert t1 * t2 < 0 and abs(t1) > 2 and abs(t2) > 2          # different gaps: no real map ...
    assert not all(isinstance(v, mp.mpf) for v in _literal(case))   # ... and the literal map agrees
    p, q, lam0, mu, b = case
    with pytest.raises(NoRealMapError) as err:
        FLOAT_ROUTES[route](p, q, lam0, mu, b)
    assert err.value.condition == "positivity"


@pytest.mark.parametrize("backend", MP_BACKENDS)
@pytest.mark.parametrize("case", [ACROSS] + ISSUE, ids=["fuzz-found", "issue-q19", "issue-q200"])
def test_no_real_map_across_gaps_on_every_mp_route(backend, case):
    p, q, lam0, mu, b = case
    with mp.workdps(30):
        with pytest.raises(NoRealMapError) as err:
            bt_step([mp.mpf(float(x)) for x in p], [mp.mpf(float(x)) for x in q], mp.mpf(lam0), mp.mpf(mu),
                    branch=b, backend=backend)
    assert err.value.condition == "positivity"


def test_opposite_trace_signs_raise_from_the_traces_not_from_rounding():
    """The sign test reports itself (its message names the traces' signs) on the mp route."""
    p, q, lam0, mu, b = ACROSS
    with mp.workdps(30), pytest.raises(NoRealMapError, match="opposite signs"):
        bt_step([mp.mpf(float(x)) for x in p], [mp.mpf(float(x)) for x in q], mp.mpf(lam0), mp.mpf(mu), branch=b,
                backend="mpmath")


@pytest.mark.parametrize("route", sorted(FLOAT_ROUTES))
def test_nearly_closed_gap_is_accurate_on_every_float_route(route):
    """kappa of the float64 formulation is ~1e14 here: the state is recomputed at higher precision."""
    ref = _literal(GAP)
    p, q, lam0, mu, b = GAP
    pt, qt = FLOAT_ROUTES[route](p, q, lam0, mu, b)
    got = np.concatenate([pt, qt])
    scale = max(float(max(abs(v) for v in ref)), float(np.max(np.abs(p))), abs(lam0) + abs(mu))
    err = max(abs(float(a) - float(r)) for a, r in zip(got, ref)) / scale
    assert err <= 4 * EPS, err                  # rounded from the higher-precision step (was 8.3e-4)


def test_nearly_closed_gap_is_flagged_by_the_kernel():
    from symbt.numeric.float64.orbit import _single

    p, q, lam0, mu, b = GAP
    for backend in ("numba", "python"):
        assert _single(p, q, lam0, mu, b, 1, 1, backend)[2] == ILLCOND


def test_escalation_decides_an_exact_band_edge():
    """The free chain's trace at lam = 0 is exactly -2 for N = 2 (a band edge): no real map, on every route."""
    for route in FLOAT_ROUTES.values():
        with pytest.raises(NoRealMapError):
            route(np.zeros(2), np.zeros(2), 0.5, -0.5, 1)          # lam1 = 0 on the edge, lam2 = 1 in the band
    _, _, st = escalate_rows(np.zeros((1, 2)), np.zeros((1, 2)), 1.5, 1.5, 1)  # lam1 = 3, lam2 = 0: edge
    assert st.tolist() == [2]


def test_kappa_threshold_is_what_the_docs_say():
    assert KAPPA_MAX == 2.0 ** 24


# lam ~ 1e88 at |q_2 - q_1| = 409 (kappa ~ 2e15): the given input has no real map, but its re-centred copy
# (q - mean(q), rounded) has one -- the orbit's general path must decide on the given input (fuzz-found)
FAR = (np.array([3.039639003075365, 2.0729077060997194]), np.array([-204.5974906157231, 204.59749061572313]),
       -7.170475903275937e+88, -2.1802594905911873e+84, -1)


@pytest.mark.parametrize("route", sorted(FLOAT_ROUTES))
def test_ill_conditioned_far_state_is_decided_on_the_given_input(route):
    assert not all(isinstance(v, mp.mpf) for v in _literal(FAR))
    with pytest.raises(NoRealMapError):
        FLOAT_ROUTES[route](*FAR)


# lam1 ~ lam2 ~ -p_2 at |q_{j+1} - q_j| ~ 550: the slope difference d_2 cancels; the exact map is ill-conditioned
# (a relative change of lam0 by 1e-17 moves q~_2 by 0.02) and every route returned q~_2 off by 0.1 (fuzz-found)
CANCEL = (np.array([-1.2645478634923202, 0.2464648524730024, 0.3255132303147244]),
          np.array([178.4767173369139, 189.5786335005842, -368.0553508374982]),
          -0.24646485247300448, 1.9567680809018384e-15, 1)


@pytest.mark.parametrize("route", sorted(FLOAT_ROUTES))
def test_cancelling_slope_difference_is_escalated(route):
    ref = _literal(CANCEL)
    pt, qt = FLOAT_ROUTES[route](*CANCEL[:4], CANCEL[4])
    err = max(abs(float(a) - float(r)) for a, r in zip(np.concatenate([pt, qt]), ref))
    assert err <= 4 * EPS * 368.1, err
