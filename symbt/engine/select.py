"""Choosing claims: scenes, lattice sizes (``n2``, ``n3``, ...) and claim ids."""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from ..claims.base import Claim

__all__ = ["select", "choose", "default_scenes"]


def default_scenes() -> list[str]:
    """The scenes ``symbt verify`` runs without ``--scene`` (every scene not marked deep)."""
    from ..claims import SCENES, load_all

    load_all()
    return [s for s, meta in SCENES.items() if not meta.get("deep")]


def choose(claims: Sequence[Claim], scenes_meta: Mapping[str, Mapping[str, Any]],
           names: Sequence[str] | None = None, *, include_deep: bool = False) -> list[Claim]:
    """The claims named by ``names`` among ``claims`` (in their order), given the scenes' metadata.

    Works on claim metadata only, so the warm path (:mod:`.warm`) and :func:`select`
    share it.  Unknown names raise ``KeyError``.

    >>> a = Claim("a.n2", "eq", "s", check=None, scene="x", N=2)
    >>> b = Claim("b", "eq", "s", check=None, scene="y", deep=True)
    >>> [c.id for c in choose([a, b], {"x": {}, "y": {}})], [c.id for c in choose([a, b], {}, ["b"])]
    (['a.n2'], ['b'])
    """
    by_id = {c.id: c for c in claims}
    if not names:
        return [c for c in claims if include_deep or not (c.deep or scenes_meta.get(c.scene, {}).get("deep"))]
    chosen: dict[str, Claim] = {}
    for name in names:
        if name in scenes_meta:
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


def select(scenes: Sequence[str] | None = None, *, include_deep: bool = False) -> list[Claim]:
    """Claims named by ``scenes`` (scene names, ``nK`` sizes or claim ids), in registry order.

    ``None`` means every non-deep scene (and non-deep claim); ``include_deep``
    adds deep claims.  Unknown names raise ``KeyError``.
    """
    from ..claims import REGISTRY, SCENES, load_all

    load_all()
    return choose(list(REGISTRY.values()), SCENES, scenes, include_deep=include_deep)
