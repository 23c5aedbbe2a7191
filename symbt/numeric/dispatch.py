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
  bits, else mpmath (:mod:`symbt.numeric.backends`, :mod:`symbt.numeric.multiprec.runners`);
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

from typing import Literal, overload

from .backends import BackendName, check_name, pick, run_orbit, run_step
from .core.context import MPValue
from .core.errors import InvalidInputError
from .core.inputs import check_branch, check_steps, mp_output
from .core.problem import OrbitOut, ParamLike, StateLike, StateOut, prepare, prepare_checked
from .float64.kernels import stored_steps
from .multiprec.runners import MPOrbit

__all__ = ["bt_step", "bt_orbit"]


def bt_step(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, *, branch: int = 1,
            allow_complex: bool = False, backend: BackendName = "auto") -> tuple[StateOut, StateOut]:
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
    pr = prepare(p, q, lam0, mu, branch=branch)
    check_name(backend, pr.arithmetic)
    if pr.arithmetic == "mpmath" and pr.mu == 0:
        return mp_output(pr.p), mp_output(pr.q)
    b = pick(backend, pr.arithmetic, 1, interval=pr.interval)
    return run_step(b, pr, allow_complex, forced=backend != "auto")

@overload
def bt_orbit(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, n: int, *, branch: int = ...,
             every: int = ..., backend: BackendName = ..., certified: Literal[False] = ...,
             tol: None = ..., q_low: Literal[False] = ...) -> tuple[OrbitOut, OrbitOut]: ...


@overload
def bt_orbit(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, n: int, *, branch: int = ...,
             every: int = ..., backend: BackendName = ..., certified: Literal[False] = ...,
             tol: None = ..., q_low: Literal[True]) -> tuple[OrbitOut, OrbitOut, OrbitOut]: ...


@overload
def bt_orbit(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, n: int, *, branch: int = ...,
             every: int = ..., backend: BackendName = ..., certified: Literal[True],
             tol: float | MPValue | None = ..., q_low: Literal[False] = ...
             ) -> tuple[MPOrbit, MPOrbit, MPOrbit, MPOrbit]: ...


def bt_orbit(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, n: int, *, branch: int = 1, every: int = 1,
             backend: BackendName = "auto", certified: bool = False,
             tol: float | MPValue | None = None, q_low: bool = False) -> tuple[OrbitOut, ...]:
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
    q_low : float64 only: also return the low parts of the stored positions, ``(P, Q, Q_low)``;
        ``Q`` is the same as without it (bit for bit) and ``Q + Q_low`` each carried position to
        about ``2**-104`` relative, so ``q_{j+1} - q_j`` is free of the rounding at ``ulp(|q|)``
        that grows with the centre of mass (docs/numeric.md, "Long orbits").

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
    >>> P, Q, Qlo = bt_orbit([-20.0, 10, 1], [1.0, 0, 0.9], 10.0, 5.0, 1000, every=1000, q_low=True)
    >>> dq = (Q[-1, 1:] - Q[-1, :-1]) + (Qlo[-1, 1:] - Qlo[-1, :-1])     # differences, not rounded at |q|
    >>> bool(abs(Q[-1, 0]) > 100), bool(np.all(np.abs(Qlo) <= np.spacing(np.abs(Q)) / 2))
    (True, True)
    """
    branch = check_branch(branch)
    n, every = check_steps(n, every)
    if certified and q_low:
        raise InvalidInputError("q_low applies to float64 orbits, not to certified ones")
    if certified:
        from .multiprec.certified import certified_orbit

        if backend != "auto":
            raise InvalidInputError("certified orbits always use Arb ball arithmetic (backend=%r given)" % backend)
        return certified_orbit(p, q, lam0, mu, n, branch=branch, every=every, tol=tol)
    if tol is not None:
        raise InvalidInputError("tol is only used with certified=True")
    pr = prepare_checked(p, q, lam0, mu, branch, n, every)
    b = pick(backend, pr.arithmetic, pr.n, interval=pr.interval)
    if q_low:
        if pr.arithmetic != "float64":
            raise InvalidInputError("q_low applies to float64 orbits (mpmath positions carry their own precision)")
        from .float64.orbit import float_orbit_low

        return float_orbit_low(pr, b.name)
    if pr.arithmetic == "mpmath" and (pr.mu == 0 or pr.n == 0):
        rows = len(stored_steps(pr.n, pr.every))
        return [mp_output(pr.p)] * rows, [mp_output(pr.q)] * rows
    return run_orbit(b, pr, forced=backend != "auto")
