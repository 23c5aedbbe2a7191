"""``symbt codegen``: emit (or ``--check``) the generated code of the checkout you stand in.

::

    symbt codegen [--n N ...] [--target python|c] [--out DIR] [--check]
                  [--project DIR | --installed] [-q]

* the source tree: the checkout found from the working directory (or ``--project DIR``);
  the package Python imported with ``--installed``, or when ``--out DIR`` is given outside
  any checkout (code for a project of your own).  When the checkout is not the
  imported package, the command re-runs itself with the checkout on ``PYTHONPATH`` so that
  its own derivation sources are used (see :mod:`symbt.codegen.project`);
* ``--n``: lattice sizes (default 2 3); ``--target c`` writes ``toda{N}.c``/``.h`` (needs
  ``--out``); ``--check`` writes nothing and exits 1 naming every missing, stale or
  hand-edited file;
* usage errors (no checkout found, unwritable directory, bad option) are one line on stderr,
  exit code 2.
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import NoReturn

from .files import LANGUAGES, TARGETS, check, file_names, generate
from .project import DELEGATED_ENV, find_project, imported_package, is_project, run_in_checkout

__all__ = ["main"]


class _UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line, exit 2 (argparse prints usage + message)
        raise _UsageError(message)


def _parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="symbt codegen", description="emit (or check) the generated numeric code "
                 "(symbt/generated/toda{N}.py, or C with --target c) of the symbt checkout you stand in")
    ap.add_argument("--n", type=int, nargs="+", metavar="N", default=list(TARGETS),
                    help="lattice sizes (default: %s)" % " ".join(map(str, TARGETS)))
    ap.add_argument("--target", choices=LANGUAGES, default="python", help="python (default) or c")
    ap.add_argument("--check", action="store_true",
                    help="write nothing; exit 1 if a generated file is missing, stale or edited by hand")
    ap.add_argument("--out", metavar="DIR", default=None,
                    help="output directory (default: <source tree>/symbt/generated; required for --target c)")
    where = ap.add_mutually_exclusive_group()
    where.add_argument("--project", metavar="DIR", default=None,
                       help="the symbt checkout to act on (default: found from the working directory)")
    where.add_argument("--installed", action="store_true",
                       help="act on the installed (imported) symbt package instead of a checkout")
    ap.add_argument("-q", "--quiet", action="store_true")
    return ap


def _fail(msg: str) -> int:
    print(f"symbt codegen: error: {msg}", file=sys.stderr)
    return 2


def _delegate_argv(argv: list[str], out: Path | None) -> list[str]:
    """The arguments for the re-run in the checkout: --project dropped (re-added), --out made absolute."""
    res, skip = [], False
    for a in argv:
        if skip:
            skip = False
        elif a in ("--project", "--out"):
            skip = True
        elif not a.startswith(("--project=", "--out=")):
            res.append(a)
    return res + (["--out", str(out)] if out is not None else [])


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["--"]:  # `symbt codegen -- --check`
        argv = argv[1:]
    try:
        args = _parser().parse_args(argv)
    except _UsageError as exc:
        return _fail(str(exc))
    if any(n < 2 for n in args.n):
        return _fail(f"--n: lattice sizes must be >= 2, got {' '.join(map(str, args.n))}")
    if args.target == "c" and args.out is None:
        return _fail("--target c needs --out DIR")
    out = Path(args.out).resolve() if args.out is not None else None
    imported = imported_package()
    # emitting into a directory of your own (--out) outside any checkout uses the installed derivations;
    # writing or checking the package's own symbt/generated needs a checkout (or --installed)
    outside = args.project is None and out is not None and find_project() is None
    if args.installed or outside:
        pkg = imported
    else:
        if args.project is not None:
            root = Path(args.project).resolve()
            if not is_project(root):
                return _fail(f"--project {args.project}: not a symbt checkout (needs pyproject.toml with "
                             "name = \"symbt\" and a symbt/ package)")
        else:
            found = find_project()
            if found is None:
                return _fail(f"no symbt checkout at or above {Path.cwd()} (a pyproject.toml naming symbt "
                             "with a symbt/ package); use --project DIR, or --installed for the installed package")
            root = found
        pkg = root / "symbt"
        if pkg.resolve() != imported.resolve():
            if os.environ.get(DELEGATED_ENV):
                return _fail(f"the checkout {root} is not importable (Python imports symbt from {imported})")
            return run_in_checkout(root, _delegate_argv(argv, out))
    out_dir = out if out is not None else pkg / "generated"
    where = f"{out_dir}" + ("" if (args.installed or outside) else f" (checkout {pkg.parent})")
    try:
        if args.check:
            problems = check(out_dir, args.n, args.target)
            for msg in problems:
                print(f"symbt codegen --check: {msg}", file=sys.stderr)
            if not problems and not args.quiet:
                print(f"symbt codegen --check: {len(file_names(args.n, args.target))} generated files up to date "
                      f"in {where}")
            return 1 if problems else 0
        paths = generate(out_dir, args.n, args.target)
    except OSError as exc:
        return _fail(f"cannot write to {out_dir}: {exc.strerror or exc}")
    except ValueError as exc:
        return _fail(str(exc))
    if not args.quiet:
        for p in paths:
            print(f"wrote {p}")
        unchanged = len(file_names(args.n, args.target)) - len(paths)
        if unchanged:
            print(f"{unchanged} file(s) already up to date in {where}; not rewritten")
    return 0
