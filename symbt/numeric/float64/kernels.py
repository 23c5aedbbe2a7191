r"""Fused float64 orbit kernels: plain-Python source, compiled by numba on demand (:mod:`symbt.numeric.float64.jit`).

One arithmetic in two layouts: :func:`orbit` (one state, scalar code; this
module) and :func:`~symbt.numeric.float64.kernels_block.run_block` /
:func:`~symbt.numeric.float64.kernels_block.ensemble` (blocks of states, ``prange``
over blocks).  Both perform the same operations in the same order, so an
ensemble member equals the single-state orbit bit for bit, and the
plain-Python and numba versions are identical bit for bit too (IEEE doubles,
libm ``sqrt/exp/log/log1p``, no ``fastmath``; ``tests/test_numeric_fast.py``).

The step is that of :mod:`symbt.numeric.core.step` (scaled eigenvector slopes,
each transported in its contracting direction, cancellation-free read-out; ``lam + p_j`` formed at
the spectral parameters made consistent with ``two_mu`` by :mod:`symbt.numeric.core.spectral_sum`),
in the scalar form written once in :mod:`symbt.numeric.core.fused`: this module
holds its float64 arithmetic (:data:`OPERATIONS`: the operators themselves) and
hooks (:data:`HOOKS`: the condition estimate, the power-of-two rescaling, the
range tests, the update of the ratios and factors below) and the orbit driver.

Orbit variables.  The dynamics carries the neighbour ratios
``r_j = exp(q_{j+1} - q_j)`` (all a step needs) and updates them as the map
does, ``r~_j = r_j (1 + xr_{j+1}) / (1 + xr_j)`` with ``1 + xr_j = Etilde_j / E_j``,
computed as ``r_j + r_j d_j``, ``d_j = (xr_{j+1} - xr_j) / (1 + xr_j)``.  The
positions accumulate the factors ``F_j = prod(1 + xr_j)`` in double-double
(``F <- F + F xr``, no rounding of ``1 + xr``: small ``mu`` loses nothing) and
are flushed into a double-double ``q = qh + ql`` (``log F``) every ``anchor``
steps, when ``r`` is also re-anchored to ``exp`` of the double-double
differences.  Stored states read ``q = qh + ql + log F`` without touching the
state, so the orbit does not depend on ``every`` (bit for bit).  The inner step
has no transcendental function except two square roots and vectorises over
the states of a block; the rounding per step stays at the level of the exp/log1p formulation (``O(eps)`` in
``log r``) and ``q`` never rounds the
increments against ``|q|`` (the centre of mass can drift to ``|q| ~ 1e3``
without perturbing the relative coordinates).  After one step the result
equals :func:`~symbt.numeric.core.step.step_core`'s to an ulp.

Status codes per state (first failure wins): ``0`` ok, ``1``/``2``
``|tr L(lam1/lam2)| <= 2``, ``3`` some ``Etilde_j <= 0`` or ``tr L(lam1)``,
``tr L(lam2)`` of opposite signs (``lam1``, ``lam2`` in different gaps), ``4``
range problem (monodromy entries beyond ``1e290`` after the exact power-of-two rescaling, or both entries of its
first row at most ``1e-290`` there -- an entry strictly above is needed --, ``|q_{j+1} - q_j| > 700``, some
``|p_j|`` or ``|q_j|`` at least ``1e300``, a non-finite intermediate such as a degenerate eigenvector), ``5``
ill-conditioned (the float64 decision or result is not trustworthy: condition estimate ``kappa``
beyond :data:`KAPPA_MAX`, see :mod:`symbt.numeric.core.step`, "Existence and
accuracy").  The drivers recompute every failing state with the general path,
which decides the error (and recomputes an ill-conditioned state at higher
precision).

Example
-------
>>> import numpy as np
>>> from symbt.numeric.float64.kernels import orbit, orbit_rows, ANCHOR
>>> P, Q = np.empty((orbit_rows(2, 1), 3)), np.empty((orbit_rows(2, 1), 3))
>>> orbit(np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9]), 15.0, 5.0, 10.0, 1, 2, 1, ANCHOR, P, Q)
0
>>> np.round(P[1], 8).tolist()
[-19.99656766, 9.78635495, 1.21021272]
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core import limits
from ..core.compile import clone, instantiate
from ..core.condition import sharp_on_floats, sharp_trace_kappa
from ..core.fused import SOURCE
from ..core.limits import KAPPA_MAX, MAX_DQ_FLOAT64, OK, RANGE
from ..core.spectral_sum import lam_add, lam_split, root_slope

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]

Track = tuple[float, float, float, float, float, float, float]

__all__ = ["orbit", "python_orbit", "python_orbit_with", "orbit_rows", "stored_steps", "python_kernels",
           "cheap_kernels", "sharp_compiled", "ANCHOR", "HOOKS", "OPERATIONS"]
# monodromy entries past _BIG are multiplied by _SHRINK (powers of two: exact, the slopes only need ratios),
# so that |tr L| ~ 1e300 and beyond (N = 256 far from the spectrum) stays in the kernel; the product of the
# absolute values (>= the monodromy entrywise) decides when, and is scaled alike
_BIG = 2.0 ** 400
_SHRINK = 2.0 ** -400

# the limits and the sharp condition (core/condition.py) are compiled into the step: their files belong to its
# cache key (core/compile.py)
_EXTRA = (Path(limits.__file__), Path(limits.__file__).with_name("condition.py"))

#: steps between re-anchoring ``r`` to ``exp`` of the accumulated positions
ANCHOR = 16


def orbit_rows(n: int, every: int) -> int:
    """Number of stored states: steps ``0, every, 2 every, ...`` and always ``n``.

    >>> orbit_rows(10, 3), orbit_rows(9, 3), orbit_rows(0, 5)
    (5, 4, 1)
    """
    return 1 + -(-n // every)


def stored_steps(n: int, every: int) -> list[int]:
    """The step numbers of the stored states (see :func:`orbit_rows`).

    >>> stored_steps(10, 3)
    [0, 3, 6, 9, 10]
    """
    out = list(range(0, n + 1, every))
    if out[-1] != n:
        out.append(n)
    return out


def _logf(fh: float, fl: float) -> float:
    """``log(fh + fl)`` for a double-double factor (NaN outside ``(1e-300, 1e300)``).

    >>> _logf(1.0, 0.0), round(_logf(2.0, 0.0), 12)
    (0.0, 0.69314718056)
    """
    if not (fh > 1e-300 and fh < 1e300):
        return math.nan
    return math.log(fh) + math.log1p(fl / fh)


def _dd_add(hi: float, lo: float, s: float) -> tuple[float, float]:
    """``(hi + lo) + s`` as a renormalised double-double (two-sum, ``|lo|`` below an ulp of ``hi``).

    >>> _dd_add(1.0, 0.0, 2.0 ** -60)
    (1.0, 8.673617379884035e-19)
    """
    t = hi + s
    bp = t - hi
    lo = lo + ((hi - (t - bp)) + (s - bp))
    h2 = t + lo
    return h2, lo - (h2 - t)


def _dd_position(qh: float, ql: float, fh: float, fl: float) -> float:
    """The position ``qh + ql + log F`` rounded once (the state is not changed)."""
    h, lo = _dd_add(qh, ql, _logf(fh, fl))
    return h + lo


def _dd_low(qh: float, ql: float, fh: float, fl: float, y: float) -> float:
    """``qh + ql + log F - y`` for the stored ``y`` (its rounding error: the low part of the position).

    >>> _dd_low(1.0, 2.0 ** -60, 1.0, 0.0, 1.0)
    8.673617379884035e-19
    """
    h, lo = _dd_add(qh, ql, _logf(fh, fl))
    return (h - y) + lo


# the float64 arithmetic of the fused step (core/fused.py): the operators themselves (numba compiles
# operator.add as ``+``), and the hooks of what float64 needs beyond the operations
def _hi(x: float) -> float:
    return x


def _ld(a: F64, j: int) -> float:
    return a[j]


def _st(a: F64, j: int, x: float) -> None:
    a[j] = x


def _track_init(lam: float, p0: float, a0: float, r0: float) -> Track:
    """The product of the entrywise absolute values (``Aa, Ba, Ca, Da``, the trace's rounding scale),
    ``max_j (|lam| + |p_j|) / |lam + p_j|`` as ``kn / kd`` (cancellation in ``a_j``) and the scale ``sc``
    (a power of two: ``[[A, B], [C, D]]`` is ``sc`` times the monodromy), after the first factor."""
    return abs(a0), 1.0, r0, 0.0, abs(lam) + abs(p0), abs(a0), 1.0


def _track(aux: Track, lam: float, pj: float, a: float, rj: float) -> Track:
    Aa, Ba, Ca, Da, kn, kd, sc = aux
    cn = abs(lam) + abs(pj)
    if cn * kd > kn * abs(a):
        kn = cn
        kd = abs(a)
    aa = abs(a)
    return aa * Aa + Ca, aa * Ba + Da, rj * Aa, rj * Ba, kn, kd, sc


def _shrunk(A: float, B: float, C: float, D: float, aux: Track) -> tuple[float, float, float, float, Track]:
    Aa, Ba, Ca, Da, kn, kd, sc = aux
    S = _SHRINK
    return A * S, B * S, C * S, D * S, (Aa * S, Ba * S, Ca * S, Da * S, kn, kd, sc * S)


def _rescale(A: float, B: float, C: float, D: float, aux: Track) -> tuple[float, float, float, float, Track]:
    if aux[0] > _BIG or aux[1] > _BIG:
        return _shrunk(A, B, C, D, aux)
    return A, B, C, D, aux


def _rescale_last(A: float, B: float, C: float, D: float, aux: Track) -> tuple[float, float, float, float, Track]:
    if aux[2] > _BIG or aux[3] > _BIG:
        return _shrunk(A, B, C, D, aux)
    return A, B, C, D, aux


def _in_range(A: float, B: float, C: float, D: float, t: float) -> bool:
    return (abs(A) < 1e290 and abs(B) < 1e290 and abs(C) < 1e290 and abs(D) < 1e290
            and (abs(A) > 1e-290 or abs(B) > 1e-290))


def _two_of(aux: Track) -> float:
    return 2.0 * aux[6]


def _decided(aux: Track, t: float, disc: float, tt: F64, i: int, p: F64, r: F64, lam: float, lo: float) -> bool:
    """The trace is decided only where it is far from ``+-2`` against its rounding error:
    ``T (|t| + 2) <= KAPPA_MAX |t**2 - 4|`` (that is ``T <= KAPPA_MAX ||t| - 2|``: ``t``'s rounding error is a
    multiple of ``eps T`` however small ``t`` is) with ``T`` the trace of the product of the entrywise absolute
    values; ``tt[i + 2]`` receives the trace's condition times ``a_j``'s (>= 1), ``k_t``.  Two-tier:
    where that cheap test fails, the sharp ``k_t`` of :func:`~symbt.numeric.core.condition.sharp_trace_kappa`
    (prefix and suffix products, computed only then) decides, ``k_t <= KAPPA_MAX``."""
    T = aux[0] + aux[3]
    ta = abs(t) + 2.0 * aux[6]          # |t| + 2 in the monodromy's scale
    k = T * ta / abs(disc) * (aux[4] / aux[5])
    if not T * ta <= KAPPA_MAX * abs(disc):
        ks = sharp_trace_kappa(p, r, lam, lo)
        k = ks if ks < k else k
        if not k <= KAPPA_MAX:
            return False
    tt[i + 2] = k
    return True


def _disc_fits(disc: float) -> bool:
    return disc < 1e300     # (sc tr)**2 overflows: not reached after the rescaling, kept as a guard


def _step_kappa(tt: F64) -> float:
    return max(tt[2], tt[3])


def _sharpen(tt: F64, p: F64, r: F64, lam1: float, lo1: float, lam2: float, lo2: float) -> float:
    """The second tier of the state's ``k_t`` (where the cheap one fails a site's read-out test): each
    trace's condition lowered to the sharp :func:`~symbt.numeric.core.condition.sharp_trace_kappa` if that is
    smaller; returns the new ``k_t``."""
    for i, lam, lo in ((2, lam1, lo1), (3, lam2, lo2)):
        ks = sharp_trace_kappa(p, r, lam, lo)
        if ks < tt[i]:
            tt[i] = ks
    return max(tt[2], tt[3])


def _bounded(x: float) -> bool:
    return abs(x) < 1e300       # the read-out's range: +-1e300 itself, inf and NaN are out


def _trusted(kt: float, u: float, w: float, dn: float, x: float) -> bool:
    # kappa = kt (|u| + |w|) / |u - w| (1 + |xr| / |1 + xr|): the slopes' error, the cancellation in
    # d_j = u_j - w_j and the read-out log1p(xr_j) -- else the sign of 1 + xr_j or the result is not
    # trusted (step.py, "Existence and accuracy in float64")
    return kt * (abs(u) + abs(w)) * (abs(x + 1.0) + abs(x)) <= KAPPA_MAX * abs(dn) * abs(x + 1.0)


def _advance(r: F64, pos: tuple[F64, F64], j: int, x: float, xn: float, pj: float) -> bool:
    """``r_j <- r_j (1 + xr_{j+1}) / (1 + xr_j)`` and ``F_j <- F_j (1 + xr_j)`` in double-double."""
    fh, fl = pos
    d = (xn - x) / (1.0 + x)
    r[j] = r[j] + r[j] * d
    a = fh[j]
    t = a * x
    s = a + t
    bp = s - a
    fl[j] = fl[j] + fl[j] * x + ((a - (s - bp)) + (t - bp))
    fh[j] = s
    return True


#: the hooks of the float64 arithmetic (compiled with ``inline="always"`` by :mod:`.jit`)
HOOKS: dict[str, Callable[..., Any]] = {
    "hi": _hi, "track_init": _track_init, "track": _track, "rescale": _rescale, "rescale_last": _rescale_last,
         "in_range": _in_range, "two_of": _two_of, "decided": _decided, "disc_fits": _disc_fits,
         "step_kappa": _step_kappa, "sharpen": _sharpen, "bounded": _bounded, "trusted": _trusted, "advance": _advance,
    "ld": _ld, "st": _st, "lam_add": lam_add, "lam_split": lam_split, "root_slope": root_slope}
#: the operations of the float64 arithmetic (the same in plain Python and under numba)
OPERATIONS = {"add": operator.add, "sub": operator.sub, "mul": operator.mul, "div": operator.truediv,
              "neg": operator.neg, "sqrt": math.sqrt, "add_d": operator.add, "mul2": operator.mul}


@cache
def sharp_compiled() -> Callable[..., Any]:
    """:func:`~symbt.numeric.core.condition.sharp_trace_kappa` compiled by numba (the global the compiled hooks
    and the block kernel call; needs numba).

    >>> callable(sharp_compiled) and sharp_compiled.__name__
    'sharp_compiled'
    """
    from ..core.compile import njit, sources_digest

    # named by a digest of both files it compiles in (numba's disk cache only watches condition.py)
    name = "sharp_trace_kappa_f64_" + sources_digest([sharp_trace_kappa, lam_add])
    return njit(clone(sharp_trace_kappa, name, lam_add=njit(lam_add, inline="always")))


def _decided_cheap(aux: Track, t: float, disc: float, tt: F64, i: int, p: F64, r: F64, lam: float,
                   lo: float) -> bool:
    T = aux[0] + aux[3]
    ta = abs(t) + 2.0 * aux[6]          # |t| + 2 in the monodromy's scale, as _decided and the emitted guard
    if not T * ta <= KAPPA_MAX * abs(disc):
        return False
    tt[i + 2] = T * ta / abs(disc) * (aux[4] / aux[5])
    return True


def _sharpen_off(tt: F64, p: F64, r: F64, lam1: float, lo1: float, lam2: float, lo2: float) -> float:
    return max(tt[2], tt[3])


@cache
def cheap_kernels() -> dict[str, Callable[..., Any]]:
    """The float64 fused step with the cheap condition estimate only (no sharp tier), plain Python: the
    boundary of what the emitted code (:mod:`symbt.codegen`, whose guard is the cheap estimate) decides,
    and the "before" of the two-tier estimate in tests and benchmarks.

    >>> import numpy as np
    >>> def status(kernels, N=8, delta=1e-6):          # the free chain, lam2 = 2 + delta near a band edge
    ...     w = [np.empty(N) for _ in range(4)]
    ...     return kernels["step"](np.zeros(N), np.ones(N), (np.ones(N), np.zeros(N)), 3.0 + delta, 2.0 + delta,
    ...                            1.0, 1, *w, np.zeros(4))
    >>> status(cheap_kernels()), status(python_kernels())     # ILLCOND with the cheap estimate only
    (5, 0)
    """
    return instantiate(SOURCE, {**OPERATIONS, **HOOKS, "decided": _decided_cheap, "sharpen": _sharpen_off},
                       tag="f64cheap", jit=False, extra=_EXTRA)


@cache
def python_kernels() -> dict[str, Callable[..., Any]]:
    """The fused step (:mod:`symbt.numeric.core.fused`) in float64, plain Python (``slopes``, ``step``), with
    the operations and the hooks written inline (:mod:`symbt.numeric.core.inline`; bit-identical).

    >>> sorted(python_kernels())
    ['slopes', 'step']
    """
    from ..core.inline import FLOAT64_INLINE

    kinds = {**FLOAT64_INLINE, **{name: "body" for name in HOOKS if name not in FLOAT64_INLINE}}
    return instantiate(SOURCE, {**OPERATIONS, **sharp_on_floats(HOOKS)}, tag="f64", jit=False, extra=_EXTRA,
                       operations=kinds)


def _anchor1(qh: F64, ql: F64, fh: F64, fl: F64, r: F64, p: F64) -> int:
    """Flush ``F`` into ``q`` and re-anchor ``r = exp(dq)`` (one state); returns the status."""
    N = qh.shape[0]
    for j in range(N):
        s = _logf(fh[j], fl[j])
        if not abs(s) < 1e300:
            return RANGE
        qh[j], ql[j] = _dd_add(qh[j], ql[j], s)
        fh[j] = 1.0
        fl[j] = 0.0
    for j in range(N):
        jn = j + 1 if j + 1 < N else 0
        dq = (qh[jn] - qh[j]) + (ql[jn] - ql[j])
        if not (abs(dq) <= MAX_DQ_FLOAT64 and abs(p[j]) < 1e300 and abs(qh[j]) < 1e300):
            return RANGE
        r[j] = math.exp(dq)
    return OK


def orbit(p0: F64, q0: F64, lam1: float, lam2: float, two_mu: float, branch: int, n: int, every: int,
          anchor: int, outP: F64, outQ: F64) -> int:
    """``n`` steps of one state; stores the states of :func:`stored_steps` in ``outP, outQ`` (rows, N).

    ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu``, ``two_mu = 2 mu``.  Returns
    the status (0 ok, else the first failure, see the module docstring).  An ``outQ`` of
    ``2 N`` columns also receives the low parts of the positions in its columns ``N ... 2N - 1``
    (:func:`_dd_low`; the first ``N`` columns are the same either way).

    >>> P, Q = np.empty((2, 3)), np.empty((2, 3))
    >>> orbit(np.array([-20.0, 10, 1]), np.array([1.0, 0, 0.9]), 15.0, 5.0, 10.0, 1, 1, 1, ANCHOR, P, Q)
    0
    >>> round(float(Q[1, 0]), 8)
    -0.08614224
    """
    N = p0.shape[0]
    p = p0.copy()
    qh = q0.copy()
    ql = np.zeros(N)
    fh = np.ones(N)
    fl = np.zeros(N)
    r = np.empty(N)
    u = np.empty(N)
    w = np.empty(N)
    xr = np.empty(N)
    gq = np.empty(N)
    tt = np.empty(4)
    for j in range(N):
        outP[0, j] = p0[j]
        outQ[0, j] = q0[j]
    st = _anchor1(qh, ql, fh, fl, r, p)
    if st != OK:
        return st
    pos = (fh, fl)
    wide = outQ.shape[1] > N
    if wide:
        for j in range(N):
            outQ[0, N + j] = 0.0
    row = 1
    for i in range(1, n + 1):
        st = step(p, r, pos, lam1, lam2, two_mu, branch, u, w, xr, gq, tt)
        if st != OK:
            return st
        if i % anchor == 0:
            st = _anchor1(qh, ql, fh, fl, r, p)
            if st != OK:
                return st
        if i % every == 0 or i == n:
            for j in range(N):
                y = _dd_position(qh[j], ql[j], fh[j], fl[j])
                if not (abs(y) < 1e300 and abs(p[j]) < 1e300):
                    return RANGE
                outP[row, j] = p[j]
                outQ[row, j] = y
                if wide:
                    outQ[row, N + j] = _dd_low(qh[j], ql[j], fh[j], fl[j], y)
            row += 1
    return OK


# the plain-Python step :func:`orbit` calls (jit.py compiles ``orbit`` with the numba instance in its place)
step = python_kernels()["step"]


class _Row(list[float]):
    """A state array of :func:`python_orbit`: Python floats, with the ``shape`` and ``copy`` the step reads."""
    __slots__ = ()

    @property
    def shape(self) -> tuple[int]:
        return (len(self),)

    def copy(self) -> _Row:
        return _Row(self)


class _Rows:
    """The array constructors of :func:`orbit` (``np.empty`` ...) as :func:`python_orbit` sees them."""

    @staticmethod
    def empty(n: int) -> _Row:
        return _Row([0.0] * n)

    @staticmethod
    def ones(n: int) -> _Row:
        return _Row([1.0] * n)

    zeros = empty


_orbit_on_rows = clone(orbit, np=_Rows)


def python_orbit_with(hooks: dict[str, Callable[..., Any]]) -> Callable[..., int]:
    """:func:`python_orbit` with some :data:`HOOKS` replaced (a measuring device of the benchmarks, as
    :func:`~symbt.numeric.float64.jit.orbit_with` is for numba).

    >>> python_orbit_with({})(np.array([-3.0, 0.0]), np.array([0.0, 1.0]), 2.0, 0.0, 2.0, 1, 1, 1, ANCHOR,
    ...                       np.empty((2, 2)), np.empty((2, 2)))
    0
    """
    from ..core.inline import FLOAT64_INLINE

    kinds = {**FLOAT64_INLINE, **{name: "body" for name in HOOKS if name not in FLOAT64_INLINE}}
    st = instantiate(SOURCE, {**OPERATIONS, **sharp_on_floats(HOOKS), **hooks}, tag="f64dev", jit=False,
                     operations=kinds)["step"]
    return clone(python_orbit, _orbit_on_rows=clone(_orbit_on_rows, step=st))


def python_orbit(p0: F64, q0: F64, lam1: float, lam2: float, two_mu: float, branch: int, n: int, every: int,
                 anchor: int, outP: F64, outQ: F64) -> int:
    """:func:`orbit` in plain Python with its state in lists of Python floats (what ``backend="python"`` runs).

    The same operations on the same doubles, so the same bits as :func:`orbit` and the numba kernel
    (``tests/test_numeric_inline.py``); a Python float's arithmetic takes a third of the time of a numpy
    scalar's.  (The step divides as IEEE arithmetic, ``x / 0`` is ``+-inf`` or NaN:
    :func:`~symbt.numeric.core.inline.ieee_div0`.)

    >>> P, Q = np.empty((2, 3)), np.empty((2, 3))
    >>> python_orbit(np.array([-20.0, 10, 1]), np.array([1.0, 0, 0.9]), 15.0, 5.0, 10.0, 1, 1, 1, ANCHOR, P, Q)
    0
    >>> round(float(Q[1, 0]), 8)
    -0.08614224
    """
    return int(_orbit_on_rows(_Row(np.asarray(p0, np.float64).tolist()), _Row(np.asarray(q0, np.float64).tolist()),
                              float(lam1), float(lam2), float(two_mu), int(branch), n, every, anchor, outP, outQ))
