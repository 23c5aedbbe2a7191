"""Throughput of the batched float64 step :func:`symbt.numeric.bt_step` (best of repeats).

N = 3 (the paper's example + 1e-2 noise, lam0 = 10, mu = 5) at batch sizes 1 .. 1e6, and the
cost per system-step versus N (batch 256, ``lam0 = 3N + 20``, ``mu = 2``) up to N = 1e4, with the
log-log slope of the time per system-step over N >= 128 (1 = linear).  Each row times the default
route (the compiled block kernel with numba) and, side by side, the numpy route (``backend="numpy"``):
large batches are memory-bound, so only the ratio within a row carries from one run to the next.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..numeric import bt_step
from ..paper import P_EXAMPLE, Q_EXAMPLE
from .timing import best_time

__all__ = ["run_throughput"]


def run_throughput(quick: bool = False, log: Callable[[str], None] = print) -> dict:
    """``{"batch": [...], "vsN": [...], "slope_time_vs_N": ...}`` (system-steps per second)."""
    rng = np.random.default_rng(0)
    P0, Q0 = np.array(P_EXAMPLE), np.array(Q_EXAMPLE)
    sizes = [1, 100, 10**4, 10**5] if quick else [1, 10, 100, 1000, 10**4, 10**5, 10**6]
    mt = 0.2 if quick else 0.5
    out: dict = {"batch": [], "vsN": []}
    log("  N = 3 batched bt_step (paper example + 1e-2 noise, lam0=10, mu=5)")
    for B in sizes:
        p = P0 + 1e-2 * rng.normal(size=(B, 3))
        q = Q0 + 1e-2 * rng.normal(size=(B, 3))
        t = best_time(lambda: bt_step(p, q, 10.0, 5.0), mt)
        tn = best_time(lambda: bt_step(p, q, 10.0, 5.0, backend="numpy"), mt)
        out["batch"].append({"batch": B, "time_s": t, "steps_per_s": B / t, "numpy_time_s": tn})
        log("    batch %8d: %.3e s/call, %.3e system-steps/s (numpy route %.3e s/call)" % (B, t, B / t, tn))
    Ns = [2, 3, 8, 32, 128, 1024] if quick else [2, 3, 8, 16, 64, 256, 1024, 4096, 10000]
    B = 256
    rng = np.random.default_rng(1)
    log("  cost vs N (fixed batch %d, lam0 = 3N + 20, mu = 2)" % B)
    for N in Ns:
        p = rng.normal(size=(B, N))
        q = 0.5 * rng.normal(size=(B, N))
        lam0 = 3.0 * N + 20.0
        t = best_time(lambda: bt_step(p, q, lam0, 2.0), mt)
        tn = best_time(lambda: bt_step(p, q, lam0, 2.0, backend="numpy"), mt)
        out["vsN"].append({"N": N, "batch": B, "steps_per_s": B / t, "ns_per_site_step": 1e9 * t / (B * N),
                           "numpy_ns_per_site_step": 1e9 * tn / (B * N)})
        log("    N %6d batch %7d: %.3e system-steps/s, %.2f ns per site-step (numpy route %.2f)"
            % (N, B, B / t, 1e9 * t / (B * N), 1e9 * tn / (B * N)))
    big = [r for r in out["vsN"] if r["N"] >= 128]
    if len(big) >= 2:
        x = np.log([r["N"] for r in big])
        y = np.log([1.0 / r["steps_per_s"] for r in big])
        out["slope_time_vs_N"] = float(np.polyfit(x, y, 1)[0])
        log("    log-log slope of time per system-step vs N (N >= 128): %.3f" % out["slope_time_vs_N"])
    return out


def main(argv: list[str] | None = None) -> None:
    """``python -m symbt.benchmarks.throughput [--quick]``: the throughput part of ``symbt bench`` on its own."""
    import argparse

    ap = argparse.ArgumentParser(prog="python -m symbt.benchmarks.throughput", description=main.__doc__)
    ap.add_argument("--quick", action="store_true", help="smaller sizes, shorter timing")
    run_throughput(quick=ap.parse_args(argv).quick)


if __name__ == "__main__":  # pragma: no cover
    main()
