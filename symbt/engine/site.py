r"""``symbt report --html DIR --from verify.json``: the annotated paper as a static site (:mod:`symbt.report.site`).

The claims are not re-run: the verdicts come from the JSON of a verify run; the labels and their
LaTeX from the project's paper (``--paper``, ``[tool.symbt] paper``, or Zullo's ``.tex`` found by
:func:`.coverage.find_paper`).  Without a readable paper the site still lists every label the
report's coverage names, without their mathematics (a warning says so).  Bad input (a missing or
malformed JSON, a ``.tex`` that does not parse): one line on stderr, exit 2.

>>> import json, tempfile, os
>>> d = tempfile.mkdtemp()
>>> _ = open(os.path.join(d, "v.json"), "w").write(json.dumps({"claims": [
...     {"id": "c", "equation": "E", "status": "verified", "statement": "1 + 1 = 2"}]}))
>>> _ = open(os.path.join(d, "p.tex"), "w").write(r"\begin{equation}\label{E} 1+1=2 \end{equation}")
>>> main(["--html", os.path.join(d, "site"), "--from", os.path.join(d, "v.json"), "--paper",
...       os.path.join(d, "p.tex"), "-q"])
0
>>> main(["--html", os.path.join(d, "site"), "--from", os.path.join(d, "no.json")])  # one line on stderr
2
"""
from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path
from typing import Any

from ..paper import LABELS
from .coverage import OneLineParser, find_paper
from .labels import LatexError, scan_file
from .project import ConfigError, Project, discover

__all__ = ["main", "read_report"]


def read_report(path: str, what: str = "verify") -> dict[str, Any]:
    """A JSON document from ``path``; :class:`ValueError` (one line) if it is missing or not a ``what`` report."""
    try:
        doc = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise ValueError(f"cannot read {path}: {exc.strerror or exc}") from None
    except ValueError as exc:
        raise ValueError(f"{path} is not JSON: {exc}") from None
    key = "claims" if what == "verify" else "summary"
    if not isinstance(doc, dict) or not isinstance(doc.get(key), (list, dict)):
        raise ValueError(f"{path} is not a symbt {what} report (no {key!r})")
    return doc


def _labels(project: Project, doc: dict[str, Any]) -> tuple[list[Any], str | None, str | None]:
    """(labels, tex, paper path): scanned from the paper when there is one."""
    paper = project.paper or (find_paper() if project.is_package else None)
    if paper is not None and Path(paper).is_file():
        return scan_file(paper), Path(paper).read_text(encoding="utf-8", errors="replace"), str(paper)
    if project.paper is not None:
        raise LatexError(f"cannot read {project.paper}")
    print("symbt report: the paper's .tex was not found (--paper PATH): displays are listed without their "
          "mathematics", file=sys.stderr)
    if project.is_package:
        return list(LABELS), None, None
    from ..paper import Label

    return [Label(k, "", "equation") for k in (doc.get("coverage") or {})], None, None


def main(argv: list[str] | None = None) -> int:
    ap = OneLineParser(prog="symbt report", description="the paper, annotated: a static HTML site from a verify run")
    ap.add_argument("--html", metavar="DIR", required=True, help="write the site into this directory")
    ap.add_argument("--from", dest="source", metavar="FILE", required=True,
                    help="the JSON of a verify run (symbt verify --json FILE); no claim is re-run")
    ap.add_argument("--paper", metavar="PATH", help="the paper's LaTeX source (default: [tool.symbt] paper; for "
                                                    "Zullo's: $SYMBT_PAPER or ../shared/paper/backlund-toda.tex)")
    ap.add_argument("--mutate", metavar="FILE", help="the JSON of symbt mutate: its score on the summary page")
    ap.add_argument("--claims", action="append", metavar="MODULE_OR_PATH",
                    help="your claims' project (for its paper; the claims are not run)")
    ap.add_argument("--no-graphviz", action="store_true", help="lay the graph out without Graphviz")
    ap.add_argument("-q", "--quiet", action="store_true")
    args = ap.parse_args(argv)
    try:
        doc = read_report(args.source)
        mutate = read_report(args.mutate, "mutate") if args.mutate else None
        project = discover(claims=args.claims or (), paper=args.paper)
        labels, tex, paper = _labels(project, doc)
    except (ValueError, ConfigError) as exc:   # LatexError is a ValueError
        print(f"symbt report: {exc}", file=sys.stderr)
        return 2
    from ..report.site import build_site

    if importlib.util.find_spec("latex2mathml") is None:
        print("symbt report: displays are shown as LaTeX source (MathML needs the optional extra 'report': "
              "pip install 'symbt[report]')", file=sys.stderr)
    try:
        out = build_site(doc, labels, args.html, tex=tex, mutate=mutate, paper=paper,
                         prefer_graphviz=not args.no_graphviz)
    except OSError as exc:
        print(f"symbt report: cannot write {args.html}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    if not args.quiet:
        converted = sum(out["mathml"].values())
        print(f"symbt report: {out['pages']} pages in {args.html} (index.html); {converted} of "
              f"{len(out['mathml'])} displays as MathML; graph laid out by {out['graph']}")
    return 0
