"""Planted bugs of seed 10's survivors (docs/mutation.md, "Seed 10"), each failing the claim that now sees it;
unpatched, every claim verifies."""
from __future__ import annotations

import pytest
from planting import claim_fails as fails
from planting import planted

from symbt.claims import REGISTRY, load_all
from symbt.numeric.core import inputs, spectral_sum
from symbt.proof import exact, lambdify

load_all()

CLAIMS = ["checker.exact_route_names", "checker.lambdify_memo", "library.codegen_c_out", "paths.spectral_overflow.n3",
          "paths.root_slope", "paths.ball_prec.n3", "paths.q_low.n3", "library.user_provenance"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


@pytest.mark.parametrize("name, old, new", [
    ("exact_route", '    if route == "auto":', '    if route != "auto":'),                       # exact:26
    # exact:107: the flint route skipped where it is chosen (the same verdicts: only the method shows it)
    ("exact_zero", 'if exact_route(route) == "flint":', 'if exact_route(route) != "flint":'),
])
def test_exact_route_names_kills_the_route(monkeypatch, name, old, new):
    monkeypatch.setattr(exact, name, planted(getattr(exact, name), old, new))
    assert fails("checker.exact_route_names")


def test_lambdify_memo_kills_the_eviction_order(monkeypatch):
    # lambdify:63: the most recent entry evicted instead of the oldest
    monkeypatch.setattr(lambdify, "plain_lambdify", planted(lambdify.plain_lambdify, "_MEMO.popitem(last=False)",
                                                            "_MEMO.popitem(last=True)"))
    assert fails("checker.lambdify_memo")


def test_lambdify_memo_kills_a_hit_not_moved(monkeypatch):
    monkeypatch.setattr(lambdify, "plain_lambdify", planted(lambdify.plain_lambdify, "_MEMO.move_to_end(key)",
                                                            "_MEMO.get(key)"))
    assert fails("checker.lambdify_memo")


def test_spectral_overflow_kills_one_sum_missed(monkeypatch):
    # inputs:297: lam0 + mu no longer tested (lam0 - mu twice): a wrong "no real map" at lam0 = mu = 1e308
    mutant = planted(inputs.prepare_spectral_pair, "math.isfinite(lam0 + mu) and math.isfinite(lam0 - mu)",
                     "math.isfinite(lam0 - mu) and math.isfinite(lam0 - mu)")
    import symbt.numeric.core.problem as problem
    monkeypatch.setattr(inputs, "prepare_spectral_pair", mutant)
    monkeypatch.setattr(problem, "prepare_spectral_pair", mutant)
    assert fails("paths.spectral_overflow.n3")


def test_root_slope_kills_the_lost_second_order_term(monkeypatch):
    # the repaired bug (found by probing seed 10's spectral_sum:124): the quotient -2 C / k corrected over kh alone
    monkeypatch.setattr(spectral_sum, "root_slope", planted(spectral_sum.root_slope, "    return q + rem / (kh + kl)\n",
                                                            "    return q + rem / den\n"))
    assert fails("paths.root_slope")


def test_two_sum_of_the_opposite_sign_is_equivalent():
    # seed 10's spectral_sum:124 (`sh = th - t4` -> `th + t4`): Knuth's two-sum is exact for either operand, so the
    # mutant's sh + e2 is th + t4 - 2 t4 = th - t4 exactly, as the original's; only the rounding of a low-order term
    # of glo can differ (relative 1e-16 of a part that is itself below an ulp of k).  Bit for bit on 4000 slopes near
    # |A| = 2**27 (where fl(t**2 +- 4) rounds) and 4000 log-uniform up to 1e14; a wrong two-sum is seen (control).
    import math

    import numpy as np

    mutant = planted(spectral_sum.root_slope, "    sh = th - t4\n", "    sh = th + t4\n")
    wrong = planted(spectral_sum.root_slope, "    e2 = (th - (sh - bp)) + (-t4 - bp)\n", "    e2 = 0.0\n")
    rng = np.random.default_rng(10)
    seen = 0
    for k in range(2000):
        A = float(rng.choice([-1.0, 1.0])) * (float(rng.uniform(9.5e7, 2.7e8)) if k % 2 else
                                              10.0 ** float(rng.uniform(0.5, 14)))
        D, B, C = float(rng.uniform(-300, 300)), float(rng.uniform(0.5, 9)), float(rng.uniform(0.5, 9))
        t, dl = A + D, A - D
        if abs(t) <= 2.0:
            continue
        g = math.sqrt((t - 2.0) * (t + 2.0))
        for plus in (True, False):
            for wantk in (True, False):
                args = (A, D, dl, g, B, C, 2.0, plus, wantk)
                assert mutant(*args) == spectral_sum.root_slope(*args), args
                seen += wrong(*args) != spectral_sum.root_slope(*args)
    assert seen > 0


def test_ball_prec_kills_a_lower_first_pass(monkeypatch):
    # certified:281: the ball method's default first pass at mp.prec - 32 (the docstring: mp.prec + 32)
    from symbt.numeric.multiprec import certified

    monkeypatch.setattr(certified, "certified_orbit", planted(certified.certified_orbit, "else out_prec + 32",
                                                              "else out_prec - 32"))
    assert fails("paths.ball_prec.n3")


@pytest.mark.parametrize("old, new", [
    ("    if f is None:\n", "    if not (f is None):\n"),                                        # files:58
    ('if spec is not None else None', 'if not (spec is not None) else None'),                   # files:63
])
def test_user_provenance_kills_a_module_not_yet_loaded(monkeypatch, old, new):
    # a project module imported only inside a function is found by its spec, not by sys.modules
    from symbt.codegen.user import files

    monkeypatch.setattr(files, "_module_file", planted(files._module_file, old, new))
    assert fails("library.user_provenance")


def test_q_low_kills_the_idle_orbit_concatenated_on_rows(monkeypatch):
    # orbit:359 (no claim ran it): at mu = 0 or n = 0 the positions and low parts joined along the rows
    import sys

    from symbt.numeric.float64 import orbit

    orig = orbit.validated_float_orbit
    mutant = planted(orig, "q0 = np.concatenate([qa, np.zeros_like(qa)], axis=-1) if low else qa",
                     "q0 = np.concatenate([qa, np.zeros_like(qa)], axis=-0) if low else qa")
    for mod in list(sys.modules.values()):
        if mod is not None and getattr(mod, "validated_float_orbit", None) is orig:
            monkeypatch.setattr(mod, "validated_float_orbit", mutant)
    assert fails("paths.q_low.n3")


def test_codegen_c_out_kills_the_target_test(monkeypatch, tmp_path):
    # codegen.files:82 (no claim ran it): `target == "c"` -> `!=`: the C target then writes into the default
    # directory (here a temporary one, so that the planted bug writes nowhere that matters)
    from symbt.codegen import files

    monkeypatch.setattr(files, "DEFAULT_OUT", tmp_path)
    monkeypatch.setattr(files, "generate", planted(files.generate, 'if out is None and target == "c":',
                                                   'if out is None and target != "c":'))
    assert fails("library.codegen_c_out")


def test_abs_products_kills_the_exponent_of_a_non_finite_row(monkeypatch):
    # condition:416: a row whose largest entry is infinite renormalised by 2**-1 with exponent 1 per site, where
    # monodromy(FLOAT) (np.frexp) gives exponent 0
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_renormalised_on_floats", planted(
        condition._renormalised_on_floats, "if mx > 0.0 and mx < math.inf else 0",
        "if mx > 0.0 and mx < math.inf else 1"))
    assert fails("paths.abs_products.n3")
