"""Reports of claim results: terminal table, JSON and JUnit XML.

JSON schema (``symbt verify --json FILE``)::

    {"claims": [{"id", "equation", "scene", "N", "statement", "where",
                 "status", "method", "seconds", "residual", "digits",
                 "printed", "corrected", "counterexample", "detail", "cached"}, ...],
     "summary": {"total", "verified", "erratum", "failed", "skipped",
                 "seconds", "ok"}}
"""
from __future__ import annotations

import json
import os
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

__all__ = ["summary", "format_table", "format_markdown", "to_json", "write_json", "write_junit", "residual_text"]


def summary(results) -> dict:
    s = {k: 0 for k in ("verified", "erratum", "failed", "skipped")}
    for r in results:
        s[r.outcome.status] += 1
    s["total"] = len(results)
    s["seconds"] = round(sum(r.outcome.seconds for r in results), 3)
    s["ok"] = s["failed"] == 0
    return s


def residual_text(out) -> str:
    if out.status == "skipped":
        return "-"
    if out.method.startswith("exact") and not out.residual:
        return "0 (exact)"
    if out.residual is None:
        return "-"
    txt = f"{out.residual:.1e}"
    if out.digits is not None and out.status == "verified":
        txt += f" ({out.digits:.0f} dig)"
    return txt


def _short_method(m: str) -> str:
    if m.startswith("printed:"):
        corr = m.split("| corrected:", 1)[-1].strip()
        return "corrected by " + _short_method(corr)
    if m.startswith("exact"):
        return ("exact" + (" +relations" if "remainder mod" in m else "") + (" (E=e^q)" if "exp->" in m else "")
                + (" + numeric" if "; numeric:" in m else ""))
    return m.split(";")[0][:40]


def format_table(results, *, width: int = 0) -> str:
    rows = [("claim", "equation", "status", "method", "residual", "time")]
    for r in results:
        o = r.outcome
        t = f"{o.seconds:.2f}s" + (" (cache)" if o.cached else "")
        rows.append((r.claim.id, r.claim.equation, o.status, _short_method(o.method), residual_text(o), t))
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = []
    for k, row in enumerate(rows):
        lines.append("  ".join(cell.ljust(widths[i]) for i, cell in enumerate(row)).rstrip())
        if k == 0:
            lines.append("  ".join("-" * w for w in widths))
    s = summary(results)
    lines.append("")
    lines.append(f"{s['total']} claims: {s['verified']} verified, {s['erratum']} erratum, "
                 f"{s['failed']} failed, {s['skipped']} skipped ({s['seconds']:.1f}s of checks)")
    errata = [r for r in results if r.outcome.status in ("erratum", "failed")]
    for r in errata:
        o = r.outcome
        lines.append("")
        lines.append(f"[{o.status}] {r.claim.id} (eq. {r.claim.equation})")
        if o.printed:
            lines.append(f"  printed:   {o.printed}")
        if o.corrected:
            lines.append(f"  corrected: {o.corrected}")
        if o.counterexample:
            pt = ", ".join(f"{k}={v}" for k, v in list(o.counterexample.items())[:8])
            lines.append(f"  counterexample: {pt}  (residual {o.residual:.3g})" if o.residual is not None
                         else f"  counterexample: {pt}")
        if o.detail:
            lines.append("  " + o.detail.strip().splitlines()[0][:300])
    return "\n".join(lines)


def format_markdown(results) -> str:
    """A Markdown table of the results (used for the README's claim table)."""
    lines = ["| claim | equation | status | method | residual |", "|---|---|---|---|---|"]
    for r in results:
        o = r.outcome
        eq = r.claim.equation.replace("|", "\\|")
        lines.append(f"| `{r.claim.id}` | `{eq}` | {o.status} | {_short_method(o.method)} | {residual_text(o)} |")
    return "\n".join(lines) + "\n"


def to_json(results) -> dict:
    return {"claims": [r.to_dict() for r in results], "summary": summary(results)}


def _atomic_write(path, text: str) -> None:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as fh:
        fh.write(text)
    os.replace(tmp, path)


def write_json(results, path) -> None:
    _atomic_write(path, json.dumps(to_json(results), indent=2, default=str) + "\n")


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
    _atomic_write(path, '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n")
