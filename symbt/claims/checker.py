r"""The checker checked: statements whose truth is known, fed to the decider, the screen and the cell table.

No verdict of the paper goes through every path of :mod:`symbt.proof` (most are decided exactly), so a
defect there -- a wrong root of a relation, a recheck at too low a precision, a worst cell that is the
best one -- would leave every claim as it was.  These claims give the checker statements that are true,
or false by a little, and require the verdict each deserves (scene ``checker``):

* ``checker.screen`` -- the numeric screen (:func:`symbt.proof.decide` with ``exact=False``):
  (a) :math:`\sin x = (1 + 10^{-20})\sin x` is refuted with a counterexample (the tolerance is
  :math:`10^{-42}` at 50 digits); (b) with the relation :math:`u^2 + bu - c = 0` (a quadratic, solved
  by the screen in closed form) :math:`u^2 + bu = c` holds and :math:`u^2 + bu = (1 + 10^{-20})c` is
  refuted; (c) the identity :math:`\sqrt{K^2 + e^x} - K = e^x/(\sqrt{K^2 + e^x} + K)` at
  :math:`K = 10^{40}` -- true, with a cancellation of 80 digits, more than the 50 asked for -- is
  never refuted (the recheck at :math:`2\cdot 50 + 10` digits sees the 50-digit value is noise: it
  is ``inconclusive`` or holds, never false); (d) an integral over an infinite range,
  :math:`\int_0^\infty e^{-t}\,dt = 1`, is a value, not an undefined side.
* ``checker.exact`` -- the exact layer: :math:`1/(x^2+1) = 1/(x^2+1) + 10^{-60}` is false *by proof*
  (a nonzero rational function), with the note that it is numerically tiny; and
  :func:`symbt.proof.Verdict.sampled` reports :math:`-\log_{10}` of the residual to one decimal (24.5 for
  :math:`3\cdot 10^{-25}`), capped at the working precision, and a residual of -0.5 does not hold.
* ``checker.cells`` -- :class:`symbt.proof.cells.CellTable`: the worst printed and corrected residuals
  are the largest over all cells and samples (computed here with ``max`` over the same numbers), a
  negative corrected residual is a failure (its size counts), the scope sentence names the one cell
  where a statement fails, and a table's verdict has at most its working precision's digits.

* ``checker.api`` -- the public checkers on statements of known truth: :func:`symbt.proof.solves_ode`
  proves the logistic solution and refutes it shifted by :math:`10^{-20}`, and scopes
  :math:`x = (t-t_0)^2/4`, :math:`x' = \sqrt x` to the cell :math:`t > t_0`;
  :func:`symbt.proof.check_identity` takes a relation as an equation or as a mapping, and proves an
  identity of exponentials of rational-linear forms exactly.  The details a verdict rests on: a relation
  given as an equation constrains the symbol of the side that has one
  (:func:`~symbt.proof.identity.normalize_relations` of :math:`\eta^2 = \mu^2 + w` and of
  :math:`\mu^2 + w = \eta^2` is keyed by :math:`\eta`); :math:`K(k)` written with the modulus where SymPy takes
  the parameter is false *with* the hint that says so; and the sampled ODE residual is relative to the
  size of the terms: :math:`x = -10^{30}e^t` for :math:`x' = -x` (both terms :math:`-10^{30}e^t`) has
  residual 2 (``exact=False``), not :math:`10^{30}`; and :math:`x = e^t` solves :math:`x' = nx` for
  :math:`n \in \{1\}` (``verified``, sampled: the exact layer's nonzero :math:`(1-n)e^t` is no proof of falsity
  where a parameter is discrete).

* ``checker.domain`` -- :meth:`symbt.proof.Domain.evaluate` with the user's own residual function (named
  parameters) and a split by the sign of a function: :math:`\sqrt{x^2}\,n = x\,n` over
  :math:`x \in (-2, 2)`, :math:`n \in \{1, 2, 3\}` fails in exactly the cell :math:`x < 0`; the counterexample
  shows the integer as an ``int`` and the real as a string of at most 17 digits (the double drawn), and
  re-evaluated there it fails again with the same residual; a residual function with ``*args`` or a
  positional-only parameter is a ``TypeError``.

>>> screen_controls.run().status
'verified'
"""
from __future__ import annotations

from typing import Any

import sympy as sp

from ..proof import Verdict, decide
from ..proof.cells import CellTable
from ..proof.exact import exact_zero
from ._facts import facts_verified as _ok
from .base import Outcome, claim, failed, scene

scene("checker", "the checker checked: true statements and statements false by a little, fed to the decider, "
                 "the numeric screen, the exact layer and the cell table; each must get the verdict it deserves")

x, b, c = sp.symbols("x b c", real=True)
u = sp.Symbol("u", real=True)
K = sp.Symbol("K", positive=True)
t = sp.Symbol("t", real=True)
SMALL = sp.Integer(10) ** -20



@claim("checker.screen", equation="checker", scene="checker",
       where="symbt.proof.decide, numeric screen (exact layer skipped)",
       statement="the numeric screen refutes sin x = (1 + 1e-20) sin x and u^2 + b u = (1 + 1e-20) c under "
                 "u^2 + b u - c = 0, accepts u^2 + b u = c there and int_0^oo e^-t dt = 1, and never refutes a "
                 "true identity whose cancellation exceeds the working precision")
def screen_controls() -> Outcome:
    near = decide(sp.sin(x), (1 + SMALL) * sp.sin(x), exact=False)
    if near.holds or near.inconclusive or not near.counterexample:
        return failed(near.method, residual=near.residual, detail="sin x = (1 + 1e-20) sin x was not refuted")
    if near.digits is None or not 19 <= near.digits <= 21:   # the sides agree to 20 digits, not more, not fewer
        return failed(near.method, residual=near.residual,
                      detail=f"sin x vs (1 + 1e-20) sin x: the screen reports {near.digits} agreeing digits (want 20)")
    rel, fixed = {u: u ** 2 + b * u - c}, {b: 3, c: 2}
    root = decide(u ** 2 + b * u, c, relations=rel, exact=False, fixed=fixed)
    if not root.holds:
        return failed(root.method, residual=root.residual, detail="u^2 + b u = c does not hold at the screen's "
                                                                  "roots of u^2 + b u - c: a wrong quadratic root")
    off = decide(u ** 2 + b * u, (1 + SMALL) * c, relations=rel, exact=False, fixed=fixed)
    if off.holds or off.inconclusive:
        return failed(off.method, residual=off.residual, detail="u^2 + b u = (1 + 1e-20) c was not refuted")
    # true; at 50 digits sqrt(K^2 + e^x) - K is rounding noise (80 digits cancel): only the recheck can tell
    lhs = sp.sqrt(K ** 2 + sp.exp(x)) - K
    deep = decide(lhs, sp.exp(x) / (sp.sqrt(K ** 2 + sp.exp(x)) + K), exact=False, fixed={K: sp.Integer(10) ** 40})
    if not deep.holds and not deep.inconclusive:
        return failed(deep.method, residual=deep.residual,
                      detail="a true identity with an 80-digit cancellation was refuted at 50 digits: the "
                             "recheck precision does not exceed the cancellation")
    integral = decide(sp.Integral(sp.exp(-t), (t, 0, sp.oo)), 1, exact=False)
    if not integral.holds:
        return failed(integral.method, residual=integral.residual,
                      detail="int_0^oo e^-t dt = 1 not accepted (an infinite limit taken for an undefined side?)")
    return _ok(near.method, "refuted: sin x vs (1 + 1e-20) sin x and the quadratic relation's c off by 1e-20 "
                            "(with counterexamples); held: u^2 + b u = c at the screen's roots, int_0^oo e^-t = 1; "
                            f"the 80-digit cancellation at 50 digits: "
                            f"{'held' if deep.holds else 'inconclusive'} (not refuted)", "sampled")


@claim("checker.exact", equation="checker", scene="checker",
       where="symbt.proof.decide, exact layer; symbt.proof.Verdict.sampled",
       statement="1/(x^2+1) = 1/(x^2+1) + 1e-60 is false by proof, noted as numerically tiny; so is + 1e-46 (below "
                 "the screen's tolerance 1e-42 at 50 digits), and + 1e-30 is not noted tiny; u^4 = 2v + 3 under "
                 "v^2 = 2, u^2 = v + 1 (two rounds of reduction) is proved on both exact routes; a sampled verdict's "
                 "digits are -log10(residual) to one decimal, capped at the working precision; a negative residual "
                 "does not hold")
def exact_controls() -> Outcome:
    f = 1 / (x ** 2 + 1)
    d = decide(f, f + sp.Integer(10) ** -60)
    if d.holds or d.evidence != "proof" or not d.definite or "numerically tiny" not in d.note:
        return failed(d.method, residual=d.residual,
                      detail=f"1/(x^2+1) vs 1/(x^2+1) + 1e-60: holds={d.holds}, evidence={d.evidence}, "
                             f"definite={d.definite}, note={d.note!r} (want: false by proof, noted tiny)")
    # "tiny" is the screen's own tolerance 10^-(digits - 8) (1e-42 at the default 50 digits), from both sides
    for e, tiny in ((46, True), (30, False)):
        d2 = decide(f, f + sp.Integer(10) ** -e)
        if d2.holds or not d2.definite or ("numerically tiny" in d2.note) != tiny:
            return failed(d2.method, residual=d2.residual,
                          detail=f"1/(x^2+1) vs 1/(x^2+1) + 1e-{e}: holds={d2.holds}, definite={d2.definite}, "
                                 f"note={d2.note!r} (want: false by proof, {'' if tiny else 'not '}noted tiny)")
    # relations that need two rounds of reduction: listed v first, u^4 -> (v + 1)^2 brings back the v^2 that the
    # first round had nothing to reduce; both exact routes must go on to the fixed point
    u_, v_ = sp.symbols("u v", positive=True)
    chain = {v_: v_ ** 2 - 2, u_: u_ ** 2 - v_ - 1}
    for route in ("flint", "sympy"):
        zero, how, _ = exact_zero(u_ ** 4 - 2 * v_ - 3, chain, route=route)
        if zero is not True:
            return failed(how or route, detail=f"u^4 = 2v + 3 under v^2 = 2, u^2 = v + 1: the {route} route gave "
                                               f"{zero} (want True: two rounds of reduction)")
    v = Verdict.sampled(1e-60, tol=1e-20, method="control", dps=30)
    if not v.holds or v.digits != 30:
        return failed("Verdict.sampled", detail=f"residual 1e-60 at 30 digits: digits={v.digits} (want 30)")
    v = Verdict.sampled(3e-25, tol=1e-20, method="control", dps=30)   # -log10(3e-25) = 24.52...
    if not v.holds or v.digits != 24.5:
        return failed("Verdict.sampled", detail=f"residual 3e-25: digits={v.digits} (want 24.5)")
    v = Verdict.sampled(-0.5, tol=1e-20, method="control", dps=30)
    if v.holds:
        return failed("Verdict.sampled", detail="a residual of -0.5 was taken for a statement that holds")
    return _ok(d.method, "false by proof (a nonzero rational function) and noted numerically tiny; "
                         "Verdict.sampled(1e-60, dps=30) has 30 digits", "proof")


def _table() -> tuple[CellTable, list]:
    table = CellTable(tol=1e-20, method="control", dps=30)
    rows = [({"b": 1}, 1e-30, 1e-25, {"x": "1"}), ({"b": 1}, 1e-28, 3e-24, {"x": "2"}),
            ({"b": -1}, 0.25, -0.5, {"x": "3"}), ({"b": -1}, 0.125, 1e-22, {"x": "4"})]
    for cell, rp, rc, pt in rows:
        table.add(cell, printed=rp, corrected=rc, point=pt)
    return table, rows


@claim("checker.cells", equation="checker", scene="checker", where="symbt.proof.cells.CellTable",
       statement="the cell table's worst printed and corrected residuals are the largest |residual| over all "
                 "samples, a negative corrected residual fails, and the scope names the one failing cell")
def cell_controls() -> Outcome:
    table, rows = _table()
    want_p = max(rows, key=lambda r: abs(r[1]))
    want_c = max(abs(r[2]) for r in rows)
    got_p, where_p = table.worst("printed")
    got_c, _ = table.worst("corrected")
    if got_p != abs(want_p[1]) or (where_p or {}).get("x") != want_p[3]["x"]:
        return failed("CellTable", detail=f"worst printed {got_p} at {where_p} "
                                          f"(want {abs(want_p[1])} at x={want_p[3]['x']})")
    if got_c != want_c:
        return failed("CellTable", detail=f"worst corrected {got_c} (want {want_c})")
    if table.corrected_holds_everywhere():
        return failed("CellTable", detail="a corrected residual of -0.5 counted as holding")
    v = table.verdict()
    scope = table.scope()
    if v.holds or v.digits is None or v.digits > 1 or "holds exactly in cells {b=+1}" not in scope \
            or "fails in {b=-1}" not in scope:
        return failed("CellTable", detail=f"verdict holds={v.holds}, digits={v.digits}, scope {scope!r}")
    tight = CellTable(tol=1e-20, method="control", dps=30)
    tight.add({"b": 1}, printed=1e-40)
    tv = tight.verdict()
    if not tv.holds or tv.digits != 30:
        return failed("CellTable", detail=f"a table at 30 digits with residual 1e-40: holds={tv.holds}, "
                                          f"digits={tv.digits} (want 30: the working precision caps them)")
    return _ok("CellTable", f"4 samples in 2 cells: worst printed {got_p:g}, corrected {got_c:g}; scope: {scope}; "
                            "a table at 30 digits with residual 1e-40 reports 30 digits", "sampled")


@claim("checker.api", equation="checker", scene="checker",
       where="symbt.proof.solves_ode, symbt.proof.check_identity (relations as equations or a mapping; "
             "exponentials of rational-linear forms)",
       statement="solves_ode proves the logistic solution and refutes it shifted by 1e-20; x = (t - t0)^2/4 solves "
                 "x' = sqrt(x) exactly in the cell t > t0 only; check_identity proves eta^2 - mu^2 = w under "
                 "eta^2 = mu^2 + w (given as an equation; the method names the remainder mod the relation, and "
                 "only there), refutes it off by 1e-20 (given as a mapping), and proves "
                 "exp(q1/2 - q2/3)^6 = exp(3 q1 - 2 q2); decide(e) with one side decides e = 0; "
                 "Eq(eta^2, mu^2 + w) constrains eta from either side; "
                 "K(k) by the modulus is false with the modulus/parameter hint; x = -1e30 e^t and x = 1e-30 e^t for "
                 "x' = -x have relative residual 2; x = e^t for x' = x + 1 has residual 1/(e^2 + 1) at t = 2 (over "
                 "its largest term); x = e^t (cosh^2 t - sinh^2 t - 1) solves x'' = 0 (sampled: "
                 "the rounding of a term that cancels is no residual); x = e^t solves x' = n x for n in {1} "
                 "(sampled, not refuted by the exact layer)")
def api_controls() -> Outcome:
    from ..proof.domain import Domain, sign
    from ..proof.identity import check_identity
    from ..proof.ode import solves_ode

    tt, t0 = sp.symbols("t t0")
    X = sp.Function("x")
    logistic = sp.Eq(X(tt).diff(tt), X(tt) * (1 - X(tt)))
    got: list[tuple[str, Any, Any]] = []
    v = solves_ode(logistic, 1 / (1 + sp.exp(-tt)))
    got.append(("logistic", v.verdict, "proved"))
    v = solves_ode(logistic, 1 / (1 + sp.exp(-tt)) + SMALL)
    got.append(("logistic + 1e-20", v.verdict, "false"))
    v = solves_ode(sp.Eq(X(tt).diff(tt), sp.sqrt(X(tt))), (tt - t0) ** 2 / 4,
                   domain=Domain({"t": (-2, 2), "t0": (-1, 1)}), splits=[sign(tt - t0)])
    got.append(("x' = sqrt(x)", (v.verdict, v.note),
                ("false", "printed statement holds exactly in cells {t>t0} and fails in {t<t0}")))
    eta, mu, w = sp.symbols("eta mu w", real=True)
    q1, q2 = sp.symbols("q1 q2", real=True)
    r = check_identity(eta ** 2 - mu ** 2 - w, relations=[sp.Eq(eta ** 2, mu ** 2 + w)])   # rhs: 0 by default
    got.append(("relation as an equation", r.verdict, "proved"))
    # the method names the reduction modulo the relation, and only where there is one
    got.append(("the method names the relation", r.method.endswith("; remainder mod eta: eta**2 - mu**2 - w=0"), True))
    r = check_identity(eta ** 2 - mu ** 2, w * (1 + SMALL), relations={eta: eta ** 2 - mu ** 2 - w})
    got.append(("relation as a mapping, off by 1e-20", r.verdict, "false"))
    from ..proof.decider import decide
    one_side = [decide(e, relations={eta: eta ** 2 - mu ** 2 - w}).verdict for e in (eta ** 2 - mu ** 2 - w, w)]
    got.append(("decide(e) decides e = 0", one_side, ["proved", "false"]))
    r = check_identity(sp.exp(q1 / 2 - q2 / 3) ** 6, sp.exp(3 * q1 - 2 * q2))
    got.append(("exponentials", (r.verdict, r.evidence, "remainder mod" in r.method), ("proved", "proof", False)))
    # which symbol an equation constrains: the side with a single symbol (eta), from either side
    from ..proof.identity import normalize_relations
    keys = [list(normalize_relations([rel])) for rel in (sp.Eq(eta ** 2, mu ** 2 + w), sp.Eq(mu ** 2 + w, eta ** 2))]
    got.append(("the symbol an equation constrains", keys, [[eta], [eta]]))
    # the convention hint of a false elliptic identity (the modulus k where SymPy takes m = k^2)
    k = sp.Symbol("k", positive=True)
    r = check_identity(sp.pi / 2 * sp.hyper([sp.S.Half, sp.S.Half], [1], k ** 2), sp.elliptic_k(k), digits=20,
                       points=3)
    got.append(("K(k) with the modulus", (r.verdict, r.note.startswith("hint: the sides agree if the modulus k is "
                                                                       "read as the parameter")), ("false", True)))
    # the sampled residual is relative to the terms' size, whatever their sign
    v = solves_ode(sp.Eq(X(tt).diff(tt), -X(tt)), -sp.Integer(10) ** 30 * sp.exp(tt), exact=False)
    got.append(("x = -1e30 e^t for x' = -x: relative residual 2",
                (v.verdict, v.residual is not None and abs(v.residual - 2) < 1e-12), ("false", True)))
    # ... small or large: no absolute floor, so x = 1e-30 e^t is as false as x = -1e30 e^t (residual 2)
    v = solves_ode(sp.Eq(X(tt).diff(tt), -X(tt)), sp.Integer(10) ** -30 * sp.exp(tt), exact=False)
    got.append(("x = 1e-30 e^t for x' = -x: relative residual 2",
                (v.verdict, v.residual is not None and abs(v.residual - 2) < 1e-12), ("false", True)))
    # ... the largest term is the scale: x = e^t for x' = x + 1 has terms e^t and -(e^t + 1) and, at t = 2,
    # residual 1 / (e^2 + 1) (over the smallest term it would be e^-2)
    import mpmath as mp

    from ..proof.ode import ode_residual
    with mp.workdps(40):
        r = ode_residual(sp.Eq(X(tt).diff(tt), X(tt) + 1), sp.exp(tt))(t=mp.mpf(2))
        got.append(("x = e^t for x' = x + 1 at t = 2: residual 1/(e^2 + 1)",
                    bool(abs(r - 1 / (mp.e ** 2 + 1)) < 1e-25), True))
    # ... and a term that cancels to 0 is measured against its own terms: its rounding is no residual
    v = solves_ode(sp.Eq(X(tt).diff(tt, 2), 0), sp.exp(tt) * (sp.cosh(tt) ** 2 - sp.sinh(tt) ** 2 - 1), exact=False)
    got.append(("x = e^t (cosh^2 t - sinh^2 t - 1) for x'' = 0, sampled", v.verdict, "verified"))
    # a nonzero rational residual proves nothing when a parameter is discrete: (1 - n) e^t vanishes at n = 1
    from ..proof.domain import integers
    n = sp.Symbol("n")
    v = solves_ode(sp.Eq(X(tt).diff(tt), n * X(tt)), sp.exp(tt), domain=Domain({"t": (0, 1), "n": integers(1, 1)}))
    got.append(("x = e^t for x' = n x, n in {1}", (v.verdict, v.evidence, "left a nonzero remainder" in v.method),
                ("verified", "sampled", True)))
    bad = [(what, g, want) for what, g, want in got if g != want]
    if bad:
        return failed("solves_ode / check_identity", detail="; ".join(f"{w_}: got {g!r}, want {v_!r}"
                                                                      for w_, g, v_ in bad))
    return _ok("solves_ode / check_identity", f"{len(got)} statements of known truth, each with the verdict it "
                                              "deserves (proved, false by proof, a cell scope, the relation's symbol, "
                                              "the convention hint, a relative ODE residual)", "proof")


@claim("checker.domain", equation="checker", scene="checker",
       where="symbt.proof.Domain.evaluate with user functions; sign() of a function; the counterexample shown",
       statement="sqrt(x^2) n = x n over x in (-2, 2), n in {1, 2, 3} fails exactly in the cell x < 0 (split by the "
                 "sign of a function); the counterexample shows n as an int and x as a string of <= 17 digits and "
                 "fails again there; a residual with *args or a positional-only parameter is a TypeError")
def domain_controls() -> Outcome:
    import mpmath as mp

    from ..proof.domain import Domain, integers, sign

    def residual(x, n):     # the user's own function: named parameters, a pair (lhs, rhs)
        return mp.sqrt(x ** 2) * n, x * n

    dom = Domain({"x": (-2, 2), "n": integers(1, 3)}, seed=5)
    table = dom.evaluate(sign(lambda x: x, name="side", labels=("x<0", "x>0")), printed=residual, dps=30, per_cell=6)
    scope = table.scope()
    if scope != "printed statement holds exactly in cells {x>0} and fails in {x<0}":
        return failed("Domain.evaluate", detail=f"scope {scope!r} (want: holds in x>0, fails in x<0)")
    worst, pt = table.worst("printed")
    pt = pt or {}
    # x is drawn as a double: 17 significant digits identify it (nstr drops trailing zeros)
    if not (isinstance(pt.get("n"), int) and isinstance(pt.get("x"), str)
            and 0 < len(pt["x"].lstrip("-").replace(".", "").strip("0")) <= 17):
        return failed("Domain.evaluate", detail=f"counterexample shown as {pt!r} (want n an int, x a double in at "
                                                "most 17 digits)")
    with mp.workdps(30):
        lhs, rhs = residual(mp.mpf(pt["x"]), pt["n"])
        again = abs(lhs - rhs) / max(1, abs(lhs), abs(rhs))
    if abs(again - worst) > 1e-15 * worst:
        return failed("Domain.evaluate", detail=f"at the shown counterexample the residual is {float(again):.17g}, "
                                                f"the table says {worst:.17g}")

    def positional(x, n, /):
        return 0

    for bad in (lambda *a: 0, positional):
        try:
            dom.evaluate(printed=bad, per_cell=1)
        except TypeError:
            continue
        except Exception as exc:    # noqa: BLE001 -- any other outcome is the defect reported
            return failed("Domain.evaluate", detail=f"a residual without named parameters raised {exc!r}, not "
                                                    "TypeError")
        return failed("Domain.evaluate", detail="a residual without named parameters was accepted")
    return _ok("Domain.evaluate", f"scope: {scope}; counterexample {pt} reproduces the residual {worst:.3g}; *args "
                                  "and positional-only residuals are TypeErrors", "sampled")
