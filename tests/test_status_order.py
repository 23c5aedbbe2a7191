"""The first failing test wins, in the order :mod:`symbt.numeric.core.limits` documents, in every kernel.

The pinned state fails two tests at once: ``p = (-2, -1/2)``, ``q = (0, 0)``, ``lam0 = 0``, ``mu = 1``,
branch -1.  Its traces are ``tr L(1) = -5/2`` and ``tr L(-1) = 5/2`` (opposite signs: lam1 and lam2 in
different gaps, ``POSITIVITY``), and the slope at site 1 is ``2`` at both spectral parameters, so
``x_1 = 2 mu / (u_1 - w_1)`` divides by an exact zero (every operation on these binary numbers is exact,
``sqrt(9/4)`` included): a non-finite value, ``RANGE``.  The documented order tests the traces' signs
before any site's range, so every kernel reports ``POSITIVITY``.  Before the redesign (commit
f7390f5^) the quad-double step and the float64 kernel both tested every site's range first and
reported ``RANGE`` here (the traces' sign test came with the conditioned decisions, merged since), so the
state went on to the next route, which decided it.

The exact values come from an independent route: the characteristic quadratic of the slope in
fractions (no kernel code)."""
from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symbt.numeric import NoRealMapError, bt_orbit, bt_step
from symbt.numeric.core.limits import POSITIVITY
from symbt.numeric.float64.jit import kernel, numba_available
from symbt.numeric.float64.kernels import ANCHOR

P, Q, LAM0, MU, BRANCH = (-2.0, -0.5), (0.0, 0.0), 0.0, 1.0, -1


def _exact_slope(lam: Fraction, s: int) -> tuple[Fraction, Fraction]:
    """``(tr, u)`` at ``lam`` for N = 2, ``r_1 = r_2 = 1``: ``u`` the root ``(A - D + s g) / (2B)`` of
    ``B u^2 - (A - D) u - C = 0`` (``M = m_2 m_1``, ``m_j = [[lam + p_j, -1], [1, 0]]``)."""
    a0, a1 = lam + Fraction(P[0]), lam + Fraction(P[1])
    A, B, C, D = a1 * a0 - 1, -a1, a0, Fraction(-1)
    t = A + D
    disc = (t - 2) * (t + 2)
    g = Fraction(3, 2)
    assert g * g == disc            # a perfect square: the kernels' sqrt is exact too
    u = (A - D + s * g) / (2 * B)
    assert B * u * u - (A - D) * u - C == 0
    return t, u


def test_the_pinned_state_fails_both_tests():
    lam0, mu = Fraction(LAM0), Fraction(MU)
    t1, u1 = _exact_slope(lam0 + mu, BRANCH)
    t2, w1 = _exact_slope(lam0 - mu, -BRANCH)
    assert abs(t1) > 2 and abs(t2) > 2          # no band: TRACE1/TRACE2 pass
    assert t1 * t2 < 0                          # opposite signs: POSITIVITY
    assert u1 == w1 == 2                        # x_1 = 2 mu / 0: RANGE


def test_quad_double_step_reports_positivity_first():
    from symbt.numeric.multiprec.qd_step import qd_orbit

    p4, q4 = np.zeros((2, 4)), np.zeros((2, 4))
    p4[:, 0], q4[:, 0] = P, Q
    spec = np.array([[LAM0, 0, 0, 0], [MU, 0, 0, 0]])
    out = np.empty((2, 2, 4))
    with np.errstate(all="ignore"):
        assert qd_orbit(p4, q4, spec, BRANCH, 1, 1, out, out.copy()) == (POSITIVITY, 1)


FLOAT64 = ["python"] + (["numba"] if numba_available() else [])


@pytest.mark.parametrize("backend", FLOAT64)
def test_float64_kernels_report_the_same_status(backend):
    fn, _ = kernel("orbit", backend)
    out = np.empty((2, 2))
    with np.errstate(all="ignore"):
        st = fn(np.array(P), np.array(Q), LAM0 + MU, LAM0 - MU, 2 * MU, BRANCH, 1, 1, ANCHOR, out, out.copy())
    assert st == POSITIVITY
    block, _ = kernel("ensemble", backend)      # the block kernel keeps its own copy of the step
    M = 3
    status = np.zeros(M, np.int64)
    outb = np.empty((2, M, 2))
    with np.errstate(all="ignore"):
        block(np.tile(P, (M, 1)), np.tile(Q, (M, 1)), np.full(M, LAM0 + MU), np.full(M, LAM0 - MU),
              np.full(M, 2 * MU), BRANCH, 1, 1, ANCHOR, 2, outb, outb.copy(), status)
    assert status.tolist() == [POSITIVITY] * M


def test_public_routes_raise_no_real_map_positivity():
    with pytest.raises(NoRealMapError) as e:
        bt_step(np.array(P), np.array(Q), LAM0, MU, branch=BRANCH)
    assert e.value.condition == "positivity"
    with pytest.raises(NoRealMapError) as e:
        bt_orbit(np.tile(P, (2, 1)), np.tile(Q, (2, 1)), LAM0, MU, 1, branch=BRANCH)
    assert e.value.condition == "positivity"
    with mpmath.workdps(30), pytest.raises(NoRealMapError) as e:
        bt_step([mpmath.mpf(v) for v in P], [mpmath.mpf(v) for v in Q], mpmath.mpf(LAM0), mpmath.mpf(MU),
                branch=BRANCH)
    assert e.value.condition == "positivity"
