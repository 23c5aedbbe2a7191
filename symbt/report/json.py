"""The JSON report (``symbt verify --json FILE``, or ``--json -`` for stdout).

The document validates against the JSON Schema shipped with the package,
``symbt/report/verify.schema.json`` (:func:`schema`); ``schema_version``
changes its major number when a field is removed or changes meaning, its minor
number when a field is added::

    {"schema_version": "1.3", "generator": "symbt 0.1.0",
     "run": {"date", "python", "platform", "machine", "cpus", "libraries": {name: version}},  # 1.3
     "claims": [{"id", "equation", "scene", "N", "statement", "where", "uses",
                 "status", "evidence", "method", "seconds", "residual", "digits",
                 "printed", "corrected", "counterexample", "scope", "n_scope", "cells",
                 "detail", "cached"}, ...],
     "summary": {"total", "verified", "erratum", "failed", "inconclusive", "todo", "skipped",
                 "seconds", "ok"},
     "coverage": {label: {"claims": [{"id", "status"}, ...]} | {"reason", "see"}}}   # 1.1, optional

Schema 1.2 added the statuses ``inconclusive`` (a check that cannot decide at the
precision or budget given) and ``todo`` (a claim stub without a check), and their
counts in ``summary``; ``ok`` is false when any claim is failed, inconclusive or todo.
Schema 1.3 added ``run`` (when and where the run happened: :func:`run_info`) and each claim's
``uses`` (the claim ids or paper labels it relies on; ``symbt report --html`` draws them).

Non-finite numbers (a residual of ``inf``) are written as the strings ``"inf"``,
``"-inf"``, ``"nan"`` (JSON has no such numbers); anything else that is not
JSON (e.g. a SymPy number in a counterexample) as its ``str``.

>>> from symbt.claims.base import Claim, ClaimResult, Outcome
>>> r = ClaimResult(Claim("t", "eq", "s", check=None), Outcome("failed", "numeric", residual=float("inf")))
>>> doc = to_json([r])
>>> doc["schema_version"], doc["claims"][0]["residual"], doc["summary"]["ok"]
('1.3', 'inf', False)
"""
from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .. import __version__
from .._files import is_stdout, output_problem, write_report
from .text import summary
from .views import ResultView

__all__ = ["SCHEMA_VERSION", "SCHEMA_PATH", "schema", "to_json", "run_info", "dumps", "write_json", "output_refused",
           "emit_document"]

SCHEMA_VERSION = "1.3"
#: the libraries whose versions a report records (those that can change a verdict or its speed)
LIBRARIES = ("sympy", "mpmath", "numpy", "scipy", "python-flint", "gmpy2", "numba", "heyoka", "pylatexenc")
SCHEMA_PATH = Path(__file__).with_name("verify.schema.json")


def schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the report."""
    return json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))


def _plain(x: Any) -> Any:
    if isinstance(x, float) and not math.isfinite(x):
        return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    if x is None or isinstance(x, (str, bool, int, float)):
        return x
    return str(x)


def run_info() -> dict[str, Any]:
    """When and where a run happened: UTC date, Python, platform, machine, cores, library versions.

    Library versions are read from the installed distributions' metadata (nothing is imported);
    a library that is not installed is left out.

    >>> info = run_info()
    >>> sorted(info) == ["cpus", "date", "libraries", "machine", "platform", "python"]
    True
    """
    import datetime
    import os
    import platform
    from importlib import metadata

    libraries = {}
    for name in LIBRARIES:
        try:
            libraries[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            pass
    return {"date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "python": platform.python_version(), "platform": platform.platform(),
            "machine": platform.machine(), "cpus": os.cpu_count() or 1, "libraries": libraries}


def to_json(results: Sequence[ResultView], *, coverage: dict[str, Any] | None = None) -> dict[str, Any]:
    """The report as a JSON-ready dict; ``coverage`` (label -> claims or reason) is added when given."""
    doc = {"schema_version": SCHEMA_VERSION, "generator": f"symbt {__version__}", "run": run_info(),
           "claims": [r.to_dict() for r in results], "summary": summary(results)}
    if coverage is not None:
        doc["coverage"] = coverage
    return _plain(doc)


def dumps(results: Sequence[ResultView], *, coverage: dict[str, Any] | None = None) -> str:
    return json.dumps(to_json(results, coverage=coverage), indent=2, allow_nan=False) + "\n"


def write_json(results: Sequence[ResultView], path: str | os.PathLike[str], *,
               coverage: dict[str, Any] | None = None) -> None:
    """Write the report to ``path`` (see :func:`symbt._files.write_report`: ``-``, files, devices, links)."""
    write_report(path, dumps(results, coverage=coverage))


def output_refused(path: str | None, command: str, flag: str = "--json") -> bool:
    """True (after a one-line message on stderr) if a report cannot be written to ``path``.

    Called before any work, so that a bad path costs nothing.
    """
    problem = path and output_problem(path)
    if problem:
        print(f"{command}: {flag} {problem}", file=sys.stderr)
    return bool(problem)


def emit_document(doc: dict[str, Any], path: str | None, *, command: str, text: str | None = None) -> int:
    """Deliver a command's JSON document; the exit status (0, or 2 when ``path`` cannot be written).

    ``path == "-"`` (or a path that is stdout, see :func:`symbt._files.is_stdout`): the document
    goes to stdout instead of ``text``; otherwise ``text`` (unless
    ``None``) is printed and the document, if ``path`` is given, written with
    :func:`symbt._files.write_report` (a file atomically; a device, pipe or symlink through).
    """
    body = json.dumps(doc, indent=1) + "\n"
    if path and is_stdout(path):      # '-', or /dev/stdout into a pipe or a file: the document alone
        print(body, end="")
        return 0
    if text is not None:
        print(text)
    if path:
        try:
            sys.stdout.flush()              # the text first when the document goes to /dev/stdout too
            write_report(path, body)
        except OSError as exc:
            print(f"{command}: cannot write {path}: {exc.strerror or exc}", file=sys.stderr)
            return 2
    return 0
