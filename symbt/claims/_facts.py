"""Claims decided by a list of facts: ``(what, got, want)`` triples, each compared with ``==``.

The checker's small rules (scene ``checker``) are checked this way: the code's answer next to one known
independently.

>>> facts_failed("here", [("1 + 1", 2, 2)]) is None
True
>>> facts_failed("here", [("1 + 1", 3, 2)]).detail
'1 + 1: got 3, want 2'
"""
from __future__ import annotations

from typing import Any

from .base import Evidence, Outcome, failed

__all__ = ["Facts", "facts_failed", "facts_verified"]

#: (what is checked, the code's answer, the answer known independently)
Facts = list[tuple[str, Any, Any]]


def facts_failed(where: str, got: Facts) -> Outcome | None:
    """A failed outcome naming every fact whose answer differs from the known one; ``None`` if none does."""
    wrong = [(what, g, want) for what, g, want in got if g != want]
    if not wrong:
        return None
    return failed(where, detail="; ".join(f"{w}: got {g!r}, want {v!r}" for w, g, v in wrong))


def facts_verified(method: str, detail: str, evidence: Evidence) -> Outcome:
    """A verified outcome of a rule that holds for every size (``n_scope="all"``)."""
    return Outcome("verified", method, evidence=evidence, detail=detail, n_scope="all")
