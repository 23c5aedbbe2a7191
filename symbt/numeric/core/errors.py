"""Typed errors of :mod:`symbt.numeric`.

All are subclasses of the matching builtin so that generic ``except ValueError``
code keeps working, but callers can tell *why* a step was refused:

* :class:`InvalidInputError` -- the input is malformed (non-finite values,
  mismatched shapes, ``N < 2``, ``branch`` not in ``{+1, -1}``, ...).
* :class:`NoRealMapError` -- the input is fine but the real Bäcklund map does
  not exist there: ``|tr L(lam_i)| <= 2`` at ``lam1 = lam0 + mu`` or
  ``lam2 = lam0 - mu`` (a spectral parameter inside a band), or some
  ``Etilde_j = E_j - x_j <= 0`` (``lam1`` and ``lam2`` lie in different
  spectral gaps).  ``allow_complex=True`` returns the complex continuation
  instead.
* :class:`NumericRangeError` -- the float64 formulation cannot represent the
  problem (``|q_{j+1} - q_j|`` beyond the exponent range, or an intermediate
  that is not finite); use mpmath inputs.
* :class:`QuadratureError` -- the quadrature for the flow coefficients did not
  reach its tolerance.
* :class:`MissingDependencyError` -- an optional backend (numba, python-flint,
  dask) was requested but is not installed; an :class:`ImportError`.

>>> from symbt.numeric import NoRealMapError
>>> err = NoRealMapError("no real map", condition="trace", where=[(1,)])
>>> isinstance(err, ValueError), err.condition, err.where
(True, 'trace', ((1,),))
"""

from __future__ import annotations

import importlib
import importlib.util
from collections.abc import Iterable

__all__ = ["InvalidInputError", "NoRealMapError", "NumericRangeError", "QuadratureError",
           "MissingDependencyError", "importable"]


class InvalidInputError(ValueError):
    """Malformed input: non-finite values, bad shapes, N < 2, bad branch.

    >>> issubclass(InvalidInputError, ValueError)
    True
    """


class NoRealMapError(ValueError):
    """The real Bäcklund map does not exist at this (p, q, lam0, mu, branch).

    Attributes
    ----------
    condition : str
        ``"trace"`` (``|tr L(lam_i)| <= 2``) or ``"positivity"``
        (some ``Etilde_j <= 0``, i.e. ``lam1``, ``lam2`` in different gaps).
    where : tuple
        Offending batch indices (empty for a single state): every member
        without a real map, for :func:`~symbt.numeric.bt_step` and ensemble
        orbits alike.

    >>> NoRealMapError("no map", condition="trace").where
    ()
    """

    def __init__(self, message: str, condition: str = "", where: Iterable[tuple[int, ...]] = ()) -> None:
        super().__init__(message)
        self.condition = condition
        self.where = tuple(where)


class NumericRangeError(OverflowError):
    """The problem is outside the range of the float64 formulation (or not certifiable).

    >>> issubclass(NumericRangeError, OverflowError)
    True
    """


class QuadratureError(ArithmeticError):
    """Adaptive quadrature failed to meet its error estimate.

    >>> issubclass(QuadratureError, ArithmeticError)
    True
    """


class MissingDependencyError(ImportError):
    """An optional dependency (numba, python-flint, dask) is needed for the requested feature.

    >>> issubclass(MissingDependencyError, ImportError)
    True
    """


_IMPORTABLE: dict[str, bool] = {}


def importable(module: str) -> bool:
    """True if the optional dependency ``module`` is installed and imports (tried once, then cached).

    A broken installation counts as missing, so that a feature falls back or says which extra to
    install instead of failing deep inside a computation.

    >>> importable("math"), importable("no_such_module_symbt")
    (True, False)
    """
    if module not in _IMPORTABLE:
        ok = importlib.util.find_spec(module) is not None
        if ok:
            try:
                importlib.import_module(module)
            except Exception:  # pragma: no cover - broken installation
                ok = False
        _IMPORTABLE[module] = ok
    return _IMPORTABLE[module]
