"""The unit of work shipped to a worker process or a Dask worker: one claim, by id."""
from __future__ import annotations

__all__ = ["run_claim"]


def run_claim(claim_id: str, deep: bool = False) -> dict:
    """Run one registered claim (loading the claim modules once per worker); its outcome as a dict.

    Plain data in and out, so it pickles to any worker.
    """
    from ..claims import REGISTRY, load_all

    if claim_id not in REGISTRY:  # a forked worker has the parent's registry already
        load_all()
    return REGISTRY[claim_id].run(deep=deep).to_dict()
