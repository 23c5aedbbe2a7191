"""Progress of a cold run, on stderr: a bar on a terminal, plain lines otherwise.

* On a terminal: a ``rich`` progress bar if rich is installed (no refresh
  thread: the bar is redrawn as outcomes arrive), else one self-overwriting
  line ``[=====     ] 41/107 claim-id``; the bar is cleared at the end, so the
  report follows on a clean screen.
* Not a terminal (CI logs, pipes): one plain line per computed claim,
  ``[ 41/107] verified  tn2 (0.31s)``.
* Cached outcomes advance the count silently; a fully cached run shows nothing.

>>> import io
>>> from symbt.claims.base import Claim, Outcome
>>> buf = io.StringIO()
>>> p = Progress(2, stream=buf)
>>> p(Claim("tn2", "tn2", "s", check=None), Outcome("verified", "exact", seconds=0.25))
>>> p.close()
>>> buf.getvalue()
'[1/2] verified tn2 (0.25s)\\n'
"""
from __future__ import annotations

import sys
import time
from typing import Any, TextIO

from .views import ClaimView, OutcomeView

__all__ = ["Progress"]


class Progress:
    """Callable ``(claim, outcome)`` for :func:`symbt.engine.run`'s ``progress``; :meth:`close` at the end."""

    def __init__(self, total: int, *, stream: TextIO | None = None, enabled: bool = True,
                 rich: bool | None = None):
        self.total, self.done = total, 0
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = enabled
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self._bar: Any = None
        self._task: Any = None
        self._drawn = False
        self._t0 = time.perf_counter()
        if enabled and self.tty and rich is not False:
            try:
                from rich.console import Console
                from rich.progress import BarColumn, MofNCompleteColumn, TextColumn, TimeElapsedColumn
                from rich.progress import Progress as RichProgress
            except ImportError:
                pass
            else:
                self._bar = RichProgress(TextColumn("symbt verify"), BarColumn(), MofNCompleteColumn(),
                                         TimeElapsedColumn(), TextColumn("{task.description}"),
                                         console=Console(file=self.stream), auto_refresh=False, transient=True)
                self._task = self._bar.add_task("", total=total)

    def __call__(self, claim: ClaimView, outcome: OutcomeView) -> None:
        self.done += 1
        if not self.enabled:
            return
        if self._bar is not None:
            if not self._drawn:
                self._bar.start()
                self._drawn = True
            self._bar.update(self._task, completed=self.done, description=claim.id)
            self._bar.refresh()
        elif self.tty:
            if outcome.cached and not self._drawn:
                return
            width = 30
            fill = int(width * self.done / max(self.total, 1))
            line = f"[{'=' * fill}{' ' * (width - fill)}] {self.done}/{self.total} {claim.id}"[:100]
            self.stream.write("\r" + line.ljust(100))
            self.stream.flush()
            self._drawn = True
        elif not outcome.cached:
            w = len(str(self.total))
            self.stream.write(f"[{self.done:>{w}}/{self.total}] {outcome.status:8s} {claim.id} "
                              f"({outcome.seconds or 0:.2f}s)\n")
            self.stream.flush()

    def close(self) -> None:
        """Remove the bar (terminal); nothing to do for plain lines."""
        if self._bar is not None and self._drawn:
            self._bar.stop()
        elif self.tty and self._drawn:
            self.stream.write("\r" + " " * 100 + "\r")
            self.stream.flush()
        self._drawn = False
