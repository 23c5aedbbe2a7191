r"""What ships, 4g: ``FlowField`` where its gradients are renormalised; ``flow_coefficients`` on mpmath input.

:class:`symbt.numeric.flow.field.FlowField` evaluates ``grad G = sum_i W_i grad tr L(lambda_i)`` (its module
docstring: the quadrature rule of the ``c_k``, fixed at the initial state) by forward and backward sweeps of
the scaled transfer matrices; where a sweep leaves ``[2**-900, 2**900]`` -- a neighbour distance
``|q_{j+1} - q_j|`` above ~625 -- it is redone with a power-of-two renormalisation at every site.  The
claims of ``shipped`` evaluate the field at moderate states only.

* ``paths.field_far.n3`` -- the field built at the paper's state (``lam0 = 10, mu = 5``) and evaluated at
  states with ``|q_{j+1} - q_j|`` = 640 .. 650 (gradients ~ ``e^650 = 2**938``): against the same quadrature
  sum evaluated with exact 2x2 products at 350 digits (the rule's nodes ``lambda_i`` and weights ``W_i`` as
  exact numbers; ``d tr / d p_j = tr(S_{j+1} E_00 P_{j-1})``, ``d tr / d r_j = tr(S_{j+1} E_10 P_{j-1})`` with the
  prefix and suffix products ``P``, ``S``; ``dG/dq_j = r_{j-1} dG/dr_{j-1} - r_j dG/dr_j``), component by
  component within ``16 N u sum_i |W_i| A_ij + m u sum_i |W_i| |g_ij|``: ``A_ij`` the same derivative of the
  product of the entrywise absolute values (the rounding scale of the sweeps' ``O(N)`` operations at node
  ``i``, the cancellation included), the second term the sum over the ``m`` nodes.  A component whose bound
  admits a relative error above 1e-8 is not informative there (the sweeps cancel in it) and is not counted;
  at least half of the components must be informative.
* ``paths.coefficients_mp.n3`` -- :func:`~symbt.numeric.flow_coefficients` on mpmath input (30 digits), the
  paper's state on ``[lam0 - mu, lam0 + mu] = [-5.5, -4.056]`` inside its gap ``(-10.27, -0.80)``, both branches,
  against the tanh-sinh quadrature of ``shipped.coefficients`` (the polynomial trace, 30 digits, checked at 42)
  within its bound ``10 * 10**-25 A_k``.  The interval is chosen so that a point outside it at which the route
  might sample its integrand -- its reflection ``a + (a + b)/2 = -10.278`` -- lies in the narrow band
  ``[-10.285, -10.271]``: the route must sample only inside the interval (where the integrand is defined).

Shown to fail on planted bugs in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

from typing import Any

import mpmath as mp
import numpy as np

from ._shipped import without_numba
from .base import Outcome, claim, failed

#: paths.field_far: the field's initial state and parameters, the far states (p, q), the digits
FIELD_P0, FIELD_Q0, FIELD_LAM0, FIELD_MU = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 10.0, 5.0
FAR_STATES = (((1.0, -2.0, 0.5), (0.0, 650.0, 0.0)), ((1.0, -2.0, 0.5), (0.0, -640.0, 3.0)),
              ((-3.0, 4.0, 0.25), (645.0, 0.0, 0.5)))
FIELD_DPS, FIELD_INFORMATIVE = 350, 1e-8
EPS = 2.0 ** -52


def trace_gradient(lam: mp.mpf, p: list, r: list, absolute: bool, inv_s: Any = 1) -> list:
    """``(d tr/dp_j, d tr/dr_j)`` of ``tr(m_N ... m_1)``, ``m_j = [[lam + p_j, -inv_s], [r_j, 0]]`` (exact
    products); ``absolute``: of the product of the entrywise absolute values."""
    N = len(p)
    f = (lambda x: abs(x)) if absolute else (lambda x: x)
    m = [mp.matrix([[f(lam + p[j]), f(-mp.mpf(inv_s))], [r[j], 0]]) for j in range(N)]
    pre = [mp.eye(2)]
    for j in range(N):
        pre.append(m[j] * pre[-1])                 # pre[j] = m_{j-1} ... m_0
    suf = [mp.eye(2)] * (N + 1)
    for j in range(N - 1, -1, -1):
        suf[j] = suf[j + 1] * m[j]                 # suf[j] = m_{N-1} ... m_j
    E00, E10 = mp.matrix([[1, 0], [0, 0]]), mp.matrix([[0, 0], [1, 0]])
    dp = [(suf[j + 1] * E00 * pre[j])[0, 0] + (suf[j + 1] * E00 * pre[j])[1, 1] for j in range(N)]
    dr = [(suf[j + 1] * E10 * pre[j])[0, 0] + (suf[j + 1] * E10 * pre[j])[1, 1] for j in range(N)]
    return dp + dr


def field_reference(f: Any, p: tuple, q: tuple) -> tuple[list, list]:
    """``(qdot, pdot)`` exactly (350 digits) from the rule of ``f``, and the components' rounding scales."""
    N = len(p)
    nodes = np.asarray(f.nodes)
    W = np.asarray(f.weights) / np.exp2((N - 1) * np.asarray(f.log2_scale))
    with mp.workdps(FIELD_DPS):
        P, Q = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]
        r = [mp.exp(Q[(j + 1) % N] - Q[j]) for j in range(N)]
        g = [mp.mpf(0)] * (2 * N)
        a = [mp.mpf(0)] * (2 * N)
        s = [mp.mpf(0)] * (2 * N)
        for lam, w in zip(nodes, W):
            w = mp.mpf(float(w))
            gi = trace_gradient(mp.mpf(float(lam)), P, r, False)
            ai = trace_gradient(mp.mpf(float(lam)), P, r, True)
            for k in range(2 * N):
                g[k] += w * gi[k]
                a[k] += abs(w) * ai[k]
                s[k] += abs(w * gi[k])
        # (qdot, pdot) = (dG/dp, -dG/dq), dG/dq_j = r_{j-1} dG/dr_{j-1} - r_j dG/dr_j
        ref = g[:N] + [-(r[j - 1] * g[N + (j - 1) % N] - r[j] * g[N + j]) for j in range(N)]
        ascale = a[:N] + [r[j - 1] * a[N + (j - 1) % N] + r[j] * a[N + j] for j in range(N)]
        sscale = s[:N] + [r[j - 1] * s[N + (j - 1) % N] + r[j] * s[N + j] for j in range(N)]
        m = len(nodes)
        bound = [16 * N * EPS * x + m * EPS * y for x, y in zip(ascale, sscale)]
    return ref, bound


@claim("paths.field_far", equation="eqdisc", source_equation="eqdisc", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/flow/field.py: FlowField.__call__ (the renormalised gradient)",
       statement="FlowField (built at the paper's state, lam0 = 10, mu = 5) at states with |q_{j+1} - q_j| = 640 .. "
                 "650 (N={N}) = its quadrature sum with exact 2x2 products at 350 digits, every informative "
                 "component within 16 N u sum_i |W_i| A_ij + m u sum_i |W_i g_ij|")
def field_far(N: int) -> Outcome:
    from ..numeric.flow.field import FlowField

    with without_numba():       # the rule's existence check: the plain-Python kernel (bit-identical), no compile
        f = FlowField(list(FIELD_P0), list(FIELD_Q0), FIELD_LAM0, FIELD_MU)
    bad, used, total, worst = [], 0, 0, 0.0
    for p, q in FAR_STATES:
        qd, pd = f(np.array(p), np.array(q))
        ref, bound = field_reference(f, p, q)
        with mp.workdps(FIELD_DPS):
            for k, (x, y, bd) in enumerate(zip(list(qd) + list(pd), ref, bound)):
                total += 1
                if not bd <= FIELD_INFORMATIVE * abs(y):
                    continue
                used += 1
                ratio = float(abs(mp.mpf(float(x)) - y) / bd)
                worst = max(worst, ratio)
                if not ratio <= 1:
                    bad.append(f"q = {q}, component {k}: |field - exact| = {ratio:.3g} x its bound")
    detail = f"{used} informative components of {total}; worst error / bound {worst:.3g}."
    if 2 * used < total:
        bad.append("fewer than half of the components are informative")
    if bad:
        return failed("numeric: FlowField at far states vs its quadrature sum (exact products)",
                      detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: FlowField at far states vs its quadrature sum (exact products, 350 digits)",
                   evidence="sampled", detail=detail, printed="field = exact quadrature sum within its rounding")


#: paths.coefficients_mp: the paper's state on an interval of its gap (exact binary lam0 -+ mu not needed: the
#: reference integrates over the same double end points)
GAP_STATE = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), -4.778, 0.722)


@claim("paths.coefficients_mp", equation="eqdisc", source_equation="eqdisc", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/flow/coefficients.py: flow_coefficients on mpmath input (_coefficients_mp)",
       statement="flow_coefficients (mpmath, 30 digits, N={N}) on the paper's state over [-5.5, -4.056] inside its "
                 "gap, both branches = the tanh-sinh quadrature of -b int lam^k / sqrt(tr^2 - 4) with the "
                 "polynomial trace (30 digits, checked at 42) within 10 * 10^-25 A_k")
def coefficients_mp(N: int) -> Outcome:
    from ..numeric import flow_coefficients
    from .shipped_spectral import MP_DPS, QUAD_C, _c_ref

    st = GAP_STATE
    c, A, agree, _ = _c_ref(st)
    bad, worst = [], 0.0
    if not agree < 1e-27:
        bad.append(f"the reference disagrees with itself at 42 digits ({agree:.3g})")
    for b in (1, -1):
        with mp.workdps(MP_DPS):
            try:
                got = flow_coefficients([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]], mp.mpf(st[2]),
                                        mp.mpf(st[3]), branch=b, check=False)
            except (ArithmeticError, ValueError) as exc:      # NoRealMapError on a gap interval: wrong
                bad.append(f"branch {b}: {type(exc).__name__}: {str(exc)[:80]}")
                continue
            for k, (v, x, a) in enumerate(zip(got, c, A)):
                r = float(abs(v - b * x) / (QUAD_C * mp.mpf(10) ** (5 - MP_DPS) * a))
                worst = max(worst, r)
                if not r <= 1:
                    bad.append(f"branch {b}, c_{k}: {r:.3g} x the bound")
    detail = f"worst error / bound {worst:.3g}."
    if bad:
        return failed("numeric: flow_coefficients (mpmath) vs the quadrature", detail="; ".join(bad[:3]) + ". "
                      + detail)
    return Outcome("verified", "numeric: flow_coefficients (mpmath) vs mpmath.quad with the polynomial trace",
                   evidence="sampled", detail=detail, printed="|c_k - quadrature| <= 10 * 10^-25 A_k")
