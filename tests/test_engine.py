"""The claims engine itself: verdicts, errata, caching, scenes, reports, CLI."""
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import mpmath as mp
import pytest
import sympy as sp

from symbt import engine
from symbt.claims import REGISTRY, load_all
from symbt.claims.base import Outcome, claim, from_decision, judge
from symbt.proof import decide


def test_false_identity_is_reported_failed():
    x = sp.Symbol("x", real=True)

    @claim("test.false", equation="none", scene="test", statement="(x+1)^2 = x^2 + 1", register=False)
    def c():
        return from_decision(decide((x + 1) ** 2, x ** 2 + 1))

    out = c.run()
    assert out.status == "failed"
    assert out.counterexample and "x" in out.counterexample
    assert out.residual > 1e-3


def test_erratum_needs_a_verified_correction():
    x = sp.Symbol("x", positive=True)
    printed = decide(sp.sqrt(x ** 2) + 1, x)
    out = judge(printed, printed="sqrt(x^2)+1 = x", corrected="sqrt(x^2) = x",
                corrected_check=lambda: decide(sp.sqrt(x ** 2), x))
    assert out.status == "erratum" and out.counterexample
    bad = judge(printed, printed="p", corrected="c", corrected_check=lambda: decide(x, x + 1))
    assert bad.status == "failed"


def test_exception_in_check_is_a_failure():
    @claim("test.crash", equation="none", scene="test", statement="crashes", register=False)
    def c():
        raise RuntimeError("boom")

    out = c.run()
    assert out.status == "failed" and "boom" in out.detail


def test_true_identity_simplify_cannot_decide_is_decided():
    # eta is algebraic: eta^2 = mu^2 + w.  Without the relation simplify sees a nonzero expression.
    eta, mu, w = sp.symbols("eta mu w", real=True)
    expr = (eta - mu) * (eta + mu) * (eta ** 2 + mu ** 2) - w * (w + 2 * mu ** 2)
    assert sp.simplify(expr) != 0
    d = decide(expr, 0, relations={eta: eta ** 2 - mu ** 2 - w})
    assert d.verdict == "proved" and d.exact


def test_exponential_identity_decided_exactly_by_E_substitution():
    q1, q2 = sp.symbols("q1 q2", real=True)
    lhs = 4 * sp.cosh(q1 - q2) ** 2 - 2
    rhs = 2 * sp.cosh(2 * q1 - 2 * q2)
    d = decide(lhs, rhs)
    assert d.verdict == "proved" and "exp->monomials" in d.method


def test_wrong_branch_is_caught():
    """If the real Phi ignored the branch, the newkmu correction would no longer verify."""
    load_all()
    c = REGISTRY["newkmu.n2"]
    parts = c.parts()
    b = sp.Symbol("branch", real=True)
    no_branch = parts.corrected["Phi"].subs(b, 1)
    assert c.run_with(parts.replace("corrected", "Phi", no_branch)).status == "failed"
    assert c.run_with(parts).status == "erratum"


def test_mutation_harness_kills_and_recognises_equivalents():
    from symbt.engine.mutate import mutate_claim, summary

    load_all()
    rec = mutate_claim(REGISTRY["newkmu.n2"], limit=6, seed=1).to_dict()
    assert rec["side"] == "corrected" and rec["mutants"] == 6
    assert rec["killed"] + rec["equivalent_count"] + len(rec["survivors"]) == 6
    assert rec["killed"] >= 1 and not rec["survivors"]
    s = summary([rec])
    assert s["mutants"] == 6 and s["score"] == 1.0
