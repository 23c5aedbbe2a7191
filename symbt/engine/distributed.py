"""Claims on a Dask cluster (``symbt verify --dask [ADDRESS]``; optional extra ``symbt[dask]``).

Claims are independent tasks: each uncached claim becomes one Dask task that
runs it on a worker (the worker imports ``symbt`` and the claim modules once) and
returns its outcome as plain data; the caller caches every outcome as it arrives,
so the report and the cache are the same as for a local run.  Without an address
a :class:`distributed.LocalCluster` of ``workers`` single-threaded processes is
started (and stopped afterwards); with one, the scheduler at that address is used
-- its workers need the same version of symbt installed.

The time budget is best-effort here: symbt does not own a remote cluster's
processes, so a check past its budget is reported ``inconclusive (timed out)``
then, but it goes on running in a thread of its Dask worker until it
ends or the worker is restarted (the processes of a local cluster end when the
cluster is closed after the run).

Worth it for the minutes-long ``--deep`` claims, exact claims at N = 5 and more,
and parameter sweeps: anything whose tasks take seconds, so that the cluster's
start-up (about a second) and per-task overhead (milliseconds) do not matter.
"""
from __future__ import annotations

import uuid
from collections.abc import Callable, Sequence

from ..claims.base import Claim, Outcome, failed
from .task import run_claim

__all__ = ["run_on_dask"]


def run_on_dask(todo: Sequence[Claim], done: Callable[[Claim, Outcome], None], *, address: str | None = None,
                workers: int = 2, deep: bool = False, budget: float | None = None) -> None:
    """Run ``todo`` on Dask and call ``done(claim, outcome)`` as each finishes.

    ``budget`` bounds each check's seconds (best-effort, see above).
    Raises ``ModuleNotFoundError`` (name ``distributed``) when Dask is not installed.
    """
    from distributed import Client, LocalCluster, as_completed

    cluster = None
    if address is None:
        cluster = LocalCluster(n_workers=max(1, workers), threads_per_worker=1, processes=True,
                               dashboard_address=None)
    client = Client(cluster if cluster is not None else address)
    try:
        tag = uuid.uuid4().hex[:8]
        ordered = sorted(todo, key=lambda c: -(c.N or 0))
        futs = {client.submit(run_claim, c.id, deep, budget, key=f"symbt-{c.id}-{tag}", pure=False): c for c in ordered}
        for f in as_completed(list(futs)):
            c = futs[f]
            try:
                out = Outcome.from_dict(f.result())
            except Exception as exc:  # a worker died, or the task failed outside Claim.run
                out = failed("exception", detail=f"dask worker: {type(exc).__name__}: {exc}")
            done(c, out)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
