r"""The checker's small rules, each checked on values whose answer is known (scene ``checker``; issue 21, seed 3).

A fresh seeded sample of ``symbt mutate --source proof`` (docs/mutation.md, seed 3) left mutants alive on lines
no claim observed: the exact layer's SymPy route with relations, hyperbolic functions in the exact layer, the
screen's trust in an unconverged quadrature and the digits of a false verdict, the value types of domains, the
words of verdicts and of ``symbt mutate``'s advice.  Each is a documented rule (docs/checker.md, "The checker's
small rules"); four claims check them against answers known independently of the code:

* ``checker.exact_routes`` -- :func:`symbt.proof.exact.exact_zero` on both routes (``sympy``; ``flint`` when
  python-flint imports) proves :math:`(\eta-\mu)(\eta+\mu) = w` modulo :math:`\eta^2 = \mu^2 + w` and does not
  prove it off by :math:`10^{-20}`; :func:`symbt.proof.decide` proves :math:`\cosh^2 x - \sinh^2 x = 1` with
  evidence ``proof`` and refutes it off by :math:`10^{-20}` *definitely*; :func:`~symbt.proof.exponentials.
  rational_linear_form` returns coefficients that rebuild its argument exactly, keyed by symbols and ``1``.
* ``checker.screen_trust`` -- the screen never verifies sides that agree when a quadrature has not converged
  (:math:`\int_0^1 \operatorname{sign}(3t - 1)\,dt` on both sides: ``inconclusive``), and a false verdict's
  digits are :math:`-\log_{10}` of the residual at its counterexample, which is recomputed here (:math:`x = -x`:
  residual 2, digits :math:`-\log_{10} 2`).
* ``checker.values`` -- the value types :class:`~symbt.proof.Range`, :class:`~symbt.proof.domain.Split`,
  :class:`~symbt.proof.mutation.Mutant` are frozen and hashable; :func:`~symbt.proof.log_uniform` draws inside
  its interval and refuses ``lo <= 0``; a sign split of a complex value with zero imaginary part is split by the
  real part, one with a nonzero imaginary part is a ``ValueError``; :class:`~symbt.proof.Worst` is the running
  maximum of the absolute residuals (Python's ``max`` of the same numbers); the default tolerance of
  :meth:`~symbt.proof.Domain.evaluate` at 30 and 60 digits is :math:`10^{-20}`, :math:`10^{-40}` (a residual ten
  times above fails, ten times below holds); :func:`~symbt.proof.screen.sample_symbol` moves a draw of the wrong
  parity to the documented neighbour.
* ``checker.texts`` -- :func:`~symbt.proof.mutation.why_no_mutants` names the documented case of each part that
  has no mutant (and only of such parts); the convention operator describes a branch symbol's mutant as a
  branch convention and a square root's as a sign convention; :meth:`~symbt.proof.IdentityResult.summary` begins
  with the verdict's words and lists at most 6 coordinates of a counterexample, then ``, ...``;
  :func:`~symbt.proof.check_identity` takes an ``Eq`` alone and refuses an ``Eq`` with a right-hand side.

>>> values_controls.run().status
'verified'
"""
from __future__ import annotations

import dataclasses
import math
import random
from typing import Any

import mpmath as mp
import sympy as sp

from ._facts import facts_failed as _bad
from ._facts import facts_verified as _ok
from .base import Outcome, claim, failed

x = sp.Symbol("x", real=True)
y = sp.Symbol("y", positive=True)
SMALL = sp.Integer(10) ** -20




# --------------------------------------------------------------------------- the exact layer

@claim("checker.exact_routes", equation="checker", scene="checker",
       where="symbt.proof.exact.exact_zero (both routes, with relations); the exact layer's hyperbolic functions; "
             "symbt.proof.exponentials.rational_linear_form",
       statement="exact_zero proves (eta - mu)(eta + mu) = w modulo eta^2 = mu^2 + w on the sympy and the flint "
                 "route and proves nothing when w is off by 1e-20; decide proves cosh^2 x - sinh^2 x = 1 (evidence "
                 "proof) and refutes it off by 1e-20 definitely; rational_linear_form's coefficients rebuild its "
                 "argument exactly, keyed by symbols and 1")
def exact_route_controls() -> Outcome:
    from ..proof.decider import decide
    from ..proof.exact import exact_route, exact_zero
    from ..proof.exponentials import rational_linear_form

    eta, mu, w = sp.symbols("eta mu w", real=True)
    rel = {eta: eta ** 2 - mu ** 2 - w}
    try:
        routes = ["sympy", exact_route("flint")]
    except ImportError:     # python-flint absent: the sympy route alone
        routes = ["sympy"]
    got: list[tuple[str, Any, Any]] = []
    for route in routes:
        zero, _m, definite = exact_zero((eta - mu) * (eta + mu) - w, rel, route=route)
        got.append((f"{route}: (eta - mu)(eta + mu) - w mod eta^2 - mu^2 - w", zero, True))
        zero, _m, definite = exact_zero((eta - mu) * (eta + mu) - w * (1 + SMALL), rel, route=route)
        # a nonzero remainder modulo a relation proves nothing either way: not zero, not definite
        got.append((f"{route}: the same off by 1e-20", (zero, definite), (False, False)))
    h = decide(sp.cosh(x) ** 2 - sp.sinh(x) ** 2, 1)
    got.append(("cosh^2 - sinh^2 = 1", (h.verdict, h.evidence), ("proved", "proof")))
    h = decide(sp.cosh(x) ** 2 - sp.sinh(x) ** 2, 1 + SMALL)
    got.append(("cosh^2 - sinh^2 = 1 + 1e-20", (h.verdict, h.evidence, h.definite), ("false", "proof", True)))
    q1, q2 = sp.symbols("q1 q2", real=True)
    for u in ((q1 - q2) / 2 + 1, sp.Rational(3, 7) * q1 - 2 * q2 + sp.Rational(-5, 3), q2 / 6, sp.Integer(4)):
        form = rational_linear_form(u)
        ok = form is not None and all(k is sp.S.One or k.is_Symbol for k in form) \
            and sp.expand(sum(c * k for k, c in form.items()) - u) == 0
        got.append((f"rational_linear_form({u}) rebuilds it", ok, True))
    bad = _bad("exact layer", got)
    return bad or _ok("exact_zero on both routes; decide; rational_linear_form rebuilt",
                      f"routes {', '.join(routes)}: proved under the relation, nothing proved off by 1e-20; "
                      "cosh^2 - sinh^2 = 1 proved, off by 1e-20 false by proof; 4 linear forms rebuilt exactly",
                      "proof")


# --------------------------------------------------------------------------- the screen's trust

@claim("checker.screen_trust", equation="checker", scene="checker",
       where="symbt.proof.decide, numeric screen: an unconverged quadrature; the digits of a false verdict",
       statement="int_0^1 sign(3t - 1) dt = int_0^1 sign(3s - 1) ds (agreeing sides, a quadrature that has not "
                 "converged) is inconclusive at 12 digits, not verified; x = -x (x real) is false with residual 2 "
                 "at its counterexample and digits -log10 2")
def screen_trust_controls() -> Outcome:
    from ..proof.decider import decide

    t, s = sp.symbols("t s", positive=True)
    q = decide(sp.Integral(sp.sign(3 * t - 1), (t, 0, 1)), sp.Integral(sp.sign(3 * s - 1), (s, 0, 1)),
               exact=False, digits=12, points=1)
    if q.verdict != "inconclusive" or q.error is None or not q.error > 1e-4:
        return failed(q.method, residual=q.residual,
                      detail=f"two equal unconverged quadratures: {q.verdict}, error {q.error} (want inconclusive: "
                             "the sides agree but the evaluation is not trustworthy to 1e-4)")
    f = decide(x, -x, exact=False, points=4)
    pt = f.counterexample or {}
    if f.verdict != "false" or "x" not in pt or f.digits is None or f.residual is None:
        return failed(f.method, residual=f.residual, detail=f"x = -x: {f.verdict} at {pt} (want false)")
    with mp.workdps(50):     # the residual at the counterexample, recomputed from the definition
        xv = mp.mpf(pt["x"])
        res = abs(xv - (-xv)) / max(abs(xv), mp.mpf(1))
    if abs(res - f.residual) > 1e-12 * res or abs(f.digits + math.log10(float(res))) > 1e-9:
        return failed(f.method, residual=f.residual,
                      detail=f"x = -x at x = {pt['x']}: residual {f.residual}, digits {f.digits}; recomputed "
                             f"residual {mp.nstr(res, 17)}, digits {-math.log10(float(res)):.12g}")
    return _ok(f.method, f"unconverged quadratures on both sides: inconclusive (error {q.error:.1e}); x = -x false, "
                         f"residual {f.residual:g} recomputed at x = {pt['x'][:12]}, digits {f.digits:.4f}", "sampled")


# --------------------------------------------------------------------------- values of domains and samples

class _Draw(random.Random):
    """A generator whose ``randint`` returns the one value it is given (to walk a sampler through every draw)."""

    def __init__(self, value: int) -> None:
        super().__init__(0)
        self.value = value

    def randint(self, a: int, b: int) -> int:
        return self.value


def _parity_rule(v: int, lo: int, hi: int, odd: bool) -> int:
    """sample_symbol's documented move of a uniform draw of the wrong parity."""
    if (v % 2 == 1) == odd:
        return v
    if odd:
        return v + 1 if v + 1 <= hi else v - 1
    return v - 1 if v - 1 >= lo else v + 1


def _frozen_and_hashable(obj: Any, again: Any) -> bool:
    name = dataclasses.fields(obj)[0].name
    try:
        setattr(obj, name, getattr(obj, name))
    except dataclasses.FrozenInstanceError:
        return obj == again and hash(obj) == hash(again) and len({obj, again}) == 1
    return False


@claim("checker.values", equation="checker", scene="checker",
       where="symbt.proof: Range, Split, Mutant; log_uniform; sign of a complex value; Worst; default_tol; "
             "sample_symbol's parity",
       statement="Range, Split and Mutant are frozen and hashable; log_uniform draws in [lo, hi] and refuses lo <= 0; "
                 "a sign split takes the real part of a complex value with zero imaginary part and refuses another; "
                 "Worst keeps the largest |residual|; Domain.evaluate's default tolerance at 30 and 60 digits is "
                 "1e-20 and 1e-40; sample_symbol moves a draw of the wrong parity to the documented neighbour")
def values_controls() -> Outcome:
    from ..proof.domain import Domain, sign
    from ..proof.mutation import Mutant
    from ..proof.ranges import log_uniform, uniform
    from ..proof.sampling import Worst
    from ..proof.screen import sample_symbol

    got: list[tuple[str, Any, Any]] = []
    for what, make in (("Range", lambda: uniform(0, 2)), ("Split", lambda: sign("t - t0")),
                       ("Mutant", lambda: Mutant("flip_sign", "flip the sign of x", -x))):
        got.append((f"{what} frozen and hashable", _frozen_and_hashable(make(), make()), True))
    r = log_uniform(1e-3, 1e3)
    draws = [r.draw(random.Random(k)) for k in range(48)]
    got.append(("log_uniform(1e-3, 1e3) draws in range, below 1e-2 and above 1e2",
                (all(1e-3 <= d <= 1e3 for d in draws), min(draws) < 1e-2, max(draws) > 1e2), (True, True, True)))
    for lo in (0, -1):
        try:
            log_uniform(lo, 1)
            got.append((f"log_uniform({lo}, 1)", "accepted", "ValueError"))
        except ValueError:
            pass
    real = sign(lambda z: mp.mpc(z, 0), name="re").bind(["z"])
    got.append(("sign of -1 + 0j, 2 + 0j", (real({"z": mp.mpf(-1)}), real({"z": mp.mpf(2)})), ("re<0", "re>0")))
    try:
        sign(lambda z: mp.mpc(z, 1), name="cx").bind(["z"])({"z": mp.mpf(1)})
        got.append(("sign of 1 + 1j", "a label", "ValueError"))
    except ValueError:
        pass
    residuals = [1e-52, -3e-3, 2e-60, 5e-41]
    worst = Worst()
    for k, res in enumerate(residuals):
        worst.add(res, {"k": str(k)})
    want = max(range(len(residuals)), key=lambda k: abs(residuals[k]))
    v = worst.verdict("control", tol=1e-40)
    got.append(("Worst of 4 residuals", (float(worst.residual), v.holds, v.counterexample, worst.n),
                (abs(residuals[want]), False, {"k": str(want)}, 4)))
    small = Worst()
    for res in (1e-52, 2e-60):
        small.add(res)
    got.append(("Worst of 1e-52, 2e-60", (float(small.residual), small.verdict("control", tol=1e-40).holds),
                (1e-52, True)))
    dom = Domain({"z": (0, 1)}, seed=2)
    for dps, tol in ((30, 1e-20), (60, 1e-40)):
        for factor, holds in ((10, False), (0.1, True)):
            off = mp.mpf(tol) * factor
            table = dom.evaluate(printed=lambda z, off=off: (1, 1 + off), dps=dps, per_cell=1)
            got.append((f"residual {factor} x 1e-{round(-math.log10(tol))} at {dps} digits",
                        table.verdict().holds, holds))
    for assume, lo, hi in (({"positive": True}, 1, 9), ({"negative": True}, -9, -1), ({}, -9, 9)):
        for odd in (True, False):
            n = sp.Symbol("n", integer=True, **({"odd": True} if odd else {"even": True}), **assume)
            moved = [int(sample_symbol(n, _Draw(v))) for v in range(lo, hi + 1)]
            want_moved = [_parity_rule(v, lo, hi, odd) for v in range(lo, hi + 1)]
            got.append((f"sample_symbol({n!r}, {assume or 'any sign'})", moved, want_moved))
    bad = _bad("symbt.proof values", got)
    return bad or _ok("frozen dataclasses, draws, splits, Worst, tolerances, parity against their stated rules",
                      f"{len(got)} facts: frozen Range/Split/Mutant, log_uniform, complex signs, Worst = max |r|, "
                      "default tolerances 1e-20 and 1e-40 (two-sided), the parity of 6 integer symbols", "proof")


# --------------------------------------------------------------------------- the words of verdicts and advice

_CASES = {   # a part without mutants -> the words of its documented case in why_no_mutants
    "0": (sp.S.Zero, "it is 0"), "zero matrix": (sp.zeros(2, 2), "it is a zero matrix"),
    "bare symbol": (sp.Symbol("a11"), "it is the bare symbol a11"),
    "matrix of bare symbols": (sp.Matrix([[sp.Symbol("a11"), 0]]), "a matrix of bare symbols and zeros"),
    "product of functions": (sp.sin(x) * sp.cos(x), "no operator applies to sin(x)*cos(x)"),
    "empty string": ("", "it is ''"),
}


def _counterexample_text(summary: str) -> str:
    head = "false: counterexample "
    return summary[len(head):summary.index(" (relative residual")] if summary.startswith(head) else "?"


@claim("checker.texts", equation="checker", scene="checker",
       where="symbt.proof.mutation.why_no_mutants and the convention operator's words; IdentityResult.summary; "
             "check_identity with an Eq",
       statement="why_no_mutants names the documented case of each part without mutants; a branch symbol's "
                 "convention mutant is a branch convention, a square root's a sign convention; a summary begins with "
                 "its verdict's words and lists at most 6 coordinates of a counterexample, then ', ...'; "
                 "check_identity takes an Eq alone and refuses an Eq with a right-hand side")
def text_controls() -> Outcome:
    from ..proof.identity import check_identity
    from ..proof.mutation import mutants, why_no_mutants

    got: list[tuple[str, Any, Any]] = []
    for case, (value, words) in _CASES.items():
        got.append((f"{case}: no mutant, and why", (len(mutants(value)), why_no_mutants(value).startswith(words)),
                    (0, True)))
    b = sp.Symbol("b")
    conv = {m.expr: m.description for m in mutants(sp.exp(b * x) + sp.exp(sp.sqrt(y)))
            if m.operator == "convention"}
    got.append(("convention mutants' words", conv,
                {sp.exp(-b * x) + sp.exp(sp.sqrt(y)): "swap the branch convention b -> -b",
                 sp.exp(b * x) + sp.exp(-sp.sqrt(y)): "swap the sign convention sqrt(y) -> -sqrt(y)"}))
    proved = check_identity(sp.Eq((x + 1) ** 2, x ** 2 + 2 * x + 1))
    got.append(("an Eq alone", (proved.status, proved.summary().startswith("proved by exact:")), ("proved", True)))
    try:
        check_identity(sp.Eq((x + 1) ** 2, x ** 2 + 2 * x + 1), 1)
        got.append(("an Eq and a right-hand side", "accepted", "ValueError"))
    except ValueError:
        pass
    seven = sp.symbols("a1:8", real=True)
    for syms in (seven, (x,)):
        r = check_identity(sum(syms), sum(syms) + 1, points=2)
        shown = _counterexample_text(r.summary())
        names = [item.split("=")[0] for item in shown.split(", ")]
        want = [s.name for s in syms][:6] + (["..."] if len(syms) > 6 else [])
        got.append((f"the counterexample of a false statement in {len(syms)} symbols", (r.status, names),
                    ("false", want)))
    bad = _bad("symbt.proof texts", got)
    return bad or _ok("why_no_mutants, Mutant.description, IdentityResult.summary, check_identity(Eq)",
                      f"{len(got)} facts: the six documented cases without mutants, the two convention words, a "
                      "proved and two false summaries (7 coordinates shown as 6 and ', ...'), Eq with and without "
                      "a right-hand side", "proof")
