"""Processes, cache and codegen at the edges (issue 26, item 4): -j bounded, read-only cache said, no false 'wrote'."""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from symbt import engine
from symbt.claims import Outcome
from symbt.engine import cache, runner

ROOT = Path(__file__).resolve().parents[1]


def _run(argv, **env) -> subprocess.CompletedProcess:
    e = dict(os.environ, **env)
    e["PYTHONPATH"] = os.pathsep.join([str(ROOT), e.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    return subprocess.run([sys.executable, "-m", "symbt", *argv], capture_output=True, text=True, env=e, cwd=ROOT,
                          timeout=300)


def test_jobs_are_bounded_by_the_machine(monkeypatch):
    sizes = []
    from symbt.engine import workers

    real = workers.Workers

    class Recording(real):
        def __init__(self, claims, size=1):
            sizes.append(size)
            super().__init__(claims, size=size)

    monkeypatch.setattr(workers, "Workers", Recording)   # the runner imports it when something runs
    monkeypatch.setattr(runner.os, "cpu_count", lambda: 2)
    claims = engine.select(["toy"])
    assert len(claims) > 2                       # more claims than cores: the cap, not the claim count, binds
    results = engine.run(claims, use_cache=False, jobs=1000)
    assert sizes and max(sizes) == 2
    assert {r.outcome.status for r in results} == {"verified"}


def test_read_only_cache_is_said_once_and_the_run_goes_on(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("")                       # a cache dir below a regular file: unwritable, even for root
    where = blocker / "cache"
    r = _run(["verify", "--scene", "toy", "-q", "--no-cache"], SYMBT_CACHE_DIR=str(where))
    assert r.returncode == 0, r.stderr
    line = f"symbt: cache directory {where} is not writable; results are not cached"
    assert r.stderr.count(line) == 1, r.stderr


def test_a_hand_edited_nan_residual_on_a_verified_claim_is_recomputed(monkeypatch, tmp_path):
    monkeypatch.setenv("SYMBT_CACHE_DIR", str(tmp_path))
    c = engine.select(["toy"])[0]
    cache.store(c, Outcome("verified", "exact", residual=0.0, evidence="proof"))
    assert cache.load_cached(c).status == "verified"
    path = cache.cache_file(c)
    entry = json.loads(path.read_text())
    entry["outcome"]["residual"] = math.nan
    path.write_text(json.dumps(entry))            # json writes NaN, as a corrupted run might
    assert cache.load_cached(c) is None


def test_codegen_does_not_say_wrote_for_unchanged_files(tmp_path):
    out = tmp_path / "gen"
    first = _run(["codegen", "--n", "2", "--out", str(out)])
    assert first.returncode == 0, first.stderr
    assert first.stdout.count("wrote ") == 2      # __init__.py and toda2.py
    stamp = {p.name: p.stat().st_mtime_ns for p in out.iterdir()}
    second = _run(["codegen", "--n", "2", "--out", str(out)])
    assert second.returncode == 0, second.stderr
    assert "wrote" not in second.stdout and "2 file(s) already up to date" in second.stdout
    assert {p.name: p.stat().st_mtime_ns for p in out.iterdir()} == stamp


@pytest.mark.parametrize("out", ["/proc/symbt-generated", "{tmp}/a-file/gen"])
def test_codegen_into_an_unwritable_directory_exits_2(tmp_path, out):
    (tmp_path / "a-file").write_text("")
    r = _run(["codegen", "--n", "2", "--out", out.format(tmp=tmp_path)])
    assert r.returncode == 2
    assert "wrote" not in r.stdout and r.stderr.count("\n") == 1 and "Traceback" not in r.stderr, r.stderr
    assert r.stderr.startswith("symbt codegen: error: cannot write")
