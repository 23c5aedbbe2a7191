"""The exact layer: a difference reduced to zero as a rational function (see :mod:`symbt.proof`)."""
from __future__ import annotations

import os
from collections.abc import Mapping
from functools import cache

import sympy as sp

from .exponentials import describe_variables, exponentials_as_monomials
from .relations import relation_poly

__all__ = ["reduce_modulo", "exact_zero", "is_rational_in_symbols", "exact_route", "ROUTES"]

#: ``route`` values of :func:`exact_zero`
ROUTES = ("auto", "flint", "sympy")


def exact_route(route: str = "auto") -> str:
    """The exact route used: ``"flint"`` (python-flint's ``fmpq_mpoly``, :mod:`.flint_exact`) when
    python-flint imports, else ``"sympy"`` (``together``/``cancel``/``rem``).  ``auto`` reads the
    environment variable ``SYMBT_EXACT`` (``flint`` or ``sympy``) first.

    >>> exact_route("sympy")
    'sympy'
    """
    if route == "auto":
        route = os.environ.get("SYMBT_EXACT", "") or "auto"
    if route not in ROUTES:
        raise ValueError(f"exact route must be one of {ROUTES}, got {route!r}")
    if route != "sympy":
        if _flint_imports():
            return "flint"
        if route == "flint":
            raise ImportError("the flint exact route needs python-flint: pip install 'symbt[certified]'")
    return "sympy"


@cache
def _flint_imports() -> bool:
    try:
        import flint  # noqa: F401
    except ImportError:
        return False
    return True



def is_rational_in_symbols(expr: sp.Expr) -> bool:
    """True if ``expr`` is built from symbols and numbers by +, *, integer powers."""
    if expr.is_Atom:
        return bool(expr.is_Symbol or expr.is_Rational or expr is sp.I)
    if isinstance(expr, (sp.Add, sp.Mul)):
        return all(is_rational_in_symbols(a) for a in expr.args)
    if isinstance(expr, sp.Pow):
        return expr.exp.is_Integer and is_rational_in_symbols(expr.base)
    return False


def reduce_modulo(numerator: sp.Expr, relations: Mapping[sp.Symbol, sp.Expr]) -> sp.Expr:
    """Reduce a polynomial modulo ``relations`` (symbol -> polynomial vanishing on it).

    The remainder of polynomial division by each relation in its symbol
    replaces the numerator; passes are repeated until nothing changes, so a
    relation may involve other constrained symbols (``e2 - e1``, ``e1**2 - x``).
    The remainder differs from the numerator by a multiple of the relation, so
    a zero remainder proves that the numerator vanishes wherever the relations do.  A relation that is not a
    polynomial of degree at least 1 in its symbol raises ``ValueError``: dividing by it would prove anything
    (the remainder of a division by a constant is 0).

    >>> x, y = sp.symbols("x y")
    >>> reduce_modulo(x**3 + y, {x: x**2 - y})
    x*y + y
    """
    out = sp.expand(numerator)
    rels = {sym: sp.expand(rel) for sym, rel in relations.items()}
    for sym, rel in rels.items():
        relation_poly(rel, sym)
    for _ in range(len(rels) + 2):
        before = out
        for sym, rel in rels.items():
            if not out.has(sym):
                continue
            out = sp.expand(sp.rem(out, rel, sym))
        if out == before:
            break
    return out


def _is_zero_polynomial(num: sp.Expr) -> bool:
    """``num == 0`` as a polynomial.  Not ``num == 0`` on the tree: SymPy 1.14's ``cancel`` can return an
    unevaluated sum such as ``-1/4 + 1/4`` (``tests/test_proof_flint.py``)."""
    gens = sorted(num.free_symbols, key=sp.default_sort_key) or [sp.Dummy("t")]
    return bool(sp.Poly(num, *gens).is_zero)


def exact_zero(diff: sp.Expr, relations: Mapping[sp.Symbol, sp.Expr],
               route: str = "auto") -> tuple[bool | None, str, bool]:
    """Try to decide ``diff == 0`` exactly.

    Returns ``(zero, method, definite)``: ``zero`` is None when the exact layer
    does not apply, True when the difference reduces to 0; ``definite`` is True
    when a nonzero result is a proof of falsity (a nonzero rational function
    without relations: it cannot vanish identically -- the ``exp(s_i/d_i)`` are
    algebraically independent over the rational functions of the ``s_i``).
    Exponentials become monomials first (:func:`~.exponentials.exponentials_as_monomials`,
    rational exponents included), in ``diff`` and in the relations alike.
    ``route`` (see :func:`exact_route`): both routes compute the same normal
    form, FLINT's about 50 times faster on the claims' differences.  A relation
    that is not a polynomial of degree at least 1 in its symbol raises
    ``ValueError`` (:func:`~.relations.relation_poly`), on either route.
    """
    (rat, *rewritten), variables = exponentials_as_monomials(diff, *relations.values())
    if not is_rational_in_symbols(rat):
        return None, "", False
    relations = dict(zip(relations, rewritten))
    for sym, rel in relations.items():     # both routes divide by them: each a polynomial of degree >= 1 in its symbol
        relation_poly(rel, sym)
    zero = None
    if exact_route(route) == "flint":
        from .flint_exact import rational_zero

        zero = rational_zero(rat, relations)
    parts = []
    if variables:
        parts.append(f"exp->monomials ({describe_variables(variables)})")
    if zero is None:
        num, _den = sp.fraction(sp.cancel(sp.together(rat)))
        if relations:
            num = reduce_modulo(num, relations)
            num = sp.cancel(num)
        zero = _is_zero_polynomial(num)
        parts.append("together/cancel")
    else:
        parts.append("one fraction in FLINT fmpq_mpoly")
    if relations:
        parts.append("remainder mod " + ", ".join(f"{s}: {sp.sstr(r)}=0" for s, r in relations.items()))
    method = "exact: " + "; ".join(parts)
    return zero, method, (not zero and not relations)
