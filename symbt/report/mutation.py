"""The report of ``symbt mutate``: totals, the text report and the progress on stderr.

Works on the records :func:`symbt.engine.mutate.mutate_claim` makes (as dicts), so it needs
nothing from the engine.  The mutation score is killed / non-equivalent mutants that ran; a
claim without mutants is counted apart (``no_mutants``), never in the score.

>>> rec = {"id": "a", "status": "verified", "mutants": 2, "killed": 2, "equivalent_count": 0,
...        "survivors": [], "planned": 3, "not_run": 1, "seconds": 0.5,
...        "note": "budget reached after 2 of 3 mutants"}
>>> print(format_text([rec]).splitlines()[-1])
budget reached after 2 of 3 mutants; cut short: a
"""
from __future__ import annotations

import sys
import time
from collections.abc import Callable, Sequence
from typing import Any, TextIO

__all__ = ["summary", "format_text", "exit_status", "MutateProgress", "EXIT_OK", "EXIT_SURVIVORS"]

EXIT_OK, EXIT_SURVIVORS = 0, 1

def summary(records: list[dict[str, Any]]) -> dict[str, Any]:
    """Totals over the records: the score is killed / non-equivalent mutants that ran.

    Claims without mutants (``no_mutants``) are counted apart, not in the score;
    ``not_run`` counts the mutants the budget left out (of ``planned``).
    """
    m = sum(r["mutants"] for r in records)
    k = sum(r["killed"] for r in records)
    e = sum(r["equivalent_count"] for r in records)
    s = sum(len(r["survivors"]) for r in records)
    zero = [r["id"] for r in records if r["killed"] == 0 and r["mutants"] > 0]
    not_run = sum(r.get("not_run", 0) for r in records)
    return {"claims": len(records), "mutants": m, "killed": k, "equivalent": e, "survivors": s,
            "score": (k / (m - e)) if m > e else None, "claims_killing_none": zero,
            "timeouts": sum(len(r.get("timeouts", ())) for r in records),
            "no_mutants": [r["id"] for r in records if r.get("no_mutants")],
            "planned": sum(r.get("planned", 0) for r in records), "not_run": not_run,
            "budget_reached": not_run > 0 or any(not r.get("started", True) for r in records),
            "not_started": [r["id"] for r in records if not r.get("started", True)],
            "cut_short": [r["id"] for r in records if r.get("started", True) and r.get("not_run", 0)]}


def format_text(records: list[dict[str, Any]]) -> str:
    """The report: a line per claim (survivors, timeouts and parts without mutants below it), then totals."""
    lines = []
    for r in records:
        if not r.get("started", True) or r["status"] == "not run":
            lines.append(f"  {r['id']:32s} not run   {r['note']} ({r.get('planned', 0)} mutants)")
            continue
        if r["mutants"] == 0:
            flag = "NO MUTANTS: " if r.get("no_mutants") else "no mutants ("
            lines.append(f"  {r['id']:32s} {r['status']:9s} {flag}{r['note']}{'' if r.get('no_mutants') else ')'}")
        else:
            extra = f", {len(r['timeouts'])} by timeout" if r.get("timeouts") else ""
            cut = f"; {r['note']}" if r.get("not_run") else ""
            lines.append(f"  {r['id']:32s} {r['status']:9s} {r['mutants']:3d} mutants: {r['killed']:3d} killed{extra}, "
                         f"{r['equivalent_count']:2d} equivalent, {len(r['survivors']):2d} survivors "
                         f"({r['seconds']:.1f}s{cut})")
        for s in r["survivors"]:
            lines.append(f"      survivor: {s['part']}: {s['mutation']}")
        for t in r.get("timeouts", ()):
            lines.append(f"      killed by timeout (> {t['limit']:g}s): {t['part']}: {t['mutation']}")
        for p in r.get("no_mutant_parts", ()):
            lines.append(f"      part '{p['part']}' gives no mutants: {p['why']}")
    s = summary(records)
    score = "-" if s["score"] is None else f"{100 * s['score']:.1f}%"
    killed = f"{s['killed']} killed" + (f" ({s['timeouts']} by timeout)" if s["timeouts"] else "")
    line = (f"{s['claims']} claims, {s['mutants']} mutants: {killed}, {s['equivalent']} equivalent, "
            f"{s['survivors']} survivors; mutation score {score} (killed / non-equivalent)")
    if s["no_mutants"]:
        line += f"; {len(s['no_mutants'])} claims gave no mutants, not in the score"
    lines += ["", line]
    if s["no_mutants"]:
        lines.append("claims without mutants (see above what to declare): " + ", ".join(s["no_mutants"]))
    if s["claims_killing_none"]:
        lines.append("claims that kill no mutant: " + ", ".join(s["claims_killing_none"]))
    if s["budget_reached"]:
        bits = [f"budget reached after {s['mutants']} of {s['planned']} mutants"]
        if s["cut_short"]:
            bits.append("cut short: " + ", ".join(s["cut_short"]))
        if s["not_started"]:
            bits.append(f"not started ({len(s['not_started'])}): " + ", ".join(s["not_started"]))
        lines.append("; ".join(bits))
    return "\n".join(lines)


def exit_status(s: dict[str, Any], fail_under: float | None = None) -> int:
    """``0`` unless a mutant that ran survived (or, with ``fail_under``, the score in % is below it).

    >>> exit_status({"survivors": 0, "score": 1.0}), exit_status({"survivors": 1, "score": 0.99})
    (0, 1)
    >>> exit_status({"survivors": 1, "score": 0.99}, fail_under=95)
    0
    """
    if fail_under is not None:
        return EXIT_SURVIVORS if s["score"] is not None and 100 * s["score"] < fail_under else EXIT_OK
    return EXIT_SURVIVORS if s["survivors"] else EXIT_OK


# --------------------------------------------------------------------------- progress

def _duration(seconds: float) -> str:
    if seconds < 60:
        return f"{seconds:.1f}s"
    return f"{int(seconds // 60)}m{int(seconds % 60):02d}s"


class MutateProgress:
    """Progress of a mutation run on ``stream`` (stderr): see the module docstring.

    >>> import io
    >>> buf = io.StringIO()
    >>> p = MutateProgress(["a", "b"], stream=buf, clock=iter([0.0, 2.0, 2.0, 4.0]).__next__)
    >>> p.event("start", "a", 4)
    >>> for i in (1, 2, 3, 4): p.event("mutant", "a", i)
    >>> p.claim_done({"id": "a", "mutants": 4, "killed": 4, "planned": 4, "seconds": 2.0})
    >>> print(buf.getvalue().strip())
    [1/2] a: 4/4 mutants, 4 killed (2.0s) | 4/~8 mutants, 2.0s elapsed, ~2.0s left
    """

    def __init__(self, ids: Sequence[str], *, stream: TextIO | None = None, enabled: bool = True,
                 budget: float | None = None, clock: Callable[[], float] = time.perf_counter):
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = enabled
        self.tty = enabled and bool(getattr(self.stream, "isatty", lambda: False)())
        self.clock = clock
        self.t0 = clock()
        self.n_claims, self.finished = len(ids), 0
        self.planned: dict[str, int] = {}
        self.done: dict[str, int] = {}
        self.budget = budget
        self._drawn = 0.0
        self._width = 0

    def _estimate(self) -> tuple[int, bool]:
        """Mutants in all: the planned ones of started claims plus their mean per claim for the others."""
        known = sum(self.planned.values())
        rest = self.n_claims - len(self.planned)
        if rest <= 0 or not self.planned:
            return known, rest > 0
        return known + round(rest * known / len(self.planned)), True

    def status(self) -> str:
        elapsed = self.clock() - self.t0
        done = sum(self.done.values())
        total, approx = self._estimate()
        text = f"{done}/{'~' if approx else ''}{total} mutants, {_duration(elapsed)} elapsed"
        if done and elapsed > 0 and total > done:
            left = (total - done) * elapsed / done
            if self.budget is not None:
                left = min(left, max(self.budget - elapsed, 0.0))
            text += f", ~{_duration(left)} left"
        elif total <= done and self.finished < self.n_claims:
            text += ", estimating"
        return text

    def event(self, kind: str, cid: str, n: int) -> None:
        if kind == "start":
            self.planned[cid] = n
        elif kind == "mutant":
            self.done[cid] = max(n, self.done.get(cid, 0))
        if self.tty and self.enabled and self.clock() - self._drawn > 0.1:
            self._draw(f"mutate [{self.finished}/{self.n_claims} claims] {self.status()}  {cid}")

    def _draw(self, line: str) -> None:
        line = line[:118]
        self.stream.write("\r" + line.ljust(self._width))
        self.stream.flush()
        self._width = len(line)
        self._drawn = self.clock()

    def _clear(self) -> None:
        if self._width:
            self.stream.write("\r" + " " * self._width + "\r")
            self._width = 0

    def claim_done(self, rec: dict[str, Any]) -> None:
        self.finished += 1
        self.planned[rec["id"]] = rec.get("planned", rec["mutants"])
        self.done[rec["id"]] = rec["mutants"]
        if not self.enabled:
            return
        w = len(str(self.n_claims))
        if not rec.get("started", True):
            what = f"not started: the budget was reached ({rec.get('planned', 0)} mutants)"
        elif rec.get("no_mutants") or (rec["mutants"] == 0 and rec.get("note")):
            what = f"no mutants: {rec.get('note', '')}"
        else:
            what = (f"{rec['mutants']}/{rec.get('planned', rec['mutants'])} mutants, {rec['killed']} killed "
                    f"({rec.get('seconds', 0.0):.1f}s)")
        if self.tty:
            self._clear()
        self.stream.write(f"[{self.finished:>{w}}/{self.n_claims}] {rec['id']}: {what} | {self.status()}\n")
        self.stream.flush()

    def close(self) -> None:
        if self.tty:
            self._clear()
            self.stream.flush()
