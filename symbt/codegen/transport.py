"""The closed form's eigenvector slopes, built as :mod:`symbt.numeric` computes them (used by :mod:`.derive`).

:func:`scaled_monodromy` is the product of the scaled one-site matrices with ``lambda + p_j`` kept whole
(no expansion in lambda: no cancellation between its powers); :func:`transported` carries the slope at
site 1 to the other sites in the contracting direction, with only neighbour differences of q.  The
divisions are :class:`~.printer.Quotient` (IEEE-style in every flavour: both branches of the selection
are evaluated).

>>> from symbt.symbolic.toda import toda_model
>>> import sympy as sp
>>> m = toda_model(2)
>>> M = scaled_monodromy(m, sp.Symbol("lam"))
>>> sp.expand(M.det())      # det m_j = r_j, and r_1 r_2 = 1
1
>>> len(transported(m, sp.Symbol("lam"), sp.Symbol("u1"), sp.true))
2
"""
from __future__ import annotations

from typing import Any

import sympy as sp

from ..symbolic.darboux import lam0, mu
from ..symbolic.toda import TodaModel
from .printer import Quotient

__all__ = ["scaled_monodromy", "transported", "turned", "read_out", "illcond_guards"]


def transported(m: TodaModel, lam_: sp.Expr, u0: sp.Expr, forward: sp.Basic) -> list[sp.Expr]:
    """Scaled slopes at every site from ``u0`` at site 1, transported forward ``u_{j+1} = -r_j/(a_j + u_j)``
    where ``forward`` holds, else backward ``u_j = -a_j - r_j/u_{j+1}`` (``a_j = lambda + p_j``, ``r_j =
    exp(q_{j+1} - q_j)``; no shifted monodromy, whose entries reach 1e542 at |q_i - q_j| ~ 650)."""
    N, p, q = m.N, m.p, m.q
    a = [lam_ + p[j] for j in range(N)]
    r = [sp.exp(q[(j + 1) % N] - q[j]) for j in range(N)]
    fwd = [u0]
    for j in range(N - 1):
        fwd.append(-Quotient(r[j], a[j] + fwd[j]))
    bwd: list[Any] = [None] * N        # bwd[0] is u0 itself: never read
    nxt = u0
    for j in range(N - 1, 0, -1):
        nxt = bwd[j] = -a[j] - Quotient(r[j], nxt)
    return [u0] + [sp.Piecewise((fwd[j], forward), (bwd[j], True)) for j in range(1, N)]


def turned(m: TodaModel, lam_: sp.Expr, u0: sp.Expr, forward: sp.Basic) -> sp.Expr:
    """The slope at site 1 after one turn of the transport around the ring from ``u0``, forward where ``forward``
    holds, else backward: the contracting direction of :func:`transported`.

    The root read off the monodromy carries the monodromy's rounding, ``eps`` times the entries of
    ``|m_N| ... |m_1|``, which at ``|lambda| >> |p|`` exceed those of ``M`` by the trace's cancellation (1e5 at the
    deep fuzz's chunk 104, docs/fuzz.md); one turn multiplies that error by the ratio of the eigenvalues
    ``1/|(t -+ g)/2|**2`` and adds only the transport's own rounding (as the transfer-matrix form's
    ``_turn_forward``/``_turn_backward``)."""
    N, p, q = m.N, m.p, m.q
    a = [lam_ + p[j] for j in range(N)]
    r = [sp.exp(q[(j + 1) % N] - q[j]) for j in range(N)]
    fwd = u0
    for j in range(N):
        fwd = -Quotient(r[j], a[j] + fwd)
    bwd = u0
    for j in range(N - 1, -1, -1):
        bwd = -a[j] - Quotient(r[j], bwd)
    return sp.Piecewise((fwd, forward), (bwd, True))


def read_out(mu_: sp.Expr, u: list[sp.Expr], w: list[sp.Expr], d: list[sp.Expr]) -> tuple[list[Any], list[Any]]:
    """``(xr, eta)``: ``xr_j = 2 mu / d_j`` divided once (as :mod:`symbt.numeric`; ``q~_j = q_j + log1p(-xr_j)``) and
    ``p~_j - p_j = 2 mu (u_j/d_j - u_{j+1}/d_{j+1})`` (``d_j = w_j - u_j``) as ``2 mu (f_j g_{j+1} - f_{j+1} g_j)``,
    ``f = u/d``, ``g = w/d = f + 1``.

    The plain difference cancels two fractions near ``-1`` where ``|w_j| << |u_j|`` (``|lambda| >> |p|``): each
    rounds at ``eps``, times a lambda-sized ``2 mu`` (p~_1 = -404 for -3.70 at the deep fuzz's chunk 105,
    docs/fuzz.md).  In the products the fraction near -1 multiplies the small one, so each term rounds at its
    own scale; the four quotients are bounded where ``d`` is not small (no product of slopes: no overflow)."""
    N = len(u)
    f = [Quotient(u[j], d[j]) for j in range(N)]
    g = [Quotient(w[j], d[j]) for j in range(N)]
    xr = [Quotient(2 * mu_, d[j]) for j in range(N)]
    return xr, [2 * mu_ * (f[j] * g[(j + 1) % N] - f[(j + 1) % N] * g[j]) for j in range(N)]


def scaled_monodromy(m: TodaModel, lam_: sp.Expr) -> sp.Matrix:
    """``M = m_N ... m_1``, ``m_j = [[lam_ + p_j, -1], [r_j, 0]]``, ``r_j = exp(q_{j+1} - q_j)``: ``S_1 L S_1^-1``
    with ``S_1 = diag(1, E_1)`` (its slopes are the scaled ``u = E_1 y``), as :mod:`symbt.numeric.core.monodromy`."""
    M = sp.eye(2)
    for j in range(m.N):
        M = sp.Matrix([[lam_ + m.p[j], -1], [sp.exp(m.q[(j + 1) % m.N] - m.q[j]), 0]]) * M
    return M


def illcond_guards(m: TodaModel, guard: Any, traces: tuple[sp.Expr, sp.Expr], u: list[sp.Expr], w: list[sp.Expr],
                   d: list[sp.Expr], disc: Any) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
    """The float64 conditioning guards of the step (condition ``illcond``: ``expr > 0`` where the float64
    result is trusted; ``guard(condition, label, expr, stage)``, ``traces`` the step's traces at ``lam1``,
    ``lam2``, ``disc(t) = (t - 2)(t + 2)``): the test of ``symbt.numeric``'s kernels
    (:func:`symbt.numeric.core.step.trace_kappa`, ``symbt.numeric.float64.kernels``) with its one limit
    :data:`~symbt.numeric.core.limits.KAPPA_MAX` printed in.  Per spectral parameter
    ``T (|t| + 2) / |t^2 - 4| <= KAPPA_MAX`` (``T`` the trace of ``|m_N| ... |m_1|``, the rounding scale of ``t``,
    against the distance ``||t| - 2|`` of the decision):
    ``+-1`` valued (a ``Piecewise``), so a non-finite estimate (an overflowed trace) leaves the decision to
    the range and sign guards after it.  Per site the margin ``KAPPA_MAX |d_j| |1 + xr_j| - kt (|u_j| +
    |w_j|)(|1 + xr_j| + |xr_j|)``, ``xr_j = -2 mu / d_j``, ``kt`` the larger trace condition times the
    cancellation ``max_j (|lam| + |p_j|) / |lam + p_j|``."""
    from ..numeric.core.limits import KAPPA_MAX

    K = sp.Integer(int(KAPPA_MAX))
    N, p = m.N, m.p

    def A(x: sp.Expr) -> sp.Expr:       # unevaluated: SymPy's sign analysis of the large slopes takes minutes
        return sp.Abs(x, evaluate=False)

    # -1 where ``big > small`` (ill-conditioned), else +1 (also where a side is NaN)
    def ill(big: sp.Expr, small: sp.Expr) -> sp.Expr:
        return sp.Piecewise((-1, sp.StrictGreaterThan(big, small, evaluate=False)), (1, True),
                            evaluate=False)

    kt0, kta = [], []
    for t, lam_ in zip(traces, (lam0 + mu, lam0 - mu)):
        Ma = sp.eye(2)
        for j in range(N):
            Ma = sp.Matrix([[A(lam_ + p[j]), 1], [sp.exp(m.q[(j + 1) % N] - m.q[j]), 0]]) * Ma
        k = Quotient(Ma[0, 0] + Ma[1, 1], A(disc(t))) * (A(t) + 2)    # T (|t| + 2) / |t^2 - 4|
        kt0.append(k)
        kta.append(k * sp.Max(*(Quotient(A(lam_) + A(p[j]), A(lam_ + p[j])) for j in range(N)), evaluate=False))
    ill_t = tuple(guard("illcond", f"tr L(lam{i + 1})", ill(kt0[i], K), 0) for i in range(2))
    kt = sp.Max(kta[0], kta[1], evaluate=False)
    ill_s = []
    for j in range(N):
        x = -2 * mu / d[j]
        big = kt * (A(u[j]) + A(w[j])) * (A(1 + x) + A(x))
        # a difference, not a Piecewise: a relation on the Piecewise slopes would print as ITE; the range
        # guards before it made u, w, d finite, and a non-finite margin is a range error (a refusal too)
        ill_s.append(guard("illcond", f"the slopes at site {j + 1}", K * A(d[j]) * A(1 + x) - big, 1))
    return ill_t, tuple(ill_s)
