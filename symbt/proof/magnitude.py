"""The size of an expression's terms: what rounding error in its evaluation is relative to."""
from __future__ import annotations

import sympy as sp

__all__ = ["magnitude"]


def magnitude(expr: sp.Expr) -> sp.Expr:
    r"""An expression for the size of ``expr``'s terms, :math:`m(e)`, to be evaluated at a point.

    :math:`m(a_1 + \dots + a_n) = \max_k m(a_k)`, :math:`m(a_1 \cdots a_n) = \prod_k m(a_k)`,
    :math:`m(b^n) = m(b)^n` for a positive integer ``n``, and :math:`m(e) = |e|` for anything else.
    A sum's rounding error is relative to its largest term and a product multiplies its factors' sizes,
    so :math:`m(e)` is the scale of the rounding error of ``e`` when ``e`` cancels: where
    :math:`\sin^2 x + \cos^2 x - 1` evaluates to rounding noise, :math:`m` is about 1; where
    :math:`10^{-50} \sin x` is small, :math:`m` is just as small.

    >>> x = sp.Symbol("x", positive=True)
    >>> magnitude(x * (sp.sin(x)**2 + sp.cos(x)**2 - 1))
    Abs(x)*Max(Abs(-1), Abs(sin(x))**2, Abs(cos(x))**2)
    >>> eta = sp.Symbol("eta", real=True)
    >>> magnitude(eta**2)          # not eta**2: a sample may be complex
    Abs(eta)**2
    """
    # unevaluated throughout: SymPy would rewrite |eta|^2 as eta^2 for a real eta, and a relation's root can be
    # complex at a sample point (the size must stay a modulus, whatever the symbols' assumptions)
    if isinstance(expr, sp.Add):
        return sp.Max(*(magnitude(a) for a in expr.args), evaluate=False)
    if isinstance(expr, sp.Mul):
        return sp.Mul(*(magnitude(a) for a in expr.args), evaluate=False)
    if isinstance(expr, sp.Pow) and expr.exp.is_Integer and expr.exp > 0:
        return sp.Pow(magnitude(expr.base), expr.exp, evaluate=False)
    return sp.Abs(expr, evaluate=False)
