"""JUnit XML: one ``<testcase>`` per claim, for CI systems.

Text that XML 1.0 forbids (control characters other than tab, newline and
carriage return; lone surrogates; U+FFFE, U+FFFF) is written as ``\\xNN`` /
``\\uNNNN`` escapes, so a claim's detail can never make the file unreadable.

>>> xml_safe("bell\\x07 and nul\\x00, tab\\t kept")
'bell\\\\x07 and nul\\\\x00, tab\\t kept'
"""
from __future__ import annotations

import os
import re
import xml.etree.ElementTree as ET
from collections.abc import Sequence

from .._files import write_report
from .text import NOT_OK, evidence_text, outcome_fields, residual_text, summary
from .views import ResultView

__all__ = ["write_junit", "junit_xml", "xml_safe"]

_FORBIDDEN = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def xml_safe(text: object) -> str:
    """``text`` with every character XML 1.0 forbids replaced by a visible escape."""
    s = "" if text is None else str(text)
    return _FORBIDDEN.sub(lambda m: f"\\x{ord(m.group()):02x}" if ord(m.group()) < 0x100
                          else f"\\u{ord(m.group()):04x}", s)


def junit_xml(results: Sequence[ResultView], *, suite: str = "symbt.verify") -> str:
    """JUnit XML text: one testcase per claim; ``failed``, ``inconclusive`` and ``todo`` ->
    ``<failure type="failed|inconclusive|todo">``, ``skipped`` -> ``<skipped>``.

    Errata are passing test cases (the paper is wrong, the package is right);
    their printed/corrected statements and scope go to ``system-out``.

    >>> from symbt.claims.base import Claim, ClaimResult, Outcome
    >>> r = ClaimResult(Claim("t", "eq", "s", check=None), Outcome("inconclusive", "numeric", detail="cannot tell"))
    >>> '<failure message="t (eq. eq) is inconclusive" type="inconclusive">' in junit_xml([r])
    True
    """
    s = summary(results)
    failures = sum(s[k] for k in NOT_OK)
    ts = ET.Element("testsuite", name=xml_safe(suite), tests=str(s["total"]), failures=str(failures),
                    errors="0", skipped=str(s["skipped"]), time=f"{s['seconds']:.3f}")
    for r in results:
        o = r.outcome
        tc = ET.SubElement(ts, "testcase", classname=xml_safe(f"symbt.{r.claim.scene}"), name=xml_safe(r.claim.id),
                           time=f"{o.seconds or 0:.3f}")
        info = [f"equation: {r.claim.equation}", f"status: {o.status}", f"evidence: {evidence_text(o)}",
                f"method: {o.method}", f"residual: {residual_text(o)}"]
        info += [f"{name}: {value}" for name, value in outcome_fields(o, limit=50)]
        if o.status in NOT_OK:
            verb = "failed" if o.status == "failed" else f"is {o.status}"
            f = ET.SubElement(tc, "failure", message=xml_safe(f"{r.claim.id} (eq. {r.claim.equation}) {verb}"),
                              type=o.status)
            f.text = xml_safe("\n".join(info + [o.detail or ""]))
        elif o.status == "skipped":
            ET.SubElement(tc, "skipped", message=xml_safe(o.detail or "skipped"))
        ET.SubElement(tc, "system-out").text = xml_safe("\n".join(info))
    suites = ET.Element("testsuites")
    suites.append(ts)
    ET.indent(suites)
    return '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n"


def write_junit(results: Sequence[ResultView], path: str | os.PathLike[str], *, suite: str = "symbt.verify") -> None:
    write_report(path, junit_xml(results, suite=suite))
