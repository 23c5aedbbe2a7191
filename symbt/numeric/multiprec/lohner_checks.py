r"""Checks and certified by-products of the Lohner orbits (:mod:`.lohner`).

* :func:`jacobian_dual` -- the step's interval Jacobian by forward-mode dual numbers (:class:`Dual`, a value
  and a gradient over Arb balls) through :func:`~symbt.numeric.core.step.step_core` itself: an independent route
  to the Jacobian that :func:`~symbt.numeric.multiprec.lohner.step_jacobian` derives from the slopes' implicit
  relations (the tests compare the two, and both with finite differences);
* :func:`invariant_enclosures`, :func:`common_invariants` -- enclosures of the conserved ``H_k`` along a
  certified orbit; the exact map preserves them, so they must all intersect (checked);
* :func:`float64_error_bounds` -- certified bounds of the float64 orbit's error,
  ``|float64 - exact| <= |float64 - mid| + rad``.

Example
-------
>>> import mpmath
>>> from symbt.numeric import certified_orbit
>>> with mpmath.workdps(30):
...     orbit = certified_orbit([-20, 10, 1], [1, 0, 0.9], 10, 5, 50, every=25)
>>> H = common_invariants(invariant_enclosures(*orbit))
>>> H[2].str(5, radius=False)                        # H_2 = p_1 + p_2 + p_3
'-9.0000'
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import mpmath
import numpy as np
from flint import arb, arb_mat, arb_poly

from ..core.step import step_core
from .arb import ArbContext, flint_prec
from .lohner import JacobianBlowup

__all__ = ["Dual", "DUAL", "jacobian_dual", "invariant_enclosures", "common_invariants", "float64_error_bounds",
           "InconsistentEnclosure"]


class Dual:
    """A dual number over Arb balls: a value ``v`` (``arb``) and its gradient ``d`` (a ``1 x n`` ``arb_mat``).

    Enough arithmetic for :func:`~symbt.numeric.core.step.step_core`; every operation encloses the value and
    the gradient of the exact function on the whole ball (the chain rule in ball arithmetic).

    >>> x = Dual(arb(3), arb_mat([[1, 0]]))
    >>> y = (x * x + 1) / x                     # x + 1/x: derivative 1 - 1/x**2
    >>> y.v.str(10, radius=False), y.d[0, 0].str(10, radius=False)
    ('3.333333333', '0.8888888889')
    """

    __slots__ = ("v", "d")

    def __init__(self, v: Any, d: Any) -> None:
        self.v = v
        self.d = d

    def __add__(self, o: Any) -> Dual:
        if isinstance(o, Dual):
            return Dual(self.v + o.v, self.d + o.d)
        return Dual(self.v + o, self.d)

    __radd__ = __add__

    def __sub__(self, o: Any) -> Dual:
        if isinstance(o, Dual):
            return Dual(self.v - o.v, self.d - o.d)
        return Dual(self.v - o, self.d)

    def __rsub__(self, o: Any) -> Dual:
        return Dual(o - self.v, -self.d)

    def __neg__(self) -> Dual:
        return Dual(-self.v, -self.d)

    def __mul__(self, o: Any) -> Dual:
        if isinstance(o, Dual):
            return Dual(self.v * o.v, self.d * o.v + o.d * self.v)
        return Dual(self.v * o, self.d * o)

    __rmul__ = __mul__

    def __truediv__(self, o: Any) -> Dual:
        if isinstance(o, Dual):
            v = self.v / o.v
            return Dual(v, (self.d - o.d * v) * (1 / o.v))
        return Dual(self.v / o, self.d * (1 / arb(o)))

    def __rtruediv__(self, o: Any) -> Dual:          # o / self with a constant o
        v = o / self.v
        return Dual(v, self.d * (-v / self.v))

    def __lt__(self, o: Any) -> bool:               # a sign decision reads the value's ball (certain only)
        return bool(self.v < (o.v if isinstance(o, Dual) else o))

    def __gt__(self, o: Any) -> bool:
        return bool(self.v > (o.v if isinstance(o, Dual) else o))

    def mid(self) -> Any:
        """The midpoint of the value (for the accuracy-only decisions of the step)."""
        return self.v.mid()

    def is_zero(self) -> bool:
        return bool(self.v.is_zero())

    def is_finite(self) -> bool:
        return bool(self.v.is_finite()) and all(a.is_finite() for a in self.d.entries())


def _dexp(x: Dual) -> Dual:
    v = x.v.exp()
    return Dual(v, x.d * v)


def _dlog1p(x: Dual) -> Dual:
    return Dual(x.v.log1p(), x.d * (1 / (1 + x.v)))


def _dlog(x: Dual) -> Dual:
    return Dual(x.v.log(), x.d * (1 / x.v))


def _dsqrt(x: Dual) -> Dual:
    v = x.v.sqrt()
    return Dual(v, x.d * (1 / (2 * v)))


class _DualContext(ArbContext):
    """``ARB_CERTAIN`` on dual numbers: existence decided on whole value balls, accuracy on midpoints."""

    exp = staticmethod(_dexp)
    log = staticmethod(_dlog)
    log1p = staticmethod(_dlog1p)
    sqrt = staticmethod(_dsqrt)

    def div(self, a: Any, b: Any) -> Any:
        if b.is_zero():                   # a slope at infinity: no derivative here
            raise JacobianBlowup("division by an exact zero in the Jacobian of the step")
        return a / b

    def positive(self, x: Any) -> bool:
        return super().positive(x.v if isinstance(x, Dual) else x)

    def isfinite_all(self, xs: Sequence[Any]) -> bool:
        return all(x.is_finite() for x in xs)


#: the context of :func:`jacobian_image`
DUAL = _DualContext(certain=True)


def jacobian_dual(box: Sequence[Any], lam0: Any, mu: Any, branch: int) -> tuple[list[Any], Any]:
    """Plain ball image ``f(box)`` and the step's Jacobian over ``box`` by forward-mode :class:`Dual` numbers.

    The slow, independent route (:func:`step_jacobian` is the fast one): ``step_core`` itself on dual
    numbers.  ``box`` is the state ``(p_1..p_N, q_1..q_N)`` as Arb balls; returns the image (a list of
    balls) and ``J`` (a ``2N x 2N`` ``arb_mat``).  Raises :class:`~symbt.numeric.multiprec.arb.Uncertain`,
    :class:`NoRealMapError`, :class:`JacobianBlowup`.

    >>> img, J = jacobian_dual([arb(-20), arb(10), arb(1), arb(1), arb(0), arb(0.9)], arb(10), arb(5), 1)
    >>> img[0].str(8, radius=False), J.nrows(), J[0, 0].str(5, radius=False)
    ('-19.996568', 6, '1.0067')
    """
    n = len(box)
    N = n // 2
    xs = [Dual(b, arb_mat(1, n, [1 if k == i else 0 for k in range(n)])) for i, b in enumerate(box)]
    Pn, Qn, _ = step_core(DUAL, xs[:N], xs[N:], lam0, mu, branch)
    out = Pn + Qn
    J = arb_mat([x.d.entries() for x in out])
    if not (all(x.v.is_finite() for x in out) and all(a.is_finite() for a in J.entries())):
        raise JacobianBlowup("the Jacobian of the step is not finite on the current box")
    return [x.v for x in out], J


class InconsistentEnclosure(ArithmeticError):
    """Two certified enclosures of one conserved quantity are disjoint: an enclosure is wrong (a bug).

    >>> issubclass(InconsistentEnclosure, ArithmeticError)
    True
    """


def _ball_of(mid: Any, rad: Any) -> Any:
    return arb(mid) + arb(0, arb(rad).abs_upper())


def invariant_enclosures(P: Sequence[Sequence[Any]], Q: Sequence[Sequence[Any]], P_rad: Sequence[Sequence[Any]],
                         Q_rad: Sequence[Sequence[Any]], prec: int = 256) -> list[list[Any]]:
    """Enclosures of ``H_0 .. H_{N-1}`` (``tr L(lam) = sum H_k lam**k``) at every stored state of a certified orbit.

    ``P, Q, P_rad, Q_rad`` as returned by :func:`~symbt.numeric.certified_orbit`; each state is the box
    ``mid +- rad``, and ``tr L`` is formed on it as a polynomial in ball arithmetic (``arb_poly``) at
    ``prec`` bits.  The exact orbit preserves every ``H_k``, so all enclosures of one ``H_k`` must intersect:
    :func:`common_invariants` checks it.

    >>> import mpmath
    >>> from symbt.numeric import certified_orbit
    >>> with mpmath.workdps(30):
    ...     orbit = certified_orbit([-20, 10, 1], [1, 0, 0.9], 10, 5, 20, every=10)
    >>> H = invariant_enclosures(*orbit)
    >>> len(H), [h.str(6, radius=False) for h in H[-1]]
    (3, ['-162.228', '-213.933', '-9.00000'])
    """
    out = []
    with flint_prec(prec):
        for p, q, pr, qr in zip(P, Q, P_rad, Q_rad):
            pb = [_ball_of(m, r) for m, r in zip(p, pr)]
            qb = [_ball_of(m, r) for m, r in zip(q, qr)]
            N = len(pb)
            rr = [(qb[(j + 1) % N] - qb[j]).exp() for j in range(N)]
            # M = m_N ... m_1, m_j = [[lam + p_j, -1], [r_j, 0]] (symbt.numeric.lax), entries as polynomials
            A, B, C, D = arb_poly([pb[0], 1]), arb_poly([-1]), arb_poly([rr[0]]), arb_poly([])
            for j in range(1, N):
                a = arb_poly([pb[j], 1])
                A, B, C, D = a * A - C, a * B - D, A * rr[j], B * rr[j]
            tr = A + D
            out.append([tr[k] for k in range(N)])
    return out


def common_invariants(H: Sequence[Sequence[Any]], prec: int = 256) -> list[Any]:
    """The intersection, over the stored states, of the enclosures of each ``H_k`` (at ``prec`` bits); raises
    :class:`InconsistentEnclosure` if two of them are disjoint (they cannot be, for correct enclosures).

    >>> h = common_invariants([[arb(1, 0.5)], [arb(1.25, 0.5)]])[0]     # [0.5, 1.5] and [0.75, 1.75]
    >>> float(h.mid()), round(float(h.rad()), 6)
    (1.125, 0.375)
    >>> try:
    ...     common_invariants([[arb(1, 0.1)], [arb(2, 0.1)]])
    ... except InconsistentEnclosure as exc:
    ...     print(exc)
    the enclosures of H_0 at stored states 0 and 1 are disjoint
    """
    cur = list(H[0])
    with flint_prec(prec):
        for i, h in enumerate(H[1:], 1):
            for k, (c, x) in enumerate(zip(cur, h)):
                if not c.overlaps(x):
                    first = next(j for j in range(i) if not H[j][k].overlaps(x))
                    raise InconsistentEnclosure("the enclosures of H_%d at stored states %d and %d are disjoint"
                                                % (k, first, i))
                cur[k] = c.intersection(x)
    return cur


def _float_up(x: Any) -> float:
    """The non-negative exact Arb number ``x`` rounded up to a float."""
    man, exp = x.man_exp()
    return float(mpmath.mpf(mpmath.libmp.from_man_exp(int(man), int(exp), 53, "u")))


def float64_error_bounds(P: Sequence[Sequence[Any]], Q: Sequence[Sequence[Any]], P_rad: Sequence[Sequence[Any]],
                         Q_rad: Sequence[Sequence[Any]], P64: Any, Q64: Any) -> list[float]:
    """Certified bounds of ``max_j |float64 - exact|`` at every stored state: ``|float64 - mid| + rad``.

    ``P, Q, P_rad, Q_rad`` from :func:`~symbt.numeric.certified_orbit`, ``P64, Q64`` the float64 orbit of
    the same (binary) input stored at the same steps (:func:`~symbt.numeric.bt_orbit`).  Each bound is
    rounded up to a float.

    >>> import mpmath
    >>> from symbt.numeric import bt_orbit, certified_orbit
    >>> with mpmath.workdps(30):
    ...     orbit = certified_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 100, every=50)
    >>> P64, Q64 = bt_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 100, every=50)
    >>> [b < 1e-12 for b in float64_error_bounds(*orbit, P64, Q64)]
    [True, True, True]
    """
    out = []
    with flint_prec(128):
        for i, (p, q, pr, qr) in enumerate(zip(P, Q, P_rad, Q_rad)):
            f64 = [float(x) for x in np.r_[P64[i], Q64[i]]]
            worst = arb(0)
            for x, m, r in zip(f64, list(p) + list(q), list(pr) + list(qr)):
                worst = worst.max(abs(arb(x) - arb(m)) + arb(r))
            out.append(_float_up(worst.abs_upper()))
    return out
