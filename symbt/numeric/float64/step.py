r"""The float64 step of a validated problem: which route each state takes.

One state goes through the fused kernel (:mod:`symbt.numeric.float64.kernels`; numba if installed), a
batch through the compiled block kernel (each state's step bit-identical to its single-state step) where
that is faster (fewer than 4096 states, or N >= 8), else -- and without numba -- the vectorised numpy
route of :mod:`symbt.numeric.float64.rows`.  Whatever a kernel gives back is recomputed by the numpy
route, which decides existence and raises the typed errors.

Example
-------
>>> from symbt.numeric.core.problem import prepare
>>> pt, qt = float_step(prepare([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0), False, "auto")
>>> np.round(pt, 8)
array([-19.99656766,   9.78635495,   1.21021272])
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..core.context import FloatValue
from ..core.problem import Problem
from .jit import numba_available
from .orbit import kernel_batch_step, kernel_step
from .rows import float_rows_step

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]

__all__ = ["float_step"]

# No route is chosen by the size of the monodromy: the kernels rescale it by exact powers of two, so
# |tr L| far past 1e150 (large N far from the spectrum) stays in the kernel.  What is still out of the
# float64 range (|q_{j+1} - q_j| > 700, an overflowing p or q) the kernel gives back at once (RANGE) and
# the numpy route below decides it and raises the typed error.


# measured (BENCHMARKS.md, throughput): one step of the block kernel beats the numpy route 2-5x on batches
# below a few thousand states and at every batch size from N = 8 on; at N = 3 numpy's vectorised step wins
# from ~5000 states (0.7-0.8x)
_BLOCK_KERNEL_MAX_STATES_SMALL_N = 4096
_BLOCK_KERNEL_MIN_N = 8


def _block_kernel_pays(pa: F64) -> bool:
    """Whether ``backend="auto"`` sends a float64 batch ``pa`` (shape ``(M, N)``) to the compiled block kernel.

    >>> import numpy as np
    >>> [_block_kernel_pays(np.zeros((M, N))) for M, N in ((100, 3), (10_000, 3), (10_000, 16))]
    [True, False, True]
    """
    M, N = pa.shape
    return M < _BLOCK_KERNEL_MAX_STATES_SMALL_N or N >= _BLOCK_KERNEL_MIN_N


def float_step(pr: Problem, allow_complex: bool, backend: str) -> tuple[FloatValue, FloatValue]:
    """One step of the float64 problem ``pr`` by ``backend`` (``"auto"``, ``"numba"``, ``"python"``,
    ``"numpy"``); arrays of the input shape."""
    pa, qa, shape, lam0, mu, branch = pr.p, pr.q, pr.shape, pr.lam0, pr.mu, pr.branch
    N = pa.shape[-1]
    if np.ndim(mu) == 0 and mu == 0:
        return pa.reshape(shape + (N,)).copy(), qa.reshape(shape + (N,)).copy()
    if shape == () and backend != "numpy":
        out = kernel_step(pa[0], qa[0], float(lam0), float(mu), branch, backend)
        if out is not None:
            return out
    if shape != () and backend in ("auto", "numba"):
        if numba_available() and (backend == "numba" or _block_kernel_pays(pa)):
            # each member by its single-state route: the block kernel (bit-identical to the single-state
            # kernel), and the numpy route for exactly the members it hands back
            outp, outq = kernel_batch_step(pa, qa, lam0, mu, branch, allow_complex, shape)
            return outp.reshape(shape + (N,)), outq.reshape(shape + (N,))
    outp, outq = float_rows_step(pa, qa, lam0, mu, branch, allow_complex, shape)
    return outp.reshape(shape + (N,)), outq.reshape(shape + (N,))
