r"""The conserved quantities of the map: ``tr L(lam)`` and its coefficients ``H_k``.

Both are computed from the scaled monodromy of :mod:`symbt.numeric.core.monodromy`
(only neighbour differences ``q_{j+1} - q_j`` enter, so a common shift of ``q`` drops out).

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

import numpy as np
import numpy.typing as npt

from ..core.context import FLOAT, MPValue, Value
from ..core.errors import NumericRangeError
from ..core.inputs import ParamLike, StateLike, as_state_pair, prepare_scalar
from ..core.monodromy import monodromy, neighbour_ratios
from ..core.problem import StateOut

__all__ = ["spectral_trace", "invariants"]


def spectral_trace(lam: ParamLike, p: StateLike, q: StateLike) -> npt.NDArray[np.float64] | MPValue:
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


def invariants(p: StateLike, q: StateLike) -> StateOut:
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


def _invariants(p: StateLike, q: StateLike) -> StateOut:
    ctx, P, Q, shape = as_state_pair(p, q)
    N = len(P)
    r = neighbour_ratios(ctx, Q)
    zero = 0.0 * P[0]

    def poly(n: int) -> list[Value]:
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
