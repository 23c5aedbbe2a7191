r"""Darboux (dressing) matrices of the Toda Bäcklund transformations.

* eq. ``dj``  : single-parameter local matrix
  :math:`d_j = \begin{pmatrix}\lambda-\zeta-\alpha_j\beta_j & -\alpha_j\\ \beta_j & 1\end{pmatrix}`;
* eq. ``hd``  : its adjugate :math:`\hat D`;
* eq. ``D1D2``/``Dapp``/``D`` : the composition :math:`\mathcal D = \hat D(\lambda,\lambda_2) D(\lambda,\lambda_1)`;
* eq. ``daj`` : the local factors :math:`\mathfrak d_j` of the composed map.

The *local relation* (eqs. ``local``/``nlocal``)
:math:`l_j(\lambda,\tilde p_j,\tilde q_j)\,d_j(\lambda) = d_{j+1}(\lambda)\,l_j(\lambda,p_j,q_j)`
involves one site only, so an identity proved for it holds for every N.

Example
-------
>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> sp.factor(composed_darboux(x, y).det())
(lambda - lambda1)*(lambda - lambda2)
"""
from __future__ import annotations

import sympy as sp

from .toda import lam, local_lax

__all__ = [
    "zeta", "lam0", "mu", "lam1", "lam2",
    "single_darboux", "single_darboux_adjugate", "composed_darboux",
    "darboux_composition", "local_relation_residual",
]

zeta = sp.Symbol("zeta")
lam0, mu = sp.symbols("lambda0 mu", real=True)
lam1, lam2 = sp.symbols("lambda1 lambda2", real=True)


def single_darboux(alpha: sp.Expr, beta: sp.Expr, zeta_: sp.Expr = zeta, lam_: sp.Expr = lam) -> sp.Matrix:
    """Eq. ``dj`` (and ``d1`` for j = 1)."""
    return sp.Matrix([[lam_ - zeta_ - alpha * beta, -alpha], [beta, 1]])


def single_darboux_adjugate(alpha: sp.Expr, beta: sp.Expr, zeta_: sp.Expr = zeta, lam_: sp.Expr = lam) -> sp.Matrix:
    """Eq. ``hd``: the adjugate of :func:`single_darboux` as printed."""
    return sp.Matrix([[1, alpha], [-beta, lam_ - zeta_ - alpha * beta]])


def composed_darboux(x: sp.Expr, y: sp.Expr, l1: sp.Expr = lam1, l2: sp.Expr = lam2, lam_: sp.Expr = lam) -> sp.Matrix:
    """Eqs. ``D``/``Dapp``/``daj``: the two-parameter Darboux matrix as printed."""
    return sp.Matrix([[lam_ - l1 - x * y, -x], [y * (l1 - l2 + x * y), lam_ - l2 + x * y]])


def darboux_composition(x1: sp.Expr, x2: sp.Expr, y1: sp.Expr, y2: sp.Expr, l1: sp.Expr = lam1, l2: sp.Expr = lam2,
                        lam_: sp.Expr = lam) -> sp.Matrix:
    """Eq. ``D1D2``: :math:`\\hat D(\\lambda,\\lambda_2)\\,D(\\lambda,\\lambda_1)`, expanded."""
    Dhat2 = sp.Matrix([[1, x2], [-y2, lam_ - l2 - x2 * y2]])
    D1 = sp.Matrix([[lam_ - l1 - x1 * y1, -x1], [y1, 1]])
    return (Dhat2 * D1).applyfunc(sp.expand)


def local_relation_residual(d_here: sp.Matrix, d_next: sp.Matrix, p: sp.Expr, E: sp.Expr, pt: sp.Expr, Et: sp.Expr,
                            lam_: sp.Expr = lam) -> sp.Matrix:
    """:math:`l_j(\\tilde p,\\tilde q) d_j - d_{j+1} l_j(p,q)` (zero iff the local relation holds)."""
    return (local_lax(lam_, pt, Et) * d_here - d_next * local_lax(lam_, p, E)).applyfunc(sp.expand)
