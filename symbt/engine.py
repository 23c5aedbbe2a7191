"""Running claims: scene selection, on-disk cache, parallel execution.

* A *scene* is a named group of claims (``symbt scenes`` lists them).  Running
  a scene runs only its claims; derivations are built lazily and memoised
  per lattice size (:func:`symbt.symbolic.toda.toda_model`), so an N=2 scene
  never builds an N=3 model, and a symbolic scene never imports scipy.
  Pseudo-scenes ``n2``, ``n3``, ``n4`` select claims by lattice size, and a
  claim id selects itself.
* Results are cached as JSON (no pickle) in ``$SYMBT_CACHE_DIR`` (default
  ``~/.cache/symbt``), one file per claim, keyed by a SHA-256 of the claim's
  id, the source of its module and of the layers below it (``symbt.proof``,
  ``symbt.symbolic``, ``symbt.literal``, ``symbt.numeric``, ``symbt.codegen``, ``symbt.generated``, the
  claims' base and sample modules)
  and the versions of Python, SymPy, mpmath and NumPy.  A corrupt or stale
  entry is recomputed; ``use_cache=False`` forces recomputation.
* Independent claims run in a process pool (``jobs`` workers).
"""
from __future__ import annotations

import hashlib
import inspect
import json
import os
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor
from functools import lru_cache
from pathlib import Path

from .claims import REGISTRY, SCENES, load_all
from .claims.base import Claim, ClaimResult, Outcome

__all__ = ["select", "run", "ClaimResult", "cache_dir", "claim_key", "default_scenes"]

_PKG = Path(__file__).resolve().parent
_LAYERS = ("proof.py", "literal.py", "flows.py", "elliptic.py", "symbolic", "numeric", "codegen", "generated",
           "claims/base.py",
           "claims/samples.py")


def cache_dir() -> Path:
    base = os.environ.get("SYMBT_CACHE_DIR")
    if base:
        return Path(base)
    xdg = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(xdg) / "symbt"


@lru_cache(maxsize=None)
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


@lru_cache(maxsize=None)
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
    mod = inspect.getmodule(c.check)
    for m in _claim_modules_used(mod):
        try:
            h.update(inspect.getsource(m).encode())
        except (OSError, TypeError):
            h.update(repr(c).encode())
    h.update(_layer_digest().encode())
    h.update(_versions().encode())
    return h.hexdigest()


def _cache_file(c: Claim) -> Path:
    safe = "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in c.id)
    return cache_dir() / f"{safe}.json"


def _load_cached(c: Claim) -> Outcome | None:
    f = _cache_file(c)
    try:
        data = json.loads(f.read_text())
        if data.get("key") != claim_key(c):
            return None
        out = Outcome.from_dict(data["outcome"])
        out.cached = True
        return out
    except (OSError, ValueError, KeyError, TypeError):
        return None  # missing, corrupt or stale: recompute


def _store(c: Claim, out: Outcome) -> None:
    if out.status == "skipped":
        return  # a skipped claim may run once its extra is installed
    d = cache_dir()
    try:
        d.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp-", suffix=".json")
        with os.fdopen(fd, "w") as fh:
            json.dump({"key": claim_key(c), "id": c.id, "outcome": out.to_dict()}, fh, indent=1)
        os.replace(tmp, _cache_file(c))
    except OSError:
        pass  # a read-only cache is not an error


def default_scenes() -> list[str]:
    load_all()
    return [s for s, meta in SCENES.items() if not meta.get("deep")]


def select(scenes: list[str] | None = None, *, include_deep: bool = False) -> list[Claim]:
    """Claims named by ``scenes`` (scene names, ``nK`` sizes or claim ids), in registry order.

    ``None`` means every non-deep scene (and non-deep claim); ``include_deep``
    adds deep claims.  Unknown names raise ``KeyError``.
    """
    load_all()
    claims = list(REGISTRY.values())
    if not scenes:
        return [c for c in claims if include_deep or not (c.deep or SCENES.get(c.scene, {}).get("deep"))]
    chosen: list[Claim] = []
    for name in scenes:
        if name in SCENES:
            hit = [c for c in claims if c.scene == name]
        elif len(name) > 1 and name[0] == "n" and name[1:].isdigit():
            hit = [c for c in claims if c.N == int(name[1:])]
        elif name in REGISTRY:
            hit = [REGISTRY[name]]
        else:
            raise KeyError(f"unknown scene or claim {name!r}; try 'symbt scenes'")
        if name not in REGISTRY and not include_deep and not SCENES.get(name, {}).get("deep"):
            hit = [c for c in hit if not c.deep]
        for c in hit:
            if c not in chosen:
                chosen.append(c)
    order = {c.id: i for i, c in enumerate(claims)}
    return sorted(chosen, key=lambda c: order[c.id])


def _run_one(claim_id: str) -> dict:
    load_all()
    return REGISTRY[claim_id].run().to_dict()


def run(claims: list[Claim], *, use_cache: bool = True, jobs: int = 1, progress=None) -> list[ClaimResult]:
    """Run ``claims`` (cached results reused), optionally in ``jobs`` processes."""
    results: dict[str, Outcome] = {}
    todo = []
    for c in claims:
        out = _load_cached(c) if use_cache else None
        if out is not None:
            results[c.id] = out
            if progress:
                progress(c, out)
        else:
            todo.append(c)
    if jobs > 1 and len(todo) > 1:
        import multiprocessing as mp_

        ctx = mp_.get_context("fork") if sys.platform != "win32" else None
        with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
            # longest-first keeps both workers busy; N=3 derivations dominate
            ordered = sorted(todo, key=lambda c: -(c.N or 0))
            futs = {c.id: pool.submit(_run_one, c.id) for c in ordered}
            for c in ordered:
                out = Outcome.from_dict(futs[c.id].result())
                results[c.id] = out
                _store(c, out)
                if progress:
                    progress(c, out)
    else:
        for c in todo:
            out = c.run()
            results[c.id] = out
            _store(c, out)
            if progress:
                progress(c, out)
    return [ClaimResult(c, results[c.id]) for c in claims]
