"""Which form ``toda{N}`` is emitted in.

The closed forms (every output one expression of ``p``, ``exp(q_i - q_j)``, ...) grow like
``(1 + sqrt 2)^N`` -- the number of monomials of tr L -- and the step's N cyclically shifted
monodromies like ``N (1 + sqrt 2)^N``: emission time, module size and the cost of a batched step
all grow by ~2.4x per site.  From :data:`LOOP_FROM` on the transfer-matrix form is emitted
instead: loops over the sites with one-site kernels, O(N) per step (BENCHMARKS.md, "Code
generation for any N", has the measurements behind the choice).

>>> form_of(3), form_of(LOOP_FROM)
('closed', 'transfer-matrix')
"""
from __future__ import annotations

from typing import Literal, get_args

__all__ = ["LOOP_FROM", "FORMS", "form_of", "Language", "LANGUAGES"]

#: ``target=`` of the generators (``symbt codegen --target``): Python (numpy + mpmath) or C99
Language = Literal["python", "c"]
LANGUAGES: tuple[Language, ...] = get_args(Language)

#: the first N emitted in the transfer-matrix form
LOOP_FROM = 4
FORMS = ("closed", "transfer-matrix")


def form_of(N: int) -> str:
    """``"closed"`` or ``"transfer-matrix"``: the form ``toda{N}`` is emitted in."""
    return "closed" if N < LOOP_FROM else "transfer-matrix"
