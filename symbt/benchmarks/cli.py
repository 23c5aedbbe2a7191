"""``symbt bench``: the command line (``main(argv)``); one call writes bench.json, bench.md and the figure.

Usage::

    symbt bench [--quick] [--out DIR] [--figure PNG] [--cases a,b] [--skip ...] [--resume]

Without scipy the scipy/Gauss--Legendre rows are skipped, without heyoka the heyoka rows, each
with a message; without matplotlib no figure is drawn.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time

from .._files import atomic_write
from .cases import cases, select
from .timing import machine_info

__all__ = ["main"]

PARTS = ("cases", "precision", "ensemble", "throughput", "band-edge")


def _have(module: str) -> bool:
    try:
        __import__(module)
    except Exception:
        return False
    return True


def _save(path: str, results: dict) -> None:
    atomic_write(path, json.dumps(results, indent=1, default=float))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="symbt bench", description="Work-precision benchmarks of the Bäcklund map "
                                 "as an exact integrator, against scipy and heyoka (see BENCHMARKS.md).")
    ap.add_argument("--quick", action="store_true", help="short horizons, thin sweeps (a few minutes)")
    ap.add_argument("--out", default="bench-results", metavar="DIR",
                    help="directory for bench.json, bench.md, work_precision.png (default bench-results)")
    ap.add_argument("--figure", metavar="PNG", help="also write the work-precision figure here")
    ap.add_argument("--cases", help="comma-separated case names (default: all); e.g. paper-mu5,n64-chain")
    ap.add_argument("--skip", default="", help="comma-separated parts to skip: " + ", ".join(PARTS))
    ap.add_argument("--no-heyoka", action="store_true", help="leave heyoka out even if installed")
    ap.add_argument("--resume", action="store_true", help="keep cases already in DIR/bench.json")
    args = ap.parse_args(argv)
    skip = {s.strip() for s in args.skip.split(",") if s.strip()}
    if skip - set(PARTS):
        ap.error("unknown part(s) in --skip: %s" % ", ".join(sorted(skip - set(PARTS))))
    try:
        todo = select(cases(args.quick), args.cases)
    except ValueError as exc:
        ap.error(str(exc))
    t_start = time.perf_counter()
    os.makedirs(args.out, exist_ok=True)

    def log(msg: str) -> None:
        print(msg, flush=True)

    hy = None
    if not args.no_heyoka:
        from .heyoka_system import load
        hy, msg = load()
        if hy is None:
            log("symbt bench: %s -- the heyoka rows are skipped" % msg)
    scipy_ok = _have("scipy")
    if not scipy_ok:
        log("symbt bench: scipy not installed (pip install 'symbt[scipy]') -- DOP853/RK45/LSODA and "
            "Gauss-Legendre rows are skipped")
    results: dict = {"machine": machine_info(), "quick": args.quick, "date": time.strftime("%Y-%m-%d"),
                     "command": "symbt bench " + " ".join(argv if argv is not None else sys.argv[2:]),
                     "cases": []}
    log("symbt bench%s: %s" % (" --quick" if args.quick else "", json.dumps(results["machine"])))
    json_path = os.path.join(args.out, "bench.json")
    done: dict = {}
    if args.resume and os.path.exists(json_path):
        with open(json_path) as fh:
            done = {c["case"]: c for c in json.load(fh).get("cases", [])}
    if "cases" not in skip:
        from .runner import run_case
        for case in todo:
            if case.name in done:
                log("\n== %s: kept from the previous run (--resume)" % case.name)
                results["cases"].append(done[case.name])
                continue
            log("\n== %s: %s (N=%d, %d steps)" % (case.name, case.note, case.N, case.n))
            results["cases"].append(run_case(case, args.quick, log, hy, scipy_ok))
            _save(json_path, results)
    if "precision" not in skip:
        from .precision import run_precision
        log("\n== high precision: mpmath BT vs heyoka.real and Taylor integration")
        results["precision"] = run_precision(args.quick, log, hy)
    if "ensemble" not in skip:
        from .ensemble import run_ensemble
        log("\n== ensemble: bt_orbit on (M, N) arrays vs heyoka batch mode")
        results["ensemble"] = run_ensemble(args.quick, log, hy)
    if "throughput" not in skip:
        from .throughput import run_throughput
        log("\n== throughput of the batched float64 step")
        results["throughput"] = run_throughput(args.quick, log)
    if "band-edge" not in skip and not args.quick:
        from .band_edge import run_band_edge
        log("\n== band-edge conditioning")
        results["band_edge"] = run_band_edge(log)
    results["total_s"] = time.perf_counter() - t_start
    _save(json_path, results)
    from .tables import format_summary, format_tables
    atomic_write(os.path.join(args.out, "bench.md"), format_tables(results))
    if results["cases"]:
        if _have("matplotlib"):
            from .figure import plot_work_precision
            plot_work_precision(results, os.path.join(args.out, "work_precision.png"))
            if args.figure:
                plot_work_precision(results, args.figure)
        else:
            log("matplotlib not installed: no figure (pip install 'symbt[plot]')")
    log("\n" + format_summary(results))
    log("wrote %s/{bench.json,bench.md%s}; total %.1f s" % (
        args.out, ",work_precision.png" if results["cases"] and _have("matplotlib") else "", results["total_s"]))
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
