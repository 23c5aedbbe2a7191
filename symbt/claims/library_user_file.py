r"""The user code-generation path observed function by function: the printer, provenance, typed shapes, loops.

Scene ``library`` (issue 21, item 4: fresh samples of ``symbt mutate --source codegen.user``, docs/mutation.md).
Each claim checks a documented property of :mod:`symbt.codegen.user` against a route that shares nothing with it
-- mpmath at 30 digits, SymPy's own rewriting, values written out by hand on dyadic inputs -- or an exact fact:

* ``library.user_printer`` -- :class:`~symbt.codegen.user.printing.UserPrinter` (numpy and mpmath flavours) over its
  whole vocabulary -- negative floats, ``pi``/``E``, the eleven trigonometric and hyperbolic functions, ``expm1``,
  ``atan2``, ``Min``/``Max`` of three arguments, ``And``/``Or``/``Not``/``Eq``/``Ne`` conditions of a ``Piecewise``
  (every piece taken at some point), ``true``/``false``, roots, negative and symbolic powers and a sum of 105 terms
  (printed in balanced chunks of :data:`~symbt.codegen.user.printing.LONG_SUM`): the printed text evaluated by
  Python at three points equals the expression's value (SymPy ``evalf`` at 30 digits) within ``1e-13`` relative
  (float64: a few correctly rounded operations on well-conditioned arguments) and ``1e-25`` (mpmath at 30 digits),
  and the C flavour's text of each has no ``**`` (C has no power operator) and names neither numpy nor mpmath;
  :func:`~symbt.codegen.user.printing.rewritten` equals SymPy's ``optimize(x, [expm1_opt, log1p_opt])`` on small
  expressions (structurally); :func:`~symbt.codegen.user.printing.optimized` leaves a declaration with
  ``optimize=False`` as declared.
* ``library.user_provenance`` -- :func:`~symbt.codegen.user.files.derivation_sources` of a module declared in a
  throw-away project (a package with relative imports of level 1 and 2, an ``import``, a module no one imports, an
  excluded folder) is the list of files written out by hand; :func:`~symbt.codegen.user.files.derivation_hash`
  names each file by its path under the project root (the same bytes elsewhere give another hash) and changes with
  one byte; ``files.check`` reports the emitted module stale after an edit of a module its declaration imports
  indirectly, and nothing after an edit of a module it does not import.
* ``library.user_typed_shapes`` -- typed declarations with a scalar, a vector and a 2 x 3 matrix output, and two
  :class:`~symbt.codegen.user.Loop` declarations (one output, two outputs): ``Emission.shape`` as documented (one
  output: its shape, several: their number), and the rendered numpy and mpmath flavours equal the values written out
  by hand at dyadic inputs, exactly; ``errors="mask"`` masks exactly the batch element whose guard fails;
  :func:`~symbt.codegen.user.check.compare` on it (``x`` drawn on both sides of the guard) holds, and its
  :class:`~symbt.codegen.user.check.Comparison` counts every refusal once under its condition; the C header of a
  module with a typed and a plain declaration is one header holding both prototypes inside its include guard.

>>> user_printer.run().status
'verified'
"""
from __future__ import annotations

import math
import sys
import tempfile
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np
import sympy as sp

from .base import Outcome, claim, failed

x, y, z = sp.symbols("x y z", real=True)
#: (x, y, z): every function below is defined and well conditioned there (|x| < 1 for asin, atanh; z > 0); each
#: takes another piece of the Piecewise (the last one: x = 3 y, z < 2)
POINTS = ((0.375, 1.25, 2.5), (-0.625, 0.75, 1.5), (0.125, -2.5, 3.25), (-0.75, -0.25, 1.75))


def vocabulary() -> list[sp.Expr]:
    """One expression per construct :class:`~symbt.codegen.user.printing.UserPrinter` prints itself."""
    trig = [f(x) for f in (sp.sin, sp.cos, sp.tan, sp.asin, sp.acos, sp.atan, sp.sinh, sp.cosh, sp.tanh, sp.asinh,
                           sp.atanh)]
    from sympy.codegen.cfunctions import expm1

    return trig + [
        sp.Float("-0.375") * x + sp.pi * y - sp.E, expm1(x) * y, sp.atan2(y, x), sp.Min(x, y, z), sp.Max(x, y, z),
        sp.Piecewise((x, sp.And(x > 0, y > 0)), (y, sp.Or(sp.Eq(x, y), sp.Not(z < 2))), (z, sp.Ne(x, 3 * y)),
                     (1, True)),
        z ** sp.Rational(1, 3), z ** sp.Rational(-2, 3), z ** y, 1 / (x * y),
        sp.Pow(sp.Float("-1.5"), 2, evaluate=False),              # a negative number as a base: in parentheses
        LONG,
    ]


#: a sum of 105 distinct terms (printed in chunks); its value summed by hand
LONG = sp.Add(*[x ** k / k for k in range(1, 106)])


def _want(e: sp.Expr, pt: tuple[float, float, float]) -> Any:
    if e is LONG:
        return mp.fsum(mp.mpf(pt[0]) ** k / k for k in range(1, 106))
    return mp.mpf(e.xreplace(dict(zip((x, y, z), (sp.Float(v, 30) for v in pt)))).evalf(30))


def _python_value(text: str, flavour: str, pt: tuple[float, float, float]) -> Any:
    # each flavour's own namespace only: the numpy text is float64 code (no mpmath), the mpmath text needs no numpy
    ns: dict[str, Any] = {"np": np} if flavour == "numpy" else {"mpmath": mp, "_Q": lambda p, q: mp.mpf(p) / q}
    vals = dict(zip("xyz", (mp.mpf(v) for v in pt) if flavour == "mpmath" else pt))
    return eval(text, ns, vals)    # noqa: S307 -- the printer's own text of fixed expressions


def _longest_chain(text: str) -> int:
    """The deepest left-nested chain of additions in the Python text, in terms (``a + b + c``: three;
    ``(a + b) + (c + d)``: three too -- the parentheses of a left operand add no depth)."""
    import ast

    def terms(node: ast.AST) -> int:         # a left-nested Add chain, not crossing parentheses of sub-sums
        return terms(node.left) + 1 if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add) else 1
    tree = ast.parse(text, mode="eval")
    return max((terms(n) for n in ast.walk(tree) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Add)),
               default=1)


@claim("library.user_printer", equation="checker", scene="library",
       where="symbt.codegen.user.printing (UserPrinter, rewritten, optimized)",
       statement="the numpy and mpmath texts of UserPrinter over its vocabulary evaluate to the expressions' values "
                 "(evalf, 30 digits) within 1e-13 / 1e-25 relative (the C text has no ** and names neither numpy "
                 "nor mpmath), a sum of 105 terms nested at most LONG_SUM + 1 "
                 "deep (two balanced partial sums); rewritten equals SymPy's optimize with the "
                 "expm1 and log1p rules; optimized keeps a declaration with optimize=False as declared")
def user_printer() -> Outcome:
    from sympy.codegen.cfunctions import expm1, log1p
    from sympy.codegen.rewriting import expm1_opt, log1p_opt, optimize

    from ..codegen.user.declare import emit
    from ..codegen.user.printing import LONG_SUM, UserPrinter, optimized, rewritten

    bad: list[str] = []
    worst = {"numpy": 0.0, "mpmath": mp.mpf(0)}
    taken: set[int] = set()
    names = {x: "x", y: "y", z: "z"}
    exprs = vocabulary()
    with mp.workdps(30):
        wants = [[_want(e, pt) for pt in POINTS] for e in exprs]
    for flavour, tol in (("numpy", 1e-13), ("mpmath", mp.mpf(10) ** -25)):
        pr = UserPrinter(flavour, names)
        for b in (sp.true, sp.false):
            if _python_value(pr.text(b), flavour, POINTS[0]) is not bool(b):
                bad.append(f"{flavour}: {b} printed {pr.text(b)!r}")
        for e, ws in zip(exprs, wants):
            text = pr.text(e)
            c_text = UserPrinter("c", names).text(e)
            if flavour == "numpy" and ("**" in c_text or "np." in c_text or "mpmath." in c_text):
                bad.append(f"c: {e} printed {c_text[:60]!r} (C has no ** operator, no numpy or mpmath)")
            # partial sums of at most LONG_SUM terms, combined as a balanced tree: the compiler's nesting depth is
            # at most LONG_SUM + ceil(log2(number of partial sums)) (a plain chain: the number of terms)
            depth = LONG_SUM + math.ceil(math.log2(math.ceil(len(LONG.args) / LONG_SUM)))
            if e is LONG and not _longest_chain(text) <= depth:
                bad.append(f"{flavour}: the {len(LONG.args)}-term sum printed nested {_longest_chain(text)} deep "
                           f"(balanced partial sums of LONG_SUM = {LONG_SUM} terms: at most {depth})")
            for pt, want in zip(POINTS, ws):
                if isinstance(e, sp.Piecewise):
                    taken.add(next(k for k, (_, c) in enumerate(e.args)
                                   if c.subs(dict(zip((x, y, z), pt))) is sp.true))
                with mp.workdps(30):
                    try:
                        got = _python_value(text, flavour, pt)
                    except Exception as exc:    # noqa: BLE001 -- any failure of the printed text is the finding
                        bad.append(f"{flavour}: {text[:60]} raises {type(exc).__name__}")
                        continue
                    r = abs(mp.mpf(float(got) if flavour == "numpy" else got) - want) / max(1, abs(want))
                worst[flavour] = max(worst[flavour], r)
                if not r <= tol:
                    bad.append(f"{flavour}: {text[:60]} = {got} at {pt}, evalf {want}")
    if taken != {0, 1, 2, 3}:
        bad.append(f"the Piecewise's pieces taken at the points: {sorted(taken)} (want all four)")
    rules = [sp.exp(x) - 1, sp.log(1 + x), sp.exp(2 * x) - sp.exp(x), sp.log(x + 1) + sp.exp(x) - 1, x ** 2 - 1,
             sp.exp(x) + 1, 3 * sp.exp(y) - 3 + x]
    for e in rules:
        if rewritten(e) != optimize(e, [expm1_opt, log1p_opt]):
            bad.append(f"rewritten({e}) = {rewritten(e)}, SymPy's optimize {optimize(e, [expm1_opt, log1p_opt])}")
    plain = [sp.exp(x) - 1, sp.log(1 + x)]
    for opt in (False, True):
        got = optimized(emit("opt_probe", plain, args=(x,), module="symbt_user_probe", optimize=opt, register=False))
        want = plain if not opt else [expm1(x), log1p(x)]
        if got != want:
            bad.append(f"optimized(optimize={opt}) = {got}, want {want}")
    detail = (f"{len(vocabulary())} expressions + true/false x 2 flavours x {len(POINTS)} points; worst relative "
              f"numpy {float(worst['numpy']):.2g}, mpmath {mp.nstr(worst['mpmath'], 2)}; {len(rules)} rewritings as "
              "SymPy's")
    if bad:
        return failed("printed text evaluated by Python vs evalf at 30 digits; SymPy's optimize",
                      detail="; ".join(bad[:6]) + "; " + detail)
    return Outcome("verified", "printed text evaluated by Python vs evalf at 30 digits; SymPy's optimize",
                   evidence="sampled", n_scope="all", detail=detail)


#: the throw-away project: file -> text (``PKG`` is replaced by the package's name)
PROJECT = {
    "PKG/__init__.py": "",
    "PKG/decl.py": "import json\nimport sympy as sp\nfrom symbt import emit\nfrom . import util\n"
                   "from .sub import leaf\nx = sp.Symbol('x', real=True)\n"
                   "E = emit('twice', 2 * x, args=(x,), module='PKG_out', register=False)\n"
                   "def later():\n    from . import lazy\n    return lazy.z\n",     # imported only when called
    "PKG/lazy.py": "z = 1\n",
    "PKG/util.py": "from .helper import h\n",
    "PKG/helper.py": "h = 1\n",
    "PKG/unused.py": "u = 1\n",
    "PKG/sub/__init__.py": "",
    "PKG/sub/leaf.py": "from ..deep import d\n",
    "PKG/deep.py": "d = 1\n",
    "PKG/gen/__init__.py": "",
}
#: what derivation_sources must list for PKG.decl (a static scan of the imports, under the root)
SOURCES = ["PKG/__init__.py", "PKG/decl.py", "PKG/deep.py", "PKG/helper.py", "PKG/lazy.py", "PKG/sub/__init__.py",
           "PKG/sub/leaf.py", "PKG/util.py"]


@claim("library.user_provenance", equation="checker", scene="library",
       where="symbt.codegen.user.files (derivation_sources, derivation_hash, check)",
       statement="derivation_sources of a module declared in a project lists exactly the project's files it imports, "
                 "directly or not (relative imports of level 1 and 2; a module imported inside a function, not yet "
                 "loaded, found by its spec), none excluded; the derivation hash names files "
                 "by their path under the root and changes with one byte; files.check reports the emitted module stale "
                 "after an edit of an indirectly imported module and not after an edit of a module nobody imports")
def user_provenance() -> Outcome:
    import importlib

    from ..codegen.user.files import check, derivation_hash, derivation_sources, generate

    pkg = "symbt_provenance_probe"
    bad: list[str] = []
    with tempfile.TemporaryDirectory(prefix="symbt-provenance-") as tmp:
        root = Path(tmp).resolve()
        for name, text in PROJECT.items():
            path = root / name.replace("PKG", pkg)
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text.replace("PKG", pkg), encoding="utf-8")
        sys.path.insert(0, str(root))
        try:
            decl = importlib.import_module(f"{pkg}.decl")
            got = [f.relative_to(root).as_posix() for f in derivation_sources([f"{pkg}.decl"], root)]
            want = [s.replace("PKG", pkg) for s in SOURCES]
            if got != want:
                bad.append(f"derivation_sources = {got}, by hand {want}")
            cut = [f.relative_to(root).as_posix()
                   for f in derivation_sources([f"{pkg}.decl"], root, root / pkg / "sub")]
            if cut != [w for w in want if "/sub/" not in w and "deep" not in w]:    # deep.py: only via sub/leaf.py
                bad.append(f"derivation_sources excluding sub/ = {cut}")
            one = root / pkg / "deep.py"
            same = root / pkg / "gen" / "deep.py"
            same.write_bytes(one.read_bytes())
            h = derivation_hash([one], root)
            if derivation_hash([one], root) != h or derivation_hash([same], root) == h:
                bad.append("derivation_hash: not a function of the files' paths under the root and their bytes")
            out = root / "out"
            out.mkdir()
            generate([decl.E], root, out)
            fresh = check([decl.E], root, out)
            (root / pkg / "unused.py").write_text("u = 2\n", encoding="utf-8")
            untouched = check([decl.E], root, out)
            one.write_text("d = 2\n", encoding="utf-8")
            stale = check([decl.E], root, out)
            if fresh or untouched:
                bad.append(f"files.check after generate: {fresh}; after editing a module nobody imports: {untouched}")
            if len(stale) != 1 or f"{pkg}_out.py" not in stale[0]:
                bad.append(f"files.check after editing {pkg}/deep.py (imported via sub/leaf.py): {stale}")
        finally:
            sys.path.remove(str(root))
            for m in [m for m in sys.modules if m == pkg or m.startswith(pkg + ".")]:
                del sys.modules[m]
    if bad:
        return failed("exact: file lists and file checks written out by hand", detail="; ".join(bad))
    return Outcome("verified", "exact: file lists and file checks written out by hand", evidence="proof",
                   n_scope="all", detail=f"{len(SOURCES)} derivation sources of 9 files; the hash moves with a path "
                                         "and a byte; check: fresh, unrelated edit, indirect edit -> 0 / 0 / 1 lines")


def _typed_probe() -> tuple[list[Any], Any]:
    """A typed declaration with a scalar, a vector and a 2 x 3 matrix output (guard ``x > 0``), two loops."""
    from ..codegen.user import Guard, Loop, emit
    from ..proof import Domain

    b = sp.Symbol("b", real=True)
    M = sp.Matrix([[x, y, x * y], [x + y, 2 * x, x - 3 * y]])
    mod = "symbt_user_shapes"
    shapes = emit("shapes", {"s": b * x * y, "v": [x, y, x + y], "M": M}, args=(("v", (x, y)), ("b", b, "sign")),
                  module=mod, guards=[Guard("domain", "x", x)], domain=Domain({"v": (-1, 2)}, seed=5),
                  register=False)
    one = emit("one", {"M": M}, args=(("v", (x, y)),), module=mod, register=False)
    np_body = "a = v[..., 0]\nc = v[..., 1]"
    loop1 = emit("loop1", Loop(outputs=(("r", (3,)),), numpy=np_body, items=(("r", "[a * c, a + c, c - a]"),),
                               mpmath="r = [v[0] * v[1], v[0] + v[1], v[1] - v[0]]"),
                 args=(("v", (x, y)),), module=mod, register=False)
    loop2 = emit("loop2", Loop(outputs=(("r", (3,)), ("t", ())), numpy=np_body,
                               items=(("r", "[a * c, a + c, c - a]"), ("t", "[2 * a]")),
                               mpmath="r = [v[0] * v[1], v[0] + v[1], v[1] - v[0]]\nt = 2 * v[0]"),
                 args=(("v", (x, y)),), module=mod, register=False)
    return [shapes, one, loop1, loop2], M


def _hand(xv: float, yv: float, bv: int) -> tuple[float, list[float], list[list[float]]]:
    return bv * xv * yv, [xv, yv, xv + yv], [[xv, yv, xv * yv], [xv + yv, 2 * xv, xv - 3 * yv]]


@claim("library.user_typed_shapes", equation="checker", scene="library",
       where="symbt.codegen.user (typed outputs of every shape, Loop bodies: declare, render_typed)",
       statement="a typed declaration's scalar, vector and 2 x 3 matrix outputs and a Loop's outputs, rendered as "
                 "numpy and mpmath, equal the values written out by hand at dyadic inputs; errors='mask' masks exactly "
                 "the element whose guard fails; a one-output declaration's shape is its output's shape")
def user_typed_shapes() -> Outcome:
    from ..codegen.user.check import Comparison, compare, load_python
    from ..codegen.user.files import generate

    ems, M = _typed_probe()
    shapes, one, loop1, loop2 = ems
    bad: list[str] = []
    if one.shape != (2, 3) or loop1.shape != (3,) or shapes.source.shape != (10, 1):
        bad.append(f"shapes: one output {one.shape}, one-output loop {loop1.shape}, three outputs' source "
                   f"{shapes.source.shape} (want (2, 3), (3,), (10, 1))")
    pts = ((1.5, -0.25, 1), (0.75, 2.5, -1))
    with tempfile.TemporaryDirectory(prefix="symbt-user-shapes-") as tmp:
        out = Path(tmp)
        generate(ems, out, out)
        mod = load_python(out / "symbt_user_shapes.py")
        for xv, yv, bv in pts:
            s, v, m = _hand(xv, yv, bv)
            got = mod.shapes([xv, yv], bv)
            gm = mod.shapes_mp([xv, yv], bv)
            for flavour, (gs, gv, gmat) in (("numpy", got), ("mpmath", gm)):
                vals = (float(gs), [float(t) for t in gv], [[float(t) for t in row] for row in gmat])
                if vals != (s, v, m):
                    bad.append(f"shapes ({flavour}) at {(xv, yv, bv)}: {vals}, by hand {(s, v, m)}")
            r = [xv * yv, xv + yv, yv - xv]
            for name, res in (("loop1", [mod.loop1([xv, yv])]), ("loop1_mp", [mod.loop1_mp([xv, yv])]),
                              ("loop2", list(mod.loop2([xv, yv]))), ("loop2_mp", list(mod.loop2_mp([xv, yv])))):
                flat = [float(t) for t in res[0]] + [float(t) for t in res[1:]]
                want = r + ([2 * xv] if name.startswith("loop2") else [])
                if flat != want:
                    bad.append(f"{name} at {(xv, yv)}: {flat}, by hand {want}")
            gone = [[float(t) for t in row] for row in mod.one([xv, yv])], mod.one_mp([xv, yv])
            if gone[0] != m or [[float(t) for t in row] for row in gone[1]] != m:
                bad.append(f"one at {(xv, yv)}: {gone}, by hand {m}")
        masked = mod.shapes(np.array([[1.5, -0.25], [-0.5, 2.0]]), np.array([1, -1]), errors="mask")
        mask = [np.ma.getmaskarray(o).reshape(2, -1).all(axis=1).tolist() for o in masked]
        s0, v0, m0 = _hand(1.5, -0.25, 1)
        if mask != [[False, True]] * 3 or float(masked[0][0]) != s0 or masked[2][0].tolist() != m0:
            bad.append(f"errors='mask' at x = (1.5, -0.5): masks {mask} (want element 1 only), values "
                       f"{masked[0][0]}, {masked[2][0]}")
        from ..codegen.user import emit
        from ..codegen.user.render import c_header

        plain = emit("plainf", x * y, args=(x, y), module="symbt_user_shapes", register=False)
        h = c_header("symbt_user_shapes", [shapes, plain])
        guard = "SYMBT_EMITTED_SYMBT_USER_SHAPES_H"
        if h.count(f"#ifndef {guard}") != 1 or not h.rstrip().endswith(f"#endif /* {guard} */") \
                or "int symbt_user_shapes_plainf(const double *in, double *out);" not in h \
                or "int symbt_user_shapes_shapes(" not in h:
            bad.append("the C header of a module with a typed and a plain declaration is not one header with both "
                       "prototypes inside its include guard")
        seen = Comparison()
        table = compare(shapes, out / "symbt_user_shapes.py", "numpy", per_cell=3, seen=seen)
        if not table.printed_holds_everywhere() or not seen.refused or not seen.compared \
                or seen.conditions != {"domain": seen.refused}:
            bad.append(f"compare: holds {table.printed_holds_everywhere()}, {seen.refused} refused, {seen.compared} "
                       f"compared, refusals by condition {seen.conditions} (want every refusal counted once, 'domain')")
    if bad:
        return failed("exact: values written out by hand at dyadic inputs", detail="; ".join(bad[:6]))
    return Outcome("verified", "exact: values written out by hand at dyadic inputs; compare's sampled table",
                   evidence="sampled", n_scope="all",
                   detail=f"scalar, vector, 2 x 3 matrix and loop outputs, numpy and mpmath, at {len(pts)} points; "
                          f"the mask of a failing guard; shapes of one-output declarations; compare: {seen.refused} "
                          f"refused, {seen.compared} compared, refusals by condition {seen.conditions}")
