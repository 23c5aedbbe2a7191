"""The outcome statuses ``inconclusive`` and ``todo``: not ok everywhere (exit 1, failed pytest items,
JUnit failures), shown by every reporter, in the JSON schema, never cached as a todo."""
from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from importlib import metadata

import pytest

from symbt import cli
from symbt.claims import base
from symbt.claims.base import NOT_OK, STATUSES, Claim, ClaimResult, Outcome, from_decision, inconclusive, judge, todo
from symbt.engine import cache
from symbt.proof import Verdict
from symbt.proof.verdict import LATEX_COLOURS, STATUS_COLOURS
from symbt.report import format_markdown, format_short, format_table, junit_xml, schema, to_json
from symbt.report.html import result_html, result_latex, scene_html
from symbt.report.text import result_text, summary

pytest_plugins = ["pytester"]

NOISE = Verdict.sampled(3e-21, tol=1e-22, error=1e-21, method="numeric: 30 digits", counterexample={"x": "1"})
WRONG = Verdict.sampled(0.5, tol=1e-22, error=1e-30, method="numeric: 30 digits", counterexample={"x": "2"})
RIGHT = Verdict.sampled(1e-40, tol=1e-22, error=1e-40, method="numeric: 30 digits")


def _r(cid: str, out: Outcome) -> ClaimResult:
    return ClaimResult(Claim(cid, "eq:" + cid, "a = b", check=None, scene="demo"), out)


def _results() -> list[ClaimResult]:
    return [_r("v", Outcome("verified", "exact", 0.0, evidence="proof")),
            _r("i", from_decision(NOISE)),
            _r("t", todo())]


def test_statuses_and_helpers():
    assert {"inconclusive", "todo"} <= set(STATUSES) and set(NOT_OK) == {"failed", "inconclusive", "todo"}
    o = inconclusive("numeric: 30 digits", detail="cannot tell", residual=1e-22, digits=21.0, evidence="sampled")
    assert (o.status, o.residual, o.digits, o.evidence, o.detail) == ("inconclusive", 1e-22, 21.0, "sampled",
                                                                       "cannot tell")
    assert todo().status == "todo" and todo("write me").detail == "write me"
    with pytest.raises(ValueError):
        Outcome("maybe", "m")


def test_from_decision_and_judge_never_turn_noise_into_failed_or_verified():
    o = from_decision(NOISE)
    assert o.status == "inconclusive" and o.counterexample is None and "inconclusive" in o.detail
    assert from_decision(WRONG).status == "failed" and from_decision(RIGHT).status == "verified"
    assert judge(NOISE, printed="P").status == "inconclusive"
    assert judge(NOISE, printed="P", corrected="C", corrected_check=lambda: RIGHT).status == "inconclusive"
    o = judge(WRONG, printed="P", corrected="C", corrected_check=lambda: NOISE)
    assert o.status == "inconclusive" and "correction cannot be decided" in o.detail
    assert o.counterexample == {"x": "2"}                     # the printed statement's counterexample is kept
    assert judge(WRONG, printed="P", corrected="C", corrected_check=lambda: RIGHT).status == "erratum"


def test_a_todo_stub_covers_no_lattice_size():
    c = base.claim("zz.todo", equation="zz", scene="zz", statement="s", N=3, register=False)(todo)
    assert c.run().status == "todo" and c.run().n_scope is None


def test_summary_and_text_reports():
    s = summary(_results())
    assert (s["verified"], s["inconclusive"], s["todo"], s["ok"]) == (1, 1, 1, False)
    assert not summary([_r("t", todo())])["ok"]
    short = format_short(_results())
    lines = short.splitlines()
    assert lines[0].split(None, 1) == ["demo", "3 claims: 1 verified, 1 inconclusive, 1 todo"]
    assert any(ln.startswith("inconclusive i") and "INCONCLUSIVE (cannot tell)" in ln for ln in lines)
    assert any(ln.startswith("todo") and "no check written yet" in ln for ln in lines)
    assert lines[-1] == "3 claims: 1 verified, 0 errata, 0 failed, 1 inconclusive, 1 todo, 0 skipped -- FAILED"
    table = format_table(_results())
    assert "[inconclusive] i (eq. eq:i)" in table and "[todo] t (eq. eq:t)" in table
    assert "reason: no check written yet" in table
    assert "detail: inconclusive" in result_text(_results()[1])


def test_junit_marks_them_failures_with_their_type():
    root = ET.fromstring(junit_xml(_results()).split("\n", 1)[1])
    suite = root.find("testsuite")
    assert suite.get("failures") == "2"
    cases = {tc.get("name"): tc for tc in suite.iter("testcase")}
    assert cases["v"].find("failure") is None
    assert cases["i"].find("failure").get("type") == "inconclusive"
    assert cases["t"].find("failure").get("type") == "todo"
    assert "is todo" in cases["t"].find("failure").get("message")


def test_json_schema_1_2_and_the_other_reporters():
    doc = json.loads(json.dumps(to_json(_results())))
    assert doc["schema_version"] == "1.3"
    assert doc["summary"]["inconclusive"] == 1 and doc["summary"]["todo"] == 1 and doc["summary"]["ok"] is False
    jsonschema = pytest.importorskip("jsonschema")
    jsonschema.Draft202012Validator(schema()).validate(doc)
    doc["claims"][0]["status"] = "unknown"
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft202012Validator(schema()).validate(doc)
    md = format_markdown(_results())
    assert "| `i` | `eq:i` | inconclusive |" in md and "| `t` | `eq:t` | todo | - |" in md
    for status in ("inconclusive", "todo"):
        assert status in STATUS_COLOURS and status in LATEX_COLOURS
    card = result_html(_results()[1])
    assert STATUS_COLOURS["inconclusive"] in card and "symbt-inconclusive" in card
    assert LATEX_COLOURS["todo"] in result_latex(_results()[2])
    assert "1 inconclusive, 1 todo" in scene_html(_results())


def test_cache_never_keeps_a_todo_and_rejects_a_verified_nan(monkeypatch, tmp_path):
    c = base.claim("zz.cache", equation="zz", scene="zz", statement="s", register=False)(todo)
    cache.store(c, todo())
    assert not cache.cache_file(c).exists()
    cache.store(c, from_decision(NOISE))               # an inconclusive outcome is a result: cached
    assert cache.load_cached(c).status == "inconclusive"
    cache.store(c, Outcome("verified", "numeric", residual=math.nan, evidence="sampled"))
    assert cache.cache_file(c).exists() and cache.load_cached(c) is None
    cache.store(c, Outcome("verified", "numeric", residual=1e-40, evidence="sampled"))
    assert cache.load_cached(c).status == "verified"


@pytest.fixture
def zz_claims():
    from symbt.claims import load_all

    load_all()
    base.scene("zz-status", "temporary")
    made = [base.claim("zz.st.noise", equation="zz", scene="zz-status", statement="n")(lambda: from_decision(NOISE)),
            base.claim("zz.st.todo", equation="zz", scene="zz-status", statement="t")(todo),
            base.claim("zz.st.ok", equation="zz", scene="zz-status", statement="o")(lambda: from_decision(RIGHT))]
    yield made
    for c in made:
        base.REGISTRY.pop(c.id, None)
    base.SCENES.pop("zz-status", None)


def test_verify_exits_1_on_inconclusive_or_todo(capsys, zz_claims):
    assert cli.main(["verify", "--scene", "zz-status", "--no-cache"]) == 1
    out = capsys.readouterr().out.strip().splitlines()
    assert out[-2] == "3 claims: 1 verified, 0 errata, 0 failed, 1 inconclusive, 1 todo, 0 skipped -- FAILED"
    assert cli.main(["verify", "--scene", "zz.st.ok", "--no-cache"]) == 0
    capsys.readouterr()
    assert cli.main(["verify", "--scene", "zz.st.todo", "--no-cache", "-q"]) == 1


CONFTEST = '''
from symbt.claims.base import REGISTRY, claim, from_decision, scene, todo
from symbt.proof import Verdict

scene("zz-plug", "statuses in the plugin")
if "zz.pl.noise" not in REGISTRY:
    @claim("zz.pl.noise", equation="zz-eq", scene="zz-plug", statement="noise")
    def _noise():
        return from_decision(Verdict.sampled(3e-21, tol=1e-22, error=1e-21, method="numeric: 30 digits"))

    claim("zz.pl.todo", equation="zz-eq", scene="zz-plug", statement="stub")(todo)
'''


def test_pytest_items_fail_naming_the_status(zz_claims, pytester):
    pytester.makeconftest(CONFTEST)
    try:
        eps = metadata.entry_points(group="pytest11")       # the installed entry point, else -p
        plugin = [] if any(ep.value == "symbt.pytest_plugin" for ep in eps) else ["-p", "symbt.pytest_plugin"]
        r = pytester.runpytest(*plugin, "-p", "no:cacheprovider", "-p", "no:xdist", "-p", "no:hypothesispytest",
                               "--symbt", "--symbt-scene", "zz-plug", "--symbt-no-cache")
    finally:
        for cid in ("zz.pl.noise", "zz.pl.todo"):
            base.REGISTRY.pop(cid, None)
        base.SCENES.pop("zz-plug", None)
    r.assert_outcomes(failed=2)
    out = r.stdout.str()
    assert "claim zz.pl.noise (eq. zz-eq) is inconclusive (cannot tell)" in out and "status:    inconclusive" in out
    assert "claim zz.pl.todo (eq. zz-eq) is a todo stub (no check written yet)" in out
