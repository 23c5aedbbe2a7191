"""Render :class:`~symbt.codegen.derive.FunctionSpec` lists into module source text."""
from __future__ import annotations

import re

from .derive import specs
from .printer import cse_block

__all__ = ["module_body", "package_init_body", "RUNTIME"]

_INT = re.compile(r"^\(?-?\d+\)?$")

# Hand-written runtime shared by every generated module (part of the derivation hash).
RUNTIME = '''
import mpmath
import numpy as np


def _Q(p, q):
    """Exact rational constant p/q at the caller's mpmath precision."""
    return mpmath.mpf(p) / q


def _state(x, n, name):
    a = np.asarray(x, dtype=np.float64)
    if a.ndim < 1 or a.shape[-1] != n:
        raise ValueError(f"{name} must have shape (..., {n}), got {a.shape}")
    return a


def _scalar(x):
    return np.asarray(x, dtype=np.float64)


def _branch(b):
    a = np.asarray(b, dtype=np.float64)
    if not np.all((a == 1.0) | (a == -1.0)):
        raise ValueError("branch must be +1 or -1")
    return a


def _pack(items, batch, shape):
    out = np.empty(batch + (len(items),), dtype=np.float64)
    for k, v in enumerate(items):
        out[..., k] = v
    return out.reshape(batch + shape)


def _mp_state(x, n, name):
    v = [mpmath.mpmathify(t) for t in x]
    if len(v) != n:
        raise ValueError(f"{name} must have length {n}, got {len(v)}")
    return v


def _mp_branch(b):
    if b not in (1, -1):
        raise ValueError("branch must be +1 or -1")
    return int(b)
'''


def _names(spec):
    names = {}
    for a in spec.args:
        if a.kind == "state":
            for s in a.symbols:
                names[s] = str(s)
        else:
            names[a.symbols[0]] = a.name
    return names


def _signature(spec):
    return ", ".join(a.name for a in spec.args)


def _doc(spec, N, flavour):
    args = "\n".join(f"        {a.name}: {a.doc}" for a in spec.args)
    if flavour == "numpy":
        shape = lambda o: "batch" + ("" if not o.shape else " + " + str(o.shape))  # noqa: E731
        kind = ("float64, vectorised: state arguments have shape (..., N), scalars broadcast "
                "against the batch shape; NaN outside the real domain")
    else:
        shape = lambda o: {0: "mpf", 1: "list", 2: "list of lists"}[len(o.shape)]  # noqa: E731
        kind = "mpmath at the current precision (single state; complex outside the real domain)"
    outs = "\n".join(f"        {o.name} ({shape(o)}): {o.doc}" for o in spec.outputs)
    return (f'    """{spec.summary} (eq. {spec.equation}, N={N}).\n\n'
            f"    {kind}.\n\n    Arguments:\n{args}\n\n    Returns:\n{outs}\n    \"\"\"")


def _function_numpy(spec, N):
    lines = [f"def {spec.name}({_signature(spec)}):", _doc(spec, N, "numpy")]
    batch = []
    for a in spec.args:
        if a.kind == "state":
            lines.append(f"    {a.name} = _state({a.name}, {N}, {a.name!r})")
            batch.append(f"{a.name}.shape[:-1]")
        elif a.kind == "branch":
            lines.append(f"    {a.name} = _branch({a.name})")
            batch.append(f"{a.name}.shape")
        else:
            lines.append(f"    {a.name} = _scalar({a.name})")
            batch.append(f"{a.name}.shape")
    lines.append(f"    _batch = np.broadcast_shapes({', '.join(batch)})")
    for a in spec.args:
        if a.kind == "state":
            for i, s in enumerate(a.symbols):
                lines.append(f"    {s} = {a.name}[..., {i}]")
    exprs = [e for o in spec.outputs for e in o.exprs]
    body, outs = cse_block(exprs, _names(spec), "numpy")
    lines.append("    with np.errstate(all=\"ignore\"):")
    lines += [f"        {ln}" for ln in body]
    res, k = [], 0
    for o in spec.outputs:
        items = outs[k:k + len(o.exprs)]
        k += len(o.exprs)
        lines.append(f"        {o.name} = _pack([{', '.join(items)}], _batch, {o.shape!r})")
        res.append(o.name)
    lines.append(f"    return {', '.join(res)}")
    return "\n".join(lines)


def _function_mpmath(spec, N):
    lines = [f"def {spec.name}_mp({_signature(spec)}):", _doc(spec, N, "mpmath")]
    for a in spec.args:
        if a.kind == "state":
            syms = ", ".join(str(s) for s in a.symbols)
            lines.append(f"    {syms} = _mp_state({a.name}, {N}, {a.name!r})")
        elif a.kind == "branch":
            lines.append(f"    {a.name} = _mp_branch({a.name})")
        else:
            lines.append(f"    {a.name} = mpmath.mpmathify({a.name})")
    exprs = [e for o in spec.outputs for e in o.exprs]
    body, outs = cse_block(exprs, _names(spec), "mpmath")
    lines += [f"    {ln}" for ln in body]
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
        lines.append(f"    {o.name} = {val}")
        res.append(o.name)
    lines.append(f"    return {', '.join(res)}")
    return "\n".join(lines)


def module_body(N: int) -> str:
    """Everything after the provenance header of ``toda{N}.py``."""
    sp_ = specs(N)
    names = [s.name for s in sp_]
    all_names = [n for s in sp_ for n in (s.name, s.name + "_mp")]
    doc = (f'"""Generated numeric code for the N={N} periodic Toda lattice (do not edit; run `symbt codegen`).\n\n'
           "Two flavours of every function: ``name(...)`` (numpy, float64, vectorised over leading\n"
           "batch axes) and ``name_mp(...)`` (mpmath at the current precision, exact rational\n"
           "constants).  Conventions: {p_i, q_j} = delta_ij, xdot = {H, x}; L = l_N ... l_1,\n"
           "tr L = sum_k H_k lambda^k (H_N = 1); branch b = +-1 means gamma_i = b sqrt(tr_i^2 - 4)\n"
           "(positive root) at lambda_1 = lambda_0 + mu, lambda_2 = lambda_0 - mu.\n\n"
           "Functions: " + ", ".join(names) + ".\n"
           '"""')
    parts = [doc, "", f"N = {N}", f"__all__ = {all_names!r}", RUNTIME.rstrip("\n")]
    for s in sp_:
        parts += ["", "", _function_numpy(s, N)]
    for s in sp_:
        parts += ["", "", _function_mpmath(s, N)]
    return "\n".join(parts) + "\n"


def package_init_body(Ns) -> str:
    return ('"""Generated numeric modules (``symbt codegen``); see docs/codegen.md.\n\n'
            "Each ``toda{N}`` module holds numpy and mpmath (``*_mp``) functions emitted from\n"
            "the SymPy derivations of :mod:`symbt.codegen.derive`.  Import a module lazily:\n"
            "``from symbt.generated import toda3`` (nothing is imported here).\n"
            '"""\n\n'
            f"MODULES = {tuple(f'toda{N}' for N in Ns)!r}\n"
            "__all__ = ['MODULES']\n")
