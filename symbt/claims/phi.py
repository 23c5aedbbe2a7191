r"""Phi = dF/dmu on the map: eq. ``newkmu`` and Appendix B (eqs. ``rte``, ``2122``, ``spec``).

What holds (both branches b = +-1, both signs of tr L, checked at 60 digits):

.. math:: \prod_k \frac{\eta_k+\mu}{\eta_k-\mu} = \frac{\operatorname{tr}_1-\gamma_1}{2}\cdot
          \frac{\operatorname{tr}_2-\gamma_2}{2},\qquad \gamma_i = b\sqrt{\operatorname{tr}_i^2-4},

so the *real* Phi, :math:`\Phi = \sum_k \ln|(\eta_k+\mu)/(\eta_k-\mu)|`, is

.. math:: \Phi = -b\,\big(\operatorname{sgn}(\operatorname{tr}_1)\,\operatorname{arccosh}(|\operatorname{tr}_1|/2)
          + \operatorname{sgn}(\operatorname{tr}_2)\,\operatorname{arccosh}(|\operatorname{tr}_2|/2)\big).

The printed eq. ``newkmu`` is this for b = +1 and tr > 2 only.
"""
from __future__ import annotations

import mpmath as mp
import sympy as sp

from ..proof import Verdict, decide
from ..reference.literal import literal_step
from ..reference.literal import phi_from_traces as phi_real  # the corrected, real Phi (module docstring)
from ..reference.samples import paper_state
from ..symbolic.darboux import lam0, mu
from ..symbolic.toda import lam, local_lax
from .base import claim, judge, scene
from .composed_map import DPS, TOL, _fmt_state, _states, eta_from_states

scene("phi", "Phi = dF/dmu on the map: spectrality, Appendix B, the real branch of arccosh (N=2,3)")

p = sp.Symbol("p_j", real=True)
E, Et, En, Etn = sp.symbols("E_j Et_j E_jp1 Et_jp1", positive=True)
eta_j, eta_n = sp.symbols("eta_j eta_jp1", real=True)



def _ratios_on_map(state, b):
    """``(eta_k+mu)/(eta_k-mu)`` on the map of branch ``b`` -- eta recovered from (p, q) and the image
    alone (eq. imptransf) -- and the traces tr L(lambda_1), tr L(lambda_2)."""
    pv, qv, l0, m = state
    pt, qt, info = literal_step(pv, qv, l0, m, b)
    ratios = [(e + m) / (e - m) for e in eta_from_states(pv, qv, pt, qt, l0)]
    return ratios, mp.re(info["tr1"]), mp.re(info["tr2"])


def _map_cases(N):
    cases = [(s, b) for s, b in _states(N)]
    if N == 3:
        cases += [(paper_state("5"), 1), (paper_state("5"), -1), (paper_state("2"), 1)]
    return cases


def _site():
    x_j, x_n = E - Et, En - Etn
    w_n = x_n * (1 / Et - 1 / E)
    p_pr = -lam0 - (Et * eta_n + E * eta_j) / (E - Et)  # eq. imptransf
    return x_j, x_n, p_pr, {eta_n: eta_n ** 2 - mu ** 2 - w_n}


@claim("2122", equation="2122", scene="phi",
       statement="combining the (2,1), (2,2) entries of eq. nlocal: (p_j + lambda) x_j = e^{q_j}(lambda - l0 - eta_j) "
                 "+ e^{q~_j}(lambda - l0 + eta_{j+1}) (local, all N)")
def eq_2122():
    x_j, x_n, p_pr, rel = _site()
    printed = decide((p_pr + lam) * x_j, E * (lam - lam0 - eta_j) + Et * (lam - lam0 + eta_n))
    return judge(printed,
                 printed="(p_j + lambda) x_j = e^{q_j}(lambda - l0 - eta_j) + e^{q~_j}(lambda - l0 + eta_{j+1})",
                 corrected="(p_j + lambda) x_j = e^{q_j}(lambda - l0 - eta_j) - e^{q~_j}(lambda - l0 + eta_{j+1})",
                 corrected_check=lambda: decide((p_pr + lam) * x_j,
                                                E * (lam - lam0 - eta_j) - Et * (lam - lam0 + eta_n)),
                 detail="p_j of eq. imptransf substituted; the printed sign of the e^{q~_j} term leaves "
                        "-2 lambda e^{q~_j} + ... (not even the lambda-dependence matches)")


@claim("rte", equation="rte", scene="phi",
       statement="l_j(l1) (x_j, mu - eta_j) = nu^1_{j+1} (x_{j+1}, mu - eta_{j+1}) with nu^1_{j+1} = e^{q~_j}(mu + "
                 "eta_{j+1})/x_{j+1}, and l_j(l2)(-x_j, mu + eta_j) = nu^2_{j+1}(-x_{j+1}, mu + eta_{j+1}) with "
                 "nu^2_{j+1} = e^{q~_j}(eta_{j+1} - mu)/x_{j+1} (local, all N)")
def rte():
    x_j, x_n, p_pr, rel = _site()
    lhs1 = local_lax(lam0 + mu, p_pr, E) * sp.Matrix([x_j, mu - eta_j])
    lhs2 = local_lax(lam0 - mu, p_pr, E) * sp.Matrix([-x_j, mu + eta_j])

    def check(nu1, nu2):
        rhs1 = nu1 * sp.Matrix([x_n, mu - eta_n])
        rhs2 = nu2 * sp.Matrix([-x_n, mu + eta_n])
        return decide(sp.Matrix([lhs1, lhs2]), sp.Matrix([rhs1, rhs2]), relations=rel)

    printed = check(Et * (mu + eta_n) / x_n, Et * (eta_n - mu) / x_n)
    return judge(printed,
                 printed="nu^1_{j+1} = e^{q~_j}(mu + eta_{j+1})/x_{j+1}, nu^2_{j+1} = e^{q~_j}(eta_{j+1} - mu)/x_{j+1}",
                 corrected="nu^1_{j+1} = -e^{q~_j}(mu + eta_{j+1})/x_{j+1}, nu^2_{j+1} = -e^{q~_j}(eta_{j+1} - mu)"
                           "/x_{j+1} (both signs flip, so nu^1/nu^2 = (mu+eta)/(eta-mu) and eq. spec are unaffected)",
                 corrected_check=lambda: check(-Et * (mu + eta_n) / x_n, -Et * (eta_n - mu) / x_n),
                 detail="the kernel vectors (x_j, mu-eta_j), (-x_j, mu+eta_j) are transported as printed; "
                        "both components at l1 and l2, modulo eta_{j+1}^2 = mu^2 + w_{j+1} (either sign of eta); "
                        "the sign slip follows from the one in eq. 2122")


for _N in (2, 3):
    def _make(N):
        @claim(f"spec.n{N}", equation="spec", scene="phi", N=N,
               statement="Phi = ln(prod nu^1 / prod nu^2) = ln v(l1) + ln v(l2) = ln((tr1 - gamma1)/2) + "
                         f"ln((tr2 - gamma2)/2) on the map (N={N})")
        def spec_check():
            worst_prod, worst_log, bad = mp.mpf(0), mp.mpf(0), None
            with mp.workdps(DPS):
                for state, b in _map_cases(N):
                    ratios, tr1, tr2 = _ratios_on_map(state, b)
                    g1, g2 = b * mp.sqrt(tr1 ** 2 - 4), b * mp.sqrt(tr2 ** 2 - 4)
                    prod = mp.fprod(ratios)
                    rhs = (tr1 - g1) / 2 * ((tr2 - g2) / 2)
                    worst_prod = max(worst_prod, abs(prod - rhs) / abs(rhs))
                    # nu-products are the eigenvalues of L(l1), L(l2) on the kernels (eq. l1l2)
                    lhs_log = mp.fsum(mp.log(x) for x in ratios)
                    rhs_log = mp.log((tr1 - g1) / 2) + mp.log((tr2 - g2) / 2)
                    r = abs(lhs_log - rhs_log)
                    if r > worst_log:
                        worst_log, bad = r, _fmt_state(state, b)
            printed = Verdict.sampled(worst_log, method=f"numeric: principal logs at {DPS} digits", counterexample=bad, tol=TOL, dps=DPS)
            corrected = Verdict.sampled(worst_prod, method=f"numeric: products at {DPS} digits", tol=TOL, dps=DPS)
            return judge(printed,
                         printed="sum_k ln((eta_k+mu)/(eta_k-mu)) = ln((tr1-gamma1)/2) + ln((tr2-gamma2)/2) "
                                 "(principal logarithms)",
                         corrected="prod_k (eta_k+mu)/(eta_k-mu) = ((tr1-gamma1)/2)((tr2-gamma2)/2) with "
                                   "gamma_i = branch*sqrt(tr_i^2-4): the log identity holds modulo 2*pi*i "
                                   "(real parts: Phi = ln|...|)",
                         corrected_check=lambda: corrected,
                         detail="8 random states (both branches, both signs of tr)"
                                + (" + the paper's example" if N == 3 else ""))

        @claim(f"newkmu.n{N}", equation="newkmu", scene="phi", N=N,
               statement="Phi = dF/dmu on the map = -arccosh(tr L(l1)/2) - arccosh(tr L(l2)/2) "
                         f"(N={N})")
        def newkmu_check():
            worst_pr, worst_re, bad = mp.mpf(0), mp.mpf(0), None
            with mp.workdps(DPS):
                for state, b in _map_cases(N):
                    # Phi = dF/dmu (eq. vqqtmu) on the map
                    ratios, tr1, tr2 = _ratios_on_map(state, b)
                    phi_c = mp.fsum(mp.log(x) for x in ratios)  # principal branch, as printed
                    phi_r = mp.fsum(mp.log(abs(x)) for x in ratios)
                    printed = -mp.acosh(tr1 / 2) - mp.acosh(tr2 / 2)
                    r = abs(phi_c - printed) / max(1, abs(printed))
                    if r > worst_pr:
                        worst_pr, bad = r, dict(_fmt_state(state, b), tr1=mp.nstr(tr1, 12), tr2=mp.nstr(tr2, 12),
                                                Phi=mp.nstr(phi_c, 15), printed=mp.nstr(printed, 15))
                    worst_re = max(worst_re, abs(phi_r - phi_real(tr1, tr2, b)) / max(1, abs(phi_r)))
            printed_d = Verdict.sampled(worst_pr, method=f"numeric: mpmath {DPS} digits on the map", counterexample=bad, tol=TOL, dps=DPS)
            corrected_d = Verdict.sampled(worst_re, method=f"numeric: mpmath {DPS} digits on the map", tol=TOL, dps=DPS)
            return judge(printed_d,
                         printed="Phi = -arccosh(tr L(l1)/2) - arccosh(tr L(l2)/2)",
                         corrected="real Phi = sum_k ln|(eta_k+mu)/(eta_k-mu)| = -branch*(sgn(tr1) arccosh(|tr1|/2) "
                                   "+ sgn(tr2) arccosh(|tr2|/2)); equals the printed formula only for branch=+1 "
                                   "and tr L > 2 at both points",
                         corrected_check=lambda: corrected_d,
                         detail="fails for tr L < -2 (e.g. the paper's own example, where printed is complex) and "
                                "for branch=-1 (sign flip)")

    _make(_N)
