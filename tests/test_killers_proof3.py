"""The claims of ``symbt/claims/checker_sample3.py`` kill the survivors of seed 3's sample in ``symbt.proof``, and the
equivalence proof of ``mutants-equivalent.toml``'s ``screen:162`` (issue 21, item 4; docs/mutation.md).

Each killer test plants the mutant's own text -- one single-point bug of ``symbt mutate --source``'s kind, with
:func:`planting.planted` -- into the module the claim reads it from, and requires the claim to fail; unpatched,
every claim verifies.
"""
from __future__ import annotations

import ast
import inspect
import math
import textwrap
from collections import OrderedDict

import mpmath
import pytest
import sympy as sp
from planting import planted

from symbt.claims import REGISTRY, load_all
from symbt.proof import decider, domain, exact, exponentials, identity, lambdify, mutation, ranges, sampling
from symbt.proof import screen as screen_module

load_all()

CLAIMS = ["checker.exact_routes", "checker.screen_trust", "checker.values", "checker.texts"]


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- checker.exact_routes

def test_sympy_route_without_its_relations(monkeypatch):
    # mutant exact:116 (branch, uncovered before): the sympy route reduces modulo the relations only when there
    # are none -- (eta - mu)(eta + mu) - w is no longer proved under eta^2 = mu^2 + w
    monkeypatch.setattr(exact, "exact_zero", planted(
        exact.exact_zero, "if relations:\n            num = reduce_modulo", "if not (relations):\n"
                                                                           "            num = reduce_modulo"))
    assert status("checker.exact_routes") == "failed"


def test_linear_form_keyed_one_below(monkeypatch):
    # mutant exponentials:72 (index-shift): `form[rest - 1] = ...` -- a consistent relabelling inside the exact
    # layer (every verdict the same), but the public form no longer rebuilds its argument
    monkeypatch.setattr(exponentials, "rational_linear_form", planted(
        exponentials.rational_linear_form, "form[rest] = form.get(", "form[rest - 1] = form.get("))
    assert status("checker.exact_routes") == "failed"


def test_hyperbolic_left_unrewritten(monkeypatch):
    # mutant exponentials:98 (branch, uncovered before): the second pass keeps cosh and sinh, so the difference is
    # not rational and cosh^2 - sinh^2 = 1 falls through to the screen (sampled, not proved)
    monkeypatch.setattr(exponentials._Walk, "_walk", planted(
        exponentials._Walk._walk, "return e if self.variables is None else rewritten",
        "return e if not (self.variables is None) else rewritten"))
    assert status("checker.exact_routes") == "failed"


# --------------------------------------------------------------------------- checker.screen_trust

def test_unconverged_quadrature_skipped(monkeypatch):
    # mutant screen:364 (compare): points whose sides agree are skipped when their error is *large*: two equal
    # unconverged quadratures are then verified instead of inconclusive
    monkeypatch.setattr(decider, "screen", planted(
        screen_module.screen, "if pc.residual <= clear and pc.error <= clear:",
        "if pc.residual <= clear and pc.error >= clear:"))
    assert status("checker.screen_trust") == "failed"


def test_false_digits_from_every_point(monkeypatch):
    # mutant screen:389 (branch): a false verdict's digits from the trusted digits of every point (clamped at 0)
    # instead of -log10 of the residual at the counterexample: x = -x reports 0.0, not -0.301
    monkeypatch.setattr(screen_module, "_result", planted(
        screen_module._result, 'if status == "verified":', 'if not (status == "verified"):'))
    assert status("checker.screen_trust") == "failed"


# --------------------------------------------------------------------------- checker.values

def test_split_not_frozen(monkeypatch):
    # mutant domain:143 (constant): `@dataclass(frozen=False)` on Split: assignable and unhashable
    src = textwrap.dedent(inspect.getsource(domain.Split))
    assert src.count("@dataclass(frozen=True)") == 1
    ns: dict = {}
    exec(compile(src.replace("@dataclass(frozen=True)", "@dataclass(frozen=False)"), domain.__file__, "exec"),
         vars(domain), ns)
    monkeypatch.setattr(domain, "Split", ns["Split"])
    assert status("checker.values") == "failed"


def test_sign_of_complex_inverted(monkeypatch):
    # mutant domain:181 (branch, uncovered before): a complex value with zero imaginary part refused, one with a
    # nonzero imaginary part split by its real part
    monkeypatch.setattr(domain, "_sign_label", planted(domain._sign_label, "if v.imag != 0:", "if not (v.imag != 0):"))
    assert status("checker.values") == "failed"


def test_default_tolerance_a_third(monkeypatch):
    # mutant domain:122 (drop-factor): 10**-(dps // 3): 1e-10 at 30 digits, so a residual of 1e-19 holds
    monkeypatch.setattr(domain, "default_tol", planted(domain.default_tol, "-(2 * dps // 3)", "-(dps // 3)"))
    assert status("checker.values") == "failed"


def test_log_uniform_refuses_positive_bounds(monkeypatch):
    # mutant ranges:73 (branch, uncovered before): `if not (a <= 0)` raises for every valid interval
    monkeypatch.setattr(ranges, "log_uniform", planted(ranges.log_uniform, "if a <= 0:", "if not (a <= 0):"))
    assert status("checker.values") == "failed"


def test_worst_starts_at_one(monkeypatch):
    # mutant sampling:28 (constant, uncovered before): the running maximum starts at 1, so every Worst is >= 1
    monkeypatch.setattr(sampling.Worst, "__init__", planted(
        sampling.Worst.__init__, "mpmath.mpf(0)", "mpmath.mpf(1)"))
    assert status("checker.values") == "failed"


def test_odd_draw_moved_down_at_the_top(monkeypatch):
    # mutant screen:40 (compare, uncovered before): `v + 1 < hi`: an even draw just below the top of the range (8 in
    # 1..9) moves down to 7 instead of up to 9
    monkeypatch.setattr(screen_module, "sample_symbol", planted(
        screen_module.sample_symbol, "v = v + 1 if v + 1 <= hi else v - 1", "v = v + 1 if v + 1 < hi else v - 1"))
    assert status("checker.values") == "failed"


# --------------------------------------------------------------------------- checker.texts

def test_zero_matrix_advice(monkeypatch):
    # mutant mutation:292 (sign, uncovered before): `"it is a zero matrix: " - _SIDES` (a TypeError)
    monkeypatch.setattr(mutation, "why_no_mutants", planted(
        mutation.why_no_mutants, '"it is a zero matrix: " + _SIDES', '"it is a zero matrix: " - _SIDES'))
    assert status("checker.texts") == "failed"


def test_convention_words_swapped(monkeypatch):
    # mutant mutation:143 (branch): a branch symbol described as a sign convention and a square root as a branch
    # convention (the same expressions).  OPERATORS holds the function itself, so its code is swapped in place
    new = planted(mutation._convention, "if isinstance(e, sp.Symbol):", "if not (isinstance(e, sp.Symbol)):")
    monkeypatch.setattr(mutation._convention, "__code__", new.__code__)
    assert status("checker.texts") == "failed"


def test_summary_of_the_other_verdicts(monkeypatch):
    # mutant identity:142 (compare, uncovered before): every verdict but "proved" summarised as "proved by ..."
    monkeypatch.setattr(identity.IdentityResult, "summary", planted(
        identity.IdentityResult.summary, 'if self.status == "proved":', 'if self.status != "proved":'))
    assert status("checker.texts") == "failed"


def test_counterexample_ellipsis_inverted(monkeypatch):
    # mutant identity:104 (branch, uncovered before): ", ..." after a short counterexample, not after a long one
    monkeypatch.setattr(identity, "_point_text", planted(
        identity._point_text, '(", ..." if len(items) > limit else "")',
        '(", ..." if not (len(items) > limit) else "")'))
    assert status("checker.texts") == "failed"


def test_eq_with_the_default_right_hand_side_refused(monkeypatch):
    # mutant identity:393 (constant, uncovered before): `rhs == 1`: an Eq alone (rhs 0 by default) is refused
    monkeypatch.setattr(identity, "check_identity", planted(
        identity.check_identity, "isinstance(rhs, (int, float)) and rhs == 0)",
        "isinstance(rhs, (int, float)) and rhs == 1)"))
    assert status("checker.texts") == "failed"


# --------------------------------------------------------------------------- killed by tests: screen:162

def _returns(func) -> list[str]:
    tree = ast.parse(textwrap.dedent(inspect.getsource(func)))
    return [ast.unparse(n.value) for n in ast.walk(tree) if isinstance(n, ast.Return) and n.value is not None]


def _assigned(func, name: str) -> list[str]:
    """The right-hand sides of every assignment (plain, augmented, tuple) to ``name`` in ``func``."""
    out = []
    for n in ast.walk(ast.parse(textwrap.dedent(inspect.getsource(func)))):
        if isinstance(n, (ast.Assign, ast.AugAssign)):
            targets = n.targets if isinstance(n, ast.Assign) else [n.target]
            for t in targets:
                names = [e.id for e in (t.elts if isinstance(t, ast.Tuple) else [t]) if isinstance(e, ast.Name)]
                if name in names:
                    out.append(("+= " if isinstance(n, ast.AugAssign) else "") + ast.unparse(n.value))
    return out


def test_quadrature_error_recorded_at_the_working_precision(monkeypatch):
    # screen:162 (abs), killed by tests: `log.append((abs(value), abs(err)))` -> `(abs(value), err)`.  Not seen by
    # verify, because the sign never matters: mpmath.quad(..., error=True)'s estimate (mpmath 1.3,
    # calculus/quadrature.py) is built only from estimate_error's returns -- abs(I_2 - I_1), ctx.zero,
    # epsilon = ctx.eps/8 > 0 or ctx.mpf(10)**int(D4) > 0 -- summed from ctx.zero over the subintervals and returned
    # unchanged, so err >= 0 (checked below on the source).  What abs does change is the precision: quad computes at
    # 20 guard bits above the working precision, and abs rounds its result to the working precision (digits + 10 in
    # the screen).  _quad_error rounds again when it sums and divides, so the mutant moves a side's error by at most
    # an ulp at digits + 10 digits -- below every threshold the screen compares it with unless tied there.  The
    # documented rule (tracked_quad's docstring) is that the recorded pair is at the working precision; this test
    # checks it, and checks that the mutant breaks it
    from mpmath.calculus.quadrature import QuadratureMethods, QuadratureRule

    assert sorted(_returns(QuadratureRule.estimate_error)) == sorted(
        ["abs(results[0] - results[1])", "self.ctx.zero", "epsilon", "self.ctx.mpf(10) ** int(D4)"])
    assert _assigned(QuadratureRule.summation, "err") == ["ctx.zero", "self.estimate_error(results, prec, epsilon)"]
    assert _assigned(QuadratureRule.summation, "total_err") == ["ctx.zero", "+= err"]
    assert _returns(QuadratureRule.summation) == ["(I, total_err)"]
    quad_err = _assigned(QuadratureMethods.quad, "err")
    assert quad_err and all(rhs.startswith("rule.summation(") for rhs in quad_err)
    assert _assigned(QuadratureMethods.quad, "epsilon") == ["ctx.eps / 8"]
    assert "(+v, err)" in _returns(QuadratureMethods.quad)

    cases = [(lambda t: t ** 2, (0, 1)), (lambda t: mpmath.sign(t - mpmath.mpf(1) / 3), (0, 1)),
             (lambda t: mpmath.exp(1j * t), (0, 3)),
             (lambda t: mpmath.exp(-t), (0, mpmath.inf))]

    def recorded(quad) -> list[tuple[object, object]]:
        got = []
        for dps in (15, 30):
            with mpmath.workdps(dps):
                for f, iv in cases:
                    screen_module._QUAD_LOG.errors = []
                    try:
                        quad(f, iv)
                        got += [(pair, mpmath.mp.prec) for pair in screen_module._QUAD_LOG.errors]
                    finally:
                        screen_module._QUAD_LOG.errors = None
        return got

    def at_working_precision(pairs) -> bool:
        return all(v >= 0 and e >= 0 and v._mpf_[3] <= prec and e._mpf_[3] <= prec for (v, e), prec in pairs)

    pairs = recorded(screen_module.tracked_quad)
    assert len(pairs) == 2 * len(cases) and at_working_precision(pairs)
    assert any(e > 0 for (_v, e), _p in pairs)
    mutated = planted(screen_module.tracked_quad, "log.append((abs(value), abs(err)))",
                      "log.append((abs(value), err))")
    assert not at_working_precision(recorded(mutated))
    # and the mutated screen decides alike where an error is recorded (the claim's unconverged quadratures)
    t = sp.Symbol("t", positive=True)
    side = sp.Integral(sp.sign(t - sp.Rational(1, 3)), (t, 0, 1))
    want = decider.decide(side, side.subs(t, sp.Symbol("s", positive=True)), exact=False, digits=12, points=1)
    monkeypatch.setattr(lambdify, "_MEMO", OrderedDict())     # the screen's functions built afresh, on the mutant
    monkeypatch.setitem(screen_module._NAMESPACE, "quad", mutated)
    got = decider.decide(side, side.subs(t, sp.Symbol("s", positive=True)), exact=False, digits=12, points=1)
    assert (got.verdict, got.residual, got.error, got.digits) == (want.verdict, want.residual, want.error, want.digits)
    assert math.isfinite(want.error) and want.error > 0


# --------------------------------------------------------------------------- a bug found on the way

@pytest.mark.parametrize("args", [(sp.Eq(sp.Symbol("x"), sp.Symbol("x")),), (sp.Eq(1, 2),), (sp.Symbol("x"), True)])
def test_an_evaluated_eq_is_a_type_error_naming_the_argument(args):
    # SymPy evaluates Eq(x, x) to True (and Eq(1, 2) to False) before check_identity sees it; that was passed on
    # to decide, which raised SymPy's "BooleanAtom not allowed in this context" -- a TypeError that did not say
    # which argument was wrong, as check_identity's docstring promises
    with pytest.raises(TypeError, match=r"check_identity: (lhs|rhs) is (True|False), not an expression"):
        identity.check_identity(*args)
