r"""The annotated paper as data: labels in reading order, their claims, the dependency graph, propagated statuses.

Built from a verify JSON document (no claim is re-run) and the paper's labels (objects with
``label``, ``section``, ``kind`` and, when read from the ``.tex``, ``source`` and ``refs``).

Dependencies (edges "uses"): a label uses every label its display references (``\eqref``,
``\ref``: the scanner's ``refs``); a claim uses what it declares (``uses``: claim ids or labels)
and what its label's display references; a label uses what its claims declare.

**Status propagation** (the "fully proved" distinction of Lean's blueprint): a node whose own
status is ``verified`` but that uses, transitively, an erratum, a failed, inconclusive or todo
claim, or an uncovered display, is ``depends`` -- "verified, depends on ...", never plain green.

>>> doc = {"claims": [{"id": "a", "equation": "A", "status": "verified", "uses": []},
...                   {"id": "b", "equation": "B", "status": "erratum", "uses": []}]}
>>> class L:  # a scanned label
...     def __init__(self, label, refs=()):
...         self.label, self.section, self.kind, self.refs = label, "1", "equation", refs
>>> site = Site.from_report(doc, [L("A", refs=("B",)), L("B")])
>>> site.status("A"), site.problems("A"), site.status("B")
('depends', ['B'], 'erratum')
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["Display", "Site", "BAD", "STATUS_ORDER", "status_text"]

#: a dependency in one of these (own) statuses makes a verified node "depends"
BAD = ("erratum", "failed", "inconclusive", "todo", "uncovered")
#: the status of a label with several claims: the first of these among them
STATUS_ORDER = ("failed", "inconclusive", "todo", "erratum", "verified", "skipped")


def status_text(status: str) -> str:
    """How a (propagated) status reads on a badge.

    >>> status_text("depends"), status_text("reason")
    ('verified, depends on', 'no claim (reason)')
    """
    return {"depends": "verified, depends on", "reason": "no claim (reason)", "uncovered": "uncovered",
            "statement": "no claim"}.get(status, status)


@dataclass
class Display:
    """One label of the paper: what the site shows for it."""

    label: str
    section: str
    kind: str
    source: str = ""
    refs: tuple[str, ...] = ()
    tag: str | None = None
    claims: list[str] = field(default_factory=list)
    reason: str | None = None
    in_paper: bool = True


def _node(label: str) -> str:
    return "L:" + label


class Site:
    """Labels, claims and the dependency graph of one verify run (see the module docstring)."""

    def __init__(self, displays: list[Display], claims: dict[str, dict[str, Any]], doc: dict[str, Any]):
        self.displays, self.claims, self.doc = displays, claims, doc
        self.by_label = {d.label: d for d in displays}
        self.claim_label = {cid: c["equation"] for cid, c in claims.items()}
        self.edges: dict[str, set[str]] = {}
        self._own: dict[str, str] = {}
        self._problems: dict[str, list[str]] = {}
        self._build()

    @classmethod
    def from_report(cls, doc: dict[str, Any], labels: list[Any]) -> Site:
        """From a verify JSON document and the paper's labels (sections are kept as headings)."""
        claims = {c["id"]: c for c in doc.get("claims", [])}
        coverage = doc.get("coverage") or {}
        displays = [Display(lab.label, str(getattr(lab, "section", "")), getattr(lab, "kind", "equation"),
                            getattr(lab, "source", "") or "", tuple(getattr(lab, "refs", ()) or ()),
                            getattr(lab, "tag", None)) for lab in labels]
        seen = {d.label for d in displays}
        # claims on statements the paper prints without a label: one pseudo-display each, after the paper's
        for c in claims.values():
            if c["equation"] not in seen:
                seen.add(c["equation"])
                displays.append(Display(c["equation"], "", "unlabelled", in_paper=False))
        by_label = {d.label: d for d in displays}
        for cid, c in claims.items():
            by_label[c["equation"]].claims.append(cid)
        for label, entry in coverage.items():
            if label in by_label and "reason" in entry:
                by_label[label].reason = str(entry["reason"])
        return cls(displays, claims, doc)

    # ------------------------------------------------------------------ graph
    def _resolve(self, name: str) -> str | None:
        if name in self.claims:
            return "C:" + name
        if name in self.by_label:
            return _node(name)
        return None

    def _build(self) -> None:
        for d in self.displays:
            self.edges.setdefault(_node(d.label), set()).update(
                _node(r) for r in d.refs if r in self.by_label and r != d.label)
        for cid, c in self.claims.items():
            mine = "C:" + cid
            label_node = _node(c["equation"])
            uses = {n for u in c.get("uses") or [] if (n := self._resolve(u)) is not None}
            uses.discard(mine)
            self.edges.setdefault(mine, set()).update(uses | self.edges.get(label_node, set()))
            self.edges[label_node] |= {n for n in uses if n != label_node and not (
                n.startswith("C:") and self.claim_label.get(n[2:]) == c["equation"])}
        for d in self.displays:
            self._own[_node(d.label)] = self._own_label_status(d)
        for cid, c in self.claims.items():
            self._own["C:" + cid] = c["status"]

    def _own_label_status(self, d: Display) -> str:
        statuses = {self.claims[c]["status"] for c in d.claims}
        for s in STATUS_ORDER:
            if s in statuses:
                return s
        if d.reason is not None:
            return "reason"
        return "uncovered" if d.kind in ("equation", "figure") else "statement"

    def descendants(self, node: str) -> list[str]:
        """Every node ``node`` uses, transitively (not itself), in a stable order."""
        out: dict[str, None] = {}
        stack = sorted(self.edges.get(node, ()))
        while stack:
            n = stack.pop(0)
            if n in out or n == node:
                continue
            out[n] = None
            stack += sorted(self.edges.get(n, ()))
        return list(out)

    def ancestors(self, node: str) -> list[str]:
        """Every node that uses ``node``, transitively."""
        return [n for n in self.edges if n != node and node in self.descendants(n)]

    # ------------------------------------------------------------------ statuses
    def own(self, name: str) -> str:
        """The status of a label (its claims' worst) or a claim, before propagation."""
        return self._own[self._key(name)]

    def _key(self, name: str) -> str:
        if name.startswith(("L:", "C:")):
            return name
        return _node(name) if name in self.by_label else "C:" + name

    def problems(self, name: str) -> list[str]:
        """The labels and claim ids ``name`` uses, transitively, whose own status is in :data:`BAD`."""
        key = self._key(name)
        if key not in self._problems:
            self._problems[key] = [n[2:] for n in self.descendants(key) if self._own.get(n) in BAD]
        return self._problems[key]

    def status(self, name: str) -> str:
        """The propagated status: ``depends`` for a verified node with :meth:`problems`, else its own."""
        own = self.own(name)
        return "depends" if own == "verified" and self.problems(name) else own

    def label_nodes(self) -> list[str]:
        """The label nodes of the graph: every display, theorem and unlabelled statement (not sections)."""
        return [_node(d.label) for d in self.displays if d.kind != "section"]
