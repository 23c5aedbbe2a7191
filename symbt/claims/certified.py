r"""Certified (Arb ball arithmetic) checks of the N = 2 addition formula, eq. ``addform``, with domain cells.

Optional extra ``python-flint``; the claims declare ``requires=("flint",)`` and are ``skipped`` without it.
The samples are those of the mpmath claims (:func:`symbt.claims._elliptic.map_samples`: regime x branch x
sign of q1 - q2).  Everything runs in acb/arb balls from the exact decimal inputs: the map
(:func:`arb_step`, the one place with the Arb version of the step), the actions, the global angle, the
Abel images of the two spectral-curve points and Jacobi's sn, cn, dn from Arb's theta functions
(``acb.modular_theta``, which includes the factor pi in its argument):

.. math:: \tau = iK'/K,\ z = u/(2K):\quad
          \operatorname{sn}u = \frac{\theta_3}{\theta_2}\frac{\theta_1(z)}{\theta_4(z)},\
          \operatorname{cn}u = \frac{\theta_4}{\theta_2}\frac{\theta_2(z)}{\theta_4(z)},\
          \operatorname{dn}u = \frac{\theta_4}{\theta_3}\frac{\theta_3(z)}{\theta_4(z)}.

The statement parts (SymPy) are evaluated in balls by :func:`arb_fn`.  Per sample a statement
*holds* if every residual ball contains 0 with radius <= 1e-30, *fails with a certificate* if a ball
excludes 0, and fails as *undecided* if a ball is wider (or not finite: e.g. the principal F on its
branch cut, where Arb returns an indeterminate ball).  The choice between the two Abel images
u, 2K - u is made on midpoints; a wrong choice could only produce a ball excluding 0, never a false pass.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace
from functools import cache

import sympy as sp

from ._common import per_cell
from ._elliptic import I1, I2, A, F_sym, ScopedTable, branch, lam0, map_samples, mu, outcome, point, tr1, tr2
from .base import Parts, claim, scene

scene("certified", "Arb ball-arithmetic certificates for the N=2 addition formula (optional extra python-flint)")

PREC = 170  # bits (~51 digits)
RAD = 1e-30  # a ball containing 0 certifies the identity at this radius
Ps, Pts = sp.symbols("P Pt", real=True)
Fr = sp.Function("Fr")  # the real antiderivative Fr(lambda, I1, I2) of 1/|w| (see elliptic_angles)
LAM_P, LAM_M = (lam0 + mu + I1) / sp.sqrt(I2 - 2), (lam0 - mu + I1) / sp.sqrt(I2 - 2)


class _prec:
    def __init__(self, bits):
        self.bits = bits

    def __enter__(self):
        from flint import ctx

        self.old = ctx.prec
        ctx.prec = self.bits

    def __exit__(self, *exc):
        from flint import ctx

        ctx.prec = self.old


def _ball(v):
    from flint import acb, arb

    return acb(arb(v)) if isinstance(v, str) else acb(v)


def arb_step(p, q, lam0_, mu_, b):
    """The map (N = 2) in acb balls from decimal strings: (p~, e^{q~}).

    This is :func:`symbt.numeric.core.step.step_core` -- the step written once against an
    arithmetic context -- run on python-flint's complex balls (:data:`symbt.numeric.multiprec.arb.ACB`,
    principal branches, the complex continuation where the real map does not exist).
    Its choices between algebraically equal formulas are made on midpoints, so every
    ball still encloses the exact image.
    """
    from ..numeric.core.step import step_core
    from ..numeric.multiprec.arb import ACB

    P, Q = [_ball(v) for v in p], [_ball(v) for v in q]
    Pn, Qn, _ = step_core(ACB, P, Q, _ball(lam0_), _ball(mu_), b, check_real=False)
    return list(Pn), [x.exp() for x in Qn]


class Jacobi:
    """sn, cn, dn for parameter m (a ball) from Arb's theta functions; the Abel map on balls."""

    def __init__(self, m):
        from flint import acb

        self.m = m
        self.K = acb(m).elliptic_k()
        self.Kp = acb(1 - m).elliptic_k()
        self.tau = acb(0, 1) * self.Kp / self.K
        _, self.t2, self.t3, self.t4 = acb(0).modular_theta(self.tau)

    def sncndn(self, u):
        th1, th2, th3, th4 = (u / (2 * self.K)).modular_theta(self.tau)
        return (self.t3 / self.t2 * th1 / th4, self.t4 / self.t2 * th2 / th4, self.t4 / self.t3 * th3 / th4)

    def abel(self, s, w):
        """u with sn u = s, cn u dn u = w, as :func:`symbt.reference.elliptic.abel` (real s balls)."""
        from flint import acb

        sr = s.real
        sg = 1 if float(sr.mid()) >= 0 else -1
        a = sg * sr
        k = self.m.real.sqrt()
        if float(a.mid()) <= 1:
            v = acb.elliptic_f(acb(a.asin()), self.m)
        elif float((k * a).mid()) < 1:
            t = ((1 - 1 / a ** 2) / (1 - self.m.real)).sqrt()
            v = self.K + acb(0, 1) * acb.elliptic_f(acb(t.asin()), 1 - self.m)
        else:
            v = acb(0, 1) * self.Kp + acb.elliptic_f(acb((1 / (k * a)).asin()), self.m)
        u0 = sg * v
        _, c, d = self.sncndn(u0)
        cd = c * d
        return u0 if abs((cd - w).mid()) <= abs((cd + w).mid()) else 2 * self.K - u0

    def Fr(self, s):
        """Fr(s) = F(s) on |s| <= 1, -F(1/(ks)) on |s| >= 1/k (real balls); indeterminate in the gap."""
        from flint import acb

        a = abs(float(s.real.mid()))
        if a <= 1:
            return acb.elliptic_f(acb(s.real.asin()), self.m)
        if a * float(self.m.real.mid()) ** 0.5 >= 1:
            return -acb.elliptic_f(acb((1 / (self.m.real.sqrt() * s.real)).asin()), self.m)
        return acb("nan")


def arb_fn(e, fns: dict):
    """A SymPy expression compiled once into a function of an environment {symbol: acb ball}; undefined
    functions (A, Fr) from ``fns``.  Integers and rationals stay exact (no floats)."""
    from flint import acb

    def comp(x):
        if isinstance(x, sp.Symbol):
            return lambda env: env[x]
        if x is sp.I:
            return lambda env: acb(0, 1)
        if isinstance(x, sp.Integer):
            n = int(x)
            return lambda env: acb(n)
        if isinstance(x, sp.Rational):
            a, b_ = int(x.p), int(x.q)
            return lambda env: acb(a) / b_
        cs = [comp(a) for a in x.args]
        if isinstance(x, sp.Add):
            return lambda env: sum((c(env) for c in cs[1:]), cs[0](env))
        if isinstance(x, sp.Mul):
            def mul(env):
                out = cs[0](env)
                for c in cs[1:]:
                    out = out * c(env)
                return out
            return mul
        if isinstance(x, sp.Pow):
            n = x.exp
            if n == sp.Rational(1, 2):
                return lambda env: cs[0](env).sqrt()
            if n == -sp.Rational(1, 2):
                return lambda env: 1 / cs[0](env).sqrt()
            if isinstance(n, sp.Integer):
                k = int(n)
                return lambda env: cs[0](env) ** k
            return lambda env: (cs[1](env) * cs[0](env).log()).exp()
        if isinstance(x, sp.elliptic_f):
            return lambda env: acb.elliptic_f(cs[0](env), cs[1](env))
        if isinstance(x, sp.elliptic_k):
            return lambda env: cs[0](env).elliptic_k()
        for f in (sp.asin, sp.exp, sp.log, sp.cosh, sp.sinh):
            if isinstance(x, f):
                name = f.__name__
                return lambda env: getattr(cs[0](env), name)()
        g = x.func.__name__
        return lambda env: fns[g](env)(*(c(env) for c in cs))

    return comp(sp.sympify(e))


def _finite(x) -> bool:
    return all(math.isfinite(float(v)) for v in (x.real.mid(), x.imag.mid(), x.real.rad(), x.imag.rad()))


UNDECIDED = 1e-20  # residual of a ball that is not finite or too wide: no certificate either way


def _residual(balls) -> float:
    """<= RAD: every ball contains 0 (the max radius); > RAD: a ball excludes 0 (a certified failure, the lower
    bound of its modulus, at least 10 RAD) or a ball is not finite / too wide (:data:`UNDECIDED`)."""
    if not all(_finite(x) for x in balls):
        return UNDECIDED
    for x in balls:
        if not x.contains(0):
            return max(float(abs(x).abs_lower()), 10 * RAD)
    rad = max(max(float(x.real.rad()), float(x.imag.rad())) for x in balls)
    return rad if rad <= RAD else UNDECIDED


@cache
def _case(key: tuple, b: int, prec: int) -> dict:
    """Arb data of one sample: actions, Jacobi, u, the image, P~, w~ (balls)."""
    from flint import acb, arb

    with _prec(prec):
        (ps, qs, l0s, mus) = key
        p, q = [arb(v) for v in ps], [arb(v) for v in qs]
        a1, a2 = (p[0] + p[1]) / 2, 2 * (q[0] - q[1]).cosh() + ((p[0] - p[1]) / 2) ** 2
        J = Jacobi(acb((a2 - 2) / (a2 + 2)))
        r, sq = (a2 - 2).sqrt(), (a2 ** 2 - 4).sqrt()
        P = (p[1] - p[0]) / (2 * r)
        C = 2 * ((q[0] - q[1]) / 2).sinh() / r
        v = acb.elliptic_f(acb(P.asin()), J.m)
        u = v if float(C.mid()) >= 0 else ((2 * J.K - v) if float(P.mid()) >= 0 else (-2 * J.K - v))
        pt, Et = arb_step(ps, qs, l0s, mus, b)
        ratio = Et[0] / Et[1]
        return dict(p=p, q=q, I1=acb(a1), I2=acb(a2), J=J, r=acb(r), P=acb(P), C=C, u=u, pt=pt, Et=Et,
                    Pt=(pt[1] - pt[0]) / (2 * r), wt=(ratio - 1 / ratio) / sq, sq=acb(sq),
                    lam0=acb(arb(l0s)), mu=acb(arb(mus)), b=b)


def _env(c: dict) -> dict:
    from flint import acb

    return {Ps: c["P"], Pts: c["Pt"], lam0: c["lam0"], mu: c["mu"], I1: c["I1"], I2: c["I2"], branch: acb(c["b"]),
            "J": c["J"]}


def _abel_fn(env: dict):
    J = env["J"]

    def A_(lam, b, a1, a2):
        T = (lam + a1) ** 2 - a2
        w = (1 if b.real > 0 else -1) * (T ** 2 - 4).sqrt() / (a2 ** 2 - 4).sqrt()
        return J.abel((lam + a1) / (a2 - 2).sqrt(), w)

    return A_


FNS = {"A": _abel_fn, "Fr": lambda env: (lambda lam, a1, a2: env["J"].Fr((lam + a1) / (a2 - 2).sqrt()))}


def _cert_outcome(table, t0: float, n: int, **kw):
    out = outcome(table, dps=int(PREC * 0.30103), **kw)
    rate = n / (time.perf_counter() - t0)
    out = replace(out, evidence="certified", detail=(out.detail + f" Arb {PREC} bits, {rate:.0f} samples/s.").strip())
    return out


# --------------------------------------------------------------------------- addform.arb

def _parts_arb() -> Parts:
    return Parts(printed={"lhs": F_sym(Pts), "rhs": F_sym(Ps) + F_sym(LAM_M) - F_sym(LAM_P)},
                 corrected={"shift": A(lam0 + mu, branch, I1, I2) - A(lam0 - mu, branch, I1, I2),
                            "v1": (tr1 - branch * sp.sqrt(tr1 ** 2 - 4)) / 2,
                            "v2": (tr2 + branch * sp.sqrt(tr2 ** 2 - 4)) / 2},
                 context={"tr1": (lam0 + mu + I1) ** 2 - I2, "tr2": (lam0 - mu + I1) ** 2 - I2})


@claim("addform.arb", equation="addform", scene="certified", N=2, requires=("flint",), parts=_parts_arb,
       statement="addition formula (eq. addform), as printed and in the corrected branch-free form, certified "
                 "with Arb ball arithmetic from exact inputs (map, actions, Abel images, theta-function sn/cn/dn)")
def addform_arb(parts: Parts, deep: bool = False):
    table = ScopedTable(tol=RAD)
    samples = map_samples(per_cell(deep))
    t0 = time.perf_counter()
    with _prec(PREC):
        v12 = arb_fn(parts.corrected["v1"].subs(tr1, parts.context["tr1"])
                     * parts.corrected["v2"].subs(tr2, parts.context["tr2"]), FNS)
        pr, shift = arb_fn(parts.printed["lhs"] - parts.printed["rhs"], FNS), arb_fn(parts.corrected["shift"], FNS)
        undecided = 0
        for s in samples:
            c = _case(s.key, s.b, PREC)
            env = _env(c)
            rp = _residual([pr(env)])
            undecided += rp == UNDECIDED
            sn, cn, dn = c["J"].sncndn(c["u"] + shift(env))
            E12 = (c["q"][0] + c["q"][1]).exp() * v12(env)
            rc = _residual([sn - c["Pt"], cn * dn - c["wt"], c["Et"][0] * c["Et"][1] - E12])
            table.add(s.cell, printed=rp, corrected=rc, point=point(s, printed_residual=rp))
    return _cert_outcome(table, t0, len(samples), method=f"certified: Arb {PREC} bits, residual balls",
                         printed="F(P~,k) = F(P,k) + F(lambda_-,k) - F(lambda_+,k) (principal F in Arb; indeterminate "
                                 "on the cut |z| > 1)",
                         corrected="sn(u + A(l0+mu) - A(l0-mu)) = P~, cn dn(...) = 2sinh(q~1-q~2)/sqrt(I2^2-4), "
                                   "e^{q~1+q~2} = e^{q1+q2} v(l1) v(l2) (claim addform.n2)",
                         detail=f"the printed formula is undecided (a ball not finite: an F argument on the cut "
                                f"|z| > 1) at {undecided}/{len(samples)} samples; elsewhere it fails by a ball "
                                "excluding 0 or holds.")


# --------------------------------------------------------------------------- addform.arb_real

def _parts_arb_real() -> Parts:
    return Parts(printed={"shift": branch * (Fr(lam0 + mu, I1, I2) - Fr(lam0 - mu, I1, I2))})


def _real_image(c: dict) -> bool | None:
    """True: p~ real and every e^{q~_j} > 0 (certified); False: certified not; None: undecided."""
    if all(x.imag.is_zero() for x in c["pt"] + c["Et"]) and all(x.real > 0 for x in c["Et"]):
        return True
    if any(not x.imag.contains(0) for x in c["pt"] + c["Et"]) or any(x.real < 0 for x in c["Et"]):
        return False
    return None


@claim("addform.arb_real", equation="addform", scene="certified", N=2, requires=("flint",), parts=_parts_arb_real,
       statement="real form of the corrected addition formula certified with acb.elliptic_f / elliptic_k: "
                 "u(P~, C~) - u(P, C) - b(Fr(lambda_+) - Fr(lambda_-)) contains 0 mod 4K where the real map exists")
def addform_arb_real(parts: Parts, deep: bool = False):
    from flint import acb, arb

    table = ScopedTable(tol=RAD)
    samples = map_samples(per_cell(deep))
    shift = arb_fn(parts.printed["shift"], FNS)
    t0 = time.perf_counter()
    with _prec(PREC):
        for s in samples:
            c = _case(s.key, s.b, PREC)
            real = _real_image(c)
            if real is False:
                table.add_na(s.cell, "no real image: p~ complex or some e^{q~_j} < 0, certified")
                continue
            J = c["J"]
            Ct = 2 * ((c["Et"][0] / c["Et"][1]).real.log() / 2).sinh() / c["r"].real
            u1 = acb.elliptic_f(acb(arb.atan2(c["Pt"].real, Ct)), J.m)  # F(am) with am = atan2(P, C)
            u0 = acb.elliptic_f(acb(arb.atan2(c["P"].real, c["C"])), J.m)
            res = u1 - u0 - shift(_env(c))
            res = res - round(float(res.real.mid()) / float((4 * J.K).real.mid())) * 4 * J.K
            table.add(s.cell, printed=_residual([res]) if real else UNDECIDED, point=point(s))
    return _cert_outcome(table, t0, len(samples), method=f"certified: Arb {PREC} bits, elliptic_f with am = "
                                                         "atan2(P, C), modulo 4K",
                         printed="u(P~, C~) = u(P, C) + b(Fr(lambda_+) - Fr(lambda_-)) mod 4K where the image is "
                                 "real; Fr(s) = F(s,k) (|s| <= 1), -F(1/(ks),k) (|s| >= 1/k)",
                         detail="acb.elliptic_f(phi, m) takes the parameter m = k^2, like mpmath.")
