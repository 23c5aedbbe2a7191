r"""Appendix A: the two-parameter Darboux matrix (eqs. ``d1``, ``v1``, ``hd``, ``v11``, ``tiltil``,
``D1D2``, ``Dapp``).

Statements about 2x2 matrices with generic entries, decided exactly; since :math:`L(\lambda)` of every N
is a 2x2 matrix, they hold for every N (``n_scope = "all"``).  The mathematics:

* :math:`D = d_1` has :math:`\det D(\zeta) = 0`, kernel :math:`(1,-\beta_1)^T`, an eigenvector of
  :math:`L(\zeta)`: :math:`A-\beta_1B = v`, :math:`C-\beta_1D = -v\beta_1`; eliminating v leaves
  :math:`\beta_1^2B-\beta_1(A-D)-C = 0` (eq. ``v1``);
* the adjugate :math:`\hat D` (eq. ``hd``) with :math:`D\hat D = \hat D D = (\lambda-\zeta)\mathbb 1`; its kernel
  :math:`(\alpha_1,-1)^T` gives :math:`\alpha_1^2\tilde C+\alpha_1(\tilde A-\tilde D)-\tilde B=0`, which is
  :math:`wv = 1` once :math:`\det\tilde L = 1` (eq. ``v11``);
* composing (eq. ``tiltil``): :math:`\tilde L D_1 = D_1 L` and :math:`\tilde{\tilde L}\hat D_2 = \hat D_2\tilde L`
  give :math:`\tilde{\tilde L}\,\hat D_2 D_1 = \hat D_2 D_1\,L` -- the order of the factors matters;
* with :math:`y_1 = y_2 = y` the product depends on :math:`x = x_1-x_2` only and is eq. ``Dapp``.

Every printed matrix or equation is a :class:`~symbt.claims.base.Parts` entry read by its check.

>>> P = tiltil.parts()
>>> swapped = (P.context["D1"] * P.context["Dhat2"]).applyfunc(sp.expand)   # D(l1) D^(l2): wrong order
>>> tiltil.run_with(P.replace("printed", "composition", swapped)).status
'failed'
"""
from __future__ import annotations

import sympy as sp

from ..proof import decide
from ..symbolic.darboux import composed_darboux, lam1, lam2, single_darboux, single_darboux_adjugate, zeta
from ..symbolic.linear import solve_linear
from ..symbolic.toda import lam
from ._site import GENERIC_2X2, for_all_n, same_equation
from .base import Outcome, Parts, claim, from_decision, scene

scene("appendix-a", "Appendix A: adjugate, eigenvector quadratics, composition D^(lambda2) D(lambda1)")

a1, b1 = sp.symbols("alpha_1 beta_1")
A, B, C, D = sp.symbols("A B C D")          # entries of L(zeta)
At, Bt, Ct, Dt = sp.symbols("At Bt Ct Dt")  # entries of L~(zeta)
v, w = sp.symbols("v w")


def _first_failure(checks, final_detail: str) -> Outcome:
    for name, c in checks:
        if not c.holds:
            return for_all_n(from_decision(c, detail=name), GENERIC_2X2)
    return for_all_n(from_decision(checks[-1][1], detail=final_detail), GENERIC_2X2)


def _parts_d1() -> Parts:
    return Parts(printed={"D": single_darboux(a1, b1), "kernel": sp.Matrix([1, -b1])})


@claim("d1", equation="d1", scene="appendix-a", parts=_parts_d1,
       statement="D(lambda) = d_1 has det D(zeta) = 0 with kernel |Omega> = (1, -beta_1)^T")
def d1(parts: Parts):
    Dm, ker = parts.printed["D"], parts.printed["kernel"]
    if ker.is_zero_matrix:
        return for_all_n(Outcome("failed", "exact", evidence="proof", detail="zero kernel vector"), GENERIC_2X2)
    return _first_failure([("D = d_1 (eq. dj at j = 1)", decide(Dm, single_darboux(a1, b1))),
                           ("det D(zeta) = 0", decide(Dm.subs(lam, zeta).det(), 0)),
                           ("D(zeta) Omega = 0", decide(Dm.subs(lam, zeta) * ker, sp.zeros(2, 1)))],
                          "D = d_1, det D(zeta) = 0, D(zeta)(1,-beta_1)^T = 0")


def _parts_v1() -> Parts:
    return Parts(printed={"eig1": A - b1 * B - v, "eig2": C - b1 * D + v * b1,
                          "quad": b1 ** 2 * B - b1 * (A - D) - C},
                 context={"kernel": sp.Matrix([1, -b1])})


@claim("v1", equation="v1", scene="appendix-a", parts=_parts_v1,
       statement="L(zeta)(1,-beta_1)^T = v (1,-beta_1)^T, i.e. A - beta_1 B = v, C - beta_1 D = -v beta_1; "
                 "eliminating v: beta_1^2 B - beta_1 (A - D) - C = 0")
def v1(parts: Parts):
    P = parts.printed
    L = sp.Matrix([[A, B], [C, D]])
    Om = parts.context["kernel"]
    eig = decide(sp.Matrix([P["eig1"], P["eig2"]]), L * Om - v * Om)
    vsol = solve_linear(P["eig1"], v)
    if not eig.holds or len(vsol) != 1:
        return for_all_n(from_decision(eig, detail="the printed equations are not L(zeta) Omega = v Omega")
                         if not eig.holds else Outcome("failed", "exact: solve", evidence="proof",
                                                       detail=f"v from the first equation: {vsol}"), GENERIC_2X2)
    elim = P["eig2"].subs(v, vsol[0])
    # conversely, at a root beta_1 of the quadratic both eigen-equations hold with v from the first
    converse = decide(sp.Matrix([P["eig1"], P["eig2"]]).subs(v, vsol[0]), sp.zeros(2, 1),
                      relations={b1: P["quad"]})
    return _first_failure([("eigen-equations", eig),
                           ("eliminating v", same_equation(elim, P["quad"], unknowns=(b1,))),
                           ("converse", converse)],
                          "the printed equations are L(zeta)Omega = v Omega; with v eliminated the second is the "
                          "printed quadratic times a nonzero factor free of beta_1; conversely its roots satisfy both "
                          "(remainder mod the quadratic)")


def _parts_hd() -> Parts:
    return Parts(printed={"Dhat": single_darboux_adjugate(a1, b1)}, context={"D": single_darboux(a1, b1)})


@claim("hd", equation="hd", scene="appendix-a", parts=_parts_hd,
       statement="the adjugate of D(lambda) is D^(lambda) = [[1, alpha_1],[-beta_1, lambda-zeta-alpha_1 beta_1]]")
def hd(parts: Parts):
    Dm, Dh = parts.context["D"], parts.printed["Dhat"]
    return _first_failure([("D D^ = det D", decide(Dm * Dh, Dm.det() * sp.eye(2))),
                           ("D^ D = det D", decide(Dh * Dm, Dm.det() * sp.eye(2)))],
                          "D D^ = D^ D = det(D) 1 = (lambda - zeta) 1, so D^ = adj D")


def _parts_v11() -> Parts:
    return Parts(printed={"eig1": At * a1 - Bt - w * a1, "eig2": Ct * a1 - Dt + w,
                          "quad": a1 ** 2 * Ct + a1 * (At - Dt) - Bt,
                          "wv": (Dt - a1 * Ct) * (At + a1 * Ct) - 1,
                          "entry11": (A - b1 * B) - (At + a1 * Ct)},
                 context={"kernel": sp.Matrix([a1, -1])})


@claim("v11", equation="v11", scene="appendix-a", parts=_parts_v11,
       statement="L~(zeta)(alpha_1,-1)^T = w (alpha_1,-1)^T gives alpha_1^2 C~ + alpha_1 (A~ - D~) - B~ = 0; "
                 "with det L~ = 1, w v = 1 (i.e. (D~ - alpha_1 C~)(A~ + alpha_1 C~) = 1) is that same equation, "
                 "and the (1,1) entry of L D^ = D^ L~ gives A - beta_1 B = A~ + alpha_1 C~")
def v11(parts: Parts):
    P = parts.printed
    Lt = sp.Matrix([[At, Bt], [Ct, Dt]])
    Om = parts.context["kernel"]
    eig = decide(sp.Matrix([P["eig1"], P["eig2"]]), Lt * Om - w * Om)
    wsol = solve_linear(P["eig2"], w)
    if not eig.holds or len(wsol) != 1:
        return for_all_n(from_decision(eig, detail="the printed equations are not L~(zeta) Omega^ = w Omega^")
                         if not eig.holds else Outcome("failed", "exact: solve", evidence="proof",
                                                       detail=f"w from the second equation: {wsol}"), GENERIC_2X2)
    elim = P["eig1"].subs(w, wsol[0])
    # w v = 1 is the quadratic once det L~ = 1: B~ = (A~ D~ - 1)/C~; the factor between them is free of alpha_1
    unimodular = {Bt: (At * Dt - 1) / Ct}
    L = sp.Matrix([[A, B], [C, D]])
    Dh = single_darboux_adjugate(a1, b1)
    R = L * Dh - Dh * Lt
    checks = [("eigen-equations", eig), ("eliminating w", same_equation(elim, P["quad"], unknowns=(a1,))),
              ("w = D~ - alpha_1 C~, v = A~ + alpha_1 C~", decide(P["wv"], wsol[0] * (At + a1 * Ct) - 1)),
              ("w v = 1 is the quadratic", same_equation(P["wv"].subs(unimodular), P["quad"].subs(unimodular),
                                                          unknowns=(a1,))),
              ("(1,1) entry of L D^ - D^ L~", decide(R[0, 0], P["entry11"]))]
    return _first_failure(checks, "eigen-equations; w eliminated gives the quadratic; w v - 1 is the quadratic "
                                  "times -C~ once det L~ = 1; the (1,1) entry of L D^ = D^ L~")


# --------------------------------------------------------------------------- composition

x1, x2, y1, y2, x, y = sp.symbols("x_1 x_2 y_1 y_2 x y")
Lg = sp.Matrix(2, 2, sp.symbols("L11 L12 L21 L22"))


def _parts_tiltil() -> Parts:
    D1m = single_darboux(x1, y1, lam1)           # D(lambda, lambda1), eq. dj with zeta = lambda1
    Dh2 = single_darboux_adjugate(x2, y2, lam2)  # D^(lambda, lambda2), eq. hd with zeta = lambda2
    return Parts(printed={"composition": (Dh2 * D1m).applyfunc(sp.expand)}, context={"D1": D1m, "Dhat2": Dh2})


@claim("tiltil", equation="tiltil", scene="appendix-a", parts=_parts_tiltil,
       statement="L~ D(l1) = D(l1) L and L~~ D^(l2) = D^(l2) L~ imply L~~ D^(l2) D(l1) = D^(l2) D(l1) L")
def tiltil(parts: Parts):
    D1m, Dh2, M = parts.context["D1"], parts.context["Dhat2"], parts.printed["composition"]
    # the hypotheses fix L~ = D1 L D1^-1 and L~~ = D^2 L~ D^2^-1 (lambda != lambda1, lambda2); cleared of the
    # nonzero denominators det D1 det D^2 the conclusion is a polynomial identity in generic L, x_i, y_i
    lhs = Dh2 * D1m * Lg * D1m.adjugate() * Dh2.adjugate() * M
    rhs = D1m.det() * Dh2.det() * M * Lg
    diff = (lhs - rhs).applyfunc(sp.expand)
    nonzero = [e for e in diff if e != 0]
    # a polynomial that expands to 0 is 0 (proof); the first nonzero entry gets a numeric counterexample
    d = decide(diff, sp.zeros(2, 2)) if not nonzero else decide(nonzero[0], 0, exact=False)
    return for_all_n(from_decision(d, detail="generic L and the Darboux matrices of eqs. dj, hd (parameters "
                                             "x_i, y_i, lambda_i); L~, L~~ from the hypotheses; polynomial identity "
                                             "after clearing det D(l1) det D^(l2)"), GENERIC_2X2)


def _parts_D1D2() -> Parts:
    return Parts(printed={"Dhat2": sp.Matrix([[1, x2], [-y2, lam - lam2 - x2 * y2]]),
                          "D1": sp.Matrix([[lam - lam1 - x1 * y1, -x1], [y1, 1]])})


@claim("D1D2", equation="D1D2", scene="appendix-a", parts=_parts_D1D2,
       statement="with y_1 = y_2 = y the product D^(lambda,lambda2) D(lambda,lambda1) depends on x_1, x_2 "
                 "only through x = x_1 - x_2")
def D1D2(parts: Parts):
    Dh2, D1m = parts.printed["Dhat2"], parts.printed["D1"]
    prod = (Dh2 * D1m).subs({y1: y, y2: y}).applyfunc(sp.expand)
    general = (Dh2 * D1m).applyfunc(sp.expand)
    dep = decide(general.diff(x1) + general.diff(x2), sp.zeros(2, 2))
    return _first_failure(
        [("D(lambda, lambda1) is eq. dj with zeta = lambda1", decide(D1m, single_darboux(x1, y1, lam1))),
         ("D^(lambda, lambda2) is the adjugate of eq. dj at lambda2",
          decide(Dh2 * single_darboux(x2, y2, lam2), (lam - lam2) * sp.eye(2))),
         ("(d/dx_1 + d/dx_2) of the product", decide(prod.diff(x1) + prod.diff(x2), sp.zeros(2, 2)))],
        f"the printed factors are eqs. dj/hd; (d/dx_1 + d/dx_2) of the product vanishes at y_1 = y_2; without "
        f"y_1 = y_2 it does not ({dep.verdict})")


def _parts_Dapp() -> Parts:
    P = _parts_D1D2().printed
    return Parts(printed={"Dapp": composed_darboux(x, y), "det": (lam - lam1) * (lam - lam2)},
                 context={"product": (P["Dhat2"] * P["D1"]).subs({y1: y, y2: y}).applyfunc(sp.expand)})


@claim("Dapp", equation="Dapp", scene="appendix-a", parts=_parts_Dapp,
       statement="D^(lambda2) D(lambda1) = [[lambda-l1-xy, -x],[y(l1-l2+xy), lambda-l2+xy]], "
                 "det = (lambda-l1)(lambda-l2)")
def Dapp(parts: Parts):
    Dp, det = parts.printed["Dapp"], parts.printed["det"]
    return _first_failure([("product = Dapp at x = x_1 - x_2", decide(parts.context["product"], Dp.subs(x, x1 - x2))),
                           ("det", decide(Dp.det(), det))],
                          "the product of eq. D1D2 at y_1 = y_2 = y equals the printed matrix with x = x_1 - x_2; "
                          "its determinant is the printed one")
