r"""Size and speed of the user codegen path as expressions grow, side by side with ``lambdify(cse=True)``.

The family: the Toda trace :math:`\operatorname{tr}L(\lambda)` of :mod:`symbt.symbolic.toda` for
``N = 2 ... 12`` (expanded, in ``lambda``, ``p_j`` and ``E_j = e^{q_j}``; its term count grows
geometrically with N).  For each N, one row:

* **emit**: ``symbt.emit`` (the declaration and its checks) plus the renderer and the atomic write
  of ``<module>.py`` into a temporary directory (:func:`symbt.codegen.user.files.generate`:
  rewriting, CSE, printing, provenance header) -- the wall time and the file's size in bytes.
  ``optimize`` (``--no-optimize``) is the declaration's flag; the ``expm1``/``log1p`` rules are
  applied only to expressions containing ``exp``/``log`` (:func:`symbt.codegen.user.render.optimized`),
  so for this family both settings emit the same file in the same time (before 2026-11-26 SymPy's
  rewriter tried ``expr.factor()`` of the whole trace: 93 % of the emission time, 98 s at N = 8);
* **lambdify**: ``sympy.lambdify(args, expr, "numpy", cse=True)`` -- its wall time and the size
  of the source it generated (``inspect.getsource``);
* **evaluation** of the emitted numpy function (imported from the written file) and of the
  lambdified one on the same batch of ``points`` seeded points (``lambda`` in [-2, 2], ``p`` in
  [-1, 1], ``E`` in [1/2, 2]): the best of ``repeats`` ``timeit`` runs, and the largest relative
  difference between the two results (both compute the same polynomial: a sanity check, not a
  verdict -- the emitted file's verdict is its claim, :mod:`symbt.engine.emitted_claims`).

A source Python cannot compile (``RecursionError``: the final sum of a large expression is one
expression of thousands of terms -- ``lambdify``'s from N = 10; the emitted file prints long sums as
balanced partial sums and compiles) is recorded as ``None`` (printed ``RecursionError``), not raised.

Run: ``python -m symbt.benchmarks.emission [--n 2 3 ...] [--points 10000] [--repeats 5] [--json FILE]``
(a Markdown table on stdout).  Times depend on the machine and its load; BENCHMARKS.md records
one run with its machine and date.  No unit test asserts a time.

>>> [r["N"] for r in run_emission([2], points=50, repeats=1)]
[2]
"""
from __future__ import annotations

import argparse
import inspect
import json
import sys
import tempfile
import time
import timeit
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["emission_row", "run_emission", "markdown", "main", "COLUMNS"]

#: (key, Markdown heading) of a row, in table order
COLUMNS = (("N", "N"), ("terms", "tr L terms"), ("emit_s", "emit [s]"), ("emit_bytes", "emitted .py [bytes]"),
           ("lambdify_s", "lambdify [s]"), ("lambdify_bytes", "lambdify source [bytes]"),
           ("emitted_eval_s", "emitted eval [ms]"), ("lambdify_eval_s", "lambdify eval [ms]"),
           ("max_rel_diff", "max rel. diff"))


def _points(model: Any, points: int, seed: int) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    cols = [rng.uniform(-2, 2, points)]
    cols += [rng.uniform(-1, 1, points) for _ in model.p]
    cols += [rng.uniform(0.5, 2, points) for _ in model.E]
    return cols


def emission_row(N: int, *, points: int = 10_000, repeats: int = 5, seed: int = 0,
                 optimize: bool = True) -> dict[str, Any]:
    """One row of the benchmark for the N-site trace (see the module docstring for its keys).

    >>> r = emission_row(2, points=20, repeats=1)
    >>> r["terms"], r["emit_bytes"] > 0, r["max_rel_diff"] < 1e-12
    (6, True, True)
    """
    import sympy as sp

    from ..codegen.user.check import load_python
    from ..codegen.user.declare import emit
    from ..codegen.user.files import generate
    from ..symbolic.toda import TodaModel

    if N < 2:
        raise ValueError(f"N = {N}: the periodic Toda lattice needs N >= 2")
    model = TodaModel(N)      # a fresh model: no cached trace from an earlier row or run
    lam = sp.Symbol("lam", real=True)       # "lambda" is a Python keyword, not an argument name
    expr = model.trace.subs(model.lam, lam)
    args = (lam, *model.p, *model.E)
    module = f"toda_trace_n{N}"
    with tempfile.TemporaryDirectory(prefix="symbt-bench-emit-") as tmp:
        out = Path(tmp)
        t0 = time.perf_counter()
        e = emit("trace", expr, args=args, module=module, doc=f"tr L(lambda), N = {N}", optimize=optimize,
                 register=False)
        (path,) = generate([e], out, out)
        emit_s = time.perf_counter() - t0
        emit_bytes = path.stat().st_size
        try:
            emitted = load_python(path).trace
        except RecursionError:    # Python's compiler on a sum of thousands of terms in one expression
            emitted = None

        t0 = time.perf_counter()
        try:
            lambdified = sp.lambdify(args, expr, "numpy", cse=True)
            lambdify_bytes: int | None = len(inspect.getsource(lambdified).encode())
        except RecursionError:
            lambdified, lambdify_bytes = None, None
        lambdify_s = time.perf_counter() - t0

        cols = _points(model, points, seed)
        rel = None
        if emitted is not None and lambdified is not None:
            a, b = np.asarray(emitted(*cols)), np.asarray(lambdified(*cols))
            rel = float(np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-300)))
        emitted_eval = None if emitted is None else \
            min(timeit.repeat(lambda: emitted(*cols), number=1, repeat=repeats))
        lambdify_eval = None if lambdified is None else \
            min(timeit.repeat(lambda: lambdified(*cols), number=1, repeat=repeats))
    return {"N": N, "terms": len(sp.Add.make_args(expr)), "emit_s": emit_s, "emit_bytes": emit_bytes,
            "lambdify_s": lambdify_s, "lambdify_bytes": lambdify_bytes, "emitted_eval_s": emitted_eval,
            "lambdify_eval_s": lambdify_eval, "max_rel_diff": rel, "points": points, "repeats": repeats,
            "optimize": optimize}


def run_emission(ns: Iterable[int] = range(2, 13), *, points: int = 10_000, repeats: int = 5, seed: int = 0,
                 optimize: bool = True, log: Any = None) -> list[dict[str, Any]]:
    """The rows for every N of ``ns`` (``log(row)`` is called as each one finishes)."""
    rows = []
    for n in ns:
        rows.append(emission_row(n, points=points, repeats=repeats, seed=seed, optimize=optimize))
        if log is not None:
            log(rows[-1])
    return rows


def _cell(key: str, v: Any) -> str:
    if v is None:     # the generated source does not compile (see emission_row)
        return "RecursionError" if key.endswith("eval_s") else "-"
    if key.endswith("eval_s"):
        return f"{1e3 * v:.3g}"
    if key.endswith("_s"):
        return f"{v:.3g}"
    if key == "max_rel_diff":
        return f"{v:.1e}"
    return str(v)


def markdown(rows: Sequence[dict[str, Any]]) -> str:
    """The rows as a Markdown table (times in s, evaluation in ms per batch).

    >>> markdown([]).startswith("| N | tr L terms | emit [s] |")
    True
    """
    head = "| " + " | ".join(h for _, h in COLUMNS) + " |"
    rule = "|" + "---|" * len(COLUMNS)
    body = ["| " + " | ".join(_cell(k, r[k]) for k, _ in COLUMNS) + " |" for r in rows]
    return "\n".join([head, rule, *body])


def main(argv: list[str] | None = None) -> int:
    """``python -m symbt.benchmarks.emission``: print the table (and write ``--json``); exit 2 on bad input."""
    ap = argparse.ArgumentParser(prog="python -m symbt.benchmarks.emission",
                                 description="emission time, file size and evaluation time of the Toda trace "
                                             "through symbt.emit, against sympy.lambdify(cse=True)")
    ap.add_argument("--n", type=int, nargs="+", default=list(range(2, 13)), metavar="N", help="sizes (default 2..12)")
    ap.add_argument("--points", type=int, default=10_000, help="batch size of the evaluation (default 10000)")
    ap.add_argument("--repeats", type=int, default=5, help="timeit repeats, the best is kept (default 5)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-optimize", action="store_true",
                    help="declare with optimize=False (no expm1/log1p rewriting: SymPy's rewriter factors the "
                         "whole expression, most of the emission time of a large polynomial)")
    ap.add_argument("--json", metavar="FILE", help="also write the rows as JSON")
    a = ap.parse_args(argv)
    bad = [n for n in a.n if n < 2]
    if bad or a.points < 1 or a.repeats < 1:
        what = f"N = {bad[0]} (need N >= 2)" if bad else "--points and --repeats must be at least 1"
        print(f"python -m symbt.benchmarks.emission: {what}", file=sys.stderr)
        return 2
    print("\n".join(markdown([]).splitlines()[:2]), flush=True)
    rows = run_emission(a.n, points=a.points, repeats=a.repeats, seed=a.seed, optimize=not a.no_optimize,
                        log=lambda r: print(markdown([r]).splitlines()[-1], flush=True))
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
