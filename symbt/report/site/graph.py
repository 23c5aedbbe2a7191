"""The dependency graph as SVG: Graphviz (``dot``) when installed, else a simple layered layout drawn here.

Nodes are coloured by their propagated status and link to their page; a section is a column
(the paper's reading order top to bottom), an arrow goes from a node to what it uses.  Without
the ``graphviz`` Python binding or Debian's ``graphviz`` (the ``dot`` program) the fallback draws
the same columns itself -- less tidy edges, same nodes, colours and links -- so a report never
needs Graphviz to exist.

>>> svg, engine = graph_svg([("L:a", "a", "verified", "a.html", "§ 1"), ("L:b", "b", "erratum", "b.html", "§ 1")],
...                         [("L:a", "L:b")], prefer_graphviz=False)
>>> engine, svg.startswith("<svg") and 'href="a.html"' in svg
('fallback', True)
"""
from __future__ import annotations

import html
import re

__all__ = ["graph_svg", "COLOURS"]

#: fill colours of the (propagated) statuses, shared with the pages' badges
COLOURS = {"verified": "#2e7d32", "depends": "#9e9d24", "erratum": "#b26a00", "failed": "#c62828",
           "inconclusive": "#6a1b9a", "todo": "#546e7a", "skipped": "#9e9e9e", "reason": "#bdbdbd",
           "uncovered": "#212121", "statement": "#e0e0e0"}
_DARK_TEXT = ("reason", "statement")

Node = tuple[str, str, str, str, str]   # key, text, status, href, column (its heading, e.g. "§ 2")


def _graphviz(nodes: list[Node], edges: list[tuple[str, str]]) -> str | None:
    try:
        import graphviz
    except ImportError:
        return None
    g = graphviz.Digraph("uses", graph_attr={"rankdir": "TB", "newrank": "true", "nodesep": "0.15",
                                              "ranksep": "0.25", "fontname": "Helvetica", "bgcolor": "transparent"},
                         node_attr={"shape": "box", "style": "rounded,filled", "fontname": "Helvetica",
                                    "fontsize": "11", "height": "0.3", "margin": "0.08,0.03"},
                         edge_attr={"color": "#455a64", "arrowsize": "0.6"})
    columns: dict[str, list[Node]] = {}
    for n in nodes:
        columns.setdefault(n[4], []).append(n)
    ids = {n[0]: f"n{i}" for i, n in enumerate(nodes)}
    for i, (column, members) in enumerate(columns.items()):
        with g.subgraph(name=f"cluster_{i}") as sub:
            sub.attr(label=column, color="#cfd8dc", fontsize="11")
            for key, text, status, href, _col in members:
                sub.node(ids[key], label=text, fillcolor=COLOURS.get(status, "#777"), URL=href, target="_top",
                         tooltip=f"{text}: {status}", fontcolor="black" if status in _DARK_TEXT else "white")
            for above, below in zip(members, members[1:]):   # keep a section's labels in reading order, top to bottom
                sub.edge(ids[above[0]], ids[below[0]], style="invis")
    for a, b in edges:
        if a in ids and b in ids:
            g.edge(ids[a], ids[b], constraint="false")
    try:
        svg = g.pipe(format="svg", encoding="utf-8")
    except (graphviz.ExecutableNotFound, graphviz.CalledProcessError, OSError):
        return None
    svg = svg[svg.index("<svg"):]
    return re.sub(r"<!--.*?-->\n?", "", svg, flags=re.S)


def _fallback(nodes: list[Node], edges: list[tuple[str, str]]) -> str:
    columns: dict[str, list[Node]] = {}
    for n in nodes:
        columns.setdefault(n[4], []).append(n)
    w, h, gap_x, gap_y = 120, 22, 30, 8
    pos: dict[str, tuple[float, float]] = {}
    parts = []
    for i, (column, members) in enumerate(columns.items()):
        x = 10 + i * (w + gap_x)
        parts.append(f'<text x="{x}" y="14" font-size="11" fill="#455a64">'
                     f'{html.escape(column)}</text>')
        for j, (key, text, status, href, _col) in enumerate(members):
            y = 24 + j * (h + gap_y)
            pos[key] = (x, y)
            fg = "black" if status in _DARK_TEXT else "white"
            parts.append(f'<a href="{html.escape(href)}"><title>{html.escape(f"{text}: {status}")}</title>'
                         f'<rect x="{x}" y="{y}" width="{w}" height="{h}" rx="5" '
                         f'fill="{COLOURS.get(status, "#777")}"/><text x="{x + w / 2}" y="{y + 15}" '
                         f'text-anchor="middle" font-size="11" fill="{fg}">{html.escape(text[:18])}</text></a>')
    lines = []
    for a, b in edges:
        if a in pos and b in pos:
            (xa, ya), (xb, yb) = pos[a], pos[b]
            lines.append(f'<line x1="{xa + w / 2}" y1="{ya + h / 2}" x2="{xb + w / 2}" y2="{yb + h / 2}" '
                         'stroke="#455a64" stroke-width="1.2" marker-end="url(#arrow)"/>')
    width = 20 + len(columns) * (w + gap_x)
    height = 40 + max((len(m) for m in columns.values()), default=0) * (h + gap_y)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
            f'viewBox="0 0 {width} {height}"><defs><marker id="arrow" viewBox="0 0 10 10" refX="10" refY="5" '
            'markerWidth="6" markerHeight="6" orient="auto"><path d="M0,0 L10,5 L0,10 z" fill="#455a64"/></marker>'
            '</defs>' + "".join(parts) + "".join(lines) + "</svg>")


def graph_svg(nodes: list[Node], edges: list[tuple[str, str]], *, prefer_graphviz: bool = True) -> tuple[str, str]:
    """``(svg, engine)``: the graph laid out by Graphviz (``engine == "graphviz"``) or by the fallback.

    ``nodes`` are ``(key, text, status, href, column)``; ``edges`` ``(user, used)`` pairs of keys.
    """
    if prefer_graphviz:
        svg = _graphviz(nodes, edges)
        if svg is not None:
            return svg, "graphviz"
    return _fallback(nodes, edges), "fallback"
