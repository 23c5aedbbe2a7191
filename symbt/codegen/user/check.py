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

The file is imported from disk afresh (never from ``sys.modules``); the C file is compiled
with the system ``cc`` (``-std=c99 -O2``, no fast-math) into a temporary shared library and
called through ``ctypes`` with the documented ABI.
"""
from __future__ import annotations

import ctypes
import hashlib
import importlib.util
import shutil
import subprocess
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import mpmath as mp
import numpy as np

from ...proof.lambdify import plain_lambdify
from .declare import Emission
from .render import c_name

if TYPE_CHECKING:
    from ...proof.cells import CellTable

__all__ = ["compare", "load_python", "load_c", "compiler", "F64_TOL_ULPS", "MP_TOL", "REF_DPS", "CHECK_DPS",
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


def _evaluator(e: Emission, flavour: str, path: Path, keep: list[Any]) -> Callable[[list[float]], list[Any]]:
    """``floats -> list of output values`` for the emitted flavour."""
    if flavour == "c":
        lib = load_c(path, keep)
        fn = getattr(lib, c_name(e.module, e))
        fn.restype = ctypes.c_int
        fn.argtypes = [ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)]
        n_in, n_out = len(e.args), len(e.exprs)

        def run_c(xs: list[float]) -> list[float]:
            inp = (ctypes.c_double * max(n_in, 1))(*xs)
            out = (ctypes.c_double * n_out)()
            fn(inp, out)
            return list(out)
        return run_c
    mod = load_python(path)
    if flavour == "numpy":
        f = getattr(mod, e.name)
        return lambda xs: [float(v) for v in np.asarray(f(*xs), dtype=np.float64).reshape(-1)]
    fm = getattr(mod, e.name + "_mp")

    def run_mp(xs: list[float]) -> list[Any]:
        with mp.workdps(MP_DPS):
            v = fm(*xs)
        return list(np.asarray(v, dtype=object).reshape(-1)) if e.shape else [v]
    return run_mp


def compare(e: Emission, path: Path, flavour: str, *, per_cell: int | None = None,
            deep: bool = False) -> CellTable:
    """The :class:`~symbt.proof.cells.CellTable` of normalised residuals (a point holds at <= 1)."""
    keep: list[Any] = []
    run = _evaluator(e, flavour, path, keep)
    ref = plain_lambdify(list(e.args), list(e.exprs), "mpmath")
    names = e.arg_names

    def values(xs: Sequence[Any]) -> list[Any]:
        return [mp.mpmathify(v) for v in ref(*[mp.mpf(x) for x in xs])]

    def residual(**point: Any) -> Any:
        xs = [float(point[n]) for n in names]
        with mp.workdps(REF_DPS):
            f0 = values(xs)
            scale = [abs(v) for v in f0]
            for i, x in enumerate(xs):
                if x == 0:      # an exact zero input has no rounding error to propagate
                    continue
                h = mp.mpf(10) ** -25 * abs(x)
                fi = values([mp.mpf(x) + h if j == i else xs[j] for j in range(len(xs))])
                scale = [s + abs(x) * abs(a - b) / h for s, a, b in zip(scale, fi, f0)]
        with mp.workdps(CHECK_DPS):
            f1 = values(xs)
        if not all(mp.isfinite(v) and mp.im(v) == 0 for v in f0 + f1):
            return mp.inf
        if any(abs(a - b) > MP_TOL * s for a, b, s in zip(f0, f1, scale)):
            return mp.inf      # the reference itself is unstable at this point
        try:
            got = run(xs)
        except (ArithmeticError, ValueError):
            return mp.inf
        tol = MP_TOL if flavour == "mpmath" else mp.mpf(F64_TOL_ULPS * EPS)
        worst = mp.mpf(0)
        with mp.workdps(REF_DPS):
            for g, r, s in zip(got, f1, scale):
                g = mp.mpmathify(g)
                if not mp.isfinite(g) or mp.im(g) != 0:
                    return mp.inf
                bound = max(tol * s, mp.mpf(10) ** -300)
                worst = max(worst, abs(mp.re(g) - r) / bound)
        return worst

    try:
        return e.domain.evaluate(*e.cells, printed=residual, dps=REF_DPS, tol=1.0, per_cell=per_cell, deep=deep)
    finally:
        for t in keep:
            t.cleanup()
