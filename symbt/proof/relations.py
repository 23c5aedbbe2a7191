"""The one rule every layer applies to a relation ``rel = 0`` that constrains a symbol ``s``.

It must be a polynomial of degree at least 1 in ``s``: the exact layer divides by it (the remainder of a division
by something constant in ``s`` is 0, so such a relation would prove any statement) and the screen solves it for
``s`` (by the closed form of a generic polynomial, hence also a largest degree there).

>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> relation_poly(x**2 - y, x).degree()
2
>>> relation_poly(y - 1, x)
Traceback (most recent call last):
...
ValueError: relation y - 1 = 0 is not a polynomial of degree 1 or more in x
"""
from __future__ import annotations

import sympy as sp

__all__ = ["relation_poly"]


def relation_poly(rel: sp.Expr, s: sp.Symbol, max_degree: int | None = None) -> sp.Poly:
    """``rel`` as a polynomial in ``s`` of degree ``1 .. max_degree`` (``None``: no largest degree), else
    ``ValueError`` naming the degrees allowed."""
    poly = sp.sympify(rel).as_poly(s)
    if poly is None or poly.degree() < 1 or (max_degree is not None and poly.degree() > max_degree):
        degrees = "1 or more" if max_degree is None else f"1..{max_degree}"
        raise ValueError(f"relation {rel} = 0 is not a polynomial of degree {degrees} in {s}")
    return poly
