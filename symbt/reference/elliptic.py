r"""Action-angle variables of the two-site Toda chain and the addition formula (eqs. ``th1th2``-``addform``).

Sympy-free: everything is mpmath at the current working precision.

Conventions
-----------
* :math:`\{p_i, q_j\} = \delta_{ij}`, :math:`\dot x = \{H, x\}`; the map is :func:`step2` (the route of
  :func:`symbt.reference.literal.literal_step` for N = 2, without matrices) with branch ``b = +-1``.
* :math:`I_1 = (p_1+p_2)/2`, :math:`I_2 = 2\cosh(q_1-q_2) + ((p_1-p_2)/2)^2 \ge 2`,
  :math:`\operatorname{tr}L(\lambda) = (\lambda+I_1)^2 - I_2`.
* Modulus :math:`k` and *parameter* :math:`m = k^2 = (I_2-2)/(I_2+2)`.  mpmath's
  ``ellipf(phi, m)``, ``ellipk(m)`` and ``ellipfun(kind, u, m)`` all take the parameter ``m``.
* The paper's :math:`F(z,k)` is the **incomplete** integral in Jacobi's form,
  :math:`F(z,k) = \int_0^z dt/\sqrt{(1-t^2)(1-k^2t^2)} = \texttt{ellipf}(\arcsin z, m=k^2)`, real for
  :math:`|z|\le 1`; :func:`F` computes it as :math:`z\,R_F(1-z^2, 1-k^2z^2, 1)` (Carlson),
  :func:`F_principal` is mpmath's principal continuation, whose value for real :math:`|z|>1`
  sits on a branch cut of ``asin`` and depends on mp.dps.

The global angle and the Abel map
---------------------------------
With :math:`P = (p_2-p_1)/(2\sqrt{I_2-2})`, :math:`C = 2\sinh((q_1-q_2)/2)/\sqrt{I_2-2}` one has
:math:`P^2 + C^2 = 1`, and :math:`(P, C) = (\operatorname{sn}u, \operatorname{cn}u)` for a unique
:math:`u \bmod 4K` (:func:`global_u`); :math:`\theta_2 = u/\sqrt{I_2+2}` is canonical everywhere.
In :math:`s = (\lambda+I_1)/\sqrt{I_2-2}` the spectral curve is :math:`w^2 = (1-s^2)(1-k^2s^2)`,
:math:`w = \gamma/\sqrt{I_2^2-4}`; :func:`abel` returns the :math:`u` with :math:`\operatorname{sn}u = s`,
:math:`\operatorname{cn}u\operatorname{dn}u = w` modulo the period lattice :math:`4K\mathbb Z + 2iK'\mathbb Z`
(:func:`lattice_residual`).  For complex :math:`s`, :math:`u_0 = s R_F(1-s^2, 1-k^2s^2, 1)` has
:math:`\operatorname{cn}\operatorname{dn} u_0 = \sqrt{1-s^2}\sqrt{1-k^2s^2}` (principal roots; tested).  For real
:math:`s` only real-argument integrals are used:
:math:`|s|\le1`: :math:`v=F(|s|)`; :math:`1<|s|<1/k`: :math:`v = K + iF(t, k')`,
:math:`t^2 = (1-s^{-2})/k'^2`; :math:`|s|\ge 1/k`: :math:`v = iK' + F(1/(k|s|))`; and
:math:`u = \operatorname{sgn}(s)v` or :math:`2K - \operatorname{sgn}(s)v`.  Since
:math:`\operatorname{cn}\operatorname{dn}(\operatorname{sgn}(s)v) = +W, -W, -W` in the three zones
(:math:`W` the principal root), the sheet is chosen by the sign of :math:`w` alone.  One step is
:math:`\tilde u \equiv u + \mathcal A(\lambda_1, \gamma_1) - \mathcal A(\lambda_2, \gamma_2)`, in every regime.

>>> with mp.workdps(30):
...     m = mp.mpf(3) / 7
...     u = abel(mp.mpf(2), mp.sqrt((1 - 4) * (1 - 4 * m)), m)
...     sn, cn, dn = sn_cn_dn(u, m)
...     print(mp.nstr(mp.chop(sn), 10), mp.nstr(mp.chop(cn * dn), 10), mp.nstr(mp.sqrt(15 / mp.mpf(7)), 10))
2.0 1.463850109 1.463850109
"""
from __future__ import annotations

import math
import random
from collections.abc import Callable, Sequence
from functools import lru_cache
from typing import Any

import mpmath as mp

from .literal import MPNumber, signed_arccosh_half

try:  # mpmath's own backend: the Carlson loop runs there when available
    import gmpy2
except ImportError:  # pragma: no cover
    gmpy2 = None

__all__ = [
    "REGIMES", "actions", "modulus", "carlson_rf", "F", "F_principal", "F_real", "angles", "global_u",
    "theta2_printed", "sn_cn_dn", "abel", "curve_point", "spectral_point", "lattice_residual", "shift",
    "printed_shift", "regime", "regime_of_state", "step2", "addition_residual", "printed_addform_residual",
    "state_on_level", "sample_case", "sample_state", "g_real",
]

#: regimes of (lambda_-, lambda_+) in the variable s = (lambda + I1)/sqrt(I2 - 2)
REGIMES = ("inner", "outer-same", "outer-opposite", "mixed", "gap")


def actions(p: Sequence[mp.mpf], q: Sequence[mp.mpf]) -> tuple[mp.mpf, mp.mpf]:
    """:math:`(I_1, I_2)` of eq. ``th1th2``."""
    return (p[0] + p[1]) / 2, 2 * mp.cosh(q[0] - q[1]) + ((p[0] - p[1]) / 2) ** 2


def modulus(I2: mp.mpf) -> tuple[mp.mpf, mp.mpf]:
    """``(k, m)``: the modulus and the parameter m = k^2 = (I2-2)/(I2+2)."""
    m = (I2 - 2) / (I2 + 2)
    return mp.sqrt(m), m


def carlson_rf(x: MPNumber, y: MPNumber, z: MPNumber) -> MPNumber:
    """Carlson's R_F(x, y, z) by duplication (principal square roots), x, y, z >= 0 (at most one zero)
    or complex off the cut (-inf, 0]; at the working precision, tested against :func:`mpmath.elliprf`.

    The loop runs in gmpy2 (mpmath's own backend) when it is installed, else in mpmath.
    """
    if gmpy2 is None:
        return _rf_loop(x, y, z, mp.sqrt, mp.mpf(2) ** ((mp.mp.prec + 3) // 6 + 1))
    prec = mp.mp.prec + 10
    with gmpy2.context(gmpy2.get_context(), precision=prec, real_prec=prec, imag_prec=prec):
        v = _rf_loop(_to_g(x), _to_g(y), _to_g(z), gmpy2.sqrt, gmpy2.mpfr(2) ** ((prec + 3) // 6 + 1))
    return _from_g(v)


# Any: the same loop on mpmath or gmpy2 numbers (gmpy2 is optional and its numbers are not mpmath's)
def _rf_loop(x: Any, y: Any, z: Any, sqrt: Callable[[Any], Any], scale: Any) -> Any:
    A0 = (x + y + z) / 3
    Q = max(abs(A0 - x), abs(A0 - y), abs(A0 - z)) * scale
    xm, ym, zm, A, p4 = x, y, z, A0, 1
    while p4 * abs(A) <= Q:
        sx, sy, sz = sqrt(xm), sqrt(ym), sqrt(zm)
        lam = sx * sy + sx * sz + sy * sz
        xm, ym, zm, A, p4 = (xm + lam) / 4, (ym + lam) / 4, (zm + lam) / 4, (A + lam) / 4, 4 * p4
    X, Y = (A0 - x) / (p4 * A), (A0 - y) / (p4 * A)
    Z = -X - Y
    E2, E3 = X * Y - Z * Z, X * Y * Z
    return (1 - E2 / 10 + E3 / 14 + E2 * E2 / 24 - 3 * E2 * E3 / 44) / sqrt(A)


def _mpf_to_g(v: mp.mpf) -> gmpy2.mpfr:
    sign, man, exp, _ = v._mpf_
    g = gmpy2.mul_2exp(gmpy2.mpfr(man), exp) if man else gmpy2.mpfr(0)
    return -g if sign else g


def _to_g(v: MPNumber) -> gmpy2.mpfr | gmpy2.mpc:
    v = mp.mpmathify(v)
    if isinstance(v, mp.mpc):
        return gmpy2.mpc(_mpf_to_g(v.real), _mpf_to_g(v.imag))
    return _mpf_to_g(v)


def _g_to_mpf(g: gmpy2.mpfr) -> mp.mpf:
    man, exp = g.as_mantissa_exp()
    return mp.mpf(mp.libmp.from_man_exp(int(man), int(exp), mp.mp.prec, "n"))


def _from_g(g: gmpy2.mpfr | gmpy2.mpc) -> MPNumber:
    if isinstance(g, type(gmpy2.mpc(0))):
        return mp.mpc(_g_to_mpf(g.real), _g_to_mpf(g.imag))
    return _g_to_mpf(g)


@lru_cache(maxsize=1 << 16)
def _F_memo(z: MPNumber, m: mp.mpf, prec: int) -> MPNumber:
    with mp.workprec(prec):
        return z * carlson_rf(1 - z * z, 1 - m * z * z, mp.mpf(1))


def _F_m(z: MPNumber, m: mp.mpf) -> MPNumber:
    """F in Jacobi's form z R_F(1-z^2, 1-m z^2, 1) (parameter m in [0, 1)) for real |z| <= 1 or complex z,
    memoised (F is odd; the Abel images of both sheets and the printed F share the values)."""
    if isinstance(z, mp.mpf) and z < 0:
        return -_F_memo(-z, m, mp.mp.prec)
    return _F_memo(z, m, mp.mp.prec)


def F(z: MPNumber, k: mp.mpf) -> MPNumber:
    """The paper's F(z, k) = int_0^z dt / sqrt((1-t^2)(1-k^2 t^2)) for real |z| <= 1 (modulus k)."""
    z = mp.mpf(z)
    if abs(z) > 1:
        raise ValueError("F(z, k) is real-defined for |z| <= 1 only; use abel() / F_real() beyond")
    return _F_m(z, k ** 2)


def F_principal(z: MPNumber, k: mp.mpf) -> MPNumber:
    """mpmath's principal continuation ellipf(asin z, k^2) -- on a branch cut for real |z| > 1."""
    return mp.ellipf(mp.asin(z), k ** 2)


def F_real(s: mp.mpf, k: mp.mpf) -> mp.mpf:
    """A real antiderivative of 1/|sqrt((1-s^2)(1-k^2 s^2))| on |s| <= 1 and on |s| >= 1/k.

    ``F(s, k)`` on [-1, 1]; ``-F(1/(k s), k)`` for |s| >= 1/k.  ValueError in the gaps 1 < |s| < 1/k.
    """
    s = mp.mpf(s)
    if abs(s) <= 1:
        return _F_m(s, k ** 2)
    if abs(k * s) >= 1:
        return -_F_m(1 / (k * s), k ** 2)
    raise ValueError("s in a gap 1 < |s| < 1/k: no real antiderivative")


def g_real(T: mp.mpf) -> mp.mpf:
    """sgn(T) arccosh(|T|/2): the real branch of arccosh(T/2) entering Phi (|T| >= 2)."""
    return signed_arccosh_half(T)


def global_u(p: Sequence[mp.mpf], q: Sequence[mp.mpf]) -> tuple[mp.mpf, mp.mpf]:
    """``(u, m)``: the global angle u in (-2K, 2K] with sn u = P, cn u = C (see module docstring)."""
    _, I2 = actions(p, q)
    _, m = modulus(I2)
    r = mp.sqrt(I2 - 2)
    P = max(mp.mpf(-1), min(mp.mpf(1), (p[1] - p[0]) / (2 * r)))
    C = 2 * mp.sinh((q[0] - q[1]) / 2) / r
    v = _F_m(P, m)
    if C >= 0:
        return v, m
    K = mp.ellipk(m)
    return (2 * K - v if P >= 0 else -2 * K - v), m


def angles(p: Sequence[mp.mpf], q: Sequence[mp.mpf]) -> tuple[mp.mpf, mp.mpf]:
    """Globally defined angles ``(theta1, theta2)``; theta2 in (-2K, 2K]/sqrt(I2+2)."""
    u, _ = global_u(p, q)
    _, I2 = actions(p, q)
    return q[0] + q[1], u / mp.sqrt(I2 + 2)


def theta2_printed(p: Sequence[mp.mpf], q: Sequence[mp.mpf], *, m: mp.mpf | None = None) -> mp.mpf:
    """The printed theta2 = F(P, k)/sqrt(I2+2), principal F (``m`` overrides the parameter)."""
    _, I2 = actions(p, q)
    mm = (I2 - 2) / (I2 + 2) if m is None else m
    P = (p[1] - p[0]) / (2 * mp.sqrt(I2 - 2))
    return mp.ellipf(mp.asin(P), mm) / mp.sqrt(I2 + 2)


def sn_cn_dn(u: MPNumber, m: mp.mpf) -> tuple[MPNumber, MPNumber, MPNumber]:
    """Jacobi sn, cn, dn at (possibly complex) u with parameter m."""
    return mp.ellipfun("sn", u, m=m), mp.ellipfun("cn", u, m=m), mp.ellipfun("dn", u, m=m)


def abel(s: MPNumber, w: MPNumber, m: mp.mpf) -> MPNumber:
    """u with sn(u) = s and cn(u) dn(u) = w (mod 4K Z + 2iK' Z), deterministic (see module docstring).

    Assumes (s, w) on the curve w^2 = (1-s^2)(1-m s^2); only the sign of w selects the sheet.
    """
    K = mp.ellipk(m)
    s = mp.mpmathify(s)
    if isinstance(s, mp.mpf):
        a = abs(s)
        W = mp.sqrt((1 - s * s) * (1 - m * s * s))
        if a <= 1:
            v, cd = _F_m(a, m), W
        elif m * a * a < 1:
            t = min(mp.sqrt((1 - 1 / (a * a)) / (1 - m)), mp.mpf(1))
            v, cd = K + 1j * _F_m(t, 1 - m), -W
        else:
            v, cd = 1j * mp.ellipk(1 - m) + _F_m(1 / (mp.sqrt(m) * a), m), -W
        u0 = mp.sign(s) * v      # s = 0: v = F(0) = 0 either way
    else:  # complex s: u0 = s R_F(1-s^2, 1-m s^2, 1) (principal), cn dn(u0) = sqrt(1-s^2) sqrt(1-m s^2)
        u0 = _F_m(s, m)
        cd = mp.sqrt(1 - s * s) * mp.sqrt(1 - m * s * s)
    return u0 if abs(cd - w) <= abs(cd + w) else 2 * K - u0


def curve_point(P: mp.mpf, Ea: mp.mpf, Eb: mp.mpf, I2: mp.mpf) -> tuple[mp.mpf, mp.mpf]:
    """(s, w) of a state: s = P, w = cn dn = 2 sinh(q1 - q2)/sqrt(I2^2-4) from e^{q1}/e^{q2} (branch-free)."""
    r = Ea / Eb
    return P, (r - 1 / r) / mp.sqrt(I2 ** 2 - 4)


def spectral_point(lam: mp.mpf, I1: mp.mpf, I2: mp.mpf,
                   branch: int) -> tuple[MPNumber, MPNumber, mp.mpf, MPNumber]:
    """(s, w, T, gamma) of the point (lambda, gamma = branch*sqrt(tr^2-4)) of the spectral curve."""
    T = (lam + I1) ** 2 - I2
    gam = branch * mp.sqrt(T ** 2 - 4)
    return (lam + I1) / mp.sqrt(I2 - 2), gam / mp.sqrt(I2 ** 2 - 4), T, gam


def lattice_residual(d: MPNumber, m: mp.mpf) -> mp.mpf:
    """Distance of d to the period lattice 4K Z + 2iK' Z (the rectangle lattice of (sn, cn dn))."""
    K, Kp = mp.ellipk(m), mp.ellipk(1 - m)
    d = mp.mpmathify(d)
    d = d - 2j * Kp * mp.nint(mp.im(d) / (2 * Kp))
    return abs(d - 4 * K * mp.nint(mp.re(d) / (4 * K)))


def shift(I1: mp.mpf, I2: mp.mpf, lam0: mp.mpf, mu: mp.mpf, branch: int) -> dict[str, MPNumber | None]:
    """The translation of one step: dict with du (in u), dtheta2, dtheta1 (complex log of v1 v2),
    dtheta1_real = branch*(g(T2) - g(T1)) (None if a |T| < 2), v1, v2, m, s_plus, s_minus, T1, T2."""
    _, m = modulus(I2)
    s1, w1, T1, g1 = spectral_point(lam0 + mu, I1, I2, branch)
    s2, w2, T2, g2 = spectral_point(lam0 - mu, I1, I2, branch)
    du = abel(s1, w1, m) - abel(s2, w2, m)
    v1, v2 = (T1 - g1) / 2, (T2 + g2) / 2  # eq. v1v2
    real = None
    if isinstance(T1, mp.mpf) and isinstance(T2, mp.mpf) and abs(T1) >= 2 and abs(T2) >= 2:
        real = branch * (g_real(T2) - g_real(T1))
    return dict(du=du, dtheta2=du / mp.sqrt(I2 + 2), dtheta1=mp.log(v1 * v2), dtheta1_real=real,
                v1=v1, v2=v2, m=m, s_plus=s1, s_minus=s2, T1=T1, T2=T2)


def printed_shift(I1: mp.mpf, I2: mp.mpf, lam0: mp.mpf, mu: mp.mpf) -> tuple[MPNumber, MPNumber]:
    """eq. citn as printed (principal arccosh, principal F): (dtheta1, dtheta2)."""
    k, _ = modulus(I2)
    r = mp.sqrt(I2 - 2)
    Tm, Tp = (lam0 - mu + I1) ** 2 - I2, (lam0 + mu + I1) ** 2 - I2
    d1 = mp.acosh(Tm / 2) - mp.acosh(Tp / 2)
    d2 = (F_principal((lam0 - mu + I1) / r, k) - F_principal((lam0 + mu + I1) / r, k)) / mp.sqrt(I2 + 2)
    return d1, d2


def regime(I1: mp.mpf, I2: mp.mpf, lam0: mp.mpf, mu: mp.mpf) -> str:
    """Classify (lambda_-, lambda_+) = lam0 -+ mu (mu > 0) in s = (lambda + I1)/sqrt(I2-2)."""
    k, _ = modulus(I2)
    r = mp.sqrt(I2 - 2)

    def zone(s: mp.mpf) -> str:
        if abs(s) < 1:
            return "in"
        if k * abs(s) > 1:
            return "out+" if s > 0 else "out-"
        return "gap"

    zp, zm = zone((lam0 + mu + I1) / r), zone((lam0 - mu + I1) / r)
    if "gap" in (zp, zm):
        return "gap"
    if zp == zm == "in":
        return "inner"
    if zp == zm:
        return "outer-same"
    return "mixed" if "in" in (zp, zm) else "outer-opposite"


def regime_of_state(p: Sequence[mp.mpf], q: Sequence[mp.mpf], lam0: mp.mpf | float | str,
                    mu: mp.mpf | float | str) -> str:
    I1, I2 = actions(p, q)
    return regime(I1, I2, mp.mpf(lam0), mp.mpf(mu))


def step2(p: Sequence[mp.mpf], q: Sequence[mp.mpf], lam0: mp.mpf, mu: mp.mpf, branch: int = 1, *,
          gammas: tuple[MPNumber, MPNumber] | None = None) -> tuple[list[MPNumber], list[MPNumber], dict[str, Any]]:
    """One step of the map for N = 2 along the paper's route (that of ``literal_step``), scalar.

    L = l_2 l_1 with l_j = [[lambda + p_j, -E_j], [1/E_j, 0]]; gamma_i = b sqrt(tr_i^2 - 4); y, x of
    eq. ``xy``; the kernels transported to site 2; e^{q~_j} = E_j - x_j, eta_j = x_j y_j + mu,
    p~_j = p_j + eta_j - eta_{j+1}.  Returns ``(p~, q~, info)`` like ``literal_step`` (complex where
    the real map does not exist; q~ = principal log of e^{q~}).  ``gammas`` fixes the curve points
    (gamma_1, gamma_2): iterating from a complex state, tr^2 - 4 < 0 carries rounding noise in its
    imaginary part and the principal root would pick a sheet at random; tr L is invariant, so the
    iterates of one map use the gammas of its first step.
    """
    p1, p2 = (mp.mpmathify(v) for v in p)
    E1, E2 = (mp.exp(v) for v in q)
    lam0, mu = mp.mpmathify(lam0), mp.mpmathify(mu)
    l1, l2 = lam0 + mu, lam0 - mu

    def abd(lam: mp.mpf) -> tuple[mp.mpf, mp.mpf, mp.mpf]:
        return (lam + p2) * (lam + p1) - E2 / E1, -(lam + p2) * E1, -E1 / E2

    A1, B1, D1 = abd(l1)
    A2, B2, D2 = abd(l2)
    tr1, tr2 = A1 + D1, A2 + D2
    if gammas is None:
        g1, g2 = branch * mp.sqrt(tr1 ** 2 - 4), branch * mp.sqrt(tr2 ** 2 - 4)
    else:
        g1, g2 = gammas
    y = (A1 - D1 + g1) / (2 * B1)
    x = 2 * B1 * B2 * (l2 - l1) / (B2 * (A1 - D1 + g1) - B1 * (A2 - D2 - g2))
    z = y + 2 * mu / x
    ys = [y, -1 / (E1 * (l1 + p1 + E1 * y))]
    zs = [z, -1 / (E1 * (l2 + p1 + E1 * z))]
    xs = [2 * mu / (b - a) for a, b in zip(ys, zs)]
    Et = [E1 - xs[0], E2 - xs[1]]
    eta = [xs[0] * ys[0] + mu, xs[1] * ys[1] + mu]
    pt = [p1 + eta[0] - eta[1], p2 + eta[1] - eta[0]]
    return pt, [mp.log(e) for e in Et], dict(tr1=tr1, tr2=tr2, gamma1=g1, gamma2=g2, E_new=Et, eta=eta)


def addition_residual(p: Sequence[mp.mpf], q: Sequence[mp.mpf], lam0: mp.mpf, mu: mp.mpf, branch: int,
                      pt: Sequence[MPNumber] | None = None, qt: Sequence[MPNumber] | None = None,
                      Et: Sequence[MPNumber] | None = None, du: MPNumber | None = None) -> mp.mpf:
    """Residual of the corrected, branch-free addition formula for one step, evaluated *forward*.

    sn(u + du) = P~, cn(u + du) dn(u + du) = 2 sinh(q~1 - q~2)/sqrt(I2^2-4), e^{q~1+q~2} =
    e^{q1+q2} v(l1) v(l2) with Jacobi's functions of mpmath; the largest relative residual.  ``du``
    overrides the shift (negative tests).  An independent route to the lattice test of the claims.
    """
    if pt is None or Et is None:
        pt, qt, info = step2(p, q, lam0, mu, branch)
        Et = info["E_new"]
    I1, I2 = actions(p, q)
    sh = shift(I1, I2, mp.mpf(lam0), mp.mpf(mu), branch)
    u, _ = global_u(p, q)
    sn, cn, dn = sn_cn_dn(u + (sh["du"] if du is None else du), sh["m"])
    Pt = (pt[1] - pt[0]) / (2 * mp.sqrt(I2 - 2))
    _, wt = curve_point(Pt, Et[0], Et[1], I2)
    E1E2 = mp.exp(q[0] + q[1]) * sh["v1"] * sh["v2"]
    return max(abs(sn - Pt) / max(1, abs(Pt)), abs(cn * dn - wt) / max(1, abs(wt)),
               abs(Et[0] * Et[1] - E1E2) / max(1, abs(E1E2)))


def printed_addform_residual(p: Sequence[mp.mpf], q: Sequence[mp.mpf], pt: Sequence[MPNumber], I2: mp.mpf,
                             lam0: mp.mpf, mu: mp.mpf, I1: mp.mpf) -> mp.mpf:
    """|F(P~) - F(P) - F(l-) + F(l+)| with the principal F, as printed (eq. addform)."""
    k, _ = modulus(I2)
    r = mp.sqrt(I2 - 2)
    P, Pt = (p[1] - p[0]) / (2 * r), (pt[1] - pt[0]) / (2 * r)
    lm, lp = (lam0 - mu + I1) / r, (lam0 + mu + I1) / r
    return abs(F_principal(Pt, k) - F_principal(P, k) - F_principal(lm, k) + F_principal(lp, k))


def state_on_level(I1: mp.mpf, I2: mp.mpf, x: mp.mpf, theta1: mp.mpf,
                   sign: int) -> tuple[list[mp.mpf], list[mp.mpf]]:
    """(p, q) with actions (I1, I2), q1 - q2 = x, q1 + q2 = theta1, sign of p1 - p2 = sign."""
    Pr = sign * mp.sqrt(I2 - 2 * mp.cosh(x))
    return [I1 + Pr, I1 - Pr], [(theta1 + x) / 2, (theta1 - x) / 2]


def _fmt(v: float) -> str:
    return f"{v:.17g}"


def sample_state(rng: random.Random, *, x_sign: int, p_sign: int) -> tuple[list[str], list[str]]:
    """A random real state (decimal strings p, q) with sign(q1 - q2) = x_sign, sign(p2 - p1) = p_sign.

    Its level set: ``I1 = (p1 + p2)/2`` uniform on [-2, 2], ``I2`` uniform on [2.3, 9], ``|q1 - q2|`` uniform on
    ``[0.03, 0.97] acosh(I2/2)`` (away from the turning points ``p1 = p2``), ``q1 + q2`` uniform on [-1, 1].
    """
    I1, I2 = rng.uniform(-2, 2), rng.uniform(2.3, 9)
    x = x_sign * rng.uniform(0.03, 0.97) * math.acosh(I2 / 2)
    Pr = -p_sign * math.sqrt(max(I2 - 2 * math.cosh(x), 0.0))
    th1 = rng.uniform(-1, 1)
    return [_fmt(I1 + Pr), _fmt(I1 - Pr)], [_fmt((th1 + x) / 2), _fmt((th1 - x) / 2)]


def _s_in(zone: str, k: float, rng: random.Random) -> float:
    if zone == "in":
        return rng.uniform(-0.95, 0.95)
    if zone == "gap":
        return rng.choice((1, -1)) * (1 + (1 / k - 1) * rng.uniform(0.1, 0.9))
    a = rng.uniform(1.05, 2.5) / k
    return a if zone == "out+" else -a


_ZONES = {"inner": [("in", "in")], "outer-same": [("out+", "out+"), ("out-", "out-")],
          "outer-opposite": [("out+", "out-")], "mixed": [("in", "out+"), ("in", "out-")],
          "gap": [("gap", "in"), ("gap", "out+"), ("gap", "gap")]}


def sample_case(reg: str, rng: random.Random, *,
                x_sign: int | None = None) -> tuple[list[str], list[str], str, str]:
    """A random case of regime ``reg``: decimal strings (p, q, lam0, mu), exact at any dps.

    ``rng`` is a ``random.Random``; ``x_sign`` forces the sign of q1 - q2.  A ``gap`` case has an end in one of
    the two gaps ``1 < |s| < 1/k`` (``s = (lambda + I1)/sqrt(I2 - 2)``), on either side.
    """
    for _ in range(1000):
        I1, I2 = rng.uniform(-2, 2), rng.uniform(2.3, 9)
        k = math.sqrt((I2 - 2) / (I2 + 2))
        za, zb = rng.choice(_ZONES[reg])
        sa, sb = _s_in(za, k, rng), _s_in(zb, k, rng)
        if abs(sa - sb) < 0.05:
            continue
        r = math.sqrt(I2 - 2)
        lp, lm = max(sa, sb) * r - I1, min(sa, sb) * r - I1
        x = rng.uniform(0.03, 0.97) * math.acosh(I2 / 2) * (x_sign if x_sign else rng.choice((1, -1)))
        Pr = rng.choice((1, -1)) * math.sqrt(max(I2 - 2 * math.cosh(x), 0.0))
        th1 = rng.uniform(-1, 1)
        case = ([_fmt(I1 + Pr), _fmt(I1 - Pr)], [_fmt((th1 + x) / 2), _fmt((th1 - x) / 2)],
                _fmt((lp + lm) / 2), _fmt((lp - lm) / 2))
        with mp.workdps(30):
            if regime_of_state([mp.mpf(v) for v in case[0]], [mp.mpf(v) for v in case[1]],
                               mp.mpf(case[2]), mp.mpf(case[3])) == reg:
                return case
    raise RuntimeError(f"could not sample regime {reg}")
