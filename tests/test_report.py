"""Reports: the JSON document against its shipped schema, XML-safe JUnit, evidence and scope shown,
missing values tolerated, the progress display."""
from __future__ import annotations

import io
import json
import xml.etree.ElementTree as ET

import pytest

from symbt.claims.base import Claim, ClaimResult, Outcome
from symbt.report import format_markdown, format_short, format_table, junit_xml, schema, to_json
from symbt.report.json import dumps
from symbt.report.progress import Progress


def _c(cid="demo.n2", scene="demo", **kw):
    return Claim(cid, kw.pop("equation", "eq:demo"), kw.pop("statement", "a = b"), check=None, scene=scene, **kw)


def _results():
    """One result of each status; some with every value missing."""
    return [
        ClaimResult(_c("v"), Outcome("verified", "exact: together/cancel", residual=0.0, evidence="proof",
                                     seconds=0.1)),
        ClaimResult(_c("v.bare"), Outcome("verified", "")),                      # nothing but a status
        ClaimResult(_c("e", scene="other", N=3, where="Section 4"),
                    Outcome("erratum", "printed: numeric | corrected: numeric", residual=2.0, digits=55.0,
                            printed="P = 1", corrected="P = -1", counterexample={"p": ["1", "2"], "q": "0.5"},
                            evidence="sampled", scope="printed fails in 3 of 8 cells; corrected holds in all 8",
                            n_scope=[2, 3], cells=[{"cell": {"b": 1}, "n": 4, "printed_holds": False}])),
        ClaimResult(_c("f"), Outcome("failed", "numeric", residual=float("inf"),
                                     counterexample={"x": "1.5"}, detail="bell\x07 nul\x00 esc\x1b end\ufffe",
                                     evidence="sampled")),
        ClaimResult(_c("s"), Outcome("skipped", "none", detail="optional dependency missing: flint")),
    ]


def _validate(doc):
    jsonschema = pytest.importorskip("jsonschema")
    jsonschema.Draft202012Validator.check_schema(schema())
    jsonschema.Draft202012Validator(schema()).validate(doc)


def test_json_report_validates_against_the_shipped_schema():
    doc = json.loads(dumps(_results()))        # through text: what a consumer reads
    assert doc["schema_version"] == "1.3" and doc["generator"].startswith("symbt ")
    _validate(doc)
    f = next(c for c in doc["claims"] if c["id"] == "f")
    assert f["residual"] == "inf" and f["evidence"] == "sampled"         # non-finite numbers as strings
    e = next(c for c in doc["claims"] if c["id"] == "e")
    assert e["scope"].startswith("printed fails") and e["n_scope"] == [2, 3] and e["where"] == "Section 4"
    assert doc["summary"] == {"total": 5, "verified": 2, "erratum": 1, "failed": 1, "inconclusive": 0, "todo": 0,
                              "skipped": 1, "seconds": 0.1, "ok": False}


def test_schema_rejects_what_it_should():
    jsonschema = pytest.importorskip("jsonschema")
    doc = to_json(_results())
    for mutate in (lambda d: d["claims"][0].update(status="bogus"),
                   lambda d: d["claims"][0].update(evidence="vibes"),
                   lambda d: d["claims"][0].pop("evidence"),
                   lambda d: d["summary"].update(ok="yes"),
                   lambda d: d.update(schema_version="2.0")):
        bad = json.loads(json.dumps(doc))
        mutate(bad)
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.Draft202012Validator(schema()).validate(bad)


def test_real_results_validate(tmp_path):
    from symbt import verify

    _validate(to_json(verify(["tn2", "n3-hamiltonians.tra"])))


def test_schema_is_shipped_next_to_the_reporter():
    from importlib.resources import files

    assert json.loads(files("symbt.report").joinpath("verify.schema.json").read_text())["title"]


def test_junit_escapes_what_xml_forbids():
    xml = junit_xml(_results())
    root = ET.fromstring(xml.encode())                  # parses: no forbidden character survived
    case = {tc.get("name"): tc for tc in root.iter("testcase")}["f"]
    text = case.find("failure").text
    assert "bell\\x07 nul\\x00 esc\\x1b end\\ufffe" in text
    assert root.find("testsuite").get("failures") == "1" and root.find("testsuite").get("skipped") == "1"
    out = {tc.get("name"): tc.find("system-out").text for tc in root.iter("testcase")}
    assert "evidence: sampled" in out["e"] and "scope: printed fails" in out["e"]


def test_short_report_one_line_per_scene_and_per_non_verified_claim():
    text = format_short(_results(), wall=1.5)
    lines = text.splitlines()
    assert lines[0].split() == ["demo", "4", "claims:", "2", "verified,", "1", "failed,", "1", "skipped"]
    assert lines[1].split()[:2] == ["other", "1"]
    failed = [ln for ln in lines if ln.startswith("failed")]
    assert failed and "residual inf" in failed[0] and "[sampled]" in failed[0]
    assert any("counterexample: x = 1.5" in ln for ln in lines)
    erratum = next(ln for ln in lines if ln.startswith("erratum"))
    assert "[sampled]" in erratum and "printed holds in 0 of 1 cells" in erratum     # evidence and cell summary
    assert next(ln for ln in lines if ln.startswith("skipped")).endswith("optional dependency missing: flint")
    assert lines[-2] == "5 claims: 2 verified, 1 erratum, 1 failed, 1 skipped -- FAILED"
    assert lines[-1].startswith("wall time 1.50s (0 of 5 from the cache")


def test_full_table_and_markdown_show_evidence_and_tolerate_missing_values():
    table = format_table(_results())
    rows = {ln.split()[0]: ln.split() for ln in table.splitlines()[2:7]}
    assert rows["v"][3] == "proof" and rows["v.bare"][3] == "-" and rows["s"][3] == "-"
    assert "scope:     printed fails in 3 of 8 cells" in table and "reason: optional dependency" in table
    md = format_markdown(_results())
    assert "| `e` | `eq:demo` | erratum | sampled |" in md and "| `v.bare` | `eq:demo` | verified | - |" in md


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_progress_plain_lines_when_not_a_terminal():
    buf = io.StringIO()
    p = Progress(3, stream=buf)
    p(_c("a"), Outcome("verified", "m", seconds=0.5, cached=True))      # cached: counted, not printed
    p(_c("b"), Outcome("erratum", "m", seconds=1.25))
    p.close()
    assert buf.getvalue() == "[2/3] erratum  b (1.25s)\n"


def test_progress_bar_on_a_terminal_without_rich():
    buf = _Tty()
    p = Progress(4, stream=buf, rich=False)
    p(_c("a"), Outcome("verified", "m", seconds=0.5))
    p(_c("b"), Outcome("verified", "m", seconds=0.5))
    drawn = buf.getvalue()
    assert drawn.startswith("\r[") and "2/4 b" in drawn and "\n" not in drawn
    p.close()
    assert buf.getvalue().endswith("\r" + " " * 100 + "\r")               # the bar is cleared
    quiet = _Tty()
    q = Progress(4, stream=quiet, enabled=False)
    q(_c("a"), Outcome("verified", "m"))
    q.close()
    assert quiet.getvalue() == ""


def test_progress_bar_with_rich():
    pytest.importorskip("rich")
    buf = _Tty()
    p = Progress(2, stream=buf)
    assert p._bar is not None
    p(_c("a"), Outcome("verified", "m"))
    p.close()
    assert "symbt verify" in buf.getvalue()


def test_verify_json_carries_the_coverage_of_the_run(tmp_path):
    """Every labelled display appears: with the claims of the run that check it, or with its reason."""
    from symbt.engine import verify
    from symbt.engine.coverage import coverage_of
    from symbt.paper import DISPLAYS
    from symbt.report.json import schema, to_json

    results = verify(["tn2", "spec.n2"], use_cache=False)
    cov = coverage_of(results)
    assert set(cov) == {lab.label for lab in DISPLAYS}
    assert cov["tn2"] == {"claims": [{"id": "tn2", "status": "verified"}]}
    assert [c["id"] for c in cov["spec"]["claims"]] == ["spec.n2"]
    assert "reason" in cov["rec"] and cov["rec"]["see"]
    assert cov["Dapp"] == {"claims": []}          # a display whose claims were not selected
    doc = to_json(results, coverage=cov)
    jsonschema = pytest.importorskip("jsonschema")
    jsonschema.validate(doc, schema())
    doc["coverage"]["tn2"] = {"claims": [{"id": "tn2"}]}   # a claim without its status is not a coverage entry
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(doc, schema())
