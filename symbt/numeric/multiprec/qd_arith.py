r"""Quad-double arithmetic (Hida, Li, Bailey: *Library for double-double and quad-double arithmetic*, 2001).

A quad-double is an unevaluated sum ``x = x0 + x1 + x2 + x3`` of four float64
(here a plain tuple of four floats) that is *renormalised*:
``|x_{i+1}| <= ulp(x_i) / 2``, so ``x0`` is ``x`` rounded to a double and the
sign of ``x`` is that of ``x0``.  That carries ``4 * 53 = 212`` bits (at least
``209`` = ``QD_BITS`` for every value: a component may borrow a bit of sign),
with the exponent range of a double (components below ``2**-1022`` lose bits,
so values are kept well inside ``[2**-700, 2**700]`` by the callers).

Every function is plain Python over floats, written so that numba compiles it
unchanged (:mod:`symbt.numeric.multiprec.qd`, lazily); run as Python the functions give
the same bits, slowly (tests and doctests).

Error-free transformations (IEEE round-to-nearest): :func:`two_sum`
``a + b = s + e`` exactly, :func:`quick_two_sum` the same for ``|a| >= |b|``,
:func:`two_prod` ``a b = p + e`` exactly (Dekker's split here; the compiled
build substitutes a hardware fused multiply-add, same bits).  On top of them
QD's algorithms: :func:`add` (QD's default "sloppy" addition: absolute error
``<= 2**-211 (|a| + |b|)`` -- in a cancellation the relative error grows, as
it must when the inputs carry an error of their own), :func:`mul` (terms up to
order ``eps**3``, relative error ``~ 2**-209``), :func:`div` (five quotient
digits, long division), :func:`sqrt` (Newton on ``1/sqrt``), :func:`exp`
(``exp(a) = 2**m exp(r)**(2**16)``, ``a = m ln 2 + 2**16 r``, Taylor for
``exp(r) - 1`` and the doubling ``e <- 2 e + e**2`` which keeps ``exp - 1``
relatively accurate: :func:`expm1`), :func:`log1p` (Newton on
``expm1(y) = x``, two steps from ``log1p(x0)``: ``53 -> 106 -> 212`` bits;
relative accuracy for small ``x``).  Measured errors against mpmath at 80
digits: ``tests/test_numeric_qd.py``.

Example
-------
>>> from symbt.numeric.multiprec.qd_arith import from_float, div, mul, add_d, to_float
>>> third = div(from_float(1.0), from_float(3.0))
>>> add_d(mul(third, from_float(3.0)), -1.0)[0] == 0.0 or abs(add_d(mul(third, from_float(3.0)), -1.0)[0]) < 1e-62
True
>>> to_float(third)
0.3333333333333333
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["QD_BITS", "two_sum", "quick_two_sum", "two_prod", "renorm4", "renorm5", "from_float", "to_float",
           "neg", "add", "add_d", "sub", "mul", "mul_d", "mul_pwr2", "ldexp_qd", "div", "sqrt", "exp_parts", "exp",
           "expm1", "log1p", "qd_of", "LN2", "COEF", "EXP_TAB", "EXPM1_TAB"]

#: bits every renormalised quad-double carries (4 x 53, less a bit of sign per lower component)
QD_BITS = 209

_SPLITTER = 134217729.0          # 2**27 + 1
_EXP_K = 65536.0                 # exp reduction 2**16 (QD's choice): 16 doublings
_EXP_INV_K = 1.0 / 65536.0
_EPS = 1.21543267145725e-63      # 2**-209


def two_sum(a: float, b: float) -> tuple[float, float]:
    """``s = fl(a + b)`` and the exact error ``e``: ``a + b = s + e`` (Knuth).

    >>> two_sum(1.0, 2.0 ** -60)
    (1.0, 8.673617379884035e-19)
    """
    s = a + b
    bb = s - a
    e = (a - (s - bb)) + (b - bb)
    return s, e


def quick_two_sum(a: float, b: float) -> tuple[float, float]:
    """:func:`two_sum` for ``|a| >= |b|`` (or ``a = 0``) (Dekker).

    >>> quick_two_sum(1.0, 2.0 ** -60)
    (1.0, 8.673617379884035e-19)
    """
    s = a + b
    e = b - (s - a)
    return s, e


def two_prod(a: float, b: float) -> tuple[float, float]:
    """``p = fl(a b)`` and the exact error ``e``: ``a b = p + e`` (Dekker's split; ``|a|, |b| < 2**996``).

    >>> two_prod(1.0 + 2.0 ** -30, 1.0 + 2.0 ** -30)
    (1.0000000018626451, 8.673617379884035e-19)
    """
    p = a * b
    t = _SPLITTER * a
    ah = t - (t - a)
    al = a - ah
    t = _SPLITTER * b
    bh = t - (t - b)
    bl = b - bh
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    return p, e


def three_sum(a: float, b: float, c: float) -> tuple[float, float, float]:
    """``a + b + c`` as three non-overlapping doubles (exact)."""
    t1, t2 = two_sum(a, b)
    a, t3 = two_sum(c, t1)
    b, c = two_sum(t2, t3)
    return a, b, c


def three_sum2(a: float, b: float, c: float) -> tuple[float, float]:
    """``a + b + c`` as two doubles (the third term rounded into the second)."""
    t1, t2 = two_sum(a, b)
    a, t3 = two_sum(c, t1)
    return a, t2 + t3


def renorm5(c0: float, c1: float, c2: float, c3: float, c4: float) -> tuple[float, float, float, float]:
    """Five overlapping doubles (roughly decreasing) -> a renormalised quad-double (QD's ``renorm``)."""
    if math.isinf(c0):
        return c0, c1, c2, c3
    s0, c4 = quick_two_sum(c3, c4)
    s0, c3 = quick_two_sum(c2, s0)
    s0, c2 = quick_two_sum(c1, s0)
    c0, c1 = quick_two_sum(c0, s0)
    s0, s1, s2, s3 = c0, c1, 0.0, 0.0
    if s1 != 0.0:
        s1, s2 = quick_two_sum(s1, c2)
        if s2 != 0.0:
            s2, s3 = quick_two_sum(s2, c3)
            if s3 != 0.0:
                s3 += c4
            else:
                s2 += c4
        else:
            s1, s2 = quick_two_sum(s1, c3)
            if s2 != 0.0:
                s2, s3 = quick_two_sum(s2, c4)
            else:
                s1, s2 = quick_two_sum(s1, c4)
    else:
        s0, s1 = quick_two_sum(s0, c2)
        if s1 != 0.0:
            s1, s2 = quick_two_sum(s1, c3)
            if s2 != 0.0:
                s2, s3 = quick_two_sum(s2, c4)
            else:
                s1, s2 = quick_two_sum(s1, c4)
        else:
            s0, s1 = quick_two_sum(s0, c3)
            if s1 != 0.0:
                s1, s2 = quick_two_sum(s1, c4)
            else:
                s0, s1 = quick_two_sum(s0, c4)
    return s0, s1, s2, s3


def renorm4(c0: float, c1: float, c2: float, c3: float) -> tuple[float, float, float, float]:
    """Four overlapping doubles -> a renormalised quad-double.

    >>> renorm4(1.0, 1.0, 0.0, 0.0)
    (2.0, 0.0, 0.0, 0.0)
    """
    return renorm5(c0, c1, c2, c3, 0.0)


def from_float(a: float) -> tuple[float, float, float, float]:
    """The double ``a`` as a quad-double (exact).

    >>> from_float(0.5)
    (0.5, 0.0, 0.0, 0.0)
    """
    return a, 0.0, 0.0, 0.0


def to_float(a: tuple[float, float, float, float]) -> float:
    """The nearest double (the leading component).

    >>> to_float((1.0, 1e-17, 0.0, 0.0))
    1.0
    """
    return a[0]


def neg(a: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
    """``-a`` (exact).

    >>> neg((1.0, 0.0, 0.0, 0.0))
    (-1.0, -0.0, -0.0, -0.0)
    """
    return -a[0], -a[1], -a[2], -a[3]


def add(a: tuple[float, float, float, float], b: tuple[float, float, float, float]
        ) -> tuple[float, float, float, float]:
    """``a + b`` (QD's ``sloppy_add``; absolute error ``<= ~2**-211 (|a| + |b|)``).

    >>> add((1.0, 0.0, 0.0, 0.0), (2.0 ** -100, 0.0, 0.0, 0.0))
    (1.0, 7.888609052210118e-31, 0.0, 0.0)
    """
    s0, t0 = two_sum(a[0], b[0])
    s1, t1 = two_sum(a[1], b[1])
    s2, t2 = two_sum(a[2], b[2])
    s3, t3 = two_sum(a[3], b[3])
    s1, t0 = two_sum(s1, t0)
    s2, t0, t1 = three_sum(s2, t0, t1)
    s3, t0 = three_sum2(s3, t0, t2)
    t0 = t0 + t1 + t3
    return renorm5(s0, s1, s2, s3, t0)


def sub(a: tuple[float, float, float, float], b: tuple[float, float, float, float]
        ) -> tuple[float, float, float, float]:
    """``a - b`` (:func:`add` of ``-b``).

    >>> sub((1.0, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))[0]
    0.0
    """
    return add(a, (-b[0], -b[1], -b[2], -b[3]))


def add_d(a: tuple[float, float, float, float], b: float) -> tuple[float, float, float, float]:
    """``a + b`` for a double ``b`` (relative error ``~2**-212`` of ``|a| + |b|``).

    >>> add_d((1.0, 0.0, 0.0, 0.0), 2.0 ** -200)
    (1.0, 6.223015277861142e-61, 0.0, 0.0)
    """
    c0, e = two_sum(a[0], b)
    c1, e = two_sum(a[1], e)
    c2, e = two_sum(a[2], e)
    c3, e = two_sum(a[3], e)
    return renorm5(c0, c1, c2, c3, e)


def mul(a: tuple[float, float, float, float], b: tuple[float, float, float, float]
        ) -> tuple[float, float, float, float]:
    """``a b`` (QD's multiplication: exact terms to order ``eps**2``, ``eps**3`` terms in double).

    >>> mul((3.0, 0.0, 0.0, 0.0), (0.5, 0.0, 0.0, 0.0))
    (1.5, 0.0, 0.0, 0.0)
    """
    p0, q0 = two_prod(a[0], b[0])
    p1, q1 = two_prod(a[0], b[1])
    p2, q2 = two_prod(a[1], b[0])
    p3, q3 = two_prod(a[0], b[2])
    p4, q4 = two_prod(a[1], b[1])
    p5, q5 = two_prod(a[2], b[0])
    p1, p2, q0 = three_sum(p1, p2, q0)
    p2, q1, q2 = three_sum(p2, q1, q2)
    p3, p4, p5 = three_sum(p3, p4, p5)
    s0, t0 = two_sum(p2, p3)
    s1, t1 = two_sum(q1, p4)
    s2 = q2 + p5
    s1, t0 = two_sum(s1, t0)
    s2 += t0 + t1
    s1 += a[0] * b[3] + a[1] * b[2] + a[2] * b[1] + a[3] * b[0] + q0 + q3 + q4 + q5
    return renorm5(p0, p1, s0, s1, s2)


def mul_d(a: tuple[float, float, float, float], b: float) -> tuple[float, float, float, float]:
    """``a b`` for a double ``b``.

    >>> mul_d((1.0, 2.0 ** -60, 0.0, 0.0), 3.0)
    (3.0, 2.6020852139652106e-18, 0.0, 0.0)
    """
    p0, q0 = two_prod(a[0], b)
    p1, q1 = two_prod(a[1], b)
    p2, q2 = two_prod(a[2], b)
    p3 = a[3] * b
    s1, s2 = two_sum(q0, p1)
    s2, q1, p2 = three_sum(s2, q1, p2)
    q1, q2 = three_sum2(q1, q2, p3)
    return renorm5(p0, s1, s2, q1, q2 + p2)


def mul_pwr2(a: tuple[float, float, float, float], b: float) -> tuple[float, float, float, float]:
    """``a b`` for a power of two ``b`` (exact barring under/overflow).

    >>> mul_pwr2((3.0, 1e-20, 0.0, 0.0), 0.5)
    (1.5, 5e-21, 0.0, 0.0)
    """
    return a[0] * b, a[1] * b, a[2] * b, a[3] * b


def ldexp_qd(a: tuple[float, float, float, float], m: int) -> tuple[float, float, float, float]:
    """``a 2**m`` (exact barring under/overflow).

    >>> ldexp_qd((3.0, 0.0, 0.0, 0.0), -1)
    (1.5, 0.0, 0.0, 0.0)
    """
    return math.ldexp(a[0], m), math.ldexp(a[1], m), math.ldexp(a[2], m), math.ldexp(a[3], m)


def div(a: tuple[float, float, float, float], b: tuple[float, float, float, float]
        ) -> tuple[float, float, float, float]:
    """``a / b`` by long division with five double quotient digits (QD's ``accurate_div``).

    Division by zero gives non-finite components (the callers test finiteness).

    >>> div((1.0, 0.0, 0.0, 0.0), (4.0, 0.0, 0.0, 0.0))
    (0.25, 0.0, 0.0, 0.0)
    """
    q0 = a[0] / b[0]
    r = sub(a, mul_d(b, q0))
    q1 = r[0] / b[0]
    r = sub(r, mul_d(b, q1))
    q2 = r[0] / b[0]
    r = sub(r, mul_d(b, q2))
    q3 = r[0] / b[0]
    r = sub(r, mul_d(b, q3))
    q4 = r[0] / b[0]
    return renorm5(q0, q1, q2, q3, q4)


def sqrt(a: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
    """``sqrt(a)`` for ``a > 0`` (three Newton steps on ``1/sqrt(a)`` from the double, then ``a / sqrt(a)``);
    ``0`` for ``a = 0``, NaN for ``a < 0``.

    >>> sqrt((4.0, 0.0, 0.0, 0.0))
    (2.0, 0.0, 0.0, 0.0)
    """
    if a[0] == 0.0:
        return 0.0, 0.0, 0.0, 0.0
    if a[0] < 0.0:
        return math.nan, math.nan, math.nan, math.nan
    r = (1.0 / math.sqrt(a[0]), 0.0, 0.0, 0.0)
    h = mul_pwr2(a, 0.5)
    for _ in range(3):
        r = add(r, mul(add_d(neg(mul(h, mul(r, r))), 0.5), r))
    return mul(r, a)


def qd_of(x: object) -> tuple[float, float, float, float]:
    """A number with ``float(...)`` (an mpmath ``mpf`` at ``>= 250`` bits) rounded to a quad-double digit by digit.

    >>> import mpmath
    >>> with mpmath.workprec(300):
    ...     qd_of(mpmath.mpf(1) / 3)[1] != 0.0
    True
    """
    out = []
    rest = x
    for _ in range(4):
        d = float(rest)          # type: ignore[arg-type]
        out.append(d)
        rest = rest - d          # type: ignore[operator]
    return out[0], out[1], out[2], out[3]


_TAB = 256                       # exp table spacing 1/256: |r| <= 2**-9 after the reduction
_TAB_HALF = 89                   # j in [-89, 89]: |a - m ln 2| <= ln2 / 2 < 89.5 / 256
_TAYLOR = 19                     # exp(r) - 1 = r sum_{n < 19} r**n / (n + 1)!, truncation < 2**-215 relative


def _constants() -> tuple[tuple[float, float, float, float], tuple[float, float, float, float], np.ndarray,
                          np.ndarray, np.ndarray]:
    import mpmath

    with mpmath.workprec(320):
        ln2, third = qd_of(mpmath.ln2), qd_of(mpmath.mpf(1) / 3)
        coef = np.array([qd_of(1 / mpmath.factorial(k + 1)) for k in range(_TAYLOR)])
        tab = np.array([qd_of(mpmath.exp(mpmath.mpf(j) / _TAB)) for j in range(-_TAB_HALF, _TAB_HALF + 1)])
        tabm1 = np.array([qd_of(mpmath.expm1(mpmath.mpf(j) / _TAB)) for j in range(-_TAB_HALF, _TAB_HALF + 1)])
    return ln2, third, coef, tab, tabm1


#: ln 2; 1/3; ``1/(k+1)!`` (row ``k``); ``exp(j/256)`` and ``expm1(j/256)`` (row ``j + 89``), rounded to quad-double
LN2, _THIRD, COEF, EXP_TAB, EXPM1_TAB = _constants()


def _qrow(t: np.ndarray, i: int) -> tuple[float, float, float, float]:
    return float(t[i, 0]), float(t[i, 1]), float(t[i, 2]), float(t[i, 3])


def exp_parts(a: tuple[float, float, float, float]) -> tuple[int, int, tuple[float, float, float, float]]:
    """``(m, i, s)`` with ``exp(a) = 2**m EXP_TAB[i] (1 + s)``, ``s = exp(r) - 1`` (``|r| <= 2**-9``).

    Reduction ``a = m ln 2 + j/256 + r`` (``i = j + 89``), then Horner for ``s`` (19 terms:
    truncation below ``2**-215`` relative).  ``|a| < 709`` (callers check).

    >>> m, i, s = exp_parts((1.0, 0.0, 0.0, 0.0))
    >>> m, i - 89, round(float(s[0]), 12)
    (1, 79, -0.001739416019)
    """
    m = math.floor(a[0] / LN2[0] + 0.5)
    b = sub(a, mul_d(LN2, float(m)))
    j = math.floor(b[0] * _TAB + 0.5)
    r = add_d(b, -j / _TAB)
    # Horner from the inside; h_k (~ 1/(k+1)!) enters s with weight r**k <= 2**-9k, so it needs relative
    # precision 2**(9k - 212) (k+1)!: doubles for k >= 14, double-doubles for k >= 10, quad-doubles below
    r0, r1 = r[0], r[1]
    hd = float(COEF[_TAYLOR - 1, 0])
    for k in range(_TAYLOR - 2, 13, -1):
        hd = hd * r0 + float(COEF[k, 0])
    hh, hl = hd, 0.0
    for k in range(13, 9, -1):                           # double-double: (hh, hl) (r0 + r1) + c_k
        p, e = two_prod(hh, r0)
        e += hh * r1 + hl * r0
        p, e = quick_two_sum(p, e)
        s1, s2 = two_sum(p, float(COEF[k, 0]))
        s2 += e + float(COEF[k, 1])
        hh, hl = quick_two_sum(s1, s2)
    h = (hh, hl, 0.0, 0.0)
    for k in range(9, 0, -1):
        h = add(mul(h, r), _qrow(COEF, k))
    h = add_d(mul(h, r), 1.0)
    return int(m), int(j) + _TAB_HALF, mul(h, r)


def exp(a: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
    """``exp(a)``: ``2**m T (1 + s)`` from :func:`exp_parts`; ``0`` below ``-709``, ``inf`` above ``709``.

    >>> round(exp((1.0, 0.0, 0.0, 0.0))[0], 12)
    2.718281828459
    """
    if a[0] <= -709.0:
        return 0.0, 0.0, 0.0, 0.0
    if a[0] >= 709.0:
        return math.inf, 0.0, 0.0, 0.0
    m, i, s = exp_parts(a)
    t = _qrow(EXP_TAB, i)
    return ldexp_qd(add(t, mul(t, s)), m)


def expm1(a: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
    """``exp(a) - 1``, relatively accurate for small ``|a|`` (``|a| < 709``): for ``m = 0``
    ``expm1(j/256) + exp(j/256) s`` (no cancellation: ``|j/256| <= 3 |a|``), else ``exp(a) - 1``.

    >>> expm1((1e-30, 0.0, 0.0, 0.0))[0]
    1e-30
    """
    m, i, s = exp_parts(a)
    t = _qrow(EXP_TAB, i)
    if m == 0:
        return add(_qrow(EXPM1_TAB, i), mul(t, s))
    return add_d(ldexp_qd(add(t, mul(t, s)), m), -1.0)


def log1p(x: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
    """``log(1 + x)`` for ``x > -1``, relatively accurate for small ``|x|``.

    From ``y0 = log1p(x0)`` (double; ``log((1 + x)_0)`` for ``x0 < -1/2``):
    ``z = (1 + x) exp(-y0) - 1`` (``|z| ~ 2**-52``, computed as ``(x - expm1(y0)) / exp(y0)``,
    resp. ``((1 + x) - exp(y0)) / exp(y0)`` with ``1 + x`` exact), and
    ``log1p(x) = y0 + z - z**2/2 + z**3/3 - z**4/4`` (the rest ``< 2**-255``): one exponential.
    NaN for ``x <= -1``.

    >>> log1p((1e-30, 0.0, 0.0, 0.0))[0]
    1e-30
    """
    xp1 = add_d(x, 1.0)
    if not xp1[0] > 0.0:
        return math.nan, math.nan, math.nan, math.nan
    near = x[0] < -0.5
    y0 = math.log(xp1[0]) if near else math.log1p(x[0])
    if y0 == 0.0:                                        # x0 == 0: |x| < 2**-1000
        return x
    m, i, s = exp_parts((y0, 0.0, 0.0, 0.0))
    t = _qrow(EXP_TAB, i)
    ey = ldexp_qd(add(t, mul(t, s)), m)
    if near:
        num = sub(xp1, ey)
    elif m == 0:
        num = sub(x, add(_qrow(EXPM1_TAB, i), mul(t, s)))
    else:
        num = sub(x, add_d(ey, -1.0))
    z = div(num, ey)
    inner = add_d(mul(z, sub(_THIRD, mul_pwr2(z, 0.25))), -0.5)
    return add((y0, 0.0, 0.0, 0.0), add(z, mul(mul(z, z), inner)))
