"""Throughput of the batched float64 Bäcklund step (symbt.numeric.bt_step).

Usage:  PYTHONPATH=. python benchmarks/bench_step.py [--quick]

Prints system-steps per second (one system-step = one state of N sites advanced by one step) for
N = 3 at batch sizes 1 .. 1e6, and the cost per system-step versus N up to 1e4.  This is the
throughput part of ``symbt bench`` (``symbt.benchmarks.run_throughput``) run on its own.
"""

from __future__ import annotations

import argparse

from symbt.benchmarks import run_throughput


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="smaller sizes, shorter timing")
    args = ap.parse_args()
    run_throughput(quick=args.quick)


if __name__ == "__main__":
    main()
