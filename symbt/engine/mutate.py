"""``symbt mutate``: mutation testing of the claims' own checks.

Every claim exposes what it checks as :class:`~symbt.claims.base.Parts`.  For a claim that
is ``verified`` the *printed* parts are mutated, for an ``erratum`` the *corrected* ones
(the statement reported as holding); each mutant (see :mod:`symbt.proof.mutation`) is fed
to the claim's own check.  The mutant is

* **killed** when the check no longer reports the statement as holding (a different status),
  or when the check runs past its time limit (*killed by timeout*, listed as such: a mutant
  can make a sampler loop forever);
* **equivalent** when the check still accepts it *and* either the check decided it by an
  exact proof, or the mutated part equals the original one (decided by
  :func:`symbt.proof.decide`: exact reduction or, for transcendental parts, the 50-digit
  screen -- the method is recorded);
* a **survivor** otherwise: the check cannot see that error, a defect to fix.

Which claims: the project's, as for ``symbt verify`` (see :mod:`symbt.engine.project`):
``--claims MODULE_OR_PATH`` (repeatable), else the ``claims`` of the ``[tool.symbt]`` table
of the ``pyproject.toml`` found from the working directory, else Zullo's paper; ``--scene``
and ``--label`` choose among them.

**Claims the harness cannot test.**  A part no operator applies to (0, a bare symbol, a
matrix of bare symbols, ...) gives no mutant, so the check is not tested through it; every
such part is listed with what to declare instead
(:func:`~symbt.proof.mutation.why_no_mutants`).  A claim whose parts give no mutant at all,
or that declares no parts, is **counted apart**: it cannot lower the mutation score (killed
/ non-equivalent mutants: it has none), so it is listed in the summary line ("N claims gave
no mutants, not in the score") and in the JSON summary's ``no_mutants``, with its reason.

**Time.**  ``--budget SECONDS`` bounds the wall-clock time of the whole run: once it is
reached no new mutant (and no new claim) starts; the report says "budget reached after N
of M mutants" and which claims were cut short or not started (M counts their mutants
too).  Each mutant's check runs under a limit, ``--mutant-timeout`` seconds (default:
:data:`TIMEOUT_FACTOR` times the claim's own check time, at least :data:`TIMEOUT_FLOOR`
seconds).  The limit is a ``SIGALRM`` timer: it stops Python code, not one long call into
C, and applies only in a main thread (worker processes and the command line are).

**Progress** goes to stderr: on a terminal a status line rewritten as mutants finish --
mutants done/total, elapsed time and the remaining time estimated from the measured rate --
and a line per claim; plain lines per claim when stderr is not a terminal; nothing with ``-q``.

Usage::

    symbt mutate [--claims MODULE_OR_PATH ...] [--scene NAME ...] [--label LABEL ...] [--limit K]
                 [--seed S] [-j N] [--budget SECONDS] [--mutant-timeout SECONDS]
                 [--fail-under PERCENT] [--json FILE] [-q]

``--limit`` keeps a seeded random subset of at most K mutants per claim (CI runs a
subset; the full run is recorded in BENCHMARKS.md).

**Exit status**: ``0`` no mutant that ran survived (mutants left out by the budget and
claims without mutants do not fail the run); ``1`` a mutant survived (with ``--fail-under
P``: the score is below P %); ``2`` usage error (unknown scene or label, a claims source
that does not exist or does not import, a bad option; one line on stderr); ``130``
interrupted.

Speed: only the project's claims run (a user's claims used to be reachable only by importing
them into a run of Zullo's 136 claims as well), a worker process imports only the project's
claims, a mutant the check itself proved is not decided a second time, and claims are dealt
to the workers as they free up.

>>> import sympy as sp
>>> from symbt.claims.base import Parts, claim, from_decision
>>> from symbt.proof import decide
>>> x = sp.Symbol("x")
>>> @claim("demo.sq", equation="demo", scene="demo", statement="(x+1)^2 = x^2+2x+1", register=False,
...        parts=lambda: Parts(printed={"rhs": x**2 + 2*x + 1}))
... def demo_sq(parts):
...     return from_decision(decide((x + 1)**2, parts.printed["rhs"]))
>>> rec = mutate_claim(demo_sq)
>>> rec.mutants == rec.killed, rec.survivors
(True, [])
"""
from __future__ import annotations

import argparse
import math
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from contextlib import contextmanager
from dataclasses import asdict, dataclass, field
from typing import Any, NoReturn

from ..claims import REGISTRY
from ..claims.base import Claim
from ..report.json import emit_document, output_refused
from ..report.mutation import EXIT_OK, EXIT_SURVIVORS, MutateProgress, exit_status, format_text, summary
from .project import ConfigError, Project, discover, load
from .select import select

__all__ = ["ClaimMutations", "MutantTimeout", "mutate_claim", "planned_mutants", "run", "summary", "format_text",
           "exit_status", "MutateProgress", "main", "TIMEOUT_FACTOR", "TIMEOUT_FLOOR", "EXIT_OK", "EXIT_SURVIVORS",
           "EXIT_USAGE"]

#: a mutant's check may run this many times as long as the claim's own check ...
TIMEOUT_FACTOR = 20.0
#: ... and at least this many seconds, before it is stopped and counted killed by timeout
TIMEOUT_FLOOR = 10.0

EXIT_USAGE = 2

NO_PARTS = ("declares no statement parts: give @claim a parts= function returning Parts(printed={...}) "
            "and let the check read them (its last argument)")


@dataclass
class ClaimMutations:
    """The mutation record of one claim.

    ``planned`` mutants were selected, ``mutants`` of them ran (``not_run``: left out by the
    budget); ``killed`` includes the ``timeouts``; ``no_mutant_parts`` lists the parts that
    gave no mutant, with why and what to declare instead; ``no_mutants`` marks a claim
    counted apart (no part gave a mutant, or it declares none; ``note`` says which).
    """

    id: str
    status: str
    side: str | None = None
    mutants: int = 0
    killed: int = 0
    equivalent: list[dict[str, str]] = field(default_factory=list)
    survivors: list[dict[str, str]] = field(default_factory=list)
    note: str = ""
    seconds: float = 0.0
    planned: int = 0
    not_run: int = 0
    timeouts: list[dict[str, Any]] = field(default_factory=list)
    no_mutant_parts: list[dict[str, str]] = field(default_factory=list)
    no_mutants: bool = False
    started: bool = True

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["equivalent_count"] = len(self.equivalent)
        return d


# --------------------------------------------------------------------------- time limits

class MutantTimeout(BaseException):
    """A check ran past its time limit.

    A ``BaseException``, so that a check's own ``except Exception`` (and
    :meth:`~symbt.claims.base.Claim.run_with`, which turns exceptions into ``failed``)
    does not swallow it.
    """


@contextmanager
def _time_limit(seconds: float | None) -> Iterator[None]:
    """Raise :class:`MutantTimeout` in the block after ``seconds`` (main thread with SIGALRM only).

    The timer re-fires every second, so a check that swallows the first one is stopped by the next.
    """
    usable = (seconds is not None and hasattr(signal, "setitimer")
              and threading.current_thread() is threading.main_thread())
    if not usable:
        yield
        return
    armed = [True]

    def alarm(signum: int, frame: Any) -> None:
        if armed[0]:
            raise MutantTimeout()

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, max(float(seconds or 0.0), 1e-3), 1.0)
    try:
        yield
    finally:
        armed[0] = False   # an alarm already pending when the block ends is ignored
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _left(deadline: float | None) -> float | None:
    return None if deadline is None else deadline - time.time()


# --------------------------------------------------------------------------- one claim

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


Candidates = list[tuple[str, Any]]


def _candidates(c: Claim, parts: Any, side: str, limit: int | None, seed: int,
                rec: ClaimMutations | None = None) -> Candidates:
    """The (part name, mutant) pairs to run, in order; parts without mutants go to ``rec``."""
    from ..proof.mutation import mutants, why_no_mutants

    cands: Candidates = []
    for name, value in sorted(getattr(parts, side).items()):
        try:
            ms, why = mutants(value), ""
        except Exception as exc:  # an object the operators cannot rebuild: say so, go on with the others
            ms, why = [], f"mutating it raised {type(exc).__name__}: {exc}"
        if not ms and rec is not None:
            rec.no_mutant_parts.append({"part": f"{side}.{name}", "why": why or why_no_mutants(value)})
        cands += [(name, m) for m in ms]
    if limit is not None and len(cands) > limit:
        import random

        rng = random.Random(f"{seed}:{c.id}")
        cands = sorted(rng.sample(cands, limit), key=cands.index)
    return cands


def planned_mutants(c: Claim, *, limit: int | None = None) -> int:
    """How many mutants a claim would run, without running anything (its status is not known yet:
    the corrected parts when it declares any, else the printed ones)."""
    if c.parts is None or c.run_parts is None:
        return 0
    try:
        parts = c.parts()
    except Exception:  # reported when the claim runs; nothing to count here
        return 0
    side = "corrected" if parts.corrected else "printed"
    return len(_candidates(c, parts, side, limit, 0))


def mutate_claim(c: Claim, *, limit: int | None = None, seed: int = 0, deadline: float | None = None,
                 mutant_timeout: float | None = None,
                 on_event: Callable[[str, str, int], None] | None = None) -> ClaimMutations:
    """Run every (or a seeded subset of) mutant of ``c`` through its own check.

    ``deadline`` (a ``time.time()`` value): no mutant starts after it.  ``mutant_timeout``:
    the limit of one mutant's check in seconds (default: :data:`TIMEOUT_FACTOR` times the
    claim's own check, at least :data:`TIMEOUT_FLOOR`).  ``on_event(kind, claim_id, n)`` is
    told ``("start", id, planned)`` and ``("mutant", id, done)`` as the run goes.
    """
    t0 = time.perf_counter()
    emit = on_event or (lambda kind, cid, n: None)
    if deadline is not None and time.time() >= deadline:
        rec = ClaimMutations(c.id, "not run", started=False, note="not started: the budget was reached")
        rec.planned = rec.not_run = planned_mutants(c, limit=limit)
        return rec
    try:
        with _time_limit(_left(deadline)):
            base = c.run()
    except MutantTimeout:
        rec = ClaimMutations(c.id, "not run", note="its own check ran past the budget")
        rec.planned = rec.not_run = planned_mutants(c, limit=limit)
        rec.seconds = round(time.perf_counter() - t0, 3)
        return rec
    rec = ClaimMutations(c.id, base.status)
    if c.parts is None or c.run_parts is None:
        rec.note, rec.no_mutants = NO_PARTS, True
    elif base.status not in ("verified", "erratum"):
        rec.note = f"not mutated: the claim itself is {base.status}"
    else:
        side = "printed" if base.status == "verified" else "corrected"
        rec.side = side
        try:
            parts = c.parts()
        except Exception as exc:  # the user's parts builder is broken: this claim cannot be mutated
            rec.note = f"not mutated: building its parts raised {type(exc).__name__}: {exc}"
            rec.seconds = round(time.perf_counter() - t0, 3)
            return rec
        cands = _candidates(c, parts, side, limit, seed, rec)
        rec.planned = len(cands)
        if not cands:
            rec.no_mutants = True
            rec.note = (f"its {side} parts give no mutants" if getattr(parts, side) else
                        f"it declares no {side} parts: put the statement it reports as holding in "
                        f"Parts({side}={{...}})")
        limit_s = mutant_timeout if mutant_timeout is not None else \
            max(TIMEOUT_FACTOR * (base.seconds or 0.0), TIMEOUT_FLOOR)
        emit("start", c.id, len(cands))
        for i, (name, m) in enumerate(cands):
            if deadline is not None and time.time() >= deadline:
                rec.not_run = len(cands) - i
                rec.note = f"budget reached after {i} of {len(cands)} mutants"
                break
            rec.mutants += 1
            entry = {"part": f"{side}.{name}", "operator": m.operator, "mutation": m.description}
            try:
                with _time_limit(limit_s):
                    out = c.run_with(parts.replace(side, name, m.expr))
            except MutantTimeout:
                rec.killed += 1
                rec.timeouts.append(dict(entry, limit=round(limit_s, 3)))
                emit("mutant", c.id, rec.mutants)
                continue
            emit("mutant", c.id, rec.mutants)
            if out.status != base.status:
                rec.killed += 1
            elif out.evidence == "proof":   # the check itself proved the mutated statement: no second decision
                rec.equivalent.append(dict(entry, decided_by="the check's own proof"))
            else:
                try:
                    with _time_limit(limit_s):
                        same, how = _equivalent(getattr(parts, side)[name], m.expr)
                except MutantTimeout:
                    same, how = False, "not decidable (timeout)"
                if same:
                    rec.equivalent.append(dict(entry, decided_by=how))
                else:
                    rec.survivors.append(entry)
    rec.seconds = round(time.perf_counter() - t0, 3)
    return rec


# --------------------------------------------------------------------------- many claims, in processes

_EVENTS: Any = None


def _init_worker(events: Any, project: Project | None, ids: Sequence[str]) -> None:
    global _EVENTS
    _EVENTS = events
    if any(i not in REGISTRY for i in ids):   # a spawned process: import the project's claims
        load(project)


def _send(kind: str, cid: str, n: int) -> None:
    if _EVENTS is not None:
        _EVENTS.put((kind, cid, n))


def _mutate_task(args: tuple[str, int | None, int, float | None, float | None]) -> dict[str, Any]:
    cid, limit, seed, deadline, mutant_timeout = args
    return mutate_claim(REGISTRY[cid], limit=limit, seed=seed, deadline=deadline, mutant_timeout=mutant_timeout,
                        on_event=_send).to_dict()


def run(claims: list[Claim], *, limit: int | None = None, seed: int = 0, jobs: int = 1,
        progress: Callable[[dict[str, Any]], None] | None = None, budget: float | None = None,
        mutant_timeout: float | None = None, project: Project | None = None,
        on_event: Callable[[str, str, int], None] | None = None) -> list[dict[str, Any]]:
    """Mutation records of ``claims`` (in order), optionally in ``jobs`` processes.

    ``budget``: wall-clock seconds for the whole run (no mutant starts after it);
    ``progress(record)`` is called as each claim finishes, ``on_event`` as in
    :func:`mutate_claim`.  ``project`` says where a spawned worker finds the claims.
    """
    deadline = None if budget is None else time.time() + budget
    tasks = [(c.id, limit, seed, deadline, mutant_timeout) for c in claims]
    if jobs <= 1 or len(tasks) <= 1:
        out = []
        for c in claims:
            rec = mutate_claim(c, limit=limit, seed=seed, deadline=deadline, mutant_timeout=mutant_timeout,
                               on_event=on_event).to_dict()
            out.append(rec)
            if progress:
                progress(rec)
        return out
    import multiprocessing as mp_
    import queue as queue_

    ctx = mp_.get_context("fork") if sys.platform != "win32" else mp_.get_context()
    events = ctx.Queue()

    def drain() -> None:
        while True:
            try:
                kind, cid, n = events.get_nowait()
            except queue_.Empty:
                return
            if on_event:
                on_event(kind, cid, n)

    records: list[dict[str, Any] | None] = [None] * len(tasks)
    pool = ProcessPoolExecutor(max_workers=min(jobs, len(tasks)), mp_context=ctx, initializer=_init_worker,
                               initargs=(events, project, [c.id for c in claims]))
    try:
        # one task per claim, dealt as workers free up (a long claim does not hold back the reports of others)
        futures: dict[Future[dict[str, Any]], int] = {pool.submit(_mutate_task, t): i for i, t in enumerate(tasks)}
        pending = set(futures)
        while pending:
            done, pending = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
            drain()
            for f in sorted(done, key=futures.__getitem__):
                rec = f.result()
                records[futures[f]] = rec
                if progress:
                    progress(rec)
        drain()
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown()
    return [r for r in records if r is not None]


# --------------------------------------------------------------------------- command line

class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line instead of usage + error
        self.exit(EXIT_USAGE, f"{self.prog}: {message}\n")


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number of seconds: {text!r}") from None
    if not (value > 0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, not {text!r}")
    return value


def build_parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="symbt mutate", description="mutation testing of the claims' checks",
                 epilog="exit status: 0 no mutant that ran survived (mutants left out by --budget and claims "
                        "without mutants do not fail), 1 a mutant survived (with --fail-under: the score is below "
                        "it), 2 usage error, 130 interrupted")
    ap.add_argument("--claims", action="append", metavar="MODULE_OR_PATH",
                    help="your claims: a module name or a .py file / package path (repeatable; default: "
                         "[tool.symbt] claims of pyproject.toml, else Zullo's paper)")
    ap.add_argument("--scene", action="append", metavar="NAME", help="scene / claim id / nK (repeatable)")
    ap.add_argument("--label", action="append", metavar="LABEL", help="every claim of this label (repeatable)")
    ap.add_argument("--limit", type=int, default=None, metavar="K", help="at most K mutants per claim (seeded)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the --limit subset (default: 0)")
    ap.add_argument("-j", "--jobs", type=int, default=min(2, os.cpu_count() or 1), metavar="N",
                    help="worker processes (default: min(2, cores))")
    ap.add_argument("--budget", type=_seconds, default=None, metavar="SECONDS",
                    help="wall-clock budget of the whole run: no mutant starts after it; the report says what did "
                         "not run")
    ap.add_argument("--mutant-timeout", type=_seconds, default=None, metavar="SECONDS",
                    help=f"limit of one mutant's check; past it the mutant counts as killed by timeout (default: "
                         f"{TIMEOUT_FACTOR:g} x the claim's own check, at least {TIMEOUT_FLOOR:g}s)")
    ap.add_argument("--fail-under", type=float, default=None, metavar="PERCENT",
                    help="exit 1 only if the mutation score is below PERCENT (default: on any survivor)")
    ap.add_argument("--json", metavar="FILE", help="write the records and the summary as JSON ('-': stdout)")
    ap.add_argument("-q", "--quiet", action="store_true", help="no report on the terminal, no progress")
    ap.add_argument("--source", nargs="*", metavar="MODULE",
                    help="mutate the implementation instead (symbt's modules, or your package's): see "
                         "'symbt mutate --source --help' and docs/mutation.md")
    return ap


def main(argv: list[str] | None = None) -> int:
    """``symbt mutate``; returns the exit status (see the module docstring)."""
    args_in = sys.argv[1:] if argv is None else argv
    if "--source" in args_in[:args_in.index("--") if "--" in args_in else None]:   # the implementation, not claims
        from .mutate_source import main as mutate_source

        return mutate_source(args_in)
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:  # --help, or a usage error already said in one line
        return exc.code if isinstance(exc.code, int) else EXIT_USAGE
    if output_refused(args.json, "symbt mutate"):
        return EXIT_USAGE
    if args.jobs < 1 or (args.limit is not None and args.limit < 1):
        print("symbt mutate: -j and --limit must be positive", file=sys.stderr)
        return EXIT_USAGE
    try:
        project = discover(claims=args.claims or ())
        claims = select(args.scene or None, project=project, labels=args.label or ())
    except (KeyError, ConfigError) as exc:
        print(f"symbt mutate: {exc.args[0] if isinstance(exc, KeyError) else exc}", file=sys.stderr)
        return EXIT_USAGE
    if not claims:
        print("symbt mutate: no claims selected", file=sys.stderr)
        return EXIT_USAGE
    t0 = time.perf_counter()
    bar = MutateProgress([c.id for c in claims], enabled=not args.quiet, budget=args.budget)
    try:
        records = run(claims, limit=args.limit, seed=args.seed, jobs=args.jobs, progress=bar.claim_done,
                      budget=args.budget, mutant_timeout=args.mutant_timeout, project=project, on_event=bar.event)
    finally:
        bar.close()
    s = summary(records)
    report = {"claims": records, "summary": s, "seconds": round(time.perf_counter() - t0, 1),
              "limit": args.limit, "seed": args.seed, "budget": args.budget}
    status = emit_document(report, args.json, command="symbt mutate", text=None if args.quiet else format_text(records))
    if status:
        return status
    return exit_status(s, args.fail_under)
