"""The backends as data: one table that :func:`~symbt.numeric.bt_step` and :func:`~symbt.numeric.bt_orbit` look up.

Each :class:`Backend` says what input it accepts (float64 arrays or mpmath numbers), whether its optional
extra is installed (``available``), whether its arithmetic carries a precision for a number of steps
(``fits``), how it runs a step and an orbit of a validated :class:`~symbt.numeric.core.problem.Problem`, and
which backend takes over (``fallback``) when it is missing -- or, under ``"auto"``, when it gives a
problem back (the quad-double range, or a state without a real map when ``allow_complex`` asks for the
complex continuation, which quad-doubles do not carry).

=========  ========  ====================================  ==========
name       accepts   extra                                 fallback
=========  ========  ====================================  ==========
``numba``  float64   numba (the fused kernels, compiled)   --
``python`` float64   --  (the same kernels, plain Python)  --
``numpy``  float64   --  (the vectorised general path)     --
``qd``     mpmath    numba (quad-double, 209 bits)         ``flint``
``flint``  mpmath    python-flint (Arb midpoints)          ``mpmath``
``mpmath`` mpmath    --                                    --
=========  ========  ====================================  ==========

``"auto"`` on float64 input lets the float64 drivers choose per state (fused kernel, block kernel or
numpy, :mod:`symbt.numeric.float64.step`); on mpmath input it takes the first backend of the chain
``qd -> flint -> mpmath`` that is available, fits ``mp.prec`` and the number of steps, and is ready
(the quad-double orbit compiled once: :func:`~symbt.numeric.multiprec.qd.qd_ready`).

Example
-------
>>> import mpmath
>>> from symbt.numeric.backends import BACKENDS, pick
>>> [name for name, b in BACKENDS.items() if b.accepts == "mpmath"]
['qd', 'flint', 'mpmath']
>>> pick("mpmath", "mpmath").name
'mpmath'
>>> with mpmath.workdps(200):
...     pick("auto", "mpmath", n=10).name in ("flint", "mpmath")       # beyond the quad-double's 209 bits
True
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from typing import Literal, get_args

import mpmath

from .core.errors import InvalidInputError, MissingDependencyError, NoRealMapError, NumericRangeError
from .core.problem import Arithmetic, Float64Backend, OrbitOut, Problem, StateOut
from .float64.jit import numba_available
from .float64.orbit import prepared_float_orbit
from .float64.step import float_step
from .multiprec import runners
from .multiprec.qd import qd_available, qd_fits, qd_need, qd_ready

__all__ = ["Backend", "BackendName", "BACKENDS", "FLOAT_AUTO", "check_name", "pick", "run_step", "run_orbit"]

#: the ``backend=`` values of :func:`~symbt.numeric.bt_step` and :func:`~symbt.numeric.bt_orbit`
BackendName = Literal[Float64Backend, "qd", "flint", "mpmath"]


def _always(*_: object) -> bool:
    return True


@dataclass(frozen=True)
class Backend:
    """One row of :data:`BACKENDS` (see the module docstring)."""

    name: BackendName
    accepts: Arithmetic
    step: Callable[[Problem, bool], tuple[StateOut, StateOut]]
    orbit: Callable[[Problem], tuple[OrbitOut, OrbitOut]]
    available: Callable[[], bool] = _always
    fits: Callable[[int, int], bool] = _always          # (mp.prec, steps)
    ready: Callable[[], bool] = _always                 # "auto" takes it only when ready
    fallback: BackendName | None = None
    gives_back: tuple[type[Exception], ...] = field(default=())   # errors after which "auto" falls back
    real_only: bool = False                             # no complex continuation: allow_complex falls back
    missing: str = ""                                   # the message when forced without its extra
    refusal: Callable[[int, int], str] | None = None    # the message when forced where it does not fit


def _float64(name: BackendName) -> Backend:
    return Backend(name, "float64", partial(float_step, backend=name), partial(prepared_float_orbit, backend=name),
                   available=numba_available if name == "numba" else _always)


def _qd_refusal(prec: int, n: int) -> str:
    return ("the qd backend carries 209 bits; mp.prec = %d with %d steps needs %d: use backend='flint' (or 'auto')"
            % (prec, n, qd_need(prec, n)))


BACKENDS: dict[str, Backend] = {
    "numba": _float64("numba"),
    "python": _float64("python"),
    "numpy": _float64("numpy"),
    "qd": Backend("qd", "mpmath", runners.qd_step, runners.qd_orbit, available=qd_available, fits=qd_fits,
                  ready=qd_ready, fallback="flint", gives_back=(NumericRangeError,), real_only=True,
                  missing="the qd backend needs numba: pip install 'symbt[fast]' (or unset SYMBT_NO_NUMBA)",
                  refusal=_qd_refusal),
    "flint": Backend("flint", "mpmath", runners.flint_step, runners.flint_orbit, available=runners.flint_available,
                     fallback="mpmath",
                     missing="the flint backend needs python-flint: pip install 'symbt[certified]'"),
    "mpmath": Backend("mpmath", "mpmath", runners.mpmath_step, runners.mpmath_orbit),
}
#: ``backend="auto"`` on float64 input: the float64 drivers choose per state
FLOAT_AUTO = _float64("auto")
_NAMES: tuple[str, ...] = get_args(BackendName)
_FIRST = {"mpmath": "qd"}


def _present(name: str) -> Backend:
    """The backend ``name``, or the first of its fallbacks whose extra is installed."""
    b = BACKENDS[name]
    while not b.available() and b.fallback is not None:
        b = BACKENDS[b.fallback]
    return b


def check_name(backend: str, arithmetic: Arithmetic) -> None:
    """:class:`InvalidInputError` unless ``backend`` is a :data:`BackendName` that takes ``arithmetic`` input.

    >>> check_name("qd", "float64")
    Traceback (most recent call last):
    ...
    symbt.numeric.core.errors.InvalidInputError: backend 'qd' needs mpmath inputs
    """
    if backend not in _NAMES:
        raise InvalidInputError("backend must be one of %s, got %r" % (_NAMES, backend))
    if backend != "auto" and BACKENDS[backend].accepts != arithmetic:
        raise InvalidInputError("backend %r needs %s inputs" % (backend, BACKENDS[backend].accepts))


def pick(backend: str, arithmetic: Arithmetic, n: int = 1, *, interval: bool = False) -> Backend:
    """The backend that runs ``n`` steps of ``arithmetic`` input at the current ``mp.prec``.

    A name outside :data:`BackendName`, or one that needs the other arithmetic, raises
    :class:`InvalidInputError`; a forced mpmath backend that is not installed
    :class:`MissingDependencyError`, one whose arithmetic cannot carry the precision
    :class:`InvalidInputError`.  Intervals (``interval=True``) always take the plain mpmath path.

    >>> pick("numpy", "mpmath")
    Traceback (most recent call last):
    ...
    symbt.numeric.core.errors.InvalidInputError: backend 'numpy' needs float64 inputs
    """
    check_name(backend, arithmetic)
    if arithmetic == "float64":
        return FLOAT_AUTO if backend == "auto" else BACKENDS[backend]
    if interval:
        return BACKENDS["mpmath"]
    prec = mpmath.mp.prec
    if backend == "auto":
        b = BACKENDS[_FIRST[arithmetic]]
        while not (b.available() and b.fits(prec, n) and b.ready()):
            assert b.fallback is not None
            b = BACKENDS[b.fallback]
        return b
    b = BACKENDS[backend]
    if not b.available():
        raise MissingDependencyError(b.missing)
    if not b.fits(prec, n):
        raise InvalidInputError(b.refusal(prec, n) if b.refusal else "backend %r does not fit" % backend)
    return b


def _next(b: Backend, exc: Exception, forced: bool, allow_complex: bool) -> Backend:
    """The backend that takes over after ``b`` raised ``exc``; re-raises when none does."""
    hand_back = (isinstance(exc, NoRealMapError) and allow_complex and b.real_only) or \
        (not forced and isinstance(exc, b.gives_back))
    if not hand_back or b.fallback is None:
        raise exc
    return _present(b.fallback)


def run_step(b: Backend, pr: Problem, allow_complex: bool, forced: bool) -> tuple[StateOut, StateOut]:
    """One step of ``pr`` on ``b``, continued on its fallbacks when it gives the problem back."""
    while True:
        try:
            return b.step(pr, allow_complex)
        except (NoRealMapError, NumericRangeError) as exc:
            b = _next(b, exc, forced, allow_complex)


def run_orbit(b: Backend, pr: Problem, forced: bool) -> tuple[OrbitOut, OrbitOut]:
    """The orbit of ``pr`` on ``b``, continued on its fallbacks when it gives the problem back."""
    while True:
        try:
            return b.orbit(pr)
        except (NoRealMapError, NumericRangeError) as exc:
            b = _next(b, exc, forced, False)
