r"""Theorem 2 on the Toda BT: eqs. ``Hdiscr``, ``linearcomb``, ``eqdisc`` (N = 2, 3) and ``Hdis``.

n steps of the map of branch b are the time-n flow of :math:`\mathcal H=\int_0^\mu\Phi\,d\mu'`,
i.e. of :math:`\sum_kc_kH_k` with :math:`c_k=\partial\mathcal H/\partial H_k`
:math:`=-b\int_{\lambda_0-\mu}^{\lambda_0+\mu}\lambda^k(\operatorname{tr}L^2-4)^{-1/2}d\lambda` (positive root,
either sign of tr L; :math:`\Phi` the real one of :mod:`symbt.claims.theorem1`).  The explicit
map (60 digits) meets an integration of Hamilton's equations that knows nothing about Bäcklund
maps (:func:`symbt.claims._flow.time_flow`: heyoka in float64, or the built-in Taylor
integrator); the :math:`c_k` are computed from the claim's parts: :math:`\partial\Phi/\partial\operatorname{tr}_i`
by SymPy, integrated by composite Gauss-Legendre.  Float64 decides at tolerance 1e-10: a
wrong sign or wrong :math:`c_k` leaves O(1) relative residuals, a relative change of 1e-6 in
any constant of the parts leaves >= 1e-8 at some sample.
"""
from __future__ import annotations

from dataclasses import replace
from functools import cache

import mpmath as mp
import numpy as np
import sympy as sp

from ..proof.cells import CellTable
from ..reference.literal import literal_step, signed_arccosh_half
from ..reference.samples import paper_state
from ..reference.spectral import flow_coefficients_mp
from ..reference.taylor import hamiltonian_flow
from ..reference.trace import hamiltonians
from ..symbolic.darboux import lam0, mu
from ..symbolic.toda import lam
from . import _flow
from ._bt import images
from ._common import fmt_state, judge_cells, per_cell
from ._flow import gl_integral, hamiltonians_float, in_domain, moments, rel_diff, time_flow
from .base import Outcome, Parts, claim, scene
from .theorem1 import branch, phi_real, tr1, tr2

scene("theorem2", "Theorem 2 (eqs. Hdiscr, linearcomb, eqdisc, Hdis): n BT steps = time-n flow of sum c_k H_k; "
                  "the constants of the captions of Figs. 1-2")

k, tr, I1, I2 = sp.symbols("k tr I1 I2", real=True)
TOL2 = 1e-10
WEIGHT = -branch * lam ** k / sp.sqrt(tr ** 2 - 4)


@cache
def _lamb(args: tuple, expr):
    """``sympy.lambdify`` to numpy (memoised); DiracDelta (derivatives of sgn, |.|) is 0 off tr = 0."""
    expr = sp.sympify(expr).replace(sp.DiracDelta, lambda *a: sp.S.Zero)
    f = sp.lambdify(args, expr, "numpy")

    def g(*v):
        with np.errstate(all="ignore"):  # principal branches at complex arguments; nan/inf judged by the caller
            out = f(*(np.asarray(a, dtype=complex) if np.ndim(a) else a for a in v))
        return np.broadcast_to(np.asarray(out, dtype=complex), np.shape(v[0]))
    return g


def rel_vec(a, b) -> float:
    """max |a - b| / max |b| (inf when undefined)."""
    with np.errstate(all="ignore"):
        r = float(np.max(np.abs(np.asarray(a) - b)) / np.max(np.abs(b)))
    return r if np.isfinite(r) else float("inf")


@cache
def _diff(expr, var):
    return sp.diff(expr, var)


@cache
def _phi_derivatives(Phi) -> tuple:
    return tuple(_lamb((tr1, tr2, branch), _diff(Phi, t)) for t in (tr1, tr2)) + (_lamb((tr1, tr2, branch), Phi),)


@cache
def samples(N: int, count: int) -> tuple:
    """Float views of :func:`symbt.claims._bt.images` (tr coefficients H, lam0, mu, image) per sample."""
    out = []
    for cell, state, b, pt, qt, _ in images(N, count):
        p, q, l0, m = state
        Hf = hamiltonians_float(p, q)
        out.append(dict(cell=cell, state=state, b=b, p=[float(v) for v in p], q=[float(v) for v in q], H=Hf,
                        l0=float(l0), mu=float(m), image=[float(v) for v in pt + qt],
                        ok=in_domain(Hf, float(l0 - m), float(l0 + m))))
    return tuple(out)


def _tr(s: dict, x):
    return np.polyval(s["H"][::-1], np.asarray(x, dtype=complex))


def c_from_phi(Phi, s: dict, upper: float) -> tuple[np.ndarray, float]:
    """``(c_k = int_0^upper dPhi/dH_k dmu', max |Im Phi(mu' = upper)|)``, tr1, tr2 at lam0 +- mu'."""
    d1, d2, phi = _phi_derivatives(Phi)
    N, l0, b = len(s["p"]), s["l0"], s["b"]

    def f(m):
        lp, lm = l0 + m, l0 - m
        t1, t2 = _tr(s, lp), _tr(s, lm)
        a, c = d1(t1, t2, b), d2(t1, t2, b)
        return np.array([a * lp ** j + c * lm ** j for j in range(N)])

    end = phi(_tr(s, l0 + upper), _tr(s, l0 - upper), b)
    return gl_integral(f, 0.0, upper), float(abs(np.imag(end)))


def c_from_weight(weight, lower: float, upper: float, s: dict) -> np.ndarray:
    """``c_k = int_lower^upper weight(lam, k, tr L(lam), b) dlam``, k < N."""
    w = _lamb((lam, k, tr, branch), weight)
    N = len(s["p"])
    return gl_integral(lambda x: np.array([w(x, j, _tr(s, x), s["b"]) for j in range(N)]), lower, upper)


def _flow_residual(s: dict, c: np.ndarray, t: float) -> float:
    """Relative distance between the BT image and the time-t flow of sum c_k H_k (inf for complex c)."""
    if not np.all(np.isfinite(c)) or np.max(np.abs(np.imag(c))) > 1e-12 * max(1e-300, np.max(np.abs(c))):
        return float("inf")
    fp, fq = time_flow(s["p"], s["q"], np.real(c), t)
    return rel_diff(fp + fq, s["image"])


def _route() -> str:
    return ("heyoka.taylor_adaptive (float64)" if _flow.flow_route() == "heyoka"
            else "symbt.reference.taylor (20 digits; heyoka not installed)")


@cache
def _limit_function(expr):
    return sp.lambdify((lam0, mu), expr, "math")


def _limit(expr, s: dict) -> float:
    return float(_limit_function(expr)(s["l0"], s["mu"]))


# --------------------------------------------------------------------------- eq. Hdiscr

def _parts_Hdiscr(N: int) -> Parts:
    return Parts(printed={"Phi": phi_real(), "upper": mu, "time": 1},
                 context={"H": "int_0^upper Phi(tr L(lam0 + mu'), tr L(lam0 - mu')) dmu'", "time": "per BT step"})


@claim("Hdiscr", equation="Hdiscr", scene="theorem2", sizes=(2, 3), parts=_parts_Hdiscr,
       statement="Theorem 2 (eqs. Hdiscr, linearcomb): one BT step of branch b is the time-1 flow of "
                 "H = int_0^mu Phi dmu' (real Phi of branch b), i.e. of sum_k c_k H_k with c_k = dH/dH_k (N={N})")
def theorem2_check(N: int, parts: Parts, deep: bool = False) -> Outcome:
    P = parts.printed
    table = CellTable(tol=TOL2)
    outside = 0
    for s in samples(N, per_cell(deep)):
        if not s["ok"]:
            outside += 1
            continue
        c, im = c_from_phi(P["Phi"], s, _limit(P["upper"], s))
        r = max(_flow_residual(s, c, float(P["time"])), im)
        table.add(s["cell"], printed=r, point=fmt_state(s["state"], s["b"]))
    out = judge_cells(table, method=f"numeric: explicit map (mpmath 60 digits) vs the time-1 flow of sum c_k H_k by "
                                    f"{_route()}; c_k = int_0^mu dPhi/dH_k by Gauss-Legendre",
                      printed="one BT step of branch b = time-1 flow of H = int_0^mu Phi dmu'", dps=15,
                      detail=f"{outside} samples outside the domain |tr L| > 2 on [lam0-mu, lam0+mu];")
    out = replace(out, n_scope=[N])
    return out


def bt_iterates(p, q, l0, mu_, b, n):
    out = [(p, q)]
    for _ in range(n):
        pt, qt, _ = literal_step(out[-1][0], out[-1][1], l0, mu_, b)
        out.append((pt, qt))
    return out


def compare_iterates_with_flow(p, q, l0, mu_, b, ns, *, sign=1, c=None):
    """max relative difference between n BT steps and the time-n flow of sign * sum c_k H_k, per n (mpmath)."""
    c = flow_coefficients_mp(p, q, l0, mu_, b) if c is None else c
    c = [sign * v for v in c]
    it = bt_iterates(p, q, l0, mu_, b, max(ns))
    res, steps = {}, {}
    for n in ns:
        fl = hamiltonian_flow(p, q, c, n)
        res[n] = max(abs(a - v) / max(1, abs(v)) for a, v in zip(fl[0] + fl[1], it[n][0] + it[n][1]))
        steps[n] = fl.steps
    return res, steps


@cache
def _iterates(N: int, count: int, n: int) -> tuple:
    """Per sample the float image after 1, 5, ..., n steps (None if the orbit leaves the real map)."""
    out = []
    with mp.workdps(60):
        for _cell, state, b, *_ in images(N, count):
            p, q, l0, m = state
            try:
                it = bt_iterates(p, q, l0, m, b, n)
                out.append({j: [float(mp.re(v)) for v in it[j][0] + it[j][1]] for j in (1, 5, n)}
                           if all(isinstance(v, mp.mpf) for st in it for v in st[1]) else None)
            except (ZeroDivisionError, ValueError):
                out.append(None)
    return tuple(out)


@claim("Hdiscr.deep", equation="Hdiscr", scene="theorem2", sizes=(2, 3), parts=_parts_Hdiscr, deep=True,
       statement="Theorem 2 (eq. Hdiscr, discr): n = 1, 5, 20 BT steps of branch b = the time-n flow of "
                 "sum_k c_k H_k, c_k = dH/dH_k, H = int_0^mu Phi dmu' (N={N}, 64 states per cell)")
def theorem2_deep(N: int, parts: Parts) -> Outcome:
    P = parts.printed
    table = CellTable(tol=1e-9)
    skipped_ = 0
    for s, its in zip(samples(N, per_cell(True)), _iterates(N, per_cell(True), 20)):
        if its is None or not s["ok"]:
            skipped_ += 1
            continue
        c, im = c_from_phi(P["Phi"], s, _limit(P["upper"], s))
        r = im
        for n, img in its.items():
            r = max(r, _flow_residual(dict(s, image=img), c, n * float(P["time"])))
        table.add(s["cell"], printed=r, point=fmt_state(s["state"], s["b"]))
    out = judge_cells(table, method=f"numeric: 20 iterates of the explicit map (mpmath 60 digits) vs the flow to "
                                    f"t = 1, 5, 20 by {_route()}", printed="n BT steps = time-n flow", dps=15,
                      detail=f"{skipped_} samples whose orbit leaves the real map or the domain;")
    out = replace(out, n_scope=[N])
    return out


@claim("Hdiscr.deep100", equation="Hdiscr", scene="theorem2", sizes=(3,), parts=_parts_Hdiscr, deep=True,
       statement="Theorem 2 at 100 digits on the paper's example (lam0 = 10, mu = 5, branch +1): 20 BT steps = "
                 "the time-20 flow of sum c_k H_k, c_k = dH/dH_k, H = int_0^mu Phi dmu'")
def theorem2_deep100(N: int, parts: Parts) -> Outcome:
    P = parts.printed
    expr = [sp.diff(P["Phi"], t).replace(sp.DiracDelta, lambda *a: sp.S.Zero) for t in (tr1, tr2)]
    d1, d2 = (sp.lambdify((tr1, tr2, branch), e, "mpmath") for e in expr)
    with mp.workdps(100):
        p, q, l0, m = paper_state("5")
        coeffs = hamiltonians(p, q)[::-1]
        up = sp.lambdify((lam0, mu), P["upper"], "mpmath")(l0, m)

        def integrand(j):
            def f(t):
                a, b_ = mp.polyval(coeffs, l0 + t), mp.polyval(coeffs, l0 - t)
                return d1(a, b_, 1) * (l0 + t) ** j + d2(a, b_, 1) * (l0 - t) ** j
            return f
        c = [mp.quad(integrand(j), [0, up]) for j in range(N)]
        res, steps = compare_iterates_with_flow(p, q, l0, m, 1, (20,), c=[mp.re(v) for v in c], sign=P["time"])
    table = CellTable(tol=1e-90)
    table.add({"branch": 1, "sign_tr": -1}, printed=res[20], point=fmt_state((p, q, l0, m), 1))
    out = judge_cells(table, method="numeric: mpmath 100 digits; 20 iterates of the explicit map vs Taylor "
                                    "integration (symbt.reference.taylor) to t = 20",
                      printed="20 BT steps = time-20 flow", dps=100, detail=f"{steps[20]} Taylor steps;")
    out = replace(out, n_scope=[N])
    return out


# --------------------------------------------------------------------------- eqs. linearcomb and eqdisc

def _parts_linearcomb(N: int) -> Parts:
    return Parts(printed={"Phi": phi_real(), "weight": WEIGHT, "lower": lam0 - mu, "upper": lam0 + mu})


@claim("linearcomb", equation="linearcomb", scene="theorem2", sizes=(2, 3), parts=_parts_linearcomb,
       statement="c_k = d/dH_k int_0^mu Phi(H, mu') dmu' (real Phi of branch b, tr L = sum H_k lam^k held as a "
                 "function of the H_k) equals -b int_{lam0-mu}^{lam0+mu} lam^k/sqrt(tr L^2 - 4) dlam with the "
                 "positive root, for both signs of tr L (eq. eqdisc for b = +1) (N={N})")
def linearcomb_check(N: int, parts: Parts, deep: bool = False) -> Outcome:
    P = parts.printed
    table = CellTable(tol=TOL2)
    for s in samples(N, per_cell(deep)):
        if not s["ok"]:
            continue
        lhs, im = c_from_phi(P["Phi"], s, s["mu"])
        rhs = c_from_weight(P["weight"], _limit(P["lower"], s), _limit(P["upper"], s), s)
        r = max(rel_vec(lhs, rhs), im)
        table.add(s["cell"], printed=r, point=fmt_state(s["state"], s["b"]))
    out = judge_cells(table, method="numeric: float64 Gauss-Legendre; d/dH_k under the integral (dPhi/dtr_i by "
                                    "SymPy) vs the weight integral", printed="d/dH_k int_0^mu Phi = -b int lam^k w",
                      dps=15)
    out = replace(out, n_scope=[N])
    return out


def _parts_eqdisc(N: int) -> Parts:
    return Parts(printed={"weight": -lam ** k / sp.sqrt(tr ** 2 - 4), "lower": lam0 - mu, "upper": lam0 + mu,
                          "flow_sign": branch},
                 context={"flow_sign": "the BT of branch b is the time-1 flow of flow_sign * sum_k c_k H_k"})


@claim("eqdisc", equation="eqdisc", scene="theorem2", sizes=(2, 3), parts=_parts_eqdisc,
       statement="with c_k = -int_{lam0-mu}^{lam0+mu} lam^k/sqrt(tr L^2-4) dlam as printed (positive root), the BT "
                 "with gamma = +sqrt(tr^2-4) (branch +1) is the time-1 flow of sum_k c_k {H_k, .}, for tr L > 2 and "
                 "tr L < -2 alike; branch b is the flow of b sum c_k H_k (N={N})")
def eqdisc_check(N: int, parts: Parts, deep: bool = False) -> Outcome:
    P = parts.printed
    sign = sp.lambdify((branch,), P["flow_sign"], "math")
    table = CellTable(tol=TOL2)
    for s in samples(N, per_cell(deep)):
        if not s["ok"]:
            continue
        c = c_from_weight(P["weight"], _limit(P["lower"], s), _limit(P["upper"], s), s)
        table.add(s["cell"], printed=_flow_residual(s, sign(s["b"]) * c, 1.0), point=fmt_state(s["state"], s["b"]))
    out = judge_cells(table, method=f"numeric: explicit map (mpmath 60 digits) vs the time-1 flow by {_route()}; "
                                    "printed c_k by Gauss-Legendre",
                      printed="BT of branch b = time-1 flow of b sum_k c_k H_k, c_k of eq. eqdisc", dps=15,
                      detail="the paper never states which root gamma takes: the printed c_k (and the negative "
                             "caption constants) belong to gamma = +sqrt(tr^2-4);")
    out = replace(out, n_scope=[N])
    return out


# --------------------------------------------------------------------------- eq. Hdis (and AA2)

HDIS = -sp.acosh(tr / 2)
AA2 = {"AA2_integrand": sp.acosh(((lam + I1) ** 2 - I2) / 2), "AA2_lower": lam0 + mu, "AA2_upper": lam0 - mu}


def _parts_Hdis() -> Parts:
    return Parts(printed={"integrand": HDIS, "lower": lam0 - mu, "upper": lam0 + mu, **AA2},
                 corrected={"integrand": -branch * signed_arccosh_half(tr, ns=sp), "lower": lam0 - mu,
                            "upper": lam0 + mu, **AA2},
                 context={"AA2": "compared with the printed H as complex numbers (N = 2, tr of eq. tn2)"})


def _hdis_residual(side: dict, s: dict, real: bool = False) -> float:
    """dH/dH_k vs c_k(b) = -b int lam^k w (relative), (N = 2) AA2's integral vs the printed H, and with
    ``real`` the imaginary part of H (relative)."""
    N, lo, up = len(s["p"]), _limit(side["lower"], s), _limit(side["upper"], s)
    dh = _lamb((tr, lam, branch), _diff(side["integrand"], tr))
    lhs = gl_integral(lambda x: np.array([dh(_tr(s, x), x, s["b"]) * x ** j for j in range(N)]), lo, up)
    ref = moments(s["H"], s["l0"], s["b"] * s["mu"], range(N))
    r = rel_vec(lhs, ref)
    if real:
        h_side = _lamb((tr, lam, branch), side["integrand"])
        H = gl_integral(lambda x: h_side(_tr(s, x), x, s["b"]), lo, up)
        r = max(r, float(abs(np.imag(H))) / max(1.0, float(abs(H))))
    if N == 2:
        (p1, p2), (q1, q2) = s["p"], s["q"]
        i1, i2 = (p1 + p2) / 2, 2 * np.cosh(q1 - q2) + ((p1 - p2) / 2) ** 2
        h = _lamb((tr, lam, branch), HDIS)
        aa2 = _lamb((lam, I1, I2), side["AA2_integrand"])
        H_pr = gl_integral(lambda x: h(_tr(s, x), x, s["b"]), s["l0"] - s["mu"], s["l0"] + s["mu"])
        H_aa2 = gl_integral(lambda x: aa2(np.asarray(x, dtype=complex), i1, i2),
                            _limit(side["AA2_lower"], s), _limit(side["AA2_upper"], s))
        r = max(r, float(abs(H_aa2 - H_pr) / max(1.0, abs(H_pr))))
    return r


@claim("Hdis", equation="Hdis", scene="theorem2", parts=_parts_Hdis,
       statement="the BTs discretise the flow of H = -int_{lam0-mu}^{lam0+mu} arccosh(tr L(lam)/2) dlam (principal "
                 "arccosh), whose gradient coefficients dH/dH_k are the c_k of the BT of branch b (eq. eqdisc: "
                 "b = +1); eq. AA2's int_{lam0+mu}^{lam0-mu} arccosh(((lam+I1)^2-I2)/2) dlam is the same H (N = 2)")
def hdis_check(parts: Parts, deep: bool = False) -> Outcome:
    table = CellTable(tol=TOL2)
    for N in (2, 3):
        for s in samples(N, per_cell(deep)):
            if not s["ok"]:
                continue
            table.add(dict(N=str(N), **s["cell"]), printed=_hdis_residual(parts.printed, s),
                      corrected=_hdis_residual(parts.corrected, s, real=True), point=fmt_state(s["state"], s["b"]))
    out = judge_cells(table, method="numeric: float64 Gauss-Legendre, d/dH_k under the integral (principal "
                                    "arccosh, complex) vs c_k = -b int lam^k/sqrt(tr^2-4)",
                      printed="H = -int_{lam0-mu}^{lam0+mu} arccosh(tr L/2) dlam with dH/dH_k = c_k of the BT",
                      corrected="H = -b int_{lam0-mu}^{lam0+mu} sgn(tr L) arccosh(|tr L|/2) dlam, real (b = +1 for "
                                "eq. eqdisc as printed); AA2's integral equals the printed H", dps=15)
    out = replace(out, n_scope=[2, 3])
    return out
