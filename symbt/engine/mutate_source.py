"""``symbt mutate --source``: mutation testing of the *implementation* (symbt's, or your package's).

Each mutant is one single-point bug planted in a module (:mod:`symbt.engine.mutants`: a sign, an
index shift, a swapped comparison or branch, a dropped factor, a loosened tolerance, a constant,
``min``/``max``, ``abs``).  It is written into a *copy* of the source tree and ``symbt verify
--no-cache`` runs on that copy in a subprocess (:mod:`symbt.engine.source_tree`); the real tree is
never written.  Only the claims that execute the mutated line run: the map line -> claims comes from
one traced run of the claims on the unmutated copy (:mod:`symbt.engine.linemap`, cached by the
source's digest); a line run at import time (a module constant, a default value) can change any
claim, so every claim runs for it; a line no claim runs is a survivor without a run (``uncovered``).
The mutant is killed when a claim's status, evidence or scope differs from the unmutated run's.

Usage::

    symbt mutate --source [MODULE ...] [--claims SRC ...] [--scene NAME ...] [--sample K] [--seed S] [-j N]
                 [--budget SECONDS] [--mutant-timeout SECONDS] [--deep] [--tests] [--equivalents FILE]
                 [--fail-under PERCENT] [--json FILE] [--list] [-q]

``MODULE``: dotted names (``symbt.proof``, or short ``proof`` for symbt's own) of a module or a package
(every file under it).  Without ``--claims`` or a ``[tool.symbt]`` table this is symbt itself (default:
``symbolic proof numeric reference codegen``); with them it is your project, from the directory of
its ``pyproject.toml`` (name the modules).  ``--sample K``: at most K mutants per module, a seeded
(``--seed``) random subset; ``--budget``: the whole run's wall clock (map included), no mutant
starts after it; ``--mutant-timeout``: one mutant's limit (default: 4 x the unmutated time of its
claims plus 30 s); ``--deep``: the deep claims and variants too (``symbt verify --deep``: the numba-compiled
paths, more samples) in the map and in every mutant's run; ``--tests``: a survivor of verify runs the test
files that import its module;
``--equivalents FILE`` (default ``mutants-equivalent.toml`` beside the project): mutants marked
equivalent, with a reason::

    [[mutant]]
    id = "symbt.proof.screen:316:tolerance:d2f600ec"
    reason = "why no claim can tell it from the original"

A marked id that matches no mutant any more is reported *stale*.  Exit status: ``0`` no survivor
(with ``--fail-under P``: score >= P %), ``1`` otherwise, ``2`` usage error (an unknown module, a
malformed equivalents file, a bad option: one line on stderr), ``130`` interrupted (the running
verify processes are killed).

>>> sorted(parse_equivalents('[[mutant]]\\nid = "m:1:sign:0123abcd"\\nreason = "dead code"\\n').items())
[('m:1:sign:0123abcd', 'dead code')]
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import queue
import random
import re
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any, NoReturn

from .._files import directory_problem
from ..report.json import emit_document, output_refused, run_info
from ..report.mutation_source import SCHEMA_VERSION, exit_status, format_text, summary
from .mutants import SourceMutant, UsageError, find_mutants, match_equivalents, module_level_lines, parse_equivalents
from .project import ConfigError, Project, discover
from .source_tree import Mutated, copy_tree, kill_running, run_command, run_verify, subprocess_env, verify_changes

__all__ = ["DEFAULT_MODULES", "EQUIVALENTS_FILE", "resolve_modules", "parse_equivalents", "match_equivalents",
           "claims_of_line", "plan", "main", "UsageError"]

#: what ``symbt mutate --source`` mutates of symbt itself by default (issue 21)
DEFAULT_MODULES = ("symbolic", "proof", "numeric", "reference", "codegen")
EQUIVALENTS_FILE = "mutants-equivalent.toml"
EXIT_USAGE = 2
#: a mutant's limit: this many times its claims' unmutated time, plus the start of a verify process
TIMEOUT_FACTOR, TIMEOUT_START = 4.0, 30.0


# --------------------------------------------------------------------------- what to mutate

def resolve_modules(names: list[str], root: Path, *, package: bool) -> dict[str, list[tuple[str, Path]]]:
    """Module name -> its (dotted name, file) pairs under ``root``; ``package``: symbt's own (short
    names like ``proof`` mean ``symbt.proof``; ``symbt.generated`` is never mutated).  An unknown
    name raises :class:`UsageError`.

    >>> import symbt
    >>> mods = resolve_modules(["proof.screen"], Path(symbt.__file__).parent.parent, package=True)
    >>> [d for d, _ in mods["symbt.proof.screen"]]
    ['symbt.proof.screen']
    """
    out: dict[str, list[tuple[str, Path]]] = {}
    for name in names:
        cands = [name] + ([f"symbt.{name}"] if package and not name.startswith("symbt") else [])
        for dotted in cands:
            if not re.fullmatch(r"[A-Za-z_][\w]*(\.[A-Za-z_][\w]*)*", dotted):
                continue
            base = root.joinpath(*dotted.split("."))
            if base.with_suffix(".py").is_file():
                out[dotted] = [(dotted, base.with_suffix(".py"))]
                break
            if (base / "__init__.py").is_file():
                files = sorted(p for p in base.rglob("*.py") if "__pycache__" not in p.parts
                               and not (package and "generated" in p.relative_to(root).parts))
                out[dotted] = [(".".join(p.relative_to(root).with_suffix("").parts), p) for p in files]
                break
        else:
            raise UsageError(f"no module {name!r} under {root}")
    return out


def claims_of_line(linemap: dict[str, Any], file: str, line: int, module_level: bool) -> list[str] | None:
    """The claims that run ``line`` of ``file`` (``None``: every claim -- an import-time line).

    >>> m = {"import": {"f": [1]}, "claims": {"a": {"lines": {"f": [5]}}, "b": {"lines": {"f": [6]}}}}
    >>> claims_of_line(m, "f", 5, False), claims_of_line(m, "f", 1, False), claims_of_line(m, "f", 9, False)
    (['a'], None, [])
    """
    if module_level or line in set(linemap["import"].get(file, ())):
        return None
    return [cid for cid, e in linemap["claims"].items() if line in set(e["lines"].get(file, ()))]


def plan(modules: dict[str, list[tuple[str, Path]]], root: Path, *, sample: int | None,
         seed: int) -> tuple[list[tuple[str, str, SourceMutant]], list[SourceMutant]]:
    """The (module, file relative to root, mutant) triples to run -- at most ``sample`` per module,
    seeded -- and every mutant of those modules (for the equivalents file)."""
    chosen, every = [], []
    for name, files in modules.items():
        here = []
        for dotted, path in files:
            try:
                ms = find_mutants(path.read_bytes(), dotted)
            except SyntaxError as exc:
                raise UsageError(f"{path}: does not parse: {exc.msg} (line {exc.lineno})") from None
            rel = str(path.relative_to(root))
            here += [(name, rel, m) for m in ms]
            every += ms
        if sample is not None and len(here) > sample:
            rng = random.Random(f"{seed}:{name}")
            here = sorted(rng.sample(here, sample), key=here.index)
        chosen += here
    return chosen, every


# --------------------------------------------------------------------------- the map and the baseline

def _sources(root: Path) -> list[Path]:
    return sorted(p for p in root.rglob("*.py") if "__pycache__" not in p.parts)


def _digest(root: Path, claims: list[str], scenes: list[str], deep: bool = False) -> str:
    from .cache import library_versions

    h = hashlib.sha256("\0".join([sys.version, library_versions(), *claims, "--scene", *scenes]
                                 + (["--deep"] if deep else [])).encode())
    for p in _sources(root):
        h.update(str(p.relative_to(root)).encode() + b"\0" + p.read_bytes())
    return h.hexdigest()[:20]


def _prepare(base: Path, claims: list[str], scenes: list[str], deadline: float | None,
             say: Any, deep: bool = False) -> tuple[dict[str, Any], dict[str, dict[str, Any]], bool]:
    """The line map of every file of the copy and the unmutated verify records (cached in the claim
    cache dir by the digest of the sources, the claims and the library versions)."""
    from .cache import cache_dir

    key = _digest(base, claims, scenes, deep)
    store = cache_dir() / "mutate-source" / f"{key}.json"
    try:
        doc = json.loads(store.read_text(encoding="utf-8"))
        return doc["map"], doc["baseline"], True
    except (OSError, ValueError, KeyError):
        pass
    left = None if deadline is None else max(deadline - time.time(), 0.1)
    import importlib.util

    tracer = "coverage.py" if importlib.util.find_spec("coverage") else \
        "sys.settrace, slower: pip install 'symbt[mutate]' for coverage.py's tracer"
    say(f"mapping lines to claims (one traced run of the claims; {tracer}) ...")
    out = base / ".symbt-linemap.json"
    argv = [sys.executable, "-m", "symbt.engine.linemap", "--out", str(out)]
    for c in claims:
        argv += ["--claims", c]
    for sc in scenes:
        argv += ["--scene", sc]
    if deep:
        argv.append("--deep")
    run = run_command([*argv, *map(str, _sources(base))], base, left or 3600.0, subprocess_env(base))
    if run.code != 0:
        why = "the budget ran out" if run.timed_out else run.last_error()
        raise UsageError(f"the traced run of the unmutated claims failed: {why}")
    linemap = json.loads(out.read_text(encoding="utf-8"))
    prefix = str(base) + os.sep
    for section in [linemap["import"], *(e["lines"] for e in linemap["claims"].values()),
                    *(e["lines"] for e in linemap.get("caches", {}).values())]:
        for f in list(section):
            section[f[len(prefix):] if f.startswith(prefix) else f] = section.pop(f)
    say("the unmutated verify run ...")
    left = None if deadline is None else max(deadline - time.time(), 0.1)
    vrun, records = run_verify(base, scenes or None, left or 3600.0, claims=claims, deep=deep)
    if records is None:
        raise UsageError(f"symbt verify on the unmutated copy wrote no report: {vrun.last_error()}")
    try:
        store.parent.mkdir(parents=True, exist_ok=True)
        store.write_text(json.dumps({"map": linemap, "baseline": records}), encoding="utf-8")
    except OSError:
        pass
    return linemap, records, False


# --------------------------------------------------------------------------- one mutant

def _tests_for(module: str, tests_dir: Path) -> list[Path]:
    """The test files that import ``module`` or a package of it (not the top-level package alone)."""
    parts = module.split(".")
    names = [".".join(parts[:i]) for i in range(len(parts), 1, -1)] or parts
    pat = re.compile(r"\b(" + "|".join(re.escape(n) for n in names) + r")\b")
    return sorted(p for p in tests_dir.glob("test_*.py") if pat.search(p.read_text(encoding="utf-8", errors="replace")))


def _record(item: tuple[str, str, SourceMutant], **fields: Any) -> dict[str, Any]:
    name, rel, m = item
    return {"id": m.id, "module": name, "file": rel, "line": m.line, "operator": m.operator, "diff": m.diff,
            "claims": 0, "seconds": 0.0, "detail": "", **fields}


def _run_one(copy: Path, item: tuple[str, str, SourceMutant], ids: list[str] | None, limit: float,
             ctx: dict[str, Any]) -> dict[str, Any]:
    _, rel, m = item
    rec = _record(item, claims=len(ctx["baseline"]) if ids is None else len(ids))
    path = copy / rel
    with Mutated(path, m.apply(path.read_bytes())):
        if ids == []:   # no claim runs the line: only the tests can kill it
            rec.update(result="uncovered", detail="no claim runs this line")
        else:
            run, records = run_verify(copy, ids if ids is not None else ctx["scenes"], limit, claims=ctx["claims"],
                                      deep=ctx["deep"])
            rec["seconds"] = round(run.seconds, 2)
            if run.timed_out:
                rec.update(result="timeout", detail=f"verify ran past {limit:.0f}s")
                return rec
            changes = verify_changes(ctx["baseline"], records, list(ctx["baseline"]) if ids is None else ids)
            if records is None or run.code not in (0, 1):
                rec.update(result="killed", detail=f"verify failed to run: {run.last_error()}")
            elif changes:
                rec.update(result="killed", detail="; ".join(changes[:3]) + (" ..." if len(changes) > 3 else ""))
            else:
                rec["result"] = "survived"
        if rec["result"] in ("survived", "uncovered") and ctx["tests"] is not None:
            tests = copy / "tests" if (copy / "tests").is_dir() else ctx["tests"]
            files = _tests_for(m.module, tests)
            if files:
                t = run_command([sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider",
                                 *map(str, files)], copy, ctx["tests_timeout"], subprocess_env(copy))
                rec["seconds"] = round(rec["seconds"] + t.seconds, 2)
                if t.timed_out or t.code not in (0, 5):
                    rec.update(result="tests", detail=f"{len(files)} test files, "
                               + ("timed out" if t.timed_out else f"pytest exit {t.code}"))
    return rec


# --------------------------------------------------------------------------- command line

class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line instead of usage + error
        raise UsageError(f"{self.prog}: {message}")


def _positive(kind: type) -> Any:
    def parse(text: str) -> Any:
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
        if not (v > 0 and v < float("inf")):
            raise argparse.ArgumentTypeError(f"must be positive, not {text!r}")
        return v
    return parse


def build_parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="symbt mutate", description="mutation testing of the implementation")
    ap.add_argument("--source", nargs="*", metavar="MODULE", required=True,
                    help="modules or packages to mutate (default for symbt: " + " ".join(DEFAULT_MODULES) + ")")
    ap.add_argument("--claims", action="append", metavar="MODULE_OR_PATH", help="your claims (as for verify)")
    ap.add_argument("--scene", action="append", metavar="NAME",
                    help="only these claims (scene, claim id or nK, as for verify; repeatable): a cheaper map, "
                         "fewer kills")
    ap.add_argument("--sample", type=_positive(int), default=None, metavar="K", help="at most K mutants per module")
    ap.add_argument("--seed", type=int, default=0, help="seed of --sample and of the run order (default 0)")
    ap.add_argument("-j", "--jobs", type=_positive(int), default=min(2, os.cpu_count() or 1), metavar="N",
                    help="mutants at once (default and maximum: the number of cores, at most 2 by default)")
    ap.add_argument("--budget", type=_positive(float), default=None, metavar="SECONDS",
                    help="wall clock of the whole run; no mutant starts after it")
    ap.add_argument("--mutant-timeout", type=_positive(float), default=None, metavar="SECONDS",
                    help=f"one mutant's limit (default {TIMEOUT_FACTOR:g} x its claims' time + {TIMEOUT_START:g}s)")
    ap.add_argument("--deep", action="store_true",
                    help="include the deep claims and variants (as symbt verify --deep) in the map and in every "
                         "mutant's run: more kills (the compiled numba paths), a slower map")
    ap.add_argument("--tests", action="store_true", help="run the test files importing the module on survivors")
    ap.add_argument("--tests-timeout", type=_positive(float), default=300.0, metavar="SECONDS")
    ap.add_argument("--equivalents", metavar="FILE", help=f"marked equivalent mutants (default {EQUIVALENTS_FILE})")
    ap.add_argument("--fail-under", type=float, default=None, metavar="PERCENT")
    ap.add_argument("--json", metavar="FILE", help="write the report as JSON ('-': stdout)")
    ap.add_argument("--list", action="store_true", help="list the mutants (id and diff) without running them")
    ap.add_argument("-q", "--quiet", action="store_true", help="no report on the terminal, no progress")
    return ap


def _setup(args: argparse.Namespace) -> tuple[Project, Path, bool, dict[str, list[tuple[str, Path]]], dict[str, str]]:
    project = discover(claims=args.claims or ())
    package = project.is_package
    if package:
        import symbt

        root = Path(symbt.__file__).resolve().parent.parent
    else:
        root = project.root
        if not args.source:
            raise UsageError("name the modules of your package to mutate: --source MODULE ...")
    modules = resolve_modules(list(args.source or DEFAULT_MODULES), root, package=package)
    if args.scene:   # known names only (this imports the claims; the runs happen in the copies)
        from .select import select

        try:
            select(args.scene, project=project)
        except KeyError as exc:
            raise UsageError(exc.args[0]) from None
    eq_path = Path(args.equivalents) if args.equivalents else project.root / EQUIVALENTS_FILE
    marked: dict[str, str] = {}
    if eq_path.is_file():
        marked = parse_equivalents(eq_path.read_text(encoding="utf-8"), str(eq_path))
    elif args.equivalents:
        raise UsageError(f"--equivalents {args.equivalents}: no such file")
    return project, root, package, modules, marked


def _in_copy(source: str, root: Path) -> str:
    """A ``--claims`` source as the copy sees it: a path under the project root, relative to it."""
    p = Path(source)
    if p.exists():
        try:
            return str(p.resolve().relative_to(root))
        except ValueError:
            raise UsageError(f"--claims {source}: outside the project root {root}, which is what is copied") from None
    return source


def main(argv: list[str] | None = None) -> int:
    """``symbt mutate --source``; returns the exit status (see the module docstring)."""
    t0 = time.time()
    try:
        args = build_parser().parse_args(argv)
        if output_refused(args.json, "symbt mutate --source"):
            return EXIT_USAGE
        if args.jobs > (os.cpu_count() or 1):
            raise UsageError(f"-j {args.jobs}: more than the {os.cpu_count()} cores of this machine")
        project, root, package, modules, marked = _setup(args)
        chosen, every = plan(modules, root, sample=args.sample, seed=args.seed)
        equivalent, stale = match_equivalents(marked, every, set(modules))
    except (UsageError, ConfigError) as exc:
        print(f"symbt mutate --source: {exc}" if not str(exc).startswith("symbt") else str(exc), file=sys.stderr)
        return EXIT_USAGE
    if args.list:
        for name, _rel, m in chosen:
            print(f"{m.id}  [{name}]\n" + "\n".join(f"    {d}" for d in m.diff.splitlines()))
        return 0
    say = (lambda text: None) if args.quiet else (lambda text: print(text, file=sys.stderr, flush=True))
    deadline = None if args.budget is None else t0 + args.budget
    claims = [] if package else [_in_copy(c, root) for c in (args.claims or ())]
    tmp = Path(tempfile.mkdtemp(prefix="symbt-mutate-"))
    problem = directory_problem(tmp)
    if problem:
        print(f"symbt mutate --source: temporary directory {problem}", file=sys.stderr)
        return EXIT_USAGE
    only = ["symbt"] if package else None
    try:
        say(f"copying {root} ({len(chosen)} mutants of {len(modules)} modules) ...")
        base = copy_tree(root, tmp / "base", only)
        try:
            linemap, baseline, cached = _prepare(base, claims, args.scene or [], deadline, say, deep=args.deep)
        except UsageError as exc:
            if deadline is None or time.time() < deadline:
                print(f"symbt mutate --source: {exc}", file=sys.stderr)
                return EXIT_USAGE
            linemap, baseline, cached = {"import": {}, "claims": {}}, {}, False   # the budget ran out first
        if baseline or deadline is None:
            records = _execute(args, chosen, equivalent, linemap, baseline, claims, tmp, base, deadline, project, say)
        else:
            records = [_record(item, result="not run", detail="the budget ran out before the line map was done")
                       for item in chosen]
    except KeyboardInterrupt:
        kill_running()
        print("symbt mutate --source: interrupted", file=sys.stderr)
        return 130
    finally:
        import shutil

        shutil.rmtree(tmp, ignore_errors=True)
    s = summary(records)
    notes = [f"map: {len(linemap['claims'])} claims traced{' (cached)' if cached else ''}; "
             f"{time.time() - t0:.0f}s in all" + (f"; budget {args.budget:g}s reached" if any(
                 r["result"] == "not run" for r in records) else "")]
    doc = {"schema_version": SCHEMA_VERSION, "kind": "mutate-source", "run": run_info(),
           "options": {"modules": list(modules), "scenes": args.scene or [], "sample": args.sample, "seed": args.seed,
                       "jobs": args.jobs,
                       "budget": args.budget, "tests": args.tests, "deep": args.deep},
           "mutants": records, "summary": s, "stale_equivalents": stale,
           "map": {"claims": len(linemap["claims"]), "cached": cached}, "seconds": round(time.time() - t0, 1)}
    status = emit_document(doc, args.json, command="symbt mutate --source",
                           text=None if args.quiet else format_text(records, stale=stale, notes=notes))
    return status or exit_status(s["total"], args.fail_under)


def _execute(args: argparse.Namespace, chosen: list[tuple[str, str, SourceMutant]], equivalent: dict[str, str],
             linemap: dict[str, Any], baseline: dict[str, dict[str, Any]], claims: list[str], tmp: Path,
             base: Path, deadline: float | None, project: Project, say: Any) -> list[dict[str, Any]]:
    """Classify and run the chosen mutants (in a seeded order, ``args.jobs`` at a time)."""
    level = {rel: module_level_lines((base / rel).read_bytes()) for rel in {rel for _, rel, _ in chosen}}
    seconds = {cid: e.get("seconds", 0.0) for cid, e in linemap["claims"].items()}
    ctx = {"baseline": baseline, "claims": claims, "scenes": args.scene or None, "tests_timeout": args.tests_timeout,
           "deep": args.deep,
           "tests": (project.root / "tests") if args.tests else None}
    records: list[dict[str, Any] | None] = [None] * len(chosen)
    todo = []
    for i, (_, rel, m) in enumerate(chosen):
        ids = claims_of_line(linemap, rel, m.line, m.line in level[rel])
        if m.id in equivalent:
            records[i] = _record(chosen[i], result="equivalent", detail=equivalent[m.id])
        elif ids == [] and not args.tests:
            records[i] = _record(chosen[i], result="uncovered", detail="no claim runs this line")
        else:
            ids = None if ids is None else [c for c in ids if c in baseline]
            est = sum(seconds.values()) if ids is None else sum(seconds.get(c, 0.0) for c in ids)
            limit = args.mutant_timeout or TIMEOUT_FACTOR * est + TIMEOUT_START
            todo.append((i, ids, limit))
    random.Random(args.seed).shuffle(todo)
    copies: queue.Queue[Path] = queue.Queue()
    for k in range(args.jobs):
        copies.put(base if k == 0 else copy_tree(base, tmp / f"w{k}"))
    done = [0]
    lock = threading.Lock()

    def work(task: tuple[int, list[str] | None, float]) -> None:
        i, ids, limit = task
        m = chosen[i][2]
        if deadline is not None and time.time() >= deadline:
            records[i] = _record(chosen[i], result="not run", detail="the budget was reached")
            return
        capped = deadline is not None and deadline - time.time() + 5.0 < limit
        if capped:
            limit = max(deadline - time.time(), 5.0) + 5.0   # type: ignore[operator]
        copy = copies.get()
        try:
            if stop:
                return
            rec = _run_one(copy, chosen[i], ids, limit, ctx)
        finally:
            copies.put(copy)
        if capped and rec["result"] == "timeout":   # stopped by the budget, not by its own limit: no verdict
            rec.update(result="not run", detail="cut short by the budget")
        records[i] = rec
        with lock:
            done[0] += 1
            say(f"[{done[0]}/{len(todo)}] {rec['result']:8s} {m.id} ({rec['seconds']:.0f}s, {rec['claims']} claims)")

    stop: list[bool] = []
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        try:
            list(pool.map(work, todo))
        except KeyboardInterrupt:   # no new mutant; the running ones are killed, with their workers
            stop.append(True)
            kill_running()
            raise
    return [r for r in records if r is not None]
