"""``sympy.lambdify`` with plain argument names, memoised on the expression it prints.

Claims and the numeric screen turn the same SymPy expressions into functions again and again (a
statement's sides in several claims, the same weight in every cell); printing and compiling one
costs a few milliseconds.  The memo is keyed on the arguments, the expression (SymPy objects
compare structurally, so a mutated statement is a new key) and the modules, and keeps the most
recent ``MAX_ENTRIES`` functions, so a mutation run does not grow it without bound.
"""
from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Iterable
from typing import Any

import sympy as sp

__all__ = ["plain_lambdify", "MAX_ENTRIES"]

MAX_ENTRIES = 512
_MEMO: OrderedDict[Any, Callable[..., Any]] = OrderedDict()


def _frozen(e: Any) -> Any:
    if isinstance(e, (list, tuple)):
        return type(e).__name__, tuple(_frozen(x) for x in e)
    if isinstance(e, sp.MatrixBase):
        return type(e).__name__, sp.ImmutableMatrix(e)
    return sp.sympify(e)


def _modules_key(modules: Any) -> Any:
    # namespace dicts are module constants: their identity names them
    if isinstance(modules, (list, tuple)):
        return tuple(id(m) if isinstance(m, dict) else m for m in modules)
    return modules


def _plain(args: list[Any], e: Any, sub: dict[Any, Any]) -> Any:
    if isinstance(e, (list, tuple)):
        return type(e)(_plain(args, x, sub) for x in e)
    if isinstance(e, sp.MatrixBase):
        return e.xreplace(sub)
    return sp.sympify(e).xreplace(sub)


def plain_lambdify(args: Iterable[Any], expr: Any, modules: Any = "mpmath") -> Callable[..., Any]:
    """``sympy.lambdify(args, expr, modules)`` with the arguments renamed ``_a0, _a1, ...`` (symbols such as
    ``lambda`` break the printer); ``expr`` may be a nested list.  Memoised.

    >>> lam, x = sp.symbols("lambda x")
    >>> f = plain_lambdify([lam, x], lam * x + 1)
    >>> f(2, 3), plain_lambdify([lam, x], lam * x + 1) is f
    (7, True)
    """
    args = list(args)
    key = (tuple(args), _frozen(expr), _modules_key(modules))
    f = _MEMO.get(key)
    if f is None:
        plain = [sp.Symbol(f"_a{i}") for i in range(len(args))]
        f = sp.lambdify(plain, _plain(args, expr, dict(zip(args, plain))), modules)
        _MEMO[key] = f
        if len(_MEMO) > MAX_ENTRIES:
            _MEMO.popitem(last=False)
    else:
        _MEMO.move_to_end(key)
    return f
