"""Reports of claim results: terminal text, progress, JSON, JUnit XML, Markdown, HTML for Jupyter, figures.

Reporters only *read* results (claim metadata + :class:`~symbt.claims.Outcome`) and
tolerate missing values; every file is written with the one atomic writer
:func:`symbt._files.atomic_write`.  The names load on first use.
"""
from __future__ import annotations

import importlib
from typing import Any

_LAZY = {
    "summary": ".text", "summary_lines": ".text", "format_short": ".text", "format_table": ".text",
    "residual_text": ".text", "short_method": ".text", "evidence_text": ".text", "result_text": ".text",
    "to_json": ".json", "write_json": ".json", "schema": ".json", "SCHEMA_VERSION": ".json",
    "write_junit": ".junit", "junit_xml": ".junit", "xml_safe": ".junit",
    "format_markdown": ".markdown",
    "result_html": ".html", "result_latex": ".html", "scene_html": ".html",
    "Progress": ".progress",
}

__all__ = list(_LAZY)


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name], __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)
