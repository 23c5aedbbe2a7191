r"""Shared pieces of the claim modules: sample states by domain cell, residuals, outcomes from cell tables.

Sampled claims on the map draw their states cell by cell (:func:`map_cells`): the sign of
:math:`\operatorname{tr}L(\lambda_{1,2})` (equal at both points wherever the real map exists)
times the branch ``b = +-1``, ``per_cell`` states each (16 by default, 64 under
``--deep``), seeded so that every run samples the same points.  A check evaluates
the printed and the corrected statement at every sample; :func:`judge_cells`
turns the resulting :class:`~symbt.proof.cells.CellTable` into an
:class:`~symbt.claims.Outcome` whose ``cells`` and ``scope`` come from that table.

Multivalued functions (the rule applied to every claim alike): a printed statement
is evaluated *as printed* with principal branches -- ``log``, ``sqrt``, ``acosh`` of
mpmath at complex arguments where needed -- and compared as complex numbers; it
holds at a sample only if both sides agree there.  No reduction modulo
:math:`2\pi i`, no real part is taken.  A corrected statement states its branch
choices explicitly (``ln|.|``, ``sgn(tr) arccosh(|tr|/2)``, ``b sqrt(.)``).
"""
from __future__ import annotations

from collections.abc import Callable, Iterable
from functools import cache
from typing import Any

import mpmath as mp

from ..proof.cells import DEEP_PER_CELL, DEFAULT_PER_CELL, CellTable
from ..reference.literal import literal_step
from ..reference.samples import admissible_states, paper_state
from .base import Outcome
from .base import judge_cells as base_judge_cells

__all__ = ["DPS", "TOL", "fmt_state", "rel", "map_cells", "per_cell", "judge_cells", "eta_from_states",
           "lambdified", "cross"]

DPS = 60
TOL = mp.mpf(10) ** -40


def per_cell(deep: bool) -> int:
    return DEEP_PER_CELL if deep else DEFAULT_PER_CELL


def fmt_state(state: tuple, branch: int | None = None, **extra: Any) -> dict[str, Any]:
    p, q, l0, m = state
    d: dict[str, Any] = {"p": [mp.nstr(v, 15) for v in p], "q": [mp.nstr(v, 15) for v in q],
                         "lambda0": mp.nstr(l0, 15), "mu": mp.nstr(m, 15)}
    if branch is not None:
        d["branch"] = branch
    d.update({k: (v if isinstance(v, (int, str)) else mp.nstr(v, 15)) for k, v in extra.items()})
    return d


def rel(a: Any, b: Any) -> Any:
    return abs(a - b) / max(mp.mpf(1), abs(a), abs(b))


def cross(u: Any, v: Any) -> Any:
    return u[0] * v[1] - u[1] * v[0]


@cache
def _states(N: int, sign: int, count: int, seed: int) -> tuple:
    with mp.workdps(30):
        states = admissible_states(N, sign, count, seed=seed)
    return tuple((tuple(mp.nstr(v, 40) for v in p), tuple(mp.nstr(v, 40) for v in q), mp.nstr(l0, 40),
                  mp.nstr(m, 40)) for p, q, l0, m in states)


def map_cells(N: int, count: int, *, seed: int = 0, paper: bool = True) -> list[tuple[dict[str, Any], tuple, int]]:
    """``(cell, state, branch)`` for ``count`` states in each cell ``{branch, sign_tr}``.

    States are admissible (the real map exists for both branches); ``paper`` adds the
    paper's example (N = 3, tr L < -2 at both points, mu = 5) to its cells.
    """
    out = []
    for sign in (1, -1):
        for p, q, l0, m in _states(N, sign, count, seed):
            st = ([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m))
            for b in (1, -1):
                out.append(({"branch": b, "sign_tr": sign}, st, b))
    if paper and N == 3:
        for b in (1, -1):
            out.append(({"branch": b, "sign_tr": -1}, paper_state("5"), b))
    return out


def judge_cells(table: CellTable, *, method: str, printed: str, corrected: str | None = None,
                dps: int = DPS, detail: str = "") -> Outcome:
    """:func:`symbt.claims.base.judge_cells` with the claim modules' working precision (digits capped at ``DPS``)."""
    return base_judge_cells(table, printed=printed, corrected=corrected, method=method, dps=dps, detail=detail)


def eta_from_states(p: list, q: list, pt: list, qt: list, lam0: Any) -> list:
    """Recover eta_j from (p, q) and the image (p~, q~) alone, via eq. ``imptransf``.

    Per site: p~_j - p_j = eta_j - eta_{j+1} and (p~_j + lam0)(E_j - E~_j) = -(E~_j eta_j + E_j eta_{j+1}),
    so eta_j = (E_j (p~_j - p_j) - (p~_j + lam0)(E_j - E~_j)) / (E_j + E~_j).
    """
    out = []
    for j in range(len(p)):
        E, Et = mp.exp(q[j]), mp.exp(qt[j])
        out.append((E * (pt[j] - p[j]) - (pt[j] + lam0) * (E - Et)) / (E + Et))
    return out


def lambdified(args: Iterable[Any], expr: Any) -> Callable[..., Any]:
    """``sympy.lambdify`` to mpmath with plain argument names (symbols like ``lambda`` break the printer),
    memoised (:func:`symbt.proof.lambdify.plain_lambdify`)."""
    from ..proof.lambdify import plain_lambdify

    return plain_lambdify(args, expr, "mpmath")


def literal_image(state: tuple, branch: int) -> tuple[list, list, dict]:
    p, q, l0, m = state
    return literal_step(p, q, l0, m, branch)
