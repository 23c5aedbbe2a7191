"""ODE integrators run on Hamilton's equations ``qdot = dG/dp``, ``pdot = -dG/dq``.

* :func:`gauss_legendre_orbit` -- the symplectic s-stage Gauss--Legendre collocation method
  (order 2s; fixed-point iteration of the stage equations to round-off), fixed step ``h``;
* :func:`scipy_orbit` -- ``scipy.integrate.solve_ivp`` (DOP853, RK45, LSODA) with
  ``rtol = atol = tol`` and dense checkpoints (scipy is imported here, lazily).

A field is a callable ``f(p, q) -> (qdot, pdot)`` on arrays of shape ``batch + (N,)``.

>>> import numpy as np
>>> f = lambda p, q: (p, -q)                         # harmonic oscillator, G = (p^2 + q^2)/2
>>> P, Q, nfev = gauss_legendre_orbit(f, np.array([0.0]), np.array([1.0]), 0.1, 10, 10)
>>> bool(abs(Q[-1, 0] - np.cos(1.0)) < 1e-10)          # order 6: error ~ h^6
True
"""
from __future__ import annotations

import warnings
from collections.abc import Callable

import numpy as np

__all__ = ["gauss_legendre_orbit", "scipy_orbit"]

Field = Callable[[np.ndarray, np.ndarray], tuple]
_GL_TABLES: dict = {}


def _gl_table(s: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    if s not in _GL_TABLES:
        x, w = np.polynomial.legendre.leggauss(s)
        c = (x + 1) / 2
        b = w / 2
        A = np.empty((s, s))                      # A_ij = int_0^{c_i} l_j(t) dt
        for j in range(s):
            others = np.delete(c, j)
            coef = np.poly(others) / np.prod(c[j] - others)
            A[:, j] = np.polyval(np.polyint(coef), c)
        _GL_TABLES[s] = (A, b, c)
    return _GL_TABLES[s]


def gauss_legendre_orbit(f: Field, p0: np.ndarray, q0: np.ndarray, h: float, nsteps: int, every: int,
                         s: int = 3, maxit: int = 60) -> tuple[np.ndarray, np.ndarray, int]:
    """``nsteps`` steps of size ``h``; returns ``(P, Q, stage evaluations)`` sampled every ``every`` steps."""
    A, b, _ = _gl_table(s)
    N = len(p0)
    y = np.concatenate([np.asarray(q0, float), np.asarray(p0, float)])
    rows = 1 + -(-nsteps // every)
    P = np.empty((rows, N))
    Q = np.empty((rows, N))
    P[0], Q[0] = p0, q0
    K = None
    nfev = 0
    row = 1
    hA = h * A
    for i in range(1, nsteps + 1):
        if K is None:
            qd, pd = f(y[N:], y[:N])
            K = np.tile(np.concatenate([qd, pd]), (s, 1))
            nfev += 1
        for _ in range(maxit):
            Y = y + hA @ K
            qd, pd = f(Y[:, N:], Y[:, :N])
            nfev += s
            Kn = np.concatenate([qd, pd], axis=-1)
            delta = np.max(np.abs(Kn - K))
            K = Kn
            if delta <= 4e-16 * (1 + np.max(np.abs(K))):
                break
        y = y + h * (b @ K)
        if i % every == 0 or i == nsteps:
            Q[row], P[row] = y[:N], y[N:]
            row += 1
    return P, Q, nfev


def scipy_orbit(method: str, f: Field, p0: np.ndarray, q0: np.ndarray, T: float, t_eval: np.ndarray,
                tol: float) -> tuple:
    """``(P, Q, nfev, message)`` at ``t_eval`` by ``solve_ivp``; ``P = None`` (and a message) on failure."""
    from scipy.integrate import solve_ivp

    N = len(p0)

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        qd, pd = f(y[N:], y[:N])
        return np.concatenate([qd, pd])

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            sol = solve_ivp(rhs, (0.0, T), np.concatenate([q0, p0]), method=method, rtol=tol, atol=tol,
                            t_eval=t_eval)
        except (ArithmeticError, ValueError) as exc:          # e.g. NumericRangeError from the field
            return None, None, 0, repr(exc)
    Y = sol.y.T
    if not sol.success or Y.shape[0] != len(t_eval):
        return None, None, sol.nfev, sol.message
    return Y[:, N:], Y[:, :N], sol.nfev, None
