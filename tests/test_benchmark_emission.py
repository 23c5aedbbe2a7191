"""``symbt.benchmarks.emission``: the user codegen path against ``lambdify`` runs and reports sensible rows.

No time is asserted (the machine is shared); only that the rows exist, are positive, and that the
emitted function and the lambdified one compute the same trace.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from symbt.benchmarks.emission import COLUMNS, emission_row, main, markdown, run_emission

ROOT = Path(__file__).resolve().parents[1]


def test_rows_for_n_2_and_3_have_positive_numbers_and_agree():
    rows = run_emission([2, 3], points=200, repeats=2)
    assert [r["N"] for r in rows] == [2, 3]
    assert [r["terms"] for r in rows] == [6, 14]          # the Lucas-like growth of tr L's expanded terms
    for r in rows:
        for key in ("emit_s", "emit_bytes", "lambdify_s", "lambdify_bytes", "emitted_eval_s", "lambdify_eval_s"):
            assert r[key] > 0, (key, r)
        assert r["max_rel_diff"] < 1e-12
    assert rows[1]["emit_bytes"] > rows[0]["emit_bytes"]   # a bigger trace, a bigger file
    table = markdown(rows).splitlines()
    assert len(table) == 4 and table[0].count("|") == len(COLUMNS) + 1


def test_without_the_rewriting_the_same_trace_is_emitted():
    (row,) = run_emission([3], points=100, repeats=1, optimize=False)
    assert row["optimize"] is False and row["emit_bytes"] > 0 and row["max_rel_diff"] < 1e-12


def test_bad_size_is_a_value_error_and_exit_2(capsys: pytest.CaptureFixture[str]):
    with pytest.raises(ValueError, match="N >= 2"):
        emission_row(1)
    assert main(["--n", "1"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "N >= 2" in err


def test_runs_as_a_module():
    p = subprocess.run([sys.executable, "-m", "symbt.benchmarks.emission", "--n", "2", "--points", "100",
                        "--repeats", "1"], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.strip().splitlines()
    assert lines[0].startswith("| N |") and lines[2].startswith("| 2 | 6 |")
