"""The claims engine itself: verdicts, errata, caching, scenes, reports, CLI."""
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

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


def test_scene_selection_and_pseudo_scenes():
    load_all()
    sel = engine.select(["n2"])
    assert sel and all(c.N == 2 for c in sel)
    sel = engine.select(["toda"])
    assert {c.scene for c in sel} == {"toda"}
    assert [c.id for c in engine.select(["tn2"])] == ["tn2"]
    with pytest.raises(KeyError):
        engine.select(["no-such-scene"])


def test_n2_scene_builds_no_n3_model():
    # budget=None runs the claims in this process (not in a worker), where the memo can be read
    code = ("import sys; from symbt import engine; import symbt.symbolic.toda as t;"
            "engine.run(engine.select(['tn2', 'th1th2.trace', 'lax.n2']), jobs=1, use_cache=False, budget=None);"
            "print(t.toda_model.cache_info().currsize);"
            "print('scipy' in sys.modules, 'matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split("\n")
    assert out[0] == "1"          # only the N=2 model was built
    assert out[1] == "False False"  # a symbolic scene imports neither scipy nor matplotlib


def test_cache_reuse_corruption_and_staleness(tmp_path, monkeypatch):
    monkeypatch.setenv("SYMBT_CACHE_DIR", str(tmp_path))
    load_all()
    c = REGISTRY["tn2"]
    first = engine.run([c])[0].outcome
    assert not first.cached
    second = engine.run([c])[0].outcome
    assert second.cached and second.status == first.status
    f = engine.cache_file(c)
    f.write_text("{not json")
    assert not engine.run([c])[0].outcome.cached           # corrupt -> recomputed
    data = json.loads(f.read_text())
    data["key"] = "0" * 64
    f.write_text(json.dumps(data))
    assert not engine.run([c])[0].outcome.cached           # stale key -> recomputed
    assert not engine.run([c], use_cache=False)[0].outcome.cached


def test_parallel_run_matches_serial():
    load_all()
    claims = engine.select(["single-bt"])
    a = [r.outcome.status for r in engine.run(claims, use_cache=False, jobs=1)]
    b = [r.outcome.status for r in engine.run(claims, use_cache=False, jobs=2)]
    assert a == b


def test_cli_json_junit_and_exit_code(tmp_path):
    js, ju = tmp_path / "r.json", tmp_path / "r.xml"
    p = subprocess.run([sys.executable, "-m", "symbt", "verify", "--scene", "toda", "--scene", "appendix-a",
                        "--json", str(js), "--junit", str(ju), "-j", "1", "-v"], capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "claim" in p.stdout and "equation" in p.stdout and "evidence" in p.stdout  # -v: the full table
    data = json.loads(js.read_text())
    ids = {c["id"] for c in data["claims"]}
    assert {"lax.n2", "Hj.n4", "D1D2"} <= ids
    for c in data["claims"]:
        for key in ("id", "equation", "status", "method", "seconds", "residual"):
            assert key in c
        if c["status"] == "erratum":
            assert c["printed"] and c["corrected"] and c["counterexample"]
    assert data["summary"]["failed"] == 0 and data["summary"]["total"] == len(data["claims"])
    root = ET.parse(ju).getroot()
    cases = root.findall(".//testcase")
    assert len(cases) == len(data["claims"])
    p = subprocess.run([sys.executable, "-m", "symbt", "verify", "--scene", "nonexistent"], capture_output=True)
    assert p.returncode == 2


def test_failed_claim_gives_exit_status_1(tmp_path, monkeypatch):
    from symbt import cli
    from symbt.claims import base

    @claim("zz.test.fails", equation="none", scene="zz-test", statement="1 = 2")
    def c():
        return from_decision(decide(sp.Integer(1), 2))

    base.scene("zz-test", "temporary")
    try:
        assert cli.main(["verify", "--scene", "zz-test", "-q", "-j", "1"]) == 1
    finally:
        base.REGISTRY.pop("zz.test.fails")
        base.SCENES.pop("zz-test")


def test_outcome_roundtrip():
    o = Outcome("erratum", "m", residual=1.0, printed="a", corrected="b", counterexample={"x": "1"})
    assert Outcome.from_dict(json.loads(json.dumps(o.to_dict()))) == o
