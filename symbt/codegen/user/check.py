r"""An emitted file against its SymPy source: the residual, in units of its error bound, at seeded points.

For a declaration ``e`` and a flavour (``numpy``, ``mpmath``, ``c``), :func:`compare` samples
``e.domain`` cell by cell (``e.cells``: by default the sign of every ``Piecewise`` condition, so
every branch is sampled) with :meth:`symbt.Domain.evaluate` and, at each point ``x`` rounded to
float64 (every evaluation sees exactly the same input):

* **reference**: the declared expression (not the rewritten one, no CSE) through plain
  ``lambdify`` to mpmath at ``REF_DPS = 60`` digits -- independent of the printer and of the file;
  it is evaluated again at ``CHECK_DPS = 80`` digits and must agree to ``1e-45`` of the
  condition scale, else the point fails (*reference unstable*);
* **condition scale** ``S = |f| + sum_i |x_i| |df/dx_i|`` per output, the derivatives by forward
  differences of the reference at 60 digits (step ``1e-25 |x_i|``): how much ``f`` moves when
  every input moves by one *relative* unit, as a float64 input rounding does (so that
  ``log(1 + x)`` printed naively fails for small ``x`` where ``log1p(x)`` passes);
* **bound**: float64 flavours (numpy, C) ``F64_TOL_ULPS * eps * S`` (16 ulp times the
  condition); mpmath (evaluated at ``MP_DPS = 50``) ``1e-45 * S``;
* **residual** at the point: the worst ``|emitted - reference| / bound`` over the outputs; a
  non-finite emitted or reference value is ``inf``.  A point holds when its residual is at most 1.

The check is two-sided: the emitted value must be finite and within the bound of a reference
that is itself stable; a wildly wrong value, a ``nan`` or an unstable reference all fail.

A *typed* declaration (:mod:`.typed`) is sampled over its elements (arrays by component, every
sign a cell) and its guards are decided on the reference first, in order, each with its own
condition scale: where the reference refuses (a guard value clearly ``<= 0``, a ``range`` guard
or an output beyond the float64 range), the emitted function must refuse too -- ``NoRealMapError``
with that condition, ``IllConditionedError``/``NumericRangeError``, or the C status of that
condition -- and the point is *counted* (:class:`Comparison`), not compared; where a guard value
is within its bound of 0 either answer is accepted; a refusal where the reference exists fails.
The mpmath flavour skips ``illcond`` guards (float64's own), as the emitted one does.

The file is imported from disk afresh (never from ``sys.modules``); the C file is compiled
with the system ``cc`` (``-std=c99 -O2``, no fast-math) into a temporary shared library and
called through ``ctypes`` with the documented ABI.
"""
from __future__ import annotations

import ctypes
import hashlib
import importlib.util
import re
import shutil
import subprocess
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np

from ...proof.cells import CellTable
from ...proof.lambdify import plain_lambdify
from .declare import Emission
from .render import c_name
from .typed import Guard

__all__ = ["compare", "Comparison", "Refusal", "c_status", "load_python",
           "load_c", "compiler", "F64_TOL_ULPS", "MP_TOL", "REF_DPS", "CHECK_DPS",
           "MP_DPS", "EPS", "method_text"]

F64_TOL_ULPS = 16
MP_TOL = mp.mpf(10) ** -45
REF_DPS, CHECK_DPS, MP_DPS = 60, 80, 50
EPS = float(np.finfo(np.float64).eps)


def method_text(flavour: str) -> str:
    bound = "1e-45 x condition (mpmath at 50 digits)" if flavour == "mpmath" else \
        f"{F64_TOL_ULPS} ulp x condition (float64)"
    return (f"numeric: emitted {flavour} file vs SymPy source (plain lambdify, mpmath {REF_DPS} digits, "
            f"re-checked at {CHECK_DPS}); bound {bound}, condition by forward differences")


def load_python(path: Path) -> Any:
    """Import the emitted ``.py`` file afresh (a private module name; not left in ``sys.modules``)."""
    digest = hashlib.sha256(path.read_bytes()).hexdigest()[:12]
    spec = importlib.util.spec_from_file_location(f"symbt_emitted_{path.stem}_{digest}", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def compiler() -> str | None:
    """The system C compiler (``cc``, else ``gcc``/``clang``), or None."""
    for name in ("cc", "gcc", "clang"):
        found = shutil.which(name)
        if found:
            return found
    return None


def load_c(source: Path, keep: list[Any]) -> ctypes.CDLL:
    """Compile ``source`` (its header beside it) into a temporary shared library and load it.

    Raises ``RuntimeError`` with the compiler's message when it does not compile.
    """
    cc = compiler()
    if cc is None:
        raise FileNotFoundError("no C compiler (cc, gcc or clang) on PATH")
    tmp = tempfile.TemporaryDirectory(prefix="symbt-emit-")
    keep.append(tmp)
    lib = Path(tmp.name) / f"lib{source.stem}.so"
    r = subprocess.run([cc, "-std=c99", "-O2", "-fPIC", "-shared", "-I", str(source.parent), "-o", str(lib),
                        str(source), "-lm"], capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        raise RuntimeError(f"{source} does not compile: {(r.stderr or r.stdout).strip().splitlines()[:1]}")
    return ctypes.CDLL(str(lib))


@dataclass(frozen=True)
class Refusal:
    """An emitted typed function declined the point: ``condition`` is the guard's condition (a
    ``NoRealMapError``, a C status), ``"illcond"`` (``IllConditionedError``) or ``"range"``
    (``NumericRangeError``, ``RANGE``)."""

    condition: str


Values = list[Any]
Evaluator = Callable[[list[Any]], "Values | Refusal"]


def _typed_call(e: Emission, xs: list[Any], array: Callable[[list[Any]], Any]) -> list[Any]:
    """The call arguments of a typed function from the flat inputs (arrays packed by ``array``)."""
    out, k = [], 0
    for a in e.params:
        n = len(a.symbols)
        out.append(array(xs[k:k + n]) if a.kind == "array" else int(xs[k]) if a.kind == "sign" else xs[k])
        k += n
    return out


def _flat(v: Any) -> list[Any]:
    return [x for item in v for x in _flat(item)] if isinstance(v, (list, tuple)) else [v]


def c_status(header: Path, e: Emission) -> dict[int, str]:
    """C status code -> condition (``ok``, a guard condition, ``range``, ``invalid``) of the typed ``e``,
    read off the macros of its ``.h`` (:mod:`.render_typed_c`)."""
    up = e.module.upper()
    names = {f"{up}_OK": "ok", f"{up}_RANGE": "range", f"{up}_INVALID_INPUT": "invalid",
             **{f"{up}_NO_REAL_{g.condition.upper()}": g.condition for g in e.guards}}
    found = {m.group(1): int(m.group(2)) for m in re.finditer(r"^#define (\w+) (\d+)\s*$", header.read_text(),
                                                              re.M)}
    return {found[m]: c for m, c in names.items() if m in found}


def _typed_evaluator(e: Emission, flavour: str, path: Path, keep: list[Any]) -> Evaluator:
    if flavour == "c":
        lib = load_c(path, keep)
        fn = getattr(lib, c_name(e.module, e))
        dp = ctypes.POINTER(ctypes.c_double)
        fn.restype = ctypes.c_int
        fn.argtypes = [dp if a.kind == "array" else ctypes.c_int if a.kind == "sign" else ctypes.c_double
                       for a in e.params] + [dp for _ in e.outputs]
        status = c_status(path.with_suffix(".h"), e)

        def run_c(xs: list[Any]) -> Values | Refusal:
            outs = [(ctypes.c_double * len(o.exprs))() for o in e.outputs]
            code = fn(*_typed_call(e, xs, lambda v: (ctypes.c_double * len(v))(*v)), *outs)
            what = status.get(code, f"status {code}")
            if what == "ok":
                return [x for o in outs for x in o]
            if what == "invalid":
                raise ValueError(f"{c_name(e.module, e)} refused valid input as INVALID_INPUT")
            return Refusal(what)
        return run_c
    mod = load_python(path)
    f = getattr(mod, e.name if flavour == "numpy" else e.name + "_mp")
    errors = (mod.IllConditionedError, mod.NoRealMapError, mod.NumericRangeError)

    def run(xs: list[Any]) -> Values | Refusal:
        try:
            if flavour == "numpy":
                res = f(*_typed_call(e, xs, lambda v: np.array(v, dtype=np.float64)))
            else:
                with mp.workdps(MP_DPS):
                    res = f(*_typed_call(e, xs, list))
        except errors as exc:
            return Refusal("illcond" if isinstance(exc, errors[0]) else getattr(exc, "condition", "")
                           if isinstance(exc, errors[1]) else "range")
        res = [res] if len(e.outputs) == 1 else list(res)
        if flavour == "numpy":
            return [float(v) for r in res for v in np.asarray(r, dtype=np.float64).reshape(-1)]
        return [v for r in res for v in _flat(r)]
    return run


def _evaluator(e: Emission, flavour: str, path: Path, keep: list[Any]) -> Evaluator:
    """``floats -> list of output values`` (or a :class:`Refusal` of a typed function) for the emitted flavour."""
    if e.typed:
        return _typed_evaluator(e, flavour, path, keep)
    if flavour == "c":
        lib = load_c(path, keep)
        fn = getattr(lib, c_name(e.module, e))
        fn.restype = ctypes.c_int
        fn.argtypes = [ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)]
        n_in, n_out = len(e.args), len(e.exprs)

        def run_c(xs: list[Any]) -> Values | Refusal:
            inp = (ctypes.c_double * n_in)(*xs)      # no arguments: an empty array, never read
            out = (ctypes.c_double * n_out)()
            fn(inp, out)
            return list(out)
        return run_c
    mod = load_python(path)
    if flavour == "numpy":
        f = getattr(mod, e.name)
        return lambda xs: [float(v) for v in np.asarray(f(*xs), dtype=np.float64).reshape(-1)]
    fm = getattr(mod, e.name + "_mp")

    def run_mp(xs: list[Any]) -> Values | Refusal:
        with mp.workdps(MP_DPS):
            v = fm(*xs)
        return list(np.asarray(v, dtype=object).reshape(-1)) if e.shape else [v]
    return run_mp


def _guards(e: Emission, flavour: str) -> list[Guard]:
    """The guards the flavour decides: the mpmath flavour skips ``illcond`` (float64's own guard)."""
    return [g for g in e.guards if not (flavour == "mpmath" and g.condition == "illcond")]


def _point_inputs(e: Emission) -> list[str]:
    """The point's name of each flat input: the symbol's, a sign argument's own (a cell choice)."""
    signs = {a.symbols[0]: a.name for a in e.params if a.kind == "sign"}
    return [signs.get(s, s.name) for s in e.args]


@dataclass
class Comparison:
    """What :func:`compare` saw besides the table: points both sides refused (counted, not compared)."""

    refused: int = 0
    compared: int = 0
    conditions: dict[str, int] = field(default_factory=dict)


def _measured(fn: Callable[..., Any], xs: list[Any], exact: set[int]) -> tuple[list[Any], list[Any]] | None:
    """``(values at CHECK_DPS, condition scales)`` of the reference ``fn`` at ``xs``; None where it is not
    finite and real or unstable (60 and 80 digits disagree beyond ``MP_TOL`` of the scale).

    The scale ``S = |f| + sum_i |x_i| |df/dx_i|`` by forward differences at 60 digits (exact inputs --
    zeros, signs -- have no rounding error to propagate)."""
    def values(v: list[Any]) -> list[Any]:
        return [mp.mpmathify(t) for t in _flat(fn(*[mp.mpf(x) for x in v]))]

    try:
        with mp.workdps(REF_DPS):
            f0 = values(xs)
            scale = [abs(v) for v in f0]
            for i, x in enumerate(xs):
                if x == 0 or i in exact:
                    continue
                h = mp.mpf(10) ** -25 * abs(x)
                fi = values([mp.mpf(x) + h if j == i else xs[j] for j in range(len(xs))])
                scale = [s + abs(x) * abs(a - b) / h for s, a, b in zip(scale, fi, f0)]
        with mp.workdps(CHECK_DPS):
            f1 = values(xs)
    except (ArithmeticError, ValueError, TypeError):
        return None
    if not all(mp.isfinite(v) and mp.im(v) == 0 for v in f0 + f1):
        return None
    if any(abs(a - b) > MP_TOL * s for a, b, s in zip(f0, f1, scale)):
        return None
    return f1, scale


_BIG = mp.mpf(float(np.finfo(np.float64).max))


def _expected(guards: list[Guard], refs: list[Callable[..., Any]], xs: list[Any], exact: set[int], flavour: str,
              tol: Any) -> tuple[bool, set[str]] | None:
    """The guards on the reference: (must the emitted function refuse?, the conditions it may refuse with);
    None where a guard the reference reaches is not defined or unstable.

    In order: a value within ``tol * S`` of 0 may go either way in float64 (its condition is allowed,
    the next guards still decide); a clear ``<= 0`` refuses (nothing after it decides); a ``range``
    guard's value beyond the float64 range refuses with ``range`` (float64 flavours)."""
    allowed: set[str] = set()
    for g, fn in zip(guards, refs):
        m = _measured(fn, xs, exact)
        if m is None:
            return None
        (v,), (s,) = m
        if g.condition == "range":
            if flavour != "mpmath" and abs(v) > _BIG:
                return True, allowed | {"range"}
        elif abs(v) <= tol * s:
            allowed.add(g.condition)
        elif v < 0:
            return True, allowed | {g.condition}
    return False, allowed


def compare(e: Emission, path: Path, flavour: str, *, per_cell: int | None = None, deep: bool = False,
            seen: Comparison | None = None) -> CellTable:
    """The :class:`~symbt.proof.cells.CellTable` of normalised residuals (a point holds at <= 1).

    A typed declaration's guards are decided on the reference first (:func:`_expected`): where the
    reference refuses, the emitted function must refuse with an allowed condition -- the point is
    counted in ``seen`` (a :class:`Comparison`), not compared; where it does not, a refusal is a
    failure unless a guard value is within the bound of 0 (or an output beyond the float64 range)."""
    keep: list[Any] = []
    seen = Comparison() if seen is None else seen
    run = _evaluator(e, flavour, path, keep)
    guards = _guards(e, flavour)
    grefs = [plain_lambdify(list(e.args), g.expr, "mpmath") for g in guards]
    ref = plain_lambdify(list(e.args), list(e.exprs), "mpmath")
    names = _point_inputs(e)
    exact = {i for i, a in enumerate(e.args) if names[i] != a.name}      # sign arguments: +-1, no rounding
    tol = MP_TOL if flavour == "mpmath" else mp.mpf(F64_TOL_ULPS * EPS)

    def residual(**point: Any) -> Any:
        xs = [int(point[n]) if i in exact else float(point[n]) for i, n in enumerate(names)]
        decided = _expected(guards, grefs, xs, exact, flavour, tol)
        if decided is None:
            return mp.inf      # the reference of a guard is undefined or unstable here
        must, allowed = decided
        measured = None if must else _measured(ref, xs, exact)
        if not must and measured is None:
            return mp.inf      # the reference itself is undefined or unstable at this point
        if measured is not None and flavour != "mpmath" and any(abs(v) > _BIG for v in measured[0]):
            must, allowed = True, allowed | {"range"}
        try:
            got = run(xs)
        except (ArithmeticError, ValueError):
            return mp.inf
        if isinstance(got, Refusal) or must:
            if not isinstance(got, Refusal) or got.condition not in allowed:
                return mp.inf       # refused where the reference exists, or returned where it does not
            seen.refused += 1
            seen.conditions[got.condition] = seen.conditions.get(got.condition, 0) + 1
            return mp.mpf(0)
        assert measured is not None
        seen.compared += 1
        worst = mp.mpf(0)
        with mp.workdps(REF_DPS):
            for g, r, s in zip(got, *measured):
                g = mp.mpmathify(g)
                if not mp.isfinite(g) or mp.im(g) != 0:
                    return mp.inf
                bound = max(tol * s, mp.mpf(10) ** -300)
                worst = max(worst, abs(mp.re(g) - r) / bound)
        return worst

    assert e.domain is not None
    try:
        return e.domain.evaluate(*e.cells, printed=residual, dps=REF_DPS, tol=1.0, per_cell=per_cell, deep=deep)
    finally:
        for t in keep:
            t.cleanup()
