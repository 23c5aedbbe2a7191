"""What the numeric screen measures a difference against (``symbt.proof.screen._scale``): the sides' own size,
with a floor ``min(1, m)`` from the size of their terms (``symbt.proof.magnitude``) -- no absolute floor."""
from __future__ import annotations

import mpmath
import pytest
import sympy as sp

from symbt.proof import decide, solves_ode
from symbt.proof import screen as screen_module
from symbt.proof.lambdify import plain_lambdify
from symbt.proof.magnitude import magnitude
from symbt.proof.screen import screen

x = sp.Symbol("x", real=True)
pos = sp.Symbol("p", positive=True)

#: (lhs, rhs, status): statements with no cancellation, true and false by a relative 1e-20 and 1/2
STATEMENTS = [
    (sp.sin(2 * x), 2 * sp.sin(x) * sp.cos(x), "verified"),
    (sp.exp(pos) * sp.exp(-2 * pos), sp.exp(-pos), "verified"),
    (sp.sin(x), sp.sin(x) * (1 + sp.Integer(10) ** -20), "false"),
    (sp.besselj(0, pos), 2 * sp.besselj(0, pos), "false"),
]


@pytest.mark.parametrize("lhs, rhs, status", STATEMENTS)
@pytest.mark.parametrize("k", [-45, 0, 45])
def test_a_statement_times_a_power_of_ten_has_the_same_verdict(lhs, rhs, status, k):
    # the old floor 1 made the test absolute below 1: at 1e-45 every one of these was "verified"
    factor = sp.Integer(10) ** k
    r = screen(factor * lhs, factor * rhs, {}, 30, 4, 3, {})
    assert r.status == status
    if status == "false":
        unscaled = screen(lhs, rhs, {}, 30, 4, 3, {})
        assert r.residual == pytest.approx(unscaled.residual, rel=1e-9)


def test_tiny_sides_are_judged_at_their_size():
    v = decide(sp.Integer(10) ** -50 * sp.sin(x), 2 * sp.Integer(10) ** -50 * sp.sin(x), exact=False)
    assert (v.verdict, v.residual) == ("false", pytest.approx(0.5))


def test_tiny_ode_solution_is_judged_at_its_size():
    t = sp.Symbol("t")
    X = sp.Function("x")
    wrong = solves_ode(sp.Eq(X(t).diff(t), -X(t)), sp.Integer(10) ** -30 * sp.exp(t), exact=False)
    right = solves_ode(sp.Eq(X(t).diff(t), -X(t)), sp.Integer(10) ** -30 * sp.exp(-t), exact=False)
    assert (wrong.verdict, right.verdict) == ("false", "verified")


def test_a_sum_that_is_zero_is_judged_against_its_terms():
    # rounding where the terms cancel is no residual of size 1; a product of such a sum keeps its factor's size
    for e in (sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1, sp.exp(x) * (sp.cosh(x) ** 2 - sp.sinh(x) ** 2 - 1)):
        assert decide(e, exact=False).verdict == "verified"
    assert decide(sp.cosh(x) ** 2 - sp.sinh(x) ** 2 - 1 - sp.Integer(10) ** -20, exact=False).verdict == "false"


def test_magnitude_rules():
    # at a = 2, b = -3: a sum's largest term, a product's factors' sizes multiplied, a power of a sum's size, and a
    # negative power its own modulus; complex values have their modulus
    a, b = sp.symbols("a b", real=True)
    cases = [(a + b, 3), (a * (a - b), 2 * 3), ((a - b) ** 2, 9), (1 / (a - b), 0.2), (a ** 2, 4)]
    for e, want in cases:
        f = plain_lambdify([a, b], magnitude(e), "mpmath")
        assert float(f(mpmath.mpf(2), mpmath.mpf(-3))) == pytest.approx(want, rel=1e-15), e
    # a real symbol's sample can be complex (a relation's root): |a|^2 stays a modulus, never a^2 = -1
    assert plain_lambdify([a, b], magnitude(a ** 2), "mpmath")(mpmath.mpc(0, 1), 0) == 1


@pytest.mark.parametrize("bad", [lambda *v: [1 / mpmath.mpf(0)], lambda *v: [mpmath.nan], lambda *v: [mpmath.inf]])
def test_a_size_that_cannot_be_evaluated_is_infinite(bad):
    # the floor is then min(1, inf) = 1, the most lenient, never a scale below what the terms warrant
    size = screen_module._sizer(bad, [mpmath.mpf(1)])()
    assert size == mpmath.inf
    assert screen_module._scale(mpmath.mpf("1e-5"), 0, lambda: size) == 1


def test_an_ode_size_that_cannot_be_evaluated_gives_the_floor_one():
    # the terms' size raising (a factor with a pole where the product has none): the floor is 1, never smaller
    from symbt.proof.ode import ode_residual

    t = sp.Symbol("t")
    X = sp.Function("x")
    r = ode_residual(sp.Eq(X(t).diff(t), -X(t)), sp.Integer(10) ** -30 * sp.exp(t))
    with mpmath.workdps(30):
        assert r(t=mpmath.mpf(1)) == 2                       # its own size: terms 1e-30 e, sum 2e-30 e
        r._sizes = [lambda *args: [1 / mpmath.mpf(0)]]
        got = r(t=mpmath.mpf(1))                             # the floor 1: an absolute residual, not a crash
        assert abs(got - 2 * mpmath.mpf(10) ** -30 * mpmath.e) <= 1e-58
