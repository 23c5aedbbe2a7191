"""The warm path: report cached outcomes without importing the claims (no SymPy, NumPy, mpmath).

After every run the engine writes a *manifest* into the cache directory: the
claims' metadata (id, equation, statement, scene, N, ...; scenes and their
descriptions) and each claim's cache key, stamped with a digest of the bytes of
every source file of the package and the library versions
(:func:`~symbt.engine.cache.library_versions`, read from metadata).  A later run
hashes the sources again -- bytes only, nothing is imported -- and, if the
manifest's stamp matches and every selected claim has a cache entry with the
manifest's key, reports from those entries.  Anything else (a changed source
file, a missing or stale entry, a claim that was skipped) returns ``None`` and
the caller takes the normal path, which recomputes only what changed and writes
a fresh manifest.

A claim whose optional ``requires`` module is missing (checked with
:func:`importlib.util.find_spec`, which imports nothing) is reported
``skipped`` exactly as :meth:`Claim.run <symbt.claims.Claim.run>` would.
"""
from __future__ import annotations

import hashlib
import importlib.util
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .._files import atomic_write
from ..claims.base import Claim, ClaimResult, skipped
from .cache import cache_dir, cache_file, library_versions, read_entry
from .project import Project, discover, emitted_digest
from .select import choose

__all__ = ["source_digest", "manifest_path", "write_manifest", "read_manifest", "cached_results",
           "scene_listing"]

FORMAT = 1
_PKG = Path(__file__).resolve().parent.parent
_META = ("id", "equation", "statement", "scene", "N", "where", "deep", "requires", "source_equation", "uses")


def source_digest() -> str:
    """SHA-256 of the package's source files (paths and bytes), the library versions and the format."""
    h = hashlib.sha256(f"symbt-manifest-{FORMAT}\0{library_versions()}\0".encode())
    for f in sorted(_PKG.rglob("*.py")):
        if "__pycache__" in f.parts:
            continue
        h.update(f.relative_to(_PKG).as_posix().encode() + b"\0")
        h.update(f.read_bytes())
    return h.hexdigest()


def manifest_path(project: Project | None = None) -> Path:
    """The manifest of ``project``'s claim set (Zullo's paper: ``manifest.json``)."""
    label = project.label() if project is not None else ""
    return cache_dir() / (f"manifest-{label}.json" if label else "manifest.json")


def _roots_digest(roots: list[str]) -> str:
    from .project import _digest_of

    h = hashlib.sha256()
    for r in roots:
        h.update(r.encode() + b"\0" + _digest_of(Path(r)).encode())
    return h.hexdigest()


def write_manifest(project: Project | None = None) -> None:
    """Record every claim of ``project`` (default: the one loaded last) with its key."""
    from ..claims import SCENES
    from .cache import claim_key
    from .project import active, claim_module, load, source_root

    project = project or active() or discover()
    claims = load(project)
    roots = sorted({str(source_root(Path(f), project.root)) for c in claims
                    if not claim_module(c).startswith("symbt.claims.")
                    and (f := getattr(sys.modules.get(claim_module(c)), "__file__", None))})
    data = {"format": FORMAT, "digest": source_digest(), "roots": roots, "roots_digest": _roots_digest(roots),
            "emitted": emitted_digest(project),
            "claims": [{**{k: (list(getattr(c, k)) if k in ("requires", "uses") else getattr(c, k)) for k in _META},
                        "key": claim_key(c)} for c in claims],
            "scenes": {s: {"description": m.get("description", ""), "deep": bool(m.get("deep"))}
                       for s, m in SCENES.items() if any(c.scene == s for c in claims)}}
    text = json.dumps(data, indent=0, sort_keys=True)
    path = manifest_path(project)
    try:
        if path.is_file() and path.read_text(encoding="utf-8") == text:
            return
        cache_dir().mkdir(parents=True, exist_ok=True)
        atomic_write(path, text)
    except OSError:
        pass  # a read-only cache is no error


def _not_loaded() -> Any:  # pragma: no cover - a warm claim is never run
    raise RuntimeError("claim metadata from the manifest; load the claims to run it")


def read_manifest(project: Project | None = None
                  ) -> tuple[list[Claim], dict[str, dict[str, Any]], dict[str, str]] | None:
    """``(claims, scenes, keys)`` from ``project``'s manifest if it matches the current sources, else ``None``.

    The current sources: symbt's, and every file under the roots the user's claims may depend on.
    """
    try:
        data = json.loads(manifest_path(project).read_bytes())
        if not isinstance(data, dict) or data.get("format") != FORMAT or data.get("digest") != source_digest():
            return None
        roots = data["roots"]
        if not isinstance(roots, list) or data.get("roots_digest") != _roots_digest([str(r) for r in roots]):
            return None
        if data.get("emitted", "") != emitted_digest(project or discover()):   # an emitted file changed
            return None
        claims, keys = [], {}
        for d in data["claims"]:
            meta = {k: d[k] for k in _META}
            meta["requires"], meta["uses"] = tuple(meta["requires"]), tuple(meta["uses"])
            claims.append(Claim(check=_not_loaded, **meta))
            keys[d["id"]] = str(d["key"])
        scenes = {str(k): dict(v) for k, v in data["scenes"].items()}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None
    return claims, scenes, keys


def cached_results(names: Sequence[str] | None = None, *, deep: bool = False, project: Project | None = None,
                   labels: Sequence[str] = ()) -> list[ClaimResult] | None:
    """Every selected claim's result from the cache, or ``None`` if any is missing or stale.

    ``None`` also for a name the manifest does not know (the caller's normal path
    decides: a claim registered outside the package, or an unknown name).
    """
    if deep:
        return None  # the manifest records the default outcomes' keys; deep runs take the normal path
    m = read_manifest(project or discover())
    if m is None:
        return None
    claims, scenes, keys = m
    try:
        chosen = choose(claims, scenes, names, include_deep=deep, labels=labels)
    except KeyError:
        return None
    if not chosen:
        return None
    out = []
    for c in chosen:
        if any("." in r for r in c.requires):
            return None  # find_spec of a submodule would import its parent
        missing = [r for r in c.requires if importlib.util.find_spec(r) is None]
        o = (skipped(f"optional dependency missing: {', '.join(missing)}") if missing
             else read_entry(cache_file(c), keys[c.id]))
        if o is None:
            return None
        out.append(ClaimResult(c, o))
    return out


def scene_listing(project: Project | None = None) -> tuple[list[Claim], dict[str, dict[str, Any]]]:
    """The project's claims and scenes from the manifest if current, else by loading the claims."""
    project = project or discover()
    m = read_manifest(project)
    if m is not None:
        return m[0], m[1]
    from ..claims import SCENES
    from .project import load

    claims = load(project)
    return claims, {s: meta for s, meta in SCENES.items() if any(c.scene == s for c in claims)}
