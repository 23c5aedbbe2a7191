"""A Markdown table of claim results (the README's claim table)."""
from __future__ import annotations

from .text import residual_text, short_method

__all__ = ["format_markdown"]


def format_markdown(results) -> str:
    """A Markdown table of the results (used for the README's claim table)."""
    lines = ["| claim | equation | status | method | residual |", "|---|---|---|---|---|"]
    for r in results:
        o = r.outcome
        eq = r.claim.equation.replace("|", "\\|")
        lines.append(f"| `{r.claim.id}` | `{eq}` | {o.status} | {short_method(o.method)} | {residual_text(o)} |")
    return "\n".join(lines) + "\n"
