"""The limits of :mod:`symbt.numeric.core.limits` at their boundaries, against 60-digit references.

State ``p = (1/4, -1/2)``, ``q = (0, D)``, ``lam0 = 1/8``, ``mu = 1``: ``tr L(lam) = (lam + 1/4)(lam - 1/2)
- 2 cosh D``, so ``|tr| ~ e^D`` and ``lam0 +- mu`` lie in the central gap for every ``D``; the neighbour
distance is ``D``.  The quad-double step runs as plain Python (the source numba compiles), so these
tests need no numba.
"""
import math

import mpmath
import numpy as np
import pytest

import symbt.numeric.multiprec.qd_step as qd_step_module
from symbt.numeric import NumericRangeError, bt_step
from symbt.numeric.core.limits import MAX_DQ_FLOAT64, MAX_DQ_QD, OK, RANGE
from symbt.numeric.multiprec.qd import from_qd, to_qd
from symbt.reference.literal import reference_step

P, LAM0, MU = (0.25, -0.5), 0.125, 1.0


def _reference(D):
    with mpmath.workdps(60):
        pr, qr = reference_step([mpmath.mpf(x) for x in P], [mpmath.mpf(0), mpmath.mpf(D)], mpmath.mpf(LAM0),
                                mpmath.mpf(MU))
    return pr + qr


def _qd_python_step(D):
    """(status, [p~, q~] as mpf) of one plain-Python quad-double step."""
    x = to_qd([mpmath.mpf(v) for v in (*P, 0.0, D, LAM0, MU)])
    outP, outQ = np.empty((2, 2, 4)), np.empty((2, 2, 4))
    with np.errstate(all="ignore"):          # past the range the arithmetic overflows, which the status reports
        status, _ = qd_step_module.qd_orbit(x[:2], x[2:4], x[4:], 1, 1, 1, outP, outQ)
    return status, from_qd(np.stack([outP[1], outQ[1]]), 600)


def _normwise(got, ref):
    return max(abs(g - r) for g, r in zip(got, ref)) / max(abs(r) for r in ref)


def test_quad_double_limit_both_sides():
    # just inside: the quad-double step carries its ~209 bits (normwise, against 60 digits ~ 2**-199)
    status, got = _qd_python_step(MAX_DQ_QD - 1)
    assert status == OK
    assert _normwise(got, _reference(MAX_DQ_QD - 1)) < 2.0**-190
    # just outside: refused with the range status (backend="auto" continues on the Arb path)
    assert _qd_python_step(MAX_DQ_QD + 1)[0] == RANGE


def test_quad_double_limit_sits_inside_the_arithmetics_own_range(monkeypatch):
    # Derivation (core/limits.py): Dekker's split multiplies a factor by 2**27 + 1, so the squared trace
    # ~ e^(2D) must stay below 2**996: D < 996 ln2 / 2 = 345.2.  With the limit lifted the step is still
    # accurate below that and overflows above it -- MAX_DQ_QD = 300 leaves a margin, 700 would not.
    monkeypatch.setattr(qd_step_module, "MAX_DQ_QD", math.inf)
    edge = 996 * math.log(2) / 2
    assert MAX_DQ_QD < edge - 5 < edge + 5 < MAX_DQ_FLOAT64
    status, got = _qd_python_step(edge - 5)
    assert status == OK and _normwise(got, _reference(edge - 5)) < 2.0**-190
    assert _qd_python_step(edge + 5)[0] == RANGE


def test_float64_limit_both_sides():
    # at the limit: the float64 step is accurate to a few ulps (the state's norm is ~D)
    pt, qt = bt_step(np.array(P), np.array([0.0, MAX_DQ_FLOAT64]), LAM0, MU)
    ref = [float(v) for v in _reference(MAX_DQ_FLOAT64)]
    err = np.abs(np.r_[pt, qt] - ref).max() / np.abs(ref).max()
    assert err < 8 * np.finfo(float).eps
    # beyond it: a typed error, never inf/NaN
    with pytest.raises(NumericRangeError):
        bt_step(np.array(P), np.array([0.0, MAX_DQ_FLOAT64 + 1.0]), LAM0, MU)
