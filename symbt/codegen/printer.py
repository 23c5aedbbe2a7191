"""A small, deterministic expression printer for the two emitted flavours.

Only the node types the derivations produce are supported (``Add``, ``Mul``,
``Pow`` with integer or half-integer exponent, ``exp``, ``log``, ``log1p``,
``acosh``, ``sign``, ``Abs``, ``Piecewise``, relations, integers and
rationals); anything else raises, so a derivation change can never slip an
unprintable -- or a floating-point -- literal into the generated files.

* ``numpy``: float64, elementwise (``np.where`` for ``Piecewise``); rational
  constants are written ``(p/q)`` (Python rounds the quotient correctly).
* ``mpmath``: every non-integer constant is an exact ratio evaluated at call
  time, ``_Q(p, q) = mpmath.mpf(p)/q``, at the caller's precision; integers
  are Python ints (exact).
* ``ops``: flavour-neutral Python for the transfer-matrix kernels: functions are
  looked up on the arithmetic namespace ``_X`` (numpy or mpmath); only integers
  and dyadic ratios (``1/2``: exact as a float, and exact times an mpf) are allowed.
* ``c``: C99 with ``<math.h>``; constants are double literals (``2.0``,
  ``(1.0/3.0)``), powers are products (``pow`` never appears), ``sign`` is the
  emitted ``sgn()``, ``Piecewise`` a conditional expression.

>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> ExprPrinter("c", {x: "x", y: "y"}).text(sp.sqrt(x**2 + 1)/y**3 + sp.Rational(1, 3))
'(1.0/3.0) + sqrt(x*x + 1.0)/(y*y*y)'
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import sympy as sp
from sympy.codegen.cfunctions import log1p

__all__ = ["ExprPrinter", "cse_block", "Quotient"]


class Quotient(sp.Function):
    """``a/b`` divided IEEE-style in every flavour: ``x/0 = +-inf``, ``x/inf = 0`` (float64 and C divide so
    already; the mpmath flavour calls the emitted ``_div``, since an mpf division by zero raises).  Used
    where both branches of a ``Piecewise`` are evaluated (CSE hoists them) and the branch not taken may
    pass through an infinite slope.

    >>> a, b = sp.symbols("a b")
    >>> names = {a: "a", b: "b"}
    >>> ExprPrinter("mpmath", names).text(-Quotient(a, b)), ExprPrinter("c", names).text(Quotient(a, b))
    ('-_div(a, b)', 'a/b')
    """

    nargs = 2

_FUNCS = {
    "numpy": {sp.exp: "np.exp", sp.log: "np.log", log1p: "np.log1p", sp.acosh: "np.arccosh",
              sp.sign: "np.sign", sp.Abs: "np.abs", "sqrt": "np.sqrt"},
    "mpmath": {sp.exp: "mpmath.exp", sp.log: "mpmath.log", log1p: "mpmath.log1p", sp.acosh: "mpmath.acosh",
               sp.sign: "mpmath.sign", sp.Abs: "abs", "sqrt": "mpmath.sqrt"},
    "ops": {sp.exp: "_X.exp", sp.log: "_X.log", log1p: "_X.log1p", sp.acosh: "_X.acosh",
            sp.sign: "_X.sign", sp.Abs: "abs", "sqrt": "_X.sqrt"},
    "c": {sp.exp: "exp", sp.log: "log", log1p: "log1p", sp.acosh: "acosh",
          sp.sign: "sgn", sp.Abs: "fabs", "sqrt": "sqrt"},
}
_REL = {sp.GreaterThan: ">=", sp.StrictGreaterThan: ">", sp.LessThan: "<=", sp.StrictLessThan: "<"}

# precedence: atom 4, power 3, unary minus / mul 2, add 1
_ATOM, _POW, _MUL, _ADD, _REL_P = 4, 3, 2, 1, 0


class ExprPrinter:
    def __init__(self, flavour: str, names: dict[Any, str]):
        if flavour not in _FUNCS:
            raise ValueError(flavour)
        self.flavour = flavour
        self.funcs = _FUNCS[flavour]
        self.names = names  # Symbol -> python identifier

    # returns (text, precedence)
    def _p(self, e: sp.Basic) -> tuple[str, int]:
        if e.is_Symbol:
            try:
                return self.names[e], _ATOM
            except KeyError:
                raise ValueError(f"unbound symbol {e}") from None
        if e.is_Integer:
            v = int(e)
            txt = f"{v}.0" if self.flavour == "c" else str(v)
            return (txt, _ATOM) if v >= 0 else (f"({txt})", _ATOM)
        if e.is_Rational:
            if self.flavour == "numpy":
                return f"({e.p}/{e.q})", _ATOM
            if self.flavour == "c":
                return f"({e.p}.0/{e.q}.0)", _ATOM
            if self.flavour == "ops":   # only dyadic ratios: exact as a float, and exact times an mpf
                if e.q & (e.q - 1):
                    raise ValueError(f"non-dyadic constant {e} in a transfer-matrix kernel")
                return f"({e.p}/{e.q})", _ATOM
            return f"_Q({e.p}, {e.q})", _ATOM
        if e.is_Number or e.is_NumberSymbol:
            raise ValueError(f"non-rational constant {e!r} in a derivation")
        if e.is_Add:
            return self._add(e), _ADD
        if e.is_Mul:
            return self._mul(e)
        if e.is_Pow:
            return self._pow(e)
        if isinstance(e, sp.Piecewise):
            return self._piecewise(e), _ATOM
        if isinstance(e, Quotient):
            if self.flavour == "mpmath":
                return f"_div({self.text(e.args[0])}, {self.text(e.args[1])})", _ATOM
            return f"{self._wrap(e.args[0], _MUL)}/{self._wrap(e.args[1], _MUL)}", _MUL
        if type(e) in _REL:
            a = self._wrap(e.lhs, _ADD)
            b = self._wrap(e.rhs, _ADD)
            return f"{a} {_REL[type(e)]} {b}", _REL_P
        f = self.funcs.get(type(e)) or self.funcs.get(e.func)
        if f is not None and len(e.args) == 1:
            return f"{f}({self.text(e.args[0])})", _ATOM
        raise ValueError(f"cannot print {type(e).__name__}: {e}")

    def text(self, e: sp.Basic) -> str:
        return self._p(sp.sympify(e))[0]

    def _wrap(self, e: sp.Basic, prec: int) -> str:
        s, p = self._p(e)
        return s if p > prec else f"({s})"

    def _add(self, e: sp.Add) -> str:
        parts = []
        for i, t in enumerate(e.as_ordered_terms()):
            c, rest = t.as_coeff_Mul()
            if c.is_Number and c < 0:
                s = self._wrap(-t, _ADD)
                parts.append(f"-{s}" if i == 0 else f" - {s}")
            else:
                s = self._wrap(t, _ADD)
                parts.append(s if i == 0 else f" + {s}")
        return "".join(parts)

    def _mul(self, e: sp.Mul) -> tuple[str, int]:
        c, rest = e.as_coeff_Mul()
        if c.is_Number and c < 0:
            s = self._wrap(-e, _MUL)
            return f"-{s}", _MUL
        num, den = [], []
        for f in sp.Mul.make_args(e):
            if f.is_Pow and f.exp.is_Rational and f.exp.is_negative:
                den.append(sp.Pow(f.base, -f.exp))
            elif f.is_Rational and not f.is_Integer and self.flavour in ("numpy", "c", "ops"):
                if f.p != 1:
                    num.append(sp.Integer(f.p))
                den.append(sp.Integer(f.q))
            else:
                num.append(f)
        ns = "*".join(self._wrap(f, _MUL) for f in num) if num else ("1.0" if self.flavour == "c" else "1")
        if not den:
            return ns, _MUL
        if len(den) == 1:
            ds = self._wrap(den[0], _MUL)
        else:
            ds = "(" + "*".join(self._wrap(f, _MUL) for f in den) + ")"
        return f"{ns}/{ds}", _MUL

    def _pow(self, e: sp.Pow) -> tuple[str, int]:
        b, x = e.base, e.exp
        if b is sp.E:
            return f"{self.funcs[sp.exp]}({self.text(x)})", _ATOM
        if not x.is_Rational:
            raise ValueError(f"non-rational exponent in {e}")
        if x.is_negative:
            one = "1.0" if self.flavour == "c" else "1"
            return f"{one}/{self._wrap(sp.Pow(b, -x), _MUL)}", _MUL
        if x == sp.Rational(1, 2):
            return f"{self.funcs['sqrt']}({self.text(b)})", _ATOM
        if self.flavour == "c":
            base = self._wrap(b, _MUL) if x.is_Integer else f"sqrt({self.text(b)})"
            n = int(x) if x.is_Integer else x.p
            if x.is_Integer or x.q == 2:
                return "*".join([base] * n), _MUL
            raise ValueError(f"exponent {x} not supported")
        if x.is_Integer:
            return f"{self._wrap(b, _POW)}**{int(x)}", _POW
        if x.q == 2:
            return f"{self.funcs['sqrt']}({self.text(b)})**{x.p}", _POW
        raise ValueError(f"exponent {x} not supported")

    def _piecewise(self, e: sp.Piecewise) -> str:
        *pairs, (last, cond) = e.args
        if cond is not sp.true:
            raise ValueError("Piecewise without a default branch")
        out = self.text(last)
        for val, cnd in reversed(pairs):
            if self.flavour == "numpy":
                out = f"np.where({self.text(cnd)}, {self.text(val)}, {out})"
            elif self.flavour == "c":
                out = f"(({self.text(cnd)}) ? {self.text(val)} : {out})"
            else:
                out = f"({self.text(val)} if {self.text(cnd)} else {out})"
        return out


def cse_block(exprs: Sequence[sp.Basic], names: dict[sp.Basic, str], flavour: str,
              prefix: str = "t", printer: type[ExprPrinter] | None = None) -> tuple[list[str], list[str]]:
    """Common subexpressions of ``exprs`` (fixed names ``t0, t1, ...``, canonical order).

    Returns ``(lines, outs)``: assignment lines and the printed reduced outputs; ``printer`` (a subclass
    of :class:`ExprPrinter`, default :class:`ExprPrinter`) prints them.
    """
    syms = sp.numbered_symbols(prefix)
    repl, reduced = sp.cse(list(exprs), symbols=syms, order="canonical")
    names = dict(names)
    pr = (printer or ExprPrinter)(flavour, names)
    lines = []
    for s, v in repl:
        lines.append(f"{s} = {pr.text(v)}")
        names[s] = str(s)
    return lines, [pr.text(r) for r in reduced]
