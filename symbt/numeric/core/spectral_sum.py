r"""``lam + p_j`` for a double-double spectral parameter, rounded once: the float64 routes' one source of it.

Every float64 route (the fused kernels, the block kernel, the numpy route of
:func:`~symbt.numeric.core.step.step_core`) is given ``lam1 = fl(lam0 + mu)``,
``lam2 = fl(lam0 - mu)`` and reads the new state out with ``two_mu = 2 mu`` (exact).  Where
``lam1 - lam2 != 2 mu`` (``lam0 = 3.4, mu = 0.3``: by an ulp) every step would be the map of
spectral parameters an ulp inconsistent with its read-out -- the same error in every step, so the
invariants drift linearly in the number of steps (issue 26).  :func:`lam_split` gives the low parts
``lo1, lo2`` (``lo1 - lo2 = two_mu - (lam1 - lam2)``, split evenly, exact) that make
``(lam1 + lo1) - (lam2 + lo2) = two_mu`` exactly, and :func:`lam_add` forms
``a_j = lam + lo + p_j`` with one rounding of the exact sum in the usual case (Knuth's two-sum), so the
error of ``a_j`` depends on ``p_j`` and averages out over an orbit instead of repeating.  Where
``lo = 0`` (``lam1 - lam2 = two_mu`` exactly, e.g. the paper's example) :func:`lam_add` is
``lam + p_j`` bit for bit: the two-sum's error term never changes a correctly rounded sum.

Both work elementwise on floats and numpy arrays alike (numba compiles them into the kernels).

:func:`root_slope` is the other invariant-valued sum of the step: the slope at site 1,
``k / (2B)`` or ``-2C / k`` with ``k = (A - D) +- sqrt(t**2 - 4)``.  ``k`` is about ``2 (A - v)`` for
an eigenvalue ``v`` -- a constant of the orbit -- and ``A`` is a double: rounded, ``k`` loses
``v``'s bits below ``ulp(A)``, the same bits in every step, and ``sqrt(t**2 - 4)``, a function of
the few doubles ``t`` takes along an orbit, repeats its rounding too.  Every step was then the map
of the same slightly wrong eigenvector: a bias of one sign per orbit, linear drift (issue 26, the
paper's example).  :func:`root_slope` takes ``A + D`` and ``A - D`` exactly, keeps the square root's
low part and ``k`` as double-doubles and rounds the slope once.

>>> lam0, mu = 3.4, 0.3
>>> lam1, lam2 = lam0 + mu, lam0 - mu
>>> lo1, lo2 = lam_split(lam1, lam2, 2.0 * mu)
>>> from fractions import Fraction as Fr
>>> (Fr(lam1) + Fr(lo1)) - (Fr(lam2) + Fr(lo2)) == 2 * Fr(mu), lo1 != 0.0
(True, True)
>>> lam_add(15.0, 0.0, -20.0), lam_add(1.0, 2.0 ** -53, 2.0 ** -53)        # the second: 1 + 2**-52
(-5.0, 1.0000000000000002)
"""
from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["lam_add", "lam_split", "root_slope", "root_slope_rows"]


def lam_add(lam: Any, lo: Any, p: Any) -> Any:
    """``lam + lo + p`` (``|lo|`` below an ulp of ``lam``): the rounding error of ``lam + p`` (two-sum)
    and ``lo`` added before the one rounding that matters.

    >>> lam_add(3.7, 0.0, 1.25) == 3.7 + 1.25
    True
    """
    h = lam + p
    bp = h - lam
    err = (lam - (h - bp)) + (p - bp)
    return h + (err + lo)


def lam_split(lam1: Any, lam2: Any, two_mu: Any) -> tuple[Any, Any]:
    """Low parts ``(lo1, lo2)`` with ``(lam1 + lo1) - (lam2 + lo2) = two_mu`` (up to ``2**-104`` relative).

    ``lam1 - lam2`` is formed exactly (two-sum), the defect ``two_mu - (lam1 - lam2)`` split evenly;
    both ``0.0`` where the parameters are consistent already.

    >>> lam_split(15.0, 5.0, 10.0)
    (0.0, -0.0)
    """
    d = lam1 - lam2
    bp = d - lam1
    dl = (lam1 - (d - bp)) + (-lam2 - bp)
    defect = (two_mu - d) - dl
    return 0.5 * defect, -0.5 * defect


def root_slope(A: float, D: float, dl: float, g: float, B: float, C: float, two: float, plus: bool,
               wantk: bool) -> float:
    """The slope at site 1 from the monodromy ``(A, B; C, D)``, rounded once: ``k / (2 B)`` if ``wantk``
    else ``-2 C / k``, ``k = (A - D) + g`` if ``plus`` else ``(A - D) - g``, with ``g`` the exact square root
    of ``(A + D)**2 - two**2`` (``dl = fl(A - D)`` and ``g`` the kernel's doubles, ``g`` the rounded root
    of ``fl(A + D)``) and ``k`` a double-double: ``A + D`` and ``A - D`` are taken exactly (two-sums), so
    neither the rounded trace -- a constant of the orbit, the same few doubles in every step -- nor the
    rounded ``k`` repeats its rounding.

    Error-free transformations (Dekker's product, Knuth's sum; no FMA, so plain Python and numba give
    the same bits): ``g``'s low part is ``(t**2 - two**2 - g**2) / (2 g)``, ``k``'s is the two-sum's
    error plus it, and the quotient is corrected by its remainder.  Scalars (the float64 kernels);
    where a split would overflow (``|x| > 2**995``) or ``g <= 0`` the uncorrected slope is returned.

    >>> import math, mpmath
    >>> A, D, B = -1760.73, -260.4873, 3.5
    >>> t, dl = A + D, A - D
    >>> g = math.sqrt((t - 2.0) * (t + 2.0))
    >>> u = root_slope(A, D, dl, g, B, 2.0, 2.0, False, True)    # (A - D - sqrt((A + D)**2 - 4)) / (2 B)
    >>> with mpmath.workdps(60):
    ...     a, d = mpmath.mpf(A), mpmath.mpf(D)
    ...     bool(abs(u - (a - d - mpmath.sqrt((a + d) ** 2 - 4)) / (2 * B)) <= math.ulp(u) / 2)
    True
    """
    t = A + D
    bp = t - A
    tlo = (A - (t - bp)) + (D - bp)
    bp = dl - A
    dlo = (A - (dl - bp)) + (-D - bp)
    sg = g if plus else -g
    k = dl + sg
    den = 2.0 * B if wantk else k
    num = k if wantk else -2.0 * C
    q = num / den
    if not (g > 0.0 and abs(t) < 2.0 ** 995 and abs(g) < 2.0 ** 995 and abs(q) < 2.0 ** 995
            and abs(den) < 2.0 ** 995):
        return q
    # t*t and g*g exactly (Dekker): tt = th + tl, gg = gh + gl
    c = 134217729.0 * t
    t1 = c - (c - t)
    t2 = t - t1
    th = t * t
    tl = ((t1 * t1 - th) + 2.0 * t1 * t2) + t2 * t2
    c = 134217729.0 * g
    g1 = c - (c - g)
    g2 = g - g1
    gh = g * g
    gl = ((g1 * g1 - gh) + 2.0 * g1 * g2) + g2 * g2
    # t**2 - two**2 - g**2: th - two**2 by two-sum (its error e2), then minus gh: nearly equal, exact
    t4 = two * two
    sh = th - t4
    bp = sh - th
    e2 = (th - (sh - bp)) + (-t4 - bp)
    res = ((sh - gh) + e2) + ((tl - gl) + 2.0 * t * tlo)     # (t + tlo)**2 - two**2 - g**2
    glo = res / (2.0 * g)
    # k = dl + dlo + sg + sglo as a double-double (kh, kl)
    sglo = glo if plus else -glo
    bp = k - dl
    kl = ((dl - (k - bp)) + (sg - bp)) + (sglo + dlo)
    kh = k
    # the quotient corrected by its remainder: num - q den, exactly (Dekker), over den
    c = 134217729.0 * q
    q1 = c - (c - q)
    q2 = q - q1
    c = 134217729.0 * den
    d1 = c - (c - den)
    d2 = den - d1
    ph = q * den
    pl = ((q1 * d1 - ph) + q1 * d2 + q2 * d1) + q2 * d2
    if wantk:
        rem = ((kh - ph) - pl) + kl
        return q + rem / den
    # rem = num - q (kh + kl), so the quotient is q + rem / (kh + kl): over kh alone it would lose the second-order
    # term q (kl/kh)**2, which is not below an ulp where kl is not (|A + D| >~ 1e11 with k ~ 1e2: 1600 ulps)
    rem = ((num - ph) - pl) - q * kl
    return q + rem / (kh + kl)


def _split(x: Any) -> tuple[Any, Any]:
    c = 134217729.0 * x
    h = c - (c - x)
    return h, x - h


#: up to this many rows :func:`root_slope_rows` calls the scalar form per row
_FEW_ROWS = 16


def root_slope_rows(A: Any, D: Any, dl: Any, g: Any, B: Any, C: Any, two: Any, plus: Any, wantk: Any) -> Any:
    """:func:`root_slope` on numpy arrays (the numpy route of :func:`~symbt.numeric.core.step.step_core`):
    the same operations elementwise, so each element equals the scalar call bit for bit.

    >>> A, D = np.array([-1760.73, 5.25]), np.array([-260.4873, 2.25])
    >>> t, dl = A + D, A - D
    >>> g = np.sqrt((t - 2.0) * (t + 2.0))
    >>> args = (A, D, dl, g, np.array([3.5, -1.25]), np.array([2.0, 0.5]), 2.0, dl >= 0, np.array([True, False]))
    >>> rows = root_slope_rows(*args)
    >>> [float(x) for x in rows] == [root_slope(*(a[i] if np.ndim(a) else a for a in args)) for i in range(2)]
    True
    """
    if np.size(A) <= _FEW_ROWS:     # a few rows: the scalar form on Python floats (a numpy op per row costs more)
        n = np.size(A)
        cols = [x.ravel().tolist() if np.size(x) == n else np.broadcast_to(x, np.shape(A)).ravel().tolist()
                for x in map(np.asarray, (A, D, dl, g, B, C, two, plus, wantk))]
        try:
            out = [root_slope(*row) for row in zip(*cols)]
        except ZeroDivisionError:   # IEEE division (inf, NaN) is numpy's: the arrays below
            pass
        else:
            return np.array(out, dtype=np.float64).reshape(np.shape(A))
    with np.errstate(all="ignore"):
        t = A + D
        bp = t - A
        tlo = (A - (t - bp)) + (D - bp)
        bp = dl - A
        dlo = (A - (dl - bp)) + (-D - bp)
        sg = np.where(plus, g, -g)
        k = dl + sg
        den = np.where(wantk, 2.0 * B, k)
        num = np.where(wantk, k, -2.0 * C)
        q = num / den
        ok = ((g > 0.0) & (np.abs(t) < 2.0 ** 995) & (np.abs(g) < 2.0 ** 995) & (np.abs(q) < 2.0 ** 995)
              & (np.abs(den) < 2.0 ** 995))
        t1, t2 = _split(t)
        th = t * t
        tl = ((t1 * t1 - th) + 2.0 * t1 * t2) + t2 * t2
        g1, g2 = _split(g)
        gh = g * g
        gl = ((g1 * g1 - gh) + 2.0 * g1 * g2) + g2 * g2
        t4 = two * two
        sh = th - t4
        bp = sh - th
        e2 = (th - (sh - bp)) + (-t4 - bp)
        glo = (((sh - gh) + e2) + ((tl - gl) + 2.0 * t * tlo)) / (2.0 * g)
        bp = k - dl
        kl = ((dl - (k - bp)) + (sg - bp)) + (np.where(plus, glo, -glo) + dlo)
        q1, q2 = _split(q)
        d1, d2 = _split(den)
        ph = q * den
        pl = ((q1 * d1 - ph) + q1 * d2 + q2 * d1) + q2 * d2
        rem = np.where(wantk, ((k - ph) - pl) + kl, ((num - ph) - pl) - q * kl)
        return np.where(ok, q + rem / np.where(wantk, den, k + kl), q)
