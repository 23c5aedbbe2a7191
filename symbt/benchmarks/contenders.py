"""The contenders of one case: float64 BT orbits and ODE integrators of the flow of ``sum c_k H_k``.

BT (float64): the documented call :func:`symbt.numeric.bt_orbit` (its own backend choice: the fused
kernel for one state); the fused kernel forced, ``bt_orbit(..., backend="numba")`` and
``backend="python"`` (both timed when numba is present; labelled ``BT fast_orbit (...)`` as in the recorded
results; a kernel run that falls back to the general path is labelled so); the emitted
closed-form step ``symbt.generated.toda{N}.bt_step`` iterated, and the emitted orbit helper
``toda{N}.bt_orbit`` (centre of mass carried) (N = 2, 3).
ODE (need scipy): ``solve_ivp`` DOP853 (and RK45, LSODA where the case asks), ``rtol = atol``;
3-stage Gauss--Legendre (order 6).  Vector field: the emitted ``toda{N}.flow_field`` with the
30-digit ``c_k`` (N = 2, 3: exact polynomials, the cheapest call) or
:class:`symbt.numeric.flow.field.FlowField` (any N).
"""
from __future__ import annotations

import importlib
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ..numeric import BackendName, bt_orbit
from ..numeric.float64.jit import kernel, numba_available
from ..numeric.flow.field import FlowField
from .cases import Case
from .integrators import gauss_legendre_orbit, scipy_orbit
from .timing import timed

__all__ = ["generated_module", "make_field", "run_bt", "run_ode"]


def generated_module(N: int) -> Any:
    """``symbt.generated.toda{N}`` or None."""
    try:
        return importlib.import_module("symbt.generated.toda%d" % N)
    except Exception:
        return None


def make_field(case: Case, c: np.ndarray) -> tuple[Callable, str, FlowField | None]:
    """``(f(p, q) -> (qdot, pdot), description, FlowField or None)``."""
    gen = generated_module(case.N)
    if gen is not None and hasattr(gen, "flow_field"):
        cf = np.asarray(c, float)
        return (lambda p, q: gen.flow_field(cf, p, q)), "symbt.generated.toda%d.flow_field" % case.N, None
    ff = FlowField(case.p, case.q, case.lam0, case.mu, branch=case.branch)
    return ff, "symbt.numeric.flow.field.FlowField (%d nodes)" % ff.m, ff


def _kernel_falls_back(case: Case, backend: str) -> bool:
    """Does one step of ``case`` leave the fused kernel (then the forced kernel runs the general path)?"""
    from ..numeric.float64.kernels import ANCHOR

    kern, _ = kernel("orbit", backend)
    P = np.empty((2, case.N))
    Q = np.empty((2, case.N))
    with np.errstate(all="ignore"):
        try:
            status = kern(np.array(case.p), np.array(case.q), case.lam0 + case.mu, case.lam0 - case.mu,
                          2.0 * case.mu, case.branch, 1, 1, ANCHOR, P, Q)
        except (ArithmeticError, ValueError):
            return True
    return status != 0


def run_bt(case: Case, rows: np.ndarray, every: int, record: Callable[..., None], setup: dict,
           quick: bool = False) -> None:
    """Time the float64 BT contenders; ``record(name, kind, P, Q, secs, reps, nfev=...)`` scores them."""
    p0, q0 = np.array(case.p), np.array(case.q)
    warm_n = max(1, case.n // 20)
    (P, Q), t, reps = timed(lambda: bt_orbit(p0, q0, case.lam0, case.mu, case.n, branch=case.branch),
                            lambda: bt_orbit(p0, q0, case.lam0, case.mu, warm_n, branch=case.branch), quick)
    record("BT bt_orbit (auto)", "bt", P[rows], Q[rows], t, reps, nfev=case.n)
    backends: list[BackendName] = ["numba", "python"] if numba_available() else ["python"]
    for be in backends:
        t0 = time.perf_counter()
        bt_orbit(p0, q0, case.lam0, case.mu, 1, branch=case.branch, backend=be)
        if be == "numba":
            setup["numba_first_call_s"] = time.perf_counter() - t0
        label = "BT fast_orbit (%s)" % be
        if _kernel_falls_back(case, be):
            label += " [falls back to bt_orbit]"
        (P, Q), t, reps = timed(lambda: bt_orbit(p0, q0, case.lam0, case.mu, case.n, branch=case.branch,
                                                   every=every, backend=be), None, quick)
        record(label, "bt", P, Q, t, reps, nfev=case.n)
    t0 = time.perf_counter()
    gen = generated_module(case.N)
    setup["generated_import_s"] = time.perf_counter() - t0
    if gen is None or not hasattr(gen, "bt_step"):
        return

    def run_gen(n: int = case.n) -> tuple:
        p, q = p0.copy(), q0.copy()
        Ps, Qs = [p], [q]
        for i in range(1, n + 1):
            p, q = gen.bt_step(p, q, case.lam0, case.mu, case.branch)
            if i % every == 0 or i == n:
                Ps.append(p)
                Qs.append(q)
        return np.array(Ps), np.array(Qs)

    (P, Q), t, reps = timed(run_gen, lambda: run_gen(warm_n), quick)
    ok = np.all(np.isfinite(P)) and np.all(np.isfinite(Q))
    record("BT generated toda%d.bt_step" % case.N, "bt", P if ok else None, Q, t, reps, nfev=case.n,
           msg="non-finite")
    if hasattr(gen, "bt_orbit"):
        # the emitted orbit helper carries the centre of mass like symbt.numeric.bt_orbit
        (P, Q), t, reps = timed(lambda: gen.bt_orbit(p0, q0, case.lam0, case.mu, case.n, case.branch),
                                lambda: gen.bt_orbit(p0, q0, case.lam0, case.mu, warm_n, case.branch), quick)
        record("BT generated toda%d.bt_orbit" % case.N, "bt", P[rows], Q[rows], t, reps, nfev=case.n)


def run_ode(case: Case, f: Callable, t_eval: np.ndarray, every: int, record: Callable[..., None],
            quick: bool = False) -> None:
    """scipy ``solve_ivp`` at the case's tolerances, then Gauss--Legendre at its step sizes."""
    p0, q0 = np.array(case.p), np.array(case.q)
    T = float(case.n)
    for method, tols in case.scipy.items():
        for tol in tols:
            early = t_eval[t_eval <= max(T / 50, t_eval[1])]
            res, t, reps = timed(lambda: scipy_orbit(method, f, p0, q0, T, t_eval, tol),
                                 lambda: scipy_orbit(method, f, p0, q0, early[-1], early, tol), quick)
            P, Q, nfev, msg = res
            record("scipy %s" % method, "ode", P, Q, t, reps, nfev=nfev, param=tol, msg=msg)
    for h in case.gl_steps:
        nsteps = int(round(T / h))
        per = int(round(every / h))
        res, t, reps = timed(lambda: gauss_legendre_orbit(f, p0, q0, h, nsteps, per),
                             lambda: gauss_legendre_orbit(f, p0, q0, h, max(1, nsteps // 50), per), quick)
        P, Q, nfev = res
        ok = np.all(np.isfinite(P)) and np.all(np.isfinite(Q))
        record("Gauss-Legendre s=3 (order 6)", "symplectic", P if ok else None, Q, t, reps, nfev=nfev,
               param=h, msg="diverged")
