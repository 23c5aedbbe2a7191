"""Helpers that other claim modules still import from :mod:`symbt.claims.composed_map` (kept for them).

New code takes its helpers from :mod:`symbt.claims._common`; these keep the old signatures
(``_states(N)`` -> ``[(state, branch)]``, ``darboux_numeric(lv, l0, mu, x, y)`` for eq. ``D``).
"""
from __future__ import annotations

from typing import Any

import mpmath as mp

from ..proof import Verdict, Worst
from ..reference.samples import admissible_states
from ._common import DPS, TOL, fmt_state

__all__ = ["worst_over", "darboux_numeric", "_states", "_fmt_state"]


def _fmt_state(state: tuple, branch: int) -> dict[str, Any]:
    return fmt_state(state, branch)


def worst_over(cases, residual, *, method: str, dps: int = DPS, tol: Any = TOL) -> Verdict:
    """Largest ``residual(state, branch)`` over ``cases`` at ``dps`` digits, as a sampled :class:`Verdict`."""
    w = Worst()
    with mp.workdps(dps):
        for state, b in cases:
            w.add(residual(state, b), _fmt_state(state, b))
    return w.verdict(method, tol=tol, dps=dps)


def darboux_numeric(lv, l0, mu, x, y):
    """Eq. ``D`` at a number ``lv`` (mpmath)."""
    return mp.matrix([[lv - (l0 + mu) - x * y, -x], [y * (2 * mu + x * y), lv - (l0 - mu) + x * y]])


def _states(N: int) -> list:
    return [(s, b) for sign in (+1, -1) for s in admissible_states(N, sign, 2) for b in (+1, -1)]
