r"""Code generation checked where no claim looked: shapes, templates, file checks, the printer, compare, the CLI.

Scene ``library`` (issue 21, item 4: the survivors of seed 3's sample of ``symbt mutate --source codegen``,
docs/mutation.md).  Each claim checks a documented property against a route that shares nothing with the code
under test -- values written out by hand, Python's own arithmetic, exact rationals, the signatures of the shipped
module -- or an exact fact:

* ``library.emit_shapes`` -- plain (untyped) :func:`symbt.emit` declarations of every shape: ``Emission.source``
  is the declared object (a scalar, a column of 3, a 2 x 3 matrix; ``==`` and shape); a registered
  :func:`~symbt.codegen.user.typed.module_template` is recorded in ``TEMPLATES`` and its head and tail frame the
  rendered module; the rendered 2 x 3 function (numpy and mpmath flavours) equals the matrix written out by hand
  (exact: dyadic inputs, sums of two dyadic products); :func:`symbt.codegen.user.files.check` reports nothing for
  fresh files, one line naming the file for a hand-edited and for a missing one.
* ``library.emit_c_sign`` (``--deep``: a C compile costs ~0.3 s on the shared machine) -- a plain C module whose
  function calls ``sgn`` compiles, and ``sign(x) y`` equals the hand value at both signs of ``x`` (skipped
  without a C compiler).
* ``library.printer_precedence`` -- :class:`symbt.codegen.printer.ExprPrinter` (numpy, mpmath and C flavours) on
  expressions where a missing parenthesis changes the value (a quotient by a product, by a quotient, a
  negated product of a quotient, a power of a sum): the printed text evaluated by Python at dyadic inputs
  equals the expression's exact rational value (every operation is exact there, so equality is exact).
* ``library.compare_refusal`` -- :func:`symbt.codegen.user.check.compare` on a typed declaration
  ``r = sqrt(x)`` (``x > 0``) / ``0`` with the guard ``x``: in the cell ``x < 0`` every point is refused on both
  sides, and its worst residual is exactly 0 (a refused point is counted, not compared); in the cell ``x > 0``
  the worst residual is at most 1/16 (a correctly rounded ``sqrt``: half an ulp of ``|r|`` against the bound
  ``16 eps 1.5 |r|``, plus the reference's 1e-45).  And two-sided: an mpmath flavour that loses 12 digits to a
  cancellation (``(r + 10^12) - 10^12``) is rejected -- the mpmath flavour runs at ``MP_DPS`` = 50 digits, where
  it is ~1e-38 off, far beyond the bound ``1e-45 S`` -- while the emitted one is accepted.
* ``library.sources_real`` -- every symbol of :func:`symbt.codegen.derive.sources` (N = 2: arguments, named
  definitions, outputs, guards) is declared real (``conjugate(s) == s``), and no two distinct symbols share a name
  (a substitution by name reaches every occurrence).
* ``library.signatures`` -- :func:`symbt.codegen.pymodule.signature` of every function of ``toda2``'s interface
  equals the parameter list of the shipped ``symbt.generated.toda2`` function (``inspect``): guarded numpy
  flavours end in ``errors="raise"``, mpmath flavours never do.
* ``library.codegen_rerun_argv`` -- the arguments ``symbt codegen`` passes when it re-runs itself in a checkout:
  ``--project`` and ``--out`` (both spellings) dropped, every other argument kept in order, ``--out`` re-added
  absolute; compared with the lists written out by hand.

>>> sources_real.run().status
'verified'
"""
from __future__ import annotations

import ctypes
import inspect
import tempfile
from fractions import Fraction
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np
import sympy as sp

from .base import Outcome, claim, failed, skipped

#: module names of the control emissions (names no user module is likely to have)
MODULE, TYPED, C_MODULE = "symbt_emit3_control", "symbt_emit3_typed", "symbt_emit3_csign"
#: a hand-written module head: the imports and the runtime the plain functions call (``DomainError``, ``_Q``, ``_pack``)
HEAD = '''"""A hand-written head."""
import mpmath
import numpy as np


class DomainError(ArithmeticError):
    pass


def _Q(p, q):
    return mpmath.mpf(p) / q


def _pack(items, batch, shape):
    arr = np.stack([np.broadcast_to(np.asarray(v, dtype=np.float64), batch) for v in items], axis=-1)
    return arr.reshape(batch + shape)'''
TAIL = "TAIL_MARK = 7"
#: (x, y): dyadic inputs, every product and sum below exact in float64
XY = ((1.5, -0.25), (-3.0, 0.75))


def _matrix(x: Any, y: Any) -> list[list[Any]]:
    """The 2 x 3 matrix declared below, written out by hand."""
    return [[x, y, x * y], [x + y, 2 * x, x - 3 * y]]


def _plain() -> list[Any]:
    from ..codegen.user.declare import emit

    x, y = sp.symbols("x y", real=True)
    return [emit("scal", x * y + 1, args=(x, y), module=MODULE, register=False),
            emit("col", [x, y, x + y], args=(x, y), module=MODULE, register=False),
            emit("mat", sp.Matrix(_matrix(x, y)), args=(x, y), module=MODULE, register=False)]


def _sources_of(ems: list[Any], x: sp.Symbol, y: sp.Symbol) -> list[str]:
    bad = []
    want = [x * y + 1, sp.ImmutableMatrix([x, y, x + y]), sp.ImmutableMatrix(_matrix(x, y))]
    for e, w in zip(ems, want):
        got = e.source
        if type(got) is not type(w) or got != w or getattr(got, "shape", ()) != getattr(w, "shape", ()):
            bad.append(f"{e.name}.source = {got!r}, declared {w!r}")
    return bad


@claim("library.emit_shapes", equation="checker", scene="library",
       where="symbt.codegen.user: Emission.source, module_template (TEMPLATES), render (plain matrices), "
             "files.check",
       statement="a plain declaration's source is the declared scalar, column or 2 x 3 matrix; a registered module "
                 "template frames the rendered module; the rendered 2 x 3 function equals the matrix written out by "
                 "hand; files.check reports nothing for fresh files and one line per edited or missing file")
def emit_shapes() -> Outcome:
    from ..codegen.user.check import load_python
    from ..codegen.user.files import check, generate
    from ..codegen.user.typed import TEMPLATES, module_template

    x, y = sp.symbols("x y", real=True)
    ems = _plain()
    bad = _sources_of(ems, x, y)
    saved = TEMPLATES.pop(MODULE, None)
    try:
        t = module_template(MODULE, head=HEAD, tail=TAIL)
        if TEMPLATES.get(MODULE) is not t:
            bad.append("module_template(register=True) did not record the template in TEMPLATES")
        with tempfile.TemporaryDirectory(prefix="symbt-emit3-") as tmp:
            out = Path(tmp)
            generate(ems, out, out)
            path = out / f"{MODULE}.py"
            text = path.read_text(encoding="utf-8")
            body = text[text.index('"""A hand-written head."""'):] if '"""A hand-written head."""' in text else ""
            if not body.startswith(HEAD) or not text.rstrip("\n").endswith(TAIL):
                bad.append("the rendered module is not framed by the registered template's head and tail")
            mod = load_python(path)
            if getattr(mod, "TAIL_MARK", None) != 7:
                bad.append("the template's tail did not run in the emitted module")
            for xv, yv in XY:
                want = _matrix(xv, yv)
                got = [[float(v) for v in row] for row in np.asarray(mod.mat(xv, yv), dtype=np.float64)]
                gm = mod.mat_mp(xv, yv)
                if got != want or [[float(v) for v in row] for row in gm] != want:
                    bad.append(f"mat({xv}, {yv}) = {got} / mat_mp = {gm}, by hand {want}")
            problems = check(ems, out, out)
            if problems:
                bad.append(f"files.check on fresh files: {problems}")
            path.write_text(text.replace("TAIL_MARK = 7", "TAIL_MARK = 8"), encoding="utf-8")
            edited = check(ems, out, out)
            path.unlink()
            missing = check(ems, out, out)
            for what, got_p in (("hand-edited", edited), ("missing", missing)):
                if len(got_p) != 1 or f"{MODULE}.py" not in got_p[0]:
                    bad.append(f"files.check on a {what} file: {got_p} (want one line naming it)")
    finally:
        TEMPLATES.pop(MODULE, None)
        if saved is not None:
            TEMPLATES[MODULE] = saved
    if bad:
        return failed("symbt.emit (plain) -> render / files.check vs values written out", detail="; ".join(bad))
    return Outcome("verified", "exact: sources, rendered values and file checks vs values written out by hand",
                   evidence="proof", n_scope="all",
                   detail=f"sources of 3 shapes; template head and tail; mat and mat_mp at {len(XY)} dyadic points "
                          "exact; files.check: 0 / 1 / 1 lines (fresh, edited, missing)")


@claim("library.emit_c_sign", equation="checker", scene="library", deep=True,
       where="symbt.codegen.user.render.c_source (a plain C module calling sgn)",
       statement="a plain C module whose function calls sgn compiles with the system C compiler and computes "
                 "sign(x) y at both signs of x (skipped without a C compiler)")
def emit_c_sign() -> Outcome:
    from ..codegen.user.check import compiler, load_c
    from ..codegen.user.declare import emit
    from ..codegen.user.files import generate
    from ..codegen.user.render import c_name

    if compiler() is None:
        return skipped("no C compiler (cc, gcc or clang) on PATH")
    x, y = sp.symbols("x y", real=True)
    cs = emit("sgn_times", sp.sign(x) * y, args=(x, y), module=C_MODULE, register=False)
    bad: list[str] = []
    keep: list[Any] = []
    try:
        with tempfile.TemporaryDirectory(prefix="symbt-emit3-c-") as tmp:
            out = Path(tmp)
            generate([cs], out, out, target="c")
            try:
                fn = getattr(load_c(out / f"{C_MODULE}.c", keep), c_name(C_MODULE, cs))
            except RuntimeError as exc:     # load_c: it does not compile
                return failed("the system C compiler", detail=f"the C module calling sgn: {str(exc)[:300]}")
            fn.restype = ctypes.c_int
            fn.argtypes = [ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)]
            for xv, yv in XY:
                res = (ctypes.c_double * 1)()
                code = fn((ctypes.c_double * 2)(xv, yv), res)
                if code != 0 or res[0] != (1.0 if xv > 0 else -1.0) * yv:
                    bad.append(f"C sgn_times({xv}, {yv}) = {res[0]!r} (status {code})")
    finally:
        for t in keep:
            t.cleanup()
    if bad:
        return failed("the system C compiler; values written out by hand", detail="; ".join(bad))
    return Outcome("verified", "the system C compiler; values written out by hand", evidence="proof",
                   n_scope="all", detail=f"compiled; sign(x) y exact at {len(XY)} points")


def _exact(e: sp.Expr, env: dict[sp.Symbol, Fraction]) -> Fraction:
    """``e`` with every ``Quotient(a, b)`` read as ``a/b``, at rational inputs, exactly (SymPy rationals)."""
    from ..codegen.printer import Quotient

    plain = e.replace(lambda t: isinstance(t, Quotient), lambda t: t.args[0] / t.args[1])
    v = plain.xreplace({s: sp.Rational(f.numerator, f.denominator) for s, f in env.items()})
    return Fraction(int(sp.numer(v)), int(sp.denom(v)))


@claim("library.printer_precedence", equation="checker", scene="library",
       where="symbt.codegen.printer.ExprPrinter (parentheses: numpy, mpmath and C flavours)",
       statement="the printed text of a quotient by a product or by a quotient, a negated product with a quotient "
                 "and a power of a sum evaluates (Python, dyadic inputs, every operation exact) to the expression's "
                 "exact value in the numpy, mpmath and C flavours")
def printer_precedence() -> Outcome:
    from ..codegen.printer import ExprPrinter, Quotient

    x, y, z = sp.symbols("x y z", real=True)
    # at both points every intermediate value is dyadic with a few bits: each operation is exact in float64
    exprs = [Quotient(x, y * z), Quotient(x, Quotient(y, z)), Quotient(x - y, y * z), -(x * Quotient(y, z)),
             (x + y) ** 3 * z, x - Quotient(y - z, y * z)]
    names = {x: "x", y: "y", z: "z"}
    points = ({x: Fraction(3), y: Fraction(1, 2), z: Fraction(4)},
              {x: Fraction(-5, 4), y: Fraction(2), z: Fraction(-1, 2)})
    bad, n = [], 0
    for flavour in ("numpy", "mpmath", "c"):
        pr = ExprPrinter(flavour, names)
        for e in exprs:
            text = pr.text(e)
            for env in points:
                want = _exact(e, env)
                if flavour == "mpmath":
                    ns: dict[str, Any] = {"mpmath": mp, "_div": lambda a, b: a / b, "_Q": lambda p, q: mp.mpf(p) / q}
                    vals = {str(s): mp.mpf(f.numerator) / f.denominator for s, f in env.items()}
                else:
                    ns = {"np": np}
                    vals = {str(s): float(f) for s, f in env.items()}
                with mp.workdps(30):
                    got = eval(text, ns, vals)     # noqa: S307 -- the printer's own text of fixed expressions
                    ok = mp.mpf(got) == mp.mpf(want.numerator) / want.denominator
                n += 1
                if not ok:
                    bad.append(f"{flavour}: {text} = {got} at {dict((str(k), str(v)) for k, v in env.items())}, "
                               f"exactly {want}")
    if bad:
        return failed("exact: printed text evaluated by Python vs exact rationals", detail="; ".join(bad[:6]))
    return Outcome("verified", "exact: printed text evaluated by Python at dyadic inputs vs the exact rational value",
                   evidence="proof", n_scope="all",
                   detail=f"{len(exprs)} expressions x 3 flavours x {len(points)} points = {n} evaluations, all exact")


CANCEL = '''

_emitted_root_mp = root_mp


def root_mp(v):
    """The emitted flavour with 12 digits lost to a cancellation."""
    r = _emitted_root_mp(v)
    return (r + mpmath.mpf(10) ** 12) - mpmath.mpf(10) ** 12
'''


@claim("library.compare_refusal", equation="checker", scene="library",
       where="symbt.codegen.user.check.compare (typed: refused points, the mpmath flavour's precision)",
       statement="compare on a typed sqrt guarded by x: the cell x < 0, refused on both sides, has worst residual "
                 "exactly 0 and the cell x > 0 at most 1/16; an mpmath flavour losing 12 digits is rejected, the "
                 "emitted one accepted")
def compare_refusal() -> Outcome:
    from ..codegen.user.check import Comparison, compare
    from ..codegen.user.declare import emit
    from ..codegen.user.files import generate
    from ..codegen.user.typed import Guard
    from ..proof import Domain

    x = sp.Symbol("x", real=True)
    e = emit("root", {"r": sp.Piecewise((sp.sqrt(x), x > 0), (0, True))}, args=(("v", (x,)),), module=TYPED,
             guards=[Guard("domain", "x", x)], domain=Domain({"x": (-2, 2)}, seed=31), register=False)
    bad: list[str] = []
    rows: dict[str, tuple[int, float]] = {}
    with tempfile.TemporaryDirectory(prefix="symbt-emit3-typed-") as tmp:
        out = Path(tmp)
        generate([e], out, out)
        path = out / f"{TYPED}.py"
        for flavour in ("numpy", "mpmath"):
            seen = Comparison()
            table = compare(e, path, flavour, per_cell=3, seen=seen)
            for r in table.rows.values():
                rows[f"{flavour} {'/'.join(str(v) for v in r.cell.values())}"] = (r.n, r.printed_worst)
            refused = [r for r in table.rows.values() if "x<0" in r.cell.values()]
            compared = [r for r in table.rows.values() if "x>0" in r.cell.values()]
            if len(refused) != 1 or len(compared) != 1 or not refused[0].n or not compared[0].n:
                bad.append(f"{flavour}: cells {[r.cell for r in table.rows.values()]} (want x<0 and x>0 sampled)")
                continue
            if seen.refused != refused[0].n or seen.compared != compared[0].n:
                bad.append(f"{flavour}: {seen.refused} refused, {seen.compared} compared; the cells hold "
                           f"{refused[0].n} (x<0) and {compared[0].n} (x>0)")
            if refused[0].printed_worst != 0:
                bad.append(f"{flavour}: worst residual {refused[0].printed_worst!r} in the refused cell x < 0 (want 0)")
            if not compared[0].printed_worst <= 1 / 16:
                bad.append(f"{flavour}: worst residual {compared[0].printed_worst:.3g} in x > 0 (bound 1/16)")
        lossy = out / "lossy.py"
        lossy.write_text(path.read_text(encoding="utf-8") + CANCEL, encoding="utf-8")
        table = compare(e, lossy, "mpmath", per_cell=3)
        worst = table.worst()[0]
        if table.printed_holds_everywhere():
            bad.append(f"an mpmath flavour losing 12 digits is accepted: worst residual {worst:.3g}")
        rows["mpmath, 12 digits lost"] = (sum(r.n for r in table.rows.values()), worst)
    detail = "; ".join(f"{k}: {n} points, worst {w:.3g}" for k, (n, w) in rows.items())
    if bad:
        return failed("symbt.codegen.user.check.compare on a guarded sqrt", detail="; ".join(bad) + "; " + detail)
    return Outcome("verified", "numeric: compare's table on a guarded sqrt (refused cell exactly 0, sqrt within "
                               "half an ulp) and on an mpmath flavour losing 12 digits", evidence="sampled",
                   n_scope="all", detail=detail)


@claim("library.sources_real", equation="checker", scene="library", N=2,
       where="symbt.codegen.derive.sources (its symbols' assumptions)",
       statement="every symbol of sources(2) -- arguments, named definitions, outputs, guards -- is real "
                 "(conjugate(s) == s) and no two distinct symbols share a name")
def sources_real() -> Outcome:
    from ..codegen import derive

    specs = derive.sources(2)
    syms: set[sp.Symbol] = set()
    def symbols(v: Any) -> set[Any]:
        if isinstance(v, derive.RingValue):     # a ring polynomial: its generators' symbols
            return set(v.ring.m.p) | set(v.ring.m.q) | set(v.ring.c) | symbols(v.lam) if v.lam is not None else \
                set(v.ring.m.p) | set(v.ring.m.q) | set(v.ring.c)
        return set(sp.sympify(v).free_symbols)

    for s in specs:
        syms |= {v for a in s.args for v in a.symbols}
        for target, value in s.defs:
            syms |= {target} | symbols(value)
        for o in s.outputs:
            for v in o.exprs:
                syms |= symbols(v)
        for g in s.guards:
            syms |= symbols(g.expr)
    syms = {v for v in syms if isinstance(v, sp.Symbol)}
    not_real = sorted(str(v) for v in syms if sp.conjugate(v) != v)
    by_name: dict[str, set[sp.Symbol]] = {}
    for v in syms:
        by_name.setdefault(v.name, set()).add(v)
    twins = sorted(name for name, vs in by_name.items() if len(vs) > 1)
    if not_real or twins:
        return failed("exact: SymPy assumptions of every symbol of sources(2)",
                      detail=f"not real: {not_real[:8]}; names shared by distinct symbols: {twins[:8]}")
    return Outcome("verified", "exact: SymPy assumptions of every symbol of sources(2)", evidence="proof",
                   n_scope=[2], detail=f"{len(syms)} symbols of {len(specs)} functions, all real, names unique")


@claim("library.signatures", equation="checker", scene="library", N=2,
       where="symbt.codegen.pymodule.signature vs the shipped symbt.generated.toda2",
       statement="pymodule.signature of every function of toda2's interface (numpy and mpmath flavours) is the "
                 "parameter list of the shipped function: guarded numpy flavours end in errors=\"raise\"")
def signatures() -> Outcome:
    from ..codegen.derive import interface
    from ..codegen.pymodule import signature
    from ..generated import toda2

    bad, guarded = [], 0
    for name, spec in interface(2).items():
        guarded += bool(spec.guards)
        for flavour, fname in (("numpy", name), ("mpmath", name + "_mp")):
            ps = inspect.signature(getattr(toda2, fname)).parameters.values()
            want = ", ".join(p.name if p.default is inspect.Parameter.empty else f'{p.name}="{p.default}"'
                             for p in ps)
            got = signature(spec, flavour)
            if got != want:
                bad.append(f"{fname}: signature {got!r}, shipped ({want})")
    if bad or not guarded:
        return failed("inspect: the shipped toda2's parameters", detail="; ".join(bad) or "no guarded function")
    return Outcome("verified", "inspect: the shipped toda2's parameters", evidence="proof", n_scope=[2],
                   detail=f"{len(interface(2))} functions x 2 flavours ({guarded} guarded) match")


#: (argv, out) -> the re-run's argv, written out by hand
RERUN = (
    (["--n", "3", "--project", "/p", "--check"], None, ["--n", "3", "--check"]),
    (["--out=rel", "--target", "c", "--project=/p", "-q"], Path("/abs/out"),
     ["--target", "c", "-q", "--out", "/abs/out"]),
    (["--out", "rel", "--n", "2", "5"], Path("/abs/o"), ["--n", "2", "5", "--out", "/abs/o"]),
)


@claim("library.codegen_rerun_argv", equation="checker", scene="library",
       where="symbt codegen re-running itself in a checkout (symbt.codegen.cli)",
       statement="the re-run's arguments drop --project and --out (both spellings), keep every other argument in "
                 "order and re-add --out absolute")
def codegen_rerun_argv() -> Outcome:
    from ..codegen.cli import _delegate_argv

    bad = [f"{argv} -> {got}, want {want}" for argv, out, want in RERUN
           if (got := _delegate_argv(list(argv), out)) != want]
    if bad:
        return failed("exact: argument lists written out by hand", detail="; ".join(bad))
    return Outcome("verified", "exact: argument lists written out by hand", evidence="proof", n_scope="all",
                   detail=f"{len(RERUN)} argument lists")
