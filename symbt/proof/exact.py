"""The exact layer: a difference reduced to zero as a rational function (see :mod:`symbt.proof`)."""
from __future__ import annotations

from collections.abc import Mapping

import sympy as sp

from ..symbolic.rewriting import rationalize_exponentials

__all__ = ["reduce_modulo", "exact_zero", "is_rational_in_symbols"]


def is_rational_in_symbols(expr) -> bool:
    """True if ``expr`` is built from symbols and numbers by +, *, integer powers."""
    if expr.is_Atom:
        return bool(expr.is_Symbol or expr.is_Rational or expr is sp.I)
    if isinstance(expr, (sp.Add, sp.Mul)):
        return all(is_rational_in_symbols(a) for a in expr.args)
    if isinstance(expr, sp.Pow):
        return expr.exp.is_Integer and is_rational_in_symbols(expr.base)
    return False


def reduce_modulo(numerator, relations: Mapping[sp.Symbol, sp.Expr]):
    """Reduce a polynomial modulo ``relations`` (symbol -> polynomial vanishing on it).

    The remainder of polynomial division by each relation in its symbol
    replaces the numerator; passes are repeated until nothing changes, so a
    relation may involve other constrained symbols (``e2 - e1``, ``e1**2 - x``).
    The remainder differs from the numerator by a multiple of the relation, so
    a zero remainder proves that the numerator vanishes wherever the relations do.
    """
    out = sp.expand(numerator)
    rels = {sym: sp.expand(rel) for sym, rel in relations.items()}
    for _ in range(len(rels) + 2):
        before = out
        for sym, rel in rels.items():
            if not out.has(sym) or sp.degree(rel, sym) < 1:
                continue
            out = sp.expand(sp.rem(out, rel, sym))
        if out == before:
            break
    return out


def exact_zero(diff, relations) -> tuple[bool | None, str, bool]:
    """Try to decide ``diff == 0`` exactly.

    Returns ``(zero, method, definite)``: ``zero`` is None when the exact layer
    does not apply, True when the difference reduces to 0; ``definite`` is True
    when a nonzero result is a proof of falsity (a nonzero rational function
    without relations: it cannot vanish identically -- the ``exp(s_i)`` are
    algebraically independent over the rational functions of the ``s_i``).
    """
    rat, mapping = rationalize_exponentials(diff)
    if not is_rational_in_symbols(rat):
        return None, "", False
    num, _den = sp.fraction(sp.cancel(sp.together(rat)))
    if relations:
        num = reduce_modulo(num, relations)
        num = sp.cancel(num)
    parts = []
    if mapping:
        parts.append("exp->monomials (" + ", ".join(f"{v}=e^{k}" for k, v in mapping.items()) + ")")
    parts.append("together/cancel")
    if relations:
        parts.append("remainder mod " + ", ".join(f"{s}: {sp.sstr(r)}=0" for s, r in relations.items()))
    method = "exact: " + "; ".join(parts)
    zero = bool(num == 0)
    return zero, method, (not zero and not relations)
