r"""float64 orbits: fused kernel for one state or an ensemble, the general path, per-state errors.

:func:`float_orbit` (behind :func:`~symbt.numeric.bt_orbit` for float64 input)

* one state (``p`` of shape ``(N,)``, scalar ``lam0, mu``): the single-orbit
  kernel of :mod:`symbt.numeric.float64.kernels` (numba if installed, else the same source as plain
  Python);
* an ensemble (``p`` of shape ``batch + (N,)``; ``lam0, mu`` scalars or
  broadcastable to ``batch``): the block kernel, ``prange`` over blocks of
  states on all cores (numba), else the vectorised numpy general path;
* every state the kernel does not finish (no real map, renormalisation,
  non-finite intermediates) is recomputed from the start by the *general
  path*: :func:`~symbt.numeric.core.step.step_core` on numpy arrays, with the
  monodromy renormalised where needed, the centre of mass carried
  separately (compensated sum), and a status per state.  The general path
  decides the error: :class:`NoRealMapError` if some state has no real map
  (``where`` lists *all* such states, ``condition`` is that of the first),
  else :class:`NumericRangeError`.

Stored states: steps ``0, every, 2 every, ...`` and always the last one
(:func:`~symbt.numeric.float64.kernels.stored_steps`), shape ``(rows,) + batch + (N,)``.

Example
-------
>>> import numpy as np
>>> from symbt.numeric.float64.orbit import float_orbit
>>> P, Q = float_orbit(np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9]), 10.0, 5.0, 100, every=50)
>>> P1, _ = float_orbit([-20.0, 10, 1], [1.0, 0, 0.9], 10.0, 5.0, 50)
>>> P.shape, bool(np.array_equal(P[1], P1[-1]))
((3, 3), True)
"""

from __future__ import annotations

from typing import TYPE_CHECKING, get_args

import numpy as np

from ..core.context import FLOAT, FloatParam, FloatValue
from ..core.errors import InvalidInputError, NoRealMapError, NumericRangeError
from ..core.inputs import check_branch, check_steps, prepare_spectral_pair, validate_float_pair
from ..core.limits import ILLCOND, MAX_DQ_FLOAT64, OK, POSITIVITY, RANGE, TRACE1, TRACE2
from ..core.problem import Float64Backend, Problem
from ..core.step import BLOCK_ELEMENTS, float_status, step_core
from .jit import kernel, numba_available
from .kernels import ANCHOR, orbit_rows
from .rows import escalate_rows, float_rows_step

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]

__all__ = ["float_orbit", "kernel_step", "kernel_batch_step", "general_orbit", "float_orbit_low", "raise_for_status",
           "ORBIT_BACKENDS", "check_orbit_backend"]

#: accepted ``backend`` values for float64 orbits
ORBIT_BACKENDS: tuple[Float64Backend, ...] = get_args(Float64Backend)


def check_orbit_backend(backend: str) -> None:
    """:class:`InvalidInputError` unless ``backend`` is one of :data:`ORBIT_BACKENDS`.

    >>> check_orbit_backend("qd")
    Traceback (most recent call last):
    ...
    symbt.numeric.core.errors.InvalidInputError: backend must be one of ('auto', 'numba', 'python', 'numpy'), got 'qd'
    """
    if backend not in ORBIT_BACKENDS:
        raise InvalidInputError("backend must be one of %s, got %r" % (ORBIT_BACKENDS, backend))
_PY_ERRORS = (FloatingPointError, ZeroDivisionError, OverflowError, ValueError)


def _block_rows(N: int) -> int:
    """States per block of the ensemble kernel (the block's work arrays stay in L1)."""
    return max(8, min(64, 2048 // N))


def _single(p: F64, q: F64, lam0: float, mu: float, branch: int, n: int, every: int,
            backend: str, low: bool = False) -> tuple[F64, F64, int]:
    fn, be = kernel("orbit", backend)
    rows = orbit_rows(n, every)
    P = np.empty((rows, p.size))
    Q = np.empty((rows, 2 * p.size if low else p.size))     # low: the positions' low parts beside them
    args = (p, q, lam0 + mu, lam0 - mu, 2.0 * mu, branch, n, every, ANCHOR, P, Q)
    if be == "numba":
        return P, Q, int(fn(*args))
    try:   # plain Python: a math range error or a numpy op under errstate raises -- a range failure
        with np.errstate(all="raise"):
            st = int(fn(*args))
    except _PY_ERRORS:
        st = RANGE
    return P, Q, st


def kernel_step(p: F64, q: F64, lam0: float, mu: float, branch: int,
                backend: str = "auto") -> tuple[F64, F64] | None:
    """One step of one state by the fused kernel, or ``None`` if the kernel cannot finish it.

    >>> import numpy as np
    >>> pt, qt = kernel_step(np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9]), 10.0, 5.0, 1)
    >>> np.round(qt, 8).tolist()
    [-0.08614224, 0.51984972, 1.88339323]
    """
    P, Q, st = _single(p, q, lam0, mu, branch, 1, 1, "auto" if backend == "auto" else backend)
    return (P[1], Q[1]) if st == OK else None


def kernel_batch_step(pa: F64, qa: F64, lam0: FloatParam, mu: FloatParam, branch: int, allow_complex: bool,
                      shape: tuple[int, ...], skip: npt.NDArray[np.bool_] | None = None,
                      ) -> tuple[FloatValue, FloatValue]:
    """One step of a validated batch ``pa, qa`` (M, N), each member by its single-state route.

    ``skip`` (optional, shape (M,)): members sent to the numpy route without a kernel attempt.

    The block kernel steps every member with ``mu != 0`` (each bit-identical to :func:`kernel_step`); the
    members it hands back are recomputed by the numpy route (:func:`~symbt.numeric.float64.rows.float_rows_step`),
    as the single-state step does, which decides existence and raises the typed errors (``where``: every
    failing member).

    >>> import numpy as np
    >>> pt, qt = kernel_batch_step(np.array([[-20.0, 10, 1]] * 2), np.array([[1.0, 0, 0.9]] * 2), 10.0,
    ...                            np.array([5.0, 0.0]), 1, False, (2,))
    >>> np.round(pt, 8).tolist()
    [[-19.99656766, 9.78635495, 1.21021272], [-20.0, 10.0, 1.0]]
    """

    M, N = pa.shape
    P = np.empty((2, M, N))
    Q = np.empty((2, M, N))
    P[1], Q[1] = pa, qa                      # mu == 0: the identity
    status = np.zeros(M, np.int64)
    moving = np.broadcast_to(mu, (M,)) != 0
    act = np.flatnonzero(moving if skip is None else moving & ~skip)
    if act.size:
        _ensemble(pa, qa, lam0, mu, branch, 1, 1, "numba", act, P, Q, status)
    todo = act[status[act] != OK]
    if skip is not None:
        todo = np.union1d(todo, np.flatnonzero(moving & skip))
    if todo.size == 0:
        return P[1], Q[1]
    return float_rows_step(pa, qa, lam0, mu, branch, allow_complex, shape, rows=todo, out=(P[1], Q[1]))


def general_orbit(pa: F64, qa: F64, lam0: FloatParam, mu: FloatParam, branch: int, n: int, every: int,
                  P: F64, Q: F64, rows: npt.NDArray[np.intp]) -> tuple[I64, I64]:
    """The general (numpy) path for the states ``rows`` of ``pa, qa``; fills ``P[:, rows], Q[:, rows]``.

    ``lam0, mu``: floats or arrays of shape (M,).  Returns ``(status, step)``
    per state of ``rows`` (status codes of :mod:`symbt.numeric.float64.kernels`; ``step`` = the
    step that failed).

    >>> import numpy as np
    >>> P, Q = np.empty((3, 1, 3)), np.empty((3, 1, 3))
    >>> st, k = general_orbit(np.array([[-20.0, 10, 1]]), np.array([[1.0, 0, 0.9]]), 10.0, 5.0, 1, 2, 1,
    ...                       P, Q, np.arange(1))
    >>> st.tolist(), np.round(P[1, 0], 8).tolist()
    ([0], [-19.99656766, 9.78635495, 1.21021272])
    """
    N = pa.shape[1]
    status = np.zeros(rows.size, np.int64)
    fail = np.zeros(rows.size, np.int64)
    block = max(256, BLOCK_ELEMENTS // N)
    for b0 in range(0, rows.size, block):
        idx = rows[b0:b0 + block]
        st, fs = _general_block(pa[idx], qa[idx], _take(lam0, idx), _take(mu, idx), branch, n, every, P, Q, idx)
        status[b0:b0 + block] = st
        fail[b0:b0 + block] = fs
    return status, fail


def _take(x: FloatParam, idx: npt.NDArray[np.intp]) -> FloatParam:
    return np.asarray(x)[idx] if np.ndim(x) else x


def _general_block(p0: F64, q0: F64, lam0: FloatParam, mu: FloatParam, branch: int, n: int, every: int,
                   P: F64, Q: F64, idx: npt.NDArray[np.intp]) -> tuple[I64, I64]:
    m, N = p0.shape
    status = np.zeros(m, np.int64)
    fail = np.zeros(m, np.int64)
    P[0, idx] = p0
    Q[0, idx, :N] = q0
    if Q.shape[-1] > N:
        Q[0, idx, N:] = 0.0
    # site lists (what step_core takes); the centre of mass is carried separately (compensated
    # two-sum): the rounding of q at |q| ~ 500 would otherwise perturb the relative coordinates
    c_hi = np.mean(q0, axis=-1)
    c_lo = np.zeros(m)
    pc = [p0[:, j].copy() for j in range(N)]
    qr = [q0[:, j] - c_hi for j in range(N)]
    alive = np.arange(m)
    row = 1
    for i in range(1, n + 1):
        full = alive.size == m
        Ps = pc if full else [x[alive] for x in pc]
        Qs = qr if full else [x[alive] for x in qr]
        L0, MU = (lam0, mu) if full else (_take(lam0, alive), _take(mu, alive))
        with np.errstate(all="ignore"):
            far = np.maximum.reduce([np.abs(Qs[(j + 1) % N] - Qs[j]) for j in range(N)]) > MAX_DQ_FLOAT64
            far = far | ~np.isfinite(np.add.reduce(Ps) + np.add.reduce(Qs))
            if far.any():            # beyond the float64 range of the scaled formulation
                keep = ~far
                status[alive[far]], fail[alive[far]] = RANGE, i
                alive = alive[keep]
                Ps, Qs = [x[keep] for x in Ps], [x[keep] for x in Qs]
                L0, MU = _take(L0, np.flatnonzero(keep)), _take(MU, np.flatnonzero(keep))
                full = False
            if alive.size == 0:
                break
            Pn, Qn, aux = step_core(FLOAT, Ps, Qs, L0, MU, branch, check_real=False)
        st = float_status(aux, Pn, Qn)
        ill = np.flatnonzero(st == ILLCOND)
        if ill.size:                 # this step of these states at higher precision (rows.escalate_rows)
            rows_ill = alive[ill]
            pin = np.stack([x[ill] for x in Ps], axis=-1)
            if i == 1:               # the given input exactly (not its rounded re-centred copy)
                ep, eq, est = escalate_rows(pin, q0[rows_ill], _take(L0, ill), _take(MU, ill), branch)
                eq = eq - c_hi[rows_ill][:, None]
            else:                    # the carried state's relative coordinates (the map commutes with q -> q + c)
                ep, eq, est = escalate_rows(pin, np.stack([x[ill] for x in Qs], axis=-1), _take(L0, ill),
                                            _take(MU, ill), branch)
            Pn = [np.array(np.broadcast_to(x, st.shape)) for x in Pn]
            Qn = [np.array(np.broadcast_to(x, st.shape)) for x in Qn]
            for j in range(N):
                Pn[j][ill], Qn[j][ill] = ep[:, j], eq[:, j]
            st[ill] = est
        good = st == OK
        if not good.all():
            bad = ~good
            status[alive[bad]], fail[alive[bad]] = st[bad], i
            Pn, Qn = [x[good] for x in Pn], [x[good] for x in Qn]
            alive = alive[good]
            full = False
        s = np.add.reduce(Qn) / N
        t = (c_hi if full else c_hi[alive]) + s                          # two-sum (Knuth)
        hi = c_hi if full else c_hi[alive]
        bp = t - hi
        lo = (c_lo if full else c_lo[alive]) + ((hi - (t - bp)) + (s - bp))
        if full:
            pc, qr, c_hi, c_lo = Pn, [x - s for x in Qn], t, lo
        else:
            for j in range(N):
                pc[j][alive] = Pn[j]
                qr[j][alive] = Qn[j] - s
            c_hi[alive], c_lo[alive] = t, lo
        if i % every == 0 or i == n:
            P[row, idx] = np.stack(pc, axis=-1)
            rel = [c_lo + x for x in qr]
            Q[row, idx, :N] = np.stack([c_hi + x for x in rel], axis=-1)
            if Q.shape[-1] > N:      # the low parts: (c_hi - y) is exact, y = fl(c_hi + rel)
                Q[row, idx, N:] = np.stack([(c_hi - y) + x for x, y in zip(rel, Q[row, idx, :N].T)], axis=-1)
            row += 1
        if alive.size == 0:
            break
    return status, fail


_MESSAGES = {
    TRACE1: "no real Bäcklund map: |tr L(lam1 = lam0 + mu)| <= 2, the spectral parameter lies in a band",
    TRACE2: "no real Bäcklund map: |tr L(lam2 = lam0 - mu)| <= 2, the spectral parameter lies in a band",
    POSITIVITY: "no real Bäcklund map: some Etilde_j = E_j - x_j <= 0 (lam1 and lam2 lie in different "
                "spectral gaps)",
    RANGE: "the float64 orbit left the range of the scaled formulation (|q_{j+1} - q_j| > 700, overflow "
           "or a non-finite intermediate); use mpmath inputs",
}


def raise_for_status(status: I64, step: I64, shape: tuple[int, ...]) -> None:
    """Raise the typed error for the failed states (``status != 0``), if any.

    :class:`NoRealMapError` if some state has no real map (``where``: all of
    them as batch indices; ``condition`` of the first), else
    :class:`NumericRangeError`.  The message ends ``(at step s; batch index
    i1, ..., i5, ...; K state(s) in all)``: the first five failing members,
    ``, ...`` only if there are more, and their count.

    >>> import numpy as np
    >>> try:
    ...     raise_for_status(np.array([0, 3, 1]), np.array([0, 4, 1]), (3,))
    ... except NoRealMapError as e:
    ...     print(e.condition, e.where)
    positivity ((1,), (2,))
    """
    bad = np.flatnonzero(status != OK)
    if bad.size == 0:
        return
    nomap = bad[np.isin(status[bad], (TRACE1, TRACE2, POSITIVITY))]
    sel = nomap if nomap.size else bad
    first = int(sel[0])
    code = int(status[first])
    where = [tuple(int(i) for i in np.unravel_index(k, shape)) for k in sel] if shape else []
    txt = " (at step %d" % step[first]
    if shape:
        txt += "; batch index %s%s; %d state(s) in all" % (
            ", ".join(map(str, where[:5])), ", ..." if len(where) > 5 else "", len(where))
    txt += ")"
    if nomap.size:
        raise NoRealMapError(_MESSAGES[code] + txt, condition="positivity" if code == POSITIVITY else "trace",
                             where=where)
    raise NumericRangeError(_MESSAGES[RANGE] + txt)


def float_orbit(p: npt.ArrayLike, q: npt.ArrayLike, lam0: npt.ArrayLike, mu: npt.ArrayLike, n: int, *,
                branch: int = 1, every: int = 1, backend: Float64Backend = "auto") -> tuple[F64, F64]:
    """``n`` steps of the float64 map from one state or an ensemble (see module docstring).

    ``backend``: ``"auto"``, ``"numba"``, ``"python"`` (plain-Python kernel;
    for ensembles the block kernel, slow -- for tests) or ``"numpy"`` (the
    general path only).

    >>> P, Q = float_orbit(np.tile([-20.0, 10, 1], (2, 1)), np.tile([1.0, 0, 0.9], (2, 1)), 10.0, [5.0, 0.0], 3)
    >>> P.shape, bool(np.array_equal(P[3, 1], P[0, 1]))       # mu = 0: the identity
    ((4, 2, 3), True)
    """
    check_orbit_backend(backend)
    branch = check_branch(branch)
    n, every = check_steps(n, every)
    pa, qa, shape = validate_float_pair(p, q)
    l0, m = prepare_spectral_pair(FLOAT, lam0, mu, shape)
    return validated_float_orbit(pa, qa, shape, l0, m, n, branch, every, backend)


def prepared_float_orbit(pr: Problem, backend: str) -> tuple[F64, F64]:
    """:func:`float_orbit` of a validated problem (:func:`~symbt.numeric.core.problem.prepare`)."""
    return validated_float_orbit(pr.p, pr.q, pr.shape, pr.lam0, pr.mu, pr.n, pr.branch, pr.every, backend)


def float_orbit_low(pr: Problem, backend: str) -> tuple[F64, F64, F64]:
    """:func:`prepared_float_orbit` with the low parts of the stored positions: ``(P, Q, Q_low)``.

    ``Q`` is bit for bit the ``Q`` of :func:`prepared_float_orbit`; ``Q_low`` is what rounding the
    carried position (double-double: kernels and general path alike) to ``Q`` dropped, so ``Q + Q_low``
    is each position to about ``2**-104`` relative and the differences ``q_{j+1} - q_j`` are free of
    the rounding at ``ulp(|q|)`` (docs/numeric.md, "Long orbits").

    >>> from symbt.numeric.core.problem import prepare
    >>> P, Q, L = float_orbit_low(prepare([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, n=2), "auto")
    >>> Q.shape == L.shape == (3, 3), bool(np.all(np.abs(L) <= np.spacing(np.abs(Q)) / 2))
    (True, True)
    """
    P, Q = validated_float_orbit(pr.p, pr.q, pr.shape, pr.lam0, pr.mu, pr.n, pr.branch, pr.every, backend,
                                 low=True)
    N = pr.p.shape[-1]
    return P, np.ascontiguousarray(Q[..., :N]), np.ascontiguousarray(Q[..., N:])


def validated_float_orbit(pa: F64, qa: F64, shape: tuple[int, ...], lam0: FloatParam, mu: FloatParam, n: int,
                          branch: int, every: int, backend: str, low: bool = False) -> tuple[F64, F64]:
    """:func:`float_orbit` on inputs already checked (``validate_float_pair``, ``prepare_spectral_pair``):
    ``pa, qa`` of shape ``(M, N)``, ``shape`` the batch shape; for callers that validated them already.
    ``low``: ``Q`` has ``2 N`` columns, the positions and their low parts (:func:`float_orbit_low`)."""
    M, N = pa.shape
    rows = orbit_rows(n, every)
    W = 2 * N if low else N
    if shape == () and backend != "numpy":
        if mu == 0 or n == 0:
            q0 = np.concatenate([qa, np.zeros_like(qa)], axis=-1) if low else qa
            return np.repeat(pa, rows, axis=0), np.repeat(q0, rows, axis=0)
        P1, Q1, st1 = _single(np.ascontiguousarray(pa[0]), np.ascontiguousarray(qa[0]), float(lam0),
                              float(mu), branch, n, every, backend, low)
        if st1 == OK:
            return P1, Q1
    P = np.empty((rows, M, N))
    Q = np.empty((rows, M, W))
    status = np.zeros(M, np.int64)
    step = np.zeros(M, np.int64)
    muv = np.broadcast_to(mu, (M,))
    act = np.flatnonzero(muv != 0) if n else np.arange(0)
    idle = np.flatnonzero(muv == 0) if n else np.arange(M)
    P[:, idle] = pa[idle]
    Q[:, idle, :N] = qa[idle]
    Q[:, idle, N:] = 0.0
    todo = act
    use_kernel = shape != () and (backend in ("numba", "python") or (backend == "auto" and numba_available()))
    if use_kernel and act.size:
        _ensemble(pa, qa, lam0, mu, branch, n, every, backend, act, P, Q, status)
        todo = act[status[act] != OK]
    if todo.size:
        st, fs = general_orbit(pa, qa, lam0, mu, branch, n, every, P, Q, todo)
        status[todo], step[todo] = st, fs
    raise_for_status(status, step, shape)
    return P.reshape((rows,) + shape + (N,)), Q.reshape((rows,) + shape + (W,))


def _ensemble(pa: F64, qa: F64, lam0: FloatParam, mu: FloatParam, branch: int, n: int, every: int, backend: str,
              act: npt.NDArray[np.intp], P: F64, Q: F64, status: I64) -> None:
    fn, be = kernel("ensemble", "numba" if backend == "auto" else backend)
    M, N = pa.shape
    full = act.size == M
    l0 = np.broadcast_to(lam0, (M,))[act]
    m = np.broadcast_to(mu, (M,))[act]
    p0 = np.ascontiguousarray(pa if full else pa[act])
    q0 = np.ascontiguousarray(qa if full else qa[act])
    rows = P.shape[0]
    outP = P if full else np.empty((rows, act.size, N))
    outQ = Q if full else np.empty((rows, act.size, Q.shape[-1]))
    st = np.zeros(act.size, np.int64)
    args = (p0, q0, l0 + m, l0 - m, 2.0 * m, branch, n, every, ANCHOR, _block_rows(N), outP, outQ, st)
    if be == "numba":
        fn(*args)
    else:
        try:
            with np.errstate(all="raise"):
                fn(*args)
        except _PY_ERRORS:
            st[:] = RANGE
    if not full:
        P[:, act] = outP
        Q[:, act] = outQ
    status[act] = st
