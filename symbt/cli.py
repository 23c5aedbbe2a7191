"""Command line: ``symbt verify | scenes | codegen | bench | figures``.

Exit status: ``0`` success (no claim *failed*: verified, errata and skipped
claims pass), ``1`` at least one claim failed (or ``codegen --check`` found a
stale file), ``2`` a usage or I/O error -- a one-line message on stderr, no
traceback (``--debug`` or ``SYMBT_DEBUG=1`` shows it), e.g. an unknown scene,
``-j 0``, a report path in a missing directory, a missing optional extra --
and ``130`` after Ctrl-C (what finished is cached).  A closed output pipe
(``symbt scenes | head``) ends the output silently.

Subcommands other than ``verify``/``scenes`` are provided by modules that may
depend on optional extras; they are imported only when invoked.  A warm
``symbt verify`` (everything cached, no source changed) imports neither SymPy
nor NumPy nor mpmath (:mod:`symbt.engine.warm`).
"""
from __future__ import annotations

import argparse
import importlib
import importlib.util
import os
import sys
import time

from . import __version__
from .engine.project import ConfigError

__all__ = ["main", "build_parser", "UsageError", "EXTRAS"]

#: top-level module -> the extra that installs it (``pip install "symbt[EXTRA]"``)
EXTRAS = {"scipy": "scipy", "matplotlib": "plot", "flint": "certified", "numba": "fast", "gmpy2": "gmpy2",
          "heyoka": "peers", "dask": "dask", "distributed": "dask", "jupytext": "notebooks",
          "nbclient": "notebooks", "ipykernel": "notebooks", "rich": "rich",
          "pylatexenc": "latex", "latex2mathml": "report", "selenium": "report", "graphviz": "report"}
EXIT_OK, EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130


class UsageError(Exception):
    """A usage or I/O error: one line on stderr, exit status 2."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # one line instead of usage + error
        raise UsageError(f"{self.prog}: {message} (see '{self.prog} --help')")


def _positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {n}")
    return n


def _positive_seconds(text: str) -> float:
    try:
        t = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive number of seconds, got {text!r}") from None
    if not 0 < t < float("inf"):
        raise argparse.ArgumentTypeError(f"expected a positive number of seconds, got {text}")
    return t


def _extra_for(exc: ImportError) -> str | None:
    name = (getattr(exc, "name", None) or "").split(".")[0]
    return EXTRAS.get(name)


# --------------------------------------------------------------------------- verify

def _check_output(flag: str, path: str) -> None:
    """Fail before any work if a report cannot be written."""
    from ._files import output_problem

    problem = output_problem(path)
    if problem:
        raise UsageError(f"symbt verify: {flag} {problem}")


def _write_output(flag: str, path: str, text: str) -> None:
    """Write one report: ``-`` to stdout, a file atomically, a device, pipe or symlink through."""
    from ._files import write_report

    try:
        write_report(path, text)
    except BrokenPipeError:
        if path != "-":
            raise UsageError(f"symbt verify: cannot write {flag} {path}: broken pipe") from None
        _silence_stdout()
    except OSError as exc:
        raise UsageError(f"symbt verify: cannot write {flag} {path}: {exc.strerror or exc}") from exc


def _render(flag: str, results, project=None) -> str:
    if flag == "--json":
        from .engine.coverage import coverage_of
        from .report.json import dumps

        return dumps(results, coverage=coverage_of(results, project))
    if flag == "--junit":
        from .report.junit import junit_xml

        return junit_xml(results)
    from .report.markdown import format_markdown

    return format_markdown(results)


def _cmd_verify(args) -> int:
    from .engine.warm import cached_results

    reports = {flag: path for flag, path in (("--json", args.json), ("--junit", args.junit),
                                             ("--markdown", args.markdown)) if path}
    from ._files import is_stdout

    to_stdout = [f for f, p in reports.items() if is_stdout(p)]   # '-', or /dev/stdout into a pipe or file
    if len(to_stdout) > 1:
        raise UsageError(f"symbt verify: only one report can go to stdout ('-'), not {' and '.join(to_stdout)}")
    for flag, path in reports.items():
        _check_output(flag, path)
    if args.dask is not None and importlib.util.find_spec("distributed") is None:
        raise ModuleNotFoundError("No module named 'distributed'", name="distributed")
    jobs = args.jobs if args.jobs is not None else min(2, os.cpu_count() or 1)
    t0 = time.perf_counter()
    project = _project(args)
    labels = args.label or ()
    results = None if args.no_cache else cached_results(args.scene or None, deep=args.deep, project=project,
                                                        labels=labels)
    if results is None:
        from . import engine
        from .report.progress import Progress

        try:
            claims = engine.select(args.scene or None, include_deep=args.deep, project=project, labels=labels)
        except KeyError as exc:
            raise UsageError(f"symbt verify: {exc.args[0]}") from None
        bar = Progress(len(claims), enabled=not args.quiet)
        try:
            seconds = args.budget if args.budget is not None else project.budget
            budget = {} if seconds is None else {"budget": seconds}
            results = engine.run(claims, use_cache=not args.no_cache, jobs=jobs, progress=bar, dask=args.dask,
                                 deep=args.deep, **budget)
        finally:
            bar.close()
    if not results:
        raise UsageError("symbt verify: no claims selected")
    wall = time.perf_counter() - t0

    from .report.text import format_short, format_table, summary

    code = EXIT_OK if summary(results)["ok"] else EXIT_FAILED
    for flag, path in reports.items():
        _write_output(flag, path, _render(flag, results, project))
    if not args.quiet:
        text = (format_table if args.verbose else format_short)(results, wall=wall)
        try:
            print(text, file=sys.stderr if to_stdout else sys.stdout, flush=True)
        except BrokenPipeError:
            _silence_stdout()
    return code


def _project(args):
    """The project of a front end: ``--claims`` and ``[tool.symbt]`` (see :mod:`symbt.engine.project`)."""
    from .engine.project import discover

    return discover(claims=args.claims or ())


def _cmd_scenes(args) -> int:
    from .engine.warm import scene_listing

    claims, scenes = scene_listing(_project(args))
    for name, meta in scenes.items():
        flag = " [deep]" if meta.get("deep") else ""
        print(f"{name}{flag}: {meta.get('description', '')}")
        for c in claims:
            if c.scene == name:
                print(f"    {c.id:34s} eq. {c.equation}" + (" [deep]" if c.deep else ""))
    print("pseudo-scenes: nK (claims by lattice size K); any claim id selects itself; --label LABEL "
          "selects a paper label's claims")
    return EXIT_OK


# --------------------------------------------------------------------------- parser and dispatch

_DELEGATED_HELP = {"codegen": "emit/check generated numeric modules", "bench": "work-precision benchmarks",
                   "figures": "regenerate the paper's figures",
                   "mutate": "mutation testing of the claims' checks (--source: of the implementation)",
                   "coverage": "the paper's labelled displays: claims or reasons",
                   "init": "scaffold a claims module from your paper's labels",
                   "report": "the paper, annotated: a static HTML site from a verify run's JSON"}


def _pop_debug(argv: list[str]) -> bool:
    """Remove ``--debug`` (anywhere before ``--``) from ``argv``."""
    end = argv.index("--") if "--" in argv else len(argv)
    hits = [i for i in range(end) if argv[i] == "--debug"]
    for i in reversed(hits):
        del argv[i]
    return bool(hits)


def _dispatch(argv: list[str]) -> int:
    # delegated subcommands parse their own options (argparse.REMAINDER would not pass leading --flags)
    if argv and argv[0] in _DELEGATED:
        return importlib.import_module(f"symbt.{_DELEGATED[argv[0]]}").main(argv[1:])
    args = build_parser().parse_args(argv)
    return args.func(args)


def _silence_stdout() -> None:
    """After a closed pipe: send further output (and the interpreter's final flush) to /dev/null."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


def _claims_argument(p: argparse.ArgumentParser) -> None:
    p.add_argument("--claims", action="append", metavar="MODULE_OR_PATH",
                   help="your claims: a module name or a .py file / package path (repeatable; default: "
                        "[tool.symbt] claims of pyproject.toml, else Zullo's paper)")


def build_parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="symbt", description="Checked, executable mathematics for "
                 "Zullo, 'Bäcklund transformations and Hamiltonian flows'.",
                 epilog="exit status: 0 ok, 1 a claim failed, 2 usage or I/O error, 130 interrupted")
    ap.add_argument("--version", action="version", version=f"symbt {__version__}")
    ap.add_argument("--debug", action="store_true", help="show tracebacks of usage and I/O errors")
    sub = ap.add_subparsers(dest="cmd", required=True, metavar="COMMAND")
    v = sub.add_parser("verify", help="check the paper's claims and report")
    v.add_argument("--scene", action="append", metavar="NAME",
                   help="run only this scene / claim id / nK (repeatable)")
    v.add_argument("--label", action="append", metavar="LABEL",
                   help="run every claim of this paper label (repeatable)")
    _claims_argument(v)
    v.add_argument("--deep", action="store_true", help="include deep (minutes-long) claims")
    v.add_argument("--json", metavar="FILE", help="write the JSON report ('-': stdout)")
    v.add_argument("--junit", metavar="FILE", help="write JUnit XML ('-': stdout)")
    v.add_argument("--markdown", metavar="FILE", help="write a Markdown table ('-': stdout)")
    v.add_argument("--no-cache", action="store_true", help="recompute every claim")
    v.add_argument("-j", "--jobs", type=_positive_int, default=None, metavar="N",
                   help="worker processes (default: min(2, cores); at most the number of cores); "
                        "with --dask: local workers")
    v.add_argument("--budget", type=_positive_seconds, default=None, metavar="SECONDS",
                   help="time limit of each check (default 300); past it: inconclusive (timed out)")
    v.add_argument("--dask", nargs="?", const="", default=None, metavar="ADDRESS",
                   help="run uncached claims on a Dask cluster (a local one without ADDRESS); needs symbt[dask]")
    v.add_argument("-q", "--quiet", action="store_true", help="no report on the terminal, no progress")
    v.add_argument("-v", "--verbose", action="store_true", help="the full table of claims")
    v.set_defaults(func=_cmd_verify)
    s = sub.add_parser("scenes", help="list scenes and their claims")
    _claims_argument(s)
    s.set_defaults(func=_cmd_scenes)
    for name in _DELEGATED:
        p = sub.add_parser(name, help=_DELEGATED_HELP.get(name, ""), add_help=False)
        p.add_argument("rest", nargs=argparse.REMAINDER)
    return ap


# codegen: a project's own `symbt.emit` declarations (engine.emitting), else symbt's own modules (symbt.codegen)
_DELEGATED = {"codegen": "engine.emitting", "bench": "benchmarks", "figures": "report.figures",
              "mutate": "engine.mutate", "coverage": "engine.coverage", "init": "engine.init", "report": "engine.site"}


def main(argv=None) -> int:
    """Run the command line; returns the exit status (see the module docstring)."""
    as_program = argv is None
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = _pop_debug(argv) or os.environ.get("SYMBT_DEBUG", "") not in ("", "0")
    cmd = argv[0] if argv and not argv[0].startswith("-") else ""
    prog = f"symbt {cmd}".strip()

    def fail(message: str, code: int) -> int:
        if debug:
            import traceback

            traceback.print_exc()
        print(message, file=sys.stderr)
        return code

    try:
        code = _dispatch(argv)
    except BrokenPipeError:
        _silence_stdout()
        return EXIT_OK
    except UsageError as exc:
        return fail(str(exc), EXIT_USAGE)
    except ConfigError as exc:
        return fail(f"{prog}: {exc}", EXIT_USAGE)
    except KeyboardInterrupt as exc:
        finished, total = getattr(exc, "finished", None), getattr(exc, "total", None)
        done = f" ({finished} of {total} claims finished; their outcomes are cached)" if total is not None else ""
        code = fail(f"{prog}: interrupted{done}", EXIT_INTERRUPTED)
        if as_program:  # everything finished is on disk; skip tearing down SymPy's objects (most of a second)
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(code)
        return code
    except ImportError as exc:
        extra = _extra_for(exc)
        if extra is None:
            raise
        return fail(f"{prog}: needs the optional extra '{extra}': pip install 'symbt[{extra}]' ({exc})",
                    EXIT_USAGE)
    except OSError as exc:
        where = f" {exc.filename}" if getattr(exc, "filename", None) else ""
        return fail(f"{prog}: I/O error{where}: {exc.strerror or exc}", EXIT_USAGE)
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _silence_stdout()
    return code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
