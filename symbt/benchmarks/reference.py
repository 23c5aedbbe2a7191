"""Reference solutions: the Bäcklund orbit at high precision is the exact flow of ``sum c_k H_k``.

By Theorem 2 (claims ``Hdiscr.n3``, ``Hdiscr.deep.n3`` of scene ``theorem2``) ``n`` steps of the
map are the time-``n`` flow of ``G = sum_k c_k H_k``, so :func:`reference_orbit` (the mpmath BT
orbit at 50 digits, checkpoints kept as double-double pairs ``hi + lo``) is the reference for
every float64 contender, and :func:`reference_states` (at ``2 digits + 20``) for the
high-precision ones.  :func:`flow_constants` are the ``c_k`` the ODE integrators get.

>>> from symbt.benchmarks.cases import cases
>>> rows, hi, lo = reference_orbit(cases(quick=True)[0], every=100)
>>> rows.tolist(), hi.shape
([0, 100, 200, 300], (4, 6))
"""
from __future__ import annotations

from typing import Any

import mpmath
import numpy as np

from ..numeric import bt_step, flow_coefficients
from .cases import Case

__all__ = ["reference_orbit", "reference_states", "flow_constants", "checkpoints"]


def checkpoints(n: int, every: int) -> list[int]:
    """Steps ``0, every, 2 every, ...`` and always ``n``."""
    rows = list(range(0, n + 1, every))
    if rows[-1] != n:
        rows.append(n)
    return rows


def reference_orbit(case: Case, dps: int = 50, every: int = 1, p0: Any = None, q0: Any = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(rows, hi, lo)``: the mpmath BT orbit at ``dps`` digits at the checkpoint rows.

    ``hi + lo`` (float64 pairs, shape ``(rows, 2N)``, ``(p, q)``) represents each state to ~1e-32.
    ``p0, q0`` override the case's initial state (exact binary values are used).
    """
    p0 = case.p if p0 is None else p0
    q0 = case.q if q0 is None else q0
    rows = checkpoints(case.n, every)
    want = set(rows)
    N = len(p0)
    hi = np.empty((len(rows), 2 * N))
    lo = np.empty_like(hi)
    with mpmath.workdps(dps):
        p = [mpmath.mpf(float(v)) for v in p0]
        q = [mpmath.mpf(float(v)) for v in q0]
        k = 0
        for i in range(case.n + 1):
            if i:
                p, q = bt_step(p, q, case.lam0, case.mu, branch=case.branch)
            if i in want:
                for j, v in enumerate(p + q):
                    h = float(v)
                    hi[k, j] = h
                    lo[k, j] = float(v - h)
                k += 1
    return np.array(rows), hi, lo


def reference_states(p0: Any, q0: Any, lam0: Any, mu: Any, n: int, dps: int, branch: int = 1) -> list:
    """The mpmath BT state after ``n`` steps at ``dps`` digits, as a list ``p + q`` of mpf."""
    with mpmath.workdps(dps):
        p = [mpmath.mpmathify(v) for v in p0]
        q = [mpmath.mpmathify(v) for v in q0]
        for _ in range(n):
            p, q = bt_step(p, q, mpmath.mpmathify(lam0), mpmath.mpmathify(mu), branch=branch)
        return list(p) + list(q)


def flow_constants(case: Case, dps: int = 30) -> np.ndarray:
    """``c_0 .. c_{N-1}`` for the ODE contenders, as float64.

    N <= 8: at ``dps`` digits (mpmath path of :func:`symbt.numeric.flow_coefficients`), rounded;
    larger N (whose contenders use :class:`~symbt.numeric.flow.field.FlowField` and only report the
    ``c_k``): the float64 path (relative accuracy ~1e-14, ``tests/test_bench_coefficients.py``).
    """
    if case.N > 8:
        return np.asarray(flow_coefficients(np.array(case.p), np.array(case.q), case.lam0, case.mu,
                                            branch=case.branch))
    with mpmath.workdps(dps):
        c = flow_coefficients([mpmath.mpf(v) for v in case.p], [mpmath.mpf(v) for v in case.q],
                              mpmath.mpf(case.lam0), mpmath.mpf(case.mu), branch=case.branch, check=False)
    return np.array([float(v) for v in c])
