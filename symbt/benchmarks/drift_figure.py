"""Invariant drift of long float64 Bäcklund orbits: random walk, not linear growth.

Usage:  python -m symbt.benchmarks.drift_figure [--n 100000] [--members 16]
        [--out docs/figures/invariant_drift.png]

16 orbits of the paper's example (lam0 = 10, mu = 5; member 0 is the paper's
state, the others are perturbed by 1e-9) are advanced with the batched
``bt_step``; at 40 log-spaced steps the invariants of the float64 states are
evaluated at 40 digits.  Plots the RMS (over orbits and k) and the maximum of
the relative drift ``|H_k(x_n) - H_k(x_0)| / |H_k(x_0)|`` against n, with the
fitted log-log slope and reference lines ``eps sqrt(n)`` and ``eps n``.
(The same measurement, with 8 orbits, is asserted in tests/test_stress.py.)
"""

from __future__ import annotations

import argparse
import json

import numpy as np

from .drift import invariant_drift_curve


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=10**5)
    ap.add_argument("--members", type=int, default=16)
    ap.add_argument("--out", default="docs/figures/invariant_drift.png")
    args = ap.parse_args()
    steps, drift, rms, slope = invariant_drift_curve(n=args.n, members=args.members, npoints=40)
    worst = drift.max(axis=(1, 2))
    print(json.dumps({"n": args.n, "members": args.members, "slope_rms": slope,
                      "rms_final": float(rms[-1]), "max_final": float(worst[-1]),
                      "paper_orbit_final": drift[-1, 0].tolist()}))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    eps = 2.0**-53
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.loglog(steps, rms, "o-", ms=3, label="RMS over %d orbits and k (slope %.2f)" % (args.members, slope))
    ax.loglog(steps, worst, "s", ms=3, color="C1", label="max over orbits and k")
    ax.loglog(steps, drift[:, 0, :].max(axis=1), "-", lw=0.8, color="C2", label="paper's orbit (max over k)")
    ax.loglog(steps, eps * np.sqrt(steps), "k--", lw=0.8, label="eps sqrt(n)")
    ax.loglog(steps, eps * steps, "k:", lw=0.8, label="eps n")
    ax.axhline(1e-12, color="r", lw=0.6)
    ax.set_xlabel("steps n")
    ax.set_ylabel("|H_k(x_n) - H_k(x_0)| / |H_k(x_0)|")
    ax.set_title("float64 BT orbits, paper's example (lam0=10, mu=5)", fontsize=10)
    ax.legend(fontsize=7)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
