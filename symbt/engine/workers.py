"""Worker processes that run claims within a time budget and never outlive the process that started them.

:class:`Workers` is a small pool of persistent processes, forked from the caller
(so a worker sees every claim the caller has registered or was handed, users'
claims loaded from their own modules included), one pipe each.  The caller
hands out claim ids one at a time and waits on the pipes and the processes at
once, so that

* a check past its budget is stopped -- its worker is killed with SIGKILL and a
  fresh one forked when there is more work -- and reported ``inconclusive
  (timed out after ... s)``, while the other workers go on;
* a worker that dies under a check (a segfault, ``os._exit``, the OOM killer)
  gives that claim a ``failed`` outcome naming the cause, and the run goes on;
* workers keep their memoised derivations from claim to claim (a worker per
  claim would rebuild them every time).

A worker dies with its parent: on Linux the kernel sends it SIGKILL when the
parent dies (``PR_SET_PDEATHSIG``), and everywhere a watchdog thread ends it once
its parent is gone.  Workers ignore SIGINT: Ctrl-C is the parent's to handle,
which kills them (:meth:`Workers.close`).
"""
from __future__ import annotations

import atexit
import multiprocessing as mp
import multiprocessing.util  # noqa: F401  (its exit handler must be registered before ours, which runs first)
import os
import signal
import sys
import threading
import time
import weakref
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from multiprocessing.connection import Connection, wait
from typing import Any

from ..claims.base import Claim, Outcome, failed
from .task import timed_out, worker_died

__all__ = ["Workers"]

Done = Callable[[Claim, Outcome], None]
_PR_SET_PDEATHSIG = 1
_WATCH_INTERVAL = 0.5
#: pools with processes, killed at exit (workers are not daemonic, so that a check may start processes itself)
_OPEN: weakref.WeakSet[Workers] = weakref.WeakSet()


@atexit.register
def _close_all() -> None:
    for w in list(_OPEN):
        w.close()


def _die_with_parent(parent: int) -> None:
    """Make this process end when ``parent`` does (set first thing in a worker)."""
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
        except (OSError, AttributeError):  # no prctl: the watchdog below is enough
            pass
    if os.getppid() != parent:  # the parent died before the death signal was armed
        os._exit(1)

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(_WATCH_INTERVAL)
        os._exit(1)

    threading.Thread(target=watch, name="symbt-parent-watchdog", daemon=True).start()


def _serve(conn: Connection, parent: int, claims: Mapping[str, Claim] | None, inherited: list[Connection]) -> None:
    """A worker's life: receive ``(claim id, deep)``, send the outcome as a dict; ``None`` or EOF ends it."""
    _die_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for other in inherited:  # other workers' pipe ends, copied by the fork: not ours to hold open
        other.close()
    if claims is None:  # a spawned (not forked) worker: the registry is loaded afresh
        from ..claims import REGISTRY, load_all

        load_all()
        claims = REGISTRY
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            break
        if task is None:
            break
        cid, deep = task
        out = claims[cid].run(deep=deep)
        try:
            conn.send(out.to_dict())
        except Exception as exc:  # an outcome that does not pickle: say so instead of hanging the parent
            conn.send(failed("exception", detail=f"worker: the outcome could not be sent: "
                                                 f"{type(exc).__name__}: {exc}").to_dict())
    conn.close()


class _Slot:
    """One worker process and the parent's end of its pipe (``proc`` is ``None`` until needed)."""

    def __init__(self) -> None:
        self.proc: Any = None
        self.conn: Connection | None = None
        self.task: tuple[Claim, float] | None = None   # the claim it runs and when it started

    def alive(self) -> bool:
        # the sentinel first: it is readable once the process has exited, whoever reaped it (is_alive()
        # answers True when waitpid fails, e.g. for a child another handler already reaped)
        return self.proc is not None and not wait([self.proc.sentinel], 0) and self.proc.is_alive()

    def kill(self) -> None:
        if self.proc is not None:
            if self.proc.is_alive():
                try:
                    os.kill(self.proc.pid, signal.SIGKILL)
                except (ProcessLookupError, PermissionError):
                    pass
            self.proc.join(timeout=5.0)
        if self.conn is not None:
            self.conn.close()
        self.proc = self.conn = self.task = None


class Workers:
    """``size`` worker processes that run claims, each check within ``budget`` seconds.

    ``claims`` maps the ids that will be run to their claims (forked workers
    inherit them; the caller's registry plus the claims it was handed).
    Processes are forked on first use and replaced after a timeout or a death;
    :meth:`close` (or leaving the ``with`` block) kills the ones left.

    >>> from symbt.claims.base import claim, Outcome
    >>> c = claim("demo.workers", equation="demo", scene="demo", statement="1 = 1",
    ...           register=False)(lambda: Outcome("verified", "by inspection"))
    >>> got = []
    >>> with Workers({c.id: c}, size=1) as w:
    ...     w.run([c], done=lambda claim, out: got.append((claim.id, out.status)), budget=60.0)
    >>> got
    [('demo.workers', 'verified')]
    """

    def __init__(self, claims: Mapping[str, Claim], size: int = 1):
        if size < 1:
            raise ValueError(f"size must be at least 1, not {size!r}")
        self.claims = dict(claims)
        self._slots = [_Slot() for _ in range(size)]
        methods = mp.get_all_start_methods()
        self._ctx = mp.get_context("fork" if "fork" in methods else None)

    @property
    def size(self) -> int:
        return len(self._slots)

    def serves(self, claims: Sequence[Claim]) -> bool:
        """Whether these workers know exactly these claim objects (else they were forked from older ones)."""
        return all(self.claims.get(c.id) is c for c in claims)

    def _start(self, slot: _Slot) -> None:
        here, there = self._ctx.Pipe(duplex=True)
        forked = self._ctx.get_start_method() == "fork"
        inherited = [s.conn for s in self._slots if s.conn is not None] + [here]
        proc = self._ctx.Process(target=_serve, name="symbt-worker", daemon=False,
                                 args=(there, os.getpid(), self.claims if forked else None,
                                       inherited if forked else []))
        proc.start()
        there.close()
        slot.proc, slot.conn = proc, here
        _OPEN.add(self)

    def _give(self, slot: _Slot, c: Claim, deep: bool) -> None:
        for attempt in (1, 2):
            if not slot.alive():
                slot.kill()          # reap a worker that died idle
                self._start(slot)
            try:
                assert slot.conn is not None
                slot.conn.send((c.id, deep))
                break
            except OSError:
                if attempt == 2:
                    raise
                slot.kill()
        slot.task = (c, time.monotonic())

    def run(self, todo: Sequence[Claim], *, done: Done, deep: bool = False,
            budget: float | None = None) -> None:
        """Run ``todo`` in this order, calling ``done(claim, outcome)`` as each outcome arrives.

        A check past ``budget`` seconds (``None``: no limit) gets the timed-out
        outcome, one whose worker died the ``worker died`` one (see :mod:`.task`).
        On any exception (Ctrl-C included) every worker is killed before it propagates.
        """
        unknown = [c.id for c in todo if c.id not in self.claims]
        if unknown:
            raise KeyError(f"these workers were not given the claims {unknown}")
        queue = deque(todo)
        try:
            while True:
                for slot in self._slots:
                    if slot.task is None and queue:
                        self._give(slot, queue.popleft(), deep)
                busy = [s for s in self._slots if s.task is not None]
                if not busy:
                    return
                timeout = None
                if budget is not None:
                    now = time.monotonic()
                    timeout = max(0.0, min(s.task[1] for s in busy if s.task) + budget - now)
                wait([s.conn for s in busy if s.conn] + [s.proc.sentinel for s in busy], timeout)
                for slot in busy:
                    self._collect(slot, done, budget)
        except BaseException:
            self.close()
            raise

    def _collect(self, slot: _Slot, done: Done, budget: float | None) -> None:
        assert slot.task is not None and slot.conn is not None
        c, t0 = slot.task
        if slot.conn.poll():
            try:
                data = slot.conn.recv()
            except (EOFError, OSError):  # the pipe closed: the worker is dead (the sentinel says how)
                slot.proc.join(timeout=5.0)
                out = worker_died(slot.proc.exitcode)
                slot.kill()
            else:
                slot.task = None
                try:
                    out = Outcome.from_dict(data)
                except (TypeError, ValueError) as exc:
                    out = failed("exception", detail=f"worker: a malformed outcome: {exc}")
            done(c, out)
        elif not slot.proc.is_alive():
            slot.proc.join(timeout=5.0)
            out = worker_died(slot.proc.exitcode)
            slot.kill()
            done(c, out)
        elif budget is not None and time.monotonic() - t0 >= budget:
            slot.kill()   # SIGKILL: a check may be stuck in C code, where no exception reaches it
            done(c, timed_out(budget, time.monotonic() - t0))

    def close(self) -> None:
        """Kill every worker (SIGKILL) and wait for it; the object can be used again (it forks anew)."""
        for slot in self._slots:
            slot.kill()
        _OPEN.discard(self)

    def __enter__(self) -> Workers:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
