r"""The inverse problem of Theorem 2: which (lam0, mu, branch) samples a given flow sum_k c_k H_k.

:func:`solve_parameters` solves :math:`c_k(\lambda_0,\mu) = c^{target}_k` by damped Newton
(Gauss-Newton for least squares), with the closed-form Jacobian of the c_k.  The attainable
set is limited by Cauchy-Schwarz for the moments of the positive weight
:math:`1/\sqrt{\operatorname{tr}^2-4}`: :math:`c_0c_2 > c_1^2`.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, TypeAlias

import mpmath as mp

from .literal import MPLike
from .spectral import flow_coefficients_jacobian, flow_coefficients_mp
from .trace import hamiltonians, trace_gap

#: a residual: the vector F(x), or None where F is not defined (no real flow at x)
Residual: TypeAlias = "Callable[[list[mp.mpf]], list[mp.mpf] | None]"
#: its Jacobian, as rows
Jacobian: TypeAlias = "Callable[[list[mp.mpf]], Any]"

__all__ = ["solve_parameters"]


def _norm(r: Sequence[mp.mpf]) -> mp.mpf:
    return mp.sqrt(mp.fsum(v ** 2 for v in r))


def _line_search(F: Residual, x: Sequence[mp.mpf], dx: Sequence[mp.mpf],
                 accept: Callable[[list[mp.mpf], mp.mpf], bool]) -> tuple[list[mp.mpf], mp.mpf] | None:
    """``(x + lam dx, lam)`` for the first of ``lam = 1, 1/2, ..., 2**-29`` (30 tries) where F is defined and
    ``accept(F(x + lam dx), lam)`` holds; None if none does."""
    lam = mp.mpf(1)
    while lam > mp.mpf(2) ** -30:
        xn = [a + lam * d for a, d in zip(x, dx)]
        rn = F(xn)
        if rn is not None and accept(rn, lam):
            return xn, lam
        lam /= 2
    return None


def _linearise(F: Residual, J: Jacobian, x: list[mp.mpf]) -> tuple[list[mp.mpf], mp.matrix] | None:
    """``(F(x), J(x))``, or None where F is not defined."""
    r = F(x)
    return None if r is None else (r, mp.matrix(J(x)))


def _solve(Jm: mp.matrix, r: Sequence[mp.mpf]) -> mp.matrix:
    """The Newton step ``dx`` with ``Jm dx = -r``: Householder QR, square or not (least squares when the
    equations outnumber the unknowns; mpmath's ``lu_solve`` would square the condition through the normal
    equations there).  A singular ``Jm`` raises ``ZeroDivisionError``."""
    try:
        return mp.qr_solve(Jm, -mp.matrix(r))[0]
    except ValueError as exc:              # mpmath: "matrix is numerically singular"
        raise ZeroDivisionError(str(exc)) from exc


def _newton(F: Residual, J: Jacobian, x0: Sequence[MPLike], tol: mp.mpf,
            maxit: int = 40) -> tuple[list[mp.mpf], int] | None:
    x = [mp.mpmathify(v) for v in x0]
    for it in range(maxit):
        lin = _linearise(F, J, x)
        if lin is None:
            return None
        r, Jm = lin
        if max(abs(v) for v in r) < tol:  # converged: one more (quadratically convergent) step, then stop
            try:
                dx = _solve(Jm, r)
                xn = [a + d for a, d in zip(x, dx)]
                rn = F(xn)
                if rn is not None and _norm(rn) <= _norm(r):      # the line search's measure
                    x = xn
            except ZeroDivisionError:
                pass
            return x, it + 1
        try:
            dx = _solve(Jm, r)
        except ZeroDivisionError:
            return None
        # damping: the residual norm must decrease (Armijo-like) where F is defined
        r0 = _norm(r)
        step = _line_search(F, x, dx, lambda rn, lam: _norm(rn) < r0 * (1 - lam / 4) + tol)
        if step is None:
            return None
        x = step[0]
    rf = F(x)
    return (x, maxit) if rf is not None and max(abs(v) for v in rf) < tol else None


def solve_parameters(p: Sequence[MPLike], q: Sequence[MPLike], c_target: Sequence[MPLike], *, mode: str = "exact",
                     indices: Sequence[int] | None = None, guess: tuple[mp.mpf, mp.mpf] | None = None,
                     tol: MPLike | None = None) -> dict[str, Any] | None:
    r"""Find (lam0, mu, branch) whose BT samples the flow of sum_k c_k H_k through (p, q).

    Uses the signed form c_k(lam0, mu) = -int_{lam0-mu}^{lam0+mu} lam^k/sqrt(tr^2-4) dlam
    (branch b at mu>0 = branch +1 at b*mu), so the unknowns are (lam0, m) in R^2 and
    ``branch = sign(m)``, ``mu = |m|``.

    ``mode``:

    ``c_target``: ``c_0, c_1, ...``; entries missing at the end (up to ``c_N``) are 0.

    * ``"exact"``: solve c_k = c_target[k] for k in ``indices`` (two indices;
      default (0, 1) -- for N = 2 these are *all* non-trivial constants);
    * ``"direction"``: match c up to a positive factor kappa (same trajectory,
      time step kappa): c_k/c_r for the two k in ``indices`` other than r =
      ``indices[-1]`` (N = 3 default (0, 1, 2), i.e. ratios to c_2);
    * ``"lstsq"``: Gauss-Newton on sum_k (c_k - c_target_k)^2 over k < N.

    Returns a dict with lam0, mu, branch, c (achieved: ``[c_0, ..., c_N]`` at the answer), kappa (achieved/target
    along the target direction: ``sum_k c_k t_k / sum_k t_k^2`` over k < N, t the target), iterations (the number
    of iterates at which the residual and the Jacobian were evaluated: 1 when the start already meets ``tol``),
    residual (``max_k |c_k - t_k|`` over k < N).  Raises ValueError if Newton fails (no admissible solution near
    the initial guess).

    Without ``guess`` the start is the small-mu asymptotics ``c_k ~ -2 m lam0^k / sqrt(tr L(lam0)^2 - 4)``:
    ``lam0 = c_1/c_0``, ``m = -c_0 sqrt(|tr L(lam0)^2 - 4|)/2`` (``branch = sign(m)``), so a target of a small
    ``mu`` meets ``tol`` at the start (its relative error is of order ``mu^2``).

    Where the guess's interval ``[lam0 - mu, lam0 + mu]`` meets a band (``|tr| <= 2``), ``mu`` is halved (up to
    16 times) first.  Newton (modes exact and direction) stops at the first iterate whose residual is below ``tol``
    (default ``10**-(dps - 8)``) and then takes one more step, kept if it does not increase the residual: the
    error of the answer is then about the *square* of the error at ``tol``, not ``tol``.  An interval is
    admissible when ``|tr| > 2`` on it (:func:`~symbt.reference.trace.trace_gap` ``> 0``), however close to a band.
    A target with ``c_0 c_2 <= c_1^2`` raises ``ValueError`` (Cauchy-Schwarz) only when ``c_0, c_1, c_2`` are all
    fitted (``indices`` holds 0, 1, 2; not in mode ``lstsq``).
    """
    N = len(p)
    c_target = [mp.mpmathify(v) for v in c_target] + [mp.mpf(0)] * (N + 1 - len(c_target))
    tol = mp.mpf(10) ** (-(mp.mp.dps - 8)) if tol is None else mp.mpf(tol)
    H = hamiltonians(p, q)
    coeffs = H[::-1]

    memo: dict[tuple[mp.mpf, mp.mpf], list[mp.mpf] | None] = {}

    def cvec(x: Sequence[mp.mpf]) -> list[mp.mpf] | None:
        l0, m = x
        key = (l0, m)
        if key not in memo:
            if m == 0 or trace_gap(p, q, l0 - m, l0 + m) <= 0:
                memo[key] = None
            else:
                memo[key] = flow_coefficients_mp(p, q, l0, m, 1, check=False, ks=range(N))
        return memo[key]

    def jac(x: Sequence[mp.mpf]) -> list[tuple[mp.mpf, mp.mpf]]:
        return flow_coefficients_jacobian(p, q, x[0], x[1], 1)

    if mode == "exact":
        idx = tuple(indices or (0, 1))
        F = lambda x: (lambda c: None if c is None else [c[k] - c_target[k] for k in idx])(cvec(x))
        J = lambda x: [list(jac(x)[k]) for k in idx]
    elif mode == "direction":
        idx = tuple(indices or tuple(range(N)))
        r = idx[-1]
        F = lambda x: (lambda c: None if c is None else
                       [c[k] / c[r] - c_target[k] / c_target[r] for k in idx[:-1]])(cvec(x))

        def J(x: Sequence[mp.mpf]) -> list[list[mp.mpf]]:
            jj, c = jac(x), cvec(x)
            assert c is not None                      # J is only taken where F is defined
            return [[(jj[k][i] * c[r] - c[k] * jj[r][i]) / c[r] ** 2 for i in (0, 1)] for k in idx[:-1]]
    elif mode == "lstsq":
        idx = tuple(indices or tuple(range(N)))
        w = [1 / max(abs(c_target[k]), mp.mpf(10) ** -30) for k in idx]  # relative residuals
        F = lambda x: (lambda c: None if c is None else [wk * (c[k] - c_target[k]) for wk, k in zip(w, idx)])(cvec(x))
        J = lambda x: [[wk * v for v in jac(x)[k]] for wk, k in zip(w, idx)]
    else:
        raise ValueError(f"unknown mode {mode!r}")

    if guess is None:
        # small-mu asymptotics: c_k ~ -2 m lam0^k / sqrt(tr(lam0)^2 - 4)  =>  lam0 ~ c_1/c_0
        l0 = c_target[1] / c_target[0]
        t0 = mp.polyval(coeffs, l0)
        m = -c_target[0] * mp.sqrt(abs(t0 ** 2 - 4)) / 2
        guess = (l0, m)
    used = set(idx)
    if {0, 1, 2} <= used and mode != "lstsq" and c_target[0] * c_target[2] <= c_target[1] ** 2:
        # c_k are moments of the positive weight w = 1/sqrt(tr^2-4) on an interval: Cauchy-Schwarz
        raise ValueError("solve_parameters: c_0 c_2 <= c_1^2 is never attained (Cauchy-Schwarz for the moments "
                         "of 1/sqrt(tr^2-4) > 0)")
    l0g, mg = guess
    sol = None
    for _attempt in range(16):  # shrink mu until [lam0 - mu, lam0 + mu] avoids |tr| <= 2, then Newton
        if F((l0g, mg)) is not None:
            sol = (_gauss_newton if mode == "lstsq" else _newton)(F, J, (l0g, mg), tol)
            if sol is not None:
                break
        mg /= 2
    if sol is None:
        raise ValueError("solve_parameters: no admissible (lam0, mu) found from the initial guess")
    (l0, m), its = sol
    c = flow_coefficients_mp(p, q, l0, m, 1, check=False)
    num = mp.fsum(a * b for a, b in zip(c[:N], c_target[:N]))
    kappa = num / mp.fsum(b ** 2 for b in c_target[:N])
    res = max(abs(c[k] - c_target[k]) for k in range(N))
    return dict(lam0=l0, mu=abs(m), branch=1 if m > 0 else -1, c=c, kappa=kappa, iterations=its,
                residual=res)


def _gauss_newton(F: Residual, J: Jacobian, x0: Sequence[MPLike], tol: mp.mpf,
                  maxit: int = 80) -> tuple[list[mp.mpf], int] | None:
    x = [mp.mpmathify(v) for v in x0]
    for it in range(maxit):
        lin = _linearise(F, J, x)
        if lin is None:
            return None
        r, Jm = lin
        dx = mp.qr_solve(Jm, -mp.matrix(r))[0]
        r0 = _norm(r)
        step = _line_search(F, x, dx, lambda rn, lam: _norm(rn) <= r0)
        if step is None:
            return x, it + 1            # iterates evaluated (solve_parameters' `iterations`), as _newton counts
        x, lam = step
        if max(abs(d) for d in dx) * lam < tol:
            return x, it + 1
    return x, maxit


