r"""The C99 flavour of *typed* declarations (:mod:`.typed`): arrays by pointer, status codes, outputs on success.

ABI of a typed declaration ``f`` of module ``m`` (arguments in declaration order, then one pointer
per output)::

    int m_f(const double *<array>, double <scalar>, int <sign>, ..., double *<output>, ...);

The return value is a status code: ``OK`` (0); one code per guard condition, numbered from 1 in
order of first appearance; ``RANGE`` (a guard or an output not finite); ``INVALID_INPUT`` (a NULL
pointer, a non-finite input, a sign not +-1).  Guards are decided in declaration order as in the
Python flavour: a non-finite guard value is ``RANGE`` and decides nothing after it, a finite value
<= 0 is its condition's code (a ``range`` guard need only be finite).  Outputs are written only on
``OK``.

A :class:`CTemplate` gives the hand-written parts: the ``.h`` text, the ``.c`` prologue (which must
define the ``finite(const double *x, int n)`` helper it names), the status macros, and optionally a
verbatim signature per function; without one the header and prologue are generated
(:func:`default_template`).  Zullo's closed-form ``toda{2,3}.c``/``.h`` are rendered so
(:mod:`symbt.codegen.zullo`).

>>> import sympy as sp
>>> from .declare import emit
>>> from .typed import Guard
>>> x = sp.Symbol("x")
>>> e = emit("root", {"r": sp.sqrt(x)}, args=(("v", (x,)),), module="m", guards=[Guard("domain", "x", x)],
...          register=False)
>>> print(c_function(e, default_template("m", [e])).splitlines()[0])
int m_root(const double *v, double *r)
"""
from __future__ import annotations

from dataclasses import dataclass

from .declare import Emission
from .printing import cse
from .render_typed import prepared

__all__ = ["CTemplate", "c_function", "c_files", "default_template", "SGN"]

SGN = "static double sgn(double x) { return (double)((x > 0.0) - (x < 0.0)); }"


@dataclass(frozen=True)
class CTemplate:
    """Hand-written parts of a typed C module (see the module docstring).

    ``status``: ``(key, macro)`` pairs for the keys ``ok``, ``range``, ``invalid`` and every guard
    condition; ``finite``: the prologue's helper ``int finite(const double *x, int n)``; ``length``:
    the C text of an array's length in that call (``None``: the number); ``signatures``:
    ``(name, text)`` verbatim prototypes; ``functions``: the declarations emitted in C, in order
    (empty: all); ``sign_local``: the name of a sign argument's ``double`` copy (``{name}`` is the
    argument); ``pointers``: ``(name, (pointer, ...))`` output pointer names (default: the output names)."""

    module: str
    header: str
    head: str
    status: tuple[tuple[str, str], ...]
    finite: str
    length: str | None = None
    signatures: tuple[tuple[str, str], ...] = ()
    functions: tuple[str, ...] = ()
    sign_local: str = "{name}_value"
    pointers: tuple[tuple[str, tuple[str, ...]], ...] = ()


def _signature(e: Emission, t: CTemplate) -> str:
    given = dict(t.signatures).get(e.name)
    if given is not None:
        return given
    ptrs = dict(t.pointers).get(e.name) or tuple(o.name for o in e.outputs)
    parts = [f"const double *{a.name}" if a.kind == "array" else f"int {a.name}" if a.kind == "sign"
             else f"double {a.name}" for a in e.params] + [f"double *{p}" for p in ptrs]
    return f"int {t.module}_{e.name}({', '.join(parts)})"


def c_function(e: Emission, t: CTemplate) -> str:
    """The C function of the typed declaration ``e`` under the template ``t`` (a :class:`~.typed.Loop`'s
    C text verbatim)."""
    if e.loop is not None:
        if not e.loop.c:
            raise ValueError(f"{e.name}: the Loop has no C text")
        return e.loop.c
    st = dict(t.status)
    names, ptrs, finite = {}, [], []
    signs = [a for a in e.params if a.kind == "sign"]
    for a in e.params:
        if a.kind == "array":
            ptrs.append(a.name)
            finite.append(f"!{t.finite}({a.name}, {t.length or len(a.symbols)})")
            names.update({s: f"{a.name}[{i}]" for i, s in enumerate(a.symbols)})
        elif a.kind == "sign":
            names[a.symbols[0]] = t.sign_local.format(name=a.name)
        else:
            finite.append(f"!isfinite({a.name})")
            names[a.symbols[0]] = a.name
    outs = dict(t.pointers).get(e.name) or tuple(o.name for o in e.outputs)
    lines = [_signature(e, t), "{",
             f"    if ({' || '.join('!' + x for x in ptrs + list(outs))})", f"        return {st['invalid']};"]
    for a in signs:
        lines += [f"    if ({a.name} != 1 && {a.name} != -1)", f"        return {st['invalid']};"]
    if finite:
        lines += [f"    if ({' || '.join(finite)})", f"        return {st['invalid']};"]
    lines += [f"    const double {t.sign_local.format(name=a.name)} = (double){a.name};" for a in signs]
    gx, ox = prepared(e)        # the expm1/log1p rewriting of the Python flavours (``optimize``)
    body, printed = cse(gx + ox, names, "c")
    lines += [f"    const double {ln};" for ln in body]
    gl, vals = printed[:len(e.guards)], printed[len(e.guards):]
    for g, v in zip(e.guards, gl):
        lines += [f"    if (!isfinite({v}))", f"        return {st['range']};"]
        if g.condition != "range":
            lines += [f"    if (!({v} > 0.0))", f"        return {st[g.condition]};"]
    lines += [f"    const double out[{len(vals)}] = {{{', '.join(vals)}}};",
              f"    if (!{t.finite}(out, {len(vals)}))", f"        return {st['range']};"]
    k = 0
    for o, ptr in zip(e.outputs, outs):
        n = len(o.exprs)
        lines += [f"    for (int i = 0; i < {n}; i++)", f"        {ptr}[i] = out[{k} + i];"]
        k += n
    lines += [f"    return {st['ok']};", "}"]
    return "\n".join(lines)


def c_files(emissions: list[Emission], t: CTemplate) -> tuple[str, str]:
    """``(<module>.c, <module>.h)`` bodies (without the provenance header) of the typed declarations."""
    chosen = [e for name in t.functions for e in emissions if e.name == name] if t.functions else list(emissions)
    body = "".join("\n" + c_function(e, t) + "\n" for e in chosen)
    src = t.head + ("\n" + SGN + "\n" if "sgn(" in body else "") + body
    return src, t.header


def default_template(module: str, emissions: list[Emission]) -> CTemplate:
    """The generated header and prologue of a typed C module without a template of its own."""
    up = module.upper()
    conds = list(dict.fromkeys(g.condition for e in emissions for g in e.guards if g.condition != "range"))
    keys = ["ok", *conds, "range", "invalid"]
    macro = {"ok": f"{up}_OK", "range": f"{up}_RANGE", "invalid": f"{up}_INVALID_INPUT",
             **{c: f"{up}_NO_REAL_{c.upper()}" for c in conds}}
    status = tuple((k, macro[k]) for k in keys)
    t = CTemplate(module, "", "", status, f"{module}_finite")
    guard = f"SYMBT_EMITTED_{up}_H"
    hdr = [f"/* {module}: typed functions emitted by symbt codegen (C99, libm only).  Return values: */",
           f"#ifndef {guard}", f"#define {guard}", ""]
    hdr += [f"#define {macro[k]} {i}" for i, k in enumerate(keys)] + [""]
    hdr += [_signature(e, t) + ";" for e in emissions] + ["", f"#endif /* {guard} */"]
    head = ["#include <math.h>", f'#include "{module}.h"', "",
            f"static int {module}_finite(const double *x, int n)", "{",
            "    for (int i = 0; i < n; i++)", "        if (!isfinite(x[i]))", "            return 0;",
            "    return 1;", "}"]
    return CTemplate(module, "\n".join(hdr) + "\n", "\n".join(head) + "\n", status, f"{module}_finite")
