"""Section 2's toy canonical transformation p~ = p + mu q, q~ = q + mu p + mu^2 q (unlabelled
displays between eqs. ``hamil`` and ``ICI``): its F, dF/dmu, Phi^ and K."""
from __future__ import annotations

import sympy as sp

from ..proof import decide
from .base import claim, from_decision, scene

scene("toy", "Section 2's toy canonical transformation: F, dF/dmu, Phi^, K")

p, q, pt, qt, mu = sp.symbols("p q pt qt mu", real=True)
WHERE = "Section 2, displays after eq. hamil"

P_NEW = p + mu * q
Q_NEW = q + mu * p + mu ** 2 * q
F = -((qt - q) ** 2 + q ** 2 * mu ** 2) / (2 * mu)
# inverse map, as printed in K: p = p~ - mu q~ + mu^2 p~, q = q~ - mu p~
P_OLD = pt - mu * qt + mu ** 2 * pt
Q_OLD = qt - mu * pt
PHI_HAT = (pt ** 2 - (qt - mu * pt) ** 2) / 2


@claim("toy.F", equation="toy-F", scene="toy", where=WHERE,
       statement="F = -((q~-q)^2 + q^2 mu^2)/(2 mu) generates the map: p = dF/dq, p~ = -dF/dq~ at q~ = q~(p,q)")
def toy_F():
    on_map = {qt: Q_NEW}
    return from_decision(decide(sp.Matrix([sp.diff(F, q).subs(on_map), -sp.diff(F, qt).subs(on_map)]),
                                sp.Matrix([p, P_NEW])))


@claim("toy.dFdmu", equation="toy-dFdmu", scene="toy", where=WHERE,
       statement="dF/dmu = ((q~-q)^2 - q^2 mu^2)/(2 mu^2) at fixed q, q~")
def toy_dFdmu():
    return from_decision(decide(sp.diff(F, mu), ((qt - q) ** 2 - q ** 2 * mu ** 2) / (2 * mu ** 2)))


@claim("toy.Phihat", equation="toy-Phihat", scene="toy", where=WHERE,
       statement="Phi^(p~,q~,mu) = dF/dmu at q = q(p~,q~,mu) = (p~^2 - (q~ - mu p~)^2)/2, and Phi^ != Phi "
                 "as functions")
def toy_Phihat():
    dF = sp.diff(F, mu)
    inverse_ok = decide(sp.Matrix([P_NEW, Q_NEW]).subs({p: P_OLD, q: Q_OLD}, simultaneous=True),
                        sp.Matrix([pt, qt]))
    if not inverse_ok.holds:
        return from_decision(inverse_ok, detail="printed inverse map")
    d = decide(dF.subs(q, Q_OLD), PHI_HAT)
    phi = dF.subs(qt, Q_NEW)  # Phi(p, q, mu)
    differ = decide(phi.subs({p: pt, q: qt}, simultaneous=True), PHI_HAT)
    out = from_decision(d, detail=f"Phi(a,b) vs Phi^(a,b) as functions: {differ.verdict} (paper: they differ)")
    if differ.holds:
        out.status = "failed"
    return out


@claim("toy.K", equation="toy-K", scene="toy", where=WHERE,
       statement="if (p, q) follow the Hamiltonian T(p,q,mu), (p~, q~) follow K = T(p~ - mu q~ + mu^2 p~, "
                 "q~ - mu p~, mu) + (p~^2 - (q~ - mu p~)^2)/2 (checked for T = 0 and a generic polynomial T)")
def toy_K():
    a, b, c = sp.symbols("a b c", real=True)
    results = []
    for T in (sp.Integer(0), a * p ** 2 / 2 + b * q ** 3 + c * mu * p * q):
        # flow of (p, q) under T: qdot = T_p, pdot = -T_q (eq. K convention)
        qdot, pdot = sp.diff(T, p), -sp.diff(T, q)
        # total mu-derivative of the image along that flow
        dqt = sp.diff(Q_NEW, mu) + sp.diff(Q_NEW, p) * pdot + sp.diff(Q_NEW, q) * qdot
        dpt = sp.diff(P_NEW, mu) + sp.diff(P_NEW, p) * pdot + sp.diff(P_NEW, q) * qdot
        K = T.subs({p: P_OLD, q: Q_OLD}, simultaneous=True) + PHI_HAT
        on_map = {pt: P_NEW, qt: Q_NEW}
        results.append(decide(sp.Matrix([dqt, dpt]),
                              sp.Matrix([sp.diff(K, pt).subs(on_map), -sp.diff(K, qt).subs(on_map)])))
    bad = next((r for r in results if not r.holds), None)
    return from_decision(bad or results[-1], detail="T = 0 and T = a p^2/2 + b q^3 + c mu p q")
