"""The one flow-coefficient routine (symbt.numeric.flow.coefficients): float64 against 50 digits, the
mpmath path against an independent quadrature of the polynomial form, the reference wrapper."""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from symbt.benchmarks.cases import chain
from symbt.numeric import NoRealMapError, flow_coefficients
from symbt.reference.spectral import NoRealFlowError, flow_coefficients_mp
from symbt.reference.trace import hamiltonians

P0, Q0 = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9)
CASES = {
    "N2-bounded-gap": ((3.0, -1.0), (0.4, -0.3), -1.0, 1.5),
    "N3-paper-mu5": (P0, Q0, 10.0, 5.0),
    "N3-paper-mu2-tr<-2": (P0, Q0, 10.0, 2.0),
    "N8-chain-inner-gap": (*chain(8, 8), 2.55, 0.4),
    "N64-chain": (*chain(64, 64), 5.0, 1.5),
    "N64-far, c_0 ~ 1e-147": (*chain(64, 64), 300.0, 100.0),
}


def _mp50(p, q, lam0, mu, **kw):
    with mp.workdps(50):
        return flow_coefficients([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(lam0), mp.mpf(mu), **kw)


@pytest.mark.parametrize("name", list(CASES))
def test_float64_against_50_digits_relative(name):
    p, q, lam0, mu = CASES[name]
    c = flow_coefficients(np.array(p), np.array(q), lam0, mu)
    ref = _mp50(p, q, lam0, mu)
    rel = max(float(abs(mp.mpf(float(a)) - b) / abs(b)) for a, b in zip(c, ref))
    assert rel < 2e-14, (name, rel)
    if name.startswith("N64-far"):
        assert 1e-150 < abs(float(ref[0])) < 1e-145      # the tiny c_0 is resolved to full relative accuracy


def _polynomial_quadrature(p, q, lam0, mu, k):
    """Independent route: tr L from its explicit polynomial, Gauss-Legendre (mpmath), 45 digits."""
    with mp.workdps(45):
        H = hamiltonians([mp.mpf(v) for v in p], [mp.mpf(v) for v in q])
        f = lambda x: x**k / mp.sqrt(mp.polyval(H[::-1], x) ** 2 - 4)
        return -mp.quad(f, mp.linspace(lam0 - mu, lam0 + mu, 5), method="gauss-legendre")


@pytest.mark.parametrize("name", ["N2-bounded-gap", "N3-paper-mu5", "N3-paper-mu2-tr<-2"])
def test_mpmath_path_against_polynomial_gauss_legendre(name):
    p, q, lam0, mu = CASES[name]
    N = len(p)
    got = _mp50(p, q, lam0, mu, ks=range(N + 1))
    for k in range(N + 1):
        ref = _polynomial_quadrature(p, q, lam0, mu, k)
        assert abs(got[k] - ref) <= mp.mpf(10) ** -38 * abs(ref), (name, k)


def test_reference_wrapper_keeps_its_contract():
    with mp.workdps(40):
        p, q = [mp.mpf(v) for v in P0], [mp.mpf(v) for v in Q0]
        full = flow_coefficients_mp(p, q, 10, 5)
        assert len(full) == 4                                           # c_0 .. c_N
        part = flow_coefficients_mp(p, q, 10, 5, ks=[1, 3], check=False)
        assert part[0] is None and part[2] is None
        assert part[1] == full[1] and part[3] == full[3]
        neg = flow_coefficients_mp(p, q, 10, -5, 1)                    # reversed interval
        assert all(abs(a + b) <= mp.mpf(10) ** -35 * abs(b) for a, b in zip(neg, full))
        other = flow_coefficients_mp(p, q, 10, 5, -1)                  # the other branch
        assert all(abs(a + b) <= mp.mpf(10) ** -35 * abs(b) for a, b in zip(other, full))
        with pytest.raises(NoRealFlowError):
            flow_coefficients_mp(p, q, 22.5, 17.5)
    assert abs(float(full[2]) + 0.512050368038) < 1e-12                 # the paper's caption constant, -0.512


def test_typed_errors_and_selection():
    with pytest.raises(NoRealMapError):
        flow_coefficients(np.array(P0), np.array(Q0), 22.5, 17.5)      # lam1, lam2 in different gaps
    with pytest.raises(NoRealMapError), mp.workdps(20):
        flow_coefficients([mp.mpf(v) for v in P0], list(Q0), 22.5, 17.5)
    with pytest.raises(NoRealMapError), mp.workdps(20):                # a band inside: no pre-check
        flow_coefficients([mp.mpf(v) for v in P0], list(Q0), 22.5, 17.5, check=False)
    c = flow_coefficients(np.array(P0), np.array(Q0), 10.0, 5.0, ks=[2, 0, 3])
    full = flow_coefficients(np.array(P0), np.array(Q0), 10.0, 5.0, ks=range(4))
    np.testing.assert_array_equal(c, full[[2, 0, 3]])
