"""``symbt mutate``: mutation testing of the claims' own checks.

Every claim exposes what it checks as :class:`~symbt.claims.base.Parts`.  For a claim that
is ``verified`` the *printed* parts are mutated, for an ``erratum`` the *corrected* ones
(the statement reported as holding); each mutant (see :mod:`symbt.proof.mutation`) is fed
to the claim's own check.  The mutant is

* **killed** when the check no longer reports the statement as holding (a different status);
* **equivalent** when the check still accepts it *and* the mutated part equals the original
  one (decided by :func:`symbt.proof.decide`: exact reduction or, for transcendental parts,
  the 50-digit screen -- the method is recorded);
* a **survivor** otherwise: the check cannot see that error, a defect to fix.

Usage::

    symbt mutate [--scene NAME ...] [--limit K] [--seed S] [-j N] [--json FILE]

``--limit`` keeps a seeded random subset of at most K mutants per claim (CI runs a
subset; the full run is recorded in BENCHMARKS.md).
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass, field
from typing import Any

from ..claims import REGISTRY, load_all
from ..claims.base import Claim
from ..report.json import emit_document, output_refused
from .select import select

__all__ = ["ClaimMutations", "mutate_claim", "run", "main"]


@dataclass
class ClaimMutations:
    """The mutation record of one claim."""

    id: str
    status: str
    side: str | None = None
    mutants: int = 0
    killed: int = 0
    equivalent: list[dict[str, str]] = field(default_factory=list)
    survivors: list[dict[str, str]] = field(default_factory=list)
    note: str = ""
    seconds: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["equivalent_count"] = len(self.equivalent)
        return d


def _equivalent(original: Any, mutated: Any) -> tuple[bool, str]:
    """Is the mutated part the same function as the original?  (decided, with the method)."""
    import sympy as sp

    from ..proof import decide

    if not isinstance(original, (sp.Basic, sp.MatrixBase)):
        return bool(original == mutated), "value comparison"
    try:
        v = decide(original, mutated)
    except Exception as exc:  # an undecidable comparison is not an equivalence
        return False, f"not decidable ({type(exc).__name__})"
    return v.holds, v.method


def mutate_claim(c: Claim, *, limit: int | None = None, seed: int = 0) -> ClaimMutations:
    """Run every (or a seeded subset of) mutant of ``c`` through its own check."""
    from ..proof.mutation import mutants

    t0 = time.perf_counter()
    base = c.run()
    rec = ClaimMutations(c.id, base.status)
    if c.parts is None:
        rec.note = "exposes no statement parts"
    elif base.status not in ("verified", "erratum"):
        rec.note = f"not mutated: the claim itself is {base.status}"
    else:
        side = "printed" if base.status == "verified" else "corrected"
        rec.side = side
        parts = c.parts()
        cands = [(name, m) for name, value in sorted(getattr(parts, side).items()) for m in mutants(value)]
        if limit is not None and len(cands) > limit:
            import random

            rng = random.Random(f"{seed}:{c.id}")
            cands = sorted(rng.sample(cands, limit), key=cands.index)
        for name, m in cands:
            out = c.run_with(parts.replace(side, name, m.expr))
            rec.mutants += 1
            entry = {"part": f"{side}.{name}", "operator": m.operator, "mutation": m.description}
            if out.status != base.status:
                rec.killed += 1
                continue
            same, how = _equivalent(getattr(parts, side)[name], m.expr)
            if same or out.evidence == "proof":
                rec.equivalent.append(dict(entry, decided_by=how if same else "the check's own proof"))
            else:
                rec.survivors.append(entry)
    rec.seconds = round(time.perf_counter() - t0, 3)
    return rec


def _mutate_id(args: tuple[str, int | None, int]) -> dict[str, Any]:
    load_all()
    cid, limit, seed = args
    return mutate_claim(REGISTRY[cid], limit=limit, seed=seed).to_dict()


def summary(records: list[dict[str, Any]]) -> dict[str, Any]:
    m = sum(r["mutants"] for r in records)
    k = sum(r["killed"] for r in records)
    e = sum(r["equivalent_count"] for r in records)
    s = sum(len(r["survivors"]) for r in records)
    zero = [r["id"] for r in records if r["killed"] == 0]
    return {"claims": len(records), "mutants": m, "killed": k, "equivalent": e, "survivors": s,
            "score": (k / (m - e)) if m > e else None, "claims_killing_none": zero}


def run(claims: list[Claim], *, limit: int | None = None, seed: int = 0, jobs: int = 1,
        progress: Any = None) -> list[dict[str, Any]]:
    """Mutation records of ``claims`` (in order), optionally in ``jobs`` processes."""
    tasks = [(c.id, limit, seed) for c in claims]
    if jobs > 1 and len(tasks) > 1:
        import multiprocessing as mp_

        ctx = mp_.get_context("fork") if sys.platform != "win32" else None
        with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
            records = []
            for rec in pool.map(_mutate_id, tasks):
                records.append(rec)
                if progress:
                    progress(rec)
            return records
    out = []
    for t in tasks:
        rec = _mutate_id(t)
        out.append(rec)
        if progress:
            progress(rec)
    return out


def format_text(records: list[dict[str, Any]]) -> str:
    lines = []
    for r in records:
        if r["mutants"] == 0:
            lines.append(f"  {r['id']:32s} {r['status']:9s} no mutants ({r['note']})")
            continue
        lines.append(f"  {r['id']:32s} {r['status']:9s} {r['mutants']:3d} mutants: {r['killed']:3d} killed, "
                     f"{r['equivalent_count']:2d} equivalent, {len(r['survivors']):2d} survivors ({r['seconds']:.1f}s)")
        for s in r["survivors"]:
            lines.append(f"      survivor: {s['part']}: {s['mutation']}")
    s = summary(records)
    score = "-" if s["score"] is None else f"{100 * s['score']:.1f}%"
    lines.append("")
    lines.append(f"{s['claims']} claims, {s['mutants']} mutants: {s['killed']} killed, {s['equivalent']} equivalent, "
                 f"{s['survivors']} survivors; mutation score {score} (killed / non-equivalent)")
    if s["claims_killing_none"]:
        lines.append("claims that kill no mutant: " + ", ".join(s["claims_killing_none"]))
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="symbt mutate", description="mutation testing of the claims' checks")
    ap.add_argument("--scene", action="append", metavar="NAME", help="scene / claim id / nK (repeatable)")
    ap.add_argument("--limit", type=int, default=None, metavar="K", help="at most K mutants per claim (seeded)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("-j", "--jobs", type=int, default=min(2, os.cpu_count() or 1))
    ap.add_argument("--json", metavar="FILE", help="write the records and the summary as JSON ('-': stdout)")
    ap.add_argument("-q", "--quiet", action="store_true")
    args = ap.parse_args(argv)
    if output_refused(args.json, "symbt mutate"):
        return 2
    if args.jobs < 1 or (args.limit is not None and args.limit < 1):
        print("symbt mutate: -j and --limit must be positive", file=sys.stderr)
        return 2
    try:
        claims = select(args.scene or None)
    except KeyError as exc:
        print(f"symbt mutate: {exc.args[0]}", file=sys.stderr)
        return 2
    t0 = time.perf_counter()

    def progress(rec: dict[str, Any]) -> None:
        if not args.quiet:
            print(f"  {rec['id']}: {rec['killed']}/{rec['mutants']} killed", file=sys.stderr, flush=True)

    records = run(claims, limit=args.limit, seed=args.seed, jobs=args.jobs, progress=progress)
    report = {"claims": records, "summary": summary(records), "seconds": round(time.perf_counter() - t0, 1),
              "limit": args.limit, "seed": args.seed}
    status = emit_document(report, args.json, command="symbt mutate", text=None if args.quiet else format_text(records))
    if status:
        return status
    return 0
