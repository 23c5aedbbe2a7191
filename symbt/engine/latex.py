r"""The LaTeX parser behind :mod:`.labels`: pylatexenc set up to read a paper's own definitions.

pylatexenc (the ``latex`` extra) parses the document into nodes.  Two things it does not do by
itself, done here:

* macro and environment definitions (``\def``, ``\newcommand``, ``\newenvironment``) are read
  without parsing their bodies -- a body such as ``\begin{equation}`` alone is no balanced LaTeX --
  and classified (:class:`Definitions`): a macro that opens, closes or wraps an equation
  environment, an environment that is one, the theorem environments of ``\newtheorem``;
* a user macro that takes arguments gets them attached (the document is parsed again with its
  argument specification).

>>> d = Definitions()
>>> d.collect(parse_nodes(r"\def\beq{\begin{equation}}\newcommand{\eeq}{\end{equation}}\newtheorem{lem}{Lemma}"))
>>> d.macros["beq"], d.macros["eeq"], d.theorems
(('open', 'equation'), ('close', 'equation'), {'lem'})
>>> d.kind_of_environment("align"), d.kind_of_environment("lem"), d.kind_of_environment("center")
(('equation', True), ('theorem', False), None)
"""
from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

__all__ = ["LatexError", "Definitions", "parse_nodes", "argument_text", "EQUATION_ENVIRONMENTS",
           "MULTIROW_ENVIRONMENTS", "FIGURE_ENVIRONMENTS", "REFERENCE_MACROS", "DEFINERS", "ENV_DEFINERS"]

#: environments whose rows are displays of their own (``\\`` separates them)
MULTIROW_ENVIRONMENTS = frozenset({"align", "align*", "eqnarray", "eqnarray*", "gather", "gather*", "flalign",
                                   "flalign*", "alignat", "alignat*"})
#: every equation-like environment (one display, or one per row for :data:`MULTIROW_ENVIRONMENTS`)
EQUATION_ENVIRONMENTS = MULTIROW_ENVIRONMENTS | {"equation", "equation*", "multline", "multline*", "displaymath"}
#: environments whose label is a figure's
FIGURE_ENVIRONMENTS = frozenset({"figure", "figure*", "table", "table*", "wrapfigure"})
#: macros that reference labels (their argument may list several, comma-separated)
REFERENCE_MACROS = frozenset({"ref", "eqref", "pageref", "autoref", "cref", "Cref", "vref", "nameref"})

# abbreviations understood without a definition in the file (often defined in a style file; see :mod:`.labels`)
_DEFAULT_MACROS = {"be": ("open", "equation"), "ee": ("close", "equation"),
                   "bea": ("open", "eqnarray"), "eea": ("close", "eqnarray")}
#: macros that define macros (the first four with TeX's ``\def`` syntax)
DEFINERS = ("def", "gdef", "edef", "xdef", "newcommand", "renewcommand", "providecommand", "DeclareRobustCommand")
#: macros that define environments
ENV_DEFINERS = ("newenvironment", "renewenvironment", "provideenvironment")


class LatexError(ValueError):
    """A LaTeX source that cannot be read or does not parse (the message is one line, with the position)."""


# --------------------------------------------------------------------------- pylatexenc context

def _pylatexenc() -> Any:
    from pylatexenc import latexwalker  # the 'latex' extra: an ImportError names pylatexenc

    return latexwalker


def _raw_group(w: Any, p: int) -> tuple[str, int]:
    """The verbatim text of the brace group starting at ``p`` (comments and escapes respected) and its end."""
    lw = _pylatexenc()
    tok = w.get_token(p, environments=False)
    if tok.tok != "brace_open":
        raise lw.LatexWalkerParseError(msg="expected '{'", s=w.s, pos=tok.pos)
    depth, start = 1, tok.pos + tok.len
    q = start
    while depth:
        try:
            t = w.get_token(q, environments=False)
        except lw.LatexWalkerEndOfStream:
            raise lw.LatexWalkerParseError(msg="unbalanced braces in a definition", s=w.s, pos=tok.pos) from None
        depth += {"brace_open": 1, "brace_close": -1}.get(t.tok, 0)
        q = t.pos + t.len
        end = t.pos
    return w.s[start:end], q


def _skip_space(s: str, p: int) -> int:
    while p < len(s) and s[p].isspace():
        p += 1
    return p


def _definition_parser() -> Any:
    """An argument parser that reads macro and environment definitions without parsing their bodies.

    A body such as ``\\begin{equation}`` alone is no balanced LaTeX, so it is kept as text and
    classified separately (:func:`_role_of`).
    """
    from pylatexenc.macrospec import MacroStandardArgsParser, ParsedMacroArgs

    class DefinitionArgs(ParsedMacroArgs):
        def __init__(self, name: str, nargs: int, optional: bool, bodies: list[str]):
            super().__init__(argnlist=[], argspec="")
            self.name, self.nargs, self.optional, self.bodies = name, nargs, optional, bodies

    class DefinitionParser(MacroStandardArgsParser):
        def __init__(self, kind: str):
            super().__init__(argspec="")
            self.kind = kind

        # Any: pylatexenc's walker and parsing state (the library ships no type information)
        def parse_args(self, w: Any, pos: int, parsing_state: Any = None) -> tuple[Any, int, int]:
            lw = _pylatexenc()
            s, p = w.s, _skip_space(w.s, pos)
            if p < len(s) and s[p] == "*":
                p += 1
            p = _skip_space(s, p)
            if self.kind == "def":  # \def\name<params>{body}
                tok = w.get_token(p, environments=False)
                if tok.tok != "macro":
                    raise lw.LatexWalkerParseError(msg="\\def without a macro name", s=s, pos=p)
                name, p = tok.arg, tok.pos + tok.len
                brace = s.find("{", p)
                if brace < 0:
                    raise lw.LatexWalkerParseError(msg=f"\\def\\{name} without a body", s=s, pos=p)
                params = s[p:brace]
                body, end = _raw_group(w, brace)
                return DefinitionArgs(name, params.count("#"), False, [body]), pos, end - pos
            if s.startswith("{", p):  # \newcommand{\name} / \newenvironment{name}
                inner, p = _raw_group(w, p)
                name = inner.strip().lstrip("\\")
            else:
                tok = w.get_token(p, environments=False)
                name, p = tok.arg, tok.pos + tok.len
            nargs, optional = 0, False
            for i in range(2):  # [n][default]
                q = _skip_space(s, p)
                if not s.startswith("[", q):
                    break
                close = s.find("]", q)
                if close < 0:
                    raise lw.LatexWalkerParseError(msg=f"unclosed '[' in the definition of {name}", s=s, pos=q)
                if i == 0:
                    try:
                        nargs = int(s[q + 1:close])
                    except ValueError:
                        raise lw.LatexWalkerParseError(msg=f"bad argument count in the definition of {name}",
                                                       s=s, pos=q) from None
                else:
                    optional = True
                p = close + 1
            bodies = []
            for _ in range(2 if self.kind == "environment" else 1):
                body, p = _raw_group(w, _skip_space(s, p))
                bodies.append(body)
            return DefinitionArgs(name, nargs, optional, bodies), pos, p - pos

    return DefinitionParser


def _context(user_specs: Sequence[Any]) -> Any:
    lw = _pylatexenc()
    from pylatexenc.macrospec import MacroSpec, std_macro

    parser = _definition_parser()
    # no specials (~, --, ``): labels never hide in them, and testing for them is a third of the time
    ctx = lw.get_default_latex_context_db().filter_context(keep_which=["macros", "environments"])
    ours = [MacroSpec(n, args_parser=parser("def")) for n in ("def", "gdef", "edef", "xdef")]
    ours += [MacroSpec(n, args_parser=parser("command")) for n in DEFINERS[4:]]
    ours += [MacroSpec(n, args_parser=parser("environment")) for n in ENV_DEFINERS]
    ours += [std_macro("newtheorem", "*{[{["), std_macro("tag", "*{"), std_macro("caption", "*[{"),
             std_macro("subsubsection", "*[{"), *[std_macro(r, "*{") for r in sorted(REFERENCE_MACROS)]]
    ctx.add_context_category("symbt-labels", macros=ours, prepend=True)
    if user_specs:
        ctx.add_context_category("symbt-user", macros=user_specs, prepend=True)
    return ctx


def parse_nodes(tex: str, user_specs: Sequence[Any] = (), where: str = "<tex>") -> list[Any]:
    """pylatexenc's nodes of ``tex`` (strict: a parse error is a :class:`LatexError` naming ``where``:line:column).

    ``user_specs``: pylatexenc macro specifications of the document's own macros (:meth:`Definitions.specs`).
    """
    lw = _pylatexenc()
    w = lw.LatexWalker(tex, latex_context=_context(user_specs), tolerant_parsing=False)
    try:
        nodes, _, _ = w.get_latex_nodes()
    except lw.LatexWalkerError as exc:
        msg = str(getattr(exc, "msg", "") or exc).splitlines()[0]
        pos = getattr(exc, "pos", None)
        at = ""
        if pos is not None:
            line, col = w.pos_to_lineno_colno(pos)
            at = f":{line}:{col + 1}"
        raise LatexError(f"{where}{at}: LaTeX does not parse: {msg}") from None
    return nodes


# --------------------------------------------------------------------------- definitions

def _tokens(text: str) -> list[Any]:
    lw = _pylatexenc()
    w = lw.LatexWalker(text, tolerant_parsing=True)
    out: list[Any] = []
    p = 0
    while True:
        try:
            t = w.get_token(p)
        except lw.LatexWalkerEndOfStream:
            return out
        if t.tok != "comment":
            out.append(t)
        p = t.pos + t.len


def _role_of(body: str, macros: dict[str, tuple[str, str]]) -> tuple[str, str] | None:
    """``("open"|"close"|"wrap", environment)`` for a body that opens, closes or wraps an environment."""
    toks = _tokens(body)
    if len(toks) == 1 and toks[0].tok in ("begin_environment", "end_environment"):
        return ("open" if toks[0].tok == "begin_environment" else "close"), toks[0].arg
    if len(toks) == 1 and toks[0].tok == "macro":
        return macros.get(toks[0].arg)  # an alias of another macro
    if (len(toks) == 4 and toks[0].tok == "begin_environment" and toks[3].tok == "end_environment"
            and toks[0].arg == toks[3].arg and toks[1].arg == "#" and toks[2].arg == "1"):
        return "wrap", toks[0].arg
    return None


@dataclass
class Definitions:
    """What a document defines that matters for its labels (see the module docstring).

    ``macros``: name -> ``("open" | "close" | "wrap", environment)``; ``environments``: a user
    environment -> the environment it opens; ``theorems``: the ``\\newtheorem`` environments;
    ``arity``: user macro -> (number of arguments, whether the first is optional).
    """

    macros: dict[str, tuple[str, str]] = field(default_factory=lambda: dict(_DEFAULT_MACROS))
    environments: dict[str, str] = field(default_factory=dict)  # user environment -> the one it opens
    theorems: set[str] = field(default_factory=set)
    arity: dict[str, tuple[int, bool]] = field(default_factory=dict)  # user macro -> (nargs, optional first)

    def collect(self, nodes: list[Any]) -> None:
        """Record the definitions among ``nodes`` (at any depth), in document order."""
        for node in _iter_nodes(nodes):
            name = getattr(node, "macroname", None)
            argd: Any = getattr(node, "nodeargd", None)
            if name in DEFINERS:
                self.macros.pop(argd.name, None)
                role = _role_of(argd.bodies[0], self.macros)
                if role is not None:
                    self.macros[argd.name] = role
                if argd.nargs:
                    self.arity[argd.name] = (argd.nargs, argd.optional)
            elif name in ENV_DEFINERS:
                role = _role_of(argd.bodies[0], self.macros)
                if role is not None and role[0] == "open":
                    self.environments[argd.name] = role[1]
            elif name == "newtheorem" and argd.argnlist[1] is not None:
                self.theorems.add(argument_text(argd.argnlist[1]))

    def specs(self) -> list[Any]:
        """pylatexenc specifications of the user macros that take arguments."""
        from pylatexenc.macrospec import std_macro

        return [std_macro(n, ("[" if opt else "{") + "{" * (k - 1)) for n, (k, opt) in sorted(self.arity.items())]

    def kind_of_environment(self, env: str) -> tuple[str, bool] | None:
        """``(kind, multirow)`` of an environment, or ``None`` if its labels are not its own."""
        env = self.environments.get(env, env)
        if env in EQUATION_ENVIRONMENTS:
            return "equation", env in MULTIROW_ENVIRONMENTS
        if env in FIGURE_ENVIRONMENTS:
            return "figure", False
        if env in self.theorems:
            return "theorem", False
        return None


def _iter_nodes(nodes: list[Any]) -> Iterator[Any]:
    for node in nodes:
        if node is None:
            continue
        yield node
        yield from _iter_nodes(getattr(node, "nodelist", None) or [])
        argd = getattr(node, "nodeargd", None)
        yield from _iter_nodes(getattr(argd, "argnlist", None) or [])


def argument_text(node: Any) -> str:
    """The verbatim text of an argument, without its braces."""
    v = node.latex_verbatim()
    if getattr(node, "delimiters", None) and v.startswith(node.delimiters[0]):
        v = v[len(node.delimiters[0]):len(v) - len(node.delimiters[1])]
    return v.strip()
