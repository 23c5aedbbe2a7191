r"""What ships, 4e: the sharp tier of the float64 condition estimate against its definition (scene ``numeric-paths``).

:func:`symbt.numeric.core.condition.sharp_trace_kappa` decides, in every float64 route, the states whose cheap
condition estimate escalates them (issue 26's two-tier estimate).  Its docstring defines the value it returns:

.. math:: k_t = (1 + 16 u N)\, T_s \frac{|t| + 2}{|t^2 - 4|} \max_j \frac{|\lambda| + |p_j|}{|a_j|},\qquad
          T_s = \frac1N \sum_j \operatorname{tr}\big(|S_{j+1}|\,|m_j|\,|P_{j-1}|\big),

with :math:`m_j = [[a_j, -1], [r_j, 0]]`, :math:`a_j = \lambda + lo + p_j`, the prefix products
:math:`P_{j-1} = m_{j-1} \cdots m_1`, the suffix products :math:`S_{j+1} = m_N \cdots m_{j+1}`, :math:`t` the
trace of the monodromy and :math:`|\cdot|` entrywise; the float64 code forms the prefixes once (their first rows
stored, their second rows rebuilt from ``r``), the suffixes backwards, both renormalised by exact powers of two
past :math:`2^{\pm 200}`.

This module holds that definition, evaluated with exact matrix products at high precision (no renormalisation,
no stored rows: the independent route), for the claims that compare the float64 value with it
(``paths.kappa_cells``, ``paths.kappa_cells_rows``, ``paths.renorm_top``), and the states the first of those
claims took: N = 3, the paper's state at :math:`\lambda = 15` and at six points of its gaps and outer zones, and
its mirror image :math:`p \to -p` at :math:`-\lambda`; N = 6, chains at :math:`\lambda = \pm 10^{25}`, whose
prefix and suffix products pass :math:`2^{200}` after three sites -- the renormalised path, stored rows with
exponents.  On these states no product cancels, so each of the :math:`O(N)` roundings is relative; a lost
renormalisation exponent, a row read from the wrong site or a term lost changes :math:`k_t` by a factor, not by ulps.

The claims that use it are shown to fail on planted bugs in ``tests/test_killers_numeric.py`` and
``tests/test_killers_condition.py``.
"""
from __future__ import annotations

import math

import mpmath as mp
import numpy as np

#: the paper's state and the chains (among paths.kappa_cells' states): (p, q) and the spectral parameters
PAPER_P, PAPER_Q = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9)
PAPER_LAMS = (15.0, -5.0, -12.0, 3.0, 0.5, 30.0, -40.0)
CHAIN_P, CHAIN_Q = (-20.0, 10.0, 1.0, 3.0, -2.0, 0.5), (1.0, 0.0, 0.9, 0.3, -0.4, 0.2)
CHAIN_LAMS = (1e25, -1e25, 3e24)
#: the digits of the reference and of its check
KAPPA_DPS, KAPPA_CHECK_DPS = 60, 80


def kappa_cases(N: int) -> list[tuple[tuple, tuple, float]]:
    """``(p, r, lam)``: double inputs of ``sharp_trace_kappa`` (``r = exp(q_{j+1} - q_j)`` rounded once): the
    paper's state and its mirror (N = 3), the chains (N = 6), none for other N."""
    def ratios(q: tuple) -> tuple:
        return tuple(math.exp(q[(j + 1) % len(q)] - q[j]) for j in range(len(q)))
    if N == 3:
        out = [(PAPER_P, ratios(PAPER_Q), lam) for lam in PAPER_LAMS]
        return out + [(tuple(-x for x in PAPER_P), ratios(PAPER_Q), -lam) for lam in PAPER_LAMS]
    return [(CHAIN_P, ratios(CHAIN_Q), lam) for lam in CHAIN_LAMS] if N == len(CHAIN_P) else []


def kappa_by_definition(p: tuple, r: tuple, lam: float, dps: int, lo: float = 0.0) -> mp.mpf:
    """The docstring's ``k_t`` with exact products at ``dps`` digits (the factor ``1 + 16 u N`` included):
    ``a_j = lam + lo + p_j`` exactly (``lo`` the spectral parameter's low part), ``T_s`` the mean of
    ``tr(|S_{j+1}| |m_j| |P_{j-1}|)``, times ``(|t| + 2) / |t**2 - 4|`` and ``max_j (|lam| + |p_j|) / |a_j|``; no
    renormalisation, no stored rows.

    >>> k = kappa_by_definition((-20.0, 10.0, 1.0), (math.exp(-1), math.exp(0.9), math.exp(0.1)), 15.0, 30)
    >>> 1 <= k < 20
    True
    """
    N = len(p)
    with mp.workdps(dps):
        a = [mp.mpf(lam) + mp.mpf(lo) + mp.mpf(x) for x in p]
        m = [mp.matrix([[a[j], -1], [mp.mpf(r[j]), 0]]) for j in range(N)]
        pre = [mp.eye(2)]
        for j in range(N):
            pre.append(m[j] * pre[-1])                    # pre[j] = m_{j-1} ... m_0
        suf = [mp.eye(2)] * (N + 1)
        for j in range(N - 1, -1, -1):
            suf[j] = suf[j + 1] * m[j]                    # suf[j] = m_{N-1} ... m_j
        ab = [x.apply(abs) for x in m]
        terms = []
        for j in range(N):
            X = suf[j + 1].apply(abs) * ab[j] * pre[j].apply(abs)
            terms.append(X[0, 0] + X[1, 1])
        Ts = mp.fsum(terms) / N * (1 + mp.mpf(16) * mp.mpf(2) ** -53 * N)
        t = pre[N][0, 0] + pre[N][1, 1]
        kk = max((abs(mp.mpf(lam)) + abs(mp.mpf(x))) / abs(aj) for x, aj in zip(p, a))
        return Ts * (abs(t) + 2) / abs(t * t - 4) * kk


def sharp_against_definition(p, r, lam) -> tuple[float, mp.mpf, float] | None:
    """``(k_t, reference, |k_t / reference - 1|)``: ``sharp_trace_kappa`` against its definition evaluated with
    exact products at ``KAPPA_DPS`` digits, or ``None`` where that reference disagrees with itself at
    ``KAPPA_CHECK_DPS`` digits (an infinite ``k_t`` has deviation ``inf``)."""
    from ..numeric.core.condition import sharp_trace_kappa

    ref = kappa_by_definition(p, r, lam, KAPPA_DPS)
    check = kappa_by_definition(p, r, lam, KAPPA_CHECK_DPS)
    if not abs(ref - check) <= abs(check) * mp.mpf(10) ** (5 - KAPPA_DPS):
        return None
    with np.errstate(all="ignore"):
        got = sharp_trace_kappa(np.array(p), np.array(r), lam, 0.0)
    return got, ref, float(abs(mp.mpf(got) / ref - 1)) if math.isfinite(got) else math.inf
