"""``symbt verify --dask``: claims as Dask tasks on a local cluster of two processes; same report, same cache."""
from __future__ import annotations

import json

import pytest

from symbt import cli


def test_dask_local_cluster_gives_the_same_report_and_fills_the_cache(tmp_path):
    pytest.importorskip("distributed")
    ids = ["--scene", "tn2", "--scene", "dj", "--scene", "n3-hamiltonians.tra"]
    on_dask, local = tmp_path / "dask.json", tmp_path / "local.json"
    assert cli.main(["verify", "--dask", "-j", "2", *ids, "--json", str(on_dask), "-q"]) == 0
    doc = json.loads(on_dask.read_text())
    assert {c["id"]: (c["status"], c["cached"]) for c in doc["claims"]} == {
        "tn2": ("verified", False), "dj": ("verified", False), "n3-hamiltonians.tra": ("erratum", False)}
    erratum = next(c for c in doc["claims"] if c["id"] == "n3-hamiltonians.tra")
    assert erratum["counterexample"] and erratum["evidence"] == "proof"
    # every outcome computed on the cluster was cached here: a local run reads them all
    assert cli.main(["verify", *ids, "--json", str(local), "-q"]) == 0
    again = json.loads(local.read_text())
    assert all(c["cached"] for c in again["claims"])
    strip = lambda d: [{k: v for k, v in c.items() if k not in ("cached", "seconds")} for c in d["claims"]]
    assert strip(again) == strip(doc)
