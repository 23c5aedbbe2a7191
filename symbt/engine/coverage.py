r"""``symbt coverage``: every labelled display of the paper with its claims, or the reason it has none.

The paper's labels are data (:data:`symbt.paper.LABELS`: label, section as printed, kind); the
reasons for displays without a claim are data too (:data:`symbt.claims.coverage.REASONS`).
:func:`coverage_map` joins them with the registry: a display is covered by every registered claim
whose ``equation`` or ``source_equation`` is its label.  What counts as a display: the labels of
``equation``-like environments and of figures; section labels and theorem environments are
listed in :data:`~symbt.paper.LABELS` but are not displays (a theorem is stated by its displays).

With the LaTeX source at hand, :func:`scan_labels` reads every ``\label{}`` with its section and
kind, and :func:`compare` reports labels the list lacks, labels the paper lacks, and labels whose
section or kind differ.

Usage::

    symbt coverage [--json FILE|-] [--paper PATH]

The paper defaults to ``$SYMBT_PAPER``, else ``shared/paper/backlund-toda.tex`` in the parent or
grandparent of the project root or of the working directory (i.e. ``../shared/paper/...``), when
it exists.  Exit status 1 if a display has neither claims nor a reason, or the paper and the list
disagree; 2 on bad arguments or an unreadable paper.

>>> from symbt.paper import Label
>>> tex = r"\begin{document}\section{A}\label{s}\begin{equation}\label{e}x\end{equation}\end{document}"
>>> scan_labels(tex)
[Label(label='s', section='1', kind='section'), Label(label='e', section='1', kind='equation')]
"""
from __future__ import annotations

import argparse
import os
import re
import sys
from pathlib import Path
from typing import Any

from ..paper import DISPLAYS, LABELS, Label
from ..report.json import emit_document, output_refused

__all__ = ["coverage_map", "coverage_of", "scan_labels", "compare", "find_paper", "unlabelled_claims", "main"]

PAPER_RELATIVE = Path("shared") / "paper" / "backlund-toda.tex"
_EQUATION_ENVS = {"equation", "equation*", "eqnarray", "eqnarray*", "align", "align*", "gather", "gather*",
                  "multline", "multline*", "displaymath"}
_FIGURE_ENVS = {"figure", "figure*", "table", "table*"}
_TOKEN = re.compile(
    r"\\(?:(?P<sec>section|subsection)\*?\s*\{"
    r"|(?P<app>appendix)(?![A-Za-z])"
    r"|begin\{(?P<begin>[A-Za-z0-9*]+)\}"
    r"|end\{(?P<end>[A-Za-z0-9*]+)\}"
    r"|(?P<be>bea|be)(?![A-Za-z])"
    r"|(?P<ee>eea|ee)(?![A-Za-z])"
    r"|label\{(?P<label>[^}]*)\})")


def _strip_comments(tex: str) -> str:
    return re.sub(r"(?<!\\)%[^\n]*", "", tex)


def scan_labels(tex: str) -> list[Label]:
    r"""Every ``\label{}`` after ``\begin{document}``: its section as printed (1, 2, 3.1, A, ...) and kind.

    Kinds: ``equation`` (inside an equation-like environment, also via ``\be``/``\bea``),
    ``figure``, ``theorem`` (an environment declared by ``\newtheorem``), else ``section``.
    """
    tex = _strip_comments(tex)
    theorems = set(re.findall(r"\\newtheorem\{([A-Za-z0-9*]+)\}", tex))
    start = tex.find(r"\begin{document}")
    body = tex[start + len(r"\begin{document}"):] if start >= 0 else tex
    sec, sub, appendix = 0, 0, False
    stack: list[str] = []
    out: list[Label] = []
    for m in _TOKEN.finditer(body):
        if m.group("sec") == "section":
            sec, sub = sec + 1, 0
        elif m.group("sec") == "subsection":
            sub += 1
        elif m.group("app"):
            appendix, sec, sub = True, 0, 0
        elif m.group("begin"):
            stack.append(m.group("begin"))
        elif m.group("be"):
            stack.append("equation" if m.group("be") == "be" else "eqnarray")
        elif (m.group("end") or m.group("ee")) and stack:
            stack.pop()
        elif m.group("label") is not None:
            number = chr(ord("A") + sec - 1) if appendix else str(sec)
            section = f"{number}.{sub}" if sub else number
            kind = "section"
            for env in reversed(stack):
                if env in _EQUATION_ENVS:
                    kind = "equation"
                elif env in _FIGURE_ENVS:
                    kind = "figure"
                elif env in theorems:
                    kind = "theorem"
                else:
                    continue
                break
            out.append(Label(m.group("label"), section, kind))
    return out


def compare(scanned: list[Label], listed: tuple[Label, ...] = LABELS) -> dict[str, list[str]]:
    """``{"missing": labels the list lacks, "stale": labels the paper lacks, "differ": "label: listed vs paper"}``."""
    by_label = {lab.label: lab for lab in listed}
    seen = {lab.label for lab in scanned}
    differ = [f"{s.label}: listed {by_label[s.label].section}/{by_label[s.label].kind}, paper {s.section}/{s.kind}"
              for s in scanned if s.label in by_label and by_label[s.label] != s]
    return {"missing": [s.label for s in scanned if s.label not in by_label],
            "stale": [lab.label for lab in listed if lab.label not in seen], "differ": differ}


def find_paper(explicit: str | None = None) -> Path | None:
    """The paper's LaTeX source: ``explicit``, ``$SYMBT_PAPER``, else ``shared/paper/backlund-toda.tex``
    next to the parent or grandparent of the project root or of the working directory (if it exists)."""
    if explicit:
        return Path(explicit)
    env = os.environ.get("SYMBT_PAPER")
    if env:
        return Path(env)
    root = Path(__file__).resolve().parents[2]
    for base in (root, Path.cwd().resolve()):
        for up in (base.parent, base.parent.parent):
            cand = up / PAPER_RELATIVE
            if cand.is_file():
                return cand
    return None


def _statuses_from_cache(claims: list) -> dict[str, str]:
    from .cache import load_cached

    out = {}
    for c in claims:
        o = load_cached(c)
        if o is not None:
            out[c.id] = o.status
    return out


def coverage_map(statuses: dict[str, str] | None = None, *, use_cache: bool = True) -> dict[str, dict[str, Any]]:
    """``{label: {"claims": [{"id", "status"}...]} | {"reason": text, "see": [claim ids]}}`` for every display.

    ``statuses`` (claim id -> status, e.g. from a verify run) fills the statuses; otherwise they
    are read from the cache (``use_cache``); a claim without a known status has ``status: None``.
    """
    from ..claims import REGISTRY, load_all
    from ..claims.coverage import REASONS

    load_all()
    claims = list(REGISTRY.values())
    known = dict(statuses) if statuses is not None else (_statuses_from_cache(claims) if use_cache else {})
    out: dict[str, dict[str, Any]] = {}
    for lab in DISPLAYS:
        hits = [{"id": c.id, "status": known.get(c.id)} for c in claims
                if lab.label in (c.equation, c.source_equation)]
        if hits:
            out[lab.label] = {"claims": hits}
        elif lab.label in REASONS:
            r = REASONS[lab.label]
            out[lab.label] = {"reason": r.text, "see": list(r.see)}
        else:
            out[lab.label] = {}
    return out


def coverage_of(results: list) -> dict[str, dict[str, Any]]:
    """The coverage of a verify run: every display with the claims *of this run* that check it, or its reason.

    Reads only the results' claim metadata (no claim module is imported), so it also serves
    the warm path.  A display whose claims were not selected, and that has no reason, maps
    to ``{"claims": []}``.
    """
    from ..claims.coverage import REASONS

    out: dict[str, dict[str, Any]] = {}
    for lab in DISPLAYS:
        hits = [{"id": r.claim.id, "status": r.outcome.status} for r in results
                if lab.label in (r.claim.equation, r.claim.source_equation)]
        if hits or lab.label not in REASONS:
            out[lab.label] = {"claims": hits}
        else:
            out[lab.label] = {"reason": REASONS[lab.label].text, "see": list(REASONS[lab.label].see)}
    return out


def unlabelled_claims() -> dict[str, list[str]]:
    """Claims on statements the paper does not label (``equation`` not among :data:`~symbt.paper.LABELS`)."""
    from ..claims import REGISTRY, load_all

    load_all()
    names = {lab.label for lab in LABELS}
    out: dict[str, list[str]] = {}
    for c in REGISTRY.values():
        if c.equation not in names and (c.source_equation or "") not in names:
            out.setdefault(c.equation, []).append(c.id)
    return out


def _format(cmap: dict[str, dict[str, Any]], unlabelled: dict[str, list[str]]) -> str:
    lines = []
    section = None
    for lab in DISPLAYS:
        if lab.section != section:
            section = lab.section
            from ..paper import SECTIONS

            lines.append(f"Section {section}: {SECTIONS[section][1]}")
        entry = cmap[lab.label]
        if "claims" in entry:
            what = ", ".join(f"{c['id']} ({c['status'] or 'not run'})" for c in entry["claims"])
        elif "reason" in entry:
            what = "no claim: " + entry["reason"]
        else:
            what = "UNCOVERED: neither a claim nor a reason"
        lines.append(f"  {lab.label:16s} {lab.kind:8s} {what}")
    others = [lab for lab in LABELS if not lab.is_display]
    lines.append("not displays: " + ", ".join(f"{lab.label} ({lab.kind} {lab.section})" for lab in others))
    if unlabelled:
        lines.append("claims on unlabelled statements: "
                     + "; ".join(f"{eq}: {', '.join(ids)}" for eq, ids in unlabelled.items()))
    n_claims = sum(1 for e in cmap.values() if "claims" in e)
    n_reason = sum(1 for e in cmap.values() if "reason" in e)
    lines.append(f"{len(cmap)} displays: {n_claims} with claims, {n_reason} with a reason, "
                 f"{len(cmap) - n_claims - n_reason} uncovered")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="symbt coverage", description="the paper's labelled displays: claims or reasons")
    ap.add_argument("--json", metavar="FILE", help="write the coverage as JSON ('-': stdout)")
    ap.add_argument("--paper", metavar="PATH", help="the paper's LaTeX source (default: $SYMBT_PAPER or "
                                                    "../shared/paper/backlund-toda.tex if it exists)")
    ap.add_argument("--no-cache", action="store_true", help="do not read claim statuses from the cache")
    ap.add_argument("-q", "--quiet", action="store_true")
    args = ap.parse_args(argv)
    if output_refused(args.json, "symbt coverage"):
        return 2
    paper = find_paper(args.paper)
    diff: dict[str, list[str]] | None = None
    if paper is not None:
        try:
            diff = compare(scan_labels(paper.read_text(encoding="utf-8")))
        except OSError as exc:
            print(f"symbt coverage: cannot read {paper}: {exc.strerror or exc}", file=sys.stderr)
            return 2
    cmap = coverage_map(use_cache=not args.no_cache)
    unlabelled = unlabelled_claims()
    uncovered = [k for k, e in cmap.items() if not e]
    report = {"coverage": cmap, "unlabelled": unlabelled, "uncovered": uncovered,
              "paper": None if paper is None else {"path": str(paper), **(diff or {})}}
    status = emit_document(report, args.json, command="symbt coverage",
                           text=None if args.quiet else _format(cmap, unlabelled))
    if status:
        return status
    bad = bool(uncovered)
    if paper is None:
        print("symbt coverage: paper not found (--paper PATH); the label list was not compared", file=sys.stderr)
    elif diff and any(diff.values()):
        bad = True
        for key, text in (("missing", "labels in the paper the list lacks"), ("stale", "labels the paper lacks"),
                          ("differ", "labels whose section/kind differ")):
            if diff[key]:
                print(f"symbt coverage: {text}: {', '.join(diff[key])}", file=sys.stderr)
    if uncovered:
        print(f"symbt coverage: displays with neither claims nor a reason: {', '.join(uncovered)}", file=sys.stderr)
    return 1 if bad else 0
