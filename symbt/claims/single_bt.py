r"""The single-parameter BT (eqs. ``dj``, ``alphabeta``, ``ptp``).

All three statements are about one site of the local relation (eq. ``local``)

.. math:: l_j(\lambda,\tilde p_j,\tilde q_j)\,d_j(\lambda) = d_{j+1}(\lambda)\,l_j(\lambda,p_j,q_j),\qquad
          d_j = \begin{pmatrix}\lambda-\zeta-\alpha_j\beta_j & -\alpha_j\\ \beta_j & 1\end{pmatrix}:

:math:`\det d_j = \lambda-\zeta`; the :math:`\lambda^1` coefficients of the off-diagonal entries force
:math:`\alpha_j = e^{q_j}`, :math:`\beta_{j+1} = e^{-\tilde q_j}`; the rest gives the implicit map
:math:`\tilde p_j = -(e^{\tilde q_j-q_j}+e^{q_{j+1}-\tilde q_j}+\zeta)`,
:math:`p_j = -(e^{\tilde q_j-q_j}+e^{q_j-\tilde q_{j-1}}+\zeta)`.  Proved for one generic site, they hold for
every N (``n_scope = "all"``): with periodic indices the local relations telescope to
:math:`\tilde L d_1 = d_1 L`, which ``ptp`` also checks at N = 3 as a witness.  The printed formulas are
:class:`~symbt.claims.base.Parts` in the paper's exponential form (turned into :math:`E = e^q` for the
exact decision).

>>> out = dj.run()
>>> out.status, out.n_scope
('verified', 'all')
"""
from __future__ import annotations

import sympy as sp

from ..proof import decide
from ..symbolic.darboux import local_relation_residual, single_darboux, zeta
from ..symbolic.toda import lam, local_lax
from ._site import PER_SITE, for_all_n, to_E
from .base import Outcome, Parts, claim, from_decision, scene

scene("single-bt", "single-parameter BT: local Darboux matrix d_j, alpha/beta, implicit map "
                   "(all N, by a local identity)")

# one generic site j and its neighbours (E = e^q, Et = e^q~)
p, pt = sp.symbols("p_j pt_j", real=True)
q, qt, qn, qtm = sp.symbols("q_j qt_j q_jp1 qt_jm1", real=True)
E, Et, En, Etm = sp.symbols("E_j Et_j E_jp1 Et_jm1", positive=True)
EXP = {q: E, qt: Et, qn: En, qtm: Etm}
alpha, beta, alpha_n, beta_n = sp.symbols("alpha_j beta_j alpha_jp1 beta_jp1")


def _parts_dj() -> Parts:
    return Parts(printed={"d": single_darboux(alpha, beta), "det": lam - zeta, "kernel": sp.Matrix([1, -beta])})


@claim("dj", equation="dj", scene="single-bt", parts=_parts_dj,
       statement="d_j = [[lambda-zeta-alpha_j beta_j, -alpha_j],[beta_j, 1]] has det d_j = lambda - zeta, "
                 "so d_j(zeta) is rank one with kernel (1, -beta_j) (local, all N)")
def dj(parts: Parts):
    d, det, ker = parts.printed["d"], parts.printed["det"], parts.printed["kernel"]
    checks = [("det d_j", decide(d.det(), det)),
              ("det vanishes at zeta", decide(det.subs(lam, zeta), 0)),
              ("kernel", decide(d.subs(lam, zeta) * ker, sp.zeros(2, 1)))]
    bad = next(((name, c) for name, c in checks if not c.holds), None)
    if bad:
        return for_all_n(from_decision(bad[1], detail=bad[0]), PER_SITE)
    if d.subs(lam, zeta).is_zero_matrix or ker.is_zero_matrix:
        return for_all_n(Outcome("failed", "exact", evidence="proof", detail="d_j(zeta) or the kernel vanishes"),
                         PER_SITE)
    return for_all_n(from_decision(checks[-1][1], detail="det d_j, its root zeta, d_j(zeta)(1,-beta_j) = 0"),
                     PER_SITE)


def _residual():
    return local_relation_residual(single_darboux(alpha, beta), single_darboux(alpha_n, beta_n), p, E, pt, Et)


def _parts_alphabeta() -> Parts:
    return Parts(printed={"alpha_j": sp.exp(q), "beta_jp1": sp.exp(-qt)})


@claim("alphabeta", equation="alphabeta", scene="single-bt", parts=_parts_alphabeta,
       statement="the off-diagonal part of l_j(p~,q~) d_j = d_{j+1} l_j(p,q) gives alpha_j = e^{q_j}, "
                 "beta_{j+1} = e^{-q~_j} (local, all N)")
def alphabeta(parts: Parts):
    R = _residual()
    # lambda^1 coefficients of the off-diagonal entries are linear in alpha_j, beta_{j+1}
    eqs = [sp.Poly(R[0, 1], lam).coeff_monomial(lam), sp.Poly(R[1, 0], lam).coeff_monomial(lam)]
    sol = sp.solve(eqs, [alpha, beta_n], dict=True)
    if len(sol) != 1:
        return for_all_n(Outcome("failed", "exact: sympy.solve of the lambda-coefficients", evidence="proof",
                                 detail=f"solutions: {sol}"), PER_SITE)
    printed = sp.Matrix([to_E(parts.printed["alpha_j"], EXP), to_E(parts.printed["beta_jp1"], EXP)])
    d = decide(sp.Matrix([sol[0][alpha], sol[0][beta_n]]), printed)
    return for_all_n(from_decision(d, detail="unique solution of the lambda^1 coefficients of the (1,2) and (2,1) "
                                             "entries"), PER_SITE)


def _parts_ptp() -> Parts:
    return Parts(printed={"pt": -(sp.exp(qt - q) + sp.exp(qn - qt) + zeta),
                          "p": -(sp.exp(qt - q) + sp.exp(q - qtm) + zeta)},
                 context={"alpha_j": sp.exp(q), "beta_j": sp.exp(-qtm)})


def _composed(pt_of, p_of, N: int = 3):
    """L~ d_1 - d_1 L for an N-site ring with the per-site map (p~_j, p_j) as functions of E, E~."""
    Es = sp.symbols(f"E1:{N + 1}", positive=True)
    Ets = sp.symbols(f"Et1:{N + 1}", positive=True)
    L, Lt = sp.eye(2), sp.eye(2)
    for j in range(N):
        s = {E: Es[j], Et: Ets[j], En: Es[(j + 1) % N], Etm: Ets[(j - 1) % N]}
        L = (local_lax(lam, p_of.subs(s, simultaneous=True), Es[j]) * L).applyfunc(sp.expand)
        Lt = (local_lax(lam, pt_of.subs(s, simultaneous=True), Ets[j]) * Lt).applyfunc(sp.expand)
    d1 = single_darboux(Es[0], 1 / Ets[-1])
    # Laurent polynomials in E, E~: expanding is the exact reduction
    return (Lt * d1 - d1 * L).applyfunc(sp.expand), sp.zeros(2, 2)


@claim("ptp", equation="ptp", scene="single-bt", parts=_parts_ptp,
       statement="with alpha_j = e^{q_j}, beta_j = e^{-q~_{j-1}}: p~_j = -(e^{q~_j-q_j} + e^{q_{j+1}-q~_j} + zeta), "
                 "p_j = -(e^{q~_j-q_j} + e^{q_j-q~_{j-1}} + zeta) solve the local relation (local, all N)")
def ptp(parts: Parts):
    a_j, b_j = to_E(parts.context["alpha_j"], EXP), to_E(parts.context["beta_j"], EXP)
    subs = {alpha: a_j, beta: b_j, alpha_n: a_j.subs(E, En), beta_n: b_j.subs(Etm, Et)}
    R = _residual().subs(subs)
    pt_E, p_E = to_E(parts.printed["pt"], EXP), to_E(parts.printed["p"], EXP)
    d = decide(R.subs({pt: pt_E, p: p_E}), sp.zeros(2, 2))
    if not d.holds:
        return for_all_n(from_decision(d, detail="local relation"), PER_SITE)
    witness = decide(*_composed(pt_E, p_E))
    return for_all_n(from_decision(witness, detail="every entry of l_j(p~,q~) d_j - d_{j+1} l_j(p,q) vanishes "
                                                   "identically; composed witness L~ d_1 = d_1 L at N = 3"), PER_SITE)
