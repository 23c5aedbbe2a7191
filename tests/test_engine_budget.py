"""Time budgets and worker processes: a check past its budget is ``inconclusive (timed out)`` and the run goes on,
a worker that dies fails only its claim, no worker outlives the run, and the pytest plugin keeps the budget too."""
from __future__ import annotations

import inspect
import multiprocessing
import os
import signal
import subprocess
import sys
import textwrap
import time
from importlib import metadata
from pathlib import Path

import pytest
import sympy as sp

from symbt import cli, engine
from symbt.claims.base import REGISTRY, Outcome, claim, from_decision
from symbt.engine.cache import cache_file
from symbt.engine.runner import KeptWorkers, keep_workers, run
from symbt.proof import decide

ROOT = Path(__file__).resolve().parent.parent


def _sleeps():
    time.sleep(120)
    return Outcome("verified", "slept")


def _square():
    a, b = sp.symbols("a b")
    return from_decision(decide((a + b) ** 2, a ** 2 + 2 * a * b + b ** 2))


def _exits():
    os._exit(3)


def _segfaults():
    import faulthandler
    import resource

    faulthandler.disable()                             # pytest's, inherited: no traceback on the test's stderr
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))   # no core file from the test
    os.kill(os.getpid(), signal.SIGSEGV)
    time.sleep(10)


def _pid():
    return Outcome("verified", "pid", detail=str(os.getpid()))


@pytest.fixture
def claims():
    """Test claims registered under unique ids, removed from the registry afterwards."""
    made = {name: claim(f"zz.budget.{name}", equation="zz-budget", scene="zz-budget", statement=name)(fn)
            for name, fn in (("sleeps", _sleeps), ("square", _square), ("square2", _square), ("exits", _exits),
                             ("segfaults", _segfaults), ("pid", _pid), ("pid2", _pid))}
    yield made
    for c in made.values():
        REGISTRY.pop(c.id, None)


@pytest.mark.parametrize("jobs", [1, 2])
def test_check_past_its_budget_is_inconclusive_and_the_run_goes_on(claims, jobs):
    chosen = [claims["square"], claims["sleeps"], claims["square2"]]
    t0 = time.monotonic()
    got = {r.claim.id: r.outcome for r in run(chosen, use_cache=False, jobs=jobs, budget=1.0)}
    elapsed = time.monotonic() - t0
    assert elapsed < 15, f"took {elapsed:.1f}s with a 1 s budget"     # the sleeping check alone takes 120 s
    slow = got["zz.budget.sleeps"]
    assert (slow.status, slow.method) == ("inconclusive", "timed out")
    assert slow.detail == "inconclusive (timed out after 1 s)"
    assert 1.0 <= slow.seconds < 10
    for name in ("square", "square2"):
        assert got[f"zz.budget.{name}"].status == "verified" and got[f"zz.budget.{name}"].evidence == "proof"
    assert not [p for p in multiprocessing.active_children() if p.name == "symbt-worker"]   # none left running


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_dead_worker_fails_its_claim_only(claims, jobs):
    chosen = [claims["exits"], claims["square"], claims["segfaults"], claims["square2"]]
    got = {r.claim.id: r.outcome for r in run(chosen, use_cache=False, jobs=jobs, budget=60.0)}
    exits, segv = got["zz.budget.exits"], got["zz.budget.segfaults"]
    assert exits.status == "failed" and exits.method == "worker died" and "exited with status 3" in exits.detail
    assert segv.status == "failed" and segv.method == "worker died" and "SIGSEGV" in segv.detail
    assert got["zz.budget.square"].status == got["zz.budget.square2"].status == "verified"


def test_timeouts_and_dead_workers_are_not_cached(claims):
    chosen = [claims["sleeps"], claims["exits"], claims["square"]]
    run(chosen, jobs=1, budget=1.0)
    assert cache_file(claims["square"]).exists()          # the cache is written ...
    assert not cache_file(claims["sleeps"]).exists()      # ... but not for what says something about this run only
    assert not cache_file(claims["exits"]).exists()
    again = {r.claim.id: r.outcome for r in run(chosen, jobs=1, budget=1.0)}
    assert again["zz.budget.square"].cached and not again["zz.budget.sleeps"].cached


def test_workers_are_kept_only_inside_keep_workers(claims):
    a, b = claims["pid"], claims["pid2"]
    with keep_workers():
        first = run([a], use_cache=False)[0].outcome.detail
        second = run([b], use_cache=False)[0].outcome.detail
    assert first == second != str(os.getpid())          # one worker served both runs
    assert not _alive(int(first))                        # and is gone after the block
    apart = {run([c], use_cache=False)[0].outcome.detail for c in (a, b)}
    assert len(apart) == 2 and first not in apart         # outside the block: a fresh worker per run
    assert run([a], use_cache=False, budget=None)[0].outcome.detail == str(os.getpid())   # no budget: in-process
    kept = KeptWorkers()                                  # kept across blocks (a walkthrough's shows)
    with keep_workers(kept):
        one = run([a], use_cache=False)[0].outcome.detail
    with keep_workers(kept):
        two = run([b], use_cache=False)[0].outcome.detail
    assert one == two and _alive(int(one))
    kept.close()
    assert not _alive(int(one))


def test_kept_workers_recover_from_a_timeout_and_from_a_death_between_runs(claims):
    a, b = claims["pid"], claims["pid2"]
    with keep_workers():
        first = int(run([a], use_cache=False)[0].outcome.detail)
        assert run([claims["sleeps"]], use_cache=False, budget=1.0)[0].outcome.method == "timed out"
        assert not _alive(first)                          # the timed-out worker was killed ...
        second = int(run([b], use_cache=False)[0].outcome.detail)
        assert second != first and _alive(second)         # ... and a fresh one serves the next run
        os.kill(second, signal.SIGKILL)                   # a worker that dies while idle
        assert _gone_within([second], 5)
        third = run([a], use_cache=False)[0].outcome
        assert third.status == "verified" and int(third.detail) not in (first, second), (third.method, third.detail)


def test_bad_budgets_are_rejected(claims, monkeypatch, capsys):
    for bad in (0, -1.0, float("inf"), float("nan"), True, "10"):
        with pytest.raises(ValueError, match="budget"):
            run([claims["square"]], budget=bad)
        with pytest.raises(ValueError, match="budget"):
            engine.verify(["tn2"], budget=bad)
    for bad in ("0", "-2", "inf", "soon"):
        assert cli.main(["verify", "--scene", "tn2", "--budget", bad]) == 2
        err = capsys.readouterr().err
        assert "--budget" in err and len(err.strip().splitlines()) == 1
    seen = {}

    def fake_run(chosen, **kw):
        seen.update(kw)
        return []

    monkeypatch.setattr(engine, "run", fake_run)
    cli.main(["verify", "--scene", "tn2", "--no-cache", "-q", "--budget", "2.5"])
    assert seen["budget"] == 2.5
    seen.clear()
    cli.main(["verify", "--scene", "tn2", "--no-cache", "-q"])
    assert "budget" not in seen                           # run's own default applies: 300 s
    assert inspect.signature(run).parameters["budget"].default == engine.DEFAULT_BUDGET == 300.0
    assert inspect.signature(engine.verify).parameters["budget"].default == engine.DEFAULT_BUDGET


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, dead but not yet reaped by its new parent, counts as dead).

    Every thread counts: a killed process's leader shows ``Z`` while its other threads (a worker's
    watchdog) are still exiting, and only then are its pipes closed.
    """
    try:
        threads = [t.name for t in Path(f"/proc/{pid}/task").iterdir()]
    except (FileNotFoundError, ProcessLookupError):
        return False
    for t in threads:
        try:
            if Path(f"/proc/{pid}/task/{t}/stat").read_text().rpartition(")")[2].split()[0] not in ("Z", "X"):
                return True
        except (FileNotFoundError, ProcessLookupError):  # that thread is gone
            continue
    return False


SLEEPERS = '''
import os, time
from pathlib import Path
from symbt.claims.base import Outcome, claim

def _sleeper(i):
    def check():
        (Path(os.environ["ZZ_MARKS"]) / f"{i}.{os.getpid()}").write_text("")
        time.sleep(120)
        return Outcome("verified", "slept")
    return check

for i in (1, 2):
    claim(f"zz.sigkill.{i}", equation="zz", scene="zz-sigkill", statement="sleeps")(_sleeper(i))
'''


def _start_sleepers(tmp_path: Path, jobs: int, n: int) -> tuple[subprocess.Popen, list[int]]:
    """``symbt verify -j JOBS`` on ``n`` sleeping claims of a module of their own, once ``jobs`` of them run:
    the process and its workers' pids (the claims write them)."""
    (tmp_path / "zz_sleepers.py").write_text(SLEEPERS)
    marks = tmp_path / "marks"
    marks.mkdir()
    scenes = [a for i in range(1, n + 1) for a in ("--scene", f"zz.sigkill.{i}")]
    code = (f"import sys; sys.path.insert(0, {str(tmp_path)!r}); import zz_sleepers; from symbt.cli import main; "
            f"sys.exit(main(['verify', '-j', '{jobs}', '--no-cache', '-q', *{scenes!r}]))")
    env = {**os.environ, "ZZ_MARKS": str(marks), "SYMBT_CACHE_DIR": str(tmp_path / "cache"),
           "PYTHONPATH": os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)}
    # SIGINT at its default in the child (as from a terminal), whatever an earlier test left in this process
    p = subprocess.Popen([sys.executable, "-c", code], env=env, cwd=tmp_path, stderr=subprocess.PIPE,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    workers: list[int] = []
    deadline = time.monotonic() + 120
    while len(workers) < jobs and time.monotonic() < deadline and p.poll() is None:
        time.sleep(0.05)
        workers = [int(m.name.split(".")[1]) for m in marks.iterdir()]
    if len(workers) < jobs:
        p.kill()
        raise AssertionError(f"the checks never started: {p.communicate()[1].decode()}")
    assert all(_alive(w) for w in workers) and os.getpid() not in workers and p.pid not in workers
    return p, workers


def _gone_within(workers: list[int], seconds: float) -> bool:
    t0 = time.monotonic()
    while any(_alive(w) for w in workers) and time.monotonic() - t0 < seconds:
        time.sleep(0.05)
    return not any(_alive(w) for w in workers)


def _clean_up(p: subprocess.Popen, workers: list[int]) -> None:
    """Whatever the test started and is still there (only if it failed)."""
    if p.poll() is None:
        p.kill()
    for w in workers:
        if _alive(w):
            os.kill(w, signal.SIGKILL)
    p.wait()
    if p.stderr:
        p.stderr.close()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_workers_die_when_verify_is_killed(tmp_path):
    """SIGKILL to ``symbt verify -j 2``: its workers, busy with sleeping checks, are gone within seconds."""
    p, workers = _start_sleepers(tmp_path, jobs=2, n=2)
    try:
        assert len(workers) == 2
        p.kill()
        p.wait(timeout=10)
        assert _gone_within(workers, 3), "a worker outlived the killed run"
    finally:
        _clean_up(p, workers)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_ctrl_c_stops_a_sleeping_check_under_one_job(tmp_path):
    """SIGINT to ``symbt verify -j 1`` (to the process only, as ``kill -INT``): exit 130 at once, no worker left."""
    p, workers = _start_sleepers(tmp_path, jobs=1, n=2)
    try:
        t0 = time.monotonic()
        os.kill(p.pid, signal.SIGINT)
        err = p.communicate(timeout=30)[1].decode()
        assert p.returncode == 130 and time.monotonic() - t0 < 5, err
        assert err.strip().splitlines()[-1].startswith("symbt verify: interrupted (0 of 2 claims finished")
        assert _gone_within(workers, 1)
    finally:
        _clean_up(p, workers)


PLUGIN_CONFTEST = '''
import time
import sympy as sp
from symbt.claims.base import Outcome, claim, from_decision, scene
from symbt.proof import decide

scene("zz-plugin", "claims of the budget test")

@claim("zz.plugin.sleeps", equation="zz", scene="zz-plugin", statement="sleeps")
def _sleeps():
    time.sleep(120)
    return Outcome("verified", "slept")

@claim("zz.plugin.square", equation="zz", scene="zz-plugin", statement="(a+b)^2")
def _square():
    a, b = sp.symbols("a b")
    return from_decision(decide((a + b) ** 2, a ** 2 + 2 * a * b + b ** 2))
'''


def test_pytest_plugin_keeps_the_budget(tmp_path):
    (tmp_path / "conftest.py").write_text(textwrap.dedent(PLUGIN_CONFTEST))
    env = {**os.environ, "SYMBT_CACHE_DIR": str(tmp_path / "cache"),
           "PYTHONPATH": os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)}
    eps = metadata.entry_points(group="pytest11")
    plugin = [] if any(ep.value == "symbt.pytest_plugin" for ep in eps) else ["-p", "symbt.pytest_plugin"]
    argv = [sys.executable, "-m", "pytest", *plugin, "-p", "no:cacheprovider",
            "-p", "no:hypothesispytest", "-p", "no:xdist", "--symbt-scene", "zz-plugin", "--symbt-budget", "1",
            "-rf", "-q", "--rootdir", str(tmp_path), str(tmp_path)]
    t0 = time.monotonic()
    r = subprocess.run(argv, env=env, cwd=tmp_path, capture_output=True, text=True, timeout=110)
    elapsed = time.monotonic() - t0
    out = r.stdout + r.stderr
    assert r.returncode == 1, out
    assert "1 failed, 1 passed" in out and "inconclusive (timed out after 1 s)" in out, out
    assert "FAILED symbt/zz-plugin::zz.plugin.sleeps" in out, out
    assert elapsed < 100, f"took {elapsed:.0f}s"      # the sleeping check alone takes 120 s
    bad = subprocess.run([*argv[:argv.index("1")], "0", *argv[argv.index("1") + 1:]], env=env, cwd=tmp_path,
                         capture_output=True, text=True, timeout=110)
    assert bad.returncode == 4 and "--symbt-budget" in bad.stderr


def test_dask_task_reports_a_timeout_at_once(claims):
    """On Dask the budget is best-effort: the task returns the timed-out outcome after the budget."""
    from symbt.engine.task import run_claim

    t0 = time.monotonic()
    out = Outcome.from_dict(run_claim("zz.budget.sleeps", budget=0.5))
    assert time.monotonic() - t0 < 5
    assert (out.status, out.detail) == ("inconclusive", "inconclusive (timed out after 0.5 s)")
    assert Outcome.from_dict(run_claim("zz.budget.square", budget=30.0)).status == "verified"
