r"""A project's own emitted code: ``symbt codegen`` for ``symbt.emit`` declarations, and their claims.

``symbt codegen`` runs :func:`main`: with ``--codegen MODULE_OR_PATH`` (repeatable) or a
``[tool.symbt]`` table listing ``codegen`` sources, it imports them (their ``symbt.emit`` calls
declare the functions) and writes or checks the user's files (:mod:`symbt.codegen.user.files`);
otherwise it is exactly the package's own ``symbt codegen`` (:mod:`symbt.codegen.cli`)::

    symbt codegen [--codegen MODULE_OR_PATH ...] [--target python|c] [--out DIR] [--check] [-q]

``--out`` defaults to ``codegen-out`` of ``[tool.symbt]``, else ``generated/`` beside the
configuration file (the working directory without one).  ``--check`` writes nothing and exits 1
with one line per missing, stale or hand-edited file; a bad declaration, a source that does not
import, a malformed ``[tool.symbt]`` or an unwritable directory is one line on stderr, exit 2.

:func:`symbt.engine.emitted_claims.register_emitted` (called by :func:`symbt.engine.project.load`
for a project with ``codegen`` sources) gives every declared function three claims in the scene ``codegen``,
owned by the module that declared it: ``emit.<module>.<name>.numpy``, ``.mpmath`` and ``.c``
(``skipped`` with the reason when the C file was not emitted or no compiler is present).  Each
checks the file's provenance (missing, stale or hand-edited: ``failed``), then compares the
emitted function, imported from disk, with its SymPy source (:mod:`symbt.codegen.user.check`).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import NoReturn

from ..codegen.user.declare import emissions_of
from ..codegen.user.files import by_module, check, generate
from .project import ConfigError, _import, discover

__all__ = ["main"]


# --------------------------------------------------------------------------- the command line

class _UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line, exit 2
        raise _UsageError(message)


def _parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="symbt codegen", description="emit (or check) the numeric code of your project's "
                 "symbt.emit declarations ([tool.symbt] codegen, or --codegen)")
    ap.add_argument("--codegen", action="append", default=[], metavar="MODULE_OR_PATH",
                    help="a module or .py file declaring functions with symbt.emit (repeatable)")
    ap.add_argument("--target", choices=("python", "c"), default="python", help="python (default) or c")
    ap.add_argument("--check", action="store_true",
                    help="write nothing; exit 1 if an emitted file is missing, stale or edited by hand")
    ap.add_argument("--out", metavar="DIR", default=None,
                    help="output directory (default: codegen-out of [tool.symbt], else generated/ beside it)")
    ap.add_argument("-q", "--quiet", action="store_true")
    return ap


def _fail(msg: str) -> int:
    print(f"symbt codegen: error: {msg}", file=sys.stderr)
    return 2


def _user_project(argv: list[str]) -> bool:
    if any(a == "--codegen" or a.startswith("--codegen=") for a in argv):
        return True
    try:
        return bool(discover().codegen)
    except ConfigError:
        return True   # let the user branch report the malformed configuration


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["--"]:
        argv = argv[1:]
    if not _user_project(argv):
        from ..codegen.cli import main as package_main

        return package_main(argv)
    try:
        args = _parser().parse_args(argv)
    except _UsageError as exc:
        return _fail(f"{exc} (in a project with [tool.symbt] codegen; --n, --project and --installed are "
                     "for symbt's own modules)" if "unrecognized" in str(exc) else str(exc))
    try:
        project = discover(codegen=args.codegen)
        if not project.codegen:
            return _fail("no codegen sources (give --codegen MODULE_OR_PATH or [tool.symbt] codegen)")
        out = Path(args.out).resolve() if args.out else (project.codegen_out or project.root / "generated")
        names = [_import(spec, "codegen") for spec in project.codegen]
        ems = emissions_of(names)
        empty = [s for s, n in zip(project.codegen, names) if not emissions_of([n])]
        if empty:
            return _fail(f"codegen source {empty[0]!r} declares nothing to emit (call symbt.emit)")
    except ConfigError as exc:
        return _fail(str(exc))
    try:
        if args.check:
            problems = check(ems, project.root, out, args.target)
            for msg in problems:
                print(f"symbt codegen --check: {msg}", file=sys.stderr)
            if not problems and not args.quiet:
                print(f"symbt codegen --check: {len(by_module(ems))} emitted module(s) up to date in {out}")
            return 1 if problems else 0
        paths = generate(ems, project.root, out, args.target)
    except OSError as exc:
        return _fail(f"cannot write to {out}: {exc.strerror or exc}")
    except ValueError as exc:
        return _fail(str(exc))
    if not args.quiet:
        for p in paths:
            print(f"wrote {p}")
    return 0
