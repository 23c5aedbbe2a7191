"""The paper's claims: every label of the core issue is covered and no claim fails.

The expected errata are the outcome of the checks (see docs/claims.md, "Errata found"); if a
derivation changes so that a claim changes status, this test fails.
"""
import re
from pathlib import Path

import pytest

from symbt import engine
from symbt.claims import REGISTRY, load_all

PAPER = Path(__file__).resolve().parents[1].parent / "shared" / "paper" / "backlund-toda.tex"

CORE_LABELS = ["eq:lax", "tra", "Hj", "tn2", "n3-hamiltonians", "th1th2", "dj", "alphabeta", "ptp",
               "d1", "v1", "hd", "v11", "tiltil", "D1D2", "Dapp", "D", "new", "l1l2", "v1v2", "xy",
               "lam0mu", "GF", "nlocal", "daj", "xyqqt", "imptransf", "newgf", "vqqtmu", "newkmu",
               "rte", "2122", "spec", "toy-F", "toy-dFdmu", "toy-Phihat", "toy-K"]

EXPECTED_ERRATA = {"n3-hamiltonians.tra", "n3-hamiltonians.involution", "v1v2.n2", "v1v2.n3", "spec.n2",
                   "2122", "rte", "newkmu.n2", "newkmu.n3", "spec.n3"}

CORE_SCENES = ["toy", "toda", "single-bt", "appendix-a", "map", "generating", "phi"]


@pytest.fixture(scope="module")
def core_results():
    load_all()
    return engine.run(engine.select(CORE_SCENES), use_cache=False, jobs=2)


def test_every_core_label_has_a_claim():
    load_all()
    labels = {c.equation for c in REGISTRY.values()}
    missing = [lab for lab in CORE_LABELS if lab not in labels]
    assert not missing


def test_labels_are_the_papers_or_say_where():
    if not PAPER.exists():
        pytest.skip("paper not found next to the checkout")
    tex_labels = set(re.findall(r"\\label\{([^}]*)\}", PAPER.read_text()))
    load_all()
    for c in REGISTRY.values():
        assert c.equation in tex_labels or c.where, f"{c.id}: label {c.equation!r} not in the paper and no 'where'"


def test_no_core_claim_fails(core_results):
    bad = [(r.claim.id, r.outcome.detail[:200]) for r in core_results if r.outcome.status == "failed"]
    assert not bad


def test_errata_are_exactly_the_expected_ones(core_results):
    errata = {r.claim.id for r in core_results if r.outcome.status == "erratum"}
    assert errata == EXPECTED_ERRATA


def test_errata_carry_counterexample_and_correction(core_results):
    for r in core_results:
        o = r.outcome
        if o.status == "erratum":
            assert o.printed and o.corrected and o.counterexample, r.claim.id
            assert o.residual is not None and o.residual > 1e-10, r.claim.id


def test_both_n2_and_n3_where_required(core_results):
    ids = {r.claim.id for r in core_results}
    for stem in ("lax", "tra", "xy", "v1v2", "D", "new", "l1l2", "lam0mu", "newgf", "vqqtmu", "GF",
                 "nlocal", "spec", "newkmu"):
        assert f"{stem}.n2" in ids and f"{stem}.n3" in ids, stem
    assert {"Hj.n2", "Hj.n3", "Hj.n4"} <= ids


def test_methods_are_reported(core_results):
    for r in core_results:
        assert r.outcome.method and r.outcome.method != "exception", r.claim.id
    exact = [r for r in core_results if r.outcome.method.startswith("exact")]
    assert len(exact) > len(core_results) // 2
