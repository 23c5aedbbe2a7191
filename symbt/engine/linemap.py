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

A cache that several claims share (a ``functools.lru_cache`` / ``functools.cache`` at module level in
the project's packages or the claims' modules) is filled by the first claim that calls it; the
others only read it.  Yet in a mutant's run each selected claim starts cold and runs the fill
itself, so the fill's lines belong to every claim that calls the cache.  Each such cache is
therefore wrapped for the traced run: the lines its fills run are recorded under a context of
their own (``cache:module.name``), the contexts that call it are noted, and every claim is credited
with the lines of each cache it reaches, directly or through other caches.  (Running each claim in
a fresh process instead was 50x slower here: each recomputes the shared derivations.)

Known limits: caches on class attributes and caches built at run time are not wrapped (their
fills are credited to the first claim that runs them); lines run in a subprocess of a claim (a C
compiler, a pool) are not seen.

The output (JSON)::

    {"import": {file: [line, ...]}, "claims": {id: {"lines": {file: [line, ...]}, "seconds": s,
     "status": st}}, "caches": {name: {"lines": {file: [line, ...]}, "callers": [context, ...]}},
     "timed_out": [id, ...], "failed": {module: "its import error"}}

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


def line_tracer(files: set[str], context: list[str] | None = None
                ) -> tuple[Callable[..., Any], dict[str, dict[str, set[int]]]]:
    """A ``sys.settrace`` function recording the lines run in ``files``, and the dict it fills:
    ``{context: {file: lines}}``, where the context is ``context[0]`` when the frame was entered (a frame
    keeps the context it started in, so a callee may record under another while its caller goes on
    under its own)."""
    current = context if context is not None else [""]
    seen: dict[str, dict[str, set[int]]] = {}
    locals_: dict[tuple[str, str], Callable[..., Any]] = {}

    def local_for(ctx: str, name: str) -> Callable[..., Any]:
        lines = seen.setdefault(ctx, {}).setdefault(name, set())

        def local(frame: Any, event: str, arg: Any) -> Any:
            if event == "line":
                lines.add(frame.f_lineno)
            return local
        return local

    def tracer(frame: Any, event: str, arg: Any) -> Any:
        name = frame.f_code.co_filename
        if name not in files:
            return None
        key = (current[0], name)
        loc = locals_.get(key)
        if loc is None:
            loc = locals_[key] = local_for(*key)
        seen[key[0]][name].add(frame.f_lineno)
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


class _Recorder:
    """The line record, switched between contexts: coverage.py's C tracer (one dynamic context each) when
    coverage is installed, else :func:`line_tracer`.  Context ``""`` is the import record."""

    def __init__(self, files: set[str]) -> None:
        try:
            import coverage
        except ImportError:   # the slower tracer of this module
            coverage = None   # type: ignore[assignment]
        self._context = [""]
        self._cov: Any = None
        self._seen: dict[str, dict[str, set[int]]] = {}
        if coverage is not None:
            self._cov = coverage.Coverage(data_file=None, config_file=False, include=sorted(files))
            self._cov.start()
        else:
            tracer, self._seen = line_tracer(files, self._context)
            threading.settrace(tracer)
            sys.settrace(tracer)

    def switch(self, context: str) -> None:
        self._context[0] = context
        if self._cov is not None:
            self._cov.switch_context(context)

    def stop(self) -> dict[str, dict[str, set[int]]]:
        """Stop recording; the lines by context."""
        if self._cov is None:
            sys.settrace(None)
            threading.settrace(None)  # type: ignore[arg-type,unused-ignore]
            return self._seen
        self._cov.stop()
        data = self._cov.get_data()
        per: dict[str, dict[str, set[int]]] = {}
        for f in data.measured_files():
            for line, contexts in data.contexts_by_lineno(f).items():
                for ctx in contexts:
                    per.setdefault(ctx, {}).setdefault(f, set()).add(line)
        return per


def _plain(seen: dict[str, set[int]]) -> dict[str, list[int]]:
    return {f: sorted(v) for f, v in seen.items() if v}


def _shared_caches(roots: set[str]) -> dict[str, Any]:
    """The module-level ``functools`` caches defined in the modules of the packages ``roots``, by name."""
    found: dict[str, Any] = {}
    for mname, mod in list(sys.modules.items()):
        if mod is None or mname.split(".")[0] not in roots:
            continue
        for attr, obj in list(vars(mod).items()):
            if (callable(getattr(obj, "cache_clear", None)) and hasattr(obj, "__wrapped__")
                    and getattr(obj, "__module__", None) == mname):
                found[f"cache:{mname}.{attr}"] = obj
    return found


class _CacheCredit:
    """Wrap the shared caches so that a fill records under the cache's own context and every call notes
    its caller (see the module's docstring); :meth:`restore` puts the caches back."""

    def __init__(self, caches: dict[str, Any], recorder: _Recorder, roots: set[str]) -> None:
        self.callers: dict[str, set[str]] = {name: set() for name in caches}
        self._stack = [""]
        self._recorder = recorder
        self._swaps: list[tuple[Any, str, Any]] = []
        wrapped = {id(orig): self._wrap(name, orig) for name, orig in caches.items()}
        for mname, mod in list(sys.modules.items()):
            if mod is None or mname.split(".")[0] not in roots:
                continue
            for attr, obj in list(vars(mod).items()):
                w = wrapped.get(id(obj))
                if w is not None:   # the defining module and every module that imported it by name
                    self._swaps.append((mod, attr, obj))
                    setattr(mod, attr, w)

    def enter_claim(self, cid: str) -> None:
        self._stack = [cid]
        self._recorder.switch(cid)

    def _wrap(self, name: str, orig: Any) -> Callable[..., Any]:
        import functools

        stack_of = self

        @functools.wraps(orig)
        def credited(*args: Any, **kwargs: Any) -> Any:
            stack = stack_of._stack
            stack_of.callers[name].add(stack[-1])
            stack.append(name)
            stack_of._recorder.switch(name)
            try:
                return orig(*args, **kwargs)
            finally:
                stack.pop()
                stack_of._recorder.switch(stack[-1])
        credited.cache_clear = orig.cache_clear     # type: ignore[attr-defined]
        credited.cache_info = orig.cache_info       # type: ignore[attr-defined]
        return credited

    def restore(self) -> None:
        for mod, attr, obj in self._swaps:
            setattr(mod, attr, obj)

    def reached(self, context: str) -> set[str]:
        """The caches ``context`` calls, directly or through other caches."""
        calls: dict[str, set[str]] = {}
        for cache, who in self.callers.items():
            for c in who:
                calls.setdefault(c, set()).add(cache)
        out: set[str] = set()
        todo = [context]
        while todo:
            for cache in calls.get(todo.pop(), ()):
                if cache not in out:
                    out.add(cache)
                    todo.append(cache)
        return out


class _Alarm(BaseException):
    """A claim ran past ``--timeout`` (a BaseException: a check's ``except Exception`` does not swallow it)."""


def _alarm(signum: int, frame: Any) -> None:
    raise _Alarm()


def _traced_runs(claims: list[Any], files: set[str], timeout: float, scenes: list[str],
                 deep: bool = False) -> dict[str, Any]:
    """Run the claims one after another (in one process, as ``symbt verify -j 1`` does), recording the
    lines of ``files`` each runs -- its own, and those of the fills of every shared cache it calls."""
    result: dict[str, Any] = {"import": {}, "claims": {}, "caches": {}, "timed_out": [], "failed": {}}
    recorder = _Recorder(files)
    from .project import discover
    from .select import select

    chosen = select(scenes or None, project=discover(claims=claims), include_deep=deep)
    result["failed"] = _import_targets(files)
    roots = {n.split(".")[0] for n in (module_name(Path(f)) for f in files) if n}
    roots |= {c.module.split(".")[0] for c in chosen if c.module}
    credit = _CacheCredit(_shared_caches(roots), recorder, roots)
    previous = signal.signal(signal.SIGALRM, _alarm)
    for c in chosen:
        credit.enter_claim(c.id)
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
        result["claims"][c.id] = {"seconds": round(time.perf_counter() - t0, 3), "status": status}
    signal.signal(signal.SIGALRM, previous)
    credit.restore()
    per = recorder.stop()
    result["import"] = _plain(per.get("", {}))
    for name, who in credit.callers.items():
        if who:
            result["caches"][name] = {"lines": _plain(per.get(name, {})), "callers": sorted(who)}
    for cid, entry in result["claims"].items():
        lines = {f: set(v) for f, v in per.get(cid, {}).items()}
        for cache in credit.reached(cid):
            for f, v in per.get(cache, {}).items():
                lines.setdefault(f, set()).update(v)
        entry["lines"] = _plain(lines)
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
