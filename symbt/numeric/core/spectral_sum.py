r"""``lam + p_j`` for a double-double spectral parameter, rounded once: the float64 routes' one source of it.

Every float64 route (the fused kernels, the block kernel, the numpy route of
:func:`~symbt.numeric.core.step.step_core`) is given ``lam1 = fl(lam0 + mu)``,
``lam2 = fl(lam0 - mu)`` and reads the new state out with ``two_mu = 2 mu`` (exact).  Where
``lam1 - lam2 != 2 mu`` (``lam0 = 3.4, mu = 0.3``: by an ulp) every step would be the map of
spectral parameters an ulp inconsistent with its read-out -- the same error in every step, so the
invariants drift linearly in the number of steps (issue 26).  :func:`lam_split` gives the low parts
``lo1, lo2`` (``lo1 - lo2 = two_mu - (lam1 - lam2)``, split evenly, exact) that make
``(lam1 + lo1) - (lam2 + lo2) = two_mu`` exactly, and :func:`lam_add` forms
``a_j = lam + lo + p_j`` with one rounding of the exact sum in the usual case (Knuth's two-sum), so the
error of ``a_j`` depends on ``p_j`` and averages out over an orbit instead of repeating.  Where
``lo = 0`` (``lam1 - lam2 = two_mu`` exactly, e.g. the paper's example) :func:`lam_add` is
``lam + p_j`` bit for bit: the two-sum's error term never changes a correctly rounded sum.

Both work elementwise on floats and numpy arrays alike (numba compiles them into the kernels).

>>> lam0, mu = 3.4, 0.3
>>> lam1, lam2 = lam0 + mu, lam0 - mu
>>> lo1, lo2 = lam_split(lam1, lam2, 2.0 * mu)
>>> from fractions import Fraction as Fr
>>> (Fr(lam1) + Fr(lo1)) - (Fr(lam2) + Fr(lo2)) == 2 * Fr(mu), lo1 != 0.0
(True, True)
>>> lam_add(15.0, 0.0, -20.0), lam_add(1.0, 2.0 ** -53, 2.0 ** -53)        # the second: 1 + 2**-52
(-5.0, 1.0000000000000002)
"""
from __future__ import annotations

from typing import Any

__all__ = ["lam_add", "lam_split"]


def lam_add(lam: Any, lo: Any, p: Any) -> Any:
    """``lam + lo + p`` (``|lo|`` below an ulp of ``lam``): the rounding error of ``lam + p`` (two-sum)
    and ``lo`` added before the one rounding that matters.

    >>> lam_add(3.7, 0.0, 1.25) == 3.7 + 1.25
    True
    """
    h = lam + p
    bp = h - lam
    err = (lam - (h - bp)) + (p - bp)
    return h + (err + lo)


def lam_split(lam1: Any, lam2: Any, two_mu: Any) -> tuple[Any, Any]:
    """Low parts ``(lo1, lo2)`` with ``(lam1 + lo1) - (lam2 + lo2) = two_mu`` (up to ``2**-104`` relative).

    ``lam1 - lam2`` is formed exactly (two-sum), the defect ``two_mu - (lam1 - lam2)`` split evenly;
    both ``0.0`` where the parameters are consistent already.

    >>> lam_split(15.0, 5.0, 10.0)
    (0.0, -0.0)
    """
    d = lam1 - lam2
    bp = d - lam1
    dl = (lam1 - (d - bp)) + (-lam2 - bp)
    defect = (two_mu - d) - dl
    return 0.5 * defect, -0.5 * defect
