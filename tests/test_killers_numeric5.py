"""The claims of ``symbt/claims/shipped_sample45.py`` kill the bugs they were written for, and the proofs of the
equivalence marks of seeds 4 and 5's numeric survivors (issue 21, item 4; docs/mutation.md, "Seeds 4 and 5").

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own text, with
:func:`planting.planted` -- and requires the claim to fail; unpatched, every claim verifies.
"""
from __future__ import annotations

import pytest
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

SAMPLE45 = ["paths.track_hooks", "paths.kappa_rows.n2", "paths.mp_verdict.n3", "paths.jacobian_dual.n3",
            "paths.inline_boolop", "paths.side_by_side.n3"]
NEEDS_FLINT = ("paths.jacobian_dual.n3",)


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.mark.parametrize("cid", SAMPLE45)
def test_unpatched_verified(cid):
    if cid in NEEDS_FLINT:
        pytest.importorskip("flint")
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- paths.track_hooks

def test_track_init_signed_lam(monkeypatch):
    # mutant kernels:180 (abs): kn = lam + |p0| -- the cancellation ratio wrong wherever lam < 0
    from symbt.numeric.float64 import kernels

    monkeypatch.setitem(kernels.HOOKS, "track_init", planted(kernels._track_init, "abs(lam) + abs(p0), abs(a0)",
                                                             "lam + abs(p0), abs(a0)"))
    assert status("paths.track_hooks") == "failed"


def test_rescale_inverted(monkeypatch):
    # mutant kernels:200 (branch, uncovered): the monodromy shrunk where it is small and kept where it is past 2**400
    from symbt.numeric.float64 import kernels

    monkeypatch.setitem(kernels.HOOKS, "rescale", planted(kernels._rescale, "if aux[0] > _BIG or aux[1] > _BIG:",
                                                          "if not (aux[0] > _BIG or aux[1] > _BIG):"))
    assert status("paths.track_hooks") == "failed"


def test_rescale_only_first_track(monkeypatch):
    # a neighbour: the Ba test dropped (a monodromy whose second column grows alone is never shrunk)
    from symbt.numeric.float64 import kernels

    monkeypatch.setitem(kernels.HOOKS, "rescale", planted(kernels._rescale, "if aux[0] > _BIG or aux[1] > _BIG:",
                                                          "if aux[0] > _BIG:"))
    assert status("paths.track_hooks") == "failed"


def test_bounded_edge(monkeypatch):
    # mutant kernels:259 (compare, uncovered): |x| <= 1e300 takes 1e300 itself in range
    from symbt.numeric.float64 import kernels

    monkeypatch.setitem(kernels.HOOKS, "bounded", planted(kernels._bounded, "return abs(x) < 1e300",
                                                          "return abs(x) <= 1e300"))
    assert status("paths.track_hooks") == "failed"


# --------------------------------------------------------------------------- paths.kappa_rows

def test_rows_rescaled_the_wrong_way(monkeypatch):
    # mutant condition:244 (unary-minus, uncovered): ldexp(x, f) -- the rows' rescaling multiplies by 2**f
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_rescaled", planted(condition._rescaled,
                                                        "return [np.ldexp(x, -f) for x in xs], e + f",
                                                        "return [np.ldexp(x, f) for x in xs], e + f"))
    assert status("paths.kappa_rows.n2") == "failed"


def test_rows_exponent_not_recorded(monkeypatch):
    # a neighbour: the rows rescaled but the exponent not kept
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_rescaled", planted(condition._rescaled,
                                                        "return [np.ldexp(x, -f) for x in xs], e + f",
                                                        "return [np.ldexp(x, -f) for x in xs], e"))
    assert status("paths.kappa_rows.n2") == "failed"


# --------------------------------------------------------------------------- paths.mp_verdict

def test_mp_verdict_trace_codes_swapped(monkeypatch):
    # mutant rows:60 (branch, uncovered): TRACE1 for a band at lam2 and TRACE2 for one at lam1
    from symbt.numeric.float64 import rows

    monkeypatch.setattr(rows, "_mp_verdict", planted(rows._mp_verdict, 'return (TRACE2 if "lam2" in str(err)',
                                                     'return (TRACE2 if not ("lam2" in str(err))'))
    assert status("paths.mp_verdict.n3") == "failed"


# --------------------------------------------------------------------------- paths.jacobian_dual

def test_jacobian_dual_zero_rows(monkeypatch):
    # mutant lohner_checks:166 (constant, uncovered): the seed derivatives as 0 x n matrices
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "jacobian_dual", planted(lohner_checks.jacobian_dual, "arb_mat(1, n, [1 if",
                                                                "arb_mat(0, n, [1 if"))
    assert status("paths.jacobian_dual.n3") == "failed"


def test_jacobian_dual_seed_shifted(monkeypatch):
    # a neighbour: every variable seeded with the next one's direction
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "jacobian_dual", planted(lohner_checks.jacobian_dual, "1 if k == i else 0",
                                                                "1 if k == (i + 1) % n else 0"))
    assert status("paths.jacobian_dual.n3") == "failed"


# --------------------------------------------------------------------------- paths.inline_boolop

def test_inline_boolop_second_operand_twice(monkeypatch):
    # mutant inline:252 (constant): a BoolOp's first operand replaced by its second, rewritten
    from symbt.numeric.core import inline

    monkeypatch.setattr(inline._Bodies, "expr", planted(inline._Bodies.expr,
                                                        "e.values[0] = self.expr(e.values[0], pre, at)",
                                                        "e.values[0] = self.expr(e.values[1], pre, at)"))
    assert status("paths.inline_boolop") == "failed"


# --------------------------------------------------------------------------- paths.side_by_side

def test_side_by_side_span_minimum(monkeypatch):
    # mutant condition:481 (min-max): the span of an entry as min(max, -min): a product past 2**500 whose entries
    # keep one sign over the rows is taken as in range, and not renormalised
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_both_in_range", planted(condition._both_in_range,
                                                             "spans = np.maximum(S.max(axis=2)",
                                                             "spans = np.minimum(S.max(axis=2)"))
    assert status("paths.side_by_side.n3") == "failed"

