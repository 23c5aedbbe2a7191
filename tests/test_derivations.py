"""The derivations/ walkthrough scripts run cleanly and are valid jupytext percent scripts."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = sorted((ROOT / "derivations").glob("[0-9][0-9]_*.py"))
MIN_CELLS = 8


def test_there_are_derivations():
    names = {s.name for s in SCRIPTS}
    assert {"01_toda_model.py", "05_section2_toy.py"} <= names


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_script_runs(script, tmp_path):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    env["SYMBT_CACHE_DIR"] = str(tmp_path / "cache")
    env["MPLBACKEND"] = "Agg"
    proc = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 0, f"{script.name} failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    assert "all claim outcomes as expected" in proc.stdout


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_script_is_a_percent_notebook(script):
    jupytext = pytest.importorskip("jupytext")
    text = script.read_text(encoding="utf-8")
    nb = jupytext.reads(text, fmt="py:percent")
    kinds = [c.cell_type for c in nb.cells]
    assert len(nb.cells) >= MIN_CELLS, f"{script.name}: only {len(nb.cells)} cells"
    assert kinds.count("markdown") >= 3 and kinds.count("code") >= 3
    # the first cell is the title; markdown cells carry LaTeX; the last code cell pins the outcomes
    assert nb.cells[0].cell_type == "markdown" and nb.cells[0].source.startswith("# ")
    assert any("$" in c.source for c in nb.cells if c.cell_type == "markdown")
    assert "wt.expect(" in [c for c in nb.cells if c.cell_type == "code"][-1].source
    # round trip: notebook -> percent script -> notebook keeps the cells
    again = jupytext.reads(jupytext.writes(nb, fmt="py:percent"), fmt="py:percent")
    assert [c.source for c in again.cells] == [c.source for c in nb.cells]
    # and it converts to an .ipynb document
    ipynb = jupytext.writes(nb, fmt="ipynb")
    assert '"cell_type": "markdown"' in ipynb
