r"""python-flint contexts: Arb real balls (``arb``) and complex balls (``acb``).

In the style of mpmath's FPContext: the step (:func:`~symbt.numeric.core.step.step_core`)
is written once; a backend only binds primitives.  Two uses of ``arb``:

* ``ARB_MID`` -- the fast path for mpmath input (:mod:`symbt.numeric.multiprec.runners`): balls at the
  caller's precision plus guard bits, every decision (existence included) on
  midpoints, as the mpmath path decides on its values.  The midpoints are
  what a midpoint arithmetic would compute.
* ``ARB_CERTAIN`` -- certified orbits (:mod:`symbt.numeric.multiprec.certified`): existence
  (``|tr| > 2``, ``Etilde_j > 0``) must hold on the whole ball; a ball that
  straddles the boundary raises :class:`Uncertain` (the driver raises the
  precision).  Accuracy-only choices (which of two algebraically equal
  formulas, transport direction) use midpoints -- both alternatives enclose
  the same exact value, so the enclosure stays rigorous.

``ACB`` is the complex continuation (``allow_complex=True``).  Division by an
*exact* zero returns an infinite ball (a projective slope at infinity, as in
IEEE arithmetic); any other ball containing zero gives NaN (not finite).
This module imports python-flint; import it only when flint is installed.

Example
-------
>>> from flint import arb
>>> from symbt.numeric.multiprec.arb import ARB_CERTAIN, flint_prec
>>> with flint_prec(100):
...     ARB_CERTAIN.positive(arb(2).sqrt() - 1), ARB_CERTAIN.div(arb(1), arb(0)).is_finite()
(True, False)
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator, Sequence
from typing import Any, TypeAlias, TypeVar

import flint
from flint import acb, arb

from ..core.context import Cond, Exponent

__all__ = ["ArbContext", "AcbContext", "ARB_MID", "ARB_CERTAIN", "ACB", "Uncertain", "flint_prec"]


class Uncertain(ArithmeticError):
    """An existence decision could not be made on a ball (it contains the boundary).

    >>> try:
    ...     ARB_CERTAIN.positive(arb(0, 1))
    ... except Uncertain:
    ...     print("undecided")
    undecided
    """


@contextlib.contextmanager
def flint_prec(bits: int) -> Iterator[None]:
    """Set python-flint's working precision (bits) for the block, restoring it afterwards.

    >>> with flint_prec(200):
    ...     print(flint.ctx.prec)
    200
    """
    old = flint.ctx.prec
    flint.ctx.prec = int(bits)
    try:
        yield
    finally:
        flint.ctx.prec = old


#: a value of the Arb contexts: a real ball (``arb``) or, in :data:`ACB`, a complex ball (``acb``)
Ball: TypeAlias = arb | acb
#: one kind of ball throughout a call (real or complex)
BallT = TypeVar("BallT", arb, acb)


class ArbContext:
    """Real balls; ``certain=True`` decides existence only when it holds on the whole ball.

    >>> ArbContext(certain=False).positive(arb(1, 5)), ArbContext(certain=True).positive(arb(-1, 0.5))
    (True, False)
    """

    is_exact_scale = True
    # Any: re-bound to the complex-ball functions in AcbContext (one attribute, two signatures)
    exp: Any = staticmethod(arb.exp)
    log: Any = staticmethod(arb.log)
    log1p: Any = staticmethod(arb.log1p)
    sqrt: Any = staticmethod(arb.sqrt)
    nan: Any = staticmethod(arb.nan)
    inf: Any = staticmethod(arb.pos_inf)

    def __init__(self, certain: bool) -> None:
        self.certain = certain

    def div(self, a: BallT, b: BallT) -> BallT:
        if b.is_zero():
            return self.nan() if a.is_zero() else self.inf()
        return a / b

    def positive(self, x: arb) -> bool:
        if not self.certain:
            return bool(x.mid() > 0)
        if x > 0:
            return True
        if x <= 0:
            return False
        raise Uncertain("a ball straddles the boundary of existence: %s" % x.str(5, radius=True))

    def all_positive(self, x: arb) -> bool:
        return self.positive(x)

    def ldexp(self, x: arb, e: Exponent) -> arb:
        return x * arb(2) ** int(e)

    def acosh_half_abs(self, t: arb, g: arb, e: Exponent) -> arb:
        return (abs(self.ldexp(t, e)) / 2).acosh()

    def re_dot(self, a: arb, b: arb) -> arb:
        return a * b

    def align(self, g: arb, ref: arb) -> tuple[arb, bool]:
        plus = (ref.mid() >= 0) == (g.mid() >= 0)     # sign of ref * g, without the product
        return (g if plus else -g), plus

    def half_plane(self, a: arb, g: arb) -> bool:
        return bool((a.mid() >= 0) == (g.mid() >= 0))

    def any(self, c: Cond) -> bool:
        return bool(c)

    all = any

    def neg(self, c: Cond) -> bool:
        return not c

    def select(self, c: Cond, f: Callable[[], BallT], g: Callable[[], BallT]) -> BallT:
        return f() if c else g()

    def out_of_range(self, *xs: Ball) -> bool:
        return False

    def renormalize(self, A: Ball, B: Ball, C: Ball, D: Ball,
                    e: Exponent) -> tuple[Ball, Ball, Ball, Ball, Exponent]:
        return A, B, C, D, e

    def subset(self, x: BallT, mask: Cond) -> BallT:
        return x

    def merge(self, full: BallT, mask: Cond, part: BallT) -> BallT:
        return part

    def isfinite_all(self, xs: Sequence[Ball]) -> bool:
        return all(x.is_finite() for x in xs)


class AcbContext(ArbContext):
    """Complex balls (principal branches) for the complex continuation; decisions on midpoints.

    >>> ACB.sqrt(acb(-4)), ACB.positive(acb(1, 1))
    (2.00000000000000j, False)
    """

    # the real-ball primitives re-bound to complex balls (the type checker's [override]: an acb context
    # is not an arb context, it shares the control-flow methods)
    exp = staticmethod(acb.exp)
    log = staticmethod(acb.log)
    log1p = staticmethod(acb.log1p)
    sqrt = staticmethod(acb.sqrt)
    nan = staticmethod(lambda: acb(arb.nan()))
    inf = staticmethod(lambda: acb(arb.pos_inf()))

    def positive(self, x: acb) -> bool:  # type: ignore[override]
        return bool(x.imag.is_zero() and x.real.mid() > 0)

    def ldexp(self, x: acb, e: Exponent) -> acb:  # type: ignore[override]
        return x * acb(2) ** int(e)

    def re_dot(self, a: acb, b: acb) -> arb:  # type: ignore[override]
        return (a * b.conjugate()).real

    def align(self, g: acb, ref: acb) -> tuple[acb, bool]:  # type: ignore[override]
        plus = bool(self.re_dot(ref, g).mid() >= 0)
        return (g if plus else -g), plus

    def half_plane(self, a: acb, g: acb) -> bool:  # type: ignore[override]
        return bool(self.re_dot(a, g).mid() >= 0)


ARB_MID = ArbContext(certain=False)
ARB_CERTAIN = ArbContext(certain=True)
ACB = AcbContext(certain=False)
