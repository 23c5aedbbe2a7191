"""Seed 11's survivors (docs/mutation.md, "Seed 11"): planted bugs that the new facts now see, and the proofs of the
mutants marked equivalent.  Unpatched, every claim verifies."""
from __future__ import annotations

import random
import sys

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from planting import claim_fails as fails
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["library.defaults", "paths.dq_range.n3", "checker.screen_arithmetic", "checker.exact_route_names"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


def test_defaults_kill_a_deep_default(monkeypatch):
    # ode:182
    from symbt.proof import ode

    monkeypatch.setattr(ode, "solves_ode", planted(ode.solves_ode, "deep: bool = False,", "deep: bool = True,"))
    assert fails("library.defaults")


def test_defaults_kill_a_branch_zero_default(monkeypatch):
    # elliptic:314
    from symbt.reference import elliptic

    monkeypatch.setattr(elliptic, "step2", planted(elliptic.step2, "branch: int = 1, *,", "branch: int = 0, *,"))
    assert fails("library.defaults")


def test_dq_range_kills_the_signed_distance(monkeypatch):
    # coefficients:97: the largest signed distance, not the largest in modulus
    from symbt.numeric.flow import coefficients

    orig = coefficients.neighbour_ratios_of
    mutant = planted(orig, "worst = max(abs(float(d)) for d in dq)", "worst = max(float(d) for d in dq)")
    for mod in list(sys.modules.values()):
        if mod is not None and getattr(mod, "neighbour_ratios_of", None) is orig:
            monkeypatch.setattr(mod, "neighbour_ratios_of", mutant)
    assert fails("paths.dq_range.n3")


def test_screen_arithmetic_kills_the_signed_side_in_the_inherited_error(monkeypatch):
    # screen:194: |side| times the relative errors, for a negative side
    from symbt.proof import screen

    monkeypatch.setattr(screen, "_quad_error", planted(screen._quad_error, "abs(value) * relative)",
                                                       "value * relative)"))
    assert fails("checker.screen_arithmetic")


def test_exact_route_names_kills_the_generator_i(monkeypatch):
    # flint_exact:58 (crashes where the claim runs it) and flint_exact:175
    from symbt.proof import flint_exact

    monkeypatch.setattr(flint_exact._Converter, "__init__", planted(
        flint_exact._Converter.__init__, '(["i"] if has_i else [])', '(["i"] if not (has_i) else [])'))
    assert fails("checker.exact_route_names", crash=True)


def test_exact_route_names_kills_the_reduction_modulo_i_squared_plus_one(monkeypatch):
    from symbt.proof import flint_exact

    monkeypatch.setattr(flint_exact, "rational_zero", planted(flint_exact.rational_zero, "conv.i ** 2 + 1))",
                                                              "conv.i ** 2 + 0))"))
    assert fails("checker.exact_route_names")


# --------------------------------------------------------------------------- proven equivalent

@pytest.mark.parametrize("new", ["v = v + 1 if v + 1 <= hi else v + 1",      # screen:54 sign (seed 11)
                                 "v = v + 1 if v + 0 <= hi else v - 1",      # screen:54 constant (seed 17)
                                 "v = v + 1 if v + 1 <= hi else v - 0"])     # screen:54 constant (seed 17)
def test_odd_draw_at_the_top_of_its_range_is_equivalent(new):
    # screen:54 (`v - 1` -> `v + 1` where an odd draw at the top moves down): every range the sampler draws from ends
    # on odd numbers (1..9, -9..-1, -9..9), so an even draw v < hi has v + 1 <= hi and the else branch is never taken
    # (nor does `v + 0 <= hi`, true wherever `v + 1 <= hi` is, change the test); the mutant draws the same values for
    # every seed (checked on 2000 seeds x each range), a wrong move is seen
    from symbt.proof import screen

    mutant = planted(screen.sample_symbol, "v = v + 1 if v + 1 <= hi else v - 1", new)
    wrong = planted(screen.sample_symbol, "v = v + 1 if v + 1 <= hi else v - 1", "v = v - 1 if v + 1 <= hi else v - 1")
    syms = [sp.Symbol("n", integer=True, odd=True, **kw) for kw in ({"positive": True}, {"negative": True}, {})]
    differs = 0
    for s in syms:
        for seed in range(2000):
            assert mutant(s, random.Random(seed)) == screen.sample_symbol(s, random.Random(seed))
            differs += wrong(s, random.Random(seed)) != screen.sample_symbol(s, random.Random(seed))
    assert differs > 0


def test_transfer_gradient_last_suffix_update_is_equivalent():
    # field:83 (`if j > 0` -> `if j >= 0`): at j = 0, the last pass of the backward loop, the mutant also updates the
    # suffix product b, which nothing reads after the loop: the same gradients (bit for bit, N = 2..7, random
    # entries); a wrong update at j > 0 is seen
    from symbt.numeric.flow import field

    mutant = planted(field.transfer_gradient, "        if j > 0:\n", "        if j >= 0:\n")
    wrong = planted(field.transfer_gradient, "b10 * a[j] + b11 * r[j], -inv_s * b10)",
                    "b10 * a[j] - b11 * r[j], -inv_s * b10)")
    rng = np.random.default_rng(11)
    seen = 0
    for N in range(2, 8):
        for _ in range(50):
            a, r, s = list(rng.normal(size=N)), list(rng.uniform(0.1, 3, size=N)), float(rng.uniform(0.5, 2))
            assert mutant(a, r, s) == field.transfer_gradient(a, r, s)
            seen += wrong(a, r, s) != field.transfer_gradient(a, r, s)
    assert seen > 0


def test_zero_mu_reversal_is_equivalent():
    # spectral:67 (`mu < 0` -> `mu <= 0`): at mu = 0 the mutant flips the branch of an empty interval, whose
    # coefficients are 0 on either branch (mpmath has no signed zero); a nonzero mu is unchanged
    from symbt.reference import spectral

    mutant = planted(spectral.flow_coefficients_mp, "    if mu < 0:\n", "    if mu <= 0:\n")
    p, q = [mp.mpf(-1) / 2, mp.mpf(1) / 4, mp.mpf(0)], [mp.mpf(0), mp.mpf(1) / 3, mp.mpf(1) / 5]
    with mp.workdps(20):
        for b in (1, -1):
            got = mutant(p, q, 3, 0, b)
            assert got == spectral.flow_coefficients_mp(p, q, 3, 0, b)
            assert all(v == 0 for v in got)
        assert mutant(p, q, 3, mp.mpf(1) / 10, 1) == spectral.flow_coefficients_mp(p, q, 3, mp.mpf(1) / 10, 1)


@pytest.mark.parametrize("test", ["v > 0", "v >= 1"])     # seed 11's printer:85 and seed 13's (the constant)
def test_zero_printed_in_parentheses_is_equivalent(test):
    # printer:85 (`v >= 0` -> `v > 0` or `v >= 1`, v an int): the integer 0 printed "(0)" (C: "(0.0)") instead of
    # "0": the same number in every flavour, evaluated; a negative or positive integer prints as before
    from symbt.codegen import printer

    x = sp.Symbol("x")
    mutant = planted(printer.ExprPrinter._p, "return (txt, _ATOM) if v >= 0 else",
                     f"return (txt, _ATOM) if {test} else")
    for flavour in ("numpy", "mpmath", "ops", "c"):
        pr = printer.ExprPrinter(flavour, {x: "x"})
        text, prec = pr._p(sp.Integer(0))
        mtext, mprec = mutant(pr, sp.Integer(0))
        assert (text, mtext) in (("0", "(0)"), ("0.0", "(0.0)")) and prec == mprec
        assert eval(text) == eval(mtext) == 0     # noqa: S307 -- the printer's own number
        assert mutant(pr, sp.Integer(-3)) == pr._p(sp.Integer(-3))
        assert mutant(pr, sp.Integer(1)) == pr._p(sp.Integer(1)) and mutant(pr, sp.Integer(7)) == pr._p(sp.Integer(7))


# --------------------------------------------------------------------------- seed 12

def test_acosh_edge_kills_the_branch_exponent(monkeypatch):
    # context:152: the log1p form chosen at e == 1 instead of e == 0 (the log form near the edge loses bits)
    from symbt.numeric.core import context

    monkeypatch.setattr(context.FloatContext, "acosh_half_abs", planted(
        context.FloatContext.acosh_half_abs, "np.asarray(e) == 0, small, big", "np.asarray(e) == 1, small, big"))
    assert fails("paths.acosh_edge")


def test_screen_scale_kills_the_smallest_residual_reported(monkeypatch):
    # screen:432: a verified screen reports the smallest residual of its points
    from symbt.proof import decider, screen

    mutant = planted(screen.screen, "worst = max(checks, key=lambda c: c.residual)",
                     "worst = min(checks, key=lambda c: c.residual)")
    monkeypatch.setattr(screen, "screen", mutant)
    monkeypatch.setattr(decider, "screen", mutant)
    assert fails("checker.screen_scale")


def test_codegen_metrics_kills_a_reported_value_of_the_wrong_output(monkeypatch):
    # verify:246: the reported mpmath value taken from output k - 1
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "compare", planted(verify.compare, "mp=mp.nstr(fm[k], 30))",
                                                   "mp=mp.nstr(fm[k - 1], 30))"))
    assert fails("checker.codegen_metrics")


def test_exact_route_names_kills_the_exponential_names(monkeypatch):
    # exponentials:190: e and e^s swapped in describe_variables
    from symbt.proof import exponentials

    monkeypatch.setattr(exponentials, "describe_variables", planted(
        exponentials.describe_variables, 'base = "e" if s is sp.S.One else', 'base = "e" if not (s is sp.S.One) else'))
    assert fails("checker.exact_route_names")


def test_magnitude_of_a_zeroth_power_is_equivalent():
    # magnitude:32 (then `exp > 0` -> `exp >= 0`; the test is `is_positive` now, no mark needed): SymPy evaluates
    # b**0 to 1, so a Pow with exponent 0 exists only unevaluated, and then m(b)**0 = |b**0| = 1 (mpmath: 0**0 = 1
    # too); every other power is unchanged
    from symbt.proof import magnitude as M
    from symbt.proof.lambdify import plain_lambdify

    mutant = planted(M.magnitude, "expr.exp.is_Integer and expr.exp.is_positive:",
                     "expr.exp.is_Integer and expr.exp.is_nonnegative:")
    x, y = sp.symbols("x y")
    assert (x - y) ** 0 == 1 and not isinstance((x - y) ** 0, sp.Pow)
    zeroth = sp.Pow(x - y, 0, evaluate=False)
    for e in (zeroth, x * zeroth, (x - y) ** 2 + zeroth, 1 / (x - y), x ** 3):
        f, g = (plain_lambdify([x, y], fn(e), "mpmath") for fn in (M.magnitude, mutant))
        for v in ((mp.mpf(2), mp.mpf(-3)), (mp.mpf(3), mp.mpf("3.5")), (mp.mpf("0.5"), mp.mpf(4))):
            assert f(*v) == g(*v), (e, v)
