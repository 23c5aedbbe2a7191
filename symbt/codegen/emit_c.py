"""Render ``toda{N}.c`` and ``toda{N}.h`` (C99, libm only): ``bt_step``, ``invariants``, ``spectral_trace``,
``flow_field``, with the status codes of :data:`symbt.codegen.c_template.HEADER`.

* closed form (N < ``LOOP_FROM``): the expressions of :func:`symbt.codegen.derive.specs` after CSE,
  printed by the ``c`` flavour of :class:`~symbt.codegen.printer.ExprPrinter`; the guards become
  status codes;
* transfer-matrix form: :data:`~symbt.codegen.c_template.LOOP` with the kernels of
  :mod:`symbt.codegen.kernels` printed in.  Updates of polynomials in lambda are printed
  coefficient-wise (``a = lambda + p_j`` substituted, the coefficient of ``lambda`` reads
  coefficient ``k - 1``), and ``tr(dm P S)`` contracted with ``c`` term by term.

>>> src, hdr = c_files(5)
>>> "int toda5_bt_step(" in src and "SYMBT_TODA_RANGE 3" in hdr
True
"""
from __future__ import annotations

import re

import sympy as sp

from .c_template import COMMON, HEADER, LOOP
from .derive import FunctionSpec, specs
from .forms import form_of
from .kernels import kernels
from .printer import ExprPrinter, cse_block

__all__ = ["c_files", "C_FUNCTIONS"]

#: the emitted C functions (same meaning as the Python functions of the same name)
C_FUNCTIONS = ("bt_step", "invariants", "spectral_trace", "flow_field")
_MARK = re.compile(r"@@(?:(coef|cdot):)?(\w+)(?:\[(\d)\])?(?:\{([^}]*)\})?@@")
_lam, _pj = sp.symbols("lambda pj", real=True)


def _kernel(name: str, item: str | None) -> sp.Basic:
    k = kernels()[name]
    return k[int(item)] if item is not None else k


def _names(expr: sp.Basic, binding: str | None = None) -> dict[sp.Basic, str]:
    names = {s: str(s) for s in expr.free_symbols}
    for pair in filter(None, (binding or "").split(",")):
        sym, _, text = pair.partition(":")
        names[sp.Symbol(sym.strip(), real=True)] = text.strip()
    return names


def _coefficientwise(expr: sp.Expr) -> str:
    """A kernel linear in the entries ``A, B, C, D`` with ``a = lambda + p_j``: coefficient ``k`` of the
    result in terms of the coefficients of the entries (stored at ``X[k + 1]``, so ``X[k]`` is k - 1)."""
    a = sp.Symbol("a", real=True)
    e = sp.expand(expr.xreplace({a: _lam + _pj}))
    e1, e0 = e.coeff(_lam, 1), e.coeff(_lam, 0)
    if sp.expand(e - _lam * e1 - e0) != 0:
        raise AssertionError(f"update {expr} is not of degree 1 in lambda")
    entries = sp.symbols("A B C D", real=True)
    n1 = {s: (f"{s}[k]" if s in entries else str(s)) for s in e1.free_symbols}
    n0 = {s: (f"{s}[k + 1]" if s in entries else str(s)) for s in e0.free_symbols}
    parts = [ExprPrinter("c", n).text(x) for x, n in ((e1, n1), (e0, n0)) if x != 0]
    return " + ".join(f"({t})" for t in parts)


def _contracted(expr: sp.Expr, N: int) -> str:
    """``sum_k c_k [lambda^k]`` of a kernel bilinear in the prefix ``Pxy`` and suffix ``Sxy`` entries."""
    out = []
    for term in sp.Add.make_args(sp.expand(expr)):
        coeff, factors = term.as_coeff_mul()
        P = [f for f in factors if str(f).startswith("P")]
        S = [f for f in factors if str(f).startswith("S")]
        if len(P) != 1 or len(S) != 1 or len(factors) != 2 or not coeff.is_Integer:
            raise AssertionError(f"kernel term {term} is not c * P * S")
        call = f"toda{N}_cdot(c, pre[j][e{str(P[0])[1:]}], suf[j][e{str(S[0])[1:]}])"
        out.append(call if coeff == 1 else f"{int(coeff)}.0*{call}")
    return " + ".join(out)


def _fill(template: str, N: int, form: str) -> str:
    def repl(m: re.Match[str]) -> str:
        kind, name, item, binding = m.groups()
        if name == "N" and kind is None:
            return str(N)
        if name == "FORM":
            return form
        expr = _kernel(name, item)
        if kind == "coef":
            return _coefficientwise(expr)
        if kind == "cdot":
            return _contracted(expr, N)
        return ExprPrinter("c", _names(expr, binding)).text(expr)

    return _MARK.sub(repl, template)


# --------------------------------------------------------------------------- closed form

_SIGNATURES = {
    "bt_step": "int toda{N}_bt_step(const double *p, const double *q, double lam0, double mu, int branch,\n"
               "                      double *pt, double *qt)",
    "invariants": "int toda{N}_invariants(const double *p, const double *q, double *H)",
    "spectral_trace": "int toda{N}_spectral_trace(double lam, const double *p, const double *q, double *tr)",
    "flow_field": "int toda{N}_flow_field(const double *c, const double *p, const double *q, double *qdot, "
                  "double *pdot)",
}
_OUT_PTRS = {"bt_step": ("pt", "qt"), "invariants": ("H",), "spectral_trace": ("tr",), "flow_field": ("qdot", "pdot")}
_CODES = {"trace": "SYMBT_TODA_NO_REAL_MAP_TRACE", "positivity": "SYMBT_TODA_NO_REAL_MAP_POSITIVITY"}


def _closed_function(spec: FunctionSpec, N: int) -> str:
    names = {}
    checks_ptr, checks_fin = [], []
    for a in spec.args:
        if a.kind == "state":
            checks_ptr.append(a.name)
            checks_fin.append(f"!toda{N}_finite({a.name}, NS)")
            for i, s in enumerate(a.symbols):
                names[s] = f"{a.name}[{i}]"
        elif a.kind == "branch":
            names[a.symbols[0]] = "b"
        else:
            checks_fin.append(f"!isfinite({a.name})")
            names[a.symbols[0]] = a.name
    outs = _OUT_PTRS[spec.name]
    lines = [_SIGNATURES[spec.name].format(N=N), "{"]
    lines.append(f"    if ({' || '.join('!' + x for x in checks_ptr + list(outs))})")
    lines.append("        return SYMBT_TODA_INVALID_INPUT;")
    if any(a.kind == "branch" for a in spec.args):
        lines.append("    if (branch != 1 && branch != -1)")
        lines.append("        return SYMBT_TODA_INVALID_INPUT;")
    lines.append(f"    if ({' || '.join(checks_fin)})")
    lines.append("        return SYMBT_TODA_INVALID_INPUT;")
    if any(a.kind == "branch" for a in spec.args):
        lines.append("    const double b = (double)branch;")
    exprs = [g.expr for g in spec.guards] + [e for o in spec.outputs for e in o.exprs]
    body, printed = cse_block(exprs, names, "c")
    lines += [f"    const double {ln};" for ln in body]
    gl, vals = printed[:len(spec.guards)], printed[len(spec.guards):]
    # in the spec's order, as the Python flavour decides: a non-finite guard is a range problem (and
    # decides nothing after it), a finite value <= 0 no real map ("range" guards need only be finite)
    for g, t in zip(spec.guards, gl):
        lines.append(f"    if (!isfinite({t}))")
        lines.append("        return SYMBT_TODA_RANGE;")
        if g.condition != "range":
            lines.append(f"    if (!({t} > 0.0))")
            lines.append(f"        return {_CODES[g.condition]};")
    lines.append(f"    const double out[{len(vals)}] = {{{', '.join(vals)}}};")
    lines.append(f"    if (!toda{N}_finite(out, {len(vals)}))")
    lines.append("        return SYMBT_TODA_RANGE;")
    k = 0
    for o, ptr in zip(spec.outputs, outs):
        n = len(o.exprs)
        lines.append(f"    for (int i = 0; i < {n}; i++)")
        lines.append(f"        {ptr}[i] = out[{k} + i];")
        k += n
    lines += ["    return SYMBT_TODA_OK;", "}"]
    return "\n".join(lines)


def c_files(N: int) -> tuple[str, str]:
    """``(toda{N}.c, toda{N}.h)`` bodies (without the provenance header)."""
    form = form_of(N)
    header = _fill(HEADER, N, form)
    src = _fill(COMMON, N, form)
    if form == "closed":
        by_name = {s.name: s for s in specs(N)}
        src += "\n/* ---- closed form: CSE of the SymPy expressions of symbt.codegen.derive ---- */\n"
        body = "".join("\n" + _closed_function(by_name[name], N) + "\n" for name in C_FUNCTIONS)
        if "sgn(" in body:   # the printer's sign (the guards' signs of the traces)
            src += "\nstatic double sgn(double x) { return (double)((x > 0.0) - (x < 0.0)); }\n"
        src += body
    else:
        src += _fill(LOOP, N, form)
    return src, header
