r"""Rewriting for exact decisions: exponentials of integer-linear forms become monomials.

For the Toda lattice, ``exp(q_i - q_j)`` and ``cosh(q_1 - q_2)`` become Laurent
monomials in ``E_j = e^{q_j}``, so identities about the model are identities of
rational functions (decided by ``cancel``, see :mod:`symbt.proof`).
"""
from __future__ import annotations

from collections.abc import Collection, Mapping

import sympy as sp

__all__ = ["rationalize_exponentials", "linear_integer_form"]


def linear_integer_form(arg: sp.Expr, symbols: Collection[sp.Symbol]) -> dict[sp.Symbol, int] | None:
    """``arg`` as an integer combination of ``symbols`` (no constant), else None."""
    arg = sp.expand(arg)
    coeffs: dict[sp.Symbol, int] = {}
    for term in sp.Add.make_args(arg):
        c, rest = term.as_coeff_Mul()
        if rest not in symbols or not c.is_Integer:
            return None
        coeffs[rest] = coeffs.get(rest, 0) + int(c)
    return coeffs


def rationalize_exponentials(expr: sp.Expr, exp_symbols: Mapping[sp.Symbol, sp.Symbol] | None = None
                             ) -> tuple[sp.Expr, dict[sp.Symbol, sp.Symbol]]:
    """Rewrite ``exp``/``cosh``/``sinh`` of integer-linear forms as monomials.

    ``exp_symbols`` maps a variable ``s`` to the positive symbol standing for
    ``exp(s)``; missing variables get a fresh ``exp_s`` symbol.  Returns the
    rewritten expression and the mapping used.  Exponentials of other
    arguments are left untouched (the caller then falls back to numerics).

    >>> q1, q2 = sp.symbols("q1 q2", real=True)
    >>> e, m = rationalize_exponentials(2 * sp.cosh(q1 - q2))
    >>> sp.cancel(e - (m[q1] / m[q2] + m[q2] / m[q1]))
    0
    """
    exp_symbols = dict(exp_symbols or {})
    expr = sp.sympify(expr)
    if expr.has(sp.cosh, sp.sinh, sp.tanh):
        # rewrite only the hyperbolic functions (a global rewrite would turn x**2 into exp(2 log x))
        expr = expr.replace(lambda e: isinstance(e, (sp.cosh, sp.sinh, sp.tanh)),
                            lambda e: e.rewrite(sp.exp))
    candidates = set()
    for e in expr.atoms(sp.exp):
        candidates |= e.args[0].free_symbols
    symbols = set(candidates)

    def repl(e: sp.Expr) -> sp.Expr:
        form = linear_integer_form(e.args[0], symbols)
        if form is None:
            return e
        out = sp.Integer(1)
        for s, k in form.items():
            if s not in exp_symbols:
                # a Dummy: a user symbol that happens to be called ``exp_q`` must not collide
                exp_symbols[s] = sp.Dummy(f"exp_{s.name}", positive=True)
            out *= exp_symbols[s] ** k
        return out

    expr = expr.replace(lambda e: isinstance(e, sp.exp), repl)
    return expr, exp_symbols
