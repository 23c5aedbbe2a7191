"""Single-point bugs planted in Python source: the operators of ``symbt mutate --source``.

A :class:`SourceMutant` is one realistic slip of the kind an audit of symbt planted by hand
(issue 21): a flipped sign, an index shifted by one, a swapped comparison or branch, a dropped
factor, a loosened tolerance, a changed constant.  :func:`find_mutants` walks a module's AST
and returns every site an operator applies to; the mutation itself is a *text* edit of the
node's bytes (the AST gives byte offsets), so the rest of the file -- comments, layout -- is
untouched and the diff is the one line that changed.

Operators (:data:`OPERATORS`):

=================  ============================================================
``sign``           ``a + b`` <-> ``a - b``
``unary-minus``    ``-x`` -> ``x``
``index-shift``    ``v[j]`` -> ``v[j + 1]``, ``v[j - 1]``; ``v[j + 1]``, ``v[j - 1]`` -> ``v[j]``
``compare``        ``<`` <-> ``<=``, ``>`` <-> ``>=``, ``<`` <-> ``>``, ``<=`` <-> ``>=``, ``==`` <-> ``!=``
``branch``         ``if c`` -> ``if not c`` (also ``x if c else y``)
``drop-factor``    ``x / 2`` -> ``x``, ``0.5 * x`` -> ``x`` (a numeric constant factor or divisor)
``tolerance``      a small float ``1e-k`` (below 1e-3) -> ``1e-(k/2)``; ``10 ** -k`` -> ``10 ** (-k / 2)``
``constant``       ``0`` <-> ``1``, ``True`` <-> ``False``
``min-max``        ``min`` <-> ``max`` (also ``np.minimum`` <-> ``np.maximum``, ``.min`` <-> ``.max``)
``abs``            ``abs(x)`` -> ``x`` (also ``np.abs``, ``math.fabs``, ``mp.fabs``)
=================  ============================================================

Not mutated: annotations, docstrings and other strings, f-strings, ``raise`` statements (error
messages), ``print``/``warn`` calls, ``__all__``, ``if TYPE_CHECKING:`` blocks, and ``if __name__ ==
"__main__":`` blocks (a module's command line, run only as ``python -m``: importing the module never
runs it, so no claim can see it -- and its guard negated would run the command at import).

A mutant's :attr:`~SourceMutant.id` is stable under edits elsewhere in the file: module, line,
operator and a hash of the line's text, the replaced snippet, its replacement and its
occurrence among identical ones -- the key of the equivalents file
(:mod:`symbt.engine.mutate_source`).  Mutants whose mutated file is identical (``j + 1 - 1``
...) are kept once.

>>> src = "def f(x, j):\\n    return x[j] + 0.5 * abs(x[0])\\n"
>>> ms = find_mutants(src, "demo")
>>> sorted({m.operator for m in ms})
['abs', 'constant', 'drop-factor', 'index-shift', 'sign']
>>> m = next(m for m in ms if m.operator == "sign")
>>> m.line, m.diff
(2, '-     return x[j] + 0.5 * abs(x[0])\\n+     return x[j] - 0.5 * abs(x[0])')
>>> m.id == find_mutants("# a comment\\n" + src, "demo")[ms.index(m)].id.replace(":3:", ":2:")
True
"""
from __future__ import annotations

import ast
import bisect
import hashlib
import math
import re
from dataclasses import dataclass

__all__ = ["SourceMutant", "find_mutants", "OPERATORS", "module_level_lines", "parse_equivalents",
           "match_equivalents", "UsageError"]

OPERATORS = ("sign", "unary-minus", "index-shift", "compare", "branch", "drop-factor", "tolerance", "constant",
             "min-max", "abs")

_COMPARE_SWAPS: dict[type, tuple[tuple[type, str], ...]] = {
    ast.Lt: ((ast.LtE, "<="), (ast.Gt, ">")), ast.LtE: ((ast.Lt, "<"), (ast.GtE, ">=")),
    ast.Gt: ((ast.GtE, ">="), (ast.Lt, "<")), ast.GtE: ((ast.Gt, ">"), (ast.LtE, "<=")),
    ast.Eq: ((ast.NotEq, "!="),), ast.NotEq: ((ast.Eq, "=="),)}
_COMPARE_TOKEN = {ast.Lt: "<", ast.LtE: "<=", ast.Gt: ">", ast.GtE: ">=", ast.Eq: "==", ast.NotEq: "!="}
_MINMAX = {"min": "max", "max": "min", "minimum": "maximum", "maximum": "minimum", "amin": "amax", "amax": "amin",
           "nanmin": "nanmax", "nanmax": "nanmin"}
_ABS = {"abs", "fabs", "absolute"}
_QUIET_CALLS = {"print", "warn", "debug", "info", "warning", "error", "exception", "write"}
#: a float constant below this (and above 0) is read as a tolerance
TOLERANCE_BELOW = 1e-3



def _is_main_guard(test: ast.expr) -> bool:
    """``__name__ == "__main__"`` (either order).

    >>> _is_main_guard(ast.parse('__name__ == "__main__"', mode="eval").body)
    True
    """
    if not (isinstance(test, ast.Compare) and len(test.ops) == 1 and isinstance(test.ops[0], ast.Eq)):
        return False
    sides = [test.left, test.comparators[0]]
    return (any(isinstance(x, ast.Name) and x.id == "__name__" for x in sides)
            and any(isinstance(x, ast.Constant) and x.value == "__main__" for x in sides))

class UsageError(ValueError):
    """Bad input to ``symbt mutate --source`` (an unknown module, a malformed equivalents file): one
    line on stderr, exit status 2."""


@dataclass(frozen=True)
class SourceMutant:
    """One mutant of one module: where, which operator, and the byte edit that makes it."""

    module: str
    line: int
    operator: str
    start: int          # byte offsets of the replaced text in the file
    end: int
    original: str       # the replaced text
    replacement: str
    line_text: str      # the (first) source line, unmutated
    mutated_line: str   # the same line(s) mutated
    key: str            # hash of line text, snippet, replacement, occurrence

    @property
    def id(self) -> str:
        """``module:line:operator:hash`` (see the module docstring)."""
        return f"{self.module}:{self.line}:{self.operator}:{self.key}"

    @property
    def description(self) -> str:
        return f"{self.original.strip()} -> {self.replacement.strip()}"

    @property
    def diff(self) -> str:
        """The one-line diff: ``- old`` / ``+ new``."""
        return f"- {self.line_text.rstrip()}\n+ {self.mutated_line.rstrip()}"

    def apply(self, source: bytes) -> bytes:
        """The mutated file (``source`` is the file this mutant was found in)."""
        return source[:self.start] + self.replacement.encode("utf-8") + source[self.end:]


class _Finder(ast.NodeVisitor):
    def __init__(self, data: bytes) -> None:
        self.data = data
        self.starts = [0]
        for line in data.splitlines(keepends=True):
            self.starts.append(self.starts[-1] + len(line))
        self.edits: list[tuple[int, str, int, int, str]] = []   # (line, operator, start, end, replacement)
        self.index_depth = 0

    # ------------------------------------------------------------------ offsets
    def off(self, line: int, col: int) -> int:
        return self.starts[line - 1] + col

    def span(self, node: ast.AST) -> tuple[int, int]:
        return (self.off(node.lineno, node.col_offset),  # type: ignore[attr-defined]
                self.off(node.end_lineno, node.end_col_offset))  # type: ignore[attr-defined]

    def text(self, node: ast.AST) -> str:
        a, b = self.span(node)
        return self.data[a:b].decode("utf-8")

    def add(self, node: ast.AST, operator: str, start: int, end: int, replacement: str) -> None:
        line = bisect.bisect_right(self.starts, start)
        self.edits.append((line, operator, start, end, replacement))

    def token_between(self, a: ast.AST, b: ast.AST, token: str) -> tuple[int, int] | None:
        """The offsets of ``token`` between nodes ``a`` and ``b`` if it is the only thing there besides
        brackets, blanks and line continuations."""
        lo, hi = self.span(a)[1], self.span(b)[0]
        between = self.data[lo:hi].decode("utf-8")
        i = between.find(token)
        rest = between[:i] + between[i + len(token):] if i >= 0 else "#"
        if i < 0 or rest.replace("(", "").replace(")", "").replace("\\", "").strip():
            return None
        start = lo + len(between[:i].encode("utf-8"))
        return start, start + len(token.encode("utf-8"))

    # ------------------------------------------------------------------ skipped subtrees
    def visit_JoinedStr(self, node: ast.JoinedStr) -> None:
        return

    def visit_Raise(self, node: ast.Raise) -> None:
        return

    def visit_AnnAssign(self, node: ast.AnnAssign) -> None:
        if node.value is not None:
            self.visit(node.value)

    def visit_arg(self, node: ast.arg) -> None:
        return

    def _visit_def(self, node: ast.FunctionDef | ast.AsyncFunctionDef) -> None:
        for d in node.decorator_list:
            self.visit(d)
        self.visit(node.args)
        for stmt in node.body:
            self.visit(stmt)

    visit_FunctionDef = _visit_def
    visit_AsyncFunctionDef = _visit_def

    def visit_Assign(self, node: ast.Assign) -> None:
        if any(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
            return
        self.generic_visit(node)

    def visit_Expr(self, node: ast.Expr) -> None:
        if isinstance(node.value, ast.Constant):   # a docstring or a bare string
            return
        self.generic_visit(node)

    # ------------------------------------------------------------------ operators
    def visit_If(self, node: ast.If) -> None:
        if isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING":
            return
        if _is_main_guard(node.test):
            return
        self._branch(node.test)
        self.generic_visit(node)

    def visit_IfExp(self, node: ast.IfExp) -> None:
        self._branch(node.test)
        self.generic_visit(node)

    def _branch(self, test: ast.expr) -> None:
        a, b = self.span(test)
        if isinstance(test, ast.UnaryOp) and isinstance(test.op, ast.Not):
            o1, o2 = self.span(test.operand)
            inner = self.data[o1:o2].decode("utf-8")
            # an operand over several lines needs the brackets that `not (...)` had
            self.add(test, "branch", a, b, f"({inner})" if "\n" in inner else inner)
        else:
            self.add(test, "branch", a, b, f"not ({self.text(test)})")

    def visit_BinOp(self, node: ast.BinOp) -> None:
        swap = {ast.Add: ("+", "-"), ast.Sub: ("-", "+")}.get(type(node.op))
        if swap:
            where = self.token_between(node.left, node.right, swap[0])
            if where:
                self.add(node, "sign", where[0], where[1], swap[1])
        a, b = self.span(node)
        if isinstance(node.op, (ast.Mult, ast.Div)) and _factor(node.right):
            self.add(node, "drop-factor", a, b, self.text(node.left))
        if isinstance(node.op, ast.Mult) and _factor(node.left):
            self.add(node, "drop-factor", a, b, self.text(node.right))
        if isinstance(node.op, ast.Pow) and _ten(node.left) and isinstance(node.right, ast.UnaryOp) \
                and isinstance(node.right.op, ast.USub):   # 10 ** -k: a tolerance written as a power
            e1, e2 = self.span(node.right)
            self.add(node, "tolerance", e1, e2, f"({self.text(node.right)}) / 2")
        self.generic_visit(node)

    def visit_UnaryOp(self, node: ast.UnaryOp) -> None:
        if isinstance(node.op, ast.USub) and not isinstance(node.operand, ast.Constant):
            a, b = self.span(node)
            self.add(node, "unary-minus", a, b, self.text(node.operand))
        self.generic_visit(node)

    def visit_Compare(self, node: ast.Compare) -> None:
        left: ast.AST = node.left
        for op, right in zip(node.ops, node.comparators):
            token = _COMPARE_TOKEN.get(type(op))
            where = self.token_between(left, right, token) if token else None
            if where:
                for _, new in _COMPARE_SWAPS[type(op)]:
                    self.add(node, "compare", where[0], where[1], new)
            left = right
        self.generic_visit(node)

    def visit_Subscript(self, node: ast.Subscript) -> None:
        s = node.slice
        if isinstance(s, ast.Name):
            a, b = self.span(s)
            self.add(s, "index-shift", a, b, f"{s.id} + 1")
            self.add(s, "index-shift", a, b, f"{s.id} - 1")
        elif (isinstance(s, ast.BinOp) and isinstance(s.op, (ast.Add, ast.Sub)) and isinstance(s.right, ast.Constant)
              and s.right.value == 1 and isinstance(s.left, ast.Name)):
            a, b = self.span(s)
            self.add(s, "index-shift", a, b, s.left.id)
        self.generic_visit(node)

    def visit_Constant(self, node: ast.Constant) -> None:
        v = node.value
        a, b = self.span(node)
        if v is True or v is False:
            self.add(node, "constant", a, b, str(not v))
        elif isinstance(v, int) and v in (0, 1):
            self.add(node, "constant", a, b, str(1 - v))
        elif isinstance(v, float) and 0 < v < TOLERANCE_BELOW:
            self.add(node, "tolerance", a, b, repr(float(f"{10 ** (math.log10(v) / 2):.3g}")))

    def visit_Call(self, node: ast.Call) -> None:
        f = node.func
        name = f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else ""
        if name in _QUIET_CALLS:
            return
        if name in _MINMAX and (isinstance(f, ast.Name) or isinstance(f, ast.Attribute)):
            a, b = self.span(f)
            if isinstance(f, ast.Attribute):
                a = b - len(name)
            self.add(f, "min-max", a, b, _MINMAX[name])
        if name in _ABS and len(node.args) == 1 and not node.keywords:
            a, b = self.span(node)
            self.add(node, "abs", a, b, self.text(node.args[0]))
        self.generic_visit(node)


def _factor(node: ast.expr) -> bool:
    """A numeric constant factor worth dropping (not 0, 1 or -1)."""
    return (isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool)
            and node.value not in (0, 1, -1))


def _ten(node: ast.expr) -> bool:
    """``10``, ``10.0`` or a call of one (``mpf(10)``)."""
    if isinstance(node, ast.Call) and len(node.args) == 1:
        node = node.args[0]
    return isinstance(node, ast.Constant) and node.value in (10, "10") and not isinstance(node.value, bool)


def _lines_of(data: bytes, start: int, end: int) -> tuple[int, int]:
    a = data.rfind(b"\n", 0, start) + 1
    b = data.find(b"\n", end)
    return a, (len(data) if b < 0 else b)


def find_mutants(source: str | bytes, module: str) -> list[SourceMutant]:
    """Every mutant of a module's source, in file order (see the module docstring).

    ``source`` that does not parse raises :class:`SyntaxError`.
    """
    data = source.encode("utf-8") if isinstance(source, str) else source
    finder = _Finder(data)
    finder.visit(ast.parse(data))
    seen: set[tuple[int, int, str]] = set()
    seen_keys: dict[str, int] = {}
    out: list[SourceMutant] = []
    for line, operator, start, end, replacement in sorted(finder.edits, key=lambda e: (e[2], e[3], e[1], e[4])):
        # the same edit from two operators, or none at all, is one mutant or none (every edit is an
        # expression for an expression or a token for a token, so the file still parses: not re-parsed)
        if data[start:end] == replacement.encode("utf-8") or (start, end, replacement) in seen:
            continue
        seen.add((start, end, replacement))
        a, b = _lines_of(data, start, end)
        line_text = data[a:b].decode("utf-8")
        mutated_line = (data[a:start] + replacement.encode("utf-8") + data[end:b]).decode("utf-8")
        original = data[start:end].decode("utf-8")
        raw = f"{line_text.strip()}|{operator}|{original}|{replacement}"
        n = seen_keys[raw] = seen_keys.get(raw, -1) + 1
        key = hashlib.sha1(f"{raw}|{n}".encode()).hexdigest()[:8]
        out.append(SourceMutant(module, line, operator, start, end, original, replacement, line_text.split("\n")[0],
                                mutated_line.split("\n")[0] if "\n" not in original else mutated_line, key))
    return out


def module_level_lines(source: str | bytes) -> set[int]:
    """The lines run when the module is imported, not when a function is called: module and class
    bodies, decorators, default values.  A mutant there can change any claim.

    >>> sorted(module_level_lines("TOL = 1e-12\\ndef f(x, t=2):\\n    return x\\n"))
    [1, 2]
    """
    tree = ast.parse(source)
    lines: set[int] = set()

    def mark(node: ast.AST) -> None:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for d in [*node.decorator_list, *node.args.defaults, *[k for k in node.args.kw_defaults if k]]:
                mark(d)
            return
        if isinstance(node, ast.Lambda):
            for d in node.args.defaults:
                mark(d)
            return
        if isinstance(node, ast.expr):   # expressions only: a compound statement spans function bodies
            lines.update(range(node.lineno, (node.end_lineno or node.lineno) + 1))
        for child in ast.iter_child_nodes(node):
            mark(child)

    mark(tree)
    return lines


# --------------------------------------------------------------------------- the equivalents file

def parse_equivalents(text: str, where: str = "equivalents file") -> dict[str, str]:
    """``[[mutant]]`` tables with ``id`` and ``reason`` -> {id: reason}; anything else raises
    :class:`UsageError` (one line)."""
    from .._files import toml_loads

    try:
        doc = toml_loads(text)
    except ValueError as exc:       # tomllib.TOMLDecodeError
        raise UsageError(f"{where}: not TOML: {exc}") from None
    extra = set(doc) - {"mutant"}
    if extra:
        raise UsageError(f"{where}: unknown table(s) {', '.join(sorted(extra))}; expected [[mutant]] entries")
    entries = doc.get("mutant", [])
    if not isinstance(entries, list):
        raise UsageError(f"{where}: 'mutant' must be an array of tables ([[mutant]])")
    out: dict[str, str] = {}
    for i, e in enumerate(entries, 1):
        if not isinstance(e, dict) or set(e) != {"id", "reason"} or not all(isinstance(v, str) for v in e.values()):
            raise UsageError(f"{where}: [[mutant]] #{i} must have exactly the strings 'id' and 'reason'")
        if not re.fullmatch(r"[\w.]+:\d+:[\w-]+:[0-9a-f]{8}", e["id"]) or not e["reason"].strip():
            raise UsageError(f"{where}: [[mutant]] #{i}: id {e['id']!r} is not module:line:operator:hash, "
                             "or the reason is empty")
        if e["id"] in out:
            raise UsageError(f"{where}: [[mutant]] #{i}: {e['id']} is marked twice")
        out[e["id"]] = e["reason"]
    return out


def match_equivalents(marked: dict[str, str], mutants: list[SourceMutant],
                       modules: set[str]) -> tuple[dict[str, str], list[dict[str, str]]]:
    """{mutant id: reason} for the marked ones (an id whose line moved matches by module, operator and
    hash), and the stale marks (of the modules in play, by dotted prefix) that match nothing."""
    by_id = {m.id: m for m in mutants}
    by_key: dict[tuple[str, str, str], list[SourceMutant]] = {}
    for m in mutants:
        by_key.setdefault((m.module, m.operator, m.key), []).append(m)
    found: dict[str, str] = {}
    stale = []
    for mid, reason in marked.items():
        module, _, operator, key = mid.rsplit(":", 3)
        if mid in by_id:
            found[mid] = reason
        elif len(by_key.get((module, operator, key), [])) == 1:
            found[by_key[(module, operator, key)][0].id] = f"{reason} (marked as {mid}: the line moved)"
        elif any(module == m or module.startswith(m + ".") for m in modules):
            stale.append({"id": mid, "reason": reason})
    return found, stale
