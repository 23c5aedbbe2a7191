r"""Phi = dF/dmu on the map: eq. ``newkmu`` and Appendix B (eqs. ``rte``, ``2122``, ``spec``).

What holds (both branches b = +-1, both signs of tr L, every sampled cell):

.. math:: \prod_k \frac{\eta_k+\mu}{\eta_k-\mu} = \frac{\operatorname{tr}_1-\gamma_1}{2}\cdot
          \frac{\operatorname{tr}_2-\gamma_2}{2},\qquad \gamma_i = b\sqrt{\operatorname{tr}_i^2-4},

so the *real* Phi, :math:`\Phi = \sum_k \ln|(\eta_k+\mu)/(\eta_k-\mu)|`, is

.. math:: \Phi = -b\,\big(\operatorname{sgn}(\operatorname{tr}_1)\,\operatorname{arccosh}(|\operatorname{tr}_1|/2)
          + \operatorname{sgn}(\operatorname{tr}_2)\,\operatorname{arccosh}(|\operatorname{tr}_2|/2)\big).

Where the printed eq. ``newkmu`` and the logarithmic form of eq. ``spec`` hold is generated from
the cell tables (printed statements are compared with principal branches, see
:mod:`symbt.claims._common`).
"""
from __future__ import annotations

from dataclasses import replace
from functools import cache

import mpmath as mp
import sympy as sp

from ..proof import decide
from ..proof.cells import CellTable
from ..reference.literal import phi_from_traces
from ..symbolic.darboux import lam0, mu
from ..symbolic.toda import lam, local_lax
from ._common import DPS, TOL, eta_from_states, fmt_state, judge_cells, lambdified, literal_image, map_cells, per_cell
from .base import Parts, claim, judge, scene

scene("phi", "Phi = dF/dmu on the map: spectrality, Appendix B, the real branch of arccosh (N=2,3)")

p = sp.Symbol("p_j", real=True)
E, Et, En, Etn = sp.symbols("E_j Et_j E_jp1 Et_jp1", positive=True)
eta_j, eta_n = sp.symbols("eta_j eta_jp1", real=True)
tr1, tr2, branch = sp.symbols("tr1 tr2 branch", real=True)
GAMMA1 = branch * sp.sqrt(tr1 ** 2 - 4)
GAMMA2 = branch * sp.sqrt(tr2 ** 2 - 4)


LOCAL = ("Holds for every N: a per-site identity of the local relation (eq. nlocal), and the composed map is "
         "the product of the local factors around the ring.")


def _site():
    x_j, x_n = E - Et, En - Etn
    w_n = x_n * (1 / Et - 1 / E)
    p_pr = -lam0 - (Et * eta_n + E * eta_j) / (E - Et)  # eq. imptransf
    return x_j, x_n, p_pr, {eta_n: eta_n ** 2 - mu ** 2 - w_n}


# --------------------------------------------------------------------------- eq. 2122

def _parts_2122() -> Parts:
    return Parts(printed={"rhs": E * (lam - lam0 - eta_j) + Et * (lam - lam0 + eta_n)},
                 corrected={"rhs": E * (lam - lam0 - eta_j) - Et * (lam - lam0 + eta_n)})


@claim("2122", equation="2122", scene="phi", parts=_parts_2122,
       statement="combining the (2,1), (2,2) entries of eq. nlocal: (p_j + lambda) x_j = e^{q_j}(lambda - l0 - eta_j) "
                 "+ e^{q~_j}(lambda - l0 + eta_{j+1}) (local, all N)")
def eq_2122(parts: Parts):
    x_j, _, p_pr, _ = _site()
    lhs = (p_pr + lam) * x_j
    out = judge(decide(lhs, parts.printed["rhs"]),
                printed="(p_j + lambda) x_j = e^{q_j}(lambda - l0 - eta_j) + e^{q~_j}(lambda - l0 + eta_{j+1})",
                corrected="(p_j + lambda) x_j = e^{q_j}(lambda - l0 - eta_j) - e^{q~_j}(lambda - l0 + eta_{j+1})",
                corrected_check=lambda: decide(lhs, parts.corrected["rhs"]),
                detail="p_j of eq. imptransf substituted; the printed sign of the e^{q~_j} term leaves "
                       "-2 lambda e^{q~_j} + ... (not even the lambda-dependence matches). " + LOCAL)
    out = replace(out, n_scope="all")
    return out


# --------------------------------------------------------------------------- eq. rte

def _parts_rte() -> Parts:
    x_n = En - Etn
    return Parts(printed={"nu1": Et * (mu + eta_n) / x_n, "nu2": Et * (eta_n - mu) / x_n},
                 corrected={"nu1": -Et * (mu + eta_n) / x_n, "nu2": -Et * (eta_n - mu) / x_n})


@claim("rte", equation="rte", scene="phi", parts=_parts_rte, uses=("2122",),
       statement="l_j(l1) (x_j, mu - eta_j) = nu^1_{j+1} (x_{j+1}, mu - eta_{j+1}) with nu^1_{j+1} = e^{q~_j}(mu + "
                 "eta_{j+1})/x_{j+1}, and l_j(l2)(-x_j, mu + eta_j) = nu^2_{j+1}(-x_{j+1}, mu + eta_{j+1}) with "
                 "nu^2_{j+1} = e^{q~_j}(eta_{j+1} - mu)/x_{j+1} (local, all N)")
def rte(parts: Parts):
    x_j, x_n, p_pr, rel = _site()
    lhs1 = local_lax(lam0 + mu, p_pr, E) * sp.Matrix([x_j, mu - eta_j])
    lhs2 = local_lax(lam0 - mu, p_pr, E) * sp.Matrix([-x_j, mu + eta_j])

    def check(nu: dict):
        rhs1 = nu["nu1"] * sp.Matrix([x_n, mu - eta_n])
        rhs2 = nu["nu2"] * sp.Matrix([-x_n, mu + eta_n])
        return decide(sp.Matrix([lhs1, lhs2]), sp.Matrix([rhs1, rhs2]), relations=rel)

    out = judge(check(parts.printed),
                printed="nu^1_{j+1} = e^{q~_j}(mu + eta_{j+1})/x_{j+1}, nu^2_{j+1} = e^{q~_j}(eta_{j+1} - mu)/x_{j+1}",
                corrected="nu^1_{j+1} = -e^{q~_j}(mu + eta_{j+1})/x_{j+1}, nu^2_{j+1} = -e^{q~_j}(eta_{j+1} - mu)"
                          "/x_{j+1} (both signs flip, so nu^1/nu^2 = (mu+eta)/(eta-mu) and eq. spec are unaffected)",
                corrected_check=lambda: check(parts.corrected),
                detail="the kernel vectors (x_j, mu-eta_j), (-x_j, mu+eta_j) are transported as printed; "
                       "both components at l1 and l2, modulo eta_{j+1}^2 = mu^2 + w_{j+1} (either sign of eta); "
                       "the sign slip follows from the one in eq. 2122. " + LOCAL)
    out = replace(out, n_scope="all")
    return out


# --------------------------------------------------------------------------- sampled on the map

@cache
def _on_map(N: int, count: int) -> tuple:
    """Per sample: cell, state, branch, the ratios (eta_k+mu)/(eta_k-mu) (eta from the image alone,
    eq. imptransf) and the traces tr L(lambda_1), tr L(lambda_2), at DPS digits."""
    out = []
    with mp.workdps(DPS):
        for cell, state, b in map_cells(N, count):
            pv, qv, l0, m = state
            pt, qt, info = literal_image(state, b)
            ratios = [(e + m) / (e - m) for e in eta_from_states(pv, qv, pt, qt, l0)]
            out.append((cell, state, b, tuple(ratios), mp.re(info["tr1"]), mp.re(info["tr2"])))
    return tuple(out)


def _parts_spec(N: int) -> Parts:
    return Parts(printed={"rhs": sp.log((tr1 - GAMMA1) / 2) + sp.log((tr2 - GAMMA2) / 2)},
                 corrected={"rhs": (tr1 - GAMMA1) / 2 * ((tr2 - GAMMA2) / 2)})


@claim("spec", equation="spec", scene="phi", sizes=(2, 3), parts=_parts_spec, uses=("rte",),
       statement="Phi = ln(prod nu^1 / prod nu^2) = ln v(l1) + ln v(l2) = ln((tr1 - gamma1)/2) + "
                 "ln((tr2 - gamma2)/2) on the map, gamma_i = b sqrt(tr_i^2 - 4) (N={N})")
def spec(N: int, parts: Parts, deep: bool = False):
    f_pr = lambdified((tr1, tr2, branch), parts.printed["rhs"])
    f_co = lambdified((tr1, tr2, branch), parts.corrected["rhs"])
    table = CellTable(tol=float(TOL))
    with mp.workdps(DPS):
        for cell, state, b, ratios, t1, t2 in _on_map(N, per_cell(deep)):
            lhs_log = mp.fsum(mp.log(x) for x in ratios)      # principal logarithms, as printed
            rhs_log = f_pr(t1, t2, b)
            lhs_prod, rhs_prod = mp.fprod(ratios), f_co(t1, t2, b)
            table.add(cell, printed=abs(lhs_log - rhs_log) / max(1, abs(rhs_log)),
                      corrected=abs(lhs_prod - rhs_prod) / max(mp.mpf(10) ** -30, abs(rhs_prod)),
                      point=fmt_state(state, b, tr1=t1, tr2=t2))
    return judge_cells(table, method=f"numeric: mpmath {DPS} digits on the map (principal logarithms)",
                       printed="sum_k ln((eta_k+mu)/(eta_k-mu)) = ln((tr1-gamma1)/2) + ln((tr2-gamma2)/2) "
                               "(principal logarithms)",
                       corrected="prod_k (eta_k+mu)/(eta_k-mu) = ((tr1-gamma1)/2)((tr2-gamma2)/2) with "
                                 "gamma_i = b sqrt(tr_i^2-4): the logarithmic form holds modulo 2 pi i "
                                 "(real parts: Phi = ln|...|)")


def _parts_newkmu(N: int) -> Parts:
    return Parts(printed={"Phi": -sp.acosh(tr1 / 2) - sp.acosh(tr2 / 2)},
                 corrected={"Phi": phi_from_traces(tr1, tr2, branch, ns=sp)})   # the library's real Phi


@claim("newkmu", equation="newkmu", scene="phi", sizes=(2, 3), parts=_parts_newkmu,
       statement="Phi = dF/dmu on the map = -arccosh(tr L(l1)/2) - arccosh(tr L(l2)/2) (N={N})")
def newkmu(N: int, parts: Parts, deep: bool = False):
    f_pr = lambdified((tr1, tr2, branch), parts.printed["Phi"])
    f_co = lambdified((tr1, tr2, branch), parts.corrected["Phi"])
    table = CellTable(tol=float(TOL))
    with mp.workdps(DPS):
        for cell, state, b, ratios, t1, t2 in _on_map(N, per_cell(deep)):
            # Phi = dF/dmu (eq. vqqtmu) on the map, as printed (principal logs) and as the real function
            phi_c = mp.fsum(mp.log(x) for x in ratios)
            phi_r = mp.fsum(mp.log(abs(x)) for x in ratios)
            printed = f_pr(t1, t2, b)
            table.add(cell, printed=abs(phi_c - printed) / max(1, abs(printed)),
                      corrected=abs(phi_r - f_co(t1, t2, b)) / max(1, abs(phi_r)),
                      point=fmt_state(state, b, tr1=t1, tr2=t2, Phi=phi_c, printed=printed))
    return judge_cells(table, method=f"numeric: mpmath {DPS} digits on the map",
                       printed="Phi = -arccosh(tr L(l1)/2) - arccosh(tr L(l2)/2)",
                       corrected="real Phi = sum_k ln|(eta_k+mu)/(eta_k-mu)| = -b (sgn(tr1) arccosh(|tr1|/2) "
                                 "+ sgn(tr2) arccosh(|tr2|/2))")
