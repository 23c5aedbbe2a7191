r"""The digits a sampled verdict reports (scene ``checker``; issue 21, seed 6's ``verdict:137``).

* ``checker.verdict_digits`` -- :meth:`symbt.proof.verdict.Verdict.sampled` reports ``digits = -log10(w)``, ``w``
  the residual or, with an error estimate, ``max(residual, error)``, capped at ``dps`` when given, rounded to one
  decimal; ``0`` where ``w`` is infinite and ``None`` (or ``dps``) where ``w = 0`` (its docstring).  Checked on
  residuals across the range -- ``1e-30``, ``0.5``, ``1``, ``2.5``, ``inf``, ``0`` -- with and without ``dps`` and
  an error estimate, against ``math.log10`` of the same numbers: a verified verdict that said 0 digits for a residual
  of ``1e-30``, or 30 for one of ``0.5``, would be read as the opposite of what the evaluation found.

>>> verdict_digits.run().status
'verified'
"""
from __future__ import annotations

import math

from .base import Outcome, claim, failed

#: checker.verdict_digits: (residual, error, dps, tol)
DIGIT_CASES = ((1e-30, None, None, 1e-20), (1e-30, None, 20.0, 1e-20), (1e-30, 1e-25, None, 1e-20),
               (0.5, None, None, 1.0), (1.0, None, None, 1.0), (2.5, None, None, 1e-3), (math.inf, None, None, 1e-3),
               (0.0, None, None, 1e-20), (0.0, None, 12.0, 1e-20), (3e-7, 1e-9, 5.0, 1e-3))


def _documented(r: float, err: float | None, dps: float | None) -> float | None:
    """The docstring's rule, written from it."""
    w = r if err is None else max(r, err)
    if w == 0:
        return dps
    if math.isinf(w):
        return 0.0
    d = -math.log10(w)
    return round(d if dps is None else min(d, dps), 1)


@claim("checker.verdict_digits", equation="checker", scene="checker",
       where="symbt.proof.verdict.Verdict.sampled (the digits it reports)",
       statement="Verdict.sampled's digits are -log10(max(residual, error)) capped at dps, rounded to 0.1; 0 for an "
                 "infinite residual, dps (or None) for 0 -- on residuals 1e-30, 0.5, 1, 2.5, inf, 0 with and without "
                 "dps and error")
def verdict_digits() -> Outcome:
    from ..proof.verdict import Verdict

    bad, seen = [], []
    for r, err, dps, tol in DIGIT_CASES:
        v = Verdict.sampled(r, tol=tol, dps=dps, error=err)
        want = _documented(r, err, dps)
        seen.append(f"{r:g}: {v.digits}")
        if v.digits != want:
            bad.append(f"residual {r:g}, error {err}, dps {dps}: digits {v.digits}, the docstring's rule {want}")
    detail = f"{len(DIGIT_CASES)} cases: " + ", ".join(seen)
    if bad:
        return failed("exact: Verdict.sampled's digits vs its documented rule", detail="; ".join(bad))
    return Outcome("verified", "exact: Verdict.sampled's digits vs its documented rule (math.log10)",
                   evidence="proof", n_scope="all", detail=detail)
