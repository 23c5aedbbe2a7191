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
``--trace N [--trace-steps n] [--save-state STEP FILE] [--start FILE] [--budget S]``: instead, the per-step
record of the N-site Lohner set (:func:`trace_large`; docs/certified.md, "The N = 64 radius jump").
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

from ..numeric import CertifiedMethod, bt_orbit, certified_orbit
from ..paper import LAM0_EXAMPLE, MU_EXAMPLE, P_EXAMPLE, Q_EXAMPLE
from .cases import chain
from .timing import machine_info

__all__ = ["run_side_by_side", "run_large", "trace_large", "save_state", "load_state", "main"]

P0, Q0, LAM0, MU = list(P_EXAMPLE), list(Q_EXAMPLE), LAM0_EXAMPLE, MU_EXAMPLE[0]
TOL, DPS = 1e-30, 40
#: random states: (N, seed, lam0, mu) with [lam0 - mu, lam0 + mu] above the spectrum (a real map)
LARGE = {8: (8, 8, 5.0, 1.5), 64: (64, 64, 5.0, 1.5)}


def _run(p: Any, q: Any, lam0: float, mu: float, n: int, method: CertifiedMethod, every: int) -> dict[str, Any]:
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


def first_pass_bits(n: int, tol: float = TOL) -> int:
    """The working precision of the Lohner method's first pass for ``n`` steps at ``tol`` (:mod:`..lohner`).

    >>> first_pass_bits(1000)
    174
    """
    return math.ceil(-math.log2(tol)) + 24 + 5 * max(1, n).bit_length()


def _enc(b: Any) -> str:
    m, e = b.mid().man_exp()
    rm, re_ = b.rad().mid().man_exp()
    return "%d %d %d %d" % (int(m), int(e), int(rm), int(re_))


def _dec(s: str) -> Any:
    from flint import arb

    from ..numeric.multiprec.arb import flint_prec

    m, e, rm, re_ = (int(v) for v in s.split())
    with flint_prec(4096):                      # exact: mantissas of at most a few hundred bits
        return arb(arb(m) * arb(2) ** e, arb(rm) * arb(2) ** re_)


def save_state(S: Any, step: int, path: str) -> None:
    """Write the Lohner set ``S`` (a :class:`~symbt.numeric.multiprec.lohner.LohnerSet` on the float64 frame
    path, exact input) after ``step`` steps to ``path`` (``.npz``): every ball and the frame, exactly."""
    import numpy as np

    np.savez_compressed(path, step=step, steps=S.steps, Bf=S.Bf, xh=[_enc(x) for x in S.xh],
                        hull=[_enc(x) for x in S.hull], r=[_enc(S.r[k, 0]) for k in range(S.n)])


def load_state(path: str) -> tuple[Any, int]:
    """``(LohnerSet, step)`` from :func:`save_state`'s file (use it at the saved precision): centres and frame
    exact, radii rounded up by at most one unit of Arb's 30-bit radius (a slightly larger, still valid set).

    >>> import os, tempfile
    >>> from flint import arb
    >>> from symbt.numeric.multiprec.lohner import LohnerSet
    >>> S = LohnerSet([arb(float(x)) for x in chain(13, 13)[0] + chain(13, 13)[1]])
    >>> S.step(arb(5.0), arb(1.5), 1)
    >>> path = os.path.join(tempfile.mkdtemp(), "s.npz"); save_state(S, 1, path)
    >>> T, step = load_state(path)
    >>> step, (T.B == S.B), all(a.mid() == b.mid() for a, b in zip(S.xh + S.hull, T.xh + T.hull)), T.has_r0
    (1, True, True, False)
    >>> all(a.rad() <= b.rad() <= a.rad() * (1 + 2 ** -28) for a, b in zip(S.hull, T.hull))
    True
    """
    import numpy as np
    from flint import arb_mat

    from ..numeric.multiprec.lohner import LohnerSet

    with np.load(path) as z:
        S = LohnerSet([_dec(s) for s in z["xh"]])          # exact centres: no r0 term (exact input)
        S.hull = [_dec(s) for s in z["hull"]]
        S.Bf = np.array(z["Bf"])
        S.B = arb_mat(S.Bf.tolist())
        S.r = arb_mat([[_dec(s)] for s in z["r"]])
        S.steps = int(z["steps"])
        return S, int(z["step"])


def trace_large(N: int, n: int, *, start: str | None = None, save: dict[int, str] | None = None,
                prec: int | None = None, budget: float = 3600.0, out: Any = None) -> list[dict[str, Any]]:
    """Per-step record of the Lohner set of ``run_large(N)``'s state at its first pass's precision.

    Steps ``1 .. n`` (or from the state file ``start``, :func:`save_state`), each ``{"i", "log2_radius" (of the
    hull), "log2_r" (of the frame coordinates), "frame_cond" (1-norm, float64), "cpu_s"}``; the state is
    saved at the steps of ``save`` (``{step: path}``); stops after ``budget`` seconds of wall time; each record
    is also written to ``out`` (a text stream) as a JSON line.

    >>> rows = trace_large(8, 3)
    >>> [r["i"] for r in rows], all(-170 < r["log2_radius"] < -140 for r in rows)
    ([1, 2, 3], True)
    """
    import numpy as np
    from flint import arb

    from ..numeric.multiprec.arb import flint_prec
    from ..numeric.multiprec.lohner import LohnerSet

    size, seed, lam0, mu = LARGE[N]
    bits = prec or first_pass_bits(1000)
    rows: list[dict[str, Any]] = []
    t0 = time.perf_counter()
    with flint_prec(bits):
        if start:
            S, i0 = load_state(start)
        else:
            p, q = chain(size, seed)
            S, i0 = LohnerSet([arb(float(x)) for x in list(p) + list(q)]), 0
        l0, m = arb(lam0), arb(mu)
        for i in range(i0 + 1, n + 1):
            c0 = time.process_time()
            S.step(l0, m, 1)
            cpu = time.process_time() - c0
            rows.append({"i": i, "log2_radius": math.log2(max(float(h.rad()) for h in S.hull)),
                         "log2_r": math.log2(max(float(S.r[k, 0].rad()) for k in range(S.n))),
                         "frame_cond": float(np.linalg.cond(np.asarray(S.Bf, dtype=float), 1)), "cpu_s": cpu})
            if out is not None:
                print(json.dumps(rows[-1]), file=out, flush=True)
            if save and i in save:
                save_state(S, i, save[i])
            if time.perf_counter() - t0 > budget:
                break
    return rows


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
    ap.add_argument("--trace", type=int, choices=sorted(LARGE), metavar="N",
                    help="instead: the per-step record of run_large(N)'s Lohner set (trace_large), JSON lines")
    ap.add_argument("--trace-steps", type=int, default=1000, help="last step of --trace (default 1000)")
    ap.add_argument("--start", metavar="FILE", help="--trace: resume from a saved state")
    ap.add_argument("--save-state", nargs=2, action="append", metavar=("STEP", "FILE"), default=[],
                    help="--trace: save the state after STEP steps to FILE (.npz); repeatable")
    ap.add_argument("--budget", type=float, default=3600.0, help="--trace: wall-time budget, seconds")
    args = ap.parse_args(argv)
    if args.trace is not None:
        try:
            save = {int(k): v for k, v in args.save_state}
        except ValueError:
            print("error: --save-state STEP must be an integer", file=sys.stderr)
            return 2
        rows = trace_large(args.trace, args.trace_steps, start=args.start, save=save, budget=args.budget,
                           out=sys.stdout)
        if rows and rows[0]["i"] == 1:
            from ..numeric.multiprec.lohner import growth_law

            print(json.dumps({"growth": growth_law([-math.inf] + [r["log2_radius"] for r in rows])}))
        return 0
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
