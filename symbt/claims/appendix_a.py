"""Appendix A: the two-parameter Darboux matrix (eqs. ``d1``, ``v1``, ``hd``, ``v11``,
``tiltil``, ``D1D2``, ``Dapp``).  These are statements about 2x2 matrices with generic
entries, decided exactly."""
from __future__ import annotations

import sympy as sp

from ..proof import decide
from ..symbolic.darboux import (
    composed_darboux,
    darboux_composition,
    lam1,
    lam2,
    single_darboux,
    single_darboux_adjugate,
    zeta,
)
from ..symbolic.toda import lam
from .base import claim, from_decision, scene

scene("appendix-a", "Appendix A: adjugate, eigenvector quadratics, composition D^(lambda2) D(lambda1)")

a1, b1 = sp.symbols("alpha_1 beta_1")
A, B, C, D = sp.symbols("A B C D")          # entries of L(zeta)
At, Bt, Ct, Dt = sp.symbols("At Bt Ct Dt")  # entries of L~(zeta)
v, w = sp.symbols("v w")


@claim("d1", equation="d1", scene="appendix-a",
       statement="D(lambda) = d_1 has det D(zeta) = 0 with kernel |Omega> = (1, -beta_1)^T")
def d1():
    Dm = single_darboux(a1, b1)
    d = decide(Dm.subs(lam, zeta).det(), 0)
    if not d.holds:
        return from_decision(d)
    return from_decision(decide(Dm.subs(lam, zeta) * sp.Matrix([1, -b1]), sp.zeros(2, 1)))


@claim("v1", equation="v1", scene="appendix-a",
       statement="L(zeta)(1,-beta_1)^T = v (1,-beta_1)^T, i.e. A - beta_1 B = v, C - beta_1 D = -v beta_1; "
                 "eliminating v: beta_1^2 B - beta_1 (A - D) - C = 0")
def v1():
    L = sp.Matrix([[A, B], [C, D]])
    eig = L * sp.Matrix([1, -b1]) - v * sp.Matrix([1, -b1])
    vsol = sp.solve(eig[0], v)[0]
    d = decide(eig[1].subs(v, vsol), -(b1 ** 2 * B - b1 * (A - D) - C))
    if not d.holds:
        return from_decision(d)
    # conversely, at a root beta_1 of the quadratic both printed eigen-equations hold with v = A - beta_1 B
    quad = b1 ** 2 * B - b1 * (A - D) - C
    return from_decision(decide(sp.Matrix([A - b1 * B, C - b1 * D]), sp.Matrix([vsol, -vsol * b1]),
                                relations={b1: quad}),
                         detail="second eigen-equation with v eliminated is minus the printed quadratic; "
                                "conversely its roots satisfy both equations (remainder mod the quadratic)")


@claim("hd", equation="hd", scene="appendix-a",
       statement="the adjugate of D(lambda) is D^(lambda) = [[1, alpha_1],[-beta_1, lambda-zeta-alpha_1 beta_1]]")
def hd():
    Dm = single_darboux(a1, b1)
    d = decide(Dm.adjugate(), single_darboux_adjugate(a1, b1))
    if not d.holds:
        return from_decision(d)
    return from_decision(decide(Dm * Dm.adjugate(), (lam - zeta) * sp.eye(2)))


@claim("v11", equation="v11", scene="appendix-a",
       statement="L~(zeta)(alpha_1,-1)^T = w (alpha_1,-1)^T gives alpha_1^2 C~ + alpha_1 (A~ - D~) - B~ = 0; "
                 "with det L~ = 1, w v = 1 (i.e. (D~ - alpha_1 C~)(A~ + alpha_1 C~) = 1) is that same equation, "
                 "and the (1,1) entry of L D^ = D^ L~ gives A - beta_1 B = A~ + alpha_1 C~")
def v11():
    Lt = sp.Matrix([[At, Bt], [Ct, Dt]])
    eig = Lt * sp.Matrix([a1, -1]) - w * sp.Matrix([a1, -1])
    wsol = sp.solve(eig[1], w)[0]  # second row: C~ alpha - D~ = -w
    quad = a1 ** 2 * Ct + a1 * (At - Dt) - Bt
    d = decide(eig[0].subs(w, wsol), quad)
    if not d.holds:
        return from_decision(d)
    # w v = 1 with w = D~ - alpha C~, v = A~ + alpha C~ is -C~ * quad once det L~ = 1 (At Dt = Bt Ct + 1)
    prod = (Dt - a1 * Ct) * (At + a1 * Ct) - 1
    d2 = decide(prod, -Ct * quad, relations={Dt: At * Dt - Bt * Ct - 1})
    if not d2.holds:
        return from_decision(d2)
    L = sp.Matrix([[A, B], [C, D]])
    Dh = single_darboux_adjugate(a1, b1)
    R = L * Dh - Dh * Lt
    d3 = decide(R[0, 0], (A - b1 * B) - (At + a1 * Ct))
    return from_decision(d3, detail="w v - 1 = -C~ (printed quadratic) modulo det L~ = 1")


@claim("tiltil", equation="tiltil", scene="appendix-a",
       statement="L~ D(l1) = D(l1) L and L~~ D^(l2) = D^(l2) L~ imply L~~ D^(l2) D(l1) = D^(l2) D(l1) L")
def tiltil():
    L = sp.Matrix(2, 2, sp.symbols("L11 L12 L21 L22"))
    M1 = sp.Matrix(2, 2, sp.symbols("m11 m12 m21 m22"))
    M2 = sp.Matrix(2, 2, sp.symbols("n11 n12 n21 n22"))
    Lt = M1 * L * M1.inv()          # the unique L~ intertwined by M1 (M1 generic, invertible)
    Ltt = M2 * Lt * M2.inv()
    return from_decision(decide(Ltt * M2 * M1, M2 * M1 * L),
                         detail="generic invertible 2x2 matrices; rational identity")


x1, x2, y1, y2, x, y = sp.symbols("x_1 x_2 y_1 y_2 x y")


@claim("D1D2", equation="D1D2", scene="appendix-a",
       statement="with y_1 = y_2 = y the product D^(lambda,lambda2) D(lambda,lambda1) depends on x_1, x_2 "
                 "only through x = x_1 - x_2")
def D1D2():
    prod = darboux_composition(x1, x2, y, y)
    d = decide(prod.diff(x1) + prod.diff(x2), sp.zeros(2, 2))
    if not d.holds:
        return from_decision(d)
    # and it genuinely depends on y_1 != y_2 otherwise (the assumption y_1 = y_2 matters)
    dep = decide(darboux_composition(x1, x2, y1, y2).diff(x1) + darboux_composition(x1, x2, y1, y2).diff(x2),
                 sp.zeros(2, 2))
    return from_decision(d, detail=f"without y_1 = y_2 the dependence on x_1 - x_2 alone fails ({dep.verdict})")


@claim("Dapp", equation="Dapp", scene="appendix-a",
       statement="D^(lambda2) D(lambda1) = [[lambda-l1-xy, -x],[y(l1-l2+xy), lambda-l2+xy]], "
                 "det = (lambda-l1)(lambda-l2)")
def Dapp():
    prod = darboux_composition(x1, x2, y, y)
    printed = composed_darboux(x, y).subs(x, x1 - x2)
    d = decide(prod, printed)
    if not d.holds:
        return from_decision(d)
    return from_decision(decide(composed_darboux(x, y).det(), (lam - lam1) * (lam - lam2)))
