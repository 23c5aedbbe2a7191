"""Which source tree ``symbt codegen`` acts on: the checkout the user stands in, not site-packages.

A *checkout* is a directory with a ``pyproject.toml`` whose ``[project] name`` is ``symbt``
and a ``symbt/`` package.  :func:`find_project` walks up from the working directory to the
first one.  If that checkout is not the package Python imported (e.g. after ``pip install .``
the import is site-packages), ``symbt codegen`` re-runs itself in a subprocess with the
checkout first on ``PYTHONPATH`` (:func:`run_in_checkout`), so that the derivation and the
hashes come from the checkout's own sources.

>>> import tempfile, pathlib
>>> d = pathlib.Path(tempfile.mkdtemp())
>>> find_project(d) is None
True
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from .._files import toml_loads
from .provenance import PACKAGE

__all__ = ["is_project", "find_project", "imported_package", "run_in_checkout", "DELEGATED_ENV"]

#: set in the environment of the re-run, so that it never delegates again
DELEGATED_ENV = "SYMBT_CODEGEN_DELEGATED"


def _project_name(pyproject: Path) -> str | None:
    try:
        text = pyproject.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    try:
        name = toml_loads(text).get("project", {}).get("name")
    except ValueError:      # tomllib.TOMLDecodeError
        return None
    return name if isinstance(name, str) else None


def is_project(root: Path) -> bool:
    """``root`` has a pyproject.toml naming the project ``symbt`` and a ``symbt/`` package."""
    root = Path(root)
    return ((root / "symbt" / "__init__.py").is_file() and (root / "pyproject.toml").is_file()
            and _project_name(root / "pyproject.toml") == "symbt")


def find_project(start: Path | None = None) -> Path | None:
    """The nearest checkout at or above ``start`` (default: the working directory), resolved."""
    here = Path.cwd() if start is None else Path(start)
    here = here.resolve()
    for d in (here, *here.parents):
        if is_project(d):
            return d
    return None


def imported_package() -> Path:
    """The ``symbt`` package directory Python imported (site-packages, an editable checkout, ...)."""
    return PACKAGE


def run_in_checkout(root: Path, argv: list[str]) -> int:
    """``python -m symbt codegen ARGV --project ROOT`` with ROOT first on PYTHONPATH; its exit code."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(root) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env[DELEGATED_ENV] = str(root)
    cmd = [sys.executable, "-m", "symbt", "codegen", *argv, "--project", str(root)]
    return subprocess.run(cmd, cwd=str(root), env=env).returncode
