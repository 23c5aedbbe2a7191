"""Reports of claim results: terminal text, JSON, JUnit XML, Markdown, HTML for Jupyter, figures.

Reporters only *read* results (claim metadata + :class:`~symbt.claims.Outcome`); every file
is written with the one atomic writer :func:`symbt._files.atomic_write`.
"""
from __future__ import annotations

from .html import result_html, result_latex, scene_html
from .json import to_json, write_json
from .junit import write_junit
from .markdown import format_markdown
from .text import format_table, residual_text, result_text, short_method, summary

__all__ = ["summary", "format_table", "residual_text", "short_method", "result_text", "to_json", "write_json",
           "write_junit", "format_markdown", "result_html", "result_latex", "scene_html"]
