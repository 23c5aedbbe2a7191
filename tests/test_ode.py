"""solves_ode: exact proofs, sampled transcendental solutions, wrong solutions, and branch scopes.

Where a verdict depends on the points, the test re-evaluates the ODE at those points in plain
mpmath/float code (derivatives written out by hand) and compares.
"""
import math

import mpmath as mp
import pytest
import sympy as sp

from symbt import Domain, choice, from_decision, judge, ode_residual, sign, solves_ode
from symbt.proof.cells import DEEP_PER_CELL, DEFAULT_PER_CELL

t, t0, K, C, k = sp.symbols("t t0 K C k")
x, y = sp.Function("x"), sp.Function("y")
LOGISTIC = sp.Eq(x(t).diff(t), x(t) * (1 - x(t) / K))
SQRT_ODE = sp.Eq(x(t).diff(t), sp.sqrt(x(t)))          # x' = sqrt(x): x = (t - t0)^2/4 only after t0
BRANCH_DOMAIN = Domain({"t": (-2, 2), "t0": (-1, 1)}, seed=4)


def test_the_logistic_solution_is_proved_exactly():
    v = solves_ode(LOGISTIC, K / (1 + C * sp.exp(-t)))
    assert (v.verdict, v.evidence, v.residual, v.cells) == ("proved", "proof", 0.0, [])
    assert v.method.startswith("exact:")


def test_a_transcendental_solution_is_sampled_in_every_cell():
    # t x'' + x' + t x = 0 (Bessel, order 0): no exact route, so residuals at 30 digits
    v = solves_ode(t * x(t).diff(t, 2) + x(t).diff(t) + t * x(t), sp.besselj(0, t),
                   domain=Domain({"t": (0.5, 20)}), splits=[sign("t - 10")])
    assert (v.verdict, v.evidence) == ("verified", "sampled")
    assert [c["n"] for c in v.cells] == [DEFAULT_PER_CELL] * 2
    assert v.digits >= 20 and "30 digits" in v.method and "exact layer does not apply" in v.method
    # and Y_0 is a solution too, J_1 is not
    assert solves_ode(t * x(t).diff(t, 2) + x(t).diff(t) + t * x(t), sp.bessely(0, t)).holds
    assert not solves_ode(t * x(t).diff(t, 2) + x(t).diff(t) + t * x(t), sp.besselj(1, t)).holds


def test_a_wrong_solution_is_false_with_a_counterexample_that_really_fails():
    v = solves_ode(sp.Eq(x(t).diff(t), x(t) * (1 - x(t))), 1 / (1 + sp.exp(t)))   # sign of t flipped
    assert (v.verdict, v.evidence, v.definite) == ("false", "proof", True)
    tc = float(v.counterexample["t"])
    xv = 1 / (1 + math.exp(tc))
    dx = -math.exp(tc) / (1 + math.exp(tc)) ** 2                      # by hand
    assert abs(dx - xv * (1 - xv)) > 1e-3
    assert v.note.startswith("exactly false")


def test_a_sampled_wrong_solution_is_false_with_a_counterexample():
    v = solves_ode(t * x(t).diff(t, 2) + x(t).diff(t) + t * x(t), sp.besselj(0, 2 * t))
    assert (v.verdict, v.evidence, v.definite) == ("false", "sampled", False)
    tc = mp.mpf(v.counterexample["t"])
    j0, j1 = mp.besselj(0, 2 * tc), mp.besselj(1, 2 * tc)
    # x = J0(2t): x' = -2 J1(2t), x'' = -4 J0(2t) + 2 J1(2t)/t
    assert abs(tc * (-4 * j0 + 2 * j1 / tc) - 2 * j1 + tc * j0) > 1e-3


def test_a_square_root_branch_solution_holds_in_one_cell_only():
    v = solves_ode(SQRT_ODE, (t - t0) ** 2 / 4, domain=BRANCH_DOMAIN, splits=[sign("t - t0")])
    assert (v.verdict, v.evidence) == ("false", "sampled")
    assert v.note == "printed statement holds exactly in cells {t>t0} and fails in {t<t0}"
    assert v.counterexample["cell"] == "{t<t0}"
    # independent: x' = (t - t0)/2 and sqrt(x) = |t - t0|/2, equal iff t > t0, at the same points
    truth: dict[bool, list[bool]] = {}
    for _cell, p in BRANCH_DOMAIN.sample(sign("t - t0")):
        d = float(p["t"]) - float(p["t0"])
        truth.setdefault(d > 0, []).append(math.isclose(d / 2, math.sqrt(d * d / 4), rel_tol=1e-12))
    assert all(truth[True]) and not any(truth[False])
    assert [(c["cell"], c["printed_holds"]) for c in v.cells] == [({"sign(t - t0)": "t<t0"}, 0),
                                                                ({"sign(t - t0)": "t>t0"}, DEFAULT_PER_CELL)]


def test_the_branch_with_a_correction_is_an_erratum_with_scope():
    corrected = sp.Piecewise((0, t < t0), ((t - t0) ** 2 / 4, True))      # rests at 0 until t0
    table = BRANCH_DOMAIN.evaluate(sign("t - t0"), printed=ode_residual(SQRT_ODE, (t - t0) ** 2 / 4),
                                   corrected=ode_residual(SQRT_ODE, corrected))
    out = judge(table, printed="x = (t - t0)^2/4", corrected="x = max(0, t - t0)^2/4")
    assert (out.status, out.evidence) == ("erratum", "sampled")
    assert out.scope == ("printed statement holds exactly in cells {t>t0} and fails in {t<t0}; "
                         "corrected statement holds in all 2 cells")


def test_systems_as_a_tuple_or_a_dict_and_choices_reach_the_residual():
    ode = [sp.Eq(x(t).diff(t), k * y(t)), sp.Eq(y(t).diff(t), -k * x(t))]
    assert solves_ode(ode, (sp.sin(k * t), sp.cos(k * t))).holds
    assert solves_ode(ode, {y: sp.cos(k * t), x: sp.sin(k * t)}).holds
    assert solves_ode(ode, [sp.Eq(x(t), sp.sin(k * t)), sp.Eq(y(t), sp.cos(k * t))]).holds
    wrong = solves_ode(ode, (sp.sin(k * t), -sp.cos(k * t)))
    assert not wrong.holds
    # a branch choice as a parameter: x = b sqrt(t) solves 2 x x' = 1 for both b
    b = sp.Symbol("b")
    # (the residual b**2 - 1 is a nonzero rational function, yet zero at both values of the choice)
    v = solves_ode(2 * x(t) * x(t).diff(t) - 1, b * sp.sqrt(t), domain=Domain({"t": (0.1, 3)}),
                   splits=[choice("b", (1, -1))])
    assert v.holds and [c["cell"] for c in v.cells] == [{"b": 1}, {"b": -1}]
    v = solves_ode(2 * x(t) * x(t).diff(t) - 1, b * sp.sqrt(t), domain=Domain({"t": (0.1, 3)}),
                   splits=[choice("b", (1, 2))])
    assert (v.verdict, v.evidence, v.counterexample["cell"]) == ("false", "sampled", "{b=+2}")
    # likewise an integer parameter: n**2 - 1 vanishes at n = 1 only
    n = sp.Symbol("n")
    v = solves_ode(2 * x(t) * x(t).diff(t) - 1, n * sp.sqrt(t), domain=Domain({"t": (0.1, 3), "n": range(1, 2)}))
    assert v.holds


def test_deep_gives_64_points_per_cell():
    v = solves_ode(SQRT_ODE, (t - t0) ** 2 / 4, domain=BRANCH_DOMAIN, splits=[sign("t - t0")], deep=True)
    assert [c["n"] for c in v.cells] == [DEEP_PER_CELL] * 2 == [64, 64]


def test_verdicts_become_outcomes():
    assert from_decision(solves_ode(LOGISTIC, K / (1 + C * sp.exp(-t)))).status == "verified"
    out = judge(solves_ode(SQRT_ODE, (t - t0) ** 2 / 4, domain=BRANCH_DOMAIN, splits=[sign("t - t0")]),
                printed="x = (t - t0)^2/4")
    assert (out.status, out.evidence, len(out.cells)) == ("failed", "sampled", 2)


@pytest.mark.parametrize("ode, solution, kw, match", [
    (sp.Eq(t, 1), t, {}, "no unknown function"),
    (sp.Eq(x(t).diff(t), x(k)), t, {}, "one and the same variable"),
    (LOGISTIC, {y: t}, {}, "not an unknown"),
    ([sp.Eq(x(t).diff(t), y(t)), sp.Eq(y(t).diff(t), x(t))], t, {}, "2 unknowns"),
    ([sp.Eq(x(t).diff(t), y(t)), sp.Eq(y(t).diff(t), x(t))], {x: t}, {}, "no closed form for y"),
    (LOGISTIC, x(t), {}, "must not contain the unknowns"),
    (SQRT_ODE, (t - t0) ** 2 / 4, {"domain": Domain({"t": (0, 1)})}, "the domain lacks t0"),
    ([], t, {}, "no equation"),
])
def test_bad_input_raises_value_error(ode, solution, kw, match):
    with pytest.raises(ValueError, match=match):
        solves_ode(ode, solution, **kw)
