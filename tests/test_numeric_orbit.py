"""3500-step orbit of the paper's example (Fig. 1) against a 50-digit orbit.

Reference: the paper's literal route (``literal_step``) iterated at 50 digits
(+ automatic guard digits); it agrees with the mpmath path of the stable
algorithm to all 50 digits.

Measured (this machine, numpy 2.4), max of the normwise relative error
(``state_error``) over steps 1..n, sampled every 25 steps:
n = 10: 5.9e-16, 100: 3.3e-14, 500: 6.4e-13, 1000: 1.5e-12, 2000: 6.0e-12,
3500: 1.9e-11.  The growth
is ~n^2: each step is accurate to ~1e-16 but its rounding perturbs the
action variables, and an action error makes the torus phase drift linearly,
so per-step errors eps give ~eps * n^2 * |d omega / d I|.  Bounds asserted:
1e-10 overall (5x margin), 1e-15 for the first 10 steps (one-step accuracy
does not degrade along the orbit), 3e-12 up to step 500.  (Without carrying the
centre of mass separately in ``bt_orbit`` the final error is 1.9e-10: the
rounding of q at |q| ~ 500 then feeds back into the relative coordinates.)
"""

import mpmath
import numpy as np

from symbt.numeric import bt_orbit, invariants
from symbt.numeric.testing import state_error
from symbt.reference.literal import reference_step as literal_step

P0 = [-20.0, 10.0, 1.0]
Q0 = [1.0, 0.0, 0.9]


def test_orbit_3500_against_50_digits():
    n = 3500
    P, Q = bt_orbit(P0, Q0, 10.0, 5.0, n)
    assert P.shape == Q.shape == (n + 1, 3)
    errs = []
    with mpmath.workdps(50):
        a, b = [mpmath.mpf(v) for v in P0], [mpmath.mpf(v) for v in Q0]
        for i in range(1, n + 1):
            a, b = literal_step(a, b, 10, 5, guard=25)
            if i % 25 == 0 or i < 10:
                errs.append((i, state_error(P[i], Q[i], a, b)))
    worst = max(e for _, e in errs)
    assert max(e for i, e in errs if i <= 10) <= 1e-15
    assert max(e for i, e in errs if i <= 500) <= 3e-12
    assert worst <= 1e-10, worst
    # invariants along the float orbit (relative to the centred state)
    H0 = invariants(P0, Q0)
    for i in (1000, 2000, 3500):
        Hi = invariants(P[i], Q[i] - Q[i].mean())
        np.testing.assert_allclose(Hi, H0, rtol=1e-11)


def test_orbit_mp_and_batch():
    with mpmath.workdps(30):
        P, Q = bt_orbit([mpmath.mpf(v) for v in P0], Q0, 10, 5, 3)
        assert len(P) == 4 and all(isinstance(v, mpmath.mpf) for v in P[3])
        Pf, Qf = bt_orbit(P0, Q0, 10.0, 5.0, 3)
        np.testing.assert_allclose(Pf[3], [float(v) for v in P[3]], rtol=1e-14)
        np.testing.assert_allclose(Qf[3], [float(v) for v in Q[3]], rtol=1e-14)
    Pb, Qb = bt_orbit(np.stack([P0, P0]), np.stack([Q0, Q0]), 10.0, 5.0, 4)
    assert Pb.shape == (5, 2, 3)
    np.testing.assert_array_equal(Pb[:, 0], Pb[:, 1])
    # forward then backward returns to the start
    Pr, Qr = bt_orbit(Pf[3], Qf[3], 10.0, 5.0, 3, branch=-1)
    np.testing.assert_allclose(Pr[3], P0, atol=1e-12)
    np.testing.assert_allclose(Qr[3], Q0, atol=1e-12)
