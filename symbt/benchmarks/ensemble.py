"""Ensembles: M states of one torus advanced together (N = 3, M = 1e4; ``--quick``: M = 1e3).

Members: the first ``M`` float64 iterates of the paper's state under the map with
``(lam0, mu) = (10, 2)`` -- all on the paper's isospectral torus, so all share the ``c_k`` of
``(lam0, mu) = (10, 5)``.  symbt: the documented call ``bt_orbit(P, Q, 10, 5, n)`` on the (M, N)
arrays.  heyoka: a batch integrator (SIMD width) re-used over the ensemble in one thread, and
``ensemble_propagate_until_batch`` (its documented ensemble API, all cores); heyoka's tolerance
is the loosest of 1e-10 .. 1e-16 at which it reaches the BT's error on the scored members.
Errors: on ``members`` states (every ``M / members``-th), against the 50-digit BT (for those
members the heyoka field gets their own 30-digit ``c_k``; the cost does not depend on them).
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import mpmath
import numpy as np

from ..numeric import bt_orbit, flow_coefficients
from ..paper import LAM0_EXAMPLE, P_EXAMPLE, Q_EXAMPLE
from .metrics import mp_state_error
from .reference import reference_states
from .timing import timed

__all__ = ["ensemble_states", "run_ensemble"]


def ensemble_states(M: int) -> tuple[np.ndarray, np.ndarray]:
    """``M`` states of the paper's torus: the orbit of the paper's state under ``(10, 2)``."""
    P, Q = bt_orbit(np.array(P_EXAMPLE), np.array(Q_EXAMPLE), LAM0_EXAMPLE, 2.0, M - 1)
    return P, Q - Q.mean(-1, keepdims=True)


def _errors(members: list, P0: np.ndarray, Q0: np.ndarray, lam0: float, mu: float, n: int,
            Pn: np.ndarray, Qn: np.ndarray, refs: dict) -> float:
    worst = 0.0
    for m in members:
        if m not in refs:
            refs[m] = reference_states(list(P0[m]), list(Q0[m]), lam0, mu, n, 50)
        worst = max(worst, mp_state_error([float(v) for v in list(Pn[m]) + list(Qn[m])], refs[m]))
    return worst


def run_ensemble(quick: bool = False, log: Callable[[str], None] = print, hy: Any = None, M: int | None = None,
                 n: int | None = None, members: int = 16) -> dict:
    """The ensemble comparison (see module docstring); JSON-ready dict."""
    M = M or (1000 if quick else 10000)
    n = n or (20 if quick else 100)
    lam0, mu = LAM0_EXAMPLE, 5.0
    P0, Q0 = ensemble_states(M)
    picks = sorted(set(np.linspace(0, M - 1, members).astype(int).tolist()))
    refs: dict = {}
    out: dict = {"M": M, "N": 3, "steps": n, "T": n, "lam0": lam0, "mu": mu, "scored_members": len(picks)}
    (Pn, Qn), secs, reps = timed(lambda: bt_orbit(P0, Q0, lam0, mu, n), lambda: bt_orbit(P0, Q0, lam0, mu, 1),
                                 quick)
    bt_err = _errors(picks, P0, Q0, lam0, mu, n, Pn[-1], Qn[-1], refs)
    out["bt"] = {"method": "bt_orbit(P, Q, lam0, mu, n) on (M, N) arrays", "time_s": secs, "repeats": reps,
                 "max_err": bt_err}
    log("  bt_orbit on (%d, 3), %d steps: %.3e s, max err %.1e (%d scored members)" % (M, n, secs, bt_err,
                                                                                       len(picks)))
    if hy is None:
        out["heyoka_skipped"] = "heyoka not run (not installed, or --no-heyoka)"
        return out
    from .heyoka_peer import ensemble
    from .heyoka_system import parametric_system

    with mpmath.workdps(30):
        c_all = [float(v) for v in flow_coefficients([mpmath.mpf(v) for v in P_EXAMPLE],
                                                    [mpmath.mpf(v) for v in Q_EXAMPLE], lam0, mu)]
    sys = parametric_system(hy, 3)
    pars = np.tile(np.array(c_all)[:, None], (1, M))
    for m in picks:                      # the scored members: their own c_k
        with mpmath.workdps(30):
            pars[:, m] = [float(v) for v in flow_coefficients([mpmath.mpf(float(v)) for v in P0[m]],
                                                             [mpmath.mpf(float(v)) for v in Q0[m]], lam0, mu,
                                                             check=False)]
    tried = []
    chosen = 1e-16
    for tol in (1e-10, 1e-12, 1e-14, 1e-16):
        r = ensemble(hy, sys, P0, Q0, float(n), tol, quick, documented=False, pars=pars, only=picks)
        e = _errors(picks, P0, Q0, lam0, mu, n, r["Y"][:, 3:], r["Y"][:, :3], refs)
        tried.append({"tol": tol, "max_err": e})
        chosen = tol
        if e <= bt_err:
            break
    out["heyoka_tolerances_tried"] = tried
    r = ensemble(hy, sys, P0, Q0, float(n), chosen, quick, documented=True, pars=pars)
    Y = r.pop("Y")
    r["max_err"] = _errors(picks, P0, Q0, lam0, mu, n, Y[:, 3:], Y[:, :3], refs)
    out["heyoka"] = r
    best = min(r["loop"]["time_s"], r.get("ensemble_api", {}).get("time_s", np.inf))
    out["ratio"] = best / secs
    log("  heyoka tol %g (SIMD %d): batch loop %.3e s, ensemble_propagate_until_batch %.3e s, max err %.1e; "
        "best / BT = %.3gx" % (chosen, r["simd"], r["loop"]["time_s"], r.get("ensemble_api", {}).get("time_s", np.nan),
                               r["max_err"], out["ratio"]))
    return out
