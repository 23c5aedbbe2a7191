r"""The exact layer on python-flint: a rational function's numerator in ``fmpq_mpoly``.

:func:`~symbt.proof.exact.exact_zero` brings a difference to one fraction and
reduces its numerator modulo algebraic relations.  SymPy's ``together`` and
``cancel`` do this on expression trees; here the same normal form is computed
with FLINT's multivariate polynomials over :math:`\mathbb Q`:

* the tree is converted bottom-up to fractions ``(num, den)`` of ``fmpq_mpoly``:
  products multiply, integer powers raise (numerator and denominator swap for
  negative exponents), sums put fractions over the *least* common denominator
  (``den1 * den2 / gcd``);
* the imaginary unit becomes a variable ``i`` with the relation ``i**2 + 1``;
* at the end the fraction is reduced by ``gcd(num, den)``, so the numerator is
  the one ``cancel`` gives, up to a rational factor;
* a relation ``sym -> rel = L sym**d + tail`` rewrites ``sym**d`` as ``-tail/L``
  (Horner, from the top power down) until the numerator has degree ``< d`` in
  ``sym``: the remainder of division by ``rel`` over the field of fractions of
  the other symbols, as ``sympy.rem`` computes it (times a power of ``L`` when
  ``L`` is not a number, which does not change whether it is zero).  Passes over
  the relations repeat until nothing changes, so relations may build on each other.

Both routes are exact; ``tests/test_proof_flint.py`` checks that they return
the same verdict on identities, non-identities and every claim's differences.
:func:`rational_zero` returns ``None`` where this route does not apply (a
power of zero with a negative exponent, a node that is not rational); the
caller then uses SymPy.

Example
-------
>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> rational_zero((x**2 - y**2) / (x - y) - x - y, {})
True
>>> eta, w = sp.symbols("eta w")
>>> rational_zero((eta - 1) * (eta + 1) - w, {eta: eta**2 - 1 - w})
True
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp

__all__ = ["rational_zero"]


class _NotApplicable(Exception):
    """This route cannot decide; use SymPy's."""


class _Converter:
    """SymPy expressions to reduced fractions of ``fmpq_mpoly`` in one context (memoised per node)."""

    def __init__(self, symbols: list[sp.Symbol], has_i: bool) -> None:
        import flint

        names = [f"x{k}" for k in range(len(symbols))] + (["i"] if has_i else [])
        self.ctx = flint.fmpq_mpoly_ctx.get(tuple(names), "lex")
        gens = self.ctx.gens()
        self.var = {s: g for s, g in zip(symbols, gens)}
        self.index = {s: k for k, s in enumerate(symbols)}
        self.i: Any = gens[-1] if has_i else None
        self.one = self.ctx.from_dict({(0,) * len(names): 1})
        self.memo: dict[Any, tuple[Any, Any]] = {}

    def const(self, value: Any) -> Any:
        return self.one * value

    def __call__(self, e: sp.Expr) -> tuple[Any, Any]:
        got = self.memo.get(e)
        if got is None:
            got = self.memo[e] = self._convert(e)
        return got

    def _convert(self, e: sp.Expr) -> tuple[Any, Any]:
        if e.is_Symbol:
            return self.var[e], self.one
        if e is sp.I:
            return self.i, self.one
        if e.is_Integer:
            return self.const(int(e)), self.one
        if e.is_Rational:
            return self.const(int(e.p)), self.const(int(e.q))
        if isinstance(e, sp.Mul):
            num, den = self.one, self.one
            for a in e.args:
                n, d = self(a)
                num, den = num * n, den * d
            return num, den
        if isinstance(e, sp.Pow):
            n, d = self(e.base)
            k = int(e.exp)
            if k < 0:
                if n.is_zero():
                    raise _NotApplicable("a negative power of zero")
                n, d, k = d, n, -k
            return n ** k, d ** k
        if isinstance(e, sp.Add):
            terms = [self(a) for a in e.args]
            num, den = terms[0]
            for n, d in terms[1:]:
                if d == den:
                    num = num + n
                    continue
                g = den.gcd(d)
                num, den = num * (d // g) + n * (den // g), den * (d // g)
            return num, den
        raise _NotApplicable(f"not a rational expression: {type(e).__name__}")


def _reduce(num: Any, rel: Any, v: int, gen: Any) -> Any:
    """``num`` reduced modulo ``rel`` in the variable with index ``v``: of degree ``< deg_v rel`` in it.

    With ``rel = L v**d + tail`` (``L`` free of ``v``), ``v**d`` becomes ``-tail/L``.  A constant ``L``
    gives the remainder of division by ``rel``; otherwise the result is ``L**m`` times the remainder
    over the field of fractions of the other variables (what ``sympy.rem`` computes), which is zero
    if and only if that remainder is (polynomials over Q form an integral domain).
    """
    d = rel.degrees()[v]                 # >= 1: exact_zero refuses any other relation first
    if num.degrees()[v] < d:
        return num
    ctx = num.context()
    lead, tail = {}, {}
    for exps, c in zip(rel.monoms(), rel.coeffs()):
        if exps[v] == d:
            lead[exps[:v] + (0,) + exps[v + 1:]] = c
        else:
            tail[exps] = c
    L, minus_tail = ctx.from_dict(lead), -ctx.from_dict(tail)
    monic = L.is_constant()                        # monic up to a rational factor: divide it out
    if monic:
        minus_tail = minus_tail / L
    parts: dict[int, dict[tuple[int, ...], Any]] = {}
    for exps, a in zip(num.monoms(), num.coeffs()):
        parts.setdefault(exps[v], {})[exps[:v] + (0,) + exps[v + 1:]] = a
    acc, scale = ctx.from_dict({}), None          # acc = scale * (the true partial remainder)
    for k in range(num.degrees()[v], -1, -1):
        acc = acc * gen
        if acc.degrees()[v] >= d:                  # one substitution suffices: acc had degree < d
            hi, lo = {}, {}
            for exps, a in zip(acc.monoms(), acc.coeffs()):
                if exps[v] >= d:
                    hi[exps[:v] + (exps[v] - d,) + exps[v + 1:]] = a
                else:
                    lo[exps] = a
            if monic:
                acc = ctx.from_dict(lo) + ctx.from_dict(hi) * minus_tail
            else:
                acc = ctx.from_dict(lo) * L + ctx.from_dict(hi) * minus_tail
                scale = L if scale is None else scale * L
        if k in parts:
            a_k = ctx.from_dict(parts[k])
            acc = acc + (a_k if scale is None else a_k * scale)
    return acc


def rational_zero(rat: sp.Expr, relations: Mapping[sp.Symbol, sp.Expr]) -> bool | None:
    """True/False: the numerator of ``rat`` (a rational expression in symbols and ``I``) reduces to zero
    modulo ``relations``, or not; ``None`` when this route does not apply (see the module docstring)."""
    rels = {s: sp.sympify(r) for s, r in relations.items()}
    syms = set(rat.free_symbols) | set(rels)
    for r in rels.values():
        syms |= r.free_symbols
    has_i = rat.has(sp.I) or any(r.has(sp.I) for r in rels.values())
    symbols = sorted(syms, key=lambda s: (s.name, s.sort_key()))
    try:
        conv = _Converter(symbols, has_i)
        num, den = conv(rat)
        if num.is_zero():
            return True
        num = num // num.gcd(den)
        reductions = [(conv.index[s], conv.var[s], conv(r)[0]) for s, r in rels.items()]
        if has_i:
            reductions.append((len(symbols), conv.i, conv.i ** 2 + 1))
        for _ in range(len(reductions) + 2):
            before = num
            for v, gen, rel in reductions:
                num = _reduce(num, rel, v, gen)
            if num == before:
                break
    except _NotApplicable:
        return None
    return bool(num.is_zero())
