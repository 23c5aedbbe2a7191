"""Invariants, spectral trace, the real Φ and the flow coefficients."""

import mpmath
import numpy as np
import pytest

from symbt.benchmarks.numeric_cases import outer_gap_case, random_gap_case
from symbt.numeric import NoRealMapError, bt_step, flow_coefficients, invariants, phi, spectral_trace
from symbt.numeric.core.context import FLOAT
from symbt.numeric.core.step import step_core
from symbt.reference.literal import literal_trace

P0 = np.array([-20.0, 10.0, 1.0])
Q0 = np.array([1.0, 0.0, 0.9])


def test_invariants_n3_closed_form():
    p, q = P0, Q0
    H = invariants(p, q)
    H2 = p[0] * p[1] + p[1] * p[2] + p[2] * p[0] - np.exp(q[0] - q[2]) - np.exp(q[1] - q[0]) - np.exp(q[2] - q[1])
    H0 = p[0] * p[1] * p[2] - p[1] * np.exp(q[0] - q[2]) - p[2] * np.exp(q[1] - q[0]) - p[0] * np.exp(q[2] - q[1])
    np.testing.assert_allclose(H, [H0, H2, p.sum()], rtol=1e-14)


@pytest.mark.parametrize("N", [2, 3, 5, 8, 20])
def test_trace_polynomial_matches_literal(N):
    rng = np.random.default_rng(N)
    p, q = rng.normal(size=N) * 3, rng.normal(size=N)
    H = invariants(p, q)
    with mpmath.workdps(40):
        for lam in (-2.5, 0.3, 4.0):
            ref = literal_trace(lam, list(p), list(q))
            poly = sum(H[k] * lam**k for k in range(N)) + lam**N
            assert abs(spectral_trace(lam, p, q) - ref) <= 1e-13 * (1 + abs(ref)) * 10 ** (N / 4)
            assert abs(poly - ref) <= 1e-11 * sum(abs(H[k] * lam**k) for k in range(N)) + 1e-11 * abs(lam) ** N
    Hb = invariants(np.stack([p, p]), np.stack([q, q]))
    assert Hb.shape == (2, N)


def test_trace_large_lambda_and_long_chain():
    rng = np.random.default_rng(1)
    p, q = rng.normal(size=64), rng.normal(size=64)
    with mpmath.workdps(60):
        ref = literal_trace(1e4, list(p), list(q))
    tr = spectral_trace(1e4, p, q)     # ~1e256: uses the power-of-two rescaling
    assert abs(tr - float(ref)) <= 1e-13 * abs(float(ref))


def _phi_from_eta(p, q, lam0, mu, branch):
    P, Q = [np.array([v]) for v in p], [np.array([v]) for v in q]
    with np.errstate(all="ignore"):
        _, _, aux = step_core(FLOAT, P, Q, lam0, mu, branch)
    gq = np.array([g[0] for g in aux["gq"]])
    eta = mu - 2 * mu * gq
    return np.sum(np.log(np.abs((eta + mu) / (eta - mu)))), eta


def test_phi_paper_example():
    assert abs(phi(P0, Q0, 10.0, 5.0) - 14.8058092992980) < 1e-12
    assert abs(phi(P0, Q0, 10.0, 5.0, branch=-1) + 14.8058092992980) < 1e-12
    s, eta = _phi_from_eta(P0, Q0, 10.0, 5.0, 1)
    np.testing.assert_allclose(eta, [4.954, 4.9505, 5.1642], atol=6e-4)
    assert abs(s - 14.8058092992980) < 1e-12
    with mpmath.workdps(40):
        v = phi([mpmath.mpf(x) for x in P0], [1, 0, mpmath.mpf("0.9")], 10, 5)
        assert abs(v - mpmath.mpf("14.8058092992980")) < 1e-12


def test_phi_equals_eta_sum_random():
    rng = np.random.default_rng(2)
    for N in (2, 3, 5):
        for _ in range(3):
            p, q, lam0, mu = random_gap_case(rng, N)
            for branch in (1, -1):
                s, _ = _phi_from_eta(p, q, lam0, mu, branch)
                assert abs(phi(p, q, lam0, mu, branch=branch) - s) < 1e-10 * (1 + abs(s))
        p, q, lam0, mu = outer_gap_case(rng, N)
        s, _ = _phi_from_eta(p, q, lam0, mu, 1)
        assert abs(phi(p, q, lam0, mu) - s) < 1e-10 * (1 + abs(s))


def test_phi_invariant_under_map():
    pt, qt = bt_step(P0, Q0, 10.0, 5.0)
    assert abs(phi(pt, qt, 10.0, 5.0) - phi(P0, Q0, 10.0, 5.0)) < 1e-12


def test_flow_coefficients_paper_and_mpmath():
    c = flow_coefficients(P0, Q0, 10.0, 5.0)
    np.testing.assert_allclose(c, [-0.005, -0.048, -0.512], atol=1.5e-3)  # paper's caption
    c2 = flow_coefficients(P0, Q0, 10.0, 2.0)
    np.testing.assert_allclose(c2, [-0.0018, -0.0183, -0.1849], atol=1e-4)  # Fig. 2 caption
    with mpmath.workdps(30):
        cm = flow_coefficients([mpmath.mpf(v) for v in P0], list(Q0), 10, 5)
    np.testing.assert_allclose(c, [float(v) for v in cm], rtol=1e-13)
    np.testing.assert_allclose(flow_coefficients(P0, Q0, 10.0, 5.0, branch=-1), -c, rtol=0)


def test_flow_coefficients_small_mu_limit_and_near_edge():
    # c_k / (2 mu) -> -lam0^k / sqrt(tr(lam0)^2 - 4) as mu -> 0
    mu = 1e-6
    c = flow_coefficients(P0, Q0, 10.0, mu)
    t = spectral_trace(10.0, P0, Q0)
    np.testing.assert_allclose(c / (2 * mu), -(10.0 ** np.arange(3)) / np.sqrt(t * t - 4), rtol=1e-9)
    # an endpoint close to a band edge: still converges (sqrt-type singularity nearby)
    lam = np.linspace(15, 17, 200001)
    tr = spectral_trace(lam, np.broadcast_to(P0, (lam.size, 3)), np.broadcast_to(Q0, (lam.size, 3)))
    edge = lam[np.argmax(np.abs(tr) <= 2)]           # first band point above the gap
    hi = edge - 1e-3
    c = flow_coefficients(P0, Q0, 0.5 * (hi + 5.0), 0.5 * (hi - 5.0))
    with mpmath.workdps(20):
        cm = flow_coefficients([mpmath.mpf(v) for v in P0], list(Q0), 0.5 * (hi + 5.0), 0.5 * (hi - 5.0))
    np.testing.assert_allclose(c, [float(v) for v in cm], rtol=1e-10)


def test_flow_coefficients_errors():
    with pytest.raises(NoRealMapError):
        flow_coefficients(P0, Q0, 22.5, 17.5)
    np.testing.assert_array_equal(flow_coefficients(P0, Q0, 10.0, 0.0), np.zeros(3))
