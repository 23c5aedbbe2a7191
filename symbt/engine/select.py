"""Choosing claims: scenes, lattice sizes (``n2``, ``n3``, ...) and claim ids."""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from ..claims.base import Claim
from .project import Project, load

__all__ = ["select", "choose", "default_scenes"]


def default_scenes(project: Project | None = None) -> list[str]:
    """The scenes ``symbt verify`` runs without ``--scene`` (every scene of the project not marked deep)."""
    from ..claims import SCENES

    scenes = {c.scene for c in load(project)}
    return [s for s, meta in SCENES.items() if s in scenes and not meta.get("deep")]


def choose(claims: Sequence[Claim], scenes_meta: Mapping[str, Mapping[str, Any]],
           names: Sequence[str] | None = None, *, include_deep: bool = False,
           labels: Sequence[str] = ()) -> list[Claim]:
    """The claims named by ``names`` among ``claims`` (in their order), given the scenes' metadata.

    ``labels`` keeps only the claims of those paper labels (``equation`` or ``source_equation``),
    deep ones included.  Works on claim metadata only, so the warm path (:mod:`.warm`) and
    :func:`select` share it.  Unknown names and labels raise ``KeyError``.

    >>> a = Claim("a.n2", "eq", "s", check=None, scene="x", N=2)
    >>> b = Claim("b", "eq", "s", check=None, scene="y", deep=True)
    >>> [c.id for c in choose([a, b], {"x": {}, "y": {}})], [c.id for c in choose([a, b], {}, ["b"])]
    (['a.n2'], ['b'])
    """
    if labels:
        wanted = set(labels)
        unknown = wanted - {c.equation for c in claims} - {c.source_equation for c in claims}
        if unknown:
            raise KeyError(f"no claim has the label(s) {', '.join(sorted(unknown))}; try 'symbt coverage'")
        claims = [c for c in claims if c.equation in wanted or c.source_equation in wanted]
        if not names:
            return list(claims)
    by_id = {c.id: c for c in claims}
    if not names:
        return [c for c in claims if include_deep or not (c.deep or scenes_meta.get(c.scene, {}).get("deep"))]
    chosen: dict[str, Claim] = {}
    scenes_here = {c.scene for c in claims}
    for name in names:
        if name in scenes_meta and name in scenes_here:
            hit = [c for c in claims if c.scene == name]
        elif len(name) > 1 and name[0] == "n" and name[1:].isdigit():
            hit = [c for c in claims if c.N == int(name[1:])]
        elif name in by_id:
            hit = [by_id[name]]
        else:
            raise KeyError(f"unknown scene or claim {name!r}; try 'symbt scenes'")
        if name not in by_id and not include_deep and not scenes_meta.get(name, {}).get("deep"):
            hit = [c for c in hit if not c.deep]
        for c in hit:
            chosen.setdefault(c.id, c)
    return [c for c in claims if c.id in chosen]


def select(scenes: Sequence[str] | None = None, *, include_deep: bool = False, project: Project | None = None,
           labels: Sequence[str] = ()) -> list[Claim]:
    """The project's claims named by ``scenes`` (scene names, ``nK`` sizes or claim ids), in registry order.

    ``None`` means every non-deep scene (and non-deep claim); ``include_deep`` adds deep
    claims; ``labels`` keeps the claims of those paper labels.  ``project`` (default:
    :func:`~symbt.engine.project.discover` from the working directory) says which claims
    there are; a name it lacks is looked up among every claim registered in this process
    (one a notebook or a test declared).  Unknown names raise ``KeyError``; a claims source that does not import,
    :class:`~symbt.engine.project.ConfigError`.
    """
    from ..claims import REGISTRY, SCENES

    try:
        return choose(load(project), SCENES, scenes, include_deep=include_deep, labels=labels)
    except KeyError:
        if not scenes:
            raise
        # a name the project lacks may be a claim registered in this process by other means (a test, a notebook)
        return choose(list(REGISTRY.values()), SCENES, scenes, include_deep=include_deep, labels=labels)
