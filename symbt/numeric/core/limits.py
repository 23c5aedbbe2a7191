"""The status codes of the fused kernels and the limits of each arithmetic, defined once.

Status codes (float64 kernels, block kernel and quad-double step alike; the drivers turn them into
the typed errors of :mod:`symbt.numeric.core.errors`):

==============  ====  ==========================================================================
``OK``          0     the step exists and was computed
``TRACE1``      1     ``|tr L(lam1)| <= 2``: ``lam1 = lam0 + mu`` lies in a band
``TRACE2``      2     ``|tr L(lam2)| <= 2``
``POSITIVITY``  3     some ``Etilde_j <= 0``: ``lam1`` and ``lam2`` lie in different spectral gaps
``RANGE``       4     beyond the arithmetic's range (the general path or the next backend takes over)
``ILLCOND``     5     the state's condition estimate exceeds :data:`KAPPA_MAX`: recomputed at higher precision
==============  ====  ==========================================================================

Neighbour distances.  Only ``r_j = exp(q_{j+1} - q_j)`` enters the step; how far ``|q_{j+1} - q_j|``
may go depends on the arithmetic:

* float64 (:data:`MAX_DQ_FLOAT64` = 700): ``exp(+-700)`` lies inside the normal doubles
  (``2**-1022 .. 2**1024``, i.e. ``exp(+-708)``); the scaled monodromy renormalises its products by
  powers of two, so the ratios themselves are the only values that must fit.
* quad-double (:data:`MAX_DQ_QD` = 300): a quad-double carries 209 bits with a double's exponent range,
  and its exact products split each factor by ``2**27 + 1`` (Dekker), so a factor must stay below
  ``2**996``.  The step squares the trace (``tr**2 - 4 = (tr - 2)(tr + 2)``) and for ``N = 2`` already
  ``|tr| ~ exp(|q_2 - q_1|)``: ``2 |dq| / ln 2 < 996`` gives ``|dq| < 345``.  300 keeps a margin of 45 in
  the exponent (``tests/test_numeric_limits.py`` checks both sides: with the limit lifted the step is
  accurate at 340 and overflows at 350).  Beyond it, ``backend="auto"`` continues on the Arb path.

numba freezes these values into the compiled kernels and checks only the kernel file's time stamp: the
quad-double cache marker hashes this file (:func:`~symbt.numeric.multiprec.qd.qd_ready`); after changing
a value, also touch ``float64/kernels.py`` and ``float64/kernels_block.py``.

>>> from symbt.numeric.core.limits import MAX_DQ_FLOAT64, MAX_DQ_QD, RANGE
>>> MAX_DQ_QD < MAX_DQ_FLOAT64, RANGE
(True, 4)
"""

from __future__ import annotations

__all__ = ["OK", "TRACE1", "TRACE2", "POSITIVITY", "RANGE", "ILLCOND", "KAPPA_MAX", "MAX_DQ_FLOAT64", "MAX_DQ_QD"]

OK, TRACE1, TRACE2, POSITIVITY, RANGE, ILLCOND = 0, 1, 2, 3, 4, 5
#: float64 states whose condition estimate exceeds this are recomputed at higher precision
#: (:func:`symbt.numeric.float64.rows.escalate_rows`)
KAPPA_MAX = 2.0 ** 24

#: largest neighbour distance ``|q_{j+1} - q_j|`` of the float64 paths
MAX_DQ_FLOAT64 = 700.0
#: largest neighbour distance the quad-double step accepts (see the module docstring)
MAX_DQ_QD = 300.0
