r"""One Bäcklund step ``(p, q) -> (p~, q~)`` of the periodic Toda chain, O(N).

Mathematics (paper eqs. ``D``, ``xy``, ``lam0mu``, ``xyqqt``, ``imptransf``)
---------------------------------------------------------------------------
With ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu`` and ``L = l_N ... l_1`` the map is
read off from two eigenvector slopes: ``(1, -y_1)`` is the eigenvector of
``L(lam1)`` with eigenvalue ``(tr1 - g1)/2`` and ``(1, -z_1)`` that of ``L(lam2)``
with eigenvalue ``(tr2 + g2)/2``, ``g_i = branch * sqrt(tr_i**2 - 4)`` (positive
root).  Slopes at the other sites follow from the Möbius action of ``l_j``,
``y_{j+1} = -1 / (E_j (lam1 + p_j + E_j y_j))`` (same for ``z`` at ``lam2``), and

    x_j = 2 mu / (z_j - y_j),   Etilde_j = E_j - x_j,   eta_j = x_j y_j + mu,
    p~_j = p_j + eta_j - eta_{j+1}        (indices mod N).

Stable formulation (what is actually computed)
----------------------------------------------
1. *Scaled slopes.*  ``u_j = E_j y_j``, ``w_j = E_j z_j`` are eigenvector slopes of
   the scaled monodromy ``M = m_N ... m_1`` with ``m_j = [[lam + p_j, -1],
   [r_j, 0]]``, ``r_j = exp(q_{j+1} - q_j)`` (see :mod:`.lax`).  The Möbius
   transport becomes ``u_{j+1} = -r_j / (lam1 + p_j + u_j)``.  Only neighbour
   differences of ``q`` appear, so the map commutes exactly with ``q -> q + c``
   and never forms ``exp(q_j)``.
2. *Slope at site 1 without cancellation.*  The two roots of
   ``B u**2 - (A - D) u - C = 0`` are ``k / (2B)`` and ``-2C / k`` with
   ``k = (A - D) + sign(A - D) * sqrt(tr**2 - 4)`` (no cancellation in ``k``);
   ``tr**2 - 4`` is formed as ``(tr - 2)(tr + 2)``.  The branch decides which root
   is wanted.
3. *Transport in the contracting direction.*  Under forward transport the
   eigenvector of the larger eigenvalue ``|v| > 1`` is attracting (errors shrink
   by ``1/v**2`` per period), the other is attracting for the inverse map
   ``u_j = -(lam + p_j) - r_j / u_{j+1}`` run from site ``N+1 = 1`` downwards.
   Each slope is transported in its own contracting direction (decided per
   batch element from the sign of ``tr * g``).  The literal route transports
   one of them forward and loses ``log10(v**2)`` digits (7 digits for the
   paper's example).
4. *Cancellation-free read-out.*  With ``d_j = w_j - u_j`` (an O(1) difference
   of the two *different* eigenvector slopes; it does not vanish as ``mu -> 0``):
   ``x_j / E_j = 2 mu / d_j``, ``q~_j = q_j + log1p(-2 mu / d_j)``,
   ``eta_j = mu + 2 mu u_j / d_j`` and ``p~_j - p_j = 2 mu (u_j/d_j - u_{j+1}/d_{j+1})``:
   both increments are ``mu`` times O(1) quantities computed to full relative
   accuracy, so small ``mu`` costs nothing (the literal ``E - x`` and
   ``eta_j - eta_{j+1}`` lose ``log10(1/mu)`` digits).

Existence: the real map needs ``|tr L(lam_i)| > 2`` and ``2 mu / d_j < 1`` for all
``j`` (``Etilde_j > 0``); otherwise :class:`NoRealMapError` (or a complex
result with ``allow_complex=True``).  ``branch = -1`` is the inverse of
``branch = +1`` and equals ``branch = +1`` at ``-mu``.

Example
-------
>>> import numpy as np
>>> from symbt.numeric import bt_step
>>> pt, qt = bt_step([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0)
>>> np.round(pt, 8)
array([-19.99656766,   9.78635495,   1.21021272])
>>> p2, q2 = bt_step(pt, qt, 10.0, 5.0, branch=-1)       # inverse step
>>> bool(np.allclose(p2, [-20, 10, 1], rtol=0, atol=1e-12))
True
"""

from __future__ import annotations

import mpmath
import numpy as np

from ._input import MP, IV, as_state_pair, check_branch, prepare_scalar, to_output
from .context import COMPLEX, FLOAT
from .errors import NoRealMapError, NumericRangeError
from .lax import monodromy, neighbour_ratios

__all__ = ["bt_step", "step_core", "SlopeData"]

_GUARD_DIGITS = 12


class SlopeData:
    """Eigenvector data at one spectral parameter (internal, documented for tests).

    ``u`` -- list of scaled slopes ``E_j * (slope)_j``, ``trace_ok`` -- mask
    ``|tr| > 2``, ``forward`` -- transport direction used, ``logv`` -- ``log|v|``
    of the selected eigenvalue (real contexts only), ``t, g, e`` -- scaled
    trace, ``sqrt(t**2 - 4**(1-e))`` and exponent.
    """

    __slots__ = ("u", "trace_ok", "forward", "t", "g", "e")

    def __init__(self, **kw):
        for k, v in kw.items():
            setattr(self, k, v)


def _forward(a, r, u1):
    u = [u1]
    for j in range(len(a) - 1):
        u.append(-r[j] / (a[j] + u[j]))
    return u


def _backward(a, r, u1):
    N = len(a)
    u = [None] * N
    u[0] = nxt = u1
    for j in range(N - 1, 0, -1):
        nxt = u[j] = -a[j] - r[j] / nxt
    return u


def eigen_slopes(ctx, a, r, s, need_slopes=True):
    """Slopes of the eigenvector with eigenvalue ``(tr - s*sqrt(tr^2-4))/2`` at every site.

    ``a_j = lam + p_j``; ``s = +1`` gives the paper's ``y`` (for ``branch=+1``),
    ``s = -1`` its ``z``.  See the module docstring for the formulas.
    """
    A, B, C, D, e = monodromy(ctx, a, r)
    t = A + D
    dl = A - D
    two = ctx.ldexp(2.0, -e) if not isinstance(e, int) or e else 2.0
    disc = (t - two) * (t + two)
    trace_ok = ctx.positive(disc)
    g = ctx.sqrt(disc)
    data = SlopeData(trace_ok=trace_ok, t=t, g=g, e=e, u=None, forward=None)
    c = ctx.re_dot(t, g)
    fwd = (c <= 0) if s > 0 else (c >= 0)
    data.forward = fwd
    if not need_slopes:
        return data
    cpos = ctx.re_dot(dl, g) >= 0
    eps = ctx.sign_as_value(cpos)
    k = dl + eps * g
    target_is_k = cpos if s > 0 else ctx.neg(cpos)
    u1 = ctx.select(target_is_k, lambda: k / (2 * B), lambda: -2 * C / k)
    if ctx.all(fwd):
        u = _forward(a, r, u1)
    elif not ctx.any(fwd):
        u = _backward(a, r, u1)
    else:
        uf, ub = _forward(a, r, u1), _backward(a, r, u1)
        u = [np.where(fwd, x, y) for x, y in zip(uf, ub)]
    data.u = u
    return data


def _where_text(mask, shape):
    idx = np.flatnonzero(np.logical_not(np.asarray(mask)))
    if not shape or idx.size == 0:
        return (), ""
    where = [tuple(int(i) for i in np.unravel_index(k, shape)) for k in idx[:5]]
    return where, " (batch index %s%s)" % (", ".join(map(str, where)), ", ..." if idx.size > 5 else "")


def step_core(ctx, P, Q, lam0, mu, branch, *, check_real=True, shape=()):
    """The step on per-site lists in context ``ctx``; returns ``(P~, Q~, aux)``.

    ``aux`` holds ``u``, ``w``, ``d`` (lists) and the two :class:`SlopeData`.
    Raises :class:`NoRealMapError` when ``check_real`` and the real map fails.
    """
    N = len(P)
    r = neighbour_ratios(ctx, Q)
    lam1, lam2 = lam0 + mu, lam0 - mu
    a1 = [lam1 + pj for pj in P]
    a2 = [lam2 + pj for pj in P]
    S1 = eigen_slopes(ctx, a1, r, branch)
    S2 = eigen_slopes(ctx, a2, r, -branch)
    if check_real:
        for name, S in (("lam1 = lam0 + mu", S1), ("lam2 = lam0 - mu", S2)):
            if not ctx.all(S.trace_ok):
                where, txt = _where_text(S.trace_ok, shape)
                raise NoRealMapError(
                    "no real Bäcklund map: |tr L(%s)| <= 2, the spectral parameter lies "
                    "in a band%s" % (name, txt), condition="trace", where=where)
    u, w = S1.u, S2.u
    d = [w[j] - u[j] for j in range(N)]
    rho = [2 * mu / d[j] for j in range(N)]
    if check_real:
        ok = None
        for j in range(N):
            okj = ctx.positive(1 - rho[j])
            ok = okj if ok is None else (ok & okj if ctx is FLOAT else (ok and okj))
        if not ctx.all(ok):
            where, txt = _where_text(ok, shape)
            raise NoRealMapError(
                "no real Bäcklund map: some Etilde_j = E_j - x_j <= 0 (lam1 and lam2 "
                "lie in different spectral gaps)%s" % txt, condition="positivity", where=where)
    Qn = [Q[j] + ctx.log1p(-rho[j]) for j in range(N)]
    gq = [u[j] / d[j] for j in range(N)]
    Pn = [P[j] + 2 * mu * (gq[j] - gq[(j + 1) % N]) for j in range(N)]
    aux = {"u": u, "w": w, "d": d, "S1": S1, "S2": S2}
    return Pn, Qn, aux


def _float_step(P, Q, lam0, mu, branch, allow_complex, shape):
    with np.errstate(all="ignore"):
        try:
            Pn, Qn, _ = step_core(FLOAT, P, Q, lam0, mu, branch, shape=shape)
            ctx = FLOAT
        except NoRealMapError:
            if not allow_complex:
                raise
            ctx = COMPLEX
            Pc = [x.astype(np.complex128) for x in P]
            Qc = [x.astype(np.complex128) for x in Q]
            Pn, Qn, _ = step_core(COMPLEX, Pc, Qc, lam0, mu, branch, check_real=False, shape=shape)
    if not ctx.isfinite_all(Pn + Qn):
        raise NumericRangeError("non-finite intermediate in the float64 step "
                                "(degenerate eigenvector or overflow); use mpmath inputs")
    return Pn, Qn


def bt_step(p, q, lam0, mu, *, branch=1, allow_complex=False):
    """One Bäcklund step of the periodic Toda chain.

    Parameters
    ----------
    p, q : array_like, shape ``batch + (N,)``, N >= 2 -- or flat sequences of
        ``mpmath.mpf`` (a single state; ``mpmath.iv`` intervals also accepted).
    lam0, mu : real; arrays broadcastable to ``batch`` are accepted on the
        float path.  ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu``.
    branch : +1 or -1.  ``branch=-1`` is the inverse map of ``branch=+1``.
    allow_complex : return the complex continuation instead of raising
        :class:`NoRealMapError` (float path: complex128 arrays; mpmath: mpc
        values where needed).

    Returns
    -------
    (p_new, q_new) : float64 arrays of the input shape, or lists of mpf at the
        current ``mp.dps`` (computed with a few guard digits).

    Raises
    ------
    InvalidInputError, NoRealMapError, NumericRangeError

    ``mu == 0`` returns copies of the input.  The algorithm and its stability
    are described in the module docstring of :mod:`symbt.numeric.step`.

    >>> from symbt.numeric import bt_step
    >>> import mpmath
    >>> with mpmath.workdps(30):
    ...     pt, qt = bt_step([mpmath.mpf(-20), 10, 1], [1, 0, mpmath.mpf('0.9')], 10, 5)
    ...     print(mpmath.nstr(qt[0], 15))
    -0.0861422421882035
    """
    branch = check_branch(branch)
    ctx, P, Q, shape = as_state_pair(p, q, lam0, mu)
    lam0 = prepare_scalar(ctx, lam0, shape, "lam0")
    mu = prepare_scalar(ctx, mu, shape, "mu")
    if ctx is FLOAT:
        if np.ndim(mu) == 0 and mu == 0:
            return to_output(ctx, P, shape).copy(), to_output(ctx, Q, shape).copy()
        nz = None
        if np.ndim(mu) > 0 and not np.all(mu != 0):
            nz = mu != 0
            Ps, Qs = [x[nz] for x in P], [x[nz] for x in Q]
            l0s = lam0[nz] if np.ndim(lam0) else lam0
            Pn, Qn = _float_step(Ps, Qs, l0s, mu[nz], branch, allow_complex, (int(nz.sum()),))
            dt = Pn[0].dtype
            Pn = [_merge(P[j], nz, Pn[j], dt) for j in range(len(P))]
            Qn = [_merge(Q[j], nz, Qn[j], dt) for j in range(len(Q))]
        else:
            Pn, Qn = _float_step(P, Q, lam0, mu, branch, allow_complex, shape)
        return to_output(ctx, Pn, shape), to_output(ctx, Qn, shape)
    # mpmath / interval path
    if mu == 0:
        return to_output(ctx, P, ()), to_output(ctx, Q, ())
    with mpmath.workdps(mpmath.mp.dps + _GUARD_DIGITS):
        try:
            Pn, Qn, _ = step_core(ctx, P, Q, lam0, mu, branch,
                                  check_real=not allow_complex or ctx is IV)
        except ZeroDivisionError as exc:
            raise NumericRangeError("degenerate eigenvector (division by zero)") from exc
        if not ctx.isfinite_all(Pn + Qn):
            raise NumericRangeError("non-finite result in the mpmath step")
    return to_output(ctx, Pn, ()), to_output(ctx, Qn, ())


def _merge(full, mask, part, dtype):
    out = np.array(full, dtype=dtype, copy=True)
    out[mask] = part
    return out
