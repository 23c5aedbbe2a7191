r"""The Python flavours of a *typed* declaration (:mod:`.typed`): validated arrays, named outputs, guards.

numpy ``f(args, errors="raise")`` (the ``errors`` keyword only when there are guards):

1. every argument validated by the typed runtime (``_state`` for an array of shape ``(..., n)``,
   ``_branch`` for a sign, ``_scalar``; ``InvalidInputError`` on text, complex, non-finite values
   or a wrong shape) and the batch shape broadcast (``_batch_of``);
2. array elements unpacked (``p1 = p[..., 0]``); guards and outputs after one common-subexpression
   elimination (names ``t0, t1, ...``), under ``np.errstate(all="ignore")``;
3. ``_guard`` decides the guards in order (``NoRealMapError`` / masked), ``_finish`` turns a
   non-finite output into ``NumericRangeError`` (or a masked element); returns the outputs in
   declaration order (one output: the array itself).

mpmath ``f_mp(args)``: the same checks one state at a time (``_mp_state``, ``_mp_branch``,
``_mp_value``); the ``early`` guards after their own elimination (names ``s0, ...``), then the
others with the outputs (``t0, ...``), each decided by ``_mp_guard``; a division by zero raises
``NumericRangeError`` (the template's message).  Zullo's closed-form ``toda{2,3}.py`` are rendered
by exactly these two functions (:mod:`symbt.codegen.zullo`).

>>> import sympy as sp
>>> from .declare import emit
>>> from .typed import Guard
>>> x = sp.Symbol("x")
>>> e = emit("r", {"y": sp.sqrt(x)}, args=(("v", (x,)),), module="m", guards=[Guard("domain", "x", x)],
...          register=False)
>>> print(numpy_function(e).splitlines()[0])
def r(v, errors="raise"):
"""
from __future__ import annotations

import re
from typing import Any

from .declare import Emission
from .printing import cse, rewritten

__all__ = ["numpy_function", "mpmath_function", "typed_doc", "prepared"]

_INT = re.compile(r"^\(?-?\d+\)?$")


def prepared(e: Emission) -> tuple[list[Any], list[Any]]:
    """(guard expressions, output expressions), with ``expm1``/``log1p`` rewriting if ``e.optimize``."""
    gx = [g.expr for g in e.guards]
    ox = [x for o in e.outputs for x in o.exprs]
    if e.optimize:
        gx, ox = [rewritten(x) for x in gx], [rewritten(x) for x in ox]
    return gx, ox


def _names(e: Emission) -> dict[Any, str]:
    names = {}
    for a in e.params:
        if a.kind == "array":
            for s in a.symbols:
                names[s] = str(s)
        else:
            names[a.symbols[0]] = a.name
    return names


def _guarded(e: Emission) -> bool:
    return bool(e.guards) or (e.loop is not None and bool(e.loop.guards))


def _signature(e: Emission, flavour: str) -> str:
    sig = ", ".join(a.name for a in e.params)
    return sig + (', errors="raise"' if _guarded(e) and flavour == "numpy" else "")


def _size(e: Emission, symbols: tuple[object, ...]) -> str:
    return e.loop.size if e.loop is not None and e.loop.size is not None else str(len(symbols))


def typed_doc(e: Emission, flavour: str) -> str:
    """The docstring text: given verbatim (``doc={"numpy": ..., "mpmath": ...}``) or generated."""
    given = dict(e.docs).get(flavour)
    if given is not None:
        return given
    head = e.doc.strip() or f"{e.name}({', '.join(a.name for a in e.params)})"
    outs = ", ".join(f"{o.name} {list(o.shape) or 'scalar'}" for o in e.outputs)
    if flavour == "numpy":
        tail = ("numpy float64, vectorised: array arguments have shape (..., n), the others broadcast against "
                "the batch shape; returns " + outs + ".  InvalidInputError on malformed input")
        if _guarded(e):
            tail += ("; errors='raise' (default): NoRealMapError where a guard fails, NumericRangeError on a "
                     "non-finite value; errors='mask': masked arrays at those batch elements")
        else:
            tail += "; NumericRangeError on a non-finite value"
    else:
        tail = f"mpmath at the caller's precision (one state); returns {outs}; raises as the numpy flavour"
    return f"{head}\n\n    {tail}.\n    "


def validation_lines(params: list[tuple[str, str, str]], guarded: bool) -> list[str]:
    """The numpy flavour's input checks with the typed runtime, up to ``_batch``: one ``(name, kind,
    size)`` per argument (kind ``"array"`` of ``size`` entries -- the source text of the length --,
    ``"sign"`` or ``"scalar"``); ``guarded`` adds the ``errors`` mode.  Zullo's loop form uses it too.

    >>> validation_lines([("p", "array", "3"), ("b", "sign", "")], False)[-1]
    '    _batch = _batch_of([p.shape[:-1], b.shape])'
    """
    lines = ["    errors = _mode(errors)"] if guarded else []
    batch = []
    for name, kind, size in params:
        if kind == "array":
            lines.append(f"    {name} = _state({name}, {size}, {name!r})")
            batch.append(f"{name}.shape[:-1]")
        elif kind == "sign":
            lines.append(f"    {name} = _branch({name})")
            batch.append(f"{name}.shape")
        else:
            lines.append(f"    {name} = _scalar({name}, {name!r})")
            batch.append(f"{name}.shape")
    lines.append(f"    _batch = _batch_of([{', '.join(batch)}])")
    return lines


def numpy_function(e: Emission) -> str:
    """The numpy flavour of the typed declaration ``e``."""
    lines = [f"def {e.name}({_signature(e, 'numpy')}):", f'    """{typed_doc(e, "numpy")}"""']
    lines += validation_lines([(a.name, a.kind, _size(e, a.symbols)) for a in e.params], _guarded(e))
    if e.loop is not None:
        return "\n".join(lines + _loop_numpy(e))
    for a in e.params:
        if a.kind == "array":
            lines += [f"    {s} = {a.name}[..., {i}]" for i, s in enumerate(a.symbols)]
    gx, ox = prepared(e)
    body, outs = cse(gx + ox, _names(e), "numpy")
    lines.append("    with np.errstate(all=\"ignore\"):")
    lines += [f"        {ln}" for ln in body]
    k = len(e.guards)
    res = []
    for o in e.outputs:
        items = outs[k:k + len(o.exprs)]
        k += len(o.exprs)
        lines.append(f"        {o.name} = _pack([{', '.join(items)}], _batch, {o.shape!r})")
        res.append(o.name)
    names = ", ".join(res)
    if e.guards:
        gl = ", ".join(f"({g.condition!r}, {g.label!r}, {t})" for g, t in zip(e.guards, outs))
        lines += [f"        _bad = _guard(errors, _batch, [{gl}])",
                  f"    {names}, = _finish(errors, _bad, _batch, [{names}])"]
    else:
        lines.append(f"    {names}, = _finish('raise', None, _batch, [{names}])")
    lines.append(f"    return {names}")
    return "\n".join(lines)


def _loop_numpy(e: Emission) -> list[str]:
    """After the validation: the :class:`~.typed.Loop`'s statements, ``_pack``, guards and ``_finish``."""
    assert e.loop is not None
    lp, items = e.loop, dict(e.loop.items)
    lines = [f"    {ln}" for ln in lp.setup.splitlines()]
    lines.append("    with np.errstate(all=\"ignore\"):")
    lines += [f"        {ln}" for ln in lp.numpy.splitlines()]
    lines += [f"        {o.name} = _pack({items[o.name]}, _batch, {o.shape!r})" for o in e.outputs]
    names = ", ".join(o.name for o in e.outputs)
    if lp.guards:
        lines += [f"        _bad = _guard(errors, _batch, {lp.guards})",
                  f"    {names}, = _finish(errors, _bad, _batch, [{names}])"]
    else:
        lines.append(f"    {names}, = _finish('raise', None, _batch, [{names}])")
    return lines + [f"    return {names}"]


def mpmath_function(e: Emission, zero_division: str = "division by zero") -> str:
    """The mpmath flavour of the typed declaration ``e``."""
    lines = [f"def {e.name}_mp({_signature(e, 'mpmath')}):", f'    """{typed_doc(e, "mpmath")}"""']
    for a in e.params:
        if a.kind == "array" and e.loop is not None:    # kept whole: the loop indexes it
            lines.append(f"    {a.name} = _mp_state({a.name}, {_size(e, a.symbols)}, {a.name!r})")
        elif a.kind == "array":
            syms = ", ".join(str(s) for s in a.symbols) + ("," if len(a.symbols) == 1 else "")
            lines.append(f"    {syms} = _mp_state({a.name}, {len(a.symbols)}, {a.name!r})")
        elif a.kind == "sign":
            lines.append(f"    {a.name} = _mp_branch({a.name})")
        else:
            lines.append(f"    {a.name} = _mp_value({a.name}, {a.name!r})")
    lines.append("    try:")
    if e.loop is not None:
        lines += [f"        {ln}" for ln in e.loop.mpmath.splitlines()]
        return "\n".join(lines + ["    except ZeroDivisionError as exc:",
                                   f"        raise NumericRangeError({zero_division!r}) from exc",
                                   f"    return {', '.join(o.name for o in e.outputs)}"])
    outs: list[str] = []
    gs: list[Any] = []
    gx, ox = prepared(e)
    for early in (True, False):     # "illcond" guards are float64's: the mpmath flavour is the recomputation
        gs = [g for g in e.guards if g.early == early and g.condition != "illcond"]
        exprs = [x for g, x in zip(e.guards, gx) if g.early == early and g.condition != "illcond"] + (
            [] if early else ox)
        if not exprs:
            continue
        body, outs = cse(exprs, _names(e), "mpmath", prefix="s" if early else "t")
        lines += [f"        {ln}" for ln in body]
        lines += [f"        _mp_guard({g.condition!r}, {g.label!r}, {t})" for g, t in zip(gs, outs)]
    outs = outs[len(gs):]
    res, k = [], 0
    for o in e.outputs:
        items = [f"mpmath.mpf({t})" if _INT.match(t) else t for t in outs[k:k + len(o.exprs)]]
        k += len(o.exprs)
        if o.shape == ():
            val = items[0]
        elif len(o.shape) == 1:
            val = "[" + ", ".join(items) + "]"
        else:
            n = o.shape[1]
            val = "[" + ", ".join("[" + ", ".join(items[r * n:(r + 1) * n]) + "]" for r in range(o.shape[0])) + "]"
        lines.append(f"        {o.name} = {val}")
        res.append(o.name)
    lines.append("    except ZeroDivisionError as exc:")
    lines.append(f"        raise NumericRangeError({zero_division!r}) from exc")
    lines.append(f"    return {', '.join(res)}")
    return "\n".join(lines)
