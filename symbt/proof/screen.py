"""The numeric screen: evaluation at random admissible points (see :mod:`symbt.proof`)."""
from __future__ import annotations

import random
from functools import cache

import mpmath
import sympy as sp

from .lambdify import plain_lambdify

__all__ = ["screen", "sample_symbol"]


def sample_symbol(sym: sp.Symbol, rng: random.Random):
    """A random value for ``sym`` honouring its SymPy assumptions.

    ``integer`` (with ``even``/``odd``, sign), ``positive``/``nonnegative``,
    ``negative``/``nonpositive``, ``real`` (either sign), ``imaginary`` (purely
    imaginary, either sign); anything else is sampled complex with imaginary
    parts up to about 4 in size (beyond pi, so branch cuts of ``log`` are hit).
    """
    a = sym.assumptions0
    if a.get("integer"):
        if a.get("positive") or a.get("nonnegative"):
            lo, hi = 1, 9
        elif a.get("negative") or a.get("nonpositive"):
            lo, hi = -9, -1
        else:
            lo, hi = -9, 9
        v = rng.randint(lo, hi)
        if a.get("even") and v % 2:
            v = v - 1 if v - 1 >= lo else v + 1
        if a.get("odd") and not v % 2:
            v = v + 1 if v + 1 <= hi else v - 1
        if v == 0 and a.get("nonzero"):
            v = 2 if a.get("even") else 1
        return mpmath.mpf(v)
    # rational-ish values with many digits, kept away from 0 and from each other
    mag = mpmath.mpf(rng.randint(3, 30)) / 10 + mpmath.mpf(rng.random()) / 7
    if a.get("positive") or a.get("nonnegative"):
        return mag
    if a.get("negative") or a.get("nonpositive"):
        return -mag
    sign = 1 if rng.random() < 0.5 else -1
    if a.get("real") or a.get("extended_real"):
        return sign * mag
    if a.get("imaginary"):
        return mpmath.mpc(0, sign * mag)
    im = mpmath.mpf(rng.randint(-40, 40)) / 10 + mpmath.mpf(rng.random()) / 11
    return mpmath.mpc(sign * mag, im)


def _as_mp(x):
    if isinstance(x, (mpmath.mpf, mpmath.mpc)):
        return x
    return mpmath.mpmathify(complex(x)) if isinstance(x, complex) else mpmath.mpmathify(x)


def _fmt(v) -> str:
    return mpmath.nstr(v, 20)


_POLE_ERRORS = (ZeroDivisionError, ValueError, OverflowError, ArithmeticError)


def _finite(v) -> bool:
    try:
        return bool(mpmath.isfinite(v))
    except (TypeError, ValueError):
        return False


#: relations are solved in closed form (quartics at most) for the numeric screen
MAX_RELATION_DEGREE = 4


@cache
def _generic_roots(degree: int) -> tuple[tuple, list]:
    """The roots of ``c0 x^d + c1 x^(d-1) + ... + cd`` in closed form, as ``sympy.solve`` writes them (tested).

    The quadratic is written out and the rest come from ``sympy.roots`` (Cardano, Ferrari):
    ``sympy.solve`` would reach the same expressions through ``simplify``, which costs a
    tenth of a second and imports ``sympy.physics`` in every process that runs the screen.
    """
    a = sp.symbols(f"_c0:{degree + 1}")
    if degree == 2:
        disc = sp.sqrt(a[1] ** 2 - 4 * a[0] * a[2])
        return a, [(-a[1] - disc) / (2 * a[0]), (-a[1] + disc) / (2 * a[0])]
    x = sp.Dummy("x")
    return a, sp.roots(sp.Poly(sum(a[i] * x ** (degree - i) for i in range(degree + 1)), x), multiple=True)


def _roots(rel, s) -> list:
    """The roots of a polynomial relation in ``s``, by the closed form of a generic polynomial.

    The coefficients are substituted into the generic solution instead of handing
    ``rel`` to ``sympy.solve``, which would factor them -- and take forever on a
    coefficient like ``exp(1000001 q / 1000000)`` (a polynomial of degree 1000001 in
    ``exp(q / 1000000)``).
    """
    poly = sp.sympify(rel).as_poly(s)
    if poly is None or not 1 <= poly.degree() <= MAX_RELATION_DEGREE:
        raise ValueError(f"relation {rel} = 0 is not a polynomial of degree 1..{MAX_RELATION_DEGREE} in {s}")
    a, generic = _generic_roots(poly.degree())
    coeffs = dict(zip(a, poly.all_coeffs()))
    return [r.xreplace(coeffs) for r in generic]


def _solve_order(relations, known):
    """Order the constrained symbols so that each one's roots use only known symbols."""
    known = set(known)
    todo = dict(relations)
    order = []
    while todo:
        progress = False
        for s, rel in list(todo.items()):
            roots = _roots(rel, s)
            if not roots:
                raise ValueError(f"cannot solve relation {rel} = 0 for {s}")
            if all(r.free_symbols <= known for r in roots):
                order.append((s, roots))
                known.add(s)
                del todo[s]
                progress = True
        if not progress:
            raise ValueError("cyclic or unsolvable relations: " + ", ".join(map(str, todo)))
    return order


def screen(lhs, rhs, relations, digits, points, seed, fixed):
    """Evaluate ``lhs - rhs`` at ``points`` admissible random points.

    A point is admissible when both sides evaluate to finite numbers (poles,
    ``nan`` and evaluation errors such as a gamma-function pole are resampled,
    up to ``6*points + 10`` draws in all).  Returns ``(ok, worst_residual,
    digits_agreeing, worst_point, points)``.
    """
    syms = set(lhs.free_symbols) | set(rhs.free_symbols)
    for r in relations.values():
        syms |= r.free_symbols
    free = sorted(syms, key=lambda s: s.name)
    free = [s for s in free if s not in relations and s not in fixed]
    rng = random.Random(seed)
    base = free + list(fixed)
    order = _solve_order(relations, base)
    constrained = [s for s, _ in order]
    rel_solvers = []
    for k, (_s, roots) in enumerate(order):
        rel_solvers.append([plain_lambdify(base + constrained[:k], r) for r in roots])
    args = base + constrained
    f_l = plain_lambdify(args, lhs)
    f_r = plain_lambdify(args, rhs)
    worst = (mpmath.mpf(-1), None)
    pts = []
    tol = mpmath.mpf(10) ** (-(digits - 8))
    attempts = 0
    with mpmath.workdps(digits + 10):
        while len(pts) < points and attempts < 6 * points + 10:
            attempts += 1
            allv = [sample_symbol(s, rng) for s in free] + [_as_mp(v) for v in fixed.values()]
            try:
                for sols in rel_solvers:
                    allv.append(sols[rng.randrange(len(sols))](*allv))
                lv, rv = f_l(*allv), f_r(*allv)
            except _POLE_ERRORS:
                continue
            if not (_finite(lv) and _finite(rv)):
                continue  # a pole or an undefined value: not a test of the identity
            scale = max(abs(lv), abs(rv), mpmath.mpf(1))
            res = abs(lv - rv) / scale
            point = {str(s): _fmt(v) for s, v in zip(args, allv)}
            pts.append(point)
            if res > worst[0]:
                worst = (res, point)
    if not pts:
        raise ValueError(f"no admissible sample point in {attempts} draws "
                         "(every point hit a pole or an undefined value)")
    res, point = worst
    ok = res <= tol
    digits_agree = float(-mpmath.log10(res)) if res > 0 else float(digits)
    return bool(ok), float(res), min(digits_agree, float(digits)), point, pts
