r"""Generating function of the composed map: eqs. ``daj``, ``xyqqt``, ``imptransf``, ``newgf``, ``vqqtmu``.

One site of the local relation (eq. ``nlocal``),
:math:`l_j(\tilde p,\tilde q)\,\mathfrak d_j = \mathfrak d_{j+1}\,l_j(p,q)` with
:math:`\mathfrak d_j = \begin{pmatrix}\lambda-\lambda_1-x_jy_j & -x_j\\ y_j(\lambda_1-\lambda_2+x_jy_j) &
\lambda-\lambda_2+x_jy_j\end{pmatrix}`, :math:`\lambda_{1,2} = \lambda_0\pm\mu`, gives

* ``daj``: :math:`\det\mathfrak d_j = (\lambda-\lambda_1)(\lambda-\lambda_2)`, kernels :math:`(x_j,\mu-\eta_j)` at
  :math:`\lambda_1` and :math:`(-x_j,\mu+\eta_j)` at :math:`\lambda_2`, :math:`\eta_j = x_jy_j+\mu`;
* ``xyqqt``: :math:`x_j = e^{q_j}-e^{\tilde q_j}`, :math:`y_{j+1}(2\mu+x_{j+1}y_{j+1}) = e^{-\tilde q_j}-e^{-q_j}`,
  hence :math:`\eta_j^2 = \mu^2 + w_j`;
* ``imptransf``: :math:`\tilde p_j = -\lambda_0-(e^{\tilde q_j}\eta_j+e^{q_j}\eta_{j+1})/(e^{q_j}-e^{\tilde q_j})`,
  :math:`p_j = -\lambda_0-(e^{\tilde q_j}\eta_{j+1}+e^{q_j}\eta_j)/(e^{q_j}-e^{\tilde q_j})`.

These are per-site identities, proved for a generic site, hence for every N (``n_scope = "all"``).
``newgf`` (:math:`F = \sum_k f(\eta_k, q_k, \tilde q_k)`, :math:`p_j = \partial F/\partial q_j`,
:math:`\tilde p_j = -\partial F/\partial\tilde q_j`) and ``vqqtmu``
(:math:`\partial F/\partial\mu = \sum_k\ln\frac{\eta_k+\mu}{\eta_k-\mu}`) are proved for each N = 2, 3, 4 (N = 5
under ``--deep``) by implicit differentiation, :math:`\partial\eta_k = \partial w_k/(2\eta_k)`,
:math:`\partial_\mu\eta_k = \mu/\eta_k`, modulo every :math:`\eta_k^2 = \mu^2+w_k` (either sign of each
:math:`\eta_k`); for ``newgf`` the two entries of site 1 are decided and the other sites follow by the cyclic
relabelling :math:`k\to k+1`, which the check verifies maps F, the relations and eq. ``imptransf`` to themselves.
The map-sampled claims ``nlocal`` and ``GF`` are in :mod:`symbt.claims.generating_map`.

>>> out = imptransf.run()
>>> out.status, out.evidence, out.n_scope
('verified', 'proof', 'all')
"""
from __future__ import annotations

from dataclasses import replace

import sympy as sp

from ..proof import Verdict, decide
from ..symbolic.darboux import composed_darboux, lam0, lam1, lam2, local_relation_residual, mu
from ..symbolic.generating import generating_function
from ..symbolic.linear import solve_linear
from ..symbolic.toda import lam
from ._site import PER_SITE, for_all_n, same_equation, to_E
from .base import Outcome, Parts, claim, from_decision, scene

scene("generating", "generating function F of the composed map, its mu-derivative (local identities; N=2,3,4)")

# one generic site j and its right neighbour
p, pt = sp.symbols("p_j pt_j", real=True)
q, qt, qn, qtn = sp.symbols("q_j qt_j q_jp1 qt_jp1", real=True)
E, Et, En, Etn = sp.symbols("E_j Et_j E_jp1 Et_jp1", positive=True)
EXP = {q: E, qt: Et, qn: En, qtn: Etn}
xj, yj, xn, yn = sp.symbols("x_j y_j x_jp1 y_jp1")
eta_j, eta_n = sp.symbols("eta_j eta_jp1", real=True)
L1, L2 = lam0 + mu, lam0 - mu
LAM0MU = {lam1: L1, lam2: L2}
DEFAULT, DEEP = (2, 3, 4), (5,)


def _site_residual():
    return local_relation_residual(composed_darboux(xj, yj, L1, L2), composed_darboux(xn, yn, L1, L2),
                                   p, E, pt, Et)


def _first_failure(checks, final_detail: str) -> Outcome:
    for name, c in checks:
        if not c.holds:
            return for_all_n(from_decision(c, detail=name), PER_SITE)
    return for_all_n(from_decision(checks[-1][1], detail=final_detail), PER_SITE)


# --------------------------------------------------------------------------- eq. daj

def _parts_daj() -> Parts:
    return Parts(printed={"d": composed_darboux(xj, yj), "eta": xj * yj + mu, "det": (lam - lam1) * (lam - lam2),
                          "ker1": sp.Matrix([xj, mu - eta_j]), "ker2": sp.Matrix([-xj, mu + eta_j])})


@claim("daj", equation="daj", scene="generating", parts=_parts_daj,
       statement="the local factors d_j = [[l-l1-x_j y_j, -x_j],[y_j(l1-l2+x_j y_j), l-l2+x_j y_j]] have "
                 "det = (l-l1)(l-l2), kernels (x_j, mu-eta_j) at l1 and (-x_j, mu+eta_j) at l2 "
                 "(eta_j = x_j y_j + mu, l1,2 = l0 +- mu), and d_1 = D (local, all N)")
def daj(parts: Parts):
    P = parts.printed
    d, eta = P["d"], P["eta"]
    kers = [(P[name].subs(eta_j, eta), at) for name, at in (("ker1", lam1), ("ker2", lam2))]
    if any(k.is_zero_matrix for k, _ in kers):
        return for_all_n(Outcome("failed", "exact", evidence="proof", detail="a kernel vector vanishes"), PER_SITE)
    x, y = sp.symbols("x y")
    return _first_failure(
        [("det", decide(d.det(), P["det"])),
         *((f"kernel at {at}", decide((d.subs(lam, at) * k).subs(LAM0MU), sp.zeros(2, 1))) for k, at in kers),
         ("d_1 = D (eq. D)", decide(d.subs({xj: x, yj: y}, simultaneous=True), composed_darboux(x, y)))],
        "det, both kernels (with l1,2 = l0 +- mu), d_1 = D")


# --------------------------------------------------------------------------- eq. xyqqt

def _parts_xyqqt() -> Parts:
    return Parts(printed={"x": sp.exp(q) - sp.exp(qt),
                          "y_eq": yn * (2 * mu + xn * yn) - (sp.exp(-qt) - sp.exp(-q)),
                          "w": (sp.exp(qn) - sp.exp(qtn)) * (sp.exp(-qt) - sp.exp(-q))})


@claim("xyqqt", equation="xyqqt", scene="generating", parts=_parts_xyqqt,
       statement="the off-diagonal entries of eq. nlocal give x_j = e^{q_j} - e^{q~_j} and "
                 "y_{j+1}(2mu + x_{j+1} y_{j+1}) = e^{-q~_j} - e^{-q_j}; hence eta_j^2 = mu^2 + w_j "
                 "with w_{j+1} = (e^{q_{j+1}} - e^{q~_{j+1}})(e^{-q~_j} - e^{-q_j}) (local, all N)")
def xyqqt(parts: Parts):
    P = {k: to_E(v, EXP) for k, v in parts.printed.items()}
    R = _site_residual()
    c01 = sp.Poly(R[0, 1], lam).coeff_monomial(lam)
    c10 = sp.Poly(R[1, 0], lam).coeff_monomial(lam)
    xsol = solve_linear(c01, xj)
    if len(xsol) != 1:
        return for_all_n(Outcome("failed", "exact: solve", evidence="proof", detail=f"x_j: {xsol}"), PER_SITE)
    # eta^2 = mu^2 + w at site j+1: x_{j+1} is the printed x shifted, y_{j+1} a root of the printed y-equation
    x_next = P["x"].subs({E: En, Et: Etn}, simultaneous=True)
    y_rel = P["y_eq"].subs(xn, x_next)
    if sp.degree(y_rel, yn) >= 1:
        # remainder by polynomial division in y_{j+1} (coefficients as expressions), then decided
        eta2 = decide(sp.rem(sp.expand((x_next * yn + mu) ** 2 - mu ** 2 - P["w"]), sp.expand(y_rel), yn,
                             domain=sp.EX), 0)
    else:
        eta2 = Verdict(False, "proof", "exact: the y-equation does not involve y_{j+1}", residual=1.0, definite=True)
    return _first_failure([("x_j", decide(xsol[0], P["x"])),
                           ("y_{j+1}", same_equation(c10, P["y_eq"], unknowns=(xn, yn))),
                           ("eta^2 = mu^2 + w", eta2)],
                          "lambda^1 coefficients of the (1,2) and (2,1) entries; eta^2 - mu^2 - w has remainder 0 "
                          "modulo the y-equation (polynomial division in y_{j+1})")


# --------------------------------------------------------------------------- eq. imptransf

def _parts_imptransf() -> Parts:
    e, et = sp.exp(q), sp.exp(qt)
    return Parts(printed={"pt": -lam0 - (et * eta_j + e * eta_n) / (e - et),
                          "p": -lam0 - (et * eta_n + e * eta_j) / (e - et)})


@claim("imptransf", equation="imptransf", scene="generating", parts=_parts_imptransf,
       statement="with eq. xyqqt, the remaining entries of eq. nlocal give p~_j = -l0 - (e^{q~_j} eta_j + "
                 "e^{q_j} eta_{j+1})/(e^{q_j} - e^{q~_j}), p_j = -l0 - (e^{q~_j} eta_{j+1} + e^{q_j} eta_j)/"
                 "(e^{q_j} - e^{q~_j}) (local, all N, either sign of eta)")
def imptransf(parts: Parts):
    x_n = En - Etn
    xy = {xj: E - Et, yj: (eta_j - mu) / (E - Et), xn: x_n, yn: (eta_n - mu) / x_n}   # eq. xyqqt, eta = x y + mu
    R = _site_residual().subs(xy).subs({pt: to_E(parts.printed["pt"], EXP), p: to_E(parts.printed["p"], EXP)})
    w_n = x_n * (1 / Et - 1 / E)
    d = decide(R, sp.zeros(2, 2), relations={eta_n: eta_n ** 2 - mu ** 2 - w_n})
    return for_all_n(from_decision(d, detail="all four entries of the local relation vanish modulo "
                                             "eta_{j+1}^2 = mu^2 + w_{j+1}"), PER_SITE)


# --------------------------------------------------------------------------- eqs. newgf, vqqtmu (per N)

eta_k, q_k, qt_k = sp.symbols("eta_k q_k qt_k", real=True)
F_SUMMAND = mu * sp.log((eta_k + mu) / (eta_k - mu)) - 2 * eta_k - lam0 * (q_k - qt_k)


def _at_sites(g, expr):
    """``expr`` at every site k: eta_k -> eta_k of the lattice, q_k = ln E_k, q~_k = ln E~_k."""
    return [expr.xreplace({eta_k: g.eta[k], q_k: sp.log(g.E[k]), qt_k: sp.log(g.Et[k])}) for k in range(g.N)]


def _sized(out: Outcome, N: int) -> Outcome:
    out = replace(out, n_scope=[N])
    return out


def _parts_newgf(N: int) -> Parts:
    return Parts(printed={"summand": F_SUMMAND})


NEWGF = ("F = sum_k (mu ln((eta_k+mu)/(eta_k-mu)) - 2 eta_k - l0 (q_k - q~_k)) satisfies p_j = dF/dq_j and "
         "p~_j = -dF/dq~_j with p, p~ of eq. imptransf (N={N})")


@claim("newgf", equation="newgf", scene="generating", sizes=DEEP, deep=True, parts=_parts_newgf, statement=NEWGF)
@claim("newgf", equation="newgf", scene="generating", sizes=DEFAULT, parts=_parts_newgf, statement=NEWGF)
def newgf(N: int, parts: Parts):
    g = generating_function(N)
    pp, ppt = g.momenta_printed()
    F = sp.Add(*_at_sites(g, parts.printed["summand"]))
    # the cyclic relabelling k -> k+1 (mod N) maps F, the relations and eq. imptransf to themselves (checked
    # here), and d/dq_j to d/dq_{j+1}; so the entries of site 1 decide those of every site
    shift = {s[k]: s[(k + 1) % N] for s in (g.E, g.Et, g.eta) for k in range(N)}
    cyclic = [("F", F.xreplace(shift), F)]
    cyclic += [(f"eta_{k + 1}^2 = mu^2 + w_{k + 1}", sp.expand(g.relations[g.eta[k]].xreplace(shift)),
                g.relations[g.eta[(k + 1) % N]]) for k in range(N)]
    cyclic += [(f"eq. imptransf at site {k + 1}", m[k].xreplace(shift), m[(k + 1) % N]) for m in (pp, ppt)
               for k in range(N)]
    for name, a, b in cyclic:
        if a != b and not decide(a, b).holds:
            return _sized(Outcome("failed", "exact: cyclic relabelling", evidence="proof",
                                  detail=f"{name} is not mapped to its neighbour's"), N)
    # the one implementation of the implicit derivative (symbt.symbolic.generating.implicit_derivative)
    checks = [("p_1 = dF/dq_1", g.E[0] * g.total_derivative(F, g.E[0]), pp[0]),
              ("p~_1 = -dF/dq~_1", -g.Et[0] * g.total_derivative(F, g.Et[0]), ppt[0])]
    for name, a, b in checks:
        # modulo the relations of the eta_k the entry involves (eta_1, eta_2)
        rel = {e: r for e, r in g.relations.items() if a.has(e) or b.has(e)}
        d = decide(a, b, relations=rel)
        if not d.holds:
            return _sized(from_decision(d, detail=name), N)
    return _sized(from_decision(d, detail="p_1 = dF/dq_1, p~_1 = -dF/dq~_1 by implicit differentiation of eta_k, "
                                          "reduced modulo the eta_k^2 = mu^2 + w_k involved (either sign of each "
                                          "eta_k; the log branch only adds constants); the other sites by the "
                                          "cyclic relabelling k -> k+1, checked to map F, the relations and eq. "
                                          "imptransf to themselves"), N)


def _parts_vqqtmu(N: int) -> Parts:
    return Parts(printed={"summand": sp.log((eta_k + mu) / (eta_k - mu))}, context={"F_summand": F_SUMMAND})


VQQTMU = "dF/dmu at fixed q, q~ = sum_k ln((eta_k+mu)/(eta_k-mu)) (N={N})"


@claim("vqqtmu", equation="vqqtmu", scene="generating", sizes=DEEP, deep=True, parts=_parts_vqqtmu, statement=VQQTMU)
@claim("vqqtmu", equation="vqqtmu", scene="generating", sizes=DEFAULT, parts=_parts_vqqtmu, statement=VQQTMU)
def vqqtmu(N: int, parts: Parts):
    g = generating_function(N)
    dF = g.total_derivative(sp.Add(*_at_sites(g, parts.context["F_summand"])), g.mu)
    printed = sp.Add(*_at_sites(g, parts.printed["summand"]))
    return _sized(from_decision(decide(dF, printed, relations=g.relations),
                                detail="d eta_k/d mu = mu/eta_k at fixed q, q~; the log terms cancel structurally"), N)
