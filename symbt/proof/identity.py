r"""Checking your own identities: ``check_identity(lhs, rhs)``.

A thin, user-facing layer over :func:`symbt.proof.decide` (the engine that
decides the paper's claims).  The answer is always one of four, and "cannot
tell" is said out loud:

``proved``
    the difference reduces to zero by exact rational arithmetic (after
    ``exp``/``cosh``/``sinh`` of integer combinations of symbols become
    monomials, and modulo the algebraic ``relations``); ``method`` names the
    steps.
``verified``
    no exact reduction applied (logarithms, radicals, special functions, or a
    nonzero remainder modulo relations), but the two sides agree to ``digits``
    significant digits at ``points`` random points, drawn according to the
    SymPy assumptions of each symbol; the points are listed.  ``digits`` counts
    only digits that agree *and* that the evaluation can be trusted to (it may
    be fewer than asked for, e.g. when a quadrature limits the accuracy).
``inconclusive``
    the numeric screen cannot tell at this precision: the residual is within
    the evaluation's own error (estimated from a second evaluation at about
    twice the precision and from the quadratures' error estimates), so it is
    no counterexample, and the sides cannot be shown to agree to the
    tolerance either.  ``error`` is that estimate; raising ``digits`` may decide.
``false``
    a counterexample: the worst point and the relative residual there (or a
    nonzero rational function, which is false even if numerically tiny).  A
    residual is a counterexample only if it is well above the evaluation's error.
    When the sides contain SymPy elliptic functions and would agree with their
    parameter ``m`` read as a modulus ``k`` (``m = k**2``) or the other way round,
    ``note`` says so: SymPy's ``elliptic_k/e/f/pi`` and mpmath take the parameter ``m``.

Assumptions are respected: a ``real`` symbol may be negative, so
``sqrt(x**2) == x`` is *false* for real ``x`` and *proved* for positive ``x``;
a symbol without assumptions is sampled in the complex plane.

Relations
---------
``relations`` says that some symbols are algebraic over the others.  Accepted forms:

* a dict ``{eta: eta**2 - mu**2 - w}`` (symbol -> polynomial that vanishes) or
  ``{eta: sp.Eq(eta**2, mu**2 + w)}``;
* a list whose items are ``sp.Eq(...)``, ``(symbol, Eq)`` or ``(symbol, polynomial)``
  pairs, or bare polynomials.

For an ``Eq`` or polynomial without a named symbol the *constrained symbol* is
chosen as follows: if one side of the ``Eq`` involves a single symbol
(``Eq(eta**2, mu**2 + w)``), it is that symbol; otherwise it is the symbol of
highest degree, and a tie is an error asking you to name it (dict or pair).
The exact layer divides by the relation in the constrained symbol; the numeric
layer sets the constrained symbol to a root of its relation (random root).

Example
-------
>>> import sympy as sp
>>> eta, mu, w = sp.symbols("eta mu w", real=True)
>>> r = check_identity((eta - mu) * (eta + mu), w, relations=[sp.Eq(eta**2, mu**2 + w)])
>>> r.status, bool(r)
('proved', True)
>>> x = sp.Symbol("x", real=True)
>>> check_identity(sp.sqrt(x**2), x).status
'false'
>>> check_identity(sp.sqrt(x**2), x, assumptions={x: {"positive": True}}).status
'proved'
"""
from __future__ import annotations

import html
import numbers
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, TypeAlias

import sympy as sp

from .decider import decide, match_shapes, read_side
from .screen import MIN_DIGITS
from .verdict import STATUS_COLOURS, Verdict, latex_text

#: a side of an identity: a SymPy expression or matrix, a number, or a string SymPy parses
ExprLike: TypeAlias = "sp.Basic | sp.MatrixBase | complex | str"
#: side conditions: ``{symbol: relation}``, a list of ``Eq`` or ``(symbol, Eq)`` pairs, one ``Eq``, or None
RelationsLike: TypeAlias = ("Mapping[sp.Symbol, sp.Basic] | Iterable[sp.Basic | tuple[sp.Symbol, sp.Basic]] | sp.Basic "
                            "| None")

__all__ = ["IdentityResult", "check_identity", "normalize_relations", "apply_assumptions", "convention_hint",
           "STATUSES"]

STATUSES = ("proved", "verified", "inconclusive", "false")

#: the elliptic functions whose last argument is the parameter m = k**2 (not the modulus k)
ELLIPTIC = (sp.elliptic_k, sp.elliptic_e, sp.elliptic_f, sp.elliptic_pi)


def _short(expr: object, limit: int = 80) -> str:
    s = " ".join(sp.sstr(expr).split())  # matrices print on several lines
    return s if len(s) <= limit else s[: limit - 3] + "..."


def _point_text(point: Mapping[str, Any] | None, limit: int = 6) -> str:
    if not point:
        return "-"
    items = list(point.items())
    txt = ", ".join(f"{k}={v}" for k, v in items[:limit])
    return txt + (", ..." if len(items) > limit else "")


@dataclass
class IdentityResult(Verdict):
    """Outcome of :func:`check_identity`: a :class:`~symbt.proof.Verdict` with its statement.

    ``status`` is ``"proved"``, ``"verified"``, ``"inconclusive"`` or ``"false"``
    (the verdict); ``evidence`` says how it was reached (``"proof"`` or ``"sampled"``);
    ``method`` names the steps; ``residual`` is the worst relative residual of
    the numeric screen (0 when proved); ``digits`` the number of significant
    digits to which the sides agree and the evaluation is trustworthy (``None``
    when proved); ``error`` the estimated error of the evaluation at the decisive
    point; ``requested_digits`` the working precision asked for; ``points`` the
    sample points (symbol name -> value as a string); ``counterexample`` the worst
    point when false.  ``bool(result)`` is true only for ``proved`` and ``verified``.  ``repr`` shows the
    verdict's fields and ``requested_digits``, not the sides (``str`` shows the statement).
    """

    requested_digits: int = 50
    lhs: Any = field(default=None, repr=False)
    rhs: Any = field(default=None, repr=False)

    @property
    def status(self) -> str:
        return self.verdict

    # -- truth ---------------------------------------------------------------
    @property
    def proved(self) -> bool:
        return self.status == "proved"

    # -- text ---------------------------------------------------------------
    @property
    def statement(self) -> str:
        return f"{_short(self.lhs)} == {_short(self.rhs)}"

    def summary(self) -> str:
        """What decided, in words (without the statement)."""
        if self.status == "proved":
            return f"proved by {self.method}"
        if self.status == "verified":
            return (f"verified numerically to {self._digits_text()} at {len(self.points)} random "
                    f"points (worst relative residual {self.residual:.1e}; {self.method})")
        res = "undefined" if self.residual is None else f"{self.residual:.3g}"
        if self.status == "inconclusive":
            err = "unknown" if self.error is None else f"{self.error:.1e}"
            return (f"inconclusive: cannot tell at {self.requested_digits} digits (relative residual {res}, "
                    f"evaluation error {err}; {self.method})")
        hint = f"; {self.note}" if self.note.startswith("hint:") else ""
        return (f"false: counterexample {_point_text(self.counterexample)} "
                f"(relative residual {res}; {self.method}){hint}")

    def _digits_text(self) -> str:
        got = int(self.digits) if self.digits is not None else self.requested_digits
        if got >= self.requested_digits:
            return f"{self.requested_digits} digits"
        return f"{got} of the {self.requested_digits} digits asked for"

    def __str__(self) -> str:
        return f"{self.statement}: {self.summary()}"

    # -- rich display -----------------------------------------------------------
    def _repr_html_(self) -> str:
        colour = STATUS_COLOURS.get(self.status, "#555")
        e = html.escape
        rows = [("method", e(self.method))]
        if self.status == "verified":
            rows.append(("residual", f"{self.residual:.2e} ({self.digits:.0f} digits agree, "
                                     f"{self.requested_digits} requested)"))
            pts = "<br>".join(e(_point_text(p)) for p in self.points)
            rows.append(("points", pts))
        elif self.status == "inconclusive":
            err = "unknown" if self.error is None else f"{self.error:.1e}"
            rows.append(("residual", f"{self.residual:.2e} (evaluation error {err}: cannot tell at "
                                     f"{self.requested_digits} digits)"))
        elif self.status == "false":
            rows.append(("residual", "undefined" if self.residual is None else f"{self.residual:.3g}"))
            rows.append(("counterexample", e(_point_text(self.counterexample, limit=20))))
        if self.note:
            rows.append(("note", e(self.note)))
        body = "".join(f"<tr><th style='text-align:left;padding-right:1em'>{k}</th><td>{v}</td></tr>"
                       for k, v in rows)
        return (f"<div class='symbt-identity symbt-{self.status}' style='border-left:4px solid {colour};"
                f"padding:0.3em 0.8em;margin:0.3em 0'>"
                f"<code>{e(self.statement)}</code> "
                f"<span style='background:{colour};color:white;padding:0 0.4em;border-radius:3px'>"
                f"{e(self.status)}</span><table>{body}</table></div>")

    def _repr_latex_(self) -> str:
        rel = {"false": r"\neq", "inconclusive": r"\overset{?}{=}"}.get(self.status, "=")
        try:
            stmt = f"{sp.latex(self.lhs)} {rel} {sp.latex(self.rhs)}"
        except Exception:  # pragma: no cover - exotic objects
            stmt = latex_text(self.statement)
        return f"$\\displaystyle {stmt}\\quad \\text{{({latex_text(self.status)})}}$"

    def to_dict(self) -> dict[str, Any]:
        return {"statement": self.statement, "status": self.status, "evidence": self.evidence,
                "method": self.method,
                "residual": self.residual, "digits": self.digits, "error": self.error, "points": self.points,
                "counterexample": self.counterexample, "note": self.note}


# --------------------------------------------------------------------------- inputs

def _symbol_lookup(exprs: Iterable[Any]) -> dict[str, sp.Symbol]:
    out: dict[str, sp.Symbol] = {}
    for e in exprs:
        for s in getattr(e, "free_symbols", ()):
            out.setdefault(s.name, s)
    return out


def apply_assumptions(assumptions: Mapping[Any, Mapping[str, bool]] | None,
                      *exprs: sp.Expr) -> tuple[Any, ...]:
    """Replace symbols by assumption-carrying ones.

    ``assumptions`` maps a symbol (or its name) to an assumption dict, e.g.
    ``{x: {"positive": True}}``; the new symbol keeps the name and combines the
    old symbol's assumptions with the new ones (inconsistent ones raise
    ``ValueError``).  Returns ``(replacement, exprs...)``.
    """
    if not assumptions:
        return ({}, *exprs)
    lookup = _symbol_lookup(exprs)
    repl: dict[sp.Symbol, sp.Symbol] = {}
    for key, extra in assumptions.items():
        name = key if isinstance(key, str) else getattr(key, "name", None)
        if name is None:
            raise TypeError(f"assumptions keys must be symbols or names, not {key!r}")
        old = key if isinstance(key, sp.Symbol) else lookup.get(name, sp.Symbol(name))
        base = dict(getattr(old, "_assumptions_orig", {}) or {})
        base.update(extra)
        try:
            new = sp.Symbol(name, **base)
        except Exception as exc:  # InconsistentAssumptions
            raise ValueError(f"inconsistent assumptions for {name}: {base}") from exc
        repl[old] = new
        if lookup.get(name) is not None and lookup[name] != old:
            repl[lookup[name]] = new
    out: list[Any] = []
    for e in exprs:
        if e is None:
            out.append(e)
        elif isinstance(e, sp.MatrixBase):
            out.append(e.xreplace(repl))
        else:
            out.append(sp.sympify(e).xreplace(repl))  # xreplace re-evaluates: sqrt(x**2) -> x for x > 0
    return (repl, *out)


def _as_poly_expr(rel: sp.Basic) -> sp.Expr:
    if isinstance(rel, sp.Equality):
        return sp.expand(rel.lhs - rel.rhs)
    return sp.expand(sp.sympify(rel))


def _pick_symbol(rel: sp.Basic) -> sp.Symbol:
    if isinstance(rel, sp.Equality):
        for side in (rel.lhs, rel.rhs):
            fs = side.free_symbols
            if len(fs) == 1 and (rel.lhs.free_symbols | rel.rhs.free_symbols) != fs:
                return next(iter(fs))
    poly = _as_poly_expr(rel)
    syms = sorted(poly.free_symbols, key=lambda s: s.name)
    if not syms:
        raise ValueError(f"relation {rel} involves no symbol")
    degs = {s: sp.degree(poly, s) for s in syms}
    top = max(degs.values())
    best = [s for s in syms if degs[s] == top]
    if len(best) > 1:
        raise ValueError(f"relation {rel}: cannot tell which symbol it constrains "
                         f"({', '.join(map(str, best))} all have degree {top}); name it with a dict "
                         f"{{symbol: relation}} or a (symbol, relation) pair")
    return best[0]


def normalize_relations(relations: RelationsLike) -> dict[sp.Symbol, sp.Expr]:
    """Turn the accepted forms of ``relations`` into ``{symbol: polynomial}``.

    >>> eta, mu, w = sp.symbols("eta mu w")
    >>> normalize_relations([sp.Eq(eta**2, mu**2 + w)])
    {eta: eta**2 - mu**2 - w}
    >>> normalize_relations([(mu, sp.Eq(eta**2, mu**2 + w))])
    {mu: eta**2 - mu**2 - w}
    """
    if relations is None:
        return {}
    if isinstance(relations, (sp.Equality, sp.Expr)):
        relations = [relations]
    out: dict[sp.Symbol, sp.Expr] = {}
    if isinstance(relations, Mapping):
        items = list(relations.items())
    else:
        items = []
        for item in relations:
            if isinstance(item, tuple) and len(item) == 2 and isinstance(item[0], sp.Symbol):
                items.append(item)
            else:
                items.append((_pick_symbol(item), item))
    for sym, rel in items:
        if not isinstance(sym, sp.Symbol):
            raise TypeError(f"relation key must be a symbol, not {sym!r}")
        poly = _as_poly_expr(rel)
        if not poly.has(sym):
            raise ValueError(f"relation {rel} does not involve {sym}")
        if sym in out:
            raise ValueError(f"two relations for {sym}")
        out[sym] = poly
    return out


# --------------------------------------------------------------------------- argument checks

def _positive_int(name: str, value: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"check_identity: {name} must be an int, not {type(value).__name__} ({value!r})")
    if value <= 0:
        raise ValueError(f"check_identity: {name} must be positive, got {value}")


def _validate(*, digits: object, points: object, seed: object, exact: object, fixed: object,
              assumptions: Mapping[Any, object] | None, relations: object) -> None:
    """Clear ``TypeError`` / ``ValueError`` for arguments the deciders would misread.

    >>> _validate(digits=0, points=8, seed=1, exact=True, fixed=None, assumptions=None, relations=None)
    Traceback (most recent call last):
    ...
    ValueError: check_identity: digits must be positive, got 0
    """
    _positive_int("digits", digits)
    if digits < MIN_DIGITS:     # type: ignore[operator]  # an int: _positive_int checked it
        raise ValueError(f"check_identity: digits must be at least {MIN_DIGITS} (the numeric screen's tolerance "
                         f"10**-(digits - 8) would be 1 or more, which any two numbers meet), got {digits}")
    _positive_int("points", points)
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral):
        raise TypeError(f"check_identity: seed must be an int, not {type(seed).__name__} ({seed!r})")
    if not isinstance(exact, bool):
        raise TypeError(f"check_identity: exact must be True or False, not {exact!r}")
    for name, value in (("fixed", fixed), ("assumptions", assumptions)):
        if value is not None and not isinstance(value, Mapping):
            raise TypeError(f"check_identity: {name} must be a dict, not {type(value).__name__}")
    if assumptions:
        for key, extra in assumptions.items():
            if not isinstance(extra, Mapping):
                raise TypeError(f"check_identity: assumptions[{key!r}] must be a dict such as "
                                f"{{'positive': True}}, not {extra!r}")
    if relations is not None and (isinstance(relations, (str, bytes))
                                  or not isinstance(relations, (Mapping, Iterable, sp.Basic))):
        raise TypeError(f"check_identity: relations must be a dict, a list or an Eq, not {type(relations).__name__}")


# --------------------------------------------------------------------------- entry point

def check_identity(lhs: ExprLike, rhs: ExprLike = 0, *, relations: RelationsLike = None,
                   assumptions: Mapping[Any, Mapping[str, bool]] | None = None, digits: int = 50,
                   points: int = 8, seed: int = 1729, exact: bool = True,
                   fixed: Mapping[Any, Any] | None = None) -> IdentityResult:
    """Decide ``lhs == rhs`` (scalars or matrices); see the module docstring.

    ``lhs`` may be an ``sp.Eq`` (then ``rhs`` is taken from it).  ``relations``:
    algebraic side conditions (dict, list of ``Eq``, ``(symbol, Eq)`` pairs).
    ``assumptions``: ``{symbol or name: {"positive": True, ...}}``.  ``digits``
    and ``points``: precision and number of random points of the numeric
    screen; ``seed`` makes it reproducible.  ``exact=False`` skips the exact
    layer; ``fixed`` pins symbols to values in the numeric screen.

    Arguments are checked first: ``digits``, ``points`` and ``seed`` must be
    integers (``digits`` at least 9, ``points`` positive), ``exact`` a bool, ``fixed`` and
    ``assumptions`` dicts, and the sides something SymPy can read; otherwise
    ``TypeError`` or ``ValueError`` says which argument is wrong.
    """
    _validate(digits=digits, points=points, seed=seed, exact=exact, fixed=fixed, assumptions=assumptions,
              relations=relations)
    if isinstance(lhs, sp.Equality):
        if not (isinstance(rhs, (int, float)) and rhs == 0):
            raise ValueError("give either an Eq or lhs and rhs, not both")
        lhs, rhs = lhs.lhs, lhs.rhs
    lhs, rhs = match_shapes(read_side("lhs", lhs, "check_identity"), read_side("rhs", rhs, "check_identity"),
                            "check_identity")
    rel_raw = normalize_relations(relations)
    if assumptions:
        rel_exprs = list(rel_raw.values()) + list(rel_raw.keys())
        repl, lhs, rhs, *rest = apply_assumptions(assumptions, lhs, rhs, *rel_exprs)
        n = len(rel_raw)
        rel = {repl.get(k, k): v for k, v in zip(rest[n:], rest[:n])}
        fixed = {repl.get(k, k): v for k, v in (fixed or {}).items()}
    else:
        rel = rel_raw
    d = decide(lhs, rhs, relations=rel, digits=digits, points=points, seed=seed, exact=exact,
               fixed=fixed)
    note = d.note
    if d.verdict == "false" and not d.definite:
        hint = convention_hint(lhs, rhs, relations=rel, digits=digits, points=points, seed=seed, fixed=fixed)
        note = (hint + (" " + note if note else "")) if hint else note
    return IdentityResult(d.holds, d.evidence, d.method, residual=d.residual, digits=d.digits,
                          points=list(d.points) if not d.exact else [], counterexample=d.counterexample,
                          note=note, definite=d.definite, inconclusive=d.inconclusive, error=d.error,
                          requested_digits=digits, lhs=lhs, rhs=rhs)


# --------------------------------------------------------------------------- convention hints

def _reparametrised(expr: sp.Basic, to: Callable[[sp.Expr], sp.Expr]) -> sp.Basic | None:
    """``expr`` with the parameter (last argument) of every SymPy elliptic function replaced by ``to(m)``."""
    if isinstance(expr, sp.MatrixBase):
        entries = [_reparametrised(e, to) for e in expr]
        if all(e is None for e in entries):
            return None
        return sp.Matrix(expr.rows, expr.cols, [o if e is None else e for o, e in zip(expr, entries)])
    reps = {f: f.func(*f.args[:-1], to(f.args[-1])) for f in sp.sympify(expr).atoms(*ELLIPTIC)}
    return expr.xreplace(reps) if reps else None


_SWAPS = (
    (lambda m: m ** 2, "hint: the sides agree if the modulus k is read as the parameter m = k**2: "
                       "SymPy/mpmath elliptic functions take m"),
    (sp.sqrt, "hint: the sides agree if the parameter m is read as the modulus k = sqrt(m): "
              "SymPy/mpmath elliptic functions take m = k**2"),
)


def convention_hint(lhs: sp.Basic, rhs: sp.Basic, *, relations: Mapping[sp.Symbol, sp.Expr] | None = None,
                    digits: int = 50, points: int = 8, seed: int = 1729,
                    fixed: Mapping[Any, Any] | None = None) -> str:
    """A hint when ``lhs == rhs`` is false but holds after a modulus/parameter swap of elliptic functions.

    SymPy's ``elliptic_k``, ``elliptic_e``, ``elliptic_f`` and ``elliptic_pi`` (and mpmath's
    ``ellipk`` ...) take the *parameter* ``m = k**2``; formulas in the literature often use the
    *modulus* ``k``.  If replacing the last argument ``a`` of every elliptic function of one side
    by ``a**2`` (or ``sqrt(a)``) makes the identity hold at the screen's precision, the hint says
    so; otherwise it is ``""``.  Only the numeric screen is run (same digits, points and seed).

    >>> k = sp.Symbol("k", positive=True)
    >>> wrong = sp.pi / 2 * sp.hyper([sp.S.Half, sp.S.Half], [1], k**2)   # K of modulus k
    >>> convention_hint(wrong, sp.elliptic_k(k), digits=20, points=3).split(":")[1]
    ' the sides agree if the modulus k is read as the parameter m = k**2'
    >>> convention_hint(sp.elliptic_k(k), sp.elliptic_k(k) + 1, digits=20, points=3)
    ''
    """
    for side in ("lhs", "rhs"):
        expr = lhs if side == "lhs" else rhs
        for to, text in _SWAPS:
            swapped = _reparametrised(expr, to)
            if swapped is None:
                continue
            new_l, new_r = (swapped, rhs) if side == "lhs" else (lhs, swapped)
            try:
                d = decide(new_l, new_r, relations=relations, digits=digits, points=points, seed=seed,
                           exact=False, fixed=fixed)
            except (ValueError, TypeError, ZeroDivisionError):
                continue
            if d.holds:
                return text
    return ""
