"""Orbits of the Bäcklund map: ``n`` steps of :func:`~symbt.numeric.bt_step` in one call.

The map preserves ``tr L(lam)`` (all ``H_k``) and, being a canonical
transformation that interpolates a Hamiltonian flow (paper Thm. 2, eq.
``eqdisc``), its orbits lie on invariant tori; the centre of mass
``Q = mean(q)`` drifts linearly.  Because each float64 step is accurate to a
few ulps, the orbit error grows only through the (linear, integrable)
dynamics (``~ eps n^2``; see ``tests/test_numeric_orbit.py``).

Backends (picked automatically, see :func:`bt_orbit`):

* float64, one state: the fused kernel (:mod:`.kernels`, numba if installed);
* float64 ensemble ``(M, N)``: the fused block kernel on all cores (numba) or
  the vectorised numpy path (:mod:`.ensemble`); ``every=k`` stores every k-th
  state only;
* mpmath numbers: python-flint's Arb at the caller's precision plus guard
  bits (:mod:`.mpfast`), else mpmath;
* ``certified=True``: rigorous enclosures by Arb ball arithmetic
  (:mod:`.certified`).

Example
-------
>>> from symbt.numeric import bt_orbit
>>> P, Q = bt_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 3)
>>> P.shape
(4, 3)
>>> P, Q = bt_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 3500, every=3500)
>>> P.shape                                     # the initial and the final state
(2, 3)
"""

from __future__ import annotations

from typing import Any, Literal, overload

import numpy as np

from ._input import check_branch, pick_context
from .context import FLOAT
from .ensemble import float_orbit
from .errors import InvalidInputError

__all__ = ["bt_orbit", "check_steps"]

_MAX_STEPS = 2 ** 62        # the kernels count steps in int64; far beyond any run


def check_steps(n: Any, every: Any) -> tuple[int, int]:
    """Validated ``(n, every)``: non-negative and positive integers.

    ``every > n`` stores the same rows as ``every = n`` (the initial and the final state) and
    is returned as such, so that any Python integer works; ``n`` must fit an int64.

    >>> check_steps(10, 3), check_steps(10, 10**20)
    ((10, 3), (10, 10))
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise InvalidInputError("n must be a non-negative integer, got %r" % (n,))
    if n > _MAX_STEPS:
        raise InvalidInputError("n = %d steps is beyond the int64 range of the kernels" % n)
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
        raise InvalidInputError("every must be a positive integer, got %r" % (every,))
    return int(n), int(min(every, max(n, 1)))


@overload
def bt_orbit(p: Any, q: Any, lam0: Any, mu: Any, n: int, *, branch: int = ..., every: int = ...,
             backend: str = ..., certified: Literal[False] = ..., tol: Any = ...) -> tuple[Any, Any]: ...


@overload
def bt_orbit(p: Any, q: Any, lam0: Any, mu: Any, n: int, *, branch: int = ..., every: int = ...,
             backend: str = ..., certified: Literal[True], tol: Any = ...) -> tuple[Any, Any, Any, Any]: ...


def bt_orbit(p: Any, q: Any, lam0: Any, mu: Any, n: int, *, branch: int = 1, every: int = 1,
             backend: str = "auto", certified: bool = False, tol: Any = None) -> tuple[Any, ...]:
    """``n`` Bäcklund steps from ``(p, q)``; returns the stored states.

    Parameters
    ----------
    p, q : float64 array_like of shape ``batch + (N,)`` (one state or an
        ensemble), or flat sequences of mpmath numbers (one state); with
        ``certified=True`` also exact decimal strings.
    lam0, mu : real (float64 ensembles: also arrays broadcastable to ``batch``).
    n : number of steps.
    every : store the states after ``0, every, 2 every, ...`` steps and always
        the last one (``every=n``: initial and final).
    branch : +1 or -1 (inverse map).
    backend : ``"auto"`` (fastest available) or float64 ``"numba"``,
        ``"python"``, ``"numpy"`` (general path only); mpmath ``"qd"``
        (quad-double, numba, if ``mp.prec`` fits: :func:`symbt.numeric.qd.qd_fits`),
        ``"flint"`` or ``"mpmath"``.
    certified, tol : see :func:`symbt.numeric.certified.certified_orbit`;
        returns ``(P, Q, P_rad, Q_rad)``.

    Returns
    -------
    float64: arrays ``P, Q`` of shape ``(rows,) + batch + (N,)`` with
    ``P[0] = p`` (``rows = n + 1`` for ``every=1``).  mpmath: two lists of
    ``rows`` states (each a list of mpf at the current ``mp.dps``).

    Notes
    -----
    Errors of any step propagate as the typed errors of :func:`bt_step`; for
    ensembles :class:`NoRealMapError` lists in ``where`` every state without a
    real map.  The map preserves the spectrum, so if the first step exists all
    later ones do too (up to round-off at the boundary of existence).

    Examples
    --------
    >>> import numpy as np
    >>> P, Q = bt_orbit(np.tile([-20.0, 10, 1], (4, 1)), np.tile([1.0, 0, 0.9], (4, 1)), 10.0, 5.0, 100, every=50)
    >>> P.shape                                      # (stored states, ensemble, sites)
    (3, 4, 3)
    """
    branch = check_branch(branch)
    n, every = check_steps(n, every)
    if certified:
        from .certified import certified_orbit

        if backend != "auto":
            raise InvalidInputError("certified orbits always use Arb ball arithmetic (backend=%r given)" % backend)
        return certified_orbit(p, q, lam0, mu, n, branch=branch, every=every, tol=tol)
    if tol is not None:
        raise InvalidInputError("tol is only used with certified=True")
    ctx = pick_context(p, q, lam0, mu)
    if ctx is FLOAT:
        if backend in ("flint", "qd", "mpmath"):
            raise InvalidInputError("backend %r needs mpmath inputs" % backend)
        return float_orbit(p, q, lam0, mu, n, branch=branch, every=every, backend=backend)
    from .mpfast import mp_orbit

    return mp_orbit(p, q, lam0, mu, n, branch=branch, every=every, backend=backend)
