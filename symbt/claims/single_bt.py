"""The single-parameter BT (eqs. ``dj``, ``alphabeta``, ``ptp``).

All three statements are about one site of the local relation
:math:`l_j(\\lambda,\\tilde p_j,\\tilde q_j) d_j(\\lambda) = d_{j+1}(\\lambda) l_j(\\lambda,p_j,q_j)`
(eq. ``local``); proving them for one generic site proves them for every N.
"""
from __future__ import annotations

import sympy as sp

from ..proof import decide
from ..symbolic.darboux import local_relation_residual, single_darboux, zeta
from ..symbolic.toda import lam
from .base import Outcome, claim, from_decision, scene

scene("single-bt", "single-parameter BT: local Darboux matrix d_j, alpha/beta, implicit map (all N, by a local identity)")

# one generic site j and its neighbour j+1 (E = e^q, Et = e^q~)
p, pt = sp.symbols("p_j pt_j", real=True)
E, Et, En = sp.symbols("E_j Et_j E_jp1", positive=True)
alpha, beta, alpha_n, beta_n = sp.symbols("alpha_j beta_j alpha_jp1 beta_jp1")


@claim("dj", equation="dj", scene="single-bt",
       statement="d_j = [[lambda-zeta-alpha_j beta_j, -alpha_j],[beta_j, 1]] has det d_j = lambda - zeta, "
                 "so d_j(zeta) is rank one with kernel (1, -beta_j)")
def dj():
    d = single_darboux(alpha, beta)
    d1 = decide(d.det(), lam - zeta)
    if not d1.holds:
        return from_decision(d1)
    return from_decision(decide(d.subs(lam, zeta) * sp.Matrix([1, -beta]), sp.zeros(2, 1)))


def _residual():
    return local_relation_residual(single_darboux(alpha, beta), single_darboux(alpha_n, beta_n), p, E, pt, Et)


@claim("alphabeta", equation="alphabeta", scene="single-bt",
       statement="the off-diagonal part of l_j(p~,q~) d_j = d_{j+1} l_j(p,q) gives alpha_j = e^{q_j}, "
                 "beta_{j+1} = e^{-q~_j} (local, all N)")
def alphabeta():
    R = _residual()
    # lambda^1 coefficients of the off-diagonal entries are linear in alpha_j, beta_{j+1}
    eqs = [sp.Poly(R[0, 1], lam).coeff_monomial(lam), sp.Poly(R[1, 0], lam).coeff_monomial(lam)]
    sol = sp.solve(eqs, [alpha, beta_n], dict=True)
    if len(sol) != 1:
        return Outcome("failed", "exact: sympy.solve of the lambda-coefficients", detail=f"solutions: {sol}")
    d = decide(sp.Matrix([sol[0][alpha], sol[0][beta_n]]), sp.Matrix([E, 1 / Et]))
    return from_decision(d, detail="unique solution of the lambda^1 coefficients of the (1,2) and (2,1) entries")


@claim("ptp", equation="ptp", scene="single-bt",
       statement="with alpha_j = e^{q_j}, beta_j = e^{-q~_{j-1}}: p~_j = -(e^{q~_j-q_j} + e^{q_{j+1}-q~_j} + zeta), "
                 "p_j = -(e^{q~_j-q_j} + e^{q_j-q~_{j-1}} + zeta) solve the local relation (local, all N)")
def ptp():
    Etm = sp.Symbol("Et_jm1", positive=True)  # e^{q~_{j-1}}
    subs = {alpha: E, beta: 1 / Etm, alpha_n: En, beta_n: 1 / Et}
    R = _residual().subs(subs)
    pt_printed = -(Et / E + En / Et + zeta)
    p_printed = -(Et / E + E / Etm + zeta)
    d = decide(R.subs({pt: pt_printed, p: p_printed}), sp.zeros(2, 2))
    return from_decision(d, detail="every entry of l_j(p~,q~) d_j - d_{j+1} l_j(p,q) vanishes identically")
