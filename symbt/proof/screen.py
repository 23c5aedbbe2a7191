"""The numeric screen: evaluation at random admissible points (see :mod:`symbt.proof`)."""
from __future__ import annotations

import random
import threading
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any

import mpmath
import sympy as sp

from .lambdify import plain_lambdify
from .magnitude import EVALUATION_ERRORS, floored_scale, magnitude, size_or_inf
from .relations import relation_poly
from .verdict import SAFETY

__all__ = ["screen", "sample_symbol", "ScreenResult", "PointCheck", "tracked_quad", "high_precision"]


#: the fewest digits the screen decides at: its tolerance 10**-(digits - 8) is then 0.1; at 8 digits or fewer it
#: would be 1 or more, which any two numbers of equal sign meet (a relative residual is at most 2)
MIN_DIGITS = 9


def sample_symbol(sym: sp.Symbol, rng: random.Random) -> mpmath.mpf | mpmath.mpc:
    """A random value for ``sym`` honouring its SymPy assumptions.

    ``integer`` (with ``even``/``odd``, sign; a uniform draw from 1..9, -9..-1 or -9..9 of the
    wrong parity moves to its neighbour above for ``odd``, below for ``even``, and the other way
    at the end of the range), ``positive``/``nonnegative``,
    ``negative``/``nonpositive``, ``real`` (either sign), ``imaginary`` (purely
    imaginary, either sign); anything else is sampled complex with imaginary
    parts up to about 4 in size (beyond pi, so branch cuts of ``log`` are hit).
    A non-integer draw's magnitude (the real part's; the imaginary part's for ``imaginary``)
    lies in ``[0.3, 3 + 1/7)``; a complex draw's imaginary part in ``[-4, 4 + 1/11)``.

    >>> v = sample_symbol(sp.Symbol("a", negative=True), random.Random(0))
    >>> -3 - 1 / 7 < v <= -0.3
    True
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


def _as_mp(x: object) -> mpmath.mpf | mpmath.mpc:
    if isinstance(x, (mpmath.mpf, mpmath.mpc)):
        return x
    return mpmath.mpmathify(complex(x)) if isinstance(x, complex) else mpmath.mpmathify(x)


def _fmt(v: mpmath.mpf | mpmath.mpc) -> str:
    return mpmath.nstr(v, 20)


def _finite(v: object) -> bool:
    try:
        return bool(mpmath.isfinite(v))
    except (TypeError, ValueError):
        return False


#: relations are solved in closed form (quartics at most) for the numeric screen
MAX_RELATION_DEGREE = 4


@cache
def _generic_roots(degree: int) -> tuple[tuple[sp.Symbol, ...], list[sp.Expr]]:
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


def _roots(rel: sp.Expr, s: sp.Symbol) -> list[sp.Expr]:
    """The roots of a polynomial relation in ``s``, by the closed form of a generic polynomial.

    The coefficients are substituted into the generic solution instead of handing
    ``rel`` to ``sympy.solve``, which would factor them -- and take forever on a
    coefficient like ``exp(1000001 q / 1000000)`` (a polynomial of degree 1000001 in
    ``exp(q / 1000000)``).
    """
    poly = relation_poly(rel, s, MAX_RELATION_DEGREE)
    a, generic = _generic_roots(poly.degree())
    coeffs = dict(zip(a, poly.all_coeffs()))
    return [r.xreplace(coeffs) for r in generic]


def _solve_order(relations: Mapping[sp.Symbol, sp.Expr],
                 known: Iterable[sp.Symbol]) -> list[tuple[sp.Symbol, list[sp.Expr]]]:
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


#: the quadrature errors of the evaluation under way (``None`` when nobody is listening)
_QUAD_LOG = threading.local()


# Any: mpmath.quad's own signature (an integrand of any arity, intervals, options), passed through
def tracked_quad(f: Callable[..., Any], *intervals: Any, **kw: Any) -> Any:
    """``mpmath.quad`` that also records its own error estimate for the screen.

    ``sympy.lambdify`` prints an unevaluated ``Integral`` as ``quad(lambda t: ..., (a, b))``;
    the screen's functions call this instead, so a quadrature that has not converged
    at the working precision (its estimate says so) is counted in the evaluation's error.
    The pair recorded, ``(|value|, |error|)``, is rounded to the working precision (mpmath
    computes the quadrature with guard bits).

    >>> import mpmath
    >>> round(float(tracked_quad(lambda t: t**2, (0, 1))), 12)
    0.333333333333
    """
    log = getattr(_QUAD_LOG, "errors", None)
    if kw.get("error") or log is None or getattr(_QUAD_LOG, "depth", 0):
        # an inner quadrature of a nested integral: the outer one's estimate covers it
        return mpmath.quad(f, *intervals, **kw)
    _QUAD_LOG.depth = 1
    try:
        value, err = mpmath.quad(f, *intervals, error=True, **kw)
    finally:
        _QUAD_LOG.depth = 0
    log.append((abs(value), abs(err)))
    return value


#: the lambdify namespace of the screen: mpmath, with the quadrature that reports its error
_NAMESPACE = {"quad": tracked_quad}
_MODULES = [_NAMESPACE, "mpmath"]


def _quad_error(value: mpmath.mpf | mpmath.mpc, errors: list[tuple[mpmath.mpf, mpmath.mpf]]) -> Any:
    """The error a side inherits from its quadratures: the larger of their absolute errors summed
    (a sum of integrals) and their relative errors summed times the side (a product or quotient)."""
    if not errors:
        return mpmath.mpf(0)
    absolute = mpmath.fsum(e for _, e in errors)
    relative = mpmath.fsum(e / v for v, e in errors if v)   # an integral that is 0 counts by its absolute error
    return max(absolute, abs(value) * relative)


def _evaluate(f: Callable[..., Any], allv: Sequence[object]) -> tuple[Any, Any]:
    """``f(*allv)`` and the error of the quadratures it ran."""
    _QUAD_LOG.errors = []
    try:
        v = f(*allv)
        return v, _quad_error(v, _QUAD_LOG.errors)
    finally:
        _QUAD_LOG.errors = None


def _scale(lv: Any, rv: Any, size: Callable[[], Any]) -> Any:
    """What a point's difference ``lhs - rhs`` is measured against: ``max(|lhs|, |rhs|)``, floored below 1 by the
    sides' terms' size ``size()`` (:func:`~symbt.proof.magnitude.floored_scale`)."""
    return floored_scale(max(abs(lv), abs(rv)), size)


def _sizer(f_size: Callable[..., Any], allv: Sequence[object]) -> Callable[[], Any]:
    """The sides' terms' size at ``allv`` (:func:`~symbt.proof.magnitude.size_or_inf`), when asked; its
    quadratures are not counted in the error again."""
    def size() -> Any:
        log, _QUAD_LOG.errors = getattr(_QUAD_LOG, "errors", None), None
        try:
            return size_or_inf(lambda: f_size(*allv))
        finally:
            _QUAD_LOG.errors = log
    return size


@dataclass
class PointCheck:
    """The difference of the sides at one point, and how far the evaluation can be trusted.

    ``residual`` is ``|lhs - rhs| / scale`` (from the higher precision when there is one), ``scale`` being
    ``max(|lhs|, |rhs|, min(1, size of the terms))`` (:func:`_scale`; a point where it is 0 has residual 0);
    ``error`` the estimated error of that residual (quadrature error estimates, plus -- once the point is
    re-evaluated -- how much the two working precisions' differences ``lhs - rhs`` differ, over the scale,
    and the rounding level).  Its repr shows ``residual``, ``error``, ``point`` and ``rechecked``; the raw
    ``values``, ``roots``, ``diff`` (``lhs - rhs``) and ``scale`` kept for the re-evaluation are not shown.
    """

    residual: Any
    error: Any
    point: dict[str, str]
    values: list[Any] = field(repr=False, default_factory=list)
    roots: list[int] = field(repr=False, default_factory=list)
    rechecked: bool = False
    diff: Any = field(repr=False, kw_only=True)         # no defaults: the re-evaluation reads both
    scale: Any = field(repr=False, kw_only=True)


@dataclass
class ScreenResult:
    """What the screen found (see :func:`screen`).

    ``status`` is ``"verified"``, ``"false"`` or ``"inconclusive"``; ``residual`` the worst
    relative residual (at the counterexample when false); ``error`` the estimated
    evaluation error there; ``digits`` the digits that agree *and* are trustworthy;
    ``point`` the counterexample (false) or the point that could not be decided
    (inconclusive); ``rechecked`` how many points were re-evaluated at the higher precision
    (``high_digits``).  ``ok`` is true only when verified.

    >>> ScreenResult("inconclusive", 1e-23, 1e-21, 21.0, {"m": "0.99"}, [{"m": "0.99"}]).ok
    False
    """

    status: str
    residual: float
    error: float
    digits: float
    point: dict[str, str] | None
    points: list[dict[str, str]]
    rechecked: int = 0
    high_digits: int = 0

    @property
    def ok(self) -> bool:
        return self.status == "verified"


def high_precision(digits: int) -> int:
    """The second working precision of the screen: twice the digits asked for, plus guard digits.

    >>> high_precision(30)
    70
    """
    return 2 * digits + 10


def _recheck(pc: PointCheck, f_l: Callable[..., Any], f_r: Callable[..., Any], f_size: Callable[..., Any],
             rel_solvers: Sequence[Sequence[Callable[..., Any]]], fixed: Mapping[sp.Symbol, Any], n_free: int,
             digits: int) -> None:
    """Evaluate the point again at :func:`high_precision`; the two evaluations' difference
    (plus the quadratures' own estimates and the rounding level) is the error of the first."""
    hi = high_precision(digits)
    pc.rechecked = True
    with mpmath.workdps(hi + 10):
        allv = list(pc.values[:n_free]) + [_as_mp(v) for v in fixed.values()]
        try:
            for sols, k in zip(rel_solvers, pc.roots):
                allv.append(sols[k](*allv))
            (lv, el), (rv, er) = _evaluate(f_l, allv), _evaluate(f_r, allv)
        except EVALUATION_ERRORS:
            pc.error = mpmath.inf
            return
        if not (_finite(lv) and _finite(rv)):
            pc.error = mpmath.inf
            return
        # the two differences lhs - rhs compared absolutely, over the new scale (the first one's if the new is 0):
        # noise that swamped sides below the floor is an error, never a residual
        scale = _scale(lv, rv, _sizer(f_size, allv)) or pc.scale
        if not scale:   # both evaluations: every side and term exactly 0
            pc.residual = pc.error = mpmath.mpf(0)
            return
        diff = lv - rv
        pc.residual = abs(diff) / scale
        pc.error = abs(diff - pc.diff) / scale + (el + er) / scale + mpmath.mpf(10) ** (-(digits + 2))


def screen(lhs: sp.Expr, rhs: sp.Expr, relations: Mapping[sp.Symbol, sp.Expr], digits: int, points: int, seed: int,
           fixed: Mapping[sp.Symbol, Any], *, recheck: bool = True) -> ScreenResult:
    """Evaluate ``lhs - rhs`` at ``points`` admissible random points, knowing the evaluation's error.

    A point is admissible when both sides evaluate to finite numbers (poles,
    ``nan`` and evaluation errors such as a gamma-function pole are resampled,
    up to ``6*points + 10`` draws in all).  Each point is evaluated at ``digits + 10``
    working digits; quadratures (a SymPy ``Integral``) report their own error estimate.

    The tolerance is ``10**-(digits - 8)``.  A point is decided at once when the
    first evaluation is clear: the sides agree to all ``digits`` with trustworthy
    quadratures.  Otherwise (``recheck``) the point is evaluated again at
    :func:`high_precision`, and the difference of the two evaluations estimates
    the first one's error.  Then a point *holds* when its residual and its error
    are both below the tolerance; it is a *counterexample* when its residual is
    above the tolerance and above ``SAFETY`` times its error (both strictly); anything else
    cannot be told apart from noise (``inconclusive``).  Candidates for a
    counterexample are re-checked worst first, and the first confirmed one is
    the counterexample (one extra evaluation for a clearly false identity).

    ``recheck=False`` keeps the first evaluation only (its error is then what the
    quadratures report): for the residual of a statement already known to be
    false, reported for information.

    >>> x = sp.Symbol("x", real=True)
    >>> r = screen(sp.sin(2 * x), 2 * sp.sin(x) * sp.cos(x), {}, 30, 4, 1, {})
    >>> r.status, r.digits, r.rechecked
    ('verified', 30.0, 0)
    >>> r = screen(sp.sin(x), sp.sin(x) * (1 + sp.Rational(1, 10**15)), {}, 30, 4, 1, {})
    >>> r.status, r.residual > 1e-16, r.rechecked       # one re-check confirms the counterexample
    ('false', True, 1)
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
        rel_solvers.append([plain_lambdify(base + constrained[:k], r, _MODULES) for r in roots])
    args = base + constrained
    f_l = plain_lambdify(args, lhs, _MODULES)
    f_r = plain_lambdify(args, rhs, _MODULES)
    f_size = plain_lambdify(args, [magnitude(lhs), magnitude(rhs)], _MODULES)
    checks: list[PointCheck] = []
    tol = mpmath.mpf(10) ** (-(digits - 8))
    clear = mpmath.mpf(10) ** (-digits)
    attempts = 0
    with mpmath.workdps(digits + 10):
        while len(checks) < points and attempts < 6 * points + 10:
            attempts += 1
            allv = [sample_symbol(s, rng) for s in free] + [_as_mp(v) for v in fixed.values()]
            picks = []
            try:
                for sols in rel_solvers:
                    k = rng.randrange(len(sols))
                    picks.append(k)
                    allv.append(sols[k](*allv))
                (lv, el), (rv, er) = _evaluate(f_l, allv), _evaluate(f_r, allv)
            except EVALUATION_ERRORS:
                continue
            if not (_finite(lv) and _finite(rv)):
                continue  # a pole or an undefined value: not a test of the identity
            scale = _scale(lv, rv, _sizer(f_size, allv))
            point = {str(s): _fmt(v) for s, v in zip(args, allv)}
            # scale 0: both sides and every term exactly 0 -- agrees (its quadratures' error counted as it is)
            rel, err = (abs(lv - rv) / scale, (el + er) / scale) if scale else (mpmath.mpf(0), el + er)
            checks.append(PointCheck(rel, err, point, allv, picks, diff=lv - rv, scale=scale))
    if not checks:
        raise ValueError(f"no admissible sample point in {attempts} draws "
                         "(every point hit a pole or an undefined value)")
    pts = [c.point for c in checks]
    n_free = len(free)

    def redo(pc: PointCheck) -> None:
        if recheck and not pc.rechecked:
            _recheck(pc, f_l, f_r, f_size, rel_solvers, fixed, n_free, digits)

    def counterexample(pc: PointCheck) -> bool:
        return bool(pc.residual > tol and pc.residual > SAFETY * pc.error)

    # counterexamples first: the worst candidate that survives its re-check decides
    for pc in sorted((c for c in checks if c.residual > tol), key=lambda c: c.residual, reverse=True):
        redo(pc)
        if counterexample(pc):
            return _result("false", pc, pts, checks, digits)
    undecided = []
    for pc in checks:
        if pc.residual <= clear and pc.error <= clear:
            continue  # agrees to every digit asked for, with trustworthy quadratures
        redo(pc)
        if counterexample(pc):
            return _result("false", pc, pts, checks, digits)
        if not (pc.residual <= tol and pc.error <= tol):
            undecided.append(pc)
    if undecided:
        worst = max(undecided, key=lambda c: max(c.residual, c.error))
        return _result("inconclusive", worst, pts, checks, digits)
    worst = max(checks, key=lambda c: c.residual)
    return _result("verified", worst, pts, checks, digits)


def _trusted_digits(pc: PointCheck, digits: int) -> float:
    worst = max(pc.residual, pc.error)
    if not worst:
        return float(digits)
    if not mpmath.isfinite(worst):
        return 0.0
    return max(0.0, min(float(-mpmath.log10(worst)), float(digits)))


def _result(status: str, pc: PointCheck, pts: list[dict[str, str]], checks: Sequence[PointCheck],
            digits: int) -> ScreenResult:
    if status == "verified":
        dig = min(_trusted_digits(c, digits) for c in checks)
    elif status == "false":
        # as before: the digits to which the sides agree at the counterexample
        dig = min(float(-mpmath.log10(pc.residual)), float(digits))
    else:
        dig = _trusted_digits(pc, digits)
    return ScreenResult(status, float(pc.residual), float(pc.error), dig,
                        None if status == "verified" else pc.point, pts,
                        rechecked=sum(1 for c in checks if c.rechecked), high_digits=high_precision(digits))
