"""Size and time of the emitted code as N grows: ``python -m symbt.benchmarks.codegen_scaling [--n 2 3 ...]``.

For each N and form (closed form up to ``--closed-max``, the transfer-matrix form always) it
measures, each emission in a fresh process (no derivation cached from another N):

* emission time of ``toda{N}.py`` (derivation + CSE + printing, imports excluded);
* module size (bytes, lines) and, for the closed form, the monomials of tr L
  (``Q_N = (1 + sqrt 2)^N + (1 - sqrt 2)^N``);
* evaluation cost per call of the numpy flavour: ``bt_step`` for one state and per state in a batch
  of 1000, ``invariants`` and ``flow_field`` for one state (best of 5 repeats of a timed loop),
  side by side with :func:`symbt.numeric.bt_step` on one state.

Prints a Markdown table (the one in BENCHMARKS.md, section "Code generation for any N").
"""
from __future__ import annotations

import argparse
import functools
import importlib.util
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
import timeit
from collections.abc import Callable
from pathlib import Path

__all__ = ["emit_in_subprocess", "call_costs", "main"]

_EMIT = """
import json, sys, time
from symbt.codegen.emit import module_body
t = time.perf_counter()
body = module_body({N}, {form!r})
dt = time.perf_counter() - t
open({path!r}, "w").write(body)
terms = None
if {form!r} == "closed":
    from symbt.codegen.derive import _trace_ring
    terms = len(_trace_ring({N}).tr.terms())
print(json.dumps(dict(seconds=dt, bytes=len(body.encode()), lines=body.count(chr(10)), terms=terms)))
"""


def emit_in_subprocess(N: int, form: str, path: str, timeout: float) -> dict:
    env = dict(os.environ)
    root = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = root + os.pathsep + env.get("PYTHONPATH", "")
    try:
        r = subprocess.run([sys.executable, "-c", _EMIT.format(N=N, form=form, path=path)], env=env,
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(seconds=None, timeout=timeout)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    return json.loads(r.stdout.strip().splitlines()[-1])


def _load(path, N, tag):
    spec = importlib.util.spec_from_file_location(f"toda{N}_{tag}", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def call_costs(paths: dict, N: int, repeat: int = 7) -> dict:
    """Seconds per call of the emitted numpy functions, form -> {function: seconds} (one state;
    bt_step also per state of a batch of 1000), and of :func:`symbt.numeric.bt_step` on one state.
    The repeats of all contenders are interleaved and the best is kept (the machine is shared)."""
    import numpy as np

    from ..numeric import bt_step
    from ..reference.samples import admissible_states

    mods = {form: _load(path, N, form[0]) for form, path in paths.items()}
    p, q, l0, m = admissible_states(N, 1, 1)[0]
    p, q, l0, m = [float(v) for v in p], [float(v) for v in q], float(l0), float(m)
    P = np.array([p] * 1000) + 1e-9 * np.arange(1000)[:, None]
    Q = np.array([q] * 1000)
    c = [0.5] * N
    jobs: dict[tuple[str, str], tuple[Callable[[], object], int, int]] = {}
    for form, mod in mods.items():
        jobs[form, "step"] = (functools.partial(mod.bt_step, p, q, l0, m, 1), 20, 1)
        jobs[form, "step_batch"] = (functools.partial(mod.bt_step, P, Q, l0, m, 1), 2, 1000)
        jobs[form, "invariants"] = (functools.partial(mod.invariants, p, q), 20, 1)
        jobs[form, "flow_field"] = (functools.partial(mod.flow_field, c, p, q), 5, 1)
    jobs["numeric", "step"] = (lambda: bt_step(p, q, l0, m), 20, 1)
    best = {k: float("inf") for k in jobs}
    for _ in range(repeat):
        for k, (fn, number, per) in jobs.items():
            best[k] = min(best[k], timeit.timeit(fn, number=number) / number / per)
    out: dict = {}
    for (form, what), t in best.items():
        out.setdefault(form, {})[what] = t
    return out


def _fmt(x, unit=1e6, nd=0):
    return "-" if x is None else f"{x * unit:.{nd}f}"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m symbt.benchmarks.codegen_scaling", description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, nargs="+", default=list(range(2, 13)))
    ap.add_argument("--closed-max", type=int, default=6, help="largest N emitted in closed form (default 6)")
    ap.add_argument("--timeout", type=float, default=900.0, help="per emission, seconds")
    ap.add_argument("--json", metavar="FILE")
    args = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for N in args.n:
            paths = {}
            for form in ("closed", "transfer-matrix"):
                if form == "closed" and N > args.closed_max:
                    continue
                path = os.path.join(tmp, f"toda{N}_{form[0]}.py")
                em = emit_in_subprocess(N, form, path, args.timeout)
                rows.append(dict(N=N, form=form, **em))
                if em.get("seconds") is not None:
                    paths[form] = path
            costs = call_costs(paths, N)
            for r in rows:
                if r["N"] == N and r["form"] in costs:
                    r.update(costs[r["form"]], numeric_step=costs["numeric"]["step"])
            print(f"# N={N}: {json.dumps([r for r in rows if r['N'] == N])}", file=sys.stderr)
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))
    print(f"machine: {platform.machine()} {os.cpu_count()} cores, Python {platform.python_version()}, "
          f"{time.strftime('%Y-%m-%d')}")
    print("| N | form | tr L terms | emit [s] | module [kB] | lines | bt_step [µs] | bt_step per state, batch 1000 "
          "[µs] | invariants [µs] | flow_field [µs] | symbt.numeric.bt_step [µs] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r.get("seconds") is None:
            print(f"| {r['N']} | {r['form']} | - | > {r['timeout']:.0f} (stopped) | - | - | - | - | - | - | - |")
            continue
        print(f"| {r['N']} | {r['form']} | {r['terms'] or '-'} | {r['seconds']:.1f} | {r['bytes'] / 1e3:.0f} | "
              f"{r['lines']} | {_fmt(r['step'])} | {_fmt(r['step_batch'], nd=2)} | {_fmt(r['invariants'])} | "
              f"{_fmt(r['flow_field'])} | {_fmt(r['numeric_step'])} |")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
