r"""A display's LaTeX as MathML (``latex2mathml``), with the paper's own macros expanded first.

:func:`macros_of` reads the user macros of a ``.tex`` (``\def\x{...}``, ``\newcommand{\x}[n]{...}``,
``\renewcommand``, ``\DeclareMathOperator``); :func:`to_mathml` expands them in a display's source
and converts it.  A display that does not convert -- the converter raises, or a command it does
not know is left in the output as text -- is ``None``: the page then shows the escaped source,
never drops it.

>>> m = macros_of(r"\def\lm{\lambda}\newcommand{\tl}[1]{\tilde{#1}}")
>>> m["lm"], m["tl"]
((0, '\\lambda'), (1, '\\tilde{#1}'))
>>> expand(r"\tl{q}_j + \lm", m)
'\\tilde{q}_j + \\lambda'
>>> "<mfrac>" in to_mathml(r"\frac{1}{\lm}", m)
True
>>> to_mathml(r"\unknownmacro{x}") is None
True
"""
from __future__ import annotations

import re

__all__ = ["macros_of", "expand", "to_mathml", "inline_parts", "SUBSTITUTES"]

#: macros whose TeX bodies are typesetting tricks with no MathML meaning -> what they denote
SUBSTITUTES = {"dblone": r"\mathbb{1}", "id": r"\mathbb{1}", "R": r"\mathbb{R}", "C": r"\mathbb{C}"}

_NAME = re.compile(r"\\([A-Za-z]+)")
_LEFT_OVER = re.compile(r">[^<]*\\[A-Za-z]+[^<]*<|<mi>&(?:amp;)?</mi>")
# latex2mathml aligns the rows of split but prints the & of aligned/gathered as text
_ALIGNED = re.compile(r"\\(begin|end)\{(?:aligned|gathered|alignedat)\}")
_REF = re.compile(r"\\(eq)?c?ref\*?\{([^{}]*)\}")
_PROSE = re.compile(
    r"\\begin\{(?P<env>equation|align|gather|multline|eqnarray|displaymath)(?P<star>\*?)\}(?P<body>.*?)"
    r"\\end\{(?P=env)(?P=star)\}"
    r"|\\\[(?P<bracket>.*?)\\\]|\$\$(?P<dd>.*?)\$\$|\$(?P<inline>[^$]+)\$"
    r"|\\(?:eq)?c?ref\{(?P<ref>[^{}]*)\}"
    r"|(?P<text>(?:[^\\$]|\\(?!begin\{(?:equation|align|gather|multline|eqnarray|displaymath)|\[|(?:eq)?c?ref\{))+)",
    re.S)
_DROP = re.compile(r"\\(?:label|nonumber|notag)\b(?:\{[^{}]*\})?|\\\\\s*$")
# text-mode spacing and sizing commands latex2mathml does not know; they carry no mathematics
_SPACING = re.compile(r"\\(?:displaystyle|textstyle|scriptstyle|small|normalsize|qquad|quad|hskip\s*-?[\d.]+\w*)\b")


def _group(s: str, i: int) -> tuple[str, int] | None:
    """The braced group starting at ``s[i]`` (after blanks): (its content, the index after it)."""
    while i < len(s) and s[i] in " \t\n":
        i += 1
    if i >= len(s) or s[i] != "{":
        return None
    depth = 0
    for j in range(i, len(s)):
        ch = s[j]
        if ch == "\\":
            continue
        if ch == "{" and (j == 0 or s[j - 1] != "\\"):
            depth += 1
        elif ch == "}" and s[j - 1] != "\\":
            depth -= 1
            if depth == 0:
                return s[i + 1:j], j + 1
    return None


def macros_of(tex: str) -> dict[str, tuple[int, str]]:
    r"""name -> (number of arguments, body) for every macro ``tex`` defines (later definitions win)."""
    out: dict[str, tuple[int, str]] = {}
    for m in re.finditer(r"\\(def|newcommand\*?|renewcommand\*?|providecommand\*?|DeclareMathOperator\*?)", tex):
        i = m.end()
        kind = m.group(1).rstrip("*")
        name_group = _group(tex, i) if kind != "def" else None
        if name_group is not None:
            name, i = name_group[0].strip(), name_group[1]
        else:
            nm = re.match(r"\s*(\\[A-Za-z]+)", tex[i:])
            if nm is None:
                continue
            name, i = nm.group(1), i + nm.end()
        if not name.startswith("\\") or not name[1:].isalpha():
            continue
        nargs = 0
        arity = re.match(r"\s*\[(\d)\]", tex[i:])
        if arity and kind != "def":
            nargs, i = int(arity.group(1)), i + arity.end()
        elif kind == "def":
            params = re.match(r"((?:#\d)*)", tex[i:])
            if params and params.group(1):
                nargs, i = len(params.group(1)) // 2, i + params.end()
        body = _group(tex, i)
        if body is None:
            continue
        text = body[0] if kind != "DeclareMathOperator" else r"\operatorname{" + body[0] + "}"
        out[name[1:]] = (nargs, text)
    return out


def expand(source: str, macros: dict[str, tuple[int, str]], *, rounds: int = 8) -> str:
    """``source`` with the user's macros (and :data:`SUBSTITUTES`) replaced by their bodies."""
    table = dict(macros)
    table.update({k: (0, v) for k, v in SUBSTITUTES.items() if k in macros or k not in table})
    for _ in range(rounds):
        out, pos, changed = [], 0, False
        for m in _NAME.finditer(source):
            if m.start() < pos or (m.start() > 0 and source[m.start() - 1] == "\\"):
                continue
            name = m.group(1)
            if name not in table:
                continue
            nargs, body = table[name]
            end, args = m.end(), []
            for _k in range(nargs):
                g = _group(source, end)
                if g is None:
                    break
                args.append(g[0])
                end = g[1]
            if len(args) < nargs:
                continue
            for k, a in enumerate(args, 1):
                body = body.replace(f"#{k}", a)
            if end < len(source) and source[end].isalpha() and body[-1:].isalpha():
                body += " "
            out += [source[pos:m.start()], body]
            pos, changed = end, True
        out.append(source[pos:])
        source = "".join(out)
        if not changed:
            break
    return source


def inline_parts(text: str) -> list[tuple[str, str]]:
    r"""A theorem's or caption's text split into ``("text" | "math" | "display" | "ref", content)`` pieces.

    >>> inline_parts(r"If $x>0$ then (\ref{a}) holds")
    [('text', 'If '), ('math', 'x>0'), ('text', ' then ('), ('ref', 'a'), ('text', ') holds')]
    >>> inline_parts(r"so \begin{equation*} y = 1 \end{equation*}.")
    [('text', 'so '), ('display', ' y = 1 '), ('text', '.')]
    """
    out: list[tuple[str, str]] = []
    for m in _PROSE.finditer(text):
        if m.group("text"):
            out.append(("text", m.group("text")))
        elif m.group("env") is not None:
            out.append(("display", m.group("body")))
        elif m.group("bracket") is not None or m.group("dd") is not None:
            out.append(("display", m.group("bracket") or m.group("dd") or ""))
        elif m.group("inline") is not None:
            out.append(("math", m.group("inline")))
        elif m.group("ref") is not None:
            out.append(("ref", m.group("ref")))
    return out


def to_mathml(source: str, macros: dict[str, tuple[int, str]] | None = None, *,
              display: str = "block") -> str | None:
    """``source`` as a ``<math>`` element (``display`` block or inline), or ``None`` when it does not
    convert cleanly."""
    try:
        from latex2mathml.converter import convert
    except ImportError:
        return None
    text = _REF.sub(lambda m: "\\text{" + ("(%s)" if m.group(1) else "%s") % m.group(2) + "}", source)
    text = _SPACING.sub(" ", _DROP.sub("", expand(text, macros or {}))).strip()
    text = _ALIGNED.sub(lambda m: f"\\{m.group(1)}{{split}}", text)
    if not text.endswith("\\right."):
        text = text.rstrip(",.;").strip()   # the sentence's punctuation
    if "&" in text and "\\begin" not in text:  # one row of an align: its alignment points
        text = "\\begin{split}" + text + "\\end{split}"
    if not text:
        return None
    try:
        out = convert(text, display=display)
    except Exception:  # the converter's errors are many and untyped: any of them means "show the source"
        return None
    if _LEFT_OVER.search(out):
        return None
    return out
