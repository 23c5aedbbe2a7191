r"""One Bäcklund step ``(p, q) -> (p~, q~)`` of the periodic Toda chain, O(N).

Mathematics (paper eqs. ``D``, ``xy``, ``lam0mu``, ``xyqqt``, ``imptransf``)
---------------------------------------------------------------------------
With ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu`` and ``L = l_N ... l_1`` the map is
read off from two eigenvector slopes: ``(1, -y_1)`` is the eigenvector of
``L(lam1)`` with eigenvalue ``(tr1 - g1)/2`` and ``(1, -z_1)`` that of ``L(lam2)``
with eigenvalue ``(tr2 + g2)/2``, ``g_i = branch * sqrt(tr_i**2 - 4)`` (positive
root).  Slopes at the other sites follow from the Möbius action of ``l_j``,
``y_{j+1} = -1 / (E_j (lam1 + p_j + E_j y_j))`` (same for ``z`` at ``lam2``), and

    x_j = 2 mu / (z_j - y_j),   Etilde_j = E_j - x_j,   eta_j = x_j y_j + mu,
    p~_j = p_j + eta_j - eta_{j+1}        (indices mod N).

Stable formulation (what is actually computed)
----------------------------------------------
1. *Scaled slopes.*  ``u_j = E_j y_j``, ``w_j = E_j z_j`` are eigenvector slopes of
   the scaled monodromy ``M = m_N ... m_1`` with ``m_j = [[lam + p_j, -1],
   [r_j, 0]]``, ``r_j = exp(q_{j+1} - q_j)`` (see :mod:`symbt.numeric.core.monodromy`).  The Möbius
   transport becomes ``u_{j+1} = -r_j / (lam1 + p_j + u_j)``.  Only neighbour
   differences of ``q`` appear, so the map commutes exactly with ``q -> q + c``
   and never forms ``exp(q_j)``.
2. *Slope at site 1 without cancellation.*  The two roots of
   ``B u**2 - (A - D) u - C = 0`` are ``k / (2B)`` and ``-2C / k`` with
   ``k = (A - D) + sign(A - D) * sqrt(tr**2 - 4)`` (no cancellation in ``k``);
   ``tr**2 - 4`` is formed as ``(tr - 2)(tr + 2)``.  The branch decides which root
   is wanted.
3. *Transport in the contracting direction.*  Under forward transport the
   eigenvector of the larger eigenvalue ``|v| > 1`` is attracting (errors shrink
   by ``1/v**2`` per period), the other is attracting for the inverse map
   ``u_j = -(lam + p_j) - r_j / u_{j+1}`` run from site ``N+1 = 1`` downwards.
   Each slope is transported in its own contracting direction (decided per
   batch element from the sign of ``tr * g``).  The literal route transports
   one of them forward and loses ``log10(v**2)`` digits (7 digits for the
   paper's example).
4. *Cancellation-free read-out.*  With ``d_j = w_j - u_j`` (an O(1) difference
   of the two *different* eigenvector slopes; it does not vanish as ``mu -> 0``):
   ``x_j / E_j = 2 mu / d_j``, ``q~_j = q_j + log1p(-2 mu / d_j)``,
   ``eta_j = mu + 2 mu u_j / d_j`` and ``p~_j - p_j = 2 mu (u_j/d_j - u_{j+1}/d_{j+1})``:
   both increments are ``mu`` times O(1) quantities computed to full relative
   accuracy, so small ``mu`` costs nothing (the literal ``E - x`` and
   ``eta_j - eta_{j+1}`` lose ``log10(1/mu)`` digits).
5. *Parameters consistent with the read-out.*  In float64 the slopes are taken at
   ``fl(lam0 +- mu)`` plus low parts that make their difference exactly the
   read-out's ``2 mu``, each ``lam + p_j`` rounded once
   (:mod:`symbt.numeric.core.spectral_sum`); an ulp of inconsistency would
   repeat in every step and make the invariants drift linearly.  For the same
   reason the slope at site 1 is rounded once (``k`` and the root of
   ``tr**2 - 4`` as double-doubles, :func:`~symbt.numeric.core.spectral_sum.root_slope`).

Existence: the real map needs ``|tr L(lam_i)| > 2``, traces of the same sign
(``lam1``, ``lam2`` in one gap; opposite signs mean different gaps) and
``1 + xr_j > 0`` for all ``j`` (``Etilde_j > 0``); otherwise
:class:`NoRealMapError` (or a complex result with ``allow_complex=True``).
``branch = -1`` is the inverse of ``branch = +1`` and equals ``branch = +1`` at ``-mu``.

Existence and accuracy in float64.  Every float64 route decides a state only
where the decision is conditioned: with ``T_i`` the trace of ``|m_N| ... |m_1|``,

    kappa = max_j k_t (|u_j| + |w_j|) / |u_j - w_j| (1 + |xr_j| / |1 + xr_j|),
    k_t = max_i T_i (|t_i| + 2) / |t_i**2 - 4| * max_j (|lam_i| + |p_j|) / |lam_i + p_j|,

two-tier: where this cheap ``k_t`` would make the state ill-conditioned, ``T_i`` is replaced by the
sharp first-order rounding scale of the computed trace
(:func:`~symbt.numeric.core.condition.sharp_trace_kappa`: prefix and suffix products,
``(1/N) sum_j tr(|S_{j+1}| |m_j| |P_{j-1}|) <= T_i``; the cheap ``T_i`` overestimates the
trace's error by orders of magnitude when the ``a_j`` take both signs, ~1e6 at N = 64 and ~1e27 at
N = 256 on the benchmark chains).  A state whose ``kappa`` still exceeds ``KAPPA_MAX = 2**24`` is
recomputed by the mpmath step
(:func:`symbt.numeric.float64.rows.escalate_rows`) and rounded to float64.  A returned
state satisfies ``max |x - x_exact| <= 32 N eps kappa rho s`` (``rho = 1 +
max |q_{j+1} - q_j|``, ``s = max(|p|, |q|, |p~|, |q~|, |lam0| + |mu|)``,
``eps = 2**-52``); docs/numeric.md, "Existence and accuracy".

Degenerate eigenvectors.  A slope is a point of the projective line: where an
eigenvector is ``(0, 1)`` the slope is infinite (e.g. ``lam + p_j = 0`` on the
backward transport).  Every context divides IEEE-style (``x / 0 = inf``,
``x / inf = 0``, :meth:`~symbt.numeric.core.context.MPContext.div`), so such a slope
passes through infinity and the read-out takes its limit (``xr_j = 2 mu / d_j = 0``)
on the float64, mpmath and Arb paths alike.

Backends.  One float64 state goes through the fused kernel
(:mod:`symbt.numeric.float64.kernels`; numba if installed), a batch through the
compiled block kernel of :mod:`symbt.numeric.float64.orbit` (numba; each state's
step bit-identical to its single-state step) where that is faster (fewer than
4096 states, or N >= 8), else -- and without numba -- the vectorised numpy
route of :mod:`symbt.numeric.float64.rows` (each member bit-identical to its
single-state step with ``backend="numpy"``; docs/numeric.md, "Batches");
mpmath numbers through
python-flint's Arb at
the caller's precision plus guard bits when python-flint is installed
(:mod:`symbt.numeric.multiprec.runners`), else through mpmath.  Whatever the kernel does
not handle (no real map, renormalisation, non-finite intermediates) is
recomputed by the general path, which raises the typed errors.

Example
-------
>>> import numpy as np
>>> from symbt.numeric import bt_step
>>> pt, qt = bt_step([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0)
>>> np.round(pt, 8)
array([-19.99656766,   9.78635495,   1.21021272])
>>> p2, q2 = bt_step(pt, qt, 10.0, 5.0, branch=-1)       # inverse step
>>> bool(np.allclose(p2, [-20, 10, 1], rtol=0, atol=1e-12))
True
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, TypedDict, TypeVar

import mpmath
import numpy as np

from .condition import SIDE_BY_SIDE_ROWS, abs_trace_rows, monodromy_and_abs, sharp_trace_kappa_rows
from .context import FLOAT, IV, Cond, Context, Exponent, FloatValue, MPValue, Value
from .errors import NoRealMapError, NumericRangeError
from .inputs import mp_output
from .limits import ILLCOND, KAPPA_MAX, OK, POSITIVITY, RANGE, TRACE1, TRACE2
from .monodromy import monodromy, neighbour_ratios
from .spectral_sum import lam_add, lam_split, root_slope_rows

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]


__all__ = ["step_core", "eigen_slopes", "SlopeData", "StepAux", "mp_step", "BLOCK_ELEMENTS", "trace_kappa",
           "sharpened", "float_status"]

_GUARD_DIGITS = 12
_T = TypeVar("_T")
#: accepted values of ``backend`` (float64: auto/numba/python/numpy; mpmath: auto/qd/flint/mpmath)

class SlopeData:
    """Eigenvector data at one spectral parameter (internal, documented for tests).

    ``u`` -- list of scaled slopes ``E_j * (slope)_j``, ``trace_ok`` -- the
    scaled ``tr**2 - 4`` (positive iff ``|tr| > 2``), ``forward`` -- transport
    direction used (selected eigenvalue has ``|v| >= 1``), ``t, g, e`` -- scaled
    trace, ``sqrt(t**2 - 4**(1-e))`` and exponent.

    >>> SlopeData(t=3.0, g=2.2, e=0, trace_ok=5.0).t
    3.0
    """

    __slots__ = ("u", "trace_ok", "forward", "t", "g", "e", "kappa", "inputs")

    def __init__(self, *, trace_ok: Value = None, t: Value = None, g: Value = None, e: Exponent = 0,
                 u: list[Value] | None = None, forward: Cond | None = None) -> None:
        self.kappa: FloatValue | None = None
        #: float64: ``(p, r, lam, lo)``, what the sharp tier of the condition estimate recomputes from
        self.inputs: tuple[Sequence[FloatValue], Sequence[FloatValue], FloatValue, FloatValue] | None = None
        self.trace_ok = trace_ok
        self.t = t
        self.g = g
        self.e = e
        self.u = u
        self.forward = forward


class StepAux(TypedDict):
    """The intermediates :func:`step_core` returns besides the new state (lists over the sites).

    >>> sorted(StepAux.__annotations__)
    ['S1', 'S2', 'gq', 'u', 'w', 'xr']
    """

    u: list[Value]
    w: list[Value]
    xr: list[Value]
    gq: list[Value]
    S1: SlopeData
    S2: SlopeData


def _forward(ctx: Context, a: Sequence[Value], r: Sequence[Value], u1: Value) -> list[Value]:
    u = [u1]
    for j in range(len(a) - 1):
        u.append(ctx.div(-r[j], a[j] + u[j]))
    return u


def _backward(ctx: Context, a: Sequence[Value], r: Sequence[Value], u1: Value) -> list[Value]:
    N = len(a)
    u: list[Value] = [None] * N
    u[0] = nxt = u1
    for j in range(N - 1, 0, -1):
        nxt = u[j] = -a[j] - ctx.div(r[j], nxt)
    return u


def eigen_slopes(ctx: Context, a: Sequence[Value], r: Sequence[Value], s: int, need_slopes: bool = True,
                 spec: tuple[Value, Sequence[Value], Value] | None = None) -> SlopeData:
    """Slopes of the eigenvector with eigenvalue ``(tr - s*sqrt(tr^2-4))/2`` at every site.

    ``a_j = lam + p_j``; ``s = +1`` gives the paper's ``y`` (for ``branch=+1``),
    ``s = -1`` its ``z``.  See the module docstring for the formulas.

    >>> import mpmath
    >>> from symbt.numeric.core.inputs import MP
    >>> from symbt.numeric.core.monodromy import neighbour_ratios
    >>> r = neighbour_ratios(MP, [mpmath.mpf(1), mpmath.mpf(0), mpmath.mpf("0.9")])
    >>> S = eigen_slopes(MP, [15 + p for p in (-20, 10, 1)], r, 1)     # lam1 = 15, the paper's example
    >>> mpmath.nstr(S.t, 8), [mpmath.nstr(x, 6) for x in S.u], S.forward
    ('-2021.2173', ['-0.0694993', '0.0725672', '-0.0980994'], True)
    """
    absolute = None
    if ctx is FLOAT and spec is not None:     # the cheap tier's product of the |a_j| in the same sweep
        (A, B, C, D, e), absolute = monodromy_and_abs(a, r)
    else:
        A, B, C, D, e = monodromy(ctx, a, r)
    t = A + D
    two = ctx.ldexp(2.0, -e) if not isinstance(e, int) or e else 2.0
    disc = (t - two) * (t + two)          # tr^2 - 4 without cancellation (scaled)
    g = ctx.sqrt(disc)
    data = SlopeData(trace_ok=disc, t=t, g=g, e=e)
    # |(t - s g)/2| >= 1  <=>  Re(t conj(s g)) <= 0  -> dominant -> transport forward
    tg = ctx.half_plane(t, g)
    fwd = ctx.neg(tg) if s > 0 else tg
    data.forward = fwd
    if not need_slopes:
        return data
    if ctx is FLOAT and spec is not None:   # float64 conditioning (``spec = (lam, p, lo)``, a_j = lam + lo + p_j)
        lam, P, lo = spec
        data.inputs = (P, r, lam, lo)
        with np.errstate(all="ignore"):
            ka = np.maximum.reduce(_over_sites(lambda Pm, am: (np.abs(lam) + np.abs(Pm)) / np.abs(am), P, a))
        data.kappa = trace_kappa(a, r, t, disc, e, ka, two, absolute=absolute)
    dl = A - D
    sg, plus = ctx.align(g, dl)           # k = dl + sign(dl) g has no cancellation
    k = dl + sg
    # roots of B u^2 - (A-D) u - C = 0 are k/(2B) and -2C/k; want (dl + s g)/(2B)
    target_is_k = plus if s > 0 else ctx.neg(plus)
    if ctx is FLOAT:                      # rounded once, as the kernels (spectral_sum.root_slope: no bias)
        u1 = root_slope_rows(A, D, dl, g, B, C, two, plus, target_is_k)
    else:
        u1 = ctx.select(target_is_k, lambda: ctx.div(k, 2 * B), lambda: ctx.div(-2 * C, k))
    if ctx.all(fwd):
        u = _forward(ctx, a, r, u1)
    elif not ctx.any(fwd):
        u = _backward(ctx, a, r, u1)
    else:
        uf, ub = _forward(ctx, a, r, u1), _backward(ctx, a, r, u1)
        u = [np.where(fwd, x, y) for x, y in zip(uf, ub)]
    data.u = u
    return data


def trace_kappa(a: Sequence[FloatValue], r: Sequence[FloatValue], t: FloatValue, disc: FloatValue, e: Exponent,
                ka: FloatValue | float = 1.0, two: FloatValue | float = 2.0, *,
                absolute: tuple[FloatValue, Exponent] | None = None) -> FloatValue:
    """float64 condition estimate of the trace decision: ``T (|t| + 2) / |t**2 - 4| = T / ||t| - 2|`` per row
    (the cheap tier).

    ``T`` is the trace of ``|m_N| ... |m_1|`` (entrywise absolute values, computed as the monodromy of
    ``|a_j|`` and ``-r_j``, which has no cancellation), the scale of the rounding error of ``t``; ``t``,
    ``disc`` are the scaled trace and ``t**2 - 4`` of :func:`eigen_slopes` (exponent ``e``; ``two`` is 2 in that
    scale), ``ka`` the cancellation factor ``max_j (|lam| + |p_j|) / |lam + p_j|`` it is multiplied by;
    ``absolute``: that product's ``(A + D, e)`` where the caller formed it already, in the sweep of the
    monodromy (:func:`~symbt.numeric.core.condition.monodromy_and_abs`), else formed here
    (:func:`~symbt.numeric.core.condition.abs_trace_rows`, bit for bit the monodromy).
    Where the state would be escalated with it, :func:`float_status` takes the sharp estimate of
    :func:`~symbt.numeric.core.condition.sharp_trace_kappa` (the second tier, as the fused and block
    kernels do).  Beyond
    :data:`~symbt.numeric.core.limits.KAPPA_MAX` the float64 decision ``|t| > 2`` and the slopes are not
    trusted (the state is recomputed at higher precision, see :func:`float_status`).  The rounding error of
    ``t`` is a multiple of ``eps T`` whatever ``t`` is, so it is compared with the distance ``||t| - 2|`` of
    the decision; ``T |t| / |t**2 - 4|`` (without the ``+ 2``) vanishes as ``t -> 0`` and passed a trace that
    cancelled to rounding noise (``|t| ~ 1e-35`` for a true ``1.6e18``, found by the deep fuzz, docs/fuzz.md).

    >>> two = [np.array([2.0]), np.array([3.0])]
    >>> float(trace_kappa(two, [np.array([1.0])] * 2, np.array([4.0]), np.array([12.0]), 0)[0])  # T = 8
    4.0
    """
    with np.errstate(all="ignore"):
        # the monodromy of |a_j|, -r_j (floats for a few rows), unless given (``absolute``: its A + D and e)
        Ta, ea = abs_trace_rows(a, r) if absolute is None else absolute
        return np.ldexp(Ta, ea - e) * ((np.abs(t) + np.abs(two)) / np.abs(disc)) * ka


def _over_sites(fn: Callable[..., _T], *lists: Sequence[FloatValue]) -> _T:
    """``fn`` of the site lists stacked to arrays ``(N,) + row shape`` (the elementwise operations of a loop
    over the sites, in fewer numpy calls); sites of different shapes are broadcast first.  From
    ``SIDE_BY_SIDE_ROWS`` rows on, ``fn`` of each site in turn, its results gathered as lists over the
    sites (a call's cost is small there against the work, and the stacked arrays would leave the cache)."""
    if np.size(lists[0][0]) > SIDE_BY_SIDE_ROWS:
        return _gathered([fn(*site) for site in zip(*lists)])
    try:
        arrays = [np.array(x, dtype=float) for x in lists]
        if len({a.shape for a in arrays}) == 1:
            return fn(*arrays)
    except ValueError:
        pass
    shape = np.broadcast_shapes(*(np.shape(v) for x in lists for v in x))
    return fn(*(np.array([np.broadcast_to(v, shape) for v in x], dtype=float) for x in lists))


def _gathered(per_site: list[_T]) -> _T:
    """A list over the sites of (nested tuples of) results as (nested tuples of) lists over the sites."""
    if isinstance(per_site[0], tuple):
        return tuple(_gathered(list(x)) for x in zip(*per_site))        # type: ignore[return-value]
    return per_site                                                      # type: ignore[return-value]


def _site_factors(U: F64, W: F64, X: F64) -> tuple[tuple[F64, F64], npt.NDArray[np.bool_], F64]:
    """The per-site factors of :func:`float_status`' slope test, ``(|u| + |w|, |x + 1| + |x|)``,
    ``x + 1 > 0`` and ``KAPPA_MAX |u - w| |x + 1|`` (the operations of the site loop, ``x + 1`` formed once)."""
    X1 = X + 1
    A1 = np.abs(X1)
    return (np.abs(U) + np.abs(W), A1 + np.abs(X)), X1 > 0, KAPPA_MAX * np.abs(U - W) * A1


def sharpened(S: SlopeData, rows: npt.NDArray[np.bool_]) -> npt.NDArray[np.float64]:
    """:func:`~symbt.numeric.core.condition.sharp_trace_kappa` of the float64 rows ``rows`` of
    :func:`eigen_slopes`' data ``S`` (``inf``
    elsewhere): the second tier of :func:`trace_kappa` and :func:`float_status`.

    >>> from symbt.numeric.core.context import FLOAT
    >>> S = eigen_slopes(FLOAT, [np.array([15.0 + x]) for x in (-20.0, 10.0, 1.0)],
    ...                  [np.array([x]) for x in np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))], 1,
    ...                  spec=(15.0, [np.array([x]) for x in (-20.0, 10.0, 1.0)], 0.0))
    >>> 1.0 <= float(sharpened(S, np.array([True]))[0]) < 20.0
    True
    """
    assert S.inputs is not None                 # set by eigen_slopes for the float context
    P, r, lam, lo = S.inputs
    shape = np.shape(rows)
    out = np.full(shape, np.inf)
    with np.errstate(all="ignore"):
        # (rows..., N); a site may be a scalar (broadcast); only flagged rows get here, so one plain stack suffices
        pv = np.stack([np.broadcast_to(x, shape) for x in P], axis=-1).astype(float)
        rv = np.stack([np.broadcast_to(x, shape) for x in r], axis=-1).astype(float)
        lv, ov = np.broadcast_to(lam, shape), np.broadcast_to(lo, shape)
        k = np.nonzero(rows)            # every row at once, each bit for bit its scalar sharp_trace_kappa
        out[k] = sharp_trace_kappa_rows(pv[k], rv[k], lv[k].astype(float), ov[k].astype(float))
    return out


def float_status(aux: StepAux, Pn: Sequence[FloatValue], Qn: Sequence[FloatValue]) -> npt.NDArray[np.int64]:
    """Per-row status codes (:mod:`symbt.numeric.core.limits`) of a float64 :func:`step_core` with ``check_real=False``.

    In the order of the fused kernels: ``ILLCOND`` where a trace is within ``KAPPA_MAX`` times its rounding
    scale of ``+-2`` (:func:`trace_kappa`; two-tier: where the cheap estimate would give ``ILLCOND``, the
    sharp one of :func:`~symbt.numeric.core.condition.sharp_trace_kappa`, see :func:`sharpened`),
    ``TRACE1``/``TRACE2`` where
    ``|tr| <= 2``, ``POSITIVITY`` where
    the traces have opposite signs (``lam1``, ``lam2`` in different gaps: no real map) or some
    ``Etilde_j / E_j = 1 + xr_j <= 0``, ``ILLCOND`` where the state's ``kappa`` (module docstring) exceeds
    ``KAPPA_MAX`` (that sign or the result not trusted), ``RANGE`` where the result is not finite.
    """
    S1, S2 = aux["S1"], aux["S2"]
    assert S1.kappa is not None and S2.kappa is not None      # set by eigen_slopes for the float context
    k1, k2 = S1.kappa, S2.kappa
    with np.errstate(all="ignore"):
        t1, t2 = S1.trace_ok > 0, S2.trace_ok > 0
        opp = (S1.t < 0) != (S2.t < 0)
        # the sites' factors at once (arrays over sites and rows; the same operations per element)
        us, xs, rhs = _over_sites(_site_factors, aux["u"], aux["w"], aux["xr"])

        def ill(k1: FloatValue, k2: FloatValue) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
            kt = np.maximum(k1, k2)
            if isinstance(rhs, list):       # site by site (many rows)
                return ~(k1 <= KAPPA_MAX) | ~(k2 <= KAPPA_MAX), np.logical_or.reduce(
                    [~(kt * a * b <= c) for a, b, c in zip(us[0], us[1], rhs)])
            return ~(k1 <= KAPPA_MAX) | ~(k2 <= KAPPA_MAX), np.logical_or.reduce(~(kt * us[0] * us[1] <= rhs))

        ill_t, ill_p = ill(k1, k2)
        rows = ill_t | ill_p
        if rows.any():          # the second tier where the cheap estimate escalates (as the kernels do)
            rows = np.broadcast_to(rows, np.shape(k1))
            k1, k2 = np.fmin(k1, sharpened(S1, rows)), np.fmin(k2, sharpened(S2, rows))
            ill_t, ill_p = ill(k1, k2)
        pos = np.logical_and.reduce(xs)
        fin = np.isfinite(np.add.reduce(Pn) + np.add.reduce(Qn))
    # the first condition that holds gives the code (np.select's order, set here from the last one back)
    out = np.where(fin, OK, RANGE)
    out = np.where(pos, out, POSITIVITY)
    out = np.where(ill_p, ILLCOND, out)
    out = np.where(opp, POSITIVITY, out)
    out = np.where(t2, out, TRACE2)
    out = np.where(t1, out, TRACE1)
    return np.where(ill_t, ILLCOND, out).astype(np.int64)


def _opposite(t1: Value, t2: Value) -> Cond:
    """Traces certainly of opposite signs (elementwise for arrays; balls and intervals: certain only)."""
    if isinstance(t1, np.ndarray) or isinstance(t2, np.ndarray):
        return np.logical_xor(np.real(t1) < 0, np.real(t2) < 0)
    return bool((t1 < 0 and t2 > 0) or (t1 > 0 and t2 < 0))


def where_text(ok: npt.ArrayLike, shape: tuple[int, ...], offset: int = 0,
               index: npt.NDArray[np.intp] | None = None) -> tuple[list[tuple[int, ...]], str]:
    """Batch indices (in ``shape``) of the rows where ``ok`` is False, and a message suffix.

    ``index`` maps local rows to flat rows of the batch (else ``row + offset``).

    >>> where_text([True, False, True], (3,))
    ([(1,)], ' (batch index (1,))')
    """
    idx = np.flatnonzero(np.logical_not(np.asarray(ok)))
    idx = index[idx] if index is not None else idx + offset
    if not shape or idx.size == 0:
        return [], ""
    where = [tuple(int(i) for i in np.unravel_index(k, shape)) for k in idx[:5]]
    return where, " (batch index %s%s)" % (", ".join(map(str, where)), ", ..." if idx.size > 5 else "")


def step_core(ctx: Context, P: Sequence[Value], Q: Sequence[Value], lam0: Value, mu: Value, branch: int, *,
              check_real: bool = True, shape: tuple[int, ...] = (), offset: int = 0,
              index: npt.NDArray[np.intp] | None = None) -> tuple[list[Value], list[Value], StepAux]:
    """The step on per-site lists in context ``ctx``; returns ``(P~, Q~, aux)``.

    ``aux`` holds ``u``, ``w``, ``xr = 2 mu / (u - w)`` (``Etilde_j / E_j = 1 + xr_j``),
    ``gq = u/(u-w)`` (lists; ``eta_j = mu - 2 mu gq_j``) and the two :class:`SlopeData`.
    Raises :class:`NoRealMapError` when ``check_real`` and the real map fails
    (its ``where`` from ``shape`` and ``offset``/``index``, see :func:`where_text`).

    >>> import mpmath
    >>> from symbt.numeric.core.inputs import MP
    >>> P, Q, aux = step_core(MP, [mpmath.mpf(-20), 10, 1], [1, 0, mpmath.mpf('0.9')], 10, 5, 1)
    >>> mpmath.nstr(P[0], 8), sorted(aux)
    ('-19.996568', ['S1', 'S2', 'gq', 'u', 'w', 'xr'])
    """
    N = len(P)
    r = neighbour_ratios(ctx, Q)
    lam1, lam2 = lam0 + mu, lam0 - mu
    if ctx is FLOAT:        # the parameters made consistent with the read-out's 2 mu, as in the kernels
        lo1, lo2 = lam_split(lam1, lam2, 2 * mu)
        a1 = [lam_add(lam1, lo1, pj) for pj in P]
        a2 = [lam_add(lam2, lo2, pj) for pj in P]
    else:
        a1 = [lam1 + pj for pj in P]
        a2 = [lam2 + pj for pj in P]
    if ctx is FLOAT:
        S1 = eigen_slopes(ctx, a1, r, branch, spec=(lam1, P, lo1))
        S2 = eigen_slopes(ctx, a2, r, -branch, spec=(lam2, P, lo2))
    else:
        S1 = eigen_slopes(ctx, a1, r, branch)
        S2 = eigen_slopes(ctx, a2, r, -branch)
    if check_real:
        for name, S in (("lam1 = lam0 + mu", S1), ("lam2 = lam0 - mu", S2)):
            if not ctx.all_positive(S.trace_ok):
                where, txt = where_text(ctx.positive(S.trace_ok), shape, offset, index)
                raise NoRealMapError(
                    "no real Bäcklund map: |tr L(%s)| <= 2, the spectral parameter lies "
                    "in a band%s" % (name, txt), condition="trace", where=where)
        opp = _opposite(S1.t, S2.t)
        if np.any(opp):
            # |tr| > 2 at both points and the signs differ: lam1, lam2 lie in different spectral gaps, so
            # some Etilde_j <= 0 in exact arithmetic -- decided here from the traces, not from the rounded xr
            where, txt = where_text(np.logical_not(opp), shape, offset, index)
            raise NoRealMapError(
                "no real Bäcklund map: tr L(lam1) and tr L(lam2) have opposite signs (lam1 and lam2 lie in "
                "different spectral gaps)%s" % txt, condition="positivity", where=where)
    u, w = S1.u, S2.u
    assert u is not None and w is not None
    two_mu = 2 * mu
    dn = [u[j] - w[j] for j in range(N)]          # = -(z_j - y_j) E_j
    xr = [ctx.div(two_mu, dn[j]) for j in range(N)]   # = -x_j / E_j = Etilde_j / E_j - 1
    if check_real:
        bad = [j for j in range(N) if not ctx.all_positive(xr[j] + 1)]
        if bad:
            ok = ctx.positive(xr[bad[0]] + 1)
            for j in bad[1:]:
                ok = ok & ctx.positive(xr[j] + 1)
            where, txt = where_text(ok, shape, offset, index)
            raise NoRealMapError(
                "no real Bäcklund map: some Etilde_j = E_j - x_j <= 0 (lam1 and lam2 "
                "lie in different spectral gaps)%s" % txt, condition="positivity", where=where)
    Qn = [Q[j] + ctx.log1p(xr[j]) for j in range(N)]
    gq = [ctx.div(u[j], dn[j]) for j in range(N)]     # = -u_j / d_j;  eta_j = mu - 2 mu gq_j
    Pn = [P[j] + two_mu * (gq[(j + 1) % N] - gq[j]) for j in range(N)]
    aux: StepAux = {"u": u, "w": w, "xr": xr, "S1": S1, "S2": S2, "gq": gq}
    return Pn, Qn, aux


#: rows of the batch processed at once (keeps temporaries in cache; see benchmarks)
BLOCK_ELEMENTS = 1 << 17



def mp_step(ctx: Context, P: list[MPValue], Q: list[MPValue], lam0: MPValue, mu: MPValue, branch: int,
             allow_complex: bool) -> tuple[list[MPValue], list[MPValue]]:
    """The plain mpmath (or interval) step at ``mp.dps`` + guard digits."""
    with mpmath.workdps(mpmath.mp.dps + _GUARD_DIGITS):
        Pn, Qn, _ = step_core(ctx, P, Q, lam0, mu, branch, check_real=not allow_complex or ctx is IV)
        if not ctx.isfinite_all(Pn + Qn):
            raise NumericRangeError("non-finite result in the mpmath step (degenerate eigenvector?)")
    return mp_output(Pn), mp_output(Qn)
