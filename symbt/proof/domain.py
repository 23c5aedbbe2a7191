r"""Cells as data: a domain, named splits, and a seeded sampler that fills every cell.

A sampled statement is decided on a *domain* :math:`D` -- named variables, each with a range
(:func:`uniform`, :func:`log_uniform`, :func:`integers`, :func:`complex_box`; a pair ``(a, b)``
means ``uniform(a, b)``) and an optional admissibility predicate ``where`` -- cut into
*cells* by *splits*:

* ``sign("t - t0")`` -- the sign of an expression: cells ``t<t0`` and ``t>t0`` (a point where the
  expression vanishes lies in no cell and is drawn again);
* ``choice("branch", (+1, -1))`` -- a choice the statement depends on, such as the branch of a
  square root: not sampled, its value is passed to the check;
* ``regime("kind", f, ("bounded", "unbounded"))`` -- a label computed from the point.

The cells are the product of the splits' values.  :meth:`Domain.sample` fills **every** cell with
``per_cell`` points (:data:`~symbt.proof.cells.DEFAULT_PER_CELL` = 16, ``deep=True``:
:data:`~symbt.proof.cells.DEEP_PER_CELL` = 64): it draws points from the ranges, rejects those
outside the domain or in another cell, and stops after ``draws_per_point * per_cell`` draws with
:class:`UnfilledCellError` naming the cell.  The points of a cell depend only on the seed and the
cell, so a run is reproducible and the first 16 points of a deep run are the default run's.

:meth:`Domain.evaluate` runs the printed (and a corrected) statement's residual at every point
at ``dps`` significant digits (mpmath) and returns the :class:`~symbt.proof.cells.CellTable` that
Zullo's sampled claims build: per-cell counts, the worst residual and the generated scope
sentence; ``symbt.judge(table, printed=...)`` turns it into an outcome.  A residual function
takes the variables (and choices) it needs as named parameters and returns a number (its absolute
value is the residual) or a pair ``(lhs, rhs)`` (the relative residual
:math:`|l - r| / \max(1, |l|, |r|)`); a sample holds when the residual is at most ``tol``
(default :math:`10^{-\lfloor 2\,\mathrm{dps}/3 \rfloor}`).

>>> import mpmath as mp
>>> dom = Domain({"t": (-2, 2), "t0": (-1, 1)}, seed=1)
>>> # sqrt((t - t0)^2) = t - t0: true where t > t0 only
>>> table = dom.evaluate(sign("t - t0"), printed=lambda t, t0: (mp.sqrt((t - t0)**2), t - t0), dps=30)
>>> print(table.scope())
printed statement holds exactly in cells {t>t0} and fails in {t<t0}
>>> [c["n"] for c in table.cells()]
[16, 16]
"""
from __future__ import annotations

import inspect
import itertools
import math
import random
import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import mpmath as mp

from .cells import DEEP_PER_CELL, DEFAULT_PER_CELL, CellTable, cell_text
from .ranges import Range, as_range, complex_box, integers, log_uniform, uniform

__all__ = ["Domain", "Range", "Split", "UnfilledCellError", "uniform", "log_uniform", "integers", "complex_box",
           "sign", "choice", "regime", "relative_residual", "default_tol"]


class UnfilledCellError(ValueError):
    """A cell of the domain got fewer than ``per_cell`` points within the draw budget."""

    def __init__(self, cell: dict[str, Any], text: str, filled: int, wanted: int, draws: int,
                 outside: int, elsewhere: int) -> None:
        self.cell, self.filled, self.wanted, self.draws = dict(cell), filled, wanted, draws
        super().__init__(f"cannot fill cell {text}: {filled} of {wanted} points after {draws} draws "
                         f"({outside} outside the domain, {elsewhere} in other cells); widen the ranges, "
                         f"relax `where` or drop the split")


# --------------------------------------------------------------------------- calling users' functions

def _caller(fn: Callable[..., Any], what: str, names: Iterable[str]) -> Callable[[dict[str, Any]], Any]:
    """``point -> fn(**the parameters fn names)``; a parameter the points lack is an error now, not later."""
    if getattr(fn, "takes_point", False):   # our own residuals: they take the whole point
        return lambda point: fn(**point)
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):
        raise TypeError(f"{what}: cannot read the parameters of {fn!r}") from None
    names = list(names)
    wanted, required = [], []
    for p in sig.parameters.values():
        if p.kind is p.VAR_KEYWORD:
            return lambda point: fn(**point)
        if p.kind in (p.VAR_POSITIONAL, p.POSITIONAL_ONLY):
            raise TypeError(f"{what}: name the variables as parameters (def f(t, t0): ...), not *args")
        wanted.append(p.name)
        if p.default is p.empty:
            required.append(p.name)
    missing = [n for n in required if n not in names]
    if missing:
        raise ValueError(f"{what} takes {', '.join(missing)}, which the points lack (they have {', '.join(names)})")
    return lambda point: fn(**{n: point[n] for n in wanted if n in point})


def relative_residual(lhs: Any, rhs: Any) -> Any:
    r"""``|lhs - rhs| / max(1, |lhs|, |rhs|)``.

    >>> float(relative_residual(3, 3.5))
    0.14285714285714285
    """
    return abs(lhs - rhs) / max(mp.mpf(1), abs(lhs), abs(rhs))


def _residual(value: Any, what: str) -> float:
    try:
        if isinstance(value, (tuple, list)):
            lhs, rhs = value
            value = relative_residual(mp.mpmathify(lhs), mp.mpmathify(rhs))
        r = float(abs(mp.mpmathify(value)))
    except (TypeError, ValueError):
        raise TypeError(f"{what} returned {value!r}; return a number or a pair (lhs, rhs)") from None
    return r if not math.isnan(r) else math.inf   # an undefined value never holds


def default_tol(dps: int) -> float:
    """The residual a sample may have and still hold: ``10**-(2*dps//3)`` (1e-20 at 30 digits).

    >>> default_tol(30), default_tol(60)
    (1e-20, 1e-40)
    """
    return float(mp.mpf(10) ** -(2 * dps // 3))


# --------------------------------------------------------------------------- splits

_NAME = re.compile(r"[A-Za-z_]\w*")
_CONSTANTS = {"pi", "E", "I", "oo"}


def _parse(text: str) -> Any:
    """A SymPy expression in which every name not followed by ``(`` is a symbol (``pi``, ``E``, ``I`` keep
    their meaning): ``S``, ``N`` or ``beta`` are variables here, not SymPy objects."""
    import sympy as sp

    names = {m.group() for m in _NAME.finditer(text) if not text[m.end():].lstrip().startswith("(")}
    try:
        return sp.parse_expr(text, local_dict={n: sp.Symbol(n) for n in names - _CONSTANTS})
    except (SyntaxError, TypeError, ValueError) as exc:
        raise ValueError(f"sign({text!r}): not an expression ({exc})") from None


@dataclass(frozen=True)
class Split:
    """One coordinate of the cells: its ``name``, ``kind`` (``sign``, ``choice``, ``regime``) and ``values``.

    Made by :func:`sign`, :func:`choice` and :func:`regime`.  ``classify`` (not for choices) maps a
    point to the split's value (``None``: on the boundary, in no cell).  A split is a coordinate of the
    cells: two splits are equal (and hash alike) when they make the same cells -- the same ``name``, ``kind``
    and ``values`` -- whatever function or expression classifies the points; for the same reason its ``repr``
    shows only those three.
    """

    name: str
    kind: str
    values: tuple[Any, ...]
    func: Callable[..., Any] | None = field(default=None, compare=False, repr=False)
    expr: Any = field(default=None, compare=False, repr=False)

    def bind(self, names: Iterable[str]) -> Callable[[dict[str, Any]], Any]:
        """``point -> value`` for points with the variables ``names``."""
        names = list(names)
        if self.expr is not None:
            from .lambdify import plain_lambdify

            syms = sorted(self.expr.free_symbols, key=lambda s: s.name)
            missing = [s.name for s in syms if s.name not in names]
            if missing:
                raise ValueError(f"split {self.name!r} names {', '.join(missing)}, which the domain lacks "
                                 f"(it has {', '.join(names)})")
            f = plain_lambdify(syms, self.expr, "mpmath")
            value = lambda point: f(*(point[s.name] for s in syms))  # noqa: E731
        else:
            assert self.func is not None
            value = _caller(self.func, f"split {self.name!r}", names)
        if self.kind == "sign":
            return lambda point: _sign_label(value(point), self)
        return lambda point: _regime_label(value(point), self)


def _sign_label(v: Any, split: Split) -> Any:
    v = mp.mpmathify(v)
    if isinstance(v, mp.mpc):
        if v.imag != 0:
            raise ValueError(f"split {split.name!r}: the sign of a complex value {mp.nstr(v, 8)}")
        v = v.real
    if v == 0 or not mp.isfinite(v):
        return None
    return split.values[0] if v < 0 else split.values[1]


def _regime_label(v: Any, split: Split) -> Any:
    if v not in split.values:
        raise ValueError(f"regime {split.name!r} returned {v!r}, not one of its labels {split.values}")
    return v


def sign(expr: Any, *, name: str | None = None, labels: tuple[str, str] | None = None) -> Split:
    """Split by the sign of ``expr``: a string or SymPy expression in the domain's variables, or a function
    of them (then give ``name``).  The cells are labelled ``lhs<rhs`` and ``lhs>rhs`` (the negative terms
    moved to the right) unless ``labels`` says otherwise; a point where ``expr`` vanishes is in no cell.

    >>> sign("t - t0").values, sign("x**2 - 1").values
    (('t<t0', 't>t0'), ('x**2<1', 'x**2>1'))
    >>> sign(lambda q1, q2: q1 - q2, name="q1-q2").values
    ('q1-q2<0', 'q1-q2>0')
    """
    import sympy as sp

    sym_expr = None
    if isinstance(expr, str):
        sym_expr = _parse(expr)
    elif isinstance(expr, sp.Basic):
        sym_expr = sp.sympify(expr)
    elif not callable(expr):
        raise TypeError(f"sign(expr): a string, a SymPy expression or a function, got {expr!r}")
    if sym_expr is not None:
        pos = [a for a in sp.Add.make_args(sym_expr) if not a.as_coeff_Mul()[0].is_negative]
        neg = [-a for a in sp.Add.make_args(sym_expr) if a.as_coeff_Mul()[0].is_negative]
        lhs, rhs = sp.sstr(sp.Add(*pos)), sp.sstr(sp.Add(*neg))
        key, auto = name or f"sign({sp.sstr(sym_expr)})", (f"{lhs}<{rhs}", f"{lhs}>{rhs}")
    else:
        key = name or str(getattr(expr, "__name__", "<lambda>"))
        if key == "<lambda>":
            raise ValueError("sign(function): give the split a name, e.g. sign(lambda t, t0: t - t0, name='t-t0')")
        auto = (f"{key}<0", f"{key}>0")
    pair: tuple[str, ...] = tuple(labels) if labels is not None else auto
    if len(pair) != 2 or pair[0] == pair[1]:
        raise ValueError(f"sign(..., labels=...): two different labels (negative, positive), got {labels!r}")
    return Split(key, "sign", pair, func=None if sym_expr is not None else expr, expr=sym_expr)


def choice(name: str, values: Iterable[Any]) -> Split:
    """Split by a choice the statement depends on (a branch, a sign convention): every value is a cell,
    and the check receives it as the parameter ``name``.

    >>> choice("branch", (+1, -1)).values
    (1, -1)
    """
    values = tuple(values)
    _check_values(f"choice({name!r})", values)
    return Split(name, "choice", values)


def regime(name: str, func: Callable[..., Any], labels: Iterable[Any]) -> Split:
    """Split by a label that ``func`` (a function of the domain's variables) computes from the point;
    ``labels`` are all the labels it may return (each one a cell).

    >>> regime("kind", lambda E: "bound" if E < 0 else "free", ("bound", "free")).values
    ('bound', 'free')
    """
    labels = tuple(labels)
    _check_values(f"regime({name!r})", labels)
    if not callable(func):
        raise TypeError(f"regime({name!r}, func, labels): func must be a function of the variables")
    return Split(name, "regime", labels, func=func)


def _check_values(what: str, values: tuple[Any, ...]) -> None:
    if not values or len(set(values)) != len(values):
        raise ValueError(f"{what}: give one or more distinct values, got {values!r}")
    bad = [v for v in values if not isinstance(v, (int, float, str))]
    if bad:
        raise TypeError(f"{what}: values are numbers or strings (they name cells in reports), got {bad!r}")


# --------------------------------------------------------------------------- the domain

def _per_cell(per_cell: int | None, deep: bool) -> int:
    n = (DEEP_PER_CELL if deep else DEFAULT_PER_CELL) if per_cell is None else per_cell
    if not isinstance(n, int) or isinstance(n, bool) or n < 1:
        raise ValueError(f"per_cell must be a positive integer, got {per_cell!r}")
    return n


def _dps(dps: Any) -> int:
    if not isinstance(dps, int) or isinstance(dps, bool) or dps < 15:
        raise ValueError(f"dps (working precision, significant digits) must be an integer >= 15, got {dps!r}")
    return dps


def _shown(v: Any) -> Any:
    return v if isinstance(v, (int, str)) else mp.nstr(v, 17)


class Domain:
    """Named variables with ranges, an optional admissibility predicate ``where``, and a ``seed``.

    ``variables`` maps a name (or a SymPy symbol) to a range: ``(lo, hi)`` (real, uniform),
    ``range(a, b)`` (integers), or :func:`uniform`, :func:`log_uniform`, :func:`integers`,
    :func:`complex_box`.  ``where`` is a function of the variables (named parameters) that is
    true on the domain; points where it is false are drawn again, at most
    ``draws_per_point * per_cell`` draws per cell.  It may also take the choices of the splits
    (:func:`choice`) as parameters: a point carries its cell's choices.

    >>> dom = Domain({"x": (-1, 1), "n": range(1, 4)}, where=lambda x: abs(x) > 0.1, seed=7)
    >>> pts = dom.sample(sign("x"), per_cell=3)
    >>> [cell for cell, _ in pts] == [{"sign(x)": "x<0"}] * 3 + [{"sign(x)": "x>0"}] * 3
    True
    >>> pts == dom.sample(sign("x"), per_cell=3)        # the seed reproduces the points
    True
    """

    def __init__(self, variables: Mapping[Any, Any], *, where: Callable[..., Any] | None = None, seed: int = 0,
                 draws_per_point: int = 100) -> None:
        if not isinstance(variables, Mapping) or not variables:
            raise TypeError("Domain(variables): a non-empty mapping name -> range, e.g. {'t': (0, 1)}")
        self.variables: dict[str, Range] = {}
        for key, spec in variables.items():
            name = key if isinstance(key, str) else getattr(key, "name", None)
            if not isinstance(name, str) or not name:
                raise TypeError(f"Domain: variable names are strings or SymPy symbols, got {key!r}")
            self.variables[name] = as_range(name, spec)
        if where is not None and not callable(where):
            raise TypeError(f"Domain(where=...): a function of the variables, got {where!r}")
        if not isinstance(seed, int) or not isinstance(draws_per_point, int) or draws_per_point < 1:
            raise TypeError(f"Domain: seed is an integer and draws_per_point a positive integer, got {seed!r}, "
                            f"{draws_per_point!r}")
        self.where, self.seed, self.draws_per_point = where, seed, draws_per_point

    def __repr__(self) -> str:
        ranges = ", ".join(f"{k}: {v}" for k, v in self.variables.items())
        return f"Domain({{{ranges}}}{', where=...' if self.where else ''}, seed={self.seed})"

    def cells(self, *splits: Split) -> list[dict[str, Any]]:
        """Every cell of the splits, in order: the product of their values.

        >>> Domain({"t": (0, 1)}).cells(sign("t - 1/2"), choice("b", (1, -1)))  # doctest: +NORMALIZE_WHITESPACE
        [{'sign(t - 1/2)': 't<1/2', 'b': 1}, {'sign(t - 1/2)': 't<1/2', 'b': -1},
         {'sign(t - 1/2)': 't>1/2', 'b': 1}, {'sign(t - 1/2)': 't>1/2', 'b': -1}]
        """
        for s in splits:
            if not isinstance(s, Split):
                raise TypeError(f"a split is made by sign(...), choice(...) or regime(...), got {s!r}")
        names = [s.name for s in splits]
        clash = sorted({n for n in names if names.count(n) > 1} | (set(names) & set(self.variables)))
        if clash:
            raise ValueError(f"split names must differ from each other and from the variables: {', '.join(clash)}")
        return [dict(zip(names, values)) for values in itertools.product(*(s.values for s in splits))]

    def sample(self, *splits: Split, per_cell: int | None = None, deep: bool = False,
               dps: int = 30) -> list[tuple[dict[str, Any], dict[str, Any]]]:
        """``(cell, point)`` pairs: ``per_cell`` points in every cell (16; 64 with ``deep``), cell by cell.

        A point maps each variable to its value (mpmath numbers at ``dps`` digits, ``int`` for
        integers) and each choice to the cell's value.  Raises :class:`UnfilledCellError` for a cell
        that cannot be filled.
        """
        n, dps = _per_cell(per_cell, deep), _dps(dps)
        cells = self.cells(*splits)
        names = [*self.variables, *(s.name for s in splits if s.kind == "choice")]
        label_only = tuple(s.name for s in splits if s.kind == "sign")
        where = None if self.where is None else _caller(self.where, "Domain(where=...)", names)
        tests = [(s.name, s.bind(names)) for s in splits if s.kind != "choice"]
        choices = [s.name for s in splits if s.kind == "choice"]
        out = []
        with mp.workdps(dps):
            for cell in cells:
                text = cell_text(cell, label_only)
                rng = random.Random(f"symbt.domain|{self.seed}|{text}")   # str seeds hash with SHA-512: stable
                got, draws, outside, elsewhere = 0, 0, 0, 0
                while got < n and draws < n * self.draws_per_point:
                    draws += 1
                    point = {k: r.draw(rng) for k, r in self.variables.items()}
                    point.update({c: cell[c] for c in choices})
                    if where is not None and not where(point):
                        outside += 1
                    elif any(test(point) != cell[name] for name, test in tests):
                        elsewhere += 1
                    else:
                        out.append((dict(cell), point))
                        got += 1
                if got < n:
                    raise UnfilledCellError(cell, text, got, n, draws, outside, elsewhere)
        return out

    def evaluate(self, *splits: Split, printed: Callable[..., Any], corrected: Callable[..., Any] | None = None,
                 dps: int = 30, tol: float | None = None, per_cell: int | None = None,
                 deep: bool = False) -> CellTable:
        """The printed (and corrected) statement's residual at every point of :meth:`sample`, as a
        :class:`~symbt.proof.cells.CellTable` (``symbt.judge(table, printed=..., corrected=...)``
        gives the outcome with cells and scope).

        ``printed``/``corrected`` take the variables and choices they need as named parameters and
        return a residual or a pair ``(lhs, rhs)``; they run at ``dps`` significant digits (mpmath);
        a sample holds when its residual is at most ``tol`` (default :func:`default_tol`).

        >>> dom = Domain({"x": (0.5, 2)}, seed=3)
        >>> t = dom.evaluate(choice("b", (1, -1)), printed=lambda x, b: (b * mp.sqrt(x)**2, x),
        ...                  corrected=lambda x, b: ((b * mp.sqrt(x))**2, x), per_cell=4)
        >>> print(t.scope())
        printed statement holds exactly in cells {b=+1} and fails in {b=-1}; corrected statement holds in all 2 cells
        >>> t.method
        'numeric: mpmath 30 digits at 4 seeded points in each of 2 cells (seed 3)'
        """
        dps = _dps(dps)
        tol = default_tol(dps) if tol is None else float(tol)
        if not tol >= 0:
            raise ValueError(f"tol must be a non-negative number, got {tol!r}")
        n = _per_cell(per_cell, deep)
        names = [*self.variables, *(s.name for s in splits if s.kind == "choice")]
        run_p = _caller(printed, "printed residual", names)
        run_c = None if corrected is None else _caller(corrected, "corrected residual", names)
        samples = self.sample(*splits, per_cell=n, dps=dps)
        table = CellTable(tol=tol, method=f"numeric: mpmath {dps} digits at {n} seeded points in each of "
                                          f"{len(samples) // n} cells (seed {self.seed})",
                          dps=dps, label_only=tuple(s.name for s in splits if s.kind == "sign"))
        with mp.workdps(dps):
            for cell, point in samples:
                shown = {k: _shown(v) for k, v in point.items()}
                try:
                    rp = _residual(run_p(point), "printed residual")
                    rc = None if run_c is None else _residual(run_c(point), "corrected residual")
                except Exception as exc:
                    if hasattr(exc, "add_note"):   # Python >= 3.11: say where
                        exc.add_note(f"at the point {shown} of cell {cell_text(cell, table.label_only)}")
                    raise
                table.add(cell, printed=rp, corrected=rc, point=shown)
        return table
