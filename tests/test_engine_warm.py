"""A warm ``symbt verify`` (everything cached) imports neither SymPy, NumPy, mpmath nor a claim module,
and a change to a source file invalidates exactly what it should."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("sympy", "numpy", "mpmath", "scipy")

# run the CLI in a fresh interpreter and report what it imported (sys.modules at exit)
PROBE = """
import json, sys
from symbt.cli import main
rc = main(sys.argv[1:])
heavy = sorted({m.split('.')[0] for m in sys.modules} & set(%r))
claims = sorted(m for m in sys.modules if m.startswith('symbt.claims.') and m != 'symbt.claims.base')
print(json.dumps({"rc": rc, "heavy": heavy, "claim_modules": claims}))
""" % (HEAVY,)


@pytest.fixture(scope="module")
def pkg(tmp_path_factory):
    """A private copy of the package (its sources are edited below) and its own cache."""
    base = tmp_path_factory.mktemp("warm")
    shutil.copytree(ROOT / "symbt", base / "symbt", ignore=shutil.ignore_patterns("__pycache__"))
    return base


def _run(pkg: Path, *argv: str) -> tuple[dict, list[str]]:
    env = {**os.environ, "PYTHONPATH": str(pkg), "SYMBT_CACHE_DIR": str(pkg / "cache")}
    p = subprocess.run([sys.executable, "-c", PROBE, *argv], capture_output=True, text=True, env=env, cwd=pkg,
                       timeout=600)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.strip().splitlines()
    return json.loads(lines[-1]), lines[:-1]


def test_warm_run_imports_nothing_heavy_and_source_changes_invalidate(pkg):
    argv = ("verify", "--scene", "tn2", "--scene", "dj")
    cold, cold_out = _run(pkg, *argv)
    assert cold["rc"] == 0 and "sympy" in cold["heavy"] and cold_out[-1].startswith("wall time")
    assert "(0 of 2 from the cache" in cold_out[-1]

    warm, warm_out = _run(pkg, *argv)
    assert warm["rc"] == 0 and warm["heavy"] == [] and warm["claim_modules"] == []
    assert "(2 of 2 from the cache" in warm_out[-1]
    assert warm_out[:-1] == cold_out[:-1]                          # the same report, but for the timing line
    listing, _ = _run(pkg, "scenes")                               # the listing, too, comes from the manifest
    assert listing["heavy"] == []

    # an unrelated claim module changes: the warm path steps aside, the entries are still valid
    toy = pkg / "symbt" / "claims" / "toy.py"
    toy.write_text(toy.read_text() + "\n# edited\n")
    after, out = _run(pkg, *argv)
    assert "sympy" in after["heavy"] and "(2 of 2 from the cache" in out[-1]
    again, out = _run(pkg, *argv)                                  # ... and the manifest is current again
    assert again["heavy"] == [] and "(2 of 2 from the cache" in out[-1]

    # the claim's own module changes: tn2 is recomputed, dj (symbt.claims.single_bt) is still cached
    model = pkg / "symbt" / "claims" / "toda_model.py"
    model.write_text(model.read_text() + "\n# edited\n")
    changed, out = _run(pkg, *argv)
    assert "sympy" in changed["heavy"] and "(1 of 2 from the cache" in out[-1]
