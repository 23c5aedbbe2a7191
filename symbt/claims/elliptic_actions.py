r"""N = 2 action-angle variables and their update (eqs. ``th1th2``, ``AA2``), as data with domain cells.

* ``th1th2.actions`` -- :math:`I_1 = (p_1+p_2)/2`, :math:`I_2 = 2\cosh(q_1-q_2) + ((p_1-p_2)/2)^2` are the
  coefficients of :math:`\operatorname{tr}L(\lambda) = (\lambda+I_1)^2 - I_2` and invariant under the map.
* ``th1th2.F`` -- which F: the reading of "F(z,k)" is a part (the complete integral as printed, the
  incomplete one in Jacobi's form with mpmath's parameter m = k^2 as corrected); the check asks
  F(0,k) = 0, dF/dz = 1/sqrt((1-z^2)(1-k^2 z^2)) and |{I_2, theta_2}| = 1.
* ``th1th2.brackets`` -- {I_j, theta_k} = delta_jk with the printed theta_2 = F(P,k)/sqrt(I2+2) and with
  the global angle F(am, k)/sqrt(I2+2), am = atan2(P, C); gradients are SymPy derivatives of the parts.
* ``AA2.n2`` -- theta~_j = theta_j + dH/dI_j: the integrand and the limits of H are parts; dH/dI_j is the
  integral of the SymPy derivative of the integrand (float64 quadrature, :func:`._elliptic.quad`).
  As corrected, H = int_0^mu Phi dmu' with the real Phi of eq. ``newkmu`` (branch b), continued
  through |tr L| < 2 by principal branches: then theta_1 advances by dH/dI_1 modulo 2 pi i and the
  global theta_2 by dH/dI_2 modulo its period lattice, in every regime.

Where each printed statement holds is generated from the cell tables (see :mod:`._elliptic`).
"""
from __future__ import annotations

import mpmath as mp
import numpy as np
import sympy as sp

from ..proof.cells import CellTable
from ..reference import elliptic as E
from ..reference.literal import signed_arccosh_half
from ._common import per_cell
from ._elliptic import (
    DPS,
    I1,
    I2,
    QTOL,
    TOL,
    F_sym,
    branch,
    breaks,
    finite,
    image,
    lam,
    lam0,
    map_samples,
    mp_fn,
    mu,
    np_fn,
    outcome,
    p1,
    p2,
    phase_samples,
    point,
    pq_point,
    q1,
    q2,
    quad_many,
    state,
)
from .base import Parts, claim

PQ = [p1, p2, q1, q2]
z, t = sp.symbols("z t", real=True)
k = sp.Symbol("k", positive=True)
Ps, Cs = sp.symbols("P C", real=True)
I1_EXPR = (p1 + p2) / 2
I2_EXPR = 2 * sp.cosh(q1 - q2) + ((p1 - p2) / 2) ** 2


# --------------------------------------------------------------------------- th1th2: actions

def _parts_actions() -> Parts:
    return Parts(printed={"I1": I1_EXPR, "I2": I2_EXPR})


@claim("th1th2.actions", equation="th1th2", scene="elliptic", N=2, parts=_parts_actions,
       statement="the actions I1 = (p1+p2)/2 and I2 = 2cosh(q1-q2) + ((p1-p2)/2)^2 (tr L(lambda) = (lambda+I1)^2 - "
                 "I2) are invariant under the map (both branches, every regime of lambda_+-)")
def actions_invariant(parts: Parts, deep: bool = False):
    fI = [mp_fn(PQ, parts.printed[n]) for n in ("I1", "I2")]
    table = CellTable(tol=TOL)
    with mp.workdps(DPS):
        for s in map_samples(per_cell(deep)):
            st, im = state(s), image(s)
            a = [f(*st.p, *st.q) for f in fI]
            at = [f(*im.pt, *im.qt) for f in fI]
            tr = [(st.lam0 + sg * st.mu + a[0]) ** 2 - a[1] for sg in (1, -1)]
            r = max(max(finite(x - y) / max(1, abs(x)) for x, y in zip(a, at)),
                    max(finite(x - y) / max(1, abs(y)) for x, y in zip(tr, im.tr)))
            table.add(s.cell, printed=r, point=point(s, I1=a[0], I2=a[1]))
    return outcome(table, method=f"numeric: the map at {DPS} digits (complex images included)",
                   printed="I(p~, q~) = I(p, q) and tr L(lambda_1,2) = (lambda_1,2 + I1)^2 - I2",
                   detail="I2 of a complex image is evaluated at the complex q~ (principal logarithms of e^{q~})")


# --------------------------------------------------------------------------- th1th2: which F

def _parts_F() -> Parts:
    k2 = (I2 - 2) / (I2 + 2)
    return Parts(printed={"F": sp.elliptic_k(k ** 2), "k2": k2},
                 corrected={"F": sp.elliptic_f(sp.asin(z), k ** 2), "k2": k2},
                 context={"integrand": 1 / sp.sqrt((1 - t ** 2) * (1 - k ** 2 * t ** 2)),
                          "modulus_as_parameter": sp.elliptic_f(sp.asin(z), k)})


def _grads(exprs: list):
    """The gradients of ``exprs`` (functions of p1, p2, q1, q2) as one mpmath function."""
    return mp_fn(PQ, [[sp.diff(e, v) for v in PQ] for e in exprs])


def _pb(a: list, b: list):
    """{f, g} from the gradients (df/dp1, df/dp2, df/dq1, df/dq2), (dg/dp1, ...)."""
    return a[0] * b[2] + a[1] * b[3] - a[2] * b[0] - a[3] * b[1]


P_EXPR = (p2 - p1) / (2 * sp.sqrt(I2_EXPR - 2))


def _F_residuals(F, k2, integrand, samples):
    """Per state: max(|F(0,k)|, |dF/dz - integrand| at z = P, ||{I2, theta2}| - 1|), theta2 = F(P,k)/sqrt(I2+2).

    {I2, theta2} = F_z(P, k) {I2, P}/sqrt(I2 + 2): the k(I2)-dependence drops out since {I2, I2} = 0.
    """
    Fz = sp.diff(F, z)
    res = mp_fn([z, k], [F.subs(z, 0), Fz - integrand.subs(t, z), Fz])
    kf = mp_fn([I2], sp.sqrt(k2))
    grads = _grads([I2_EXPR, P_EXPR])
    for cell, (p, q) in samples:
        x = [mp.mpf(v) for v in p + q]
        gI2, gP = grads(*x)
        a2 = 2 * mp.cosh(x[2] - x[3]) + ((x[0] - x[1]) / 2) ** 2
        F0, dF, fz = res((x[1] - x[0]) / (2 * mp.sqrt(a2 - 2)), kf(a2))
        b = fz * _pb(gI2, gP) / mp.sqrt(a2 + 2)
        yield cell, x, max(finite(F0), finite(dF), finite(abs(b) - 1)), b


@claim("th1th2.F", equation="th1th2", scene="elliptic", N=2, parts=_parts_F,
       statement="F(z,k) in theta2 = F(P,k)/sqrt(I2+2) 'is the complete elliptic integral of the first kind' with "
                 "modulus k, k^2 = (I2-2)/(I2+2)")
def which_F(parts: Parts, deep: bool = False):
    samples = phase_samples(per_cell(deep))
    ig = parts.context["integrand"]
    table = CellTable(tol=TOL)
    with mp.workdps(DPS):
        pr = _F_residuals(parts.printed["F"], parts.printed["k2"], ig, samples)
        co = _F_residuals(parts.corrected["F"], parts.corrected["k2"], ig, samples)
        for (cell, x, rp, b), (_, _, rc, _) in zip(pr, co):
            table.add(cell, printed=rp, corrected=rc, point=pq_point(x[:2], x[2:], **{"{I2,theta2}": b}))
        alt = max(r for *_, r, _ in _F_residuals(parts.context["modulus_as_parameter"], parts.corrected["k2"], ig,
                                                 samples))
    return outcome(table, method=f"numeric: SymPy derivatives of the F reading at {DPS} digits",
                   printed="F(z,k) = K(k), the complete integral (no z-dependence)",
                   corrected="F(z,k) = int_0^z dt/sqrt((1-t^2)(1-k^2 t^2)) = mpmath.ellipf(asin z, m=k^2), the "
                             "INCOMPLETE integral in Jacobi's form (k = modulus; mpmath and Arb take the parameter "
                             "m = k^2); |P| <= 1 on the whole real phase space",
                   detail="checked per state: F(0,k) = 0, dF/dz = the Jacobi integrand at z = P, |{I2, theta2}| = 1. "
                          f"Passing the modulus as mpmath's parameter (ellipf(asin z, k)) fails the same check "
                          f"(worst residual {mp.nstr(alt, 3)})")


# --------------------------------------------------------------------------- th1th2: brackets

def _parts_brackets() -> Parts:
    k2 = (I2 - 2) / (I2 + 2)
    base = {"I1": I1_EXPR, "I2": I2_EXPR, "theta1": q1 + q2}
    return Parts(printed=dict(base, theta2=sp.elliptic_f(sp.asin(Ps), k2) / sp.sqrt(I2 + 2)),
                 corrected=dict(base, theta2=sp.elliptic_f(sp.atan2(Ps, Cs), k2) / sp.sqrt(I2 + 2)),
                 context={"P": (p2 - p1) / (2 * sp.sqrt(I2 - 2)), "C": 2 * sp.sinh((q1 - q2) / 2) / sp.sqrt(I2 - 2)})


def _bracket_residual(d: dict, ctx: dict):
    """(p, q) -> (max |{I_j, theta_k} - delta_jk|, |{I1,I2}|, |{theta1,theta2}|;  {I2, theta2}).

    theta2 = G(P, C, I2) is differentiated by the chain rule: grad theta2 = G_P grad P + G_C grad C +
    G_I2 grad I2.  The last term enters {f, theta2} as G_I2 {f, I2}, f = I1, theta1: it is evaluated only
    when some |{f, I2}| > 1e-25 (otherwise it is below 1e-24, and {f, I2} itself is part of the residual).
    """
    base = [d["I1"], d["I2"], d["theta1"], ctx["P"].subs(I2, d["I2"]), ctx["C"].subs(I2, d["I2"])]
    grads = _grads(base)
    G = mp_fn([Ps, Cs, I2], [sp.diff(d["theta2"], Ps), sp.diff(d["theta2"], Cs)])
    GI: list = []
    Pf, Cf, mp_I2 = mp_fn(PQ, base[3]), mp_fn(PQ, base[4]), mp_fn(PQ, d["I2"])

    def residual(*x):
        gI1, gI2, gt1, gP, gC = grads(*x)
        a2 = mp_I2(*x)
        args = (Pf(*x), Cf(*x), a2)
        GP, GC = G(*args)
        gt2 = [GP * a + GC * b for a, b in zip(gP, gC)]
        side = [_pb(gI1, gI2), _pb(gt1, gI2)]
        if max(finite(v) for v in side) > 1e-25:
            if not GI:
                GI.append(mp_fn([Ps, Cs, I2], sp.diff(d["theta2"], I2)))
            gt2 = [v + GI[0](*args) * c for v, c in zip(gt2, gI2)]
        br = [_pb(gI1, gt1) - 1, _pb(gI1, gt2), _pb(gI2, gt1), _pb(gI2, gt2) - 1, side[0], _pb(gt1, gt2)]
        return max(finite(v) for v in br), br[3] + 1

    return residual


@claim("th1th2.brackets", equation="th1th2", scene="elliptic", N=2, parts=_parts_brackets,
       statement="{I_j, theta_k} = delta_jk (eq. AA for N=2) for I1, I2, theta1 = q1+q2, theta2 = F(P,k)/sqrt(I2+2); "
                 "also {I1, I2} = {theta1, theta2} = 0")
def brackets(parts: Parts, deep: bool = False):
    rp = _bracket_residual(parts.printed, parts.context)
    rc = _bracket_residual(parts.corrected, parts.context)
    table = CellTable(tol=TOL)
    with mp.workdps(DPS):
        for cell, (p, q) in phase_samples(per_cell(deep)):
            x = [mp.mpf(v) for v in p + q]
            (r1, b), (r2, _) = rp(*x), rc(*x)
            table.add(cell, printed=r1, corrected=r2, point=pq_point(x[:2], x[2:], **{"{I2,theta2}": b}))
    return outcome(table, method=f"numeric: SymPy gradients of the parts (chain rule through P, C, I2) at {DPS} "
                                 "digits",
                   printed="{I_j, theta_k} = delta_jk with theta2 = F(P,k)/sqrt(I2+2)",
                   corrected="the global angle theta2 = F(am, k)/sqrt(I2+2), am = atan2(P, C), C = 2sinh((q1-q2)/2)/"
                             "sqrt(I2-2) (sn u = P, cn u = C, u mod 4K) is canonical: {I_j, theta_k} = delta_jk, "
                             "{I1,I2} = {theta1,theta2} = 0; the printed F(P,k)/sqrt(I2+2) equals it where C > 0",
                   detail="the printed theta2 is not differentiable at q1 = q2 (P = +-1), where the orbit turns")


# --------------------------------------------------------------------------- AA2

T_EXPR = (lam + I1) ** 2 - I2


def _parts_aa2() -> Parts:
    return Parts(printed={"integrand": sp.acosh(T_EXPR / 2), "lower": lam0 + mu, "upper": lam0 - mu},
                 corrected={"integrand": -branch * signed_arccosh_half(T_EXPR, ns=sp),
                            "lower": lam0 - mu, "upper": lam0 + mu})


def _dH(d: dict, samples) -> list[np.ndarray]:
    """[dH/dI1, dH/dI2] at every sample: the integral over [lower, upper] of the SymPy derivative of the
    integrand (DiracDelta from sign -> 0), by :func:`._elliptic.quad_many`."""
    lims = mp_fn([lam0, mu], [d["lower"], d["upper"]])
    jobs = []
    for s in samples:
        st = state(s)
        a1, a2 = float(st.I1), float(st.I2)
        lo, hi = (float(v) for v in lims(st.lam0, st.mu))
        jobs.append((lo, hi, breaks(a1, a2), (a1, a2, s.b)))
    return [quad_many(np_fn([lam, I1, I2, branch], sp.diff(d["integrand"], a)), jobs) for a in (I1, I2)]


@claim("AA2.n2", equation="AA2", scene="elliptic", N=2, parts=_parts_aa2,
       statement="theta~_j = theta_j + d/dI_j int_{l0+mu}^{l0-mu} arccosh(((lambda+I1)^2 - I2)/2) dlambda, j=1,2 "
                 "(Theorem 2 for N=2)")
def aa2(parts: Parts, deep: bool = False):
    samples = map_samples(per_cell(deep))
    h1, h2 = _dH(parts.printed, samples)
    g1, g2 = _dH(parts.corrected, samples)
    th2p = mp_fn([Ps, I2], F_sym(Ps) / sp.sqrt(I2 + 2))
    table = CellTable(tol=QTOL)
    with mp.workdps(DPS), np.errstate(all="ignore"):
        for i, s in enumerate(samples):
            st, im = state(s), image(s)
            d1 = complex(im.qt[0] + im.qt[1] - st.q[0] - st.q[1])
            d2 = complex(th2p(im.Pt, st.I2) - th2p(st.P, st.I2))
            rp = max(abs(h1[i] - d1) / max(1, abs(d1)), abs(h2[i] - d2) / max(1, abs(d2)))
            ratio = complex(im.Et[0] * im.Et[1] / (st.E[0] * st.E[1]))
            rc1 = abs(np.exp(g1[i]) - ratio) / abs(ratio)
            rc2 = E.lattice_residual(im.ut - st.u - mp.sqrt(st.I2 + 2) * mp.mpc(g2[i]), st.m)
            table.add(s.cell, printed=float(finite(rp)), corrected=float(max(finite(rc1), finite(rc2))),
                      point=point(s, dH_dI1=mp.mpc(h1[i]), dtheta1=mp.mpc(d1), dH_dI2=mp.mpc(h2[i]),
                                  dtheta2=mp.mpc(d2)))
    return outcome(table, method="numeric: float64 Gauss-Legendre of the SymPy derivative of the integrand (96 nodes "
                                 f"per piece between the zeros of tr L -+ 2), the map at {DPS} digits",
                   printed="theta~_j = theta_j + d/dI_j int_{l0+mu}^{l0-mu} arccosh(((lambda+I1)^2-I2)/2) dlambda, "
                           "printed theta2 = F(P,k)/sqrt(I2+2), as complex numbers (principal branches)",
                   corrected="H = int_0^mu Phi dmu' = -b int_{l0-mu}^{l0+mu} sgn(T) arccosh(|T|/2) dlambda, T = "
                             "(lambda+I1)^2 - I2, the real Phi of eq. newkmu (branch b) continued by principal "
                             "branches where |T| < 2: e^{theta~1 - theta1} = e^{dH/dI1} and the global angle "
                             "(u~ - u)/sqrt(I2+2) = dH/dI2 modulo the periods (4K, 2iK')/sqrt(I2+2); this confirms "
                             "Theorem 2 for N=2 in every regime",
                   detail=f"tolerance {QTOL:g} (float64 quadrature)")
