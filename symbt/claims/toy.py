r"""Section 2's toy canonical transformation (unlabelled displays between eqs. ``hamil`` and ``ICI``).

The map :math:`\tilde p = p + \mu q,\ \tilde q = q + \mu p + \mu^2 q` (one degree of freedom) has

.. math:: F = -\frac{(\tilde q-q)^2 + q^2\mu^2}{2\mu},\qquad
          \frac{\partial F}{\partial\mu} = \frac{(\tilde q-q)^2 - q^2\mu^2}{2\mu^2},\qquad
          \hat\Phi = \frac{\tilde p^2-(\tilde q-\mu\tilde p)^2}{2},

the inverse :math:`p = \tilde p - \mu\tilde q + \mu^2\tilde p,\ q = \tilde q - \mu\tilde p`, and the transformed
Hamiltonian :math:`K = T(p(\tilde p,\tilde q), q(\tilde p,\tilde q), \mu) + \hat\Phi`.  Each printed formula is a
:class:`~symbt.claims.base.Parts` entry read by its check and decided exactly (rational functions).

>>> toy_dFdmu.run().status
'verified'
"""
from __future__ import annotations

from dataclasses import replace

import sympy as sp

from ..proof import decide
from .base import Parts, claim, from_decision, scene

scene("toy", "Section 2's toy canonical transformation: F, dF/dmu, Phi^, K")

p, q, pt, qt, mu = sp.symbols("p q pt qt mu", real=True)
WHERE = "Section 2, displays after eq. hamil"
ONE_DOF = "one degree of freedom (N = 1)"

# the map itself (the hypothesis, not a checked statement)
P_NEW = p + mu * q
Q_NEW = q + mu * p + mu ** 2 * q
F = -((qt - q) ** 2 + q ** 2 * mu ** 2) / (2 * mu)
DFDMU = ((qt - q) ** 2 - q ** 2 * mu ** 2) / (2 * mu ** 2)
# inverse map, as printed in K: p = p~ - mu q~ + mu^2 p~, q = q~ - mu p~
P_OLD = pt - mu * qt + mu ** 2 * pt
Q_OLD = qt - mu * pt
PHI_HAT = (pt ** 2 - (qt - mu * pt) ** 2) / 2


def _one_dof(out):
    out = replace(out, n_scope=[1])
    out = replace(out, detail=(out.detail + f" [{ONE_DOF}]").strip())
    return out


def _parts_F() -> Parts:
    return Parts(printed={"F": F}, context={"map": (P_NEW, Q_NEW)})


@claim("toy.F", equation="toy-F", scene="toy", where=WHERE, parts=_parts_F,
       statement="F = -((q~-q)^2 + q^2 mu^2)/(2 mu) generates the map: p = dF/dq, p~ = -dF/dq~ at q~ = q~(p,q)")
def toy_F(parts: Parts):
    Fp = parts.printed["F"]
    on_map = {qt: Q_NEW}
    return _one_dof(from_decision(decide(sp.Matrix([sp.diff(Fp, q).subs(on_map), -sp.diff(Fp, qt).subs(on_map)]),
                                         sp.Matrix([p, P_NEW])),
                                  detail="both derivatives of the printed F on the map"))


def _parts_dFdmu() -> Parts:
    return Parts(printed={"dFdmu": DFDMU}, context={"F": F})


@claim("toy.dFdmu", equation="toy-dFdmu", scene="toy", where=WHERE, parts=_parts_dFdmu,
       statement="dF/dmu = ((q~-q)^2 - q^2 mu^2)/(2 mu^2) at fixed q, q~")
def toy_dFdmu(parts: Parts):
    return _one_dof(from_decision(decide(sp.diff(parts.context["F"], mu), parts.printed["dFdmu"]),
                                  detail="mu-derivative of the printed F at fixed q, q~"))


def _parts_Phihat() -> Parts:
    return Parts(printed={"Phihat": PHI_HAT, "q_inv": Q_OLD}, context={"F": F, "p_inv": P_OLD})


@claim("toy.Phihat", equation="toy-Phihat", scene="toy", where=WHERE, parts=_parts_Phihat,
       statement="Phi^(p~,q~,mu) = dF/dmu at q = q(p~,q~,mu) = (p~^2 - (q~ - mu p~)^2)/2, and Phi^ != Phi "
                 "as functions")
def toy_Phihat(parts: Parts):
    Phihat, q_inv, p_inv = parts.printed["Phihat"], parts.printed["q_inv"], parts.context["p_inv"]
    inverse_ok = decide(sp.Matrix([P_NEW, Q_NEW]).subs({p: p_inv, q: q_inv}, simultaneous=True),
                        sp.Matrix([pt, qt]))
    if not inverse_ok.holds:
        return _one_dof(from_decision(inverse_ok, detail="printed inverse map q = q~ - mu p~"))
    dF = sp.diff(parts.context["F"], mu)
    d = decide(dF.subs(q, q_inv), Phihat)
    phi = dF.subs(qt, Q_NEW)  # Phi(p, q, mu)
    differ = decide(phi.subs({p: pt, q: qt}, simultaneous=True), Phihat)
    out = from_decision(d, detail=f"Phi(a,b) vs Phi^(a,b) as functions: {differ.verdict} (paper: they differ)")
    if differ.holds:
        out = replace(out, status="failed")
    return _one_dof(out)


def _parts_K() -> Parts:
    return Parts(printed={"p_inv": P_OLD, "q_inv": Q_OLD, "Phihat": PHI_HAT})


@claim("toy.K", equation="toy-K", scene="toy", where=WHERE, parts=_parts_K,
       statement="if (p, q) follow the Hamiltonian T(p,q,mu), (p~, q~) follow K = T(p~ - mu q~ + mu^2 p~, "
                 "q~ - mu p~, mu) + (p~^2 - (q~ - mu p~)^2)/2 (checked for T = 0 and a generic polynomial T)")
def toy_K(parts: Parts):
    a, b, c = sp.symbols("a b c", real=True)
    P_inv, Q_inv, Phihat = parts.printed["p_inv"], parts.printed["q_inv"], parts.printed["Phihat"]
    results = []
    for T in (sp.Integer(0), a * p ** 2 / 2 + b * q ** 3 + c * mu * p * q):
        # flow of (p, q) under T: qdot = T_p, pdot = -T_q (eq. K convention)
        qdot, pdot = sp.diff(T, p), -sp.diff(T, q)
        # total mu-derivative of the image along that flow
        dqt = sp.diff(Q_NEW, mu) + sp.diff(Q_NEW, p) * pdot + sp.diff(Q_NEW, q) * qdot
        dpt = sp.diff(P_NEW, mu) + sp.diff(P_NEW, p) * pdot + sp.diff(P_NEW, q) * qdot
        K = T.subs({p: P_inv, q: Q_inv}, simultaneous=True) + Phihat
        on_map = {pt: P_NEW, qt: Q_NEW}
        results.append(decide(sp.Matrix([dqt, dpt]),
                              sp.Matrix([sp.diff(K, pt).subs(on_map), -sp.diff(K, qt).subs(on_map)])))
    bad = next((r for r in results if not r.holds), None)
    return _one_dof(from_decision(bad or results[-1], detail="T = 0 and T = a p^2/2 + b q^3 + c mu p q"))
