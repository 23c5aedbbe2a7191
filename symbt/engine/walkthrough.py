"""Walkthroughs: the ``derivations/`` scripts show claims and objects, then pin the outcomes."""
from __future__ import annotations

from typing import Any

from ..claims import REGISTRY, load_all
from ..report.text import result_text

__all__ = ["Walkthrough"]


def _in_ipython() -> bool:
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    return get_ipython() is not None


class Walkthrough:
    """Helper for the ``derivations/`` scripts: show claims and objects, then pin the outcomes.

    In Jupyter, :meth:`show` and :meth:`display` use rich display (claim cards,
    LaTeX); in a terminal they print plain text.  :meth:`expect` raises
    ``AssertionError`` if a shown claim's status differs from the expected one
    (or an expected claim was not shown), so a changed outcome breaks the script.
    """

    def __init__(self) -> None:
        from .runner import KeptWorkers

        load_all()
        self.shown: dict[str, str] = {}
        self.rich = _in_ipython()
        self.workers = KeptWorkers()   # one worker for every claim shown: it keeps the derivations it built

    # Any: claim results, text, or anything IPython can display (told apart at run time)
    def display(self, *objs: Any) -> None:
        for obj in objs:
            if self.rich:
                from IPython.display import display

                display(obj)
            elif hasattr(obj, "claim") and hasattr(obj, "outcome"):
                print(result_text(obj))
            elif isinstance(obj, str):
                print(obj)
            else:
                try:
                    import sympy as sp

                    print(sp.pretty(obj, use_unicode=True) if isinstance(obj, (sp.Basic, sp.MatrixBase))
                          else str(obj))
                except Exception:  # pragma: no cover
                    print(obj)

    def show(self, *claim_ids: str) -> None:
        """Run the claims (registry ids; cached outcomes are reused) and display their results."""
        from .runner import keep_workers, run

        for cid in claim_ids:
            with keep_workers(self.workers):
                r = run([REGISTRY[cid]], manifest=False)[0]
            self.shown[cid] = r.status
            self.display(r)

    def expect(self, expected: dict[str, str]) -> None:
        """Assert that exactly the expected claims were shown, with the expected statuses."""
        diffs = [f"{cid}: expected {st}, got {self.shown.get(cid, 'not shown')}"
                 for cid, st in expected.items() if self.shown.get(cid) != st]
        diffs += [f"{cid}: shown ({st}) but not expected" for cid, st in self.shown.items()
                  if cid not in expected]
        if diffs:
            raise AssertionError("claim outcomes changed:\n  " + "\n  ".join(diffs))
