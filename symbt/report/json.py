"""The JSON report (``symbt verify --json FILE``).

Schema::

    {"claims": [{"id", "equation", "scene", "N", "statement", "where",
                 "status", "method", "seconds", "residual", "digits",
                 "printed", "corrected", "counterexample", "detail", "cached"}, ...],
     "summary": {"total", "verified", "erratum", "failed", "skipped",
                 "seconds", "ok"}}
"""
from __future__ import annotations

import json

from .._files import atomic_write
from .text import summary

__all__ = ["to_json", "write_json"]


def to_json(results) -> dict:
    return {"claims": [r.to_dict() for r in results], "summary": summary(results)}


def write_json(results, path) -> None:
    atomic_write(path, json.dumps(to_json(results), indent=2, default=str) + "\n")
