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
>>> from symbt.numeric import spectral_trace, invariants
>>> p, q = np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9])
>>> H = invariants(p, q)               # H_0, H_1, H_2
>>> lam = 3.0
>>> bool(np.isclose(spectral_trace(lam, p, q), H[0] + H[1]*lam + H[2]*lam**2 + lam**3))
True
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ._input import as_state_pair, prepare_scalar
from .context import FLOAT, Context
from .errors import NumericRangeError

__all__ = ["spectral_trace", "invariants", "neighbour_ratios", "monodromy"]

# exp overflows/underflows (to subnormals) beyond about this difference
MAX_DQ = 700.0


def neighbour_ratios(ctx: Context, q: Sequence[Any]) -> list[Any]:
    """``r_j = exp(q_{j+1} - q_j)`` (cyclic) as a list of context values.

    >>> import mpmath
    >>> from symbt.numeric._input import MP
    >>> [mpmath.nstr(x, 6) for x in neighbour_ratios(MP, [mpmath.mpf(0), mpmath.mpf(1)])]
    ['2.71828', '0.367879']
    """
    N = len(q)
    dq = [q[(j + 1) % N] - q[j] for j in range(N)]
    if not ctx.is_exact_scale:
        worst = max(float(max(np.max(d), -np.min(d))) if np.size(d) else 0.0 for d in np.real(dq))
        if worst > MAX_DQ:
            raise NumericRangeError(
                "|q_{j+1} - q_j| = %.4g exceeds the float64 range of the scaled "
                "formulation (limit %g); use mpmath inputs" % (worst, MAX_DQ))
    return [ctx.exp(d) for d in dq]


def _product(ctx: Context, a: Sequence[Any], r: Sequence[Any], renorm: bool) -> tuple[Any, Any, Any, Any, Any]:
    # M = m_N ... m_1 applied to the identity; m_j = [[a_j, -1], [r_j, 0]].
    # m_1 itself; B and D start as plain scalars (cheap broadcasting)
    A, B, C, D = a[0], -1.0, r[0], 0.0
    e = 0
    if renorm:
        A, B, C, D, e = ctx.renormalize(A, B, C, D, e)
    for j in range(1, len(a)):
        A, B, C, D = a[j] * A - C, a[j] * B - D, r[j] * A, r[j] * B
        if renorm:
            A, B, C, D, e = ctx.renormalize(A, B, C, D, e)
    return A, B, C, D, e


def monodromy(ctx: Context, a: Sequence[Any], r: Sequence[Any]) -> tuple[Any, Any, Any, Any, Any]:
    """Scaled monodromy ``M = 2**e (A, B; C, D)`` for site lists ``a_j = lam + p_j``, ``r_j``.

    Returns ``(A, B, C, D, e)``; ``e`` is ``0`` unless renormalisation was
    needed (float64) -- for mpmath it is always ``0``.

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


def spectral_trace(lam: Any, p: Any, q: Any) -> Any:
    """``tr L(lam)`` for a state (or batch of states) ``(p, q)``; O(N) per state.

    ``lam`` is a scalar (or broadcastable to the batch shape).  float64 inputs
    give a float64 array of the batch shape (a 0-d array for one state),
    mpmath inputs give an mpf.  Raises :class:`NumericRangeError` if the trace
    itself overflows float64.

    >>> from symbt.numeric import spectral_trace
    >>> float(spectral_trace(0.0, [0.0, 0.0], [0.0, 0.0]))   # lam^2 + p1 p2 - 2 cosh(q1-q2)
    -2.0
    """
    ctx, P, Q, shape = as_state_pair(p, q)
    lam = prepare_scalar(ctx, lam, shape, "lam")
    r = neighbour_ratios(ctx, Q)
    A, B, C, D, e = monodromy(ctx, [lam + pj for pj in P], r)
    if ctx is FLOAT:
        with np.errstate(over="ignore"):
            tr = np.ldexp(A + D, e)
        if not np.all(np.isfinite(tr)):
            raise NumericRangeError("tr L(lam) overflows float64")
        return tr.reshape(shape)
    return A + D


def invariants(p: Any, q: Any) -> Any:
    """Conserved quantities ``H_0, ..., H_{N-1}`` (coefficients of ``tr L``; ``H_N = 1``).

    O(N^2) per state, no N x N matrices: the entries of the scaled monodromy
    are propagated as polynomials in ``lam`` (coefficient arrays), using the
    same 6-flop recursion as :func:`monodromy`.  Output has shape
    ``batch + (N,)`` (float64) or is a list of mpf.

    >>> from symbt.numeric import invariants
    >>> [round(float(h), 12) for h in invariants([1.0, 2.0], [0.0, 0.0])]   # p1 p2 - 2, p1 + p2
    [0.0, 3.0]
    """
    with np.errstate(over="ignore", invalid="ignore"):   # overflow -> NumericRangeError below
        return _invariants(p, q)


def _invariants(p: Any, q: Any) -> Any:
    ctx, P, Q, shape = as_state_pair(p, q)
    N = len(P)
    r = neighbour_ratios(ctx, Q)
    zero = 0.0 * P[0]

    def poly(n: int) -> list[Any]:
        return [zero] * n

    # polynomials as lists of coefficients (index = power of lam)
    A = [P[0], 1.0 + zero]
    B = [-1.0 + zero]
    C = [r[0] + zero]
    D = [zero]
    for j in range(1, N):
        nA = poly(len(A) + 1)
        nB = poly(len(B) + 1)
        for k, c in enumerate(A):
            nA[k] = nA[k] + P[j] * c
            nA[k + 1] = nA[k + 1] + c
        for k, c in enumerate(C):
            nA[k] = nA[k] - c
        for k, c in enumerate(B):
            nB[k] = nB[k] + P[j] * c
            nB[k + 1] = nB[k + 1] + c
        for k, c in enumerate(D):
            nB[k] = nB[k] - c
        C = [r[j] * c for c in A]
        D = [r[j] * c for c in B]
        A, B = nA, nB
    H = poly(N + 1)
    for k, c in enumerate(A):  # noqa: B007
        H[k] = H[k] + c
    for k, c in enumerate(D):
        H[k] = H[k] + c
    H = H[:N]
    if ctx is FLOAT:
        out = np.stack([np.asarray(h, dtype=float) for h in H], axis=-1)
        if not np.all(np.isfinite(out)):
            raise NumericRangeError("the invariants H_k overflow float64; use mpmath inputs")
        return out.reshape(shape + (N,))
    return list(H)
