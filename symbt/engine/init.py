r"""``symbt init --paper my.tex``: scaffold a claims module with one stub per labelled display of your paper.

Reads the ``.tex`` with :func:`symbt.engine.labels.scan_file` (the ``latex`` extra) and writes
``<tex stem>_claims.py`` beside it (or ``--out FILE``): for every display label (each labelled
equation, ``align`` row, figure) a claim written with the public API only, the display's LaTeX
source as a comment above it::

    # eq-energy (Section 1, equation)
    #   E = \frac{p^2}{2} + V(q)
    @claim("eq-energy", equation="eq-energy", scene="note",
           statement="E = \\frac{p^2}{2} + V(q)  (TODO: state it)")
    def check_eq_energy():
        return todo()

Claim ids are the labels made valid (letters, digits, ``.-_:``) and unique; the scene is the
paper's stem.  A stub is reported ``todo`` -- never verified -- by ``symbt verify`` (exit 1), and
``symbt coverage`` counts its display as a gap until the stub is replaced by a check.

It also adds a ``[tool.symbt]`` table (``claims``, ``paper``) to ``pyproject.toml`` in the
``.tex``'s directory (creating the file if absent).  An existing ``[tool.symbt]`` is never
rewritten: the lines to add are printed instead.

Usage::

    symbt init --paper my.tex [--out FILE] [--force]

Exit status 0 when written; 2 (one line on stderr) when the claims file exists (give
``--force``), the ``.tex`` cannot be read, does not parse or has no labelled display, a
``pyproject.toml`` is not valid TOML, or a file cannot be written.

>>> from symbt.engine.labels import TexLabel
>>> print(stubs([TexLabel("eq:H", "2", "equation", source="H = p^2/2")], scene="note"))
# eq:H (Section 2, equation)
#   H = p^2/2
@claim("eq:H", equation="eq:H", scene="note",
       statement="H = p^2/2  (TODO: state it)")
def check_eq_H():
    return todo()
"""
from __future__ import annotations

import json
import os
import sys
from collections.abc import Sequence
from pathlib import Path

from .._files import atomic_write, toml_loads
from .coverage import OneLineParser
from .labels import LatexError, TexLabel, scan_file
from .project import ConfigError, read_config

__all__ = ["claim_ids", "stubs", "claims_module", "config_lines", "main"]

# written below the table: where the reasons for displays without a claim go
_REASONS_HINT = ("\n# [tool.symbt.reasons]            # displays that are no checkable statement, and why\n"
                 "# \"eq:energy\" = \"a definition\"   # a label is a TOML key: quote it\n")
_ID_CHARS = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789.-_:")


def _unique(name: str, taken: set[str], sep: str = "-") -> str:
    out, k = name, 2
    while out in taken:
        out, k = f"{name}{sep}{k}", k + 1
    taken.add(out)
    return out


def claim_ids(labels: Sequence[str]) -> list[str]:
    """Valid, unique claim ids for ``labels``: other characters become ``-``.

    >>> claim_ids(["eq:a", "eq a", "eq-a", ""])
    ['eq:a', 'eq-a', 'eq-a-2', 'label']
    """
    taken: set[str] = set()
    return [_unique("".join(ch if ch in _ID_CHARS else "-" for ch in lab) or "label", taken) for lab in labels]


def _function_names(ids: Sequence[str]) -> list[str]:
    taken: set[str] = set()
    return [_unique("check_" + "".join(ch if ch.isalnum() or ch == "_" else "_" for ch in cid), taken, "_")
            for cid in ids]


def _one_line(source: str) -> str:
    return " ".join(source.split())


def stubs(labels: Sequence[TexLabel], *, scene: str) -> str:
    """The stubs (decorated functions returning ``todo()``) of the display labels among ``labels``."""
    shown = [lab for lab in labels if lab.is_display]
    ids = claim_ids([lab.label for lab in shown])
    blocks = []
    for lab, cid, fn in zip(shown, ids, _function_names(ids)):
        comment = [f"# {lab.label} (Section {lab.section}, {lab.kind}"
                   + (f", tag {lab.tag}" if lab.tag else "") + ")"]
        comment += [f"#   {line}" for line in lab.source.splitlines()] or ["#   (no LaTeX source)"]
        statement = json.dumps(f"{_one_line(lab.source) or lab.label}  (TODO: state it)", ensure_ascii=False)
        blocks.append("\n".join([
            *comment,
            f"@claim({json.dumps(cid)}, equation={json.dumps(lab.label)}, scene={json.dumps(scene)},",
            f"       statement={statement})",
            f"def {fn}():",
            "    return todo()",
        ]))
    return "\n\n\n".join(blocks)


def claims_module(labels: Sequence[TexLabel], *, paper: Path, scene: str) -> str:
    """The text of a claims module for ``labels`` of ``paper``: a docstring, the public import, the stubs."""
    n = sum(lab.is_display for lab in labels)
    head = (f'"""Claims of {paper.name}: one stub per labelled display ({n}), written by `symbt init`.\n\n'
            "Replace each `return todo()` by a check that could fail, e.g. with\n"
            "`from_decision(decide(lhs, rhs))` (see symbt's docs/coverage.md); `symbt verify` runs them,\n"
            '`symbt coverage` lists what is still a stub.\n"""\n'
            "from symbt import claim, todo\n\n\n")
    return head + stubs(labels, scene=scene) + "\n"


def _toml_string(text: str) -> str:
    return json.dumps(text, ensure_ascii=False)


def config_lines(claims: str, paper: str) -> str:
    """The ``[tool.symbt]`` table naming the claims module and the paper (paths relative to pyproject.toml).

    >>> print(config_lines("note_claims.py", "note.tex"))
    [tool.symbt]
    claims = ["note_claims.py"]
    paper = "note.tex"
    """
    return f"[tool.symbt]\nclaims = [{_toml_string(claims)}]\npaper = {_toml_string(paper)}"


def _relative(path: Path, base: Path) -> str:
    try:
        return Path(os.path.relpath(path, base)).as_posix()
    except ValueError:  # another drive
        return str(path)


def _scene_name(stem: str) -> str:
    return "".join(ch if ch.isalnum() or ch in "-_" else "-" for ch in stem) or "paper"


def _toml_parses(text: str) -> bool:
    try:
        toml_loads(text)
    except ValueError:
        return False
    return True


def main(argv: list[str] | None = None) -> int:
    ap = OneLineParser(prog="symbt init",
                                 description="scaffold a claims module with one todo stub per labelled display "
                                             "of your paper, and a [tool.symbt] table in pyproject.toml")
    ap.add_argument("--paper", metavar="PATH", required=True, help="your paper's LaTeX source")
    ap.add_argument("--out", metavar="FILE", help="the claims module to write (default: <tex stem>_claims.py "
                                                  "beside the .tex)")
    ap.add_argument("--force", action="store_true", help="overwrite an existing claims module")
    args = ap.parse_args(argv)
    paper = Path(args.paper).resolve()
    out = Path(args.out).resolve() if args.out else paper.with_name(f"{paper.stem}_claims.py")
    if out.suffix != ".py" or not out.stem.isidentifier():
        print(f"symbt init: {out.name} is not an importable module name (give --out NAME.py)", file=sys.stderr)
        return 2
    if out.exists() and not args.force:
        print(f"symbt init: {out} exists; give --force to overwrite it", file=sys.stderr)
        return 2
    try:
        labels = scan_file(paper)
    except LatexError as exc:
        print(f"symbt init: {exc}", file=sys.stderr)
        return 2
    if not any(lab.is_display for lab in labels):
        print(f"symbt init: {paper} has no labelled display (equation or figure): nothing to scaffold",
              file=sys.stderr)
        return 2
    pyproject = paper.parent / "pyproject.toml"
    table = config_lines(_relative(out, paper.parent), _relative(paper, paper.parent))
    existing = ""
    has_table = False
    if pyproject.exists():
        try:
            existing = pyproject.read_text(encoding="utf-8")
            has_table = bool(read_config(pyproject)) or "[tool.symbt" in existing
        except (OSError, ConfigError) as exc:
            print(f"symbt init: {exc}", file=sys.stderr)
            return 2
    new_pyproject = None
    if not has_table:
        candidate = (existing.rstrip("\n") + "\n\n" if existing.strip() else "") + table + "\n" + _REASONS_HINT
        if _toml_parses(candidate):
            new_pyproject = candidate
    try:
        atomic_write(out, claims_module(labels, paper=paper, scene=_scene_name(paper.stem)), mkdir=False)
        if new_pyproject is not None:
            atomic_write(pyproject, new_pyproject, mkdir=False)
    except OSError as exc:
        print(f"symbt init: cannot write {exc.filename or out}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    n = sum(lab.is_display for lab in labels)
    print(f"wrote {out}: {n} todo stubs, one per labelled display of {paper.name}")
    if new_pyproject is not None:
        print(f"{'added [tool.symbt] to' if existing else 'wrote'} {pyproject}")
    else:
        print(f"{pyproject} already has a [tool.symbt] table (or cannot take one); make sure it has:\n{table}")
    print("next: symbt verify (every stub is todo), symbt coverage (the displays still to check)")
    return 0
