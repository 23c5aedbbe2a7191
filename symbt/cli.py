"""Command line: ``symbt verify | scenes | codegen | bench | figures``.

Subcommands other than ``verify``/``scenes`` are provided by modules that may
depend on optional extras; they are imported only when invoked.
"""
from __future__ import annotations

import argparse
import importlib
import os
import sys
import time

__all__ = ["main"]


def _cmd_verify(args) -> int:
    from . import engine, report
    from ._files import atomic_write

    try:
        claims = engine.select(args.scene or None, include_deep=args.deep)
    except KeyError as exc:
        print(f"symbt: {exc.args[0]}", file=sys.stderr)
        return 2
    if not claims:
        print("symbt: no claims selected", file=sys.stderr)
        return 2
    jobs = args.jobs if args.jobs is not None else min(2, os.cpu_count() or 1)
    t0 = time.perf_counter()

    def progress(c, out):
        if args.verbose:
            print(f"  {out.status:9s} {c.id} ({out.seconds:.2f}s)", file=sys.stderr, flush=True)

    results = engine.run(claims, use_cache=not args.no_cache, jobs=jobs, progress=progress)
    wall = time.perf_counter() - t0
    if not args.quiet:
        print(report.format_table(results))
        print(f"wall time {wall:.1f}s")
    if args.json:
        report.write_json(results, args.json)
    if args.junit:
        report.write_junit(results, args.junit)
    if args.markdown:
        atomic_write(args.markdown, report.format_markdown(results))
    return 0 if report.summary(results)["ok"] else 1


def _cmd_scenes(args) -> int:
    from .claims import REGISTRY, SCENES, load_all

    load_all()
    for name, meta in SCENES.items():
        ids = [c.id for c in REGISTRY.values() if c.scene == name]
        flag = " [deep]" if meta.get("deep") else ""
        print(f"{name}{flag}: {meta['description']}")
        for cid in ids:
            c = REGISTRY[cid]
            print(f"    {cid:34s} eq. {c.equation}" + (" [deep]" if c.deep else ""))
    print("pseudo-scenes: n2, n3, n4 (claims by lattice size); any claim id selects itself")
    return 0


def _delegate(module: str, func: str = "main"):
    def run(args) -> int:
        mod = importlib.import_module(f"symbt.{module}")
        return getattr(mod, func)(args.rest)
    return run


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="symbt", description="Checked, executable mathematics for "
                                 "Zullo, 'Bäcklund transformations and Hamiltonian flows'.")
    sub = ap.add_subparsers(dest="cmd", required=True)
    v = sub.add_parser("verify", help="check the paper's claims and print a table")
    v.add_argument("--scene", action="append", metavar="NAME",
                   help="run only this scene / claim id / nK (repeatable)")
    v.add_argument("--deep", action="store_true", help="include deep (minutes-long) claims")
    v.add_argument("--json", metavar="FILE", help="write results as JSON")
    v.add_argument("--junit", metavar="FILE", help="write JUnit XML")
    v.add_argument("--markdown", metavar="FILE", help="write a Markdown table")
    v.add_argument("--no-cache", action="store_true", help="recompute every claim")
    v.add_argument("-j", "--jobs", type=int, default=None, help="worker processes (default: min(2, cores))")
    v.add_argument("-q", "--quiet", action="store_true")
    v.add_argument("-v", "--verbose", action="store_true")
    v.set_defaults(func=_cmd_verify)
    s = sub.add_parser("scenes", help="list scenes and their claims")
    s.set_defaults(func=_cmd_scenes)
    for name, module, helptext in (("codegen", "codegen", "emit/check generated numeric modules"),
                                   ("bench", "bench", "work-precision benchmarks"),
                                   ("figures", "report.figures", "regenerate the paper's figures")):
        p = sub.add_parser(name, help=helptext, add_help=False)
        p.add_argument("rest", nargs=argparse.REMAINDER)
        p.set_defaults(func=_delegate(module))
    return ap


_DELEGATED = {"codegen": "codegen", "bench": "benchmarks", "figures": "report.figures"}


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    # delegated subcommands parse their own options (argparse.REMAINDER would not pass leading --flags)
    if argv and argv[0] in _DELEGATED:
        return importlib.import_module(f"symbt.{_DELEGATED[argv[0]]}").main(argv[1:])
    args = build_parser().parse_args(argv)
    return args.func(args)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
