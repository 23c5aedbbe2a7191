r"""What the samples of seeds 20 and 21 found unread (issue 21).

* ``library.fresh_toda2`` -- the shipped ``symbt/generated/toda2.py`` below its provenance header is the text
  :func:`symbt.codegen.emit.module_body` renders now.  A consistency check (the file against a fresh rendering of
  its own derivation), and the only one in the default run that reads the emitted *text*: ``symbt codegen
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
* ``paths.inline_globals`` -- :func:`symbt.numeric.core.inline.inlined` with two bodies *of one name* from two
  modules, each reading its own global ``TABLE`` (temporary files): the inlined function gives the plain calls'
  values (``2x + 3x``) and calls neither body (seed 21: renaming every global by its function's name bound both
  tables to one name).
"""
from __future__ import annotations

from pathlib import Path

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
       where="symbt/generated/toda2.py vs symbt.codegen.emit.module_body(2) rendered now",
       statement="the shipped toda2.py below its provenance header is the text module_body(2) renders now (a "
                 "consistency check of the emitted text; skipped under a SymPy other than the header's)")
def fresh_toda2() -> Outcome:
    import sympy

    from .. import generated
    from ..codegen.emit import module_body
    from ..codegen.provenance import read_header

    method = "exact: the shipped file's text against a fresh rendering (consistency)"
    path = Path(generated.__file__).with_name("toda2.py")
    text = path.read_text(encoding="utf-8")
    made_with = read_header(text).get("sympy")
    if made_with != sympy.__version__:
        return skipped(f"{path.name} was rendered with SymPy {made_with}, this is {sympy.__version__}")
    body, rendered = _body(text), module_body(2)
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
