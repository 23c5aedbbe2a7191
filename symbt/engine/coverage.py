r"""``symbt coverage``: every labelled display of the project's paper with its claims, or the reason it has none.

The displays are the paper's, the claims and reasons the project's (:mod:`.project`):

* **your paper** (a ``[tool.symbt]`` table or ``--claims``): the labels are read from the ``.tex``
  of ``--paper`` or ``[tool.symbt] paper`` with a LaTeX parser (:mod:`.labels`, the ``latex``
  extra), the reasons are ``[tool.symbt.reasons]`` (label = "why it carries no claim");
* **Zullo's paper** (no configuration): the labels are data (:data:`symbt.paper.LABELS`: label,
  section as printed, kind), the reasons too (:data:`symbt.claims.coverage.REASONS`); with the
  LaTeX source at hand (``--paper``, ``$SYMBT_PAPER`` or ``../shared/paper/backlund-toda.tex``)
  the list is compared with it: labels the list lacks, labels the paper lacks, labels whose
  section or kind differ.

A display is covered by every claim of the project whose ``equation`` or ``source_equation`` is
its label (:func:`coverage_map`).  What counts as a display: a labelled equation (each labelled
row of an ``align``/``eqnarray``) or figure; section and theorem labels are listed but are not
displays (a theorem is stated by its displays).

Statuses come from the claim cache.  In your project a claim without a cached outcome is run
(a ``todo`` stub is never cached, so this is how stubs are recognised; after ``symbt verify``
only stubs and skipped claims run); ``--no-cache`` neither reads nor runs anything.

Usage::

    symbt coverage [--claims MODULE_OR_PATH ...] [--paper PATH] [--json FILE|-] [--no-cache] [-q]

Exit status 1 on a gap: a display with neither claims nor a reason, a display whose claims are
all ``todo`` stubs, and in your project a claim or reason whose label the paper lacks ("unknown
label"; Zullo's claims on unlabelled statements are listed, not gaps) or, for Zullo's, the paper
and the list disagreeing.  Exit 2 (one line on stderr) on bad arguments, a paper that is not
configured, cannot be read or does not parse, and a missing ``latex`` extra.

>>> cmap = coverage_map({"speccurve": "verified"}, use_cache=False)
>>> cmap["speccurve"], cmap["rec"]["see"][:2]
({'claims': [{'id': 'speccurve', 'status': 'verified'}]}, ['Hdiscr.n2', 'Hdiscr.n3'])
"""
from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from ..paper import LABELS, SECTIONS, Label
from ..report.json import emit_document, output_refused
from .labels import LatexError, scan, scan_file
from .project import ConfigError, Project, active, discover, load

if TYPE_CHECKING:
    from ..claims.base import Claim, ClaimResult

__all__ = ["OneLineParser", "coverage_map", "coverage_of", "paper_labels", "reasons_of", "scan_labels", "compare",
           "find_paper", "unlabelled_claims", "unknown_labels", "main"]

PAPER_RELATIVE = Path("shared") / "paper" / "backlund-toda.tex"
NO_PAPER = "no paper: give --paper PATH, or paper = \"my.tex\" in [tool.symbt] of pyproject.toml"


class OneLineParser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line on stderr (exit 2), as every symbt command's."""

    def error(self, message: str) -> NoReturn:
        print(f"{self.prog}: {message} (see '{self.prog} --help')", file=sys.stderr)
        raise SystemExit(2)


def scan_labels(tex: str) -> list[Label]:
    r"""Every ``\label{}`` of ``tex`` (after ``\begin{document}``) as ``(label, section, kind)``; see :mod:`.labels`.

    >>> tex = r"\begin{document}\section{A}\label{s}\begin{equation}\label{e}x\end{equation}\end{document}"
    >>> scan_labels(tex)
    [Label(label='s', section='1', kind='section'), Label(label='e', section='1', kind='equation')]
    """
    return [lab.as_label() for lab in scan(tex)]


def compare(scanned: list[Label], listed: tuple[Label, ...] = LABELS) -> dict[str, list[str]]:
    """``{"missing": labels the list lacks, "stale": labels the paper lacks, "differ": "label: listed vs paper"}``."""
    by_label = {lab.label: lab for lab in listed}
    seen = {lab.label for lab in scanned}
    differ = [f"{s.label}: listed {by_label[s.label].section}/{by_label[s.label].kind}, paper {s.section}/{s.kind}"
              for s in scanned if s.label in by_label and by_label[s.label] != s]
    return {"missing": [s.label for s in scanned if s.label not in by_label],
            "stale": [lab.label for lab in listed if lab.label not in seen], "differ": differ}


def find_paper(explicit: str | None = None) -> Path | None:
    """Zullo's LaTeX source: ``explicit``, ``$SYMBT_PAPER``, else ``shared/paper/backlund-toda.tex``
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


# --------------------------------------------------------------------------- the paper and the reasons of a project

def paper_labels(project: Project) -> list[Label]:
    """Every label of the project's paper, in its order: Zullo's list, or the labels scanned from your ``.tex``.

    Raises :class:`~.project.ConfigError` when your project configures no paper,
    :class:`~.labels.LatexError` when it cannot be read or does not parse.
    """
    if project.is_package:
        return list(LABELS)
    if project.paper is None:
        raise ConfigError(NO_PAPER)
    return [lab.as_label() for lab in scan_file(project.paper)]


def reasons_of(project: Project) -> dict[str, dict[str, Any]]:
    """label -> ``{"reason": text, "see": [claim ids]}``: Zullo's ``REASONS``, else ``[tool.symbt.reasons]``."""
    if project.is_package:
        from ..claims.coverage import REASONS

        return {k: {"reason": r.text, "see": list(r.see)} for k, r in REASONS.items()}
    return {k: {"reason": text, "see": []} for k, text in project.reasons.items()}


def _covers(c: Any, label: str) -> bool:
    return label in (c.equation, c.source_equation)


def _statuses_from_cache(claims: list[Claim]) -> dict[str, str]:
    from .cache import load_cached

    out: dict[str, str] = {}
    for c in claims:
        o = load_cached(c)
        if o is not None:
            out[c.id] = o.status
    return out


def _statuses_by_running(claims: list[Claim], known: dict[str, str]) -> dict[str, str]:
    """Run the claims without a known status (stubs are never cached); deep claims stay unknown."""
    from .runner import run

    todo = [c for c in claims if c.id not in known and not c.deep]
    return {r.claim.id: r.outcome.status for r in run(todo, use_cache=False, manifest=False)} if todo else {}


def _join(displays: Sequence[Label], claims: Sequence[Any], statuses: Mapping[str, str | None],
          reasons: dict[str, dict[str, Any]], *, empty_if_unclaimed: bool) -> dict[str, dict[str, Any]]:
    out: dict[str, dict[str, Any]] = {}
    for lab in displays:
        hits = [{"id": c.id, "status": statuses.get(c.id)} for c in claims if _covers(c, lab.label)]
        if hits:
            out[lab.label] = {"claims": hits}
        elif lab.label in reasons:
            out[lab.label] = dict(reasons[lab.label])
        else:
            out[lab.label] = {"claims": []} if empty_if_unclaimed else {}
    return out


def coverage_map(statuses: dict[str, str] | None = None, *, use_cache: bool = True,
                 project: Project | None = None, run: bool = False) -> dict[str, dict[str, Any]]:
    """``{label: {"claims": [{"id", "status"}...]} | {"reason": text, "see": [claim ids]} | {}}`` for every display.

    ``project`` defaults to the one found from the working directory.  ``statuses`` (claim id ->
    status, e.g. from a verify run) fills the statuses; otherwise they are read from the cache
    (``use_cache``), and with ``run`` the claims the cache lacks are run; a claim without a known
    status has ``status: None``.  ``{}``: neither claims nor a reason.
    """
    project = project or discover()
    displays = [lab for lab in paper_labels(project) if lab.is_display]
    claims = load(project)
    known: dict[str, Any] = dict(statuses) if statuses is not None else (
        _statuses_from_cache(claims) if use_cache else {})
    if run and statuses is None and use_cache:
        known.update(_statuses_by_running(claims, known))
    return _join(displays, claims, known, reasons_of(project), empty_if_unclaimed=False)


def coverage_of(results: list[ClaimResult], project: Project | None = None) -> dict[str, dict[str, Any]]:
    """The coverage of a verify run: every display with the claims *of this run* that check it, or its reason.

    Reads only the results' claim metadata (no claim module is imported), so it also serves
    the warm path.  A display whose claims were not selected, and that has no reason, maps
    to ``{"claims": []}``.  ``project`` defaults to the project whose claims were loaded last,
    else the one found from the working directory; when its paper is not configured, cannot be
    read or parsed (or the ``latex`` extra is missing) the coverage is empty (``symbt coverage``
    says why).
    """
    project = project or active() or discover()
    try:
        displays = [lab for lab in paper_labels(project) if lab.is_display]
    except (ConfigError, LatexError, ImportError):
        return {}
    statuses = {r.claim.id: r.outcome.status for r in results}
    claims = [r.claim for r in results]
    return _join(displays, claims, statuses, reasons_of(project), empty_if_unclaimed=True)


def unlabelled_claims(project: Project | None = None) -> dict[str, list[str]]:
    """The project's claims on labels its paper lacks: ``{label: [claim ids]}``.

    For Zullo's paper these are claims on statements the paper prints without a label (the
    N = 3 Hamiltonians, the toy example); for yours, see :func:`unknown_labels`.
    """
    project = project or discover()
    names = {lab.label for lab in paper_labels(project)}
    out: dict[str, list[str]] = {}
    for c in load(project):
        if c.equation not in names and (c.source_equation or "") not in names:
            out.setdefault(c.equation, []).append(c.id)
    return out


def unknown_labels(project: Project, labels: Sequence[Label]) -> dict[str, Any]:
    """``{"claims": {label: [claim ids]}, "reasons": [labels]}``: what names a label the paper lacks."""
    names = {lab.label for lab in labels}
    claims: dict[str, list[str]] = {}
    for c in load(project):
        if c.equation not in names and (c.source_equation or "") not in names:
            claims.setdefault(c.equation, []).append(c.id)
    reasons = [k for k in project.reasons if k not in names] if not project.is_package else []
    return {"claims": claims, "reasons": reasons}


# --------------------------------------------------------------------------- the command

def _is_todo(entry: dict[str, Any]) -> bool:
    return bool(entry.get("claims")) and all(c["status"] == "todo" for c in entry["claims"])


def _format(labels: Sequence[Label], cmap: dict[str, dict[str, Any]], *, package: bool,
            unlabelled: dict[str, list[str]]) -> str:
    lines = []
    section = None
    for lab in labels:
        if not lab.is_display:
            continue
        if lab.section != section:
            section = lab.section
            name = SECTIONS[section][1] if package and section in SECTIONS else ""
            lines.append(f"Section {section}" + (f": {name}" if name else ""))
        entry = cmap[lab.label]
        if _is_todo(entry):
            what = "TODO (stubs only): " + ", ".join(c["id"] for c in entry["claims"])
        elif entry.get("claims"):
            what = ", ".join(f"{c['id']} ({c['status'] or 'not run'})" for c in entry["claims"])
        elif "reason" in entry:
            what = "no claim: " + entry["reason"]
        else:
            what = "UNCOVERED: neither a claim nor a reason"
        lines.append(f"  {lab.label:16s} {lab.kind:8s} {what}")
    others = [lab for lab in labels if not lab.is_display]
    if others:
        lines.append("not displays: " + ", ".join(f"{lab.label} ({lab.kind} {lab.section})" for lab in others))
    if unlabelled and package:
        lines.append("claims on unlabelled statements: "
                     + "; ".join(f"{eq}: {', '.join(ids)}" for eq, ids in unlabelled.items()))
    n_todo = sum(1 for e in cmap.values() if _is_todo(e))
    n_claims = sum(1 for e in cmap.values() if e.get("claims")) - n_todo
    n_reason = sum(1 for e in cmap.values() if "reason" in e)
    lines.append(f"{len(cmap)} displays: {n_claims} with claims, {n_reason} with a reason, {n_todo} todo, "
                 f"{len(cmap) - n_claims - n_reason - n_todo} uncovered")
    return "\n".join(lines)


def _compare_with_source(paper: Path, explicit: bool) -> dict[str, list[str]] | None:
    """Zullo's list against the LaTeX source; ``None`` when pylatexenc is missing and the source was not asked for."""
    try:
        return compare([lab.as_label() for lab in scan_file(paper)])
    except ImportError:
        if explicit:
            raise
        print("symbt coverage: the label list was not compared with the paper "
              "(needs the optional extra 'latex': pip install 'symbt[latex]')", file=sys.stderr)
        return None


def main(argv: list[str] | None = None) -> int:
    ap = OneLineParser(prog="symbt coverage",
                                 description="the paper's labelled displays: claims, reasons, gaps")
    ap.add_argument("--claims", action="append", metavar="MODULE_OR_PATH",
                    help="your claims: a module name or a .py file / package path (repeatable; default: "
                         "[tool.symbt] claims of pyproject.toml, else Zullo's paper)")
    ap.add_argument("--paper", metavar="PATH", help="the paper's LaTeX source (default: [tool.symbt] paper; for "
                                                    "Zullo's: $SYMBT_PAPER or ../shared/paper/backlund-toda.tex)")
    ap.add_argument("--json", metavar="FILE", help="write the coverage as JSON ('-': stdout)")
    ap.add_argument("--no-cache", action="store_true", help="neither read claim statuses from the cache nor run "
                                                            "claims")
    ap.add_argument("-q", "--quiet", action="store_true")
    args = ap.parse_args(argv)
    if output_refused(args.json, "symbt coverage"):
        return 2
    try:
        project = discover(claims=args.claims or (), paper=args.paper)
        package = project.is_package
        labels = paper_labels(project)
        diff: dict[str, list[str]] | None = None
        paper = (project.paper or find_paper()) if package else project.paper
        if package and paper is not None:
            diff = _compare_with_source(paper, explicit=project.paper is not None)
        statuses = None
        if not package and not args.no_cache:  # stubs are never cached: run what the cache lacks
            claims = load(project)
            statuses = _statuses_from_cache(claims)
            missing = [c for c in claims if c.id not in statuses and not c.deep]
            if missing and not args.quiet:
                print(f"symbt coverage: running {len(missing)} claim(s) without a cached outcome "
                      "(todo stubs are never cached)", file=sys.stderr)
            statuses.update(_statuses_by_running(claims, statuses))
        cmap = coverage_map(statuses, use_cache=not args.no_cache, project=project)
        unknown = unknown_labels(project, labels)
    except (ConfigError, LatexError) as exc:
        print(f"symbt coverage: {exc}", file=sys.stderr)
        return 2
    uncovered = [k for k, e in cmap.items() if not e]
    todo = [k for k, e in cmap.items() if _is_todo(e)]
    report: dict[str, Any] = {"coverage": cmap, "uncovered": uncovered, "todo": todo,
                              "paper": None if paper is None else {"path": str(paper), **(diff or {})}}
    if package:
        report["unlabelled"] = unknown["claims"]
    else:
        report["unknown"] = unknown
    status = emit_document(report, args.json, command="symbt coverage",
                           text=None if args.quiet else _format(labels, cmap, package=package,
                                                                unlabelled=unknown["claims"]))
    if status:
        return status
    bad = bool(uncovered or todo)
    if package and paper is None:
        print("symbt coverage: paper not found (--paper PATH); the label list was not compared", file=sys.stderr)
    elif diff and any(diff.values()):
        bad = True
        if len(diff["missing"]) and len(diff["stale"]) == len(LABELS):
            print("symbt coverage: this .tex shares no label with Zullo's paper; for your own paper give your "
                  "claims (--claims, or claims = [...] in [tool.symbt])", file=sys.stderr)
        for key, text in (("missing", "labels in the paper the list lacks"), ("stale", "labels the paper lacks"),
                          ("differ", "labels whose section/kind differ")):
            if diff[key]:
                print(f"symbt coverage: {text}: {', '.join(diff[key])}", file=sys.stderr)
    if not package:
        for label, ids in unknown["claims"].items():
            bad = True
            print(f"symbt coverage: unknown label {label!r}: claims {', '.join(ids)} (the paper has no such label)",
                  file=sys.stderr)
        for label in unknown["reasons"]:
            bad = True
            print(f"symbt coverage: unknown label {label!r}: a reason in [tool.symbt] reasons (the paper has no "
                  "such label)", file=sys.stderr)
    if todo:
        print(f"symbt coverage: displays whose claims are all todo stubs: {', '.join(todo)}", file=sys.stderr)
    if uncovered:
        print(f"symbt coverage: displays with neither claims nor a reason: {', '.join(uncovered)}", file=sys.stderr)
    return 1 if bad else 0
