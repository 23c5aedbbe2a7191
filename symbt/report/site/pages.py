"""HTML fragments of the site: page shell, badges, claim cards, cell grids.  Everything from claims is escaped.

>>> badge("erratum")
'<span class="badge s-erratum">erratum</span>'
>>> "&lt;b&gt;" in claim_card({"id": "<b>", "equation": "e", "status": "verified", "statement": "s"}, "verified", [])
True
"""
from __future__ import annotations

import html
import re
from typing import Any

from .graph import COLOURS
from .model import status_text

__all__ = ["page", "badge", "claim_card", "cell_grid", "slug", "CSS"]

_e = html.escape

CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Helvetica,Arial,sans-serif;margin:0;color:#212121;
 background:#fafafa;line-height:1.45}
nav{background:#263238;padding:.5em 1.2em}nav a{color:#eceff1;margin-right:1.2em;text-decoration:none}
main{max-width:70em;margin:0 auto;padding:1em 1.5em 3em}
h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #cfd8dc;padding-bottom:.2em;margin-top:1.6em}
.badge{display:inline-block;padding:0 .5em;border-radius:4px;color:#fff;font-weight:600;font-size:.85em;
 white-space:nowrap}
.s-reason,.s-statement{color:#212121}.s-depends{border:2px dashed #33691e}
.display{background:#fff;border:1px solid #e0e0e0;border-radius:6px;padding:.4em 1em;margin:.6em 0}
.display header{display:flex;gap:.8em;align-items:baseline;flex-wrap:wrap}
.display header a.label{font-weight:600;font-family:ui-monospace,monospace}
.math{overflow-x:auto;overflow-y:hidden;padding:.2em 0}
.source{white-space:pre-wrap;font-family:ui-monospace,monospace;font-size:.85em;
 background:#f5f5f5;padding:.3em .5em;border-radius:4px}
.prose{padding:.2em 0;font-style:italic}
.muted{color:#607d8b;font-size:.9em}.card{background:#fff;border:1px solid #e0e0e0;border-left:6px solid #999;
 border-radius:6px;padding:.5em 1em;margin:1em 0}
.card dl{display:grid;grid-template-columns:9em 1fr;gap:.2em .8em;margin:.4em 0}.card dt{color:#546e7a}
.card dd{margin:0;overflow-wrap:anywhere}
table{border-collapse:collapse}td,th{padding:.15em .6em;border-bottom:1px solid #eceff1;text-align:left}
table.cells th{white-space:nowrap}
table.cells td.c{width:5.5em;text-align:center;color:#fff;font-size:.85em;border:2px solid #fff}
.holds{background:#2e7d32}.fails{background:#c62828}.partly{background:#b26a00}.none{background:#bdbdbd}
.counts{display:flex;gap:1.5em;flex-wrap:wrap}.counts div{background:#fff;border:1px solid #e0e0e0;
 border-radius:6px;padding:.5em 1em}.graph{overflow:auto;background:#fff;border:1px solid #e0e0e0;
 border-radius:6px;padding:.5em}.graph svg{max-width:none}
"""
CSS += "".join(f".s-{s}{{background:{c}}}" for s, c in COLOURS.items())
CSS += "".join(f".card.k-{s}{{border-left-color:{c}}}" for s, c in COLOURS.items())


def slug(label: str) -> str:
    """A file-system-safe, unique name for a label's page.

    >>> slug("eq:lax"), slug("fig:1"), slug("a b")
    ('eq_3alax', 'fig_3a1', 'a_20b')
    """
    return re.sub(r"[^A-Za-z0-9-]", lambda m: f"_{ord(m.group()):x}", label)


def page(title: str, body: str) -> str:
    """A complete HTML5 page with the site's navigation."""
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
            f"<title>{_e(title)}</title><link rel=\"stylesheet\" href=\"style.css\"></head><body>"
            "<nav><a href=\"index.html\">summary &amp; paper</a><a href=\"graph.html\">dependency graph</a>"
            "<a href=\"claims.html\">all claims</a></nav>"
            f"<main>{body}</main></body></html>\n")


def badge(status: str, problems: list[str] | None = None) -> str:
    """A status badge; ``depends`` lists what it depends on."""
    text = status_text(status)
    if status == "depends" and problems:
        shown = ", ".join(problems[:4]) + (f" (+{len(problems) - 4})" if len(problems) > 4 else "")
        text = f"{text} {shown}"
    return f'<span class="badge s-{_e(status)}">{_e(text)}</span>'


def _cell_name(cell: Any) -> str:
    if isinstance(cell, dict):
        return ", ".join(f"{k}={v:+d}" if isinstance(v, int) and not isinstance(v, bool) else f"{k}={v}"
                         for k, v in cell.items()) or "all"
    return str(cell)


def _grid_td(holds: Any, n: Any) -> str:
    if not isinstance(holds, int) or not isinstance(n, int) or n == 0:
        return '<td class="c none">-</td>'
    kind = "holds" if holds == n else ("fails" if holds == 0 else "partly")
    return f'<td class="c {kind}" title="{kind}">{holds}/{n}</td>'


def cell_grid(cells: list[dict[str, Any]]) -> str:
    """The cell table as a small coloured grid: one row per cell, printed / corrected x holds / fails."""
    if not cells:
        return ""
    corrected = any("corrected_holds" in c for c in cells)
    head = "<tr><th>cell</th><th>n</th><th>printed</th>" + ("<th>corrected</th>" if corrected else "") + "</tr>"
    rows = []
    for c in cells:
        n = c.get("n")
        holds = c.get("printed_holds", c.get("holds"))
        row = f"<tr><td>{_e(_cell_name(c.get('cell')))}</td><td>{_e(str(n))}</td>{_grid_td(holds, n)}"
        if corrected:
            row += _grid_td(c.get("corrected_holds"), n)
        rows.append(row + "</tr>")
    return f'<table class="cells">{head}{"".join(rows)}</table>'


def _value(v: Any) -> str:
    if isinstance(v, dict):
        return "<br>".join(f"{_e(str(k))} = {_e(str(x))}" for k, x in v.items())
    if isinstance(v, list):
        return _e(", ".join(str(x) for x in v))
    return _e(str(v))


def claim_card(c: dict[str, Any], status: str, problems: list[str], link_of: Any = None) -> str:
    """One claim: statement, printed vs corrected, counterexample, residual, cells, scope, method, time, n_scope."""
    rows = [("statement", _e(c.get("statement") or ""))]
    for key in ("where", "printed", "corrected"):
        if c.get(key):
            rows.append((key, _e(str(c[key]))))
    if c.get("counterexample"):
        rows.append(("counterexample", _value(c["counterexample"])))
    if c.get("residual") is not None:
        digits = f" ({c['digits']} digits)" if c.get("digits") is not None else ""
        rows.append(("residual", _e(f"{c['residual']}{digits}")))
    if c.get("cells"):
        rows.append(("cells", cell_grid(c["cells"])))
    if c.get("scope"):
        rows.append(("scope", _e(c["scope"])))
    rows.append(("evidence", _e(str(c.get("evidence") or "-"))))
    for key in ("method", "detail"):
        if c.get(key):
            rows.append((key, _e(str(c[key]))))
    rows.append(("time", _e(f"{c.get('seconds', 0)} s" + (" (cached)" if c.get("cached") else ""))))
    rows.append(("n_scope", _value(c.get("n_scope") if c.get("n_scope") is not None else "-")))
    if c.get("uses"):
        uses = [(f'<a href="{_e(link_of(u))}">{_e(u)}</a>' if link_of and link_of(u) else _e(u)) for u in c["uses"]]
        rows.append(("uses", ", ".join(uses)))
    body = "".join(f"<dt>{k}</dt><dd>{v}</dd>" for k, v in rows)
    return (f'<section class="card k-{_e(status)}" id="claim-{_e(slug(str(c["id"])))}">'
            f'<h3><code>{_e(str(c["id"]))}</code> {badge(status, problems)}</h3><dl>{body}</dl></section>')
