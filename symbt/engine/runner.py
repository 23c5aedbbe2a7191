"""Running claims: cached outcomes are reused, the rest run serially, in a process pool or on Dask.

Every outcome is cached the moment it arrives, so an interrupted run (Ctrl-C)
keeps what finished: the pool's pending work is cancelled, its workers are
terminated, and :class:`Interrupted` (a ``KeyboardInterrupt``) says how far it got.
"""
from __future__ import annotations

import signal
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from ..claims.base import Claim, ClaimResult, Outcome, failed
from .cache import load_cached, store
from .task import run_claim

__all__ = ["run", "Interrupted", "refresh_manifest"]

Progress = Callable[[Claim, Outcome], None]


class Interrupted(KeyboardInterrupt):
    """The run was interrupted; ``finished`` of ``total`` outcomes are known (and cached)."""

    def __init__(self, finished: int, total: int):
        super().__init__(f"interrupted: {finished} of {total} claims finished")
        self.finished, self.total = finished, total


def _ignore_sigint() -> None:
    """Pool workers leave Ctrl-C to the parent, which cancels and terminates them."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _stop(pool) -> None:
    procs = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    for p in procs:
        p.join(timeout=1.0)


def _run_pool(todo: Sequence[Claim], jobs: int, done: Progress, deep: bool = False) -> None:
    import multiprocessing as mp_
    from concurrent.futures import ProcessPoolExecutor, as_completed

    ctx = mp_.get_context("fork") if sys.platform != "win32" else None
    pool = ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=_ignore_sigint)
    try:
        # longest-first keeps every worker busy; N=3 derivations dominate
        ordered = sorted(todo, key=lambda c: -(c.N or 0))
        futs = {pool.submit(run_claim, c.id, deep): c for c in ordered}
        for f in as_completed(futs):
            c = futs[f]
            try:
                out = Outcome.from_dict(f.result())
            except Exception as exc:  # the worker died (BrokenProcessPool) or the outcome did not pickle
                out = failed("exception", detail=f"worker: {type(exc).__name__}: {exc}")
            done(c, out)
    except BaseException:
        _stop(pool)
        raise
    pool.shutdown(wait=True)


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
        dask: str | bool | None = None, manifest: bool = True, deep: bool = False) -> list[ClaimResult]:
    """Run ``claims`` (cached results reused unless ``use_cache=False``); results in the given order.

    ``jobs > 1`` runs the uncached claims in that many worker processes;
    ``dask`` runs them on a Dask cluster instead (``True`` or ``""``: a local
    cluster of ``jobs`` worker processes; a string: a scheduler address), see
    :mod:`.distributed`.  ``progress(claim, outcome)`` is called as each outcome
    arrives (cached ones first).  Each computed outcome is cached at once; on
    Ctrl-C :class:`Interrupted` is raised after the workers are stopped.
    ``manifest=False`` leaves the warm path's manifest alone (callers running
    claims one by one refresh it once, with :func:`refresh_manifest`).  ``deep``
    runs each claim's deep variant (more samples per domain cell) where it has
    one; its outcomes are cached apart from the default ones.
    """
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
        store(c, out, deep)
        if progress:
            progress(c, out)

    try:
        if todo and dask is not None and dask is not False:
            from .distributed import run_on_dask

            run_on_dask(todo, done, address=dask if isinstance(dask, str) and dask else None, workers=jobs,
                        deep=deep)
        elif jobs > 1 and len(todo) > 1:
            _run_pool(todo, jobs, done, deep)
        else:
            for c in todo:
                done(c, c.run(deep=deep))
    except KeyboardInterrupt as exc:
        raise Interrupted(len(results), len(claims)) from exc
    if manifest:
        refresh_manifest()
    return [ClaimResult(c, results[c.id]) for c in claims]
