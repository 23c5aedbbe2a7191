r"""Code generation checked where Zullo's claims do not look: the user path and the sources' guards.

Scene ``library``:

* ``library.emit`` -- the user code-generation path (:func:`symbt.emit`, :func:`symbt.codegen.user.files.generate`,
  :mod:`symbt.codegen.user.render`, :func:`symbt.codegen.user.check.compare`), which only ``symbt codegen`` in a
  user's project runs.  Six small declarations (a scalar, a vector with ``Max``/``Min``, a matrix,
  :math:`xy + 1` near its zero, :math:`x/2 + y/3 - 1` and :math:`x + 1/3`) are emitted into a temporary directory over a
  stale file of the same name, and the emitted module is imported from disk.  Three routes:

  1. *consistency* (the emitted code against the expression it was generated from): ``compare`` -- the
     SymPy source through plain ``lambdify`` at 60 digits -- accepts the numpy and mpmath flavours of every
     function (for :math:`xy + 1` only with the condition scale :math:`|f| + \sum_i |x_i\,\partial_i f|`: the
     float64 product rounds to ~1e-16 while :math:`|f| \le 0.02`), and rejects a hand-written file whose
     constant is off by 1e-9 (two-sided);
  2. *printed numbers*: ``softplus(0) = ln 2 = 0.6931471805599453``, ``softplus_mp(0)`` at 50 digits equals
     :math:`\ln 2` to 1e-45, ``third_mp(0)`` is :math:`1/3` to 1e-48;
  3. *independent formulas*: :math:`\sinh, \cosh` against :math:`(e^x \mp e^{-x})/2` by ``math.exp``,
     ``Max``/``Min`` against Python's ``max``/``min``, the rotation :math:`R` against :math:`R^T R = x^2 I`, within
     16 ulp of the value's size; ``half(0.5, 1.5) = -0.25`` exactly;
  4. *the docstrings*: each function's states the shape it returns -- ``batch + S`` (numpy), "a scalar" or
     ``shape S`` (mpmath) -- read against the values returned at one point (seed 25's ``user.render:60``: the
     mpmath docstring's words for a scalar and a shape, which nothing read).

  The C target (where a C compiler is present; else the detail says it was not compiled): the module
  compiles (a first term with a coefficient in (0, 1) printed ``x/2.0``, never ``--x/2.0``) and ``compare``
  accepts :math:`xy + 1` through it.
* ``checker.codegen`` -- the check of Zullo's emitted functions, :func:`symbt.codegen.verify.compare`, is
  two-sided and says where it failed: the shipped ``symbt.generated.toda2.invariants`` passes, and the same
  module with output 1 of the numpy flavour off by a relative 1e-9 fails, with output 1 and its float64
  value as the reported counterexample.
* ``library.guards`` -- the guards of :func:`symbt.codegen.derive.sources`' ``bt_step`` (N = 2), the paper's
  route: the trace guards :math:`(T_i - 2)(T_i + 2)` and the positivity guards :math:`1 - x_j/E_j` against
  :math:`\operatorname{tr}L(\lambda_i)^2 - 4` and :math:`\tilde E_j/E_j` of the literal map
  (:func:`symbt.reference.literal.literal_step`) at 30 digits, both branches, states of both trace signs.

>>> guard_sources.run().status
'verified'
"""
from __future__ import annotations

import math
import tempfile
from pathlib import Path
from types import ModuleType
from typing import cast

import mpmath as mp
import numpy as np
import sympy as sp

from .base import Outcome, claim, failed

#: module name of the control emissions (a name no user module is likely to have)
MODULE = "symbt_emit_control"


def _declarations():
    from ..codegen.user.declare import emit
    from ..proof import Domain

    x, y = sp.symbols("x y", real=True)
    box = Domain({"x": (-3, 3), "y": (-2, 2)}, seed=11)
    return [
        emit("softplus", sp.log(1 + sp.exp(x)), args=(x,), module=MODULE, domain=Domain({"x": (-3, 3)}, seed=10),
             register=False),
        emit("hyp", [sp.sinh(x), sp.cosh(x), sp.Max(x, y), sp.Min(x, y)], args=(x, y), module=MODULE, domain=box,
             register=False),
        emit("rot", sp.Matrix([[sp.cos(y), -sp.sin(y)], [sp.sin(y), sp.cos(y)]]) * x, args=(x, y), module=MODULE,
             domain=box, register=False),
        emit("cancel", x * y + 1, args=(x, y), module=MODULE,
             domain=Domain({"x": (0.99, 1.01), "y": (-1.01, -0.99)}, seed=12), register=False),
        # a sum whose first term has a coefficient in (0, 1): printed "x/2.0 + ...", never "--x/2.0" (C's decrement)
        emit("half", x / 2 + y / 3 - 1, args=(x, y), module=MODULE, domain=box, register=False),
        # a rational constant on its own: exact in mpmath (_Q(1, 3)), never a float 1/3 or C's integer 1/3
        emit("third", x + sp.Rational(1, 3), args=(x,), module=MODULE, domain=Domain({"x": (-1, 1)}, seed=13),
             register=False),
    ]


WRONG = '''import numpy as np
import mpmath
def cancel(x, y):
    return np.asarray(x, dtype=np.float64) * y + 1.000000001
def cancel_mp(x, y):
    return mpmath.mpf(x) * y + mpmath.mpf("1.000000001")
'''


def _c_warnings(source: Path) -> str:
    """The compiler's diagnostics for ``source`` under ``-std=c99 -Wall -Wextra`` ('' if none)."""
    import subprocess

    from ..codegen.user.check import compiler

    cc = compiler()
    assert cc is not None
    r = subprocess.run([cc, "-std=c99", "-Wall", "-Wextra", "-c", "-I", str(source.parent), "-o", "/dev/null",
                        str(source)], capture_output=True, text=True, timeout=120)
    return (r.stderr.strip().splitlines() or [""])[0] if (r.returncode or r.stderr.strip()) else ""


@claim("library.emit", equation="checker", scene="library",
       where="symbt.emit -> symbt.codegen.user (generate, render, check.compare): the user code-generation path",
       statement="functions declared with symbt.emit and emitted into a directory agree with their SymPy source "
                 "(compare, numpy and mpmath; a file off by 1e-9 is rejected), with printed numbers (softplus(0) = "
                 "ln 2) and with independent formulas (sinh, cosh by exp; Max, Min; R^T R = x^2 I); a stale file "
                 "is replaced; the C target (where a compiler is present) compiles without a warning under -Wall "
                 "-Wextra, with sgn() exactly where a sign is printed; each function's docstring names the shape "
                 "it returns")
def emitted_user_functions() -> Outcome:
    from ..codegen.user.check import compare, compiler, load_python
    from ..codegen.user.declare import emit
    from ..codegen.user.files import generate, render
    from ..proof import Domain

    ems = _declarations()
    bad: list[str] = []
    with tempfile.TemporaryDirectory(prefix="symbt-emit-control-") as tmp:
        out = Path(tmp)
        target = out / f"{MODULE}.py"
        target.write_text("# a stale file: generate must replace it\n")
        generate(ems, out, out)
        want = render(ems, out, out)[target.name]
        if target.read_text(encoding="utf-8") != want:
            return failed("symbt.codegen.user.files.generate", detail="a stale file of the emitted module was not "
                                                                      "replaced by the rendered text")
        mod = load_python(target)
        # 1. consistency with the SymPy source (compare: 60 digits, the condition scale), and two-sided
        for e in ems:
            for flavour in ("numpy", "mpmath"):
                table = compare(e, target, flavour, per_cell=6)
                if not table.printed_holds_everywhere():
                    bad.append(f"compare({e.name}, {flavour}) rejects the emitted file: worst {table.worst()[0]:.3g}")
        wrong = out / "wrong.py"
        wrong.write_text(WRONG)
        for flavour in ("numpy", "mpmath"):
            if compare(ems[3], wrong, flavour, per_cell=6).printed_holds_everywhere():
                bad.append(f"compare(cancel, {flavour}) accepts a file whose constant is off by 1e-9")
        # the C target, where a compiler is present: one compile of the whole module, cancel called through it
        c_note = "C target not compiled (no C compiler on PATH)"
        if compiler() is not None:
            generate(ems, out, out, target="c")
            try:
                if not compare(ems[3], out / f"{MODULE}.c", "c", per_cell=6).printed_holds_everywhere():
                    bad.append("compare(cancel, c) rejects the emitted C")
            except RuntimeError as exc:     # load_c: it does not compile
                bad.append(f"the emitted C: {exc}")
            # warning-free under -Wall -Wextra: no helper the functions do not call -- sgn() only where a sign is
            # printed (then it must be there, and right)
            warned = _c_warnings(out / f"{MODULE}.c")
            if warned or "sgn(" in (out / f"{MODULE}.c").read_text(encoding="utf-8"):
                bad.append(f"the emitted C without a sign: sgn() present or a warning: {warned}")
            x, y = sp.symbols("x y", real=True)
            signed = emit("signed", sp.sign(x) * y + x, args=(x, y), module=MODULE,
                          domain=Domain({"x": (-3, 3), "y": (-2, 2)}, seed=14), register=False)
            generate(ems + [signed], out, out, target="c")
            warned = _c_warnings(out / f"{MODULE}.c")
            if warned or "sgn(" not in (out / f"{MODULE}.c").read_text(encoding="utf-8"):
                bad.append(f"the emitted C with a sign: sgn() absent or a warning: {warned}")
            elif not compare(signed, out / f"{MODULE}.c", "c", per_cell=6).printed_holds_everywhere():
                bad.append("compare(signed, c) rejects the emitted C")
            c_note = ("the C target compiled without a warning (-Wall -Wextra; sgn() only with a sign); compare "
                      "accepts cancel and sign(x) y + x through it")
        # 2. printed numbers
        if float(mod.half(0.5, 1.5)) != -0.25:      # 1/4 + 1/2 - 1, exact in binary
            bad.append(f"half(0.5, 1.5) = {float(mod.half(0.5, 1.5))!r}, not -0.25")
        with mp.workdps(50):
            if abs(mod.third_mp(0) - mp.mpf(1) / 3) > mp.mpf(10) ** -48:
                bad.append("third_mp(0) differs from 1/3 at 50 digits")
        if float(mod.softplus(0.0)) != 0.6931471805599453:
            bad.append(f"softplus(0) = {float(mod.softplus(0.0))!r}, not ln 2 = 0.6931471805599453")
        with mp.workdps(50):
            if abs(mod.softplus_mp(0) - mp.log(2)) > mp.mpf(10) ** -45:
                bad.append("softplus_mp(0) differs from ln 2 at 50 digits")
        # 3. independent formulas, within 16 ulp of the value's size
        eps = 16 * 2.0 ** -52
        for xv, yv in ((0.3, -1.7), (-2.5, 0.4), (1.25, 1.25)):
            h = [float(v) for v in mod.hyp(xv, yv)]
            ref = [(math.exp(xv) - math.exp(-xv)) / 2, (math.exp(xv) + math.exp(-xv)) / 2, max(xv, yv), min(xv, yv)]
            if any(abs(a - b) > eps * max(1.0, abs(b)) for a, b in zip(h, ref)):
                bad.append(f"hyp({xv}, {yv}) = {h}, independent formulas give {ref}")
            with mp.workdps(30):
                hm = [mp.mpf(v) for v in mod.hyp_mp(xv, yv)]
                refm = [mp.sinh(xv), mp.cosh(xv), max(xv, yv), min(xv, yv)]
                if any(abs(a - b) > mp.mpf(10) ** -25 * max(1, abs(b)) for a, b in zip(hm, refm)):
                    bad.append(f"hyp_mp({xv}, {yv}) differs from mpmath's sinh, cosh, max, min")
            R = [[float(v) for v in row] for row in mod.rot(xv, yv)]
            gram = [[R[0][i] * R[0][j] + R[1][i] * R[1][j] for j in (0, 1)] for i in (0, 1)]
            want_g = [[xv * xv, 0.0], [0.0, xv * xv]]
            if any(abs(gram[i][j] - want_g[i][j]) > 4 * eps * xv * xv for i in (0, 1) for j in (0, 1)):
                bad.append(f"rot({xv}, {yv})^T rot = {gram}, not x^2 I")
        # 4. each function's docstring names the shape it returns (numpy: batch + shape; mpmath: a scalar or the
        # shape), read against the values returned at one point
        for e in ems:
            pt = [0.5] * len(e.arg_names)
            S = np.shape(getattr(mod, e.name)(*pt))
            Sm = np.shape(np.array(getattr(mod, e.name + "_mp")(*pt), dtype=object))
            docs = (getattr(mod, e.name).__doc__ or "", getattr(mod, e.name + "_mp").__doc__ or "")
            if f"batch + {S}" not in docs[0] or ("a scalar" if Sm == () else f"shape {Sm}") not in docs[1]:
                bad.append(f"{e.name} returns shape {S} (mpmath {Sm}); its docstrings say {docs[0][-80:]!r}, "
                           f"{docs[1][-70:]!r}")
    if bad:
        return failed("symbt.emit -> generate -> compare / independent formulas", detail="; ".join(bad))
    return Outcome("verified", "numeric: emitted numpy and mpmath flavours vs the SymPy source at 60 digits "
                               "(consistency), printed ln 2, and independent formulas", evidence="sampled",
                   n_scope="all",
                   detail=f"{len(ems)} declarations emitted over a stale file; compare accepts both flavours of "
                          "each (6 points per cell) and rejects a file off by 1e-9; softplus(0) = ln 2, "
                          "third_mp(0) = 1/3, half(0.5, 1.5) = -0.25; sinh, cosh, Max, Min and R^T R = x^2 I at 3 "
                          f"points within 16 ulp; docstrings name the shapes returned; {c_note}")


@claim("library.guards", equation="xy", scene="library", N=2,
       where="symbt.codegen.derive.sources: the guards of bt_step (the paper's route, eq. xy)",
       statement="the guards of sources()' bt_step are tr L(lambda_i)^2 - 4 and E~_j/E_j of the literal map (N=2, "
                 "both branches, both trace signs)")
def guard_sources() -> Outcome:
    from ..codegen import derive
    from ..codegen.verify import evaluate_source, map_states
    from ..reference.literal import literal_step

    N = 2
    spec = next(s for s in derive.sources(N) if s.name == "bt_step")
    labels = [g.condition for g in spec.guards]
    if labels != ["trace", "trace"] + ["positivity"] * N:
        return failed("derive.sources", detail=f"bt_step's guards are {labels} (want 2 trace, {N} positivity)")
    worst, where = mp.mpf(0), None
    with mp.workdps(30):
        for p, q, l0, m in map_states(N):
            for b in (1, -1):
                pt = {"p": p, "q": q, "lam0": l0, "mu": m, "branch": b}
                got = evaluate_source(N, "bt_step", pt, dps=30, part="guards")
                P, Q = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]
                info = literal_step(P, Q, mp.mpf(l0), mp.mpf(m), b)[2]
                want = [info["tr1"] ** 2 - 4, info["tr2"] ** 2 - 4] + [e / mp.exp(v) for e, v in zip(info["E_new"], Q)]
                for k, (g, w) in enumerate(zip(got, want)):
                    r = abs(g - w) / max(1, abs(w))
                    if r > worst:
                        worst, where = r, {"guard": k, "branch": b, "p": p, "q": q}
    if worst > mp.mpf(10) ** -20:
        return failed("numeric: literal map at 30 digits", residual=float(worst), counterexample=where,
                      detail=f"a guard of sources()' bt_step differs from the literal map by {float(worst):.2e} "
                             "(relative; accepted below 1e-20)")
    return Outcome("verified", "numeric: literal map (symbt.reference.literal) at 30 digits", residual=float(worst),
                   evidence="sampled", n_scope=[N],
                   detail=f"{len(spec.guards)} guards at {len(map_states(N))} states x 2 branches: trace guards = "
                          f"tr^2 - 4, positivity guards = E~_j/E_j; worst relative difference {float(worst):.1e} "
                          f"(accepted below 1e-20)")


@claim("checker.codegen", equation="tra", scene="checker", N=2,
       where="symbt.codegen.verify.compare (the check of the emitted functions against their SymPy sources)",
       statement="codegen.verify.compare passes the shipped toda2.invariants and fails it with output 1 of the numpy "
                 "flavour off by a relative 1e-9, reporting output 1 and its float64 value")
def codegen_check_controls() -> Outcome:
    from types import SimpleNamespace

    import numpy as np

    from ..codegen.derive import interface
    from ..codegen.verify import compare, points
    from ..generated import toda2

    pts = points(interface(2)["invariants"], 2)[:3]
    good = compare(toda2, 2, "invariants", pts=pts)
    if not good["ok"]:
        return failed("codegen.verify.compare", detail=f"the shipped toda2.invariants fails: {good['bad']}")

    def off(**pt):
        v = np.array(toda2.invariants(**pt), dtype=np.float64)
        v[..., 1] *= 1 + 1e-9
        return v

    wrong = SimpleNamespace(invariants=off, invariants_mp=toda2.invariants_mp)
    res = compare(cast(ModuleType, wrong), 2, "invariants", pts=pts)
    bad = res["bad"] or {}
    want = None if not bad else repr(float(off(**_point_of(bad["point"]))[1]))
    if res["ok"] or bad.get("output") != 1 or bad.get("f64") != want:
        return failed("codegen.verify.compare", detail=f"a numpy flavour off by 1e-9 in output 1: ok={res['ok']}, "
                                                       f"reported {bad} (want output 1, f64 {want})")
    return Outcome("verified", "numeric: codegen.verify.compare on the shipped module and on a module off by 1e-9",
                   evidence="sampled", n_scope=[2],
                   detail=f"shipped invariants: {good['worst_f64']:.2f} eps x condition; off by 1e-9 in output 1: "
                          f"{res['worst_f64']:.3g} eps x condition, reported at output 1 with f64 {bad['f64']}")


def _point_of(text: str) -> dict:
    """The point a report shows as ``repr(dict)`` of floats, lists of floats and ints."""
    import ast

    return ast.literal_eval(text)
