r"""Action-angle variables of the two-site Toda chain and the addition formula (eqs. ``th1th2``-``addform``).

Sympy-free: everything is mpmath at the current working precision.

Conventions
-----------
* :math:`\{p_i, q_j\} = \delta_{ij}`, :math:`\dot x = \{H, x\}`; the map is
  :func:`symbt.reference.literal.literal_step` with branch ``b = +-1``.
* :math:`I_1 = (p_1+p_2)/2`, :math:`I_2 = 2\cosh(q_1-q_2) + ((p_1-p_2)/2)^2 \ge 2`,
  :math:`\operatorname{tr}L(\lambda) = (\lambda+I_1)^2 - I_2`.
* Modulus :math:`k` and *parameter* :math:`m = k^2 = (I_2-2)/(I_2+2)`.  mpmath's
  ``ellipf(phi, m)``, ``ellipk(m)`` and ``ellipfun(kind, u, m)`` all take the parameter
  ``m``, never the modulus.
* The paper's :math:`F(z,k)` is the **incomplete** elliptic integral of the first kind in
  Jacobi's algebraic form,
  :math:`F(z,k) = \int_0^z dt/\sqrt{(1-t^2)(1-k^2t^2)} = \texttt{ellipf}(\arcsin z, m=k^2)`,
  real for :math:`|z|\le 1` (the paper's word "complete" is a slip: the complete integral is
  :math:`K(k) = F(1,k)`, which has no argument :math:`z`).  :func:`F` implements it for
  :math:`|z|\le 1` only; :func:`F_principal` is mpmath's principal continuation, whose value for
  real :math:`|z|>1` sits on a branch cut and *depends on mp.dps* (e.g. at ``z=2``,
  ``m=3/7`` it returns :math:`v` at 30 digits and :math:`2K-v` at 50 digits).

The globally defined angle
--------------------------
With :math:`P = (p_2-p_1)/(2\sqrt{I_2-2})` and :math:`C = 2\sinh((q_1-q_2)/2)/\sqrt{I_2-2}`
one has :math:`P^2 + C^2 = 1` identically, and the point :math:`(P, C)` is
:math:`(\operatorname{sn}u, \operatorname{cn}u)` for a unique :math:`u \bmod 4K`:
:math:`\operatorname{am} u = \operatorname{atan2}(P, C)`.  Then
:math:`\theta_2 = u/\sqrt{I_2+2}` satisfies :math:`\{I_2,\theta_2\}=1` everywhere; the printed
:math:`F(P,k)/\sqrt{I_2+2}` equals it for :math:`q_1 > q_2` only (for :math:`q_1<q_2`
it is :math:`(2K-u)/\sqrt{I_2+2}` and :math:`\{I_2, \cdot\} = -1`).

The Abel map and the branch-free addition formula
-------------------------------------------------
The Darboux matrix uses the points :math:`(\lambda_i, \gamma_i)`, :math:`\gamma_i=b\sqrt{\operatorname{tr}_i^2-4}`
of the spectral curve.  In :math:`s = (\lambda+I_1)/\sqrt{I_2-2}` the curve is
:math:`w^2 = (1-s^2)(1-k^2s^2)` with :math:`w = \gamma/\sqrt{I_2^2-4}`, and
:func:`abel` returns the :math:`u` with :math:`\operatorname{sn}u = s`,
:math:`\operatorname{cn}u\operatorname{dn}u = w` (mod :math:`4K\mathbb Z + 2iK'\mathbb Z`).  One step is

.. math:: \tilde u = u + \mathcal A(\lambda_+,\gamma_+) - \mathcal A(\lambda_-,\gamma_-), \qquad
          e^{\tilde\theta_1} = e^{\theta_1}\, v(\lambda_1)\, v(\lambda_2),

i.e. :math:`\operatorname{sn}\tilde u = \tilde P` and :math:`\operatorname{cn}\tilde u\operatorname{dn}\tilde u
= 2\sinh(\tilde q_1-\tilde q_2)/\sqrt{I_2^2-4}`, in every regime (also where the map is complex).

Deterministic continuation (:func:`abel`): for real :math:`s` only real-argument ``ellipf`` with
:math:`\phi\in[0,\pi/2]` is used -- :math:`|s|\le1`: :math:`v=F(|s|)`; :math:`1<|s|\le 1/k`:
:math:`v = K + i\,F(\arcsin\sqrt{(1-s^{-2})/k'^2}, k'^2)`; :math:`|s|\ge 1/k`:
:math:`v = iK' + F(1/(k|s|))`; then :math:`u=\operatorname{sgn}(s)v` or :math:`2K-\operatorname{sgn}(s)v`,
whichever has :math:`\operatorname{cn}\operatorname{dn}` closer to :math:`w`.  The result does not depend on
mp.dps (tested at 30/50/80 digits).
"""
from __future__ import annotations

import mpmath as mp

__all__ = [
    "REGIMES", "actions", "modulus", "F", "F_principal", "F_real", "angles", "global_u", "theta2_printed",
    "sn_cn_dn", "abel", "spectral_point", "shift", "printed_shift", "regime", "regime_of_state",
    "addition_residual", "printed_addform_residual", "state_on_level", "sample_case", "g_real",
]

#: regimes of (lambda_-, lambda_+) in the variable s = (lambda + I1)/sqrt(I2 - 2)
REGIMES = ("inner", "outer-same", "outer-opposite", "mixed", "gap")


def actions(p, q):
    """:math:`(I_1, I_2)` of eq. ``th1th2``."""
    return (p[0] + p[1]) / 2, 2 * mp.cosh(q[0] - q[1]) + ((p[0] - p[1]) / 2) ** 2


def modulus(I2):
    """``(k, m)``: the modulus and the parameter m = k^2 = (I2-2)/(I2+2)."""
    m = (I2 - 2) / (I2 + 2)
    return mp.sqrt(m), m


def F(z, k):
    """The paper's F(z, k) = int_0^z dt / sqrt((1-t^2)(1-k^2 t^2)) for real |z| <= 1 (modulus k)."""
    z = mp.mpf(z)
    if abs(z) > 1:
        raise ValueError("F(z, k) is real-defined for |z| <= 1 only; use abel() / F_real() beyond")
    return mp.ellipf(mp.asin(z), k ** 2)


def F_principal(z, k):
    """mpmath's principal continuation ellipf(asin z, k^2) -- on a branch cut for real |z| > 1."""
    return mp.ellipf(mp.asin(z), k ** 2)


def F_real(s, k):
    """A real antiderivative of 1/|sqrt((1-s^2)(1-k^2 s^2))| on |s| <= 1 and on |s| >= 1/k.

    ``F(s, k)`` on [-1, 1]; ``-F(1/(k s), k)`` for |s| >= 1/k (odd, increasing on each piece).
    Undefined (ValueError) in the gaps 1 < |s| < 1/k.
    """
    s = mp.mpf(s)
    if abs(s) <= 1:
        return mp.ellipf(mp.asin(s), k ** 2)
    if abs(k * s) >= 1:
        return -mp.ellipf(mp.asin(1 / (k * s)), k ** 2)
    raise ValueError("s in a gap 1 < |s| < 1/k: no real antiderivative")


def g_real(T):
    """sgn(T) arccosh(|T|/2): the real branch of arccosh(T/2) entering Phi (|T| >= 2)."""
    return mp.sign(T) * mp.acosh(abs(T) / 2)


def global_u(p, q):
    """``(u, m)``: the global angle u mod 4K with sn u = P, cn u = C (see module docstring)."""
    I1, I2 = actions(p, q)
    k, m = modulus(I2)
    r = mp.sqrt(I2 - 2)
    P = (p[1] - p[0]) / (2 * r)
    C = 2 * mp.sinh((q[0] - q[1]) / 2) / r
    P = max(mp.mpf(-1), min(mp.mpf(1), P))
    v = mp.ellipf(mp.asin(P), m)
    if C >= 0:
        return v, m
    K = mp.ellipk(m)
    return (2 * K - v if P >= 0 else -2 * K - v), m


def angles(p, q):
    """Globally defined angles ``(theta1, theta2)``; theta2 in (-2K, 2K]/sqrt(I2+2)."""
    u, m = global_u(p, q)
    _, I2 = actions(p, q)
    return q[0] + q[1], u / mp.sqrt(I2 + 2)


def theta2_printed(p, q, *, m=None):
    """The printed theta2 = F(P, k)/sqrt(I2+2) (``m`` overrides the parameter, for negative tests)."""
    _, I2 = actions(p, q)
    mm = (I2 - 2) / (I2 + 2) if m is None else m
    P = (p[1] - p[0]) / (2 * mp.sqrt(I2 - 2))
    return mp.ellipf(mp.asin(P), mm) / mp.sqrt(I2 + 2)


def sn_cn_dn(u, m):
    """Jacobi sn, cn, dn at (possibly complex) u with parameter m."""
    return mp.ellipfun("sn", u, m=m), mp.ellipfun("cn", u, m=m), mp.ellipfun("dn", u, m=m)


def abel(s, w, m):
    """u with sn(u) = s and cn(u) dn(u) = w (mod 4K Z + 2iK' Z), deterministic (see module docstring)."""
    K = mp.ellipk(m)
    s = mp.mpmathify(s)
    if isinstance(s, mp.mpf):
        a, sg = abs(s), (1 if s >= 0 else -1)
        k = mp.sqrt(m)
        if a <= 1:
            v = mp.ellipf(mp.asin(a), m)
        elif k * a < 1:
            t = mp.sqrt((1 - 1 / a ** 2) / (1 - m))
            v = K + 1j * mp.ellipf(mp.asin(min(t, mp.mpf(1))), 1 - m)
        else:
            v = 1j * mp.ellipk(1 - m) + mp.ellipf(mp.asin(1 / (k * a)), m)
        u0 = sg * v
    else:  # complex s: principal continuation, then the same choice of sheet
        u0 = mp.ellipf(mp.asin(s), m)
    _, c, d = sn_cn_dn(u0, m)
    return u0 if abs(c * d - w) <= abs(c * d + w) else 2 * K - u0


def spectral_point(lam, I1, I2, branch):
    """(s, w) of the point (lambda, gamma = branch*sqrt(tr^2-4)) of the spectral curve."""
    T = (lam + I1) ** 2 - I2
    gam = branch * mp.sqrt(T ** 2 - 4)
    return (lam + I1) / mp.sqrt(I2 - 2), gam / mp.sqrt(I2 ** 2 - 4), T, gam


def shift(I1, I2, lam0, mu, branch):
    """The translation of one step: dict with du (in u), dtheta2, dtheta1 (complex log of v1 v2),
    dtheta1_real = branch*(g(T2) - g(T1)) (None if a |T| < 2), v1, v2, m."""
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


def printed_shift(I1, I2, lam0, mu):
    """eq. citn as printed (principal arccosh, principal F): (dtheta1, dtheta2)."""
    k, m = modulus(I2)
    r = mp.sqrt(I2 - 2)
    Tm, Tp = (lam0 - mu + I1) ** 2 - I2, (lam0 + mu + I1) ** 2 - I2
    d1 = mp.acosh(Tm / 2) - mp.acosh(Tp / 2)
    d2 = (F_principal((lam0 - mu + I1) / r, k) - F_principal((lam0 + mu + I1) / r, k)) / mp.sqrt(I2 + 2)
    return d1, d2


def regime(I1, I2, lam0, mu):
    """Classify (lambda_-, lambda_+) = lam0 -+ mu (mu > 0) in s = (lambda + I1)/sqrt(I2-2)."""
    k, _ = modulus(I2)
    r = mp.sqrt(I2 - 2)
    sp_, sm = (lam0 + mu + I1) / r, (lam0 - mu + I1) / r

    def zone(s):
        a = abs(s)
        if a < 1:
            return "in"
        if k * a > 1:
            return "out+" if s > 0 else "out-"
        return "gap"

    zp, zm = zone(sp_), zone(sm)
    if "gap" in (zp, zm):
        return "gap"
    if zp == zm == "in":
        return "inner"
    if zp == zm:
        return "outer-same"
    if "in" in (zp, zm):
        return "mixed"
    return "outer-opposite"


def regime_of_state(p, q, lam0, mu):
    I1, I2 = actions(p, q)
    return regime(I1, I2, mp.mpf(lam0), mp.mpf(mu))


def _curve_w(Et, I2):
    """cn*dn of the state with e^{q~_1 - q~_2} = Et[0]/Et[1]: 2 sinh(q1-q2)/sqrt(I2^2-4), branch-free."""
    r = Et[0] / Et[1]
    return (r - 1 / r) / mp.sqrt(I2 ** 2 - 4)


def addition_residual(p, q, lam0, mu, branch, pt=None, qt=None, Et=None, du=None):
    """Residual of the corrected, branch-free addition formula for one step.

    Checks sn(u + du) = P~, cn(u + du) dn(u + du) = 2 sinh(q~1 - q~2)/sqrt(I2^2-4) and
    e^{q~1+q~2} = e^{q1+q2} v(l1) v(l2); returns the largest relative residual.  ``pt``/``Et``
    default to :func:`symbt.reference.literal.literal_step`; ``du`` overrides the shift (negative tests).
    """
    if pt is None or Et is None:
        from .literal import literal_step

        pt, qt, info = literal_step(p, q, lam0, mu, branch)
        Et = info["E_new"]
    I1, I2 = actions(p, q)
    sh = shift(I1, I2, mp.mpf(lam0), mp.mpf(mu), branch)
    m = sh["m"]
    u, _ = global_u(p, q)
    d = sh["du"] if du is None else du
    sn, cn, dn = sn_cn_dn(u + d, m)
    Pt = (pt[1] - pt[0]) / (2 * mp.sqrt(I2 - 2))
    r1 = abs(sn - Pt) / max(1, abs(Pt))
    wt = _curve_w(Et, I2)
    r2 = abs(cn * dn - wt) / max(1, abs(wt))
    E1E2 = mp.exp(q[0] + q[1]) * sh["v1"] * sh["v2"]
    r3 = abs(Et[0] * Et[1] - E1E2) / max(1, abs(E1E2))
    return max(r1, r2, r3)


def printed_addform_residual(p, q, pt, I2, lam0, mu, I1):
    """|F(P~) - F(P) - F(l-) + F(l+)| with the principal F, as printed (eq. addform)."""
    k, _ = modulus(I2)
    r = mp.sqrt(I2 - 2)
    P, Pt = (p[1] - p[0]) / (2 * r), (pt[1] - pt[0]) / (2 * r)
    lm, lp = (lam0 - mu + I1) / r, (lam0 + mu + I1) / r
    return abs(F_principal(Pt, k) - F_principal(P, k) - F_principal(lm, k) + F_principal(lp, k))


def state_on_level(I1, I2, x, theta1, sign):
    """(p, q) with actions (I1, I2), q1 - q2 = x, q1 + q2 = theta1, sign of p1 - p2 = sign."""
    Pr = sign * mp.sqrt(I2 - 2 * mp.cosh(x))
    return [I1 + Pr, I1 - Pr], [(theta1 + x) / 2, (theta1 - x) / 2]


def _s_in(zone, k, rng):
    lo_out = 1 / k
    if zone == "in":
        return rng.uniform(-0.95, 0.95)
    if zone == "gap":
        return rng.choice((1, -1)) * (1 + (lo_out - 1) * rng.uniform(0.1, 0.9))
    a = lo_out * rng.uniform(1.05, 2.5)
    return a if zone == "out+" else -a


def sample_case(reg, rng, *, x_sign=None):
    """A random case of regime ``reg``: decimal strings (p, q, lam0, mu), exact at any dps.

    ``rng`` is a ``random.Random``; ``x_sign`` forces the sign of q1 - q2.
    """
    import math

    zones = {"inner": [("in", "in")], "outer-same": [("out+", "out+"), ("out-", "out-")],
             "outer-opposite": [("out+", "out-")], "mixed": [("in", "out+"), ("in", "out-")],
             "gap": [("gap", "in"), ("gap", "out+"), ("gap", "gap")]}[reg]
    for _ in range(1000):
        I1 = rng.uniform(-2, 2)
        I2 = rng.uniform(2.3, 9)
        k = math.sqrt((I2 - 2) / (I2 + 2))
        za, zb = rng.choice(zones)
        sa, sb = _s_in(za, k, rng), _s_in(zb, k, rng)
        if abs(sa - sb) < 0.05:
            continue
        sp_, sm = max(sa, sb), min(sa, sb)
        r = math.sqrt(I2 - 2)
        lp, lm = sp_ * r - I1, sm * r - I1
        lam0, mu = (lp + lm) / 2, (lp - lm) / 2
        xmax = math.acosh(I2 / 2)
        x = rng.uniform(0.03, 0.97) * xmax * (x_sign if x_sign else rng.choice((1, -1)))
        Pr = rng.choice((1, -1)) * math.sqrt(max(I2 - 2 * math.cosh(x), 0.0))
        th1 = rng.uniform(-1, 1)
        fmt = lambda v: f"{v:.17g}"  # noqa: E731
        case = ([fmt(I1 + Pr), fmt(I1 - Pr)], [fmt((th1 + x) / 2), fmt((th1 - x) / 2)], fmt(lam0), fmt(mu))
        with mp.workdps(30):
            pm = [mp.mpf(v) for v in case[0]]
            qm = [mp.mpf(v) for v in case[1]]
            if regime_of_state(pm, qm, mp.mpf(case[2]), mp.mpf(case[3])) == reg:
                return case
    raise RuntimeError(f"could not sample regime {reg}")
