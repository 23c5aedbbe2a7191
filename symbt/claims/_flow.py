r"""Float64 tools of the Theorem 2 and inverse-problem claims: quadrature, Hamiltonian flows, Newton.

The claims of Theorem 2 sample 16 states per domain cell; at that count the 40-digit Taylor
integration of :mod:`symbt.reference.taylor` (about a second a state) is out of budget, so the
*independent* side runs in float64 here, with tolerances far above its rounding (1e-10) and
far below what a wrong sign or a wrong :math:`c_k` produces (O(1) relative):

* :func:`gl_integral` -- composite Gauss-Legendre quadrature (vectorised numpy), panels doubled
  until two estimates agree to ``rtol``; complex integrands allowed (principal branches);
* :func:`time_flow` -- the time-t flow of :math:`\sum_k c_kH_k` (Hamilton's equations
  :math:`\dot q = \partial G/\partial p`, :math:`\dot p = -\partial G/\partial q`), by heyoka's
  Taylor integrator when installed (``heyoka.taylor_adaptive``, float64, compiled once per N with
  the :math:`c_k` as runtime parameters), else by :func:`symbt.reference.taylor.hamiltonian_flow`
  at 20 digits (:func:`flow_route` says which route runs by default; ``route=`` forces one, and
  :func:`flow_routes` lists every route installed: the claim ``Hdiscr.routes`` runs each of them, so
  the built-in route is checked whatever is installed).  The built-in route runs within a budget
  (:data:`TAYLOR_MAX_STEPS` Taylor steps, :data:`TAYLOR_SECONDS` seconds): a flow it cannot finish
  raises :class:`FlowBudgetExceeded` instead of running for minutes (a wrong vector field that
  blows up shrinks the steps without end);
* :func:`moments`, :func:`solve_signed` -- the constants
  :math:`c_k(\lambda_0, m) = -\int_{\lambda_0-m}^{\lambda_0+m}\lambda^k(\operatorname{tr}L^2-4)^{-1/2}d\lambda`
  (signed m: branch b at mu is branch +1 at b mu) and their inversion by damped Newton /
  Gauss-Newton with the closed-form Jacobian (the float64 twin of :mod:`symbt.reference.inverse`).

>>> import numpy as np
>>> abs(float(gl_integral(np.exp, 0.0, 1.0)) - (np.e - 1)) < 1e-14
True
"""
from __future__ import annotations

from collections.abc import Callable
from functools import cache
from typing import Any

import mpmath as mp
import numpy as np

from ..reference.trace import hamiltonians, trace_polynomial

__all__ = ["gl_integral", "hamiltonians_float", "in_domain", "time_flow", "flow_route", "flow_routes", "moments",
           "solve_signed", "rel_diff", "QuadratureNotConverged", "FlowBudgetExceeded", "TAYLOR_MAX_STEPS",
           "TAYLOR_SECONDS"]

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(16)


#: the built-in route's budget: Taylor steps per unit of time (a time-1 flow of the claims' samples takes 1-3),
#: and seconds per flow
TAYLOR_MAX_STEPS = 16
TAYLOR_SECONDS = 60.0


class FlowBudgetExceeded(ArithmeticError):
    """The built-in Taylor route did not finish a flow within :data:`TAYLOR_MAX_STEPS` / :data:`TAYLOR_SECONDS`."""


class QuadratureNotConverged(ArithmeticError):
    """Composite Gauss-Legendre did not settle (an integrable singularity on the interval)."""


@cache
def _panel_rule(panels: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of ``panels`` equal 16-point Gauss-Legendre panels on [-1, 1]."""
    mid = (2 * np.arange(panels) + 1) / panels - 1
    return (mid[:, None] + _NODES[None, :] / panels).ravel(), np.tile(_WEIGHTS / panels, panels)


def gl_integral(f: Callable[[np.ndarray], Any], a: float, b: float, *, rtol: float = 1e-13,
                max_panels: int = 512) -> np.ndarray:
    """``int_a^b f`` for a vectorised ``f`` (values of shape ``(..., len(x))``), composite 16-point GL."""
    prev = None
    panels = 2
    c, h = (a + b) / 2, (b - a) / 2
    while panels <= max_panels:
        u, w = _panel_rule(panels)
        x = c + h * u
        vals = np.asarray(f(x))
        if vals.shape[-1:] != (x.size,):
            vals = np.broadcast_to(vals[..., None], vals.shape + (x.size,))
        est = (vals @ w) * h
        if prev is not None and np.all(np.abs(est - prev) <= rtol * np.maximum(1.0, np.abs(est))):
            return est
        prev, panels = est, panels * 2
    raise QuadratureNotConverged(f"no convergence on [{a}, {b}] with {max_panels} panels")


def horner(H, x):
    """tr L(x) = sum_k H_k x^k (H ascending), vectorised."""
    y = H[-1] + 0 * x
    for h in H[-2::-1]:
        y = y * x + h
    return y


def hamiltonians_float(p, q) -> np.ndarray:
    """``[H_0, ..., H_N]`` (tr L = sum H_k lam^k) as float64, computed in mpmath."""
    with mp.workdps(30):
        return np.array([float(h) for h in hamiltonians(p, q)])


@cache
def _crossings(H: tuple) -> np.ndarray:
    """Real roots of tr L = +-2 (tr given by its coefficients H)."""
    out = []
    for shift in (2.0, -2.0):
        c = np.array(H[::-1])
        c[-1] -= shift
        r = np.roots(c)
        out.extend(r.real[np.abs(r.imag) < 1e-9])
    return np.array(out)


def in_domain(H: np.ndarray, lo: float, hi: float) -> bool:
    """|tr L| > 2 on [lo, hi] (no root of tr = +-2 there), tr given by its coefficients H."""
    lo, hi = min(lo, hi), max(lo, hi)
    r = _crossings(tuple(float(h) for h in H))
    return not np.any((r >= lo - 1e-12) & (r <= hi + 1e-12)) and abs(horner(H, lo)) > 2


def rel_diff(xs, ys) -> float:
    return max(abs(float(a) - float(b)) / max(1.0, abs(float(b))) for a, b in zip(xs, ys))


# --------------------------------------------------------------------------- flows

@cache
def _heyoka_integrator(N: int):
    import heyoka as hy

    q = hy.make_vars(*[f"q{j}" for j in range(N)])
    p = hy.make_vars(*[f"p{j}" for j in range(N)])
    fac = list(p) + [hy.exp(q[(j + 1) % N] - q[j]) for j in range(N)]
    G = 0.0
    for key, v in trace_polynomial(N).items():
        if key[0] == N:
            continue
        term = float(v) * hy.par[key[0]]
        for i, e in enumerate(key[1:]):
            for _ in range(e):
                term = term * fac[i]
        G = G + term
    rhs = [(qj, hy.diff(G, pj)) for qj, pj in zip(q, p)] + [(pj, -hy.diff(G, qj)) for qj, pj in zip(q, p)]
    return hy.taylor_adaptive(rhs, [0.0] * (2 * N), pars=[0.0] * N, compact_mode=True, opt_level=0)


@cache
def flow_route() -> str:
    """``"heyoka"`` if heyoka imports, else ``"taylor"`` (the built-in mpmath integrator)."""
    try:
        import heyoka  # noqa: F401
    except ImportError:
        return "taylor"
    return "heyoka"


def flow_routes() -> tuple[str, ...]:
    """Every route installed: ``("heyoka", "taylor")`` with heyoka, else ``("taylor",)``.

    >>> "taylor" in flow_routes()
    True
    """
    return ("heyoka", "taylor") if flow_route() == "heyoka" else ("taylor",)


def _taylor_flow(p, q, c, t: float) -> tuple[list[float], list[float]]:
    """The built-in route within its budget: unit-time pieces of at most TAYLOR_MAX_STEPS steps each, the clock
    checked between them."""
    import math
    import time

    from ..reference.taylor import hamiltonian_flow

    N = len(p)
    start = time.perf_counter()
    pieces = max(1, math.ceil(abs(float(t))))
    with mp.workdps(20):
        P, Q = [mp.mpf(float(v)) for v in p], [mp.mpf(float(v)) for v in q]
        cc = [mp.mpf(float(v)) for v in c[:N]]
        dt = mp.mpf(float(t)) / pieces
        for _ in range(pieces):
            try:
                r = hamiltonian_flow(P, Q, cc, dt, max_steps=TAYLOR_MAX_STEPS)
            except RuntimeError as exc:   # "too many steps"
                raise FlowBudgetExceeded(f"built-in Taylor route: more than {TAYLOR_MAX_STEPS} steps per unit "
                                         "of time") from exc
            P, Q = list(r[0]), list(r[1])
            if time.perf_counter() - start > TAYLOR_SECONDS:
                raise FlowBudgetExceeded(f"built-in Taylor route: past {TAYLOR_SECONDS:g} s")
    return [float(v) for v in P], [float(v) for v in Q]


def time_flow(p, q, c, t: float, *, route: str | None = None) -> tuple[list[float], list[float]]:
    """``(p(t), q(t))`` under the flow of ``sum_k c_k H_k`` (``c = [c_0..c_{N-1}]`` real) from ``(p, q)``.

    ``route``: ``"heyoka"`` or ``"taylor"`` (default :func:`flow_route`).  The built-in route raises
    :class:`FlowBudgetExceeded` past its budget.
    """
    N = len(p)
    route = flow_route() if route is None else route
    if route not in ("heyoka", "taylor"):
        raise ValueError(f"unknown flow route {route!r}")
    if route == "heyoka":
        ta = _heyoka_integrator(N)
        ta.time = 0.0
        ta.state[:] = [float(v) for v in q] + [float(v) for v in p]
        ta.pars[:] = [float(v) for v in c[:N]]
        res = ta.propagate_until(float(t))
        if "time_limit" not in str(res[0]):
            raise ArithmeticError(f"heyoka: {res[0]}")
        s = ta.state
        return [float(v) for v in s[N:]], [float(v) for v in s[:N]]
    return _taylor_flow(p, q, c, t)


# --------------------------------------------------------------------------- the constants and their inverse

def _weight(H: np.ndarray, x: np.ndarray) -> np.ndarray:
    return 1.0 / np.sqrt(horner(H, x) ** 2 - 4)


def moments(H: np.ndarray, lam0: float, m: float, ks) -> np.ndarray | None:
    """``c_k(lam0, m) = -int_{lam0-m}^{lam0+m} lam^k w``, w = (tr^2-4)^{-1/2} > 0; None off the domain."""
    if m == 0 or not in_domain(H, lam0 - m, lam0 + m):
        return None
    ks = np.asarray(list(ks))
    return -gl_integral(lambda x: x[None, :] ** ks[:, None] * _weight(H, x)[None, :], lam0 - m, lam0 + m)


def _jacobian(H, lam0, m, ks):
    lp, lm = lam0 + m, lam0 - m
    wp, wm = _weight(H, np.array([lp]))[0], _weight(H, np.array([lm]))[0]
    return np.array([[-(lp ** k * wp - lm ** k * wm), -(lp ** k * wp + lm ** k * wm)] for k in ks])


def solve_signed(H: np.ndarray, target, *, mode: str = "exact", indices=(0, 1), tol: float = 1e-14,
                 maxit: int = 60) -> tuple[float, float, int]:
    """``(lam0, m, iterations)`` with c(lam0, m) = target (``"exact"`` on two indices), c parallel to the
    target (``"direction"``: ratios to the last index) or closest to it (``"lstsq"``, relative weights).

    Newton from the small-mu guess lam0 = c_1/c_0, m = -c_0 sqrt(|tr(lam0)^2 - 4|)/2, damped so that
    the interval stays in the domain; raises ``ArithmeticError`` without convergence.
    """
    t = np.asarray(target, dtype=float)
    if not np.all(np.isfinite(t)) or np.any(t[:2] == 0) or np.any(t[list(indices)] == 0):
        raise ArithmeticError("target constants must be finite and nonzero")
    idx = list(indices)
    ks = sorted(set(idx))
    w = {k: 1 / abs(t[k]) for k in idx}

    def resid(x, jac=False):
        c = moments(H, x[0], x[1], ks)
        if c is None:
            return None
        cv = dict(zip(ks, c))
        if mode == "exact":
            r = np.array([cv[k] - t[k] for k in idx])
        elif mode == "direction":
            r = np.array([cv[k] / cv[idx[-1]] - t[k] / t[idx[-1]] for k in idx[:-1]])
        else:
            r = np.array([w[k] * (cv[k] - t[k]) for k in idx])
        if not jac:
            return r
        J = dict(zip(ks, _jacobian(H, x[0], x[1], ks)))
        if mode == "exact":
            return r, np.array([J[k] for k in idx])
        if mode == "direction":
            q = idx[-1]
            return r, np.array([(J[k] * cv[q] - cv[k] * J[q]) / cv[q] ** 2 for k in idx[:-1]])
        return r, np.array([w[k] * J[k] for k in idx])

    lam0 = t[1] / t[0]
    m = -t[0] * np.sqrt(abs(horner(H, lam0) ** 2 - 4)) / 2
    x = np.array([lam0, m])
    for _ in range(40):
        if resid(x) is not None:
            break
        x[1] /= 2
    else:
        raise ArithmeticError("no admissible initial guess")
    scale = float(np.max(np.abs(t))) if mode == "exact" else 1.0
    for it in range(maxit):
        r, J = resid(x, jac=True)
        n0, step = np.linalg.norm(r), 1.0
        if mode != "lstsq" and n0 <= 10 * tol * scale:  # at rounding level
            return float(x[0]), float(x[1]), it
        dx = np.linalg.lstsq(J, -r, rcond=None)[0]
        if np.max(np.abs(dx)) <= tol * max(1.0, float(np.max(np.abs(x)))):
            return float(x[0] + dx[0]), float(x[1] + dx[1]), it + 1
        while step > 2.0 ** -30:
            rn = resid(x + step * dx)
            if rn is not None and np.linalg.norm(rn) <= n0 * (1 - step / 4) + tol * scale:
                break
            step /= 2
        else:  # no descent: converged to rounding (or, for least squares, to the optimum)
            if mode == "lstsq" or n0 <= 1e3 * tol * scale:
                return float(x[0]), float(x[1]), it
            raise ArithmeticError("Newton: no descent")
        x = x + step * dx
    raise ArithmeticError("Newton: no convergence")
