r"""Certified orbits: midpoints plus rigorous error bounds from Arb ball arithmetic.

By default (``method="auto"``) the Lohner-type method of :mod:`.lohner` runs: its radius grows
polynomially, not exponentially (docs/certified.md); where its Jacobian enclosure is not finite the plain
ball path described below runs instead (``info["method"]`` says which ran).  ``method="ball"`` forces the
plain path.

:func:`certified_orbit` (also ``bt_orbit(..., certified=True)``) runs
:func:`~symbt.numeric.core.step.step_core` on python-flint ``arb`` balls
(:data:`~symbt.numeric.multiprec.arb.ARB_CERTAIN`).  The input is taken *exactly*:
mpmath numbers, Python ints and floats are exact binary numbers, decimal
strings (``"0.9"``) become balls that contain the decimal value, so the result
encloses the exact orbit of the given input.

* Existence (``|tr L(lam_i)| > 2``, ``Etilde_j > 0``) must hold on the whole
  ball; a ball that certainly violates it raises :class:`NoRealMapError`, one
  that straddles the boundary makes the working precision go up; at
  ``max_prec`` :class:`NumericRangeError` is raised (the decision cannot be
  certified).  Accuracy-only choices use midpoints (both alternatives enclose
  the same exact value).
* Ball arithmetic loses correlations (the wrapping effect), so the radius
  grows *exponentially* with the number of steps -- about 2 bits (0.6 digits)
  per step for the paper's example -- although the true error propagation of
  this integrable map is polynomial.  The working precision is therefore
  chosen automatically: a first pass at ``mp.prec + 32`` bits measures the
  growth rate; if the radii exceed the target the orbit is recomputed at the
  precision the measured rate requires (about ``2 n + target bits``).
  The rule (``method="ball"``): with ``e_k = max_i log2(rad_i / target_i)``
  after step ``k`` of a pass at ``p`` bits (which stops once ``e_k > 8``),
  the first and last finite ``e`` at steps ``i0 < i1`` give the rate
  ``g = max(0, (e_{i1} - e_{i0}) / (i1 - i0))`` and the next pass runs at
  ``floor(p + e_{i1} + 1.15 g (n - i1) + 4 g + 24) + 1`` bits; with only one
  finite ``e`` (exact input and a pass that stopped after its first step)
  at ``floor(p + e + 24) + 1``; never below ``p + floor(p/4) + 32``
  (``paths.ball_prec`` checks the one-excess case).
* Target: every radius ``<= tol`` (absolute) or, by default, ``<= 2**-mp.prec
  * max(1, |x|)`` (one unit of the returned precision).  The returned radius
  adds the rounding of the midpoint to ``mp.prec`` bits, so it bounds
  ``|returned midpoint - exact value|``.

Measured (paper's example, ``tests/test_numeric_certified.py``,
``python -m symbt.benchmarks.numeric_timings``): see ``docs/numeric.md``.

Example
-------
>>> import mpmath
>>> from symbt.numeric import bt_orbit
>>> with mpmath.workdps(30):
...     P, Q, Pr, Qr = bt_orbit(["-20", "10", "1"], ["1", "0", "0.9"], 10, 5, 20, certified=True, every=10)
...     print(mpmath.nstr(P[-1][0], 12), float(max(Pr[-1] + Qr[-1])) < 1e-29)
8.38673489171 True
"""

from __future__ import annotations

import math
import numbers
from typing import TYPE_CHECKING, get_args

import mpmath
import numpy as np

from ..core.context import MPValue
from ..core.errors import InvalidInputError, MissingDependencyError, NumericRangeError
from ..core.problem import CertifiedMethod
from ..core.step import step_core
from ..float64.kernels import stored_steps
from .runners import MPOrbit, flint_available

if TYPE_CHECKING:
    from flint import arb

    from ..core.inputs import ParamLike, StateLike

__all__ = ["certified_orbit", "DEFAULT_MAX_PREC", "CERTIFIED_METHODS", "CertifiedMethod"]

#: precision cap (bits) of the automatic precision increase
DEFAULT_MAX_PREC = 1 << 16
#: ``method=`` values of :func:`certified_orbit`
CERTIFIED_METHODS: tuple[CertifiedMethod, ...] = get_args(CertifiedMethod)
_MARGIN = 24          # extra bits beyond the estimate
_ATTEMPTS = 8


def _ball(x: object, name: str) -> arb:
    """An exact input value as an Arb ball at the current flint precision."""
    from flint import arb

    if isinstance(x, (bool, np.bool_)):
        raise InvalidInputError("%s: booleans are not numbers here" % name)
    if isinstance(x, (complex, np.complexfloating, mpmath.mpc)):
        raise InvalidInputError("%s: complex input is not supported (the real map takes real states)" % name)
    if isinstance(x, (int, np.integer)):
        return arb(int(x))
    if isinstance(x, numbers.Rational):                       # fractions.Fraction
        return arb(int(x.numerator)) / arb(int(x.denominator))
    if isinstance(x, (float, np.floating)):
        if not math.isfinite(x):
            raise InvalidInputError("%s contains a non-finite value" % name)
        return arb(float(x))
    if isinstance(x, mpmath.mpf):
        if not mpmath.isfinite(x):
            raise InvalidInputError("%s contains a non-finite value" % name)
        return arb(x)
    if isinstance(x, str):
        try:
            b = arb(x.strip())
        except (ValueError, TypeError) as exc:
            raise InvalidInputError("%s: cannot parse %r as a decimal number" % (name, x)) from exc
        if not b.is_finite():
            raise InvalidInputError("%s contains a non-finite value" % name)
        return b
    raise InvalidInputError("%s: unsupported number type %s (use mpf, int, float, Fraction or a decimal "
                            "string)" % (name, type(x).__name__))


def _state(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike) -> tuple[list[arb], list[arb], arb, arb]:
    seqs = []
    for name, v in (("p", p), ("q", q)):
        if isinstance(v, np.ndarray):
            v = v.tolist()
        if not isinstance(v, (list, tuple)) or any(isinstance(x, (list, tuple, np.ndarray)) for x in v):
            raise InvalidInputError("%s must be a flat sequence (one state) for certified orbits" % name)
        seqs.append([_ball(x, name) for x in v])
    P, Q = seqs
    if len(P) != len(Q) or len(P) < 2:
        raise InvalidInputError("p and q need equal lengths N >= 2, got %d and %d" % (len(P), len(Q)))
    for name, v in (("lam0", lam0), ("mu", mu)):
        if isinstance(v, (list, tuple, np.ndarray)):
            raise InvalidInputError("%s must be a scalar for certified orbits" % name)
    return P, Q, _ball(lam0, "lam0"), _ball(mu, "mu")


def _excess(xs: list[arb], tol: float | None, out_prec: int) -> float:
    """``max log2(rad / target)`` over the balls ``xs`` (``-inf`` if all are exact)."""
    worst = -math.inf
    for x in xs:
        r = float(x.rad())
        if r == 0.0:
            continue
        if tol is None:
            m = abs(float(x.mid()))
            t = math.ldexp(max(1.0, m), -out_prec)
        else:
            t = tol
        worst = max(worst, math.log2(r) - math.log2(t) if math.isfinite(r) else math.inf)
    return worst


def _run(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, n: int, branch: int, keep: set[int], prec: int,
         tol: float | None, out_prec: int) -> tuple[bool, list[tuple[list[arb], list[arb]]], list[float], int]:
    """One pass at ``prec`` bits; returns ``(ok, stored balls, excess history, steps done)``."""
    from .arb import ARB_CERTAIN, Uncertain, flint_prec

    with flint_prec(prec):
        P, Q, l0, m = _state(p, q, lam0, mu)
        stored = [(P, Q)]
        hist = [_excess(P + Q, tol, out_prec)]
        for i in range(1, n + 1):
            try:
                P, Q, _ = step_core(ARB_CERTAIN, P, Q, l0, m, branch)
            except Uncertain:
                return False, stored, hist, i - 1
            if not ARB_CERTAIN.isfinite_all(P + Q):
                return False, stored, hist, i - 1
            e = _excess(P + Q, tol, out_prec)
            hist.append(e)
            if i in keep:
                stored.append((P, Q))
            if e > 8:          # already too wide: stop early, the next pass uses the measured growth
                return False, stored, hist, i
    return max(hist) <= 0, stored, hist, n


def _next_prec(prec: int, hist: list[float], done: int, n: int) -> int:
    """Precision for the next pass from the measured growth of the radius (bits per step)."""
    finite = [(i, e) for i, e in enumerate(hist) if math.isfinite(e)]
    extra = 0.0
    if len(finite) >= 2:
        (i0, e0), (i1, e1) = finite[0], finite[-1]
        rate = max(0.0, (e1 - e0) / max(1, i1 - i0))
        # the growth rate creeps up along the orbit (paper's example: 1.7 bits/step early, 2.5 later)
        extra = e1 + 1.15 * rate * (n - i1) + 4 * rate + _MARGIN
    elif finite:
        extra = finite[-1][1] + _MARGIN
    return max(int(prec + extra) + 1, prec + prec // 4 + 32)


def _upper(x: arb) -> MPValue:
    """An mpf upper bound (53-bit, rounded up) of the non-negative exact Arb number ``x``."""
    man, exp = x.man_exp()
    return mpmath.mpf(mpmath.libmp.from_man_exp(int(man), int(exp), 53, "u"))


def _output(balls: list[arb]) -> tuple[list[MPValue], list[MPValue]]:
    from flint import arb

    mids, rads = [], []
    for b in balls:
        mid = mpmath.mpf(b.mid())
        err = (arb(b.rad()) + abs(b.mid() - arb(mid))).abs_upper()
        mids.append(mid)
        rads.append(_upper(err))
    return mids, rads


def _outputs(stored: list[tuple[list[arb], list[arb]]]) -> tuple[MPOrbit, MPOrbit, MPOrbit, MPOrbit]:
    Pm, Qm, Pr, Qr = [], [], [], []
    for Pb, Qb in stored:
        a, b = _output(Pb)
        c, d = _output(Qb)
        Pm.append(a)
        Pr.append(b)
        Qm.append(c)
        Qr.append(d)
    return Pm, Qm, Pr, Qr


def certified_orbit(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, n: int, *, branch: int = 1,
                    every: int = 1, tol: float | MPValue | None = None, prec: int | None = None,
                    max_prec: int = DEFAULT_MAX_PREC, info: dict[str, object] | None = None,
                    method: CertifiedMethod = "auto") -> tuple[MPOrbit, MPOrbit, MPOrbit, MPOrbit]:
    """Certified ``n``-step orbit: ``(P, Q, P_rad, Q_rad)``, lists over the stored states.

    ``P[i][j]`` is an mpf at the current ``mp.prec`` and
    ``|P[i][j] - p_exact| <= P_rad[i][j]`` rigorously (same for ``Q``), where
    ``p_exact`` is the exact orbit of the exact input (see module docstring).
    ``tol``: absolute radius target (default: one unit in the last place of
    each returned value, relative to ``max(1, |x|)``); ``prec``: first working
    precision (bits, default ``mp.prec + 32``); ``max_prec``: cap of the
    automatic increase; ``info``: a dict that receives ``passes`` (the working
    precisions tried, bits), ``prec`` (the one that succeeded), ``method``
    (which ran) and, for ``"lohner"``, ``growth`` (the radius growth law,
    :func:`~symbt.numeric.lohner.growth_law`), or ``fallback`` (why the plain
    path ran instead).  ``method``: ``"auto"`` (the Lohner method of
    :mod:`~symbt.numeric.lohner`, sharp for long orbits; the plain ball path
    where its Jacobian enclosure is not finite, e.g. at a degenerate
    eigenvector), ``"lohner"`` (no fallback) or ``"ball"`` (plain ball
    arithmetic only).  Stored states as in :func:`~symbt.numeric.bt_orbit`.

    Raises :class:`NoRealMapError` (certainly no real map),
    :class:`NumericRangeError` (not certifiable below ``max_prec``),
    :class:`InvalidInputError`, :class:`MissingDependencyError` (no python-flint).

    >>> with mpmath.workdps(20):
    ...     P, Q, Pr, Qr = certified_orbit([-20, 10, 1], [1, 0, "0.9"], 10, 5, 1)
    >>> mpmath.nstr(P[1][0], 10), float(Pr[1][0]) < 1e-19
    ('-19.99656766', True)
    """
    from ..core.inputs import check_branch, check_steps

    if not flint_available():
        raise MissingDependencyError("certified orbits need python-flint: pip install 'symbt[certified]'")
    branch = check_branch(branch)
    n, every = check_steps(n, every)
    if tol is not None:
        tol = float(tol)
        if not tol > 0 or not math.isfinite(tol):
            raise InvalidInputError("tol must be a positive finite number, got %r" % (tol,))
    if method not in CERTIFIED_METHODS:
        raise InvalidInputError("method must be one of %s, got %r" % (CERTIFIED_METHODS, method))
    out_prec = mpmath.mp.prec
    keep = set(stored_steps(n, every))
    passes: list[int] = []
    info = info if info is not None else {}
    info["passes"] = passes
    if method != "ball":
        from .lohner import lohner_certified

        try:
            stored, info["prec"], info["growth"] = lohner_certified(
                lambda: _state(p, q, lam0, mu), n, branch, keep, lambda xs: _excess(xs, tol, out_prec),
                out_prec if tol is None else max(1, math.ceil(-math.log2(tol))), prec, max_prec, passes)
            info["method"] = "lohner"
            return _outputs(stored)
        except ArithmeticError as exc:      # JacobianBlowup, NumericRangeError, an overflow: the plain path decides
            if method == "lohner":
                raise NumericRangeError("certified orbit (Lohner): %s" % exc) from exc
            info["fallback"] = str(exc)
    info["method"] = "ball"
    work = int(prec) if prec is not None else out_prec + 32
    for _ in range(_ATTEMPTS):
        if work > max_prec:
            break
        passes.append(work)
        ok, stored, hist, done = _run(p, q, lam0, mu, n, branch, keep, work, tol, out_prec)
        if ok:
            info["prec"] = work
            return _outputs(stored)
        work = _next_prec(work, hist, done, n)
    raise NumericRangeError("certified orbit: the enclosure could not be certified below max_prec = %d bits "
                            "(a decision on the boundary of existence, a degenerate eigenvector, or too many "
                            "steps for the target radius)" % max_prec)



