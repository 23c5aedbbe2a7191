"""The on-disk cache of claim outcomes.

Results are cached as JSON (no pickle) in ``$SYMBT_CACHE_DIR`` (default
``$XDG_CACHE_HOME/symbt`` or ``~/.cache/symbt``), one file per claim, keyed by a
SHA-256 of the claim's id, the source of its module (and of the sibling claim
modules whose helpers it uses -- imported at module level or inside a function,
transitively), the sources of the layers below the claims, and
the versions of Python and of the libraries a result can depend on
(:func:`library_versions`, read from the installed distributions' metadata
without importing them).

An entry is used only if it parses, carries the current key and has the shape of
an :class:`~symbt.claims.Outcome` (:func:`outcome_from_json`); anything else --
missing, unreadable, corrupt, stale, or valid JSON of the wrong shape -- is
recomputed.

>>> outcome_from_json({"status": "verified", "method": "exact", "residual": 0.0}).status
'verified'
>>> outcome_from_json({"status": "verified", "method": "exact", "residual": "0"}) is None
True
"""
from __future__ import annotations

import hashlib
import json
import math
import os
import sys
from collections.abc import Callable
from dataclasses import replace
from functools import cache
from pathlib import Path
from types import ModuleType
from typing import Any

from .._files import atomic_write
from ..claims.base import STATUSES, Claim, Outcome
from ..proof.verdict import EVIDENCE

__all__ = ["cache_dir", "cache_file", "claim_key", "load_cached", "store", "library_versions",
           "outcome_from_json", "read_entry"]

_PKG = Path(__file__).resolve().parent.parent
#: the layers below the claims: a change to any of their sources invalidates every cached outcome
_LAYERS = ("paper.py", "_files.py", "symbolic", "proof", "numeric", "reference", "codegen", "generated",
           "claims/base.py")
#: distributions whose version can change a claim's outcome (absent ones count as "-")
_LIBRARIES = ("sympy", "mpmath", "numpy", "scipy", "python-flint", "gmpy2", "heyoka", "numba")


def cache_dir() -> Path:
    """``$SYMBT_CACHE_DIR``, else ``$XDG_CACHE_HOME/symbt``, else ``~/.cache/symbt``."""
    base = os.environ.get("SYMBT_CACHE_DIR")
    if base:
        return Path(base)
    xdg = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(xdg) / "symbt"


@cache
def _layer_digest(layers: tuple[str, ...] = _LAYERS) -> str:
    h = hashlib.sha256()
    for name in layers:
        path = _PKG / name
        files = sorted(path.rglob("*.py")) if path.is_dir() else [path]
        for f in files:
            if f.exists():
                h.update(str(f.relative_to(_PKG)).encode())
                h.update(f.read_bytes())
    return h.hexdigest()


def _norm(name: str) -> str:
    return name.lower().replace("-", "_").replace(".", "_")


def _dist_versions_on_path() -> dict[str, str]:
    """``{normalised name: version}`` from the ``*.dist-info`` / ``*.egg-info`` names on ``sys.path``.

    The first entry of ``sys.path`` that holds a distribution wins, as for imports;
    one directory listing per entry -- far cheaper than importing
    :mod:`importlib.metadata` (which also needs to scan) or the libraries themselves.
    """
    found: dict[str, str] = {}
    for entry in sys.path:
        try:
            names = os.listdir(entry or ".")
        except OSError:
            continue
        for n in names:
            for suffix in (".dist-info", ".egg-info"):
                if n.endswith(suffix):
                    stem = n[: -len(suffix)]
                    name, _, version = stem.partition("-")
                    if version:
                        found.setdefault(_norm(name), version.split("-py")[0])
    return found


@cache
def library_versions() -> str:
    """Python and library versions that key the cache, e.g. ``"py3.11.7 sympy1.14.0 ... gmpy2-"``.

    Read from distribution metadata on ``sys.path``, never by importing a library
    (a warm ``symbt verify`` must not import SymPy, NumPy or mpmath).

    >>> library_versions().startswith("py")
    True
    """
    on_path = _dist_versions_on_path()
    parts = [f"py{'.'.join(map(str, sys.version_info[:3]))}"]
    for lib in _LIBRARIES:
        v = on_path.get(_norm(lib))
        if v is None:  # unusual layouts: ask importlib.metadata (still no import of the library)
            try:
                from importlib import metadata

                v = metadata.version(lib)
            except Exception:
                v = "-"
        parts.append(f"{lib}{v}")
    return " ".join(parts)


@cache
def _sibling_imports(name: str) -> frozenset[str]:
    """The claim modules ``symbt.claims.<name>``'s source imports from, at module level or inside a function (a
    helper imported where it is used): ``from .x import``, ``from . import x``, ``from symbt.claims.x import``."""
    import ast
    import importlib
    import inspect

    try:
        tree = ast.parse(inspect.getsource(importlib.import_module(name)))
    except (ImportError, OSError, SyntaxError, TypeError):
        return frozenset()
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level == 1:
                out |= {module.split(".")[0]} if module else {a.name for a in node.names}
            elif node.level == 0 and module.startswith("symbt.claims."):
                out.add(module.split(".")[2])
    return frozenset(f"symbt.claims.{x}" for x in out)


def _claim_modules_used(mod: ModuleType) -> list[ModuleType]:
    """The claim's module and the sibling claim modules whose helpers it uses: the objects bound at its module
    level and the modules it imports from anywhere in its source (helpers imported inside a function too),
    transitively -- a cached outcome is reused only if none of their sources changed."""
    import importlib

    used: dict[str, ModuleType | None] = {}
    todo = [mod.__name__]
    while todo:
        name = todo.pop()
        if name in used:
            continue
        m = mod if name == mod.__name__ else sys.modules.get(name)
        if m is None:
            try:
                m = importlib.import_module(name)
            except ImportError:
                m = None
        used[name] = m
        if m is None:
            continue
        for obj in vars(m).values():
            owner = getattr(obj, "__module__", None)
            if isinstance(owner, str) and owner.startswith("symbt.claims.") and owner not in used:
                todo.append(owner)
        todo.extend(sibling for sibling in _sibling_imports(name) if sibling not in used)
    return [m for k in sorted(used) if (m := used[k]) is not None]


def claim_key(c: Claim, deep: bool = False) -> str:
    """Hash of what determines the claim's outcome (its deep variant has its own key).

    For the package's own claims: the claim's module and the sibling claim modules it uses,
    and the layers below the claims.  For any other claim (a user's): every Python file of the
    user's project the claim may depend on (:func:`~symbt.engine.project.project_digest`: the
    project root's files when the claim's module lies under it) and every source of symbt's
    layers up to the claims.  Both: Python and library versions.
    """
    import inspect

    from .project import active, claim_module, project_digest

    h = hashlib.sha256()
    h.update(c.id.encode())
    if deep and c.deep_check is not None:
        h.update(b"\0deep")
    module = claim_module(c)
    if module.startswith("symbt.claims."):
        mod = inspect.getmodule(c.func or c.check)
        for m in _claim_modules_used(mod) if mod is not None else []:
            try:
                h.update(inspect.getsource(m).encode())
            except (OSError, TypeError):
                h.update(repr(c).encode())
        if mod is None:
            h.update(repr(c).encode())
        h.update(_layer_digest().encode())
    else:
        project = active()
        root = project.root if project is not None else Path.cwd()
        h.update(b"\0user\0" + module.encode())
        h.update(project_digest([module], root).encode())
        h.update(_layer_digest(_LAYERS + ("claims", "engine/project.py", "engine/emitted_claims.py")).encode())
    h.update(library_versions().encode())
    return h.hexdigest()


def cache_file(c: Claim | str, deep: bool = False) -> Path:
    """The cache entry of a claim (or claim id); ``deep`` names the entry of its deep variant."""
    cid = c if isinstance(c, str) else c.id
    safe = "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in cid)
    has_deep = deep and (isinstance(c, str) or c.deep_check is not None)
    return cache_dir() / f"{safe}{'.deep' if has_deep else ''}.json"


# --------------------------------------------------------------------------- shape of an entry

def _number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _opt(test: Callable[[Any], bool]) -> Callable[[Any], bool]:
    return lambda v: v is None or test(v)


_FIELD_OK = {
    "status": lambda v: v in STATUSES,
    "method": lambda v: isinstance(v, str),
    "residual": _opt(_number),
    "digits": _opt(_number),
    "printed": _opt(lambda v: isinstance(v, str)),
    "corrected": _opt(lambda v: isinstance(v, str)),
    "counterexample": _opt(lambda v: isinstance(v, dict)),
    "detail": lambda v: isinstance(v, str),
    "seconds": lambda v: _number(v) and v >= 0,
    "cached": lambda v: isinstance(v, bool),
    "evidence": lambda v: v is None or v in EVIDENCE,
    "cells": lambda v: isinstance(v, list) and all(isinstance(x, dict) for x in v),
    "scope": lambda v: isinstance(v, str),
    "n_scope": _opt(lambda v: v == "all" or (isinstance(v, list) and all(isinstance(n, int) for n in v))),
}


def outcome_from_json(d: Any) -> Outcome | None:
    """An :class:`Outcome` from its JSON form, or ``None`` if ``d`` does not have its shape.

    ``status`` and ``method`` are required; every other field may be missing (its
    default is used) but, if present, must have the right type.  Unknown keys are ignored.
    """
    if not isinstance(d, dict) or "status" not in d or "method" not in d:
        return None
    for k, ok in _FIELD_OK.items():
        if k in d and not ok(d[k]):
            return None
    try:
        return Outcome.from_dict(d)
    except (TypeError, ValueError):
        return None


def read_entry(path: Path, key: str) -> Outcome | None:
    """The outcome stored at ``path`` if the entry is well formed and carries ``key``."""
    try:
        data = json.loads(path.read_bytes())
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("key") != key:
        return None
    out = outcome_from_json(data.get("outcome"))
    if out is None or out.status in ("skipped", "todo"):
        return None
    if out.status == "verified" and isinstance(out.residual, float) and math.isnan(out.residual):
        return None  # a verification with a NaN residual is no verification: recompute
    out = replace(out, cached=True)
    return out


def load_cached(c: Claim, deep: bool = False) -> Outcome | None:
    """The cached outcome of ``c`` or ``None`` (missing, corrupt, stale or of the wrong shape)."""
    return read_entry(cache_file(c, deep), claim_key(c, deep))


def store(c: Claim, out: Outcome, deep: bool = False) -> None:
    """Cache ``out`` at once (atomically); skipped and todo outcomes are not cached.

    A read-only cache is no error: the run goes on and says so once on stderr
    (``symbt: cache directory X is not writable; results are not cached``).
    """
    if out.status in ("skipped", "todo"):
        return  # a skipped claim may run once its extra is installed; a todo stub once its check is written
    try:
        cache_dir().mkdir(parents=True, exist_ok=True)
        d = out.to_dict()
        d["cached"] = False
        text = json.dumps({"key": claim_key(c, deep), "id": c.id, "outcome": d}, indent=1, default=str)
    except OSError:
        _say_not_writable()
        return
    except ValueError:
        return
    try:
        atomic_write(cache_file(c, deep), text)
    except OSError:
        _say_not_writable()


_told: set[str] = set()


def _say_not_writable() -> None:
    """Say once per process and directory that outcomes are not cached: the run goes on, only slower next time."""
    where = str(cache_dir())
    if where not in _told:
        _told.add(where)
        print(f"symbt: cache directory {where} is not writable; results are not cached", file=sys.stderr, flush=True)
