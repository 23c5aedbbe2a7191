"""check_identity: proved / verified numerically / false, assumptions, relations."""
from __future__ import annotations

import pytest
import sympy as sp

import symbt
from symbt.proof.identity import IdentityResult, check_identity, normalize_relations

x_real = sp.Symbol("x", real=True)
x_pos = sp.Symbol("x", positive=True)
eta, mu, w = sp.symbols("eta mu w", real=True)


# --------------------------------------------------------------------------- three outcomes

def test_proved_rational_identity_names_the_method():
    a, b = sp.symbols("a b")
    r = check_identity((a + b) ** 3, a ** 3 + 3 * a ** 2 * b + 3 * a * b ** 2 + b ** 3)
    assert r.status == "proved" and r.proved and bool(r)
    assert r.method.startswith("exact")
    from symbt.proof.exact import exact_route

    assert ("fmpq_mpoly" in r.method) == (exact_route() == "flint") != ("cancel" in r.method)
    assert r.residual == 0.0 and r.digits is None and r.points == [] and r.counterexample is None
    assert "proved" in str(r)


def test_proved_hyperbolic_identity_via_exponential_monomials():
    q1, q2 = sp.symbols("q1 q2", real=True)
    r = check_identity(4 * sp.cosh(q1 - q2) ** 2 - 4 * sp.sinh(q1 - q2) ** 2, 4)
    assert r.status == "proved" and "exp->monomials" in r.method


def test_verified_numerically_when_no_exact_reduction_applies():
    # simplify cannot decide it: it leaves the difference unsimplified ...
    lhs, rhs = sp.asinh(x_real), sp.log(x_real + sp.sqrt(x_real ** 2 + 1))
    assert sp.simplify(lhs - rhs) != 0
    # ... check_identity decides it, numerically, to the digits asked for, listing the points
    r = check_identity(lhs, rhs, digits=40, points=5)
    assert r.status == "verified" and bool(r)
    assert r.method.startswith("numeric") and "40 digits" in r.method
    assert len(r.points) == 5 and all(set(p) == {"x"} for p in r.points)
    assert r.residual < 1e-32 and r.digits >= 32
    assert "verified numerically to 40 digits at 5 random points" in str(r)


def test_false_identity_reports_a_counterexample_with_its_residual():
    a, b = sp.symbols("a b", real=True)
    r = check_identity((a + b) ** 2, a ** 2 + b ** 2)  # forgot 2ab
    assert r.status == "false" and not r
    assert set(r.counterexample) == {"a", "b"}
    # the residual is the relative residual at the counterexample
    vals = {s: sp.Float(r.counterexample[s.name], 30) for s in (a, b)}
    l, rr = ((a + b) ** 2).subs(vals), (a ** 2 + b ** 2).subs(vals)
    assert abs(abs(float((l - rr) / max(abs(l), abs(rr), 1))) - r.residual) < 1e-12
    assert "false" in str(r) and "counterexample" in str(r)


def test_false_even_if_numerically_tiny():
    a = sp.Symbol("a")
    r = check_identity(a + sp.Rational(1, 10 ** 60), a)
    assert r.status == "false" and "nonzero rational" in r.note


def test_never_silent_on_undefined_expressions():
    assert check_identity(sp.nan, 0).status == "false"
    assert check_identity(sp.zoo * x_real, 0).status == "false"


def test_poles_are_resampled_not_counted():
    n = sp.Symbol("n", integer=True, nonnegative=True)
    r = check_identity(sp.factorial(n) / n, sp.factorial(n - 1), points=6)
    assert r.status == "verified" and len(r.points) == 6


# --------------------------------------------------------------------------- assumptions

def test_real_symbol_can_be_negative():
    r = check_identity(sp.sqrt(x_real ** 2), x_real)
    assert r.status == "false"
    assert float(r.counterexample["x"]) < 0


def test_positive_symbol_makes_it_true():
    assert check_identity(sp.sqrt(x_pos ** 2), x_pos).status == "proved"


def test_assumptions_argument_replaces_symbols():
    x = sp.Symbol("x")
    assert check_identity(sp.sqrt(x ** 2), x).status == "false"          # complex x
    assert check_identity(sp.sqrt(x ** 2), x, assumptions={x: {"positive": True}}).status == "proved"
    assert check_identity(sp.sqrt(x ** 2), x, assumptions={"x": {"positive": True}}).status == "proved"
    r = check_identity(sp.sqrt(x ** 2), -x, assumptions={x: {"negative": True}})
    assert r.status == "proved"


def test_atan_sum_depends_on_the_sign():
    lhs = sp.atan(x_real) + sp.atan(1 / x_real)
    assert check_identity(lhs, sp.pi / 2).status == "false"
    assert check_identity(lhs, sp.pi / 2, assumptions={x_real: {"positive": True}}).status == "verified"


def test_complex_symbols_hit_branch_cuts():
    z = sp.Symbol("z")
    assert check_identity(sp.log(sp.exp(z)), z).status == "false"


def test_inconsistent_assumptions_are_an_error():
    with pytest.raises(ValueError, match="inconsistent"):
        check_identity(x_pos, 1, assumptions={x_pos: {"negative": True}})


# --------------------------------------------------------------------------- relations

def test_relation_decides_what_simplify_cannot():
    lhs, rhs = (eta - mu) * (eta + mu), w
    assert sp.simplify(lhs - rhs) != 0          # simplify does not know eta**2 = mu**2 + w
    r = check_identity(lhs, rhs, relations={eta: eta ** 2 - mu ** 2 - w})
    assert r.status == "proved" and "remainder mod" in r.method


@pytest.mark.parametrize("relations", [
    [sp.Eq(eta ** 2, mu ** 2 + w)],
    sp.Eq(eta ** 2, mu ** 2 + w),
    {eta: sp.Eq(eta ** 2, mu ** 2 + w)},
    [(eta, sp.Eq(eta ** 2, mu ** 2 + w))],
    [(eta, eta ** 2 - mu ** 2 - w)],
])
def test_relation_forms(relations):
    assert check_identity((eta - mu) * (eta + mu), w, relations=relations).status == "proved"


def test_relation_in_a_denominator_and_numeric_fallback():
    # 1/(eta - mu) = (eta + mu)/w on eta**2 = mu**2 + w
    r = check_identity(1 / (eta - mu), (eta + mu) / w, relations=[sp.Eq(eta ** 2, mu ** 2 + w)])
    assert r.status == "proved"
    # a log of eta: no exact layer, the numeric screen respects the relation
    r = check_identity(sp.log(eta ** 2), sp.log(mu ** 2 + w), relations=[sp.Eq(eta ** 2, mu ** 2 + w)])
    assert r.status == "verified"
    assert all("eta" in p for p in r.points)


def test_relation_false_without_it():
    assert check_identity((eta - mu) * (eta + mu), w).status == "false"
    # a wrong relation consequence is still found false
    r = check_identity((eta - mu) * (eta + mu), w + 1, relations=[sp.Eq(eta ** 2, mu ** 2 + w)])
    assert r.status == "false" and "eta" in r.counterexample


def test_chained_relations():
    e1, e2, t = sp.symbols("e1 e2 t")
    r = check_identity(e2 ** 2, t, relations={e2: e2 - e1, e1: e1 ** 2 - t})
    assert r.status == "proved"


def test_ambiguous_relation_must_be_named():
    a, b = sp.symbols("a b")
    with pytest.raises(ValueError, match="name it"):
        normalize_relations([a ** 2 - b ** 2 - 1])
    assert normalize_relations([(a, a ** 2 - b ** 2 - 1)]) == {a: a ** 2 - b ** 2 - 1}


# --------------------------------------------------------------------------- API surface

def test_eq_input_matrices_and_lazy_export():
    a = sp.Symbol("a")
    assert check_identity(sp.Eq((a + 1) ** 2, a ** 2 + 2 * a + 1)).status == "proved"
    M = sp.Matrix([[a, 1], [0, a]])
    assert check_identity(M * M.inv(), sp.eye(2)).status == "proved"
    assert check_identity(M - M).status == "proved"
    assert symbt.check_identity is check_identity and symbt.IdentityResult is IdentityResult


def test_rich_reprs_and_dict():
    r = check_identity(sp.sqrt(x_real ** 2), x_real)
    h = r._repr_html_()
    assert "false" in h and "counterexample" in h and "<code>" in h
    assert r._repr_latex_().startswith("$") and r"\neq" in r._repr_latex_()
    assert r.to_dict()["status"] == "false"
    with pytest.raises(ValueError):
        IdentityResult(True, "unknown", "m")


def test_seed_makes_it_reproducible():
    lhs, rhs = sp.asinh(x_real), sp.log(x_real + sp.sqrt(x_real ** 2 + 1))
    assert check_identity(lhs, rhs, seed=3).points == check_identity(lhs, rhs, seed=3).points
    assert check_identity(lhs, rhs, seed=3).points != check_identity(lhs, rhs, seed=4).points


@pytest.mark.parametrize("degree", [1, 2, 3, 4])
def test_generic_roots_are_the_closed_forms_sympy_solve_gives(degree):
    # the screen samples relations through these roots; they must be sympy.solve's, in its order
    from symbt.proof.screen import _generic_roots

    a, roots = _generic_roots(degree)
    x = sp.Dummy("x")
    expected = sp.solve(sum(a[i] * x ** (degree - i) for i in range(degree + 1)), x)
    assert [sp.srepr(r) for r in roots] == [sp.srepr(r) for r in expected]
