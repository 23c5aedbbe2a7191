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
written either way).  Only ``<math.h>`` is used; no global state; link with ``-lm``.

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

import sympy as sp
from sympy.codegen.cfunctions import expm1
from sympy.codegen.rewriting import FuncMinusOneOptim, ReplaceOptim, expm1_opt, log1p_opt

from ..printer import _ATOM, _FUNCS, _MUL, _POW, ExprPrinter
from .declare import Emission

__all__ = ["UserPrinter", "optimized", "rewritten", "python_module", "c_source", "c_header", "c_name"]

_TRIG = (sp.sin, sp.cos, sp.tan, sp.asin, sp.acos, sp.atan, sp.sinh, sp.cosh, sp.tanh, sp.asinh, sp.atanh)
_NP = {"asin": "arcsin", "acos": "arccos", "atan": "arctan", "asinh": "arcsinh", "atanh": "arctanh"}
_EXTRA = {
    "numpy": {**{f: "np." + _NP.get(f.__name__, f.__name__) for f in _TRIG}, expm1: "np.expm1"},
    "mpmath": {**{f: "mpmath." + f.__name__ for f in _TRIG}, expm1: "mpmath.expm1"},
    "c": {**{f: f.__name__ for f in _TRIG}, expm1: "expm1"},
}
_CONST = {"numpy": {"pi": "np.pi", "E": "np.e"}, "mpmath": {"pi": "mpmath.pi", "E": "mpmath.e"},
          "c": {"pi": "3.141592653589793", "E": "2.718281828459045"}}
_MINMAX = {"numpy": ("np.minimum", "np.maximum"), "mpmath": ("min", "max"), "c": ("fmin", "fmax")}
_BOOL = {"numpy": (" & ", " | ", "~"), "mpmath": (" and ", " or ", "not "), "c": (" && ", " || ", "!")}


class UserPrinter(ExprPrinter):
    """:class:`~symbt.codegen.printer.ExprPrinter` for users' expressions (flavours numpy, mpmath, c).

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> UserPrinter("c", {x: "x"}).text(sp.Piecewise((sp.sin(x), x < 0), (x**sp.Rational(1, 3), True)))
    '((x < 0.0) ? sin(x) : pow(x, (1.0/3.0)))'
    """

    def __init__(self, flavour: str, names: dict):
        super().__init__(flavour, names)
        self.funcs = {**_FUNCS[flavour], **_EXTRA[flavour]}

    def _p(self, e):
        fl = self.flavour
        if e.is_Float:
            v = float(e)
            txt = repr(v) if fl != "mpmath" else f"mpmath.mpf({repr(v)!r})"
            return (txt, _ATOM) if v >= 0 else (f"({txt})", _ATOM)
        if e is sp.pi or e is sp.E:
            return _CONST[fl][str(e)], _ATOM
        if isinstance(e, sp.atan2):
            f = {"numpy": "np.arctan2", "mpmath": "mpmath.atan2", "c": "atan2"}[fl]
            return f"{f}({self.text(e.args[0])}, {self.text(e.args[1])})", _ATOM
        if isinstance(e, (sp.Min, sp.Max)):
            f = _MINMAX[fl][isinstance(e, sp.Max)]
            out = self.text(e.args[0])
            for a in e.args[1:]:
                out = f"{f}({out}, {self.text(a)})"
            return out, _ATOM
        if isinstance(e, (sp.And, sp.Or)):
            op = _BOOL[fl][isinstance(e, sp.Or)]
            return "(" + op.join(f"({self.text(a)})" for a in e.args) + ")", _ATOM
        if isinstance(e, sp.Not):
            return f"({_BOOL[fl][2]}({self.text(e.args[0])}))", _ATOM
        if isinstance(e, (sp.Eq, sp.Ne)):
            op = "==" if isinstance(e, sp.Eq) else "!="
            return f"({self._wrap(e.lhs, 1)} {op} {self._wrap(e.rhs, 1)})", _ATOM
        if e is sp.true or e is sp.false:
            v = bool(e)
            return {"numpy": str(v), "mpmath": str(v), "c": str(int(v))}[fl], _ATOM
        return super()._p(e)

    def _add(self, e):
        terms = e.as_ordered_terms()
        if self.flavour == "c" or len(terms) <= LONG_SUM:
            return super()._add(e)
        chunks = [super(UserPrinter, self)._add(sp.Add(*terms[k:k + LONG_SUM], evaluate=False))
                  for k in range(0, len(terms), LONG_SUM)]

        def tree(parts):   # balanced: nesting depth log2(chunks), few temporaries alive at once
            if len(parts) == 1:
                return parts[0]
            mid = len(parts) // 2
            return f"({tree(parts[:mid])}) + ({tree(parts[mid:])})"
        return tree(chunks)

    def _pow(self, e):
        b, x = e.base, e.exp
        if b is sp.E or (x.is_Rational and (x.is_Integer or x.q == 2)):
            return super()._pow(e)
        if x.is_Rational and x.is_negative:
            one = "1.0" if self.flavour == "c" else "1"
            return f"{one}/{self._wrap(sp.Pow(b, -x), _MUL)}", _MUL
        if self.flavour == "c":
            return f"pow({self.text(b)}, {self.text(x)})", _ATOM
        if self.flavour == "mpmath":
            return f"mpmath.power({self.text(b)}, {self.text(x)})", _ATOM
        return f"{self._wrap(b, _POW)}**{self._wrap(x, _POW)}", _POW


#: above this many operations the expm1 rule is applied term by term only: SymPy's rule also tries
#: ``factor()`` of the whole expression, which took 93 % of the emission time of a large polynomial
FACTOR_MAX_OPS = 400
#: a sum of more terms is printed in Python as a balanced sum of partial sums of at most this many terms,
#: ``(a + ... ) + (...)``: a chain ``a + b + ...`` of thousands of terms makes Python's compiler raise
#: RecursionError
LONG_SUM = 100


def rewritten(x: sp.Expr) -> sp.Expr:
    """SymPy's ``optimize(x, [expm1_opt, log1p_opt])``, each rule only where its function occurs.

    >>> x = sp.Symbol("x")
    >>> rewritten(sp.log(1 + x) + sp.exp(x) - 1)
    expm1(x) + log1p(x)
    """
    for fn, opt in ((sp.exp, expm1_opt), (sp.log, log1p_opt)):
        if not x.has(fn):
            continue
        if isinstance(opt, FuncMinusOneOptim) and sp.count_ops(x) > FACTOR_MAX_OPS:
            new = ReplaceOptim.__call__(opt, x)
        else:
            new = opt(x)
        x = opt.cheapest(x, new) if opt.cost_function is not None else new
    return x


def optimized(e: Emission) -> list[sp.Expr]:
    """The elements to print: ``expm1``/``log1p`` rewriting when the declaration asks for it.

    Each rule of :mod:`sympy.codegen.rewriting` is applied only to an expression containing its
    function (``exp``, ``log``), and on an expression of more than :data:`FACTOR_MAX_OPS` operations
    without the rule's whole-expression ``factor()`` attempt.

    >>> import sympy as sp
    >>> from .declare import emit
    >>> x = sp.Symbol("x")
    >>> optimized(emit("g", [sp.exp(x) - 1, sp.log(1 + x), x**2 - 1], args=(x,), module="m", register=False))
    [expm1(x), log1p(x), x**2 - 1]
    """
    if not e.optimize:
        return list(e.exprs)
    return [rewritten(x) for x in e.exprs]


def _cse(exprs, names, flavour):
    repl, reduced = sp.cse(list(exprs), symbols=sp.numbered_symbols("t"), order="canonical")
    names = dict(names)
    pr = UserPrinter(flavour, names)
    lines = []
    for s, v in repl:
        lines.append((str(s), pr.text(v)))
        names[s] = str(s)
    return lines, [pr.text(r) for r in reduced]


def _names(e: Emission) -> dict:
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


def _py_function(e: Emission, exprs) -> str:
    args = ", ".join(e.arg_names)
    lines = [f"def {e.name}({args}):", _doc(e, "numpy")]
    for a in e.arg_names:
        lines.append(f"    {a} = np.asarray({a}, dtype=np.float64)")
    lines.append(f"    _batch = np.broadcast_shapes({', '.join(a + '.shape' for a in e.arg_names)})")
    body, outs = _cse(exprs, _names(e), "numpy")
    lines.append('    with np.errstate(all="ignore"):')
    lines += [f"        {s} = {v}" for s, v in body]
    lines.append(f"        return _pack([{', '.join(outs)}], _batch, {e.shape!r})")
    return "\n".join(lines)


def _mp_function(e: Emission, exprs) -> str:
    args = ", ".join(e.arg_names)
    lines = [f"def {e.name}_mp({args}):", _doc(e, "mpmath")]
    for a in e.arg_names:
        lines.append(f"    {a} = mpmath.mpf({a})")
    body, outs = _cse(exprs, _names(e), "mpmath")
    lines.append("    try:")
    lines += [f"        {s} = {v}" for s, v in body]
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
                      "", "", f"_WHY = {why!r}"])


def python_module(module: str, emissions: list[Emission], sources: str, template=None) -> str:
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


def _typed_c(module: str, emissions: list[Emission]):
    """``(source, header)`` when the module's declarations are typed (:mod:`.render_typed_c`), else None."""
    typed = [e.name for e in emissions if e.typed]
    if not typed:
        return None
    if len(typed) != len(emissions):
        from .declare import EmitError

        raise EmitError(f"emit({typed[0]!r}): module {module} mixes typed and plain declarations; the C target "
                        "takes one kind per module (two ABIs)")
    from .render_typed_c import c_files, default_template

    return c_files(emissions, default_template(module, emissions))


def c_header(module: str, emissions: list[Emission]) -> str:
    typed = _typed_c(module, emissions)
    if typed is not None:
        return typed[1]
    guard = f"SYMBT_EMITTED_{module.upper()}_H"
    lines = [f"#ifndef {guard}", f"#define {guard}", "",
             "/* ABI: int <module>_<name>(const double *in, double *out);",
             " * in: the NIN arguments in declaration order; out: the NOUT outputs (row-major);",
             " * returns 0 if every output is finite, 1 otherwise (outputs written either way). */", ""]
    for e in emissions:
        up = c_name(module, e).upper()
        lines += [f"/* {e.name}({', '.join(e.arg_names)}) -> {list(e.shape) or 'scalar'} */",
                  f"#define {up}_NIN {len(e.args)}", f"#define {up}_NOUT {_nout(e)}",
                  f"int {c_name(module, e)}(const double *in, double *out);", ""]
    lines.append(f"#endif /* {guard} */")
    return "\n".join(lines) + "\n"


def c_source(module: str, emissions: list[Emission]) -> str:
    typed = _typed_c(module, emissions)
    if typed is not None:
        return typed[0]
    lines = ["#include <math.h>", f'#include "{module}.h"', "",
             "static double sgn(double x) { return (double)((x > 0.0) - (x < 0.0)); }", ""]
    for e in emissions:
        body, outs = _cse(optimized(e), _names(e), "c")
        lines.append(f"int {c_name(module, e)}(const double *in, double *out)")
        lines.append("{")
        lines += [f"    const double {a} = in[{i}];" for i, a in enumerate(e.arg_names)]
        lines += [f"    const double {s} = {v};" for s, v in body]
        lines += [f"    out[{k}] = {v};" for k, v in enumerate(outs)]
        lines += [f"    for (int k = 0; k < {_nout(e)}; ++k) {{", "        if (!isfinite(out[k])) return 1;",
                  "    }", "    return 0;", "}", ""]
    if "sgn(" not in "\n".join(lines[5:]):
        lines = lines[:3] + lines[5:]
    return "\n".join(lines).rstrip("\n") + "\n"
