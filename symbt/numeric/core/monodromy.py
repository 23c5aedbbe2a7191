r"""Scaled Lax monodromy of the periodic Toda chain.

Conventions (paper eq. ``eq:lax``, ``tra``)::

    l_j(lam) = [[lam + p_j, -E_j], [1/E_j, 0]],   E_j = exp(q_j),
    L(lam)   = l_N ... l_1,       tr L(lam) = sum_{k=0}^{N} H_k lam^k,  H_N = 1.

Scaling.  With ``S_j = diag(1, E_j)`` one has ``S_{j+1} l_j S_j^{-1} = m_j`` with

    m_j(lam) = [[lam + p_j, -1], [r_j, 0]],     r_j = E_{j+1} / E_j = exp(q_{j+1} - q_j),

and ``S_{N+1} = S_1`` by periodicity, so ``M = m_N ... m_1 = S_1 L S_1^{-1}`` has
the same trace and eigenvalues as ``L`` and its eigenvector slopes are the
*scaled* slopes ``u = E_1 y``.  Only neighbour differences ``q_{j+1} - q_j``
enter: a common shift of all ``q`` drops out exactly (no overflow for
``|q| ~ 800``), and the product needs 6 flops per site because the second row
of ``m_j M`` is ``r_j`` times the first row of ``M``.

In float64 the product is first formed unscaled; rows of the batch whose
entries leave ``[2**-500, 2**500]`` are recomputed with a power-of-two
renormalisation after every site (exact, no rounding), carrying an integer
exponent ``e`` so that ``M = 2**e * (A, B; C, D)``.

Example
-------
>>> import numpy as np
>>> from symbt.numeric import spectral_trace
>>> from symbt.numeric.core.context import FLOAT
>>> p, q = [np.array([x]) for x in (-20.0, 10.0, 1.0)], [np.array([x]) for x in (1.0, 0.0, 0.9)]
>>> A, B, C, D, e = monodromy(FLOAT, [3.0 + pj for pj in p], neighbour_ratios(FLOAT, q))
>>> bool(np.isclose(np.ldexp(A + D, e)[0], spectral_trace(3.0, [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9])))
True"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .context import Context, Exponent, Value
from .errors import NumericRangeError
from .limits import MAX_DQ_FLOAT64

__all__ = ["neighbour_ratios", "monodromy"]



def neighbour_ratios(ctx: Context, q: Sequence[Value]) -> list[Value]:
    """``r_j = exp(q_{j+1} - q_j)`` (cyclic) as a list of context values.

    >>> import mpmath
    >>> from symbt.numeric.core.inputs import MP
    >>> [mpmath.nstr(x, 6) for x in neighbour_ratios(MP, [mpmath.mpf(0), mpmath.mpf(1)])]
    ['2.71828', '0.367879']
    """
    N = len(q)
    dq = [q[(j + 1) % N] - q[j] for j in range(N)]
    if not ctx.is_exact_scale:
        re = np.real(dq).reshape(N, -1)     # (sites, rows): one state is one row
        worst = float(np.max(np.maximum(re.max(axis=1), -re.min(axis=1)))) if re.size else 0.0
        if worst > MAX_DQ_FLOAT64:
            raise NumericRangeError(
                "|q_{j+1} - q_j| = %.4g exceeds the float64 range of the scaled "
                "formulation (limit %g); use mpmath inputs" % (worst, MAX_DQ_FLOAT64))
    return [ctx.exp(d) for d in dq]


def _product(ctx: Context, a: Sequence[Value], r: Sequence[Value],
             renorm: bool) -> tuple[Value, Value, Value, Value, Exponent]:
    # M = m_N ... m_1 applied to the identity; m_j = [[a_j, -1], [r_j, 0]].
    # m_1 itself; B and D start as plain scalars (cheap broadcasting)
    A, B, C, D = a[0], -1.0, r[0], 0.0
    e: Exponent = 0
    if renorm:
        A, B, C, D, e = ctx.renormalize(A, B, C, D, e)
    for j in range(1, len(a)):
        A, B, C, D = a[j] * A - C, a[j] * B - D, r[j] * A, r[j] * B
        if renorm:
            A, B, C, D, e = ctx.renormalize(A, B, C, D, e)
    return A, B, C, D, e


def monodromy(ctx: Context, a: Sequence[Value], r: Sequence[Value]) -> tuple[Value, Value, Value, Value, Exponent]:
    """Scaled monodromy ``M = 2**e (A, B; C, D)`` for site lists ``a_j = lam + p_j``, ``r_j``.

    Returns ``(A, B, C, D, e)``; ``e`` is ``0`` unless renormalisation was
    needed (float64) -- for mpmath it is always ``0``.

    >>> from symbt.numeric.core.context import FLOAT
    >>> A, B, C, D, e = monodromy(FLOAT, [np.array([2.0]), np.array([3.0])], [np.array([1.0]), np.array([1.0])])
    >>> float((A + D)[0]), e                           # tr = a1 a2 - r1 - r2
    (4.0, 0)
    """
    if ctx.is_exact_scale:
        return _product(ctx, a, r, renorm=False)
    with np.errstate(over="ignore", invalid="ignore"):   # out-of-range rows are redone below
        A, B, C, D, e = _product(ctx, a, r, renorm=False)
    bad = ctx.out_of_range(A, B, C, D)
    if ctx.any(bad):
        sa = [ctx.subset(x, bad) for x in a]
        sr = [ctx.subset(x, bad) for x in r]
        A2, B2, C2, D2, e2 = _product(ctx, sa, sr, renorm=True)
        shape = np.shape(bad)
        A, B, C, D = (ctx.merge(np.broadcast_to(X, shape), bad, X2)
                      for X, X2 in ((A, A2), (B, B2), (C, C2), (D, D2)))
        e = ctx.merge(np.zeros(shape, dtype=np.int64), bad, e2)
    return A, B, C, D, e
