"""Running claims: scene selection, on-disk cache, parallel and distributed execution, the warm path.

* A *scene* is a named group of claims (``symbt scenes`` lists them).  Running
  a scene runs only its claims; derivations are built lazily and memoised
  per lattice size (:func:`symbt.symbolic.toda.toda_model`), so an N=2 scene
  never builds an N=3 model, and a symbolic scene never imports scipy.
  Pseudo-scenes ``n2``, ``n3``, ``n4`` select claims by lattice size, and a
  claim id selects itself (:mod:`.select`).
* Results are cached as JSON (no pickle) in ``$SYMBT_CACHE_DIR`` (default
  ``~/.cache/symbt``), one file per claim, keyed by a SHA-256 of the claim's
  id, the source of its module and of the layers below it, and the versions of
  Python and the libraries (:mod:`.cache`).  A corrupt, stale or wrongly shaped
  entry is recomputed; ``use_cache=False`` forces recomputation.
* Independent claims run in worker processes (``jobs`` of them, one for
  ``jobs=1``; :mod:`.workers`) or on a Dask cluster (:mod:`.distributed`); every
  outcome is cached as it arrives, so an interrupted run keeps what finished
  (:mod:`.runner`).  Each check has a time *budget* (``DEFAULT_BUDGET`` = 300 s,
  deep variants too): past it the check is stopped and reported ``inconclusive
  (timed out after 300 s)``, uncached, and the run goes on; a worker that dies
  under a check gives a ``failed`` outcome naming the cause.  Workers die with
  the process that started them, even when it is killed with SIGKILL.
* When every selected claim is cached and no source file changed, the results
  are read without importing the claim modules, SymPy, NumPy or mpmath (:mod:`.warm`).
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._lazy import lazy_attributes

if TYPE_CHECKING:
    from ..claims.base import ClaimResult
    from .runner import Progress

from .select import choose, default_scenes, select  # cheap (claim metadata only); binds over the submodule

# the rest loads on first use: the warm path (symbt verify with everything cached) imports only .warm
_LAZY = {
    "run": ".runner", "Interrupted": ".runner", "refresh_manifest": ".runner", "keep_workers": ".runner",
    "KeptWorkers": ".runner", "DEFAULT_BUDGET": ".task",
    "cache_dir": ".cache", "cache_file": ".cache", "claim_key": ".cache",
    "Project": ".project", "ConfigError": ".project", "discover": ".project", "load": ".project",
    "cached_results": ".warm", "Walkthrough": ".walkthrough", "ClaimResult": "..claims.base",
}

__all__ = ["verify", "select", "choose", "default_scenes", *_LAZY]


__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, __all__)


# budget's default is task.DEFAULT_BUDGET, written out: importing .task here would load the claims' base early
def verify(scenes: Sequence[str] | None = None, *, deep: bool = False, use_cache: bool = True,
           jobs: int = 1, progress: Progress | None = None, dask: str | bool | None = None,
           claims: Sequence[str] = (), labels: Sequence[str] = (), budget: float | None = 300.0) -> list[ClaimResult]:
    """Select and run claims; the Python entry point behind ``symbt verify``.

    ``scenes`` are scene names, lattice sizes (``"n2"``) or claim ids (``None``:
    every default scene); ``deep`` adds the minutes-long claims and runs every
    claim's deep variant (64 instead of 16 samples per domain cell); ``jobs``
    worker processes; ``dask`` runs uncached claims on a Dask cluster (``True``:
    a local one, or a scheduler address).  ``claims`` are claims sources (module names
    or paths, as ``--claims``; default: ``[tool.symbt]`` of the working directory, else
    Zullo's paper) and ``labels`` keeps the claims of those paper labels.  Returns one
    :class:`ClaimResult` per claim, in the paper's order.  Unknown names raise
    ``KeyError``; ``jobs`` below 1 raises ``ValueError``; a claims source that does not
    import, :class:`~symbt.engine.project.ConfigError`.  ``budget`` is the seconds each check may
    take (``None``: no limit), past which it is ``inconclusive (timed out)``; a budget
    that is not a positive number raises ``ValueError``.

    >>> import symbt
    >>> [r.status for r in symbt.verify(["tn2"], use_cache=False)]
    ['verified']
    """
    from .project import discover
    from .runner import run
    from .task import check_budget
    from .warm import cached_results

    check_budget(budget)
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs must be a positive integer, not {jobs!r}")
    project = discover(claims=claims)
    if use_cache and dask is None and progress is None:
        warm = cached_results(scenes, deep=deep, project=project, labels=labels)
        if warm is not None:
            return warm
    return run(select(scenes, include_deep=deep, project=project, labels=labels), use_cache=use_cache, jobs=jobs,
               progress=progress, dask=dask, deep=deep, budget=budget)
