r"""Spectral quantities at high precision: the real Phi, its gradient and the flow coefficients c_k.

* :func:`phi_real` -- :math:`\Phi = -b(\operatorname{sgn}\operatorname{tr}_1
  \operatorname{arccosh}|\operatorname{tr}_1|/2 + \operatorname{sgn}\operatorname{tr}_2
  \operatorname{arccosh}|\operatorname{tr}_2|/2)` at :math:`\lambda_0\pm\mu`;
* :func:`flow_coefficients_mp` -- the constants of eq. ``eqdisc``,
  :math:`c_k = -b\int_{\lambda_0-\mu}^{\lambda_0+\mu}\lambda^k/\sqrt{\operatorname{tr}L(\lambda)^2-4}\,d\lambda`
  (positive root), by the one routine :func:`symbt.numeric.flow_coefficients`, and their closed-form
  Jacobian in (lam0, mu).
"""
from __future__ import annotations

from collections.abc import Iterable, Sequence

import mpmath as mp

from ..numeric import flow_coefficients
from .literal import MPLike, phi_from_traces
from .trace import hamiltonians, trace, trace_gap, trace_gradient

__all__ = ["NoRealFlowError", "phi_real", "phi_gradient", "flow_coefficients_mp", "flow_coefficients_jacobian"]


class NoRealFlowError(ValueError):
    """|tr L| <= 2 somewhere on [lam0 - mu, lam0 + mu]: Phi and the c_k are not real there."""


def phi_real(p: Sequence[MPLike], q: Sequence[MPLike], lam0: mp.mpf, mu: mp.mpf, branch: int) -> mp.mpf:
    """Real Phi = -b (sgn tr1 arccosh(|tr1|/2) + sgn tr2 arccosh(|tr2|/2)), tr_i = tr L(lam0 +- mu)."""
    return phi_from_traces(trace(lam0 + mu, p, q), trace(lam0 - mu, p, q), branch)


def phi_gradient(p: Sequence[MPLike], q: Sequence[MPLike], lam0: mp.mpf, mu: mp.mpf,
                 branch: int) -> tuple[list[mp.mpf], list[mp.mpf]]:
    """``(dPhi/dp, dPhi/dq)``: dPhi/dtr_i = -b / sqrt(tr_i^2 - 4) (positive root, either sign of tr)."""
    N = len(p)
    gp, gq = [mp.mpf(0)] * N, [mp.mpf(0)] * N
    for lv in (lam0 + mu, lam0 - mu):
        t = trace(lv, p, q)
        if abs(t) <= 2:
            raise NoRealFlowError(f"|tr L({mp.nstr(lv, 8)})| <= 2")
        w = -branch / mp.sqrt(t ** 2 - 4)
        dp, dq = trace_gradient(lv, p, q)
        gp = [g + w * d for g, d in zip(gp, dp)]
        gq = [g + w * d for g, d in zip(gq, dq)]
    return gp, gq


def flow_coefficients_mp(p: Sequence[MPLike], q: Sequence[MPLike], lam0: MPLike, mu: MPLike, branch: int = 1, *,
                         check: bool = True, ks: Iterable[int] | None = None) -> list[mp.mpf | None]:
    """``[c_0, ..., c_N]``, c_k = -b int_{lam0-mu}^{lam0+mu} lam^k / sqrt(tr L^2 - 4) dlam (eq. ``eqdisc``).

    The positive root is used for both signs of tr L; ``branch`` b = +1 is the
    branch of the printed eq. ``eqdisc`` (see :mod:`symbt.claims.theorems`).
    ``c_N`` multiplies H_N = 1 and does not move anything.  ``ks``: compute only
    these k (the others are ``None``).  ``check``: raise :class:`NoRealFlowError`
    if |tr L| <= 2 somewhere on the interval (decided on the polynomial tr L,
    :func:`~symbt.reference.trace.trace_gap`).  The quadrature itself is the one
    routine :func:`symbt.numeric.flow_coefficients` at the current ``mp.dps``
    (scaled integrands, tanh-sinh); a negative ``mu`` is the reversed interval.
    """
    lam0, mu = mp.mpmathify(lam0), mp.mpmathify(mu)
    if check and trace_gap(p, q, lam0 - mu, lam0 + mu) <= 0:
        raise NoRealFlowError("|tr L| <= 2 inside [lam0 - mu, lam0 + mu]")
    N = len(p)
    want = list(range(N + 1)) if ks is None else [k for k in range(N + 1) if k in set(ks)]
    if mu < 0:
        mu, branch = -mu, -branch
    vals = flow_coefficients([mp.mpmathify(v) for v in p], [mp.mpmathify(v) for v in q], lam0, mu,
                             branch=branch, ks=want, check=False)
    got = dict(zip(want, vals))
    return [got.get(k) for k in range(N + 1)]


def flow_coefficients_jacobian(p: Sequence[MPLike], q: Sequence[MPLike], lam0: mp.mpf, mu: mp.mpf,
                               branch: int = 1) -> list[tuple[mp.mpf, mp.mpf]]:
    """``J[k] = (dc_k/dlam0, dc_k/dmu)`` in closed form (fundamental theorem of calculus)."""
    H = hamiltonians(p, q)
    coeffs = H[::-1]
    f = lambda x, k: x ** k / mp.sqrt(mp.polyval(coeffs, x) ** 2 - 4)
    lp, lm = lam0 + mu, lam0 - mu
    return [(-branch * (f(lp, k) - f(lm, k)), -branch * (f(lp, k) + f(lm, k))) for k in range(len(p) + 1)]


