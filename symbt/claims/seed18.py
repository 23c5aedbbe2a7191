r"""Paths the claims did not reach (issue 21, seed 18).

* ``paths.many_rows.n3`` -- past ``SIDE_BY_SIDE_ROWS`` rows ``step_core(FLOAT)`` and ``float_status`` work site
  by site (lists over the sites, not stacked arrays): ``paths.threshold``'s scans (both sides of ``KAPPA_MAX``)
  repeated to 2304 rows give the bits and statuses of the same rows in batches of one scan (a consistency check
  of the two forms of one computation).  And ``bt_orbit``'s block ensemble (the python backend: the kernel numba
  compiles, in plain Python) over one block - 1, one block and one block + 1 states gives each state's bits in a
  batch of the distinct states alone: a last block that is partial, full, or one state long (seed 18: a block
  count rounded up once too often made a batch of ``block - 1`` states fail as a whole).
"""
from __future__ import annotations

import numpy as np

from ._shipped import without_numba
from .base import Outcome, claim, failed


@claim("paths.many_rows", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/core/step.py: step_core past SIDE_BY_SIDE_ROWS rows (_over_sites site by site, "
             "float_status's condition test per site); core/condition.py: monodromy_and_abs's two calls",
       statement="step_core(FLOAT) and float_status on paths.threshold's scans (N={N}; per branch, repeated past "
                 "SIDE_BY_SIDE_ROWS rows) give the bits and statuses of the same rows in batches of one scan "
                 "(the stacked form), the statuses both OK and ILLCOND; bt_orbit's block ensemble (python) over one "
                 "block - 1, one block and one block + 1 states gives each state's bits in a batch of the distinct "
                 "states")
def many_rows(N: int) -> Outcome:
    from ..numeric.core.condition import SIDE_BY_SIDE_ROWS
    from ..numeric.core.context import FLOAT
    from ..numeric.core.limits import ILLCOND, OK
    from ..numeric.core.step import float_status, step_core
    from .shipped_routes import threshold_states

    def run(rows: list, b: int) -> tuple[np.ndarray, np.ndarray]:
        pa, qa = np.array([st[0] for st in rows]), np.array([st[1] for st in rows])
        l0, m = np.array([st[2] for st in rows]), np.array([st[3] for st in rows])
        with np.errstate(all="ignore"):
            Pn, Qn, aux = step_core(FLOAT, list(pa.T.copy()), list(qa.T.copy()), l0, m, b, check_real=False)
            status = float_status(aux, Pn, Qn)
        return np.concatenate([np.array(Pn), np.array(Qn)]).T, np.asarray(status)

    bad: list[str] = []
    counts = []
    for b in (1, -1):
        scans = [list(sts) for _, bb, sts in threshold_states() if bb == b]
        one = [st for sts in scans for st in sts]
        rows = one * (SIDE_BY_SIDE_ROWS // len(one) + 1)
        X, st = run(rows, b)
        parts = [run(sts, b) for sts in scans]
        Xs = np.concatenate([x for x, _ in parts] * (len(rows) // len(one)))
        sts = np.concatenate([s for _, s in parts] * (len(rows) // len(one)))
        if not (np.array_equal(X, Xs, equal_nan=True) and np.array_equal(st, sts)):
            rows_off = np.flatnonzero(np.any((X != Xs) & ~(np.isnan(X) & np.isnan(Xs)), axis=1) | (st != sts))
            bad.append(f"branch {b}: {rows_off.size} of {len(rows)} rows differ (first {rows_off[:3].tolist()})")
        counts.append((len(rows), int(np.sum(st == OK)), int(np.sum(st == ILLCOND))))
        if not (np.any(st == OK) and np.any(st == ILLCOND)):
            bad.append(f"branch {b}: the statuses are not both OK and ILLCOND (the test would not see the estimate)")
    # the block ensemble (python backend) over M = one block - 1, one block, one block + 1 states: each row the
    # bits of the same state in a batch of the distinct states alone (a last block that is partial, full or one
    # state long)
    from ..codegen.verify import map_states
    from ..numeric import bt_orbit
    from ..numeric.float64.orbit import _block_rows

    states = map_states(N)
    block = _block_rows(N)

    def batch(idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        with without_numba(), np.errstate(all="ignore"):
            return bt_orbit(np.array([states[i][0] for i in idx]), np.array([states[i][1] for i in idx]),
                            np.array([states[i][2] for i in idx]), np.array([states[i][3] for i in idx]), 2,
                            backend="python")
    Pd, Qd = batch(np.arange(len(states)))
    for M in (block - 1, block, block + 1):
        idx = np.arange(M) % len(states)
        Pm, Qm = batch(idx)
        if not (np.array_equal(Pm, Pd[:, idx]) and np.array_equal(Qm, Qd[:, idx])):
            bad.append(f"the block ensemble over {M} states (blocks of {block}) differs from the distinct states' "
                       "batch")
    detail = "; ".join(f"{n} rows ({ok} OK, {ill} ILLCOND)" for n, ok, ill in counts) + \
        f" (SIDE_BY_SIDE_ROWS = {SIDE_BY_SIDE_ROWS}); block ensembles of {block - 1}, {block}, {block + 1} " \
        "states."
    if bad:
        return failed("numeric: step_core past SIDE_BY_SIDE_ROWS rows vs batches of one scan",
                      detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: step_core past SIDE_BY_SIDE_ROWS rows vs batches of one scan, bit for bit "
                   "(consistency)", evidence="sampled", n_scope=[N], detail=detail,
                   printed="the same bits and statuses")
