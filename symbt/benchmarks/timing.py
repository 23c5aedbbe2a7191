"""Wall-clock timing and the machine description recorded with every run.

:func:`timed`: one untimed warm-up call, then the median of repeats (5 below 0.2 s, 3 below
1 s, else 1; ``quick``: 3 below 0.2 s, else 1).  A call shorter than 20 ms is timed in batches of
calls at least 20 ms long (per-call time = batch time / calls), so that timer resolution, the
garbage collector and scheduler noise do not dominate millisecond timings; every contender goes
through the same rule.  :func:`best_time`: best of ``repeats`` batches of
calls, each batch at least ``min_time / repeats`` long (throughput).

>>> res, secs, reps = timed(lambda: sum(range(1000)))
>>> res, reps
(499500, 5)
"""
from __future__ import annotations

import os
import platform
import statistics
import time
from collections.abc import Callable
from typing import Any

__all__ = ["timed", "best_time", "machine_info"]

_BATCH_S = 0.02          # shortest timed batch (s)


def timed(fn: Callable[[], Any], warm: Callable[[], Any] | None = None, quick: bool = False
          ) -> tuple[Any, float, int]:
    """``(result, median seconds, repeats)`` of ``fn()`` after one warm-up call of ``warm`` (or ``fn``)."""
    (warm or fn)()
    t0 = time.perf_counter()
    res = fn()
    first = time.perf_counter() - t0
    batch = 1 if first >= _BATCH_S else max(1, int(_BATCH_S / max(first, 1e-7)) + 1)
    reps = 1 if first >= 1.0 else (3 if first >= 0.2 else 5)
    if quick:
        reps = 1 if first >= 0.2 else 3
    times = [first] if batch == 1 else []
    while len(times) < reps:
        t0 = time.perf_counter()
        for _ in range(batch):
            fn()
        times.append((time.perf_counter() - t0) / batch)
    return res, statistics.median(times), len(times)


def best_time(fn: Callable[[], Any], min_time: float, repeats: int = 5) -> float:
    """Best time per call over ``repeats`` batches (each at least ``min_time / repeats`` seconds)."""
    fn()
    best = float("inf")
    for _ in range(repeats):
        reps, t0 = 0, time.perf_counter()
        while True:
            fn()
            reps += 1
            dt = time.perf_counter() - t0
            if dt >= min_time / repeats:
                break
        best = min(best, dt / reps)
    return best


def interleaved_best(fns: dict[str, Callable[[], Any]], rounds: int, reps: int = 1,
                     clock: Callable[[], float] = time.perf_counter) -> dict[str, float]:
    """Best time per call of each of ``fns`` over ``rounds`` rounds, one batch of ``reps`` calls of every
    function per round, in turn (a shared machine's load then falls on all of them alike).

    >>> sorted(interleaved_best({"a": lambda: None, "b": lambda: None}, rounds=2))
    ['a', 'b']
    """
    best = {name: float("inf") for name in fns}
    for _ in range(rounds):
        for name, fn in fns.items():
            t0 = clock()
            for _ in range(reps):
                fn()
            best[name] = min(best[name], (clock() - t0) / reps)
    return best


def _version(module: str) -> str | None:
    try:
        mod = __import__(module)
    except Exception:
        return None
    return getattr(mod, "__version__", "?")


def machine_info() -> dict:
    """CPU, core count, platform and the versions of the numeric packages (None = not installed)."""
    cpu = ""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    info: dict = {"python": platform.python_version(), "cpu": cpu, "cores": os.cpu_count(),
                  "platform": platform.platform()}
    for mod in ("numpy", "mpmath", "scipy", "numba", "heyoka", "matplotlib"):
        info[mod] = _version(mod)
    try:
        info["loadavg"] = list(os.getloadavg())
    except OSError:
        pass
    return info
