r"""The statement mutations of ``symbt mutate`` checked on statements whose mutants are known (scene ``checker``).

``symbt mutate`` judges every claim's check by the mutants :func:`symbt.proof.mutation.mutants` derives from
its statement; an operator that silently yields fewer (or other) mutants leaves checks untested and still
reports a high score.  ``checker.mutation`` applies the operators to two true statements,

.. math:: (x-1)(x+1) + e^{\sqrt y} = x^2 - 1 + e^{\sqrt y}, \qquad x(x+2) = x^2 + 2x

(:math:`x` real, :math:`y > 0`), whose mutants follow from the operators' documented rules (flip the sign of
a term, drop a term of a sum of two or more, :math:`n \to n+1` with :math:`-1 \to -2`, a relative
:math:`10^{-6}` on a coefficient, :math:`\sqrt{\cdot} \to -\sqrt{\cdot}`; exponents are structure, not
constants), and requires

* the mutants of each right-hand side to be exactly that list (operator and expression), and
* the verdict to flip: :func:`symbt.proof.decide` proves each statement and refutes every mutant.

>>> mutation_controls.run().status
'verified'
"""
from __future__ import annotations

import sympy as sp

from ..proof import decide
from ..proof.mutation import PERTURBATION, mutants
from .base import Outcome, claim, failed

x = sp.Symbol("x", real=True)
y = sp.Symbol("y", positive=True)


def _expected() -> list[tuple[sp.Expr, sp.Expr, set[tuple[str, sp.Expr]]]]:
    """(lhs, rhs, the mutants of rhs by the documented rules) for the two statements."""
    e = sp.exp(sp.sqrt(y))
    one = 1 + PERTURBATION
    first = {("flip_sign", x ** 2 + e + 1), ("flip_sign", -x ** 2 + e - 1), ("flip_sign", x ** 2 - e - 1),
             ("drop_term", x ** 2 + e), ("drop_term", e - 1), ("drop_term", x ** 2 - 1),
             ("change_const", x ** 2 + e - 2),                      # -1 -> -2 (-1 + 1 = 0 would repeat drop_term)
             ("perturb", x ** 2 + e - one),
             ("convention", x ** 2 - 1 + sp.exp(-sp.sqrt(y)))}      # sqrt -> -sqrt; the exponent 2 of x**2 is not
    second = {("flip_sign", -x ** 2 + 2 * x), ("flip_sign", x ** 2 - 2 * x),
              ("drop_term", 2 * x), ("drop_term", x ** 2),           # a sum of two terms loses either
              ("change_const", x ** 2 + 3 * x), ("perturb", x ** 2 + 2 * one * x)}
    return [((x - 1) * (x + 1) + e, x ** 2 - 1 + e, first), (x * (x + 2), x ** 2 + 2 * x, second)]


@claim("checker.mutation", equation="checker", scene="checker",
       where="symbt.proof.mutation: mutants and its six operators (the statement mutations of symbt mutate)",
       statement="the mutants of x^2 - 1 + exp(sqrt(y)) and of x^2 + 2x are exactly those the operators' rules give "
                 "(9 and 6), and decide proves (x-1)(x+1) + exp(sqrt(y)) = x^2 - 1 + exp(sqrt(y)) and x(x+2) = x^2 + "
                 "2x and refutes every mutant")
def mutation_controls() -> Outcome:
    total, evidence = 0, set()
    for lhs, rhs, want in _expected():
        got = [(m.operator, m.expr) for m in mutants(rhs)]
        if len(got) != len(set(got)) or set(got) != want:
            extra = sorted(map(str, set(got) - want))
            lost = sorted(map(str, want - set(got)))
            return failed("symbt.proof.mutation.mutants",
                          detail=f"mutants of {rhs}: unexpected {extra}, missing {lost}")
        d = decide(lhs, rhs)
        if not d.holds:
            return failed(d.method, residual=d.residual, detail=f"{lhs} = {rhs} (true) was not proved")
        for op, expr in got:
            dm = decide(lhs, expr)
            evidence.add(dm.evidence)
            if dm.holds or dm.inconclusive:
                return failed(dm.method, residual=dm.residual,
                              detail=f"the {op} mutant {lhs} = {expr} was not refuted: the verdict did not flip")
        total += len(got)
    return Outcome("verified", "exact: the mutant lists against the operators' rules; decide on every mutant",
                   evidence="proof" if evidence == {"proof"} else "sampled", n_scope="all",
                   detail=f"2 true statements proved; their {total} mutants are the documented ones and each is "
                          f"refuted (by {' and '.join(sorted(evidence))})")
