r"""The periodic Toda lattice: local Lax matrices, monodromy, spectral invariants.

Paper, eq. ``eq:lax``:

.. math::  L(\lambda) = l_N(\lambda)\cdots l_1(\lambda),\qquad
           l_j(\lambda) = \begin{pmatrix}\lambda + p_j & -e^{q_j}\\ e^{-q_j} & 0\end{pmatrix}

and eq. ``tra``: :math:`\operatorname{tr}L(\lambda) = \sum_{k=0}^N H_k\lambda^k`, :math:`H_N = 1`.

Everything is built in the *rational* variables :math:`E_j = e^{q_j}` (positive
symbols), so that every identity about the model is an identity of rational
functions and can be decided by ``cancel``.  Derivatives in :math:`q_j` use the
chain rule :math:`\partial_{q_j} = E_j\,\partial_{E_j}`.

Conventions: :math:`\{p_i, q_j\} = \delta_{ij}`, :math:`\dot x = \{H, x\}`, so
:math:`\{f, g\} = \sum_i \partial_{p_i} f\,\partial_{q_i} g - \partial_{q_i} f\,\partial_{p_i} g`
and :math:`\dot q = \partial H/\partial p`, :math:`\dot p = -\partial H/\partial q`.

Example
-------
>>> m = toda_model(2)
>>> m.hamiltonians[2], m.hamiltonians[1]
(1, p1 + p2)
"""
from __future__ import annotations

from collections.abc import Sequence
from functools import cache, cached_property

import sympy as sp

__all__ = ["TodaModel", "toda_model", "local_lax"]

lam = sp.Symbol("lambda", real=True)


def local_lax(lam_: sp.Expr, p: sp.Expr, E: sp.Expr) -> sp.Matrix:
    """:math:`l_j(\\lambda)` of eq. ``eq:lax`` with ``E = e^{q_j}``."""
    return sp.Matrix([[lam_ + p, -E], [1 / E, 0]])


class TodaModel:
    """Symbolic N-site periodic Toda lattice in the variables ``p_j``, ``E_j = e^{q_j}``."""

    def __init__(self, N: int):
        if N < 2:
            raise ValueError("the periodic Toda lattice needs N >= 2")
        self.N = N
        self.lam = lam
        self.p = sp.symbols(f"p1:{N + 1}", real=True)
        self.q = sp.symbols(f"q1:{N + 1}", real=True)
        self.E = sp.symbols(f"E1:{N + 1}", positive=True)

    # -- Lax matrix -------------------------------------------------------
    def lax(self, lam_: sp.Expr | None = None, p: Sequence[sp.Expr] | None = None,
            E: Sequence[sp.Expr] | None = None) -> sp.Matrix:
        """``L = l_N ... l_1`` (eq. ``eq:lax``), entries polynomial in lambda, p and E^{±1}."""
        lam_ = self.lam if lam_ is None else lam_
        p = self.p if p is None else p
        E = self.E if E is None else E
        M = sp.eye(2)
        for j in range(self.N):
            M = local_lax(lam_, p[j], E[j]) * M
        return M.applyfunc(sp.expand)

    @cached_property
    def L(self) -> sp.Matrix:
        return self.lax()

    @cached_property
    def trace(self) -> sp.Expr:
        return sp.expand(self.L[0, 0] + self.L[1, 1])

    @cached_property
    def hamiltonians(self) -> list[sp.Expr]:
        """``[H_0, ..., H_N]``: coefficients of tr L in powers of lambda (eq. ``tra``)."""
        poly = sp.Poly(self.trace, self.lam)
        return [sp.expand(poly.coeff_monomial(self.lam ** k)) for k in range(self.N + 1)]

    # -- exp(q) <-> E -----------------------------------------------------
    def to_E(self, expr: sp.Expr) -> sp.Expr:
        """Replace ``exp(integer combination of q)`` (and cosh/sinh) by monomials in ``E``."""
        from .rewriting import rationalize_exponentials

        out, _ = rationalize_exponentials(expr, dict(zip(self.q, self.E)))
        return out

    def to_q(self, expr: sp.Expr) -> sp.Expr:
        """Inverse of :meth:`to_E`."""
        return sp.sympify(expr).subs({E: sp.exp(q) for E, q in zip(self.E, self.q)})

    # -- calculus in canonical coordinates ---------------------------------
    def d_q(self, expr: sp.Expr, j: int) -> sp.Expr:
        """:math:`\\partial/\\partial q_j` of an expression in E (0-based ``j``)."""
        return self.E[j] * sp.diff(expr, self.E[j])

    def d_p(self, expr: sp.Expr, j: int) -> sp.Expr:
        return sp.diff(expr, self.p[j])

    def poisson(self, f: sp.Expr, g: sp.Expr) -> sp.Expr:
        """:math:`\\{f, g\\} = \\sum_i f_{p_i} g_{q_i} - f_{q_i} g_{p_i}` (paper's ``{p_i,q_j}=δ_ij``).

        The one bracket of the library; its sign is the claim ``intdis.poisson``'s.

        >>> m = toda_model(2)
        >>> m.poisson(m.p[0], sp.log(m.E[0])), m.poisson(sp.log(m.E[0]), m.p[0]), m.poisson(m.p[0], m.p[1])
        (1, -1, 0)
        """
        return sp.Add(*[self.d_p(f, i) * self.d_q(g, i) - self.d_q(f, i) * self.d_p(g, i)
                        for i in range(self.N)])

    def hamiltonian_vector_field(self, H: sp.Expr) -> tuple[list[sp.Expr], list[sp.Expr]]:
        """``(qdot, pdot)`` for ``xdot = {H, x}``: ``qdot = H_p``, ``pdot = -H_q``.

        >>> m = toda_model(2)
        >>> m.hamiltonian_vector_field(m.p[0] ** 2 / 2 + m.E[0])
        ([p1, 0], [-E1, 0])
        """
        return ([self.d_p(H, i) for i in range(self.N)],
                [-self.d_q(H, i) for i in range(self.N)])


@cache
def toda_model(N: int) -> TodaModel:
    """Cached :class:`TodaModel` (derivations for one N are never redone)."""
    return TodaModel(N)
