"""The claims of ``symbt/claims/library_ref45.py`` kill the survivors of seeds 4 and 5 they were written for, tests
kill the ones that change only cost or a branch no valid draw reaches, and the equivalence proofs of
``elliptic:145``, ``elliptic:295`` and ``spectral:67`` (issue 21, item 4; docs/mutation.md, "Seeds 4 and 5").

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own text, with
:func:`planting.planted` -- and requires the claim (or the documented rule) to fail; unpatched, every claim verifies.
"""
from __future__ import annotations

import random

import mpmath as mp
import pytest
import sympy as sp
from planting import planted

from symbt.claims import library_ref45 as L
from symbt.reference import elliptic as E
from symbt.reference import inverse, literal, samples, spectral, taylor
from symbt.symbolic import linear

CLAIMS = [L.reference_verify, L.printed_forms, L.gap_cases, L.taylor_rule, L.inverse_targets, L.addition_w,
          L.trace_band, L.ks_selection]


def status(check) -> str:
    return check.run().status


@pytest.mark.parametrize("check", CLAIMS, ids=lambda c: c.id)
def test_unpatched_verified(check):
    assert status(check) == "verified"


# ------------------------------------------------------------------------- reference.literal: library.reference_verify

def test_literal_step_complex_route_eta_killed(monkeypatch):
    # literal:153 (seed 8): eta = x y - mu on the complex route; mu cancels in p~ = p + eta_j - eta_{j+1}, so only
    # info's eta shows it -- against the real route's
    bad = planted(literal._literal_step_generic, "eta = [xx * yy + mu for", "eta = [xx * yy - mu for")
    monkeypatch.setattr(literal, "_literal_step_generic", bad)
    assert status(L.reference_verify) == "failed"


def test_literal_step_extra_site_killed(monkeypatch):
    # literal:148 (seed 4): the complex route's transport loop runs N times, not N - 1: N + 1 values of y, z, x and
    # eta in info (p~, q~ and E_new are cut to N by zip, so unchanged); no claim gave literal_step complex-route
    # inputs before (the real route has its own loop)
    bad = planted(literal._literal_step_generic, "for j in range(N - 1):", "for j in range(N - 0):")
    monkeypatch.setattr(literal, "_literal_step_generic", bad)
    assert status(L.reference_verify) == "failed"


@pytest.mark.parametrize("old, new", [
    ("with mp.workdps(dps + guard + 25):", "with mp.workdps(dps - guard + 25):"),       # literal:285 (seed 5)
    ("if diff > scale * mp.mpf(10) ** (-dps):", "if not (diff > scale * mp.mpf(10) ** (-dps)):"),  # literal:291
    # seed 6, literal:279: the default guard shrinks with the trace; at traces ~1e45 the transport's loss is uncovered
    ("guard = 20 + 2 * int(mp.log10(big)) + 2 * len(P)", "guard = 20 - 2 * int(mp.log10(big)) + 2 * len(P)"),
])
def test_reference_step_verify_killed(monkeypatch, old, new):
    # uncovered before: no claim ran reference_step(verify=True)
    monkeypatch.setattr(L, "reference_step", planted(literal.reference_step, old, new))
    assert status(L.reference_verify) == "failed"


# --------------------------------------------------------------------------- reference.elliptic: library.printed_forms

@pytest.mark.parametrize("func, old, new", [
    ("theta2_printed", "P = (p[1] - p[0]) / (2 * mp.sqrt(I2 - 2))", "P = (p[0] - p[0]) / (2 * mp.sqrt(I2 - 2))"),
    ("theta2_printed", "return mp.ellipf(mp.asin(P), mm) / mp.sqrt(I2 + 2)",
     "return mp.ellipf(mp.asin(P), mm) / mp.sqrt(I2 - 2)"),
    ("printed_shift", "r = mp.sqrt(I2 - 2)", "r = mp.sqrt(I2 + 2)"),
])
def test_printed_forms_killed(monkeypatch, func, old, new):
    # elliptic:206, 207 (seed 4, uncovered), elliptic:279 (seed 4, uncovered)
    monkeypatch.setattr(E, func, planted(getattr(E, func), old, new))
    assert status(L.printed_forms) == "failed"


def test_gap_sampler_one_sided_killed(monkeypatch):
    # elliptic:414 (seed 5): rng.choice((1, -0)): a gap end is drawn at s = 0 (not a gap) or on the + side only
    bad = planted(E._s_in, "rng.choice((1, -1))", "rng.choice((1, -0))")
    monkeypatch.setattr(E, "_s_in", bad)
    assert status(L.gap_cases) == "failed"


# --------------------------------------------------------------------------- reference.taylor: library.taylor_rule

@pytest.mark.parametrize("old, new", [
    ("mp.mpf(10) ** (-(dps + 2)) if tol is None", "mp.mpf(10) ** (-(dps - 2)) if tol is None"),       # taylor:151
    ("hs.append((tol / nK1) ** (mp.mpf(1) / (K - 1)))", "hs.append((tol / nK1) ** (mp.mpf(0) / (K - 1)))"),  # :169
    ('h = min(hs) * mp.mpf("0.7") if hs else T - done', 'h = min(hs) * mp.mpf("0.7") if not (hs) else T - done'),
])
def test_taylor_rule_killed(monkeypatch, old, new):
    monkeypatch.setattr(L, "hamiltonian_flow", planted(taylor.hamiltonian_flow, old, new))
    assert status(L.taylor_rule) == "failed"


# --------------------------------------------------------------------------- reference.inverse: library.inverse_targets

@pytest.mark.parametrize("old, new", [
    ("trace_gap(p, q, l0 - m, l0 + m) <= 0:", "trace_gap(p, q, l0 - m, l0 + m) <= 1:"),   # inverse:122 (seed 5)
    ("if {0, 1, 2} <= used", "if {1, 1, 2} <= used"),                                     # inverse:160 (seed 4)
    ("[mp.mpf(0)] * (N + 1 - len(c_target))", "[mp.mpf(0)] * (N - 1 - len(c_target))"),  # inverse:120 (seed 8)
])
def test_inverse_targets_killed(monkeypatch, old, new):
    # the solver is imported inside the claim (from the module), so the module's attribute is patched
    monkeypatch.setattr(inverse, "solve_parameters", planted(inverse.solve_parameters, old, new))
    assert status(L.inverse_targets) == "failed"


# --------------------------------------------------------------------------- reference.elliptic: library.addition_w

def test_addition_residual_signed_w_term_killed(monkeypatch):
    # elliptic:372 (seed 5): cn dn - wt / max(1, |wt|): a signed second term, so a w~ above cn dn no longer counts
    bad = planted(E.addition_residual, "abs(cn * dn - wt) / max(1, abs(wt))", "cn * dn - wt / max(1, abs(wt))")
    monkeypatch.setattr(E, "addition_residual", bad)
    assert status(L.addition_w) == "failed"


def test_addition_residual_w_scale_killed(monkeypatch):
    # elliptic:372 (seeds 24 and 26): the second term's scale max(1, wt), 1 where w~ < -1
    bad = planted(E.addition_residual, "abs(cn * dn - wt) / max(1, abs(wt))", "abs(cn * dn - wt) / max(1, wt)")
    monkeypatch.setattr(E, "addition_residual", bad)
    assert status(L.addition_w) == "failed"


# --------------------------------------------------------------------------- reference.trace: library.trace_band

def test_trace_gap_derivative_shifted_killed(monkeypatch):
    # trace:132 (seed 4): the derivative's coefficients shifted by one: its "critical points" are not tr's, and one
    # falls inside the middle band of the N = 3 state, where |tr| - 2 is lower than at the ends
    T = pytest.importorskip("symbt.reference.trace")
    bad = planted(T.trace_gap, "d = [coeffs[i] * (len(coeffs) - 1 - i)", "d = [coeffs[i + 1] * (len(coeffs) - 1 - i)")
    monkeypatch.setattr(T, "trace_gap", bad)
    assert status(L.trace_band) == "failed"


# --------------------------------------------------------------------------- killed by tests

def test_solve_linear_does_not_call_sympy_solve(monkeypatch):
    # symbolic.linear:37 (seeds 4 and 5) -- killed by tests: a linear equation is solved as -c0/c1 without
    # sympy.solve (module docstring: solve costs a tenth of a second); the mutant sends every linear equation with
    # c1 != 0 to sympy.solve, which gives the same solutions -- a cost change
    a, b, x = sp.symbols("a b x")

    def no_solve(*args, **kwargs):
        raise AssertionError("sympy.solve called for a linear equation")

    monkeypatch.setattr(linear.sp, "solve", no_solve)
    assert linear.solve_linear(a * x + b, x) == [-b / a]
    bad = planted(linear.solve_linear, "if sp.cancel(c1) != 0:", "if sp.cancel(c1) == 0:")
    with pytest.raises(AssertionError):
        bad(a * x + b, x)


def test_failed_literal_step_is_not_admissible(monkeypatch):
    # samples:33 (seed 4, uncovered) -- killed by tests: a proposal whose literal step raises (ZeroDivisionError,
    # ValueError) is not admissible; no random draw reaches it, so a failing literal_step is planted
    def raising(*args, **kwargs):
        raise ZeroDivisionError

    monkeypatch.setattr(samples, "literal_step", raising)
    p, q = [mp.mpf(1), mp.mpf(2)], [mp.mpf(0), mp.mpf(0)]
    assert samples._real_map(p, q, mp.mpf(3), mp.mpf("0.1"), 1) == (False, None)
    bad = planted(samples._real_map, "return False, None", "return True, None")
    assert bad(p, q, mp.mpf(3), mp.mpf("0.1"), 1) == (True, None)


# --------------------------------------------------------------------------- equivalences (mutants-equivalent.toml)

def test_F_m_sign_at_zero_is_equivalent():
    # elliptic:145 (seed 4): `z <= 0` for `z < 0`: differs only at z = 0, where -F(-0) = -(0 * R_F) = 0 = F(0)
    # (mpmath has no signed zero); bit for bit at 0 and on both sides
    bad = planted(E._F_m, "z < 0:", "z <= 0:")
    with mp.workdps(30):
        m = mp.mpf("0.4")
        for z in (mp.mpf(0), -mp.mpf(0), mp.mpf("0.3"), mp.mpf("-0.3"), mp.mpf("1e-40")):
            assert bad(z, m) == E._F_m(z, m)
            assert repr(bad(z, m)) == repr(E._F_m(z, m))


def test_zone_out_sign_is_equivalent():
    # elliptic:295 (seed 5): `s > 1` for `s > 0` in the branch k |s| > 1: there |s| > 1/k > 1 (0 < k < 1 for I2 > 2),
    # so s > 0 iff s > 1; checked at the branch's edge s = +-1/k (just beyond) for moduli near 0 and 1
    bad = planted(E.regime, '"out+" if s > 0 else "out-"', '"out+" if s > 1 else "out-"')
    with mp.workdps(30):
        for I2 in (mp.mpf("2.0001"), mp.mpf(3), mp.mpf(1000)):
            k, _ = E.modulus(I2)
            r = mp.sqrt(I2 - 2)
            for I1 in (mp.mpf(0), mp.mpf("0.7")):
                for s in (1 / k * (1 + mp.mpf("1e-20")), 1 / k * 3, -1 / k * (1 + mp.mpf("1e-20")), -3 / k,
                          mp.mpf("0.5"), 1 / k * mp.mpf("0.99")):
                    for mu in (mp.mpf("0.01") * r, r):
                        lam0 = s * r - I1 - mu
                        assert bad(I1, I2, lam0, mu) == E.regime(I1, I2, lam0, mu)


@pytest.mark.parametrize("N", [2, 3])
@pytest.mark.parametrize("test", ["mu > 0", "mu < 1", "not (mu < 0)"])     # spectral:67 of seeds 4, 15, 16
def test_flow_coefficients_mu_sign_is_equivalent(N, test):
    # spectral:67 (seed 4): the normalisation of a negative mu (mu, b -> -mu, -b) taken for a positive mu instead
    # (seed 15: for every mu < 1; seed 16: for every mu >= 0): flow_coefficients_mp passes the pair on to
    # symbt.numeric.flow_coefficients, which documents and computes c(-mu, b) = c(mu, -b) itself (the reversed
    # interval of one tanh-sinh rule); bit for bit
    bad = planted(spectral.flow_coefficients_mp, "if mu < 0:", f"if {test}:")
    rng = random.Random(N)
    with mp.workdps(30):
        p = [mp.mpf(f"{rng.uniform(-0.5, 0.5):.6f}") for _ in range(N)]
        q = [mp.mpf(f"{rng.uniform(-0.5, 0.5):.6f}") for _ in range(N)]
        for mu in (mp.mpf("0.2"), mp.mpf("-0.2"), mp.mpf("0.75")):
            for b in (1, -1):
                assert bad(p, q, mp.mpf(6), mu, b) == spectral.flow_coefficients_mp(p, q, mp.mpf(6), mu, b)


def _random_state(rng: random.Random, N: int) -> tuple[list, list]:
    return ([mp.mpf(f"{rng.uniform(-2, 2):.6f}") for _ in range(N)],
            [mp.mpf(f"{rng.uniform(-2, 2):.6f}") for _ in range(N)])


@pytest.mark.parametrize("old, new", [
    # (trace:134 and :138, seeds 4, 5, 17: the critical points' imaginary-part filter -- removed since, every root
    # being real: seed 27)
    ("    if len(d) > 1:\n", "    if not (len(d) > 1):\n"),   # trace:137 branch (seed 17): no critical point at all
])
def test_trace_gap_critical_points_are_equivalent(old, new):
    # trace:134 (seeds 4, 5; :137-138 in seed 17): which critical points of tr L enter trace_gap's candidates.
    # Proof: for a real state tr L(lam) -+ 2 has all its 2N roots real (the periodic and antiperiodic spectra of a
    # real symmetric Jacobi matrix), so tr' (degree N - 1) has its N - 1 roots real, one in each closed gap, where
    # |tr| >= 2 and |tr| rises to its one maximum there.  An interval [lo, hi] that reaches trace_gap's candidates
    # holds no root of tr = +-2; it lies in one band (no critical point inside) or in one gap (|tr| rising to its
    # maximum at the critical point), so no critical point inside [lo, hi] is below the ends' least |tr| - 2: they
    # never decide. Checked: the premise (tr' has only real roots, at |tr| >= 2) on random states, N = 2..4, and the
    # planted mutant's trace_gap bit for bit on intervals in gaps, bands and across them
    T = pytest.importorskip("symbt.reference.trace")
    bad = planted(T.trace_gap, old, new)
    rng = random.Random("ref45 trace_gap")
    with mp.workdps(30):
        for N in (2, 3, 4):
            for _ in range(6):
                p, q = _random_state(rng, N)
                coeffs = T.hamiltonians(p, q)[::-1]
                d = [coeffs[i] * (len(coeffs) - 1 - i) for i in range(len(coeffs) - 1)]
                roots = mp.polyroots(d, maxsteps=200, extraprec=60) if len(d) > 1 else []
                for r in roots:
                    assert abs(mp.im(r)) < mp.mpf(10) ** -15
                    assert abs(mp.polyval(coeffs, mp.re(r))) >= 2 - mp.mpf(10) ** -20
                pts = sorted([mp.re(r) for r in roots] + [mp.mpf(rng.uniform(-8, 8)) for _ in range(6)])
                for lo, hi in zip(pts, pts[1:]):
                    for a, b in ((lo, hi), (lo - mp.mpf("0.01"), hi), ((lo + hi) / 2, hi + 1)):
                        assert bad(p, q, a, b) == T.trace_gap(p, q, a, b)


# --------------------------------------------------------------------------- reference.spectral: library.ks_selection

@pytest.mark.parametrize("old, new", [
    # seed 6, spectral:66: k = N never selected
    ("[k for k in range(N + 1) if k in set(ks)]", "[k for k in range(N + 0) if k in set(ks)]"),
    ("[k for k in range(N + 1) if k in set(ks)]", "list(range(N + 1))"),                 # ks ignored
    ("return [got.get(k) for k in range(N + 1)]", "return [got.get(k) for k in range(N)] + [got.get(0)]"),
])
def test_ks_selection_killed(monkeypatch, old, new):
    from symbt.reference import spectral

    monkeypatch.setattr(spectral, "flow_coefficients_mp", planted(spectral.flow_coefficients_mp, old, new))
    assert status(L.ks_selection) == "failed"


def test_trace_gap_swap_at_equal_ends_is_equivalent():
    # trace:126 (seed 8), `if lo >= hi:` for `if lo > hi:`: the mutant also swaps lo and hi when they are equal,
    # which leaves the same pair (mpf values are immutable): every return value is the same
    from symbt.reference import trace as T

    bad = planted(T.trace_gap, "    if lo > hi:", "    if lo >= hi:")
    p, q = [mp.mpf(-1), mp.mpf("0.5")], [mp.mpf("0.3"), mp.mpf(-1)]
    for lo, hi in [(3, 3), (-1, -1), ("2.5", "2.5"), (0, 4), (4, 0), (-5, 5), (1, 1.5)]:
        assert bad(p, q, lo, hi) == T.trace_gap(p, q, lo, hi)
