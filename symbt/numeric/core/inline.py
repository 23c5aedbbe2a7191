"""Plain-Python instances of the fused step with the float64 operations written inline.

The fused step (:mod:`symbt.numeric.core.fused`) is written once against an arithmetic's functions
(``add(a, b)``, ``ld(u, j)``, ``st(u, j, x)`` ...).  numba compiles those calls away; plain Python pays a
call for each, 2-3x the time of the hand-written loop the package had before the step was written once
(BENCHMARKS.md, "Before and after the numeric redesign").  :func:`inlined` rewrites the source's syntax
tree so that, for float64, each such call *is* the operation -- ``add(a, b)`` -> ``(a + b)``,
``ld(u, j)`` -> ``u[j]``, ``st(u, j, x)`` -> ``u[j] = x``, ``hi(x)`` -> ``x`` -- which evaluates the same
IEEE operations in the same order, so the results are bit-identical to the called form.

>>> def f(a, b):
...     return mul2(add(a, b), 2.0)
>>> g = inlined(f, "f_inline", FLOAT64_INLINE, {})
>>> g(1.5, 2.25), "add" in g.__code__.co_names
(7.5, False)
"""
from __future__ import annotations

import ast
import inspect
import textwrap
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["FLOAT64_INLINE", "inlined"]

_BINARY = {"add": ast.Add, "add_d": ast.Add, "sub": ast.Sub, "mul": ast.Mult, "mul2": ast.Mult, "div": ast.Div}

#: the float64 arithmetic's calls that are single operations: name -> kind
FLOAT64_INLINE: Mapping[str, str] = {**{k: "binary" for k in _BINARY}, "neg": "neg", "hi": "identity",
                                     "ld": "load", "st": "store"}


class _Inline(ast.NodeTransformer):
    def __init__(self, kinds: Mapping[str, str]) -> None:
        self.kinds = kinds

    def _kind(self, node: ast.AST) -> str | None:
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and not node.keywords:
            return self.kinds.get(node.func.id)
        return None

    def visit_Call(self, node: ast.Call) -> ast.AST:
        self.generic_visit(node)
        kind, a = self._kind(node), node.args
        if kind == "binary" and len(a) == 2:
            return ast.BinOp(a[0], _BINARY[node.func.id](), a[1])      # type: ignore[attr-defined]
        if kind == "neg" and len(a) == 1:
            return ast.UnaryOp(ast.USub(), a[0])
        if kind == "identity" and len(a) == 1:
            return a[0]
        if kind == "load" and len(a) == 2:
            return ast.Subscript(a[0], a[1], ast.Load())
        return node

    def visit_Expr(self, node: ast.Expr) -> ast.AST:
        self.generic_visit(node)
        if self._kind(node.value) == "store" and len(node.value.args) == 3:   # type: ignore[attr-defined]
            arr, j, x = node.value.args                                      # type: ignore[attr-defined]
            return ast.Assign([ast.Subscript(arr, j, ast.Store())], x)
        return node


def inlined(fn: Callable[..., Any], name: str, kinds: Mapping[str, str],
            env: Mapping[str, Any]) -> Callable[..., Any]:
    """``fn`` recompiled from its source with the calls named in ``kinds`` written inline, named ``name``,
    with ``fn``'s module globals overridden by ``env``."""
    tree = ast.parse(textwrap.dedent(inspect.getsource(fn)))
    ast.increment_lineno(tree, fn.__code__.co_firstlineno - 1)      # tracebacks name the source's lines
    func = tree.body[0]
    assert isinstance(func, ast.FunctionDef)
    func.decorator_list = []
    func.name = name
    tree = ast.fix_missing_locations(_Inline(kinds).visit(tree))
    g = dict(fn.__globals__)
    g.update(env)
    ns: dict[str, Any] = {}
    exec(compile(tree, inspect.getsourcefile(fn) or "<inlined>", "exec"), g, ns)
    out = ns[name]
    out.__module__ = fn.__module__
    return out
