r"""The labels of a paper's LaTeX source, read with a LaTeX parser (pylatexenc).

:func:`scan` parses a ``.tex`` (``pip install 'symbt[latex]'``) and returns every ``\label`` after
``\begin{document}`` as a :class:`TexLabel`: its name, the section as printed (``1``, ``3.2``, ``A``),
its kind, the LaTeX source of its display and the labels that display references.

* **kind** -- ``equation`` (an ``equation``-like environment, ``\[...\]``, or a user macro or
  environment defined as one), ``figure`` (``figure``/``table``), ``theorem`` (an environment
  declared by ``\newtheorem``), else ``section``;
* **rows** -- in ``align``, ``eqnarray``, ``gather``, ... each row (``\\`` at the environment's own
  level) is its own display: a label gets its row's math as ``source``, ``\tag{...}`` as ``tag``,
  and ``\nonumber``/``\notag`` make the row ``numbered=False``;
* **references** -- ``\ref``, ``\eqref``, ``\cref``, ... are not labels; each label records the
  labels its display references (``refs``), in order;
* **comments** -- ``% \label{x}`` is no label (the parser drops comments, and the ``comment``
  environment);
* **user macros** -- ``\def\be{\begin{equation}}`` / ``\newcommand{\bea}{\begin{eqnarray}}`` (and the
  matching ``\ee``, ``\eea``) open and close displays; a one-argument macro defined as
  ``\begin{equation}#1\end{equation}`` wraps one; ``\newenvironment{eq}{\begin{equation}}{...}``
  is an equation environment.  The common abbreviations ``\be``/``\ee`` (equation) and
  ``\bea``/``\eea`` (eqnarray) are understood even when their definitions live in a style file
  the scanner does not see; a definition in the file wins;
* **sections** -- ``\section``, ``\subsection``, ``\subsubsection`` are numbered as LaTeX prints
  them (starred ones are not), after ``\appendix`` with letters.

Not followed: ``\input``/``\include`` (scan each file), conditionals (``\iffalse``).
A source that does not parse, or an opening macro without its closing one, raises
:class:`LatexError` (a :class:`ValueError`, one line with the position).

>>> tex = r'''\documentclass{article}\def\be{\begin{equation}}\def\ee{\end{equation}}
... \begin{document}\section{Model}\label{s-model}
... \be\label{eq-H} H = p^2/2 % \label{old}
... \ee
... \begin{align} x &= 1 \label{eq-x}\\ y &= 2 \nonumber \\ z &= x \tag{$*$}\label{eq-z} \eqref{eq-H}
... \end{align}
... \end{document}'''
>>> for lab in scan(tex):
...     print(lab.label, lab.section, lab.kind, repr(lab.source), lab.refs, lab.tag)
s-model 1 section 'Model' () None
eq-H 1 equation 'H = p^2/2' () None
eq-x 1 equation 'x &= 1' () None
eq-z 1 equation 'z &= x \\eqref{eq-H}' ('eq-H',) $*$
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..paper import DISPLAY_KINDS, Label
from .latex import (
    DEFINERS,
    ENV_DEFINERS,
    EQUATION_ENVIRONMENTS,
    FIGURE_ENVIRONMENTS,
    MULTIROW_ENVIRONMENTS,
    REFERENCE_MACROS,
    Definitions,
    LatexError,
    argument_text,
    parse_nodes,
)

__all__ = ["TexLabel", "LatexError", "scan", "scan_file", "EQUATION_ENVIRONMENTS", "MULTIROW_ENVIRONMENTS",
           "FIGURE_ENVIRONMENTS", "REFERENCE_MACROS"]

@dataclass(frozen=True)
class TexLabel:
    r"""One ``\label`` of a LaTeX source (see the module docstring).

    ``source`` is the display's LaTeX without its ``\label``, ``\tag``, ``\nonumber`` and
    comments (an ``align`` row's math; a figure's or theorem's body; a section's title);
    ``refs`` the labels it references; ``line`` the label's line in the file.

    >>> TexLabel("e", "2", "equation").as_label()
    Label(label='e', section='2', kind='equation')
    """

    label: str
    section: str
    kind: str
    source: str = ""
    refs: tuple[str, ...] = ()
    tag: str | None = None
    numbered: bool = True
    line: int = 0

    @property
    def is_display(self) -> bool:
        """An equation (row) or a figure: what coverage asks a claim or a reason for."""
        return self.kind in DISPLAY_KINDS

    def as_label(self) -> Label:
        """The ``(label, section, kind)`` triple of :class:`symbt.paper.Label`."""
        return Label(self.label, self.section, self.kind)


# --------------------------------------------------------------------------- the walk

@dataclass
class _Row:
    start: int
    end: int = -1
    labels: list[int] = field(default_factory=list)  # indices into the scanner's entries
    refs: list[str] = field(default_factory=list)
    tag: str | None = None
    numbered: bool = True


@dataclass
class _Frame:
    kind: str
    multirow: bool
    level: int
    rows: list[_Row]
    closer: str | None = None  # the macro that closes a display opened by a macro
    env: str = ""


class _Scanner:
    def __init__(self, tex: str, defs: Definitions, where: str):
        self.s, self.defs, self.where = tex, defs, where
        self.sec, self.sub, self.subsub, self.appendix = 0, 0, 0, False
        self.heading = ""
        self.frames: list[_Frame] = []
        self.entries: list[dict[str, Any]] = []
        self.drops: list[tuple[int, int]] = []

    # -- helpers
    def section(self) -> str:
        number = (chr(ord("A") + self.sec - 1) if self.sec else "0") if self.appendix else str(self.sec)
        parts = [number] + ([str(self.sub)] if self.sub or self.subsub else []) + \
            ([str(self.subsub)] if self.subsub else [])
        return ".".join(parts)

    def fail(self, pos: int, msg: str) -> LatexError:
        line = self.s.count("\n", 0, pos) + 1
        return LatexError(f"{self.where}:{line}: {msg}")

    def row(self) -> _Row | None:
        return self.frames[-1].rows[-1] if self.frames else None

    def drop(self, node: Any) -> None:
        end = node.pos + node.len
        if self.s[node.pos:end].endswith("\n"):
            end -= 1
        self.drops.append((node.pos, end))

    def open(self, kind: str, multirow: bool, level: int, start: int, closer: str | None = None,
             env: str = "") -> None:
        self.frames.append(_Frame(kind, multirow, level, [_Row(start)], closer, env))

    def close(self, end: int) -> None:
        frame = self.frames.pop()
        frame.rows[-1].end = end
        for row in frame.rows:
            source = self.source(row.start, row.end)
            for i in row.labels:
                self.entries[i].update(kind=frame.kind, source=source, refs=tuple(dict.fromkeys(row.refs)),
                                       tag=row.tag, numbered=row.numbered)

    def source(self, start: int, end: int) -> str:
        out, p = [], start
        for a, b in sorted(d for d in self.drops if start <= d[0] < end):
            if a >= p:
                out.append(self.s[p:a])
                p = b
        out.append(self.s[p:end])
        lines = [" ".join(ln.split()) for ln in "".join(out).strip().splitlines()]
        return "\n".join(ln for ln in lines if ln.strip())

    # -- nodes
    def walk(self, nodes: list[Any], level: int) -> None:
        for node in nodes:
            if node is None:
                continue
            kind = type(node).__name__
            if kind == "LatexCommentNode":
                self.drop(node)
            elif kind == "LatexMacroNode":
                self.macro(node, level)
            elif kind == "LatexEnvironmentNode":
                self.environment(node, level)
            elif kind == "LatexMathNode":
                if node.displaytype == "display":
                    self.open("equation", False, level + 1, node.pos + len(node.delimiters[0]))
                    self.walk(node.nodelist, level + 1)
                    self.close(node.pos + node.len - len(node.delimiters[1]))
                else:
                    self.walk(node.nodelist, level + 1)
            elif kind == "LatexGroupNode":
                self.walk(node.nodelist, level + 1)

    def macro(self, node: Any, level: int) -> None:
        name, argd = node.macroname, node.nodeargd
        args = list(getattr(argd, "argnlist", None) or [])
        if name in DEFINERS or name in ENV_DEFINERS or name == "newtheorem":
            return
        if name in ("section", "subsection", "subsubsection"):
            if args and args[0] is None:  # starred sections are not numbered
                if name == "section":
                    self.sec, self.sub, self.subsub = self.sec + 1, 0, 0
                elif name == "subsection":
                    self.sub, self.subsub = self.sub + 1, 0
                else:
                    self.subsub += 1
            self.heading = argument_text(args[2]) if len(args) > 2 and args[2] is not None else ""
            return
        if name == "appendix":
            self.appendix, self.sec, self.sub, self.subsub = True, 0, 0, 0
            return
        row = self.row()
        if name == "label":
            if not args or args[0] is None:
                raise self.fail(node.pos, "\\label without an argument")
            self.drop(node)
            self.entries.append(dict(label=argument_text(args[0]), section=self.section(), kind="section",
                                     source=self.heading, refs=(), tag=None, numbered=True, pos=node.pos,
                                     line=self.s.count("\n", 0, node.pos) + 1))
            if row is not None:
                row.labels.append(len(self.entries) - 1)
            return
        if name in REFERENCE_MACROS:
            if row is not None and args and args[1] is not None:
                row.refs += [r.strip() for r in argument_text(args[1]).split(",") if r.strip()]
            return
        if name == "tag":
            self.drop(node)
            if row is not None and len(args) > 1 and args[1] is not None:
                row.tag = argument_text(args[1])
            return
        if name in ("nonumber", "notag"):
            self.drop(node)
            if row is not None:
                row.numbered = False
            return
        if name == "\\":
            frame = self.frames[-1] if self.frames else None
            if frame is not None and frame.multirow and level == frame.level:
                frame.rows[-1].end = node.pos
                frame.rows.append(_Row(node.pos + node.len))
            return
        role = self.defs.macros.get(name)
        if role is not None and role[0] == "open":
            found = self.defs.kind_of_environment(role[1])
            if found is not None:
                closer = next((m for m, r in self.defs.macros.items() if r == ("close", role[1])), None)
                self.open(*found, level, node.pos + node.len, closer=closer or "", env=role[1])
                return
        if role is not None and role[0] == "close":
            if self.frames and self.frames[-1].closer is not None and self.frames[-1].env == role[1]:
                self.close(node.pos)
                return
            if self.defs.kind_of_environment(role[1]) is not None:
                raise self.fail(node.pos, f"\\{name} closes a display that no macro opened")
        if role is not None and role[0] == "wrap" and args and args[0] is not None:
            found = self.defs.kind_of_environment(role[1])
            if found is not None:
                arg = args[0]
                self.open(*found, level + 1, arg.pos + 1, env=role[1])
                self.walk(arg.nodelist if hasattr(arg, "nodelist") else [arg], level + 1)
                self.close(arg.pos + arg.len - 1)
                return
        self.walk(args, level + 1)

    def environment(self, node: Any, level: int) -> None:
        name = node.environmentname
        if name == "comment":
            self.drop(node)
            return
        if name == "appendices":
            self.appendix, self.sec, self.sub, self.subsub = True, 0, 0, 0
        found = self.defs.kind_of_environment(name)
        if found is None:
            self.walk(node.nodelist, level + 1)
            return
        body = self.s[node.pos:node.pos + node.len]
        start = node.pos + body.index("}") + 1
        argd = getattr(node, "nodeargd", None)
        for a in getattr(argd, "argnlist", None) or []:
            if a is not None:
                start = max(start, a.pos + a.len)
        self.open(*found, level + 1, start)
        self.walk(node.nodelist, level + 1)
        self.close(node.pos + body.rindex("\\end"))

    def result(self) -> list[TexLabel]:
        if self.frames:
            f = self.frames[-1]
            raise self.fail(f.rows[0].start, f"a display opened here is never closed (\\{f.closer or f.env})")
        out = []
        for e in sorted(self.entries, key=lambda e: e["pos"]):
            e = dict(e)
            e.pop("pos")
            out.append(TexLabel(**e))
        return out


# --------------------------------------------------------------------------- public

def scan(tex: str, *, where: str = "<tex>") -> list[TexLabel]:
    r"""Every ``\label`` of ``tex`` after ``\begin{document}`` (all of them in a fragment), in document order.

    ``where`` names the source in error messages.  Raises :class:`LatexError` if it does not
    parse; :class:`ImportError` (``pylatexenc``) without the ``latex`` extra.

    >>> [(lab.label, lab.kind) for lab in scan(r"\begin{figure}\caption{c \ref{a}}\label{f}\end{figure}")]
    [('f', 'figure')]
    """
    defs = Definitions()
    nodes = parse_nodes(tex, [], where)
    defs.collect(nodes)
    if defs.arity:  # user macros take arguments: parse again, so that they are attached to their macro
        nodes = parse_nodes(tex, defs.specs(), where)
    body = next((n for n in nodes if getattr(n, "environmentname", None) == "document"), None)
    scanner = _Scanner(tex, defs, where)
    scanner.walk(body.nodelist if body is not None else nodes, 0)
    return scanner.result()


def scan_file(path: str | os.PathLike[str]) -> list[TexLabel]:
    """:func:`scan` of a file; an unreadable file is a :class:`LatexError` too."""
    p = Path(path)
    try:
        tex = p.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        try:
            tex = p.read_text(encoding="latin-1")
        except OSError as exc:
            raise LatexError(f"cannot read {p}: {exc.strerror or exc}") from None
    except OSError as exc:
        raise LatexError(f"cannot read {p}: {exc.strerror or exc}") from None
    return scan(tex, where=str(p))
