r"""The emitted files of a user's module: numpy + mpmath Python, and C99 with a fixed ABI.

Python (``<module>.py``): for every declared function ``f(a, b, ...)``

* ``f`` -- numpy float64, vectorised: the arguments broadcast against each other and the result
  has shape ``batch + shape`` (a scalar function of scalars returns a 0-d value).  Invalid
  operations are not trapped (``np.errstate(all="ignore")``): a point outside the function's
  domain gives ``nan``/``inf`` there and nowhere else (the masked-result convention);
* ``f_mp`` -- mpmath at the caller's ``mpmath.mp.dps``: rational constants are exact ratios at
  that precision; returns an ``mpf``, a list (vector) or a list of rows (matrix); a division by
  zero raises ``DomainError`` (an ``ArithmeticError``) naming the function.

C99 (``<module>.c`` / ``<module>.h``), the ABI, fixed::

    #define MODULE_F_NIN  <number of arguments>
    #define MODULE_F_NOUT <number of outputs>
    int module_f(const double *in, double *out);

``in`` holds the arguments in declaration order, ``out`` receives the outputs (row-major for a
matrix); the return value is ``0`` when every output is finite, ``1`` otherwise (the outputs are
written either way).  Only ``<math.h>`` is used; no global state; link with ``-lm``.  Typed
declarations keep their own ABI (:mod:`.render_typed_c`); a module with both kinds gets one
source and header, the typed part first.

Both are printed by :class:`UserPrinter` (Zullo's :class:`~symbt.codegen.printer.ExprPrinter`
plus floats, ``pi``/``E``, trigonometric and hyperbolic functions, ``expm1``, ``atan2``, ``Min``/
``Max``, boolean conditions and general powers) after SymPy's ``cse`` with fixed names
``t0, t1, ...`` in canonical order; with ``optimize`` the ``expm1``/``log1p`` rules of
:mod:`sympy.codegen.rewriting` are applied first.  Rendering is deterministic.

>>> import sympy as sp
>>> from .declare import emit
>>> x = sp.Symbol("x")
>>> e = emit("lg", sp.log(x + 1), args=(x,), module="m", register=False)
>>> "np.log1p(x)" in python_module("m", [e], "demo")
True
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from .declare import Emission
from .printing import FACTOR_MAX_OPS, LONG_SUM, UserPrinter, cse, optimized, rewritten

if TYPE_CHECKING:
    import sympy as sp

    from .typed import ModuleTemplate

__all__ = ["UserPrinter", "optimized", "rewritten", "python_module", "c_source", "c_header", "c_name",
           "FACTOR_MAX_OPS", "LONG_SUM"]


def _names(e: Emission) -> dict[Any, str]:
    return {a: a.name for a in e.args}


def _doc(e: Emission, flavour: str) -> str:
    what = "a scalar" if e.shape == () else f"shape {e.shape}"
    head = e.doc.strip() or f"{e.name}({', '.join(e.arg_names)})"
    if flavour == "numpy":
        tail = (f"numpy float64; the arguments broadcast, the result is batch + {e.shape}; "
                f"nan/inf where the function is undefined.")
    else:
        tail = f"mpmath at the caller's precision; {what}; DomainError on a division by zero."
    return f'    """{head}\n\n    {tail}\n    """'


def _py_function(e: Emission, exprs: Sequence[sp.Expr]) -> str:
    args = ", ".join(e.arg_names)
    lines = [f"def {e.name}({args}):", _doc(e, "numpy")]
    for a in e.arg_names:
        lines.append(f"    {a} = np.asarray({a}, dtype=np.float64)")
    lines.append(f"    _batch = np.broadcast_shapes({', '.join(a + '.shape' for a in e.arg_names)})")
    body, outs = cse(list(exprs), _names(e), "numpy")
    lines.append('    with np.errstate(all="ignore"):')
    lines += [f"        {line}" for line in body]
    lines.append(f"        return _pack([{', '.join(outs)}], _batch, {e.shape!r})")
    return "\n".join(lines)


def _mp_function(e: Emission, exprs: Sequence[sp.Expr]) -> str:
    args = ", ".join(e.arg_names)
    lines = [f"def {e.name}_mp({args}):", _doc(e, "mpmath")]
    for a in e.arg_names:
        lines.append(f"    {a} = mpmath.mpf({a})")
    body, outs = cse(list(exprs), _names(e), "mpmath")
    lines.append("    try:")
    lines += [f"        {line}" for line in body]
    items = [f"mpmath.mpf({t})" for t in outs]
    if e.shape == ():
        val = items[0]
    elif len(e.shape) == 1:
        val = "[" + ", ".join(items) + "]"
    else:
        n = e.shape[1]
        val = "[" + ", ".join("[" + ", ".join(items[r * n:(r + 1) * n]) + "]" for r in range(e.shape[0])) + "]"
    lines.append(f"        return {val}")
    lines.append("    except ZeroDivisionError as exc:")
    lines.append(f"        raise DomainError({e.name + '_mp: division by zero'!r}) from exc")
    return "\n".join(lines)


_PY_HEAD = '''"""{module}: functions emitted by `symbt codegen` from {sources}.

Each function has a numpy float64 flavour (vectorised over broadcast arguments) and an
mpmath flavour ``<name>_mp`` (the caller's precision).  See docs/codegen.md, "Your own
expressions".
"""
import mpmath
import numpy as np

__all__ = {names!r}


class DomainError(ArithmeticError):
    """An mpmath flavour divided by zero (the point is outside the function's domain)."""


def _Q(p, q):
    return mpmath.mpf(p) / q


def _pack(items, batch, shape):
    arr = np.stack([np.broadcast_to(np.asarray(v, dtype=np.float64), batch) for v in items], axis=-1)
    return arr.reshape(batch + shape)
'''


_TYPED_HEAD = '''"""{module}: functions emitted by `symbt codegen` from {sources}.

Each function has a numpy float64 flavour (vectorised over leading batch axes) and an
mpmath flavour ``<name>_mp`` (the caller's precision).  Typed errors: InvalidInputError
(malformed input), NoRealMapError (a guard fails; ``errors="mask"``: masked results),
NumericRangeError (a non-finite value).  See docs/codegen.md, "Your own expressions".
"""'''


def _typed_head(module: str, emissions: list[Emission], sources: str, names: list[str]) -> str:
    """symbt's typed runtime (:data:`symbt.codegen.runtime.RUNTIME`) with messages for this module's guards."""
    from ..runtime import RUNTIME

    conds = sorted({g.condition for e in emissions for g in e.guards} - {"range"})
    why = {c: f"guard {c} fails at %s" for c in conds}
    return "\n".join([_TYPED_HEAD.format(module=module, sources=sources), "", f"__all__ = {names!r}",
                      RUNTIME.rstrip("\n"), "", "",
                      "class DomainError(ArithmeticError):",
                      '    """An mpmath flavour divided by zero (the point is outside the function\'s domain)."""',
                      "", "", f"_WHY = {why!r}", "_RANGE_CAUSE = 'an overflow or a non-finite intermediate'"])


def python_module(module: str, emissions: list[Emission], sources: str,
                  template: ModuleTemplate | None = None) -> str:
    """The body (after the provenance header) of ``<module>.py``.

    ``template`` (a :class:`~.typed.ModuleTemplate`): its ``head`` replaces the generated module head
    and its ``tail`` follows the functions (Zullo's runtime and ``bt_orbit``).  Typed declarations
    are rendered by :mod:`.render_typed`.
    """
    from .render_typed import mpmath_function, numpy_function

    names = sorted([e.name for e in emissions] + [e.name + "_mp" for e in emissions] + ["DomainError"])
    typed = any(e.typed for e in emissions)
    if template is not None:
        head = template.head
    elif typed:
        names = sorted(names + ["IllConditionedError", "InvalidInputError", "NoRealMapError", "NumericRangeError"])
        head = _typed_head(module, emissions, sources, names)
    else:
        head = _PY_HEAD.format(module=module, sources=sources, names=names)
    parts = [head.rstrip("\n")]
    zero = template.zero_division if template is not None else "division by zero"
    opt = [[] if e.typed else optimized(e) for e in emissions]     # once for both flavours
    for e, x in zip(emissions, opt):
        parts += ["", "", numpy_function(e) if e.typed else _py_function(e, x)]
    for e, x in zip(emissions, opt):
        parts += ["", "", mpmath_function(e, zero) if e.typed else _mp_function(e, x)]
    if template is not None and template.tail:
        parts.append(template.tail)
    return "\n".join(parts) + "\n"


def c_name(module: str, e: Emission) -> str:
    """The C symbol of a declared function: ``<module>_<name>``."""
    return f"{module}_{e.name}"


def _nout(e: Emission) -> int:
    return len(e.exprs)


def _typed_c(module: str, emissions: list[Emission]) -> tuple[str, str] | None:
    """``(source, header)`` of the module's typed declarations (:mod:`.render_typed_c`), or None without any."""
    typed = [e for e in emissions if e.typed]
    if not typed:
        return None
    from .render_typed_c import c_files, default_template

    return c_files(typed, default_template(module, typed))


_PLAIN_ABI = ["/* ABI: int <module>_<name>(const double *in, double *out);",
              " * in: the NIN arguments in declaration order; out: the NOUT outputs (row-major);",
              " * returns 0 if every output is finite, 1 otherwise (outputs written either way). */", ""]


def _plain_prototypes(module: str, emissions: list[Emission]) -> list[str]:
    lines = []
    for e in emissions:
        up = c_name(module, e).upper()
        lines += [f"/* {e.name}({', '.join(e.arg_names)}) -> {list(e.shape) or 'scalar'} */",
                  f"#define {up}_NIN {len(e.args)}", f"#define {up}_NOUT {_nout(e)}",
                  f"int {c_name(module, e)}(const double *in, double *out);", ""]
    return lines


def c_header(module: str, emissions: list[Emission]) -> str:
    """``<module>.h``: the typed declarations' status codes and prototypes (:mod:`.render_typed_c`), then the
    plain declarations' (the ABI in the module docstring) -- one header when a module has both kinds."""
    guard = f"SYMBT_EMITTED_{module.upper()}_H"
    plain = [e for e in emissions if not e.typed]
    typed = _typed_c(module, emissions)
    if typed is not None:
        if not plain:
            return typed[1]
        end = f"#endif /* {guard} */\n"
        assert typed[1].endswith(end)
        return typed[1][:-len(end)] + "\n".join(_PLAIN_ABI + _plain_prototypes(module, plain)) + end
    lines = [f"#ifndef {guard}", f"#define {guard}", "", *_PLAIN_ABI, *_plain_prototypes(module, plain)]
    lines.append(f"#endif /* {guard} */")
    return "\n".join(lines) + "\n"


def _plain_functions(module: str, emissions: list[Emission]) -> list[str]:
    lines = []
    for e in emissions:
        body, outs = cse(optimized(e), _names(e), "c")
        lines.append(f"int {c_name(module, e)}(const double *in, double *out)")
        lines.append("{")
        lines += [f"    const double {a} = in[{i}];" for i, a in enumerate(e.arg_names)]
        lines += [f"    const double {line};" for line in body]
        lines += [f"    out[{k}] = {v};" for k, v in enumerate(outs)]
        lines += [f"    for (int k = 0; k < {_nout(e)}; ++k) {{", "        if (!isfinite(out[k])) return 1;",
                  "    }", "    return 0;", "}", ""]
    return lines


def c_source(module: str, emissions: list[Emission]) -> str:
    """``<module>.c``: the typed functions (:mod:`.render_typed_c`), then the plain ones."""
    from .render_typed_c import SGN

    plain = [e for e in emissions if not e.typed]
    typed = _typed_c(module, emissions)
    if typed is not None:
        if not plain:
            return typed[0]
        body = _plain_functions(module, plain)
        sgn = [SGN, ""] if SGN not in typed[0] and "sgn(" in "\n".join(body) else []
        return (typed[0] + "\n" + "\n".join(sgn + body)).rstrip("\n") + "\n"
    lines = ["#include <math.h>", f'#include "{module}.h"', "", SGN, ""] + _plain_functions(module, plain)
    if "sgn(" not in "\n".join(lines[5:]):
        lines = lines[:3] + lines[5:]
    return "\n".join(lines).rstrip("\n") + "\n"
