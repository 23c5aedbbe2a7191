r"""One-site kernels of the transfer-matrix (O(N)) form, derived from :mod:`symbt.symbolic`.

The transfer-matrix form evaluates everything by loops over the sites; the
formulas inside the loops are the SymPy expressions built here (printed by
:mod:`symbt.codegen.printer`), and every one of them is checked *exactly*
(``expand``/``cancel`` of a difference, never ``simplify``) when it is derived:

* *scaled transfer matrix* ``m_j = S_{j+1} l_j S_j^{-1} = [[a, -1], [r, 0]]`` with
  ``S_j = diag(1, E_j)``, ``a = lambda + p_j``, ``r = r_j = E_{j+1}/E_j = exp(q_{j+1} - q_j)``;
  ``M = m_N ... m_1 = S_1 L S_1^{-1}`` has the trace of ``L`` and only neighbour
  differences of ``q`` enter;
* *update* ``M <- m_j M`` (entries ``A, B, C, D``), and ``tr = A + D``,
  ``tr^2 - 4 = (tr - 2)(tr + 2)``; for ``M = 2^e (A, B; C, D)`` (float64 entries rescaled by powers
  of two, exactly) ``disc_scaled = (t - two)(t + two) = 4^-e (tr^2 - 4)`` with ``t = A + D``,
  ``two = 2^(1 - e)``: the sign of ``tr^2 - 4`` without forming ``tr``;
* *eigenvector slopes*: ``M (1, -u)^T = nu (1, -u)^T`` iff ``B u^2 - (A - D) u - C = 0``;
  with ``det M = 1`` the roots ``(A - D + s g)/(2B)`` (``g^2 = tr^2 - 4``) are, without
  cancellation, ``k/(2B)`` and ``-2C/k``, ``k = (A - D) + sign(A - D) g`` (both unchanged when ``A, B, C, D, g``
  are scaled alike: the scaled monodromy gives the same slopes); the eigenvalue of
  ``(A - D + s g)/(2B)`` is ``(tr - s g)/2``, of modulus >= 1 (the slope attracts under forward
  transport) iff ``s tr < 0``;
* *transport* of a slope by ``m_j`` (Möbius action): ``u' = -r/(a + u)``, and its inverse
  ``u = -a - r/u'``;
* *derivatives of the trace*: with ``P`` the product of the sites before ``j`` and
  ``S`` of those after it, ``tr M = tr(S m_j P)``, so
  ``d tr/dp_j = tr(dm_j/dp_j P S)``, ``d tr/dr_j = tr(dm_j/dr_j P S)``, and by the chain
  rule ``d tr/dq_j = r_{j-1} d tr/dr_{j-1} - r_j d tr/dr_j``;
* *read-out* of the step from the scaled slopes ``u_j = E_j y_j``, ``w_j = E_j z_j``,
  ``d_j = w_j - u_j``: ``q~_j - q_j = log1p(-2 mu/d_j)``,
  ``eta_j = mu + 2 mu u_j/d_j``, ``p~_j - p_j = eta_j - eta_{j+1}``; the guard
  ``E~_j/E_j = 1 - 2 mu/d_j > 0``; Dapp's ``x = e^{q_1} 2 mu/d_1``, ``y = e^{-q_1} u_1``;
* the real Phi and its gradient from the two traces (as in :mod:`symbt.codegen.derive`).

>>> k = kernels()
>>> k["update"]
(A*a - C, B*a - D, A*r, B*r)
"""
from __future__ import annotations

from functools import cache
from typing import Any

import sympy as sp
from sympy.codegen.cfunctions import log1p

from ..symbolic.linear import solve_linear
from ..symbolic.toda import local_lax
from .derive import branch, disc, phi_of, tr1, tr2
from .printer import Quotient

__all__ = ["kernels", "SYMBOLS"]

A, B, C, D, a, r, u, un, g, mu, sd, s = sp.symbols("A B C D a r u un g mu sd s", real=True)
P00, P01, P10, P11, S00, S01, S10, S11 = sp.symbols("P00 P01 P10 P11 S00 S01 S10 S11", real=True)
r_prev, dr_prev, dr = sp.symbols("r_prev dr_prev dr", real=True)
uj, dj, un1, dn1, wj, wn1 = sp.symbols("uj dj un1 dn1 wj wn1", real=True)
t, q, x1, x2, two = sp.symbols("t q x1 x2 two", real=True)
_lam, _p = sp.symbols("lambda p", real=True)
_E, _En = sp.symbols("E En", positive=True)

#: every symbol a kernel may contain (the emitters bind them to variables of the same name)
SYMBOLS = (A, B, C, D, a, r, u, un, g, mu, sd, s, P00, P01, P10, P11, S00, S01, S10, S11,
           r_prev, dr_prev, dr, uj, dj, un1, dn1, wj, wn1, t, q, x1, x2, two, branch, tr1, tr2)


def _zero(expr: sp.Expr, what: str) -> None:
    if sp.cancel(sp.expand(expr)) != 0:
        raise AssertionError(f"kernel derivation failed: {what}")


@cache
def kernels() -> dict[str, Any]:
    """Name -> SymPy expression (or tuple of them) for every one-site kernel (see the module doc)."""
    out: dict[str, Any] = {}
    # scaled transfer matrix from the local Lax matrix of the model
    l = local_lax(_lam, _p, _E)
    m = (sp.diag(1, _En) * l * sp.diag(1, 1 / _E)).applyfunc(sp.cancel)
    m_ar = m.applyfunc(lambda x: sp.cancel(x.xreplace({_lam: a - _p}).xreplace({_En: r * _E})))
    for x, y in zip(m_ar, m):
        _zero(x.xreplace({a: _lam + _p, r: _En / _E}) - y, "m_j = S_{j+1} l_j S_j^-1")
    if m_ar.free_symbols - {a, r}:
        raise AssertionError(f"scaled transfer matrix depends on more than a, r: {m_ar}")
    out["site"] = tuple(m_ar)                                    # m_1 applied to the identity
    upd = (m_ar * sp.Matrix([[A, B], [C, D]])).applyfunc(sp.expand)
    out["update"] = tuple(upd)                                   # M <- m_j M (prefix products)
    out["update_right"] = tuple((sp.Matrix([[A, B], [C, D]]) * m_ar).applyfunc(sp.expand))  # M <- M m_j
    out["trace"] = A + D
    out["disc"] = disc(t)
    out["inv_sqrt_disc"] = 1 / sp.sqrt(disc(t))
    _zero(out["disc"] - (t ** 2 - 4), "tr^2 - 4 = (tr - 2)(tr + 2)")
    out["disc_scaled"] = sp.Mul(t - two, t + two, evaluate=False)
    pe = sp.Symbol("pe", positive=True)     # pe = 2^e, M = pe M_s: tr = pe t, 2 = pe two
    _zero(pe ** 2 * out["disc_scaled"].xreplace({two: 2 / pe}) - out["disc"].xreplace({t: pe * t}),
          "tr^2 - 4 = 4^e (t - two)(t + two), two = 2^(1 - e)")
    out["det_site"] = m_ar.det()                                 # = r: det M = prod r_j = 1

    # eigenvector slopes: M (1, -u) = nu (1, -u)  <=>  quadratic in u
    M = sp.Matrix([[A, B], [C, D]])
    v = M * sp.Matrix([1, -u])
    quad = sp.expand(v[1] + v[0] * u)                            # C - D u + (A - B u) u = 0
    _zero(quad - (-(B * u ** 2 - (A - D) * u - C)), "eigenvector quadratic")
    out["quadratic"] = B * u ** 2 - (A - D) * u - C
    dl = A - D
    k = dl + sd * g                                              # sd = sign(A - D): no cancellation
    out["k"] = k
    out["root_k"] = k / (2 * B)
    out["root_c"] = -2 * C / k
    # with det M = 1, g^2 = tr^2 - 4 = (A - D)^2 + 4 B C; both roots solve the quadratic
    gsq = dl ** 2 + 4 * B * C
    _zero((A + D) ** 2 - 4 * (A * D - B * C) - gsq, "tr^2 - 4 det = (A-D)^2 + 4BC")
    for name in ("root_k", "root_c"):
        val = sp.expand(sp.numer(sp.together(out["quadratic"].xreplace({u: out[name]}))))
        _, rem = sp.reduced(val, [g ** 2 - gsq, sd ** 2 - 1], g, sd, A, B, C, D)
        _zero(rem, f"{name} solves the eigenvector quadratic (mod g^2 = tr^2 - 4, sd^2 = 1)")
    # root_k is the slope (A - D + s g)/(2B) iff s = sd; its eigenvalue nu = A - B u = (tr - s g)/2
    # has |nu| >= 1 (the slope is attracting under forward transport) iff s tr < 0 (|tr| > 2, g > 0)
    _zero(out["root_k"].xreplace({sd: s}) - (dl + s * g) / (2 * B), "root_k = (A - D + s g)/(2B) for sd = s")
    out["eigenvalue"] = sp.expand(A - B * (dl + s * g) / (2 * B))
    _zero(out["eigenvalue"] - (A + D - s * g) / 2, "eigenvalue of the slope (A - D + s g)/(2B)")
    _zero(out["root_k"] * out["root_c"] - (-C / B), "Vieta")
    lam_s = sp.Symbol("lambda_s", positive=True)    # the slopes of 2^e M_s are those of M_s
    for name in ("root_k", "root_c"):
        _zero(out[name].xreplace({A: lam_s * A, B: lam_s * B, C: lam_s * C, D: lam_s * D, g: lam_s * g}) - out[name],
              f"{name} is homogeneous of degree 0 in (A, B, C, D, g)")

    # Möbius transport of a slope by m_j, forward and its inverse
    w = m_ar * sp.Matrix([1, -u])
    fwd = -w[1] / w[0]
    out["forward"] = fwd
    sol = solve_linear(sp.Eq(un, fwd), u)
    if len(sol) != 1:
        raise AssertionError("transport is not invertible")
    out["backward"] = sp.expand(sol[0])
    _zero(fwd.xreplace({u: out["backward"]}) - un, "backward o forward = id")

    # derivatives of the trace through one site: tr(dm P S)
    Pm = sp.Matrix([[P00, P01], [P10, P11]])
    Sm = sp.Matrix([[S00, S01], [S10, S11]])
    dm_da = m_ar.diff(a)                                          # d/dp_j = d/da
    dm_dr = m_ar.diff(r)
    out["dtr_dp"] = sp.expand((dm_da * Pm * Sm).trace())
    out["dtr_dr"] = sp.expand((dm_dr * Pm * Sm).trace())
    # chain rule: r_{j-1} = exp(q_j - q_{j-1}), r_j = exp(q_{j+1} - q_j)
    qm, q0, qp = sp.symbols("qm q0 qp", real=True)
    rp_expr, r_expr = sp.exp(q0 - qm), sp.exp(qp - q0)
    chain = sp.diff(rp_expr, q0) * dr_prev + sp.diff(r_expr, q0) * dr
    out["dtr_dq"] = sp.expand(chain.xreplace({rp_expr: r_prev, r_expr: r}))
    if out["dtr_dq"].free_symbols - {r_prev, dr_prev, r, dr}:
        raise AssertionError("chain rule did not close")

    # read-out of the step (scaled slopes u = E y, w = E z; d = w - u; x/E = 2 mu/d)
    out["dq"] = log1p(-2 * mu / dj)
    # 2 mu (f_j g_{j+1} - f_{j+1} g_j), f = u/d, g = w/d = f + 1: no two fractions near -1 cancelled (as the
    # closed form, symbt.codegen.transport.read_out); Quotient keeps each division (no slope products)
    out["eta_diff"] = 2 * mu * (Quotient(uj, dj) * Quotient(wn1, dn1) - Quotient(un1, dn1) * Quotient(wj, dj))
    eta = lambda uu, dd: mu + 2 * mu * uu / dd  # noqa: E731
    plain = out["eta_diff"].replace(Quotient, lambda x, y: x / y).xreplace({wj: dj + uj, wn1: dn1 + un1})
    _zero(eta(uj, dj) - eta(un1, dn1) - plain, "p~ - p = eta_j - eta_{j+1}")
    out["positivity"] = 1 - 2 * mu / dj                          # Etilde_j/E_j = exp(q~_j - q_j) > 0
    # Dapp's x = E_1 (x_1/E_1) = e^{q_1} 2 mu/d_1 and y = y_1 = u_1/E_1 (eq. xy)
    out["dapp_x"] = sp.exp(q) * 2 * mu / dj
    out["dapp_y"] = sp.exp(-q) * uj
    # real Phi and its gradient from the traces (as in symbt.codegen.derive; d/dx of
    # sgn(t) arccosh(|t|/2) = t_x/sqrt(t^2 - 4), checked there)
    out["phi"] = phi_of(tr1, tr2)
    out["grad"] = -branch * (x1 / sp.sqrt(disc(tr1)) + x2 / sp.sqrt(disc(tr2)))
    # near a closed gap (|t| ~ 2, M ~ +-I) the trace's discriminant from the entries: ``disc_entries = (A - D)^2 +
    # 4BC = 4^-e (tr^2 - 4)`` as det M = 1, without the cancellation of ``t -+ two``, where ``near_closed`` (its
    # scale the smaller; symbt.codegen.closed_gap); imported here, the lines above are named by mutant ids
    from .closed_gap import entries_discriminant, near_closed_gap

    out["disc_entries"] = entries_discriminant(A, B, C, D)
    _zero(out["disc_entries"] - ((A + D) ** 2 - 4 * (A * D - B * C)), "(A - D)^2 + 4BC = tr^2 - 4 det")
    out["near_closed"] = near_closed_gap(A, B, C, D, two)
    return out
