r"""Fused float64 orbit kernels: plain-Python source, compiled by numba on demand (:mod:`.jit`).

One source serves three uses: the plain-Python single-orbit kernel (no numba),
the numba single-orbit kernel and the numba ensemble kernel (``prange`` over
blocks of states).  The arithmetic is that of :mod:`symbt.numeric.step`
(scaled eigenvector slopes, each transported in its contracting direction,
cancellation-free read-out); results of the Python and numba versions are
identical bit for bit (IEEE doubles, libm ``sqrt/exp/log1p``, no ``fastmath``).

Data layout.  A *block* of ``B`` states is held site-major, ``x[j, k]`` with the
state index ``k`` innermost, so every loop over ``k`` is a plain elementwise
loop that LLVM vectorises; a block is small enough to stay in L1.

Orbit variables.  Instead of ``q`` the dynamics carries the neighbour ratios
``r_j = exp(q_{j+1} - q_j)`` (all the step needs) and updates them exactly as
the map does, ``r~_j = r_j (1 + xr_{j+1}) / (1 + xr_j)`` with
``xr_j = Etilde_j / E_j - 1``, computed as ``r_j + r_j d_j``,
``d_j = (xr_{j+1} - xr_j) / (1 + xr_j)``.  The positions are accumulated as
``X_j = prod(1 + xr_j) - 1`` (``X <- X + xr + X xr``: relative accuracy for small
``mu``) and flushed into a double-double ``q = qh + ql`` with one ``log1p`` per
site every ``anchor`` steps (or earlier if ``X`` leaves ``(-1/2, 1e6)``), where
``r`` is also re-anchored to ``exp`` of the double-double differences.  Stored
states read ``q = qh + ql + log1p(X)`` without touching the state, so the
orbit does not depend on ``every`` (bit for bit).  So there are no
transcendental functions in the inner step except two square roots, the
rounding per step stays at the level of the exp/log1p formulation (``O(eps)``
in ``log r``), and ``q`` never loses the low bits of the increments (the
centre of mass can drift to ``|q| ~ 1e3`` without perturbing the relative
coordinates).  After one step (``n = 1``) the result is exactly the formula of
:func:`~symbt.numeric.step.step_core`: ``r`` from ``exp(q_{j+1} - q_j)``,
``q~ = q + log1p(xr)`` (rounded once).

Status codes per state (first failure wins): ``0`` ok, ``1``/``2``
``|tr L(lam1/lam2)| <= 2``, ``3`` some ``Etilde_j <= 0``, ``4`` range problem
(monodromy entries beyond ``1e290``, ``|q_{j+1} - q_j| > 700``, a non-finite
intermediate such as a degenerate eigenvector).  The drivers recompute every
failing state with the general path, which decides the error.

Example
-------
>>> import numpy as np
>>> from symbt.numeric.kernels import run_block, orbit_rows
>>> p0, q0 = np.array([[-20.0, 10.0, 1.0]]), np.array([[1.0, 0.0, 0.9]])
>>> rows = orbit_rows(2, 1)
>>> P, Q, st = np.empty((rows, 1, 3)), np.empty((rows, 1, 3)), np.zeros(1, np.int64)
>>> one = np.ones(1)
>>> run_block(p0, q0, 15.0 * one, 5.0 * one, 10.0 * one, 1, 2, 1, 16, P, Q, st, 0, 1)
>>> int(st[0]), np.round(P[1, 0], 8).tolist()
(0, [-19.99656766, 9.78635495, 1.21021272])
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

__all__ = ["orbit", "run_block", "ensemble", "orbit_rows", "stored_steps", "ANCHOR", "OK", "TRACE1", "TRACE2",
           "POSITIVITY", "RANGE"]

OK, TRACE1, TRACE2, POSITIVITY, RANGE = 0, 1, 2, 3, 4
#: steps between re-anchoring ``r`` to ``exp`` of the accumulated positions
ANCHOR = 16

prange = range  # the ensemble kernel is compiled with numba.prange in its place

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]


def orbit_rows(n: int, every: int) -> int:
    """Number of stored states: steps ``0, every, 2 every, ...`` and always ``n``.

    >>> orbit_rows(10, 3), orbit_rows(9, 3), orbit_rows(0, 5)
    (5, 4, 1)
    """
    return 1 + -(-n // every)


def stored_steps(n: int, every: int) -> list[int]:
    """The step numbers of the stored states (see :func:`orbit_rows`).

    >>> stored_steps(10, 3)
    [0, 3, 6, 9, 10]
    """
    out = list(range(0, n + 1, every))
    if out[-1] != n:
        out.append(n)
    return out


def _slopes(p: F64, r: F64, lam: F64, s: int, u: F64, tmp: F64, A: F64, Bm: F64, C: F64, D: F64,
            u1: F64, fw: I64, status: I64, code: int) -> None:
    """Scaled eigenvector slopes ``u[j, k]`` at ``lam[k]`` for sign ``s`` (see :mod:`.step`)."""
    N, B = p.shape
    for k in range(B):
        A[k] = lam[k] + p[0, k]
        Bm[k] = -1.0
        C[k] = r[0, k]
        D[k] = 0.0
    for j in range(1, N):
        for k in range(B):
            a = lam[k] + p[j, k]
            a0 = A[k]
            b0 = Bm[k]
            A[k] = a * a0 - C[k]
            Bm[k] = a * b0 - D[k]
            C[k] = r[j, k] * a0
            D[k] = r[j, k] * b0
    spos = s > 0
    nf = 0
    for k in range(B):
        a_ = A[k]
        b_ = Bm[k]
        c_ = C[k]
        d_ = D[k]
        t = a_ + d_
        inrange = (abs(a_) < 1e290 and abs(b_) < 1e290 and abs(c_) < 1e290 and abs(d_) < 1e290
                   and (abs(a_) > 1e-290 or abs(b_) > 1e-290))
        disc = (t - 2.0) * (t + 2.0)
        bad = RANGE if not inrange else (code if not disc > 0.0 else OK)
        st = status[k]
        status[k] = st if st != OK else bad
        g = math.sqrt(disc if disc > 0.0 else 0.0)
        dl = a_ - d_
        plus = dl >= 0.0
        kk = dl + (g if plus else -g)
        tk = plus == spos                      # the wanted root is k / (2B), else -2C / k
        num = kk if tk else -2.0 * c_
        den = 2.0 * b_ if tk else kk
        u1[k] = num / den
        f = (t < 0.0) if spos else (t >= 0.0)  # dominant eigenvalue: transport forward
        fw[k] = 1 if f else 0
        nf += fw[k]
    for k in range(B):
        u[0, k] = u1[k]
    if nf > 0:
        for j in range(N - 1):
            for k in range(B):
                u[j + 1, k] = -r[j, k] / (lam[k] + p[j, k] + u[j, k])
    if nf < B:
        dst = tmp if nf > 0 else u
        for k in range(B):
            dst[0, k] = u1[k]
        for j in range(N - 1, 0, -1):
            jn = j + 1 if j + 1 < N else 0
            for k in range(B):
                dst[j, k] = -(lam[k] + p[j, k]) - r[j, k] / dst[jn, k]
        if nf > 0:
            for j in range(1, N):
                for k in range(B):
                    if fw[k] == 0:
                        u[j, k] = tmp[j, k]


def _anchor(qh: F64, ql: F64, X: F64, r: F64, p: F64, status: I64, need: I64, every_row: bool) -> None:
    """Flush ``X`` into the double-double positions and re-anchor ``r = exp(dq)``.

    Done for every state if ``every_row``, else for the states with ``need[k] != 0``.
    """
    N, B = qh.shape
    for k in range(B):
        if every_row or need[k] != 0:
            for j in range(N):
                x = X[j, k]
                if not (x > -1.0 and x < 1e300):
                    status[k] = status[k] if status[k] != OK else RANGE
                    x = 0.0
                s = math.log1p(x)
                X[j, k] = 0.0
                a = qh[j, k]
                t = a + s
                bp = t - a
                lo = ql[j, k] + ((a - (t - bp)) + (s - bp))
                hi = t + lo                                  # renormalise (|t| >= |lo|)
                ql[j, k] = lo - (hi - t)
                qh[j, k] = hi
            for j in range(N):
                jn = j + 1 if j + 1 < N else 0
                dq = (qh[jn, k] - qh[j, k]) + (ql[jn, k] - ql[j, k])
                if not (abs(dq) <= 700.0 and abs(p[j, k]) < 1e300 and abs(qh[j, k]) < 1e300):
                    status[k] = status[k] if status[k] != OK else RANGE
                    dq = 0.0
                r[j, k] = math.exp(dq)


def _position(qh: float, ql: float, x: float) -> float:
    """The position ``qh + ql + log1p(x)`` rounded once (the state itself is not changed)."""
    if not (x > -1.0 and x < 1e300):
        return math.nan
    s = math.log1p(x)
    t = qh + s
    bp = t - qh
    return t + (ql + ((qh - (t - bp)) + (s - bp)))


def _slopes1(p: F64, r: F64, lam: float, s: int, u: F64, code: int) -> int:
    """One state of :func:`_slopes` (same operations in the same order); returns the status."""
    N = p.shape[0]
    A = lam + p[0]
    Bm = -1.0
    C = r[0]
    D = 0.0
    for j in range(1, N):
        a = lam + p[j]
        a0 = A
        b0 = Bm
        A = a * a0 - C
        Bm = a * b0 - D
        C = r[j] * a0
        D = r[j] * b0
    t = A + D
    if not (abs(A) < 1e290 and abs(Bm) < 1e290 and abs(C) < 1e290 and abs(D) < 1e290
            and (abs(A) > 1e-290 or abs(Bm) > 1e-290)):
        return RANGE
    disc = (t - 2.0) * (t + 2.0)
    if not disc > 0.0:
        return code
    g = math.sqrt(disc)
    dl = A - D
    plus = dl >= 0.0
    kk = dl + (g if plus else -g)
    tk = plus == (s > 0)
    num = kk if tk else -2.0 * C
    den = 2.0 * Bm if tk else kk
    u[0] = num / den
    if (t < 0.0) if s > 0 else (t >= 0.0):
        for j in range(N - 1):
            u[j + 1] = -r[j] / (lam + p[j] + u[j])
    else:
        for j in range(N - 1, 0, -1):
            jn = j + 1 if j + 1 < N else 0
            u[j] = -(lam + p[j]) - r[j] / u[jn]
    return OK


def _anchor1(qh: F64, ql: F64, X: F64, r: F64, p: F64) -> int:
    """One state of :func:`_anchor`; returns the status."""
    N = qh.shape[0]
    for j in range(N):
        x = X[j]
        if not (x > -1.0 and x < 1e300):
            return RANGE
        s = math.log1p(x)
        X[j] = 0.0
        a = qh[j]
        t = a + s
        bp = t - a
        lo = ql[j] + ((a - (t - bp)) + (s - bp))
        hi = t + lo
        ql[j] = lo - (hi - t)
        qh[j] = hi
    for j in range(N):
        jn = j + 1 if j + 1 < N else 0
        dq = (qh[jn] - qh[j]) + (ql[jn] - ql[j])
        if not (abs(dq) <= 700.0 and abs(p[j]) < 1e300 and abs(qh[j]) < 1e300):
            return RANGE
        r[j] = math.exp(dq)
    return OK


def orbit(p0: F64, q0: F64, lam1: float, lam2: float, two_mu: float, branch: int, n: int, every: int,
          anchor: int, outP: F64, outQ: F64) -> int:
    """Single-state version of :func:`run_block` (identical arithmetic); returns the status.

    ``outP, outQ`` have shape (rows, N) (see :func:`orbit_rows`).

    >>> P, Q = np.empty((2, 3)), np.empty((2, 3))
    >>> orbit(np.array([-20.0, 10, 1]), np.array([1.0, 0, 0.9]), 15.0, 5.0, 10.0, 1, 1, 1, ANCHOR, P, Q)
    0
    >>> round(float(Q[1, 0]), 8)
    -0.08614224
    """
    N = p0.shape[0]
    p = p0.copy()
    qh = q0.copy()
    ql = np.zeros(N)
    X = np.zeros(N)
    r = np.empty(N)
    u = np.empty(N)
    w = np.empty(N)
    xr = np.empty(N)
    gq = np.empty(N)
    for j in range(N):
        outP[0, j] = p0[j]
        outQ[0, j] = q0[j]
    st = _anchor1(qh, ql, X, r, p)
    if st != OK:
        return st
    row = 1
    for i in range(1, n + 1):
        st = _slopes1(p, r, lam1, branch, u, TRACE1)
        if st != OK:
            return st
        st = _slopes1(p, r, lam2, -branch, w, TRACE2)
        if st != OK:
            return st
        for j in range(N):
            dn = u[j] - w[j]
            x = two_mu / dn
            xr[j] = x
            gq[j] = u[j] / dn
            if not abs(x) < 1e300:
                return RANGE
            if not x + 1.0 > 0.0:
                return POSITIVITY
        flag = 0
        for j in range(N):
            jn = j + 1 if j + 1 < N else 0
            p[j] = p[j] + two_mu * (gq[jn] - gq[j])
            if not abs(p[j]) < 1e300:
                return RANGE
            x = xr[j]
            d = (xr[jn] - x) / (1.0 + x)
            r[j] = r[j] + r[j] * d
            y = X[j] + x + X[j] * x
            X[j] = y
            if not (y > -0.5 and y < 1e6):
                flag = 1
        if flag > 0 or i % anchor == 0:
            st = _anchor1(qh, ql, X, r, p)
            if st != OK:
                return st
        if i % every == 0 or i == n:
            for j in range(N):
                outP[row, j] = p[j]
                y = _position(qh[j], ql[j], X[j])
                if not abs(y) < 1e300:
                    return RANGE
                outQ[row, j] = y
            row += 1
    return OK


def run_block(P0: F64, Q0: F64, lam1: F64, lam2: F64, two_mu: F64, branch: int, n: int, every: int,
              anchor: int, outP: F64, outQ: F64, status: I64, i0: int, i1: int) -> None:
    """``n`` steps of the states ``i0 <= i < i1`` of ``(P0, Q0)`` (shape (M, N)).

    ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu``, ``two_mu = 2 mu`` per state;
    stored states (see :func:`orbit_rows`) go to ``outP, outQ`` (rows, M, N);
    ``status[i]`` is set (0 ok, else the first failure, see module docstring).
    Example: see the module docstring.

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
    X = np.zeros((N, B))
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
    need = np.zeros(B, np.int64)
    l1 = np.empty(B)
    l2 = np.empty(B)
    tm = np.empty(B)
    for k in range(B):
        l1[k] = lam1[i0 + k]
        l2[k] = lam2[i0 + k]
        tm[k] = two_mu[i0 + k]
        for j in range(N):
            p[j, k] = P0[i0 + k, j]
            qh[j, k] = Q0[i0 + k, j]
            outP[0, i0 + k, j] = P0[i0 + k, j]
            outQ[0, i0 + k, j] = Q0[i0 + k, j]
    _anchor(qh, ql, X, r, p, st, need, True)
    row = 1
    for i in range(1, n + 1):
        _slopes(p, r, l1, branch, u, tmp, A, Bm, C, D, u1, fw, st, TRACE1)
        _slopes(p, r, l2, -branch, w, tmp, A, Bm, C, D, u1, fw, st, TRACE2)
        for j in range(N):
            for k in range(B):
                dn = u[j, k] - w[j, k]
                x = tm[k] / dn
                xr[j, k] = x
                gq[j, k] = u[j, k] / dn
                bad = RANGE if not abs(x) < 1e300 else (POSITIVITY if not x + 1.0 > 0.0 else OK)
                s0 = st[k]
                st[k] = s0 if s0 != OK else bad
        flag = 0
        for j in range(N):
            jn = j + 1 if j + 1 < N else 0
            for k in range(B):
                pn = p[j, k] + tm[k] * (gq[jn, k] - gq[j, k])
                p[j, k] = pn
                s1 = st[k]
                st[k] = s1 if (s1 != OK or abs(pn) < 1e300) else RANGE
                x = xr[j, k]
                d = (xr[jn, k] - x) / (1.0 + x)
                r[j, k] = r[j, k] + r[j, k] * d
                y = X[j, k] + x + X[j, k] * x
                X[j, k] = y
                far = 0 if (st[k] != OK or (y > -0.5 and y < 1e6)) else 1
                need[k] = need[k] | far
                flag += far
        if i % anchor == 0:
            _anchor(qh, ql, X, r, p, st, need, True)
        elif flag > 0:
            _anchor(qh, ql, X, r, p, st, need, False)
        if flag > 0:
            for k in range(B):
                need[k] = 0
        if i % every == 0 or i == n:
            for k in range(B):
                for j in range(N):
                    outP[row, i0 + k, j] = p[j, k]
                    y = _position(qh[j, k], ql[j, k], X[j, k])
                    outQ[row, i0 + k, j] = y
                    if not abs(y) < 1e300:
                        st[k] = st[k] if st[k] != OK else RANGE
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

    >>> M = 3
    >>> P, Q, st = np.empty((2, M, 3)), np.empty((2, M, 3)), np.zeros(M, np.int64)
    >>> ensemble(np.tile([-20.0, 10, 1], (M, 1)), np.tile([1.0, 0, 0.9], (M, 1)), np.full(M, 15.0),
    ...          np.full(M, 5.0), np.full(M, 10.0), 1, 1, 1, ANCHOR, 2, P, Q, st)
    >>> st.tolist(), bool(np.all(P[1] == P[1, 0]))
    ([0, 0, 0], True)
    """
    M = P0.shape[0]
    nb = (M + block - 1) // block
    for b in prange(nb):
        i0 = b * block
        i1 = min(M, i0 + block)
        run_block(P0, Q0, lam1, lam2, two_mu, branch, n, every, anchor, outP, outQ, status, i0, i1)
