"""The report of ``symbt mutate --source``: per-module totals, the text report, the JSON schema.

Works on the mutant records of :mod:`symbt.engine.mutate_source` (dicts with ``id``, ``module``,
``file``, ``line``, ``operator``, ``diff``, ``result``, ``detail``, ``claims``, ``seconds``).
``result`` is one of :data:`RESULTS`:

* ``killed`` -- ``symbt verify`` of the claims that run the mutated line reported another status,
  evidence or scope for one of them, or crashed;
* ``timeout`` -- that run went past the per-mutant limit (killed by timeout, counted apart);
* ``tests`` -- verify did not see it, the test files that import the module failed (``--tests``);
* ``survived`` -- nothing saw it; ``uncovered`` -- no claim runs the line (a survivor not run);
* ``equivalent`` -- marked so, with a reason, in the equivalents file (not run);
* ``not run`` -- left out by ``--budget``.

Score = killed (by verify, timeout or tests) / (mutants - equivalent); the verify score counts
verify's kills and timeouts only.  ``not run`` mutants are in neither.

>>> recs = [{"module": "m", "result": r} for r in ("killed", "timeout", "survived", "uncovered", "equivalent")]
>>> s = summary(recs)["modules"]["m"]
>>> s["mutants"], s["killed_verify"], s["timeouts"], s["survivors"], s["score"]
(5, 1, 1, 2, 0.5)
"""
from __future__ import annotations

import json
from pathlib import Path
from typing import Any

__all__ = ["RESULTS", "SCHEMA_VERSION", "SCHEMA_PATH", "schema", "summary", "format_text", "exit_status"]

RESULTS = ("killed", "timeout", "tests", "survived", "uncovered", "equivalent", "not run")
SCHEMA_VERSION = "1.0"
SCHEMA_PATH = Path(__file__).with_name("mutate-source.schema.json")


def schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of ``symbt mutate --source --json``."""
    return json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))


def _totals(recs: list[dict[str, Any]]) -> dict[str, Any]:
    n = {r: sum(1 for x in recs if x["result"] == r) for r in RESULTS}
    mutants = len(recs) - n["not run"]
    denominator = mutants - n["equivalent"]
    killed = n["killed"] + n["timeout"] + n["tests"]
    return {"mutants": mutants, "killed_verify": n["killed"], "timeouts": n["timeout"], "killed_tests": n["tests"],
            "survivors": n["survived"] + n["uncovered"], "uncovered": n["uncovered"], "equivalent": n["equivalent"],
            "not_run": n["not run"],
            "score": killed / denominator if denominator > 0 else None,
            "verify_score": (n["killed"] + n["timeout"]) / denominator if denominator > 0 else None}


def summary(records: list[dict[str, Any]]) -> dict[str, Any]:
    """Totals per module (in the order first seen) and over all (see the module docstring)."""
    modules: dict[str, list[dict[str, Any]]] = {}
    for r in records:
        modules.setdefault(r["module"], []).append(r)
    return {"modules": {m: _totals(rs) for m, rs in modules.items()}, "total": _totals(records)}


def _pct(x: float | None) -> str:
    return "-" if x is None else f"{100 * x:.1f}%"


def format_text(records: list[dict[str, Any]], *, stale: list[dict[str, str]] = (),  # type: ignore[assignment]
                notes: list[str] = ()) -> str:  # type: ignore[assignment]
    """The table per module, the survivors with their diffs, stale equivalents, then the totals."""
    s = summary(records)
    head = (f"{'module':28s} {'mutants':>7s} {'verify':>6s} {'timeout':>7s} {'tests':>5s} {'surv.':>5s} "
            f"{'uncov.':>6s} {'equiv.':>6s} {'not run':>7s} {'score':>7s} {'verify':>7s}")
    lines = [head]
    for m, t in [*s["modules"].items(), ("total", s["total"])]:
        lines.append(f"{m:28s} {t['mutants']:7d} {t['killed_verify']:6d} {t['timeouts']:7d} {t['killed_tests']:5d} "
                     f"{t['survivors']:5d} {t['uncovered']:6d} {t['equivalent']:6d} {t['not_run']:7d} "
                     f"{_pct(t['score']):>7s} {_pct(t['verify_score']):>7s}")
    surv = [r for r in records if r["result"] in ("survived", "uncovered", "tests")]
    if surv:
        lines += ["", "not killed by verify (survivors; 'tests': killed by the test files only):"]
        for r in sorted(surv, key=lambda r: (r["module"], r["file"], r["line"])):
            why = {"uncovered": "no claim runs this line", "tests": f"killed by tests: {r.get('detail', '')}",
                   "survived": f"{r.get('claims', 0)} claims ran"}[r["result"]]
            lines.append(f"  {r['id']}  [{why}]")
            lines += [f"      {d}" for d in r["diff"].splitlines()]
    timeouts = [r for r in records if r["result"] == "timeout"]
    if timeouts:
        lines += ["", "killed by timeout:"] + [f"  {r['id']} ({r.get('detail', '')})" for r in timeouts]
    for st in stale:
        lines.append(f"stale equivalent (no such mutant any more): {st['id']} ({st.get('reason', '')})")
    lines += ["", f"score {_pct(s['total']['score'])} = killed / (mutants - equivalent); by verify alone "
                  f"{_pct(s['total']['verify_score'])}", *notes]
    return "\n".join(lines)


def exit_status(s: dict[str, Any], fail_under: float | None = None) -> int:
    """``0`` unless a mutant survived (with ``fail_under``: unless the score in % is below it).

    >>> exit_status({"survivors": 1, "score": 0.95}), exit_status({"survivors": 1, "score": 0.95}, 90)
    (1, 0)
    """
    if fail_under is not None:
        return 1 if s["score"] is not None and 100 * s["score"] < fail_under else 0
    return 1 if s["survivors"] else 0
