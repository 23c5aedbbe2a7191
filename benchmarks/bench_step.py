"""Throughput of the batched float64 Bäcklund step (symbt.numeric.bt_step).

Usage:  PYTHONPATH=. python benchmarks/bench_step.py [--quick]

Prints system-steps per second (one system-step = one state of N sites
advanced by one step) for N = 3 at batch sizes 1 .. 1e6, and the cost per
system-step versus N at a large batch.  Single process; numpy is used
single-threaded for elementwise work anyway.  The batch is processed in
blocks of ``symbt.numeric.step.BLOCK_ELEMENTS`` (rows x N) so temporaries
stay in cache.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from symbt.numeric import bt_step

P0 = np.array([-20.0, 10.0, 1.0])
Q0 = np.array([1.0, 0.0, 0.9])


def _timeit(fn, min_time=0.5, repeats=5):
    """Best (minimum) mean time per call over ``repeats`` runs of >= min_time/repeats s.

    The minimum is the usual estimator on a shared machine (other load only
    ever adds time).
    """
    fn()  # warm up
    best = float("inf")
    for _ in range(repeats):
        reps, t0 = 0, time.perf_counter()
        while True:
            fn()
            reps += 1
            dt = time.perf_counter() - t0
            if dt >= min_time / repeats:
                break
        best = min(best, dt / reps)
    return best


def bench_batch(sizes, min_time):
    rng = np.random.default_rng(0)
    print("N = 3, paper example (+1e-2 noise), lam0 = 10, mu = 5, branch = +1")
    print("%10s %14s %16s" % ("batch", "time/call [s]", "system-steps/s"))
    for B in sizes:
        p = P0 + 1e-2 * rng.normal(size=(B, 3))
        q = Q0 + 1e-2 * rng.normal(size=(B, 3))
        t = _timeit(lambda: bt_step(p, q, 10.0, 5.0), min_time)
        print("%10d %14.3e %16.3e" % (B, t, B / t))


def bench_N(Ns, total, min_time):
    rng = np.random.default_rng(1)
    print("\ncost vs N (batch = %d / N states, lam0 +- mu beyond the spectrum)" % total)
    print("%6s %8s %16s %18s" % ("N", "batch", "system-steps/s", "ns per site-step"))
    for N in Ns:
        B = max(1, total // N)
        p = rng.normal(size=(B, N))
        q = 0.5 * rng.normal(size=(B, N))
        lam0, mu = 3.0 * N + 20.0, 2.0
        t = _timeit(lambda: bt_step(p, q, lam0, mu), min_time)
        print("%6d %8d %16.3e %18.2f" % (N, B, B / t, 1e9 * t / (B * N)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="smaller sizes, shorter timing")
    args = ap.parse_args()
    if args.quick:
        bench_batch([1, 100, 10**4, 10**5], 0.2)
        bench_N([2, 3, 8, 32], 10**5, 0.2)
    else:
        bench_batch([1, 10, 100, 1000, 10**4, 10**5, 10**6], 1.0)
        bench_N([2, 3, 5, 8, 16, 32, 64, 128], 3 * 10**6, 1.0)


if __name__ == "__main__":
    main()
