"""Running claims: scene selection, on-disk cache, parallel execution.

* A *scene* is a named group of claims (``symbt scenes`` lists them).  Running
  a scene runs only its claims; derivations are built lazily and memoised
  per lattice size (:func:`symbt.symbolic.toda.toda_model`), so an N=2 scene
  never builds an N=3 model, and a symbolic scene never imports scipy.
  Pseudo-scenes ``n2``, ``n3``, ``n4`` select claims by lattice size, and a
  claim id selects itself.
* Results are cached as JSON (no pickle) in ``$SYMBT_CACHE_DIR`` (default
  ``~/.cache/symbt``), one file per claim, keyed by a SHA-256 of the claim's
  id, the source of its module and of the layers below it (``symbt.proof``,
  ``symbt.symbolic``, ``symbt.reference.literal``, ``symbt.numeric``, ``symbt.codegen``, ``symbt.generated``, the
  claims' base and sample modules)
  and the versions of Python, SymPy, mpmath and NumPy.  A corrupt or stale
  entry is recomputed; ``use_cache=False`` forces recomputation.
* Independent claims run in a process pool (``jobs`` workers).
"""
from __future__ import annotations

from ..claims.base import ClaimResult
from .cache import cache_dir, cache_file, claim_key
from .runner import run
from .select import default_scenes, select
from .walkthrough import Walkthrough

__all__ = ["verify", "select", "run", "ClaimResult", "cache_dir", "claim_key", "default_scenes", "Walkthrough"]


def verify(scenes: list[str] | None = None, *, deep: bool = False, use_cache: bool = True,
           jobs: int = 1, progress=None) -> list[ClaimResult]:
    """Select and run claims; the Python entry point behind ``symbt verify``.

    ``scenes`` are scene names, lattice sizes (``"n2"``) or claim ids (``None``:
    every default scene); ``deep`` adds the minutes-long claims; ``jobs``
    worker processes.  Returns one :class:`ClaimResult` per claim, in the
    paper's order.

    >>> import symbt
    >>> [r.status for r in symbt.verify(["tn2"], use_cache=False)]
    ['verified']
    """
    return run(select(scenes, include_deep=deep), use_cache=use_cache, jobs=jobs, progress=progress)
