r"""Private helpers of the exact claim modules (toy, toda_model, single_bt, appendix_a, generating).

* :func:`to_E` turns a statement printed with exponentials :math:`e^{\pm q_j}` into a rational
  function of the positive symbols :math:`E_j = e^{q_j}` (exactly what :func:`symbt.proof.decide`
  reduces), so printed parts can be kept in the paper's form and still be mutated.
* :func:`same_equation` decides that two equations ``a = 0`` and ``b = 0`` are the same up to a
  nonzero constant factor (``cancel(a/b)`` is a nonzero number) -- how the paper's "eliminating v
  we are left with ..." is checked.
* :func:`for_all_n` / :func:`for_sizes` record the lattice sizes an outcome covers
  (``Outcome.n_scope``): ``"all"`` with the argument appended to the detail, or the sizes checked.

>>> import sympy as sp
>>> q, E = sp.Symbol("q_j", real=True), sp.Symbol("E_j", positive=True)
>>> to_E(sp.exp(-2 * q), {q: E})
E_j**(-2)
>>> a, b = sp.symbols("a b")
>>> same_equation(2 * a - 4 * b, b - a / 2).holds, same_equation(a - b, a + b).holds
(True, False)
>>> same_equation(b * (a - 1), a - 1, unknowns=(a,)).holds
True
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import sympy as sp

from ..proof.verdict import Verdict
from ..symbolic.rewriting import rationalize_exponentials
from .base import Outcome

__all__ = ["to_E", "same_equation", "for_all_n", "for_sizes", "PER_SITE", "GENERIC_2X2"]

#: the argument behind n_scope = "all" for a statement about one site of a local relation
PER_SITE = ("per-site identity plus composition: the residual involves site j and its neighbours only, and "
            "with periodic indices (d_{N+1} = d_1) the local relations telescope, "
            "l~_N...l~_1 d_1 = d_{N+1} l_N...l_1 = d_1 L, for every N >= 2")
#: the argument behind n_scope = "all" for a statement about generic 2x2 matrices
GENERIC_2X2 = ("2x2 matrix algebra with generic entries: L(lambda) = l_N...l_1 of any N is a 2x2 matrix "
               "(unimodular, eq. eq:lax), so the identity specialises to every N")


def to_E(expr: Any, pairs: Mapping[sp.Symbol, sp.Symbol]) -> Any:
    """``exp``/``cosh`` of integer combinations of the keys of ``pairs`` as monomials in the values."""
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(lambda e: to_E(e, pairs))
    out, _ = rationalize_exponentials(sp.sympify(expr), dict(pairs))
    return out


def same_equation(a: Any, b: Any, unknowns: tuple = ()) -> Verdict:
    """Is ``a = 0`` the equation ``b = 0`` times a nonzero factor?  (exact: ``cancel(a/b)``).

    Without ``unknowns`` the factor must be a nonzero number; with them it may be any nonzero
    rational function free of the unknowns (then ``a = 0`` and ``b = 0`` have the same solutions
    for the unknowns wherever the factor is finite and nonzero).
    """
    a, b = sp.sympify(a), sp.sympify(b)
    if b == 0 or a == 0:
        return Verdict(False, "proof", "exact: cancel(a/b)", residual=1.0, definite=True,
                       counterexample={"a": sp.sstr(a), "b": sp.sstr(b)}, note="an equation is 0 = 0")
    r = sp.cancel(sp.together(a / b))
    free = r.is_number if not unknowns else not (r.free_symbols & set(unknowns))
    if free and r != 0 and not r.has(sp.zoo, sp.nan, sp.oo):
        what = "a nonzero constant" if not unknowns else "nonzero and free of " + ", ".join(map(str, unknowns))
        return Verdict.from_proof(f"exact: cancel(a/b) = {sp.sstr(r)}, {what}")
    return Verdict(False, "proof", "exact: cancel(a/b) is not an admissible factor", residual=1.0, definite=True,
                   counterexample={"ratio": sp.sstr(r)[:200]})


def for_all_n(out: Outcome, argument: str) -> Outcome:
    """``n_scope = "all"``, with the argument why in the detail."""
    return replace(out, n_scope="all", detail=(out.detail + f" [every N: {argument}]").strip())


def for_sizes(out: Outcome, *sizes: int) -> Outcome:
    return replace(out, n_scope=list(sizes))
