r"""What ships, 4g: ``FlowField`` far from its initial state, where its gradients are renormalised (``numeric-paths``).

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

Shown to fail on a planted bug in ``tests/test_killers_numeric.py``.
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


def trace_gradient(lam: mp.mpf, p: list, r: list, absolute: bool) -> list:
    """``(d tr/dp_j, d tr/dr_j)`` of ``tr(m_N ... m_1)``, ``m_j = [[lam + p_j, -1], [r_j, 0]]`` (exact products);
    ``absolute``: of the product of the entrywise absolute values."""
    N = len(p)
    f = (lambda x: abs(x)) if absolute else (lambda x: x)
    m = [mp.matrix([[f(lam + p[j]), f(mp.mpf(-1))], [r[j], 0]]) for j in range(N)]
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
