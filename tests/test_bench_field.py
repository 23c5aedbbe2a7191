"""The one float64 Hamiltonian vector field (symbt.numeric.flow.field.FlowField) against 50-digit routes:
the polynomial H_k for small N, mpmath.diff of an mpmath evaluation of G = sum c_k H_k for N = 64."""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from symbt.benchmarks.cases import chain
from symbt.numeric import flow_coefficients, invariants
from symbt.numeric.flow.field import FlowField, _gradient_renormalised, transfer_gradient
from symbt.reference.taylor import hamilton_equations
from symbt.reference.trace import bonds

P0, Q0 = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9)
SMALL = {"N2-bounded-gap": ((3.0, -1.0), (0.4, -0.3), -1.0, 1.5), "N3-paper-mu5": (P0, Q0, 10.0, 5.0),
         "N3-paper-mu2": (P0, Q0, 10.0, 2.0), "N5-chain": (*chain(5, 5), 6.0, 2.0)}


def _c50(p, q, lam0, mu):
    return flow_coefficients([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(lam0), mp.mpf(mu))


def _polynomial_field(p, q, c):
    """(qdot, pdot) at mp precision from the explicit polynomials of sum c_k H_k (reference.taylor)."""
    N = len(p)
    vals = list(p) + bonds(q)
    out = []
    for P in hamilton_equations(N, c)[: 2 * N]:
        s = mp.mpf(0)
        for e, v in P.items():
            t = mp.mpf(v)
            for x, k in zip(vals, e):
                t *= x**k
            s += t
        out.append(s)
    return out


@pytest.mark.parametrize("name", list(SMALL))
def test_small_N_against_50_digit_polynomial_field(name):
    p0, q0, lam0, mu = SMALL[name]
    f = FlowField(p0, q0, lam0, mu)
    rng = np.random.default_rng(3)
    P = np.array(p0) + 0.05 * rng.normal(size=(4, len(p0)))       # a batch near the initial torus
    Q = np.array(q0) + 0.05 * rng.normal(size=(4, len(p0)))
    qd, pd = f(P, Q)
    with mp.workdps(50):
        c = _c50(p0, q0, lam0, mu)
        for i in range(4):
            ref = _polynomial_field([mp.mpf(v) for v in P[i]], [mp.mpf(v) for v in Q[i]], c)
            got = np.r_[qd[i], pd[i]]
            err = mp.sqrt(mp.fsum((mp.mpf(float(a)) - b) ** 2 for a, b in zip(got, ref)))
            assert err <= 4e-15 * mp.sqrt(mp.fsum(b**2 for b in ref)), (name, i, float(err))
    # one state at a time gives the same numbers as the batch
    q1, p1 = f(P[2], Q[2])
    np.testing.assert_allclose(np.r_[q1, p1], np.r_[qd[2], pd[2]], rtol=1e-15, atol=0)


def test_n64_against_mpmath_diff_of_G():
    p0, q0 = chain(64, 64)
    f = FlowField(p0, q0, 5.0, 1.5)
    rng = np.random.default_rng(64)
    p = np.array(p0) + 0.01 * rng.normal(size=64)
    q = np.array(q0) + 0.01 * rng.normal(size=64)
    qd, pd = f(p, q)
    grad = np.r_[-pd, qd]                        # (dG/dq, dG/dp)
    with mp.workdps(50):
        c = _c50(p0, q0, 5.0, 1.5)
        Q, P = [mp.mpf(v) for v in q], [mp.mpf(v) for v in p]

        def G(t, v):                             # G along the line (q, p) + t v, at 50 digits
            H = invariants([a + t * b for a, b in zip(P, v[64:])], [a + t * b for a, b in zip(Q, v[:64])])
            return mp.fsum(ck * h for ck, h in zip(c, H))

        for _ in range(3):
            v = rng.normal(size=128)
            d = mp.diff(lambda t: G(t, [mp.mpf(x) for x in v]), 0)
            assert abs(float(d) - grad @ v) <= 1e-14 * np.linalg.norm(grad) * np.linalg.norm(v)


def test_n64_compressed_rule_gives_the_composite_field():
    p0, q0 = chain(64, 64)
    f = FlowField(p0, q0, 5.0, 1.5)
    g = FlowField(p0, q0, 5.0, 1.5, compress=None)
    assert f.m <= 64 < g.m                        # one Gauss-Legendre rule instead of the composite panels
    rng = np.random.default_rng(1)
    P = np.array(p0) + 0.01 * rng.normal(size=(3, 64))
    Q = np.array(q0) + 0.01 * rng.normal(size=(3, 64))
    a, b = np.concatenate(f(P, Q), -1), np.concatenate(g(P, Q), -1)
    assert np.max(np.linalg.norm(a - b, axis=-1) / np.linalg.norm(b, axis=-1)) < 3e-15
    # the composite rule's c~_k are the c_k (the compressed rule's small-k ones need not be: see FlowField)
    c = flow_coefficients(np.array(p0), np.array(q0), 5.0, 1.5)
    assert np.max(np.abs(g.c - c) / np.abs(c)) < 1e-14


def test_renormalised_sweep_equals_plain_sweep_and_generated_field():
    rng = np.random.default_rng(7)
    a = [rng.normal(size=(3, 2)) for _ in range(9)]
    r = [np.exp(rng.normal(size=(3, 2))) for _ in range(9)]
    inv = np.full((3, 2), 0.5)
    da, dr = transfer_gradient(a, r, inv)
    da2, dr2 = _gradient_renormalised(a, r, inv)
    np.testing.assert_allclose(np.stack(da), da2, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(np.stack(dr), dr2, rtol=1e-12, atol=1e-14)
    gen = pytest.importorskip("symbt.generated.toda3")
    f = FlowField(P0, Q0, 10.0, 5.0)
    with mp.workdps(30):
        c = np.array([float(v) for v in _c50(P0, Q0, 10.0, 5.0)])
    qd, pd = f(np.array(P0), np.array(Q0))
    gq, gp = gen.flow_field(c, np.array(P0), np.array(Q0))
    np.testing.assert_allclose(np.r_[qd, pd], np.r_[gq, gp], rtol=0, atol=1e-15 * np.linalg.norm(np.r_[gq, gp]))
