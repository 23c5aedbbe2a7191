"""The two dispatchers: :func:`bt_step` and :func:`bt_orbit` validate the input and hand it to a backend.

The map preserves ``tr L(lam)`` (all ``H_k``) and, being a canonical
transformation that interpolates a Hamiltonian flow (paper Thm. 2, eq.
``eqdisc``), its orbits lie on invariant tori; the centre of mass
``Q = mean(q)`` drifts linearly.  Because each float64 step is accurate to a
few ulps, the orbit error grows only through the (linear, integrable)
dynamics (``~ eps n^2``; see ``tests/test_numeric_orbit.py``).

Backends (picked automatically, see :func:`bt_step` and :func:`bt_orbit`):

* float64, one state: the fused kernel (:mod:`symbt.numeric.float64.kernels`, numba if installed);
* float64 ensemble ``(M, N)``: the fused block kernel on all cores (numba) or
  the vectorised numpy path (:mod:`symbt.numeric.float64.orbit`); ``every=k`` stores every k-th
  state only;
* mpmath numbers: quad-doubles, python-flint's Arb at the caller's precision plus guard
  bits, else mpmath (:mod:`symbt.numeric.multiprec.choose`);
* ``certified=True``: rigorous enclosures by Arb ball arithmetic
  (:mod:`symbt.numeric.multiprec.certified`).

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

from collections.abc import Callable
from typing import Any, Literal, overload

import numpy as np

from .core.context import FLOAT, IV
from .core.errors import InvalidInputError
from .core.inputs import (
    as_state_pair,
    check_branch,
    check_steps,
    pick_context,
    prepare_spectral_pair,
    to_output,
    validate_float_pair,
)
from .core.step import _block_kernel_pays, _monodromy_may_overflow, mp_step, overflow_rows
from .float64.orbit import float_orbit

__all__ = ["bt_step", "bt_orbit", "STEP_BACKENDS"]

STEP_BACKENDS = ("auto", "numba", "python", "numpy", "flint", "qd", "mpmath")


def bt_step(p: Any, q: Any, lam0: Any, mu: Any, *, branch: int = 1, allow_complex: bool = False,
            backend: str = "auto") -> tuple[Any, Any]:
    """One Bäcklund step of the periodic Toda chain.

    Parameters
    ----------
    p, q : array_like, shape ``batch + (N,)``, N >= 2 -- or flat sequences of
        ``mpmath.mpf`` (a single state; ``mpmath.iv`` intervals also accepted).
    lam0, mu : real; arrays broadcastable to ``batch`` are accepted on the
        float path.  ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu``.
    branch : +1 or -1.  ``branch=-1`` is the inverse map of ``branch=+1``.
    allow_complex : return the complex continuation instead of raising
        :class:`NoRealMapError` (float path: complex128 arrays; mpmath: mpc
        values where needed).
    backend : ``"auto"`` (default: the fastest available), or force one:
        float64 ``"numba"`` (fused kernel; for a batch the block kernel),
        ``"python"`` (fused kernel in plain Python, one state; a batch takes
        the numpy route) or ``"numpy"``; mpmath ``"qd"`` (quad-double, numba;
        ``mp.prec <= 191``), ``"flint"`` (Arb, python-flint) or ``"mpmath"``.

    Returns
    -------
    (p_new, q_new) : float64 arrays of the input shape, or lists of mpf at the
        current ``mp.dps`` (computed with a few guard digits).

    Raises
    ------
    InvalidInputError, NoRealMapError, NumericRangeError
    MissingDependencyError
        for a forced backend that is not installed.

    Notes
    -----
    ``mu == 0`` returns copies of the input.  The algorithm and its stability
    are described in the module docstring of :mod:`symbt.numeric.core.step`.

    Examples
    --------
    >>> from symbt.numeric import bt_step
    >>> import mpmath
    >>> with mpmath.workdps(30):
    ...     pt, qt = bt_step([mpmath.mpf(-20), 10, 1], [1, 0, mpmath.mpf('0.9')], 10, 5)
    ...     print(mpmath.nstr(qt[0], 15))
    -0.0861422421882023
    """
    branch = check_branch(branch)
    if backend not in STEP_BACKENDS:
        raise InvalidInputError("backend must be one of %s, got %r" % (STEP_BACKENDS, backend))
    ctx = pick_context(p, q, lam0, mu)
    if ctx is FLOAT:
        if backend in ("flint", "qd", "mpmath"):
            raise InvalidInputError("backend %r needs mpmath inputs" % backend)
        pa, qa, shape = validate_float_pair(p, q)
        lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
        N = pa.shape[-1]
        if np.ndim(mu) == 0 and mu == 0:
            return pa.reshape(shape + (N,)).copy(), qa.reshape(shape + (N,)).copy()
        if shape == () and backend != "numpy" and not (backend == "auto" and _monodromy_may_overflow(pa, lam0, mu)):
            from .float64.orbit import kernel_step

            out = kernel_step(pa[0], qa[0], float(lam0), float(mu), branch, backend)
            if out is not None:
                return out
        if shape != () and backend in ("auto", "numba"):
            from .float64.jit import numba_available

            if numba_available() and (backend == "numba" or _block_kernel_pays(pa, lam0, mu)):
                # each member by its single-state route: the block kernel (bit-identical to the single-state
                # kernel), and the numpy route for exactly the members it hands back
                from .float64.orbit import kernel_batch_step

                skip = overflow_rows(N, lam0, mu, pa.shape[0]) if backend == "auto" else None
                outp, outq = kernel_batch_step(pa, qa, lam0, mu, branch, allow_complex, shape, skip)
                return outp.reshape(shape + (N,)), outq.reshape(shape + (N,))
        from .float64.rows import float_rows_step

        outp, outq = float_rows_step(pa, qa, lam0, mu, branch, allow_complex, shape)
        return outp.reshape(shape + (N,)), outq.reshape(shape + (N,))
    if backend in ("numba", "python", "numpy"):
        raise InvalidInputError("backend %r needs float64 inputs" % backend)
    ctx, P, Q, shape = as_state_pair(p, q, lam0, mu)
    lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
    if mu == 0:
        return to_output(ctx, P, ()), to_output(ctx, Q, ())
    if ctx is not IV:
        from .multiprec.choose import mp_backend

        fast: Callable[..., tuple[list[Any], list[Any]]] | None = mp_backend(backend)
        if fast is not None:
            return fast(P, Q, lam0, mu, branch, allow_complex)
    return mp_step(ctx, P, Q, lam0, mu, branch, allow_complex)


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
        (quad-double, numba, if ``mp.prec`` fits: :func:`symbt.numeric.multiprec.qd.qd_fits`),
        ``"flint"`` or ``"mpmath"``.
    certified, tol : see :func:`symbt.numeric.multiprec.certified.certified_orbit`;
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
        from .multiprec.certified import certified_orbit

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
    from .multiprec.choose import mp_orbit

    return mp_orbit(p, q, lam0, mu, n, branch=branch, every=every, backend=backend)
