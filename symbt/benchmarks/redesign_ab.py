"""The numeric timings of two checkouts side by side, interleaved (``python -m symbt.benchmarks.redesign_ab``).

Written for issue 22 ("a full ``symbt bench`` rerun in one run shows no ratio worse than before beyond
noise"), reusable for any change of :mod:`symbt.numeric` that keeps its public calls::

    git worktree add --detach /tmp/before <commit>
    python -m symbt.benchmarks.redesign_ab /tmp/before . --rounds 3 --json ab.json

Each *round* runs one worker process per tree, in alternating order (A B, B A, A B, ...), so that
the load of a shared machine falls on both alike.  A worker imports ``symbt`` from its tree
(``PYTHONPATH``; it checks which file it got) and times, through the public calls only
(``bt_orbit``, ``bt_step`` with their ``backend=`` names, which both trees share), the float64 rows of
``symbt bench --quick``: every case's ``bt_orbit`` (auto, and the ``numba``, ``python``, ``numpy``
backends), the batched ``bt_step`` throughput (auto and numpy, by batch and by N), the (1000, 3)
ensemble, and ``bt_orbit`` on mpmath input at 50 and 100 digits (auto and each multiprecision
backend).  Each row is the best time per call over 5 batches of at least ``min_time / 5`` seconds
after one untimed call (numba compiles or loads from its disk cache there).  A row's time is the best
over the rounds; the table gives ``after / before`` and, as the noise estimate, the smallest and
largest ratio of one round's pair.

>>> from symbt.benchmarks.redesign_ab import ratio_table
>>> ratio_table({"x": [1.0, 2.0]}, {"x": [1.1, 1.8]})["x"]
{'before_s': 1.0, 'after_s': 1.1, 'ratio': 1.1, 'round_min': 0.9, 'round_max': 1.1}
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from symbt.numeric import BackendName

__all__ = ["rows", "problem", "ratio_table", "main"]

THROUGHPUT_BATCHES = (1, 100, 10**4, 10**5)
THROUGHPUT_NS = (2, 3, 8, 32, 128, 1024)


def problem() -> dict[str, Any]:
    """The inputs of every row, as JSON (computed once, by the tree that runs the comparison)."""
    import numpy as np

    from .cases import cases
    from .ensemble import ensemble_states

    P, Q = ensemble_states(1000)
    return {"cases": [{"name": c.name, "p": list(c.p), "q": list(c.q), "lam0": c.lam0, "mu": c.mu, "n": c.n,
                       "branch": c.branch} for c in cases(quick=True)],
            "ensemble": {"P": np.asarray(P).tolist(), "Q": np.asarray(Q).tolist()}}


def rows(spec: dict[str, Any]) -> dict[str, Callable[[], Any]]:
    """Row name -> a call of the public API of whichever ``symbt`` is imported (both trees)."""
    import mpmath
    import numpy as np

    from symbt.numeric import bt_orbit, bt_step

    out: dict[str, Callable[[], Any]] = {}
    orbit_backends: tuple[BackendName, ...] = ("numba", "python", "numpy")
    for c in spec["cases"]:
        p, q, n = np.array(c["p"]), np.array(c["q"]), c["n"]
        args = (p, q, c["lam0"], c["mu"], n)
        out[f"{c['name']} bt_orbit auto"] = partial(bt_orbit, *args, branch=c["branch"])
        for be in orbit_backends:
            out[f"{c['name']} bt_orbit {be}"] = partial(bt_orbit, *args, branch=c["branch"],
                                                        every=max(1, n // 100), backend=be)
    step_backends: tuple[BackendName, ...] = ("auto", "numpy")
    rng = np.random.default_rng(0)
    P0, Q0 = np.array(spec["cases"][0]["p"]), np.array(spec["cases"][0]["q"])
    for B in THROUGHPUT_BATCHES:
        p = P0 + 1e-2 * rng.normal(size=(B, 3))
        q = Q0 + 1e-2 * rng.normal(size=(B, 3))
        for be in step_backends:
            out[f"bt_step batch {B} {be}"] = partial(bt_step, p, q, 10.0, 5.0, backend=be)
    rng = np.random.default_rng(1)
    for N in THROUGHPUT_NS:
        p, q = rng.normal(size=(256, N)), 0.5 * rng.normal(size=(256, N))
        for be in step_backends:
            out[f"bt_step N={N} batch 256 {be}"] = partial(bt_step, p, q, 3.0 * N + 20.0, 2.0, backend=be)
    EP, EQ = np.array(spec["ensemble"]["P"]), np.array(spec["ensemble"]["Q"])
    out["ensemble (1000, 3) 20 steps auto"] = partial(bt_orbit, EP, EQ, 10.0, 5.0, 20)
    c0 = spec["cases"][0]
    mp_backends: tuple[BackendName, ...] = ("auto", "qd", "flint", "mpmath")
    for digits in (50, 100):
        for be in mp_backends:
            if be == "qd" and digits > 60:      # beyond quad-double precision: both trees refuse
                continue

            def mp_orbit(digits: int = digits, be: BackendName = be) -> Any:
                with mpmath.workdps(digits):
                    p = [mpmath.mpf(v) for v in c0["p"]]
                    q = [mpmath.mpf(v) for v in c0["q"]]
                    return bt_orbit(p, q, mpmath.mpf(c0["lam0"]), mpmath.mpf(c0["mu"]), 10, backend=be)
            out[f"mp {digits} digits 10 steps {be}"] = mp_orbit
    return out


def _worker(tree: str, spec_path: str, min_time: float, only: str = "") -> None:
    import symbt
    from symbt.benchmarks.timing import best_time  # the tree's own (the same function in both trees)

    got = Path(symbt.__file__).resolve()
    if not got.is_relative_to(Path(tree).resolve()):
        raise SystemExit(f"redesign_ab: imported {got}, not from {tree}")
    spec = json.loads(Path(spec_path).read_text())
    times: dict[str, Any] = {}
    keep = [s for s in only.split(",") if s]
    for name, fn in rows(spec).items():
        if keep and not any(s in name for s in keep):
            continue
        try:
            times[name] = best_time(fn, min_time)
        except Exception as exc:           # a row one tree refuses is reported, not fatal
            times[name] = f"failed: {type(exc).__name__}: {exc}"
    print(json.dumps(times))


def _run(tree: Path, spec_path: Path, min_time: float, only: str = "") -> dict[str, Any]:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    r = subprocess.run([sys.executable, __file__, "--worker", str(tree), str(spec_path), str(min_time), only],
                       cwd=tree, env=env, capture_output=True, text=True, timeout=900)
    if r.returncode != 0:
        raise RuntimeError(f"worker in {tree} failed: {r.stderr.strip().splitlines()[-1:]}")
    result: dict[str, Any] = json.loads(r.stdout.strip().splitlines()[-1])
    return result


def ratio_table(before: dict[str, list[Any]], after: dict[str, list[Any]]) -> dict[str, dict[str, Any]]:
    """Per row: best times over the rounds, ``after / before`` and the extreme ratios of one round's pair."""
    out: dict[str, dict[str, Any]] = {}
    for name, b in before.items():
        a = after.get(name, [])
        pairs = [(x, y) for x, y in zip(b, a) if isinstance(x, float) and isinstance(y, float)]
        if not pairs:
            out[name] = {"failed": next((v for v in b + a if isinstance(v, str)), "no times")}
            continue
        bb, aa = min(x for x, _ in pairs), min(y for _, y in pairs)
        per = [y / x for x, y in pairs]
        out[name] = {"before_s": bb, "after_s": aa, "ratio": round(aa / bb, 3),
                     "round_min": round(min(per), 3), "round_max": round(max(per), 3)}
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m symbt.benchmarks.redesign_ab", description=__doc__.split("\n")[0])
    ap.add_argument("before", type=Path, help="checkout (work tree root) timed as 'before'")
    ap.add_argument("after", type=Path, help="checkout timed as 'after'")
    ap.add_argument("--rounds", type=int, default=3, help="worker pairs, alternating order (default 3)")
    ap.add_argument("--min-time", type=float, default=0.1, help="seconds of calls per row and worker (default 0.1)")
    ap.add_argument("--only", default="", help="comma-separated substrings: time only the rows whose name has one")
    ap.add_argument("--json", type=Path, help="write the times and ratios here")
    args = ap.parse_args(argv)
    for t in (args.before, args.after):
        if not (t / "symbt" / "numeric" / "__init__.py").is_file():
            ap.error(f"{t} is not a symbt checkout")
    if args.rounds < 1 or args.min_time <= 0:
        ap.error("--rounds must be >= 1 and --min-time > 0")
    spec_path = Path(os.environ.get("TMPDIR", "/tmp")) / f"redesign_ab_{os.getpid()}.json"
    spec_path.write_text(json.dumps(problem()))
    times: dict[str, dict[str, list[Any]]] = {"before": {}, "after": {}}
    try:
        for k in range(args.rounds):
            order = ("before", "after") if k % 2 == 0 else ("after", "before")
            for which in order:
                t0 = time.perf_counter()
                res = _run(getattr(args, which).resolve(), spec_path, args.min_time, args.only)
                for name, v in res.items():
                    times[which].setdefault(name, []).append(v)
                print(f"round {k + 1} {which}: {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)
    finally:
        spec_path.unlink(missing_ok=True)
    table = ratio_table(times["before"], times["after"])
    print(f"{'row':<44} {'before s':>10} {'after s':>10} {'ratio':>6}  rounds")
    for name, r in table.items():
        if "failed" in r:
            print(f"{name:<44} {r['failed']}")
        else:
            print(f"{name:<44} {r['before_s']:10.3e} {r['after_s']:10.3e} {r['ratio']:6.2f}  "
                  f"{r['round_min']:.2f}-{r['round_max']:.2f}")
    if args.json:
        args.json.write_text(json.dumps({"times": times, "ratios": table}, indent=1))
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--worker":
        here = Path(__file__).resolve().parent     # the script's folder is no package root: symbt comes from PYTHONPATH
        sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != here]
        _worker(sys.argv[2], sys.argv[3], float(sys.argv[4]), sys.argv[5] if len(sys.argv) > 5 else "")
    else:
        sys.exit(main())
