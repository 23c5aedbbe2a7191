"""Certified orbits side by side: the plain ball path against the Lohner method (issue 23).

``python -m symbt.benchmarks.certified [--quick] [--json FILE] [--ball-max-steps K] [--large N ...]``
runs in one process, on the paper's example (N = 3, ``lam0 = 10``, ``mu = 5``, exact binary input):

* both methods (``certified_orbit(..., method="ball" | "lohner")``) for 100, 3500 and 1e5 steps at
  ``tol = 1e-30`` (``mp.dps = 40``): wall and CPU seconds, working bits, largest returned radius; the ball
  path beyond ``--ball-max-steps`` (default 3500) is not run -- it needs about ``2.1 n`` bits and its cost
  grows like ``n**2`` -- and is reported with that estimate;
* the Lohner radius growth law over n = 1e2 ... 1e5 (``info["growth"]``), the invariants' enclosures along
  the 1e5-step orbit (checked to intersect) and the certified float64 error over the run;
* random states N = 8 and N = 64 (``symbt.benchmarks.cases.chain``), 1000 steps: time, bits, growth law.

``--quick``: 100 and 1000 steps, N = 8 only (a minute); ``--steps`` and ``--large`` select parts.
Results go to stdout (a Markdown table) and, with ``--json``, to a file.

>>> rows = run_side_by_side([20], ball_max_steps=20)
>>> sorted(r["method"] for r in rows), all(r["max_radius"] <= 1e-30 for r in rows)
(['ball', 'lohner'], True)
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from typing import Any

import mpmath

from ..numeric import bt_orbit, certified_orbit
from ..paper import LAM0_EXAMPLE, MU_EXAMPLE, P_EXAMPLE, Q_EXAMPLE
from .cases import chain
from .timing import machine_info

__all__ = ["run_side_by_side", "run_large", "main"]

P0, Q0, LAM0, MU = list(P_EXAMPLE), list(Q_EXAMPLE), LAM0_EXAMPLE, MU_EXAMPLE[0]
TOL, DPS = 1e-30, 40
#: random states: (N, seed, lam0, mu) with [lam0 - mu, lam0 + mu] above the spectrum (a real map)
LARGE = {8: (8, 8, 5.0, 1.5), 64: (64, 64, 5.0, 1.5)}


def _run(p: Any, q: Any, lam0: float, mu: float, n: int, method: str, every: int) -> dict[str, Any]:
    info: dict[str, Any] = {}
    t0, c0 = time.perf_counter(), time.process_time()
    with mpmath.workdps(DPS):
        P, Q, Pr, Qr = certified_orbit(p, q, lam0, mu, n, every=every, tol=TOL, info=info, method=method)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    row = {"N": len(p), "steps": n, "method": info["method"], "wall_s": wall, "cpu_s": cpu, "bits": info["prec"],
           "passes": info["passes"], "max_radius": float(max(max(a + b) for a, b in zip(Pr, Qr))),
           "growth": info.get("growth")}
    row["orbit"] = (P, Q, Pr, Qr)
    return row


def run_side_by_side(steps: list[int], ball_max_steps: int = 3500) -> list[dict[str, Any]]:
    """Rows ``{steps, method, wall_s, cpu_s, bits, max_radius, ...}`` for the paper's example, both methods."""
    rows = []
    for n in steps:
        for method in ("ball", "lohner"):
            if method == "ball" and n > ball_max_steps:
                rows.append({"N": 3, "steps": n, "method": "ball", "skipped": True,
                             "bits": int(2.1 * n + 100), "note": "not run: ~2.1 n + 100 bits (estimate)"})
                continue
            row = _run(P0, Q0, LAM0, MU, n, method, every=max(1, n // 100))
            if method == "lohner":
                row.update(_by_products(row.pop("orbit"), n, max(1, n // 100)))
            else:
                row.pop("orbit")
            rows.append(row)
    return rows


def _by_products(orbit: Any, n: int, every: int) -> dict[str, Any]:
    from ..numeric.multiprec.lohner_checks import common_invariants, float64_error_bounds, invariant_enclosures

    P, Q, Pr, Qr = orbit
    H = common_invariants(invariant_enclosures(P, Q, Pr, Qr))       # raises if two enclosures are disjoint
    Pf, Qf = bt_orbit(P0, Q0, LAM0, MU, n, every=every)
    bounds = float64_error_bounds(P, Q, Pr, Qr, Pf, Qf)
    return {"invariants": ["%s +- %.1e" % (h.mid().str(15, radius=False), float(h.rad())) for h in H],
            "float64_error": max(bounds),
            "float64_error_at_end": bounds[-1]}


def run_large(N: int, n: int = 1000) -> dict[str, Any]:
    """The Lohner orbit of the random state of size ``N`` (``LARGE``): time, bits, growth law."""
    size, seed, lam0, mu = LARGE[N]
    p, q = chain(size, seed)
    row = _run(list(p), list(q), lam0, mu, n, "lohner", every=max(1, n // 100))
    row.pop("orbit")
    return row


def _fmt(rows: list[dict[str, Any]]) -> str:
    out = ["| N | steps | method | working bits | wall / CPU time | max radius | growth degree |",
           "|---|---|---|---|---|---|---|"]
    for r in rows:
        if r.get("skipped"):
            out.append("| %d | %d | %s | ~%d (est.) | not run | — | — |" % (r["N"], r["steps"], r["method"], r["bits"]))
            continue
        g = r.get("growth") or {}
        deg = "%.2f (n = %d…%d)" % (g["degree"], *g["steps"]) if g.get("degree") is not None else "—"
        out.append("| %d | %d | %s | %d | %.2f s / %.2f s | %.1e | %s |" % (
            r["N"], r["steps"], r["method"], r["bits"], r["wall_s"], r["cpu_s"], r["max_radius"], deg))
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m symbt.benchmarks.certified", description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="100 and 1000 steps, N = 8 only")
    ap.add_argument("--json", metavar="FILE", help="also write the rows as JSON")
    ap.add_argument("--ball-max-steps", type=int, default=3500, help="longest orbit run on the ball path")
    ap.add_argument("--large", type=int, nargs="*", choices=sorted(LARGE), help="random states (default 8 64)")
    ap.add_argument("--steps", type=int, nargs="*", help="orbit lengths of the side-by-side part "
                    "(default 100 3500 100000)")
    args = ap.parse_args(argv)
    steps = args.steps if args.steps is not None else ([100, 1000] if args.quick else [100, 3500, 100_000])
    large = args.large if args.large is not None else ([8] if args.quick else [8, 64])
    head = {"machine": machine_info(), "date": time.strftime("%Y-%m-%d %H:%M"),
            "command": "python -m symbt.benchmarks.certified " + " ".join(sys.argv[1:] if argv is None else argv)}
    print(json.dumps(head), flush=True)
    rows = run_side_by_side(steps, args.ball_max_steps)
    for N in large:
        rows.append(run_large(N))
    print(_fmt(rows))
    for r in rows:
        if "invariants" in r:
            print("n = %d: H_k (intersection over the stored states) %s; certified float64 error <= %.2e (max "
                  "over the run), %.2e at the end" % (r["steps"], ", ".join(r["invariants"]), r["float64_error"],
                                                      r["float64_error_at_end"]))
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({**head, "rows": rows}, fh, indent=1, default=str)
    return 0 if all(math.isfinite(r.get("max_radius", 0.0)) for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
