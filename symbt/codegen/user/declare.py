r"""``symbt.emit``: declare, next to a derivation, a function that ``symbt codegen`` writes.

``emit(name, expr, args=(p, q), module="mymodel", doc=..., domain=...)`` declares a function
``name`` of the emitted module ``module`` (the files ``<module>.py`` and, with ``--target c``,
``<module>.c``/``<module>.h``):

* ``expr``: a SymPy expression (a scalar), a list of them (a vector) or a ``Matrix``;
  ``Piecewise`` and relations (conditionals) are allowed;
* ``args``: the scalar symbols the function takes, in order; every free symbol of ``expr``
  must be one of them;
* ``domain``: a :class:`symbt.Domain` over the arguments (by name) where the emitted code is
  verified against ``expr`` (a claim per flavour, see :mod:`symbt.codegen.user.check`); ``cells``:
  splits of that domain (default: the sign of every ``Piecewise`` condition, so every branch is
  sampled); in the typed form over the elements (:func:`~.typed.typed_domain`: an array by one
  range or one per element, every sign argument a cell);
* ``optimize``: apply SymPy's ``expm1``/``log1p`` rewriting (:mod:`sympy.codegen.rewriting`)
  before common-subexpression elimination (the reference always uses ``expr`` as given);
* the *typed* form (:mod:`symbt.codegen.user.typed`): array arguments ``("p", [p1, ...])``, a sign
  argument ``("b", b, "sign")``, several named outputs ``expr={"x": ..., "y": ...}`` and ordered
  ``guards`` -- emitted with typed errors (``InvalidInputError``, ``NoRealMapError``,
  ``NumericRangeError``) and ``errors="mask"``, as Zullo's modules (which are declared so:
  :mod:`symbt.codegen.zullo`).

A bad declaration raises :class:`EmitError` at once (a symbol not in ``args``, a non-finite
constant, a function the C target cannot print, a duplicate name).  Declarations are kept in
:data:`EMISSIONS` (keyed by ``(module, name)``) with the module that declared them, like the
claims registry; re-importing a declaring module replaces its declarations.

>>> import sympy as sp
>>> x = sp.Symbol("x")
>>> e = emit("softplus_demo", sp.log(1 + sp.exp(x)), args=(x,), module="demo_emit", register=False)
>>> e.shape, e.arg_names
((), ('x',))
>>> emit("bad_demo", x + sp.Symbol("y"), args=(x,), module="demo_emit", register=False)
Traceback (most recent call last):
...
symbt.codegen.user.declare.EmitError: emit('bad_demo'): symbol y is not among args (x)
"""
from __future__ import annotations

import keyword
import re
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import sympy as sp
from sympy.codegen.cfunctions import expm1, log1p

from ..printer import Quotient
from .typed import Arg, Guard, Loop, Output, arg_of, outputs_of, sign_cells, typed_domain

__all__ = ["emit", "Emission", "EmitError", "EMISSIONS", "SUPPORTED_FUNCTIONS", "emissions_of", "Arg", "Guard",
           "Output"]

#: functions every target prints (numpy, mpmath and C99 ``<math.h>``)
SUPPORTED_FUNCTIONS: tuple[type, ...] = (
    sp.exp, sp.log, log1p, expm1, sp.sin, sp.cos, sp.tan, sp.asin, sp.acos, sp.atan, sp.atan2,
    sp.sinh, sp.cosh, sp.tanh, sp.asinh, sp.acosh, sp.atanh, sp.Abs, sp.sign, sp.Min, sp.Max, sp.Piecewise)

_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
_RESERVED = re.compile(r"^([st]\d+|out|i|np|mpmath|errors)$")


class EmitError(ValueError):
    """A declaration ``symbt codegen`` cannot emit (one line saying which and why)."""


@dataclass(frozen=True)
class Emission:
    """One declared function: what to emit and where to verify it (see :func:`emit`)."""

    name: str
    module: str
    args: tuple[sp.Symbol, ...]
    exprs: tuple[sp.Expr, ...]              # the elements, row-major
    shape: tuple[int, ...]                  # () scalar, (n,) vector, (r, c) matrix
    doc: str = ""
    domain: Any = None                      # a symbt.Domain, or None (then the claims are todo)
    cells: tuple[Any, ...] = ()
    optimize: bool = True
    equation: str | None = None             # the paper label the expression comes from (coverage)
    declared_in: str = field(default="", compare=False)
    params: tuple[Arg, ...] = ()            # the arguments as declared (typed form: arrays, signs)
    outputs: tuple[Output, ...] = ()        # the named outputs (typed form; ``exprs`` is their concatenation)
    guards: tuple[Guard, ...] = ()          # ordered guards (typed form)
    docs: tuple[tuple[str, str], ...] = ()  # (flavour, docstring text) given verbatim
    loop: Loop | None = None                # a fixed template body instead of expressions (typed form)

    @property
    def typed(self) -> bool:
        """Array or sign arguments, named outputs or guards: emitted with typed errors (see :mod:`.typed`)."""
        return bool(self.outputs)

    @property
    def arg_names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.args)

    @property
    def source(self) -> sp.Expr | sp.ImmutableMatrix:
        """The declared expression (as a SymPy object of the declared shape)."""
        if self.shape == ():
            return self.exprs[0]
        if len(self.shape) == 1:
            return sp.ImmutableMatrix(list(self.exprs))
        return sp.ImmutableMatrix(self.shape[0], self.shape[1], list(self.exprs))


#: (module, name) -> Emission, in declaration order
EMISSIONS: dict[tuple[str, str], Emission] = {}


def _fail(name: str, msg: str) -> EmitError:
    return EmitError(f"emit({name!r}): {msg}")


def _elements(name: str, expr: Any) -> tuple[tuple[sp.Expr, ...], tuple[int, ...]]:
    if isinstance(expr, sp.MatrixBase):
        r, c = expr.shape
        if r == 0 or c == 0:
            raise _fail(name, "an empty matrix")
        return tuple(sp.sympify(v) for v in expr), (r, c)
    if isinstance(expr, (list, tuple)):
        if not expr:
            raise _fail(name, "an empty vector")
        if any(isinstance(v, (list, tuple, sp.MatrixBase)) for v in expr):
            raise _fail(name, "a nested list; give a Matrix for a matrix")
        items = expr
        shape: tuple[int, ...] = (len(expr),)
    else:
        items, shape = [expr], ()
    try:
        return tuple(sp.sympify(v, strict=True) for v in items), shape
    except (sp.SympifyError, TypeError):
        raise _fail(name, f"not a SymPy expression: {expr!r}") from None


def _nodes(e: sp.Basic) -> Iterator[sp.Basic]:
    """Every distinct subexpression of ``e`` once (a tree with shared subtrees is not walked repeatedly)."""
    seen, todo = set(), [e]
    while todo:
        node = todo.pop()
        if node in seen:
            continue
        seen.add(node)
        yield node
        todo.extend(node.args)


def _check_expr(name: str, e: sp.Expr, args: tuple[sp.Symbol, ...], typed: bool = False) -> None:
    if not isinstance(e, sp.Expr) or isinstance(e, sp.Tuple):
        raise _fail(name, f"not a scalar expression: {e!r}")
    extra = sorted(e.free_symbols - set(args), key=lambda s: s.name)
    if extra:
        listed = ", ".join(s.name for s in args) or "none"
        raise _fail(name, f"symbol {', '.join(map(str, extra))} is not among args ({listed})")
    # Quotient (IEEE-style division) needs the typed runtime's _div in the mpmath flavour
    supported = SUPPORTED_FUNCTIONS + ((Quotient,) if typed else ())
    for node in _nodes(e):
        if node in (sp.nan, sp.oo, -sp.oo, sp.zoo) or (node.is_Float and not node.is_finite):
            raise _fail(name, f"non-finite constant {node} in {e}")
        if node.is_Number and not node.is_real:
            raise _fail(name, f"complex constant {node} (real arithmetic only)")
        if node.is_Function and not isinstance(node, supported):
            raise _fail(name, f"function {type(node).__name__} is not supported by the C target "
                        f"(supported: {', '.join(f.__name__ for f in SUPPORTED_FUNCTIONS)})")
        if isinstance(node, sp.Piecewise) and node.args[-1][1] is not sp.true:
            raise _fail(name, "a Piecewise needs a default branch (expr, True) as its last piece")
        if isinstance(node, (sp.Derivative, sp.Integral, sp.Sum, sp.Product)) or node is sp.I:
            raise _fail(name, f"{type(node).__name__} cannot be emitted (evaluate it first)")


def emit(name: str, expr: Any, *, args: Any, module: str, doc: Any = "", domain: Any = None,
         cells: Any = (), optimize: bool = True, equation: str | None = None, guards: Any = (),
         register: bool = True) -> Emission:
    """Declare the function ``name`` of the emitted module ``module`` (see the module docstring).

    ``equation``: the paper label (``\\label{}``) of the display the expression comes from; its
    claims are then counted by ``symbt coverage`` as claims of that display (their
    ``source_equation``) instead of as claims on an unknown label.

    Typed form (:mod:`.typed`): ``args`` may hold arrays ``("p", [p1, p2])`` and signs
    ``("b", b, "sign")``, ``expr`` may be a dict of named outputs, ``guards`` a sequence of
    :class:`Guard`; ``doc`` may then be ``{"numpy": text, "mpmath": text}``, the two docstrings
    verbatim.

    Returns the :class:`Emission`; raises :class:`EmitError` for a declaration that cannot be
    emitted.  ``register=False`` checks without recording it.

    >>> import sympy as sp
    >>> p, q = sp.symbols("p q", real=True)
    >>> emit("flow_demo", sp.Matrix([[p, q], [-q, p]]), args=(p, q), module="demo_emit", register=False).shape
    (2, 2)
    >>> b = sp.Symbol("b")
    >>> e = emit("step_demo", {"p_new": [p * b, q], "r": p / q}, args=(("s", (p, q)), ("b", b, "sign")),
    ...          module="demo_emit", guards=[Guard("domain", "q", q)], register=False)
    >>> e.typed, [o.name for o in e.outputs], [a.kind for a in e.params]
    (True, ['p_new', 'r'], ['array', 'sign'])
    """
    if not isinstance(name, str) or not _IDENT.match(name) or keyword.iskeyword(name) or name.endswith("_mp"):
        raise EmitError(f"emit({name!r}): the name must be a Python/C identifier not ending in _mp")
    if not isinstance(module, str) or not _IDENT.match(module) or keyword.iskeyword(module):
        raise _fail(name, f"module={module!r} must be an identifier (the file is <module>.py)")
    if isinstance(args, sp.Symbol):
        args = (args,)
    try:
        args = tuple(args)
    except TypeError:
        raise _fail(name, f"args={args!r} must be a tuple of SymPy symbols") from None
    if not all(isinstance(a, (sp.Symbol, tuple, Arg)) for a in args):
        raise _fail(name, f"args must be SymPy symbols, got {args!r}")
    try:
        params = tuple(arg_of(a) for a in args)
    except ValueError as exc:
        raise _fail(name, str(exc)) from None
    flat = tuple(s for a in params for s in a.symbols)
    names = [a.name for a in params]
    elements = [s.name for a in params if a.kind == "array" for s in a.symbols]
    every = names + elements
    bad = [n for n in every if not _IDENT.match(n) or keyword.iskeyword(n) or n.startswith("_")]
    if bad or len(set(every)) != len(every):
        raise _fail(name, f"argument names must be distinct identifiers, got {', '.join(every)}")
    try:
        guards = tuple(guards or ())
    except TypeError:
        raise _fail(name, f"guards={guards!r} must be a sequence of Guard") from None
    loop = expr if isinstance(expr, Loop) else None
    typed = isinstance(expr, (dict, Loop)) or bool(guards) or any(a.kind != "scalar" for a in params)
    taken = [n for n in every if _RESERVED.match(n)] if typed else []
    if taken:   # the typed renderers' own names: CSE temporaries, the C output buffer and loop index, modules
        raise _fail(name, f"argument name {taken[0]!r} is reserved in the typed form (t0, s0, ..., out, i, np, "
                    "mpmath, errors)")
    outputs: tuple[Output, ...] = ()
    exprs: tuple[sp.Expr, ...]
    shape: tuple[int, ...]
    if loop is not None:
        if guards or domain is not None:
            raise _fail(name, "a Loop body decides its own guards (Loop.guards) and has no SymPy source to "
                        "sample: no guards= or domain=")
        outputs = tuple(Output(o, tuple(shape), ()) for o, shape in loop.outputs)
        if not outputs or dict(loop.items).keys() != {o.name for o in outputs}:
            raise _fail(name, "a Loop needs outputs and one items text per output")
        exprs, shape = (), (outputs[0].shape if len(outputs) == 1 else (len(outputs),))
    elif isinstance(expr, dict):
        try:
            outputs = outputs_of(expr, lambda v: _elements(name, v))
        except ValueError as exc:
            raise (exc if isinstance(exc, EmitError) else _fail(name, str(exc))) from None
        exprs = tuple(x for o in outputs for x in o.exprs)
        shape = outputs[0].shape if len(outputs) == 1 else (len(exprs),)
    else:
        exprs, shape = _elements(name, expr)
        if typed:
            outputs = (Output("result", shape, exprs),)
    for e in exprs:
        _check_expr(name, e, flat, typed)
    gs = []
    for g in guards:
        if (not isinstance(g, Guard) or not isinstance(g.condition, str) or not _IDENT.match(g.condition)
                or g.condition in ("ok", "invalid")):
            raise _fail(name, "a guard must be Guard(condition, label, expr) with an identifier condition other "
                        f"than ok/invalid, got {g!r}")
        gx = sp.sympify(g.expr)
        _check_expr(name, gx, flat, True)
        gs.append(Guard(g.condition, str(g.label), gx, bool(g.early)))
    docs: tuple[tuple[str, str], ...] = ()
    if isinstance(doc, dict):
        if not typed or set(doc) != {"numpy", "mpmath"}:
            raise _fail(name, "doc as a dict needs the typed form and exactly the keys 'numpy' and 'mpmath'")
        docs = (("numpy", str(doc["numpy"])), ("mpmath", str(doc["mpmath"])))
        doc = ""
    if domain is not None:
        from ...proof import Domain

        if not isinstance(domain, Domain):
            raise _fail(name, f"domain must be a symbt.Domain, got {type(domain).__name__}")
        if typed:       # arrays by component (or one interval per array), signs as cells: over the elements
            try:
                domain = typed_domain(params, domain)
            except ValueError as exc:
                raise _fail(name, str(exc)) from None
        missing = [n for n in names if n not in domain.variables] if not typed else []
        if missing:
            raise _fail(name, f"the domain lacks the argument(s) {', '.join(missing)}")
    if equation is not None and (not isinstance(equation, str) or not equation.strip()):
        raise _fail(name, f"equation={equation!r} must be a paper label (a non-empty string)")
    signs = {a.symbols[0] for a in params if a.kind == "sign"}
    cells = tuple(cells) if cells else _branch_splits(exprs + tuple(g.expr for g in gs), signs)
    if typed and domain is not None:
        cells += sign_cells(params, cells)
    declared_in = sys._getframe(1).f_globals.get("__name__", "")
    em = Emission(name=name, module=module, args=flat, exprs=exprs, shape=shape, doc=str(doc), domain=domain,
                  cells=cells, optimize=bool(optimize), equation=equation, declared_in=declared_in,
                  params=params if typed else (), outputs=outputs, guards=tuple(gs), docs=docs, loop=loop)
    if register:
        old = EMISSIONS.get((module, name))
        if old is not None and old.declared_in != declared_in:
            raise _fail(name, f"{module}.{name} is already declared in {old.declared_in}")
        EMISSIONS[(module, name)] = em
    return em


def _branch_splits(exprs: tuple[sp.Expr, ...], exact: set[sp.Symbol] | None = None) -> tuple[Any, ...]:
    """The sign of every relational condition of a ``Piecewise`` (``a < b`` -> ``sign(a - b)``); a
    condition on a sign argument (``exact``) is no split: every sign is a cell already."""
    from ...proof import sign

    seen: dict[str, Any] = {}
    for e in exprs:
        for pw in e.atoms(sp.Piecewise):
            for _, cond in pw.args:
                for rel in (cond.atoms(sp.core.relational.Relational) if cond not in (sp.true, sp.false) else ()):
                    d = rel.lhs - rel.rhs
                    if d.free_symbols and not d.free_symbols & (exact or set()) and str(d) not in seen:
                        seen[str(d)] = sign(d)
    return tuple(seen.values())


def emissions_of(modules: Any) -> list[Emission]:
    """The declarations made by the modules named in ``modules`` (or their submodules), in order."""
    mods = tuple(modules)
    return [e for e in EMISSIONS.values()
            if any(e.declared_in == m or e.declared_in.startswith(m + ".") for m in mods)]
