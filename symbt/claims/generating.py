"""Generating function of the composed map: eqs. ``GF``, ``nlocal``, ``daj``, ``xyqqt``,
``imptransf``, ``newgf``, ``vqqtmu``.

``daj``, ``xyqqt``, ``imptransf`` are statements about one site of the local relation
:math:`l_j(\\tilde p,\\tilde q)\\mathfrak d_j = \\mathfrak d_{j+1} l_j(p,q)` and are proved for a generic
site (hence for every N).  ``newgf``/``vqqtmu`` are proved for N = 2 and 3 exactly, modulo
:math:`\\eta_j^2 = \\mu^2 + w_j` (so for either sign of every eta_j).
"""
from __future__ import annotations

import mpmath as mp
import sympy as sp

from ..proof import decide
from ..reference.literal import literal_step
from ..symbolic.darboux import composed_darboux, lam0, local_relation_residual, mu
from ..symbolic.generating import generating_function
from ..symbolic.toda import lam
from .base import claim, from_decision, scene
from .composed_map import DPS, _states, darboux_numeric, worst_over

scene("generating", "generating function F of the composed map, its mu-derivative (local identities; N=2,3)")

# one generic site j and its right neighbour
p, pt = sp.symbols("p_j pt_j", real=True)
E, Et, En, Etn = sp.symbols("E_j Et_j E_jp1 Et_jp1", positive=True)
xj, yj, xn, yn = sp.symbols("x_j y_j x_jp1 y_jp1")
eta_j, eta_n = sp.symbols("eta_j eta_jp1", real=True)
L1, L2 = lam0 + mu, lam0 - mu


def _site_residual():
    return local_relation_residual(composed_darboux(xj, yj, L1, L2), composed_darboux(xn, yn, L1, L2),
                                   p, E, pt, Et)


@claim("daj", equation="daj", scene="generating",
       statement="the local factors d_j = [[l-l1-x_j y_j, -x_j],[y_j(l1-l2+x_j y_j), l-l2+x_j y_j]] have "
                 "det = (l-l1)(l-l2), kernels (x_j, mu-eta_j) at l1 and (-x_j, mu+eta_j) at l2 "
                 "(eta_j = x_j y_j + mu), and d_1 = D")
def daj():
    d = composed_darboux(xj, yj, L1, L2)
    et = xj * yj + mu
    lhs = sp.Matrix([d.det(), *(d.subs(lam, L1) * sp.Matrix([xj, mu - et])),
                     *(d.subs(lam, L2) * sp.Matrix([-xj, mu + et]))])
    return from_decision(decide(lhs, sp.Matrix([(lam - L1) * (lam - L2), 0, 0, 0, 0])))


@claim("xyqqt", equation="xyqqt", scene="generating",
       statement="the off-diagonal entries of eq. nlocal give x_j = e^{q_j} - e^{q~_j} and "
                 "y_{j+1}(2mu + x_{j+1} y_{j+1}) = e^{-q~_j} - e^{-q_j}; hence eta_j^2 = mu^2 + w_j "
                 "with w_{j+1} = (e^{q_{j+1}} - e^{q~_{j+1}})(e^{-q~_j} - e^{-q_j}) (local, all N)")
def xyqqt():
    R = _site_residual()
    c01 = sp.Poly(R[0, 1], lam).coeff_monomial(lam)
    c10 = sp.Poly(R[1, 0], lam).coeff_monomial(lam)
    d1 = decide(sp.solve(c01, xj)[0], E - Et)
    if not d1.holds:
        return from_decision(d1, detail="x_j")
    d2 = decide(-c10, yn * (2 * mu + xn * yn) - (1 / Et - 1 / E))
    if not d2.holds:
        return from_decision(d2, detail="y_{j+1}")
    # eta^2 = mu^2 + w at site j+1: substitute x_{j+1} = E_{j+1} - E~_{j+1}, reduce modulo the y-equation
    w_n = (En - Etn) * (1 / Et - 1 / E)
    x_n = En - Etn
    d3 = decide((x_n * yn + mu) ** 2, mu ** 2 + w_n,
                relations={yn: yn * (2 * mu + x_n * yn) - (1 / Et - 1 / E)})
    return from_decision(d3, detail="lambda^1 coefficients of the (1,2) and (2,1) entries; eta^2 = mu^2 + w "
                                    "by remainder modulo the y-equation")


def _imptransf_subs():
    """x_j, y_j, y_{j+1} in terms of E, E~, eta (eqs. xyqqt and eta = x y + mu)."""
    xnv = En - Etn
    return {xj: E - Et, yj: (eta_j - mu) / (E - Et), xn: xnv, yn: (eta_n - mu) / xnv}


@claim("imptransf", equation="imptransf", scene="generating",
       statement="with eq. xyqqt, the remaining entries of eq. nlocal give p~_j = -l0 - (e^{q~_j} eta_j + "
                 "e^{q_j} eta_{j+1})/(e^{q_j} - e^{q~_j}), p_j = -l0 - (e^{q~_j} eta_{j+1} + e^{q_j} eta_j)/"
                 "(e^{q_j} - e^{q~_j}) (local, all N, either sign of eta)")
def imptransf():
    pt_pr = -lam0 - (Et * eta_j + E * eta_n) / (E - Et)
    p_pr = -lam0 - (Et * eta_n + E * eta_j) / (E - Et)
    R = _site_residual().subs(_imptransf_subs()).subs({pt: pt_pr, p: p_pr})
    w_n = (En - Etn) * (1 / Et - 1 / E)
    return from_decision(decide(R, sp.zeros(2, 2), relations={eta_n: eta_n ** 2 - mu ** 2 - w_n}),
                         detail="all four entries of the local relation vanish modulo eta_{j+1}^2 = mu^2 + w_{j+1}")


for _N in (2, 3):
    def _make(N):
        @claim(f"nlocal.n{N}", equation="nlocal", scene="generating", N=N,
               statement="the composed map factorizes site by site: l_j(p~,q~) d_j = d_{j+1} l_j(p,q) with d_j "
                         f"of eq. daj, d_{{N+1}} = d_1 = D (N={N})")
        def nlocal_check():
            def residual(state, b):
                pv, qv, l0, m = state
                ptv, qtv, info = literal_step(pv, qv, l0, m, b)
                worst = mp.mpf(0)
                for lv in (mp.mpf("0.3"), mp.mpf("-2.2")):
                    for j in range(N):
                        n = (j + 1) % N
                        dj = darboux_numeric(lv, l0, m, info["x"][j], info["y"][j])
                        dn = darboux_numeric(lv, l0, m, info["x"][n], info["y"][n])
                        lt = mp.matrix([[lv + ptv[j], -mp.exp(qtv[j])], [mp.exp(-qtv[j]), 0]])
                        lo = mp.matrix([[lv + pv[j], -mp.exp(qv[j])], [mp.exp(-qv[j]), 0]])
                        worst = max(worst, mp.mnorm(lt * dj - dn * lo, 1) / (mp.mnorm(lt, 1) * mp.mnorm(dj, 1)))
                return worst

            return from_decision(worst_over(_states(N), residual,
                                            method=f"numeric: mpmath {DPS} digits, every site, 8 states x 2 lambdas"))

        @claim(f"newgf.n{N}", equation="newgf", scene="generating", N=N,
               statement="F = sum_k (mu ln((eta_k+mu)/(eta_k-mu)) - 2 eta_k - l0 (q_k - q~_k)) satisfies "
                         f"p_j = dF/dq_j and p~_j = -dF/dq~_j with p, p~ of eq. imptransf (N={N})")
        def newgf_check():
            g = generating_function(N)
            pp, ppt = g.momenta_printed()
            lhs = sp.Matrix([g.dF_dq(j) for j in range(N)] + [-g.dF_dqt(j) for j in range(N)])
            return from_decision(decide(lhs, sp.Matrix(pp + ppt), relations=g.relations),
                                 detail="implicit differentiation of eta_j; remainder modulo all eta_j^2 = mu^2 + w_j "
                                        "(either sign of each eta_j; the log branch only adds constants)")

        @claim(f"vqqtmu.n{N}", equation="vqqtmu", scene="generating", N=N,
               statement=f"dF/dmu at fixed q, q~ = sum_k ln((eta_k+mu)/(eta_k-mu)) (N={N})")
        def vqqtmu_check():
            g = generating_function(N)
            printed = sp.Add(*[sp.log((e + mu) / (e - mu)) for e in g.eta])
            return from_decision(decide(g.dF_dmu(), printed, relations=g.relations),
                                 detail="d eta/d mu = mu/eta at fixed q, q~; the log terms cancel structurally")

        @claim(f"GF.n{N}", equation="GF", scene="generating", N=N,
               statement="the composed BT is canonical (a generating function F(q, q~) exists): its Jacobian J "
                         f"satisfies J^T Omega J = Omega (N={N})")
        def gf_check():
            Om = mp.matrix(2 * N, 2 * N)
            for i in range(N):
                Om[i, N + i], Om[N + i, i] = 1, -1

            def residual(state, b):
                pv, qv, l0, m = state

                def component(k):
                    return lambda *z: (lambda r: (r[0] + r[1])[k])(literal_step(list(z[:N]), list(z[N:]), l0, m, b))

                J = mp.matrix(2 * N, 2 * N)
                for k in range(2 * N):
                    for i in range(2 * N):
                        J[k, i] = mp.diff(component(k), pv + qv, tuple(int(i == c) for c in range(2 * N)))
                return mp.mnorm(J.T * Om * J - Om, 1) / mp.mnorm(J, 1) ** 2

            return from_decision(worst_over(_states(N)[::3], residual, dps=40, tol=mp.mpf(10) ** -25,
                                            method="numeric: mpmath.diff Jacobian at 40 digits, 3 states"))

    _make(_N)
