r"""Generating function of the composed BT (eqs. ``xyqqt``, ``imptransf``, ``newgf``, ``vqqtmu``).

Variables: :math:`E_j = e^{q_j}`, :math:`\tilde E_j = e^{\tilde q_j}` (positive), and
:math:`\eta_j` treated as an *algebraic* symbol subject to

.. math:: \eta_j^2 = \mu^2 + w_j,\qquad
          w_j = (E_j - \tilde E_j)\,(\tilde E_{j-1}^{-1} - E_{j-1}^{-1})

(eq. ``xyqqt`` and the display after it; indices mod N).  The sign of
:math:`\eta_j` is *not* fixed by this relation; every identity below is proved
modulo the relation, hence for both signs.  Derivatives of functions of
:math:`\eta` use implicit differentiation,
:math:`\partial\eta_j/\partial s = (\partial w_j/\partial s)/(2\eta_j)` and
:math:`\partial\eta_j/\partial\mu = \mu/\eta_j`.

Logarithms: :math:`(\eta+\mu)/(\eta-\mu) = (\eta+\mu)^2/w`, which is negative
when :math:`w < 0`.  The real generating function uses
:math:`\ln|(\eta+\mu)/(\eta-\mu)|`; it differs from any complex branch by a
constant, so all derivatives below are the same.

Example
-------
>>> import sympy as sp
>>> g = GeneratingFunction(2)
>>> g.w(0) == (g.E[0] - g.Et[0]) * (1 / g.Et[1] - 1 / g.E[1])   # the neighbour of site 1 is 2 (mod 2)
True
>>> sp.expand(g.relations[g.eta[0]] - (g.eta[0]**2 - g.mu**2 - g.w(0)))
0
"""
from __future__ import annotations

from collections.abc import Mapping
from functools import cache, cached_property

import sympy as sp

from .darboux import lam0, mu

__all__ = ["GeneratingFunction", "generating_function", "implicit_derivative"]


def implicit_derivative(expr: sp.Expr, var: sp.Symbol, etas: Mapping[sp.Symbol, sp.Expr], mu_: sp.Symbol) -> sp.Expr:
    r"""d expr / d var with each :math:`\eta` of ``etas`` an implicit function, :math:`\eta^2 = \mu^2 + w`.

    ``etas`` maps each :math:`\eta` to its :math:`w`; then
    :math:`\partial\eta/\partial s = (\partial w/\partial s)/(2\eta)` for a variable :math:`s \ne \mu`
    and :math:`\partial\eta/\partial\mu = \mu/\eta` (``mu_`` is :math:`\mu`; :math:`w` does not
    depend on it).  This is the one implementation of the derivatives of the generating function:
    :meth:`GeneratingFunction.total_derivative` and the claims on eqs. ``newgf``, ``vqqtmu`` and
    ``PoincareCartan`` all call it.

    >>> import sympy as sp
    >>> eta, mu, s = sp.symbols("eta mu s", positive=True)
    >>> implicit_derivative(eta**2, s, {eta: s**3}, mu)      # d(mu^2 + s^3)/ds
    3*s**2
    >>> implicit_derivative(eta, mu, {eta: s}, mu)
    mu/eta
    """
    out = sp.diff(expr, var)
    for e, w in etas.items():
        de = sp.diff(expr, e)
        if de == 0:
            continue
        # d eta/d var = (d w/d var)/(2 eta), or mu/eta for var = mu (from eta^2 = mu^2 + w)
        deta = mu_ / e if var == mu_ else sp.diff(w, var) / (2 * e)
        if deta != 0:
            out += de * deta
    return out


class GeneratingFunction:
    """Symbolic F(q, q~, mu) of eq. ``newgf`` for an N-site periodic lattice."""

    def __init__(self, N: int):
        self.N = N
        self.E = sp.symbols(f"E1:{N + 1}", positive=True)
        self.Et = sp.symbols(f"Et1:{N + 1}", positive=True)
        self.eta = sp.symbols(f"eta1:{N + 1}", real=True)
        self.mu, self.lam0 = mu, lam0

    def w(self, j: int) -> sp.Expr:
        """:math:`w_j` (0-based j; the neighbour j-1 is taken mod N)."""
        k = (j - 1) % self.N
        return (self.E[j] - self.Et[j]) * (1 / self.Et[k] - 1 / self.E[k])

    @cached_property
    def relations(self) -> dict[sp.Expr, sp.Expr]:
        return {self.eta[j]: sp.expand(self.eta[j] ** 2 - self.mu ** 2 - self.w(j)) for j in range(self.N)}

    @cached_property
    def F(self) -> sp.Expr:
        """Eq. ``newgf`` with q_k = log E_k, q~_k = log E~_k."""
        mu, lam0 = self.mu, self.lam0
        return sp.Add(*[mu * sp.log((e + mu) / (e - mu)) - 2 * e - lam0 * (sp.log(E) - sp.log(Et))
                        for e, E, Et in zip(self.eta, self.E, self.Et)])

    def total_derivative(self, expr: sp.Expr, var: sp.Symbol) -> sp.Expr:
        """d expr / d var with every eta_j = eta_j(E, E~, mu) differentiated implicitly
        (:func:`implicit_derivative` with :math:`\\eta_j^2 = \\mu^2 + w_j`).

        >>> g = generating_function(2)
        >>> g.total_derivative(g.eta[0] ** 2, g.E[0]) - sp.diff(g.w(0), g.E[0])
        0
        """
        return implicit_derivative(expr, var, {e: self.w(j) for j, e in enumerate(self.eta)}, self.mu)

    def dF_dq(self, j: int) -> sp.Expr:
        """:math:`\\partial F/\\partial q_j = E_j\\,dF/dE_j`."""
        return self.E[j] * self.total_derivative(self.F, self.E[j])

    def dF_dqt(self, j: int) -> sp.Expr:
        return self.Et[j] * self.total_derivative(self.F, self.Et[j])

    def dF_dmu(self) -> sp.Expr:
        return self.total_derivative(self.F, self.mu)

    def momenta_printed(self) -> tuple[list[sp.Expr], list[sp.Expr]]:
        """Eq. ``imptransf`` as printed: (p_j, p~_j) in terms of eta, E, E~."""
        N, lam0 = self.N, self.lam0
        p, pt = [], []
        for j in range(N):
            n = (j + 1) % N
            E, Et, e, en = self.E[j], self.Et[j], self.eta[j], self.eta[n]
            pt.append(-lam0 - (Et * e + E * en) / (E - Et))
            p.append(-lam0 - (Et * en + E * e) / (E - Et))
        return p, pt


@cache
def generating_function(N: int) -> GeneratingFunction:
    """Cached :class:`GeneratingFunction` (one per N).

    >>> generating_function(3).N
    3
    """
    return GeneratingFunction(N)
