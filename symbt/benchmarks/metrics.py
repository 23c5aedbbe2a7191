"""Error metrics: normwise relative state error and invariant drift.

State error at a checkpoint: ``||x - x_ref|| / ||(p_ref, q_ref - mean q_ref)||`` (2-norms).  The
numerator includes everything (also the error of the centre of mass ``mean q``); the
denominator leaves the centre of mass out because it drifts linearly (``|mean q| ~ 500`` after
3500 steps of the paper's example) and would make every error look ~100x smaller.
Invariant drift: ``max |H_k(x) - H_k(x_0)| / |H_k(x_0)|`` over checkpoints and k (N <= 8), for
larger N the relative change of ``tr L`` at ``lam0`` and ``lam0 +- mu`` (float64 evaluation).

>>> import numpy as np
>>> hi = np.array([[1.0, 0.0, 0.0, 2.0]]); lo = np.zeros_like(hi)
>>> float(state_errors(np.array([[1.0, 0.0]]), np.array([[0.0, 2.0]]), hi, lo)[0])
0.0
"""
from __future__ import annotations

from typing import Any

import mpmath
import numpy as np

from ..numeric import invariants, spectral_trace
from .cases import Case

__all__ = ["state_errors", "mp_state_error", "InvariantMeter"]


def state_errors(P: np.ndarray, Q: np.ndarray, hi: np.ndarray, lo: np.ndarray) -> np.ndarray:
    """Normwise relative errors of float64 states ``(P, Q)`` (rows) against ``hi + lo``."""
    X = np.concatenate([P, Q], axis=-1)
    d = (X - hi) - lo
    N = P.shape[-1]
    pr = hi[:, :N]
    qr = hi[:, N:]
    den = np.sqrt(np.sum(pr**2, -1) + np.sum((qr - qr.mean(-1, keepdims=True)) ** 2, -1))
    return np.sqrt(np.sum(d**2, -1)) / den


def mp_state_error(x: list, ref: list) -> float:
    """The same metric for one state ``x = p + q`` (mpf or exact binary floats) against ``ref`` (mpf)."""
    N = len(ref) // 2
    with mpmath.workdps(max(mpmath.mp.dps, 250)):
        x = [mpmath.mpmathify(v) for v in x]
        mq = mpmath.fsum(ref[N:]) / N
        den = mpmath.fsum(v**2 for v in ref[:N]) + mpmath.fsum((v - mq) ** 2 for v in ref[N:])
        num = mpmath.fsum((a - b) ** 2 for a, b in zip(x, ref))
        return float(mpmath.sqrt(num / den))


class InvariantMeter:
    """Relative drift of the invariants along float64 checkpoint states (see module docstring)."""

    def __init__(self, case: Case) -> None:
        self.small = case.N <= 8
        with mpmath.workdps(40):
            P = [mpmath.mpf(v) for v in case.p]
            Q = [mpmath.mpf(v) for v in case.q]
            if self.small:
                self.ref = np.array([float(v) for v in invariants(P, Q)])
            else:
                self.lams = (case.lam0 - case.mu, case.lam0, case.lam0 + case.mu)
                self.ref = np.array([float(spectral_trace(lam, P, Q)) for lam in self.lams])

    def drift(self, P: Any, Q: Any) -> float:
        P = np.asarray(P, dtype=float)
        Qc = np.asarray(Q, dtype=float)
        Qc = Qc - Qc.mean(-1, keepdims=True)
        with np.errstate(all="ignore"):
            if self.small:
                H = invariants(P, Qc)
            else:
                H = np.stack([spectral_trace(lam, P, Qc) for lam in self.lams], -1)
        return float(np.max(np.abs(H - self.ref) / np.abs(self.ref)))
