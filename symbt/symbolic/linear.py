"""Solving one equation for one unknown, without ``sympy.solve`` where the equation is linear.

The derivations solve linear equations (an eigenvalue from an eigen-equation, a transport from a
Möbius map).  ``sympy.solve`` gets there through ``checksol`` and ``simplify``, which import
``sympy.physics`` (a tenth of a second per process) and cost more than the answer; for
``c1 x + c0 = 0`` with ``c1`` not identically zero the answer is ``-c0/c1``.  Anything else (a
nonlinear equation, e.g. a mutant's) goes to ``sympy.solve``, so the callers keep its semantics:
a list of solutions.
"""
from __future__ import annotations

from typing import Any

import sympy as sp

__all__ = ["solve_linear"]


def solve_linear(eq: Any, x: sp.Symbol) -> list[sp.Expr]:
    """The solutions of ``eq = 0`` (or of an ``Eq``) for ``x``.

    >>> a, b, x = sp.symbols("a b x")
    >>> solve_linear(a * x + b, x)
    [-b/a]
    >>> solve_linear(sp.Eq(x ** 2, 4), x)
    [-2, 2]
    """
    if isinstance(eq, sp.Eq):
        eq = eq.lhs - eq.rhs
    eq = sp.sympify(eq)
    try:
        poly = sp.Poly(eq, x)
    except sp.PolynomialError:
        poly = None
    if poly is not None and poly.degree() == 1:
        c1, c0 = poly.all_coeffs()
        if sp.cancel(c1) != 0:
            return [sp.cancel(-c0 / c1)]
    return list(sp.solve(eq, x))
