r"""N = 2: the map as an addition formula (eq. ``addform``), its regimes and the continuation of F, as data.

* ``addform.n2`` -- printed :math:`F(\tilde P,k) = F(P,k) + F(\lambda_-,k) - F(\lambda_+,k)` (principal F, as
  complex numbers) against the branch-free form: :math:`\tilde u \equiv u + \mathcal A(\lambda_0+\mu) -
  \mathcal A(\lambda_0-\mu)` modulo :math:`4K\mathbb Z + 2iK'\mathbb Z` (i.e. :math:`\operatorname{sn}` and
  :math:`\operatorname{cn}\operatorname{dn}` of the shifted u give :math:`\tilde P` and
  :math:`2\sinh(\tilde q_1-\tilde q_2)/\sqrt{I_2^2-4}`) and :math:`e^{\tilde q_1+\tilde q_2} = e^{q_1+q_2}v_1v_2`.
* ``addform.regimes`` -- the signature of each regime (real gamma, real p~, signs of e^{q~_j}, |P~| > 1,
  the imaginary part of the shift) is a tuple-valued part, compared with what every sample shows.
* ``addform.continuation`` -- the printed reading continues F beyond |z| = 1 by mpmath's principal
  ``ellipf(asin z, m)``, which is discontinuous there (z on the cut of asin); the corrected parts are the
  zone formulas of the deterministic continuation by the Abel map (value and sheet rule), checked by
  Jacobi's functions and for independence of the working precision.
"""
from __future__ import annotations

import random
from functools import cache

import mpmath as mp
import sympy as sp

from ..proof.cells import CellTable
from ..reference import elliptic as E
from ._common import per_cell
from ._elliptic import (
    DPS,
    I1,
    I2,
    TOL,
    A,
    F_sym,
    branch,
    finite,
    image,
    lam0,
    map_samples,
    mp_fn,
    mu,
    outcome,
    point,
    state,
    tr1,
    tr2,
)
from .base import Parts, claim

Ps, Pts = sp.symbols("P Pt", real=True)
TR = {"tr1": (lam0 + mu + I1) ** 2 - I2, "tr2": (lam0 - mu + I1) ** 2 - I2}
STEP = [lam0, mu, I1, I2, branch]
LAM_P, LAM_M = (lam0 + mu + I1) / sp.sqrt(I2 - 2), (lam0 - mu + I1) / sp.sqrt(I2 - 2)


# --------------------------------------------------------------------------- addform.n2

def _parts_addform() -> Parts:
    return Parts(printed={"lhs": F_sym(Pts), "rhs": F_sym(Ps) + F_sym(LAM_M) - F_sym(LAM_P)},
                 corrected={"shift": A(lam0 + mu, branch, I1, I2) - A(lam0 - mu, branch, I1, I2),
                            "v1": (tr1 - branch * sp.sqrt(tr1 ** 2 - 4)) / 2,
                            "v2": (tr2 + branch * sp.sqrt(tr2 ** 2 - 4)) / 2},
                 context=dict(TR))


@claim("addform.n2", equation="addform", scene="elliptic", N=2, parts=_parts_addform,
       uses=("th1th2",),
       statement="F(P~,k) = F(P,k) + F(lambda_-,k) - F(lambda_+,k), P = (p2-p1)/(2sqrt(I2-2)), "
                 "lambda_+- = (l0 +- mu + I1)/sqrt(I2-2), k^2 = (I2-2)/(I2+2)")
def addform(parts: Parts, deep: bool = False):
    args = [Pts, Ps] + STEP
    fp = mp_fn(args, [parts.printed["lhs"], parts.printed["rhs"]])
    fs = mp_fn(STEP, parts.corrected["shift"])
    c = parts.corrected
    fv = mp_fn(STEP, c["v1"].subs(tr1, parts.context["tr1"]) * c["v2"].subs(tr2, parts.context["tr2"]))
    table = CellTable(tol=TOL)
    inner = [0, 0]
    with mp.workdps(DPS):
        for s in map_samples(per_cell(deep)):
            st, im = state(s), image(s)
            a = (st.lam0, st.mu, st.I1, st.I2, s.b)
            lp, rp_ = fp(im.Pt, st.P, *a)
            rp = finite(lp - rp_) / max(1, abs(lp))
            lhs, rhs = im.Et[0] * im.Et[1], st.E[0] * st.E[1] * fv(*a)
            rc = max(finite(E.lattice_residual(im.ut - st.u - fs(*a), st.m)) + im.on_curve,
                     finite(lhs - rhs) / max(abs(lhs), abs(rhs), 1e-30))
            table.add(s.cell, printed=rp, corrected=rc, point=point(s, residual=rp))
            if s.cell["regime"] == "inner":  # all F real: where does the printed formula hold?
                x0, x1 = mp.sign(st.q[0] - st.q[1]), mp.sign(mp.re(im.qt[0] - im.qt[1]))
                pred = x0 == x1 and s.b * x0 == -1
                inner[0] += int(pred == (rp <= TOL))
                inner[1] += 1
    return outcome(table, method=f"numeric: the map at {DPS} digits; printed with mpmath's principal ellipf(asin z, "
                                 "k^2) as complex numbers, corrected modulo the period lattice (4K, 2iK')",
                   printed="F(P~,k) = F(P,k) + F(lambda_-,k) - F(lambda_+,k)",
                   corrected="branch-free: u~ = u + A(l0+mu) - A(l0-mu) modulo 4K Z + 2iK' Z, i.e. sn(u + A(l0+mu) - "
                             "A(l0-mu)) = P~ and (cn dn)(...) = 2 sinh(q~1-q~2)/sqrt(I2^2-4), where sn u = P, "
                             "cn u dn u = 2sinh(q1-q2)/sqrt(I2^2-4) and A(lambda) is the Abel image of the "
                             "spectral-curve point (lambda, gamma) used by the map: sn A = (lambda+I1)/sqrt(I2-2), "
                             "cn A dn A = gamma/sqrt(I2^2-4), gamma = b sqrt(tr L^2 - 4); plus e^{q~1+q~2} = "
                             "e^{q1+q2} v(l1) v(l2)",
                   detail="inner regime (all F real): the printed formula holds exactly where b sgn(q1-q2) = -1 "
                          f"and the step keeps the sign of q1-q2 (prediction matched at {inner[0]}/{inner[1]} "
                          "samples): for q1 > q2 the printed F(P) is u and the printed shift is the one of b = -1; "
                          "for q1 < q2 F(P) = +-2K - u runs backwards and it is the one of b = +1. Beyond |z| = 1 "
                          "the principal F sits on a cut (addform.continuation)")


# --------------------------------------------------------------------------- addform.regimes

def _parts_regimes() -> Parts:
    # one entry per regime, in the order of symbt.reference.elliptic.REGIMES; None = not asserted
    return Parts(printed={"real_gamma": (True, True, True, True, False), "real_p": (True, True, True, True, False),
                          "E_signs": ((1, 1), (1, 1), (-1, -1), None, None), "E_product": (1, 1, 1, -1, None),
                          "P_beyond_1": (False, False, False, True, None),
                          "shift_real": (True, True, True, False, None),
                          "shift_im_half": (False, False, False, True, None),
                          "real_map": (True, True, False, False, False)})


def _signature(s) -> dict:
    st, im = state(s), image(s)
    Kp = mp.ellipk(1 - st.m)
    gam = [s.b * mp.sqrt(t ** 2 - 4) for t in ((st.lam0 + sg * st.mu + st.I1) ** 2 - st.I2 for sg in (1, -1))]
    real_g = all(isinstance(g, mp.mpf) for g in gam)
    real_p = all(finite(mp.im(v)) < TOL for v in im.pt)
    signs = tuple(int(mp.sign(mp.re(e))) if finite(mp.im(e)) < TOL else 0 for e in im.Et)
    sp_plus = E.spectral_point(st.lam0 + st.mu, st.I1, st.I2, s.b)
    sp_minus = E.spectral_point(st.lam0 - st.mu, st.I1, st.I2, s.b)
    du = E.abel(sp_plus[0], sp_plus[1], st.m) - E.abel(sp_minus[0], sp_minus[1], st.m)
    im_mod = abs(mp.im(du) - 2 * Kp * mp.nint(mp.im(du) / (2 * Kp)))
    return {"real_gamma": real_g, "real_p": real_p, "E_signs": signs, "E_product": signs[0] * signs[1],
            "P_beyond_1": bool(real_p and abs(mp.re(im.Pt)) > 1), "shift_real": bool(im_mod < TOL),
            "shift_im_half": bool(abs(im_mod - Kp) < TOL), "real_map": bool(real_p and signs == (1, 1))}


@claim("addform.regimes", equation="addform", scene="elliptic", N=2, parts=_parts_regimes,
       where="regimes of lambda_+- in the addition formula (not stated in the paper)",
       statement="the real map exists iff lambda_+- lie both in (-1,1) or both beyond 1/k on the same side; "
                 "beyond 1/k on opposite sides both e^{q~_j} < 0 (the shift is real mod 2iK'); with one inside and one "
                 "outside, e^{q~1} e^{q~2} < 0 and |P~| > 1 (shift has Im = K' mod 2K'); in a gap 1 < |lambda| < 1/k "
                 "gamma is imaginary and p~ complex")
def regimes(parts: Parts, deep: bool = False):
    table = CellTable(tol=0.5)
    with mp.workdps(DPS):
        for s in map_samples(per_cell(deep)):
            sig = _signature(s)
            i = E.REGIMES.index(s.cell["regime"])
            off = [k for k, v in parts.printed.items() if v[i] is not None and sig[k] != v[i]]
            table.add(s.cell, printed=float(len(off)), point=point(s, off=", ".join(off) or "-",
                                                                  **{k: str(v) for k, v in sig.items()}))
    out = outcome(table, method=f"numeric: the map at {DPS} digits, the signature of every sample compared with the "
                                "tabulated one (residual = number of mismatching entries)",
                  printed="inner / outer-same: gamma real, p~ real, e^{q~_j} > 0, shift real; outer-opposite: both "
                          "e^{q~_j} < 0, shift real mod 2iK'; mixed: e^{q~1}e^{q~2} < 0, |P~| > 1, Im shift = K' mod "
                          "2K'; gap: gamma imaginary, p~ complex",
                  detail="outer-opposite: q~_j = ln|e^{q~_j}| + i pi, the relative motion is real and theta1 gains "
                         "2 pi i; mixed: cosh(q~1-q~2) < 0, another real form, |P~| > 1 since sn(v + iK') = "
                         "1/(k sn v)")
    return out


# --------------------------------------------------------------------------- addform.continuation

zz = sp.Symbol("z", real=True)
a_, m_ = sp.symbols("a m", positive=True)
ZONES = ("in", "gap", "out")


@cache
def _continuation_samples(per: int) -> tuple:
    """(cell, z, m) with z in a zone (|z| < 1, 1 < |z| < 1/k, |z| > 1/k) of either sign; both sheets."""
    out = []
    for zone in ZONES:
        for sg in (1, -1):
            rng = random.Random(f"continuation/{zone}/{sg}")
            for _ in range(per):
                m = rng.uniform(0.05, 0.95)
                k = m ** 0.5
                a = {"in": rng.uniform(0.02, 0.95), "gap": 1 + (1 / k - 1) * rng.uniform(0.05, 0.95),
                     "out": rng.uniform(1.05, 3.0) / k}[zone]
                for sheet in (1, -1):
                    out.append(({"zone": zone, "sign_z": sg, "sheet": sheet}, f"{sg * a:.17g}", f"{m:.17g}"))
    return tuple(out)


def _parts_continuation() -> Parts:
    return Parts(printed={"F": sp.elliptic_f(sp.asin(zz), m_)},
                 corrected={"v_in": sp.elliptic_f(sp.asin(a_), m_),
                            "v_gap": sp.elliptic_k(m_) + sp.I * sp.elliptic_f(sp.asin(sp.sqrt((1 - 1 / a_ ** 2)
                                                                                             / (1 - m_))), 1 - m_),
                            "v_out": sp.I * sp.elliptic_k(1 - m_) + sp.elliptic_f(sp.asin(1 / (sp.sqrt(m_) * a_)), m_),
                            "sheet": (1, -1, -1)})


@cache
def _forward(u, m, prec):
    with mp.workprec(prec):
        sn, cn, dn = E.sn_cn_dn(u, m)
        return sn, cn * dn


@claim("addform.continuation", equation="addform", scene="elliptic", N=2, parts=_parts_continuation,
       statement="F(lambda_+-, k) in eq. addform/citn is meaningful for |lambda_+-| > 1 "
                 "(continuation of F(z,k) beyond |z| = 1)")
def continuation(parts: Parts, deep: bool = False):
    fF = mp_fn([zz, m_], parts.printed["F"])
    fv = {zone: mp_fn([a_, m_], parts.corrected["v_" + zone]) for zone in ZONES}
    sheet = dict(zip(ZONES, parts.corrected["sheet"]))
    # continuity along the real axis where the zones meet (|z| = 1 and 1/k), at the exact junctions
    c = parts.corrected
    jumps = mp_fn([m_], [c["v_in"].subs(a_, 1) - c["v_gap"].subs(a_, 1),
                         c["v_gap"].subs(a_, 1 / sp.sqrt(m_)) - c["v_out"].subs(a_, 1 / sp.sqrt(m_))])
    table = CellTable(tol=TOL)
    eps = mp.mpf(10) ** -(DPS - 5)
    with mp.workdps(DPS):
        for cell, zs, ms in _continuation_samples(per_cell(deep)):
            z, m = mp.mpf(zs), mp.mpf(ms)
            f0 = fF(z, m)
            rp = max(finite(f0 - fF(mp.mpc(z, eps), m)), finite(f0 - fF(mp.mpc(z, -eps), m)))
            zone, a = cell["zone"], abs(z)
            v = fv[zone](a, m)
            with mp.workdps(DPS + 10):
                drift = finite(fv[zone](abs(mp.mpf(zs)), mp.mpf(ms)) - v)
            u0 = (1 if z > 0 else -1) * v
            W = mp.sqrt((1 - z * z) * (1 - m * z * z))
            sn, cd = _forward(u0, m, mp.mp.prec)
            if sheet[zone] != cell["sheet"]:  # the other sheet: 2K - u0, sn unchanged, cn dn negated
                cd = -cd
            rc = max(finite(sn - z), finite(cd - cell["sheet"] * W), drift, *(finite(j) for j in jumps(m)))
            table.add(cell, printed=rp, corrected=rc, point={"z": zs, "m": ms, "F(z)": mp.nstr(f0, 12),
                                                             "F(z+i0)-F(z-i0)": mp.nstr(rp, 5)})
    return outcome(table, method=f"numeric: mpmath {DPS} digits (one-sided limits z +- 1e-{DPS - 5} i; Jacobi "
                                 "sn, cn, dn)",
                   printed="F(z,k) for real |z| > 1 via the principal continuation ellipf(asin z, k^2) "
                           "(continuous at z)",
                   corrected="F(z,k) has no canonical value for real |z| > 1 (z on the branch cut of asin; the two "
                             "sides give v and 2K - v). Deterministic continuation: the Abel map of the curve point "
                             "(z, w), w^2 = (1-z^2)(1-k^2 z^2): v = F(|z|) (|z| <= 1), K + i F(asin sqrt((1 - "
                             "z^-2)/k'^2), k'^2) (1 < |z| < 1/k), iK' + F(1/(k|z|)) (|z| >= 1/k), continuous at "
                             "|z| = 1 and 1/k; u = sgn(z) v, whose cn dn is +W, -W, -W (W the principal root), or "
                             "2K - u for the other sheet (symbt.reference.elliptic.abel); the same at DPS and DPS + 10 "
                             "digits",
                   detail="mpmath's value on the cut is one of the one-sided limits, chosen by rounding: it depends "
                          "on mp.dps (e.g. z = 2, m = 3/7: v at 30 and 80 digits, 2K - v at 50)")
