r"""What ships, 3: the emitted code (closed form, loop form, C target) against the literal map, and existence
decided alike on every route (scene ``shipped``).

* ``shipped.emitted.n{2,3}`` -- ``symbt.generated.toda{N}.bt_step`` (float64) and ``bt_step_mp`` (30 digits),
  the closed form as shipped;
* ``shipped.loop.n{4,5}`` (N = 8 under ``--deep``) -- the loop (transfer-matrix) form, rendered by
  :func:`symbt.codegen.render` into a temporary directory and imported from there;
* ``shipped.c.n{2,3,5}`` -- the C99 target, rendered likewise and compiled with the system C compiler
  (``cc``, ``gcc`` or ``clang``; without one the claim is ``skipped`` with that reason), called by ctypes;

each compared with the literal map (50 digits, checked at 75) within ``16 N u S_i`` (:mod:`symbt.claims._shipped`)
in every branch x sign(mu) x sign(tr) cell and at states with q spread over ~1000 (for N = 3 the state of issue 21,
where the closed form returned a wrong finite state).  Unlike the ``codegen`` claims, nothing here is derived
from the expressions the code was generated from.

``shipped.nomap`` -- states where the exact map does not exist (``tr L(lambda_1)``, ``tr L(lambda_2)`` of
opposite signs, or of one sign with some ``E~_j <= 0``: lambda_1, lambda_2 in different gaps), decided by the
literal route with guard digits at 50 and at 75 digits (both must agree): every route must raise
``NoRealMapError`` (the C target: return ``SYMBT_TODA_NO_REAL_MAP_*``), never return a state.
"""
from __future__ import annotations

import ctypes
import importlib.util
import shutil
import subprocess
import tempfile
from collections.abc import Callable
from dataclasses import replace
from functools import cache
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np

from ..proof.cells import CellTable
from ._common import fmt_state
from ._shipped import (
    CHECK_DPS,
    EPS,
    REF_DPS,
    Tally,
    literal_state,
    range_error,
    ratios,
    scale_parts,
    scaled,
    ship_cells,
    step_constant,
    step_outputs,
    step_ref,
    wide_states,
)
from .base import Outcome, Parts, claim, failed, judge_cells, skipped

MP_DPS = 30
C_OK, C_NO_MAP, C_RANGE = 0, (1, 2), 3


class _CRangeError(ArithmeticError):
    """The C target's SYMBT_TODA_RANGE, under the name of the documented range error."""


_CRangeError.__name__ = "NumericRangeError"


@cache
def emitted_module(N: int) -> Any:
    """The Python module ``toda{N}`` as ``symbt codegen`` renders it now, imported from a temporary directory
    (removed once imported: nothing is left behind, whichever way the process ends)."""
    from ..codegen import render

    with tempfile.TemporaryDirectory(prefix="symbt-shipped-") as d:
        path = Path(d) / f"toda{N}.py"
        path.write_text(render((N,), "python")[f"toda{N}.py"], encoding="utf-8")
        spec = importlib.util.spec_from_file_location(f"symbt_shipped_toda{N}", path)
        assert spec is not None and spec.loader is not None
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
    return mod


def c_compiler() -> str | None:
    return shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")


@cache
def c_texts(N: int) -> dict[str, str]:
    """The C target's files for ``N`` (``toda{N}.c``, ``toda{N}.h``), rendered once."""
    from ..codegen import render

    return render((N,), "c")


def c_form_problem(N: int) -> str | None:
    """Why ``toda{N}.c``'s body is not the form its header names (``form_of(N)``: the closed form's CSE section
    for N = 2, 3, the transfer-matrix loop beyond), or None."""
    text = c_texts(N)[f"toda{N}.c"]
    header = next(line for line in text.splitlines() if "symbt-codegen-target:" in line)
    closed_header, closed_body = "closed form" in header, "closed form: CSE" in text
    if closed_header != closed_body or closed_header != (N <= 3):
        return f"toda{N}.c: header {header.split(':', 1)[1].strip()!r}, closed-form body {closed_body}"
    return None


@cache
def c_step(N: int) -> Callable[..., tuple[int, list, list]]:
    """``toda{N}_bt_step`` of the C target, rendered, compiled (``-O2``) and wrapped: ``(status, p~, q~)``."""
    with tempfile.TemporaryDirectory(prefix="symbt-shipped-") as tmp:   # a loaded library outlives its file
        d = Path(tmp)
        for name, text in c_texts(N).items():
            (d / name).write_text(text, encoding="utf-8")
        so = d / f"libtoda{N}.so"
        cmd = [str(c_compiler()), "-std=c99", "-O2", "-shared", "-fPIC", "-o", str(so), str(d / f"toda{N}.c"), "-lm"]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        if r.returncode:
            raise RuntimeError(f"C compilation failed: {r.stderr[:300]}")
        lib = ctypes.CDLL(str(so))
    fn = getattr(lib, f"toda{N}_bt_step")
    D, P = ctypes.c_double, ctypes.POINTER(ctypes.c_double)
    fn.argtypes, fn.restype = [P, P, D, D, ctypes.c_int, P, P], ctypes.c_int

    def call(p, q, lam0, mu, branch):
        arr = ctypes.c_double * N
        pt, qt = arr(), arr()
        rc = fn(arr(*p), arr(*q), float(lam0), float(mu), int(branch), pt, qt)
        return rc, list(pt), list(qt)
    return call


def _check_emitted(N: int, routes: dict[str, Callable[..., Any]], deep: bool, what: str, scale: float) -> Outcome:
    tally, C = Tally(), step_constant(N)
    for cell, st, b in ship_cells(N, 8 if deep else 2) + wide_states(N):
        ref = step_ref(st, b)
        for name, fn in routes.items():
            u = 2.0 ** -int(MP_DPS * 3.33 + 3) if name.endswith("(mpmath)") else EPS
            try:
                out = fn(st, b)
            except Exception as exc:  # an admissible state has a real map: raising fails the sample
                if range_error(exc) and cell.get("q") == "wide":
                    tally.decline(name, cell, st, b)
                    continue
                if not any(n.startswith(name) for n in tally.notes):
                    tally.notes.append(f"{name} raised {type(exc).__name__}: {str(exc)[:120]}.")
                out = None
            r, allowed = (ratios(scaled(step_outputs(out), scale), ref.x, ref.S, u, C) if out is not None
                          else (np.inf, 0.0))
            tally.add(name, cell, st, b, r, allowed, ref.agree)
    return tally.outcome(method=f"numeric: {what} vs the literal map ({REF_DPS} digits), bound 16 N u S_i",
                         printed=f"|{what} - literal| <= {C} u S_i")


def _py_routes(mod: Any) -> dict[str, Callable[..., Any]]:
    def f64(st, b):
        return mod.bt_step(list(st[0]), list(st[1]), st[2], st[3], b)

    def mpr(st, b):
        with mp.workdps(MP_DPS):
            return mod.bt_step_mp([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]], mp.mpf(st[2]),
                                  mp.mpf(st[3]), b)
    return {f"toda{mod.N} (float64)": f64, f"toda{mod.N} (mpmath)": mpr}


@claim("shipped.emitted", equation="toda{N}.bt_step", source_equation="imptransf", scene="shipped",
       parts=scale_parts, sizes=(2, 3),
       where="symbt/generated/toda{N}.py: bt_step, bt_step_mp (closed form)",
       statement="the shipped closed form toda{N}.bt_step (float64) and bt_step_mp (30 digits) = the literal map "
                 "(50 digits) within 16 N u S_i, every branch x sign(mu) x sign(tr) cell and at q spread over "
                 "~1000 (N={N})")
def emitted(N: int, parts: Parts, deep: bool = False) -> Outcome:
    mod = importlib.import_module(f"symbt.generated.toda{N}")
    return _check_emitted(N, _py_routes(mod), deep, f"symbt.generated.toda{N}.bt_step", parts.printed["scale"])


@claim("shipped.loop", equation="toda{N}.bt_step", source_equation="imptransf", scene="shipped",
       parts=scale_parts, sizes=(4, 8),
       deep=True, where="symbt codegen --n {N}: toda{N}.py (loop form)",
       statement="the loop form emitted by symbt codegen for N={N} (bt_step, bt_step_mp) = the literal map within "
                 "16 N u S_i, every cell and at q spread over ~1000")
@claim("shipped.loop", equation="toda{N}.bt_step", source_equation="imptransf", scene="shipped",
       parts=scale_parts, sizes=(5,),
       where="symbt codegen --n {N}: toda{N}.py (loop form)",
       statement="the loop form emitted by symbt codegen for N={N} (rendered into a temporary directory and "
                 "imported: bt_step float64, bt_step_mp 30 digits) = the literal map (50 digits) within 16 N u S_i, "
                 "every branch x sign(mu) x sign(tr) cell and at q spread over ~1000")
def loop(N: int, parts: Parts, deep: bool = False) -> Outcome:
    mod = emitted_module(N)
    return _check_emitted(N, _py_routes(mod), deep, f"emitted toda{N}.bt_step ({mod.FORM} form)",
                          parts.printed["scale"])


@claim("shipped.c", equation="toda{N}_bt_step", source_equation="imptransf", scene="shipped",
       parts=scale_parts, sizes=(2,), deep=True,
       where="symbt codegen --target c --n {N}: toda{N}.c",
       statement="the C99 target of symbt codegen for N={N}, compiled with the system C compiler, = the literal "
                 "map (50 digits) within 16 N eps S_i, every cell and at q spread over ~1000, its body the form its "
                 "header names (closed for N <= 3, the loop beyond; skipped without a C compiler)")
@claim("shipped.c", equation="toda{N}_bt_step", source_equation="imptransf", scene="shipped",
       parts=scale_parts, sizes=(3, 5),
       where="symbt codegen --target c --n {N}: toda{N}.c",
       statement="the C99 target of symbt codegen for N={N}, compiled with the system C compiler, = the literal "
                 "map (50 digits) within 16 N eps S_i, every cell and at q spread over ~1000, its body the form its "
                 "header names (closed for N <= 3, the loop beyond; skipped without a C compiler)")
def c_target(N: int, parts: Parts, deep: bool = False) -> Outcome:
    if c_compiler() is None:
        return skipped("no C compiler (cc, gcc or clang) on PATH")
    call = c_step(N)

    def run(st, b):
        rc, pt, qt = call(st[0], st[1], st[2], st[3], b)
        if rc == C_RANGE:
            raise _CRangeError("status SYMBT_TODA_RANGE")
        if rc != C_OK:
            raise RuntimeError(f"status {rc}")
        return pt, qt
    problem = c_form_problem(N)
    if problem:
        return failed("the C target's form", detail=problem + " (closed form for N = 2, 3; the loop beyond)")
    return _check_emitted(N, {f"toda{N}.c": run}, deep, f"C toda{N}_bt_step", parts.printed["scale"])


# --------------------------------------------------------------------------- existence

ISSUE_STATES = (((0.0, 0.0), (0.0, 19.0), float(np.exp(9.5)), 0.3 * float(np.exp(9.5))),
                ((0.0, 0.0), (0.0, 200.0), 2.5e43, 0.5e43))


def _no_map(st: tuple, b: int) -> tuple[str | None, bool]:
    """``(condition, decided)``: why no real map exists (None: it exists), and whether the literal route at
    REF_DPS and CHECK_DPS (guard digits from the traces) agrees on it."""
    from ._shipped import guard_digits

    g = guard_digits(st)
    verdicts: list[str | None] = []
    for dps in (REF_DPS + g, CHECK_DPS + g):
        _, _, info = literal_state(st, b, dps)
        t1, t2 = info["tr1"], info["tr2"]
        if not (isinstance(t1, mp.mpf) and isinstance(t2, mp.mpf)) or abs(t1) <= 2 or abs(t2) <= 2:
            verdicts.append("trace")
        elif t1 * t2 < 0:
            verdicts.append("opposite signs")
        elif not all(isinstance(e, mp.mpf) and e > 0 for e in info["E_new"]):
            verdicts.append("E~ <= 0")
        else:
            verdicts.append(None)
    return verdicts[0], verdicts[0] == verdicts[1]


@cache
def nomap_states(N: int) -> tuple:
    """``(state, branch, condition)`` without a real map: issue 21's (N = 2) and seeded ones."""
    out: list[tuple[tuple, int]] = [(st, 1) for st in ISSUE_STATES] if N == 2 else []
    rng = np.random.default_rng(777 + N)
    want = {"opposite signs": 2, "E~ <= 0": 2 if N >= 3 else 0}
    tries = 0
    while any(want.values()) and tries < 3000:
        tries += 1
        p = tuple(float(v) for v in np.round(rng.uniform(-3, 3, N), 6))
        q = tuple(float(v) for v in np.round(rng.uniform(-1.5, 1.5, N), 6))
        st = (p, q, float(np.round(rng.uniform(-5, 5), 6)), float(np.round(rng.uniform(0.3, 3), 6)))
        b = int(rng.choice((1, -1)))
        cond, decided = _no_map(st, b)
        if decided and want.get(str(cond), 0) > 0:
            want[str(cond)] -= 1
            out.append((st, b))
    return tuple((st, b, _no_map(st, b)) for st, b in out)


def _nomap_routes(N: int, deep: bool) -> dict[str, Callable[..., Any]]:
    from ..numeric import bt_orbit, bt_step

    def f(be):
        return lambda st, b: bt_step(np.array(st[0]), np.array(st[1]), st[2], st[3], branch=b, backend=be)

    def mpr(be):
        def run(st, b):
            with mp.workdps(MP_DPS):
                return bt_step([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]], mp.mpf(st[2]),
                               mp.mpf(st[3]), branch=b, backend=be)
        return run

    routes: dict[str, Callable[..., Any]] = {
        "bt_step (fused kernel)": f("python"), "bt_step (general path)": f("numpy"),
        "batch": lambda st, b: bt_step(np.array([st[0]] * 2), np.array([st[1]] * 2), st[2], st[3], branch=b,
                                       backend="numpy"),
        "bt_orbit": lambda st, b: bt_orbit(np.array(st[0]), np.array(st[1]), st[2], st[3], 3, branch=b,
                                           backend="python"),
        "ensemble (block kernel)": lambda st, b: bt_orbit(np.array([st[0]] * 2), np.array([st[1]] * 2), st[2],
                                                         st[3], 3, branch=b, backend="python"),
        "bt_step (mpmath)": mpr("mpmath")}
    if importlib.util.find_spec("flint") is not None:
        routes["bt_step (Arb)"] = mpr("flint")
    if deep and importlib.util.find_spec("numba") is not None:   # numba: bit-identical to the fused kernel above
        routes["bt_step (auto)"], routes["bt_step (numba)"] = f("auto"), f("numba")
    mod = importlib.import_module(f"symbt.generated.toda{N}") if N in (2, 3) else emitted_module(N)
    routes[f"toda{N}.bt_step"] = lambda st, b: mod.bt_step(list(st[0]), list(st[1]), st[2], st[3], b)
    if c_compiler() is not None and (deep or N == 5):   # the loop form's C renders in ms; closed forms need SymPy
        call = c_step(N)

        def c_route(st, b):
            rc, pt, qt = call(st[0], st[1], st[2], st[3], b)
            if rc in C_NO_MAP:
                raise mod.NoRealMapError(f"C status {rc}")
            if rc != C_OK:
                raise RuntimeError(f"C status {rc}")
            return pt, qt
        routes[f"toda{N}.c"] = c_route
    return routes


def _nomap_parts() -> Parts:
    return Parts(printed={"error": "NoRealMapError"})


@claim("shipped.nomap", equation="imptransf", scene="shipped", parts=_nomap_parts,
       where="symbt.numeric (every backend), symbt.generated.toda2/3, the loop form (N = 5), the C target",
       statement="where the exact map does not exist (tr L(lambda_1), tr L(lambda_2) of opposite signs, or some "
                 "E~_j <= 0; decided by the literal route at 50 and 75 digits), every route raises NoRealMapError "
                 "(the C target returns SYMBT_TODA_NO_REAL_MAP_*): float64 bt_step (fused kernel, general path, "
                 "batch; numba and auto under --deep), bt_orbit (one state, ensemble), mpmath and Arb, the emitted "
                 "modules (N = 2, 3, 5) and the C target (N = 5; N = 2, 3 under --deep)")
def nomap(parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import NoRealMapError

    table = CellTable(tol=0.5)
    bad: list[str] = []
    n = 0
    for N in (2, 3, 5):
        routes = _nomap_routes(N, deep)
        for st, b, (cond, decided) in nomap_states(N):
            for name, fn in routes.items():
                n += 1
                if not decided:
                    res, why = 1.0, "the reference disagrees with itself at 50 and 75 digits"
                else:
                    try:
                        fn(st, b)
                        res, why = 1.0, "returned a finite state"
                    except (NoRealMapError, ValueError) as exc:
                        ok = type(exc).__name__ == parts.printed["error"]
                        res, why = (0.0, "") if ok else (1.0, f"raised {type(exc).__name__}")
                    except Exception as exc:
                        res, why = 1.0, f"raised {type(exc).__name__}"
                if res and len(bad) < 6:
                    bad.append(f"{name} at N={N} ({cond}): {why}")
                table.add({"route": name, "N": N, "condition": str(cond)}, printed=res,
                          point=fmt_state(tuple(mp.mpf(v) if not isinstance(v, tuple) else [mp.mpf(x) for x in v]
                                                for v in st), b))
    detail = ("; ".join(bad) + ".") if bad else "every route raised NoRealMapError (the C target: its status)."
    out = judge_cells(table, printed="no real map -> NoRealMapError on every route", method="numeric: existence "
                      "decided by the literal route (50 and 75 digits) vs each route's answer", dps=REF_DPS,
                      detail=detail)
    out = replace(out, n_scope=[2, 3, 5])
    return out
