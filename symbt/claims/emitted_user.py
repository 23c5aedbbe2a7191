r"""The typed user code-generation path checked against formulas written out by hand (scene ``library``).

``library.emit`` checks the plain form of :func:`symbt.emit`; these claims check what only a *typed* declaration
reaches -- array arguments sampled by component, a sign argument, named outputs, a guard, a ``Piecewise`` -- and
the printer on powers and on ``exp(s) - 1`` near 0 (issue 21, item 4: the survivors of ``symbt mutate --source
codegen``, docs/mutation.md).

* ``library.emit_typed`` -- one typed declaration, ``probe(z, s, b)`` with ``z = (x, y)``, outputs
  ``v = (b x^2 sqrt(y), x^3 - s, 1/(2 b))`` (the last a quotient with no numerator factor, of the sign ``b``) and
  ``w = x - y`` (``x > y``) or ``exp(s) - 1``, the guard ``y > 0``, the domain
  given per element of ``z``; emitted (numpy, mpmath and, where a C compiler is present, C99) into a temporary
  directory and loaded from disk.  Three routes:

  1. *independent formulas*: at fixed points (both branches of the ``Piecewise``, both signs ``b``) every flavour
     against the same quantities computed with mpmath at 60 digits from the formulas above (``mp.expm1``), not
     from the SymPy expression: float64 within ``4 u = 2 eps`` relative (each output is at most three correctly
     rounded operations -- ``x*x``, ``sqrt``, a product; ``pow``/``expm1`` within one ulp, a subtraction --
     on exact inputs, and no output cancels at these points), mpmath at 50 digits within ``1e-45``; and the
     60-digit reference agrees with itself at 80 digits;
  2. *refusal*: at ``y < 0`` the numpy flavour raises ``NoRealMapError`` with ``condition == "positive"``, the
     mpmath flavour too, and ``errors="mask"`` masks exactly that batch element;
  3. *consistency* (the emitted code against the expression it was generated from, :func:`~symbt.codegen.user.check.
     compare`): every flavour accepted, points refused by the guard on both sides and points compared both
     present, and every cell -- both signs of ``x - y`` (the ``Piecewise``), both signs ``b`` -- sampled.

  A domain without the scalar ``s`` is refused with an :class:`~symbt.codegen.user.EmitError` naming
  "the argument s"; text in place of an expression (``"x + 1"``, a list holding ``"x"``) is refused as "not a
  SymPy expression" (not parsed), and ``x - oo``, ``x + oo`` as a "non-finite constant" of their sign.
* ``library.emit_c_errors`` -- :func:`~symbt.codegen.user.check.load_c` on a C file that does not compile raises
  ``RuntimeError`` carrying the compiler's first diagnostic line (which names the file), and loads a file
  that does (skipped without a C compiler).

>>> emit_typed.run().status in ("verified", "skipped")
True
"""
from __future__ import annotations

import ctypes
import tempfile
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np
import sympy as sp

from .base import Outcome, claim, failed, skipped

#: module name of the typed control emission (a name no user module is likely to have)
MODULE = "symbt_typed_control"
EPS = float(np.finfo(np.float64).eps)
#: float64 bound, relative: at most three correctly rounded operations (or pow/expm1 within one ulp) per output
F64_REL = 2 * EPS
MP_REL = mp.mpf(10) ** -45
#: (x, y, s, b): both branches of the Piecewise (x > y, x < y) and both signs, s small (expm1's cancellation)
POINTS = ((1.25, 0.640625, 3e-10, 1), (-0.7, 1.69, -7e-10, -1), (1.5, 0.25, 1e-9, -1), (0.375, 2.25, 5e-10, 1))


def declaration(domain: dict[str, Any] | None = None) -> Any:
    """The typed control declaration (not registered)."""
    from ..codegen.user.declare import emit
    from ..codegen.user.typed import Guard
    from ..proof import Domain

    x, y, s, b = sp.symbols("x y s b", real=True)
    dom = Domain(domain or {"x": (-2, 2), "y": (-1, 3), "s": (-1e-9, 1e-9)}, seed=21)
    return emit("probe", {"v": [b * x**2 * sp.sqrt(y), x**3 - s, 1 / (2 * b)],
                          "w": sp.Piecewise((x - y, x > y), (sp.exp(s) - 1, True))},
                args=(("z", (x, y)), s, ("b", b, "sign")), module=MODULE,
                guards=[Guard("positive", "y", y, early=True)], domain=dom, register=False)


def by_hand(x: float, y: float, s: float, b: int) -> list[mp.mpf]:
    """``v1, v2, v3, w`` from the formulas written out (mpmath at the working precision), not from SymPy."""
    X, Y, S = mp.mpf(x), mp.mpf(y), mp.mpf(s)
    return [b * X * X * mp.sqrt(Y), X ** 3 - S, mp.mpf(b) / 2, X - Y if X > Y else mp.expm1(S)]


def _worst(got: list[Any], want: list[mp.mpf]) -> mp.mpf:
    with mp.workdps(60):
        return max(abs(mp.mpf(g) - w) / abs(w) for g, w in zip(got, want))


def _c_probe(path: Path, e: Any, keep: list[Any]) -> Any:
    """``probe`` of the compiled C target: ``(status, [v1, v2, v3, w])``."""
    from ..codegen.user.check import load_c
    from ..codegen.user.render import c_name

    fn = getattr(load_c(path, keep), c_name(MODULE, e))
    dp = ctypes.POINTER(ctypes.c_double)
    fn.restype, fn.argtypes = ctypes.c_int, [dp, ctypes.c_double, ctypes.c_int, dp, dp]

    def call(x: float, y: float, s: float, b: int) -> tuple[int, list[float]]:
        v, w = (ctypes.c_double * 3)(), (ctypes.c_double * 1)()
        code = fn((ctypes.c_double * 2)(x, y), s, b, v, w)
        return code, [v[0], v[1], v[2], w[0]]
    return call


@claim("library.emit_typed", equation="checker", scene="library",
       where="symbt.emit (typed form) -> symbt.codegen.user (typed domain, render_typed, render_typed_c, printing, "
             "check.compare)",
       statement="a typed declaration (array argument, sign, named outputs, a guard, a Piecewise) emitted as numpy, "
                 "mpmath and C equals formulas written out by hand (float64 within 2 eps relative, mpmath within "
                 "1e-45), refuses where its guard fails, and compare samples every cell of it; a one-column or one-row "
                 "Matrix keeps its shape; the method text names each flavour's bound")
def emit_typed() -> Outcome:
    from ..codegen.user.check import Comparison, c_status, compare, compiler, load_python
    from ..codegen.user.declare import EmitError, emit
    from ..codegen.user.files import generate
    from ..codegen.user.render_typed import typed_doc

    bad: list[str] = []
    e = declaration()
    try:
        declaration({"x": (-2, 2), "y": (-1, 3)})
        bad.append("a domain without the scalar s was accepted")
    except EmitError as exc:
        if "lacks the argument s" not in str(exc):
            bad.append(f"a domain without s: the message does not name the argument s: {exc}")
    xs = sp.Symbol("x", real=True)
    # text is not parsed (sympify's strict mode); an infinity of either sign is no finite constant
    for given, words in (("x + 1", "not a SymPy expression"), (["x", xs], "not a SymPy expression"),
                         (xs - sp.oo, "non-finite constant -oo"), (xs + sp.oo, "non-finite constant oo")):
        try:
            emit("refused_probe", given, args=(xs,), module=MODULE, register=False)
            bad.append(f"{given!r} was accepted as an expression")
        except EmitError as exc:
            if words not in str(exc):
                bad.append(f"{given!r}: the message does not say {words!r}: {exc}")
    # the verdict's method names the bound of its flavour (what a reader of the report checks the error against)
    from ..codegen.user.check import F64_TOL_ULPS, method_text
    for fl, words in (("mpmath", "1e-45 x condition (mpmath at 50 digits)"),
                      ("numpy", f"{F64_TOL_ULPS} ulp x condition (float64)"),
                      ("c", f"{F64_TOL_ULPS} ulp x condition (float64)")):
        if words not in method_text(fl) or fl not in method_text(fl):
            bad.append(f"method_text({fl!r}) does not name its flavour and the bound {words!r}: {method_text(fl)}")
    # a matrix of one column or one row is a matrix, not an empty one
    for given, shape in ((sp.Matrix([xs, 1]), (2, 1)), (sp.Matrix([[xs, 1]]), (1, 2))):
        try:
            got_shape = emit("shape_probe", given, args=(xs,), module=MODULE, register=False).shape
            if got_shape != shape:
                bad.append(f"a {shape} matrix was declared with shape {got_shape}")
        except EmitError as exc:
            bad.append(f"a {shape} matrix was refused: {exc}")
    worst = {"numpy": mp.mpf(0), "mpmath": mp.mpf(0), "c": mp.mpf(0)}
    cc = compiler()
    flavours = ("numpy", "mpmath", "c") if cc is not None else ("numpy", "mpmath")
    keep: list[Any] = []
    with tempfile.TemporaryDirectory(prefix="symbt-typed-control-") as tmp:
        out = Path(tmp)
        generate([e], out, out)
        if cc is not None:
            generate([e], out, out, target="c")
        mod = load_python(out / f"{MODULE}.py")
        c_call = _c_probe(out / f"{MODULE}.c", e, keep) if cc is not None else None
        codes = c_status(out / f"{MODULE}.h", e) if cc is not None else {}
        try:
            # 1. independent formulas
            for x, y, s, b in POINTS:
                with mp.workdps(80):
                    check = by_hand(x, y, s, b)
                with mp.workdps(60):
                    want = by_hand(x, y, s, b)
                    if max(abs(a - c) / abs(c) for a, c in zip(want, check)) > mp.mpf(10) ** -55:
                        bad.append(f"the hand-written reference disagrees with itself at ({x}, {y}, {s}, {b})")
                try:
                    v, w = mod.probe([x, y], s, b)
                    got = [float(v[0]), float(v[1]), float(v[2]), float(w)]
                    worst["numpy"] = max(worst["numpy"], _worst(got, want))
                    with mp.workdps(50):
                        vm, wm = mod.probe_mp([x, y], s, b)
                    worst["mpmath"] = max(worst["mpmath"], _worst([vm[0], vm[1], vm[2], wm], want))
                except Exception as exc:    # a valid point: no flavour may refuse it
                    bad.append(f"probe({x}, {y}, {s}, {b}) raised {type(exc).__name__}: {str(exc)[:100]}")
                if c_call is not None:
                    code, got = c_call(x, y, s, b)
                    if codes.get(code) != "ok":
                        bad.append(f"C probe({x}, {y}, {s}, {b}) returned status {code} ({codes.get(code)})")
                    worst["c"] = max(worst["c"], _worst(got, want))
            for fl in flavours:
                tol = MP_REL if fl == "mpmath" else F64_REL
                if worst[fl] > tol:
                    bad.append(f"{fl}: worst relative error {mp.nstr(worst[fl], 3)} against the formulas "
                               f"(bound {mp.nstr(tol, 3)})")
            # 2. refusal where the guard fails
            for call in (lambda: mod.probe([0.5, -0.25], 1e-10, 1), lambda: mod.probe_mp([0.5, -0.25], 1e-10, 1)):
                try:
                    call()
                    bad.append("probe returned a value at y = -0.25 (guard y > 0)")
                except mod.NoRealMapError as exc:
                    if exc.condition != "positive":
                        bad.append(f"probe at y < 0 raised NoRealMapError with condition {exc.condition!r}")
            # the docstrings: generated for this declaration (it gives none), the given text verbatim otherwise
            doc = mod.probe.__doc__ or ""
            if not ("errors='mask'" in doc and "NoRealMapError" in doc):
                bad.append(f"probe's generated docstring does not describe its guard: {doc[:80]!r}")
            x_, y_ = sp.symbols("x y", real=True)
            given = emit("probe_doc", x_ * y_, args=(("z", (x_, y_)),), module=MODULE, register=False,
                         doc={"numpy": "Given, numpy.", "mpmath": "Given, mpmath."})
            if [typed_doc(given, fl) for fl in ("numpy", "mpmath")] != ["Given, numpy.", "Given, mpmath."]:
                bad.append(f"a given docstring not kept verbatim: {typed_doc(given, 'numpy')[:60]!r}")
            mv, mw = mod.probe(np.array([[0.5, -0.25], [0.5, 0.25]]), 1e-10, 1, errors="mask")
            if list(np.ma.getmaskarray(mw)) != [True, False] or abs(float(mw[1]) - 0.25) > 2 * EPS:
                bad.append(f"errors='mask' at y = (-0.25, 0.25): w = {mw!r}")
            if c_call is not None and codes.get(c_call(0.5, -0.25, 1e-10, 1)[0]) != "positive":
                bad.append("C probe at y < 0 did not return the status of its guard 'positive'")
            # 3. consistency with the SymPy source: every flavour, both guard outcomes, every cell
            for fl in flavours:
                seen = Comparison()
                table = compare(e, out / f"{MODULE}.{'c' if fl == 'c' else 'py'}", fl, per_cell=3, seen=seen)
                if not table.printed_holds_everywhere():
                    bad.append(f"compare({fl}) rejects the emitted file: worst {table.worst()[0]:.3g}")
                if not (seen.refused and seen.compared):
                    bad.append(f"compare({fl}): {seen.refused} refused, {seen.compared} compared (want both)")
                cells = {tuple(sorted(r.cell.items())) for r in table.rows.values() if r.n}
                want_cells = {(("b", sb), ("sign(x - y)", c)) for sb in (1, -1) for c in ("x<y", "x>y")}
                if cells != want_cells:
                    bad.append(f"compare({fl}) sampled the cells {sorted(cells)}, not both signs of x - y and of b")
        finally:
            for t in keep:
                t.cleanup()
    c_note = "C compiled and checked" if cc is not None else "C not compiled (no C compiler on PATH)"
    detail = (f"worst relative error against the hand-written formulas: numpy {mp.nstr(worst['numpy'], 3)}, "
              f"mpmath {mp.nstr(worst['mpmath'], 3)}, C {mp.nstr(worst['c'], 3)} (bounds 2 eps = {F64_REL:.2g}, "
              f"1e-45) at {len(POINTS)} points; {c_note}")
    if bad:
        return failed("typed symbt.emit vs formulas written out", detail="; ".join(bad) + "; " + detail)
    return Outcome("verified", "numeric: typed emitted numpy/mpmath/C vs formulas written out (mpmath, 60 digits); "
                               "guard refusals; compare's cells", evidence="sampled", n_scope="all",
                   residual=float(max(worst.values())), detail=detail)


NOT_C = "int broken(double x) { return x +; }\n"


@claim("library.emit_c_errors", equation="checker", scene="library",
       where="symbt.codegen.user.check.load_c (the C compile of the emit.*.c claims)",
       statement="load_c raises RuntimeError with the compiler's first diagnostic line (naming the file) for a "
                 "C file that does not compile, and loads one that does (skipped without a C compiler)")
def emit_c_errors() -> Outcome:
    from ..codegen.user.check import compiler, load_c

    if compiler() is None:
        return skipped("no C compiler (cc, gcc or clang) on PATH")
    keep: list[Any] = []
    try:
        with tempfile.TemporaryDirectory(prefix="symbt-c-check-") as tmp:
            src = Path(tmp) / "broken.c"
            src.write_text(NOT_C)
            try:
                load_c(src, keep)
                return failed("load_c", detail="a C file with a syntax error was loaded")
            except RuntimeError as exc:
                msg = str(exc)
            except Exception as exc:    # anything but the documented RuntimeError
                return failed("load_c", detail=f"a file that does not compile raised {type(exc).__name__}: {exc}")
            if "broken.c" not in msg.split("does not compile", 1)[-1]:
                return failed("load_c", detail=f"the message does not carry the compiler's diagnostic: {msg!r}")
            good = Path(tmp) / "good.c"
            good.write_text("double twice(double x) { return 2.0 * x; }\n")
            fn = load_c(good, keep).twice
            fn.restype, fn.argtypes = ctypes.c_double, [ctypes.c_double]
            if fn(1.5) != 3.0:
                return failed("load_c", detail=f"the loaded twice(1.5) = {fn(1.5)!r}")
    finally:
        for t in keep:
            t.cleanup()
    return Outcome("verified", "the system C compiler on a broken and a correct file", evidence="proof",
                   n_scope="all", detail=f"RuntimeError: {msg[:160]}; a correct file loads and twice(1.5) = 3.0")
