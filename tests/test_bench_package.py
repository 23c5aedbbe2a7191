"""``symbt bench`` end to end: the package imports and runs without scipy/heyoka (with a message),
a --quick run of a small case writes its files and scores the contenders against the 50-digit BT,
heyoka (if installed) integrates the same flow as the BT."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from symbt.benchmarks.cases import Case

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

BLOCKED = """
import sys
class Block:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("scipy", "heyoka"):
            raise ImportError("blocked for the test: " + name)
sys.meta_path.insert(0, Block())
import symbt.benchmarks
from symbt import cli
rc = cli.main(["bench", "--quick", "--cases", "n2-inner-gap", "--skip", "precision,ensemble,throughput",
               "--out", sys.argv[1]])
print("RC", rc, "scipy" in sys.modules, "heyoka" in sys.modules)
"""


def test_runs_without_scipy_and_heyoka(tmp_path):
    env = dict(os.environ, PYTHONPATH=ROOT + os.pathsep + os.environ.get("PYTHONPATH", ""),
               SYMBT_NO_NUMBA="1")                                   # and without numba (plain-Python kernel)
    out = subprocess.run([sys.executable, "-c", BLOCKED, str(tmp_path)], capture_output=True, text=True, env=env,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    assert "RC 0 False False" in out.stdout
    assert "heyoka not available" in out.stdout and "heyoka rows are skipped" in out.stdout
    assert "scipy not installed" in out.stdout
    res = json.loads((tmp_path / "bench.json").read_text())
    runs = res["cases"][0]["runs"]
    assert runs and all(r["kind"] == "bt" for r in runs)
    assert not any("numba" in r["method"] for r in runs)
    assert all(r["final_err"] < 1e-11 for r in runs if "final_err" in r)
    assert res["cases"][0]["heyoka_skipped"].startswith("heyoka not run")


def test_quick_small_case_end_to_end(tmp_path):
    pytest.importorskip("scipy")
    from symbt import cli
    rc = cli.main(["bench", "--quick", "--cases", "n2-inner-gap", "--skip", "precision,ensemble,throughput",
                   "--no-heyoka", "--out", str(tmp_path)])
    assert rc == 0
    res = json.loads((tmp_path / "bench.json").read_text())
    assert res["quick"] and res["cases"][0]["case"] == "n2-inner-gap"
    runs = {(r["method"], r["param"]): r for r in res["cases"][0]["runs"]}
    assert runs[("BT bt_orbit (auto)", None)]["final_err"] < 1e-11       # the BT against its 50-digit self
    dop = [r for (m, _), r in runs.items() if m == "scipy DOP853"]
    assert len(dop) == 3
    # DOP853 integrates the flow whose time-1 map is the BT: its error shrinks with the tolerance
    errs = [r["final_err"] for r in sorted(dop, key=lambda r: -r["param"])]
    assert errs[-1] < 1e-7 and errs[-1] < errs[0] / 1e4
    md = (tmp_path / "bench.md").read_text()
    assert "n2-inner-gap" in md and "provisional" in md
    if os.path.exists(tmp_path / "work_precision.png"):
        assert (tmp_path / "work_precision.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_heyoka_contender_on_a_tiny_case():
    hy = pytest.importorskip("heyoka")
    from symbt.benchmarks.heyoka_system import load
    from symbt.benchmarks.runner import run_case
    from symbt.paper import P_EXAMPLE, Q_EXAMPLE
    hy, _ = load()
    case = Case("tiny", P_EXAMPLE, Q_EXAMPLE, 10.0, 5.0, 20, heyoka_tols=(1e-8, 1e-15))
    out = run_case(case, quick=True, log=lambda s: None, hy=hy, scipy_ok=False)
    h = {r["param"]: r for r in out["runs"] if r["kind"] == "heyoka"}
    assert h[1e-15]["final_err"] < 1e-12 < h[1e-8]["final_err"]          # same flow; tolerance matters
    assert "vs_heyoka" in "".join(out["headline"])


def test_heyoka_transfer_field_and_real_precision():
    hy = pytest.importorskip("heyoka")
    from symbt.benchmarks.cases import chain
    from symbt.benchmarks.heyoka_peer import high_precision
    from symbt.benchmarks.heyoka_system import load, transfer_system
    from symbt.benchmarks.metrics import mp_state_error
    from symbt.benchmarks.reference import reference_states
    from symbt.numeric.flow.field import FlowField
    hy, _ = load()
    p, q = chain(4, 4)
    f = FlowField(p, q, 4.5, 1.0)
    ta = hy.taylor_adaptive(transfer_system(hy, f), list(q) + list(p), tol=1e-15, compact_mode=True)
    ta.propagate_until(2.0)
    ref = reference_states(p, q, 4.5, 1.0, 2, 40)
    x = list(ta.state[4:]) + list(ta.state[:4])
    assert mp_state_error(x, ref) < 1e-13
    ref30 = reference_states(["-20", "10", "1"], ["1", "0", "0.9"], 10, 5, 1, 80)
    r = high_precision(hy, ["-20", "10", "1"], ["1", "0", "0.9"], "10", "5", 1, 30, 1.0, ref30, quick=True)
    assert r["err"] < 1e-29 and r["prec_bits"] >= 100
    assert np.isfinite(r["time_s"])


def test_short_calls_are_timed_in_batches_long_ones_singly():
    import time

    from symbt.benchmarks.timing import timed

    calls = []

    def fast():
        calls.append(1)
        return 7

    res, secs, reps = timed(fast)
    # warm-up + first call + 5 batches, each batch at least 20 ms of calls
    assert res == 7 and reps == 5 and len(calls) > 2 + 5 * 10 and secs < 1e-3

    calls.clear()

    def slow():
        calls.append(1)
        time.sleep(0.03)

    _, secs, reps = timed(slow)
    assert reps == 5 and len(calls) == 1 + 5 and secs >= 0.03
