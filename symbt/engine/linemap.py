"""Which claim executes which line: the map ``symbt mutate --source`` uses to run only the claims that
can see a mutant.

Run as ``python -m symbt.engine.linemap --out FILE [--claims SRC ...] [--scene NAME ...] [--timeout S] FILE.py ...``
in the (unmutated) copy of the source tree.  It loads the project's default claims under a line
tracer (the lines run at import time are recorded apart: a mutant there can change any claim),
then runs the claims one after another in this process, as ``symbt verify -j 1`` does, switching
the record at each claim.  The tracer is coverage.py's C tracer with one dynamic context per claim
when coverage is installed (``symbt[mutate]``), else ``sys.settrace`` restricted to the target
files (slower, no extra library).

Every target module is imported before the first claim runs, so a line run while a module is
imported -- its top level and whatever the top level calls, a table builder say -- is an import
line even when the claims import that module lazily (such a line can change any claim; credited
to the claim that first imported the module, it would hide the mutant from all the others).

Known limits: a line run only to fill a cache that several claims share is credited to the first
claim that ran it (running each claim in a fresh process instead was 50x slower here: each
recomputes the shared derivations); lines run in a subprocess of a claim (a C compiler, a pool)
are not seen.

The output (JSON)::

    {"import": {file: [line, ...]}, "claims": {id: {"lines": {file: [line, ...]}, "seconds": s,
     "status": st}}, "timed_out": [id, ...], "failed": {module: "its import error"}}

>>> tracer, seen = line_tracer({__file__})
>>> callable(tracer), seen
(True, {})
"""
from __future__ import annotations

import argparse
import json
import signal
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

__all__ = ["line_tracer", "main", "module_name"]


def line_tracer(files: set[str]) -> tuple[Callable[..., Any], dict[str, set[int]]]:
    """A ``sys.settrace`` function recording the lines run in ``files``, and the dict it fills."""
    seen: dict[str, set[int]] = {}
    locals_: dict[str, Callable[..., Any]] = {}

    def local_for(name: str) -> Callable[..., Any]:
        lines = seen.setdefault(name, set())

        def local(frame: Any, event: str, arg: Any) -> Any:
            if event == "line":
                lines.add(frame.f_lineno)
            return local
        return local

    def tracer(frame: Any, event: str, arg: Any) -> Any:
        name = frame.f_code.co_filename
        if name not in files:
            return None
        loc = locals_.get(name)
        if loc is None:
            loc = locals_[name] = local_for(name)
        seen[name].add(frame.f_lineno)
        return loc

    return tracer, seen


def module_name(path: Path) -> str | None:
    """The dotted name under which ``path`` is imported: its parents up to the first directory without
    ``__init__.py`` (``None`` for a ``__main__`` module: importing it would run a command).

    >>> module_name(Path(__file__))
    'symbt.engine.linemap'
    """
    parts = [path.stem] if path.name != "__init__.py" else []
    d = path.parent
    while (d / "__init__.py").is_file():
        parts.insert(0, d.name)
        d = d.parent
    return None if not parts or parts[-1] == "__main__" else ".".join(parts)


def _import_targets(files: set[str]) -> dict[str, str]:
    """Import the module of every target file (under the import record); the modules that failed to
    import, with their error (an optional dependency missing, say: its lines then run in no claim
    either)."""
    import importlib

    failed: dict[str, str] = {}
    for f in sorted(files):
        name = module_name(Path(f))
        if name is None or name in sys.modules:
            continue
        try:
            importlib.import_module(name)
        except Exception as exc:  # recorded; the run goes on
            failed[name] = f"{type(exc).__name__}: {exc}"
    return failed


def _start(tracer: Callable[..., Any]) -> None:
    threading.settrace(tracer)
    sys.settrace(tracer)


def _stop() -> None:
    sys.settrace(None)
    threading.settrace(None)  # type: ignore[arg-type,unused-ignore]


def _plain(seen: dict[str, set[int]]) -> dict[str, list[int]]:
    return {f: sorted(v) for f, v in seen.items() if v}


class _Alarm(BaseException):
    """A claim ran past ``--timeout`` (a BaseException: a check's ``except Exception`` does not swallow it)."""


def _alarm(signum: int, frame: Any) -> None:
    raise _Alarm()


def _traced_runs(claims: list[Any], files: set[str], timeout: float, scenes: list[str],
                 deep: bool = False) -> dict[str, Any]:
    """Run the claims one after another (in one process, as ``symbt verify -j 1`` does), recording the
    lines of ``files`` each runs: with coverage.py's C tracer when it is installed, else ``sys.settrace``."""
    result: dict[str, Any] = {"import": {}, "claims": {}, "timed_out": [], "failed": {}}
    cov: Any = None
    seen: dict[str, set[int]] = {}
    try:
        import coverage
    except ImportError:   # the slower tracer of this module
        coverage = None   # type: ignore[assignment]
    if coverage is not None:
        cov = coverage.Coverage(data_file=None, config_file=False, include=sorted(files))
        cov.start()
    else:
        tracer, seen = line_tracer(files)
        _start(tracer)
    from .project import discover
    from .select import select

    chosen = select(scenes or None, project=discover(claims=claims), include_deep=deep)
    result["failed"] = _import_targets(files)
    if cov is None:
        result["import"] = _plain(seen)
    previous = signal.signal(signal.SIGALRM, _alarm)
    for c in chosen:
        if cov is not None:
            cov.switch_context(c.id)
        else:
            _stop()
            tracer, seen = line_tracer(files)
            _start(tracer)
        t0 = time.perf_counter()
        signal.setitimer(signal.ITIMER_REAL, timeout, 1.0)
        try:
            status: str = c.run(deep=deep).status
        except _Alarm:
            status = "timed out"
            result["timed_out"].append(c.id)
        except Exception as exc:  # recorded with what it ran
            status = f"raised {type(exc).__name__}"
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        entry: dict[str, object] = {"seconds": round(time.perf_counter() - t0, 3), "status": status}
        if cov is None:
            entry["lines"] = _plain(seen)
        result["claims"][c.id] = entry
    signal.signal(signal.SIGALRM, previous)
    if cov is None:
        _stop()
        return result
    cov.stop()
    data = cov.get_data()
    imports: dict[str, set[int]] = {}
    per: dict[str, dict[str, set[int]]] = {}
    for f in data.measured_files():
        for line, contexts in data.contexts_by_lineno(f).items():
            for ctx in contexts:
                (imports.setdefault(f, set()) if ctx == "" else
                 per.setdefault(ctx, {}).setdefault(f, set())).add(line)
    result["import"] = _plain(imports)
    for cid, entry in result["claims"].items():
        entry["lines"] = _plain(per.get(cid, {}))
    return result


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m symbt.engine.linemap")
    ap.add_argument("--out", required=True)
    ap.add_argument("--claims", action="append", default=[])
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--scene", action="append", default=[])
    ap.add_argument("--deep", action="store_true", help="the deep claims and variants too (symbt verify --deep)")
    ap.add_argument("files", nargs="+")
    args = ap.parse_args(argv)
    files = {str(Path(f).resolve()) for f in args.files}
    result = _traced_runs(args.claims, files, args.timeout, args.scene, deep=args.deep)
    Path(args.out).write_text(json.dumps(result), encoding="utf-8")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
