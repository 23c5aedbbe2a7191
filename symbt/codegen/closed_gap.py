r"""``tr^2 - 4`` of the scaled monodromy near a nearly closed gap, without the cancellation of ``tr -+ 2``.

Where a gap nearly closes, ``tr L`` has an extremum ``+-2`` in lambda and the monodromy is close to ``+-I``:
``tr -+ 2`` cancels, and its rounding (``eps`` times the scale of the terms of the trace, ~2) is not an input
perturbation -- every first derivative of ``tr`` is small there, so the condition scale ``S`` of
docs/codegen.md does not count it -- and ``sqrt(tr^2 - 4)`` amplifies it into the slopes (17-74 eps S at the
deep fuzz's nearly closed gaps, docs/fuzz.md).  With ``det M = 1``,

.. math:: \operatorname{tr}^2 - 4 = (A + D)^2 - 4 (AD - BC) = (A - D)^2 + 4 BC,

whose terms are all small there: each rounds at the scale of ``A - D``, ``B``, ``C`` (a few ``eps`` times
``|A - D| + |B| + |C|``), not at the scale 2 of ``tr``.  It is selected where that scale is the smaller,
``|A - D| + 2 (|B| + |C|) < |t| + two`` (the first-order rounding of ``(t - two)(t + two)`` is
``(|t - two| + |t + two|) delta t``, of ``(A - D)^2 + 4 BC`` about ``(2 |A - D| + 4 |B| + 4 |C|) delta`` for
entries rounded alike); elsewhere ``(t - two)(t + two)`` as before (at a regular band edge ``|A - D|``, ``B``, ``C``
stay of order ``|t|`` and the entries' form cancels instead).  Homogeneous: for the rescaled
``M = 2^e (A, B; C, D)`` it gives ``4^-e (tr^2 - 4)`` with ``t = A + D``, ``two = 2^(1 - e)``.

>>> A, B, C, D = sp.symbols("A B C D", real=True)
>>> sp.expand(entries_discriminant(A, B, C, D) - ((A + D)**2 - 4*(A*D - B*C)))
0
>>> x = sp.Rational(1, 1000)
>>> M = sp.Matrix([[-1 - x, x], [-x, -1 + x]])     # det M = 1, tr M = -2: a closed gap
>>> d = trace_discriminant(M)
>>> d.args[0][0], bool(d.args[0][1].doit())       # the entries' form, selected
(0, True)
"""
from __future__ import annotations

from typing import Any

import sympy as sp

__all__ = ["entries_discriminant", "near_closed_gap", "trace_discriminant"]


def _abs(x: Any) -> Any:        # unevaluated: SymPy's sign analysis of the monodromy's entries is slow
    return sp.Abs(x, evaluate=False)


def entries_discriminant(A: Any, B: Any, C: Any, D: Any) -> Any:
    """``(A - D)^2 + 4 B C``: ``tr^2 - 4 det`` of ``(A, B; C, D)``, the trace's discriminant where ``det = 1``."""
    return (A - D) ** 2 + 4 * B * C


def near_closed_gap(A: Any, B: Any, C: Any, D: Any, two: Any = 2) -> Any:
    """True where :func:`entries_discriminant` rounds at the smaller scale: ``|A - D| + 2 (|B| + |C|) < |t| + two``,
    ``t = A + D`` (``two = 2^(1 - e)`` for the rescaled monodromy ``2^e (A, B; C, D)``)."""
    return sp.StrictLessThan(_abs(A - D) + 2 * (_abs(B) + _abs(C)), _abs(A + D) + two, evaluate=False)


def trace_discriminant(M: sp.Matrix) -> sp.Piecewise:
    """``tr^2 - 4`` of the monodromy ``M`` (``det M = 1``): :func:`entries_discriminant` near a closed gap
    (:func:`near_closed_gap`), else ``(t - 2)(t + 2)``."""
    A, B, C, D = M[0, 0], M[0, 1], M[1, 0], M[1, 1]
    t = A + D
    return sp.Piecewise((entries_discriminant(A, B, C, D), near_closed_gap(A, B, C, D)),
                        (sp.Mul(t - 2, t + 2, evaluate=False), True), evaluate=False)
