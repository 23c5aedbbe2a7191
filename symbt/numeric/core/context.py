"""Arithmetic contexts: the step is written once against this small interface.

A *context* plays the role of ``mpmath.mp``: it supplies elementary functions
and the few decisions the algorithm needs.  A "value" is whatever the context
computes with -- a 1-D numpy array over the batch (``FloatContext``), or an
mpmath scalar (``MPContext``, ``IVContext``).  Ordinary ``+ - * /`` are used
directly on values; everything else goes through the context:

=====================  ====================================================
``exp log log1p sqrt``  elementary functions (principal branches if complex)
``div(a, b)``           ``a / b``; division by an exact zero gives an (unsigned,
                        projective) infinity as in IEEE arithmetic, so an
                        eigenvector slope may pass through infinity
``ldexp(x, e)``         ``x * 2**e`` exactly
``acosh_half_abs``      ``arccosh(|t 2**e| / 2)`` for a scaled trace
``re_dot(a, b)``        ``Re(a * conj(b))`` (a real number/array)
``positive(x)``         "certainly ``x > 0``" (bool or bool array)
``any / all / neg``     reductions and negation of such conditions
``select(c, f, g)``     ``f()`` where ``c`` else ``g()`` (lazy when scalar)
``renormalize``         rescale a 2x2 matrix by a power of two (ball/float)
=====================  ====================================================

Decisions that only affect *accuracy* (which of two algebraically equal
formulas to use, transport direction) may be taken on midpoints; decisions
that affect *existence* (``|tr| > 2``, ``Etilde > 0``) use ``positive`` which
for an interval context means "the whole interval is positive".  That is all
a ball-arithmetic backend (python-flint ``arb``, :mod:`symbt.numeric.multiprec.arb`)
provides as well.

Example
-------
>>> from symbt.numeric.core.context import MPContext
>>> ctx = MPContext()
>>> ctx.div(1, 0), ctx.positive(ctx.sqrt(4) - 1)
(mpf('+inf'), True)
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any, Protocol, TypeAlias

import mpmath
import numpy as np
import numpy.typing as npt

__all__ = ["Context", "FloatContext", "MPContext", "IVContext", "FLOAT", "COMPLEX", "MP", "IV", "iv_prec",
           "Value", "Cond", "Exponent", "FloatValue", "FloatParam", "MPValue"]


#: a context value: a float64/complex128 array over the batch or a Python float (:class:`FloatContext`),
#: an mpmath ``mpf``/``mpc`` or ``iv`` interval (:class:`MPContext`, :class:`IVContext`), an Arb ball
#: (:mod:`symbt.numeric.multiprec.arb`).  The context-generic step mixes these with Python floats and ints;
#: they share no static type (mpmath ships no type information), so to a type checker this is ``Any`` --
#: the one deliberate ``Any`` of the numeric core; the name says what a parameter holds.
Value: TypeAlias = Any
#: a float-context value: a 1-D float64 or complex128 array over the flattened batch
FloatValue: TypeAlias = npt.NDArray[np.inexact]
#: a validated real parameter of the float path (``lam0``, ``mu``): a Python float, or a float64 array
#: over the flattened batch
FloatParam: TypeAlias = float | npt.NDArray[np.float64]
#: an mpmath value: ``mpf``/``mpc``, or an ``mpmath.iv`` interval (mpmath ships no type information, so
#: to a type checker this is ``Any``; the name says what is meant)
MPValue: TypeAlias = mpmath.mpf | mpmath.mpc
#: an existence/accuracy condition: a bool (scalar contexts) or a bool array over the batch (float)
Cond: TypeAlias = bool | npt.NDArray[np.bool_]
#: a power-of-two scale exponent: an int (scalar contexts) or an integer array over the batch (float)
Exponent: TypeAlias = int | npt.NDArray[np.integer]


class Context(Protocol):
    """The interface :func:`~symbt.numeric.core.step.step_core` is written against (see module docstring).

    Each context computes with its own kind of ``Value``: :class:`FloatContext` with ``FloatValue``,
    :class:`MPContext` with ``MPValue``, the Arb contexts with balls.

    >>> isinstance(FLOAT.is_exact_scale, bool) and callable(MPContext.div)
    True
    """

    is_exact_scale: bool

    def exp(self, x: Value) -> Value: ...
    def log(self, x: Value) -> Value: ...
    def log1p(self, x: Value) -> Value: ...
    def sqrt(self, x: Value) -> Value: ...
    def div(self, a: Value, b: Value) -> Value: ...
    def ldexp(self, x: Value, e: Exponent) -> Value: ...
    def acosh_half_abs(self, t: Value, g: Value, e: Exponent) -> Value: ...
    def re_dot(self, a: Value, b: Value) -> Value: ...
    def positive(self, x: Value) -> Cond: ...
    def all_positive(self, x: Value) -> bool: ...
    def align(self, g: Value, ref: Value) -> tuple[Value, Cond]: ...
    def half_plane(self, a: Value, g: Value) -> Cond: ...
    def any(self, c: Cond) -> bool: ...
    def all(self, c: Cond) -> bool: ...
    def neg(self, c: Cond) -> Cond: ...
    def select(self, c: Cond, f: Callable[[], Value], g: Callable[[], Value]) -> Value: ...
    def out_of_range(self, *xs: Value) -> Cond: ...
    def renormalize(self, A: Value, B: Value, C: Value, D: Value,
                    e: Exponent) -> tuple[Value, Value, Value, Value, Exponent]: ...
    def subset(self, x: Value, mask: Cond) -> Value: ...
    def merge(self, full: Value, mask: Cond, part: Value) -> Value: ...
    def isfinite_all(self, xs: Sequence[Value]) -> bool: ...


_LN2 = math.log(2.0)


class FloatContext:
    """numpy float64 (or complex128) arrays over a flattened batch axis.

    >>> FLOAT.all_positive(np.array([1.0, 2.0])), COMPLEX.is_complex
    (True, True)
    """

    is_exact_scale = False

    def __init__(self, dtype: npt.DTypeLike = np.float64) -> None:
        self.dtype = np.dtype(dtype)
        # this context's own switch between its real and complex forms (no algorithm asks a context for it)
        self.is_complex = self.dtype.kind == "c"

    # elementary functions -------------------------------------------------
    exp = staticmethod(np.exp)
    log = staticmethod(np.log)
    sqrt = staticmethod(np.sqrt)
    div = staticmethod(operator.truediv)   # IEEE: x / 0 = +-inf (callers silence the warning)

    def log1p(self, x: FloatValue) -> FloatValue:
        """``log(1 + x)``, accurate for small ``|x|`` -- complex ``x`` too, where numpy's ``log1p`` is
        ``log(1 + x)`` (a relative error of 6e-9 at ``|x| = 1e-8``): for ``|x| < 1/2``, ``Re = log1p(2 Re x +
        |x|^2) / 2`` and ``Im = atan2(Im x, 1 + Re x)``."""
        if not self.is_complex:
            return np.log1p(x)
        z = np.asarray(x)
        small = np.abs(z) < 0.5
        if not np.any(small):
            return np.log1p(z)
        a, b = z.real, z.imag
        near = np.empty(z.shape, dtype=z.dtype)
        near.real, near.imag = 0.5 * np.log1p(a * (2.0 + a) + b * b), np.arctan2(b, 1.0 + a)
        return np.where(small, near, np.log1p(z))

    @staticmethod
    def ldexp(x: FloatValue | float, e: Exponent) -> FloatValue | float:
        if isinstance(e, (int, np.integer)) and e == 0:
            return x
        if np.iscomplexobj(x):              # numpy's ldexp takes real arrays: each part scaled, exactly
            z = np.asarray(x)
            out = np.empty(np.broadcast_shapes(z.shape, np.shape(e)), dtype=z.dtype)
            out.real, out.imag = np.ldexp(z.real, e), np.ldexp(z.imag, e)
            return out
        return np.ldexp(x, e)

    def acosh_half_abs(self, t: FloatValue, g: FloatValue, e: Exponent) -> FloatValue:
        """``arccosh(|t| 2**e / 2)`` given ``g = sqrt(t**2 - 4**(1-e))``.

        For ``e == 0`` this uses ``log1p(h - 1 + sqrt((h-1)(h+1)))`` which is
        accurate near the band edge ``h -> 1``; for scaled (huge) traces it
        uses ``e ln 2 + log((|t| + g) / 2)``.
        """
        at = np.abs(t)
        h = 0.5 * at
        hm1 = h - 1.0
        # for e == 0, g / 2 = sqrt((h - 1)(h + 1)) exactly in exact arithmetic
        small = np.log1p(hm1 + 0.5 * np.abs(g))
        big = np.asarray(e, dtype=float) * _LN2 + np.log(0.5 * (at + np.abs(g)))
        return np.where(np.asarray(e) == 0, small, big)

    def re_dot(self, a: FloatValue, b: FloatValue) -> FloatValue:
        if self.is_complex:
            return (a * np.conj(b)).real
        return a * b

    def positive(self, x: FloatValue) -> Cond:
        if self.is_complex:                 # certainly > 0: real and positive (as MP and ACB decide it)
            return (np.imag(x) == 0) & (np.real(x) > 0)
        return x > 0

    def all_positive(self, x: FloatValue) -> bool:
        """``all(x > 0)`` as a bool (a single reduction; NaN counts as failure)."""
        if self.is_complex:
            return bool(np.all(self.positive(x)))
        return bool(np.min(x) > 0)

    def align(self, g: FloatValue, ref: FloatValue) -> tuple[FloatValue, Cond]:
        """``+g`` or ``-g``, whichever satisfies ``Re(ref * conj(+-g)) >= 0``.

        Returns ``(aligned_g, is_plus)``.
        """
        if self.is_complex:
            plus = (ref * np.conj(g)).real >= 0
            return np.where(plus, g, -g), plus
        return np.copysign(g, ref), ref >= 0

    def half_plane(self, a: FloatValue, g: FloatValue) -> Cond:
        """``Re(a * conj(g)) >= 0`` for a principal square root ``g`` (real: ``a >= 0``)."""
        if self.is_complex:
            return (a * np.conj(g)).real >= 0
        return a >= 0

    @staticmethod
    def any(c: Cond) -> bool:
        return bool(np.any(c))

    @staticmethod
    def all(c: Cond) -> bool:
        return bool(np.all(c))

    @staticmethod
    def neg(c: Cond) -> Cond:
        return np.logical_not(c)

    @staticmethod
    def select(c: Cond, f: Callable[[], FloatValue], g: Callable[[], FloatValue]) -> FloatValue:
        if c is True or (isinstance(c, np.ndarray) and c.all()):
            return f()
        if c is False or (isinstance(c, np.ndarray) and not c.any()):
            return g()
        return np.where(c, f(), g())

    # scaling support for the monodromy product ----------------------------
    def out_of_range(self, *xs: FloatValue) -> Cond:
        """Mask of batch rows whose entries are non-finite or too large/small.

        Returns ``False`` (cheaply, by reductions only) when all is fine.
        """
        arrays = [x for x in xs if np.ndim(x) and np.size(x)]
        if not arrays:
            return False
        big = max(float(np.max(np.abs(x) if self.is_complex else np.maximum(x.max(), -x.min())))
                  for x in arrays)
        if big < 2.0**500 and np.isfinite(big):
            # det M = 1 forces max|entry| >~ 1 per row, so no per-row test needed
            return False
        mx: FloatValue | None = None
        for x in arrays:
            ax = np.abs(x)
            ax = np.where(np.isfinite(ax), ax, np.inf)
            mx = ax if mx is None else np.maximum(mx, ax)
        assert mx is not None           # arrays is not empty
        shape = np.broadcast_shapes(*(np.shape(x) for x in arrays))
        return np.broadcast_to((mx > 2.0**500) | (mx < 2.0**-500) | np.isnan(mx), shape)

    @staticmethod
    def renormalize(A: FloatValue, B: FloatValue | float, C: FloatValue, D: FloatValue | float,
                    e: Exponent) -> tuple[FloatValue, FloatValue, FloatValue, FloatValue, Exponent]:
        mx = np.maximum(np.maximum(np.abs(A), np.abs(B)), np.maximum(np.abs(C), np.abs(D)))
        _, k = np.frexp(mx)
        k = np.where(mx > 0, k, 0)
        return (np.ldexp(A, -k), np.ldexp(B, -k), np.ldexp(C, -k), np.ldexp(D, -k), e + k)

    @staticmethod
    def subset(x: FloatValue, mask: Cond) -> FloatValue:
        if np.ndim(x) == 0:
            return x
        return x[mask]

    @staticmethod
    def merge(full: npt.ArrayLike, mask: Cond, part: npt.ArrayLike) -> npt.NDArray[np.generic]:
        # ``full`` has the rows' shape (monodromy passes the broadcast entries and an array of exponents)
        full = np.array(full, copy=True)
        full[mask] = part
        return full

    def isfinite_all(self, xs: Sequence[FloatValue]) -> bool:
        return all(bool(np.all(np.isfinite(x))) for x in xs)


class MPContext:
    """mpmath multiprecision scalars (``mpmath.mp``) at the current ``mp.dps``.

    >>> MPContext().positive(mpmath.mpc(1, 1)), MPContext.div(0, 0)
    (False, mpf('nan'))
    """

    is_exact_scale = True

    exp = staticmethod(mpmath.exp)
    log = staticmethod(mpmath.log)
    log1p = staticmethod(mpmath.log1p)

    @staticmethod
    def sqrt(x: MPValue) -> MPValue:
        return mpmath.sqrt(x)

    @staticmethod
    def div(a: MPValue, b: MPValue) -> MPValue:
        if b == 0:
            return mpmath.nan if a == 0 else mpmath.inf
        return a / b

    @staticmethod
    def ldexp(x: MPValue | float, e: Exponent) -> MPValue:
        z = mpmath.mpmathify(x)
        if isinstance(z, mpmath.mpc):       # mpmath's ldexp takes reals: each part scaled, exactly
            return mpmath.mpc(mpmath.ldexp(z.real, int(e)), mpmath.ldexp(z.imag, int(e)))
        return mpmath.ldexp(z, int(e))

    @staticmethod
    def acosh_half_abs(t: MPValue, g: MPValue, e: Exponent) -> MPValue:
        return mpmath.acosh(abs(MPContext.ldexp(t, e)) / 2)

    @staticmethod
    def re_dot(a: MPValue, b: MPValue) -> MPValue:
        return mpmath.re(a * mpmath.conj(b))

    @staticmethod
    def positive(x: MPValue) -> bool:
        return bool(mpmath.im(x) == 0 and mpmath.re(x) > 0)

    def all_positive(self, x: MPValue) -> bool:
        return self.positive(x)

    def align(self, g: MPValue, ref: MPValue) -> tuple[MPValue, Cond]:
        plus = self.re_dot(ref, g) >= 0
        return (g if plus else -g), plus

    def half_plane(self, a: MPValue, g: MPValue) -> Cond:
        return self.re_dot(a, g) >= 0

    @staticmethod
    def any(c: Cond) -> bool:
        return bool(c)

    @staticmethod
    def all(c: Cond) -> bool:
        return bool(c)

    @staticmethod
    def neg(c: Cond) -> Cond:
        return not c

    @staticmethod
    def select(c: Cond, f: Callable[[], MPValue], g: Callable[[], MPValue]) -> MPValue:
        return f() if c else g()

    @staticmethod
    def out_of_range(*xs: MPValue) -> Cond:
        return False

    @staticmethod
    def renormalize(A: MPValue | float, B: MPValue | float, C: MPValue | float, D: MPValue | float,
                    e: Exponent) -> tuple[MPValue | float, MPValue | float, MPValue | float, MPValue | float, Exponent]:
        return A, B, C, D, e

    @staticmethod
    def subset(x: MPValue, mask: Cond) -> MPValue:
        return x

    @staticmethod
    def merge(full: MPValue, mask: Cond, part: MPValue) -> MPValue:
        return part

    def isfinite_all(self, xs: Sequence[MPValue]) -> bool:
        return all(mpmath.isfinite(x) for x in xs)


class IVContext(MPContext):
    """mpmath interval arithmetic (``mpmath.iv``) -- an experimental rigorous path.

    Accuracy decisions use interval midpoints; existence decisions
    (``positive``) require the whole interval to be positive.  Complex
    continuation is not supported.  (For certified orbits use the Arb
    contexts of :mod:`symbt.numeric.multiprec.arb`.)

    >>> IVContext.positive(mpmath.iv.mpf([-1, 2]))
    False
    """

    exp = staticmethod(mpmath.iv.exp)
    log = staticmethod(mpmath.iv.log)
    log1p = staticmethod(mpmath.iv.log1p)
    sqrt = staticmethod(mpmath.iv.sqrt)

    @staticmethod
    def div(a: MPValue, b: MPValue) -> MPValue:
        return a / b

    @staticmethod
    def ldexp(x: MPValue | float, e: Exponent) -> MPValue:
        return mpmath.iv.mpf(x) * mpmath.iv.mpf(2) ** int(e)

    @staticmethod
    def acosh_half_abs(t: MPValue, g: MPValue, e: Exponent) -> MPValue:
        h = abs(IVContext.ldexp(t, e)) / 2
        return mpmath.iv.log(h + mpmath.iv.sqrt((h - 1) * (h + 1)))

    @staticmethod
    def re_dot(a: MPValue, b: MPValue) -> MPValue:
        return (a * b).mid

    @staticmethod
    def positive(x: MPValue) -> bool:
        return bool(x.a > 0)

    def isfinite_all(self, xs: Sequence[MPValue]) -> bool:
        return all(mpmath.isfinite(x.a) and mpmath.isfinite(x.b) for x in xs)


@contextmanager
def iv_prec(bits: int) -> Iterator[None]:
    """``mpmath.iv``'s working precision ``bits`` inside (mpmath's interval context has no ``workprec``).

    >>> with iv_prec(200):
    ...     mpmath.iv.prec
    200
    """
    old = mpmath.iv.prec
    mpmath.iv.prec = bits
    try:
        yield
    finally:
        mpmath.iv.prec = old


FLOAT = FloatContext(np.float64)
COMPLEX = FloatContext(np.complex128)
MP = MPContext()
IV = IVContext()
