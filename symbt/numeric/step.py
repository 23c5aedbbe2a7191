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

from ._input import (
    IV,
    as_state_pair,
    check_branch,
    pick_context,
    prepare_spectral_pair,
    sites,
    to_output,
    validate_float_pair,
)
from .context import COMPLEX, FLOAT
from .errors import NoRealMapError, NumericRangeError
from .lax import monodromy, neighbour_ratios

__all__ = ["bt_step", "step_core", "SlopeData"]

_GUARD_DIGITS = 12


class SlopeData:
    """Eigenvector data at one spectral parameter (internal, documented for tests).

    ``u`` -- list of scaled slopes ``E_j * (slope)_j``, ``trace_ok`` -- the
    scaled ``tr**2 - 4`` (positive iff ``|tr| > 2``), ``forward`` -- transport
    direction used (selected eigenvalue has ``|v| >= 1``), ``t, g, e`` -- scaled
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
    two = ctx.ldexp(2.0, -e) if not isinstance(e, int) or e else 2.0
    disc = (t - two) * (t + two)          # tr^2 - 4 without cancellation (scaled)
    g = ctx.sqrt(disc)
    data = SlopeData(trace_ok=disc, t=t, g=g, e=e, u=None, forward=None)
    # |(t - s g)/2| >= 1  <=>  Re(t conj(s g)) <= 0  -> dominant -> transport forward
    tg = ctx.half_plane(t, g)
    fwd = ctx.neg(tg) if s > 0 else tg
    data.forward = fwd
    if not need_slopes:
        return data
    dl = A - D
    sg, plus = ctx.align(g, dl)           # k = dl + sign(dl) g has no cancellation
    k = dl + sg
    # roots of B u^2 - (A-D) u - C = 0 are k/(2B) and -2C/k; want (dl + s g)/(2B)
    target_is_k = plus if s > 0 else ctx.neg(plus)
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


def _where_text(mask, shape, offset=0):
    idx = np.flatnonzero(np.logical_not(np.asarray(mask))) + offset
    if not shape or idx.size == 0:
        return (), ""
    where = [tuple(int(i) for i in np.unravel_index(k, shape)) for k in idx[:5]]
    return where, " (batch index %s%s)" % (", ".join(map(str, where)), ", ..." if idx.size > 5 else "")


def step_core(ctx, P, Q, lam0, mu, branch, *, check_real=True, shape=(), offset=0):
    """The step on per-site lists in context ``ctx``; returns ``(P~, Q~, aux)``.

    ``aux`` holds ``u``, ``w``, ``gq = u/(u-w)`` (lists; ``eta_j = mu - 2 mu gq_j``)
    and the two :class:`SlopeData`.
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
            if not ctx.all_positive(S.trace_ok):
                where, txt = _where_text(ctx.positive(S.trace_ok), shape, offset)
                raise NoRealMapError(
                    "no real Bäcklund map: |tr L(%s)| <= 2, the spectral parameter lies "
                    "in a band%s" % (name, txt), condition="trace", where=where)
    u, w = S1.u, S2.u
    two_mu = 2 * mu
    dn = [u[j] - w[j] for j in range(N)]          # = -(z_j - y_j) E_j
    xr = [two_mu / dn[j] for j in range(N)]       # = -x_j / E_j = Etilde_j / E_j - 1
    if check_real:
        bad = [j for j in range(N) if not ctx.all_positive(xr[j] + 1)]
        if bad:
            ok = ctx.positive(xr[bad[0]] + 1)
            for j in bad[1:]:
                ok = ok & ctx.positive(xr[j] + 1)
            where, txt = _where_text(ok, shape, offset)
            raise NoRealMapError(
                "no real Bäcklund map: some Etilde_j = E_j - x_j <= 0 (lam1 and lam2 "
                "lie in different spectral gaps)%s" % txt, condition="positivity", where=where)
    Qn = [Q[j] + ctx.log1p(xr[j]) for j in range(N)]
    gq = [u[j] / dn[j] for j in range(N)]         # = -u_j / d_j;  eta_j = mu - 2 mu gq_j
    Pn = [P[j] + two_mu * (gq[(j + 1) % N] - gq[j]) for j in range(N)]
    aux = {"u": u, "w": w, "S1": S1, "S2": S2, "gq": gq}
    return Pn, Qn, aux


#: rows of the batch processed at once (keeps temporaries in cache; see benchmarks)
BLOCK_ELEMENTS = 1 << 17


def _float_block(pa, qa, lam0, mu, branch, allow_complex, shape, offset):
    """Step for one block of rows ``pa, qa`` (B, N); returns (B, N) arrays."""
    P, Q = sites(pa), sites(qa)
    with np.errstate(all="ignore"):
        try:
            Pn, Qn, _ = step_core(FLOAT, P, Q, lam0, mu, branch, shape=shape, offset=offset)
        except NoRealMapError:
            if not allow_complex:
                raise
            Pc = [x.astype(np.complex128) for x in P]
            Qc = [x.astype(np.complex128) for x in Q]
            Pn, Qn, _ = step_core(COMPLEX, Pc, Qc, lam0, mu, branch, check_real=False)
        outp = np.stack(Pn, axis=-1)
        outq = np.stack(Qn, axis=-1)
        if not (np.isfinite(outp.sum()) and np.isfinite(outq.sum())):
            if not (np.all(np.isfinite(outp)) and np.all(np.isfinite(outq))):
                raise NumericRangeError(
                    "non-finite intermediate in the float64 step (degenerate eigenvector "
                    "or overflow); use mpmath inputs")
    return outp, outq


def _float_step(pa, qa, lam0, mu, branch, allow_complex, shape):
    B, N = pa.shape
    block = max(256, BLOCK_ELEMENTS // N)
    outp = np.empty((B, N))
    outq = np.empty((B, N))
    for s0 in range(0, B, block):
        sl = slice(s0, min(B, s0 + block))
        l0 = lam0[sl] if np.ndim(lam0) else lam0
        m = mu[sl] if np.ndim(mu) else mu
        if np.ndim(m) and not np.all(m != 0):
            nz = np.flatnonzero(m != 0)
            rp, rq = pa[sl].copy(), qa[sl].copy()
            if nz.size:
                bp, bq = _float_block(pa[sl][nz], qa[sl][nz], l0[nz] if np.ndim(l0) else l0,
                                      m[nz], branch, allow_complex, (), 0)
                if np.iscomplexobj(bp):
                    rp, rq = rp.astype(complex), rq.astype(complex)
                rp[nz], rq[nz] = bp, bq
            bp, bq = rp, rq
        else:
            bp, bq = _float_block(pa[sl], qa[sl], l0, m, branch, allow_complex, shape, s0)
        if np.iscomplexobj(bp) and not np.iscomplexobj(outp):
            outp, outq = outp.astype(complex), outq.astype(complex)
        outp[sl], outq[sl] = bp, bq
    return outp, outq


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
    -0.0861422421882023
    """
    branch = check_branch(branch)
    ctx = pick_context(p, q, lam0, mu)
    if ctx is FLOAT:
        pa, qa, shape = validate_float_pair(p, q)
        lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
        N = pa.shape[-1]
        if np.ndim(mu) == 0 and mu == 0:
            return pa.reshape(shape + (N,)).copy(), qa.reshape(shape + (N,)).copy()
        outp, outq = _float_step(pa, qa, lam0, mu, branch, allow_complex, shape)
        return outp.reshape(shape + (N,)), outq.reshape(shape + (N,))
    ctx, P, Q, shape = as_state_pair(p, q, lam0, mu)
    lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
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
