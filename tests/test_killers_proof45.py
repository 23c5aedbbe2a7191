"""The claims of ``symbt/claims/checker_sample45.py`` kill the survivors of seeds 4 and 5's samples in
``symbt.proof``; two ties of the screen are killed by tests here, and ``verdict:132`` is shown equivalent
(issue 21, item 4; docs/mutation.md).

Each killer test plants the mutant's own text -- one single-point bug of ``symbt mutate --source``'s kind, with
:func:`planting.planted` (a function) or :func:`planting.mutated` (a module copy, for class fields and operator
tables) -- where the claim reads it from, and requires the claim to fail; unpatched, every claim verifies.
"""
from __future__ import annotations

import ast
import inspect
import itertools
import math
import textwrap
from collections import OrderedDict

import mpmath
import pytest
import sympy as sp
from planting import mutated, planted

from symbt.claims import REGISTRY, load_all
from symbt.proof import decider, domain, identity, lambdify, mutation, ode, ranges, verdict
from symbt.proof import screen as screen_module

load_all()

CLAIMS = ["checker.screen_numbers", "checker.identity_inputs", "checker.value_words"]


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.fixture
def fresh_memo(monkeypatch):
    # the lambdified functions built afresh (a memoised one would skip a planted line)
    monkeypatch.setattr(lambdify, "_MEMO", OrderedDict())


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- checker.screen_numbers

SCREEN = [   # (seed:line, old, new): planted into symbt.proof.screen.screen, seen through decide
    ("screen:326", "tol = mpmath.mpf(10) ** (-(digits - 8))", "tol = mpmath.mpf(10) ** (-(digits + 8))"),
    ("screen:330", "attempts < 6 * points + 10", "attempts < points + 10"),
]


@pytest.mark.parametrize("where, old, new", SCREEN, ids=[s[0] for s in SCREEN])
def test_screen_numbers_kill_screen_mutants(monkeypatch, fresh_memo, where, old, new):
    monkeypatch.setattr(decider, "screen", planted(screen_module.screen, old, new))
    assert status("checker.screen_numbers") == "failed"


def test_rounding_floor_subtracted(monkeypatch, fresh_memo):
    # mutant screen:275: a re-evaluated point's error loses the rounding level 10^-(d+2) instead of adding it
    monkeypatch.setattr(screen_module, "_recheck", planted(
        screen_module._recheck, "(el + er) / scale + mpmath.mpf(10)", "(el + er) / scale - mpmath.mpf(10)"))
    assert status("checker.screen_numbers") == "failed"


def test_trusted_digits_clamped_to_zero(monkeypatch, fresh_memo):
    # mutant screen:388: max(0, ...) -> min(0, ...): a verified screen reports 0 trusted digits
    monkeypatch.setattr(screen_module, "_trusted_digits", planted(
        screen_module._trusted_digits, "return max(0.0, min(", "return min(0.0, min("))
    assert status("checker.screen_numbers") == "failed"


def test_negative_integers_may_be_zero(monkeypatch):
    # mutant screen:35: a negative integer symbol drawn from -9..0
    monkeypatch.setattr(screen_module, "sample_symbol", planted(
        screen_module.sample_symbol, "lo, hi = -9, -1", "lo, hi = -9, -0"))
    assert status("checker.screen_numbers") == "failed"


def test_inconclusive_note_names_a_wrong_tolerance(monkeypatch, fresh_memo):
    # mutant decider:157: the note of an inconclusive verdict computes the tolerance 10^+(d-8)
    monkeypatch.setattr(decider, "_cannot_tell", planted(
        decider._cannot_tell, "tol = 10.0 ** (-(digits - 8))", "tol = 10.0 ** (digits - 8)"))
    assert status("checker.screen_numbers") == "failed"


# --------------------------------------------------------------------------- ties of the screen (killed by tests)

x = sp.Symbol("x", real=True)


def _recheck_to(residual, error):
    def stub(pc, *args, **kwargs):     # the re-evaluation, replaced by one with the given numbers
        pc.rechecked = True
        pc.residual, pc.error = residual(), error()
    return stub


@pytest.mark.parametrize("mutant, old, new, values, want, planted_want", [
    # screen:359 (first compare): a residual exactly at the tolerance holds (as in Verdict.sampled, r <= tol)
    ("residual >= tol", "return bool(pc.residual > tol and", "return bool(pc.residual >= tol and",
     (lambda: mpmath.mpf(10) ** (-(30 - 8)), lambda: mpmath.mpf(0)), "verified", "false"),
    # screen:359 (second compare): a residual exactly SAFETY times its error is no counterexample: inconclusive
    ("residual >= SAFETY * error", "and pc.residual > SAFETY * pc.error)", "and pc.residual >= SAFETY * pc.error)",
     (lambda: 10 * mpmath.mpf(2) ** -20, lambda: mpmath.mpf(2) ** -20), "inconclusive", "false"),
    # screen:385 (seed 8): an error exactly at the tolerance, the residual 0, is trusted (r, e <= tol): verified
    ("error < tol", "if not (pc.residual <= tol and pc.error <= tol):",
     "if not (pc.residual <= tol and pc.error < tol):",
     (lambda: mpmath.mpf(0), lambda: mpmath.mpf(10) ** (-(30 - 8))), "verified", "inconclusive"),
])
def test_screen_ties_are_not_counterexamples(monkeypatch, fresh_memo, mutant, old, new, values, want,
                                             planted_want):
    # the tolerance is computed at the ambient precision (outside the working-precision block), as is the stub's
    assert mpmath.mp.dps == 15
    monkeypatch.setattr(screen_module, "_recheck", _recheck_to(*values))
    r, e = values[0](), values[1]()
    assert mpmath.mpf(10) ** -22 in (r, e) or r == verdict.SAFETY * e      # an exact tie, as the mutant needs
    assert decider.decide(x, -x, exact=False, digits=30, points=1).verdict == want
    monkeypatch.setattr(decider, "screen", planted(screen_module.screen, old, new))
    assert decider.decide(x, -x, exact=False, digits=30, points=1).verdict == planted_want


# --------------------------------------------------------------------------- checker.identity_inputs

IDENTITY = [   # (seed:line, function, old, new)
    ("identity:243", "apply_assumptions", "lookup[name] != old", "lookup[name] == old"),
    ("identity:270", "_pick_symbol", "    if not syms:\n", "    if syms:\n"),
    ("identity:274", "_pick_symbol", "if degs[s] == top]", "if degs[s + 1] == top]"),
    ("identity:275", "_pick_symbol", "if len(best) > 1:", "if not (len(best) > 1):"),
    ("identity:404", "match_shapes", "if lm and not rm and rhs == 0:",     # now decider's match_shapes
     "if not (lm and not rm and rhs == 0):"),
    ("identity:408", "check_identity", "    if assumptions:\n        rel_exprs", "    if not (assumptions):\n"
                                                                                "        rel_exprs"),
]


@pytest.mark.parametrize("where, name, old, new", IDENTITY, ids=[s[0] for s in IDENTITY])
def test_identity_inputs_kill_identity_mutants(monkeypatch, where, name, old, new):
    monkeypatch.setattr(identity, name, planted(getattr(identity, name), old, new))
    assert status("checker.identity_inputs") == "failed"


def test_inconclusive_display_without_its_error(monkeypatch, fresh_memo):
    # mutant identity:177 (uncovered before): the HTML of an inconclusive result says "unknown" for a known error
    monkeypatch.setattr(identity.IdentityResult, "_repr_html_", planted(
        identity.IdentityResult._repr_html_, 'err = "unknown" if self.error is None else',
        'err = "unknown" if not (self.error is None) else'))
    assert status("checker.identity_inputs") == "failed"


def test_undefined_side_not_undefined(monkeypatch):
    # mutant decider:79 (uncovered before): a side with nan or zoo is not recognised as undefined
    monkeypatch.setattr(decider, "_undefined", planted(decider._undefined, "return True", "return False"))
    assert status("checker.identity_inputs") == "failed"


@pytest.mark.parametrize("where, old, new", [
    ("lambdify:41", "if isinstance(e, sp.MatrixBase):", "if not (isinstance(e, sp.MatrixBase)):"),
])
def test_plain_of_a_nested_list(monkeypatch, fresh_memo, where, old, new):
    monkeypatch.setattr(lambdify, "_plain", planted(lambdify._plain, old, new))
    assert status("checker.identity_inputs") == "failed"


def test_memo_evicting_everything(monkeypatch, fresh_memo):
    # mutant lambdify:62: the memo drops every entry it has just stored -- the same call builds a new function
    monkeypatch.setattr(lambdify, "plain_lambdify", planted(
        lambdify.plain_lambdify, "if len(_MEMO) > MAX_ENTRIES:", "if not (len(_MEMO) > MAX_ENTRIES):"))
    assert status("checker.identity_inputs") == "failed"


def test_ode_falsity_not_definite(monkeypatch):
    # mutant ode:218: a residual that is a nonzero rational function is false by proof but not "definitely"
    monkeypatch.setattr(ode, "solves_ode", planted(
        ode.solves_ode, "cells=sampled.cells, definite=True,", "cells=sampled.cells, definite=False,"))
    assert status("checker.identity_inputs") == "failed"


# --------------------------------------------------------------------------- checker.value_words

def test_range_with_any_step(monkeypatch):
    # mutant ranges:108 (uncovered before): a range is refused when its step is 1 and accepted otherwise
    monkeypatch.setattr(ranges, "as_range", planted(ranges.as_range, "if spec.step != 1 or", "if spec.step == 1 or"))
    assert status("checker.value_words") == "failed"


def test_range_one_past_its_end(monkeypatch):
    # mutant ranges:110 (uncovered before): range(1, 4) draws 1..4
    monkeypatch.setattr(ranges, "as_range", planted(
        ranges.as_range, "integers(spec.start, spec.stop - 1)", "integers(spec.start, spec.stop - 0)"))
    assert status("checker.value_words") == "failed"


def test_draws_outside_not_counted(monkeypatch):
    # mutant domain:363 (uncovered before): a draw rejected by `where` is not counted as outside
    monkeypatch.setattr(domain.Domain, "sample", planted(domain.Domain.sample, "outside += 1", "outside += 0"))
    assert status("checker.value_words") == "failed"


def test_split_compared_by_its_expression(monkeypatch):
    # mutant domain:155: Split's expr takes part in == and hash, so splits making the same cells differ
    copy = mutated("symbt.proof.domain", "expr: Any = field(default=None, compare=False, repr=False)",
                   "expr: Any = field(default=None, compare=True, repr=False)")
    monkeypatch.setattr(domain, "sign", copy.sign)
    assert status("checker.value_words") == "failed"


def test_point_check_shows_its_values(monkeypatch):
    # mutant screen:208: PointCheck's repr shows the raw values kept for the re-evaluation
    copy = mutated("symbt.proof.screen", "values: list[Any] = field(repr=False, default_factory=list)",
                   "values: list[Any] = field(repr=True, default_factory=list)")
    monkeypatch.setattr(screen_module, "PointCheck", copy.PointCheck)
    assert status("checker.value_words") == "failed"


def test_swap_keeps_unchanged_terms(monkeypatch):
    # mutant mutation:113 (uncovered before): the swap operator yields the terms a swap leaves unchanged
    copy = mutated("symbt.proof.mutation", "if u != t:", "if u == t:", same_classes=True)
    monkeypatch.setattr(mutation, "mutants", copy.mutants)
    assert status("checker.value_words") == "failed"


def test_tuple_entries_subtracted(monkeypatch):
    # mutant mutation:244 (uncovered before): a tuple's entry mutant built with `-` (a TypeError)
    monkeypatch.setattr(mutation, "mutate_value", planted(
        mutation.mutate_value, "value[:i] + (m.expr,) + value[i + 1:]", "value[:i] - (m.expr,) + value[i + 1:]"))
    assert status("checker.value_words") == "failed"


def test_short_text_cut(monkeypatch):
    # mutant mutation:315: short texts get '...' and long ones are shown whole
    monkeypatch.setattr(mutation, "_short", planted(mutation._short, "if len(text) <= limit", "if len(text) >= limit"))
    assert status("checker.value_words") == "failed"


# --------------------------------------------------------------------------- verdict:132 is equivalent

def _inconclusive_tests():
    """The expression of Verdict.sampled's ``inconclusive = ...`` line, and the mutant's, as functions of
    (holds, err, r, t, SAFETY)."""
    src = textwrap.dedent(inspect.getsource(verdict.Verdict.sampled.__func__))
    (line,) = [ln.strip() for ln in src.splitlines() if ln.strip().startswith("inconclusive = ")]
    expr = line[len("inconclusive = "):]
    assert expr.count("r > t and") == 1
    mutant = expr.replace("r > t and", "r >= t and")
    return [eval(compile(f"lambda holds, err, r, t, SAFETY: {e}", "verdict", "eval")) for e in (expr, mutant)]


def test_verdict_132_equivalent():
    # `(r > t and r > SAFETY * err)` -> `(r >= t and ...)`: the two differ only at r == t; there either
    # err <= t, and `holds` (r <= t and err <= t) is true, so `not holds` decides; or err > t = r >= 0, so err > 0
    # and SAFETY * err >= err > r (SAFETY = 10 >= 1), and the second conjunct is false in both.  r, err and t are
    # abs() of floats (never negative); NaN compares false in > and >= alike.
    src = inspect.getsource(verdict.Verdict.sampled.__func__)
    tree = ast.parse(textwrap.dedent(src))
    names = {n.targets[0].id: ast.unparse(n.value) for n in ast.walk(tree)
             if isinstance(n, ast.Assign) and isinstance(n.targets[0], ast.Name)}
    assert names["r"] == "_as_float(residual)" and names["t"] == "_as_float(tol)"
    assert names["err"] == "None if error is None else _as_float(error)"
    assert names["holds"] == "r <= t and (err is None or err <= t)"
    assert verdict.SAFETY >= 1
    original, mutant = _inconclusive_tests()
    values = [0.0, 1e-300, 1e-40, 1e-22, 1e-21, 0.1, 1.0, 10.0, 1e300, math.inf, math.nan]
    for r, t, e in itertools.product(values, values, [None, *values]):
        holds = r <= t and (e is None or e <= t)
        assert original(holds, e, r, t, verdict.SAFETY) == mutant(holds, e, r, t, verdict.SAFETY), (r, t, e)
    # and through the public constructor, at the ties r == t
    for t in values[:-1]:
        for e in [None, *values]:
            v = verdict.Verdict.sampled(t, tol=t, error=e)
            assert v.inconclusive == mutant(v.holds, v.error, v.residual, t, verdict.SAFETY)


# --------------------------------------------------------------------------- a bug found on the way

@pytest.mark.parametrize("call", [
    lambda d: identity.check_identity(sp.sin(x), sp.cos(x), digits=d, exact=False, points=2),
    lambda d: decider.decide(1, 0, digits=d, exact=False, points=2),
])
def test_fewer_than_nine_digits_refused(call):
    # the screen's tolerance is 10^-(d - 8): at d = 8 it was 1, and sin x = cos x (check_identity) or 1 = 0
    # (decide) came out verified; at d = 5 every statement did.  Now a ValueError naming digits; at 9, false
    for d in (1, 5, 8):
        with pytest.raises(ValueError, match="digits must be at least 9"):
            call(d)
    assert call(9).verdict == "false"
