"""Band-edge conditioning: one float64 step near ``|tr L| = 2`` against ``eps * cond``.

:func:`band_edge_case` puts one end of ``[lam0 - mu, lam0 + mu]`` at ``|tr L| - 2 = delta`` from a
band edge of the paper's example; :func:`map_condition` is the relative normwise condition
number of ``(p, q, lam0, mu) -> (p~, q~)`` from a 50-digit central-difference Jacobian;
:func:`run_band_edge` tabulates the float64 error against ``eps * cond`` (the test
``tests/test_stress.py::test_band_edge_error_within_eps_cond`` asserts ``err <= 4 eps cond``).
"""
from __future__ import annotations

import math
from collections.abc import Callable

import mpmath
import numpy as np

from ..numeric import bt_step, spectral_trace
from ..paper import P_EXAMPLE, Q_EXAMPLE
from .numeric_cases import state_error

__all__ = ["band_edge_case", "map_condition", "run_band_edge"]

P_PAPER, Q_PAPER = P_EXAMPLE, Q_EXAMPLE


def band_edge_case(delta, side=+1, mu=0.5):
    """Paper state with ``|tr L(lam_edge)| - 2 = delta`` at one end of [lam0-mu, lam0+mu].

    The gap of the paper's example containing ``[5, 15]`` ends at the band near
    ``lam = -0.79``; ``side=+1`` puts ``lam2 = lam0 - mu`` at distance ``delta``
    (in |tr| - 2) from that band edge.  ``side=-1`` does the same for the band
    edge near ``lam = -10.28`` from the left, i.e. ``lam1 = lam0 + mu`` close to
    it.  Returns ``(p, q, lam0, mu, delta_actual)`` with float64 parameters
    (``delta_actual`` recomputed at 50 digits from the rounded values).
    """
    p, q = list(P_PAPER), list(Q_PAPER)
    with mpmath.workdps(60):
        P = [mpmath.mpf(v) for v in p]
        Q = [mpmath.mpf(v) for v in q]

        def trm(l):
            return spectral_trace(l, P, Q)
        # bracket the edge: find where |tr| - 2 changes sign near the band
        if side > 0:
            lo, hi = mpmath.mpf(-0.78), mpmath.mpf(2)      # gap side: hi
        else:
            lo, hi = mpmath.mpf(-10.28), mpmath.mpf(-14)    # gap side: hi (left of the band)
        f = lambda l: abs(trm(l)) - 2 - delta
        a, b = lo, hi
        fa = f(a)
        if fa > 0:
            raise RuntimeError("bracket")
        for _ in range(400):
            m = (a + b) / 2
            if f(m) > 0:
                b = m
            else:
                a = m
            if abs(b - a) < mpmath.mpf(10) ** -40:
                break
        le = b
        lam0 = float(le + mu) if side > 0 else float(le - mu)
        lam0_m = mpmath.mpf(lam0)
        edge = lam0_m - mu if side > 0 else lam0_m + mu
        d_act = float(abs(trm(edge)) - 2)
    return p, q, lam0, mu, d_act


def map_condition(p, q, lam0, mu, branch=1, dps=50):
    """Relative normwise condition number of the map (p, q, lam0, mu) -> (p~, q~) at 50 digits.

    ``kappa = ||J|| ||x|| / ||f(x)||`` with the 2-norm, ``x = (p, q - mean q, lam0, mu)``
    and ``f = (p~, q~ - mean q~)`` (the shift of q is a symmetry); ``J`` by central
    differences with step ``1e-20`` at ``dps`` digits (the map's error is then
    far below the O(1e-40) differencing error).  Returns ``(kappa, f(x))``.
    """
    N = len(p)
    with mpmath.workdps(dps):
        x = [mpmath.mpf(v) for v in list(p) + list(q) + [lam0, mu]]

        def F(x):
            pt, qt = bt_step(x[:N], x[N:2 * N], x[2 * N], x[2 * N + 1], branch=branch)
            return pt + qt
        f0 = F(x)
        h = mpmath.mpf(10) ** -20
        cols = []
        for i in range(len(x)):
            xp = list(x)
            xm = list(x)
            xp[i] += h
            xm[i] -= h
            fp, fm = F(xp), F(xm)
            cols.append([(a - b) / (2 * h) for a, b in zip(fp, fm)])
        J = mpmath.matrix(2 * N, len(x))
        for i, col in enumerate(cols):
            for k, v in enumerate(col):
                J[k, i] = v
        Jf = np.array(J.tolist(), dtype=float)
        nJ = np.linalg.norm(Jf, 2)
        xq = [float(v) for v in x]
        mq = sum(xq[N:2 * N]) / N
        xn = math.sqrt(sum(v * v for v in xq[:N]) + sum((v - mq)**2 for v in xq[N:2 * N]) +
                       xq[2 * N]**2 + xq[2 * N + 1]**2)
        ff = [float(v) for v in f0]
        mf = sum(ff[N:]) / N
        fn = math.sqrt(sum(v * v for v in ff[:N]) + sum((v - mf)**2 for v in ff[N:]))
        return nJ * xn / fn, f0


def run_band_edge(log: Callable[[str], None] = print) -> list:
    """The band-edge table: both sides, delta = 1e-2 .. 1e-8."""
    eps = 2.0**-53
    rows = []
    log("  one float64 step near the band edge: error vs eps*cond (cond at 50 digits)")
    for side in (+1, -1):
        for delta in (1e-2, 1e-4, 1e-6, 1e-8):
            p, q, lam0, mu, d = band_edge_case(delta, side)
            kappa, f0 = map_condition(p, q, lam0, mu)
            pt, qt = bt_step(np.array(p), np.array(q), lam0, mu)
            e = state_error(pt, qt, f0[:3], f0[3:])
            rows.append({"side": side, "delta": d, "lam0": lam0, "mu": mu, "err": e, "cond": kappa,
                         "eps_cond": eps * kappa, "ratio": e / (eps * kappa)})
            log("    side %+d  |tr|-2 = %.1e  err %.2e  cond %.2e  eps*cond %.2e  err/(eps cond) %.2f" % (
                side, d, e, kappa, eps * kappa, e / (eps * kappa)))
    return rows
