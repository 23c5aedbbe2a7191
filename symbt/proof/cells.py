r"""Domain cells: a sampled check records, per cell of its domain, where each statement holds.

A sampled claim partitions its domain into *cells* -- at least the branch
``b = +-1`` of :math:`\gamma_i = b\sqrt{\operatorname{tr}L(\lambda_i)^2-4}` and the sign of
:math:`\operatorname{tr}L` at :math:`\lambda_{1,2}` (equal wherever the real map exists); for
N = 2 also the elliptic regime, and any other split the statement is sensitive to
(e.g. the sign of :math:`q_1-q_2`).  Every cell is sampled (seeded, >= 16 states by
default).  :class:`CellTable` collects, per cell, how many samples there were, at how
many the printed and the corrected statement held, and the worst residual; its
:meth:`~CellTable.scope` sentence is *generated* from that table, never written by hand.

>>> t = CellTable(tol=1e-40)
>>> for b in (1, -1):
...     for s in (1, -1):
...         for _ in range(3):
...             t.add({"branch": b, "sign_tr": s}, printed=0.0 if (b, s) == (1, 1) else 2.0, corrected=1e-50)
>>> t.printed_holds_everywhere(), t.corrected_holds_everywhere()
(False, True)
>>> print(t.scope().replace("; ", ";\n").replace("fails in ", "fails in\n"))
printed statement holds exactly in cells {branch=+1, sign_tr=+1} and fails in
{branch=+1, sign_tr=-1}, {branch=-1, sign_tr=+1}, {branch=-1, sign_tr=-1};
corrected statement holds in all 4 cells
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any

from .verdict import Verdict

__all__ = ["CellTable", "CellStats", "cell_text", "DEFAULT_PER_CELL", "DEEP_PER_CELL"]

#: samples per cell in the default run and under ``--deep``
DEFAULT_PER_CELL = 16
DEEP_PER_CELL = 64


def _fmt_value(v: Any) -> str:
    if isinstance(v, bool):
        return str(v).lower()
    if isinstance(v, int):
        return f"{v:+d}"
    return str(v)


def cell_text(cell: dict[str, Any], label_only: tuple[str, ...] = ()) -> str:
    """``{branch=+1, sign_tr=-1}``; a coordinate named in ``label_only`` shows its value alone (the value
    of a sign split, ``t<t0``, already names the coordinate).

    >>> cell_text({"sign(t - t0)": "t<t0", "branch": -1}, label_only=("sign(t - t0)",))
    '{t<t0, branch=-1}'
    """
    return "{" + ", ".join(_fmt_value(v) if k in label_only else f"{k}={_fmt_value(v)}"
                           for k, v in cell.items()) + "}"


@dataclass
class CellStats:
    """Samples of one cell: counts and the worst residual of each statement."""

    cell: dict[str, Any]
    n: int = 0
    printed_holds: int = 0
    corrected_holds: int = 0
    printed_worst: float = 0.0
    corrected_worst: float = 0.0
    has_corrected: bool = False
    worst_point: dict[str, Any] | None = None

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"cell": dict(self.cell), "n": self.n, "printed_holds": self.printed_holds,
                             "worst_residual": self.printed_worst}
        if self.has_corrected:
            d["corrected_holds"] = self.corrected_holds
            d["corrected_worst_residual"] = self.corrected_worst
        return d


@dataclass
class CellTable:
    """Per-cell tallies of a sampled check (see the module docstring).

    ``method`` and ``dps`` say how the residuals were computed (a table filled by
    :meth:`symbt.proof.domain.Domain.evaluate` sets them; ``judge`` reads them);
    ``label_only`` names the coordinates shown by their value alone (see :func:`cell_text`).
    """

    tol: float
    rows: dict[tuple[tuple[str, Any], ...], CellStats] = field(default_factory=dict)
    method: str = ""
    dps: int | None = None
    label_only: tuple[str, ...] = ()

    def add(self, cell: dict[str, Any], *, printed: Any, corrected: Any = None,
            point: dict[str, Any] | None = None) -> None:
        """Record one sample: the relative residuals of the printed (and corrected) statement."""
        key = tuple(cell.items())
        row = self.rows.get(key)
        if row is None:
            row = self.rows[key] = CellStats(dict(cell))
        row.n += 1
        rp = float(abs(printed))
        if rp <= self.tol:
            row.printed_holds += 1
        if rp >= row.printed_worst:
            row.printed_worst = rp
            row.worst_point = point
        if corrected is not None:
            row.has_corrected = True
            rc = float(abs(corrected))
            row.corrected_holds += rc <= self.tol
            row.corrected_worst = max(row.corrected_worst, rc)

    # -- summaries ------------------------------------------------------------
    def cells(self) -> list[dict[str, Any]]:
        return [r.to_dict() for r in self.rows.values()]

    def printed_holds_everywhere(self) -> bool:
        return all(r.printed_holds == r.n for r in self.rows.values())

    def corrected_holds_everywhere(self) -> bool:
        return all(r.corrected_holds == r.n for r in self.rows.values())

    def worst(self, which: str = "printed") -> tuple[float, dict[str, Any] | None]:
        """The worst residual over all cells and where it occurred."""
        attr = "printed_worst" if which == "printed" else "corrected_worst"
        rows = list(self.rows.values())
        if not rows:
            return 0.0, None
        row = max(rows, key=lambda r: getattr(r, attr))
        text = cell_text(row.cell, self.label_only)
        return getattr(row, attr), (dict(row.worst_point or {}, cell=text) if which == "printed"
                                    else {"cell": text})

    def verdict(self, *, method: str | None = None, dps: int | None = None) -> Verdict:
        """The printed statement's sampled :class:`~symbt.proof.Verdict`: holds iff it held at every
        sample; the worst residual and where it occurred, the cells, and the scope sentence as ``note``.

        >>> t = CellTable(tol=1e-20, method="numeric: demo", dps=30)
        >>> t.add({"side": "x<0"}, printed=0.5, point={"x": "-1"}); t.add({"side": "x>0"}, printed=0.0)
        >>> v = t.verdict()
        >>> v.holds, v.counterexample
        (False, {'x': '-1', 'cell': '{side=x<0}'})
        >>> v.note
        'printed statement holds exactly in cells {side=x>0} and fails in {side=x<0}'
        """
        rp, where = self.worst("printed")
        return Verdict.sampled(rp, tol=self.tol, method=method or self.method or "numeric: sampled cells",
                               counterexample=where, dps=self.dps if dps is None else dps, cells=self.cells(),
                               note=self.scope())

    def scope(self) -> str:
        """Where the printed (and corrected) statement holds, generated from the table."""
        rows = list(self.rows.values())
        if not rows:
            return "no samples"
        text = functools.partial(cell_text, label_only=self.label_only)
        full = [text(r.cell) for r in rows if r.printed_holds == r.n]
        none = [text(r.cell) for r in rows if r.printed_holds == 0]
        part = [f"{text(r.cell)} ({r.printed_holds}/{r.n})" for r in rows if 0 < r.printed_holds < r.n]
        if len(full) == len(rows):
            txt = f"printed statement holds in all {len(rows)} cells"
        elif not full and not part:
            txt = f"printed statement fails in all {len(rows)} cells"
        else:
            bits = []
            if full:
                bits.append("holds exactly in cells " + ", ".join(full))
            if part:
                bits.append("holds at some samples of " + ", ".join(part))
            if none:
                bits.append("fails in " + ", ".join(none))
            txt = "printed statement " + " and ".join(bits)
        if any(r.has_corrected for r in rows):
            bad = [text(r.cell) for r in rows if r.corrected_holds < r.n]
            txt += ("; corrected statement holds in all %d cells" % len(rows) if not bad
                    else "; corrected statement FAILS in " + ", ".join(bad))
        return txt
