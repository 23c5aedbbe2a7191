r"""The sharp tier of the float64 condition estimate: the first-order rounding scale of a computed trace.

The float64 routes (:mod:`symbt.numeric.core.step`, "Existence and accuracy in float64") decide a state only
where its condition ``kappa`` is below ``KAPPA_MAX``; its trace factor ``k_t`` uses the cheap scale ``T``,
the trace of the product of the entrywise absolute values of the transfer matrices.  Where the ``a_j =
lam + p_j`` take both signs, ``T`` grows much faster than the products themselves and overestimates the
trace's rounding error by orders of magnitude (the benchmark chains: ~1e6 at N = 64, ~1e27 at N = 256);
where the cheap ``k_t`` would escalate the state to mpmath, every float64 route (the fused kernel's hooks
in :mod:`symbt.numeric.float64.kernels`, the block kernel, the numpy rows) takes :func:`sharp_trace_kappa`
instead.  Plain scalar code: the numba kernels compile it as it is.

The numpy route decides many rows at once: :func:`sharp_trace_kappa_rows` (the sharp tier of every row),
:func:`abs_trace_rows` (the cheap tier's product of the absolute values) and :func:`monodromy_and_abs`
(that product in the sweep of the monodromy itself) give each row's result bit for bit as the scalar
forms do -- on Python floats for a few rows, as numpy operations over the rows for many.

Example
-------
>>> import numpy as np
>>> p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
>>> 1.0 <= sharp_trace_kappa(p, r, 15.0, 0.0) < 20.0        # the paper's example at lam1 = 15
True
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, TypeVar

import numpy as np

from .compile import clone
from .context import FLOAT, Exponent, FloatValue
from .monodromy import _product, monodromy
from .spectral_sum import lam_add

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]
    I64 = npt.NDArray[np.int64]

__all__ = ["sharp_trace_kappa", "SHARP_UNIT", "SHARP_ON_FLOATS", "sharp_on_floats", "sharp_trace_kappa_rows",
           "abs_trace_rows", "FEW_ROWS"]

#: the relative allowance per site for the rounding of the sum of :func:`sharp_trace_kappa` and products
#: (``16 u``, ``u = 2**-53``)``
SHARP_UNIT = 16.0 * 2.0 ** -53

_G = TypeVar("_G", bound=np.generic)
_FAR = 2.0 ** 200
_NEAR = 2.0 ** -200


def sharp_trace_kappa(p: npt.NDArray[np.float64], r: npt.NDArray[np.float64], lam: float, lo: float) -> float:
    r"""The sharp condition ``k_t`` of one trace decision (one state, scalar code): ``Ts (|t| + 2) / |t**2 - 4|``
    times ``max_j (|lam| + |p_j|) / |lam + p_j|``, with the rounding scale ``Ts`` below in place of the cheap
    ``T`` of :func:`trace_kappa`.

    Derivation.  The float64 routes form ``M = m_N ... m_1`` by ``A' = a_j A - C``, ``B' = a_j B - D``,
    ``C' = r_j A``, ``D' = r_j B`` (``a_j = lam_add(lam, lo, p_j)``, one rounding) with exact
    power-of-two rescalings, and ``t = A + D``.  Each site's computed product is
    ``(m_j + Delta_j) M_{j-1}`` with ``|Delta_j| <= gamma_3 |m_j|`` entrywise (first row: ``a_j``'s own
    rounding, the product, the difference; second row: one product; the rescalings are exact), so to
    first order, with the prefix ``P_{j-1} = m_{j-1} ... m_1`` and the suffix ``S_{j+1} = m_N ... m_{j+1}``,

        t_computed - t = sum_j tr(S_{j+1} Delta_j P_{j-1}) + delta (A + D),
        |t_computed - t| <= gamma_3 sum_j tr(|S_{j+1}| |m_j| |P_{j-1}|) + u |t|.

    The cheap bound is ``gamma_{3N} T``, ``T = tr(|m_N| ... |m_1|)``; since
    ``|S_{j+1}| |m_j| |P_{j-1}| <= |m_N| ... |m_1|`` entrywise, each term is at most ``T``, so the mean
    ``Ts = (1/N) sum_j tr(|S_{j+1}| |m_j| |P_{j-1}|)`` takes ``T``'s place in the same form
    ``N gamma_3 Ts`` -- hence in ``kappa`` and in the bound ``32 N eps kappa rho s`` with its constant
    unchanged.  The sum is formed from the prefix products' first rows, stored (the second row of ``P_j``
    is ``r_j`` times the first row of ``P_{j-1}``), and a backward pass for ``S``, both renormalised by
    exact powers of two; its own rounding and the use of the computed rather than the exact ``P``, ``S``
    change it by a relative ``O(N u)``, for which ``Ts`` is multiplied by ``1 + SHARP_UNIT N``.

    *First order only*: the terms with two or more ``Delta`` (and the deviation of the computed ``P``,
    ``S`` from the exact ones, bounded a priori only by ``gamma_{3N}`` times the absolute products) are
    not bounded here -- the a priori bound ``(3 N u)**2 T`` would bring back the pessimism this estimate
    removes.  ``tests/test_numeric_kappa.py`` measures the accuracy bound against the 50-digit literal
    step where this estimate decides.

    The result does not depend on the routes' scaling (``t``, ``t**2 - 4`` and ``Ts`` are formed here,
    in this function's own power-of-two scale); ``inf`` or NaN (not trusted) where ``t = +-2`` or a
    product leaves the range.  Plain scalar code: the compiled kernels run it as it is.

    >>> p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
    >>> k = sharp_trace_kappa(p, r, 15.0, 0.0)        # the paper's example at lam1 = 15: far from +-2
    >>> 1.0 <= k < 20.0
    True
    """
    N = p.shape[0]
    pa = np.empty(N)
    pb = np.empty(N)
    pe = np.empty(N, dtype=np.int64)
    az = np.empty(N)                    # every a_j, formed once (the suffix pass reads them again)
    A = lam_add(lam, lo, p[0])
    az[0] = A
    B = -1.0
    C = r[0]
    D = 0.0
    e = 0
    kn = abs(lam) + abs(p[0])           # max_j (|lam| + |p_j|) / |a_j| as kn / kd (as the kernels' track)
    kd = abs(A)
    pa[0] = A
    pb[0] = B
    pe[0] = 0
    for j in range(1, N):
        a = lam_add(lam, lo, p[j])
        az[j] = a
        cn = abs(lam) + abs(p[j])
        if cn * kd > kn * abs(a):
            kn = cn
            kd = abs(a)
        rj = r[j]
        A, B, C, D = a * A - C, a * B - D, rj * A, rj * B
        m = max(abs(A), abs(B), abs(C), abs(D))
        if (m > _FAR or m < _NEAR) and m > 0.0 and m < math.inf:      # exact power-of-two rescaling
            f = math.frexp(m)[1]
            A, B, C, D, e = math.ldexp(A, -f), math.ldexp(B, -f), math.ldexp(C, -f), math.ldexp(D, -f), e + f
        pa[j] = A
        pb[j] = B
        pe[j] = e
    t = A + D
    two = math.ldexp(2.0, -e)
    disc = (t - two) * (t + two)        # 2**(-2e) (tr**2 - 4), no cancellation
    S11, S12, S21, S22 = 1.0, 0.0, 0.0, 1.0
    es = 0
    total = 0.0
    for j in range(N - 1, -1, -1):
        sa = az[j]
        a = abs(sa)
        rj = r[j]
        if j == 0:                      # P_0 = identity
            P11, P12, P21, P22, ep = 1.0, 0.0, 0.0, 1.0, 0
        else:
            ep = int(pe[j - 1])
            P11, P12 = abs(pa[j - 1]), abs(pb[j - 1])
            if j == 1:                  # P_1 = m_1: second row (r_1, 0)
                P21, P22 = math.ldexp(r[0], -ep), 0.0
            else:                       # (an exponent 0 scales by 1: no call)
                fr = r[j - 1] if pe[j - 2] == ep else math.ldexp(r[j - 1], int(pe[j - 2]) - ep)
                P21, P22 = fr * abs(pa[j - 2]), fr * abs(pb[j - 2])
        X11, X12 = a * P11 + P21, a * P12 + P22
        X21, X22 = rj * P11, rj * P12
        term = abs(S11) * X11 + abs(S12) * X21 + abs(S21) * X12 + abs(S22) * X22
        sh = es + ep - e
        # (frexp's exponent is at most 1024, 0 for inf: only sh > 0 can pass 1024)
        if term > 0.0 and sh > 0 and math.frexp(term)[1] + sh > 1024:     # beyond float64: math.ldexp would raise
            return math.inf             # the rounding scale of t overflows: not conditioned in float64
        total += term if sh == 0 else math.ldexp(term, sh)
        S11, S12, S21, S22 = S11 * sa + S12 * rj, -S11, S21 * sa + S22 * rj, -S21    # S_j = S_{j+1} m_j
        m = max(abs(S11), abs(S12), abs(S21), abs(S22))
        if (m > _FAR or m < _NEAR) and m > 0.0 and m < math.inf:
            f = math.frexp(m)[1]
            S11, S12 = math.ldexp(S11, -f), math.ldexp(S12, -f)
            S21, S22, es = math.ldexp(S21, -f), math.ldexp(S22, -f), es + f
    Ts = total / N * (1.0 + SHARP_UNIT * N)
    if disc == 0.0 or kd == 0.0:        # t = +-2, or some a_j = 0 with lam, p_j not both 0: not decided
        return math.inf
    return float(Ts * (abs(t) + two) / abs(disc) * (kn / kd))     # Ts / ||t| - 2|, as the cheap tier


# ----------------------------------------------------------------------------------------------------------
# The same estimates for many rows at once (the numpy route): bit-identical to the scalar forms, row by row.

#: up to this many rows :func:`sharp_trace_kappa_rows` and :func:`abs_trace_rows` run the scalar form on
#: Python floats, one row after the other (a numpy operation on a few elements costs ~20 Python float
#: operations); from here on, numpy operations over the rows, one site after the other
FEW_ROWS = 16

#: up to this many rows :func:`monodromy_and_abs` runs the two products side by side; from here on numpy's
#: per-call cost is small against the work and the copies that join them cost more than they save (a
#: batch of 10000 states at N = 3: 1.10x, interleaved in one process)
SIDE_BY_SIDE_ROWS = 2048


class _Sites(list[float]):
    """A list of Python floats with the ``shape`` the scalar :func:`sharp_trace_kappa` reads."""

    @property
    def shape(self) -> tuple[int]:
        return (len(self),)


class _Lists:
    """What :func:`sharp_trace_kappa` takes from numpy (``empty``, ``int64``), on Python lists: the scalar
    form then computes on Python floats (a numpy scalar's arithmetic costs ~3x a float's), the same bits."""

    int64 = int

    @staticmethod
    def empty(n: int, dtype: type = float) -> list[float]:
        return [0.0] * n


#: the scalar form as it is, its arrays Python lists (one source: a change of it reaches this form too)
SHARP_ON_FLOATS: Callable[..., float] = clone(sharp_trace_kappa, np=_Lists)


def sharp_on_floats(hooks: Mapping[str, Callable[..., object]]) -> dict[str, Callable[..., object]]:
    """``hooks`` (a float64 arithmetic, e.g. :data:`symbt.numeric.float64.kernels.HOOKS`) with every hook that
    calls :func:`sharp_trace_kappa` cloned to call :data:`SHARP_ON_FLOATS` instead: the same source on Python
    floats, for a plain-Python step whose arrays are lists of floats (a numpy scalar's arithmetic takes ~3x a
    float's).  Cloned at each call, so a hook sees its module's globals as they are then.

    >>> from symbt.numeric.float64.kernels import HOOKS
    >>> new = sharp_on_floats(HOOKS)
    >>> new["decided"].__globals__["sharp_trace_kappa"] is SHARP_ON_FLOATS, new["track"] is HOOKS["track"]
    (True, True)
    """
    def calls_sharp(v: Callable[..., object]) -> bool:
        code = getattr(v, "__code__", None)
        return code is not None and "sharp_trace_kappa" in code.co_names and \
            getattr(v, "__globals__", {}).get("sharp_trace_kappa") is sharp_trace_kappa
    return {k: clone(v, sharp_trace_kappa=SHARP_ON_FLOATS) if calls_sharp(v) else v for k, v in hooks.items()}


def _pymax(*xs: F64) -> F64:
    """Python's ``max(x1, x2, ...)`` elementwise: the first operand unless a later one compares greater
    (so a NaN operand is kept only in first place, as the builtin does)."""
    m = xs[0]
    for x in xs[1:]:
        m = np.where(x > m, x, m)
    return m


def _exponent(m: F64) -> I64:
    """``math.frexp(m)[1]`` elementwise (0 for 0, inf and NaN, as ``math.frexp``)."""
    return np.where(np.isfinite(m) & (m != 0.0), np.frexp(m)[1], 0).astype(np.int64)


def _rescaled(xs: list[F64], e: I64) -> tuple[list[F64], I64]:
    """:func:`sharp_trace_kappa`'s exact power-of-two rescaling of ``xs`` where their largest magnitude
    (Python's ``max``) leaves ``[2**-200, 2**200]``, row by row."""
    m = _pymax(*[np.abs(x) for x in xs])
    hit = ((m > _FAR) | (m < _NEAR)) & (m > 0.0) & (m < math.inf)
    if not hit.any():
        return xs, e
    f = np.where(hit, _exponent(m), 0)
    return [np.ldexp(x, -f) for x in xs], e + f


def sharp_trace_kappa_rows(p: F64, r: F64, lam: F64, lo: F64) -> F64:
    r""":func:`sharp_trace_kappa` of every row of ``p, r`` (shape ``(R, N)``) at ``lam, lo`` (shape ``(R,)``),
    each row bit for bit the scalar call's result (and its ``OverflowError``, where ``math.ldexp`` raises).

    Up to :data:`FEW_ROWS` rows: the scalar source itself on Python floats, row by row.  More rows: the
    same operations in the same order as numpy operations over the rows -- the prefix and suffix products
    one site after the other (with the scalar's rescaling decisions per row), the terms
    ``tr(|S_{j+1}| |m_j| |P_{j-1}|)`` over all sites at once, summed in the scalar's order (from the last
    site down).  Rows where a ``math.ldexp`` of the scalar would overflow are given to the scalar form.

    >>> p = np.array([[-20.0, 10.0, 1.0]] * 20)
    >>> r = np.tile(np.exp(np.diff([1.0, 0.0, 0.9, 1.0])), (20, 1))
    >>> lam, lo = np.full(20, 15.0), np.zeros(20)
    >>> bool(np.all(sharp_trace_kappa_rows(p, r, lam, lo) == sharp_trace_kappa(p[0], r[0], 15.0, 0.0)))
    True
    """
    R, N = p.shape
    if R <= FEW_ROWS:
        return np.array([SHARP_ON_FLOATS(_Sites(p[k].tolist()), _Sites(r[k].tolist()), float(lam[k]),
                                          float(lo[k])) for k in range(R)], dtype=float)
    with np.errstate(all="ignore"):
        return _sharp_over_rows(p, r, lam, lo)


def _sharp_over_rows(p: F64, r: F64, lam: F64, lo: F64) -> F64:
    R, N = p.shape
    a = lam_add(lam[:, None], lo[:, None], p)                   # (R, N): every a_j, as the scalar forms them
    aa = np.abs(a)
    pa, pb = np.empty((R, N)), np.empty((R, N))
    pe = np.zeros((R, N), np.int64)
    A, B, C, D = a[:, 0], np.full(R, -1.0), r[:, 0], np.zeros(R)
    e = np.zeros(R, np.int64)
    kn, kd = np.abs(lam) + np.abs(p[:, 0]), aa[:, 0]
    pa[:, 0], pb[:, 0] = A, B
    for j in range(1, N):
        cn = np.abs(lam) + np.abs(p[:, j])
        up = cn * kd > kn * aa[:, j]
        kn, kd = np.where(up, cn, kn), np.where(up, aa[:, j], kd)
        aj, rj = a[:, j], r[:, j]
        A, B, C, D = aj * A - C, aj * B - D, rj * A, rj * B
        (A, B, C, D), e = _rescaled([A, B, C, D], e)
        pa[:, j], pb[:, j], pe[:, j] = A, B, e
    t = A + D
    two = np.ldexp(2.0, -e)
    disc = (t - two) * (t + two)
    # the prefix P_{j-1} of every site j (identity at j = 0; m_1 at j = 1, second row (r_1, 0))
    P11, P12 = np.ones((R, N)), np.zeros((R, N))
    P21, P22 = np.zeros((R, N)), np.ones((R, N))
    ep = np.zeros((R, N), np.int64)
    if N > 1:
        P11[:, 1:], P12[:, 1:], ep[:, 1:] = np.abs(pa[:, :-1]), np.abs(pb[:, :-1]), pe[:, :-1]
        P21[:, 1], P22[:, 1] = r[:, 0], 0.0           # math.ldexp(r[0], -pe[0]) with pe[0] = 0
    fr = np.ldexp(r[:, 1:N - 1], pe[:, :N - 2] - pe[:, 1:N - 1]) if N > 2 else np.zeros((R, 0))
    P21[:, 2:], P22[:, 2:] = fr * np.abs(pa[:, :N - 2]), fr * np.abs(pb[:, :N - 2])
    hazard = np.isinf(two) | np.isinf(fr).any(axis=1)       # where math.ldexp raises in the scalar form
    # the suffix S_{j+1} of every site j, from the last site down
    S = [np.ones(R), np.zeros(R), np.zeros(R), np.ones(R)]
    es = np.zeros(R, np.int64)
    Sj = np.empty((4, R, N))
    esj = np.empty((R, N), np.int64)
    for j in range(N - 1, -1, -1):
        Sj[:, :, j], esj[:, j] = S, es
        sa, rj = a[:, j], r[:, j]
        S11, S12, S21, S22 = S
        S = [S11 * sa + S12 * rj, -S11, S21 * sa + S22 * rj, -S21]
        S, es = _rescaled(S, es)
    X11, X12 = aa * P11 + P21, aa * P12 + P22
    X21, X22 = r * P11, r * P12
    term = np.abs(Sj[0]) * X11 + np.abs(Sj[1]) * X21 + np.abs(Sj[2]) * X12 + np.abs(Sj[3]) * X22
    sh = esj + ep - e[:, None]
    over = ((term > 0.0) & (_exponent(term) + sh > 1024)).any(axis=1)     # the scalar returns inf there
    parts = np.ldexp(term, np.where(term > 0.0, np.minimum(sh, 1100), 0))
    total = np.add.accumulate(np.concatenate([np.zeros((R, 1)), parts[:, ::-1]], axis=1), axis=1)[:, -1]
    Ts = total / N * (1.0 + SHARP_UNIT * N)
    out = Ts * (np.abs(t) + two) / np.abs(disc) * (kn / kd)
    out = np.where(over | (disc == 0.0) | (kd == 0.0), math.inf, out)
    for k in np.flatnonzero(hazard):
        out[k] = SHARP_ON_FLOATS(_Sites(p[k].tolist()), _Sites(r[k].tolist()), float(lam[k]), float(lo[k]))
    return out


def _range_stats(col: list[float]) -> float:
    """``float(np.maximum(x.max(), -x.min()))`` of the column ``col`` (NaN if any element is NaN)."""
    m = 0.0
    for x in col:
        if x != x:
            return math.nan
        m = max(m, abs(x))
    return m


def abs_trace_rows(a: Sequence[FloatValue], r: Sequence[FloatValue]) -> tuple[F64, Exponent]:
    """``(A + D, e)`` of :func:`~symbt.numeric.core.monodromy.monodromy` ``(FLOAT, [|a_j|], [-r_j])`` -- the
    product of the entrywise absolute values of the ``m_j``, the cheap tier's scale ``T`` -- bit for bit.

    Up to :data:`FEW_ROWS` rows (site lists of equal 1-d arrays, ``N >= 2``): the product on Python floats,
    row by row (:func:`_product_on_floats`); more rows: the monodromy itself.

    >>> a, r = [np.array([2.0, -3.0]), np.array([3.0, 0.5])], [np.array([1.0, 2.0])] * 2
    >>> T, e = abs_trace_rows(a, r)
    >>> T.tolist(), e                               # |a_1| |a_2| + r_1 + r_2
    ([8.0, 5.5], 0)
    """
    sites = _few_rows(a, r)
    if sites is None:
        Aa, _, _, Da, ea = monodromy(FLOAT, [np.abs(x) for x in a], [-x for x in r])
        return np.asarray(Aa + Da), ea
    ents, e = _product_on_floats(np.abs(sites[0]), -sites[1])
    return np.array([x[0] + x[3] for x in ents]), e


def _few_rows(a: Sequence[FloatValue], r: Sequence[FloatValue]) -> tuple[F64, F64] | None:
    """``a, r`` as ``(N, R)`` arrays if they are site lists of ``R <= FEW_ROWS`` rows (1-d, equal) and
    ``N >= 2``, else ``None``."""
    if len(a) < 2 or np.ndim(a[0]) != 1 or not 0 < np.shape(a[0])[0] <= FEW_ROWS:
        return None                     # (before converting many rows)
    try:
        am, rm = np.array(a, dtype=float), np.array(r, dtype=float)
    except ValueError:                  # sites of different shapes: the general form
        return None
    if am.ndim != 2 or am.shape != rm.shape or not 0 < am.shape[1] <= FEW_ROWS or am.shape[0] < 2:
        return None
    return am, rm


def _product_on_floats(am: F64, rm: F64) -> tuple[list[tuple[float, float, float, float]], Exponent]:
    """``monodromy(FLOAT, list(am), list(rm))`` of the ``(N, R)`` arrays ``am, rm`` (``N >= 2``) on Python
    floats: the entries ``(A, B, C, D)`` of every row and the exponents (``0``, or an array where some row
    was renormalised).  :meth:`~symbt.numeric.core.context.FloatContext.out_of_range`'s decision is taken on
    the same numbers -- its test of the whole batch first (Python's ``max`` over the four entries' largest
    magnitudes, NaN if an entry has one), then per row -- and the rows it sends to the renormalised product
    go through :func:`_renormalised_on_floats`."""
    N = am.shape[0]
    ents = []
    for ak, rk in zip(am.T.tolist(), rm.T.tolist()):
        A, B, C, D = ak[0], -1.0, rk[0], 0.0
        for j in range(1, N):
            aj, rj = ak[j], rk[j]
            A, B, C, D = aj * A - C, aj * B - D, rj * A, rj * B
        ents.append((A, B, C, D))
    big = float(np.max([_range_stats([x[i] for x in ents]) for i in range(4)]))   # NaN anywhere: NaN
    if big < 2.0 ** 500 and math.isfinite(big):
        return ents, 0
    # per row: a non-finite entry, or the largest magnitude outside [2**-500, 2**500]
    bad = [not all(math.isfinite(v) for v in x) or not 2.0 ** -500 <= max(abs(v) for v in x) <= 2.0 ** 500
           for x in ents]
    if not any(bad):
        return ents, 0
    e = np.zeros(len(ents), np.int64)
    for k in np.flatnonzero(bad):       # the renormalised product (FloatContext.renormalize after every site)
        A, B, C, D, e[k] = _renormalised_on_floats(am[:, k].tolist(), rm[:, k].tolist())
        ents[k] = (A, B, C, D)
    return ents, e


def _nanmax(x: float, y: float) -> float:
    """``np.maximum`` of two floats (NaN if either is NaN)."""
    return x if x != x or x >= y else y


def _renormalised_on_floats(a: list[float], r: list[float]) -> tuple[float, float, float, float, int]:
    """:func:`~symbt.numeric.core.monodromy.monodromy`'s renormalised product of one row on Python floats:
    after every site the entries are divided by the power of two of their largest magnitude (exact), as
    :meth:`~symbt.numeric.core.context.FloatContext.renormalize` does."""
    A, B, C, D, e = a[0], -1.0, r[0], 0.0, 0
    for j in range(len(a)):
        if j:
            A, B, C, D = a[j] * A - C, a[j] * B - D, r[j] * A, r[j] * B
        mx = _nanmax(_nanmax(abs(A), abs(B)), _nanmax(abs(C), abs(D)))
        k = math.frexp(mx)[1] if mx > 0.0 and mx < math.inf else 0      # np.frexp(inf) has exponent 0
        A, B, C, D, e = math.ldexp(A, -k), math.ldexp(B, -k), math.ldexp(C, -k), math.ldexp(D, -k), e + k
    return A, B, C, D, e


def monodromy_and_abs(a: Sequence[FloatValue], r: Sequence[FloatValue]
                      ) -> tuple[tuple[FloatValue, FloatValue, FloatValue, FloatValue, Exponent],
                                 tuple[F64, Exponent]]:
    """``monodromy(FLOAT, a, r)`` and :func:`abs_trace_rows` ``(a, r)``, bit for bit, in one sweep.

    Up to :data:`FEW_ROWS` rows both on Python floats; up to :data:`SIDE_BY_SIDE_ROWS` rows, the two
    products run as one over the rows side by side (``a_j`` beside ``|a_j|``, ``r_j`` beside ``-r_j``):
    the same operations per element in half the numpy calls, each product's range test and renormalised
    rows decided separately, as two calls would; more rows: the two calls.

    >>> a, r = [np.array([2.0, -3.0] * 9), np.array([3.0, 0.5] * 9)], [np.array([1.0, 2.0] * 9)] * 2
    >>> (A, B, C, D, e), (T, ea) = monodromy_and_abs(a, r)
    >>> (A + D)[:2].tolist(), T[:2].tolist()        # a_1 a_2 - r_1 - r_2 and |a_1| |a_2| + r_1 + r_2
    ([4.0, -5.5], [8.0, 5.5])
    """
    N = len(a)
    few = _few_rows(a, r)
    if few is not None:                 # a few rows: both products on Python floats
        (main, e), (ents, ea) = (_product_on_floats(*few), _product_on_floats(np.abs(few[0]), -few[1]))
        A, B, C, D = (np.array(x) for x in zip(*main))
        return (A, B, C, D, e), (np.array([x[0] + x[3] for x in ents]), ea)
    try:
        am, rm = np.array(a, dtype=float), np.array(r, dtype=float)
    except ValueError:
        am = rm = np.empty(0)
    if N < 2 or am.ndim != 2 or am.shape != rm.shape or not FEW_ROWS < am.shape[1] <= SIDE_BY_SIDE_ROWS:
        return monodromy(FLOAT, a, r), abs_trace_rows(a, r)
    R = am.shape[1]
    a2, r2 = np.concatenate([am, np.abs(am)], axis=1), np.concatenate([rm, -rm], axis=1)
    with np.errstate(over="ignore", invalid="ignore"):
        X = _product(FLOAT, list(a2), list(r2), renorm=False)[:4]
    halves = ([x[:R] for x in X], [x[R:] for x in X])
    if _both_in_range(X, R):            # the usual case: neither product needs a row renormalised
        return (*halves[0], 0), (halves[1][0] + halves[1][3], 0)
    bad = [np.broadcast_to(FLOAT.out_of_range(*h), (R,)) for h in halves]
    out: list[list[FloatValue]] = [list(h) for h in halves]
    es: list[Exponent] = [0, 0]
    if bad[0].any() or bad[1].any():     # the renormalised rows of both products, side by side again
        if bad[0].all() and bad[1].all():          # every row of both (far from the spectrum): no copies
            sub, subr = a2, r2
        else:
            sub = np.concatenate([a2[:, :R][:, bad[0]], a2[:, R:][:, bad[1]]], axis=1)
            subr = np.concatenate([r2[:, :R][:, bad[0]], r2[:, R:][:, bad[1]]], axis=1)
        *Y, e2 = _product(FLOAT, list(sub), list(subr), renorm=True)
        n0 = int(bad[0].sum())
        for i, (b, sl) in enumerate(zip(bad, (slice(0, n0), slice(n0, None)))):
            if b.any():                 # FloatContext.merge, as the monodromy merges its renormalised rows
                out[i] = [_merged(x, b, y[sl]) for x, y in zip(out[i], Y)]
                es[i] = _merged(np.zeros(R, np.int64), b, np.asarray(e2)[sl])
    A, B, C, D = out[0]
    return (A, B, C, D, es[0]), (np.asarray(out[1][0] + out[1][3]), es[1])


def _both_in_range(X: Sequence[FloatValue], R: int) -> bool:
    """Whether :meth:`~symbt.numeric.core.context.FloatContext.out_of_range` returns ``False`` for both halves
    (rows ``:R`` and ``R:``) of the four side-by-side entries ``X``: its whole-batch test -- Python's ``max``
    over the entries, in order, of ``float(np.maximum(x.max(), -x.min()))`` (a NaN entry kept only in first
    place, as the builtin does), below ``2**500`` and finite -- for both halves in four numpy calls instead of
    sixteen, on the same numbers."""
    S = np.array(X, dtype=float).reshape(4, 2, R)
    spans = np.maximum(S.max(axis=2), -S.min(axis=2)).tolist()        # [entry][half]
    for h in (0, 1):
        big = max(spans[i][h] for i in range(4))
        if not (big < 2.0 ** 500 and math.isfinite(big)):
            return False
    return True


def _merged(full: npt.NDArray[_G], mask: npt.NDArray[np.bool_], part: npt.ArrayLike) -> npt.NDArray[_G]:
    if mask.all():                      # every row replaced: the part itself, in the dtype of ``full``
        return np.asarray(part, dtype=full.dtype)
    out = np.array(full, copy=True)
    out[mask] = part
    return out
