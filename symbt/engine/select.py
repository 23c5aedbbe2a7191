"""Choosing claims: scenes, lattice sizes (``n2``, ``n3``, ...) and claim ids."""
from __future__ import annotations

from ..claims import REGISTRY, SCENES, load_all
from ..claims.base import Claim

__all__ = ["select", "default_scenes"]


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
