"""Report paths written *through*: devices, pipes and symlinks are never replaced; bad paths fail before any work."""
from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from symbt import cli
from symbt._files import output_problem, write_report

ROOT = Path(__file__).resolve().parents[1]


def _run(argv, cache: Path, **kw) -> subprocess.CompletedProcess:
    env = dict(os.environ, SYMBT_CACHE_DIR=str(cache))
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    kw.setdefault("stdout", subprocess.PIPE)
    return subprocess.run([sys.executable, "-m", "symbt", *argv], stderr=subprocess.PIPE, text=True, env=env,
                          cwd=ROOT, timeout=300, **kw)


def _read_fifo(path: Path, sink: list) -> threading.Thread:
    def reader():
        with open(path, encoding="utf-8") as fh:
            sink.append(fh.read())
    t = threading.Thread(target=reader, daemon=True)
    t.start()
    return t


def test_json_to_dev_stdout_reaches_stdout_and_keeps_the_link(tmp_path):
    before = os.lstat("/dev/stdout")
    r = _run(["verify", "--scene", "toy", "--json", "/dev/stdout"], tmp_path / "cache")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)                       # the report alone on stdout (a pipe here), as with '-'
    assert "toy" in r.stderr                         # the text report moved to stderr
    assert {c["id"] for c in doc["claims"]} and doc["summary"]["ok"] is True
    after = os.lstat("/dev/stdout")
    assert stat.S_ISLNK(after.st_mode) == stat.S_ISLNK(before.st_mode)
    assert stat.S_IFMT(after.st_mode) == stat.S_IFMT(before.st_mode) and after.st_ino == before.st_ino


def test_junit_to_dev_null_leaves_the_device(tmp_path):
    # read-only observation of the real device; the write-through of a device is tested on a FIFO below
    r = _run(["verify", "--scene", "toy", "-q", "--junit", "/dev/null"], tmp_path / "cache")
    assert r.returncode == 0, r.stderr
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_junit_to_a_fifo_is_written_through(tmp_path):
    fifo = tmp_path / "report.fifo"
    os.mkfifo(fifo)
    got: list = []
    t = _read_fifo(fifo, got)
    r = _run(["verify", "--scene", "toy", "-q", "--junit", str(fifo)], tmp_path / "cache")
    t.join(60)
    assert r.returncode == 0, r.stderr
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)     # still a pipe, not a regular file
    assert got and got[0].startswith("<?xml") and "toy.F" in got[0]


def test_symlinked_report_keeps_the_link_and_writes_the_target(tmp_path):
    target = tmp_path / "out" / "report.json"
    target.parent.mkdir()
    target.write_text("old")
    link = tmp_path / "link.json"
    link.symlink_to(target)
    r = _run(["verify", "--scene", "toy", "-q", "--json", str(link)], tmp_path / "cache")
    assert r.returncode == 0, r.stderr
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert json.loads(target.read_text())["summary"]["ok"] is True
    assert [p.name for p in target.parent.iterdir()] == ["report.json"]     # no temporary file left beside it


def test_json_to_dev_stdout_redirected_to_a_file(tmp_path):
    out = tmp_path / "out.json"
    with open(out, "w") as fh:
        r = _run(["verify", "--scene", "toy", "--json", "/dev/stdout"], tmp_path / "cache", stdout=fh)
    assert r.returncode == 0, r.stderr
    assert json.loads(out.read_text())["summary"]["ok"] is True


def test_coverage_json_to_dev_stdout_is_the_document_alone(capfd):
    # capfd: fd 1 is a temporary file here, so /dev/stdout is that file
    assert cli.main(["coverage", "--json", "/dev/stdout"]) in (0, 1)
    assert "coverage" in json.loads(capfd.readouterr().out)


def test_dangling_symlink_creates_its_target(tmp_path):
    link = tmp_path / "link.md"
    link.symlink_to(tmp_path / "new.md")
    assert output_problem(link) is None
    write_report(link, "# report\n")
    assert link.is_symlink() and (tmp_path / "new.md").read_text() == "# report\n"


def test_regular_file_is_still_replaced_atomically(tmp_path):
    path = tmp_path / "r.json"
    path.write_text("old")
    ino = path.stat().st_ino
    write_report(path, "new")
    assert path.read_text() == "new" and path.stat().st_ino != ino      # a new inode: os.replace, not a rewrite


@pytest.mark.parametrize("bad, words", [
    ("/proc/symbt-report.json", "not writable"),
    ("{tmp}/no/such/report.json", "does not exist"),
    ("{tmp}", "is a directory"),
])
def test_unwritable_report_path_exits_2_before_any_work(tmp_path, bad, words):
    cache = tmp_path / "cache"
    path = bad.format(tmp=tmp_path)
    r = _run(["verify", "--scene", "toy", "--json", path], cache)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "Traceback" not in r.stderr and words in r.stderr, r.stderr
    assert r.stdout == ""                                            # no progress, no summary
    assert not cache.exists() or not any(cache.rglob("*.json"))      # nothing ran, nothing cached


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into a mode-0555 directory")
def test_read_only_directory_is_refused(tmp_path):
    d = tmp_path / "ro"
    d.mkdir()
    d.chmod(0o555)
    try:
        assert "not writable" in output_problem(d / "r.json")
    finally:
        d.chmod(0o755)


@pytest.mark.parametrize("command", ["coverage", "mutate"])
def test_other_commands_refuse_proc_before_any_work(capsys, command):
    argv = [command, "--json", "/proc/symbt-report.json"] + (["--scene", "toy"] if command == "mutate" else [])
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"symbt {command}: --json") and "not writable" in err


def test_coverage_json_through_a_symlink(capsys, tmp_path):
    target = tmp_path / "cov.json"
    link = tmp_path / "cov-link.json"
    link.symlink_to(target)
    assert cli.main(["coverage", "-q", "--json", str(link)]) in (0, 1)
    assert link.is_symlink()
    assert "coverage" in json.loads(target.read_text())
