"""Invariant drift of long float64 Bäcklund orbits: random walk, not linear growth.

Used by ``symbt/benchmarks/drift_figure.py`` (the figure) and ``tests/test_stress.py``.
"""
from __future__ import annotations

import mpmath
import numpy as np

from ..numeric import bt_step, invariants
from ..paper import P_EXAMPLE, Q_EXAMPLE

__all__ = ["invariant_drift_curve"]

P_PAPER, Q_PAPER = P_EXAMPLE, Q_EXAMPLE


def invariant_drift_curve(n=10**5, members=16, npoints=40, lam0=10.0, mu=5.0, seed=0, spread=1e-9,
                          keep_first=False):
    """Relative invariant drift of float64 BT orbits of the paper's example, for a growth fit.

    ``members`` orbits start at the paper's state perturbed by ``spread``
    (independent round-off, same torus to ~1e-9); they are advanced together
    with the batched :func:`~symbt.numeric.bt_step` (centre of mass removed each
    step -- the invariants only see ``q`` differences).  At ``npoints``
    log-spaced steps the invariants of the float64 states are evaluated at 40
    digits (so evaluation round-off does not mask the drift).  Returns
    ``(steps, drift)`` with ``drift[i, m, k] = |H_k(x_n) - H_k(x_0)| / |H_k(x_0)|``
    and the RMS over members and k, and the fitted log-log slope of the RMS
    drift versus n (over n >= 100).  Member 0 is the paper's state itself;
    ``keep_first=True`` also returns its whole centred trajectory ``(P, Q)``.
    """
    rng = np.random.default_rng(seed)
    p = np.array(P_PAPER) + spread * rng.normal(size=(members, 3))
    q = np.array(Q_PAPER) + spread * rng.normal(size=(members, 3))
    p[0], q[0] = P_PAPER, Q_PAPER                 # member 0: the paper's state itself
    q = q - q.mean(-1, keepdims=True)
    traj = (np.empty((n + 1, 3)), np.empty((n + 1, 3))) if keep_first else None
    if keep_first:
        traj[0][0], traj[1][0] = p[0], q[0]
    steps = np.unique(np.round(np.logspace(0, np.log10(n), npoints)).astype(int))

    def inv_mp(p, q):
        with mpmath.workdps(40):
            return [invariants([mpmath.mpf(float(a)) for a in pp], [mpmath.mpf(float(b)) for b in qq])
                    for pp, qq in zip(p, q)]
    H0 = inv_mp(p, q)
    drift = np.empty((len(steps), members, 3))
    k = 0
    for i in range(1, n + 1):
        p, q = bt_step(p, q, lam0, mu)
        q = q - q.mean(-1, keepdims=True)
        if keep_first:
            traj[0][i], traj[1][i] = p[0], q[0]
        if i == steps[k]:
            H = inv_mp(p, q)
            with mpmath.workdps(40):
                for m in range(members):
                    for j in range(3):
                        drift[k, m, j] = float(abs(H[m][j] - H0[m][j]) / abs(H0[m][j]))
            k += 1
    rms = np.sqrt(np.mean(drift**2, axis=(1, 2)))
    sel = steps >= 100
    slope = float(np.polyfit(np.log(steps[sel]), np.log(rms[sel]), 1)[0])
    if keep_first:
        return steps, drift, rms, slope, traj
    return steps, drift, rms, slope
