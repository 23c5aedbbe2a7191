"""One case end to end: reference, contenders, heyoka, scores and the headline ratios.

Headline (per case): ``time(cheapest contender whose final error <= the BT's) / time(BT)``,
measured in the same run, for "BT" = the fused kernel and = the documented ``bt_orbit``; if no
contender reaches the BT's error, the ratio against the most accurate one is given with its
error.  The same is computed against heyoka alone (``vs_heyoka``).
"""
from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np

from .cases import Case
from .contenders import make_field, run_bt, run_ode
from .metrics import InvariantMeter, state_errors
from .reference import flow_constants, reference_orbit

__all__ = ["run_case", "headline", "compare"]


def run_case(case: Case, quick: bool = False, log: Callable[[str], None] = print, hy: Any = None,
             scipy_ok: bool = True) -> dict:
    """Run every contender on ``case``; returns the JSON-ready record of the case."""
    every = max(1, case.n // 100)
    out: dict = {"case": case.name, "note": case.note, "N": case.N, "p0": list(case.p), "q0": list(case.q),
                 "lam0": case.lam0, "mu": case.mu, "branch": case.branch, "steps": case.n, "T": case.n,
                 "checkpoint_every": every, "runs": [], "setup": {}}
    t0 = time.perf_counter()
    rows, hi, lo = reference_orbit(case, 50, every)
    out["setup"]["reference_mp50_orbit_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    c = flow_constants(case)
    out["setup"]["c_k_30digits_s" if case.N <= 8 else "c_k_float64_s"] = time.perf_counter() - t0
    out["c"] = c.tolist()
    inv = InvariantMeter(case)

    def record(name: str, kind: str, P: Any, Q: Any, secs: float, reps: int, nfev: Any = None,
               param: Any = None, msg: Any = None, extra: dict | None = None) -> None:
        if P is None:
            out["runs"].append({"method": name, "kind": kind, "param": param, "failed": str(msg)})
            log("  %-44s %-8s failed: %s" % (name, "" if param is None else "%g" % param, msg))
            return
        e = state_errors(np.asarray(P), np.asarray(Q), hi, lo)
        r = {"method": name, "kind": kind, "param": param, "final_err": float(e[-1]),
             "max_err": float(np.max(e)), "inv_drift": inv.drift(P, Q), "time_s": secs, "repeats": reps,
             "nfev": nfev, **(extra or {})}
        out["runs"].append(r)
        log("  %-44s %-8s final %.2e  max %.2e  drift %.1e  %.3e s  nfev %s" % (
            name, "" if param is None else "%g" % param, r["final_err"], r["max_err"], r["inv_drift"], secs, nfev))

    run_bt(case, rows, every, record, out["setup"], quick)
    t_eval = rows.astype(float)
    field = None
    if scipy_ok or hy is not None:
        t0 = time.perf_counter()
        f, fdesc, field = make_field(case, c)
        out["setup"]["field_setup_s"] = time.perf_counter() - t0
        out["field"] = fdesc
        if field is not None:
            out["field_c_check"] = float(np.max(np.abs(field.c - c) / np.abs(c)))
    if scipy_ok:
        run_ode(case, f, t_eval, every, record, quick)
    else:
        log("  scipy not installed: DOP853/RK45/LSODA and Gauss-Legendre rows skipped (pip install scipy)")
    if hy is not None and case.heyoka_tols:
        from .heyoka_peer import float_system, sweep
        if field is None and case.N > 8:
            from ..numeric.flow.field import FlowField
            field = FlowField(case.p, case.q, case.lam0, case.mu, branch=case.branch)
        sys, desc = float_system(hy, case, c, field)
        out["heyoka_system"] = desc
        out["setup"]["heyoka_jit_s"] = sweep(hy, case, sys, t_eval, case.heyoka_tols, record, quick, log)
    elif case.heyoka_tols:
        out["heyoka_skipped"] = "heyoka not run (not installed, or --no-heyoka)"
    out["headline"] = headline(out)
    log("  headline: %s" % out["headline"]["text"])
    return out


def compare(bt: dict, others: list[dict]) -> dict:
    """Cheapest of ``others`` reaching ``bt``'s final error (or the most accurate one), and the ratio."""
    reach = [r for r in others if r["final_err"] <= bt["final_err"]]
    best = min(reach, key=lambda r: r["time_s"]) if reach else min(others, key=lambda r: (r["final_err"], r["time_s"]))
    return {"reached": bool(reach), "contender": best["method"], "param": best["param"],
            "contender_time_s": best["time_s"], "contender_final_err": best["final_err"],
            "bt": bt["method"], "bt_time_s": bt["time_s"], "bt_final_err": bt["final_err"],
            "ratio": best["time_s"] / bt["time_s"]}


def _text(cmp: dict) -> str:
    if cmp["reached"]:
        return "%s (%g) reaches the BT's final error %.1e in %.3g s: %.3gx %s (%.3g s)" % (
            cmp["contender"], cmp["param"], cmp["bt_final_err"], cmp["contender_time_s"], cmp["ratio"], cmp["bt"],
            cmp["bt_time_s"])
    return ("no contender reaches the BT's final error %.1e; the most accurate, %s (%g), has %.1e and takes "
            "%.3g s = %.3gx %s (%.3g s)" % (cmp["bt_final_err"], cmp["contender"], cmp["param"],
                                           cmp["contender_final_err"], cmp["contender_time_s"], cmp["ratio"],
                                           cmp["bt"], cmp["bt_time_s"]))


def headline(out: dict) -> dict:
    """Ratios against the fused kernel and against ``bt_orbit``; all contenders and heyoka alone."""
    runs = [r for r in out["runs"] if "final_err" in r]
    bts = {r["method"]: r for r in runs if r["kind"] == "bt"}
    kernel = next((r for m, r in bts.items() if m.startswith("BT fast_orbit (numba)")), None) or \
        next((r for m, r in bts.items() if m.startswith("BT fast_orbit")), None)
    lib = bts.get("BT bt_orbit (auto)")
    others = [r for r in runs if r["kind"] != "bt"]
    hys = [r for r in runs if r["kind"] == "heyoka"]
    res: dict = {}
    if not others:
        res["text"] = "BT contenders only (no ODE contender ran)"
        return res
    for key, bt in (("kernel", kernel), ("bt_orbit", lib)):
        if bt is None:
            continue
        res[key] = compare(bt, others)
        if hys:
            res[key + "_vs_heyoka"] = compare(bt, hys)
    res["text"] = _text(res["kernel"])
    if "bt_orbit" in res:
        res["text"] += "; vs bt_orbit: %.3gx" % res["bt_orbit"]["ratio"]
    return res
