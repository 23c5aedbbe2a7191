r"""Block layout of the fused float64 kernels: many states at once (numba ``prange`` over blocks).

The arithmetic of :func:`symbt.numeric.float64.kernels.orbit`, operation for
operation, on a *block* of ``B`` states held site-major, ``x[j, k]`` with the
state index ``k`` innermost: every loop over ``k`` is a plain elementwise
loop without calls or reductions that LLVM vectorises (AVX2: 4 states per
instruction), and a block's work arrays stay in L1.  A state that fails gets
its status set and is carried along (its values are garbage and discarded);
the block stops when all of its states have failed.

Example
-------
>>> import numpy as np
>>> from symbt.numeric.float64.kernels import ANCHOR, orbit_rows
>>> P, Q, st = np.empty((2, 2, 3)), np.empty((2, 2, 3)), np.zeros(2, np.int64)
>>> ones = np.ones(2)
>>> run_block(np.tile([-20.0, 10, 1], (2, 1)), np.tile([1.0, 0, 0.9], (2, 1)), 15 * ones, 5 * ones, 10 * ones,
...           1, 1, 1, ANCHOR, P, Q, st, 0, 2)
>>> st.tolist(), np.round(P[1, 1], 8).tolist()
([0, 0], [-19.99656766, 9.78635495, 1.21021272])
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..core.condition import sharp_trace_kappa
from ..core.limits import ILLCOND, KAPPA_MAX, MAX_DQ_FLOAT64, OK, POSITIVITY, RANGE, TRACE1, TRACE2
from ..core.spectral_sum import lam_add, lam_split, root_slope
from .kernels import _BIG, _SHRINK, _dd_add, _dd_low, _dd_position, _logf

if TYPE_CHECKING:
    from .kernels import F64, I64

__all__ = ["run_block", "ensemble"]

prange = range  # the ensemble kernel is compiled with numba.prange in its place


def _shrink(A: F64, Bm: F64, C: F64, D: F64, Ab: F64, sc: F64, k: int) -> None:
    """Scale member ``k``'s monodromy, its absolute-value product and ``sc`` by ``_SHRINK`` (exact)."""
    A[k] = A[k] * _SHRINK
    Bm[k] = Bm[k] * _SHRINK
    C[k] = C[k] * _SHRINK
    D[k] = D[k] * _SHRINK
    for i in range(4):
        Ab[i, k] = Ab[i, k] * _SHRINK
    sc[k] = sc[k] * _SHRINK


def _slopes(p: F64, r: F64, lam: F64, lo: F64, s: int, u: F64, tmp: F64, A: F64, Bm: F64, C: F64, D: F64,
            u1: F64, fw: I64, status: I64, code: int, Ab: F64, tt: F64, kt: F64, Kn: F64, Kd: F64,
            sc: F64) -> None:
    """Scaled eigenvector slopes ``u[j, k]`` at ``lam[k] + lo[k]`` for sign ``s`` (see :mod:`symbt.numeric.core.step`;
    every ``lam + lo + p_j`` by :func:`~symbt.numeric.core.spectral_sum.lam_add`, as in the fused step).

    ``tt[k]`` receives the trace, ``kt[k]`` the trace's condition (two-tier, as the fused step's
    ``decided`` hook); ``Ab`` (4, B) is scratch for the product of the absolute values (the trace's
    rounding scale, the float64 hooks of :mod:`symbt.numeric.core.fused` in :mod:`.kernels`); ``sc[k]``
    the power of two the monodromy is scaled by."""
    N, B = p.shape
    for k in range(B):
        A[k] = lam_add(lam[k], lo[k], p[0, k])
        Bm[k] = -1.0
        C[k] = r[0, k]
        D[k] = 0.0
        Ab[0, k] = abs(A[k])
        Ab[1, k] = 1.0
        Ab[2, k] = C[k]
        Ab[3, k] = 0.0
        Kn[k] = abs(lam[k]) + abs(p[0, k])      # kernels._track_init: cancellation in a_j = lam + p_j
        Kd[k] = abs(A[k])
        sc[k] = 1.0
    for j in range(1, N):
        big = 0
        for k in range(B):
            a = lam_add(lam[k], lo[k], p[j, k])
            cn = abs(lam[k]) + abs(p[j, k])
            if cn * Kd[k] > Kn[k] * abs(a):
                Kn[k] = cn
                Kd[k] = abs(a)
            a0 = A[k]
            b0 = Bm[k]
            A[k] = a * a0 - C[k]
            Bm[k] = a * b0 - D[k]
            C[k] = r[j, k] * a0
            D[k] = r[j, k] * b0
            aa = abs(a)
            a0 = Ab[0, k]
            b0 = Ab[1, k]
            Ab[0, k] = aa * a0 + Ab[2, k]
            Ab[1, k] = aa * b0 + Ab[3, k]
            Ab[2, k] = r[j, k] * a0
            Ab[3, k] = r[j, k] * b0
            big += 1 if (Ab[0, k] > _BIG or Ab[1, k] > _BIG) else 0
        if big > 0:                    # the exact power-of-two rescaling of :func:`.kernels._rescale`
            for k in range(B):
                if Ab[0, k] > _BIG or Ab[1, k] > _BIG:
                    _shrink(A, Bm, C, D, Ab, sc, k)
    for k in range(B):
        if Ab[2, k] > _BIG or Ab[3, k] > _BIG:
            _shrink(A, Bm, C, D, Ab, sc, k)
    spos = s > 0
    nf = 0
    for k in range(B):
        a_ = A[k]
        b_ = Bm[k]
        c_ = C[k]
        d_ = D[k]
        t = a_ + d_
        tt[k] = t
        two = 2.0 * sc[k]
        disc = (t - two) * (t + two)    # sc**2 (tr**2 - 4): exact
        inrange = (abs(a_) < 1e290 and abs(b_) < 1e290 and abs(c_) < 1e290 and abs(d_) < 1e290
                   and (abs(a_) > 1e-290 or abs(b_) > 1e-290))
        T = Ab[0, k] + Ab[3, k]
        ta = abs(t) + two               # |t| + 2 in the scale: T <= K ||t| - 2|
        kap = T * ta / abs(disc) * (Kn[k] / Kd[k])
        decided = T * ta <= KAPPA_MAX * abs(disc)
        if inrange and not decided:     # the cheap test fails: the sharp k_t decides (kernels._decided)
            ks = sharp_trace_kappa(p[:, k], r[:, k], lam[k], lo[k])
            kap = ks if ks < kap else kap
            decided = kap <= KAPPA_MAX
        bad = (RANGE if not inrange else ILLCOND if not decided else code if not disc > 0.0
               else RANGE if not disc < 1e300 else OK)   # tr**2 must not overflow
        kt[k] = kap
        st = status[k]
        status[k] = st if st != OK else bad
        g = math.sqrt(disc if disc > 0.0 else 0.0)
        dl = a_ - d_
        plus = dl >= 0.0
        # the wanted root is k / (2B), else -2C / k, k = dl +- g; rounded once, as the fused step
        u1[k] = root_slope(a_, d_, dl, g, b_, c_, two, plus, plus == spos)
        f = (t < 0.0) if spos else (t >= 0.0)  # dominant eigenvalue: transport forward
        fw[k] = 1 if f else 0
        nf += fw[k]
    for k in range(B):
        u[0, k] = u1[k]
    if nf > 0:
        for j in range(N - 1):
            for k in range(B):
                u[j + 1, k] = -r[j, k] / (lam_add(lam[k], lo[k], p[j, k]) + u[j, k])
    if nf < B:
        dst = tmp if nf > 0 else u
        for k in range(B):
            dst[0, k] = u1[k]
        for j in range(N - 1, 0, -1):
            jn = j + 1 if j + 1 < N else 0
            for k in range(B):
                dst[j, k] = -lam_add(lam[k], lo[k], p[j, k]) - r[j, k] / dst[jn, k]
        if nf > 0:
            for j in range(1, N):
                for k in range(B):
                    if fw[k] == 0:
                        u[j, k] = tmp[j, k]


def _anchor(qh: F64, ql: F64, fh: F64, fl: F64, r: F64, p: F64, status: I64) -> None:
    """Flush ``F`` into ``q`` and re-anchor ``r = exp(dq)`` (every state of the block)."""
    N, B = qh.shape
    for k in range(B):
        for j in range(N):
            s = _logf(fh[j, k], fl[j, k])
            if not abs(s) < 1e300:
                status[k] = status[k] if status[k] != OK else RANGE
                s = 0.0
            qh[j, k], ql[j, k] = _dd_add(qh[j, k], ql[j, k], s)
            fh[j, k] = 1.0
            fl[j, k] = 0.0
        for j in range(N):
            jn = j + 1 if j + 1 < N else 0
            dq = (qh[jn, k] - qh[j, k]) + (ql[jn, k] - ql[j, k])
            if not (abs(dq) <= MAX_DQ_FLOAT64 and abs(p[j, k]) < 1e300 and abs(qh[j, k]) < 1e300):
                status[k] = status[k] if status[k] != OK else RANGE
                dq = 0.0
            r[j, k] = math.exp(dq)


def run_block(P0: F64, Q0: F64, lam1: F64, lam2: F64, two_mu: F64, branch: int, n: int, every: int,
              anchor: int, outP: F64, outQ: F64, status: I64, i0: int, i1: int) -> None:
    """``n`` steps of the states ``i0 <= i < i1`` of ``(P0, Q0)`` (shape (M, N)).

    ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu``, ``two_mu = 2 mu`` per state;
    stored states (see :func:`~symbt.numeric.float64.kernels.orbit_rows`) go to
    ``outP, outQ`` (rows, M, N); ``status[i]`` is set (0 ok, else the first failure).  An ``outQ`` of
    ``2 N`` columns also receives the positions' low parts (as :func:`~symbt.numeric.float64.kernels.orbit`).

    >>> from symbt.numeric.float64.kernels import ANCHOR
    >>> st = np.zeros(1, np.int64)
    >>> run_block(np.zeros((1, 2)), np.zeros((1, 2)), np.ones(1), -np.ones(1), 2 * np.ones(1), 1, 1, 1, ANCHOR,
    ...           np.empty((2, 1, 2)), np.empty((2, 1, 2)), st, 0, 1)
    >>> int(st[0])                      # tr L(1) = 1 - 2 = -1: lam1 = 1 lies in a band
    1
    """
    N = P0.shape[1]
    B = i1 - i0
    p = np.empty((N, B))
    qh = np.empty((N, B))
    ql = np.zeros((N, B))
    fh = np.ones((N, B))
    fl = np.zeros((N, B))
    r = np.empty((N, B))
    u = np.empty((N, B))
    w = np.empty((N, B))
    tmp = np.empty((N, B))
    xr = np.empty((N, B))
    gq = np.empty((N, B))
    A = np.empty(B)
    Bm = np.empty(B)
    C = np.empty(B)
    D = np.empty(B)
    u1 = np.empty(B)
    fw = np.empty(B, np.int64)
    st = np.zeros(B, np.int64)
    l1 = np.empty(B)
    l2 = np.empty(B)
    tm = np.empty(B)
    o1 = np.empty(B)
    o2 = np.empty(B)
    Ab = np.empty((4, B))
    kt = np.empty(B)
    k1 = np.empty(B)
    k2 = np.empty(B)
    sh = np.empty(B, np.int64)
    Kn = np.empty(B)
    Kd = np.empty(B)
    sc = np.empty(B)
    t1 = np.empty(B)
    t2 = np.empty(B)
    for k in range(B):
        l1[k] = lam1[i0 + k]
        l2[k] = lam2[i0 + k]
        tm[k] = two_mu[i0 + k]
        o1[k], o2[k] = lam_split(l1[k], l2[k], tm[k])
        for j in range(N):
            p[j, k] = P0[i0 + k, j]
            qh[j, k] = Q0[i0 + k, j]
            outP[0, i0 + k, j] = P0[i0 + k, j]
            outQ[0, i0 + k, j] = Q0[i0 + k, j]
    wide = outQ.shape[2] > N
    if wide:
        for k in range(B):
            for j in range(N):
                outQ[0, i0 + k, N + j] = 0.0
    _anchor(qh, ql, fh, fl, r, p, st)
    row = 1
    for i in range(1, n + 1):
        _slopes(p, r, l1, o1, branch, u, tmp, A, Bm, C, D, u1, fw, st, TRACE1, Ab, t1, k1, Kn, Kd, sc)
        _slopes(p, r, l2, o2, -branch, w, tmp, A, Bm, C, D, u1, fw, st, TRACE2, Ab, t2, k2, Kn, Kd, sc)
        for k in range(B):
            kt[k] = max(k1[k], k2[k])
            if st[k] == OK and (t1[k] < 0.0) != (t2[k] < 0.0):
                st[k] = POSITIVITY          # lam1, lam2 in different gaps (kernels.orbit)
            sh[k] = st[k]
        for j in range(N):
            for k in range(B):
                dn = u[j, k] - w[j, k]
                x = tm[k] / dn
                xr[j, k] = x
                gq[j, k] = u[j, k] / dn
                ok = (kt[k] * (abs(u[j, k]) + abs(w[j, k])) * (abs(x + 1.0) + abs(x))
                      <= KAPPA_MAX * abs(dn) * abs(x + 1.0))          # kernels.orbit
                bad = (RANGE if not abs(x) < 1e300 else ILLCOND if not ok
                       else POSITIVITY if not x + 1.0 > 0.0 else OK)
                s0 = st[k]
                st[k] = s0 if s0 != OK else bad
        for k in range(B):
            if sh[k] == OK and st[k] == ILLCOND:
                # a site's read-out test failed with the cheap k_t: the sharp tier (kernels._sharpen), and the
                # sites decided again in order (those before passed with the larger k_t), off the SIMD loop
                ks = sharp_trace_kappa(p[:, k], r[:, k], l1[k], o1[k])
                k1[k] = ks if ks < k1[k] else k1[k]
                ks = sharp_trace_kappa(p[:, k], r[:, k], l2[k], o2[k])
                k2[k] = ks if ks < k2[k] else k2[k]
                kt[k] = max(k1[k], k2[k])
                st[k] = OK
                for j in range(N):
                    x = xr[j, k]
                    dn = u[j, k] - w[j, k]
                    ok = (kt[k] * (abs(u[j, k]) + abs(w[j, k])) * (abs(x + 1.0) + abs(x))
                          <= KAPPA_MAX * abs(dn) * abs(x + 1.0))
                    bad = (RANGE if not abs(x) < 1e300 else ILLCOND if not ok
                           else POSITIVITY if not x + 1.0 > 0.0 else OK)
                    if bad != OK:
                        st[k] = bad
                        break
        for j in range(N):
            jn = j + 1 if j + 1 < N else 0
            for k in range(B):
                p[j, k] = p[j, k] + tm[k] * (gq[jn, k] - gq[j, k])
                x = xr[j, k]
                d = (xr[jn, k] - x) / (1.0 + x)
                r[j, k] = r[j, k] + r[j, k] * d
                a = fh[j, k]
                t = a * x
                s = a + t
                bp = s - a
                fl[j, k] = fl[j, k] + fl[j, k] * x + ((a - (s - bp)) + (t - bp))
                fh[j, k] = s
        if i % anchor == 0:
            _anchor(qh, ql, fh, fl, r, p, st)
        if i % every == 0 or i == n:
            for k in range(B):
                for j in range(N):
                    y = _dd_position(qh[j, k], ql[j, k], fh[j, k], fl[j, k])
                    if not (abs(y) < 1e300 and abs(p[j, k]) < 1e300):
                        st[k] = st[k] if st[k] != OK else RANGE
                    outP[row, i0 + k, j] = p[j, k]
                    outQ[row, i0 + k, j] = y
                    if wide:
                        outQ[row, i0 + k, N + j] = _dd_low(qh[j, k], ql[j, k], fh[j, k], fl[j, k], y)
            row += 1
        nbad = 0
        for k in range(B):
            nbad += 1 if st[k] != OK else 0
        if nbad == B:
            break
    for k in range(B):
        status[i0 + k] = st[k]


def ensemble(P0: F64, Q0: F64, lam1: F64, lam2: F64, two_mu: F64, branch: int, n: int, every: int,
             anchor: int, block: int, outP: F64, outQ: F64, status: I64) -> None:
    """:func:`run_block` over all blocks of ``block`` states (``prange`` when compiled).

    >>> from symbt.numeric.float64.kernels import ANCHOR
    >>> M = 3
    >>> P, Q, st = np.empty((2, M, 3)), np.empty((2, M, 3)), np.zeros(M, np.int64)
    >>> ensemble(np.tile([-20.0, 10, 1], (M, 1)), np.tile([1.0, 0, 0.9], (M, 1)), np.full(M, 15.0),
    ...          np.full(M, 5.0), np.full(M, 10.0), 1, 1, 1, ANCHOR, 2, P, Q, st)
    >>> st.tolist(), bool(np.all(P[1] == P[1, 0]))
    ([0, 0, 0], True)
    """
    M = P0.shape[0]
    nb = -(-M // block)         # ceil(M / block): the last block may be partial
    for b in prange(nb):
        i0 = b * block
        i1 = min(M, i0 + block)
        run_block(P0, Q0, lam1, lam2, two_mu, branch, n, every, anchor, outP, outQ, status, i0, i1)
