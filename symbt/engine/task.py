"""The unit of work shipped to a worker process or a Dask worker: one claim, by id; and the outcomes a run
reports for a claim that did not finish by itself (timed out, its worker died)."""
from __future__ import annotations

import signal
import threading
from dataclasses import replace
from typing import Any

from ..claims.base import Outcome, failed

__all__ = ["run_claim", "check_budget", "timed_out", "worker_died", "lasting",
           "DEFAULT_BUDGET", "TIMED_OUT", "WORKER_DIED"]

#: seconds one claim's check may take before it is reported ``inconclusive (timed out ...)``
DEFAULT_BUDGET = 300.0
#: the methods of outcomes that say something about this run, not about the claim: never cached
TIMED_OUT, WORKER_DIED = "timed out", "worker died"


def check_budget(budget: object) -> None:
    """Raise ``ValueError`` unless ``budget`` is ``None`` or a finite positive number of seconds.

    >>> check_budget(0.5)
    >>> check_budget(0)
    Traceback (most recent call last):
    ValueError: budget must be a positive number of seconds or None, not 0
    """
    if budget is None:
        return
    if isinstance(budget, bool) or not isinstance(budget, (int, float)) or not 0 < budget < float("inf"):
        raise ValueError(f"budget must be a positive number of seconds or None, not {budget!r}")


def timed_out(budget: float, seconds: float | None = None) -> Outcome:
    """The outcome of a check stopped after ``budget`` seconds: ``inconclusive``, never cached.

    >>> o = timed_out(300.0)
    >>> o.status, o.method, o.detail
    ('inconclusive', 'timed out', 'inconclusive (timed out after 300 s)')
    """
    out = Outcome("inconclusive", TIMED_OUT, detail=f"inconclusive (timed out after {budget:g} s)")
    out = replace(out, seconds=round(budget if seconds is None else seconds, 4))
    return out


def worker_died(exitcode: int | None) -> Outcome:
    """The outcome of a check whose worker process died under it (``exitcode`` as multiprocessing gives it).

    >>> worker_died(-11).detail
    'the worker process died while running the check: killed by signal SIGSEGV (11)'
    """
    if exitcode is not None and exitcode < 0:
        try:
            name = signal.Signals(-exitcode).name
        except ValueError:
            name = "signal"
        cause = f"killed by signal {name} ({-exitcode})"
    else:
        cause = f"exited with status {exitcode}"
    return failed(WORKER_DIED, detail=f"the worker process died while running the check: {cause}")


def lasting(out: Outcome) -> bool:
    """Whether ``out`` says something about the claim (cacheable), not only about this run.

    >>> lasting(timed_out(1.0)), lasting(worker_died(-9)), lasting(Outcome("verified", "exact"))
    (False, False, True)
    """
    return out.method not in (TIMED_OUT, WORKER_DIED)


def run_claim(claim_id: str, deep: bool = False, budget: float | None = None) -> dict[str, Any]:
    """Run one registered claim (loading the claim modules once per worker); its outcome as a dict.

    Plain data in and out, so it pickles to any worker.  With a ``budget`` the
    check runs in a thread that is waited for at most ``budget`` seconds; past it
    the timed-out outcome is returned at once and the thread is left to finish in
    the background (a thread cannot be killed: best-effort, for Dask workers,
    whose processes symbt does not own).
    """
    from ..claims import REGISTRY, load_all

    if claim_id not in REGISTRY:  # a forked worker has the parent's registry already
        load_all()
    c = REGISTRY[claim_id]
    if budget is None:
        return c.run(deep=deep).to_dict()
    box: list[Outcome] = []
    t = threading.Thread(target=lambda: box.append(c.run(deep=deep)), name=f"symbt-{claim_id}", daemon=True)
    t.start()
    t.join(budget)
    return (box[0] if box else timed_out(budget)).to_dict()
