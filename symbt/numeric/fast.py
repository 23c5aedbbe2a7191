r"""Fused single-orbit kernel of the float64 Bäcklund map (kept for compatibility).

:func:`fast_orbit` is :func:`~symbt.numeric.bt_orbit` for one float64 state
with a choice of kernel backend; ``bt_orbit`` itself now runs the same fused
kernel (:mod:`symbt.numeric.float64.kernels`, numba compiled lazily by
:mod:`symbt.numeric.float64.jit`) whenever it applies.  The pure-Python and numba
versions run the *same* source on IEEE doubles with ``sqrt/exp/log1p`` from the
C math library (no ``fastmath``), so their results are identical bit for bit
(``tests/test_numeric_fast.py``).  Cases outside the kernel's fast path are
recomputed by the general path, which raises the documented typed errors.

``HAVE_NUMBA`` (module attribute) is evaluated lazily: reading it imports
numba (once); importing this module does not.

Example
-------
>>> from symbt.numeric.fast import fast_orbit
>>> P, Q = fast_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 3500, every=3500)
>>> P.shape
(2, 3)
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from .core.errors import InvalidInputError
from .core.inputs import check_branch, check_steps
from .float64.jit import kernel, numba_available

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["fast_orbit", "kernel_backend"]  # and HAVE_NUMBA (lazy, see __getattr__)


def __getattr__(name: str) -> Any:
    if name == "HAVE_NUMBA":
        return numba_available()
    raise AttributeError("module %r has no attribute %r" % (__name__, name))


def kernel_backend(backend: str = "auto") -> tuple[Callable[..., Any], str]:
    """The single-orbit kernel for ``backend`` in {"auto", "numba", "python"} and its name.

    >>> kernel_backend("python")[1]
    'python'
    """
    return kernel("orbit", backend)


def fast_orbit(p: Any, q: Any, lam0: Any, mu: Any, n: int, *, branch: int = 1, every: int = 1,
               backend: str = "auto") -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """``n`` Bäcklund steps of one float64 state, sampled every ``every`` steps.

    Returns arrays ``P, Q`` of shape ``(rows, N)``: the initial state, the
    states after ``every, 2 every, ...`` steps and always the final state
    (``rows = 1 + ceil(n / every)``), exactly as ``bt_orbit(..., every=every)``.
    ``backend`` in {"auto", "numba", "python"} selects the kernel.

    >>> P, Q = fast_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 10, every=5, backend="python")
    >>> P.shape
    (3, 3)
    """
    from .float64.orbit import float_orbit

    branch = check_branch(branch)
    n, every = check_steps(n, every)
    if backend not in ("auto", "numba", "python"):
        raise InvalidInputError("backend must be 'auto', 'numba' or 'python', got %r" % (backend,))
    if np.ndim(p) != 1 or np.ndim(q) != 1:
        raise InvalidInputError("fast_orbit takes one state: p, q of shape (N,)")
    if np.ndim(lam0) or np.ndim(mu):
        raise InvalidInputError("fast_orbit takes scalar lam0 and mu")
    return float_orbit(p, q, lam0, mu, n, branch=branch, every=every, backend=backend)
