"""The benchmark problems: a state, a map ``(lam0, mu, branch)`` and a number of steps.

* ``paper-mu5``, ``paper-mu2`` -- the paper's N=3 example (``p = (-20, 10, 1)``, ``q = (1, 0, 0.9)``,
  ``lam0 = 10``), 3500 steps (300 with ``--quick``);
* ``n2-inner-gap`` -- N=2 in the bounded gap (``tr < -2`` on the interval);
* ``n64-chain`` -- N=64, ``p ~ N(0, 1)``, ``q ~ N(0, 1/4)`` (seed 64, 6 decimals), ``[3.5, 6.5]``
  above the spectrum (top band edge ~2.98);
* ``n256-chain`` -- N=256, ``p ~ N(0, 1/4)``, ``q ~ N(0, 1/16)`` (seed 256), ``[3.1, 3.7]`` above the
  spectrum (top band edge ~2.78; there ``|tr L| < 1e154``, inside the range of the fused kernel).

>>> [c.name for c in cases(quick=True)]
['paper-mu5', 'paper-mu2', 'n2-inner-gap', 'n64-chain', 'n256-chain']
>>> cases()[3].N, cases()[3].n
(64, 20)
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..paper import P_EXAMPLE, Q_EXAMPLE

__all__ = ["Case", "cases", "chain", "select"]


@dataclass(frozen=True)
class Case:
    """One benchmark problem; ``n`` steps of the map = the flow of ``sum c_k H_k`` up to ``T = n``."""

    name: str
    p: tuple
    q: tuple
    lam0: float
    mu: float
    n: int
    branch: int = 1
    note: str = ""
    #: ODE settings: scipy methods and tolerances, Gauss-Legendre step sizes, heyoka tolerances
    scipy: dict = field(default_factory=dict)
    gl_steps: tuple = ()
    heyoka_tols: tuple = ()

    @property
    def N(self) -> int:
        return len(self.p)


def chain(N: int, seed: int, sp: float = 1.0, sq: float = 0.5) -> tuple[tuple, tuple]:
    """A random chain: ``p ~ N(0, sp^2)``, ``q ~ N(0, sq^2)`` rounded to 6 decimals."""
    rng = np.random.default_rng(seed)
    p = tuple(float(v) for v in np.round(sp * rng.normal(size=N), 6))
    q = tuple(float(v) for v in np.round(sq * rng.normal(size=N), 6))
    return p, q


HEYOKA_TOLS = tuple(10.0 ** -k for k in range(6, 17))          # 1e-6 ... 1e-16, every decade


def cases(quick: bool = False) -> list[Case]:
    """The benchmark cases; ``quick`` shortens the horizons and thins the tolerance sweeps."""
    n3 = 300 if quick else 3500
    dop = (1e-4, 1e-8, 1e-12) if quick else (1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-13, 1e-14)
    others = {} if quick else {"RK45": (1e-5, 1e-8, 1e-11), "LSODA": (1e-5, 1e-8, 1e-11)}
    hy3 = (1e-8, 1e-12, 1e-16) if quick else HEYOKA_TOLS
    p64, q64 = chain(64, 64)
    p256, q256 = chain(256, 256, 0.5, 0.25)
    return [
        Case("paper-mu5", P_EXAMPLE, Q_EXAMPLE, 10.0, 5.0, n3, note="paper's N=3 example, mu=5",
             scipy={"DOP853": dop, **others}, gl_steps=(0.25,) if quick else (0.25, 0.125), heyoka_tols=hy3),
        Case("paper-mu2", P_EXAMPLE, Q_EXAMPLE, 10.0, 2.0, n3, note="paper's N=3 example, mu=2",
             scipy={"DOP853": dop}, heyoka_tols=hy3),
        Case("n2-inner-gap", (3.0, -1.0), (0.4, -0.3), -1.0, 1.5, 100 if quick else 1000,
             note="N=2, bounded gap (tr < -2 on [lam0-mu, lam0+mu])", scipy={"DOP853": dop}, heyoka_tols=hy3),
        Case("n64-chain", p64, q64, 5.0, 1.5, 5 if quick else 20,
             note="N=64, p~N(0,1), q~N(0,1/4) (seed 64, 6 decimals); [3.5, 6.5] lies above the spectrum "
                  "(top band edge ~2.98)",
             scipy={"DOP853": (1e-8,) if quick else (1e-6, 1e-9, 1e-12, 1e-14)},
             heyoka_tols=(1e-12,) if quick else (1e-9, 1e-13, 1e-16)),
        Case("n256-chain", p256, q256, 3.4, 0.3, 2 if quick else 10,
             note="N=256, p~N(0,1/4), q~N(0,1/16) (seed 256, 6 decimals); [3.1, 3.7] lies above the spectrum "
                  "(top band edge ~2.78)",
             scipy={"DOP853": (1e-8,) if quick else (1e-6, 1e-10, 1e-13)},
             heyoka_tols=() if quick else (1e-10, 1e-15)),
    ]


def select(all_cases: list[Case], names: str | None) -> list[Case]:
    """The cases named in a comma-separated list (all if ``names`` is empty); unknown names raise."""
    if not names:
        return all_cases
    want = [s.strip() for s in names.split(",") if s.strip()]
    known = {c.name: c for c in all_cases}
    bad = [w for w in want if w not in known]
    if bad:
        raise ValueError("unknown case(s) %s; known: %s" % (", ".join(bad), ", ".join(known)))
    return [known[w] for w in want]
