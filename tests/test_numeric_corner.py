"""Numeric corner cases: complex input refused alike everywhere; degenerate eigenvectors take the limit on
every path (float64, mpmath, Arb, certified), checked against an independent limit."""

import mpmath
import numpy as np
import pytest

from symbt.numeric import (
    InvalidInputError,
    bt_orbit,
    bt_step,
    certified_orbit,
    invariants,
    phi,
    spectral_trace,
)
from symbt.reference.literal import reference_step

P0 = np.array([-20.0, 10.0, 1.0])
Q0 = np.array([1.0, 0.0, 0.9])

COMPLEX_STATES = {
    "complex128 p": (P0.astype(complex), Q0),
    "complex128 q with zero imaginary part": (P0, Q0 + 0j),
    "complex128 q": (P0, Q0 + 1e-3j),
    "python complex in a list": ([-20.0, 10.0, 1 + 2j], Q0),
    "numpy complex scalar in a list": ([-20.0, 10.0, np.complex128(1)], Q0),
    "batch of complex": (np.tile(P0, (2, 1)) + 0j, np.tile(Q0, (2, 1))),
}


@pytest.mark.parametrize("name", sorted(COMPLEX_STATES))
def test_complex_states_refused_everywhere(name):
    p, q = COMPLEX_STATES[name]
    calls = [lambda: bt_step(p, q, 10.0, 5.0), lambda: bt_orbit(p, q, 10.0, 5.0, 3),
             lambda: bt_orbit(p, q, 10.0, 5.0, 3, backend="numpy"), lambda: invariants(p, q),
             lambda: spectral_trace(3.0, p, q), lambda: phi(p, q, 10.0, 5.0)]
    if np.ndim(p) == 1:
        calls += [lambda: bt_orbit(p, q, 10.0, 5.0, 3, backend="python"),
                  lambda: bt_orbit(p, q, 10.0, 5.0, 3, certified=True)]
    for call in calls:
        with pytest.raises(InvalidInputError, match="complex|real"):
            call()


@pytest.mark.parametrize("bad", [5 + 0j, np.complex128(5), mpmath.mpc(5, 1), np.array(5 + 0j)])
def test_complex_parameters_refused(bad):
    with pytest.raises(InvalidInputError):
        bt_orbit(P0, Q0, 10.0, bad, 3)
    with pytest.raises(InvalidInputError):
        bt_step(P0, Q0, bad, 5.0)
    with pytest.raises(InvalidInputError):
        bt_orbit(P0, Q0, 10.0, bad, 3, backend="python")
    with pytest.raises(InvalidInputError):
        bt_step([mpmath.mpf(v) for v in P0], Q0, 10, bad)
    with pytest.raises(InvalidInputError):
        certified_orbit(P0, Q0, 10, bad, 2)


def test_mpc_state_refused():
    with pytest.raises(InvalidInputError):
        bt_step([mpmath.mpc(1, 1), mpmath.mpf(2)], [0, 0], 10, 5)
    with pytest.raises(InvalidInputError):
        bt_orbit([mpmath.mpc(1, 1), mpmath.mpf(2)], [0, 0], 10, 5, 2)


# --------------------------------------------------------------------------- degenerate eigenvector

# lam2 = lam0 - mu = 0 and p_2 = 0: on the backward transport the lam2-slope at site 1 is infinite
# (eigenvector (0, 1)); the map itself is smooth there.
DEG = ([-3, 0], [0, 1], 1, 1)


def independent_limit(digits):
    """The map at mu = 1 from the literal route at mu = 1 +- delta (symmetric mean: error O(delta^2)),
    delta = 10**-(digits/2 + 5), with enough working digits for the literal route's 1/delta cancellation."""
    p, q, lam0, mu = DEG
    e = digits // 2 + 5
    with mpmath.workdps(digits + e + 30):
        d = mpmath.mpf(10) ** -e
        a = reference_step(p, q, lam0, mu + d)
        b = reference_step(p, q, lam0, mu - d)
        return [(x + y) / 2 for x, y in zip(a[0] + a[1], b[0] + b[1])]


def test_degenerate_eigenvector_limit_every_path():
    lim = independent_limit(50)
    p, q, lam0, mu = DEG
    # float64 (kernel and general path)
    for backend in ("auto", "numpy"):
        pt, qt = bt_step(np.array(p, float), np.array(q, float), lam0, mu, backend=backend)
        assert np.allclose(np.r_[pt, qt], [float(v) for v in lim], rtol=0, atol=1e-14)
    # 50 and 100 digits, Arb and mpmath
    for dps in (50, 100):
        lim = independent_limit(dps + 10)
        with mpmath.workdps(dps):
            for backend in ("flint", "mpmath"):
                pt, qt = bt_step([mpmath.mpf(v) for v in p], q, lam0, mu, backend=backend)
                assert max(abs(a - b) for a, b in zip(pt + qt, lim)) < mpmath.mpf(10) ** (1 - dps), (dps, backend)
    # certified: the exact zero is exact in ball arithmetic, so the projective infinity is rigorous
    lim = independent_limit(80)
    with mpmath.workdps(50):
        P, Q, Pr, Qr = certified_orbit(p, q, lam0, mu, 1)
        for x, r, y in zip(P[1] + Q[1], Pr[1] + Qr[1], lim):
            assert abs(x - y) <= r + mpmath.mpf(10) ** -88      # the O(delta^2) error of the limit
            assert r < mpmath.mpf(10) ** -49


def test_degenerate_orbit_continues_after_the_limit():
    p, q, lam0, mu = DEG
    with mpmath.workdps(50):
        a = bt_orbit([mpmath.mpf(v) for v in p], q, lam0, mu, 3, backend="flint")
        b = bt_orbit([mpmath.mpf(v) for v in p], q, lam0, mu, 3, backend="mpmath")
        assert max(abs(x - y) for x, y in zip(a[0][3] + a[1][3], b[0][3] + b[1][3])) < mpmath.mpf(10) ** -45
    Pf, Qf = bt_orbit(np.array(p, float), np.array(q, float), lam0, mu, 3)
    np.testing.assert_allclose(Pf[3], [float(v) for v in a[0][3]], rtol=1e-13)
