"""Render the emitted Python modules: closed form (:mod:`.derive`) or transfer-matrix form (:mod:`.emit_loop`).

Every module has the same surface: ``N``, ``FORM``, the typed errors, and for each
function of :data:`~symbt.codegen.derive.FUNCTIONS` a numpy flavour ``name(...)``
and an mpmath flavour ``name_mp(...)``, plus ``bt_orbit``/``bt_orbit_mp``.

>>> "def bt_step_mp(" in module_body(2)
True
"""
from __future__ import annotations

import re

from .derive import specs
from .emit_loop import loop_module_body
from .forms import FORMS, form_of
from .printer import cse_block
from .pymodule import function_doc, module_head, numpy_epilogue, numpy_prologue, package_init_body, signature
from .runtime import ORBIT

__all__ = ["module_body", "package_init_body", "form_of"]

_INT = re.compile(r"^\(?-?\d+\)?$")


def _names(spec):
    names = {}
    for a in spec.args:
        if a.kind == "state":
            for s in a.symbols:
                names[s] = str(s)
        else:
            names[a.symbols[0]] = a.name
    return names


def _function_numpy(spec, N):
    lines = numpy_prologue(spec, N, "closed")
    for a in spec.args:
        if a.kind == "state":
            for i, s in enumerate(a.symbols):
                lines.append(f"    {s} = {a.name}[..., {i}]")
    exprs = [g.expr for g in spec.guards] + [e for o in spec.outputs for e in o.exprs]
    body, outs = cse_block(exprs, _names(spec), "numpy")
    lines.append("    with np.errstate(all=\"ignore\"):")
    lines += [f"        {ln}" for ln in body]
    guards = outs[:len(spec.guards)]
    k = len(spec.guards)
    res = []
    for o in spec.outputs:
        items = outs[k:k + len(o.exprs)]
        k += len(o.exprs)
        lines.append(f"        {o.name} = _pack([{', '.join(items)}], _batch, {o.shape!r})")
        res.append(o.name)
    gl = ", ".join(f"({g.condition!r}, {g.label!r}, {t})" for g, t in zip(spec.guards, guards))
    lines += numpy_epilogue(spec, res, f"[{gl}]")
    return "\n".join(lines)


def _function_mpmath(spec, N):
    lines = [f"def {spec.name}_mp({signature(spec, 'mpmath')}):", function_doc(spec, N, "mpmath", "closed")]
    for a in spec.args:
        if a.kind == "state":
            syms = ", ".join(str(s) for s in a.symbols)
            lines.append(f"    {syms} = _mp_state({a.name}, {N}, {a.name!r})")
        elif a.kind == "branch":
            lines.append(f"    {a.name} = _mp_branch({a.name})")
        else:
            lines.append(f"    {a.name} = _mp_value({a.name}, {a.name!r})")
    lines.append("    try:")
    for stage in (0, 1):
        gs = [g for g in spec.guards if g.stage == stage]
        exprs = [g.expr for g in gs]
        if stage == 1:
            exprs += [e for o in spec.outputs for e in o.exprs]
        if not exprs:
            continue
        body, outs = cse_block(exprs, _names(spec), "mpmath", prefix="s" if stage == 0 else "t")
        lines += [f"        {ln}" for ln in body]
        for g, t in zip(gs, outs):
            lines.append(f"        _mp_guard({g.condition!r}, {g.label!r}, {t})")
    outs = outs[len(gs):]
    res, k = [], 0
    for o in spec.outputs:
        items = [f"mpmath.mpf({t})" if _INT.match(t) else t for t in outs[k:k + len(o.exprs)]]
        k += len(o.exprs)
        if o.shape == ():
            val = items[0]
        elif len(o.shape) == 1:
            val = "[" + ", ".join(items) + "]"
        else:
            n = o.shape[1]
            rows = ["[" + ", ".join(items[r * n:(r + 1) * n]) + "]" for r in range(o.shape[0])]
            val = "[" + ", ".join(rows) + "]"
        lines.append(f"        {o.name} = {val}")
        res.append(o.name)
    lines.append("    except ZeroDivisionError as exc:")
    lines.append("        raise NumericRangeError('division by zero (degenerate eigenvector)') from exc")
    lines.append(f"    return {', '.join(res)}")
    return "\n".join(lines)


def module_body(N: int, form: str | None = None) -> str:
    """Everything after the provenance header of ``toda{N}.py``; ``form`` defaults to :func:`form_of`."""
    form = form_of(N) if form is None else form
    if form not in FORMS:
        raise ValueError(f"unknown form {form!r}")
    if form != "closed":
        return loop_module_body(N)
    sp_ = specs(N)
    parts = module_head(N, "closed")
    for s in sp_:
        parts += ["", "", _function_numpy(s, N)]
    for s in sp_:
        parts += ["", "", _function_mpmath(s, N)]
    parts.append(ORBIT.rstrip("\n"))
    return "\n".join(parts) + "\n"
