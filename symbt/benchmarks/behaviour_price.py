"""What the float64 kernels' documented behaviour changes cost (``python -m symbt.benchmarks.behaviour_price``).

Issue 22's A/B table (BENCHMARKS.md, "Before and after the numeric redesign") compares with trees that
lack the conditioning guard (status ``ILLCOND``: the cheap and the sharp condition estimate) and the
drift repair (``lam_split``/``lam_add``'s two-sum, :mod:`symbt.numeric.core.spectral_sum`).  This
measures their share directly, in one process: the single-state orbit of each quick benchmark case
with those hooks replaced by no-ops -- ``decided``/``trusted`` always true (no guard), ``lam_add``
as ``lam + p`` and ``lam_split`` zero (no two-sum) -- plain Python (:func:`~symbt.numeric.float64.
kernels.python_orbit_with`) and numba (:func:`~symbt.numeric.float64.jit.orbit_with`, when
installed).  The variants are measuring devices, not results: without the guard a state is decided
that the shipped kernels refuse.  Each time is the best process time over ``--rounds`` interleaved
calls (numba: per call, over batches of 50).

>>> sorted(variants())
['as is', 'neither', 'no guard', 'no two-sum']
"""
from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from .timing import interleaved_best

__all__ = ["variants", "measure", "main"]


def _decided_off(aux: Any, t: float, disc: float, tt: Any, i: int, p: Any, r: Any, lam: float, lo: float) -> bool:
    tt[i + 2] = 1.0
    return True


def _trusted_off(kt: float, u: float, w: float, dn: float, x: float) -> bool:
    return True


def _lam_add_plain(lam: float, lo: float, p: float) -> float:
    return lam + p


def _lam_split_off(lam1: float, lam2: float, two_mu: float) -> tuple[float, float]:
    return 0.0, 0.0


def variants() -> dict[str, dict[str, Callable[..., Any]]]:
    """Variant name -> the hooks of :data:`~symbt.numeric.float64.kernels.HOOKS` it replaces."""
    guard: dict[str, Callable[..., Any]] = {"decided": _decided_off, "trusted": _trusted_off}
    two_sum: dict[str, Callable[..., Any]] = {"lam_add": _lam_add_plain, "lam_split": _lam_split_off}
    return {"as is": {}, "no guard": guard, "no two-sum": two_sum, "neither": {**guard, **two_sum}}


def measure(backend: str, rounds: int = 5) -> dict[str, dict[str, float]]:
    """Case -> variant -> best seconds per orbit (``backend``: ``"python"`` or ``"numba"``)."""
    from ..numeric.float64 import kernels as K
    from .cases import cases

    if backend == "numba":
        from ..numeric.float64.jit import orbit_with

        fns = {name: orbit_with(hooks=h) for name, h in variants().items()}
    else:
        fns = {name: K.python_orbit_with(h) for name, h in variants().items()}
    reps = 50 if backend == "numba" else 1
    out: dict[str, dict[str, float]] = {}
    for c in cases(quick=True):
        every = max(1, c.n // 100)
        args = (np.array(c.p), np.array(c.q), c.lam0 + c.mu, c.lam0 - c.mu, 2 * c.mu, c.branch, c.n, every, K.ANCHOR)
        rows = (K.orbit_rows(c.n, every), len(c.p))

        def run(fn: Callable[..., int], name: str, case: str = c.name) -> None:
            status = fn(*args, np.empty(rows), np.empty(rows))
            if status != 0:
                raise RuntimeError(f"{case} {name}: status {status}")

        out[c.name] = interleaved_best({name: partial(run, fn, name) for name, fn in fns.items()}, rounds, reps,
                                       clock=time.process_time)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m symbt.benchmarks.behaviour_price",
                                 description=__doc__.split("\n")[0] if __doc__ else None)
    ap.add_argument("--rounds", type=int, default=5, help="interleaved calls per variant (default 5)")
    args = ap.parse_args(argv)
    if args.rounds < 1:
        ap.error("--rounds must be >= 1")
    from ..numeric.core.compile import numba_available

    for backend in ("python", "numba"):
        if backend == "numba" and not numba_available():
            print("numba: not installed, skipped", file=sys.stderr)
            continue
        for case, times in measure(backend, args.rounds).items():
            print(f"{backend:6} {case:13} " + "  ".join(f"{k}: {v * 1e3:.3f} ms" for k, v in times.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
