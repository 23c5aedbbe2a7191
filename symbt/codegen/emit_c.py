"""Render ``toda{N}.c`` and ``toda{N}.h`` (C99, libm only): ``bt_step``, ``invariants``, ``spectral_trace``,
``flow_field``, with the status codes of :data:`symbt.codegen.c_template.HEADER`.

* closed form (N < ``LOOP_FROM``): through ``symbt.emit`` -- the declarations of
  :mod:`symbt.codegen.zullo` rendered by :mod:`symbt.codegen.user.render_typed_c` under a C template
  holding Zullo's header, runtime, status codes and prototypes (the guards become status codes);
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
from typing import TYPE_CHECKING

import sympy as sp

from ..numeric.core.limits import KAPPA_MAX
from .c_template import COMMON, HEADER, LOOP
from .forms import form_of
from .kernels import kernels
from .printer import ExprPrinter

if TYPE_CHECKING:
    from .user.declare import Emission

__all__ = ["c_files", "C_FUNCTIONS", "loop_c_parts"]

#: the emitted C functions (same meaning as the Python functions of the same name)
C_FUNCTIONS = ("bt_step", "invariants", "spectral_trace", "flow_field")
_MARK = re.compile(r"@@(?:(coef|cdot):)?(\w+)(?:\[(\d)\])?(?:\{([^}]*)\})?@@")
_lam, _pj = sp.symbols("lambda pj", real=True)


def _kernel(name: str, item: str | None) -> sp.Expr:
    k = kernels()[name]
    return k[int(item)] if item is not None else k


def _names(expr: sp.Expr, binding: str | None = None) -> dict[sp.Symbol, str]:
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
_CODES = {"trace": "SYMBT_TODA_NO_REAL_MAP_TRACE", "positivity": "SYMBT_TODA_NO_REAL_MAP_POSITIVITY",
          "illcond": "SYMBT_TODA_ILL_CONDITIONED"}


def c_files(N: int) -> tuple[str, str]:
    """``(toda{N}.c, toda{N}.h)`` bodies (without the provenance header)."""
    form = form_of(N)
    header = _fill(HEADER.replace("@@KAPPA@@", str(int(KAPPA_MAX))), N, form)   # the one limit, printed in
    src = _fill(COMMON, N, form)
    if form == "closed":
        return _emit_path_c_files(N, header, src)
    return _loop_c_files(N, header, src)


_PUBLIC = re.compile(r"^int toda\d+_(\w+)\(", re.M)


def loop_c_parts(N: int) -> tuple[str, dict[str, str]]:
    """The transfer-matrix C of ``toda{N}`` (:data:`~symbt.codegen.c_template.LOOP`, kernels printed in) as
    ``(helpers, {function: text})``: the static helpers every function uses, then per public function its
    text verbatim, preceded by the helpers only it (and those after it) use -- the C of the ``Loop``
    declarations of :mod:`.zullo`."""
    text = _fill(LOOP.replace("@@KAPPA@@", str(int(KAPPA_MAX))), N, "transfer-matrix")
    found = list(_PUBLIC.finditer(text))
    parts: dict[str, str] = {}
    start = found[0].start()
    for m in found:
        end = text.index("\n}\n", m.start()) + 2
        parts[m.group(1)] = text[start:end].strip("\n")
        start = end
    if text[start:].strip():
        raise AssertionError(f"text after the last public function of the C template: {text[start:][:60]!r}")
    return text[:found[0].start()].rstrip("\n") + "\n", parts


_SECTION = "\n/* ---- closed form: CSE of the SymPy expressions of symbt.codegen.derive ---- */\n"


def _emit_path_c_files(N: int, header: str, common: str, ems: list[Emission] | None = None) -> tuple[str, str]:
    """The closed form through ``symbt.emit``: the declarations of :mod:`.zullo` (or ``ems``) under a C template
    (Zullo's header, runtime, status codes and prototypes, hand-written once in :mod:`.c_template`)."""
    from .user.render_typed_c import CTemplate
    from .user.render_typed_c import c_files as typed_c_files
    from .zullo import declarations

    ems = declarations(N)[0] if ems is None else ems
    status = (("ok", "SYMBT_TODA_OK"), ("range", "SYMBT_TODA_RANGE"), ("invalid", "SYMBT_TODA_INVALID_INPUT"),
              *_CODES.items())
    t = CTemplate(f"toda{N}", header, common + _SECTION, status, f"toda{N}_finite", length="NS",
                  signatures=tuple((n, s.format(N=N)) for n, s in _SIGNATURES.items()), functions=C_FUNCTIONS,
                  sign_local="b", pointers=tuple(_OUT_PTRS.items()))
    return typed_c_files(ems, t)


def _loop_c_files(N: int, header: str, common: str) -> tuple[str, str]:
    """The transfer-matrix form through ``symbt.emit`` too: the ``Loop`` declarations of :mod:`.zullo` (their
    C text verbatim, :func:`loop_c_parts`) placed by the same renderer under the same kind of C template."""
    from .user.render_typed_c import CTemplate
    from .user.render_typed_c import c_files as typed_c_files
    from .zullo import declarations

    ems, _ = declarations(N, "transfer-matrix")
    helpers, parts = loop_c_parts(N)
    status = (("ok", "SYMBT_TODA_OK"), ("range", "SYMBT_TODA_RANGE"), ("invalid", "SYMBT_TODA_INVALID_INPUT"))
    t = CTemplate(f"toda{N}", header, common + helpers, status, f"toda{N}_finite", functions=tuple(parts))
    return typed_c_files(ems, t)
