"""The numpy route of one float64 step for the rows of a batch, decided per row.

:func:`float_rows_step` steps the rows of a batch (``(M, N)`` arrays) in blocks of
``max(256, BLOCK_ELEMENTS // N)`` rows with :func:`~symbt.numeric.core.step.step_core`'s elementwise numpy
operations: a row's result and its verdict (real map or not, finite or not) never depend on the other rows
or on the block it falls in, so every member of a batch equals its own single-state step with
``backend="numpy"`` bit for bit, and a failing batch names every failing member in
:attr:`~symbt.numeric.core.errors.NoRealMapError.where`.

Example
-------
>>> import numpy as np
>>> pt, qt = float_rows_step(np.array([[-20.0, 10, 1]] * 3), np.array([[1.0, 0, 0.9]] * 3), 10.0,
...                          np.array([5.0, 0.0, 5.0]), 1, False, (3,))
>>> np.round(pt[:2], 8).tolist()
[[-19.99656766, 9.78635495, 1.21021272], [-20.0, 10.0, 1.0]]
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from ..core.context import COMPLEX, FLOAT, MP, FloatParam, FloatValue, MPValue
from ..core.errors import NoRealMapError, NumericRangeError
from ..core.limits import ILLCOND, MAX_DQ_FLOAT64, OK, POSITIVITY, RANGE, TRACE1, TRACE2
from ..core.step import BLOCK_ELEMENTS, float_status, mp_step, step_core
from . import existence
from .existence import decide_existence

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]

__all__ = ["float_rows_step", "raise_for_rows", "escalate_rows", "ESCALATION_DIGITS"]

#: working precisions (decimal digits) tried for an ill-conditioned float64 state; each is checked against a
#: second run with 20 more digits
ESCALATION_DIGITS = (40, 80, 160, 320)


def _mp_verdict(p: F64, q: F64, lam0: float, mu: float, branch: int, dps: int) -> tuple[int, list[MPValue]]:
    """One state ``(p, q)`` at ``dps`` digits through the mpmath step: ``(status, p~ + q~)``."""
    import mpmath

    with mpmath.workdps(dps):
        P = [mpmath.mpf(float(v)) for v in p]            # float64 values are exact binary numbers
        Q = [mpmath.mpf(float(v)) for v in q]
        try:
            Pn, Qn = mp_step(MP, P, Q, mpmath.mpf(float(lam0)), mpmath.mpf(float(mu)), branch, False)
        except NoRealMapError as err:
            if err.condition == "positivity":
                return POSITIVITY, []
            return (TRACE2 if "lam2" in str(err) else TRACE1), []
        except NumericRangeError:
            return RANGE, []
        return OK, list(Pn) + list(Qn)


def escalate_rows(pa: F64, qa: F64, lam0: FloatParam, mu: FloatParam, branch: int) -> tuple[F64, F64, I64]:
    """Recompute ill-conditioned float64 states (rows of ``pa, qa``) at higher precision.

    Each row goes through the mpmath step (:func:`~symbt.numeric.core.step.mp_step` on the exact binary values of
    its float64 input) at the digits of :data:`ESCALATION_DIGITS` in turn, each run repeated with 20 more
    digits; the first precision at which both runs agree -- the same verdict, and values equal to
    ``2**-64`` of the state's scale -- decides the row: the result rounded to float64.  A "no real map" the
    runs agree on is not taken on agreement: :func:`~.existence.decide_existence` decides it by interval
    arithmetic (the no-real-map status where it certainly holds; where the map certainly exists the higher
    precisions compute it; undecided: ``RANGE``).  A row not decided at the last precision gets ``RANGE``
    (:class:`NumericRangeError`).
    The map commutes with ``q -> q + c`` (it reads ``q`` through ``e^{q_{j+1} - q_j}`` only), so an orbit hands
    over its relative coordinates and adds its carried centre of mass to the result itself.

    >>> pt, qt, st = escalate_rows(np.array([[0.0, 0.0]]), np.array([[0.0, 0.0]]), 0.0, 2.0 ** -30, 1)
    >>> st.tolist()                               # tr L(+-2**-30) = 2**-60 - 2: inside the band
    [1]
    """
    import mpmath

    M, N = pa.shape
    outp, outq = pa.copy(), qa.copy()
    status = np.full(M, RANGE, np.int64)
    deadline = time.monotonic() + existence.BUDGET_S     # one existence budget for the batch, not per state
    for k in range(M):
        l0, m = float(_take(lam0, k)), float(_take(mu, k))
        exists = None                  # the interval verdict, once a no-real-map verdict asked for it
        for dps in ESCALATION_DIGITS:
            st, vals = _mp_verdict(pa[k], qa[k], l0, m, branch, dps)
            st2, vals2 = _mp_verdict(pa[k], qa[k], l0, m, branch, dps + 20)
            if st != st2:
                continue
            if st not in (OK, RANGE):  # agreement is not proof (chunks 86, 162, 188 of docs/fuzz.md)
                if exists is None:
                    exists = decide_existence(pa[k], qa[k], l0, m, branch, deadline=deadline)[0]
                if exists == OK:       # the map exists: a higher precision computes it
                    continue
                status[k] = RANGE if exists is None else exists
                break
            if st == OK:
                with mpmath.workdps(dps):
                    scale = max(max(abs(v) for v in vals2), abs(mpmath.mpf(l0)) + abs(mpmath.mpf(m)))
                    if max(abs(a - b) for a, b in zip(vals, vals2)) > scale * mpmath.mpf(2) ** -64:
                        continue
                x = np.array([float(v) for v in vals2])
                if not np.all(np.isfinite(x)):
                    break
                outp[k], outq[k] = x[:N], x[N:]
            status[k] = st
            break
    return outp, outq, status


def _float_block(pa: F64, qa: F64, lam0: FloatParam, mu: FloatParam, branch: int) -> tuple[F64, F64, I64]:
    """Real step for one block of rows ``pa, qa`` (B, N): ``(B, N)`` arrays and a status code per row.

    The codes are those of :mod:`symbt.numeric.core.limits` (``OK``, ``TRACE1``, ``TRACE2``, ``POSITIVITY``,
    ``RANGE``, ``ILLCOND``), decided per row (:func:`~symbt.numeric.core.step.float_status`), so that a row's
    verdict does not depend on the other rows of the batch; ill-conditioned rows are decided and computed by
    :func:`escalate_rows`.
    """
    P, Q = list(pa.T.copy()), list(qa.T.copy())
    with np.errstate(all="ignore"):
        Pn, Qn, aux = step_core(FLOAT, P, Q, lam0, mu, branch, check_real=False)
        outp = np.stack(Pn, axis=-1)
        outq = np.stack(Qn, axis=-1)
    status = float_status(aux, Pn, Qn)
    ill = np.flatnonzero(status == ILLCOND)
    if ill.size:                       # the float64 verdict or result is not trustworthy: higher precision
        ep, eq, est = escalate_rows(pa[ill], qa[ill], _take(lam0, ill), _take(mu, ill), branch)
        outp[ill], outq[ill], status[ill] = ep, eq, est
    return outp, outq, status


def _complex_rows(pa: F64, qa: F64, lam0: FloatParam, mu: FloatParam, branch: int) -> tuple[FloatValue, FloatValue]:
    """The complex continuation for rows ``pa, qa`` (B, N) without a real map."""
    Pc = [x.astype(np.complex128) for x in pa.T]
    Qc = [x.astype(np.complex128) for x in qa.T]
    with np.errstate(all="ignore"):
        Pn, Qn, _ = step_core(COMPLEX, Pc, Qc, lam0, mu, branch, check_real=False)
    return np.stack(Pn, axis=-1), np.stack(Qn, axis=-1)


_NO_MAP = {
    TRACE1: ("trace", "no real Bäcklund map: |tr L(lam1 = lam0 + mu)| <= 2, the spectral parameter lies in a band"),
    TRACE2: ("trace", "no real Bäcklund map: |tr L(lam2 = lam0 - mu)| <= 2, the spectral parameter lies in a band"),
    POSITIVITY: ("positivity", "no real Bäcklund map: some Etilde_j = E_j - x_j <= 0 (lam1 and lam2 lie in "
                 "different spectral gaps)"),
}


def raise_for_rows(status: I64, shape: tuple[int, ...]) -> None:
    """Raise the typed error of one step for the rows with ``status != OK``, if any.

    :class:`NoRealMapError` if some row has no real map -- ``where`` names *every* such row of the batch
    (batch indices), ``condition`` and message are those of the first -- else :class:`NumericRangeError`.

    >>> import numpy as np
    >>> from symbt.numeric.core.limits import OK, POSITIVITY, TRACE2
    >>> try:
    ...     raise_for_rows(np.array([OK, TRACE2, OK, POSITIVITY]), (2, 2))
    ... except NoRealMapError as e:
    ...     print(e.condition, e.where)
    trace ((0, 1), (1, 1))
    """
    bad = np.flatnonzero(status != OK)
    if bad.size == 0:
        return
    nomap = bad[status[bad] != RANGE]
    sel = nomap if nomap.size else bad
    where = [tuple(int(i) for i in np.unravel_index(k, shape)) for k in sel] if shape else []
    txt = ""
    if shape:
        txt = " (batch index %s%s; %d state(s) in all)" % (
            ", ".join(map(str, where[:5])), ", ..." if len(where) > 5 else "", len(where))
    if nomap.size:
        condition, message = _NO_MAP[int(status[nomap[0]])]
        raise NoRealMapError(message + txt, condition=condition, where=where)
    raise NumericRangeError("the float64 step left the range of the scaled formulation (|q_{j+1} - q_j| > 700, "
                            "overflow or a non-finite intermediate such as a degenerate eigenvector); use mpmath "
                            "inputs" + txt)


def float_rows_step(pa: F64, qa: F64, lam0: FloatParam, mu: FloatParam, branch: int, allow_complex: bool,
                    shape: tuple[int, ...], rows: npt.NDArray[np.intp] | None = None,
                    out: tuple[F64, F64] | None = None) -> tuple[FloatValue, FloatValue]:
    """The numpy route for the rows ``rows`` (flat indices; default all) of ``pa, qa`` (M, N).

    Rows are cut into blocks of ``max(256, BLOCK_ELEMENTS // N)``; every row is computed by the same
    elementwise operations whatever block it falls in, so each row equals its own single-state call with
    ``backend="numpy"`` bit for bit.  Rows with ``mu == 0`` are copies.  The other rows of the result are
    taken from ``out`` (default: copies of the input).  Existence is decided per row; a failing row raises
    (:func:`raise_for_rows`, ``where`` naming every failing row) unless ``allow_complex``, where exactly the
    rows without a real map are continued in complex arithmetic.
    """
    M, N = pa.shape
    idx_all = np.arange(M) if rows is None else rows
    if np.ndim(mu):
        idx_all = idx_all[np.asarray(mu)[idx_all] != 0]
    elif mu == 0:
        idx_all = idx_all[:0]
    outp: FloatValue = pa.copy() if out is None else out[0]
    outq: FloatValue = qa.copy() if out is None else out[1]
    status = np.zeros(M, np.int64)
    block = max(256, BLOCK_ELEMENTS // N)
    if idx_all.size:
        # out of the scaled formulation's range (what neighbour_ratios refuses for a whole block): per row
        dq = _largest_step(qa if rows is None and idx_all.size == M else qa[idx_all])
        far = ~(dq <= MAX_DQ_FLOAT64)
        status[idx_all[far]] = RANGE
        idx_all = idx_all[~far]
    for s0 in range(0, idx_all.size, block):
        sel = idx_all[s0:s0 + block]
        idx: npt.NDArray[np.intp] | slice = sel
        if sel[-1] - sel[0] + 1 == sel.size:          # contiguous rows (the usual case): views, not copies
            idx = slice(int(sel[0]), int(sel[-1]) + 1)
        bp, bq, st = _float_block(pa[idx], qa[idx], _take(lam0, idx), _take(mu, idx), branch)
        outp[idx], outq[idx] = bp, bq
        status[idx] = st
    nomap = np.flatnonzero((status != OK) & (status != RANGE))
    if allow_complex and nomap.size:
        cp, cq = _complex_rows(pa[nomap], qa[nomap], _take(lam0, nomap), _take(mu, nomap), branch)
        outp, outq = outp.astype(np.complex128), outq.astype(np.complex128)
        outp[nomap], outq[nomap] = cp, cq
        fin = np.isfinite(cp).all(axis=-1) & np.isfinite(cq).all(axis=-1)
        status[nomap] = np.where(fin, OK, RANGE)
    raise_for_rows(status, shape)
    return outp, outq


def _largest_step(q: F64) -> F64:
    """``max_j |q_{j+1} - q_j|`` (cyclic) of every row of ``q`` (R, N); NaN where a difference is NaN.

    The same differences and the same maximum as ``np.abs(np.roll(q, -1, axis=1) - q).max(axis=1)``, without
    the rolled copy: up to 8 sites column by column (a row-wise ``max`` over a few columns is slow: 100000
    rows of 3 sites, 0.4 ms against 15 ms), more sites into one array of the differences.

    >>> _largest_step(np.array([[0.0, 3.0, 1.0], [0.0, np.nan, 1.0]])).tolist()
    [3.0, nan]
    """
    N = q.shape[1]
    if N <= 8:
        out = np.abs(q[:, 1 % N] - q[:, 0])
        for j in range(1, N):
            np.maximum(out, np.abs(q[:, (j + 1) % N] - q[:, j]), out=out)
        return out
    d = np.empty_like(q)
    np.subtract(q[:, 1:], q[:, :-1], out=d[:, :-1])
    np.subtract(q[:, 0], q[:, -1], out=d[:, -1])
    return np.abs(d, out=d).max(axis=1)


def _take(x: FloatParam, idx: npt.NDArray[np.intp] | slice | int) -> FloatParam:
    return np.asarray(x)[idx] if np.ndim(x) else x
