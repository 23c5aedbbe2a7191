r"""Rich display of claim results in Jupyter (HTML and LaTeX).

:class:`symbt.claims.base.ClaimResult` delegates ``_repr_html_`` and
``_repr_latex_`` to :func:`result_html` and :func:`result_latex`; a list of
results renders as a table with :func:`scene_html`.  Everything printed from
claims (statements, methods, counterexamples) is escaped.

>>> from symbt.claims.base import Claim, ClaimResult, Outcome
>>> c = Claim("demo", "eq:demo", "a < b & c", check=lambda: None)
>>> "a &lt; b &amp; c" in result_html(ClaimResult(c, Outcome("verified", "exact")))
True
"""
from __future__ import annotations

import html
from collections.abc import Iterable
from typing import Any

from ..proof.verdict import LATEX_COLOURS as _LATEX_COLOURS
from ..proof.verdict import STATUS_COLOURS, latex_text
from .text import outcome_fields, point_text, residual_text, short_method, summary
from .views import OutcomeView, ResultView

__all__ = ["result_html", "result_latex", "scene_html", "latex_text", "STATUS_COLOURS"]

_e = html.escape


def _badge(status: str) -> str:
    colour = STATUS_COLOURS.get(status, "#555")
    return (f"<span class='symbt-status' style='background:{colour};color:white;padding:0 0.45em;"
            f"border-radius:3px;font-weight:bold'>{_e(status)}</span>")


def _residual(out: OutcomeView) -> str:
    try:
        return residual_text(out)
    except Exception:  # pragma: no cover - malformed outcome
        return "-" if out.residual is None else f"{out.residual:.3g}"


_FIELD_HTML = {"corrected": "<b>{}</b>", "counterexample": "<code>{}</code>"}


def _rows(result: ResultView) -> list[tuple[str, str]]:
    """(label, already-escaped HTML) rows describing one result."""
    c, o = result.claim, result.outcome
    rows = [("statement", _e(c.statement))]
    if c.where:
        rows.append(("where", _e(c.where)))
    rows += [(name, _FIELD_HTML.get(name, "{}").format(_e(value))) for name, value in outcome_fields(o, limit=12)]
    rows.append(("method", _e(o.method)))
    res = _residual(o)
    if o.digits is not None and o.status != "verified":
        res += f" ({o.digits:.0f} digits)"
    rows.append(("residual", _e(res)))
    if o.detail:
        detail = o.detail.strip()
        if o.status in ("failed", "inconclusive") and "\n" in detail:
            rows.append(("detail", f"<pre style='white-space:pre-wrap;margin:0'>{_e(detail)}</pre>"))
        else:
            rows.append(("detail", _e(detail)))
    rows.append(("time", _e(f"{o.seconds:.2f} s" + (" (cached)" if getattr(o, "cached", False) else ""))))
    return rows


def result_html(result: ResultView) -> str:
    """One claim result as an HTML card: id, equation label, status, statement, method, residual."""
    c, o = result.claim, result.outcome
    colour = STATUS_COLOURS.get(o.status, "#555")
    n = "" if c.N is None else f" <span style='color:#666'>(N = {int(c.N)})</span>"
    head = (f"<div style='margin-bottom:0.2em'><b><code>{_e(c.id)}</code></b> &nbsp;"
            f"eq. (<code>{_e(c.equation)}</code>){n} &nbsp;{_badge(o.status)}</div>")
    body = "".join(f"<tr><th style='text-align:left;vertical-align:top;padding-right:1em'>{k}</th>"
                   f"<td style='text-align:left'>{v}</td></tr>" for k, v in _rows(result))
    return (f"<div class='symbt-claim symbt-{_e(o.status)}' style='border-left:4px solid {colour};"
            f"padding:0.3em 0.8em;margin:0.4em 0'>{head}<table>{body}</table></div>")


def result_latex(result: ResultView) -> str:
    """One claim result as LaTeX (a MathJax-compatible ``array`` of text lines)."""
    c, o = result.claim, result.outcome
    colour = _LATEX_COLOURS.get(o.status, "black")
    t = latex_text
    lines = [rf"\textbf{{{t(c.id)}}}\ \text{{(eq. {t(c.equation)})}}:\ "
             rf"{{\color{{{colour}}}\textbf{{{t(o.status)}}}}}",
             rf"\text{{{t(c.statement)}}}"]
    lines += [rf"\text{{{name}: {t(value)}}}" for name, value in outcome_fields(o, limit=6)]
    lines.append(rf"\text{{method: {t(o.method)}; residual {t(_residual(o))}}}")
    return r"$\begin{array}{l}" + r"\\ ".join(lines) + r"\end{array}$"


def scene_html(results: Iterable[Any], *, title: str | None = None) -> str:
    """A table of claim results (one row each) with a summary line; errata show both statements."""
    results = list(results)
    head = ("<tr><th>claim</th><th>equation</th><th>status</th><th>method</th>"
            "<th>residual</th><th>statement</th></tr>")
    rows = []
    for r in results:
        c, o = r.claim, r.outcome
        stmt = _e(c.statement)
        if o.status in ("erratum", "failed", "inconclusive"):
            if o.printed:
                stmt += f"<br><i>printed:</i> {_e(o.printed)}"
            if o.corrected:
                stmt += f"<br><i>corrected:</i> <b>{_e(o.corrected)}</b>"
            if o.counterexample:
                stmt += f"<br><i>counterexample:</i> <code>{_e(point_text(o.counterexample, limit=6))}</code>"
        rows.append(f"<tr class='symbt-{_e(o.status)}'><td><code>{_e(c.id)}</code></td>"
                    f"<td><code>{_e(c.equation)}</code></td><td>{_badge(o.status)}</td>"
                    f"<td>{_e(short_method(o.method))}</td><td>{_e(_residual(o))}</td>"
                    f"<td style='text-align:left'>{stmt}</td></tr>")
    s = summary(results)
    extra = "".join(f"{s[k]} {k}, " for k in ("inconclusive", "todo") if s[k])
    foot = (f"<p>{s['total']} claims: {s['verified']} verified, {s['erratum']} erratum, "
            f"{s['failed']} failed, {extra}{s['skipped']} skipped</p>")
    cap = f"<caption>{_e(title)}</caption>" if title else ""
    return (f"<div class='symbt-scene'><table>{cap}<thead>{head}</thead><tbody>{''.join(rows)}"
            f"</tbody></table>{foot}</div>")
