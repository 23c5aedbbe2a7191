"""Exact proofs with exponentials of rational combinations of the coordinates, whatever their spelling.

Both exact routes (SymPy's together/cancel and FLINT's fmpq_mpoly) must decide every case alike.
"""
import importlib.util

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symbt.proof import decide
from symbt.proof.exact import exact_zero
from symbt.proof.exponentials import exponentials_as_monomials, rational_linear_form

HAVE_FLINT = importlib.util.find_spec("flint") is not None
ROUTES = ["sympy", pytest.param("flint", marks=pytest.mark.skipif(not HAVE_FLINT, reason="needs python-flint"))]

q, q1, q2, p1, p2 = sp.symbols("q q1 q2 p1 p2", real=True)
x = sp.Symbol("x")                                  # no assumptions: sampled complex
eta = sp.Symbol("eta")
half = sp.Rational(1, 2)


def uexp(u):
    """exp(u) as SymPy writes it (auto-evaluated)."""
    return sp.exp(u)


def umul(*factors):
    return sp.Mul(*factors, evaluate=False)


def upow(base, k):
    return sp.Pow(base, k, evaluate=False)


@pytest.fixture(params=ROUTES)
def route(request, monkeypatch):
    """The exact route ``decide`` uses, chosen through ``SYMBT_EXACT``."""
    monkeypatch.setenv("SYMBT_EXACT", request.param)
    return request.param


def _proved(lhs, rhs, **kw):
    d = decide(lhs, rhs, **kw)
    return d.holds and d.exact and d.evidence == "proof"


def test_toda_half_exponent_identity_is_proved(route):
    a = sp.exp((q1 - q2) / 2) + sp.exp((q2 - q1) / 2)
    d = decide(a ** 2, sp.exp(q1 - q2) + 2 + sp.exp(q2 - q1))
    assert d.holds and d.exact and d.evidence == "proof"
    assert "e^(q1/2)" in d.method and "e^(q2/2)" in d.method


def test_n2_flaschka_lax_matrix_with_half_exponents(route):
    # periodic N = 2 in Flaschka's symmetric form: the off-diagonal entry is a_1 + a_2 with a_j = e^{(q_j - q_{j+1})/2}
    a = sp.exp((q1 - q2) / 2) + sp.exp((q2 - q1) / 2)
    lax = sp.Matrix([[p1, a], [a, p2]])
    hamiltonian = (p1 ** 2 + p2 ** 2) / 2 + sp.exp(q1 - q2) + sp.exp(q2 - q1) + 2
    assert _proved((lax ** 2).trace() / 2, hamiltonian)
    assert _proved(lax.det(), p1 * p2 - sp.exp(q1 - q2) - 2 - sp.exp(q2 - q1))
    wrong = decide((lax ** 2).trace() / 2, hamiltonian - 2)       # the constant of the periodic closure dropped
    assert not wrong.holds and wrong.definite and wrong.evidence == "proof"


def test_square_roots_of_exponentials(route):
    r = upow(sp.exp(q), half)                                       # sqrt(exp(q)) kept as a power
    assert _proved((r + 1) ** 2, sp.exp(q) + 2 * sp.exp(q / 2) + 1)
    assert _proved(umul(sp.sqrt(sp.exp(q1)), sp.sqrt(sp.exp(q2))), sp.exp((q1 + q2) / 2))
    assert _proved(upow(umul(sp.exp(q1), sp.exp(q2)), half) * (1 + sp.exp(-q1)),
                   sp.exp((q1 + q2) / 2) + sp.exp((q2 - q1) / 2))


def test_mixed_denominators(route):
    assert _proved(umul(sp.exp(q / 2), sp.exp(q / 3)), sp.exp(5 * q / 6))
    assert _proved((sp.exp(q / 2) + 1) * (sp.exp(q / 3) + 1), sp.exp(5 * q / 6) + sp.exp(q / 2) + sp.exp(q / 3) + 1)
    (_rat,), variables = exponentials_as_monomials(sp.exp(q / 2) + sp.exp(q / 3) + sp.exp(q1 / 4) + sp.exp(q2))
    assert {s: d for s, (_v, d) in variables.items()} == {q: 6, q1: 4, q2: 1}


def test_near_miss_is_exactly_false(route):
    tiny = sp.Rational(1, 10 ** 30)
    for lhs, rhs in ((upow(sp.exp(q / 2), 2), sp.exp(q) + tiny),
                     ((sp.exp(q / 2) + sp.exp(-q / 2)) ** 2, sp.exp(q) + 2 + sp.exp(-q) + tiny * sp.exp(q / 3))):
        d = decide(lhs, rhs)
        assert not d.holds and d.definite and d.evidence == "proof", (lhs, rhs)
        assert "nonzero rational function" in d.note


# each pair: one exponential spelled two ways; SymPy does not fold the difference to 0 by itself
SPELLINGS = [
    (umul(sp.exp(q1 / 2), sp.exp(-q2 / 3)), sp.exp(q1 / 2 - q2 / 3)),           # exp(a)*exp(b) vs exp(a + b)
    (upow(sp.exp(x), 2), sp.exp(2 * x)),                                        # exp(x)**2 vs exp(2x), x complex
    (upow(sp.exp(x), -1), sp.exp(-x)),                                          # 1/exp(x) vs exp(-x)
    (upow(upow(sp.exp(q), half), 2), sp.exp(q)),                                # sqrt(exp(q))**2
    (upow(sp.E, q / 2), upow(sp.exp(q), half)),                                 # E**(q/2) vs (e^q)^(1/2)
    (upow(sp.exp(q), sp.Rational(1, 3)), sp.exp(q / 3)),                        # exp(q)**(1/3)
    (sp.cosh(q / 2), (sp.exp(q / 2) + sp.exp(-q / 2)) / 2),                     # hyperbolic
    (sp.tanh(q / 3), (sp.exp(2 * q / 3) - 1) / (sp.exp(2 * q / 3) + 1)),
    (sp.E * sp.exp(q), sp.exp(q + 1)),                                          # a constant in the exponent
    (umul(sp.exp(x / 2), sp.exp(x / 2)), sp.exp(x)),
]


@pytest.mark.parametrize("a, b", SPELLINGS, ids=[str(i) for i in range(len(SPELLINGS))])
def test_equivalent_spellings_are_proved_on_both_routes(a, b, route):
    for lhs, rhs in ((a, b), ((a + q1) ** 3, sp.expand((b + q1) ** 3))):
        assert lhs - rhs != 0                              # the check is not SymPy's own cancellation
        zero, method, _definite = exact_zero(lhs - rhs, {}, route)
        assert zero is True, (lhs, rhs, method)
        assert _proved(lhs, rhs)
    zero, _method, definite = exact_zero(a - b - sp.exp(q2 / 5), {}, route)
    assert zero is False and definite


def test_relations_may_involve_exponentials(route):
    # eta is a square root of e^q: (eta - e^{q/2})(eta + e^{q/2}) = eta^2 - e^q = 0 on it
    zero, _m, definite = exact_zero((eta - sp.exp(q / 2)) * (eta + sp.exp(q / 2)), {eta: eta ** 2 - sp.exp(q)}, route)
    assert zero is True and not definite


def test_not_rational_linear_exponents_are_left_to_the_screen(route):
    assert exact_zero(sp.exp(q1 * q2) - 1, {}, route)[0] is None
    assert exact_zero(sp.exp(sp.sqrt(2) * q) - 1, {}, route)[0] is None
    assert exact_zero(sp.exp(sp.I * q) - 1, {}, route)[0] is None
    # the principal square root of e^{2x} is not e^x for complex x (x = i*pi): never "proved"
    assert exact_zero(sp.sqrt(sp.exp(2 * x)) - sp.exp(x), {}, route)[0] is None
    assert exact_zero(sp.sqrt(sp.exp(x)) - sp.exp(x / 2), {}, route)[0] is None
    d = decide(sp.sqrt(sp.exp(2 * x)), sp.exp(x))
    assert not d.holds and d.evidence == "sampled"


def test_rational_linear_form():
    assert rational_linear_form(2 * (q1 - q2) / 3 - half) == {1: -half, q1: sp.Rational(2, 3), q2: sp.Rational(-2, 3)}
    assert rational_linear_form(q1 - q1) == {}
    for u in (q1 * q2, sp.sqrt(2) * q, sp.I * q, sp.pi, sp.log(q)):
        assert rational_linear_form(u) is None


# ---- property tests: random Laurent polynomials in e^{a q1 + b q2} with rational a, b

rationals = st.builds(sp.Rational, st.integers(-6, 6), st.sampled_from([1, 2, 3, 4, 6]))
coefficients = st.builds(sp.Rational, st.integers(-5, 5).filter(bool), st.integers(1, 3))
terms = st.lists(st.tuples(coefficients, rationals, rationals), min_size=1, max_size=4)


def _spell(u, how: int):
    """exp(u) for a real u, written one of six ways SymPy does not fold together."""
    if how == 0:
        return sp.exp(u)
    if how == 1:
        parts = sp.Add.make_args(u)
        return umul(*[sp.exp(t) for t in parts]) if len(parts) > 1 else sp.exp(u)
    if how == 2:
        return upow(sp.exp(u / 2), 2)
    if how == 3:
        return upow(sp.exp(2 * u), half)
    if how == 4:
        return upow(sp.E, u)
    return upow(sp.exp(-u), -1)


def _laurent(ts, spellings):
    return sp.Add(*[umul(c, _spell(a * q1 + b * q2, spellings.draw(st.integers(0, 5)))) for c, a, b in ts])


def _expanded_product(ts1, ts2):
    """The product, multiplied out on exponent vectors (no SymPy cancellation involved)."""
    acc: dict[tuple, sp.Rational] = {}
    for c1, a1, b1 in ts1:
        for c2, a2, b2 in ts2:
            key = (a1 + a2, b1 + b2)
            acc[key] = acc.get(key, 0) + c1 * c2
    return sp.Add(*[c * sp.exp(a * q1 + b * q2) for (a, b), c in acc.items() if c != 0])


@settings(max_examples=25, deadline=None)
@given(terms, terms, rationals, rationals, st.data())
def test_random_laurent_products_equal_their_expansion_on_both_routes(ts1, ts2, pa, pb, data):
    lhs = _laurent(ts1, data) * _laurent(ts2, data)
    rhs = _expanded_product(ts1, ts2)
    perturbed = rhs + sp.Rational(1, 7) * sp.exp(pa * q1 + pb * q2)
    routes = ["sympy", "flint"] if HAVE_FLINT else ["sympy"]
    for route in routes:
        assert exact_zero(lhs - rhs, {}, route)[0] is True, (lhs, rhs, route)
        zero, _m, definite = exact_zero(lhs - perturbed, {}, route)
        assert zero is False and definite, (lhs, perturbed, route)


def test_hyperbolic_functions_of_constants_are_still_rewritten():
    """With no rational-linear exponent at all, tanh/cosh of a constant still become exponentials (a proof)."""
    assert decide(sp.tanh(sp.log(199) / 2), sp.Rational(99, 100)).exact
    assert decide(sp.cosh(sp.log(3)), sp.Rational(5, 3)).exact
    wrong = decide(sp.tanh(sp.log(199) / 2), sp.Rational(98, 100))
    assert not wrong.holds and wrong.evidence == "proof"
