"""One validation of the input, shared by every backend: :func:`prepare` returns a frozen :class:`Problem`.

The dispatchers (:func:`~symbt.numeric.bt_step`, :func:`~symbt.numeric.bt_orbit`) call :func:`prepare`
once; the backends of :mod:`symbt.numeric.backends` take the record and validate nothing again.

Example
-------
>>> from symbt.numeric.core.problem import prepare
>>> pr = prepare([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, n=3)
>>> pr.arithmetic, pr.shape, pr.p.shape, pr.n, pr.every
('float64', (), (1, 3), 3, 1)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal, TypeAlias

import numpy as np
import numpy.typing as npt

from .context import FLOAT, IV, Context, Value
from .inputs import (
    ParamLike,
    StateLike,
    as_state_pair,
    check_branch,
    check_steps,
    pick_context,
    prepare_spectral_pair,
    validate_float_pair,
)

__all__ = ["Problem", "prepare", "prepare_checked", "Arithmetic", "Float64Backend", "CertifiedMethod", "StateLike",
           "ParamLike", "FloatArray", "StateOut", "OrbitOut"]

#: a validated float64 array
FloatArray = npt.NDArray[np.float64]
#: a state (or N per-site values such as the invariants) as the public functions return it: a float64
#: array of shape ``batch + (N,)`` for float64 input, a list of N mpmath numbers for mpmath input.  Which
#: one follows from the input's kind, which no signature can say (mpmath numbers are ``Any`` to a type
#: checker), so this is ``Any`` -- a union would make every caller narrow what its own input decides
StateOut: TypeAlias = Any
#: the stored states of an orbit, likewise: a float64 array ``(rows,) + batch + (N,)`` or a list of
#: ``rows`` lists of N mpmath numbers
OrbitOut: TypeAlias = Any

#: what a backend computes in: float64 arrays, or mpmath numbers (intervals included)
Arithmetic = Literal["float64", "mpmath"]
#: the ``backend=`` values for float64 input (the float64 rows of :data:`~symbt.numeric.BackendName`, which is
#: built from it): ``backend=`` of :func:`~symbt.numeric.dask_orbit` and of the float64 orbits
Float64Backend = Literal["auto", "numba", "python", "numpy"]
#: ``method=`` of :func:`~symbt.numeric.certified_orbit`
CertifiedMethod = Literal["auto", "lohner", "ball"]


@dataclass(frozen=True)
class Problem:
    """A validated input: ``p, q`` as float64 arrays of shape ``(B, N)`` (``shape`` the batch shape)
    or as lists of N mpmath numbers (``shape == ()``); ``lam0, mu`` as context values (float64:
    scalars or arrays over the ``B`` states); ``branch`` in {+1, -1}; ``n`` steps storing every
    ``every``-th state."""

    ctx: Context
    # FloatArray (B, N) or list[MPValue] (N): ``arithmetic`` says which, and each backend takes one kind,
    # so a union here would only make every backend narrow what its table entry already guarantees
    p: Any
    q: Any
    shape: tuple[int, ...]
    lam0: Value
    mu: Value
    branch: int
    n: int = 1
    every: int = 1

    @property
    def arithmetic(self) -> Arithmetic:
        return "float64" if self.ctx is FLOAT else "mpmath"

    @property
    def interval(self) -> bool:
        """True for ``mpmath.iv`` intervals (only the plain mpmath backend computes on them)."""
        return self.ctx is IV


def prepare(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, *, branch: int = 1, n: int = 1,
            every: int = 1) -> Problem:
    """Validate the input of a step or an orbit once (the typed errors of :mod:`symbt.numeric.core.errors`).

    >>> prepare([1.0, 2.0], [0.0, 0.0], 1.0, 0.5, branch=2)
    Traceback (most recent call last):
    ...
    symbt.numeric.core.errors.InvalidInputError: branch must be +1 or -1, got 2
    """
    branch = check_branch(branch)
    n, every = check_steps(n, every)
    return prepare_checked(p, q, lam0, mu, branch, n, every)


def prepare_checked(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, branch: int, n: int,
                    every: int) -> Problem:
    """:func:`prepare` for a caller that has checked ``branch`` (:func:`check_branch`) and ``n, every``
    (:func:`check_steps`) itself; validates the states and the spectral parameters.

    >>> prepare_checked([1.0, 2.0], [0.0, 0.0], 1.0, 0.5, 1, 2, 1).n
    2
    """
    ctx = pick_context(p, q, lam0, mu)
    if ctx is FLOAT:
        pa, qa, shape = validate_float_pair(p, q)
        lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
        return _record(ctx, pa, qa, shape, lam0, mu, branch, n, every)
    ctx, P, Q, shape = as_state_pair(p, q, lam0, mu)
    lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
    return _record(ctx, P, Q, shape, lam0, mu, branch, n, every)


def _record(ctx: Context, p: object, q: object, shape: tuple[int, ...], lam0: Value, mu: Value, branch: int, n: int,
            every: int) -> Problem:
    """``Problem(...)`` without the frozen dataclass's nine ``object.__setattr__`` calls: the record is
    built on every call of the dispatchers, where that costs more than a short orbit's own overhead
    (1.5 us against 0.4 us); the result is the same frozen, comparable record."""
    pr = object.__new__(Problem)
    pr.__dict__.update(ctx=ctx, p=p, q=q, shape=shape, lam0=lam0, mu=mu, branch=branch, n=n, every=every)
    return pr
