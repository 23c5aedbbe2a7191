"""Cost per step of the slope at site 1 rounded once (issue 26, item 6): the fused kernel against itself with
the slope computed as before (``k = dl +- g`` rounded, then divided), compiled and run interleaved in one
process, best of ``repeat`` per case.

``python -m symbt.benchmarks.drift_cost`` prints one line per case: the paper's example (N = 3), the
``n64-chain`` state at lam0 = 5.1, mu = 1.3 and the ``n256-chain`` state at lam0 = 8.3, mu = 0.3
(:func:`~symbt.benchmarks.drift.drift_case`); BENCHMARKS.md, "Drift at the round-off limit".

>>> k_rounded(-1760.7, -260.5, -1500.2, 2020.2, 3.5, 2.0, 2.0, False, True) == (-1500.2 - 2020.2) / 7.0
True
"""
from __future__ import annotations

import argparse
from functools import partial
from typing import Any

import numpy as np

from .timing import interleaved_best

__all__ = ["k_rounded", "compare", "step_accuracy", "main"]


def k_rounded(A: float, D: float, dl: float, g: float, B: float, C: float, two: float, plus: bool,
              wantk: bool) -> float:
    """The slope at site 1 as the kernels computed it before :func:`~symbt.numeric.core.spectral_sum.root_slope`:
    ``k = dl +- g`` rounded, then ``k / (2 B)`` or ``-2 C / k``."""
    k = dl + g if plus else dl - g
    return k / (2.0 * B) if wantk else (-2.0 * C) / k


def compare(N: int, n: int, repeat: int = 5) -> dict[str, Any]:
    """Best-of-``repeat`` seconds per step of the shipped kernel (``after``) and of the same kernel with
    :func:`k_rounded` (``before``), runs interleaved; and whether the two orbits are bit-identical."""
    from ..numeric.float64.jit import kernel, orbit_with
    from ..numeric.float64.kernels import ANCHOR, orbit_rows
    from .drift import drift_case

    p, q, lam0, mu = drift_case(N)
    if N == 64:
        lam0, mu = 5.1, 1.3
    fns = {"after": kernel("orbit", "numba")[0], "before": orbit_with({"root_slope": k_rounded})}
    out: dict[str, Any] = {}

    def run(name: str) -> None:
        P, Q = np.empty((orbit_rows(n, n), N)), np.empty((orbit_rows(n, n), N))
        st = fns[name](p, q, lam0 + mu, lam0 - mu, 2.0 * mu, 1, n, n, ANCHOR, P, Q)
        if st != 0:
            raise RuntimeError("kernel status %d" % st)
        out[name + "_state"] = (P[-1].copy(), Q[-1].copy())

    best = {k: t / n for k, t in interleaved_best({k: partial(run, k) for k in fns}, repeat).items()}
    out.update(N=N, n=n, lam0=lam0, mu=mu, before=best["before"], after=best["after"],
               ratio=best["after"] / best["before"])
    return out


def step_accuracy(N: int, lam0: float, mu: float, states: int, seed: int = 0) -> dict[str, Any]:
    """One step of the case's state and ``states - 1`` states perturbed by 1e-3, before and after, against the
    50-digit literal step (:func:`~symbt.reference.literal.reference_step`): max error over p and q in ulps
    of ``max(||x||_inf, |lam0| + |mu|)``; returns ``{"before": (mean, max), "after": (mean, max)}``."""
    import mpmath

    from ..numeric.float64.jit import kernel, orbit_with
    from ..numeric.float64.kernels import ANCHOR
    from ..reference.literal import reference_step
    from .drift import drift_case

    p0, q0, _, _ = drift_case(N)
    rng = np.random.default_rng(seed)
    fns = {"after": kernel("orbit", "numba")[0], "before": orbit_with({"root_slope": k_rounded})}
    errs: dict[str, list[float]] = {k: [] for k in fns}
    for i in range(states):
        p = p0 + (1e-3 * rng.normal(size=N) if i else 0.0)
        q = q0 + (1e-3 * rng.normal(size=N) if i else 0.0)
        with mpmath.workdps(50):
            pr, qr = reference_step([mpmath.mpf(float(x)) for x in p], [mpmath.mpf(float(x)) for x in q],
                                    mpmath.mpf(lam0), mpmath.mpf(mu))
        for name, fn in fns.items():
            P, Q = np.empty((2, N)), np.empty((2, N))
            if fn(p, q, lam0 + mu, lam0 - mu, 2.0 * mu, 1, 1, 1, ANCHOR, P, Q) != 0:
                raise RuntimeError("kernel refused the step")
            scale = max(np.abs(np.concatenate([p, q, P[1], Q[1]])).max(), abs(lam0) + abs(mu))
            with mpmath.workdps(50):
                e = max(float(abs(mpmath.mpf(float(a)) - b)) for a, b in zip(list(P[1]) + list(Q[1]), pr + qr))
            errs[name].append(e / np.spacing(scale))
    return {k: (float(np.mean(v)), float(np.max(v))) for k, v in errs.items()}


def main(argv: list | None = None) -> int:
    """Command line: one line per case."""
    ap = argparse.ArgumentParser(prog="python -m symbt.benchmarks.drift_cost", description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--accuracy", action="store_true", help="the per-step accuracy table instead of the cost")
    a = ap.parse_args(argv)
    if a.accuracy:
        for N, lam0, mu, m in ((3, 10.0, 5.0, 12), (3, 10.1, 5.3, 12), (3, 10.3, 1e-6, 12), (3, 10.3, 3e-10, 12),
                               (64, 5.1, 1.3, 4), (256, 8.3, 0.3, 2)):
            r = step_accuracy(N, lam0, mu, m)
            print("N=%d lam0 %g mu %g, %d states: ulps mean/max before %.2f / %.2f, after %.2f / %.2f" % (
                N, lam0, mu, m, *r["before"], *r["after"]), flush=True)
        return 0
    for N, n in ((3, 10**5), (64, 2 * 10**4), (256, 4 * 10**3)):
        r = compare(N, n, a.repeat)
        print("N=%d (lam0 %g, mu %g, %d steps): before %.3g us/step, after %.3g us/step, after/before %.2f" % (
            N, r["lam0"], r["mu"], n, 1e6 * r["before"], 1e6 * r["after"], r["ratio"]), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
