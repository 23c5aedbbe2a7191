r"""The fused scalar step, written once: eigenvector slopes of both spectral parameters, the existence
decisions and the update, against the names of an arithmetic.

:mod:`symbt.numeric.core.step` computes the step on whole arrays through a context; the compiled kernels
need it per state, in one pass, without allocation.  That scalar form is this module, instantiated by
:func:`symbt.numeric.core.compile.instantiate` for float64 (:mod:`symbt.numeric.float64.kernels`, numba or
plain Python) and for quad-double (:mod:`symbt.numeric.multiprec.qd_step`).  The operations and their
order are those of :func:`~symbt.numeric.core.step.step_core` (module docstring there: scaled monodromy,
slope at site 1 without cancellation, transport in the contracting direction, cancellation-free
read-out).

The arithmetic (module globals replaced per instantiation; here they are unbound):

* numbers: ``add, sub, mul, div, neg, sqrt``; ``add_d(x, c)`` adds a double, ``mul2(x, c)`` multiplies by
  a power of two (exact); ``hi(x)`` the double nearest ``x``, whose sign every decision reads;
  ``ld(a, j)`` / ``st(a, j, x)`` read and write site ``j`` of a state array;
* hooks, where one arithmetic needs what the other does not (quad-double computes ``root_slope`` with its
  operations, ``k = dl +- g`` divided once) -- float64 forms ``lam + p_j`` from a
  double-double spectral parameter rounded once (``lam_add(lam, lo, p_j)``, two-sum) with the low parts
  ``lam_split(lam1, lam2, two_mu)`` that make ``lam1 - lam2`` equal ``two_mu`` exactly (else every step
  would be the map of parameters an ulp inconsistent with its read-out: a bias, linear drift), rounds the slope
  at site 1 once (``root_slope(A, D, dl, g, B, C, two, plus, wantk)``: ``A +- D`` exact, ``k = dl +- g`` and the root
  of ``(A + D)**2 - two**2`` as double-doubles, else the rounding of the orbit's eigenvalue against ``ulp(A)`` repeats
  in every step: the same kind of bias), tracks the product of the
  entrywise absolute values (the trace's rounding scale) and the cancellation in ``lam + p_j``
  (``track_init``, ``track``), rescales the monodromy by powers of two (``rescale``, ``rescale_last``,
  ``two_of``), tests its range (``in_range``, ``disc_fits``, ``bounded``) and its condition
  (``decided``, two-tier: the cheap bound, and where it fails the sharp one of
  :func:`~symbt.numeric.core.condition.sharp_trace_kappa` from ``p, r, lam, lo``; ``step_kappa``,
  ``trusted``, and ``sharpen``, the sharp tier of ``k_t`` where a site fails ``trusted``: status
  ``ILLCOND``), and carries the positions as
  neighbour ratios and double-double factors; quad-double tests finiteness and carries the positions
  themselves (``advance``).

Status codes: :mod:`symbt.numeric.core.limits`; the first failure wins (per state, sites in order).

Example (the float64 instantiation, plain Python):

>>> import numpy as np
>>> from symbt.numeric.float64.kernels import python_kernels
>>> K = python_kernels()
>>> p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
>>> u, tt = np.empty(3), np.zeros(4)
>>> K["slopes"](p, r, 15.0, 0.0, 1, u, 1, tt, 0), round(float(tt[0]), 4)     # lam1 = 15: the paper's example
(0, -2021.2173)
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .limits import ILLCOND, OK, POSITIVITY, RANGE, TRACE1, TRACE2

__all__ = ["SOURCE", "slopes", "step"]


def _unbound(*args: Any) -> Any:
    raise TypeError("the fused step runs only instantiated with an arithmetic "
                    "(symbt.numeric.core.compile.instantiate)")


# the arithmetic (see the module docstring), bound by instantiate()
add = sub = mul = div = neg = sqrt = add_d = mul2 = hi = ld = st = _unbound
track_init = track = rescale = rescale_last = in_range = two_of = decided = disc_fits = _unbound
step_kappa = sharpen = bounded = trusted = advance = lam_add = lam_split = root_slope = _unbound


def slopes(p: Any, r: Any, lam: Any, lo: Any, s: int, u: Any, code: int, tt: Any, i: int) -> int:
    """Scaled eigenvector slopes at ``lam + lo`` (sign ``s``) into ``u``; ``tt[i]`` the trace's leading double.

    Every ``a_j = lam + lo + p_j`` (monodromy and transport alike) is ``lam_add(lam, lo, p_j)``.

    The eigenvector of the eigenvalue ``(tr - s sqrt(tr**2 - 4)) / 2`` of the scaled monodromy of
    ``m_j = [[lam + p_j, -1], [r_j, 0]]``; returns ``OK``, ``code`` (``|tr| <= 2``), ``RANGE`` or
    ``ILLCOND``.
    """
    N = p.shape[0]
    a0 = lam_add(lam, lo, ld(p, 0))
    a1 = lam_add(lam, lo, ld(p, 1))
    r0 = ld(r, 0)
    r1 = ld(r, 1)
    A = sub(mul(a1, a0), r0)            # m_2 m_1, written out: m_1's zero and -1 cost nothing
    B = neg(a1)
    C = mul(r1, a0)
    D = neg(r1)
    aux = track(track_init(lam, ld(p, 0), a0, r0), lam, ld(p, 1), a1, r1)
    A, B, C, D, aux = rescale(A, B, C, D, aux)
    for j in range(2, N):
        aj = lam_add(lam, lo, ld(p, j))
        rj = ld(r, j)
        A, B, C, D = sub(mul(aj, A), C), sub(mul(aj, B), D), mul(rj, A), mul(rj, B)
        aux = track(aux, lam, ld(p, j), aj, rj)
        A, B, C, D, aux = rescale(A, B, C, D, aux)
    A, B, C, D, aux = rescale_last(A, B, C, D, aux)
    t = add(A, D)
    tt[i] = hi(t)
    if not in_range(A, B, C, D, t):
        return RANGE
    two = two_of(aux)                   # 2 in the monodromy's scale
    disc = mul(add_d(t, -two), add_d(t, two))     # tr**2 - 4 without cancellation
    if not decided(aux, t, disc, tt, i, p, r, lam, lo):     # cheap bound, else the sharp one
        return ILLCOND
    if not hi(disc) > 0.0:
        return code
    if not disc_fits(disc):
        return RANGE
    g = sqrt(disc)
    dl = sub(A, D)
    plus = hi(dl) >= 0.0
    # the roots of B u**2 - (A - D) u - C = 0 are k / (2B) and -2C / k, k = dl + sign(dl) g (no cancellation);
    # the wanted one is (dl + s g) / (2B)
    u1 = root_slope(A, D, dl, g, B, C, two, plus, plus == (s > 0))
    st(u, 0, u1)
    if (hi(t) < 0.0) if s > 0 else (hi(t) >= 0.0):      # dominant eigenvalue: transport forward
        for j in range(N - 1):
            st(u, j + 1, div(neg(ld(r, j)), add(lam_add(lam, lo, ld(p, j)), ld(u, j))))
    else:
        nxt = u1
        for j in range(N - 1, 0, -1):
            nxt = sub(neg(lam_add(lam, lo, ld(p, j))), div(ld(r, j), nxt))
            st(u, j, nxt)
    return OK


def step(p: Any, r: Any, pos: Any, lam1: Any, lam2: Any, two_mu: Any, branch: int, u: Any, w: Any, xr: Any,
         gq: Any, tt: Any) -> int:
    """One step in place: ``p`` and the positions ``pos`` (with the ratios ``r``) advance; the status.

    ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu``, ``two_mu = 2 mu``; ``u, w, xr, gq`` are work arrays of
    the state's shape, ``tt`` four doubles (the traces and, in float64, their condition).  The slopes
    are taken at ``lam1 + lo1`` and ``lam2 + lo2`` (``lam_split``), whose difference is ``two_mu``.
    """
    N = p.shape[0]
    lo1, lo2 = lam_split(lam1, lam2, two_mu)
    s = slopes(p, r, lam1, lo1, branch, u, TRACE1, tt, 0)
    if s != OK:
        return s
    s = slopes(p, r, lam2, lo2, -branch, w, TRACE2, tt, 1)
    if s != OK:
        return s
    if (tt[0] < 0.0) != (tt[1] < 0.0):
        return POSITIVITY        # lam1, lam2 in different gaps (|tr| > 2 decided, so the signs are)
    kt = step_kappa(tt)
    sharp = False
    for j in range(N):
        uj = ld(u, j)
        wj = ld(w, j)
        dn = sub(uj, wj)
        x = div(two_mu, dn)                    # xr_j = Etilde_j / E_j - 1
        st(xr, j, x)
        st(gq, j, div(uj, dn))                 # eta_j = mu - 2 mu gq_j
        if not bounded(x):
            return RANGE
        if not trusted(kt, uj, wj, dn, x):
            if sharp:
                return ILLCOND
            # the cheap condition fails: the sharp one (computed once; the sites before passed a larger kt)
            kt = sharpen(tt, p, r, lam1, lo1, lam2, lo2)
            sharp = True
            if not trusted(kt, uj, wj, dn, x):
                return ILLCOND
        if not hi(add_d(x, 1.0)) > 0.0:
            return POSITIVITY
    for j in range(N):
        jn = j + 1 if j + 1 < N else 0
        pj = add(ld(p, j), mul(two_mu, sub(ld(gq, jn), ld(gq, j))))
        st(p, j, pj)
        if not advance(r, pos, j, ld(xr, j), ld(xr, jn), pj):
            return RANGE
    return OK


#: the source in dependency order, for :func:`~symbt.numeric.core.compile.instantiate`
SOURCE: dict[str, Callable[..., Any]] = {"slopes": slopes, "step": step}
