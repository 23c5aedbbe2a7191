"""The terminal report: a short report (default), the full table (``-v``), the summary lines.

Every reporter tolerates outcomes with missing values (no evidence, no scope,
no residual): a missing value prints as ``-`` or is left out.

>>> from symbt.claims.base import Claim, ClaimResult, Outcome
>>> r = ClaimResult(Claim("t", "eq", "s", check=None, scene="demo"), Outcome("verified", "exact", 0.0))
>>> print(format_short([r]))
demo    1 claim: 1 verified
<BLANKLINE>
1 claim: 1 verified, 0 errata, 0 failed, 0 skipped -- ok
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from .views import OutcomeView, ResultView

__all__ = ["ORDER", "NOT_OK", "summary", "summary_lines", "format_short", "format_table", "residual_text",
           "short_method", "result_text", "point_text", "evidence_text"]


#: every status, in the order the reports list them
ORDER = ("verified", "erratum", "failed", "inconclusive", "todo", "skipped")
#: statuses that make a run fail (as :data:`symbt.claims.base.NOT_OK`; kept here so that
#: reading a report never imports the claim layer)
NOT_OK = ("failed", "inconclusive", "todo")


def summary(results: Sequence[ResultView]) -> dict[str, Any]:
    """Counts by status, ``total``, ``seconds`` (sum of the checks' times) and ``ok``
    (no claim failed, is inconclusive or is a todo stub).

    >>> from symbt.claims.base import Claim, ClaimResult, Outcome
    >>> c = Claim("t", "eq", "s", check=None)
    >>> s = summary([ClaimResult(c, Outcome("verified", "m")), ClaimResult(c, Outcome("inconclusive", "m"))])
    >>> s["verified"], s["inconclusive"], s["todo"], s["ok"]
    (1, 1, 0, False)
    """
    s: dict[str, Any] = {k: 0 for k in ORDER}
    for r in results:
        s[r.outcome.status] += 1
    s["total"] = len(results)
    s["seconds"] = round(sum(r.outcome.seconds or 0.0 for r in results), 3)
    s["ok"] = all(s[k] == 0 for k in NOT_OK)
    return s


def _plural(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")


def _errata(n: int) -> str:
    return f"{n} errat{'um' if n == 1 else 'a'}"


def residual_text(out: OutcomeView) -> str:
    if out.status in ("skipped", "todo"):
        return "-"
    if (out.method or "").startswith("exact") and not out.residual:
        return "0 (exact)"
    if out.residual is None:
        return "-"
    try:
        txt = f"{out.residual:.1e}"
    except (TypeError, ValueError):
        return str(out.residual)
    if out.digits is not None and out.status == "verified":
        txt += f" ({out.digits:.0f} dig)"
    return txt


def evidence_text(out: OutcomeView) -> str:
    """``proof`` / ``certified`` / ``sampled``, or ``-`` when the outcome does not say."""
    return getattr(out, "evidence", None) or "-"


def short_method(m: str | None) -> str:
    m = m or ""
    if m.startswith("printed:"):
        corr = m.split("| corrected:", 1)[-1].strip()
        return "corrected by " + short_method(corr)
    if m.startswith("exact"):
        return ("exact" + (" +relations" if "remainder mod" in m else "") + (" (E=e^q)" if "exp->" in m else "")
                + (" + numeric" if "; numeric:" in m else ""))
    return m.split(";")[0][:40]


def point_text(point: Mapping[str, object] | None, limit: int = 12) -> str:
    """``k = v, ...`` for a counterexample or sample point (at most ``limit`` items)."""
    if not point:
        return ""
    items = list(point.items())
    txt = ", ".join(f"{k} = {v}" for k, v in items[:limit])
    return txt + (", ..." if len(items) > limit else "")


def outcome_fields(o: OutcomeView, *, limit: int = 8) -> list[tuple[str, str]]:
    """The labelled fields every reporter shows for an outcome, in one order (those present):
    ``printed``, ``corrected``, ``scope``, ``counterexample`` (as :func:`point_text`).

    >>> from symbt.claims.base import Outcome
    >>> outcome_fields(Outcome("erratum", "m", printed="P = 1", corrected="P = -1", counterexample={"x": 2}))
    [('printed', 'P = 1'), ('corrected', 'P = -1'), ('counterexample', 'x = 2')]
    """
    fields = [(name, getattr(o, name)) for name in ("printed", "corrected", "scope") if getattr(o, name)]
    if o.counterexample:
        fields.append(("counterexample", point_text(o.counterexample, limit=limit)))
    return fields


def field_lines(o: OutcomeView, indent: str, *, limit: int = 8) -> list[str]:
    """:func:`outcome_fields` as aligned ``label: value`` lines."""
    return [f"{indent}{name + ':':<10} {value}" for name, value in outcome_fields(o, limit=limit)]


def _first_line(text: str | None, limit: int = 200) -> str:
    lines = (text or "").strip().splitlines()
    return lines[0][:limit] if lines else ""


def summary_lines(results: Sequence[ResultView], *, wall: float | None = None) -> list[str]:
    """The last lines of every terminal report: the counts, then time and cache use."""
    s = summary(results)
    verdict = "ok" if s["ok"] else "FAILED"
    # inconclusive and todo are named only when there are some (the common line stays short)
    extra = "".join(f"{s[k]} {k}, " for k in ("inconclusive", "todo") if s[k])
    lines = [f"{_plural(s['total'], 'claim')}: {s['verified']} verified, {_errata(s['erratum'])}, "
             f"{s['failed']} failed, {extra}{s['skipped']} skipped -- {verdict}"]
    if wall is not None:
        cached = sum(1 for r in results if r.outcome.cached)
        lines.append(f"wall time {wall:.2f}s ({cached} of {s['total']} from the cache; "
                     f"{s['seconds']:.1f}s of checks)")
    return lines


def cell_summary(o: OutcomeView) -> str:
    """A compact form of the generated scope: in how many domain cells the printed statement holds.

    >>> from symbt.claims.base import Outcome
    >>> o = Outcome("erratum", "m", cells=[{"cell": {"b": 1}, "n": 16, "printed_holds": 16, "corrected_holds": 16},
    ...                                    {"cell": {"b": -1}, "n": 16, "printed_holds": 3, "corrected_holds": 16}])
    >>> cell_summary(o)
    'printed holds in 1 of 2 cells (partly in 1); corrected in all 2'
    """
    cells = [c for c in (o.cells or []) if isinstance(c, dict) and c.get("n")]
    if not cells:
        return ""
    full = sum(1 for c in cells if c.get("printed_holds") == c["n"])
    part = sum(1 for c in cells if 0 < (c.get("printed_holds") or 0) < c["n"])
    txt = f"printed holds in {full} of {len(cells)} cells" + (f" (partly in {part})" if part else "")
    if any("corrected_holds" in c for c in cells):
        bad = sum(1 for c in cells if c.get("corrected_holds") != c["n"])
        txt += f"; corrected in all {len(cells)}" if not bad else f"; corrected FAILS in {bad}"
    return txt


def _claim_line(r: ResultView, width: int = 0) -> list[str]:
    """One line for a claim that is not plainly verified (failed ones get their evidence below it)."""
    c, o = r.claim, r.outcome
    head = f"{o.status:8s} {c.id.ljust(width)}  eq. {c.equation}"
    if o.status in ("skipped", "todo"):
        return [f"{head}: {_first_line(o.detail) or 'no reason given'}"]
    if o.status == "inconclusive":
        lines = [f"{head}: INCONCLUSIVE (cannot tell), residual {residual_text(o)} [{evidence_text(o)}]"]
        if o.detail:
            lines.append(f"    {_first_line(o.detail, 300)}")
        return lines
    if o.status == "erratum":
        scope = cell_summary(o) or (o.scope or "").strip()
        what = f"printed fails (residual {residual_text(o)}), corrected holds [{evidence_text(o)}]"
        return [f"{head}: {what}" + (f"; {scope}" if scope else "")]
    lines = [f"{head}: FAILED, residual {residual_text(o)} [{evidence_text(o)}]"]
    if o.counterexample:
        lines.append(f"    counterexample: {point_text(o.counterexample, limit=8)}")
    if o.detail:
        lines.append(f"    {_first_line(o.detail, 300)}")
    return lines


def format_short(results: Sequence[ResultView], *, wall: float | None = None) -> str:
    """The default report: one line per scene, one per claim that is not verified, then the summary."""
    scenes: dict[str, dict[str, int]] = {}
    for r in results:
        counts = scenes.setdefault(r.claim.scene, {})
        counts[r.outcome.status] = counts.get(r.outcome.status, 0) + 1
    width = max((len(s) for s in scenes), default=0)
    lines = []
    for name, counts in scenes.items():
        total = sum(counts.values())
        parts = [(_errata(counts[k]) if k == "erratum" else f"{counts[k]} {k}")
                 for k in ORDER if counts.get(k)]
        lines.append(f"{name.ljust(width)}  {_plural(total, 'claim').rjust(9)}: {', '.join(parts)}")
    odd = [r for r in results if r.outcome.status != "verified"]
    if odd:
        lines.append("")
    width = max((len(r.claim.id) for r in odd), default=0)
    urgent = ("failed", "inconclusive", "todo", "erratum", "skipped")
    for r in sorted(odd, key=lambda r: urgent.index(r.outcome.status)):
        lines.extend(_claim_line(r, width))
    lines.append("")
    lines.extend(summary_lines(results, wall=wall))
    return "\n".join(lines)


def format_table(results: Sequence[ResultView], *, wall: float | None = None) -> str:
    """The full report (``symbt verify -v``): every claim, the errata and failures in full, the summary."""
    rows = [("claim", "equation", "status", "evidence", "method", "residual", "time")]
    for r in results:
        o = r.outcome
        t = f"{o.seconds or 0:.2f}s" + (" (cache)" if o.cached else "")
        rows.append((r.claim.id, r.claim.equation, o.status, evidence_text(o), short_method(o.method),
                     residual_text(o), t))
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = []
    for k, row in enumerate(rows):
        lines.append("  ".join(cell.ljust(widths[i]) for i, cell in enumerate(row)).rstrip())
        if k == 0:
            lines.append("  ".join("-" * w for w in widths))
    for r in results:
        o = r.outcome
        if o.status == "verified":
            continue
        lines.append("")
        lines.append(f"[{o.status}] {r.claim.id} (eq. {r.claim.equation})")
        if o.status in ("skipped", "todo"):
            lines.append(f"  reason: {_first_line(o.detail, 300) or 'no reason given'}")
            continue
        lines += field_lines(o, "  ")
        if o.counterexample and isinstance(o.residual, (int, float)):
            lines[-1] += f"  (residual {o.residual:.3g})"
        if o.detail:
            lines.append("  " + _first_line(o.detail, 300))
    lines.append("")
    lines.extend(summary_lines(results, wall=wall))
    return "\n".join(lines)


def result_text(result: ResultView) -> str:
    """Plain-text rendering (terminal): status, id, label, statement, errata details."""
    c, o = result.claim, result.outcome
    lines = [f"[{o.status}] {c.id} (eq. {c.equation}): {c.statement}",
             f"    method: {o.method}; residual {residual_text(o)}; evidence {evidence_text(o)}"]
    lines += field_lines(o, "    ")
    if o.status in ("failed", "inconclusive", "skipped", "todo") and o.detail:
        label = "reason" if o.status in ("skipped", "todo") else "detail"
        lines.append(f"    {label}: {_first_line(o.detail, 300)}")
    return "\n".join(lines)
