"""The terminal report: a table of claim results, the summary, the errata."""
from __future__ import annotations

__all__ = ["summary", "format_table", "residual_text", "short_method", "result_text", "point_text"]


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


def short_method(m: str) -> str:
    if m.startswith("printed:"):
        corr = m.split("| corrected:", 1)[-1].strip()
        return "corrected by " + short_method(corr)
    if m.startswith("exact"):
        return ("exact" + (" +relations" if "remainder mod" in m else "") + (" (E=e^q)" if "exp->" in m else "")
                + (" + numeric" if "; numeric:" in m else ""))
    return m.split(";")[0][:40]


def format_table(results, *, width: int = 0) -> str:
    rows = [("claim", "equation", "status", "method", "residual", "time")]
    for r in results:
        o = r.outcome
        t = f"{o.seconds:.2f}s" + (" (cache)" if o.cached else "")
        rows.append((r.claim.id, r.claim.equation, o.status, short_method(o.method), residual_text(o), t))
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


def point_text(point, limit: int = 12) -> str:
    """``k = v, ...`` for a counterexample or sample point (at most ``limit`` items)."""
    if not point:
        return ""
    items = list(point.items())
    txt = ", ".join(f"{k} = {v}" for k, v in items[:limit])
    return txt + (", ..." if len(items) > limit else "")


def result_text(result) -> str:
    """Plain-text rendering (terminal): status, id, label, statement, errata details."""
    c, o = result.claim, result.outcome
    lines = [f"[{o.status}] {c.id} (eq. {c.equation}): {c.statement}",
             f"    method: {o.method}; residual {residual_text(o)}"]
    if o.printed:
        lines.append(f"    printed:   {o.printed}")
    if o.corrected:
        lines.append(f"    corrected: {o.corrected}")
    if o.counterexample:
        lines.append(f"    counterexample: {point_text(o.counterexample, limit=8)}")
    if o.status == "failed" and o.detail:
        lines.append(f"    detail: {o.detail.strip().splitlines()[0]}")
    return "\n".join(lines)
