"""Running claims: cached outcomes are reused, the rest run in a process pool."""
from __future__ import annotations

import sys
from concurrent.futures import ProcessPoolExecutor

from ..claims import REGISTRY, load_all
from ..claims.base import Claim, ClaimResult, Outcome
from .cache import load_cached, store

__all__ = ["run"]


def _run_one(claim_id: str) -> dict:
    load_all()
    return REGISTRY[claim_id].run().to_dict()


def run(claims: list[Claim], *, use_cache: bool = True, jobs: int = 1, progress=None) -> list[ClaimResult]:
    """Run ``claims`` (cached results reused), optionally in ``jobs`` processes."""
    results: dict[str, Outcome] = {}
    todo = []
    for c in claims:
        out = load_cached(c) if use_cache else None
        if out is not None:
            results[c.id] = out
            if progress:
                progress(c, out)
        else:
            todo.append(c)
    if jobs > 1 and len(todo) > 1:
        import multiprocessing as mp_

        ctx = mp_.get_context("fork") if sys.platform != "win32" else None
        with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
            # longest-first keeps both workers busy; N=3 derivations dominate
            ordered = sorted(todo, key=lambda c: -(c.N or 0))
            futs = {c.id: pool.submit(_run_one, c.id) for c in ordered}
            for c in ordered:
                out = Outcome.from_dict(futs[c.id].result())
                results[c.id] = out
                store(c, out)
                if progress:
                    progress(c, out)
    else:
        for c in todo:
            out = c.run()
            results[c.id] = out
            store(c, out)
            if progress:
                progress(c, out)
    return [ClaimResult(c, results[c.id]) for c in claims]
