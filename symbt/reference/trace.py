r"""tr L(lambda) of the periodic Toda lattice as an explicit polynomial (mpmath, sympy-free).

:func:`trace_polynomial` expands :math:`\operatorname{tr}L(\lambda)` of eq. ``tra`` in
:math:`\lambda`, :math:`p_j` and the bond variables :math:`a_j = e^{q_{j+1}-q_j}` (cyclic) by the
closed-walk expansion of :math:`l_N\cdots l_1`: a sum over the matchings of the N-cycle,
:math:`\sum_M\prod_{j\notin M}(\lambda+p_j)\prod_{b\in M}(-a_b)`.  The number of terms grows
like a Lucas number, so this is a reference for small N, independent of the 2x2 products
used everywhere else.

>>> import mpmath as mp

from .literal import MPLike, MPNumber
>>> H = hamiltonians([mp.mpf("0.3"), mp.mpf("-0.2")], [mp.mpf("0.1"), mp.mpf("0.4")])
>>> mp.nstr(H[1], 5), H[2]
('0.1', mpf('1.0'))
"""
from __future__ import annotations

from collections.abc import Sequence
from itertools import combinations

import mpmath as mp

from .literal import MPLike, MPNumber

__all__ = ["trace_polynomial", "hamiltonians", "trace", "trace_gradient", "trace_gap", "bonds"]


def trace_polynomial(N: int) -> dict[tuple[int, ...], int]:
    """``{(k, e_p1..e_pN, e_a1..e_aN): integer coefficient}`` with tr L = sum coef * lam^k p^e a^e.

    ``a_j = exp(q_{j+1} - q_j)`` (indices mod N).  Bond j joins sites j, j+1 and
    carries the weight ``-a_j`` (the walk 1 -> 2 at site j, 2 -> 1 at site j+1
    of the product ``l_N ... l_1``); a matching is a set of bonds with disjoint
    sites.  For N = 2 the two bonds join the same two sites (weights
    ``-e^{q2-q1}``, ``-e^{q1-q2}``) and are never matched together.
    """
    if N < 2:
        raise ValueError("N >= 2")
    bonds = [frozenset((j, (j + 1) % N)) for j in range(N)]
    poly: dict[tuple[int, ...], int] = {}
    for r in range(N // 2 + 1):
        for M in combinations(range(N), r):
            covered = [s for b in M for s in bonds[b]]
            if len(covered) != len(set(covered)):
                continue
            free = [j for j in range(N) if j not in covered]
            # prod_{j free} (lam + p_j): choose a subset S of free sites contributing p_j
            for s in range(len(free) + 1):
                for S in combinations(free, s):
                    e = [0] * (2 * N)
                    for j in S:
                        e[j] = 1
                    for b in M:
                        e[N + b] = 1
                    key = (len(free) - s, *e)
                    poly[key] = poly.get(key, 0) + (-1) ** r
    return {k: v for k, v in poly.items() if v}


def bonds(q: Sequence[MPNumber]) -> list[MPNumber]:
    N = len(q)
    return [mp.exp(q[(j + 1) % N] - q[j]) for j in range(N)]


def _mono(vals: Sequence[MPNumber], e: Sequence[int]) -> MPNumber:
    out = mp.mpf(1)
    for v, k in zip(vals, e):
        if k:
            out *= v ** k
    return out


def hamiltonians(p: Sequence[MPLike], q: Sequence[MPLike]) -> list[MPNumber]:
    """``[H_0, ..., H_N]`` with tr L(lam) = sum_k H_k lam^k (eq. ``tra``)."""
    N = len(p)
    p = [mp.mpmathify(v) for v in p]
    vals = p + bonds([mp.mpmathify(v) for v in q])
    H = [mp.mpf(0)] * (N + 1)
    for key, c in trace_polynomial(N).items():
        H[key[0]] += c * _mono(vals, key[1:])
    return H


def trace(lam: MPLike, p: Sequence[MPLike], q: Sequence[MPLike]) -> MPNumber:
    H = hamiltonians(p, q)
    return mp.polyval(H[::-1], mp.mpmathify(lam))


def trace_gradient(lam: MPLike, p: Sequence[MPLike],
                   q: Sequence[MPLike]) -> tuple[list[MPNumber], list[MPNumber]]:
    """``(d tr/dp_j, d tr/dq_j)`` at lam, from the polynomial (chain rule through a_j)."""
    N = len(p)
    p = [mp.mpmathify(v) for v in p]
    a = bonds([mp.mpmathify(v) for v in q])
    vals = p + a
    lam = mp.mpmathify(lam)
    dvals = [mp.mpf(0)] * (2 * N)  # d tr / d p_j, d tr / d a_j
    for key, c in trace_polynomial(N).items():
        k, e = key[0], key[1:]
        base = c * lam ** k
        for i, ei in enumerate(e):
            if ei:
                ee = list(e)
                ee[i] -= 1
                dvals[i] += base * ei * _mono(vals, ee)
    dp = dvals[:N]
    da = dvals[N:]
    # a_j = exp(q_{j+1} - q_j): d a_j/d q_j = -a_j, d a_{j-1}/d q_j = +a_{j-1}
    dq = [da[(j - 1) % N] * a[(j - 1) % N] - da[j] * a[j] for j in range(N)]
    return dp, dq



def trace_gap(p: Sequence[MPLike], q: Sequence[MPLike], lo: MPLike, hi: MPLike) -> mp.mpf:
    """min over [lo, hi] of |tr L(lam)| - 2 (end points and critical points), or 0 if tr L = +-2 somewhere.

    The interval is closed: a root of ``tr L = +-2`` (as ``mpmath.polyroots`` finds it) at ``lo`` or ``hi`` gives 0.
    On an interval inside one gap the value is ``min(|tr L(lo)|, |tr L(hi)|) - 2 > 0``, the least ``|tr| - 2``
    there (``|tr|`` has its one maximum inside a gap).  Inside one band it is the same expression, negative (the
    critical points of ``tr`` lie in the gaps), which is not the least ``|tr| - 2`` there (``tr`` crosses 0 in
    each band): only its sign is meant.
    """
    H = hamiltonians(p, q)
    lo, hi = mp.mpmathify(lo), mp.mpmathify(hi)
    if lo > hi:
        lo, hi = hi, lo
    coeffs = H[::-1]
    # every root of tr = +-2 is real (the periodic and antiperiodic spectra of a real symmetric Jacobi matrix), and
    # so is every root of tr' (N - 1 of them, one between each two neighbouring roots of tr = 2: Rolle); polyroots'
    # imaginary parts are rounding -- up to about 10^(-dps/2) at a double root, a closed gap -- so the real parts
    # are taken, none dropped
    for shift in (2, -2):  # a root of tr = +-2 in [lo, hi] means |tr| <= 2 there: not admissible
        c = list(coeffs)
        c[-1] -= shift
        if any(lo <= r.real <= hi for r in mp.polyroots(c, maxsteps=200, extraprec=60)):
            return mp.mpf(0)
    cands = [lo, hi]
    d = [coeffs[i] * (len(coeffs) - 1 - i) for i in range(len(coeffs) - 1)]
    if len(d) > 1:
        cands += [r.real for r in mp.polyroots(d, maxsteps=200, extraprec=60)]
    cands = [x for x in cands if lo <= x <= hi]
    return min(abs(mp.polyval(coeffs, x)) - 2 for x in cands)


