r"""Fused single-orbit kernel of the float64 Bäcklund map (optional numba JIT).

:func:`fast_orbit` computes the same orbit as :func:`symbt.numeric.bt_orbit`
for *one* state (the algorithm of :mod:`symbt.numeric.step`: scaled
eigenvector slopes, each transported in its contracting direction,
cancellation-free read-out, centre of mass carried separately with a
compensated sum), but as one scalar loop over steps and sites instead of
numpy calls on 0-d/1-element arrays.  For small ``N`` the numpy path spends
almost all of its ~0.2 ms per step in interpreter and dispatch overhead; the
kernel costs ~10 µs per N=3 step as plain Python (``math`` module) and well
under 1 µs when numba is installed (``pip install symbt[fast]``).

The pure-Python and numba versions run the *same* source on IEEE doubles with
``sqrt``/``exp``/``log1p`` from the C math library (numba calls libm, no
``fastmath``), so their results are identical bit for bit (checked in
``tests/test_stress.py``).  Against ``bt_orbit`` they agree to a few ulps (numpy's
vectorised ``exp``/``log1p`` may round differently in the last bit).

Anything outside the kernel's fast path -- ``|tr L| <= 2``, ``Etilde_j <= 0``,
overflow of the unscaled monodromy (huge ``N`` or ``lam``) or any non-finite
intermediate -- makes :func:`fast_orbit` recompute the orbit with
:func:`~symbt.numeric.bt_orbit`, which raises the documented typed errors or
renormalises.  Only float64 single states are supported.

Example
-------
>>> from symbt.numeric.fast import fast_orbit
>>> P, Q = fast_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 3500, every=3500)
>>> P.shape
(2, 3)
"""

from __future__ import annotations

import math
import os

import numpy as np

from ._input import check_branch, prepare_spectral_pair
from .context import FLOAT
from .errors import InvalidInputError
from .orbit import bt_orbit

__all__ = ["fast_orbit", "HAVE_NUMBA", "kernel_backend"]


def _slopes(p, r, lam, s, u, out_tr):
    """Slopes ``u_j`` at ``lam`` for eigenvector sign ``s``; returns status (0 ok)."""
    N = p.shape[0]
    A = lam + p[0]
    B = -1.0
    C = r[0]
    D = 0.0
    for j in range(1, N):
        a = lam + p[j]
        A, B, C, D = a * A - C, a * B - D, r[j] * A, r[j] * B
    t = A + D
    out_tr[0] = t
    if not (abs(A) < 1e290 and abs(B) < 1e290 and abs(C) < 1e290 and abs(D) < 1e290):
        return 3                      # overflow risk: let the renormalising path do it
    if not (abs(A) > 1e-290 or abs(B) > 1e-290):
        return 3
    disc = (t - 2.0) * (t + 2.0)
    if not disc > 0.0:
        return 1                      # |tr| <= 2: no real map
    g = math.sqrt(disc)
    dl = A - D
    plus = dl >= 0.0
    sg = g if plus else -g
    k = dl + sg
    target_is_k = plus if s > 0 else not plus
    if target_is_k:
        u1 = k / (2.0 * B)
    else:
        u1 = -2.0 * C / k
    fwd = (t < 0.0) if s > 0 else (t >= 0.0)
    u[0] = u1
    if fwd:
        for j in range(N - 1):
            u[j + 1] = -r[j] / (lam + p[j] + u[j])
    else:
        nxt = u1
        for j in range(N - 1, 0, -1):
            nxt = -(lam + p[j]) - r[j] / nxt
            u[j] = nxt
    return 0


def _orbit_kernel(p0, q0, lam0, mu, branch, n, every, outP, outQ):
    """``n`` steps from ``(p0, q0)``; stores every ``every``-th state (and the last).

    Returns ``(status, steps_done)``; status 0 = success, 1 = |tr| <= 2,
    2 = Etilde <= 0, 3 = range problem / non-finite.
    """
    N = p0.shape[0]
    p = p0.copy()
    c_hi = 0.0
    for j in range(N):
        c_hi += q0[j]
    c_hi = c_hi / N
    c_lo = 0.0
    qr = np.empty(N)
    for j in range(N):
        qr[j] = q0[j] - c_hi
    r = np.empty(N)
    u = np.empty(N)
    w = np.empty(N)
    gq = np.empty(N)
    qn = np.empty(N)
    tr = np.empty(1)
    lam1 = lam0 + mu
    lam2 = lam0 - mu
    two_mu = 2.0 * mu
    for j in range(N):
        outP[0, j] = p0[j]
        outQ[0, j] = q0[j]
    row = 1
    for i in range(1, n + 1):
        for j in range(N - 1):
            r[j] = math.exp(qr[j + 1] - qr[j])
        r[N - 1] = math.exp(qr[0] - qr[N - 1])
        st = _slopes(p, r, lam1, branch, u, tr)
        if st != 0:
            return st, i - 1
        st = _slopes(p, r, lam2, -branch, w, tr)
        if st != 0:
            return st, i - 1
        s = 0.0
        for j in range(N):
            dn = u[j] - w[j]
            xr = two_mu / dn
            if not xr + 1.0 > 0.0:
                return 2, i - 1
            qn[j] = qr[j] + math.log1p(xr)
            gq[j] = u[j] / dn
        for j in range(N):
            jn = j + 1 if j + 1 < N else 0
            p[j] = p[j] + two_mu * (gq[jn] - gq[j])
            s += qn[j]
        s = s / N
        ok = True
        for j in range(N):
            qr[j] = qn[j] - s
            if not (abs(qr[j]) < 1e300 and abs(p[j]) < 1e300):
                ok = False
        if not ok:
            return 3, i - 1
        t = c_hi + s                                  # two-sum (Knuth), as in bt_orbit
        bp = t - c_hi
        c_lo = c_lo + ((c_hi - (t - bp)) + (s - bp))
        c_hi = t
        if i % every == 0 or i == n:
            for j in range(N):
                outP[row, j] = p[j]
                outQ[row, j] = c_hi + (c_lo + qr[j])
            row += 1
    return 0, n


_slopes_py = _slopes
_orbit_kernel_py = _orbit_kernel

HAVE_NUMBA = False
_orbit_kernel_nb = None
if os.environ.get("SYMBT_NO_NUMBA", "") in ("", "0"):
    try:  # optional extra: identical results, ~50x faster
        import numba as _numba

        _slopes_nb = _numba.njit(cache=False, fastmath=False)(_slopes)

        def _make():
            src_globals = {"np": np, "math": math, "_slopes": _slopes_nb}
            fn = type(_orbit_kernel)(_orbit_kernel.__code__, src_globals, "_orbit_kernel_nb")
            return _numba.njit(cache=False, fastmath=False)(fn)

        _orbit_kernel_nb = _make()
        HAVE_NUMBA = True
    except Exception:  # pragma: no cover - numba missing or broken
        HAVE_NUMBA = False


def kernel_backend(backend="auto"):
    """The kernel function for ``backend`` in {"auto", "numba", "python"} and its name."""
    if backend == "python" or (backend == "auto" and not HAVE_NUMBA):
        return _orbit_kernel_py, "python"
    if not HAVE_NUMBA:
        raise InvalidInputError("numba is not installed (pip install symbt[fast])")
    return _orbit_kernel_nb, "numba"


def fast_orbit(p, q, lam0, mu, n, *, branch=1, every=1, backend="auto"):
    """``n`` Bäcklund steps of one float64 state, sampled every ``every`` steps.

    Returns arrays ``P, Q`` of shape ``(rows, N)``: the initial state, the
    states after ``every, 2 every, ...`` steps and always the final state
    (``rows = 1 + ceil(n / every)``).  ``every=1`` gives the same layout as
    :func:`~symbt.numeric.bt_orbit`.  Cases outside the fast path are handed
    to ``bt_orbit`` (see module docstring), so errors are the documented ones.
    """
    branch = check_branch(branch)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise InvalidInputError("n must be a non-negative integer, got %r" % (n,))
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
        raise InvalidInputError("every must be a positive integer, got %r" % (every,))
    p0 = np.ascontiguousarray(p, dtype=np.float64)
    q0 = np.ascontiguousarray(q, dtype=np.float64)
    if p0.ndim != 1 or p0.shape != q0.shape or p0.size < 2:
        raise InvalidInputError("fast_orbit takes one state: p, q of equal shape (N,), N >= 2")
    if not (np.all(np.isfinite(p0)) and np.all(np.isfinite(q0))):
        raise InvalidInputError("non-finite input")
    if np.ndim(lam0) or np.ndim(mu):
        raise InvalidInputError("fast_orbit takes scalar lam0 and mu")
    lam0, mu = prepare_spectral_pair(FLOAT, lam0, mu, ())  # typed errors for complex/non-finite/overflow
    lam0, mu = float(lam0), float(mu)
    n, every = int(n), int(every)
    rows = 1 + -(-n // every)
    P = np.empty((rows, p0.size))
    Q = np.empty((rows, p0.size))
    if mu == 0 or n == 0:
        P[:] = p0
        Q[:] = q0
        return P, Q
    kern, _ = kernel_backend(backend)
    try:
        # the pure-Python kernel computes with numpy scalars: make over/underflow raise, not warn
        with np.errstate(over="raise", divide="raise", invalid="raise"):
            status, _done = kern(p0, q0, float(lam0), float(mu), branch, n, every, P, Q)
    except (ZeroDivisionError, OverflowError, ValueError, FloatingPointError):  # degenerate slope / exp range
        status = 3
    if status != 0:
        # slow path: the library orbit raises the typed errors / renormalises
        Pf, Qf = bt_orbit(p0, q0, lam0, mu, n, branch=branch)
        idx = list(range(0, n + 1, every))
        if idx[-1] != n:
            idx.append(n)
        return Pf[idx], Qf[idx]
    return P, Q
