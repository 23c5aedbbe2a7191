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

import sympy as sp

from ..symbolic.toda import TodaModel
from .printer import Quotient

__all__ = ["scaled_monodromy", "transported"]


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
    bwd: list = [None] * N
    bwd[0] = nxt = u0
    for j in range(N - 1, 0, -1):
        nxt = bwd[j] = -a[j] - Quotient(r[j], nxt)
    return [u0] + [sp.Piecewise((fwd[j], forward), (bwd[j], True)) for j in range(1, N)]


def scaled_monodromy(m: TodaModel, lam_: sp.Expr) -> sp.Matrix:
    """``M = m_N ... m_1``, ``m_j = [[lam_ + p_j, -1], [r_j, 0]]``, ``r_j = exp(q_{j+1} - q_j)``: ``S_1 L S_1^-1``
    with ``S_1 = diag(1, E_1)`` (its slopes are the scaled ``u = E_1 y``), as :mod:`symbt.numeric.core.monodromy`."""
    M = sp.eye(2)
    for j in range(m.N):
        M = sp.Matrix([[lam_ + m.p[j], -1], [sp.exp(m.q[(j + 1) % m.N] - m.q[j]), 0]]) * M
    return M
