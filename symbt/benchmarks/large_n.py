"""Large N far from the spectrum: the fused kernel (rescaled monodromy) against the general path, one run.

States past ``|tr L| ~ 1e150`` used to be handed from the kernel to the general numpy path
(:func:`symbt.numeric.float64.orbit.general_orbit`); the kernel now carries the monodromy with an exact
power-of-two scale and finishes them.  :func:`run_large_n` times both routes on the same states
side by side (the general path is what such a state cost before) and checks that they agree within
the documented bound (``tests/test_numeric_large_n.py``).  ``python -m symbt.benchmarks.large_n``.

>>> cases = large_n_cases()
>>> [(c[0], c[3]) for c in cases]
[(128, 100.0), (256, 10.0), (256, 100.0)]
"""
from __future__ import annotations

import json
import sys
import time

import mpmath
import numpy as np

from ..numeric import spectral_trace
from .cases import chain

__all__ = ["large_n_cases", "run_large_n"]


def large_n_cases() -> list:
    """``(N, p, q, lam0, mu)``: chains ``p ~ N(0, 1/4)``, ``q ~ N(0, 1/16)`` far above the spectrum."""
    out = []
    for N, lam0, mu in ((128, 100.0, 5.0), (256, 10.0, 1.0), (256, 100.0, 5.0)):
        p, q = chain(N, N, 0.5, 0.25)
        out.append((N, np.array(p), np.array(q), lam0, mu))
    return out


def _best(fn, reps: int = 3) -> float:
    best = np.inf
    for _ in range(reps):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def run_large_n(steps: int = 200) -> list:
    """Seconds per step of the kernel and of the general path on each case, and their difference."""
    from ..numeric.float64.jit import kernel
    from ..numeric.float64.kernels import ANCHOR
    from ..numeric.float64.orbit import general_orbit

    orbit, backend = kernel("orbit", "auto")
    rows = []
    for N, p, q, lam0, mu in large_n_cases():
        with mpmath.workdps(30):
            tr = spectral_trace(mpmath.mpf(lam0 + mu), [mpmath.mpf(float(x)) for x in p],
                                [mpmath.mpf(float(x)) for x in q])
        Pk, Qk = np.empty((2, N)), np.empty((2, N))

        def fast() -> None:
            st = orbit(p, q, lam0 + mu, lam0 - mu, 2 * mu, 1, steps, steps, ANCHOR, Pk, Qk)
            if st != 0:
                raise RuntimeError("kernel status %d" % st)

        Pg, Qg = np.empty((2, 1, N)), np.empty((2, 1, N))

        def general() -> None:
            st, _ = general_orbit(p[None], q[None], lam0, mu, 1, steps, steps, Pg, Qg, np.arange(1))
            if st[0] != 0:
                raise RuntimeError("general path status %d" % st[0])

        fast()
        tk = _best(fast) / steps
        tg = _best(general, 2) / steps
        scale = max(np.abs(Pk[1]).max(), np.abs(Qk[1] - Qk[1].mean()).max(), abs(lam0) + abs(mu))
        diff = max(np.abs(Pk[1] - Pg[1, 0]).max(), np.abs(Qk[1] - Qg[1, 0]).max()) / scale
        rows.append({"N": N, "lam0": lam0, "mu": mu, "log10_tr": float(mpmath.log10(abs(tr))), "steps": steps,
                     "kernel_s_per_step": tk, "general_s_per_step": tg, "ratio": tg / tk,
                     "relative_difference": float(diff), "backend": backend})
    return rows


def main() -> int:
    """Print the table as JSON lines."""
    steps = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    for r in run_large_n(steps):
        print(json.dumps(r))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
