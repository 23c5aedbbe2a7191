r"""Exponentials of rational-linear forms as monomials, whatever the spelling (the exact layer's first step).

The exact layer (:func:`~symbt.proof.exact.exact_zero`) decides identities of
rational functions; this module turns a difference with exponentials into one.
Every exponential of the expression -- ``exp(u)``, ``E**u``, ``exp(u)**r``,
``sqrt(exp(u))``, a product of exponentials under a power, hyperbolic
functions (rewritten as exponentials first) -- is read as ``exp(u)`` with its
exponent ``u`` a linear combination of symbols with **rational** coefficients
(and a rational constant).  Per symbol ``s`` the least common denominator
``d_s`` of its coefficients, over the whole expression, is taken, and
``S = exp(s/d_s)`` becomes a fresh positive symbol, so that
``exp(a s) = S**(a d_s)`` with an integer exponent; the constant direction
is ``exp(1/d)`` (``E`` itself is ``exp(1)``).

Why a polynomial identity in the ``S`` is equivalent to the identity:
``exp(a s) = exp(s/d)**(a d)`` holds for every complex ``s`` when ``a d`` is an
integer, and the ``exp(s/d_s)`` are algebraically independent over the
rational functions of the symbols (``e^{1/d}`` is transcendental), so a
nonzero rational function in them does not vanish identically.

A rational power of an exponential is rewritten only when that is exact:
``exp(u)**r = exp(r u)`` for integer ``r`` always, for rational ``r`` when
``u`` is real (the principal power of a positive number); ``sqrt(exp(x))``
with a complex ``x`` is left alone, and so is any exponent that is not
rational-linear (``exp(q1*q2)``, ``exp(sqrt(2)*q)``): the expression is then
not rational and the decider falls through to its numeric screen.

The expression tree is walked here, node by node: the result does not depend
on whether SymPy auto-combined ``exp(a)*exp(b)`` into ``exp(a + b)``, or wrote
``exp(x)**2``, ``exp(-x)``, ``1/exp(x)``, ``sqrt(exp(x))**2``, ``E**x`` --
every spelling of the same exponential gives the same monomial.

Example
-------
>>> import sympy as sp
>>> q = sp.Symbol("q", real=True)
>>> (rat,), variables = exponentials_as_monomials(sp.sqrt(sp.exp(q)) + sp.exp(q / 3))
>>> S, d = variables[q]
>>> d, rat == S**3 + S**2
(6, True)
>>> describe_variables(variables)
'exp_q=e^(q/6)'
"""
from __future__ import annotations

from math import lcm
from typing import Any

import sympy as sp

__all__ = ["exponentials_as_monomials", "rational_linear_form", "describe_variables"]

#: rewritten as exponentials before the walk
_HYPERBOLIC = (sp.cosh, sp.sinh, sp.tanh, sp.coth, sp.sech, sp.csch)


def rational_linear_form(u: sp.Expr) -> dict[sp.Expr, sp.Rational] | None:
    """``u`` as ``{symbol: coefficient}`` with rational coefficients (the constant under the key ``1``),
    or None when ``u`` is not a rational-linear combination of symbols.

    >>> x, y = sp.symbols("x y")
    >>> rational_linear_form((x - y) / 2 + 1)
    {1: 1, x: 1/2, y: -1/2}
    >>> rational_linear_form(x * y) is None, rational_linear_form(sp.sqrt(2) * x) is None
    (True, True)
    """
    form: dict[sp.Expr, sp.Rational] = {}
    for term in sp.Add.make_args(sp.expand(u)):
        c, rest = term.as_coeff_Mul()
        if not c.is_Rational or not (rest is sp.S.One or rest.is_Symbol):
            return None
        form[rest] = form.get(rest, sp.S.Zero) + c
    return {k: c for k, c in sorted(form.items(), key=lambda kc: sp.default_sort_key(kc[0])) if c != 0}


class _Walk:
    """The walk over the tree, twice: pass 1 (``variables`` None) only reads the exponents' linear
    forms, pass 2 rebuilds the tree with every exponential as its monomial.  Memoised per node."""

    def __init__(self) -> None:
        self.forms: dict[sp.Expr, dict[sp.Expr, sp.Rational] | None] = {}     # exponent -> its form
        self.variables: dict[sp.Expr, tuple[sp.Dummy, int]] | None = None
        self.monomials: dict[tuple[Any, ...], sp.Expr] = {}
        self.memo: dict[sp.Expr, sp.Expr] = {}

    def __call__(self, e: sp.Expr) -> sp.Expr:
        got = self.memo.get(e)
        if got is None:
            got = self.memo[e] = self._walk(e)
        return got

    def second_pass(self, variables: dict[sp.Expr, tuple[sp.Dummy, int]]) -> None:
        self.variables, self.memo = variables, {}

    def _walk(self, e: sp.Expr) -> sp.Expr:
        if isinstance(e, _HYPERBOLIC):
            rewritten = self(e.rewrite(sp.exp))
            return e if self.variables is None else rewritten
        u = _exponent(e)
        if u is not None:
            if u not in self.forms:
                self.forms[u] = rational_linear_form(u)
            form = self.forms[u]
            # not rational-linear: left as it is (not rational, the caller's screen decides)
            return e if form is None or self.variables is None else self._monomial(form)
        if isinstance(e, (sp.Add, sp.Mul)) or (isinstance(e, sp.Pow) and e.exp.is_Integer):
            args = [self(a) for a in e.args]
            # rebuild only what changed: re-evaluating a large sum that holds no exponential is costly
            return e if all(a is b for a, b in zip(args, e.args)) else e.func(*args)
        # any other node is left whole: inside sqrt(exp(2*x)) with a complex x, the positive monomial
        # exp_x**2 would let SymPy "simplify" sqrt(exp_x**2) to exp_x -- false for x = i*pi
        return e

    def _monomial(self, form: dict[sp.Expr, sp.Rational]) -> sp.Expr:
        assert self.variables is not None
        key = tuple(form.items())
        got = self.monomials.get(key)
        if got is None:
            got = self.monomials[key] = sp.Mul(*[self.variables[s][0] ** int(c * self.variables[s][1])
                                                 for s, c in form.items()])
        return got


def _exponent(e: sp.Expr) -> sp.Expr | None:
    """``u`` if the node ``e`` is ``exp(u)`` exactly, in any spelling; None if it is not an exponential."""
    if e is sp.E:
        return sp.S.One
    if isinstance(e, sp.Pow):                      # first: isinstance(E**u, sp.exp) is True in SymPy
        if e.base is sp.E:
            return e.exp
        r = e.exp
        if r.is_Rational:
            v = _exponent(e.base)
            # (e^v)^r = e^(r v): always for an integer r, for a rational r when e^v > 0 (principal power)
            if v is not None and (r.is_Integer or v.is_extended_real):
                return r * v
        return None
    if isinstance(e, sp.exp):
        return e.args[0]
    if isinstance(e, sp.Mul):
        parts = []
        for a in e.args:
            v = _exponent(a)
            if v is None:
                return None
            parts.append(v)
        return sp.Add(*parts)
    return None


def exponentials_as_monomials(*exprs: sp.Expr) -> tuple[tuple[sp.Expr, ...], dict[sp.Expr, tuple[sp.Dummy, int]]]:
    """Rewrite the exponentials of ``exprs`` (jointly) as monomials in ``S = exp(s/d_s)``.

    Returns the rewritten expressions and the variables used: ``{s: (S, d_s)}`` per direction ``s``
    (a symbol, or ``1`` for exponentials of constants such as ``E`` or ``exp(1/2)``).  Exponentials
    that are not of a rational-linear form are left untouched (see the module docstring).

    >>> q1, q2 = sp.symbols("q1 q2", real=True)
    >>> (rat,), v = exponentials_as_monomials(sp.exp((q1 - q2) / 2) * sp.exp(q2))
    >>> rat == v[q1][0] * v[q2][0], v[q1][1], v[q2][1]
    (True, 2, 2)
    """
    walk = _Walk()
    exprs = tuple(sp.sympify(e) for e in exprs)
    for e in exprs:
        walk(e)
    denominators: dict[sp.Expr, int] = {}
    for form in walk.forms.values():
        for s, c in (form or {}).items():
            denominators[s] = lcm(denominators.get(s, 1), int(c.q))
    if not denominators:
        walk.second_pass({})   # still rewrite hyperbolic functions (of constants, say) as exponentials
        return tuple(walk(e) for e in exprs), {}
    directions = sorted(denominators, key=sp.default_sort_key)
    # Dummies: a user symbol that happens to be called ``exp_q`` must not collide
    variables = {s: (sp.Dummy(f"exp_{s.name if s.is_Symbol else s}", positive=True), denominators[s])
                 for s in directions}
    walk.second_pass(variables)
    return tuple(walk(e) for e in exprs), variables


def describe_variables(variables: dict[sp.Expr, tuple[sp.Dummy, int]]) -> str:
    """The variables of :func:`exponentials_as_monomials` as text, e.g. ``exp_q1=e^q1, exp_q2=e^(q2/2)``.

    >>> q = sp.Symbol("q")
    >>> describe_variables(exponentials_as_monomials(sp.exp(q / 2) + sp.E)[1])
    'exp_1=e, exp_q=e^(q/2)'
    """
    def power(s: sp.Expr, d: int) -> str:
        base = "e" if s is sp.S.One else f"e^{s}"
        if d == 1:
            return base
        return f"e^(1/{d})" if s is sp.S.One else f"e^({s}/{d})"
    return ", ".join(f"{v.name}={power(s, d)}" for s, (v, d) in variables.items())
