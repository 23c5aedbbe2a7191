"""The printer, rewriting rules and common subexpressions of users' expressions (numpy, mpmath, C).

One home for what every renderer of :mod:`symbt.codegen.user` prints with: :class:`UserPrinter`
(:class:`~symbt.codegen.printer.ExprPrinter` plus floats, ``pi``/``E``, trigonometric and
hyperbolic functions, ``expm1``, ``atan2``, ``Min``/``Max``, boolean conditions and general
powers), the ``expm1``/``log1p`` rules (:func:`rewritten`, :func:`optimized`) and :func:`cse`.

>>> import sympy as sp
>>> x = sp.Symbol("x")
>>> cse([sp.sin(x) + 1, sp.sin(x)], {x: "x"}, "c")
(['t0 = sin(x)'], ['t0 + 1.0', 't0'])
"""
from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.codegen.cfunctions import expm1
from sympy.codegen.rewriting import FuncMinusOneOptim, ReplaceOptim, expm1_opt, log1p_opt

from ..printer import _ATOM, _FUNCS, _MUL, _POW, ExprPrinter, cse_block
from .declare import Emission

__all__ = ["UserPrinter", "optimized", "rewritten", "cse", "FACTOR_MAX_OPS", "LONG_SUM"]

_TRIG = (sp.sin, sp.cos, sp.tan, sp.asin, sp.acos, sp.atan, sp.sinh, sp.cosh, sp.tanh, sp.asinh, sp.atanh)
_NP = {"asin": "arcsin", "acos": "arccos", "atan": "arctan", "asinh": "arcsinh", "atanh": "arctanh"}
_EXTRA = {
    "numpy": {**{f: "np." + _NP.get(f.__name__, f.__name__) for f in _TRIG}, expm1: "np.expm1"},
    "mpmath": {**{f: "mpmath." + f.__name__ for f in _TRIG}, expm1: "mpmath.expm1"},
    "c": {**{f: f.__name__ for f in _TRIG}, expm1: "expm1"},
}
_CONST = {"numpy": {"pi": "np.pi", "E": "np.e"}, "mpmath": {"pi": "mpmath.pi", "E": "mpmath.e"},
          "c": {"pi": "3.141592653589793", "E": "2.718281828459045"}}
_MINMAX = {"numpy": ("np.minimum", "np.maximum"), "mpmath": ("min", "max"), "c": ("fmin", "fmax")}
_BOOL = {"numpy": (" & ", " | ", "~"), "mpmath": (" and ", " or ", "not "), "c": (" && ", " || ", "!")}


class UserPrinter(ExprPrinter):
    """:class:`~symbt.codegen.printer.ExprPrinter` for users' expressions (flavours numpy, mpmath, c).

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> UserPrinter("c", {x: "x"}).text(sp.Piecewise((sp.sin(x), x < 0), (x**sp.Rational(1, 3), True)))
    '((x < 0.0) ? sin(x) : pow(x, (1.0/3.0)))'
    """

    def __init__(self, flavour: str, names: dict[Any, str]):
        super().__init__(flavour, names)
        self.funcs = {**_FUNCS[flavour], **_EXTRA[flavour]}

    def _p(self, e: sp.Basic) -> tuple[str, int]:
        fl = self.flavour
        if e.is_Float:
            v = float(e)
            txt = repr(v) if fl != "mpmath" else f"mpmath.mpf({repr(v)!r})"
            return (txt, _ATOM) if v >= 0 else (f"({txt})", _ATOM)
        if e is sp.pi or e is sp.E:
            return _CONST[fl][str(e)], _ATOM
        if isinstance(e, sp.atan2):
            f = {"numpy": "np.arctan2", "mpmath": "mpmath.atan2", "c": "atan2"}[fl]
            return f"{f}({self.text(e.args[0])}, {self.text(e.args[1])})", _ATOM
        if isinstance(e, (sp.Min, sp.Max)):
            f = _MINMAX[fl][isinstance(e, sp.Max)]
            out = self.text(e.args[0])
            for a in e.args[1:]:
                out = f"{f}({out}, {self.text(a)})"
            return out, _ATOM
        if isinstance(e, (sp.And, sp.Or)):
            op = _BOOL[fl][isinstance(e, sp.Or)]
            return "(" + op.join(f"({self.text(a)})" for a in e.args) + ")", _ATOM
        if isinstance(e, sp.Not):
            return f"({_BOOL[fl][2]}({self.text(e.args[0])}))", _ATOM
        if isinstance(e, (sp.Eq, sp.Ne)):
            op = "==" if isinstance(e, sp.Eq) else "!="
            return f"({self._wrap(e.lhs, 1)} {op} {self._wrap(e.rhs, 1)})", _ATOM
        if e is sp.true or e is sp.false:
            v = bool(e)
            return {"numpy": str(v), "mpmath": str(v), "c": str(int(v))}[fl], _ATOM
        return super()._p(e)

    def _add(self, e: sp.Add) -> str:
        terms = e.as_ordered_terms()
        if self.flavour == "c" or len(terms) <= LONG_SUM:
            return super()._add(e)
        chunks = [super(UserPrinter, self)._add(sp.Add(*terms[k:k + LONG_SUM], evaluate=False))
                  for k in range(0, len(terms), LONG_SUM)]

        def tree(parts: list[str]) -> str:   # balanced: nesting depth log2(chunks), few temporaries alive at once
            if len(parts) == 1:
                return parts[0]
            mid = len(parts) // 2
            return f"({tree(parts[:mid])}) + ({tree(parts[mid:])})"
        return tree(chunks)

    def _pow(self, e: sp.Pow) -> tuple[str, int]:
        b, x = e.base, e.exp
        if b is sp.E or (x.is_Rational and (x.is_Integer or x.q == 2)):
            return super()._pow(e)
        if x.is_Rational and x.is_negative:
            one = "1.0" if self.flavour == "c" else "1"
            return f"{one}/{self._wrap(sp.Pow(b, -x), _MUL)}", _MUL
        if self.flavour == "c":
            return f"pow({self.text(b)}, {self.text(x)})", _ATOM
        if self.flavour == "mpmath":
            return f"mpmath.power({self.text(b)}, {self.text(x)})", _ATOM
        return f"{self._wrap(b, _POW)}**{self._wrap(x, _POW)}", _POW


#: above this many operations the expm1 rule is applied term by term only: SymPy's rule also tries
#: ``factor()`` of the whole expression, which took 93 % of the emission time of a large polynomial
FACTOR_MAX_OPS = 400
#: a sum of more terms is printed in Python as a balanced sum of partial sums of at most this many terms,
#: ``(a + ... ) + (...)``: a chain ``a + b + ...`` of thousands of terms makes Python's compiler raise
#: RecursionError
LONG_SUM = 100


def rewritten(x: sp.Expr) -> sp.Expr:
    """SymPy's ``optimize(x, [expm1_opt, log1p_opt])``, each rule only where its function occurs.

    >>> x = sp.Symbol("x")
    >>> rewritten(sp.log(1 + x) + sp.exp(x) - 1)
    expm1(x) + log1p(x)
    """
    for fn, opt in ((sp.exp, expm1_opt), (sp.log, log1p_opt)):
        if not x.has(fn):
            continue
        if isinstance(opt, FuncMinusOneOptim) and sp.count_ops(x) > FACTOR_MAX_OPS:
            new = ReplaceOptim.__call__(opt, x)
        else:
            new = opt(x)
        x = opt.cheapest(x, new) if opt.cost_function is not None else new
    return x


def optimized(e: Emission) -> list[sp.Expr]:
    """The elements to print: ``expm1``/``log1p`` rewriting when the declaration asks for it.

    Each rule of :mod:`sympy.codegen.rewriting` is applied only to an expression containing its
    function (``exp``, ``log``), and on an expression of more than :data:`FACTOR_MAX_OPS` operations
    without the rule's whole-expression ``factor()`` attempt.

    >>> import sympy as sp
    >>> from .declare import emit
    >>> x = sp.Symbol("x")
    >>> optimized(emit("g", [sp.exp(x) - 1, sp.log(1 + x), x**2 - 1], args=(x,), module="m", register=False))
    [expm1(x), log1p(x), x**2 - 1]
    """
    if not e.optimize:
        return list(e.exprs)
    return [rewritten(x) for x in e.exprs]


def cse(exprs: list[sp.Expr], names: dict[Any, str], flavour: str, prefix: str = "t") -> tuple[list[str], list[str]]:
    """:func:`~symbt.codegen.printer.cse_block` printed by :class:`UserPrinter`: assignment lines
    ``t0 = ...`` (names ``prefix`` + k, canonical order) and the printed reduced expressions."""
    return cse_block(exprs, names, flavour, prefix, printer=UserPrinter)
