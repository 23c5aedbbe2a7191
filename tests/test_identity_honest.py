"""Honest numeric verdicts: the screen knows its own error (issue 20, items 5 and 9).

A residual within the evaluation's own error is never a counterexample (``inconclusive``
instead), ``digits`` counts only digits that agree *and* are trustworthy, genuine near
misses stay false, and a modulus/parameter mix-up of elliptic functions gets a hint.
"""
from __future__ import annotations

import math

import mpmath
import pytest
import sympy as sp

from symbt.proof import Verdict, check_identity, decide
from symbt.proof.screen import screen, tracked_quad
from symbt.proof.verdict import SAFETY

s = sp.Symbol("s", positive=True)     # m = 1/(1+s) is sampled in (0, 1)
t, x = sp.symbols("t x", real=True)
M = 1 / (1 + s)
K_SIN = sp.Integral(1 / sp.sqrt(1 - M * sp.sin(t) ** 2), (t, 0, sp.pi / 2))            # K(m), Legendre form
K_ALG = sp.Integral(1 / sp.sqrt((1 - x ** 2) * (1 - M * x ** 2)), (x, 0, 1))             # K(m), endpoint singular
K_FULL = sp.Integral(1 / sp.sqrt(1 - M * sp.sin(t) ** 2), (t, 0, 2 * sp.pi)) / 4         # K(m), whole period
NEAR_ONE = {s: sp.Rational(1, 99)}                                                        # m = 0.99


# --------------------------------------------------------------------------- the elliptic integral

def test_quadrature_noise_is_never_a_counterexample():
    # the old screen called this true identity false ("relative residual 2.7e-22" at 30 digits):
    # tanh-sinh quadrature of the endpoint-singular form is only good to ~22 digits at 40 working digits
    r = check_identity(K_ALG, sp.elliptic_k(M), digits=30, fixed=NEAR_ONE, points=2)   # m fixed: one point twice
    assert r.status == "inconclusive" and not r and r.counterexample is None
    assert r.error is not None and r.error > 1e-22          # the evaluation's own error, measured
    assert r.digits is not None and r.digits < 23           # trustworthy digits, not the 30 asked for
    assert "cannot tell at 30 digits" in r.note and "raise digits" in r.note
    assert str(r).split(": ", 1)[1].startswith("inconclusive: cannot tell at 30 digits")
    assert r.to_dict()["status"] == "inconclusive" and r.to_dict()["error"] == r.error


def test_sampled_modulus_never_false_and_digits_never_overstated():
    for digits in (30, 50):
        r = check_identity(K_ALG, sp.elliptic_k(M), digits=digits, points=4)
        assert r.status in ("verified", "inconclusive"), (digits, r)
        assert r.digits is not None and r.digits <= digits - 7    # ~22 of 30, ~32 of 50 digits are trustworthy
        if r.status == "verified":
            assert f"of the {digits} digits asked for" in str(r)


def test_digits_count_only_trustworthy_agreeing_digits():
    # m = 1/3: the sides agree to 22 digits at 30 asked for; "verified to 30 digits" would be a lie
    r = check_identity(K_ALG, sp.elliptic_k(M), digits=30, fixed={s: 2}, points=2)
    assert r.status == "verified" and r
    assert 20 < r.digits < 23
    assert r.error is not None and r.digits == pytest.approx(-math.log10(max(r.error, r.residual)), abs=0.05)
    assert "verified numerically to 22 of the 30 digits asked for" in str(r)


def test_a_quadrature_that_converges_to_the_same_wrong_value_is_caught_by_its_error_estimate():
    # at 40 and 70 working digits mpmath's quad returns the *same* value, 6.4e-20 off (its degree
    # is capped at both): two precisions alone would call this a counterexample; quad's own estimate does not
    with mpmath.workdps(40):
        m = mpmath.mpf(99) / 100
        f = lambda u: 1 / mpmath.sqrt(1 - m * mpmath.sin(u) ** 2)  # noqa: E731
        lo = mpmath.quad(f, (0, 2 * mpmath.pi))
        with mpmath.workdps(70):
            hi = mpmath.quad(f, (0, 2 * mpmath.pi))
        assert abs(lo - hi) < 1e-35 and abs(lo / 4 / mpmath.ellipk(m) - 1) > 1e-20     # the premise
    r = check_identity(K_FULL, sp.elliptic_k(M), digits=30, fixed=NEAR_ONE, points=2)
    assert r.status == "inconclusive" and r.counterexample is None


def test_tracked_quad_reports_its_error_to_the_screen():
    sr = screen(K_FULL, sp.elliptic_k(M), {}, 30, 1, 1, NEAR_ONE, recheck=False)
    assert sr.error > 1e-21                 # the quadrature's estimate alone, no second evaluation
    assert sr.rechecked == 0 and sr.status == "inconclusive"
    assert tracked_quad(lambda u: u, (0, 2)) == 2


def test_the_legendre_form_is_verified_to_every_digit():
    r = check_identity(K_SIN, sp.elliptic_k(M), digits=30)
    assert r.status == "verified" and r.digits == 30
    assert "verified numerically to 30 digits" in str(r)


# --------------------------------------------------------------------------- genuine near misses stay false

def test_a_near_miss_is_still_false():
    r = check_identity(sp.sin(x), sp.Float("1.001") * sp.sin(x))
    assert r.status == "false" and set(r.counterexample) == {"x"}
    assert r.residual == pytest.approx(1e-3, rel=0.01) and r.residual > SAFETY * r.error


def test_a_perturbation_at_1e20_is_false_at_50_digits():
    r = check_identity(sp.sin(x) + sp.Rational(1, 10 ** 20) * sp.cos(x), sp.sin(x), digits=50)
    assert r.status == "false" and 1e-22 < r.residual < 1e-19
    r = check_identity(K_SIN, sp.elliptic_k(M) * (1 + sp.Rational(1, 10 ** 20)), digits=50)
    assert r.status == "false" and r.residual == pytest.approx(1e-20, rel=1e-6)


def test_a_true_transcendental_identity_is_verified():
    r = check_identity(sp.elliptic_k(M), sp.pi / 2 * sp.hyper([sp.S.Half, sp.S.Half], [1], M))
    assert r.status == "verified" and r.digits == 50 and r.error is not None and r.error < 1e-50
    r = check_identity(sp.asinh(x), sp.log(x + sp.sqrt(x ** 2 + 1)), digits=40)
    assert r.status == "verified" and r.digits >= 39


def test_false_is_still_cheap_one_recheck():
    v = decide(sp.sin(x), sp.cos(x), exact=False)
    assert v.verdict == "false" and "(1 re-evaluated at 110 digits)" in v.method


# --------------------------------------------------------------------------- the verdict and matrices

def test_verdict_sampled_with_an_error_estimate():
    assert Verdict.sampled(1e-30, tol=1e-22, error=1e-40).verdict == "verified"
    v = Verdict.sampled(1e-30, tol=1e-22, error=1e-25)
    assert v.verdict == "verified" and v.digits == 25.0          # only 25 digits are trustworthy
    v = Verdict.sampled(5e-21, tol=1e-22, error=1e-21, counterexample={"x": "1"})
    assert v.verdict == "inconclusive" and v.counterexample is None and not v.holds
    v = Verdict.sampled(5e-3, tol=1e-22, error=1e-21, counterexample={"x": "1"})
    assert v.verdict == "false" and v.counterexample == {"x": "1"}
    with pytest.raises(ValueError, match="inconclusive"):
        Verdict(True, "sampled", "m", inconclusive=True)


def test_a_matrix_is_false_before_inconclusive_and_inconclusive_before_verified():
    k = sp.elliptic_k(M)
    undecided = decide(sp.Matrix([K_ALG, 1]), sp.Matrix([k, 1]), digits=30, fixed=NEAR_ONE, points=2)
    assert undecided.verdict == "inconclusive"
    wrong = decide(sp.Matrix([K_ALG, sp.sin(x)]), sp.Matrix([k, sp.cos(x)]), digits=30, fixed=NEAR_ONE, points=2)
    assert wrong.verdict == "false"


# --------------------------------------------------------------------------- modulus vs parameter

def test_hint_when_the_modulus_is_read_as_the_parameter():
    k_modulus = sp.Integral(1 / sp.sqrt(1 - M ** 2 * sp.sin(t) ** 2), (t, 0, sp.pi / 2))   # K of modulus M
    r = check_identity(k_modulus, sp.elliptic_k(M), digits=30)
    assert r.status == "false"
    assert ("the sides agree if the modulus k is read as the parameter m = k**2: "
            "SymPy/mpmath elliptic functions take m") in r.note
    assert "hint:" in str(r)


def test_hint_the_other_way_round():
    r = check_identity(K_SIN, sp.elliptic_k(M ** 2), digits=30)
    assert r.status == "false" and "parameter m is read as the modulus k = sqrt(m)" in r.note


def test_no_hint_for_an_unrelated_mistake_or_without_elliptic_functions():
    r = check_identity(K_SIN, sp.elliptic_e(M), digits=30)
    assert r.status == "false" and "hint" not in r.note
    r = check_identity(sp.sin(x) ** 2, sp.cos(x) ** 2)
    assert r.status == "false" and r.note == ""


def test_assert_identity_says_it_cannot_decide():
    from symbt.testing import IdentityAssertionError, assert_identity

    with pytest.raises(IdentityAssertionError, match=r"cannot be decided \(inconclusive\)") as exc:
        assert_identity(K_ALG, sp.elliptic_k(M), digits=30, points=2, fixed=NEAR_ONE)
    assert "raise digits" in str(exc.value) and exc.value.result.status == "inconclusive"


def test_an_infinite_integration_limit_is_not_an_undefined_side():
    a = sp.Symbol("a", positive=True)
    gauss = sp.Integral(sp.exp(-a * t ** 2), (t, -sp.oo, sp.oo))
    r = check_identity(gauss, sp.sqrt(sp.pi / a), digits=30, points=3)
    assert r.status == "verified" and r.digits == 30          # was "false: a side contains oo"
    r = check_identity(gauss, sp.sqrt(sp.pi / a) * (1 + sp.Rational(1, 10 ** 15)), digits=30, points=3)
    assert r.status == "false" and r.residual == pytest.approx(1e-15, rel=1e-6)
    assert check_identity(t + sp.oo, t).status == "false"


def test_the_convention_hint_leaves_matrices_without_elliptic_functions_alone():
    """A false matrix identity with no elliptic function in it gets no hint (and no crash)."""
    import sympy as sp

    from symbt.proof.identity import check_identity, convention_hint

    x = sp.Symbol("x", real=True)
    assert convention_hint(sp.Matrix([x, 1]), sp.Matrix([x, 2]), digits=20, points=3) == ""
    k = sp.Symbol("k", positive=True)
    wrong = sp.pi / 2 * sp.hyper([sp.S.Half, sp.S.Half], [1], k**2)
    assert "modulus" in convention_hint(sp.Matrix([wrong, x]), sp.Matrix([sp.elliptic_k(k), x]), digits=20,
                                        points=3)
    assert check_identity(sp.Matrix([x, 1]), sp.Matrix([x, 2])).status == "false"
