"""The copies of a source tree that ``symbt mutate --source`` mutates, and the runs in them.

The real tree is never written: each worker gets its own copy (:func:`copy_tree`), a mutant is
written into that copy, ``symbt verify`` runs on it in a subprocess whose working directory is the
copy (so the copy is first on ``sys.path``), and the file is put back, with its original time
stamp (:class:`Mutated`).  The mutated file gets a different time stamp and the subprocesses never
write byte code, so a stale ``.pyc`` of the original can never stand in for the mutant.

A subprocess that runs past its limit is killed with its whole process group (the verify workers
included) and reported as such.
"""
from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = ["IGNORED", "copy_tree", "Mutated", "subprocess_env", "Run", "run_command", "run_verify",
           "verify_changes", "COMPARED", "kill_running"]

#: process groups of the subprocesses running now (:func:`kill_running` ends them on Ctrl-C)
RUNNING: set[int] = set()

#: never copied: version control, caches, virtual environments, build output
IGNORED = (".git", ".hg", "__pycache__", ".venv", "venv", ".venv-ci", "node_modules", "build", "dist", ".tox",
           ".mypy_cache", ".ruff_cache", ".pytest_cache", ".symbt-cache", "*.egg-info", ".ipynb_checkpoints")
#: the fields of a claim's verify record a mutant must leave unchanged to survive
COMPARED = ("status", "evidence", "scope")


def copy_tree(root: Path, dest: Path, only: Sequence[str] | None = None) -> Path:
    """Copy ``root`` (or only its entries ``only``) to ``dest``, without :data:`IGNORED` entries;
    time stamps are kept.  Returns ``dest``."""
    dest.mkdir(parents=True, exist_ok=True)
    ignore = shutil.ignore_patterns(*IGNORED)
    names = list(only) if only is not None else [p.name for p in root.iterdir()]
    skipped = set(ignore(str(root), names))
    for name in names:
        if name in skipped:
            continue
        src = root / name
        if src.is_dir():
            shutil.copytree(src, dest / name, ignore=ignore, symlinks=True, dirs_exist_ok=True)
        elif src.is_file():
            shutil.copy2(src, dest / name)
    subprocess.run([sys.executable, "-m", "compileall", "-q", "-x", r"/\.", str(dest)],
                   capture_output=True, check=False)   # byte code of the unmutated files, once
    return dest


class Mutated:
    """``with Mutated(path, data):`` -- the file holds ``data`` inside the block, its own bytes and
    time stamp after it (also when the block raises)."""

    def __init__(self, path: Path, data: bytes) -> None:
        self.path, self.data = path, data

    def __enter__(self) -> Path:
        self.original = self.path.read_bytes()
        st = self.path.stat()
        self.times = (st.st_atime_ns, st.st_mtime_ns)
        self.path.write_bytes(self.data)
        # another second stamp than the original's: its .pyc (keyed by stamp and size) is not valid for this file
        os.utime(self.path, ns=(self.times[0], self.times[1] + 7_000_000_000))
        return self.path

    def __exit__(self, *exc: Any) -> None:
        self.path.write_bytes(self.original)
        os.utime(self.path, ns=self.times)


def subprocess_env(copy_root: Path) -> dict[str, str]:
    """The environment of a run in a copy: the copy first on the path, a throwaway claim cache and
    numba cache inside the copy, no byte code written, no debug tracebacks."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(copy_root), *filter(None, [env.get("PYTHONPATH")])])
    env["SYMBT_CACHE_DIR"] = str(copy_root / ".symbt-mutate-cache")
    env["NUMBA_CACHE_DIR"] = str(copy_root / ".numba-cache")
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env.pop("SYMBT_DEBUG", None)
    return env


@dataclass
class Run:
    """What a subprocess did: exit ``code`` (``None``: killed at the time limit), output, seconds."""

    code: int | None
    stdout: str
    stderr: str
    seconds: float

    @property
    def timed_out(self) -> bool:
        return self.code is None

    def last_error(self) -> str:
        lines = [ln for ln in self.stderr.strip().splitlines() if ln.strip()]
        return lines[-1][:200] if lines else f"exit status {self.code}"


def run_command(argv: Sequence[str], cwd: Path, timeout: float, env: dict[str, str] | None = None) -> Run:
    """Run ``argv`` in ``cwd`` with a time limit; past it the whole process group is killed."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(list(argv), cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    RUNNING.add(proc.pid)
    try:
        out, err = proc.communicate(timeout=max(timeout, 0.1))
        return Run(proc.returncode, out, err, time.perf_counter() - t0)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        out, err = proc.communicate()
        return Run(None, out, err, time.perf_counter() - t0)
    except BaseException:   # Ctrl-C: leave no process behind
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        raise
    finally:
        RUNNING.discard(proc.pid)


def kill_running() -> None:
    """Kill the process groups of every subprocess :func:`run_command` is running now (other threads')."""
    for pid in list(RUNNING):
        try:
            os.killpg(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


def run_verify(copy_root: Path, ids: Sequence[str] | None, timeout: float, *,
               claims: Sequence[str] = (), deep: bool = False) -> tuple[Run, dict[str, dict[str, Any]] | None]:
    """``symbt verify --no-cache`` of the claims ``ids`` (``None``: the default set) in a copy, with ``--deep``
    if ``deep``; the run and its claims' records by id (``None`` when it wrote no report)."""
    report = copy_root / ".symbt-mutate-verify.json"
    report.unlink(missing_ok=True)
    argv = [sys.executable, "-m", "symbt", "verify", "--no-cache", "-q", "-j", "1", "--json", str(report),
            "--budget", f"{2 * max(timeout, 1.0) + 10:.0f}"]   # our kill comes first: a hang is a timeout
    for c in claims:
        argv += ["--claims", c]
    if deep:
        argv.append("--deep")
    for i in ids or ():
        argv += ["--scene", i]
    run = run_command(argv, copy_root, timeout, subprocess_env(copy_root))
    try:
        doc = json.loads(report.read_text(encoding="utf-8"))
        return run, {c["id"]: c for c in doc["claims"]}
    except (OSError, ValueError, KeyError, TypeError):
        return run, None


def verify_changes(base: dict[str, dict[str, Any]], now: dict[str, dict[str, Any]] | None,
                   ids: Sequence[str]) -> list[str]:
    """How the records of ``ids`` differ from the unmutated run (:data:`COMPARED` fields); empty: no change.

    >>> base = {"a": {"status": "verified", "evidence": "proof", "scope": None}}
    >>> verify_changes(base, {"a": dict(base["a"], status="failed")}, ["a"])
    ['a: status verified -> failed']
    >>> verify_changes(base, base, ["a"]), verify_changes(base, {}, ["a"])
    ([], ['a: no result'])
    """
    out = []
    for cid in ids:
        b, n = base.get(cid), (now or {}).get(cid)
        if b is None:
            continue
        if n is None:
            out.append(f"{cid}: no result")
            continue
        for f in COMPARED:
            if b.get(f) != n.get(f):
                out.append(f"{cid}: {f} {str(b.get(f))[:60]} -> {str(n.get(f))[:60]}")
    return out
