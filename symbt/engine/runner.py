"""Running claims: cached outcomes are reused, the rest run in worker processes (or on Dask), each within a budget.

Uncached claims run in :class:`~.workers.Workers`, persistent processes forked
from the caller (one for ``jobs=1``), longest first.  A check past its *budget*
(:data:`DEFAULT_BUDGET` seconds per claim, the same for deep variants) is
stopped and reported ``inconclusive`` with method ``"timed out"``; a check whose
worker dies is ``failed`` with method ``"worker died"``; neither is cached, and
the run goes on.  Workers die with the process that started them.
``budget=None`` sets no limit (``jobs=1`` then runs in this process).

Every outcome is cached the moment it arrives, so an interrupted run (Ctrl-C)
keeps what finished: the workers are killed and :class:`Interrupted` (a
``KeyboardInterrupt``) says how far it got.
"""
from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from ..claims.base import Claim, ClaimResult, Outcome
from .cache import load_cached, store
from .task import DEFAULT_BUDGET, check_budget, lasting

if TYPE_CHECKING:
    from .workers import Workers

__all__ = ["run", "Interrupted", "refresh_manifest", "keep_workers", "KeptWorkers", "DEFAULT_BUDGET"]

Progress = Callable[[Claim, Outcome], None]


class Interrupted(KeyboardInterrupt):
    """The run was interrupted; ``finished`` of ``total`` outcomes are known (and cached)."""

    def __init__(self, finished: int, total: int):
        super().__init__(f"interrupted: {finished} of {total} claims finished")
        self.finished, self.total = finished, total


class KeptWorkers:
    """Worker processes kept from one :func:`run` to the next (see :func:`keep_workers`); :meth:`close` kills them."""

    def __init__(self) -> None:
        self.pools: list[Workers] = []

    def close(self) -> None:
        for w in self.pools:
            w.close()
        self.pools.clear()


#: the workers kept inside :func:`keep_workers` (``None`` outside it)
_kept: KeptWorkers | None = None


@contextlib.contextmanager
def keep_workers(kept: KeptWorkers | None = None) -> Iterator[KeptWorkers]:
    """Within the block, successive :func:`run` calls reuse their worker processes (and their memoised derivations).

    For callers that run claims one at a time (the pytest plugin: one call per
    test item; a walkthrough: one per claim shown).  Workers are forked anew
    when a call brings claims they were not forked with, or another ``jobs``.
    They are killed when the block ends -- unless ``kept`` (from an earlier
    block) is given: then they stay for the next block with the same ``kept``,
    until ``kept.close()`` or the end of the process.  Outside such blocks
    every run forks its own workers, so a run sees the caller's state as it is
    when the run starts.

    >>> from symbt.claims import REGISTRY, load_all
    >>> _ = load_all()
    >>> with keep_workers():
    ...     [run([REGISTRY[i]], use_cache=False)[0].status for i in ("tn2", "tra.n2")]
    ['verified', 'verified']
    """
    global _kept
    outer, _kept = _kept, (KeptWorkers() if kept is None else kept)
    try:
        yield _kept
    finally:
        if kept is None:
            _kept.close()
        _kept = outer


def _workers_for(todo: Sequence[Claim], jobs: int) -> tuple[Workers, bool]:
    """Workers for ``todo`` and whether the caller owns them (closes them after the run)."""
    from ..claims import REGISTRY
    from .workers import Workers  # multiprocessing: only when something runs (not on the warm path)

    size = max(1, min(jobs, len(todo)))
    if _kept is not None:
        for w in _kept.pools:
            if w.size == size and w.serves(todo):
                return w, False
        _kept.close()
    known = {**REGISTRY, **{c.id: c for c in todo}}
    w = Workers(known, size=size)
    if _kept is not None:
        _kept.pools.append(w)
        return w, False
    return w, True


def refresh_manifest() -> None:
    """Refresh the warm path's manifest of the project whose claims were loaded (or of the package's
    claims, when every claim module of the package is loaded)."""
    import importlib.util

    from ..claims import CLAIM_MODULES
    from .project import PACKAGE_CLAIMS, Project, active
    from .warm import write_manifest

    project = active()
    if project is None:
        names = [f"{PACKAGE_CLAIMS}.{m}" for m in CLAIM_MODULES]
        if all(n in sys.modules or importlib.util.find_spec(n) is None for n in names):
            project = Project(root=Path.cwd())
    if project is not None:
        write_manifest(project)


def run(claims: Sequence[Claim], *, use_cache: bool = True, jobs: int = 1, progress: Progress | None = None,
        dask: str | bool | None = None, manifest: bool = True, deep: bool = False,
        budget: float | None = DEFAULT_BUDGET) -> list[ClaimResult]:
    """Run ``claims`` (cached results reused unless ``use_cache=False``); results in the given order.

    The uncached claims run in ``jobs`` worker processes (one for ``jobs=1``; at most
    ``os.cpu_count()`` and at most one per claim, whatever ``jobs`` asks);
    ``dask`` runs them on a Dask cluster instead (``True`` or ``""``: a local
    cluster of ``jobs`` worker processes; a string: a scheduler address), see
    :mod:`.distributed`.  ``progress(claim, outcome)`` is called as each outcome
    arrives (cached ones first).  Each computed outcome is cached at once; on
    Ctrl-C :class:`Interrupted` is raised after the workers are stopped.
    ``manifest=False`` leaves the warm path's manifest alone (callers running
    claims one by one refresh it once, with :func:`refresh_manifest`).  ``deep``
    runs each claim's deep variant (more samples per domain cell) where it has
    one; its outcomes are cached apart from the default ones.  ``budget`` is the
    time limit of each check in seconds (``None``: none); on Dask it is
    best-effort (:mod:`.distributed`).  A bad ``budget`` raises ``ValueError``.
    """
    check_budget(budget)
    jobs = max(1, min(jobs, os.cpu_count() or 1))     # -j 1000 must not fork 1000 processes
    results: dict[str, Outcome] = {}
    todo = []
    for c in claims:
        out = load_cached(c, deep) if use_cache else None
        if out is not None:
            results[c.id] = out
            if progress:
                progress(c, out)
        else:
            todo.append(c)

    def done(c: Claim, out: Outcome) -> None:
        results[c.id] = out
        if lasting(out):   # a timeout or a dead worker says something about this run only
            store(c, out, deep)
        if progress:
            progress(c, out)

    try:
        if todo and dask is not None and dask is not False:
            from .distributed import run_on_dask

            run_on_dask(todo, done, address=dask if isinstance(dask, str) and dask else None, workers=jobs,
                        deep=deep, budget=budget)
        elif todo and (budget is not None or (jobs > 1 and len(todo) > 1)):
            workers, owned = _workers_for(todo, jobs)
            # longest first keeps every worker busy; N=3 derivations dominate
            ordered = sorted(todo, key=lambda c: -(c.N or 0))
            try:
                workers.run(ordered, done=done, deep=deep, budget=budget)
            finally:
                if owned:
                    workers.close()
        else:
            for c in todo:
                done(c, c.run(deep=deep))
    except KeyboardInterrupt as exc:
        raise Interrupted(len(results), len(claims)) from exc
    if manifest:
        refresh_manifest()
    return [ClaimResult(c, results[c.id]) for c in claims]
