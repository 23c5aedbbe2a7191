r"""The Bäcklund step and orbit in quad-double arithmetic (:mod:`symbt.numeric.multiprec.qd_arith`).

:func:`qd_step` performs the operations of :func:`~symbt.numeric.multiprec.runners.arb_step`
(the fused :func:`~symbt.numeric.core.step.step_core`) in the same order, on
quad-doubles, with the same decisions taken on the leading components (the
sign of a renormalised quad-double): ``disc = (t - 2)(t + 2) > 0`` else
"trace"; the branch of the eigenvector slope from the signs of ``t`` and
``A - D``; ``1 + x_j > 0`` else "positivity".  :func:`qd_orbit` runs ``n``
steps in one call and writes the stored states (steps ``0, every, ...`` and
``n``) into its output arrays.  A state is an ``(N, 4)`` float64 array (row
``j``: the components of site ``j``).

Status codes (those of :mod:`symbt.numeric.core.limits`): ``0`` ok, ``1``/``2``
``|tr L(lam1/lam2)| <= 2``, ``3`` some ``1 + x_j <= 0``, ``4`` range: a
neighbour distance ``|q_{j+1} - q_j| > MAX_DQ_QD = 300`` (the squared trace must stay inside the
range of the quad-double product, :mod:`symbt.numeric.core.limits`) or a
non-finite value (an overflow, a division by an exact zero).  The caller
(:mod:`symbt.numeric.multiprec.qd`) turns them into the typed errors of
:mod:`symbt.numeric.core.errors`, or for ``4`` falls back to the Arb path.

Example (plain Python, slow; numba compiles the same functions):

>>> import numpy as np
>>> from symbt.numeric.multiprec.qd_step import qd_orbit
>>> P, Q = np.zeros((3, 4)), np.zeros((3, 4))
>>> P[:, 0], Q[:, 0] = [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9]
>>> Q[2, :2] = 0.9, -2.2204460492503132e-17           # 0.9 to 106 bits
>>> spec = np.array([[10.0, 0, 0, 0], [5.0, 0, 0, 0]])
>>> outP, outQ = np.empty((2, 3, 4)), np.empty((2, 3, 4))
>>> qd_orbit(P, Q, spec, 1, 1, 1, outP, outQ)
(0, 1)
>>> round(float(outP[1, 0, 0]), 8)
-19.99656766
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..core.limits import MAX_DQ_QD, OK, POSITIVITY, RANGE, TRACE1, TRACE2
from .qd_arith import add, add_d, div, exp, log1p, mul, mul_pwr2, neg, renorm4, sqrt, sub

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]

__all__ = ["qd_step", "qd_orbit"]

QD = tuple[float, float, float, float]


def _row(a: F64, j: int) -> QD:
    return a[j, 0], a[j, 1], a[j, 2], a[j, 3]


def _put(a: F64, j: int, x: QD) -> None:
    a[j, 0] = x[0]
    a[j, 1] = x[1]
    a[j, 2] = x[2]
    a[j, 3] = x[3]


def _finite(x: QD) -> bool:
    return math.isfinite(x[0]) and math.isfinite(x[3])


def _slopes(a: F64, r: F64, s: int, u: F64) -> int:
    """Eigenvector slopes of the scaled monodromy (``arb_step``'s ``_slopes``) into ``u``; status 0 (or
    ``-1``: ok and ``tr < 0``), 1 or 4."""
    N = a.shape[0]
    a0, a1, r0, r1 = _row(a, 0), _row(a, 1), _row(r, 0), _row(r, 1)
    A, B, C, D = sub(mul(a1, a0), r0), neg(a1), mul(r1, a0), neg(r1)
    for j in range(2, N):
        aj, rj = _row(a, j), _row(r, j)
        A, B, C, D = sub(mul(aj, A), C), sub(mul(aj, B), D), mul(rj, A), mul(rj, B)
    t = add(A, D)
    if not (_finite(A) and _finite(B) and _finite(C) and _finite(D) and _finite(t)):
        return RANGE
    disc = mul(add_d(t, -2.0), add_d(t, 2.0))
    if not disc[0] > 0.0:
        return TRACE1
    g = sqrt(disc)
    tg = t[0] >= 0.0
    fwd = (not tg) if s > 0 else tg
    dl = sub(A, D)
    plus = dl[0] >= 0.0
    k = add(dl, g) if plus else sub(dl, g)
    if plus if s > 0 else not plus:
        u1 = div(k, mul_pwr2(B, 2.0))
    else:
        u1 = div(mul_pwr2(C, -2.0), k)
    _put(u, 0, u1)
    if fwd:
        for j in range(N - 1):
            _put(u, j + 1, div(neg(_row(r, j)), add(_row(a, j), _row(u, j))))
    else:
        nxt = u1
        for j in range(N - 1, 0, -1):
            nxt = sub(neg(_row(a, j)), div(_row(r, j), nxt))
            _put(u, j, nxt)
    return OK if tg else -1


def qd_step(P: F64, Q: F64, lam1: QD, lam2: QD, two_mu: QD, branch: int, work: F64, Pn: F64, Qn: F64) -> int:
    """One step ``(P, Q) -> (Pn, Qn)`` (``(N, 4)`` arrays; ``work``: ``(6, N, 4)`` scratch); the status code."""
    N = P.shape[0]
    r, a, u, w, dn, xr = work[0], work[1], work[2], work[3], work[4], work[5]
    for j in range(N):
        dq = sub(_row(Q, (j + 1) % N), _row(Q, j))
        if not abs(dq[0]) <= MAX_DQ_QD:
            return RANGE
        _put(r, j, exp(dq))
    for j in range(N):
        _put(a, j, add(lam1, _row(P, j)))
    st = _slopes(a, r, branch, u)
    if st > OK:
        return st
    sign1 = st
    for j in range(N):
        _put(a, j, add(lam2, _row(P, j)))
    st = _slopes(a, r, -branch, w)
    if st > OK:
        return TRACE2 if st == TRACE1 else st
    if st != sign1:
        return POSITIVITY       # tr L(lam1), tr L(lam2) of opposite signs: lam1, lam2 in different gaps
    positive = True
    for j in range(N):
        d = sub(_row(u, j), _row(w, j))
        x = div(two_mu, d)
        if not _finite(x):
            return RANGE
        positive = positive and add_d(x, 1.0)[0] > 0.0
        _put(dn, j, d)
        _put(xr, j, x)
    if not positive:
        return POSITIVITY
    for j in range(N):
        _put(Qn, j, add(_row(Q, j), log1p(_row(xr, j))))
        _put(a, j, div(_row(u, j), _row(dn, j)))          # gq_j = u_j / dn_j
    for j in range(N):
        pj = add(_row(P, j), mul(two_mu, sub(_row(a, (j + 1) % N), _row(a, j))))
        if not (_finite(pj) and _finite(_row(Qn, j))):
            return RANGE
        _put(Pn, j, pj)
    return OK


def qd_orbit(P0: F64, Q0: F64, spec: F64, branch: int, n: int, every: int, outP: F64, outQ: F64
             ) -> tuple[int, int]:
    """``n`` steps from ``(P0, Q0)`` (``(N, 4)``, any non-overlapping components: renormalised here);
    ``spec`` rows ``lam0, mu``.  Writes the stored states into ``outP, outQ`` (``(rows, N, 4)``) and
    returns ``(status, step)`` (``(0, n)``, or the failing step)."""
    N = P0.shape[0]
    P, Q, Pn, Qn = np.empty((N, 4)), np.empty((N, 4)), np.empty((N, 4)), np.empty((N, 4))
    work = np.empty((6, N, 4))
    for j in range(N):
        _put(P, j, renorm4(P0[j, 0], P0[j, 1], P0[j, 2], P0[j, 3]))
        _put(Q, j, renorm4(Q0[j, 0], Q0[j, 1], Q0[j, 2], Q0[j, 3]))
    lam0 = renorm4(spec[0, 0], spec[0, 1], spec[0, 2], spec[0, 3])
    mu = renorm4(spec[1, 0], spec[1, 1], spec[1, 2], spec[1, 3])
    lam1, lam2, two_mu = add(lam0, mu), sub(lam0, mu), mul_pwr2(mu, 2.0)
    outP[0] = P
    outQ[0] = Q
    row = 1
    for i in range(1, n + 1):
        st = qd_step(P, Q, lam1, lam2, two_mu, branch, work, Pn, Qn)
        if st != OK:
            return st, i
        P, Pn = Pn, P
        Q, Qn = Qn, Q
        if i % every == 0 or i == n:
            outP[row] = P
            outQ[row] = Q
            row += 1
    return OK, n
