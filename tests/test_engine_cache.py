"""The claim cache: any unreadable or wrongly shaped entry is recomputed; the warm path and its manifest."""
from __future__ import annotations

import json

import pytest

from symbt import engine
from symbt.claims import REGISTRY, load_all
from symbt.engine import cache, warm


@pytest.fixture(scope="module")
def tn2():
    load_all()
    return REGISTRY["tn2"]


GOOD = {"status": "verified", "method": "exact", "residual": 0.0, "evidence": "proof"}
BAD_ENTRIES = {
    "empty file": b"",
    "not utf-8": b"\xff\xfe\x00garbage",
    "truncated json": b'{"key": "',
    "a list": b"[]",
    "a number": b"42",
    "no outcome": None,                          # filled in with the right key below
    "outcome is a list": [],
    "outcome without method": {"status": "verified"},
    "unknown status": {**GOOD, "status": "bogus"},
    "residual as text": {**GOOD, "residual": "0"},
    "boolean residual": {**GOOD, "residual": True},
    "unknown evidence": {**GOOD, "evidence": "vibes"},
    "cells not a list": {**GOOD, "cells": {"a": 1}},
    "cells of numbers": {**GOOD, "cells": [1, 2]},
    "n_scope of text": {**GOOD, "n_scope": "two"},
    "counterexample a list": {**GOOD, "counterexample": [1]},
    "negative seconds": {**GOOD, "seconds": -1},
    "skipped status": {"status": "skipped", "method": "none"},
}


@pytest.mark.parametrize("case", list(BAD_ENTRIES))
def test_bad_entries_are_recomputed(tn2, case):
    f = cache.cache_file(tn2)
    f.parent.mkdir(parents=True, exist_ok=True)
    value = BAD_ENTRIES[case]
    if isinstance(value, bytes):
        f.write_bytes(value)
    else:
        entry = {"key": cache.claim_key(tn2), "id": tn2.id}
        if case != "no outcome":
            entry["outcome"] = value
        f.write_text(json.dumps(entry))
    assert cache.load_cached(tn2) is None
    out = engine.run([tn2])[0].outcome
    assert not out.cached and out.status == "verified"
    assert engine.run([tn2])[0].outcome.cached          # the recomputed entry is good again


def test_an_unreadable_entry_is_recomputed(tn2):
    f = cache.cache_file(tn2)
    f.mkdir(parents=True)                                # a directory where the file should be
    out = engine.run([tn2])[0].outcome
    assert not out.cached and out.status == "verified"


def test_a_well_formed_entry_with_missing_optional_fields_is_used(tn2):
    f = cache.cache_file(tn2)
    f.parent.mkdir(parents=True, exist_ok=True)
    f.write_text(json.dumps({"key": cache.claim_key(tn2), "outcome": {"status": "verified", "method": "exact"}}))
    out = engine.run([tn2])[0].outcome
    assert out.cached and out.evidence is None and out.cells == []


def test_library_versions_are_read_without_importing(monkeypatch):
    import sympy

    text = cache.library_versions()
    assert f"sympy{sympy.__version__}" in text and text.startswith("py3.")


def test_warm_results_come_from_the_manifest_and_entries(tn2):
    load_all()
    assert warm.cached_results(["tn2"]) is None          # nothing cached yet
    first = engine.run([tn2])[0]
    got = warm.cached_results(["tn2"])
    assert got is not None and got[0].claim.id == "tn2" and got[0].outcome.cached
    assert got[0].outcome.status == first.outcome.status and got[0].claim.statement == tn2.statement
    assert warm.cached_results(["tn2", "tra.n2"]) is None  # one missing entry: the normal path decides
    assert warm.cached_results(["no-such-name"]) is None
    cache.cache_file(tn2).write_text("{}")
    assert warm.cached_results(["tn2"]) is None          # a bad entry is never reported from


def test_manifest_holds_only_the_package_claims_and_is_stamped(tn2):
    from symbt.claims.base import SCENES, claim, scene

    scene("zz-warm", "temporary")
    extra = claim("zz.warm", equation="zz", scene="zz-warm", statement="s")(lambda: None)
    try:
        engine.run([tn2])
        data = json.loads(warm.manifest_path().read_text())
        ids = {c["id"] for c in data["claims"]}
        assert "tn2" in ids and "zz.warm" not in ids and "zz-warm" not in data["scenes"]
        assert ids == {c.id for c in REGISTRY.values() if c.id != "zz.warm"}
        assert data["digest"] == warm.source_digest()
    finally:
        REGISTRY.pop(extra.id)
        SCENES.pop("zz-warm")


def test_a_missing_optional_module_is_reported_skipped_by_the_warm_path(tn2, monkeypatch):
    engine.run([tn2])
    claims, scenes, keys = warm.read_manifest()
    monkeypatch.setattr(warm, "read_manifest", lambda project=None: (
        [c if c.id != "tn2" else type(c)(**{**{f: getattr(c, f) for f in c.__dataclass_fields__},
                                            "requires": ("no_such_module_zz",)}) for c in claims], scenes, keys))
    got = warm.cached_results(["tn2"])
    assert got[0].outcome.status == "skipped" and "no_such_module_zz" in got[0].outcome.detail


def test_verify_rejects_bad_jobs():
    import symbt

    for jobs in (0, -3, 1.5, True):
        with pytest.raises(ValueError, match="jobs"):
            symbt.verify(["tn2"], jobs=jobs)


@pytest.mark.parametrize("cid, helper_module", [
    ("paths.many_rows.n3", "symbt.claims.shipped_routes"),     # `from .shipped_routes import ...` inside the claim
    ("shipped.loop_xy.n5", "symbt.claims.shipped_emitted"),    # the same, in another function of the module
    ("library.fresh_toda2", "symbt.claims._shipped"),          # a helper bound at module level
])
def test_a_helper_module_imported_anywhere_keys_the_claim(monkeypatch, cid, helper_module):
    # the key covers the sibling modules a claim imports helpers from -- also inside a function, where the helper is
    # used: an edit there must not leave the cached outcome standing
    import inspect

    load_all()
    claim = REGISTRY[cid]
    assert helper_module in [m.__name__ for m in cache._claim_modules_used(inspect.getmodule(claim.func))]
    before = cache.claim_key(claim)
    real = inspect.getsource

    def edited(obj):
        text = real(obj)
        return text + "\n# an edit\n" if getattr(obj, "__name__", "") == helper_module else text
    monkeypatch.setattr(inspect, "getsource", edited)
    assert cache.claim_key(claim) != before
