"""The command line as users meet it: exit codes, one-line errors, reports on stdout, pipes, Ctrl-C."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import symbt
from symbt import cli

ROOT = Path(__file__).resolve().parents[1]


def _env(**extra) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    env.update(extra)
    return env


def _one_line_error(capsys, argv, *, code=2) -> str:
    assert cli.main(argv) == code
    err = capsys.readouterr().err
    assert err.endswith("\n") and err.count("\n") == 1, err
    assert "Traceback" not in err
    return err


@pytest.fixture(scope="module")
def loaded():
    from symbt.claims import load_all

    load_all()


@pytest.fixture
def temp_claims(loaded):
    """A failing claim, a skipped claim and a verified one, in scene ``zz-cli`` (removed afterwards)."""
    import sympy as sp

    from symbt.claims import base
    from symbt.proof import decide

    x = sp.Symbol("x", real=True)
    base.scene("zz-cli", "temporary")
    made = [base.claim("zz.cli.fails", equation="zz", scene="zz-cli", statement="(x+1)^2 = x^2+1")(
                lambda: base.from_decision(decide((x + 1) ** 2, x ** 2 + 1))),
            base.claim("zz.cli.needs", equation="zz", scene="zz-cli", statement="s", requires=("no_such_mod_zz",))(
                lambda: None),
            base.claim("zz.cli.ok", equation="zz", scene="zz-cli", statement="x = x")(
                lambda: base.from_decision(decide(x, x)))]
    yield made
    for c in made:
        base.REGISTRY.pop(c.id, None)
    base.SCENES.pop("zz-cli", None)


def test_version_is_single_sourced(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"symbt {symbt.__version__}"


@pytest.mark.parametrize("argv, words", [
    (["verify", "-j", "0"], "positive integer"),
    (["verify", "-j", "-3"], "positive integer"),
    (["verify", "-j", "two"], "positive integer"),
    (["verify", "--json", "/no/such/dir/x.json"], "does not exist"),
    (["coverage", "--json", "/no/such/dir/x.json"], "does not exist"),
    (["mutate", "--scene", "tn2", "--json", "/no/such/dir/x.json"], "does not exist"),
    (["verify", "--json", "-", "--junit", "-"], "only one report"),
    (["no-such-command"], "invalid choice"),
    ([], "required"),
])
def test_usage_errors_are_one_line_with_exit_2(capsys, argv, words):
    err = _one_line_error(capsys, argv)
    assert err.startswith("symbt") and words in err


def test_report_path_that_is_a_directory(capsys, tmp_path):
    err = _one_line_error(capsys, ["verify", "--scene", "tn2", "--junit", str(tmp_path)])
    assert "is a directory" in err


@pytest.mark.parametrize("command", ["coverage", "mutate"])
def test_other_commands_refuse_a_directory_before_any_work(capsys, tmp_path, command):
    err = _one_line_error(capsys, [command, "--scene", "tn2", "--json", str(tmp_path)] if command == "mutate"
                          else [command, "--json", str(tmp_path)])
    assert err.startswith(f"symbt {command}: --json") and "is a directory" in err


def test_unknown_scene(capsys, loaded):
    err = _one_line_error(capsys, ["verify", "--scene", "no-such-scene"])
    assert "unknown scene or claim 'no-such-scene'" in err


def test_debug_shows_the_traceback(capsys):
    assert cli.main(["--debug", "verify", "-j", "0"]) == 2
    err = capsys.readouterr().err
    assert "Traceback" in err and err.strip().splitlines()[-1].startswith("symbt verify: argument -j")


def test_missing_extra_is_one_line_naming_it(capsys, monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "scipy", None)       # `import scipy` now fails as if not installed
    err = _one_line_error(capsys, ["figures", "--out", str(tmp_path / "f")])
    assert "pip install 'symbt[plot,scipy]'" in err
    # (symbt bench degrades instead: without scipy it runs the BT and heyoka rows, see test_bench_package)
    monkeypatch.setitem(sys.modules, "distributed", None)
    err = _one_line_error(capsys, ["verify", "--dask", "--scene", "tn2"])
    assert "pip install 'symbt[dask]'" in err


def test_json_to_stdout_and_the_short_report(capsys, loaded, tmp_path):
    assert cli.main(["verify", "--scene", "tn2", "--scene", "n3-hamiltonians.tra", "--json", "-"]) == 0
    cap = capsys.readouterr()
    doc = json.loads(cap.out)                              # stdout is the JSON document alone
    assert doc["schema_version"] and [c["id"] for c in doc["claims"]] == ["tn2", "n3-hamiltonians.tra"]
    lines = cap.err.strip().splitlines()                   # the human report went to stderr
    assert lines[-2] == "2 claims: 1 verified, 1 erratum, 0 failed, 0 skipped -- ok"
    assert lines[-1].startswith("wall time")
    assert any(ln.startswith("erratum  n3-hamiltonians.tra") and "[proof]" in ln for ln in lines)
    assert not any(ln.split()[:1] == ["verified"] for ln in lines)   # verified claims get no line of their own
    # -v: the full table, with the evidence column; the summary is still last
    assert cli.main(["verify", "--scene", "tn2", "-v"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    assert out[0].split() == ["claim", "equation", "status", "evidence", "method", "residual", "time"]
    assert out[2].split()[:4] == ["tn2", "tn2", "verified", "proof"]
    assert out[-2].startswith("1 claim: 1 verified")


def test_failures_and_skip_reasons_in_the_report(capsys, temp_claims, tmp_path):
    md = tmp_path / "new-dir" / "r.md"                     # one missing directory level is created
    assert cli.main(["verify", "--scene", "zz-cli", "--markdown", str(md)]) == 1
    out = capsys.readouterr().out
    assert "skipped  zz.cli.needs" in out and "optional dependency missing: no_such_mod_zz" in out
    assert "failed   zz.cli.fails" in out and "counterexample: x = " in out
    assert out.strip().splitlines()[-2].endswith("-- FAILED")
    assert "| `zz.cli.fails` | `zz` | failed |" in md.read_text()


def test_closed_pipe_is_silent(loaded, tmp_path, monkeypatch):
    monkeypatch.setenv("SYMBT_CACHE_DIR", str(tmp_path))
    assert cli.main(["verify", "--scene", "tn2", "-q"]) == 0   # warm cache: the subprocesses need no SymPy
    env = _env(SYMBT_CACHE_DIR=str(tmp_path))
    for argv in (["scenes"], ["verify", "--scene", "tn2"]):
        p = subprocess.Popen([sys.executable, "-m", "symbt", *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             env=env, cwd=tmp_path)
        p.stdout.close()                                   # the reader is gone before anything is written
        err = p.stderr.read()
        assert p.wait(timeout=120) == 0, err
        assert b"BrokenPipe" not in err and b"Traceback" not in err and b"Exception ignored" not in err


def test_ctrl_c_stops_promptly_and_keeps_finished_outcomes(tmp_path):
    """SIGINT to the process group (what Ctrl-C does): the pool stops within seconds, finished outcomes stay."""
    cache = tmp_path / "cache"
    # two fast claims and two that take many seconds; -j 2
    argv = [sys.executable, "-m", "symbt", "verify", "--no-cache", "-j", "2",
            "--scene", "tn2", "--scene", "tra.n2", "--scene", "inverse.n2", "--scene", "inverse.n3"]
    # the child starts with SIGINT at its default (as from a terminal): a test earlier in the same pytest worker
    # may have left it ignored, and a process started with SIGINT ignored rightly keeps ignoring it
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=_env(SYMBT_CACHE_DIR=str(cache)),
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
                         cwd=tmp_path, start_new_session=True)
    deadline = time.monotonic() + 180
    while not (cache / "tn2.json").exists() and time.monotonic() < deadline and p.poll() is None:
        time.sleep(0.05)
    assert (cache / "tn2.json").exists() and p.poll() is None, "tn2 never finished, or the run ended early"
    t0 = time.monotonic()
    os.killpg(p.pid, signal.SIGINT)
    out, err = p.communicate(timeout=30)
    stopped_after = time.monotonic() - t0
    assert p.returncode == 130, err
    assert stopped_after < 5, f"took {stopped_after:.1f}s to stop"      # inverse.n3 alone takes far longer
    assert b"Traceback" not in err and err.decode().strip().splitlines()[-1].startswith("symbt verify: interrupted (")
    with pytest.raises(ProcessLookupError):                # no worker process survives in the group
        os.killpg(p.pid, 0)
    entry = json.loads((cache / "tn2.json").read_text())
    assert entry["outcome"]["status"] == "verified"
    assert not (cache / "inverse.n3.json").exists()
