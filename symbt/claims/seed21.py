r"""What the samples of seeds 20 and 21 found unread (issue 21).

* ``library.fresh_toda2`` -- the shipped ``symbt/generated/toda2.py`` below its provenance header is the text
  ``symbt codegen --installed --n 2 --out DIR`` writes now (into a throw-away directory, in this process), and the
  command names the two files it wrote (seed 25: its report under ``--quiet`` negated, which no claim had run).  A
  consistency check (the file against a fresh rendering of its own derivation; the body only -- the header's hash
  is ``--check``'s), and the only one in the default run that reads the emitted *text*: ``symbt codegen
  --check`` compares the derivation's hash, the value claims compare numbers, and a changed docstring or a guard
  printed in another form passes both (seed 20: the numpy docstrings' shape words, the error list of ``bt_step``).
  Skipped when the installed SymPy is not the one the header names (another SymPy may print other text).  And
  :func:`~symbt.codegen.forms.form_of` gives the closed form below N = 4 and the transfer-matrix form from N = 4
  on, as docs/codegen.md says (``symbt codegen --n 4`` writes loops).
* ``library.emissions_of`` -- :func:`symbt.codegen.user.declare.emissions_of` (how ``symbt verify`` and ``symbt
  codegen`` find a user project's declarations): declarations registered from modules ``P``, ``P.sub`` and ``Px``
  (throw-away names, removed afterwards) -- ``emissions_of(["P"])`` is the first two in order, ``["P.sub"]`` the
  second, ``["Px"]`` the third, ``["P.su"]`` none.
* ``paths.field_ivp.n3`` -- :class:`symbt.numeric.FlowField` handed to ``scipy.integrate.solve_ivp`` (its
  :meth:`~symbt.numeric.FlowField.rhs`, DOP853) over ``t in [0, 1]`` from the paper's state at both branches:
  Theorem 2 as a user of the field meets it.  The flow at ``rtol = 1e-12`` lands on the literal map (50 digits)
  within a tenth of its distance to the flow at ``rtol = 1e-9`` (plus 16 u of the state's size), and the looser
  flow's error is that distance within a factor 2 -- the integrations converge, and to the map, not to something
  near it.  ``FlowField.nfev`` counts the calls scipy reports (seed 21: the counter could stand still).
* ``checker.undefined_points`` -- :func:`symbt.decide` on a side undefined at half its points (``Piecewise((x,
  x > 0))`` with no piece for ``x <= 0``, SymPy's ``None`` there): ``= x`` holds by the screen at points with
  ``x > 0`` only (an undefined value is no test of the identity, never a crash), and ``= x + 10^-20`` is false
  there (seed 21: a value ``mpmath.isfinite`` cannot read taken as finite crashed the screen).
* ``paths.qd_decompose`` -- the quad-double read-out's ``_decompose`` (numba compiles it for ``from_qd``; here its
  plain-Python source runs): 400 quad-doubles -- random exact components in any order, of both signs, with zeros,
  equal exponents and exponents near ``2**+-600`` -- give integer mantissas below ``2**53`` and shifts
  with ``sum x = ((((m0 << s1) + m1) << s2) + m2 << s3) + m3) 2**e`` exactly (Python's integers and fractions).
* ``paths.inline_globals`` -- :func:`symbt.numeric.core.inline.inlined` with two bodies *of one name* from two
  modules, each reading its own global ``TABLE`` (temporary files): the inlined function gives the plain calls'
  values (``2x + 3x``) and calls neither body (seed 21: renaming every global by its function's name bound both
  tables to one name).

And :func:`positive_traces_enclosed`, a fact of ``paths.jacobian_dual.n3`` (``claims/shipped_sample45.py``): where both
traces are positive the dual-number step computes the map and encloses it (seed 21: a sign test on dual numbers took
two positive traces for opposite ones).
"""
from __future__ import annotations

from fractions import Fraction
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np
import sympy as sp

from ._shipped import without_numba
from .base import Outcome, claim, failed, skipped


def _body(text: str) -> str:
    """``text`` without its leading ``#`` comment lines (the provenance header)."""
    lines = text.splitlines(keepends=True)
    k = 0
    while k < len(lines) and lines[k].startswith("#"):
        k += 1
    return "".join(lines[k:])


@claim("library.fresh_toda2", equation="checker", scene="library", N=2,
       where="symbt/generated/toda2.py vs `symbt codegen --installed --n 2 --out DIR` run now",
       statement="the shipped toda2.py below its provenance header is the text `symbt codegen --installed --n 2 "
                 "--out DIR` writes now, and the command names the two files it wrote (a consistency check of the "
                 "emitted text; skipped under a SymPy other than the header's); form_of is the closed form for N = "
                 "2, 3 and the transfer-matrix form for N = 4, 5, 6")
def fresh_toda2() -> Outcome:
    import contextlib
    import io
    import tempfile

    import sympy

    from .. import generated
    from ..codegen.cli import main as codegen_main
    from ..codegen.provenance import read_header

    method = "exact: the shipped file's text against a fresh rendering (consistency)"
    path = Path(generated.__file__).with_name("toda2.py")
    text = path.read_text(encoding="utf-8")
    made_with = read_header(text).get("sympy")
    if made_with != sympy.__version__:
        return skipped(f"{path.name} was rendered with SymPy {made_with}, this is {sympy.__version__}")
    # the body only: the header's hash of the derivation sources is `symbt codegen --check`'s business
    with tempfile.TemporaryDirectory() as d, contextlib.redirect_stdout(io.StringIO()) as said:
        out = Path(d).resolve()
        status = codegen_main(["--installed", "--n", "2", "--out", str(out)])
        rendered = _body((out / "toda2.py").read_text(encoding="utf-8")) if status == 0 else ""
    wrote = [f"wrote {out / name}" for name in ("__init__.py", "toda2.py")]
    if status != 0 or said.getvalue().splitlines() != wrote:
        return failed(method, detail=f"symbt codegen exit {status}, said {said.getvalue()!r}, want {wrote}")
    body = _body(text)
    shipped, fresh = body.splitlines(), rendered.splitlines()
    if body != rendered:
        k = next((i for i, (a, b) in enumerate(zip(shipped, fresh)) if a != b), min(len(shipped), len(fresh)))
        return failed(method, detail=f"line {k + 1} of the body differs (shipped {len(shipped)} lines, fresh "
                                     f"{len(fresh)}): {shipped[k:k + 1]} vs {fresh[k:k + 1]}")
    from ..codegen.forms import form_of

    forms = [form_of(N) for N in range(2, 7)]
    if forms != ["closed"] * 2 + ["transfer-matrix"] * 3:
        return failed(method, detail=f"form_of(2..6) = {forms}: the closed form is emitted for N < 4 only")
    return Outcome("verified", method, evidence="proof", n_scope=[2],
                   detail=f"{len(fresh)} lines equal (rendered with SymPy {made_with}); form_of(2..6) as documented")


#: library.emissions_of: throw-away module names (a package, its subpackage, a sibling sharing the prefix)
PROBE_MODULES = ("symbt_probe_pkg", "symbt_probe_pkg.sub", "symbt_probe_pkgx")


@claim("library.emissions_of", equation="checker", scene="library",
       where="symbt.codegen.user.declare.emissions_of",
       statement="declarations registered from modules P, P.sub and Px: emissions_of([P]) is the first two in "
                 "order, [P.sub] the second, [Px] the third, [P.su] none (a package means itself and its "
                 "submodules, not a name that merely starts like it)")
def emissions_of() -> Outcome:
    from ..codegen.user import declare

    made = []
    try:
        for k, mod in enumerate(PROBE_MODULES):
            ns = {"__name__": mod, "emit": declare.emit, "sp": sp}
            exec(f"x = sp.Symbol('x', real=True)\n"   # noqa: S102 -- a fixed declaration, not user text
                 f"E = emit('probe{k}', (k + 1) * x, args=(x,), module='symbt_probe_out')\n", {**ns, "k": k}, ns)
            made.append(("symbt_probe_out", f"probe{k}"))
        names = {tuple(q): [e.name for e in declare.emissions_of(q)] for q in
                 (PROBE_MODULES[:1], PROBE_MODULES[1:2], PROBE_MODULES[2:], ("symbt_probe_pkg.su",))}
    finally:
        for key in made:
            declare.EMISSIONS.pop(key, None)
    want = [["probe0", "probe1"], ["probe1"], ["probe2"], []]
    if list(names.values()) != want:
        return failed("exact: declarations written out by hand", detail=f"got {names}, want {want}")
    return Outcome("verified", "exact: declarations written out by hand", evidence="proof", n_scope="all",
                   detail="4 queries over 3 registered declarations")


#: paths.field_ivp: the paper's state and the two tolerances of scipy's integrations
IVP_STATE = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 10.0, 5.0)
IVP_LOOSE, IVP_TIGHT = 1e-9, 1e-12


@claim("paths.field_ivp", equation="eqdisc", source_equation="eqdisc", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/flow/field.py: FlowField.rhs and nfev, as scipy.integrate.solve_ivp calls them",
       statement="FlowField.rhs integrated by scipy's DOP853 over t in [0, 1] from the paper's state (N={N}, "
                 "lam0 = 10, mu = 5, both branches) at rtol = atol = 1e-12 equals the literal map (50 digits) within "
                 "a tenth of its distance to the flow at 1e-9 plus 16 u |x|; the flow at 1e-9 is off by that distance "
                 "within a factor 2; FlowField.nfev = scipy's nfev")
def field_ivp(N: int) -> Outcome:
    try:
        from scipy.integrate import solve_ivp
    except ImportError:
        return skipped("optional dependency missing: scipy")
    from ..numeric import FlowField
    from ..reference.literal import literal_step

    method = "numeric: scipy DOP853 on FlowField.rhs vs the literal map (50 digits)"
    p0, q0, lam0, mu = IVP_STATE
    bad, notes = [], []
    for b in (1, -1):
        with without_numba():   # the existence check of FlowField is bt_step(backend="auto")
            field = FlowField(list(p0), list(q0), lam0, mu, branch=b)
        ends = {}
        for rtol in (IVP_LOOSE, IVP_TIGHT):
            field.nfev = 0
            sol = solve_ivp(field.rhs, (0.0, 1.0), np.array(q0 + p0), method="DOP853", rtol=rtol, atol=rtol)
            if not sol.success or field.nfev != sol.nfev:
                bad.append(f"branch {b}, rtol {rtol:g}: {sol.message}; FlowField.nfev {field.nfev}, scipy {sol.nfev}")
            ends[rtol] = sol.y[:, -1]
        with mp.workdps(50):
            P, Q, _ = literal_step([mp.mpf(v) for v in p0], [mp.mpf(v) for v in q0], mp.mpf(lam0), mp.mpf(mu), b)
            ref = np.array([float(v) for v in list(Q) + list(P)])
        gap = float(np.max(np.abs(ends[IVP_LOOSE] - ends[IVP_TIGHT])))
        err_tight = float(np.max(np.abs(ends[IVP_TIGHT] - ref)))
        err_loose = float(np.max(np.abs(ends[IVP_LOOSE] - ref)))
        floor = 16 * np.finfo(float).eps * float(np.max(np.abs(ref)))
        notes.append(f"branch {b}: error {err_tight:.2g} at {IVP_TIGHT:g}, {err_loose:.2g} at {IVP_LOOSE:g}")
        if not err_tight <= gap / 10 + floor:
            bad.append(f"branch {b}: the flow at {IVP_TIGHT:g} is {err_tight:.3g} from the map, not within a tenth "
                       f"of its distance {gap:.3g} to the flow at {IVP_LOOSE:g}")
        if not gap / 2 <= err_loose <= 2 * gap:
            bad.append(f"branch {b}: the flow at {IVP_LOOSE:g} is {err_loose:.3g} from the map, not within a factor "
                       f"2 of {gap:.3g}")
    if bad:
        return failed(method, detail="; ".join(bad[:3]))
    return Outcome("verified", method, evidence="sampled", n_scope=[N], detail="; ".join(notes))


#: paths.inline_globals: two modules defining ``scaled`` over their own ``TABLE``, and a function calling both
INLINE_PROBES = {
    "m1": "TABLE = (2.0, 0.0)\n\n\ndef scaled(x):\n    y = x * TABLE[0]\n    return y\n",
    "m2": "TABLE = (3.0, 0.0)\n\n\ndef scaled(x):\n    y = x * TABLE[0]\n    return y\n",
    "outer": "def both(x):\n    a = s1(x)\n    b = s2(x)\n    return a + b\n",
}


@claim("paths.inline_globals", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/core/inline.py: inlined's binding of a body's globals (names shared by two modules)",
       statement="inlined with two bodies of one name from two modules, each reading its own global TABLE (2 and "
                 "3), gives the plain calls' values 5 x at x = 1, -0.5, 3 and calls neither body")
def inline_globals() -> Outcome:
    import importlib.util
    import tempfile

    from ..numeric.core.inline import FLOAT64_INLINE, inlined

    with tempfile.TemporaryDirectory(prefix="symbt-inline-") as tmp:
        mods = {}
        for name, text in INLINE_PROBES.items():
            path = Path(tmp) / f"symbt_inline_probe_{name}.py"
            path.write_text(text, encoding="utf-8")
            spec = importlib.util.spec_from_file_location(path.stem, path)
            assert spec is not None and spec.loader is not None
            mods[name] = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(mods[name])
        g = inlined(mods["outer"].both, "both_inline", {**FLOAT64_INLINE, "s1": "body", "s2": "body"},
                    {"s1": mods["m1"].scaled, "s2": mods["m2"].scaled})
    got = {x: g(x) for x in (1.0, -0.5, 3.0)}
    bad = [f"x = {x}: {v}, the plain calls {5 * x}" for x, v in got.items() if v != 5 * x]
    if {"s1", "s2"} & set(g.__code__.co_names):
        bad.append("a body is still called")
    if bad:
        return failed("exact: inlined vs the plain calls", detail="; ".join(bad))
    return Outcome("verified", "exact: inlined vs the plain calls (consistency of the rewrite)", evidence="sampled",
                   n_scope="all", detail=f"{got}")


@claim("checker.undefined_points", equation="checker", scene="checker",
       where="symbt.proof.screen: a point where a side has no value (a Piecewise with no piece that applies)",
       statement="decide(Piecewise((x, x > 0)), x) (x real) holds by the numeric screen, every point it reports "
                 "at x > 0; decide(Piecewise((x, x > 0)), x + 10^-20) is false with a counterexample at x > 0")
def undefined_points() -> Outcome:
    from ..proof import decide

    x = sp.Symbol("x", real=True)
    half = sp.Piecewise((x, x > 0))
    bad = []
    try:
        same, off = decide(half, x), decide(half, x + sp.Rational(1, 10 ** 20))
    except Exception as exc:  # noqa: BLE001 -- a crash on an undefined point is the finding
        return failed("decide on a partly undefined side", detail=f"{type(exc).__name__}: {exc}")
    xs = [mp.mpf(pt["x"]) for pt in same.points]
    if not (same.holds and same.evidence == "sampled" and xs and min(xs) > 0):
        bad.append(f"= x: holds {same.holds} ({same.method}), points {[mp.nstr(v, 3) for v in xs]}")
    cx = (off.counterexample or {}).get("x")
    if off.holds or off.inconclusive or cx is None or not mp.mpf(cx) > 0:
        bad.append(f"= x + 1e-20: holds {off.holds}, inconclusive {off.inconclusive}, counterexample {cx}")
    if bad:
        return failed("decide on a partly undefined side", detail="; ".join(bad))
    return Outcome("verified", "decide on a partly undefined side: the screen's points and counterexample",
                   evidence="sampled", n_scope="all",
                   detail=f"{len(xs)} points, all x > 0; the near miss refuted at x = {cx}")


def decomposed_value(ints: list[int]) -> Fraction | None:
    """The number ``_decompose``'s integers ``(m0, m1, m2, m3, s1, s2, s3, e)`` stand for (``None`` if a shift is
    negative): ``((((m0 << s1) + m1) << s2) + m2 << s3) + m3) 2**e``, in Python's integers and fractions."""
    m0, m1, m2, m3, s1, s2, s3, e = ints
    if min(s1, s2, s3) < 0:
        return None
    return Fraction((((((m0 << s1) + m1) << s2) + m2) << s3) + m3) * Fraction(2) ** e


def decompose_rows(k: int, seed: int = 21) -> np.ndarray:
    """``k`` quad-doubles for ``paths.qd_decompose``: four components each, in a random order, with zeros, equal
    exponents and exponents from ``2**-600`` to ``2**600`` (every third row an edge case)."""
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(k):
        top = int(rng.integers(-600, 600))
        exps = top - np.sort(rng.integers(0, 200, 4))
        vals = rng.choice([-1.0, 1.0], 4) * rng.uniform(1, 2, 4) * np.ldexp(1.0, exps)
        if i % 3 == 0:
            vals[rng.integers(0, 4, int(rng.integers(1, 4)))] = 0.0       # zeros
        elif i % 3 == 1:
            vals[1] = -vals[0] / 2 if i % 2 else vals[0]                    # an equal exponent
        rows.append(rng.permutation(vals))
    return np.array(rows)


@claim("paths.qd_decompose", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/multiprec/qd.py: _decompose (the quad-double read-out, run as plain Python)",
       statement="_decompose on 400 quad-doubles (random components in any order, both signs, zeros, equal "
                 "exponents, exponents up to 2**+-600) gives mantissas below 2**53 and shifts >= 0 with sum x = "
                 "((((m0 << s1) + m1) << s2) + m2 << s3) + m3) 2**e exactly")
def qd_decompose() -> Outcome:
    from ..numeric.multiprec.qd import _decompose

    x = decompose_rows(400)
    out = np.zeros((x.shape[0], 8), np.int64)
    _decompose(x, out)
    bad = []
    for row, ints in zip(x, out.tolist()):
        if decomposed_value(ints) != sum(Fraction(float(v)) for v in row) or max(map(abs, ints[:4])) >= 2 ** 53:
            bad.append(f"{row.tolist()}: {tuple(ints)}")
    if bad:
        return failed("exact: the integers against the components' exact sum", detail="; ".join(bad[:2]))
    return Outcome("verified", "exact: the integers against the components' exact sum (fractions)",
                   evidence="sampled", n_scope="all", detail=f"{x.shape[0]} quad-doubles")


#: paths.jacobian_dual: lam0, mu with both traces positive at the paper's state (24200 and 4489.5)
POSITIVE_TRACES = (30.0, 5.0)


def encloses(balls: Any, values: list[Any]) -> bool:
    """Every ball (Arb) contains its value (mpf, at the current precision): ``|mid - y| <= rad + 1e-40``, the balls'
    midpoints read to 40 digits and radii to 5 (the slack covers that reading)."""
    return all(abs(mp.mpf(c.mid().str(40, radius=False)) - y) <= mp.mpf(c.rad().str(5, radius=False))
               + mp.mpf(10) ** -40 for c, y in zip(balls, values))


def positive_traces_enclosed(jd: Any, p: tuple[float, ...], q: tuple[float, ...]) -> list[str]:
    """For ``paths.jacobian_dual``: at :data:`POSITIVE_TRACES` (both traces positive, by the literal trace at 50
    digits) ``jd`` (:func:`~symbt.numeric.multiprec.lohner_checks.jacobian_dual`) computes the map at both branches
    and its image encloses the literal map (50 digits); what fails, as sentences."""
    from flint import arb

    from ..reference.literal import literal_step, literal_trace

    l0, m = POSITIVE_TRACES
    bad = []
    for b in (1, -1):
        with mp.workdps(50):
            P, Q = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]
            signs = [mp.sign(literal_trace(mp.mpf(l0) + s * m, P, Q)) for s in (1, -1)]
            pt, qt, _ = literal_step(P, Q, mp.mpf(l0), mp.mpf(m), b)
        with mp.workdps(30):
            try:
                img, _J = jd([arb(v) for v in list(p) + list(q)], arb(l0), arb(m), b)
            except Exception as exc:  # noqa: BLE001 -- any refusal is the finding: the map exists
                bad.append(f"lam0 = {l0}, mu = {m}, branch {b} (trace signs {signs}): {type(exc).__name__}: {exc}")
                continue
        with mp.workdps(50):
            if signs != [1, 1] or not encloses(img, list(pt) + list(qt)):
                bad.append(f"lam0 = {l0}, mu = {m}, branch {b}: trace signs {signs}, the image does not enclose "
                           "the literal map")
    return bad
