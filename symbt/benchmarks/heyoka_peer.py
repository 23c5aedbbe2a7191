"""heyoka as a peer contender: float64 tolerance sweeps, ``heyoka.real`` at high precision, ensembles.

Same problem, same reference, same error metric as the other contenders.  JIT build times
(construction of each ``taylor_adaptive``: decomposition + LLVM compilation) are reported apart
from the propagation times.  Every function returns plain dicts (JSON-ready).
"""
from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import mpmath
import numpy as np

from ..numeric import flow_coefficients
from .heyoka_system import polynomial_system, real_prec, transfer_system
from .metrics import mp_state_error
from .timing import timed

__all__ = ["float_system", "sweep", "high_precision", "ensemble"]


def float_system(hy: Any, case: Any, c: np.ndarray, field: Any = None) -> tuple[list, str]:
    """The float64 system of a case: explicit polynomials (N <= 8) or the transfer-sweep field."""
    if case.N <= 8:
        return polynomial_system(hy, case.N, [float(v) for v in c]), "explicit H_k polynomials (exact c_k)"
    return transfer_system(hy, field), "FlowField transfer sweeps (%d nodes)" % field.m


def _build(hy: Any, sys: list, y0: list, **kw: Any) -> tuple[Any, float]:
    t0 = time.perf_counter()
    ta = hy.taylor_adaptive(sys, y0, **kw)
    return ta, time.perf_counter() - t0


def _grid_run(hy: Any, ta: Any, y0: np.ndarray, grid: np.ndarray) -> tuple:
    ta.time = 0.0
    ta.state[:] = y0
    out = ta.propagate_grid(grid)
    ok = out[0] == hy.taylor_outcome.time_limit
    return out[-1], int(out[3]), ok, str(out[0])


def sweep(hy: Any, case: Any, sys: list, t_grid: np.ndarray, tols: tuple, record: Callable[..., None],
          quick: bool = False, log: Callable[[str], None] = print) -> dict:
    """float64 ``taylor_adaptive`` at each tolerance; ``record`` gets the checkpoint states."""
    N = case.N
    y0 = np.concatenate([case.q, case.p]).astype(float)
    builds = {}
    for tol in tols:
        ta, tb = _build(hy, sys, list(y0), tol=tol, compact_mode=N > 8)
        builds["%g" % tol] = tb
        warm = t_grid[t_grid <= max(t_grid[-1] / 50, t_grid[1])]
        (Y, nsteps, ok, msg), secs, reps = timed(lambda: _grid_run(hy, ta, y0, t_grid),
                                                 lambda: _grid_run(hy, ta, y0, warm), quick)
        name = "heyoka taylor_adaptive (float64)"
        if not ok:
            record(name, "heyoka", None, None, secs, reps, param=tol, msg=msg)
            continue
        record(name, "heyoka", Y[:, N:], Y[:, :N], secs, reps, nfev=nsteps, param=tol,
               extra={"order": int(ta.order), "jit_s": tb})
    log("  heyoka JIT build times [s]: " + ", ".join("%s: %.2f" % kv for kv in builds.items()))
    return builds


def high_precision(hy: Any, p0: list, q0: list, lam0: Any, mu: Any, n: int, digits: int, bt_secs: float,
                   ref: list, quick: bool = False) -> dict:
    """heyoka.real at ``digits`` digits (tolerance ``10**-digits``, ``c_k`` at ``digits + 15`` digits)."""
    N = len(p0)
    prec = real_prec(digits)
    out: dict = {"digits": digits, "prec_bits": prec}
    with mpmath.workdps(digits + 15):
        t0 = time.perf_counter()
        c = flow_coefficients([mpmath.mpf(v) for v in p0], [mpmath.mpf(v) for v in q0], mpmath.mpf(lam0),
                              mpmath.mpf(mu), check=False)
        out["c_k_s"] = time.perf_counter() - t0

        def const(v: Any) -> Any:
            return hy.real(mpmath.nstr(mpmath.mpf(v), digits + 15), prec)

        sys = polynomial_system(hy, N, c, const)
        y0 = [const(v) for v in list(q0) + list(p0)]
    ta, tb = _build(hy, sys, y0, fp_type=hy.real, prec=prec, tol=hy.real("1e-%d" % digits, prec))
    out.update(jit_s=tb, order=int(ta.order))

    def run() -> list:
        ta.time = hy.real(0, prec)
        ta.state[:] = y0
        ta.propagate_until(hy.real(n, prec))
        return [str(v) for v in ta.state]

    st, secs, reps = timed(run, None, quick)
    with mpmath.workdps(2 * digits + 20):
        x = [mpmath.mpf(v) for v in st[N:]] + [mpmath.mpf(v) for v in st[:N]]
        out.update(time_s=secs, repeats=reps, err=mp_state_error(x, ref), ratio=secs / bt_secs)
    return out


def ensemble(hy: Any, sys: list, P: np.ndarray, Q: np.ndarray, T: float, tol: float, quick: bool = False,
             documented: bool = True, pars: np.ndarray | None = None, only: list | None = None) -> dict:
    """Propagate the ensemble ``(P, Q)`` (M, N) to time ``T`` with heyoka's batch integrator.

    A batch integrator of the SIMD width re-used in a loop over the ensemble (one thread, timed
    with repeats), and -- if ``documented`` -- ``ensemble_propagate_until_batch`` (all cores, one
    run).  ``pars``: runtime parameters, shape ``(npars, M)``.  ``only``: propagate just the
    batches holding these members (untimed scoring runs).  Returns timings and the final states
    ``Y`` (M, 2N) in ``(q, p)`` order (rows not propagated are NaN).
    """
    M, N = P.shape
    B = int(hy.recommended_simd_size())
    Y0 = np.concatenate([Q, P], axis=1)
    t0 = time.perf_counter()
    tb = hy.taylor_adaptive_batch(sys, np.ascontiguousarray(Y0[:B].T), tol=tol)
    out: dict = {"tol": tol, "simd": B, "jit_s": time.perf_counter() - t0}
    starts = list(range(0, M - B + 1, B))
    if M % B:
        starts.append(M - B)                           # the last batch overlaps the one before
    if only is not None:
        starts = sorted({min(m - m % B, M - B) for m in only})

    def load(ta: Any, i: int) -> Any:
        ta.set_time(0.0)
        ta.state[:] = Y0[i:i + B].T
        if pars is not None:
            ta.pars[:] = pars[:, i:i + B]
        return ta

    def loop() -> np.ndarray:
        Y = np.full_like(Y0, np.nan)
        for i in starts:
            load(tb, i).propagate_until(T)
            Y[i:i + B] = tb.state.T
        return Y

    if only is not None:
        out["Y"] = loop()
        return out
    Y, secs, reps = timed(loop, lambda: None, quick)
    out["loop"] = {"time_s": secs, "repeats": reps, "threads": 1, "batches": len(starts)}
    out["Y"] = Y
    if documented:
        t0 = time.perf_counter()
        hy.ensemble_propagate_until_batch(tb, T, len(starts), lambda ta, k: load(ta, starts[k]))
        out["ensemble_api"] = {"time_s": time.perf_counter() - t0, "repeats": 1,
                               "threads": "default (all cores)"}
    return out
