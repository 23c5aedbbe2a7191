r"""The typed form of ``symbt.emit``: array arguments, several named outputs, ordered guards, module templates.

A declaration is *typed* when it uses any of these (:attr:`Emission.typed
<symbt.codegen.user.declare.Emission.typed>`); it is then emitted with symbt's typed-error
convention -- the one of Zullo's ``toda{N}`` modules -- instead of the plain ``nan``/``inf`` one:

* ``args`` items: a SymPy ``Symbol`` (a scalar), ``("p", [p1, p2, ...])`` (an array: numpy shape
  ``(..., n)``, validated -- :class:`InvalidInputError` on a wrong shape, text, complex or
  non-finite input), ``("b", b, "sign")`` (``+1`` or ``-1`` only), or an :class:`Arg`;
* ``expr`` a dict ``{"p_new": [...], "q_new": [...]}``: several named outputs, returned as a
  tuple in that order (each a scalar, a list -- a vector -- or a ``Matrix``);
* ``guards``: :class:`Guard` s decided in order, each ``expr > 0`` exactly where the function
  exists (``NoRealMapError(condition, where)``) or, with ``condition="range"``, only required
  finite (``NumericRangeError``); the numpy flavour takes ``errors="raise"`` or ``"mask"``
  (masked arrays at the failing batch elements);
* :func:`module_template`: hand-written text placed before (``head``) and after (``tail``) the
  rendered functions of a module -- a runtime, helpers such as Zullo's ``bt_orbit``.  Without a
  template a module with typed declarations gets symbt's typed runtime
  (:data:`symbt.codegen.runtime.RUNTIME`).

>>> import sympy as sp
>>> x = sp.Symbol("x")
>>> arg_of(("v", sp.symbols("v1 v2"))), arg_of(x).kind
(Arg(name='v', symbols=(v1, v2), kind='array'), 'scalar')
>>> Guard("domain", "x", x).early
False
"""
from __future__ import annotations

import keyword
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import sympy as sp

__all__ = ["Arg", "Output", "Guard", "Loop", "ModuleTemplate", "KINDS", "arg_of", "outputs_of", "module_template",
           "TEMPLATES"]

#: argument kinds: a float, an array of shape ``(..., n)``, a sign ``+-1``
KINDS = ("scalar", "array", "sign")
_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class Arg:
    """One argument of a typed declaration: ``kind`` is one of :data:`KINDS`; ``symbols`` the array's
    elements in order (one symbol for ``scalar`` and ``sign``)."""

    name: str
    symbols: tuple[sp.Symbol, ...]
    kind: str = "scalar"


@dataclass(frozen=True)
class Output:
    """One named output: ``shape`` () / (n,) / (r, c), ``exprs`` row-major."""

    name: str
    shape: tuple[int, ...]
    exprs: tuple[sp.Expr, ...]


@dataclass(frozen=True)
class Guard:
    """``expr > 0`` exactly where the function exists (else ``NoRealMapError`` with this ``condition``;
    ``label`` names the place in the message); ``condition="range"``: ``expr`` must only be finite
    (else ``NumericRangeError``).  ``early`` guards are decided before anything else is computed in the
    mpmath flavour (their expressions must not need the others)."""

    condition: str
    label: str
    expr: Any
    early: bool = False


@dataclass(frozen=True)
class Loop:
    """The body of a typed function written once as fixed template code (loops over sites, not
    expressions): ``emit(name, Loop(...), args=...)`` -- Zullo's transfer-matrix form.

    The renderers place it where a typed declaration's expressions would go, with the same signature,
    argument validation, ``_pack``/``_guard``/``_finish`` and error conventions: ``outputs`` the
    ``(name, shape)`` pairs returned; ``numpy`` the statements (under ``np.errstate``) computing them,
    ``items`` per output the source text of its ``_pack`` items; ``guards`` the source text of the
    guard list the statements fill (``""``: unguarded, no ``errors`` argument); ``setup`` statements
    before ``np.errstate``; ``mpmath`` the statements assigning the outputs (one state); ``size`` the
    source text of an array's length (default: its number of symbols), for arrays kept whole; ``c``
    the C function verbatim (:mod:`.render_typed_c`; the generated prologue defines
    ``static int <module>_finite(const double *x, int n)`` and the status macros).  A loop has no
    SymPy source: no ``domain=`` claims (verify it with claims of your own, as Zullo's ``codegen``
    scene does)."""

    outputs: tuple[tuple[str, tuple[Any, ...]], ...]
    numpy: str
    items: tuple[tuple[str, str], ...]
    mpmath: str
    guards: str = ""
    setup: str = ""
    size: str | None = None
    c: str = ""


@dataclass(frozen=True)
class ModuleTemplate:
    """Hand-written parts of an emitted module: ``head`` replaces the generated module head (docstring,
    imports, runtime), ``tail`` follows the functions; ``zero_division`` is the message of the
    ``NumericRangeError`` an mpmath flavour raises on a division by zero."""

    head: str
    tail: str = ""
    zero_division: str = "division by zero"


#: module name -> its template (see :func:`module_template`)
TEMPLATES: dict[str, ModuleTemplate] = {}


def module_template(module: str, *, head: str, tail: str = "", zero_division: str = "division by zero",
                    register: bool = True) -> ModuleTemplate:
    """Declare the hand-written parts of the emitted module ``module``: ``head`` (everything before the
    functions: docstring, imports, the runtime the typed functions call) and ``tail`` (after them).

    >>> t = module_template("demo_t", head="import numpy as np", register=False)
    >>> t.tail, t.zero_division
    ('', 'division by zero')
    """
    if not isinstance(module, str) or not _IDENT.match(module) or keyword.iskeyword(module):
        raise ValueError(f"module_template: module={module!r} must be an identifier")
    if not isinstance(head, str) or not isinstance(tail, str) or not head.strip():
        raise ValueError(f"module_template({module!r}): head (non-empty) and tail must be text")
    t = ModuleTemplate(head.rstrip("\n"), tail.rstrip("\n"), str(zero_division))
    if register:
        TEMPLATES[module] = t
    return t


def arg_of(item: Any) -> Arg:
    """An ``args`` item as an :class:`Arg` (``ValueError`` saying why when it is not one).

    >>> arg_of(("b", sp.Symbol("b"), "sign"))
    Arg(name='b', symbols=(b,), kind='sign')
    """
    if isinstance(item, Arg):
        a = item
    elif isinstance(item, sp.Symbol):
        a = Arg(item.name, (item,), "scalar")
    elif isinstance(item, tuple) and len(item) == 3 and item[2] == "sign":
        a = Arg(item[0], (item[1],), "sign")
    elif isinstance(item, tuple) and len(item) == 2:
        try:
            syms = tuple(item[1])
        except TypeError:
            raise ValueError(f"array argument {item[0]!r}: give a sequence of symbols") from None
        a = Arg(item[0], syms, "array")
    else:
        raise ValueError(f"an argument must be a Symbol, (name, [symbols]) or (name, symbol, 'sign'), got {item!r}")
    if a.kind not in KINDS:
        raise ValueError(f"argument {a.name!r}: kind must be one of {', '.join(KINDS)}, got {a.kind!r}")
    if not a.symbols or not all(isinstance(s, sp.Symbol) for s in a.symbols):
        raise ValueError(f"argument {a.name!r}: its elements must be SymPy symbols, got {a.symbols!r}")
    if a.kind != "array" and len(a.symbols) != 1:
        raise ValueError(f"argument {a.name!r}: a {a.kind} is one symbol")
    return a


def outputs_of(expr: dict[Any, Any],
               elements: Callable[[Any], tuple[tuple[sp.Expr, ...], tuple[int, ...]]]) -> tuple[Output, ...]:
    """The named outputs of a dict ``expr`` (``elements(value) -> (exprs, shape)`` splits each value)."""
    if not expr:
        raise ValueError("no outputs (an empty dict)")
    outs = []
    for key, value in expr.items():
        if not isinstance(key, str) or not _IDENT.match(key) or keyword.iskeyword(key):
            raise ValueError(f"output name {key!r} must be an identifier")
        exprs, shape = elements(value)
        outs.append(Output(key, shape, exprs))
    return tuple(outs)


def typed_domain(params: tuple[Arg, ...], domain: Any) -> Any:
    """The :class:`symbt.Domain` of a typed declaration over its elements: ``domain`` names a scalar by its
    argument (or symbol) name, an array by its name (every component drawn from that range) or by each of
    its element names (a box); a sign argument is not sampled (every sign is a cell, :func:`sign_cells`).
    ``ValueError`` saying what is wrong otherwise.

    >>> from symbt import Domain
    >>> x, y, b = sp.symbols("x y b")
    >>> typed_domain((Arg("z", (x, y), "array"), Arg("b", (b,), "sign")), Domain({"z": (0, 1)}, seed=2))
    Domain({x: uniform(0, 1), y: uniform(0, 1)}, seed=2)
    """
    from ...proof import Domain

    given = dict(domain.variables)
    variables: dict[str, Any] = {}
    for a in params:
        if a.kind == "sign":
            if a.name in given or a.symbols[0].name in given:
                raise ValueError(f"the domain names the sign argument {a.name!r}: every sign is a cell, "
                                 "not a sampled variable")
            continue
        elements = [s.name for s in a.symbols]
        whole = given.pop(a.name, None)
        if a.kind == "scalar" and whole is None:
            whole = given.pop(elements[0], None)
        parts = {n: given.pop(n) for n in elements if n in given}
        if whole is not None and parts:
            raise ValueError(f"the domain gives the array {a.name!r} both one range and ranges of its elements "
                             f"({', '.join(parts)})")
        if whole is None and len(parts) < len(elements):
            missing = [n for n in elements if n not in parts]
            what = (f"argument {a.name}" if a.kind == "scalar" else
                    f"array {a.name} (one range for it, or one for each of {', '.join(missing)})")
            raise ValueError(f"the domain lacks the {what}")
        variables.update({n: whole for n in elements} if whole is not None else parts)
    if given:
        raise ValueError(f"the domain names {', '.join(given)}, which is no argument or array element")
    return Domain(variables, where=domain.where, seed=domain.seed, draws_per_point=domain.draws_per_point)


def sign_cells(params: tuple[Arg, ...], cells: tuple[Any, ...]) -> tuple[Any, ...]:
    """One ``choice(name, (1, -1))`` per sign argument that ``cells`` does not split already.

    >>> [s.values for s in sign_cells((Arg("b", (sp.Symbol("b"),), "sign"),), ())]
    [(1, -1)]
    """
    from ...proof import choice

    have = {getattr(c, "name", None) for c in cells}
    return tuple(choice(a.name, (1, -1)) for a in params if a.kind == "sign" and a.name not in have)
