r"""The sharp tier of the float64 condition estimate: the first-order rounding scale of a computed trace.

The float64 routes (:mod:`symbt.numeric.core.step`, "Existence and accuracy in float64") decide a state only
where its condition ``kappa`` is below ``KAPPA_MAX``; its trace factor ``k_t`` uses the cheap scale ``T``,
the trace of the product of the entrywise absolute values of the transfer matrices.  Where the ``a_j =
lam + p_j`` take both signs, ``T`` grows much faster than the products themselves and overestimates the
trace's rounding error by orders of magnitude (the benchmark chains: ~1e6 at N = 64, ~1e27 at N = 256);
where the cheap ``k_t`` would escalate the state to mpmath, every float64 route (the fused kernel's hooks
in :mod:`symbt.numeric.float64.kernels`, the block kernel, the numpy rows) takes :func:`sharp_trace_kappa`
instead.  Plain scalar code: the numba kernels compile it as it is.

Example
-------
>>> import numpy as np
>>> p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
>>> 1.0 <= sharp_trace_kappa(p, r, 15.0, 0.0) < 20.0        # the paper's example at lam1 = 15
True
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .spectral_sum import lam_add

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["sharp_trace_kappa", "SHARP_UNIT"]

#: the relative allowance per site for the rounding of the sum of :func:`sharp_trace_kappa` and products
#: (``16 u``, ``u = 2**-53``)``
SHARP_UNIT = 16.0 * 2.0 ** -53

_FAR = 2.0 ** 200
_NEAR = 2.0 ** -200


def sharp_trace_kappa(p: npt.NDArray[np.float64], r: npt.NDArray[np.float64], lam: float, lo: float) -> float:
    r"""The sharp condition ``k_t`` of one trace decision (one state, scalar code): ``Ts (|t| + 2) / |t**2 - 4|``
    times ``max_j (|lam| + |p_j|) / |lam + p_j|``, with the rounding scale ``Ts`` below in place of the cheap
    ``T`` of :func:`trace_kappa`.

    Derivation.  The float64 routes form ``M = m_N ... m_1`` by ``A' = a_j A - C``, ``B' = a_j B - D``,
    ``C' = r_j A``, ``D' = r_j B`` (``a_j = lam_add(lam, lo, p_j)``, one rounding) with exact
    power-of-two rescalings, and ``t = A + D``.  Each site's computed product is
    ``(m_j + Delta_j) M_{j-1}`` with ``|Delta_j| <= gamma_3 |m_j|`` entrywise (first row: ``a_j``'s own
    rounding, the product, the difference; second row: one product; the rescalings are exact), so to
    first order, with the prefix ``P_{j-1} = m_{j-1} ... m_1`` and the suffix ``S_{j+1} = m_N ... m_{j+1}``,

        t_computed - t = sum_j tr(S_{j+1} Delta_j P_{j-1}) + delta (A + D),
        |t_computed - t| <= gamma_3 sum_j tr(|S_{j+1}| |m_j| |P_{j-1}|) + u |t|.

    The cheap bound is ``gamma_{3N} T``, ``T = tr(|m_N| ... |m_1|)``; since
    ``|S_{j+1}| |m_j| |P_{j-1}| <= |m_N| ... |m_1|`` entrywise, each term is at most ``T``, so the mean
    ``Ts = (1/N) sum_j tr(|S_{j+1}| |m_j| |P_{j-1}|)`` takes ``T``'s place in the same form
    ``N gamma_3 Ts`` -- hence in ``kappa`` and in the bound ``32 N eps kappa rho s`` with its constant
    unchanged.  The sum is formed from the prefix products' first rows, stored (the second row of ``P_j``
    is ``r_j`` times the first row of ``P_{j-1}``), and a backward pass for ``S``, both renormalised by
    exact powers of two; its own rounding and the use of the computed rather than the exact ``P``, ``S``
    change it by a relative ``O(N u)``, for which ``Ts`` is multiplied by ``1 + SHARP_UNIT N``.

    *First order only*: the terms with two or more ``Delta`` (and the deviation of the computed ``P``,
    ``S`` from the exact ones, bounded a priori only by ``gamma_{3N}`` times the absolute products) are
    not bounded here -- the a priori bound ``(3 N u)**2 T`` would bring back the pessimism this estimate
    removes.  ``tests/test_numeric_kappa.py`` measures the accuracy bound against the 50-digit literal
    step where this estimate decides.

    The result does not depend on the routes' scaling (``t``, ``t**2 - 4`` and ``Ts`` are formed here,
    in this function's own power-of-two scale); ``inf`` or NaN (not trusted) where ``t = +-2`` or a
    product leaves the range.  Plain scalar code: the compiled kernels run it as it is.

    >>> p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
    >>> k = sharp_trace_kappa(p, r, 15.0, 0.0)        # the paper's example at lam1 = 15: far from +-2
    >>> 1.0 <= k < 20.0
    True
    """
    N = p.shape[0]
    pa = np.empty(N)
    pb = np.empty(N)
    pe = np.empty(N, dtype=np.int64)
    A = lam_add(lam, lo, p[0])
    B = -1.0
    C = r[0]
    D = 0.0
    e = 0
    kn = abs(lam) + abs(p[0])           # max_j (|lam| + |p_j|) / |a_j| as kn / kd (as the kernels' track)
    kd = abs(A)
    pa[0] = A
    pb[0] = B
    pe[0] = 0
    for j in range(1, N):
        a = lam_add(lam, lo, p[j])
        cn = abs(lam) + abs(p[j])
        if cn * kd > kn * abs(a):
            kn = cn
            kd = abs(a)
        rj = r[j]
        A, B, C, D = a * A - C, a * B - D, rj * A, rj * B
        m = max(abs(A), abs(B), abs(C), abs(D))
        if (m > _FAR or m < _NEAR) and m > 0.0 and m < math.inf:      # exact power-of-two rescaling
            f = math.frexp(m)[1]
            A, B, C, D, e = math.ldexp(A, -f), math.ldexp(B, -f), math.ldexp(C, -f), math.ldexp(D, -f), e + f
        pa[j] = A
        pb[j] = B
        pe[j] = e
    t = A + D
    two = math.ldexp(2.0, -e)
    disc = (t - two) * (t + two)        # 2**(-2e) (tr**2 - 4), no cancellation
    S11, S12, S21, S22 = 1.0, 0.0, 0.0, 1.0
    es = 0
    total = 0.0
    for j in range(N - 1, -1, -1):
        sa = lam_add(lam, lo, p[j])
        a = abs(sa)
        rj = r[j]
        if j == 0:                      # P_0 = identity
            P11, P12, P21, P22, ep = 1.0, 0.0, 0.0, 1.0, 0
        else:
            ep = int(pe[j - 1])
            P11, P12 = abs(pa[j - 1]), abs(pb[j - 1])
            if j == 1:                  # P_1 = m_1: second row (r_1, 0)
                P21, P22 = math.ldexp(r[0], -ep), 0.0
            else:
                fr = math.ldexp(r[j - 1], int(pe[j - 2]) - ep)
                P21, P22 = fr * abs(pa[j - 2]), fr * abs(pb[j - 2])
        X11, X12 = a * P11 + P21, a * P12 + P22
        X21, X22 = rj * P11, rj * P12
        term = abs(S11) * X11 + abs(S12) * X21 + abs(S21) * X12 + abs(S22) * X22
        sh = es + ep - e
        if term > 0.0 and math.frexp(term)[1] + sh > 1024:     # beyond float64: math.ldexp would raise
            return math.inf             # the rounding scale of t overflows: not conditioned in float64
        total += math.ldexp(term, sh)
        S11, S12, S21, S22 = S11 * sa + S12 * rj, -S11, S21 * sa + S22 * rj, -S21    # S_j = S_{j+1} m_j
        m = max(abs(S11), abs(S12), abs(S21), abs(S22))
        if (m > _FAR or m < _NEAR) and m > 0.0 and m < math.inf:
            f = math.frexp(m)[1]
            S11, S12 = math.ldexp(S11, -f), math.ldexp(S12, -f)
            S21, S22, es = math.ldexp(S21, -f), math.ldexp(S22, -f), es + f
    Ts = total / N * (1.0 + SHARP_UNIT * N)
    if disc == 0.0 or kd == 0.0:        # t = +-2, or some a_j = 0 with lam, p_j not both 0: not decided
        return math.inf
    return float(Ts * (abs(t) + two) / abs(disc) * (kn / kd))     # Ts / ||t| - 2|, as the cheap tier
