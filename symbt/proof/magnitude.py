"""The size of an expression's terms: what rounding error in its evaluation is relative to."""
from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

import mpmath
import sympy as sp

__all__ = ["EVALUATION_ERRORS", "floored_scale", "magnitude", "size_or_inf"]

# what evaluating an expression (or its size) at a point can raise: a factor's pole where the product has none,
# a domain error, an overflow
EVALUATION_ERRORS = (ZeroDivisionError, ValueError, OverflowError, ArithmeticError)


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
    if isinstance(expr, sp.Pow) and expr.exp.is_Integer and expr.exp.is_positive:
        return sp.Pow(magnitude(expr.base), expr.exp, evaluate=False)
    return sp.Abs(expr, evaluate=False)


def size_or_inf(sizes: Callable[[], Iterable[Any]]) -> Any:
    """The largest of ``sizes()`` (values of :func:`magnitude` at a point), or infinity where it cannot be
    evaluated or is not finite -- so that the floor of :func:`floored_scale` is then 1, the most lenient, never a
    smaller scale than the terms warrant.

    >>> size_or_inf(lambda: [mpmath.mpf(2), mpmath.mpf(3)]), size_or_inf(lambda: [1 / mpmath.mpf(0)])
    (mpf('3.0'), mpf('+inf'))
    """
    try:
        m = max(sizes())
    except EVALUATION_ERRORS:
        return mpmath.inf
    try:
        return m if mpmath.isfinite(m) else mpmath.inf
    except (TypeError, ValueError):
        return mpmath.inf


def floored_scale(big: Any, size: Callable[[], Any]) -> Any:
    r"""What a difference of terms whose largest modulus is ``big`` is measured against:
    ``big`` when it is at least 1, else :math:`\max(\mathrm{big}, \min(1, m))`, ``m = size()``.

    ``size()`` is the size of the terms' own terms (:func:`magnitude`, through :func:`size_or_inf`), evaluated
    only when ``big`` is below 1.  The floor keeps rounding noise where terms cancel to 0 from counting as a
    relative residual of 1; capped at 1, it never makes a statement of size 1 or more absolute, and far below 1
    (``1e-50 sin x = 2e-50 sin x``) a statement is judged at its own size.  One rule for the screen
    (:mod:`symbt.proof.screen`) and the ODE residual (:mod:`symbt.proof.ode`).

    >>> floored_scale(mpmath.mpf(3), lambda: 1 / 0)        # not asked: the sides are large
    mpf('3.0')
    >>> floored_scale(mpmath.mpf("1e-20"), lambda: mpmath.mpf(5)), floored_scale(0, lambda: mpmath.mpf(2) ** -40)
    (mpf('1.0'), mpf('9.0949470177292824e-13'))
    """
    if big >= 1:
        return big
    return max(big, min(mpmath.mpf(1), size()))
