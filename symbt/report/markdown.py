"""A Markdown table of claim results (the claims table of the documentation, docs/claims.md)."""
from __future__ import annotations

from collections.abc import Sequence

from .text import evidence_text, residual_text, short_method
from .views import ResultView

__all__ = ["format_markdown"]


def format_markdown(results: Sequence[ResultView]) -> str:
    """A Markdown table of the results (the claims table of docs/claims.md, generated when the site is built).

    >>> from symbt.claims.base import Claim, ClaimResult, Outcome
    >>> r = ClaimResult(Claim("t", "a|b", "s", check=None), Outcome("verified", "exact", 0.0, evidence="proof"))
    >>> print(format_markdown([r]).splitlines()[-1])
    | `t` | `a\\|b` | verified | proof | exact | 0 (exact) |
    """
    lines = ["| claim | equation | status | evidence | method | residual |", "|---|---|---|---|---|---|"]
    for r in results:
        o = r.outcome
        eq = r.claim.equation.replace("|", "\\|")
        lines.append(f"| `{r.claim.id}` | `{eq}` | {o.status} | {evidence_text(o)} | "
                     f"{short_method(o.method).replace('|', '/')} | {residual_text(o)} |")
    return "\n".join(lines) + "\n"
