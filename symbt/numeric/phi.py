r"""Spectral quantities of the map: the real Φ and the flow coefficients ``c_k``.

Φ (paper eqs. ``vqqtmu``, ``newkmu``, App. B).  On the map,
``Φ = sum_k ln|(eta_k + mu)/(eta_k - mu)|`` equals ``ln|v(lam1)| - ln|v_z(lam2)|``
where ``v(lam1) = (tr1 - g1)/2`` and ``v_z(lam2) = (tr2 + g2)/2`` are the eigenvalues
of the two kernel vectors.  Written with traces this is

    Φ = branch * ( -sgn(tr1) arccosh(|tr1|/2) - sgn(tr2) arccosh(|tr2|/2) ).

The paper's eq. ``newkmu``, ``-arccosh(tr1/2) - arccosh(tr2/2)``, is the case
``tr > 2``, ``branch = +1`` only (for ``tr < -2`` it is not even real).

Flow coefficients (eq. ``eqdisc``).  The map interpolates the flow of
``sum_k c_k H_k`` with

    c_k = -branch * \int_{lam0-mu}^{lam0+mu} lam^k / sqrt(tr L(lam)^2 - 4) dlam,

positive square root, valid when ``|tr| > 2`` on the whole interval (``lam1``
and ``lam2`` in the same spectral gap; otherwise :class:`NoRealMapError`).

Examples
--------
>>> from symbt.numeric import phi, flow_coefficients
>>> round(float(phi([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0)), 10)
14.8058092993
>>> c = flow_coefficients([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0)
>>> [round(float(v), 4) for v in c]          # the paper's caption: -0.005, -0.048, -0.512
[-0.005, -0.0485, -0.5121]
"""

from __future__ import annotations

import math
import warnings

import mpmath
import numpy as np

from ._input import IV, as_state_pair, check_branch, prepare_spectral_pair
from .context import FLOAT
from .errors import InvalidInputError, NoRealMapError, QuadratureError
from .lax import monodromy, neighbour_ratios
from .step import bt_step, eigen_slopes

__all__ = ["phi", "flow_coefficients"]


def phi(p, q, lam0, mu, *, branch=1):
    """The real Φ of the map (see module docstring); O(N) per state.

    Only the trace condition ``|tr L(lam_i)| > 2`` is checked (Φ is a spectral
    quantity); :class:`NoRealMapError` otherwise.  float64: array of the batch
    shape (0-d for one state); mpmath: mpf.
    """
    branch = check_branch(branch)
    ctx, P, Q, shape = as_state_pair(p, q, lam0, mu)
    if ctx is IV:
        raise InvalidInputError("phi takes float64 or mpf inputs (interval arithmetic covers bt_step only)")
    lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
    if ctx is FLOAT and 0 in shape:
        return np.zeros(shape)  # an empty batch has an empty Φ
    r = neighbour_ratios(ctx, Q)
    out = 0
    with np.errstate(all="ignore"):
        for lam, name in ((lam0 + mu, "lam1"), (lam0 - mu, "lam2")):
            S = eigen_slopes(ctx, [lam + pj for pj in P], r, 1, need_slopes=False)
            if not ctx.all_positive(S.trace_ok):
                raise NoRealMapError("no real Φ: |tr L(%s)| <= 2" % name, condition="trace")
            L = ctx.acosh_half_abs(S.t, S.g, S.e)
            sgn = np.sign(S.t) if ctx is FLOAT else mpmath.sign(S.t)
            out = out - sgn * L
    out = branch * out
    if ctx is FLOAT:
        return np.asarray(out, dtype=float).reshape(shape)
    return +out


_GL = {}


def _gauss_legendre(n):
    if n not in _GL:
        _GL[n] = np.polynomial.legendre.leggauss(n)
    return _GL[n]


def _integrand(lam, P, r, kmax):
    """Rows ``lam^k / sqrt(tr^2 - 4)`` for k < kmax at the nodes ``lam`` (float64).

    Evaluated through logarithms and the scaled monodromy so that neither
    ``lam^k`` nor ``tr`` overflow; returns (values, min of scaled ``tr^2-4``).
    """
    A, B, C, D, e = monodromy(FLOAT, [lam + pj for pj in P], r)
    t = A + D
    two = np.ldexp(2.0, -np.asarray(e)) if np.ndim(e) else 2.0
    disc = (t - two) * (t + two)
    with np.errstate(all="ignore"):
        base = -(np.asarray(e, dtype=float) * math.log(2.0)) - 0.5 * np.log(disc)
        la = np.log(np.abs(lam))
        k = np.arange(kmax)[:, None]
        sign = np.where(lam < 0, (-1.0) ** k, 1.0)
        vals = sign * np.exp(k * la + base)
        vals = np.where(k == 0, np.exp(base), vals)
    return vals, float(np.min(disc)) if disc.size else 1.0


def _adaptive(P, r, a, b, kmax, rtol, max_intervals):
    x16, w16 = _gauss_legendre(16)
    x32, w32 = _gauss_legendre(32)

    def rule(lo, hi):
        c, h = 0.5 * (lo + hi), 0.5 * (hi - lo)
        v16, m16 = _integrand(c + h * x16, P, r, kmax)
        v32, m32 = _integrand(c + h * x32, P, r, kmax)
        if not (m16 > 0 and m32 > 0):
            raise NoRealMapError("|tr L(lam)| <= 2 inside [lam0 - mu, lam0 + mu]: the interval "
                                 "crosses a band", condition="trace")
        return h * (v32 @ w32), h * (v16 @ w16)

    todo = [(a, b) + rule(a, b)]
    scale = np.abs(todo[0][2])
    done = np.zeros(kmax)
    n = 1
    errsum = np.zeros(kmax)
    while todo:
        lo, hi, i32, i16 = todo.pop()
        err = np.abs(i32 - i16)
        width = abs(hi - lo) / abs(b - a)
        if np.all(err <= rtol * np.maximum(np.abs(i32), scale * width)) or hi - lo == 0:
            done += i32
            errsum += err
            continue
        mid = 0.5 * (lo + hi)
        if n >= max_intervals or mid in (lo, hi):
            raise QuadratureError("flow_coefficients: adaptive Gauss-Legendre did not converge "
                                  "(an endpoint is very close to a band edge?)")
        todo.append((lo, mid) + rule(lo, mid))
        todo.append((mid, hi) + rule(mid, hi))
        n += 1
    return done, errsum


def flow_coefficients(p, q, lam0, mu, *, branch=1, rtol=1e-13, max_intervals=4000):
    r"""Coefficients ``c_0..c_{N-1}`` of the flow interpolated by the map (eq. ``eqdisc``).

    float64 (a single state ``p, q`` of shape (N,)): adaptive Gauss–Legendre
    (16 vs 32 nodes per subinterval, bisection where they differ by more than
    ``rtol`` relative to the local contribution); the integrand is evaluated
    via logarithms of the scaled monodromy.  Raises :class:`QuadratureError`
    if the error estimate is not met within ``max_intervals`` subintervals,
    and :class:`NoRealMapError` if ``|tr| <= 2`` somewhere on the interval
    (checked at every node and by requiring the real map to exist).
    mpmath inputs: ``mpmath.quad`` (tanh-sinh) per ``k`` at the current
    precision, with its error estimate checked; if it stays above
    ``10**(5 - dps)`` relative after a split and 10 more digits, a
    ``RuntimeWarning`` is issued and the value returned (``mpmath.quad``
    controls the absolute error, so tiny integrals, e.g. ``c_0 ~ 1e-149`` for
    N = 64 far from the spectrum, may be only ~1e-11 relative accurate).
    Returns a list of mpf.
    """
    branch = check_branch(branch)
    ctx, P, Q, shape = as_state_pair(p, q, lam0, mu)
    if ctx is FLOAT and shape != ():
        raise InvalidInputError("flow_coefficients takes a single state (p, q of shape (N,))")
    if ctx is not FLOAT and not isinstance(P[0], mpmath.mpf):
        raise InvalidInputError("flow_coefficients does not support interval inputs")
    lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
    N = len(P)
    if mu == 0:
        return np.zeros(N) if ctx is FLOAT else [mpmath.mpf(0)] * N
    # existence of the real map <=> lam1, lam2 in the same gap; raises otherwise
    bt_step(p, q, lam0, mu, branch=branch)
    r = neighbour_ratios(ctx, Q)
    if ctx is FLOAT:
        P1 = [float(v[0]) for v in P]
        r1 = [float(v[0]) for v in r]
        if lam0 - mu == lam0 + mu:
            # |mu| below the spacing of floats at lam0: the integral is 2 mu f(lam0) to
            # relative O(mu^2) (bisection would divide by the zero interval width)
            vals, _ = _integrand(np.array([float(lam0)]), P1, r1, N)
            return -branch * 2.0 * mu * vals[:, 0]
        I, err = _adaptive(P1, r1, lam0 - mu, lam0 + mu, N, rtol, max_intervals)
        return -branch * I

    def trace(lam):
        A, B, C, D, _ = monodromy(ctx, [lam + pj for pj in P], r)
        return A + D

    out = []
    for k in range(N):
        def f(lam, k=k):
            t = trace(lam)
            return lam**k / mpmath.sqrt((t - 2) * (t + 2))
        val, err = mpmath.quad(f, [lam0 - mu, lam0 + mu], error=True)
        if err > abs(val) * mpmath.mpf(10) ** (-mpmath.mp.dps + 5) + mpmath.mpf(10) ** (-mpmath.mp.dps):
            with mpmath.workdps(mpmath.mp.dps + 10):
                val, err = mpmath.quad(f, [lam0 - mu, lam0, lam0 + mu], error=True, maxdegree=10)
            if err > abs(val) * mpmath.mpf(10) ** (-mpmath.mp.dps + 5):
                warnings.warn("flow_coefficients: mpmath.quad error estimate %s" % mpmath.nstr(err, 3),
                              RuntimeWarning, stacklevel=2)
        if isinstance(val, mpmath.mpc):
            raise NoRealMapError("|tr L(lam)| <= 2 inside the interval", condition="trace")
        out.append(-branch * val)
    return out
