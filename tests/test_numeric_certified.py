"""Certified orbits (Arb ball arithmetic): the enclosures contain independent higher-precision orbits and
the float64 orbit; existence decisions are certain; precision is raised automatically.

Reference: the paper's literal route (``reference_step``) at 120 digits -- a different algorithm at more
than twice the working precision.
"""

import fractions

import mpmath
import numpy as np
import pytest

from symbt.numeric import (
    InvalidInputError,
    MissingDependencyError,
    NoRealMapError,
    NumericRangeError,
    bt_orbit,
    certified_orbit,
)

pytest.importorskip("flint")

P_DEC, Q_DEC = ["-20", "10", "1"], ["1", "0", "0.9"]


def reference_orbit(p, q, lam0, mu, n, every, dps=120):
    from symbt.reference.literal import reference_step

    out = []
    with mpmath.workdps(dps):
        a, b = [mpmath.mpf(v) for v in p], [mpmath.mpf(v) for v in q]
        out.append((a, b))
        for i in range(1, n + 1):
            a, b = reference_step(a, b, lam0, mu)
            if i % every == 0 or i == n:
                out.append((a, b))
    return out


def test_100_steps_at_50_digits_enclose_120_digit_reference():
    n = 100
    with mpmath.workdps(50):
        P, Q, Pr, Qr = bt_orbit(P_DEC, Q_DEC, 10, 5, n, certified=True, every=10)
    assert len(P) == len(Pr) == 11
    worst = max(max(a + b) for a, b in zip(Pr, Qr))
    assert worst <= 1e-30                      # the target of the task; measured ~2e-50 (one ulp at 50 digits)
    ref = reference_orbit(P_DEC, Q_DEC, 10, 5, n, 10)
    with mpmath.workdps(120):
        for (a, b), Pm, Qm, Pr_, Qr_ in zip(ref, P, Q, Pr, Qr):
            for x, m, r in zip(a + b, Pm + Qm, Pr_ + Qr_):
                assert abs(x - m) <= r, (x, m, r)
    # the midpoints are the caller's 50-digit numbers
    assert all(isinstance(v, mpmath.mpf) for v in P[-1] + Q[-1] + Pr[-1] + Qr[-1])


def test_float_input_is_exact_and_float_orbit_within_enclosure_plus_bound():
    n = 300
    p, q = [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9]      # 0.9 is the binary double: certified exactly
    with mpmath.workdps(30):
        P, Q, Pr, Qr = certified_orbit(p, q, 10.0, 5.0, n, every=50)
    Pf, Qf = bt_orbit(p, q, 10.0, 5.0, n, every=50)
    scale = np.linalg.norm(np.r_[Pf[0], Qf[0] - np.mean(Qf[0])])
    bound = 3e-12 * scale     # documented float64 orbit error up to 500 steps (test_numeric_orbit.py)
    for i in range(len(P)):
        for x, m, r in zip(np.r_[Pf[i], Qf[i]], P[i] + Q[i], Pr[i] + Qr[i]):
            assert float(r) < 1e-25
            assert abs(mpmath.mpf(x) - m) <= r + bound
    # the certified decimal 0.9 and the binary 0.9 give different (certified) orbits
    with mpmath.workdps(30):
        Pd, _, Prd, _ = certified_orbit(P_DEC, Q_DEC, 10, 5, 50, every=50)
    assert abs(Pd[-1][0] - P[1][0]) > Prd[-1][0] + Pr[1][0]


@pytest.mark.slow
def test_3500_steps_certify_the_float64_orbit():
    """3500 steps at tol = 1e-15 (working precision ~7300 bits, ~10 s): the enclosure certifies the
    float64 orbit's documented error bound (1e-10 relative, test_numeric_orbit.py)."""
    n = 3500
    p, q = [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9]
    with mpmath.workdps(30):
        P, Q, Pr, Qr = certified_orbit(p, q, 10.0, 5.0, n, every=500, tol=1e-15)
    assert max(max(a + b) for a, b in zip(Pr, Qr)) <= 1e-15
    Pf, Qf = bt_orbit(p, q, 10.0, 5.0, n, every=500)
    scale = np.linalg.norm(np.r_[Pf[0], Qf[0] - np.mean(Qf[0])])
    for i in range(len(P)):
        err = max(abs(mpmath.mpf(x) - m) + r for x, m, r in zip(np.r_[Pf[i], Qf[i]], P[i] + Q[i], Pr[i] + Qr[i]))
        assert err <= 1e-10 * scale           # certified: measured ~2e-11 absolute at step 3500


def test_existence_certain_or_refused():
    # lam1 = -10.278 + 0.002 in a band: certainly no real map
    with pytest.raises(NoRealMapError) as info:
        certified_orbit(P_DEC, Q_DEC, "-10.278", "0.002", 3)
    assert info.value.condition == "trace"
    # |tr L(lam1)| = 2 exactly for exact input: certainly not > 2
    with pytest.raises(NoRealMapError):
        certified_orbit([0, 0], [0, 0], 1, 1, 1)
    # the same boundary reached through inexact decimals: every ball straddles it -> not certifiable
    with pytest.raises(NumericRangeError, match="max_prec"):
        certified_orbit(["0.1", "0.1"], [0, 0], "-4.05", "5.95", 1, max_prec=2000)


def test_precision_raised_automatically_and_tol():
    with mpmath.workdps(20):
        P, Q, Pr, Qr = certified_orbit(P_DEC, Q_DEC, 10, 5, 200, every=200, tol=1e-40)
    # the returned radius includes the rounding to 20 digits (|p| ~ 20 -> ~1e-18), the enclosure itself is
    # tighter; at 60 digits the tolerance shows
    assert max(Pr[-1] + Qr[-1]) < 1e-17
    with mpmath.workdps(60):
        P, Q, Pr, Qr = certified_orbit(P_DEC, Q_DEC, 10, 5, 200, every=200, tol=1e-40)
    assert max(Pr[-1] + Qr[-1]) <= 1e-40


def test_input_kinds_and_errors(monkeypatch):
    with mpmath.workdps(30):
        a = certified_orbit([fractions.Fraction(-20), 10, mpmath.mpf(1)], [1, 0, "0.9"], 10, 5, 2)
        b = certified_orbit(P_DEC, Q_DEC, "10", "5", 2)
        assert a[0] == b[0] and a[1] == b[1]
        for bad in ([True, 1, 2], [[1, 2, 3]], ["x", 1, 2], [float("nan"), 1, 2]):
            with pytest.raises(InvalidInputError):
                certified_orbit(bad, Q_DEC, 10, 5, 1)
        with pytest.raises(InvalidInputError):
            certified_orbit(P_DEC, Q_DEC, 10, 5, 1, tol=-1)
        with pytest.raises(InvalidInputError):
            bt_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 3, tol=1e-10)    # tol without certified
        with pytest.raises(InvalidInputError):
            bt_orbit(P_DEC, Q_DEC, 10, 5, 3, certified=True, backend="numba")
    from symbt.numeric.multiprec import certified as cert

    monkeypatch.setattr(cert, "flint_available", lambda: False)
    with pytest.raises(MissingDependencyError, match="python-flint"):
        certified_orbit(P_DEC, Q_DEC, 10, 5, 1)
