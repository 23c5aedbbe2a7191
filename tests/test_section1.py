"""The claims on Sections 1-2 specialised to the Toda BT (scenes ``general`` and ``single-bt-map``):
pinned statuses, evidence and n_scope on every outcome, every cell sampled, and the checks kill mutants."""
from __future__ import annotations

import pytest

from symbt import engine
from symbt.claims import REGISTRY, load_all
from symbt.engine.mutate import mutate_claim

SCENES = ["general", "single-bt-map"]
#: every other claim of these scenes is verified
EXPECTED_ERRATA = {"spe.n2", "spe.n3"}
IDS = {"intdis.n2", "intdis.n3", "speccurve", "backlund.n2", "backlund.n3", "canonical.n2", "canonical.n3",
       "intertwin.n2", "intertwin.n3", "spe.n2", "spe.n3", "PoincareCartan", "hamil.n2", "hamil.n3", "ICI.n2",
       "ICI.n3", "local.n2", "local.n3", "LhDhDL.n2", "LhDhDL.n3"}


@pytest.fixture(scope="module")
def results():
    load_all()
    return {r.claim.id: r for r in engine.run(engine.select(SCENES), use_cache=False, jobs=1)}


def test_the_claims_and_their_statuses(results):
    assert set(results) == IDS
    for cid, r in results.items():
        assert r.status == ("erratum" if cid in EXPECTED_ERRATA else "verified"), (cid, r.outcome.detail[:300])


def test_every_outcome_has_evidence_and_n_scope(results):
    for cid, r in results.items():
        o = r.outcome
        assert o.evidence in ("proof", "sampled"), cid
        assert o.n_scope == "all" or o.n_scope == [r.claim.N], cid
        if o.n_scope == "all":
            assert "N" in o.detail, cid      # the argument for all N is stated


def test_sampled_claims_sample_every_cell(results):
    for cid, r in results.items():
        o = r.outcome
        if o.evidence != "sampled":
            continue
        cells = {tuple(sorted(c["cell"].items())) for c in o.cells}
        single = r.claim.scene == "single-bt-map" or cid.startswith("intertwin")
        assert len(cells) == (2 if single else 4), cid
        assert all(c["n"] >= 16 for c in o.cells), cid
        assert o.scope.startswith("printed statement"), cid


def test_spe_erratum_holds_corrected_everywhere(results):
    for cid in EXPECTED_ERRATA:
        o = results[cid].outcome
        assert o.counterexample and o.printed and o.corrected
        assert o.residual > 1e-3
        assert "corrected statement holds in all 4 cells" in o.scope


@pytest.mark.parametrize("cid", ["intertwin.n2", "ICI.n2", "speccurve"])
def test_checks_kill_their_mutants(cid):
    load_all()
    rec = mutate_claim(REGISTRY[cid], limit=6)
    assert rec.mutants > 0 and not rec.survivors and rec.killed == rec.mutants - len(rec.equivalent)
