"""Reproducible sample states for numeric claims (the paper's example and random ones).

``admissible_states(N, trace_sign, count)`` draws (p, q, lam0, mu) at random
(seeded) and keeps those where the real map exists (|tr L| > 2 at both
lambda_1, lambda_2, with the requested sign of tr L there, and every
e^{q~_j} > 0 for *both* branches).  Values are exact decimal strings turned
into mpf at the working precision, so the points are the same at any dps.
"""
from __future__ import annotations

import random
from typing import Any

import mpmath as mp

from ..paper import EXAMPLE
from .literal import literal_step

__all__ = ["admissible_states", "paper_state"]


def paper_state(mu: str = "5") -> tuple[list[mp.mpf], list[mp.mpf], mp.mpf, mp.mpf]:
    """The paper's example ``(p, q, lam0, mu)`` as mpf at the current precision."""
    return ([mp.mpf(v) for v in EXAMPLE["p"]], [mp.mpf(v) for v in EXAMPLE["q"]],
            mp.mpf(EXAMPLE["lam0"]), mp.mpf(mu))


def _real_map(p: list[mp.mpf], q: list[mp.mpf], lam0: mp.mpf, mu: mp.mpf,
              branch: int) -> tuple[bool, dict[str, Any] | None]:
    try:
        pt, qt, info = literal_step(p, q, lam0, mu, branch)
    except (ZeroDivisionError, ValueError):
        return False, None
    if not all(isinstance(e, mp.mpf) and e > 0 for e in info["E_new"]):
        return False, info
    return True, info


def admissible_states(N: int, trace_sign: int, count: int, seed: int = 0, max_proposals: int = 20000
                      ) -> list[tuple[list[mp.mpf], list[mp.mpf], mp.mpf, mp.mpf]]:
    """``count`` tuples ``(p, q, lam0, mu)`` (lists of mpf) with sign(tr L(lambda_i)) = ``trace_sign``.

    The stream is ``random.Random(1000 N + 10 seed + (trace_sign > 0))`` (the two signs draw from different
    streams); each proposal draws ``p_j`` uniform on [-3, 3], then ``q_j`` on [-1.5, 1.5], ``lam0`` on [-5, 5] and
    ``mu`` on [0.05, 0.8], each rounded to 6 decimals, and the admissible proposals are kept in order (so a
    sample can be reproduced from this description, and ``count`` states are the first ``count`` of more).
    ``RuntimeError`` after ``max_proposals`` proposals without ``count`` admissible ones.

    >>> len(admissible_states(2, 1, 2))
    2
    """
    rng = random.Random(1000 * N + 10 * seed + (trace_sign > 0))
    out: list[tuple[list[mp.mpf], list[mp.mpf], mp.mpf, mp.mpf]] = []
    tries = 0
    with mp.workdps(max(mp.mp.dps, 30)):
        while len(out) < count:
            tries += 1
            if tries > max_proposals:
                raise RuntimeError(f"no admissible state found for N={N}, sign={trace_sign}")
            p = [f"{rng.uniform(-3, 3):.6f}" for _ in range(N)]
            q = [f"{rng.uniform(-1.5, 1.5):.6f}" for _ in range(N)]
            lam0 = f"{rng.uniform(-5, 5):.6f}"
            mu = f"{rng.uniform(0.05, 0.8):.6f}"
            state = ([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(lam0), mp.mpf(mu))
            ok1, info = _real_map(*state, 1)
            if not ok1:
                continue
            assert info is not None                   # a real map has its info
            t1, t2 = info["tr1"], info["tr2"]
            if not (isinstance(t1, mp.mpf) and isinstance(t2, mp.mpf)):
                continue
            if not (trace_sign * t1 > 2.2 and trace_sign * t2 > 2.2):
                continue
            if not _real_map(*state, -1)[0]:
                continue
            out.append((p, q, lam0, mu))
    return [([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m)) for p, q, l0, m in out]
