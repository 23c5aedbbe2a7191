"""JUnit XML: one ``<testcase>`` per claim, for CI systems."""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET

from .._files import atomic_write
from .text import residual_text, summary

__all__ = ["write_junit"]


def write_junit(results, path, *, suite: str = "symbt.verify") -> None:
    """JUnit XML: one testcase per claim; ``failed`` -> <failure>, ``skipped`` -> <skipped>.

    Errata are passing test cases (the paper is wrong, the package is right);
    their printed/corrected statements go to ``system-out``.
    """
    s = summary(results)
    ts = ET.Element("testsuite", name=suite, tests=str(s["total"]), failures=str(s["failed"]),
                    errors="0", skipped=str(s["skipped"]), time=f"{s['seconds']:.3f}")
    for r in results:
        o = r.outcome
        tc = ET.SubElement(ts, "testcase", classname=f"symbt.{r.claim.scene}", name=r.claim.id,
                           time=f"{o.seconds:.3f}")
        info = [f"equation: {r.claim.equation}", f"status: {o.status}", f"method: {o.method}",
                f"residual: {residual_text(o)}"]
        if o.printed:
            info.append(f"printed: {o.printed}")
        if o.corrected:
            info.append(f"corrected: {o.corrected}")
        if o.counterexample:
            info.append(f"counterexample: {json.dumps(o.counterexample)}")
        if o.status == "failed":
            f = ET.SubElement(tc, "failure", message=f"{r.claim.id} (eq. {r.claim.equation}) failed")
            f.text = "\n".join(info + [o.detail])
        elif o.status == "skipped":
            ET.SubElement(tc, "skipped", message=o.detail or "skipped")
        ET.SubElement(tc, "system-out").text = "\n".join(info)
    suites = ET.Element("testsuites")
    suites.append(ts)
    ET.indent(suites)
    atomic_write(path, '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n")
