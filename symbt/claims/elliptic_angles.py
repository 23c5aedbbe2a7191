r"""N = 2: the update of the angles by one step and by n steps (eqs. ``citn``, ``linBts``), as data with cells.

Printed statements are evaluated as printed -- principal ``arccosh``, ``asin`` and ``ellipf`` of
mpmath, the printed angle :math:`\theta_2 = F(P,k)/\sqrt{I_2+2}`, :math:`\theta_1 = q_1 + q_2` with the
map's principal logarithms -- and compared as complex numbers.  The corrected statements are
branch-free and hold in every regime:

* :math:`e^{\tilde\theta_1-\theta_1} = v(\lambda_1)\,v(\lambda_2)`,
  :math:`v_1 = (\operatorname{tr}_1 - b\sqrt{\operatorname{tr}_1^2-4})/2`,
  :math:`v_2 = (\operatorname{tr}_2 + b\sqrt{\operatorname{tr}_2^2-4})/2` (eq. ``v1v2``); where both traces have
  the same sign this is :math:`\tilde\theta_1 = \theta_1 + b(g(\operatorname{tr}_2) - g(\operatorname{tr}_1))`,
  :math:`g(T) = \operatorname{sgn}(T)\operatorname{arccosh}(|T|/2)`;
* the global angle :math:`\theta_2 = u/\sqrt{I_2+2}` advances by
  :math:`(\mathcal A(\lambda_0+\mu) - \mathcal A(\lambda_0-\mu))/\sqrt{I_2+2}` modulo its periods, with the
  Abel image :math:`\mathcal A` of the spectral-curve point :math:`(\lambda, b\sqrt{\operatorname{tr}^2-4})`
  used by the map (``A`` in the parts, :func:`symbt.reference.elliptic.abel`).  Where the map is real
  this reads :math:`b(F_r(\lambda_+) - F_r(\lambda_-))`, :math:`F_r(s) = F(s,k)` on :math:`|s|\le1` and
  :math:`-F(1/(ks),k)` on :math:`|s|\ge 1/k` (see ``addform.arb_real``).
"""
from __future__ import annotations

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
    next_state,
    outcome,
    p1,
    p2,
    point,
    q1,
    q2,
    state,
    tr1,
    tr2,
)
from .base import Parts, claim

PQ = [p1, p2, q1, q2]
Ps = sp.Symbol("P", real=True)
TR = {"tr1": (lam0 + mu + I1) ** 2 - I2, "tr2": (lam0 - mu + I1) ** 2 - I2}
PRINTED_D1 = sp.acosh(((lam0 - mu + I1) ** 2 - I2) / 2) - sp.acosh(((lam0 + mu + I1) ** 2 - I2) / 2)
PRINTED_D2 = (F_sym((lam0 - mu + I1) / sp.sqrt(I2 - 2)) - F_sym((lam0 + mu + I1) / sp.sqrt(I2 - 2))) / sp.sqrt(I2 + 2)
V1 = (tr1 - branch * sp.sqrt(tr1 ** 2 - 4)) / 2
V2 = (tr2 + branch * sp.sqrt(tr2 ** 2 - 4)) / 2
ABEL_D2 = (A(lam0 + mu, branch, I1, I2) - A(lam0 - mu, branch, I1, I2)) / sp.sqrt(I2 + 2)
STEP = [lam0, mu, I1, I2, branch]


def _theta2_printed():
    return mp_fn([Ps, I2], F_sym(Ps) / sp.sqrt(I2 + 2))


def _v(parts_side: dict, ctx: dict):
    """(lam0, mu, I1, I2, b) -> v(lambda_1) v(lambda_2), with tr_i from the context (tr L = (lambda+I1)^2 - I2)."""
    return mp_fn(STEP, parts_side["v1"].subs(tr1, ctx["tr1"]) * parts_side["v2"].subs(tr2, ctx["tr2"]))


def _args(st, b):
    return st.lam0, st.mu, st.I1, st.I2, b


# --------------------------------------------------------------------------- citn, theta1

def _parts_theta1() -> Parts:
    return Parts(printed={"dtheta1": PRINTED_D1}, corrected={"v1": V1, "v2": V2}, context=dict(TR))


@claim("citn.theta1", equation="citn", scene="elliptic", N=2, parts=_parts_theta1,
       statement="theta~1 = theta1 + arccosh(((l0-mu+I1)^2-I2)/2) - arccosh(((l0+mu+I1)^2-I2)/2)")
def citn_theta1(parts: Parts, deep: bool = False):
    fp = mp_fn(STEP, parts.printed["dtheta1"])
    fv = _v(parts.corrected, parts.context)
    table = CellTable(tol=TOL)
    with mp.workdps(DPS):
        for s in map_samples(per_cell(deep)):
            st, im = state(s), image(s)
            d1 = im.qt[0] + im.qt[1] - st.q[0] - st.q[1]
            pr = fp(*_args(st, s.b))
            lhs, rhs = im.Et[0] * im.Et[1], st.E[0] * st.E[1] * fv(*_args(st, s.b))
            table.add(s.cell, printed=finite(pr - d1) / max(1, abs(d1)),
                      corrected=finite(lhs - rhs) / max(abs(lhs), abs(rhs), 1e-30),
                      point=point(s, printed=pr, measured=d1, tr1=im.tr[0], tr2=im.tr[1]))
    return outcome(table, method=f"numeric: the map at {DPS} digits, principal arccosh/log compared as complex numbers",
                   printed="theta~1 = theta1 + arccosh(tr L(l0-mu)/2) - arccosh(tr L(l0+mu)/2), theta1 = q1 + q2",
                   corrected="e^{theta~1 - theta1} = v(l1) v(l2), v1 = (tr1 - b sqrt(tr1^2-4))/2, v2 = (tr2 + b sqrt("
                             "tr2^2-4))/2 (eq. v1v2), i.e. theta~1 = theta1 + log(v1 v2) mod 2 pi i; where tr1, tr2 "
                             "have one sign: theta~1 = theta1 + b(g(tr2) - g(tr1)), g(T) = sgn(T) arccosh(|T|/2)")


# --------------------------------------------------------------------------- citn, theta2

def _parts_theta2() -> Parts:
    return Parts(printed={"dtheta2": PRINTED_D2}, corrected={"dtheta2": ABEL_D2})


@claim("citn.theta2", equation="citn", scene="elliptic", N=2, parts=_parts_theta2,
       statement="theta~2 = theta2 + (F((l0-mu+I1)/sqrt(I2-2),k) - F((l0+mu+I1)/sqrt(I2-2),k))/sqrt(I2+2)")
def citn_theta2(parts: Parts, deep: bool = False):
    fp, fc = mp_fn(STEP, parts.printed["dtheta2"]), mp_fn(STEP, parts.corrected["dtheta2"])
    th2p = _theta2_printed()
    table = CellTable(tol=TOL)
    with mp.workdps(DPS):
        for s in map_samples(per_cell(deep)):
            st, im = state(s), image(s)
            d2 = th2p(im.Pt, st.I2) - th2p(st.P, st.I2)
            pr = fp(*_args(st, s.b))
            rc = E.lattice_residual(im.ut - st.u - mp.sqrt(st.I2 + 2) * fc(*_args(st, s.b)), st.m)
            table.add(s.cell, printed=finite(pr - d2) / max(1, abs(d2)), corrected=finite(rc) + im.on_curve,
                      point=point(s, printed_increment=pr, measured=d2))
    return outcome(table, method=f"numeric: the map at {DPS} digits, principal ellipf(asin z, k^2) compared as "
                                 "complex numbers; corrected modulo the period lattice (4K, 2iK')",
                   printed="theta~2 = theta2 + (F(lambda_-,k) - F(lambda_+,k))/sqrt(I2+2), theta2 = F(P,k)/sqrt(I2+2)",
                   corrected="with the global angle theta2 = u/sqrt(I2+2) (sn u = P, cn u dn u = 2sinh(q1-q2)/"
                             "sqrt(I2^2-4)): theta~2 = theta2 + (A(l0+mu) - A(l0-mu))/sqrt(I2+2) modulo the periods, "
                             "A = the Abel image of the curve point (lambda, b sqrt(tr L^2-4)) used by the map "
                             "(= dH/dI2 of AA2.n2); where the map is real, b(Fr(lambda_+) - Fr(lambda_-))/sqrt(I2+2)")


# --------------------------------------------------------------------------- linBts

N_ITERATES = 3


@cache
def _orbit(key: tuple, b: int, n: int, dps: int) -> tuple:
    """The first ``n`` images of the sample's state (complex where the map is not real), with the curve
    points (gamma_1, gamma_2) of the first step (tr L is invariant; see ``step2``)."""
    from ._elliptic import _image, _state

    st = _state(key, dps)
    out = [_image(key, b, dps)]
    with mp.workdps(dps):
        while len(out) < n:
            out.append(next_state(out[-1].pt, out[-1].qt, st, b, out[0].gammas))
    return tuple(out)


def _parts_lin() -> Parts:
    acts = {"I1": (p1 + p2) / 2, "I2": 2 * sp.cosh(q1 - q2) + ((p1 - p2) / 2) ** 2}
    return Parts(printed=dict(acts, dtheta1=PRINTED_D1, dtheta2=PRINTED_D2),
                 corrected=dict(acts, v1=V1, v2=V2, dtheta2=ABEL_D2), context=dict(TR))


@claim("linBts", equation="linBts", scene="elliptic", N=2, parts=_parts_lin,
       statement="over n iterates: I_n = I_0, (theta1)_n = (theta1)_0 + n*dtheta1, (theta2)_n = (theta2)_0 + n*dtheta2 "
                 "with the increments of eq. citn")
def lin_bts(parts: Parts, deep: bool = False):
    th2p = _theta2_printed()
    sides = {}
    for side in ("printed", "corrected"):
        d = getattr(parts, side)
        sides[side] = (mp_fn(PQ, [d["I1"], d["I2"]]), mp_fn(STEP, d["dtheta2"]),
                       mp_fn(STEP, d["dtheta1"]) if side == "printed" else _v(d, parts.context))
    def residuals(st, orbit, b):
        res = {}
        for side, (fI, f2, f1) in sides.items():
            I0 = fI(*st.p, *st.q)
            c2, c1 = f2(*_args(st, b)), f1(*_args(st, b))
            r = 0
            for n, im in enumerate(orbit, start=1):
                In = fI(*im.pt, *im.qt)
                r = max(r, *(finite(a - b_) / max(1, abs(a)) for a, b_ in zip(I0, In)))
                if side == "printed":
                    d1 = im.qt[0] + im.qt[1] - st.q[0] - st.q[1]
                    d2 = th2p(im.Pt, st.I2) - th2p(st.P, st.I2)
                    r = max(r, finite(d1 - n * c1) / max(1, abs(d1)), finite(d2 - n * c2) / max(1, abs(d2)))
                else:
                    lhs, rhs = im.Et[0] * im.Et[1], st.E[0] * st.E[1] * c1 ** n
                    r = max(r, finite(lhs - rhs) / max(abs(lhs), abs(rhs), 1e-30), im.on_curve,
                            finite(E.lattice_residual(im.ut - st.u - n * mp.sqrt(st.I2 + 2) * c2, st.m)))
            res[side] = r
        return res

    table = CellTable(tol=TOL)
    rechecked = 0
    for s in map_samples(per_cell(deep)):
        with mp.workdps(DPS):
            res = residuals(state(s), _orbit(s.key, s.b, N_ITERATES, DPS), s.b)
        if res["corrected"] > TOL:
            # iterating the map loses digits where it is ill-conditioned (e.g. the mixed regime): a failure
            # of the statement survives 30 more digits, a loss of precision does not
            rechecked += 1
            with mp.workdps(DPS + 30):
                res = residuals(state(s, DPS + 30), _orbit(s.key, s.b, N_ITERATES, DPS + 30), s.b)
        table.add(s.cell, printed=res["printed"], corrected=res["corrected"], point=point(s))
    return outcome(table, method=f"numeric: {N_ITERATES} iterates of the map at {DPS} digits",
                   printed="(theta_j)_n = (theta_j)_0 + n*(printed citn increment), theta2 = F(P,k)/sqrt(I2+2), "
                           "as complex numbers",
                   corrected="I_n = I_0; e^{(theta1)_n - (theta1)_0} = (v(l1) v(l2))^n; the global angle "
                             "(theta2)_n = (theta2)_0 + n (A(l0+mu) - A(l0-mu))/sqrt(I2+2) modulo its periods "
                             "(citn.theta2): sn(u_0 + n du) = P_n",
                   detail=f"n = 1..{N_ITERATES} on every sample ({rechecked} whose corrected residual exceeded "
                          f"{TOL:g} at {DPS} digits re-evaluated at {DPS + 30}); the printed "
                          "theta2 = F(P,k)/sqrt(I2+2) is bounded by K/sqrt(I2+2) on real orbits and cannot grow "
                          "linearly: it must be the global angle, taken modulo its period")
