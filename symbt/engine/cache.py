"""The on-disk cache of claim outcomes.

Results are cached as JSON (no pickle) in ``$SYMBT_CACHE_DIR`` (default
``~/.cache/symbt``), one file per claim, keyed by a SHA-256 of the claim's id,
the source of its module (and of the sibling claim modules whose helpers it
uses), the sources of the layers below the claims, and the versions of Python,
SymPy, mpmath and NumPy.  A corrupt or stale entry is recomputed.
"""
from __future__ import annotations

import hashlib
import inspect
import json
import os
import sys
from functools import cache
from pathlib import Path

from .._files import atomic_write
from ..claims.base import Claim, Outcome

__all__ = ["cache_dir", "cache_file", "claim_key", "load_cached", "store"]

_PKG = Path(__file__).resolve().parent.parent
#: the layers below the claims: a change to any of their sources invalidates every cached outcome
_LAYERS = ("paper.py", "_files.py", "symbolic", "proof", "numeric", "reference", "codegen", "generated",
           "claims/base.py")


def cache_dir() -> Path:
    base = os.environ.get("SYMBT_CACHE_DIR")
    if base:
        return Path(base)
    xdg = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(xdg) / "symbt"


@cache
def _layer_digest() -> str:
    h = hashlib.sha256()
    for name in _LAYERS:
        path = _PKG / name
        files = sorted(path.rglob("*.py")) if path.is_dir() else [path]
        for f in files:
            if f.exists():
                h.update(str(f.relative_to(_PKG)).encode())
                h.update(f.read_bytes())
    return h.hexdigest()


@cache
def _versions() -> str:
    import mpmath
    import numpy
    import sympy

    return f"py{sys.version_info[:3]} sympy{sympy.__version__} mpmath{mpmath.__version__} numpy{numpy.__version__}"


def _claim_modules_used(mod) -> list:
    """The claim's module and the sibling claim modules whose helpers it imports."""
    used = {mod.__name__: mod}
    for obj in vars(mod).values():
        name = getattr(obj, "__module__", None)
        if isinstance(name, str) and name.startswith("symbt.claims.") and name not in used:
            used[name] = sys.modules.get(name)
    return [used[k] for k in sorted(used) if used[k] is not None]


def claim_key(c: Claim) -> str:
    """Hash of what determines the claim's outcome."""
    h = hashlib.sha256()
    h.update(c.id.encode())
    mod = inspect.getmodule(c.func or c.check)
    for m in _claim_modules_used(mod):
        try:
            h.update(inspect.getsource(m).encode())
        except (OSError, TypeError):
            h.update(repr(c).encode())
    h.update(_layer_digest().encode())
    h.update(_versions().encode())
    return h.hexdigest()


def cache_file(c: Claim) -> Path:
    safe = "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in c.id)
    return cache_dir() / f"{safe}.json"


def load_cached(c: Claim) -> Outcome | None:
    f = cache_file(c)
    try:
        data = json.loads(f.read_text())
        if data.get("key") != claim_key(c):
            return None
        out = Outcome.from_dict(data["outcome"])
        out.cached = True
        return out
    except (OSError, ValueError, KeyError, TypeError):
        return None  # missing, corrupt or stale: recompute


def store(c: Claim, out: Outcome) -> None:
    if out.status == "skipped":
        return  # a skipped claim may run once its extra is installed
    d = cache_dir()
    try:
        d.mkdir(parents=True, exist_ok=True)
        atomic_write(cache_file(c), json.dumps({"key": claim_key(c), "id": c.id, "outcome": out.to_dict()},
                                                indent=1))
    except OSError:
        pass  # a read-only cache is not an error
