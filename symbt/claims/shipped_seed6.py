r"""The numpy route's rows written into a caller's arrays (scene ``numeric-paths``; issue 21, seed 6's
``rows:209``).

* ``paths.rows_out.n3`` -- :func:`~symbt.numeric.float64.rows.float_rows_step` with ``rows`` and ``out`` (how the
  batched kernel step hands back the members its kernel gave up on): the rows named are stepped, the others are
  taken from ``out`` (its docstring), and the result is written into ``out``'s arrays.  Three rows -- the paper's
  state, another state, the paper's state shifted by 1/2 in ``q`` -- with ``rows = [0, 2]`` and ``out`` filled with
  ``+7`` (``p``) and ``-7`` (``q``): row 1 of the result is ``out``'s row 1 exactly, rows 0 and 2 are within
  ``1e-12 (1 + |x|)`` of the literal map at 40 digits (the paper's state is well conditioned: the float64 step is
  ~1e-15 off there), ``p~`` in ``out[0]`` and ``q~`` in ``out[1]``.

Shown to fail on planted bugs in ``tests/test_killers_controls.py``.

>>> rows_out(3).status
'verified'
"""
from __future__ import annotations

import mpmath as mp
import numpy as np

from .base import Outcome, claim, failed

#: paths.rows_out: the three rows (p, q), lam0, mu, the rows stepped, the fill of out (p, q)
ROWS_P = ((-20.0, 10.0, 1.0), (1.0, -2.0, 0.5), (-20.0, 10.0, 1.0))
ROWS_Q = ((1.0, 0.0, 0.9), (0.0, 0.3, -0.2), (1.5, 0.5, 1.4))
ROWS_LAM0, ROWS_MU, ROWS_STEPPED, ROWS_FILL = 10.0, 5.0, (0, 2), (7.0, -7.0)


@claim("paths.rows_out", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/rows.py: float_rows_step(rows=..., out=...)",
       statement="float_rows_step on 3 rows (N={N}) with rows = [0, 2] and out filled with +7 (p) and -7 (q): row 1 "
                 "is out's row 1 exactly, rows 0 and 2 within 1e-12 (1 + |x|) of the literal map at 40 digits, p~ "
                 "written into out[0] and q~ into out[1]")
def rows_out(N: int) -> Outcome:
    from ..numeric.float64.rows import float_rows_step
    from ..reference.literal import literal_step

    pa, qa = np.array(ROWS_P), np.array(ROWS_Q)
    out = (np.full(pa.shape, ROWS_FILL[0]), np.full(qa.shape, ROWS_FILL[1]))
    pt, qt = float_rows_step(pa, qa, ROWS_LAM0, ROWS_MU, 1, False, (len(pa),), rows=np.array(ROWS_STEPPED),
                             out=out)
    bad, worst = [], 0.0
    if pt is not out[0] or qt is not out[1]:
        bad.append("the result is not written into out's arrays (p~ into out[0], q~ into out[1])")
    for i in range(len(pa)):
        if i not in ROWS_STEPPED:
            if not (np.all(pt[i] == ROWS_FILL[0]) and np.all(qt[i] == ROWS_FILL[1])):
                bad.append(f"row {i} (not stepped): {pt[i].tolist()}, {qt[i].tolist()}, not out's row")
            continue
        with mp.workdps(40):
            rp, rq, _ = literal_step([mp.mpf(v) for v in pa[i]], [mp.mpf(v) for v in qa[i]], mp.mpf(ROWS_LAM0),
                                     mp.mpf(ROWS_MU), 1)
            ref = [float(v) for v in rp + rq]
        got = list(pt[i]) + list(qt[i])
        err = max(abs(a - b) / (1 + abs(b)) for a, b in zip(got, ref))
        worst = max(worst, err)
        if not err <= 1e-12:
            bad.append(f"row {i}: {err:.3g} (relative to 1 + |x|) from the literal map")
    detail = f"rows {list(ROWS_STEPPED)} stepped, worst {worst:.2g} (accepted 1e-12); the other row out's"
    if bad:
        return failed("numeric: float_rows_step(rows, out) vs the literal map and out", detail="; ".join(bad))
    return Outcome("verified", "numeric: float_rows_step(rows, out) vs the literal map (40 digits) and out",
                   evidence="sampled", n_scope=[N], residual=worst, detail=detail)
