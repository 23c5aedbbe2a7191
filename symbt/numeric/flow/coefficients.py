r"""Flow coefficients ``c_k`` of the map (paper eq. ``eqdisc``): one routine, float64 and mpmath.

The map interpolates the time-1 flow of ``G = sum_k c_k H_k`` with

    c_k = -b \int_{lam0-mu}^{lam0+mu} lam^k / sqrt(tr L(lam)^2 - 4) dlam,

positive square root, valid when ``|tr L| > 2`` on the whole interval (``lam1 = lam0 + mu``
and ``lam2 = lam0 - mu`` in one spectral gap; :class:`NoRealMapError` otherwise).

Scaling (relative accuracy at any N).  For N = 64 far from the spectrum ``c_0`` can be
``~1e-149`` while ``c_{63} ~ 1e-30``: an absolute error control (``mpmath.quad``) or an
unscaled float64 integrand loses everything.  So each integrand is evaluated in scaled form
``f_k(lam) 2**(-E_k)`` with an integer ``E_k`` = the (rounded) ``log2`` of its size at three
interior points, and ``tr`` itself is carried as ``T * 2**e`` (2x2 transfer products of
``m_j = [[lam + p_j, -1], [r_j, 0]]``, ``r_j = exp(q_{j+1} - q_j)``, renormalised by powers of
two -- exact, no overflow).  ``c_k = -b 2**E_k \int f_k 2**(-E_k)``.

Quadrature.  float64: adaptive Gauss--Legendre (16 vs 32 nodes per panel, bisection until
they agree to ``rtol`` relative to the local contribution); the integrand goes through
logarithms.  mpmath: tanh-sinh (``mpmath.quad`` on ``[lam2, lam0, lam1]``) with the values
of ``tr`` shared between the ``k`` (same nodes), its error estimate checked.  Both paths
evaluate the same scaled integrand (:func:`scaled_trace`).  The float64 panels are exposed as
a quadrature rule (:func:`flow_quadrature`), which :mod:`symbt.numeric.flow.field` reuses for the
vector field of ``G``.

Examples
--------
>>> from symbt.numeric import flow_coefficients
>>> c = flow_coefficients([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0)
>>> [round(float(v), 4) for v in c]          # the paper's caption: -0.005, -0.048, -0.512
[-0.005, -0.0485, -0.5121]
>>> import mpmath
>>> with mpmath.workdps(30):
...     cm = flow_coefficients([mpmath.mpf(v) for v in (-20, 10, 1)], [1, 0, mpmath.mpf("0.9")], 10, 5)
>>> mpmath.nstr(cm[2], 12)
'-0.512050368038'
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import mpmath
import numpy as np
import numpy.typing as npt

from ..core.context import FLOAT, MP, MPValue, Value
from ..core.errors import InvalidInputError, NoRealMapError, NumericRangeError, QuadratureError
from ..core.inputs import ParamLike, StateLike, _to_mp, check_branch, float_array, prepare_spectral_pair
from ..core.limits import MAX_DQ_FLOAT64
from ..core.problem import StateOut
from ..dispatch import bt_step

__all__ = ["flow_coefficients", "flow_quadrature", "FlowQuadrature", "scaled_trace", "neighbour_ratios_of"]

_LOG2 = math.log(2.0)


# --------------------------------------------------------------------------- input

def _is_mp(*objs: object) -> bool:
    for o in objs:
        if isinstance(o, (mpmath.mpf, mpmath.mpc)):
            return True
        if isinstance(o, (list, tuple)) and _is_mp(*o):
            return True
        if isinstance(o, np.ndarray) and o.dtype == object and _is_mp(*o.ravel().tolist()):
            return True
    return False


def _float_state(p: npt.ArrayLike, q: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    pa, qa = float_array(p, "p"), float_array(q, "q")     # complex, text, 10**400: typed errors
    if pa.ndim != 1 or pa.shape != qa.shape:
        raise InvalidInputError("flow_coefficients takes a single state (p, q of shape (N,))")
    if not (np.all(np.isfinite(pa)) and np.all(np.isfinite(qa))):
        raise InvalidInputError("p and q must be finite (found NaN or inf)")
    return pa, qa


def neighbour_ratios_of(q: Sequence[float] | Sequence[MPValue]) -> list[float] | list[MPValue]:
    """``r_j = exp(q_{j+1} - q_j)`` (cyclic), float64 (range-checked) or mpf."""
    N = len(q)
    dq = [q[(j + 1) % N] - q[j] for j in range(N)]
    if isinstance(q[0], mpmath.mpf):
        return [mpmath.exp(d) for d in dq]
    worst = max(abs(float(d)) for d in dq)
    if worst > MAX_DQ_FLOAT64:
        raise NumericRangeError("|q_{j+1} - q_j| = %.4g exceeds the float64 range (limit %g); "
                                "use mpmath inputs" % (worst, MAX_DQ_FLOAT64))
    return [math.exp(float(d)) for d in dq]


# --------------------------------------------------------------------------- tr L(lam), scaled

def scaled_trace(lam: Value, p: Sequence[Value], r: Sequence[Value]) -> tuple[Value, Value]:
    """``tr L(lam) = T * 2**e`` by the 2x2 transfer product; returns ``(T, e)``.

    float64: ``lam`` an array of nodes, the product renormalised by a power of two at every
    site (exact), ``e`` an integer array; mpmath: ``lam`` an mpf, ``e = 0``.

    >>> T, e = scaled_trace(np.array([3.0]), [-20.0, 10.0, 1.0], neighbour_ratios_of([1.0, 0.0, 0.9]))
    >>> float(np.ldexp(T, e)[0])                                 # tr L(3) of the paper's example
    -858.025486...
    """
    if not isinstance(lam, np.ndarray):
        A, B, C, D = lam + p[0], mpmath.mpf(-1), r[0], mpmath.mpf(0)
        for j in range(1, len(p)):
            a = lam + p[j]
            A, B, C, D = a * A - C, a * B - D, r[j] * A, r[j] * B
        return A + D, 0
    lam = np.asarray(lam, dtype=float)
    A = lam + p[0]
    B = np.full_like(lam, -1.0)
    C = np.full_like(lam, r[0])
    D = np.zeros_like(lam)
    e = np.zeros(lam.shape, dtype=np.int64)
    with np.errstate(over="ignore", invalid="ignore"):
        for j in range(len(p)):
            if j:
                a = lam + p[j]
                A, B, C, D = a * A - C, a * B - D, r[j] * A, r[j] * B
            _, s = np.frexp(np.maximum(np.maximum(np.abs(A), np.abs(B)), np.maximum(np.abs(C), np.abs(D))))
            A, B, C, D = np.ldexp(A, -s), np.ldexp(B, -s), np.ldexp(C, -s), np.ldexp(D, -s)
            e += s
        T = A + D
    if not np.all(np.isfinite(T)):
        raise NumericRangeError("tr L(lam) beyond the float64 range of the scaled product (|lam| ~ 1e308?)")
    return T, e


def _log2_inv_disc(T: np.ndarray, e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``log2(1/sqrt(tr^2 - 4))`` for ``tr = T 2**e``, and the scaled discriminant (must be > 0)."""
    two = np.ldexp(2.0, -e)
    with np.errstate(all="ignore"):
        disc = (T - two) * (T + two)
        return -e - 0.5 * np.log2(disc), disc


# --------------------------------------------------------------------------- float64 rule

@dataclass(frozen=True)
class FlowQuadrature:
    """Composite Gauss--Legendre rule on ``[lam0 - mu, lam0 + mu]`` for the state it was built at.

    ``c_k ~= -b sum_i w_i lam_i^k / sqrt(tr_0(lam_i)^2 - 4)``: ``nodes`` ``lam_i``, ``weights``
    ``w_i`` (signed: negative for ``mu < 0``), ``log2_inv`` = ``log2(1/sqrt(tr_0^2 - 4))`` at
    the nodes, ``log2_tr`` = ``log2|tr_0|``.  :meth:`moments` gives the ``c_k``.
    """

    nodes: np.ndarray
    weights: np.ndarray
    log2_inv: np.ndarray
    log2_tr: np.ndarray
    branch: int
    N: int
    panels: int

    def moments(self, ks: Iterable[int]) -> np.ndarray:
        """``c_k`` for ``k`` in ``ks`` from this rule (float64, scaled per ``k``; no overflow)."""
        ks = np.asarray(list(ks), dtype=float)
        L, sgn = _log2_rows(self.nodes, self.log2_inv, ks)
        E = np.floor(np.max(L, axis=1))
        with np.errstate(all="ignore"):
            I = (sgn * np.exp2(L - E[:, None])) @ self.weights
            out = -self.branch * np.ldexp(I, E.astype(np.int64))
        if not np.all(np.isfinite(out)):
            raise NumericRangeError("a flow coefficient c_k overflows float64; use mpmath inputs")
        return out


def _log2_rows(lam: np.ndarray, log2_inv: np.ndarray, ks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``log2|lam^k / sqrt(tr^2-4)|`` and its sign, rows k."""
    with np.errstate(divide="ignore", invalid="ignore"):
        la = np.log2(np.abs(lam))
        L = ks[:, None] * la[None, :] + log2_inv[None, :]
    L = np.where(ks[:, None] == 0, log2_inv[None, :], L)     # 0 * log(0) is not an issue for k = 0
    odd = (ks % 2 == 1)[:, None]
    sgn = np.where(odd & (lam < 0)[None, :], -1.0, 1.0)
    return L, sgn


_GL: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def _gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    if n not in _GL:
        _GL[n] = np.polynomial.legendre.leggauss(n)
    return _GL[n]


def adaptive_panels(rows: Callable[[np.ndarray], np.ndarray], a: float, b: float, rtol: float,
                    max_intervals: int, groups: np.ndarray | None = None) -> list[tuple[float, float]]:
    """Panels of ``[a, b]`` on which 16- and 32-point Gauss--Legendre agree for every row.

    ``rows(nodes)`` returns the integrands (rows, nodes), already scaled to O(1) magnitudes;
    it raises :class:`NoRealMapError` where ``|tr| <= 2``.  Agreement is required to ``rtol``
    relative to ``max(|local integral|, scale * width share)``, ``scale`` = the row's whole
    integral, or the largest whole integral of its group (``groups[row]``: the components of
    one vector are judged against the vector's size).
    """
    x16, w16 = _gauss_legendre(16)
    x32, w32 = _gauss_legendre(32)

    def rule(lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
        c, h = 0.5 * (lo + hi), 0.5 * (hi - lo)
        return h * (rows(c + h * x32) @ w32), h * (rows(c + h * x16) @ w16)

    i32, i16 = rule(a, b)
    scale = _group_scale(np.abs(i32), groups)
    todo = [(a, b, i32, i16)]
    done: list[tuple[float, float]] = []
    n = 1
    while todo:
        lo, hi, i32, i16 = todo.pop()
        width = abs(hi - lo) / abs(b - a)
        if np.all(np.abs(i32 - i16) <= rtol * np.maximum(np.abs(i32), scale * width)):
            done.append((lo, hi))
            continue
        mid = 0.5 * (lo + hi)
        if n >= max_intervals or mid in (lo, hi):
            raise QuadratureError("flow_coefficients: adaptive Gauss-Legendre did not converge "
                                  "(an endpoint is very close to a band edge?)")
        todo.append((lo, mid) + rule(lo, mid))
        todo.append((mid, hi) + rule(mid, hi))
        n += 1
    done.sort(key=lambda t: min(t))
    return done


def _group_scale(v: np.ndarray, groups: np.ndarray | None) -> np.ndarray:
    if groups is None:
        return v
    out = v.copy()
    for g in np.unique(groups):
        out[groups == g] = np.max(v[groups == g])
    return out


def _trace_rows(P: Sequence[float], r: Sequence[float]) -> Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]:
    def f(lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        T, e = scaled_trace(lam, P, r)
        l2, disc = _log2_inv_disc(T, e)
        if not np.all(disc > 0):
            raise NoRealMapError("|tr L(lam)| <= 2 inside [lam0 - mu, lam0 + mu]: the interval crosses a band",
                                 condition="trace")
        return l2, T
    return f


def _c_rows(P: Sequence[float], r: Sequence[float], ks: np.ndarray, E: np.ndarray
            ) -> Callable[[np.ndarray], np.ndarray]:
    trace = _trace_rows(P, r)

    def rows(lam: np.ndarray) -> np.ndarray:
        l2, _ = trace(lam)
        L, sgn = _log2_rows(lam, l2, ks)
        with np.errstate(all="ignore"):
            return sgn * np.exp2(L - E[:, None])
    return rows


def _row_scales(P: Sequence[float], r: Sequence[float], a: float, b: float, ks: np.ndarray) -> np.ndarray:
    """Integer ``E_k`` ~ log2 of the size of the k-th integrand (three interior points)."""
    probe = np.array([a + 0.25 * (b - a), 0.5 * (a + b), a + 0.75 * (b - a)])
    l2, _ = _trace_rows(P, r)(probe)
    L, _ = _log2_rows(probe, l2, ks)
    return np.floor(np.max(L, axis=1))


def flow_quadrature(p: npt.ArrayLike, q: npt.ArrayLike, lam0: float, mu: float, *, branch: int = 1, rtol: float = 1e-13,
                    max_intervals: int = 4000,
                    extra_rows: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray] | None = None,
                    compress: float | None = None, check: bool = True) -> FlowQuadrature:
    """The float64 quadrature rule behind :func:`flow_coefficients` (single float64 state).

    Panels are refined until every ``c_k`` integrand (k = 0..N, scaled) converges; if
    ``extra_rows(lam, log2_inv, T)`` is given, its rows (O(1), one vector) must converge too --
    :mod:`symbt.numeric.flow.field` passes the integrand of the vector field.  ``compress`` (a
    tolerance): replace the composite rule by the smallest single Gauss--Legendre rule on the
    whole interval (8 to 128 nodes) whose integrals agree with the composite ones to ``compress``
    (relative; the extra rows as one vector if given -- they define the field --, else every
    ``c_k``; the composite 32-point panels are far more accurate than their 16-vs-32 estimate).

    >>> rule = flow_quadrature([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0)
    >>> [round(float(v), 4) for v in rule.moments(range(3))]
    [-0.005, -0.0485, -0.5121]
    """
    branch = check_branch(branch)
    P, Q = _float_state(p, q)
    lam0, mu = prepare_spectral_pair(FLOAT, lam0, mu, ())
    a, b = lam0 - mu, lam0 + mu
    N = P.size
    r = neighbour_ratios_of(Q.tolist())
    Pl = P.tolist()
    if check:
        bt_step(P, Q, lam0, mu, branch=branch)     # the real map exists <=> lam1, lam2 in one gap
    if a == b:
        raise InvalidInputError("flow_quadrature: lam0 - mu == lam0 + mu (mu below the float spacing)")
    ks = np.arange(N + 1, dtype=float)
    E = _row_scales(Pl, r, a, b, ks)
    crow = _c_rows(Pl, r, ks, E)
    trace = _trace_rows(Pl, r)
    groups = None
    if extra_rows is None:
        rows = crow
    else:
        def rows(lam: np.ndarray) -> np.ndarray:
            l2, T = trace(lam)
            return np.vstack([crow(lam), extra_rows(lam, l2, T)])
        groups = np.r_[np.arange(N + 1), np.full(rows(np.array([0.5 * (a + b)])).shape[0] - N - 1, -1)]
    with np.errstate(all="ignore"):
        panels = adaptive_panels(rows, a, b, rtol, max_intervals, groups)
        x32, w32 = _gauss_legendre(32)
        lo = np.array([t[0] for t in panels])
        hi = np.array([t[1] for t in panels])
        c, h = 0.5 * (lo + hi), 0.5 * (hi - lo)
        nodes = (c[:, None] + h[:, None] * x32[None, :]).ravel()
        weights = (h[:, None] * w32[None, :]).ravel()
        if compress is not None:
            judged = slice(None) if extra_rows is None else slice(N + 1, None)
            ref = (rows(nodes) @ weights)[judged]
            scale = _group_scale(np.abs(ref), None if groups is None else groups[judged])
            for n in (8, 12, 16, 20, 24, 32, 40, 48, 56, 64, 80, 96, 112, 128):
                if n >= nodes.size:
                    break
                x, w = _gauss_legendre(n)
                nd, wt = 0.5 * (a + b) + 0.5 * (b - a) * x, 0.5 * (b - a) * w
                if np.all(np.abs((rows(nd) @ wt)[judged] - ref) <= compress * np.maximum(np.abs(ref), scale)):
                    nodes, weights = nd, wt
                    panels = [(a, b)]
                    break
        l2, T = trace(nodes)
        _, e = scaled_trace(nodes, Pl, r)
        log2_tr = np.log2(np.abs(T)) + e
    return FlowQuadrature(nodes, weights, l2, log2_tr, branch, N, len(panels))


# --------------------------------------------------------------------------- public routine

def flow_coefficients(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, *, branch: int = 1,
                      ks: Iterable[int] | None = None, check: bool = True, rtol: float = 1e-13,
                      max_intervals: int = 4000) -> StateOut:
    r"""Coefficients ``c_k`` of the flow interpolated by the map (eq. ``eqdisc``), see the module docstring.

    ``ks``: which ``k`` (default ``0..N-1``; ``k = N``, the coefficient of ``H_N = 1``, is
    allowed).  float64 (a single state ``p, q`` of shape (N,)): returns an array, adaptive
    Gauss--Legendre to ``rtol`` (:class:`QuadratureError` beyond ``max_intervals`` panels).
    mpmath (any argument an mpf): returns a list of mpf at the current precision (tanh-sinh;
    a ``RuntimeWarning`` if its error estimate stays above ``10**(5 - dps)`` relative after a
    retry with 10 more digits).  ``check``: first require the real map to exist
    (:func:`~symbt.numeric.bt_step`; ``lam1``, ``lam2`` in one gap).  :class:`NoRealMapError`
    when ``|tr| <= 2`` on the interval.  ``mu = 0`` gives zeros, and so does an mpmath
    integral that cancels to exactly 0 at the working precision (e.g. ``k = 1`` on an interval
    symmetric about 0 where ``tr`` is nearly even); ``mu < 0`` is the reversed
    interval (``c(-mu, b) = c(mu, -b)``).
    """
    branch = check_branch(branch)
    if _is_mp(p, q, lam0, mu):
        Pm, Qm = _to_mp(MP, p, "p"), _to_mp(MP, q, "q")
        if len(Pm) != len(Qm) or len(Pm) < 2:
            raise InvalidInputError("p and q must have the same length N >= 2")
        l0m, mum = _to_mp(MP, [lam0, mu], "lam0, mu")
        kl = _selection(ks, len(Pm))
        if mum == 0:
            return [mpmath.mpf(0)] * len(kl)
        if check:
            bt_step(Pm, Qm, l0m, mum, branch=branch)
        return _coefficients_mp(Pm, Qm, l0m, mum, branch, kl)
    P, Q = _float_state(p, q)
    if P.size < 2:
        raise InvalidInputError("need N >= 2 sites, got N = %d" % P.size)
    lam0, mu = prepare_spectral_pair(FLOAT, lam0, mu, ())
    kl = _selection(ks, P.size)
    if mu == 0:
        return np.zeros(len(kl))
    if check:
        bt_step(P, Q, lam0, mu, branch=branch)
    r = neighbour_ratios_of(Q.tolist())
    Pl = P.tolist()
    a, b = lam0 - mu, lam0 + mu
    kk = np.asarray(kl, dtype=float)
    if a == b:
        # |mu| below the spacing of floats at lam0: the integral is 2 mu f(lam0) to relative O(mu^2)
        l2, _ = _trace_rows(Pl, r)(np.array([lam0]))
        L, sgn = _log2_rows(np.array([lam0]), l2, kk)
        with np.errstate(all="ignore"):
            out = -branch * 2.0 * mu * sgn[:, 0] * np.exp2(L[:, 0])
        if not np.all(np.isfinite(out)):
            raise NumericRangeError("a flow coefficient c_k overflows float64; use mpmath inputs")
        return out
    E = _row_scales(Pl, r, a, b, kk)
    rows = _c_rows(Pl, r, kk, E)
    with np.errstate(all="ignore"):
        panels = adaptive_panels(rows, a, b, rtol, max_intervals)
        x32, w32 = _gauss_legendre(32)
        I = np.zeros(len(kl))
        for lo, hi in panels:
            c, h = 0.5 * (lo + hi), 0.5 * (hi - lo)
            I += h * (rows(c + h * x32) @ w32)
        out = -branch * np.ldexp(I, E.astype(np.int64))
    if not np.all(np.isfinite(out)):
        raise NumericRangeError("a flow coefficient c_k overflows float64; use mpmath inputs")
    return out


def _selection(ks: Iterable[int] | None, N: int) -> list[int]:
    kl = list(range(N)) if ks is None else [int(k) for k in ks]
    if any(k < 0 or k > N for k in kl):
        raise InvalidInputError("ks must lie in 0..N")
    return kl


def _coefficients_mp(P: list[MPValue], Q: list[MPValue], lam0: MPValue, mu: MPValue, branch: int,
                     ks: list[int]) -> list[MPValue]:
    """mpmath path: tanh-sinh per k on the scaled integrand, ``tr`` values shared between the k."""
    r = neighbour_ratios_of(Q)
    memo: dict[MPValue, MPValue] = {}

    def inv(lam: MPValue) -> MPValue:
        v = memo.get(lam)
        if v is None:
            t, _ = scaled_trace(lam, P, r)
            disc = (t - 2) * (t + 2)
            if not disc > 0:
                raise NoRealMapError("|tr L(lam)| <= 2 inside [lam0 - mu, lam0 + mu]", condition="trace")
            v = memo[lam] = 1 / mpmath.sqrt(disc)
        return v

    a, b = lam0 - mu, lam0 + mu
    dps = mpmath.mp.dps
    out = []
    for k in ks:
        probes = [a + (b - a) * mpmath.mpf(f) for f in ("0.25", "0.5", "0.75")]
        E = max(int(mpmath.floor(mpmath.log(abs(x ** k * inv(x)), 2))) for x in probes if x ** k * inv(x) != 0)

        def f(lam: MPValue, k: int = k, E: int = E) -> MPValue:
            return mpmath.ldexp(lam ** k * inv(lam), -E)

        val, err = mpmath.quad(f, [a, lam0, b], error=True)
        # f is scaled to O(1) at the probes, so an integral that cancels to exactly 0 is judged
        # against that scale (1), not against itself: the result is 0 to the quadrature's error
        if err > (abs(val) or 1) * mpmath.mpf(10) ** (5 - dps):
            with mpmath.workdps(dps + 10):
                memo.clear()
                val, err = mpmath.quad(f, [a, lam0, b], error=True, maxdegree=10)
                memo.clear()
            if err > (abs(val) or 1) * mpmath.mpf(10) ** (5 - dps):
                warnings.warn("flow_coefficients: mpmath.quad error estimate %s (relative)"
                              % mpmath.nstr(err / (abs(val) or 1), 3), RuntimeWarning, stacklevel=3)
        out.append(-branch * mpmath.ldexp(+val, E))
    return out
