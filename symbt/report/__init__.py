"""Reports of claim results: terminal text, progress, JSON, JUnit XML, Markdown, HTML for Jupyter, figures.

Reporters only *read* results (claim metadata + :class:`~symbt.claims.Outcome`) and
tolerate missing values; every file is written with the one atomic writer
:func:`symbt._files.atomic_write`.  The names load on first use.
"""
from __future__ import annotations

from .._lazy import lazy_attributes

_LAZY = {
    "summary": ".text", "summary_lines": ".text", "format_short": ".text", "format_table": ".text",
    "residual_text": ".text", "short_method": ".text", "evidence_text": ".text", "result_text": ".text",
    "to_json": ".json", "write_json": ".json", "emit_document": ".json", "schema": ".json", "SCHEMA_VERSION": ".json",
    "write_junit": ".junit", "junit_xml": ".junit", "xml_safe": ".junit",
    "format_markdown": ".markdown",
    "result_html": ".html", "result_latex": ".html", "scene_html": ".html",
    "Progress": ".progress",
}

__all__ = list(_LAZY)


__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, __all__)
