"""Literal ("paper-route") Bäcklund step in mpmath -- a slow, *independent* reference.

This follows eqs. (eq:lax), (xy), (lam0mu), (xyqqt) of the paper verbatim:

1. build the 2x2 monodromy ``L(lam) = l_N ... l_1`` with ``E_j = exp(q_j)`` at
   ``lam1 = lam0 + mu`` and ``lam2 = lam0 - mu``;
2. ``y_1 = (A1 - D1 + g1) / (2 B1)``, ``z_1 = (A2 - D2 - g2) / (2 B2)`` with
   ``g_i = branch * sqrt(tr_i**2 - 4)``;
3. transport both slopes *forward* with ``y' = -1 / (E_j (lam + p_j + E_j y))``;
4. ``x_j = 2 mu / (z_j - y_j)``, ``Etilde_j = E_j - x_j``, ``eta_j = x_j y_j + mu``,
   ``ptilde_j = p_j + eta_j - eta_{j+1}``.

Step 3 is numerically unstable for one of the two slopes (it is transported
against the contracting direction) and loses about ``log10(|v_max|**2)`` digits
per period; step 4 cancels catastrophically for small ``mu``.  The function
therefore works at ``mp.dps + guard`` digits with an *automatic* guard chosen
from the size of the traces, and can be asked to verify itself by re-running
with more digits.  It is meant for tests, never for production use.

Example
-------
>>> import mpmath
>>> from symbt.numeric.reference import literal_step
>>> with mpmath.workdps(30):
...     pt, qt = literal_step([-20, 10, 1], [1, 0, 0.9], 10, 5)
>>> print(mpmath.nstr(pt[0], 12))
-19.9965676649
"""

from __future__ import annotations

import mpmath

from ..literal import literal_step as _paper_route
from ..literal import spectral_trace_mp

__all__ = ["literal_step", "literal_trace"]


def literal_trace(lam, p, q):
    """``tr L(lam)`` from the literal 2x2 product (mpmath, current precision)."""
    return spectral_trace_mp(mpmath.mpf(lam), [mpmath.mpf(v) for v in p], [mpmath.mpf(v) for v in q])


def _literal_once(p, q, lam0, mu, branch):
    # the paper's route itself lives in symbt.literal (shared with the claims); this module adds
    # the automatic guard digits and the self-verification
    pt, qt, info = _paper_route(p, q, lam0, mu, branch)
    return pt, qt, (info["tr1"], info["tr2"])


def literal_step(p, q, lam0, mu, *, branch=1, guard=None, verify=False):
    """Literal Bäcklund step; returns ``(p_new, q_new)`` as lists at ``mp.dps``.

    ``guard`` extra decimal digits are used internally (default: 20 plus twice
    ``log10`` of the larger trace, which bounds the loss of the unstable
    forward transport).  With ``verify=True`` the computation is repeated with
    25 more digits and an ``AssertionError`` is raised unless both agree to
    ``mp.dps`` digits.  Complex results (no real map) are returned as mpc.
    """
    dps = mpmath.mp.dps
    with mpmath.workdps(dps + 30):
        P = [mpmath.mpf(v) for v in p]
        Q = [mpmath.mpf(v) for v in q]
        l0, m = mpmath.mpf(lam0), mpmath.mpf(mu)
        t1 = literal_trace(l0 + m, P, Q)
        t2 = literal_trace(l0 - m, P, Q)
    if guard is None:
        big = max(abs(t1), abs(t2), mpmath.mpf(10))
        guard = 20 + 2 * int(mpmath.log10(big)) + 2 * len(P)
    with mpmath.workdps(dps + guard):
        P = [mpmath.mpf(v) for v in p]
        Q = [mpmath.mpf(v) for v in q]
        pt, qt, _ = _literal_once(P, Q, mpmath.mpf(lam0), mpmath.mpf(mu), branch)
    if verify:
        with mpmath.workdps(dps + guard + 25):
            P = [mpmath.mpf(v) for v in p]
            Q = [mpmath.mpf(v) for v in q]
            pt2, qt2, _ = _literal_once(P, Q, mpmath.mpf(lam0), mpmath.mpf(mu), branch)
            scale = max(abs(v) for v in pt + qt) + 1
            diff = max(abs(a - b) for a, b in zip(pt + qt, pt2 + qt2))
            if diff > scale * mpmath.mpf(10) ** (-dps):
                raise AssertionError("literal reference not converged: %s" % mpmath.nstr(diff, 5))
    return [+v for v in pt], [+v for v in qt]
