r"""A closed form solves an ODE: exactly, or per domain cell at high precision.

The ODE is given as SymPy equations in unknown functions :math:`x_1(t), \dots, x_m(t)` and their
derivatives -- explicit, ``Eq(x(t).diff(t), f(t, x(t)))``, or implicit, an expression
:math:`F(t, x, x', x'') = 0` -- with any parameters; the closed form maps each unknown to an
expression :math:`X_j(t; p)`.  The residual of equation :math:`i` is

.. math::  R_i(t; p) = F_i(t, X, X', X'', \dots; p),

the derivatives of the closed form taken exactly (SymPy), and:

1. **exact** -- each :math:`R_i` goes to the exact layer of :func:`symbt.proof.decide`
   (exponentials of integer-linear forms become monomials, one fraction): all zero is a proof;
   a nonzero rational function is a proof that the closed form is no solution (a counterexample
   is still sampled);
2. **sampled** otherwise -- :math:`R_i` at ``dps`` significant digits (mpmath) at the seeded points
   of every cell of a :class:`~symbt.proof.domain.Domain` (default: each variable uniform on
   ``[1/4, 2]``); the residual of a point is the largest over the equations of
   :math:`|\sum_k T_{ik}| / \max(\max_k |T_{ik}|, \min(1, \max_k m(T_{ik})))`, the :math:`T_{ik}`
   being the terms of :math:`F_i` (``lhs`` and ``-rhs`` of an equation) and :math:`m` the size of a
   term's own terms (:func:`~symbt.proof.magnitude.magnitude`), so that a solution is judged relative
   to its size, large or small, and rounding where a term cancels to 0 is not a residual.  The verdict
   carries the cells and, as its ``note``, the scope sentence.

>>> import sympy as sp
>>> t, t0 = sp.symbols("t t0")
>>> x = sp.Function("x")
>>> solves_ode(sp.Eq(x(t).diff(t), x(t) * (1 - x(t))), 1 / (1 + sp.exp(-t))).verdict     # logistic
'proved'
>>> # x = (t - t0)^2/4 solves x' = sqrt(x) only after t0
>>> from symbt.proof.domain import Domain, sign
>>> v = solves_ode(sp.Eq(x(t).diff(t), sp.sqrt(x(t))), (t - t0)**2 / 4,
...                domain=Domain({"t": (-2, 2), "t0": (-1, 1)}), splits=[sign(t - t0)])
>>> v.verdict, v.note
('false', 'printed statement holds exactly in cells {t>t0} and fails in {t<t0}')
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from functools import partial
from typing import Any

import mpmath as mp
import sympy as sp
from sympy.core.function import AppliedUndef, UndefinedFunction

from .cells import CellTable
from .domain import Domain, Split
from .exact import exact_zero
from .lambdify import plain_lambdify
from .magnitude import floored_scale, magnitude, size_or_inf
from .verdict import Verdict

__all__ = ["solves_ode", "ode_residual", "OdeResidual", "DEFAULT_RANGE"]

#: the range of every variable when ``solves_ode`` is given no domain (positive: logs and roots stay real)
DEFAULT_RANGE = (0.25, 2.0)


def _equations(ode: Any) -> list[Any]:
    eqs = list(ode) if isinstance(ode, (list, tuple)) else [ode]
    if not eqs:
        raise ValueError("solves_ode: no equation given")
    out = []
    for e in eqs:
        e = sp.sympify(e)
        if not isinstance(e, (sp.Equality, sp.Expr)):
            raise TypeError(f"solves_ode: an equation is Eq(lhs, rhs) or an expression equal to 0, got {e!r}")
        out.append(e)
    return out


def _unknowns(eqs: list[Any]) -> tuple[sp.Symbol, list[Any]]:
    found = set().union(*(e.atoms(AppliedUndef) for e in eqs))
    if not found:
        raise ValueError("solves_ode: the ODE names no unknown function such as x(t) (x = sympy.Function('x'))")
    args = {u.args for u in found}
    if len(args) != 1 or len(next(iter(args))) != 1 or not isinstance(next(iter(args))[0], sp.Symbol):
        raise ValueError(f"solves_ode: the unknowns must be functions of one and the same variable, got "
                         f"{', '.join(sorted(map(str, found)))}")
    t = next(iter(args))[0]
    return t, sorted(found, key=str)    # by name: a tuple solution is paired in the equations' order (_solution)


def _solution(solution: Any, unknowns: list[Any], eqs: list[Any]) -> dict[Any, Any]:
    by_func = {u.func: u for u in unknowns}
    items: list[tuple[Any, Any]]
    if isinstance(solution, Mapping):
        items = list(solution.items())
    elif isinstance(solution, sp.Equality):
        items = [(solution.lhs, solution.rhs)]
    elif isinstance(solution, (list, tuple)) and all(isinstance(s, sp.Equality) for s in solution):
        items = [(s.lhs, s.rhs) for s in solution]
    elif isinstance(solution, (list, tuple)):
        explicit = [e.lhs.expr for e in eqs if isinstance(e, sp.Equality) and isinstance(e.lhs, sp.Derivative)]
        if len(solution) != len(unknowns) or sorted(map(str, explicit)) != sorted(map(str, unknowns)):
            raise ValueError("solves_ode: a tuple of closed forms needs one equation x'(t) = ... per unknown, in "
                             "that order; otherwise give a dict {x: ..., y: ...}")
        items = list(zip(explicit, solution))
    else:
        if len(unknowns) != 1:
            raise ValueError(f"solves_ode: {len(unknowns)} unknowns; give a dict {{x: ..., y: ...}} or a tuple")
        items = [(unknowns[0], solution)]
    out = {}
    for key, value in items:
        u = by_func.get(key) if isinstance(key, UndefinedFunction) else key
        if u not in unknowns:
            raise ValueError(f"solves_ode: {key} is not an unknown of the ODE ({', '.join(map(str, unknowns))})")
        out[u] = sp.sympify(value)
    missing = [str(u) for u in unknowns if u not in out]
    if missing:
        raise ValueError(f"solves_ode: no closed form for {', '.join(missing)}")
    if any(v.atoms(AppliedUndef) & set(unknowns) for v in out.values()):
        raise ValueError("solves_ode: a closed form must not contain the unknowns")
    return out


def _residual_terms(ode: Any, solution: Any) -> tuple[sp.Symbol, list[list[Any]]]:
    """The independent variable and, per equation, its terms with the closed form substituted."""
    eqs = _equations(ode)
    t, unknowns = _unknowns(eqs)
    sol = _solution(solution, unknowns, eqs)
    rules: dict[Any, Any] = {}
    for e in eqs:
        for d in e.atoms(sp.Derivative):
            if d.expr in sol:
                if set(d.variables) != {t}:
                    raise ValueError(f"solves_ode: {d} is not a derivative in {t}")
                rules[d] = sp.diff(sol[d.expr], *d.variables)
    rules.update(sol)
    terms = []
    for e in eqs:
        parts = [e.lhs, -e.rhs] if isinstance(e, sp.Equality) else list(sp.Add.make_args(e))
        terms.append([p.xreplace(rules) for p in parts])
    return t, terms


class OdeResidual:
    """The residual of a closed form in an ODE at one point (made by :func:`ode_residual`): called with the
    point's values by name (``Domain.evaluate`` passes the whole point: ``**point`` takes it); ``variables`` are the
    names it needs."""

    def __init__(self, symbols: list[sp.Symbol], terms: list[list[Any]]) -> None:
        self.variables = tuple(s.name for s in symbols)
        self._f = plain_lambdify(symbols, terms, "mpmath")
        # each equation's terms' sizes (symbt.proof.magnitude), for the floor of its scale where every term is below 1
        self._sizes = [plain_lambdify(symbols, [magnitude(p) for p in eq], "mpmath") for eq in terms]

    def __call__(self, **point: Any) -> Any:
        missing = [n for n in self.variables if n not in point]
        if missing:
            raise ValueError(f"the ODE residual needs {', '.join(missing)}; the point has {', '.join(point)}")
        args = [point[n] for n in self.variables]
        worst = mp.mpf(0)
        for values, sizes in zip(self._f(*args), self._sizes):
            scale = floored_scale(max(abs(v) for v in values), partial(size_or_inf, partial(sizes, *args)))
            if scale:       # every term exactly 0: residual 0
                worst = max(worst, abs(mp.fsum(values)) / scale)
        return worst


def ode_residual(ode: Any, solution: Any) -> OdeResidual:
    r"""The closed form's residual as a function of the points of a :class:`~symbt.proof.domain.Domain`
    (for ``Domain.evaluate(..., printed=ode_residual(...), corrected=...)``); its ``variables``
    are the names it needs.  Arguments as in :func:`solves_ode`.

    >>> t, k = sp.symbols("t k"); x = sp.Function("x")
    >>> r = ode_residual(sp.Eq(x(t).diff(t, 2), -k**2 * x(t)), sp.sin(k * t))
    >>> r.variables, r(t=mp.mpf(1), k=mp.mpf(2)) < 1e-14
    (('k', 't'), True)
    """
    t, terms = _residual_terms(ode, solution)
    syms = sorted(set().union({t}, *(p.free_symbols for eq in terms for p in eq)), key=lambda s: s.name)
    return OdeResidual(syms, terms)


def solves_ode(ode: Any, solution: Any, *, domain: Domain | None = None, splits: Iterable[Split] = (),
               dps: int = 30, tol: float | None = None, per_cell: int | None = None, deep: bool = False,
               exact: bool = True) -> Verdict:
    """Whether ``solution`` solves ``ode`` (see the module docstring), as a :class:`~symbt.proof.Verdict`.

    ``ode``: ``Eq(...)`` or an expression equal to zero, or a list of them for a system, in unknown
    functions such as ``x(t)``.  ``solution``: the closed form (one unknown), ``Eq(x(t), ...)``, a dict
    ``{x: ..., y: ...}`` or a tuple in the order of the equations ``x'(t) = ...``, ``y'(t) = ...``.
    ``domain`` and ``splits`` are the cells of the sampled check; ``dps``, ``tol``, ``per_cell`` and
    ``deep`` as in :meth:`~symbt.proof.domain.Domain.evaluate`; ``exact=False`` skips the exact layer.
    ``judge(verdict, printed=...)`` or ``from_decision(verdict)`` make it a claim's outcome.

    >>> t = sp.Symbol("t"); x = sp.Function("x")
    >>> v = solves_ode(t * x(t).diff(t, 2) + x(t).diff(t) + t * x(t), sp.besselj(0, t))   # Bessel, order 0
    >>> v.verdict, v.evidence, len(v.cells)
    ('verified', 'sampled', 1)
    >>> v = solves_ode(sp.Eq(x(t).diff(t), x(t)), sp.exp(2 * t))
    >>> v.verdict, v.evidence, sorted(v.counterexample)
    ('false', 'proof', ['cell', 't'])
    """
    t, terms = _residual_terms(ode, solution)
    method_exact, definite = "", False
    if exact:
        results = [exact_zero(sp.Add(*eq), {}) for eq in terms]
        if all(zero for zero, _, _ in results):
            return Verdict.from_proof(results[0][1] + " of every equation's residual",
                                      note="the closed form's residual is exactly zero")
        definite = any(zero is False and sure for zero, _, sure in results)
        method_exact = next((m for zero, m, _ in results if zero is False), "")
    residual = ode_residual(ode, solution)
    splits = list(splits)
    chosen = {s.name for s in splits if s.kind == "choice"}     # a choice's value is a parameter too
    needed = [n for n in residual.variables if n not in chosen]
    if domain is None:
        domain = Domain({name: DEFAULT_RANGE for name in needed})
    lacking = [n for n in needed if n not in domain.variables]
    if lacking:
        raise ValueError(f"solves_ode: the domain lacks {', '.join(lacking)} (it has {', '.join(domain.variables)})")
    # a nonzero rational function vanishes on no open set, but may at the values of a choice or an integer
    discrete = chosen | {n for n, r in domain.variables.items() if r.kind == "integers"}
    definite = definite and not discrete & set(residual.variables)
    table: CellTable = domain.evaluate(*splits, printed=residual, dps=dps, tol=tol, per_cell=per_cell, deep=deep)
    sampled = table.verdict(method="ODE residual by " + table.method)
    if definite:
        return Verdict(False, "proof", method_exact + " left a nonzero rational function; worst point by "
                       + sampled.method, residual=sampled.residual, digits=sampled.digits,
                       counterexample=table.worst("printed")[1], cells=sampled.cells, definite=True,
                       note="exactly false: the residual is a nonzero rational function; " + sampled.note)
    if method_exact:
        sampled.method = method_exact + " left a nonzero remainder; " + sampled.method
    elif exact:
        sampled.method = "exact layer does not apply (not rational after exp->monomials); " + sampled.method
    return sampled
