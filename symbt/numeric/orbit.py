"""Orbits of the Bäcklund map: repeated :func:`~symbt.numeric.bt_step`.

The map preserves ``tr L(lam)`` (all ``H_k``) and, being a canonical
transformation that interpolates a Hamiltonian flow (paper Thm. 2, eq.
``eqdisc``), its orbits lie on invariant tori; the centre of mass
``Q = mean(q)`` drifts linearly.  Because each float64 step is accurate to a
few ulps, the orbit error grows only through the (linear, integrable)
dynamics.  The float64 orbit carries the centre of mass separately (see
:func:`bt_orbit`), which keeps the 3500-step error of the paper's example near
the conditioning of the orbit itself (see ``tests/test_numeric_orbit.py``).

Example
-------
>>> from symbt.numeric import bt_orbit
>>> P, Q = bt_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 3)
>>> P.shape
(4, 3)
"""

from __future__ import annotations

import numpy as np

from ._input import check_branch, pick_context
from .context import FLOAT
from .errors import InvalidInputError
from .step import bt_step

__all__ = ["bt_orbit"]


def bt_orbit(p, q, lam0, mu, n, *, branch=1):
    """``n`` Bäcklund steps from ``(p, q)``; returns the ``n + 1`` states.

    float64: arrays ``P, Q`` of shape ``(n + 1,) + p.shape`` with ``P[0] = p``.
    mpmath: two lists of ``n + 1`` states (each a list of mpf).
    Errors of any step (e.g. :class:`NoRealMapError`) propagate; the map
    preserves the spectrum, so if the first step exists all later ones do too
    (up to round-off at the boundary of existence).
    """
    branch = check_branch(branch)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise InvalidInputError("n must be a non-negative integer, got %r" % (n,))
    ctx = pick_context(p, q, lam0, mu)
    if ctx is FLOAT:
        p0 = np.asarray(p, dtype=np.float64)
        q0 = np.asarray(q, dtype=np.float64)
        # n == 0: bt_step with mu = 0 still validates (no silent NaN passthrough)
        pn, qn = bt_step(p0, q0, lam0, mu if n else 0.0, branch=branch)
        P = np.empty((n + 1,) + pn.shape, dtype=pn.dtype)
        Q = np.empty_like(P)
        P[0], Q[0] = p0, q0
        if n == 0:
            return P, Q
        # Carry the centre of mass separately: the dynamics only sees qr = q - c
        # with |qr| = O(1); c (which drifts linearly) is accumulated with a
        # compensated (two-sum) sum.  Without this the rounding of q~ = fl(q + dq)
        # at |q| ~ 500 perturbs the relative coordinates by ulp(500) per step and
        # the orbit error grows ~100x faster.
        c_hi = np.mean(q0, axis=-1, keepdims=True)
        c_lo = np.zeros_like(c_hi)
        qr = q0 - c_hi
        pc = p0
        for i in range(1, n + 1):
            pc, qr = bt_step(pc, qr, lam0, mu, branch=branch)
            s = np.mean(qr, axis=-1, keepdims=True)
            qr = qr - s
            t = c_hi + s                                   # two-sum (Knuth)
            bp = t - c_hi
            c_lo = c_lo + ((c_hi - (t - bp)) + (s - bp))
            c_hi = t
            P[i] = pc
            Q[i] = c_hi + (c_lo + qr)
        return P, Q
    P, Q = [], []
    pc, qc = bt_step(p, q, lam0, 0, branch=branch)  # validated copy at mp precision
    P.append(pc)
    Q.append(qc)
    for _ in range(n):
        pc, qc = bt_step(pc, qc, lam0, mu, branch=branch)
        P.append(pc)
        Q.append(qc)
    return P, Q
