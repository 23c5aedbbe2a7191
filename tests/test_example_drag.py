"""The example project ``examples/drag`` (a user's own note), run end to end from its own directory.

Each test works on a copy of the project in a temporary directory, with its own claim cache, and runs
the front ends in a subprocess as a user would (``python -m symbt ...`` from the project's root, which
finds ``[tool.symbt]`` in its ``pyproject.toml``).
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "drag"

EMITTED = {"emit.drag_numeric.velocity.numpy": "verified", "emit.drag_numeric.velocity.mpmath": "verified",
           # the C claim compiles the committed generated/drag_numeric.c; without a compiler it is skipped
           "emit.drag_numeric.velocity.c": "verified" if shutil.which("cc") or shutil.which("gcc")
           or shutil.which("clang") else "skipped"}
EXPECTED = {"drag.vT": "verified", "drag.v": "verified", "drag.x": "verified", "drag.v2x": "verified",
            "drag.t99": "erratum", "drag.v0": "erratum", **EMITTED}


@pytest.fixture
def project(tmp_path: Path) -> Path:
    dest = tmp_path / "drag"
    shutil.copytree(EXAMPLE, dest, ignore=shutil.ignore_patterns("__pycache__", ".symbt-cache", "*.ipynb"))
    return dest


def run(project: Path, *argv: str, cache: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, SYMBT_CACHE_DIR=str(cache),
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep))
    return subprocess.run([sys.executable, *argv], cwd=project, env=env, capture_output=True, text=True,
                          timeout=300)


def verify(project: Path, cache: Path) -> tuple[int, dict[str, dict]]:
    p = run(project, "-m", "symbt", "verify", "-q", "--json", "-", cache=cache)
    assert p.returncode in (0, 1), p.stderr
    return p.returncode, {c["id"]: c for c in json.loads(p.stdout)["claims"]}


def test_verify_from_the_project_directory(project: Path, tmp_path: Path):
    code, claims = verify(project, tmp_path / "cache")
    assert code == 0
    assert {cid: c["status"] for cid, c in claims.items()} == EXPECTED
    t99, v0 = claims["drag.t99"], claims["drag.v0"]
    assert t99["evidence"] == "proof" and "2 sqrt(g k)" in t99["corrected"]
    assert v0["evidence"] == "sampled"
    assert v0["scope"] == ("printed statement holds exactly in cells {|v0|<v_T, v0<0}, {|v0|<v_T, v0>0} and fails "
                           "in {|v0|>v_T, v0<0}, {|v0|>v_T, v0>0}; corrected statement holds in all 4 cells")


def test_editing_the_model_module_changes_the_cached_verdict(project: Path, tmp_path: Path):
    cache = tmp_path / "cache"
    model = project / "drag_model.py"
    original = model.read_text()
    assert "return g - k * v**2" in original
    verify(project, cache)                                        # fill the cache
    code, warm = verify(project, cache)
    assert code == 0 and all(c["cached"] for c in warm.values())

    model.write_text(original.replace("return g - k * v**2", "return g - 2 * k * v**2"))
    code, edited = verify(project, cache)                         # the cache must not answer for the old model
    assert code == 1
    assert edited["drag.v"]["status"] == "failed" and not edited["drag.v"]["cached"]
    assert edited["drag.vT"]["status"] == "failed"
    assert edited["drag.t99"]["status"] == "erratum"              # does not use the right-hand side
    # drag_emit imports drag_model: the emitted file is stale now, and its claims say so
    assert edited["emit.drag_numeric.velocity.numpy"]["status"] == "failed"

    model.write_text(original)                                    # reverting restores the verdicts
    code, reverted = verify(project, cache)
    assert code == 0
    assert {cid: c["status"] for cid, c in reverted.items()} == EXPECTED


def test_pytest_plugin_collects_the_claims_through_the_config(project: Path, tmp_path: Path):
    p = run(project, "-m", "pytest", "--symbt", "--collect-only", "-q", "-p", "no:cacheprovider",
            cache=tmp_path / "cache")
    assert p.returncode == 0, p.stdout + p.stderr
    items = {line.split("::")[-1] for line in p.stdout.splitlines() if line.startswith("symbt/")}
    assert items == set(EXPECTED)
    assert "tests/test_drag_identities.py::" in p.stdout           # and the project's own tests


def test_the_emitted_module_is_up_to_date_and_its_claims_tie_to_eq_v0(project: Path, tmp_path: Path):
    cache = tmp_path / "cache"
    for target in ("python", "c"):
        p = run(project, "-m", "symbt", "codegen", "--check", "--target", target, cache=cache)
        assert p.returncode == 0, p.stdout + p.stderr
    p = run(project, "-m", "symbt", "coverage", "--json", "-", "-q", cache=cache)
    assert p.returncode == 0, p.stdout + p.stderr
    report = json.loads(p.stdout)
    assert report["unknown"] == {"claims": {}, "reasons": []}    # no claim on a label the note lacks
    assert {c["id"] for c in report["coverage"]["v0"]["claims"]} == {"drag.v0", *EMITTED}


def test_codegen_check_fails_on_a_hand_edit_and_a_changed_derivation(project: Path, tmp_path: Path):
    cache = tmp_path / "cache"
    emitted = project / "generated" / "drag_numeric.py"
    original = emitted.read_text()
    emitted.write_text(original.replace("t3*np.tanh", "0.99*t3*np.tanh"))
    p = run(project, "-m", "symbt", "codegen", "--check", cache=cache)
    assert p.returncode == 1 and "drag_numeric.py" in p.stdout + p.stderr
    emitted.write_text(original)

    model = project / "drag_model.py"
    model.write_text(model.read_text().replace("RATE = sp.sqrt(g * k)", "RATE = sp.sqrt(2 * g * k)"))
    p = run(project, "-m", "symbt", "codegen", "--check", cache=cache)
    assert p.returncode == 1 and "drag_numeric.py" in p.stdout + p.stderr
    assert run(project, "-m", "symbt", "codegen", cache=cache).returncode == 0     # regenerated: checks again
    assert run(project, "-m", "symbt", "codegen", "--check", cache=cache).returncode == 0
    assert emitted.read_text() != original
