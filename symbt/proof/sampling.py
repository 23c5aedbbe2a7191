"""Sampled verdicts: the worst relative residual over finitely many points.

A numeric check evaluates a residual at many states and keeps the worst one
together with a description of where it occurred; :meth:`Worst.verdict`
turns that into a :class:`~symbt.proof.Verdict` with ``evidence="sampled"``.

>>> w = Worst()
>>> w.add(1e-52, {"x": "0.5"}); w.add(3e-3, {"x": "2.0"})
>>> v = w.verdict("numeric: 50 digits at 2 points", tol=1e-40)
>>> v.holds, v.counterexample, w.n
(False, {'x': '2.0'}, 2)
"""
from __future__ import annotations

from typing import Any

import mpmath

from .verdict import Verdict

__all__ = ["Worst"]


class Worst:
    """Running maximum of a relative residual and the point where it occurred."""

    def __init__(self) -> None:
        self.residual: Any = mpmath.mpf(0)
        self.counterexample: dict[str, Any] | None = None
        self.n = 0

    def add(self, residual: Any, counterexample: dict[str, Any] | None = None) -> None:
        """Record one sample (``residual`` is made non-negative)."""
        r = abs(mpmath.mpmathify(residual))
        self.n += 1
        if r > self.residual or self.counterexample is None:
            self.residual = max(self.residual, r)
            self.counterexample = counterexample

    def verdict(self, method: str, *, tol: Any, dps: float | None = None, note: str = "") -> Verdict:
        """The sampled verdict: holds iff the worst residual is at most ``tol``."""
        return Verdict.sampled(self.residual, tol=tol, method=method, counterexample=self.counterexample,
                               dps=dps, note=note)
