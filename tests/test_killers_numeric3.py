"""The claims of ``symbt/claims/shipped_edges.py`` kill the bugs they were written for, and two survivors of seed 2's
numeric sample are killed by tests (issue 21, item 4; docs/mutation.md, branch ``seed2k``).

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own text, with
:func:`planting.planted` -- and requires the claim (or, for the survivors, the test's own check) to fail;
unpatched, every claim verifies.
"""
from __future__ import annotations

import math

import pytest
from planting import planted

from symbt.claims import REGISTRY, load_all
from symbt.numeric.float64 import kernels, kernels_block

load_all()

EDGES = ["paths.inline_rule.n3", "paths.kappa_edge.n2", "paths.renorm_top.n2"]


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.mark.parametrize("cid", EDGES)
def test_unpatched_verified(cid):
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- paths.renorm_top

def test_suffix_renormalised_without_the_abs_of_s12(monkeypatch):
    # mutant condition:151 (abs): `max(abs(S11), abs(S12), ...)` -> `max(abs(S11), S12, ...)`: with S12 = -1 the
    # largest entry and the others below 2**-200 the suffix is scaled up by ~2**599 and overflows at the next site
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "sharp_trace_kappa", planted(
        condition.sharp_trace_kappa, "m = max(abs(S11), abs(S12), abs(S21), abs(S22))",
        "m = max(abs(S11), S12, abs(S21), abs(S22))"))
    assert status("paths.renorm_top.n2") == "failed"


# --------------------------------------------------------------------------- paths.kappa_edge

def test_block_kernel_refuses_the_estimate_at_kappa_max(monkeypatch):
    # mutant kernels_block:126 (compare): `decided = kap <= KAPPA_MAX` -> `kap < KAPPA_MAX`
    monkeypatch.setattr(kernels_block, "_slopes", planted(kernels_block._slopes, "decided = kap <= KAPPA_MAX",
                                                          "decided = kap < KAPPA_MAX"))
    assert status("paths.kappa_edge.n2") == "failed"


def test_fused_hook_refuses_the_estimate_at_kappa_max(monkeypatch):
    # the same rule in the fused kernel's hook (kernels._decided), which the claim also calls directly
    monkeypatch.setitem(kernels.HOOKS, "decided", planted(kernels._decided, "if not k <= KAPPA_MAX:",
                                                          "if not k < KAPPA_MAX:"))
    assert status("paths.kappa_edge.n2") == "failed"


def test_kappa_edge_premise_by_the_kernel_itself():
    # the claim's premise is recomputed with exact rationals; the kernels' own cheap estimate, formed with the fused
    # hooks' track, is the same double at the three states, and 2**24 exactly at the edge
    from symbt.claims.shipped_edges import EDGE_L, EDGE_LO, EDGE_RATIOS, edge_ratios, kappa_estimate

    for name in EDGE_RATIOS:
        r = edge_ratios(name)
        est = kappa_estimate(EDGE_L, EDGE_LO, r)[0]
        a = kernels.HOOKS["lam_add"](EDGE_L, EDGE_LO, 0.0)
        aux = kernels.HOOKS["track"](kernels.HOOKS["track_init"](EDGE_L, 0.0, a, r[0]), EDGE_L, 0.0, a, r[1])
        t = (a * a - r[0]) + -r[1]
        disc = (t - 2.0) * (t + 2.0)
        T = aux[0] + aux[3]
        assert T * (abs(t) + 2.0) / abs(disc) * (aux[4] / aux[5]) == est
    assert kappa_estimate(EDGE_L, EDGE_LO, edge_ratios("at 2**24"))[0] == 2.0 ** 24


def test_kappa_edge_ratios_are_the_reanchored_exponentials():
    # provenance of EDGE_RATIOS: r = (e**d, e**-d) as the kernels' re-anchoring computes them (math.exp of the
    # neighbour difference), at d = EDGE_D and its neighbouring doubles
    from symbt.claims.shipped_edges import EDGE_D, edge_ratios

    for name, d in (("at 2**24", EDGE_D), ("one ulp above", math.nextafter(EDGE_D, math.inf)),
                    ("one ulp below", math.nextafter(EDGE_D, -math.inf))):
        assert edge_ratios(name) == (math.exp(d - 0.0), math.exp(0.0 - d))


# --------------------------------------------------------------------------- paths.inline_rule

def test_inliner_substitutes_an_impure_body_anywhere(monkeypatch):
    # mutant inline:247 (constant): `self.value(e, pre, root=False, at=at)` -> `root=True` in _Bodies.expr: a body
    # that writes to an array is written inline in the middle of an expression instead of refused
    from symbt.numeric.core import inline

    monkeypatch.setattr(inline._Bodies, "expr", planted(inline._Bodies.expr,
                                                        "return self.value(e, pre, root=False, at=at)",
                                                        "return self.value(e, pre, root=True, at=at)"))
    assert status("paths.inline_rule.n3") == "failed"


def test_why_the_inliner_refuses():
    # the reason of the documented rule, shown on the mutant: written inline, `u[0] + store_first(u, x)` reads
    # u[0] after the body's statements ran (placed before the statement) -- a different result
    from symbt.claims.shipped_edges import nested_operand, store_first
    from symbt.numeric.core import inline

    mutant = planted(inline._Bodies.expr, "return self.value(e, pre, root=False, at=at)",
                     "return self.value(e, pre, root=True, at=at)")
    original = inline._Bodies.expr
    try:
        inline._Bodies.expr = mutant
        g = inline.inlined(nested_operand, "nested_operand_inline",
                           {**inline.FLOAT64_INLINE, "store_first": "body"}, {"store_first": store_first})
    finally:
        inline._Bodies.expr = original
    assert nested_operand([7.0], 2.5) == 9.5 and g([7.0], 2.5) == 5.0


# --------------------------------------------------------------------------- paths.compress (the compressed rule)

def test_compressed_rule_nodes_shifted(monkeypatch):
    # mutant coefficients:338 (drop-factor): the candidate rules' nodes `0.5 * (a + b) + ...` -> `a + b + ...`:
    # every candidate fails the agreement test, the composite rule (32 nodes) stays
    from symbt.numeric.flow import coefficients

    monkeypatch.setattr(coefficients, "flow_quadrature", planted(
        coefficients.flow_quadrature, "nd, wt = 0.5 * (a + b) + 0.5 * (b - a) * x",
        "nd, wt = a + b + 0.5 * (b - a) * x"))
    assert status("paths.compress.n3") == "failed"


def test_compressed_rule_keeps_a_larger_rule(monkeypatch):
    # a rule that agrees but is not the smallest (the loop starting at 20 nodes) fails the claim too
    from symbt.numeric.flow import coefficients

    monkeypatch.setattr(coefficients, "flow_quadrature", planted(
        coefficients.flow_quadrature, "for n in (8, 12, 16, 20,", "for n in (20,"))
    assert status("paths.compress.n3") == "failed"


# --------------------------------------------------------------------------- survivors killed by tests

def _pass_with_a_transient(i1: int, degree: float):
    """A Lohner pass record that stopped after ``i1`` steps, excess 20 bits at every step, whose largest radius grows
    exactly like ``n**degree`` from step ``i1 // 10`` on and is 100 bits smaller before (a transient)."""
    from symbt.numeric.multiprec.lohner import LohnerPass

    first = max(1, i1 // 10)
    lograd = [-300.0] + [-200.0 + degree * math.log2(i) - (100.0 if i < first else 0.0) for i in range(1, i1 + 1)]
    return LohnerPass(False, [], [0.0] + [20.0] * i1, lograd, i1)


def test_next_precision_fits_the_growth_after_the_transient(monkeypatch):
    # lohner:450 (min-max): `first=max(1, i1 // 10)` -> `min(1, i1 // 10)`: the fit starts at step 1 and takes in
    # the transient.  lohner_certified's docstring: the degree is fitted from step max(1, done // 10); on a record
    # growing exactly like n**1 there, the next precision is the documented rule with degree 1 (not growth_law's
    # output: the degree of the construction), max(floor(p + e + 1.5 log2(n / i1) + 16) + 1, p + 32)
    from symbt.numeric.multiprec import lohner

    prec, n, i1 = 200, 1000, 40
    want = max(int(prec + 20.0 + 1.5 * 1.0 * math.log2(n / i1) + 16) + 1, prec + 32)
    run = _pass_with_a_transient(i1, 1.0)
    assert lohner._next_prec(prec, run, n) == want == 243


def test_next_precision_check_sees_the_mutant():
    # the check above on the planted mutant: the fit from step 1 takes in the transient (degree ~21.6)
    from symbt.numeric.multiprec import lohner

    mutant = planted(lohner._next_prec, "first=max(1, i1 // 10)", "first=min(1, i1 // 10)")
    assert mutant(200, _pass_with_a_transient(40, 1.0), 1000) != 243


def test_arb_half_plane_at_a_zero_root_as_the_real_routes():
    # arb:129 (compare): ArbContext.half_plane's `(g.mid() >= 0)` -> `(g.mid() > 0)`.  The transport direction of
    # a real trace t with root g = sqrt(t**2 - 4) >= 0 is decided by the sign of t alone on the real routes:
    # FloatContext.half_plane (real: `a >= 0`) and the fused Arb step (runners._slopes: `tg = t.mid() >= 0`).  At
    # an exact band edge (g = 0 exactly: exact input, t = +-2) the mutant reverses it.  Not equivalent: at
    # p = (0, -3, -3, -1.5), q = 0, lam1 = 1.5 (t = 2 exactly) jacobian_dual raises JacobianBlowup where it raised
    # NoRealMapError (branch 1), and the reverse at branch -1 (below) -- no documented rule says which of the two
    # an exact band edge gives, so verify cannot kill it; this test does.
    pytest.importorskip("flint")
    from flint import arb

    from symbt.numeric.core.context import FLOAT
    from symbt.numeric.multiprec.arb import ARB_CERTAIN

    for t in (2.0, -2.0, 3.5, -3.5):
        for g in (0.0, 1.5):
            want = bool(FLOAT.half_plane(t, g))
            assert want == (t >= 0)
            assert ARB_CERTAIN.half_plane(arb(t), arb(g)) == want


def test_arb_half_plane_check_sees_the_mutant():
    pytest.importorskip("flint")
    from flint import arb

    from symbt.numeric.multiprec.arb import ARB_CERTAIN, ArbContext

    mutant = planted(ArbContext.half_plane, "(g.mid() >= 0))", "(g.mid() > 0))")
    assert [mutant(ARB_CERTAIN, arb(t), arb(0)) for t in (2.0, -2.0)] == [False, True]


def test_arb_half_plane_mutant_changes_the_dual_jacobians_error(monkeypatch):
    # the counterexample to equivalence of arb:129 (found by a search over exact states with |tr| = 2)
    pytest.importorskip("flint")
    from flint import arb

    from symbt.numeric.core.errors import NoRealMapError
    from symbt.numeric.multiprec.arb import ArbContext
    from symbt.numeric.multiprec.lohner_checks import JacobianBlowup, jacobian_dual

    box = [arb(0), arb(-3), arb(-3), arb(-1.5)] + [arb(0)] * 4
    lam1, lam2 = 1.5, 7.0

    def error(branch):
        try:
            jacobian_dual(box, arb((lam1 + lam2) / 2), arb((lam1 - lam2) / 2), branch)
        except (NoRealMapError, JacobianBlowup) as exc:
            return type(exc)
        return None

    before = {b: error(b) for b in (1, -1)}
    monkeypatch.setattr(ArbContext, "half_plane", planted(ArbContext.half_plane, "(g.mid() >= 0))",
                                                          "(g.mid() > 0))"))
    after = {b: error(b) for b in (1, -1)}
    assert before == {1: NoRealMapError, -1: JacobianBlowup}
    assert after == {1: JacobianBlowup, -1: NoRealMapError}
