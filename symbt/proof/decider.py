"""Deciding identities: exact reduction first, high-precision random evaluation as screen.

``sympy.simplify`` is neither fast nor a decision procedure: it may return an
unsimplified expression that is in fact zero.  The claims of symbt are decided
here instead, in this order:

1. **Exact reduction.**  Hyperbolic functions are rewritten as exponentials,
   and every ``exp(a_1 s_1 + ... + a_k s_k)`` with *rational* ``a_i`` -- in any
   spelling: ``E**u``, ``sqrt(exp(u))`` and ``exp(u)**r`` for real ``u``,
   products of exponentials -- becomes the monomial
   ``S_1**(a_1 d_1) ... S_k**(a_k d_k)`` in fresh *positive* symbols
   ``S_i = exp(s_i/d_i)``, ``d_i`` the common denominator of the coefficients of
   ``s_i`` (for the Toda lattice ``E_j = e^{q_j}``, or ``e^{q_j/2}`` with
   half-exponents; :mod:`.exponentials`).  The tree is read node by node, so
   the result does not depend on how SymPy auto-combined the exponentials.  The
   difference ``lhs - rhs`` is then a rational function; it is brought to one
   fraction with ``together``/``cancel`` and its numerator is reduced modulo the
   user's algebraic relations (e.g. ``eta**2 = mu**2 + w``) by polynomial
   remainder in the constrained symbol.  A zero remainder *proves* the
   identity.  This step is skipped when the difference is not rational after
   the rewriting (logarithms, ``acosh``, radicals of non-symbols, exponents
   that are not rational-linear such as ``exp(q1*q2)`` or ``exp(sqrt(2)*q)``).
2. **Numeric screen.**  The difference is evaluated with mpmath at ``digits``
   significant digits at ``points`` random points drawn according to the SymPy
   assumptions of each symbol (a ``real`` symbol may be negative, a symbol
   without assumptions is sampled complex) and satisfying the relations (a
   constrained symbol is set to a root of its relation, with a random sign
   for square roots; relations may build on each other).  Points where a side
   is not finite (poles, ``nan``, evaluation errors) are resampled.  If every
   relative residual is below ``10**-(digits-8)`` the identity is *verified
   numerically*; otherwise it is *false* and the worst point is returned as a
   counterexample with its residual.  The screen knows its own error: a point
   that is not clearly decided at once is evaluated again at about twice the
   precision, and quadratures (a SymPy ``Integral``) report their error
   estimates; a residual within the evaluation's error is never a
   counterexample -- the verdict is then *inconclusive* ("cannot tell at this
   precision") -- and the digits reported are those that agree *and* can be
   trusted (see :func:`symbt.proof.screen.screen`).

The result says which of the two decided.  A difference that is a nonzero
rational function (no relations, no ``fixed`` values) is *false* even when it
is numerically tiny (``x + 10**-60`` vs ``x``): a nonzero rational function
cannot vanish identically.  A side containing ``nan``/``zoo``/``oo`` is *false*.

Example
-------
>>> import sympy as sp
>>> from symbt.proof import decide
>>> eta, mu, w = sp.symbols("eta mu w", real=True)
>>> d = decide((eta - mu) * (eta + mu), w, relations={eta: eta**2 - mu**2 - w})
>>> d.verdict, d.exact
('proved', True)
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp
from sympy.core.relational import Relational
from sympy.logic.boolalg import BooleanAtom

from .exact import exact_zero
from .screen import MIN_DIGITS, ScreenResult, screen
from .verdict import SAFETY, Verdict

__all__ = ["decide"]


def _undefined(expr: sp.Expr) -> bool:
    """A side that is ``nan``/``zoo`` somewhere, or infinite outside the limits of an integral.

    (An infinite limit of an ``Integral`` is a value mpmath's quadrature takes; a ``Sum`` to
    infinity is not something the screen can evaluate, and stays undefined.)

    >>> t = sp.Symbol("t")
    >>> _undefined(sp.Integral(sp.exp(-t**2), (t, -sp.oo, sp.oo))), _undefined(t + sp.oo)
    (False, True)
    """
    if expr.has(sp.nan, sp.zoo):
        return True
    if expr.has(sp.Integral):   # an infinite limit is not an infinite value
        expr = expr.replace(lambda e: isinstance(e, sp.Integral), lambda e: sp.Dummy())
    return bool(expr.has(sp.oo, -sp.oo))


def read_side(name: str, value: Any, caller: str = "decide") -> sp.Basic:
    """``value`` as a SymPy expression or matrix; ``TypeError`` naming the argument for what SymPy cannot read
    (``ValueError`` for a string it cannot parse), and for a relation or a truth value, which is not a side.

    >>> read_side("lhs", "x**2 + 1")
    x**2 + 1
    >>> read_side("rhs", [1, 2])
    Traceback (most recent call last):
    ...
    TypeError: decide: rhs must be a SymPy expression, number or matrix, not list ([1, 2])
    """
    if isinstance(value, sp.MatrixBase):
        return value
    unreadable = value is None or isinstance(value, (bytes, bytearray, set, frozenset, dict))
    if unreadable or (callable(value) and not isinstance(value, sp.Basic)):
        raise TypeError(f"{caller}: {name} must be a SymPy expression, number or matrix, not {type(value).__name__}")
    try:
        expr = sp.sympify(value, strict=not isinstance(value, str))
    except (sp.SympifyError, TypeError, ValueError) as exc:
        if isinstance(value, str):
            raise ValueError(f"{caller}: cannot parse {name} {value!r}: {exc}") from exc
        raise TypeError(f"{caller}: {name} must be a SymPy expression, number or matrix, "
                        f"not {type(value).__name__} ({value!r})") from exc
    if isinstance(expr, BooleanAtom):   # Eq(x, x) is already True when it arrives
        raise TypeError(f"{caller}: {name} is {expr}, not an expression (an Eq that SymPy has already "
                        "evaluated?): give its two sides as lhs and rhs")
    if isinstance(expr, Relational) or not isinstance(expr, (sp.Expr, sp.MatrixBase)):   # x > 1, And(...): not a side
        raise TypeError(f"{caller}: {name} is {type(expr).__name__} ({expr}), not an expression: give the two "
                        "sides of a statement as lhs and rhs")
    return expr


def match_shapes(lhs: sp.Basic, rhs: sp.Basic, caller: str = "decide") -> tuple[sp.Basic, sp.Basic]:
    """The two sides with one shape: a scalar ``0`` beside a matrix becomes the zero matrix of its shape;
    ``ValueError`` naming both sides for any other scalar beside a matrix, or matrices of different shapes.

    >>> match_shapes(sp.Matrix([1, 2]), 0)
    (Matrix([
    [1],
    [2]]), Matrix([
    [0],
    [0]]))
    """
    lm, rm = isinstance(lhs, sp.MatrixBase), isinstance(rhs, sp.MatrixBase)
    if lm and not rm and rhs == 0:
        return lhs, sp.zeros(*lhs.shape)
    if rm and not lm and lhs == 0:
        return sp.zeros(*rhs.shape), rhs
    if lm != rm:
        m, other = ("lhs", "rhs") if lm else ("rhs", "lhs")
        shape = (lhs if lm else rhs).shape
        raise ValueError(f"{caller}: {m} is a {shape[0]}x{shape[1]} matrix and {other} the scalar "
                         f"{rhs if lm else lhs}: give both sides as matrices of one shape (a scalar side may only "
                         "be 0)")
    if lm and lhs.shape != rhs.shape:
        raise ValueError(f"{caller}: shape mismatch: lhs is {lhs.shape[0]}x{lhs.shape[1]}, "
                         f"rhs {rhs.shape[0]}x{rhs.shape[1]}")
    return lhs, rhs


def decide(lhs: sp.Expr, rhs: sp.Expr = 0, *, relations: Mapping[sp.Symbol, sp.Expr] | None = None,
           digits: int = 50, points: int = 6, seed: int = 1729, exact: bool = True,
           fixed: Mapping[sp.Symbol, Any] | None = None) -> Verdict:
    """Decide ``lhs == rhs`` (scalars or matrices of equal shape).

    ``relations`` maps a symbol to a polynomial that vanishes on it (the
    symbol is algebraic over the others, e.g. ``{eta: eta**2 - mu**2 - w}``).
    ``fixed`` pins symbols to given values in the numeric screen (e.g. a
    parameter known to be of one sign).  ``exact=False`` skips the exact
    layer (used for statements involving transcendental functions).  ``digits``
    must be at least ``MIN_DIGITS`` = 9 (``ValueError``): below, the screen's
    tolerance ``10**-(digits - 8)`` would be 1 or more and every statement would pass.
    Each side must be something SymPy reads as an expression or matrix (:func:`read_side`: ``TypeError`` or
    ``ValueError`` naming it); a matrix beside a scalar other than 0, or matrices of different shapes, are a
    ``ValueError`` (:func:`match_shapes`).  A matrix is decided entry by entry: false if an entry is (the worst),
    else inconclusive if an entry is, else proved (its method: the entries' distinct exact methods in entry
    order, joined by a vertical bar) or holding by the screen.
    """
    if isinstance(digits, int) and digits < MIN_DIGITS:
        raise ValueError(f"decide: digits must be at least {MIN_DIGITS} (the numeric screen's tolerance "
                         f"10**-(digits - 8) would be {10.0 ** -(digits - 8):g}, which any two numbers meet), "
                         f"got {digits}")
    relations = dict(relations or {})
    fixed = dict(fixed or {})
    lhs, rhs = match_shapes(read_side("lhs", lhs), read_side("rhs", rhs))
    if isinstance(lhs, sp.MatrixBase):
        parts = [decide(a, b, relations=relations, digits=digits, points=points, seed=seed,
                        exact=exact, fixed=fixed) for a, b in zip(lhs, rhs)]
        if not parts:
            return Verdict.from_proof("exact: empty matrices")
        bad = [d for d in parts if not d.holds and not d.inconclusive]
        if bad:
            return max(bad, key=lambda d: d.residual or 0.0)
        undecided = [d for d in parts if d.inconclusive]
        if undecided:  # no entry is false, some cannot be told apart from noise
            return max(undecided, key=lambda d: d.residual or 0.0)
        res = max((d.residual or 0.0) for d in parts)
        all_exact = all(d.exact for d in parts)
        if all_exact:
            return Verdict.from_proof(" | ".join(dict.fromkeys(d.method for d in parts)))
        numeric = [d for d in parts if not d.exact]
        errors = [d.error for d in numeric if d.error is not None]
        return Verdict(True, "sampled", numeric[0].method, residual=res,
                       digits=min((d.digits if d.digits is not None else digits) for d in numeric),
                       points=numeric[0].points, note=numeric[0].note, error=max(errors) if errors else None)
    if _undefined(lhs) or _undefined(rhs):
        return Verdict(False, "proof", "undefined: a side contains nan, zoo or oo", definite=True,
                       note="a statement with an undefined side cannot hold")
    diff = lhs - rhs
    method_exact, definite = "", False
    if exact:
        zero, method_exact, definite = exact_zero(diff, relations)
        if zero:
            return Verdict.from_proof(method_exact)
        definite = definite and not fixed
    sr = screen(lhs, rhs, relations, digits, points, seed, fixed, recheck=not definite)
    res, dig, point, pts = sr.residual, sr.digits, sr.point, sr.points
    nmethod = f"numeric: mpmath {digits} digits at {len(pts)} random points"
    if sr.rechecked:
        nmethod += f" ({sr.rechecked} re-evaluated at {sr.high_digits} digits)"
    if sr.ok and not definite:
        note = "" if not method_exact else "exact reduction left a nonzero remainder; numeric screen agrees with zero"
        return Verdict(True, "sampled", nmethod, residual=res, digits=dig, points=pts, note=note, error=sr.error)
    if definite:
        method = method_exact + " left a nonzero rational function; worst point by " + nmethod
        note = "exactly false: the difference is a nonzero rational function"
        if sr.residual <= 10.0 ** (-(digits - 8)):
            note += f" (numerically tiny at the sample points: residual {res:.3g})"
        return Verdict(False, "proof", method, residual=res, digits=dig, counterexample=point, points=pts,
                       note=note, definite=True)
    method = nmethod if not method_exact else method_exact + "; counterexample by " + nmethod
    if sr.status == "inconclusive":
        return Verdict(False, "sampled", method.replace("; counterexample by ", "; "), residual=res, digits=dig,
                       points=pts, note=_cannot_tell(sr, digits), inconclusive=True, error=sr.error)
    return Verdict(False, "sampled", method, residual=res, digits=dig, counterexample=point, points=pts,
                   error=sr.error)


def _cannot_tell(sr: ScreenResult, digits: int) -> str:
    """Why the screen could not decide, in words."""
    tol = 10.0 ** (-(digits - 8))
    where = f"at {_point_brief(sr.point)}"
    if sr.residual > tol:
        why = (f"the relative residual {sr.residual:.1e} is within {SAFETY:g}x the evaluation's own error "
               f"{sr.error:.1e}: no counterexample, and no agreement to the tolerance {tol:.0e} either")
    else:
        why = (f"the sides agree to {sr.residual:.1e}, but the evaluation is only trustworthy to {sr.error:.1e} "
               f"(the {digits}- and {sr.high_digits}-digit evaluations differ, or a quadrature has not "
               f"converged), above the tolerance {tol:.0e}")
    return f"cannot tell at {digits} digits: {where} {why}; raise digits"


def _point_brief(point: Mapping[str, str] | None, limit: int = 4) -> str:
    items = list((point or {}).items())
    txt = ", ".join(f"{k}={v}" for k, v in items[:limit])
    return (txt + (", ..." if len(items) > limit else "")) or "a sample point"
