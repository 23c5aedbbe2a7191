"""Plain-Python instances of the fused step with the float64 operations and hooks written inline.

The fused step (:mod:`symbt.numeric.core.fused`) is written once against an arithmetic's functions
(``add(a, b)``, ``ld(u, j)``, ``track(aux, ...)`` ...).  numba compiles those calls away; plain Python
pays a call for each, 2-3x the time of the hand-written loop the package had before the step was
written once (BENCHMARKS.md, "Before and after the numeric redesign").  :func:`inlined` rewrites the
source's syntax tree so that those calls disappear, in two ways named by the ``kinds`` table:

* a *single operation* (kinds ``binary``, ``neg``, ``identity``, ``load``, ``store``) is written as the
  operator itself: ``add(a, b)`` -> ``(a + b)``, ``ld(u, j)`` -> ``u[j]``, ``st(u, j, x)`` ->
  ``u[j] = x``, ``hi(x)`` -> ``x``;
* a *body* (kind ``body``: a small plain-Python function of the arithmetic, such as float64's hooks)
  is substituted at the call: its locals renamed apart (``_track3_Aa``), its parameters replaced by the
  arguments (names and constants directly, other arguments bound once before), its numeric globals
  written as constants, its other globals bound under their own names, the plain functions of its own
  module it calls substituted in turn, and its ``return`` statements turned into assignments at the end
  of each path (the statements after an ``if`` that returns are copied into both branches; an assignment
  of names to themselves this leaves, ``a, b = a, b`` from a body returning its arguments, is dropped).  A call in
  the middle of an expression is computed by statements placed before its statement; the rewrite
  therefore refuses a body that writes to an array or calls an unknown function anywhere but at the
  root of its statement (``x = f(...)``, ``f(...)``, ``if [not] f(...):``), where that move changes
  nothing, and does not substitute bodies in ``while`` tests, in the branches of ``a if c else b`` or in
  the second operand of ``and``/``or`` (those calls stay calls).

After the substitution, a local that only ever holds a tuple of one size (float64's ``aux``), written
whole and read by unpacking or by constant index, becomes one local per element (no tuple is built).
With ``"/": "ieee"`` in ``kinds`` every division divides as IEEE arithmetic (numpy's scalars, numba):
``a / b if b else ieee_div0(a, b)``, so that the instance runs on Python floats (a third of the time of
numpy's scalars) where a Python float divided by zero would raise.

Either way the same IEEE operations run on the same operands, so the results are bit for bit those of
the called form (and of the numba instance; ``tests/test_numeric_inline.py``).  The order of
independent operations can change (arguments placed before their statement, a denominator before its
numerator); that never changes a result.

>>> def f(a, b):
...     return mul2(add(a, b), 2.0)
>>> g = inlined(f, "f_inline", FLOAT64_INLINE, {})
>>> g(1.5, 2.25), "add" in g.__code__.co_names
(7.5, False)
>>> def half_abs(x):
...     if x < 0.0:
...         return -0.5 * x
...     return 0.5 * x
>>> def h(a, b):
...     y = half_abs(add(a, b))
...     return y
>>> k = inlined(h, "h_inline", {**FLOAT64_INLINE, "half_abs": "body"}, {"half_abs": half_abs})
>>> k(-3.0, 1.0), "half_abs" in k.__code__.co_names
(1.0, False)
"""
from __future__ import annotations

import ast
import builtins
import copy
import inspect
import itertools
import math
import textwrap
import types
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["FLOAT64_INLINE", "inlined", "ieee_div0"]

_BINARY = {"add": ast.Add, "add_d": ast.Add, "sub": ast.Sub, "mul": ast.Mult, "mul2": ast.Mult, "div": ast.Div}

#: the float64 arithmetic's calls that are single operations: name -> kind
FLOAT64_INLINE: Mapping[str, str] = {**{k: "binary" for k in _BINARY}, "neg": "neg", "hi": "identity",
                                     "ld": "load", "st": "store", "/": "ieee"}

# functions a body may call at any position of a statement: they read their arguments only
_PURE_BUILTINS = frozenset({"abs", "max", "min", "float", "int", "bool", "range"})


class _Inline(ast.NodeTransformer):
    """The single operations, written as operators."""

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


class _Callee:
    """A function prepared for substitution: parameters, body without docstring, locals, purity."""

    def __init__(self, fn: Callable[..., Any]) -> None:
        if not isinstance(fn, types.FunctionType):
            raise TypeError("only a plain Python function can be written inline, not %r" % (fn,))
        tree = ast.parse(textwrap.dedent(inspect.getsource(fn)))
        func = tree.body[0]
        a = func.args                                              # type: ignore[attr-defined]
        if a.vararg or a.kwarg or a.kwonlyargs or a.posonlyargs or a.defaults:
            raise ValueError("%s: only plain positional parameters can be written inline" % fn.__name__)
        body = func.body                                           # type: ignore[attr-defined]
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]                                        # the docstring
        self.fn, self.body = fn, body
        self.params = [p.arg for p in a.args]
        stored = {n.id for s in body for n in ast.walk(s) if isinstance(n, ast.Name)
                  and isinstance(n.ctx, ast.Store)}
        self.locals = stored | set(self.params)
        self.rebound = stored & set(self.params)
        self.pure = not any(isinstance(n, (ast.Subscript, ast.Attribute)) and isinstance(n.ctx, ast.Store)
                            or isinstance(n, ast.Call) and not self._pure_call(n)
                            for s in body for n in ast.walk(s))
        loops = [n for s in body for n in ast.walk(s) if isinstance(n, (ast.For, ast.While, ast.With, ast.Try))]
        if any(_returns(n) for n in loops) or any(
                isinstance(n, (ast.Global, ast.Nonlocal, ast.FunctionDef, ast.Lambda, ast.Yield, ast.YieldFrom))
                for s in body for n in ast.walk(s)):
            raise ValueError("%s: returns inside loops, nested functions or global statements cannot be "
                             "written inline" % fn.__name__)

    def _pure_call(self, node: ast.Call) -> bool:
        """The call only reads its arguments: ``math.*``, a few builtins, a pure helper of the module."""
        f = node.func
        if isinstance(f, ast.Attribute):
            return isinstance(f.value, ast.Name) and f.value.id == "math"
        if not isinstance(f, ast.Name):
            return False
        if f.id in self.fn.__globals__:
            h = _helper(self.fn, f.id)
            return h is not None and _Callee(h).pure
        return f.id in _PURE_BUILTINS


def _helper(fn: Callable[..., Any], name: str) -> Callable[..., Any] | None:
    """The plain function ``name`` of ``fn``'s own module (substituted too), else None."""
    v = fn.__globals__.get(name)
    if isinstance(v, types.FunctionType) and v.__module__ == fn.__module__:
        return v
    return None


def _returns(node: ast.AST) -> bool:
    return any(isinstance(n, ast.Return) for n in ast.walk(node))


def _single_exit(stmts: list[ast.stmt], exit_: Callable[[ast.expr], list[ast.stmt]]) -> list[ast.stmt]:
    """``stmts`` with every ``return v`` replaced by ``exit_(v)`` at the end of its path."""
    out: list[ast.stmt] = []
    for i, s in enumerate(stmts):
        if isinstance(s, ast.Return):
            out.extend(exit_(s.value if s.value is not None else ast.Constant(None)))
            return out
        if isinstance(s, ast.If) and _returns(s):
            rest = stmts[i + 1:]
            body = _single_exit(s.body + copy.deepcopy(rest), exit_) or [ast.Pass()]
            orelse = _single_exit(s.orelse + copy.deepcopy(rest), exit_)
            out.append(ast.If(s.test, body, orelse))
            return out
        out.append(s)
    out.extend(exit_(ast.Constant(None)))
    return out


def _same(target: ast.expr, value: ast.expr) -> bool:
    """``target = value`` assigns every name to itself (``A, B = A, B``)."""
    if isinstance(target, ast.Name) and isinstance(value, ast.Name):
        return target.id == value.id
    if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) and len(target.elts) == len(value.elts):
        return all(_same(t, v) for t, v in zip(target.elts, value.elts))
    return False


class _Bodies:
    """Substitutes the bodies of the functions named ``body`` in a function's statements."""

    def __init__(self, bodies: Mapping[str, Callable[..., Any]], globals_: dict[str, Any]) -> None:
        self.bodies = dict(bodies)
        self.callees: dict[str, _Callee] = {}
        self.globals = globals_                  # the instance's globals; bodies' globals are added here
        self.count = itertools.count()

    def callee(self, name: str) -> _Callee:
        if name not in self.callees:
            self.callees[name] = _Callee(self.bodies[name])
        return self.callees[name]

    def is_body(self, node: ast.AST) -> bool:
        return (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in self.bodies
                and not node.keywords and not any(isinstance(a, ast.Starred) for a in node.args))

    # statements --------------------------------------------------------------------------------------
    def block(self, stmts: list[ast.stmt]) -> list[ast.stmt]:
        out: list[ast.stmt] = []
        for s in stmts:
            out.extend(self.stmt(s))
        return out

    def stmt(self, s: ast.stmt) -> list[ast.stmt]:
        pre: list[ast.stmt] = []
        if isinstance(s, ast.Assign) and len(s.targets) == 1 and self.is_body(s.value):
            target = s.targets[0]

            def assign(v: ast.expr) -> list[ast.stmt]:
                return [] if _same(target, v) else [ast.Assign([copy.deepcopy(target)], v)]
            body = self.substitute(s.value, pre, assign, root=True, at=s)       # type: ignore[arg-type]
            return pre + body                   # the arguments' statements, then the body's
        if isinstance(s, ast.Expr) and self.is_body(s.value):
            body = self.substitute(s.value, pre, lambda v: [], root=True, at=s)  # type: ignore[arg-type]
            return pre + body
        if isinstance(s, ast.If):
            t = s.test
            if isinstance(t, ast.UnaryOp) and isinstance(t.op, ast.Not) and self.is_body(t.operand):
                s.test = ast.UnaryOp(ast.Not(), self.value(t.operand, pre, root=True, at=s))  # type: ignore
            else:
                s.test = self.expr(t, pre, at=s)
            s.body, s.orelse = self.block(s.body), self.block(s.orelse)
        elif isinstance(s, ast.For):
            s.iter = self.expr(s.iter, pre, at=s)
            s.body, s.orelse = self.block(s.body), self.block(s.orelse)
        elif isinstance(s, ast.While):
            s.body, s.orelse = self.block(s.body), self.block(s.orelse)
        elif isinstance(s, (ast.Assign, ast.AugAssign, ast.AnnAssign, ast.Expr, ast.Return)) and s.value:
            s.value = self.expr(s.value, pre, at=s)
        return pre + [s]

    # expressions -------------------------------------------------------------------------------------
    def expr(self, e: ast.expr, pre: list[ast.stmt], at: ast.stmt) -> ast.expr:
        """``e`` with the bodies it always evaluates substituted (their statements appended to ``pre``)."""
        if self.is_body(e):
            return self.value(e, pre, root=False, at=at)                  # type: ignore[arg-type]
        if isinstance(e, ast.IfExp):
            e.test = self.expr(e.test, pre, at)
            return e
        if isinstance(e, ast.BoolOp):
            e.values[0] = self.expr(e.values[0], pre, at)
            return e
        if isinstance(e, (ast.Lambda, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)):
            return e
        for field, old in ast.iter_fields(e):
            if isinstance(old, ast.expr):
                setattr(e, field, self.expr(old, pre, at))
            elif isinstance(old, list):
                old[:] = [self.expr(x, pre, at) if isinstance(x, ast.expr) else x for x in old]
        return e

    def value(self, call: ast.Call, pre: list[ast.stmt], root: bool, at: ast.stmt) -> ast.expr:
        """The call's result as an expression: the body's one returned expression, or a fresh name."""
        result = "_%s%d_result" % (call.func.id.lstrip("_"), next(self.count))   # type: ignore[attr-defined]
        got: list[ast.expr] = []

        def bind(v: ast.expr) -> list[ast.stmt]:
            got.append(v)
            return [ast.Assign([ast.Name(result, ast.Store())], v)]
        stmts = self.substitute(call, pre, bind, root=root, at=at)
        if len(stmts) == 1 and len(got) == 1 and isinstance(stmts[0], ast.Assign) and stmts[0].value is got[0]:
            return got[0]                   # a single expression: no statement, no name
        pre.extend(stmts)
        return ast.Name(result, ast.Load())

    def substitute(self, call: ast.Call, pre: list[ast.stmt], exit_: Callable[[ast.expr], list[ast.stmt]],
                   root: bool, at: ast.stmt) -> list[ast.stmt]:
        """The statements of ``call``'s body (after ``pre``, which receives the arguments' own)."""
        name = call.func.id                                               # type: ignore[attr-defined]
        c = self.callee(name)
        if not c.pure and not root:
            raise ValueError("%s writes to an array or calls an unknown function: it can be written inline "
                             "only at the root of its statement (line %d)" % (name, at.lineno))
        if len(call.args) != len(c.params):
            raise TypeError("%s takes %d arguments, %d given" % (name, len(c.params), len(call.args)))
        args = [self.expr(a, pre, at) for a in call.args]
        tag = "_%s%d_" % (name.lstrip("_"), next(self.count))
        subst: dict[str, ast.expr] = {}
        binds: list[ast.stmt] = []
        for p, a in zip(c.params, args):
            if isinstance(a, (ast.Name, ast.Constant)) and p not in c.rebound:
                subst[p] = a
            else:
                binds.append(ast.Assign([ast.Name(tag + p, ast.Store())], a))
        body = [self._resolve(copy.deepcopy(s), c, tag, subst) for s in c.body]
        out = binds + self.block(_single_exit(body, exit_))
        for s in out:
            for n in ast.walk(s):
                if "lineno" in n._attributes:         # tracebacks name the call's line
                    ast.copy_location(n, at)
        return out

    def _resolve(self, s: ast.stmt, c: _Callee, tag: str, subst: Mapping[str, ast.expr]) -> ast.stmt:
        """Locals renamed apart, parameters replaced, globals bound (helpers of the module: bodies)."""
        outer = self

        class Resolve(ast.NodeTransformer):
            def visit_Name(self, n: ast.Name) -> ast.AST:
                if n.id in subst and isinstance(n.ctx, ast.Load):
                    return copy.deepcopy(subst[n.id])
                if n.id in c.locals:
                    return ast.Name(tag + n.id, n.ctx)
                return outer.global_name(c.fn, n.id, n.ctx)

        return Resolve().visit(s)

    def global_name(self, fn: Callable[..., Any], name: str, ctx: ast.expr_context) -> ast.expr:
        g = fn.__globals__
        if name not in g:
            if not hasattr(builtins, name):
                raise NameError("%s: unknown name %r" % (fn.__name__, name))
            return ast.Name(name, ctx)                                     # a builtin
        v = g[name]
        if type(v) in (float, int, bool):
            return ast.Constant(v)                                         # exact: the value itself
        helper = _helper(fn, name)
        if helper is not None:
            own = "_inline_%s" % name.lstrip("_")
            if own not in self.bodies:
                self.bodies[own] = helper
            return ast.Name(own, ctx)
        if name in self.globals and self.globals[name] is not v:
            name = "_inline_%s_%s" % (fn.__name__.lstrip("_"), name)
        self.globals[name] = v
        return ast.Name(name, ctx)


def _names(node: ast.AST) -> set[str]:
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name)}


def _pairs(target: ast.expr, value: ast.expr, sizes: Mapping[str, int]) -> list[tuple[ast.expr, ast.expr]]:
    """``target = value`` as element assignments (``(a, b) = (x, y)``: ``a = x``, ``b = y``), the tuples
    held by the locals of ``sizes`` spread into one local each."""
    if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) and len(target.elts) == len(value.elts):
        return [pq for t, v in zip(target.elts, value.elts) for pq in _pairs(t, v, sizes)]
    if isinstance(target, ast.Name) and target.id in sizes and isinstance(value, ast.Tuple):
        return [pq for i, v in enumerate(value.elts) for pq in _pairs(ast.Name("%s__%d" % (target.id, i),
                                                                               ast.Store()), v, sizes)]
    if isinstance(target, ast.Tuple) and isinstance(value, ast.Name) and value.id in sizes:
        return [(t, ast.Name("%s__%d" % (value.id, i), ast.Load())) for i, t in enumerate(target.elts)]
    if isinstance(target, ast.Name) and isinstance(value, ast.Name) and target.id in sizes and value.id in sizes:
        return [(ast.Name("%s__%d" % (target.id, i), ast.Store()), ast.Name("%s__%d" % (value.id, i), ast.Load()))
                for i in range(sizes[value.id])]
    return [(target, value)]


def _index(n: ast.AST) -> int | None:
    """``k`` for ``name[k]`` read with a constant ``k >= 0``, else None."""
    if isinstance(n, ast.Subscript) and isinstance(n.value, ast.Name) and isinstance(n.ctx, ast.Load) and \
            isinstance(n.slice, ast.Constant) and type(n.slice.value) is int and n.slice.value >= 0:
        return n.slice.value
    return None


def _tuple_locals(func: ast.FunctionDef) -> dict[str, int]:
    """The locals that only ever hold tuples of one size, written whole and read by unpacking or by a
    constant index: name -> size."""
    sizes: dict[str, int] = {}
    allowed: set[int] = set()
    bad = {a.arg for a in func.args.args}

    def size(name: str, k: int) -> None:
        if sizes.setdefault(name, k) != k:
            bad.add(name)

    def note(target: ast.expr, value: ast.expr) -> None:
        if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) and len(target.elts) == len(value.elts):
            for t, v in zip(target.elts, value.elts):
                note(t, v)
        elif isinstance(target, ast.Name) and isinstance(value, ast.Tuple) and \
                not any(isinstance(e, ast.Starred) for e in value.elts):
            allowed.add(id(target))
            size(target.id, len(value.elts))
        elif isinstance(target, ast.Tuple) and isinstance(value, ast.Name) and \
                all(isinstance(e, ast.Name) for e in target.elts):
            allowed.add(id(value))
            size(value.id, len(target.elts))

    for n in ast.walk(func):
        if isinstance(n, ast.Assign) and len(n.targets) == 1:
            note(n.targets[0], n.value)
        elif _index(n) is not None:
            allowed.add(id(n.value))                                       # type: ignore[attr-defined]
    for n in ast.walk(func):
        k = _index(n)
        if k is not None and isinstance(n, ast.Subscript) and isinstance(n.value, ast.Name) and \
                not k < sizes.get(n.value.id, 0):
            bad.add(n.value.id)                     # an index past the tuple (or never a whole tuple)
        if isinstance(n, ast.Name) and id(n) not in allowed:
            bad.add(n.id)
    return {k: v for k, v in sizes.items() if k not in bad}


class _SpreadTuples(ast.NodeTransformer):
    """Each local of ``sizes`` held as one local per element: no tuple is built or unpacked."""

    def __init__(self, sizes: Mapping[str, int]) -> None:
        self.sizes = sizes

    def visit_Subscript(self, n: ast.Subscript) -> ast.AST:
        k = _index(n)
        if k is not None and n.value.id in self.sizes:                 # type: ignore[attr-defined]
            return ast.copy_location(ast.Name("%s__%d" % (n.value.id, k), ast.Load()), n)  # type: ignore
        return self.generic_visit(n)

    def visit_Assign(self, n: ast.Assign) -> ast.AST | list[ast.stmt]:
        self.generic_visit(n)
        if len(n.targets) != 1:
            return n
        pairs = _pairs(n.targets[0], n.value, self.sizes)
        if len(pairs) == 1 and pairs[0][0] is n.targets[0]:
            return n
        # one assignment per element where no later element reads an earlier target, else all at once
        stored = [_names(t) for t, _ in pairs]
        if all(not (stored[i] & _names(v)) for j, (_, v) in enumerate(pairs) for i in range(j)):
            return [ast.copy_location(ast.Assign([t], v), n) for t, v in pairs if not _same(t, v)]
        return ast.copy_location(ast.Assign([ast.Tuple([t for t, _ in pairs], ast.Store())],
                                            ast.Tuple([v for _, v in pairs], ast.Load())), n)


def ieee_div0(a: float, b: float) -> float:
    """``a / b`` for ``b = +-0`` as IEEE arithmetic (numpy's scalars, numba) gives it: ``+-inf``, or NaN
    where ``a`` is zero or NaN (the same NaN: ``0 * inf`` is the processor's default NaN, as ``0 / 0``).

    >>> ieee_div0(1.0, -0.0), ieee_div0(-2.0, 0.0), ieee_div0(0.0, 0.0) != ieee_div0(0.0, 0.0)
    (-inf, -inf, True)
    """
    return a * math.inf * math.copysign(1.0, b)


class _IeeeDivision(ast.NodeTransformer):
    """``a / b`` -> ``a / b if b else ieee_div0(a, b)`` (``b`` evaluated once): a Python float divided by
    zero raises, an IEEE one is ``+-inf`` or NaN."""

    def __init__(self) -> None:
        self.count = itertools.count()

    def visit_BinOp(self, n: ast.BinOp) -> ast.AST:
        self.generic_visit(n)
        if not isinstance(n.op, ast.Div) or isinstance(n.right, ast.Constant) and n.right.value:
            return n
        if isinstance(n.right, (ast.Name, ast.Constant)):
            test: ast.expr = n.right
            d: ast.expr = n.right
        else:
            name = "_div%d" % next(self.count)
            test, d = ast.NamedExpr(ast.Name(name, ast.Store()), n.right), ast.Name(name, ast.Load())
        zero = ast.Call(ast.Name("_inline_ieee_div0", ast.Load()), [copy.deepcopy(n.left), copy.deepcopy(d)], [])
        return ast.copy_location(ast.IfExp(test, ast.BinOp(n.left, ast.Div(), copy.deepcopy(d)), zero), n)


def inlined(fn: Callable[..., Any], name: str, kinds: Mapping[str, str],
            env: Mapping[str, Any]) -> Callable[..., Any]:
    """``fn`` recompiled from its source with the calls named in ``kinds`` written inline, named ``name``,
    with ``fn``'s module globals overridden by ``env`` (where the functions of kind ``body`` are looked up;
    examples in the module docstring).  Raises ``ValueError`` or ``TypeError`` for a call it cannot write
    inline as the module docstring says (rather than changing what runs)."""
    tree = ast.parse(textwrap.dedent(inspect.getsource(fn)))
    ast.increment_lineno(tree, fn.__code__.co_firstlineno - 1)      # tracebacks name the source's lines
    func = tree.body[0]
    assert isinstance(func, ast.FunctionDef)
    func.decorator_list = []
    func.name = name
    g = dict(fn.__globals__)
    g.update(env)
    bodies = {k: env[k] for k, kind in kinds.items() if kind == "body" and k in env}
    if bodies:
        func.body = _Bodies(bodies, g).block(func.body)
    tree = _Inline(kinds).visit(tree)
    if bodies:                  # the hooks' tuples (float64's aux) as one local per element
        func.body = _SpreadTuples(_tuple_locals(func)).visit(ast.Module(func.body, [])).body
    if kinds.get("/") == "ieee":
        tree = _IeeeDivision().visit(tree)
        g["_inline_ieee_div0"] = ieee_div0
    tree = ast.fix_missing_locations(tree)
    ns: dict[str, Any] = {}
    exec(compile(tree, inspect.getsourcefile(fn) or "<inlined>", "exec"), g, ns)
    out = ns[name]
    out.__module__ = fn.__module__
    return out

