r"""Mutation operators: small, deliberate errors injected into a statement.

In the style of ``sympy.codegen.rewriting`` the operators are *values* --
:class:`Mutation` (a name, a ``query`` saying where it applies and a ``value``
giving the replacements) -- collected in the named tuple :data:`OPERATORS` and
applied by one function, :func:`mutants`.  A claim exposes the statements it
checks as named parts (SymPy expressions or matrices, or plain numbers such as a
branch sign or a printed constant); the harness (:mod:`symbt.engine.mutate`) reruns
the claim's own check on every mutant.  A mutant the check still accepts is either
*equivalent* (the mutated part is provably the same function) or a *survivor* (the
check cannot see the error -- a defect of the check).

Operators:

``flip_sign``     a term ``t`` of a sum becomes ``-t``
``drop_term``     a term of a sum is removed
``swap_index``    two indexed symbols (``p1``/``p2``, ``E_j``/``E_jp1``, ``lambda1``/``lambda2``) are
                  exchanged inside one term
``change_const``  an integer or rational ``n`` becomes ``n + 1``
``perturb``       a numeric coefficient is multiplied by ``1 + 1e-6``
``convention``    the branch or sign convention is swapped: ``sign(x) -> -sign(x)``,
                  ``sqrt(x) -> -sqrt(x)``, ``Abs(x) -> x``, a symbol named ``branch``/``b`` -> its negative

>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> [m.operator for m in mutants(x + 2*y)]
['flip_sign', 'flip_sign', 'drop_term', 'drop_term', 'change_const', 'perturb']
>>> mutants(x + 2*y)[0].expr
-x + 2*y

A part no operator applies to gives no mutant, so the check is not tested through it;
:func:`why_no_mutants` says why and what to declare instead:

>>> why_no_mutants(sp.S(0))
'it is 0: declare both sides of the statement as parts (e.g. lhs and rhs) and let the check compare them'
"""
from __future__ import annotations

import random
import re
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any, NamedTuple

import sympy as sp

__all__ = ["Mutation", "Mutant", "OPERATORS", "mutants", "mutate_value", "index_parts", "why_no_mutants"]

PERTURBATION = sp.Rational(1, 10**6)


class Mutation(NamedTuple):
    """One mutation operator: where it applies (``query``) and what it yields there (``value``)."""

    name: str
    query: Callable[[sp.Basic], bool]
    value: Callable[[sp.Basic], list[tuple[str, sp.Basic]]]


@dataclass(frozen=True)
class Mutant:
    """A mutated statement part: which operator, what it changed, the new value."""

    operator: str
    description: str
    expr: Any


# --------------------------------------------------------------------------- indexed symbols

_INDEX = re.compile(r"^(?P<stem>.*?)(?P<idx>_?(?:\d+|jp1|jm1|j))$")


def index_parts(sym: sp.Symbol) -> tuple[str, str] | None:
    """``("p", "1")`` for ``p1``; ``("E_", "jp1")`` for ``E_jp1``; ``None`` if not indexed."""
    m = _INDEX.match(sym.name)
    if not m or not m.group("stem"):
        return None
    stem, idx = m.group("stem"), m.group("idx")
    if idx.startswith("_"):
        stem, idx = stem + "_", idx[1:]
    return stem, idx


def _index_pairs(expr: sp.Basic) -> list[tuple[sp.Symbol, sp.Symbol]]:
    groups: dict[str, list[sp.Symbol]] = {}
    for s in sorted(expr.free_symbols, key=lambda s: s.name):
        parts = index_parts(s)
        if parts:
            groups.setdefault(parts[0], []).append(s)
    return [(a, b) for syms in groups.values() for i, a in enumerate(syms) for b in syms[i + 1:]]


# --------------------------------------------------------------------------- operators

def _flip(e: sp.Basic) -> list[tuple[str, sp.Basic]]:
    args = list(e.args)
    return [(f"flip the sign of {sp.sstr(t)}", sp.Add(*args[:i], -t, *args[i + 1:]))
            for i, t in enumerate(args)]


def _drop(e: sp.Basic) -> list[tuple[str, sp.Basic]]:
    args = list(e.args)
    return [(f"drop the term {sp.sstr(t)}", sp.Add(*args[:i], *args[i + 1:])) for i, t in enumerate(args)]


def _swap(e: sp.Basic) -> list[tuple[str, sp.Basic]]:
    out = []
    pairs = _index_pairs(e)
    for i, t in enumerate(e.args):
        for a, b in pairs:
            u = t.xreplace({a: b, b: a})
            if u != t:
                out.append((f"swap {a} and {b} in {sp.sstr(t)}", sp.Add(*e.args[:i], u, *e.args[i + 1:])))
    return out


def _is_term_sum(e: sp.Basic) -> bool:
    return isinstance(e, sp.Add)


def _const(e: sp.Basic) -> list[tuple[str, sp.Basic]]:
    n = e
    new = n - 1 if n == -1 else n + 1
    return [(f"change the constant {n} to {new}", new)]


def _is_const(e: sp.Basic) -> bool:
    return isinstance(e, sp.Rational) and e not in (sp.S.Zero,)


def _perturb(e: sp.Basic) -> list[tuple[str, sp.Basic]]:
    return [(f"perturb the coefficient {e} by a relative 1e-6", e * (1 + PERTURBATION))]


def _is_coefficient(e: sp.Basic) -> bool:
    return isinstance(e, (sp.Rational, sp.Float)) and e != 0


def _convention(e: sp.Basic) -> list[tuple[str, sp.Basic]]:
    if isinstance(e, sp.Abs):
        return [(f"drop the absolute value in {sp.sstr(e)}", e.args[0])]
    if isinstance(e, sp.Symbol):
        return [(f"swap the branch convention {e} -> -{e}", -e)]
    return [(f"swap the sign convention {sp.sstr(e)} -> -{sp.sstr(e)}", -e)]


def _is_convention(e: sp.Basic) -> bool:
    if isinstance(e, (sp.sign, sp.Abs)):
        return True
    if isinstance(e, sp.Pow) and e.exp == sp.Rational(1, 2):
        return True
    return isinstance(e, sp.Symbol) and e.name in ("branch", "b")


class Operators(NamedTuple):
    flip_sign: Mutation
    drop_term: Mutation
    swap_index: Mutation
    change_const: Mutation
    perturb: Mutation
    convention: Mutation


#: every operator, applied in this order
OPERATORS = Operators(
    flip_sign=Mutation("flip_sign", _is_term_sum, _flip),
    drop_term=Mutation("drop_term", lambda e: isinstance(e, sp.Add) and len(e.args) >= 2, _drop),
    swap_index=Mutation("swap_index", _is_term_sum, _swap),
    change_const=Mutation("change_const", _is_const, _const),
    perturb=Mutation("perturb", _is_coefficient, _perturb),
    convention=Mutation("convention", _is_convention, _convention),
)


# --------------------------------------------------------------------------- application

def _sites(expr: sp.Basic) -> Iterator[tuple[tuple[int, ...], sp.Basic]]:
    """Every node of the tree with its path (preorder; the same node at two paths counts twice)."""
    stack: list[tuple[tuple[int, ...], sp.Basic]] = [((), expr)]
    while stack:
        path, node = stack.pop(0)
        yield path, node
        stack[0:0] = [(path + (i,), a) for i, a in enumerate(node.args)]


def _replace_at(expr: sp.Basic, path: tuple[int, ...], new: sp.Basic) -> sp.Basic:
    if not path:
        return new
    args = list(expr.args)
    args[path[0]] = _replace_at(args[path[0]], path[1:], new)
    return expr.func(*args)


def _expr_mutants(expr: sp.Basic, operators: Operators) -> list[Mutant]:
    out: list[Mutant] = []
    seen: set[Any] = set()
    for op in operators:
        for path, node in _sites(expr):
            # exponents -1 (divisions) and the 1/2 of a square root are structure, not constants
            if op.name in ("change_const", "perturb") and path and _parent_is_pow_exp(expr, path):
                continue
            if not op.query(node):
                continue
            for desc, new in op.value(node):
                mutated = _replace_at(expr, path, new)
                if mutated == expr or mutated in seen:
                    continue
                seen.add(mutated)
                out.append(Mutant(op.name, desc, mutated))
    return out


def _parent_is_pow_exp(expr: sp.Basic, path: tuple[int, ...]) -> bool:
    node = expr
    for i in path[:-1]:
        node = node.args[i]
    return isinstance(node, sp.Pow) and path[-1] == 1


def mutate_value(value: Any) -> list[Mutant]:
    """Mutants of a plain value: a branch sign is negated, a nonzero number negated and perturbed, a
    recorded string (e.g. a hash) changed in its last character.

    >>> [m.expr for m in mutate_value(2.0)], mutate_value(0)
    ([-2.0, 2.000002], [])
    """
    if isinstance(value, bool):
        return [Mutant("convention", f"negate {value}", not value)]
    if isinstance(value, int) and value in (1, -1):
        return [Mutant("convention", f"swap the branch {value:+d} -> {-value:+d}", -value)]
    if isinstance(value, (int, float)) or type(value).__name__ in ("mpf", "Float"):
        if value == 0:  # -0 and 0 * (1 + 1e-6) are 0 again: no mutant (see why_no_mutants)
            return []
        return [Mutant("flip_sign", f"negate {value}", -value),
                Mutant("perturb", f"perturb {value} by a relative 1e-6", value * (1 + 1e-6))]
    if isinstance(value, str) and value:
        last = "0" if value[-1] != "0" else "1"
        return [Mutant("change_const", f"change the last character of {value[:12]}... to {last}", value[:-1] + last)]
    if isinstance(value, tuple):
        out = []
        for i, v in enumerate(value):
            for m in mutate_value(v):
                out.append(Mutant(m.operator, f"entry {i}: {m.description}", value[:i] + (m.expr,) + value[i + 1:]))
        return out
    return []


def mutants(value: Any, operators: Operators = OPERATORS, *, limit: int | None = None,
            seed: int = 0) -> list[Mutant]:
    """Every single-site mutant of ``value`` (a SymPy expression or matrix, or a plain value).

    In order: operator by operator (the order of :data:`OPERATORS`), and for each operator its sites in preorder
    (a node, then the subtree of its first argument, then of its second ...); a matrix entry by entry.

    With ``limit``, a seeded random subset of that size (the same for the same seed).
    """
    if isinstance(value, sp.MatrixBase):
        out = []
        for k, entry in enumerate(value):
            for m in _expr_mutants(sp.sympify(entry), operators):
                M = sp.Matrix(value)
                M[k] = m.expr
                out.append(Mutant(m.operator, f"entry {divmod(k, value.shape[1])}: {m.description}", M))
    elif isinstance(value, sp.Basic):
        out = _expr_mutants(value, operators)
    else:
        out = mutate_value(value)
    if limit is not None and len(out) > limit:
        rng = random.Random(seed)
        out = sorted(rng.sample(out, limit), key=out.index)
    return out


_SIDES = "declare both sides of the statement as parts (e.g. lhs and rhs) and let the check compare them"


def why_no_mutants(value: Any) -> str:
    """Why ``value`` (a statement part) gives no mutant, and what to declare instead.

    A part no operator applies to leaves the check untested: a zero right-hand side, a bare
    symbol, a matrix of bare symbols, a product of functions with no sum or numeric constant
    in it, or a value of a type the operators do not know.

    >>> import sympy as sp
    >>> a, b = sp.symbols("a11 a12")
    >>> why_no_mutants(sp.Matrix([[a, b]]))
    "a matrix of bare symbols and zeros: declare the entries' expressions (the matrix the statement is about)"
    >>> why_no_mutants(a)
    'it is the bare symbol a11: declare the expression it stands for'
    """
    if isinstance(value, sp.MatrixBase):
        entries = [sp.sympify(e) for e in value]
        if all(e == 0 for e in entries):
            return "it is a zero matrix: " + _SIDES
        if all(isinstance(e, sp.Symbol) or e.is_number for e in entries):
            return ("a matrix of bare symbols and zeros: declare the entries' expressions "
                    "(the matrix the statement is about)")
        return ("no operator applies to any entry (no sum, no numeric constant, no sign, Abs or sqrt): "
                "declare the entries' expressions with their terms, or " + _SIDES)
    if isinstance(value, sp.Basic):
        if value == 0:
            return "it is 0: " + _SIDES
        if isinstance(value, sp.Symbol):
            return f"it is the bare symbol {value}: declare the expression it stands for"
        return (f"no operator applies to {_short(value)} (no sum, no numeric constant other than 0, no sign, "
                "Abs or sqrt): declare the expression with its terms, or " + _SIDES)
    if isinstance(value, (bool, int, float, str, tuple)) or type(value).__name__ in ("mpf", "Float"):
        if value == 0 or value in ("", ()):
            return f"it is {value!r}: " + _SIDES
        return f"no operator applies to {value!r}: " + _SIDES
    return (f"a {type(value).__name__} is not mutated: parts must be SymPy expressions or matrices, numbers, "
            "strings or tuples of them")


def _short(expr: Any, limit: int = 60) -> str:
    text = sp.sstr(expr)
    return text if len(text) <= limit else text[:limit - 3] + "..."
