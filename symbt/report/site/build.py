"""Write the site: the summary and the annotated paper, a page per label, the graph, every claim."""
from __future__ import annotations

import html
import re
from collections import Counter
from pathlib import Path
from typing import Any

from ..._files import atomic_write
from .graph import graph_svg
from .mathml import inline_parts, macros_of, to_mathml
from .model import Display, Site, status_text
from .pages import CSS, badge, claim_card, page, slug

__all__ = ["build_site"]

_e = html.escape


def _href(label: str) -> str:
    return f"label-{slug(label)}.html"


class _Writer:
    def __init__(self, site: Site, out: Path, macros: dict[str, tuple[int, str]], prefer_graphviz: bool):
        self.site, self.out, self.macros, self.prefer_graphviz = site, out, macros, prefer_graphviz
        self.engine = "none"
        self.mathml: dict[str, bool] = {}

    def link_of(self, name: str) -> str | None:
        s = self.site
        if name in s.claims:
            return f"{_href(s.claims[name]['equation'])}#claim-{slug(name)}"
        return _href(name) if name in s.by_label else None

    def _link(self, name: str) -> str:
        href = self.link_of(name)
        return f'<a href="{_e(href)}">{_e(name)}</a>' if href else _e(name)

    def math(self, d: Display) -> str:
        if d.kind == "equation" and d.source:
            m = to_mathml(d.source, self.macros)
            self.mathml[d.label] = m is not None
            if m is not None:
                return f'<div class="math">{m}</div>'
            return f'<div class="source" title="not converted to MathML">{_e(d.source)}</div>'
        if d.source and d.kind == "theorem":
            return f'<div class="prose">{self.prose(d.source)}</div>'
        if d.source:
            return f'<div class="source">{_e(d.source)}</div>'
        return '<p class="muted">(no source: the paper\'s .tex was not given)</p>' if d.in_paper else ""

    def prose(self, text: str) -> str:
        """A theorem's text: inline math as MathML, references as links, the rest escaped."""
        out = []
        for kind, piece in inline_parts(text):
            if kind == "math":
                m = to_mathml(piece, self.macros, display="inline")
                out.append(m if m is not None else f"<code>{_e(piece)}</code>")
            elif kind == "display":
                m = to_mathml(piece, self.macros)
                out.append(f'<span class="math">{m}</span>' if m is not None else
                           f'<span class="source">{_e(piece.strip())}</span>')
            elif kind == "ref":
                out.append(self._link(piece))
            else:
                piece = re.sub(r"\\(?:emph|textbf|textit|textrm|textsf)\{([^{}]*)\}", r"\1", piece)
                out.append(_e(re.sub(r"\s+", " ", piece)))
        return "".join(out)

    def display_block(self, d: Display, *, link: bool = True) -> str:
        s = self.site
        status = s.status(d.label)
        name = f'<a class="label" href="{_href(d.label)}">{_e(d.label)}</a>' if link else \
            f'<span class="label">{_e(d.label)}</span>'
        evidence = sorted({str(s.claims[c].get("evidence")) for c in d.claims if s.claims[c].get("evidence")})
        claims = ", ".join(self._link(c) for c in d.claims)
        meta = [f'<span class="muted">{_e(d.kind)}{" (" + _e(d.tag) + ")" if d.tag else ""}</span>']
        if evidence:
            meta.append(f'<span class="muted">evidence: {_e(", ".join(evidence))}</span>')
        if claims:
            meta.append(f'<span class="muted">claims: {claims}</span>')
        elif d.reason:
            meta.append(f'<span class="muted">no claim: {_e(d.reason)}</span>')
        return (f'<article class="display" id="d-{_e(slug(d.label))}" data-label="{_e(d.label)}" '
                f'data-status="{_e(status)}"><header>{name} {badge(status, s.problems(d.label))} '
                f'{" ".join(meta)}</header>{self.math(d)}</article>')

    # ------------------------------------------------------------------ pages
    def write(self, name: str, text: str) -> None:
        atomic_write(self.out / name, text)

    def graph(self, keys: list[str] | None, *, with_claims: bool = False) -> str:
        s = self.site
        keys = keys if keys is not None else s.label_nodes()
        wanted = set(keys)
        nodes = []
        for key in keys:
            name = key[2:]
            if key.startswith("L:"):
                d = s.by_label[name]
                nodes.append((key, name, s.status(name), _href(name), f"§ {d.section}" if d.section else "unlabelled"))
            elif with_claims:
                nodes.append((key, name, s.status(name), self.link_of(name) or "", "claims"))
        edges = [(a, b) for a in wanted for b in sorted(s.edges.get(a, ())) if b in wanted]
        if with_claims:   # a label's status is its claims': draw what decides it
            edges += [(k, "C:" + c) for k in wanted if k.startswith("L:") for c in s.by_label[k[2:]].claims
                      if "C:" + c in wanted]
        svg, self.engine = graph_svg(nodes, sorted(edges), prefer_graphviz=self.prefer_graphviz)
        return f'<div class="graph">{svg}</div>'

    def label_page(self, d: Display) -> None:
        s = self.site
        key = "L:" + d.label
        up, down = s.ancestors(key), s.descendants(key)
        sub = [key] + [n for n in down + up if n.startswith("L:")] + ["C:" + c for c in d.claims]
        uses = ", ".join(self._link(n[2:]) for n in down if n.startswith("L:")) or "nothing"
        used_by = ", ".join(self._link(n[2:]) for n in up if n.startswith("L:")) or "nothing"
        cards = "".join(claim_card(s.claims[c], s.status(c), s.problems(c), self.link_of) for c in d.claims)
        where = f"section {d.section}" if d.section else "a statement the paper prints without a label"
        body = (f"<h1>{_e(d.label)}</h1><p class=\"muted\">{_e(d.kind)} in {_e(where)}</p>"
                f"{self.display_block(d, link=False)}<p>uses: {uses}<br>used by: {used_by}</p>"
                f"<h2>Claims</h2>{cards or '<p>none</p>'}"
                f"<h2>Dependencies</h2>{self.graph(list(dict.fromkeys(sub)), with_claims=True)}")
        self.write(_href(d.label), page(f"{d.label} -- symbt report", body))

    def index(self, mutate: dict[str, Any] | None, paper: str | None) -> None:
        s, doc = self.site, self.site.doc
        claims = list(s.claims.values())
        by_status = Counter(c["status"] for c in claims)
        by_evidence = Counter(str(c.get("evidence") or "none") for c in claims)
        papers = [d for d in s.displays if d.in_paper and d.kind in ("equation", "figure")]
        cover = Counter(s.own(d.label) if s.own(d.label) in ("reason", "uncovered", "todo") else "claims"
                        for d in papers)
        depends = sum(1 for d in s.displays if s.status(d.label) == "depends")
        run = doc.get("run") or {}
        libs = ", ".join(f"{k} {v}" for k, v in (run.get("libraries") or {}).items())
        counts = "".join(f"<div>{badge(k)} {v}</div>" for k, v in sorted(by_status.items()))
        parts = [f"<h1>symbt report{(': ' + _e(Path(paper).name)) if paper else ''}</h1>",
                 f'<div class="counts" id="counts">{counts}<div>{len(claims)} claims</div></div>',
                 "<h2>Summary</h2><table>",
                 f"<tr><th>evidence</th><td>{_e(', '.join(f'{k}: {v}' for k, v in sorted(by_evidence.items())))}"
                 "</td></tr>",
                 f"<tr><th>coverage</th><td>{len(papers)} displays: {cover['claims']} with claims, "
                 f"{cover['reason']} with a reason, {cover['todo']} todo, {cover['uncovered']} uncovered</td></tr>",
                 f"<tr><th>propagation</th><td>{depends} labels verified but depending on an erratum or an "
                 "open claim</td></tr>"]
        if mutate:
            m = mutate.get("summary", mutate)
            parts.append(f"<tr><th>mutation score</th><td id=\"mutation\">{_e(str(m.get('score')))} "
                         f"({_e(str(m.get('mutants')))} mutants, {_e(str(m.get('killed')))} killed, "
                         f"{_e(str(m.get('equivalent')))} equivalent, {_e(str(m.get('survivors')))} "
                         "survivors)</td></tr>")
        parts += [f"<tr><th>run</th><td>{_e(str(run.get('date', 'date not recorded')))}, "
                  f"{_e(str(doc.get('generator', '')))}, {_e(str(doc.get('summary', {}).get('seconds', '')))} s</td>"
                  "</tr>",
                  f"<tr><th>machine</th><td>{_e(str(run.get('platform', '-')))}, {_e(str(run.get('cpus', '-')))} "
                  f"cores, Python {_e(str(run.get('python', '-')))}</td></tr>",
                  f"<tr><th>libraries</th><td>{_e(libs or '-')}</td></tr></table>",
                  "<h2>The paper, annotated</h2>"]
        for d in s.displays:
            if d.kind == "section":
                title = d.source.replace("\\&", "&").replace("~", " ")   # the heading's TeX escapes
                parts.append(f"<h3>{_e(d.section)} {_e(title)}</h3>")
            elif d.in_paper:
                parts.append(self.display_block(d))
        extra = [d for d in s.displays if not d.in_paper]
        if extra:
            parts.append("<h2>Claims on unlabelled statements</h2>")
            parts += [self.display_block(d) for d in extra]
        self.write("index.html", page("symbt report", "".join(parts)))

    def claims_page(self) -> None:
        s = self.site
        rows = "".join(f"<tr data-claim=\"{_e(cid)}\"><td>{self._link(cid)}</td><td>{self._link(c['equation'])}</td>"
                       f"<td>{badge(s.status(cid), s.problems(cid))}</td><td>{_e(str(c.get('evidence') or '-'))}</td>"
                       f"<td>{_e(str(c.get('seconds', '')))}</td></tr>" for cid, c in s.claims.items())
        body = ("<h1>All claims</h1><table id=\"claims\"><tr><th>claim</th><th>label</th><th>status</th>"
                f"<th>evidence</th><th>seconds</th></tr>{rows}</table>")
        self.write("claims.html", page("all claims -- symbt report", body))


def build_site(doc: dict[str, Any], labels: list[Any], out: str | Path, *, tex: str | None = None,
               mutate: dict[str, Any] | None = None, paper: str | None = None,
               prefer_graphviz: bool = True) -> dict[str, Any]:
    """Write the site for a verify JSON ``doc`` and the paper's ``labels`` into the directory ``out``.

    ``tex`` (the paper's source) supplies its macros to the MathML conversion; ``mutate`` is a
    ``symbt mutate --json`` document.  Returns ``{"pages": n, "graph": "graphviz" | "fallback",
    "mathml": {label: converted}, "site": Site}``.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    site = Site.from_report(doc, labels)
    w = _Writer(site, out, macros_of(tex) if tex else {}, prefer_graphviz)
    w.write("style.css", CSS)
    w.index(mutate, paper)
    pages = 2
    for d in site.displays:
        if d.kind != "section":
            w.label_page(d)
            pages += 1
    w.claims_page()
    legend = " ".join(badge(k) for k in ("verified", "depends", "erratum", "failed", "inconclusive", "todo",
                                         "reason", "uncovered", "statement"))
    w.write("graph.html", page("dependency graph -- symbt report",
                               "<h1>Dependency graph</h1><p>An arrow goes from a label to the labels it uses "
                               f"(its display's references, its claims' <code>uses</code>). {legend}</p>"
                               + w.graph(None)))
    pages += 1
    return {"pages": pages, "graph": w.engine, "mathml": w.mathml, "site": site,
            "statuses": {d.label: status_text(site.status(d.label)) for d in site.displays}}
