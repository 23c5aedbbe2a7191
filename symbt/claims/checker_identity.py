r"""Whole functions of ``check_identity``, the domains and the statement mutations, observed across their branches
(scene ``checker``; issue 21, item 4, fresh samples of ``symbt/proof/identity.py``, ``domain.py``, ``mutation.py``).

The claims of seeds 3, 4 and 5 (``checker_sample3``, ``checker_sample45``) each observe the one case a survivor
missed, so a fresh sample found the next case of the same function unobserved.  These claims take a function at a
time and walk it through every documented case -- every verdict, every accepted form, every refused argument --
against answers written down from the functions' docstrings, not computed by the code under test (docs/mutation.md,
"Fresh samples of symbt/proof/identity.py, domain.py, mutation.py"):

* ``checker.identity_result`` -- :class:`~symbt.proof.IdentityResult` of each of the four verdicts, built from
  known fields: ``status``, ``proved``, ``bool``, the statement (sides cut at 80 characters), ``summary`` (every
  optional field present and absent; the digits asked for reached or not; a hint note shown, another note not),
  ``str``, the notebook displays (HTML rows of each verdict, the LaTeX relation) and ``to_dict``.
* ``checker.identity_arguments`` -- :func:`~symbt.proof.check_identity`'s refused arguments (each the documented
  exception, naming the argument) and the effect of each accepted one: ``exact``, ``points``, ``seed``,
  ``digits``, ``fixed`` (also under assumptions), a string side, an ``Eq``.
* ``checker.identity_relations`` -- :func:`~symbt.proof.identity.normalize_relations` of every accepted form and
  every refused one, the symbol an equation or a polynomial constrains (single-symbol side, else highest degree),
  :func:`~symbt.proof.identity.apply_assumptions` (keys by symbol and by name, combined and inconsistent
  assumptions, matrices, ``None``), relations under assumptions, and
  :func:`~symbt.proof.identity.convention_hint` on either side, both swaps, and matrices.
* ``checker.domain_rules`` -- :mod:`symbt.proof.domain`: residual functions (named, ``**kw``, defaults, missing),
  :func:`~symbt.proof.domain.relative_residual`, :func:`~symbt.proof.domain.default_tol` at every remainder of
  ``2 dps / 3``, the labels of :func:`~symbt.proof.domain.sign` splits and their refusals, the sign of zero,
  infinity and each side, choices and regimes, :class:`~symbt.proof.Domain`'s refusals, cells, and a sample
  checked point by point against its cell, its ``where`` and the deep run's prefix; an unfilled cell's counts.
* ``checker.mutation_rules`` -- :mod:`symbt.proof.mutation`: the indexed names, the complete mutant lists of five
  expressions and a matrix (operator, words, expression), the exponent rule, plain values of every type, a
  seeded subset, and :func:`~symbt.proof.mutation.why_no_mutants` of every type.

>>> identity_result.run().status
'verified'
"""
from __future__ import annotations

from typing import Any

import mpmath as mp
import sympy as sp

from ..proof.verdict import Evidence
from . import _identity_cases as cases
from ._facts import facts_failed as _bad
from ._facts import facts_verified as _ok
from .base import Outcome, claim

x = sp.Symbol("x", real=True)
y = sp.Symbol("y", positive=True)




def _raises(call: Any) -> tuple[str, str]:
    """``(exception class name, message)`` of ``call()``, or ``("returned", "")``."""
    try:
        call()
    except Exception as exc:    # noqa: BLE001 -- the class is the observation
        return type(exc).__name__, str(exc)
    return "returned", ""


def _refused(got: list[tuple[str, Any, Any]], what: str, call: Any, kind: str, words: str) -> None:
    name, text = _raises(call)
    got.append((what, (name, words in text), (kind, True)))


# --------------------------------------------------------------------------- IdentityResult

def _result(status: str, **kw: Any) -> Any:
    from ..proof.identity import IdentityResult

    holds = status in ("proved", "verified")
    evidence: Evidence = "proof" if status == "proved" else "sampled"
    kw.setdefault("lhs", x + 1)
    kw.setdefault("rhs", 1 + x)
    return IdentityResult(holds, evidence, "m", inconclusive=status == "inconclusive", **kw)




@claim("checker.identity_result", equation="checker", scene="checker",
       where="symbt.proof.IdentityResult: status, proved, bool, statement, summary, str, HTML and LaTeX displays, "
             "to_dict, for each of the four verdicts",
       statement="an IdentityResult of each verdict reports its status, truth and words as documented, with every "
                 "optional field present or absent, the digits asked for reached or not, sides cut at 80 characters "
                 "and counterexamples at 6 coordinates")
def identity_result() -> Outcome:
    got: list[tuple[str, Any, Any]] = []
    rows = cases.summaries()
    for status, fields, summary in rows:
        r = _result(status, **fields)
        holds = status in ("proved", "verified")
        got.append((f"{status} {fields}", (r.status, r.proved, bool(r), r.summary(), str(r)),
                    (status, status == "proved", holds, summary, f"x + 1 == x + 1: {summary}")))
    long_side = sp.Add(*sp.symbols("b0:40"))      # 40 terms: more than 80 characters
    text = sp.sstr(long_side)
    r = _result("proved", lhs=long_side, rhs=sp.Matrix([[x, 1], [0, x]]))
    got.append(("statement of a long side and a matrix", r.statement,
                f"{text[:77]}... == Matrix([ [x, 1], [0, x]])"))   # one line: the rows joined by a space
    exactly = sp.Symbol("c" * 80)
    got.append(("statement of an 80-character side", _result("proved", lhs=exactly).statement,
                f"{'c' * 80} == x + 1"))
    # (status, fields, what the display must contain, what it must not)
    html_rows = cases.displays()
    for status, fields, has, lacks in html_rows:
        page = _result(status, **fields)._repr_html_()
        got.append((f"HTML of {status} {fields}", ([h in page for h in has], [h in page for h in lacks]),
                    ([True] * len(has), [False] * len(lacks))))
    for status, rel in (("proved", "="), ("verified", "="), ("inconclusive", r"\overset{?}{=}"), ("false", r"\neq")):
        fields = {"residual": 1e-60, "digits": 50.0} if status == "verified" else {}
        got.append((f"LaTeX of {status}", _result(status, **fields)._repr_latex_(),
                    rf"$\displaystyle x + 1 {rel} x + 1\quad \text{{({status})}}$"))
    shown = repr(_result("proved", residual=0.0, lhs=sp.Symbol("left_side"), rhs=sp.Symbol("right_side")))
    got.append(("repr: the verdict's fields, not the sides", [w in shown for w in ("holds=True", "evidence='proof'",
                                                                                 "requested_digits=50", "left_side",
                                                                                 "right_side")],
                [True, True, True, False, False]))
    d = _result("false", residual=0.5, digits=0.3, error=1e-40, counterexample={"x": "2"}, note="n").to_dict()
    got.append(("to_dict", d, {"statement": "x + 1 == x + 1", "status": "false", "evidence": "sampled", "method": "m",
                               "residual": 0.5, "digits": 0.3, "error": 1e-40, "points": [],
                               "counterexample": {"x": "2"}, "note": "n"}))
    bad = _bad("IdentityResult", got)
    return bad or _ok("IdentityResult of each verdict against its documented words",
                      f"{len(got)} facts: {len(rows)} summaries and strings, 2 statements, {len(html_rows)} HTML "
                      "displays, 4 LaTeX relations, to_dict", "proof")


# --------------------------------------------------------------------------- check_identity's arguments


@claim("checker.identity_arguments", equation="checker", scene="checker",
       where="symbt.proof.check_identity: every refused argument and the effect of each accepted one",
       statement="check_identity refuses each malformed argument with the documented TypeError or ValueError naming "
                 "it, and each accepted argument has its documented effect: exact=False samples a polynomial "
                 "identity, points and seed choose the points, digits the tolerance, fixed pins a symbol (also under "
                 "assumptions), a string side is parsed, an Eq with rhs 0 or 0.0 is taken apart")
def identity_arguments() -> Outcome:
    from ..proof.identity import check_identity

    got: list[tuple[str, Any, Any]] = []
    for what, kw, kind, words in cases.calls_refused():
        _refused(got, what, lambda kw=kw: check_identity(x, x, **kw), kind, f"check_identity: {words}")
    for what, lhs, rhs, kind, words in cases.sides_refused():
        _refused(got, what, lambda lhs=lhs, rhs=rhs: check_identity(lhs, rhs), kind, words)
    square, expanded = (x + 1) ** 2, x ** 2 + 2 * x + 1
    r = check_identity(square, expanded, points=3)
    got.append(("exact layer on", (r.status, r.evidence, r.points, r.digits), ("proved", "proof", [], None)))
    sampled = [check_identity(square, expanded, exact=False, points=k, seed=s) for k, s in ((3, 7), (5, 7), (3, 8))]
    got.append(("exact=False: status, evidence, points", [(v.status, v.evidence, len(v.points)) for v in sampled],
                [("verified", "sampled", 3), ("verified", "sampled", 5), ("verified", "sampled", 3)]))
    again = check_identity(square, expanded, exact=False, points=3, seed=7)
    got.append(("the same seed, the same points; another seed, others",
                (again.points == sampled[0].points, sampled[2].points == sampled[0].points), (True, False)))
    # x against x(1 + 1e-24): at d = 30 the tolerance 10^-(d-8) is 1e-22 (holds), at 40
    # it is 1e-32 (a counterexample); the requested digits are reported as given
    off = x * (1 + sp.Integer(10) ** -24)
    by_digits = [check_identity(x, off, digits=d, exact=False, points=2) for d in (30, 40)]
    got.append(("digits 30 and 40 on a 1e-24 difference", [(v.status, v.requested_digits) for v in by_digits],
                [("verified", 30), ("false", 40)]))
    for assumptions in (None, {x: {"positive": True}}, {"x": {"positive": True}}):
        r = check_identity(x ** 2, x * x, exact=False, points=3, fixed={x: 3}, assumptions=assumptions)
        got.append((f"fixed x = 3, assumptions {assumptions}", (r.status, {p.get("x") for p in r.points}),
                    ("verified", {"3.0"})))
    r = check_identity("(z + 1)**2", "z**2 + 2*z + 1")
    got.append(("string sides", (r.status, r.statement), ("proved", "(z + 1)**2 == z**2 + 2*z + 1")))
    r = check_identity(x, x, digits=9, exact=False, points=1)
    got.append(("digits 9, the fewest accepted", (r.status, r.requested_digits), ("verified", 9)))
    for zero in (0, 0.0):
        r = check_identity(sp.Eq(square, expanded), zero)
        got.append((f"an Eq with rhs {zero!r}", (r.status, r.statement), ("proved", "(x + 1)**2 == x**2 + 2*x + 1")))
    r = check_identity(sp.Eq(square, expanded + 1))
    got.append(("a false Eq", r.status, "false"))
    # a matrix side against the number 0 is compared with the zero matrix of its shape, on either side; against
    # another number it is not (SymPy cannot subtract them: an error, never a verdict)
    zero = sp.Matrix([[square - expanded, 0]])
    got.append(("a matrix against 0", [check_identity(a, b, points=2).status for a, b in
                                       ((zero, 0), (0, zero), (sp.Matrix([[x, 0]]), 0), (0, sp.Matrix([[0, x]])))],
                ["proved", "proved", "false", "false"]))
    got.append(("a matrix against 1", [_raises(lambda a=a, b=b: check_identity(a, b))[0] != "returned"
                                       for a, b in ((zero, 1), (1, zero))], [True, True]))
    bad = _bad("check_identity's arguments", got)
    return bad or _ok("check_identity on refused and accepted arguments of known effect",
                      f"{len(got)} facts: {len(cases.calls_refused())} refused arguments, "
                      f"{len(cases.sides_refused())} refused sides, exact, points, seed, digits, fixed (3 ways), "
                      "string sides, Eq", "sampled")


# --------------------------------------------------------------------------- relations, assumptions, hints


@claim("checker.identity_relations", equation="checker", scene="checker",
       where="symbt.proof.identity: normalize_relations, the constrained symbol, apply_assumptions, relations under "
             "assumptions, convention_hint and the note of check_identity",
       statement="normalize_relations turns every accepted form into {symbol: polynomial}, constraining the symbol "
                 "of a single-symbol side of an Eq, else the symbol of highest degree, and refuses ties, constants, "
                 "names as keys, a relation without its key and two relations for one symbol; apply_assumptions "
                 "replaces by symbol and by name, combines assumptions and refuses inconsistent ones; relations follow "
                 "their symbol under assumptions; the modulus/parameter hint is found on either side, both ways, and "
                 "in matrices, and is check_identity's whole note")
def identity_relations() -> Outcome:
    from ..proof.identity import apply_assumptions, check_identity, convention_hint, normalize_relations

    got: list[tuple[str, Any, Any]] = []
    for what, rel, want in cases.relations_cases():
        if isinstance(want, dict):
            out = normalize_relations(rel)
            got.append((f"relations: {what}", (out, [type(s) for s in out]), (want, [sp.Symbol] * len(want))))
        else:
            name, text = _raises(lambda rel=rel: normalize_relations(rel))
            got.append((f"relations: {what}", (name, want[1] in text), (want[0], True)))
    plain = sp.Symbol("x")
    for key in (x, "x", plain):
        # the statement's x is real; the key names it, or is it, or is another symbol of its name: the new x is
        # real (kept) and positive (added), so sqrt(x^2) and |x| become x
        repl, new, none, mat = apply_assumptions({key: {"positive": True}}, sp.sqrt(x ** 2), None,
                                                 sp.Matrix([[x, sp.Abs(x)]]))
        got.append((f"assumptions keyed by {key!r}", (new.is_positive, new.is_real, none, mat, set(repl.values()),
                                                      x in repl), (True, True, None, sp.Matrix([[new, new]]), {new},
                                                                   True)))
    got.append(("no assumptions", apply_assumptions({}, x + 1, None), ({}, x + 1, None)))
    # the key's own assumptions are combined with the new ones: a positive key of x's name, made an integer, turns
    # the real x of the statement into a positive integer (sqrt(x^2) = x proved); the matrix stays a mutable one
    key = sp.Symbol("x", positive=True)
    repl, new, mat = apply_assumptions({key: {"integer": True}}, sp.sqrt(x ** 2), sp.Matrix([[x]]))
    got.append(("a positive key made an integer", (new.is_positive, new.is_integer, set(repl), type(mat)),
                (True, True, {key, x}, sp.MutableDenseMatrix)))
    r = check_identity(sp.sqrt(x ** 2), x, assumptions={key: {"integer": True}})
    got.append(("sqrt(x^2) = x under a positive key made an integer", r.status, "proved"))
    for what, assume, kind in (("inconsistent", {x: {"positive": True, "negative": True}}, "ValueError"),
                               ("against the symbol's own", {y: {"negative": True}}, "ValueError"),
                               ("a number as key", {3: {"positive": True}}, "TypeError")):
        name, text = _raises(lambda assume=assume: apply_assumptions(assume, x + y))
        got.append((f"assumptions {what}", name, kind))
    eta = sp.Symbol("eta", real=True)
    w = sp.Symbol("w")
    lhs, rhs = eta ** 2 * sp.sqrt(eta ** 2), w * eta       # eta^3 = eta w modulo eta^2 = w once eta > 0
    for relations in ({eta: eta ** 2 - w}, [sp.Eq(eta ** 2, w)]):
        for key in (eta, "eta"):
            r = check_identity(lhs, rhs, relations=relations, assumptions={key: {"positive": True}})
            got.append((f"relations {relations} under assumptions keyed by {key!r}", (r.status, r.evidence),
                        ("proved", "proof")))
    r = check_identity(lhs, rhs, relations={eta: eta ** 2 - w}, points=4)
    got.append(("the same without assumptions (a negative root of eta^2 = w)", r.status, "false"))
    for what, left, right, hint in cases.hint_cases():
        text = convention_hint(left, right, digits=20, points=3)
        got.append((f"hint: {what}", (text.startswith(hint), bool(text) == bool(hint)), (True, True)))
    k = sp.Symbol("k", positive=True)
    r = check_identity(sp.elliptic_k(k), sp.pi / 2 * sp.hyper([sp.S.Half, sp.S.Half], [1], k ** 2), digits=20,
                       points=3)
    got.append(("check_identity's note is the hint", (r.status, r.note),
                ("false", "hint: the sides agree if the modulus k is read as the parameter m = k**2: SymPy/mpmath "
                          "elliptic functions take m")))
    bad = _bad("relations, assumptions, hints", got)
    return bad or _ok("normalize_relations, apply_assumptions, check_identity, convention_hint on known answers",
                      f"{len(got)} facts: {len(cases.relations_cases())} relation forms, assumptions 3 ways and 3 "
                      "refusals, "
                      f"relations under assumptions 4 ways, {len(cases.hint_cases())} hints", "sampled")


# --------------------------------------------------------------------------- domains


def _in_cell(point: dict[str, Any], cell: dict[str, Any]) -> bool:
    """The cell of a point of the sample below, computed here from the point's values."""
    side = "t<t0" if float(point["t"]) < float(point["t0"]) else "t>t0"
    parity = "odd" if point["n"] % 2 else "even"
    return cell == {"sign(t - t0)": side, "b": point["b"], "r": parity}


@claim("checker.domain_rules", equation="checker", scene="checker",
       where="symbt.proof.domain: residual functions, relative_residual, default_tol, sign/choice/regime, Domain's "
             "refusals, cells, sample and evaluate, UnfilledCellError",
       statement="every refused argument of the domain API is the documented exception; sign labels move negative "
                 "terms right and a point where the split is 0 or infinite is in no cell; residuals are relative to "
                 "max(1, |lhs|, |rhs|), undefined ones never hold; the default tolerance is 10^-(2 dps // 3); a sample "
                 "fills every cell of the product with points of that cell inside where, reproducibly, the default "
                 "run a prefix of the deep one; an unfilled cell accounts for every draw")
def domain_rules() -> Outcome:
    from ..proof.domain import Domain, UnfilledCellError, choice, default_tol, integers, regime, relative_residual, sign

    got: list[tuple[str, Any, Any]] = []
    for what, call, kind, words in cases.domain_refusals():
        _refused(got, what, call, kind, words)
    got.append(("auto labels", [sign(e).values for e in ("t - t0", "-a - b + c", "x**2 - 1", "S - N*beta")],
                [("t<t0", "t>t0"), ("c<a + b", "c>a + b"), ("x**2<1", "x**2>1"), ("S<N*beta", "S>N*beta")]))
    u = sp.Symbol("u")

    def gap(t: Any, t0: Any) -> Any:
        return t - t0

    got.append(("named splits", [(s.name, s.values) for s in (sign(u - 2), sign(gap), sign("t", labels=("lo", "hi")))],
                [("sign(u - 2)", ("u<2", "u>2")), ("gap", ("gap<0", "gap>0")), ("sign(t)", ("lo", "hi"))]))
    by_f, by_g = sign(lambda t: t, name="s"), sign(lambda t: 2 * t, name="s")
    by_e, by_h = (sign(e, name="s", labels=("s<0", "s>0")) for e in ("t - t0", "2*t0 - 2*t"))
    got.append(("splits by two functions, by two expressions, making the same cells",
                (by_f == by_g, len({by_f, by_g}), by_e == by_h, len({by_e, by_h})), (True, 1, True, 1)))
    cx = sign(lambda z: z, name="c").bind(["z"])
    got.append(("sign labels of -1 + 0j, 2 + 0j", (cx({"z": mp.mpc(-1, 0)}), cx({"z": mp.mpc(2, 0)})), ("c<0", "c>0")))
    got.append(("the sign of 1 + 1j", _raises(lambda: cx({"z": mp.mpc(1, 1)}))[0], "ValueError"))
    got.append(("a split's repr", repr(sign(lambda t: t, name="s")), "Split(name='s', kind='sign', values=('s<0', "
                                                                      "'s>0'))"))
    side = sign(lambda z: z, name="s").bind(["z"])
    got.append(("sign labels of -1, 2, 0, inf, nan", [side({"z": v}) for v in (mp.mpf(-1), mp.mpf(2), mp.mpf(0),
                                                                            mp.inf, mp.nan)],
                ["s<0", "s>0", None, None, None]))
    with mp.workdps(30):
        rel = [float(relative_residual(mp.mpf(a), mp.mpf(b))) for a, b in ((3, 3.5), (-4, -4.5), (0.1, 0.2),
                                                                           (-0.5, 0.5), (3.5, 3), (-4.5, -4))]
    got.append(("relative residuals", [round(r, 15) for r in rel],
                [round(v, 15) for v in (0.5 / 3.5, 0.5 / 4.5, 0.1, 1.0, 0.5 / 3.5, 0.5 / 4.5)]))
    got.append(("default tolerances", [default_tol(d) for d in (15, 30, 31, 32, 45)],
                [1e-10, 1e-20, 1e-20, 1e-21, 1e-30]))
    one = Domain({"t": (1, 2)}, seed=3)
    shapes = [lambda t: (t, t * (1 + mp.mpf(10) ** -3)), lambda t: [t, -t], lambda t: -mp.mpf(10) ** -25,
              lambda t: mp.nan, lambda t: -1, lambda t: mp.mpc(3, 4) * mp.mpf(10) ** -26]
    tables = [one.evaluate(printed=f, per_cell=2) for f in shapes]
    got.append(("residual of a pair, a list, a negative number, nan, -1, a complex number",
                ([float(f"{tb.worst('printed')[0]:.12g}") for tb in tables], [tb.verdict().holds for tb in tables]),
                ([float(f"{1e-3 / (1 + 1e-3):.12g}"), 2.0, 1e-25, float("inf"), 1.0, 5e-26],
                 [False, False, True, False, False, True])))
    scope = Domain({"t": (1, 2), "n": integers(1, 2)}, seed=2).evaluate(
        sign("t - 3/2"), printed=lambda t, n: (mp.sqrt((t - mp.mpf(3) / 2) ** 2) * n, (t - mp.mpf(3) / 2) * n))
    shown = scope.worst("printed")[1] or {}
    got.append(("a sign split's scope, method and counterexample", (scope.scope(), scope.method, type(shown.get("n")),
                                                                    type(shown.get("t"))),
                ("printed statement holds exactly in cells {t>3/2} and fails in {t<3/2}",
                 "numeric: mpmath 30 digits at 16 seeded points in each of 2 cells (seed 2)", int, str)))
    got.append(("the least dps, tol 0", (len(one.sample(dps=15, per_cell=2)),
                                          one.evaluate(printed=lambda t: 0, tol=0, per_cell=1).verdict().holds),
                (2, True)))
    got.append(("tol given, default", [one.evaluate(printed=lambda t: 1e-10, tol=tl, per_cell=1).verdict().holds
                                       for tl in (1e-9, 1e-11)], [True, False]))

    def everything(**point: Any) -> Any:
        return 0 if set(point) == {"t", "b"} else 1

    def with_default(t: Any, scale: Any = 2) -> Any:
        return scale - 2

    def whole(**point: Any) -> Any:
        return 0 if set(point) == {"t", "b"} else 1

    whole.takes_point = True  # type: ignore[attr-defined]
    kinds = [one.evaluate(choice("b", (1, -1)), printed=f, per_cell=1).verdict().holds
             for f in (everything, with_default, whole)]
    got.append(("residuals with **point, a default, takes_point", kinds, [True, True, True]))
    t = one.evaluate(choice("b", (1, -1)), printed=lambda t, b: b * 1e-30, corrected=lambda t, b: 0, per_cell=3)
    got.append(("evaluate's table", (t.method, t.scope()),
                ("numeric: mpmath 30 digits at 3 seeded points in each of 2 cells (seed 3)",
                 "printed statement holds in all 2 cells; corrected statement holds in all 2 cells")))
    try:
        one.evaluate(printed=lambda t: 1 / 0, per_cell=1)
        got.append(("a residual that raises", "returned", "ZeroDivisionError"))
    except ZeroDivisionError as exc:
        # Python >= 3.11 (add_note): the note says where
        notes: list[str] = getattr(exc, "__notes__", []) if hasattr(exc, "add_note") else ["at the point {'t': "]
        got.append(("a residual that raises: where", bool(notes) and notes[0].startswith("at the point {'t': "),
                    True))
    dom = Domain({"t": (-2, 2), "t0": (-1, 1), "n": integers(1, 3)}, where=lambda t, n: abs(t) > 0.3 * n, seed=11)
    splits = (sign("t - t0"), choice("b", (1, -1)), regime("r", lambda n: "odd" if n % 2 else "even", ("odd", "even")))
    pts = dom.sample(*splits, per_cell=4)
    cells = dom.cells(*splits)
    got.append(("the sample's cells, in order", [c for c, _ in pts], [c for c in cells for _ in range(4)]))
    got.append(("every point in its cell and in the domain", [(_in_cell(p, c), abs(p["t"]) > 0.3 * p["n"],
                                                               sorted(p), type(p["n"])) for c, p in pts],
                [(True, True, ["b", "n", "t", "t0"], int)] * len(pts)))
    chosen = Domain({"t": (-1, 1)}, where=lambda t, b: b * t > 0, seed=1).sample(splits[1], per_cell=2)
    got.append(("a where that takes the choice", [(c["b"], p["b"] * p["t"] > 0) for c, p in chosen],
                [(1, True)] * 2 + [(-1, True)] * 2))
    again, other = dom.sample(*splits, per_cell=4), Domain(dict(dom.variables), where=dom.where, seed=12)
    got.append(("reproducible; another seed, other points", (again == pts, other.sample(*splits, per_cell=4) == pts),
                (True, False)))
    plain, deep = dom.sample(splits[0]), dom.sample(splits[0], deep=True)
    got.append(("16 per cell, 64 deep, the first 16 the same", (len(plain), len(deep), deep[:16] == plain[:16],
                                                                deep[64:80] == plain[16:]), (32, 128, True, True)))
    rare = Domain({"t": (0, 1)}, where=lambda t: not 0.3 < t < 0.5, seed=1, draws_per_point=3)
    try:
        rare.sample(sign("t - 9/10"), per_cell=10)
        got.append(("a cell of a tenth of the draws", "filled", "UnfilledCellError"))
    except UnfilledCellError as exc:
        counts = [int(v) for v in str(exc).replace("(", " ").split() if v.isdigit()]
        filled, wanted, draws, outside, elsewhere = counts[:5]
        got.append(("an unfilled cell's words", str(exc).startswith("cannot fill cell {t>9/10}: "), True))
        got.append(("an unfilled cell's counts", (exc.cell, exc.wanted, exc.draws, exc.filled == filled, wanted, draws,
                                                  filled + outside + elsewhere, filled < 10, elsewhere > outside > 0),
                    ({"sign(t - 9/10)": "t>9/10"}, 10, 30, True, 10, 30, 30, True, True)))
    got.append(("repr", [repr(Domain({"t": (0, 1), u: range(1, 3)}, where=lambda t: t > 0, seed=4)),
                         repr(Domain({"t": (0, 1)}, draws_per_point=1))],
                ["Domain({t: uniform(0, 1), u: integers(1, 2)}, where=..., seed=4)", "Domain({t: uniform(0, 1)}, "
                                                                                   "seed=0)"]))
    bad = _bad("symbt.proof.domain", got)
    return bad or _ok("the domain API on refused arguments and on samples checked point by point",
                      f"{len(got)} facts: {len(cases.domain_refusals())} refusals, labels, residuals, tolerances, a "
                      "sample "
                      f"of {len(pts)} points in {len(cells)} cells, the deep prefix, an unfilled cell", "proof")


# --------------------------------------------------------------------------- the statement mutations


@claim("checker.mutation_rules", equation="checker", scene="checker",
       where="symbt.proof.mutation: index_parts, the six operators on sums, functions, exponents, conventions and "
             "matrices, mutate_value of each type, the seeded subset, why_no_mutants of each type",
       statement="indexed names split into stem and index (p1, E_jp1, a_jm1, b_2, xj; x, j and _1 are not indexed); "
                 "the mutants of five expressions and of a matrix are exactly the documented ones with their words; "
                 "plain values of each type give their documented mutants; a seeded subset is a reproducible ordered "
                 "subset of its size; why_no_mutants names the case of each type")
def mutation_rules() -> Outcome:
    from ..proof.mutation import index_parts, mutants, mutate_value, why_no_mutants

    got: list[tuple[str, Any, Any]] = []
    names = {"p1": ("p", "1"), "E_jp1": ("E_", "jp1"), "E_j": ("E_", "j"), "a_jm1": ("a_", "jm1"),
             "lambda12": ("lambda", "12"), "b_2": ("b_", "2"), "xj": ("x", "j"), "p_0": ("p_", "0"), "x": None,
             "_1": None, "j": None}
    got.append(("index_parts", {n: index_parts(sp.Symbol(n)) for n in names}, names))
    for expr, want in cases.mutant_lists():
        found = [(m.operator, m.description, m.expr) for m in mutants(expr)]
        got.append((f"mutants of {expr}", (len(found), set(found)), (len(want), want)))
    for expr, order in cases.ordered_mutants():
        got.append((f"the order of the mutants of {expr}", [(m.operator, m.description) for m in mutants(expr)],
                    order))
    matrix = sp.Matrix([[x + 1, 0], [2 * x, y]])
    found = [(m.operator, m.description, m.expr.tolist()) for m in mutants(matrix)]
    got.append(("mutants of a matrix", found, [
        ("flip_sign", "entry (0, 0): flip the sign of 1", [[x - 1, 0], [2 * x, y]]),
        ("flip_sign", "entry (0, 0): flip the sign of x", [[1 - x, 0], [2 * x, y]]),
        ("drop_term", "entry (0, 0): drop the term 1", [[x, 0], [2 * x, y]]),
        ("drop_term", "entry (0, 0): drop the term x", [[1, 0], [2 * x, y]]),
        ("change_const", "entry (0, 0): change the constant 1 to 2", [[x + 2, 0], [2 * x, y]]),
        ("perturb", "entry (0, 0): perturb the coefficient 1 by a relative 1e-6",
         [[x + sp.Rational(1000001, 1000000), 0], [2 * x, y]]),
        ("change_const", "entry (1, 0): change the constant 2 to 3", [[x + 1, 0], [3 * x, y]]),
        ("perturb", "entry (1, 0): perturb the coefficient 2 by a relative 1e-6",
         [[x + 1, 0], [sp.Rational(1000001, 500000) * x, y]])]))
    for value, want_v in cases.value_mutants():
        got.append((f"mutate_value({value!r})", [(m.operator, m.description, m.expr) for m in mutate_value(value)],
                    want_v))
    expr = cases.mutant_lists()[0][0]
    full = [m.expr for m in mutants(expr)]
    subsets = [[m.expr for m in mutants(expr, limit=4, seed=s)] for s in (5, 5, 6)]
    positions = [full.index(e) for e in subsets[0]]
    got.append(("a seeded subset of 4 of 11", (len(subsets[0]), positions == sorted(set(positions)),
                                                 subsets[0] == subsets[1], subsets[0] == subsets[2]),
                (4, True, True, False)))
    got.append(("the default seed is 0", [m.expr for m in mutants(expr, limit=4)],
                [m.expr for m in mutants(expr, limit=4, seed=0)]))
    got.append(("limits of 11 and 12", [[m.expr for m in mutants(expr, limit=k, seed=5)] for k in (11, 12)],
                [full, full]))
    why = cases.why_cases()
    got.append(("why_no_mutants of each type", [why_no_mutants(v) for v, _ in why], [w for _, w in why]))
    bad = _bad("symbt.proof.mutation", got)
    return bad or _ok("index_parts, mutants, mutate_value, why_no_mutants against the documented operator rules",
                      f"{len(got)} facts: {len(names)} names, the mutants of 5 expressions and a matrix, "
                      f"{len(cases.value_mutants())} plain values, a seeded subset, {len(why)} cases without mutants",
                      "proof")
