r"""Existence of the real map decided rigorously, for the escalation of :mod:`.rows`.

The escalation (:func:`~symbt.numeric.float64.rows.escalate_rows`) recomputes an ill-conditioned float64 state
with mpmath at 40 to 340 digits and takes the verdict two precisions agree on.  Agreement between
precisions is not proof: where ``lambda_1`` or ``lambda_2`` is exactly 0 and the positions are far apart, the
smallest ``Etilde_j / E_j`` is ~1e-150 and every run below ~1400 digits rounds it to a value ``<= 0`` (the deep
fuzz's chunks 86, 162 and 188, docs/fuzz.md): "no real map" where the map exists.

:func:`decide_existence` decides it by interval arithmetic (``mpmath.iv``; every float64 input is an exact
binary number, so the intervals enclose the exact quantities): the traces' ``t**2 - 4``, their signs and
every ``Etilde_j / E_j = 1 + 2 mu / (u_j - w_j)`` (the slopes of
:func:`~symbt.numeric.core.step.eigen_slopes` on intervals, as :func:`~symbt.numeric.core.step.step_core`).
A verdict is returned only when every interval it rests on excludes 0; otherwise the precision doubles, up to
:data:`MAX_BITS` (and :data:`BUDGET_S` seconds), and the answer is ``None`` -- undecided: the caller refuses
the state with ``NumericRangeError`` rather than say "no real map".

>>> import numpy as np
>>> decide_existence(np.array([0.0, 0.0]), np.array([0.0, 0.0]), 0.0, 2.0 ** -30, 1)[0]   # inside the band
1
>>> decide_existence(np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9]), 10.0, 5.0, 1)[0]  # the paper's
0
"""
from __future__ import annotations

import time
from typing import TYPE_CHECKING

import mpmath

from ..core.context import IV, iv_prec
from ..core.limits import OK, POSITIVITY, TRACE1, TRACE2
from ..core.monodromy import monodromy, neighbour_ratios
from ..core.step import eigen_slopes

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

__all__ = ["decide_existence", "MAX_BITS", "BUDGET_S"]

#: the last working precision (bits) of :func:`decide_existence`; it starts at 256 and doubles
MAX_BITS = 16384
#: wall-time budget (seconds) of one :func:`decide_existence` -- and of all the states of one
#: :func:`~.rows.escalate_rows` call together -- checked between precisions
BUDGET_S = 20.0


def _sign(x: mpmath.ctx_iv.ivmpf) -> int | None:
    """+1 / -1 where the interval excludes 0, 0 where it is the point 0 (the exact value is 0: every operation
    was exact, e.g. the free chain's trace -2 at lam = 0), else None."""
    if x.a > 0:
        return 1
    if x.b < 0:
        return -1
    return 0 if x.a == 0 and x.b == 0 else None


def _at(p: npt.NDArray[np.float64], q: npt.NDArray[np.float64], lam0: float, mu: float, branch: int) -> int | None:
    """The verdict at the current ``mpmath.iv.prec``: ``OK``, a no-real-map code, or None (undecided)."""
    iv = mpmath.iv
    P = [iv.mpf(float(v)) for v in p]
    Q = [iv.mpf(float(v)) for v in q]
    l0, m = iv.mpf(float(lam0)), iv.mpf(float(mu))
    r = neighbour_ratios(IV, Q)
    signs, bands = [], []
    for code, lam in ((TRACE1, l0 + m), (TRACE2, l0 - m)):
        A, _, _, D, _ = monodromy(IV, [lam + x for x in P], r)     # intervals are never renormalised: e = 0
        t = A + D
        s = _sign((t - 2) * (t + 2))
        bands.append(None if s is None else OK if s > 0 else code)      # |t| = 2 exactly: no real map
        signs.append(_sign(t))
    for verdict in bands:                  # a certain band at either parameter decides, the other undecided or not
        if verdict not in (OK, None):
            return verdict
    if None in bands:
        return None
    if signs[0] != signs[1]:               # |t_i| > 2 certainly: both signs are decided, and they differ
        return POSITIVITY
    try:                                   # the slopes of step_core; no read-out (log1p of a negative interval raises)
        u = eigen_slopes(IV, [l0 + m + x for x in P], r, branch).u
        w = eigen_slopes(IV, [l0 - m + x for x in P], r, -branch).u
        assert u is not None and w is not None
        verdicts = [_sign(IV.div(2 * m, a - b) + 1) for a, b in zip(u, w)]
    except (ArithmeticError, ValueError):  # an interval slope through 0 or infinity: not decided here
        return None
    if -1 in verdicts or 0 in verdicts:  # some Etilde_j <= 0 certainly
        return POSITIVITY
    return OK if None not in verdicts else None


def decide_existence(p: npt.NDArray[np.float64], q: npt.NDArray[np.float64], lam0: float, mu: float, branch: int,
                     bits: int = 256, deadline: float | None = None) -> tuple[int | None, int]:
    """``(verdict, bits)``: ``OK`` (the real map certainly exists), ``TRACE1``/``TRACE2``/``POSITIVITY``
    (certainly not; the codes of :mod:`symbt.numeric.core.limits`) or ``None`` (undecided up to
    :data:`MAX_BITS` or :data:`BUDGET_S`), and the interval precision that decided it.  The state is
    ``(p, q)`` with the exact binary values of its floats.  ``deadline`` (a ``time.monotonic()`` value) ends the
    doubling earlier: a batch shares one budget, each of its states then tried at least at the first precision."""
    start = time.monotonic()
    end = start + BUDGET_S if deadline is None else min(deadline, start + BUDGET_S)
    while bits <= MAX_BITS:
        with iv_prec(bits):
            verdict = _at(p, q, lam0, mu, branch)
        if verdict is not None:
            return verdict, bits
        if time.monotonic() > end:
            break
        bits *= 2
    return None, bits
