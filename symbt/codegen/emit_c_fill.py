"""Zullo's C templates (:mod:`symbt.codegen.c_template`) with the kernels of :mod:`symbt.codegen.kernels`
printed in, and the transfer-matrix C split per function (:func:`loop_c_parts`).

Markers: see :mod:`symbt.codegen.c_template`.  Updates of polynomials in lambda are printed
coefficient-wise (``a = lambda + p_j`` substituted, the coefficient of ``lambda`` reads
coefficient ``k - 1``), and ``tr(dm P S)`` contracted with ``c`` term by term.  Below
:mod:`symbt.codegen.zullo` (which declares the C of the ``Loop`` functions from it) and
:mod:`symbt.codegen.emit_c` (which renders the files).

>>> helpers, parts = loop_c_parts(5)
>>> list(parts), "static int toda5_monodromy(" in helpers
(['bt_step', 'spectral_trace', 'invariants', 'flow_field'], True)
"""
from __future__ import annotations

import re

import sympy as sp

from ..numeric.core.limits import KAPPA_MAX
from .c_template import LOOP
from .kernels import kernels
from .printer import ExprPrinter

__all__ = ["fill", "loop_c_parts"]

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


def fill(template: str, N: int, form: str) -> str:
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


_PUBLIC = re.compile(r"^int toda\d+_(\w+)\(", re.M)


def loop_c_parts(N: int) -> tuple[str, dict[str, str]]:
    """The transfer-matrix C of ``toda{N}`` (:data:`~symbt.codegen.c_template.LOOP`, kernels printed in) as
    ``(helpers, {function: text})``: the static helpers every function uses, then per public function its
    text verbatim, preceded by the helpers only it (and those after it) use -- the C of the ``Loop``
    declarations of :mod:`.zullo`."""
    text = fill(LOOP.replace("@@KAPPA@@", str(int(KAPPA_MAX))), N, "transfer-matrix")
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
