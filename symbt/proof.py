"""Deciding identities: exact reduction first, high-precision random evaluation as screen.

``sympy.simplify`` is neither fast nor a decision procedure: it may return an
unsimplified expression that is in fact zero.  The claims of symbt are decided
here instead, in this order:

1. **Exact reduction.**  Hyperbolic functions are rewritten as exponentials,
   and every ``exp(a_1 s_1 + ... + a_k s_k)`` with integer ``a_i`` becomes the
   monomial ``S_1**a_1 ... S_k**a_k`` in fresh *positive* symbols
   ``S_i = exp(s_i)`` (for the Toda lattice these are ``E_j = e^{q_j}``).  The
   difference ``lhs - rhs`` is then a rational function; it is brought to one
   fraction with ``together``/``cancel`` and its numerator is reduced modulo the
   user's algebraic relations (e.g. ``eta**2 = mu**2 + w``) by polynomial
   remainder in the constrained symbol.  A zero remainder *proves* the
   identity.  This step is skipped when the difference is not rational after
   the rewriting (logarithms, ``acosh``, radicals of non-symbols).
2. **Numeric screen.**  The difference is evaluated with mpmath at ``digits``
   significant digits at ``points`` random points drawn according to the SymPy
   assumptions of each symbol (a ``real`` symbol may be negative, a symbol
   without assumptions is sampled complex) and satisfying the relations (a
   constrained symbol is set to a root of its relation, with a random sign
   for square roots; relations may build on each other).  Points where a side
   is not finite (poles, ``nan``, evaluation errors) are resampled.  If every
   relative residual is below ``10**-(digits-8)`` the identity is *verified
   numerically*; otherwise it is *false* and the worst point is returned as a
   counterexample with its residual.

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

import random
from dataclasses import dataclass, field
from typing import Any, Mapping

import mpmath
import sympy as sp

__all__ = ["Decision", "decide", "rationalize_exponentials", "reduce_modulo"]


@dataclass
class Decision:
    """Outcome of :func:`decide`.

    ``verdict`` is ``"proved"`` (exact reduction to zero), ``"verified"``
    (numerically, at ``digits`` digits at every point of ``points``) or
    ``"false"`` (``counterexample`` holds the worst point and ``residual`` the
    relative residual there).
    """

    verdict: str
    method: str
    residual: float | None = None
    digits: float | None = None
    counterexample: dict[str, str] | None = None
    points: list[dict[str, str]] = field(default_factory=list)
    note: str = ""

    @property
    def holds(self) -> bool:
        return self.verdict in ("proved", "verified")

    @property
    def exact(self) -> bool:
        return self.verdict == "proved"

    def __bool__(self) -> bool:  # pragma: no cover - convenience
        return self.holds


# --------------------------------------------------------------------------- exact layer

def _linear_integer_form(arg: sp.Expr, symbols) -> dict[sp.Symbol, int] | None:
    """``arg`` as an integer combination of ``symbols`` (no constant), else None."""
    arg = sp.expand(arg)
    coeffs: dict[sp.Symbol, int] = {}
    for term in sp.Add.make_args(arg):
        c, rest = term.as_coeff_Mul()
        if rest not in symbols or not c.is_Integer:
            return None
        coeffs[rest] = coeffs.get(rest, 0) + int(c)
    return coeffs


def rationalize_exponentials(expr, exp_symbols: Mapping[sp.Symbol, sp.Symbol] | None = None):
    """Rewrite ``exp``/``cosh``/``sinh`` of integer-linear forms as monomials.

    ``exp_symbols`` maps a variable ``s`` to the positive symbol standing for
    ``exp(s)``; missing variables get a fresh ``exp_s`` symbol.  Returns the
    rewritten expression and the mapping used.  Exponentials of other
    arguments are left untouched (the caller then falls back to numerics).

    >>> q1, q2 = sp.symbols("q1 q2", real=True)
    >>> e, m = rationalize_exponentials(2 * sp.cosh(q1 - q2))
    >>> sp.simplify(e - (m[q1] / m[q2] + m[q2] / m[q1]))
    0
    """
    exp_symbols = dict(exp_symbols or {})
    expr = sp.sympify(expr)
    if expr.has(sp.cosh, sp.sinh, sp.tanh):
        # rewrite only the hyperbolic functions (a global rewrite would turn x**2 into exp(2 log x))
        expr = expr.replace(lambda e: isinstance(e, (sp.cosh, sp.sinh, sp.tanh)),
                            lambda e: e.rewrite(sp.exp))
    candidates = set()
    for e in expr.atoms(sp.exp):
        candidates |= e.args[0].free_symbols
    symbols = set(candidates)

    def repl(e):
        form = _linear_integer_form(e.args[0], symbols)
        if form is None:
            return e
        out = sp.Integer(1)
        for s, k in form.items():
            if s not in exp_symbols:
                # a Dummy: a user symbol that happens to be called ``exp_q`` must not collide
                exp_symbols[s] = sp.Dummy(f"exp_{s.name}", positive=True)
            out *= exp_symbols[s] ** k
        return out

    expr = expr.replace(lambda e: isinstance(e, sp.exp), repl)
    return expr, exp_symbols


def _is_rational_in_symbols(expr) -> bool:
    """True if ``expr`` is built from symbols and numbers by +, *, integer powers."""
    if expr.is_Atom:
        return bool(expr.is_Symbol or expr.is_Rational or expr is sp.I)
    if isinstance(expr, (sp.Add, sp.Mul)):
        return all(_is_rational_in_symbols(a) for a in expr.args)
    if isinstance(expr, sp.Pow):
        return expr.exp.is_Integer and _is_rational_in_symbols(expr.base)
    return False


def reduce_modulo(numerator, relations: Mapping[sp.Symbol, sp.Expr]):
    """Reduce a polynomial modulo ``relations`` (symbol -> polynomial vanishing on it).

    The remainder of polynomial division by each relation in its symbol
    replaces the numerator; passes are repeated until nothing changes, so a
    relation may involve other constrained symbols (``e2 - e1``, ``e1**2 - x``).
    The remainder differs from the numerator by a multiple of the relation, so
    a zero remainder proves that the numerator vanishes wherever the relations do.
    """
    out = sp.expand(numerator)
    rels = {sym: sp.expand(rel) for sym, rel in relations.items()}
    for _ in range(len(rels) + 2):
        before = out
        for sym, rel in rels.items():
            if not out.has(sym) or sp.degree(rel, sym) < 1:
                continue
            out = sp.expand(sp.rem(out, rel, sym))
        if out == before:
            break
    return out


def _exact(diff, relations) -> tuple[bool | None, str, bool]:
    """Try to decide ``diff == 0`` exactly.

    Returns ``(zero, method, definite)``: ``zero`` is None when the exact layer
    does not apply, True when the difference reduces to 0; ``definite`` is True
    when a nonzero result is a proof of falsity (a nonzero rational function
    without relations: it cannot vanish identically -- the ``exp(s_i)`` are
    algebraically independent over the rational functions of the ``s_i``).
    """
    rat, mapping = rationalize_exponentials(diff)
    if not _is_rational_in_symbols(rat):
        return None, "", False
    num, _den = sp.fraction(sp.cancel(sp.together(rat)))
    if relations:
        num = reduce_modulo(num, relations)
        num = sp.cancel(num)
    parts = []
    if mapping:
        parts.append("exp->monomials (" + ", ".join(f"{v}=e^{k}" for k, v in mapping.items()) + ")")
    parts.append("together/cancel")
    if relations:
        parts.append("remainder mod " + ", ".join(f"{s}: {sp.sstr(r)}=0" for s, r in relations.items()))
    method = "exact: " + "; ".join(parts)
    zero = bool(num == 0)
    return zero, method, (not zero and not relations)


# --------------------------------------------------------------------------- numeric layer

def _sample(sym: sp.Symbol, rng: random.Random):
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


def _lambdify(args, expr):
    """mpmath lambdify with plain argument names (symbols such as ``lambda`` break the printer)."""
    plain = [sp.Symbol(f"_a{i}") for i in range(len(args))]
    return sp.lambdify(plain, sp.sympify(expr).xreplace(dict(zip(args, plain))), "mpmath")


_POLE_ERRORS = (ZeroDivisionError, ValueError, OverflowError, ArithmeticError)


def _finite(v) -> bool:
    try:
        return bool(mpmath.isfinite(v))
    except (TypeError, ValueError):
        return False


def _solve_order(relations, known):
    """Order the constrained symbols so that each one's roots use only known symbols."""
    known = set(known)
    todo = dict(relations)
    order = []
    while todo:
        progress = False
        for s, rel in list(todo.items()):
            roots = sp.solve(rel, s)
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


def _numeric(lhs, rhs, relations, digits, points, seed, fixed):
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
    for k, (s, roots) in enumerate(order):
        rel_solvers.append([_lambdify(base + constrained[:k], r) for r in roots])
    args = base + constrained
    f_l = _lambdify(args, lhs)
    f_r = _lambdify(args, rhs)
    worst = (mpmath.mpf(-1), None)
    pts = []
    tol = mpmath.mpf(10) ** (-(digits - 8))
    attempts = 0
    with mpmath.workdps(digits + 10):
        while len(pts) < points and attempts < 6 * points + 10:
            attempts += 1
            allv = [_sample(s, rng) for s in free] + [_as_mp(v) for v in fixed.values()]
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


def _undefined(expr) -> bool:
    return bool(expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo))


def decide(lhs, rhs=0, *, relations: Mapping[sp.Symbol, sp.Expr] | None = None,
           digits: int = 50, points: int = 6, seed: int = 1729, exact: bool = True,
           fixed: Mapping[sp.Symbol, Any] | None = None) -> Decision:
    """Decide ``lhs == rhs`` (scalars or matrices of equal shape).

    ``relations`` maps a symbol to a polynomial that vanishes on it (the
    symbol is algebraic over the others, e.g. ``{eta: eta**2 - mu**2 - w}``).
    ``fixed`` pins symbols to given values in the numeric screen (e.g. a
    parameter known to be of one sign).  ``exact=False`` skips the exact
    layer (used for statements involving transcendental functions).
    """
    relations = dict(relations or {})
    fixed = dict(fixed or {})
    lhs, rhs = sp.sympify(lhs), sp.sympify(rhs)
    if isinstance(lhs, sp.MatrixBase) or isinstance(rhs, sp.MatrixBase):
        lm, rm = sp.Matrix(lhs), sp.Matrix(rhs)
        if lm.shape != rm.shape:
            raise ValueError(f"shape mismatch {lm.shape} vs {rm.shape}")
        parts = [decide(a, b, relations=relations, digits=digits, points=points, seed=seed,
                        exact=exact, fixed=fixed) for a, b in zip(lm, rm)]
        if not parts:
            return Decision("proved", "exact: empty matrices", 0.0, None)
        bad = [d for d in parts if not d.holds]
        if bad:
            return max(bad, key=lambda d: d.residual or 0.0)
        res = max((d.residual or 0.0) for d in parts)
        all_exact = all(d.exact for d in parts)
        if all_exact:
            return Decision("proved", parts[0].method, res, None)
        numeric = [d for d in parts if not d.exact]
        return Decision("verified", numeric[0].method, res,
                        min((d.digits if d.digits is not None else digits) for d in numeric),
                        points=numeric[0].points, note=numeric[0].note)
    if _undefined(lhs) or _undefined(rhs):
        return Decision("false", "undefined: a side contains nan, zoo or oo", None, None,
                        note="a statement with an undefined side cannot hold")
    diff = lhs - rhs
    method_exact, definite = "", False
    if exact:
        zero, method_exact, definite = _exact(diff, relations)
        if zero:
            return Decision("proved", method_exact, 0.0, None)
        definite = definite and not fixed
    ok, res, dig, point, pts = _numeric(lhs, rhs, relations, digits, points, seed, fixed)
    nmethod = f"numeric: mpmath {digits} digits at {len(pts)} random points"
    if ok and not definite:
        note = "" if not method_exact else "exact reduction left a nonzero remainder; numeric screen agrees with zero"
        return Decision("verified", nmethod, res, dig, points=pts, note=note)
    if definite:
        method = method_exact + " left a nonzero rational function; worst point by " + nmethod
        note = "exactly false: the difference is a nonzero rational function"
        if ok:
            note += f" (numerically tiny at the sample points: residual {res:.3g})"
        return Decision("false", method, res, dig, counterexample=point, points=pts, note=note)
    method = nmethod if not method_exact else method_exact + "; counterexample by " + nmethod
    return Decision("false", method, res, dig, counterexample=point, points=pts)
