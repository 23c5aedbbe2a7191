"""The exact layer's two routes (SymPy's together/cancel/rem and FLINT's fmpq_mpoly) decide alike."""
import importlib.util
import random

import pytest
import sympy as sp

from symbt.proof.exact import exact_route, exact_zero

HAVE_FLINT = importlib.util.find_spec("flint") is not None
needs_flint = pytest.mark.skipif(not HAVE_FLINT, reason="needs the optional dependency 'flint'")

x, y, z, w, mu = sp.symbols("x y z w mu")
eta, beta, B, C = sp.symbols("eta beta B C")
E1, E2 = sp.symbols("E1 E2", positive=True)
q1, q2 = sp.symbols("q1 q2", real=True)


def _random_rational(rng: random.Random, depth: int = 3) -> sp.Expr:
    """A random expression of +, *, / and small integer powers over x, y, z, I and rationals."""
    if depth == 0:
        return rng.choice([x, y, z, sp.I, sp.Rational(rng.randint(-5, 5), rng.randint(1, 4))])
    a, b = _random_rational(rng, depth - 1), _random_rational(rng, depth - 1)
    op = rng.choice("+-*/^")
    if op == "/" and b == 0:
        op = "*"
    return {"+": a + b, "-": a - b, "*": a * b, "/": a / b if b != 0 else a,
            "^": a ** rng.choice([-2, -1, 2, 3]) if a != 0 else a}[op]


def _both(diff, relations=None):
    relations = relations or {}
    return exact_zero(diff, relations, "flint"), exact_zero(diff, relations, "sympy")


@needs_flint
def test_routes_agree_on_random_identities_and_perturbations():
    rng = random.Random(20261123)
    for _ in range(60):
        e = _random_rational(rng)
        # the same function written differently: one fraction, numerator and denominator expanded
        n, d = sp.fraction(sp.together(e))
        same = sp.expand(n) / sp.expand(d)
        for diff, want in ((e - same, True), (e - same + w / (x + 7), False)):
            (zf, mf, df), (zs, ms, ds) = _both(diff)
            assert zf == zs == want, diff
            assert df == ds and "fmpq_mpoly" in mf and "cancel" in ms


@needs_flint
def test_routes_agree_modulo_relations():
    monic = {eta: eta ** 2 - mu ** 2 - w}
    lead = {beta: B * beta ** 2 - C - beta}                  # leading coefficient B, not a number
    chain = {y: y - x ** 2, z: z ** 2 - y}                    # relations building on each other
    cases = [
        ((eta - mu) * (eta + mu) - w, monic, True),
        ((eta - mu) ** 3 * (eta + mu) ** 3 - w ** 3, monic, True),
        ((eta - mu) ** 2 - w, monic, False),
        (beta ** 3 - (C + beta * (B * C + 1)) / B ** 2, lead, True),
        (beta ** 3 - (C + beta * (B * C + 2)) / B ** 2, lead, False),
        (z ** 4 - x ** 4, chain, True),
        (z ** 4 - x ** 3, chain, False),
        (1 / (eta + mu) - (eta - mu) / w, monic, True),
    ]
    for diff, rel, want in cases:
        (zf, _, df), (zs, _, ds) = _both(diff, rel)
        assert zf == zs == want, diff
        assert df is ds is False                          # with relations, nonzero is not a proof of falsity


@needs_flint
def test_exponential_monomials_and_a_claim_shape():
    # hyperbolic functions become monomials in exp(q_j)
    (zf, mf, _), (zs, _, _) = _both(sp.cosh(q1 - q2) ** 2 - sp.sinh(q1 - q2) ** 2 - 1)
    assert zf and zs and "exp->monomials" in mf
    (zf, _, df), (zs, _, ds) = _both(sp.sinh(q1) ** 2 - sp.cosh(q1) ** 2 + 2)
    assert zf is zs is False and df is ds is True


def test_route_selection():
    assert exact_route("sympy") == "sympy"
    if HAVE_FLINT:
        assert exact_route("flint") == "flint" and exact_route("auto") in ("flint", "sympy")
    else:
        assert exact_route("auto") == "sympy"
        with pytest.raises(ImportError, match="symbt\\[certified\\]"):
            exact_route("flint")
    with pytest.raises(ValueError):
        exact_route("maple")


@needs_flint
def test_not_rational_is_left_to_the_screen():
    assert exact_zero(sp.log(x) - sp.log(x), {}, "flint")[0] is not None     # SymPy folds it to 0
    assert exact_zero(sp.sqrt(x) ** 3 - x * sp.sqrt(x), {}, "flint")[0] is not None
    assert exact_zero(sp.acosh(x) - y, {}, "flint")[0] is None


def test_sympy_route_reads_an_unevaluated_zero_as_zero():
    # SymPy 1.14: cancel(together(d)) returns the unevaluated sum -1/4 + 1/4 for this d; the SymPy route
    # once read that as a nonzero rational function, i.e. "exactly false"
    d = -4 * x ** 2 + 2 * x + (2 * x - sp.Rational(1, 2)) ** 2 - sp.Rational(1, 4)
    assert exact_zero(d, {}, "sympy")[0] is True
    if HAVE_FLINT:
        assert exact_zero(d, {}, "flint")[0] is True
