"""Mutation testing: every claim exposes what it checks, and its check kills mutants of it.

The full run (every mutant of every claim) is recorded in BENCHMARKS.md; here a seeded subset of
claims and mutants runs in the test-suite's time.
"""
from __future__ import annotations

import random
from pathlib import Path

import pytest
import sympy as sp

from symbt.claims import REGISTRY, load_all
from symbt.engine.mutate import mutate_claim, summary
from symbt.proof.mutation import OPERATORS, mutants, mutate_value

#: scenes whose claims check symbt's own checker, library and numeric paths against statements of known truth:
#: a claim there may have no printed statement to perturb; it is then shown to fail on a planted bug in one of
#: tests/test_killers*.py instead
PLANTED_BUG_SCENES = ("checker", "library", "numeric-paths")


def test_every_claim_exposes_statement_parts():
    load_all()
    missing = [c.id for c in REGISTRY.values() if c.parts is None and c.scene not in PLANTED_BUG_SCENES]
    assert not missing, f"claims whose statement cannot be mutated: {missing}"
    killers = "".join(p.read_text(encoding="utf-8") for p in sorted(Path(__file__).parent.glob("test_killers*.py")))
    untested = sorted({c.id for c in REGISTRY.values() if c.parts is None and c.scene in PLANTED_BUG_SCENES
                       and c.func.__name__ not in killers and f'"{c.id}"' not in killers})
    assert not untested, f"claims without parts and without a planted-bug test: {untested}"



def test_operators_are_values_applied_by_one_function():
    x, y = sp.symbols("x y")
    ops = {m.operator for m in mutants(x + 2 * y - sp.Abs(x))}
    assert {"flip_sign", "drop_term", "change_const", "perturb", "convention"} <= ops
    assert [op.name for op in OPERATORS] == list(OPERATORS._fields)
    p1, p2 = sp.symbols("p1 p2")
    swaps = [m.expr for m in mutants(p1 ** 2 + p2) if m.operator == "swap_index"]
    assert p2 ** 2 + p2 in swaps and p1 ** 2 + p1 in swaps
    assert [m.expr for m in mutate_value(1)] == [-1]
    assert mutate_value("abc0")[0].expr == "abc1"


SEED_CLAIMS = 14


@pytest.fixture(scope="module")
def sample():
    load_all()
    # the paper's claims (the claims about what ships are mutated in tests/test_claims_shipped.py); claims without
    # statement parts have nothing to mutate (their planted-bug tests: tests/test_killers*.py), and drawing them only
    # shifted the sample whenever such a claim was added
    ids = sorted(c.id for c in REGISTRY.values() if not c.deep and not c.requires and c.scene != "shipped"
                 and not c.id.startswith("Hdiscr.routes") and c.parts is not None)
    chosen = random.Random(2026).sample(ids, SEED_CLAIMS)
    return [mutate_claim(REGISTRY[cid], limit=3, seed=1).to_dict() for cid in chosen]


def test_seeded_subset_every_claim_kills_and_the_score_is_high(sample):
    s = summary(sample)
    assert s["mutants"] >= 2 * SEED_CLAIMS
    assert not s["claims_killing_none"], s["claims_killing_none"]
    assert s["score"] >= 0.95, [r["survivors"] for r in sample if r["survivors"]]
