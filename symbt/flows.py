r"""Continuous flows of the periodic Toda lattice at high precision (sympy-free).

This module is the *independent* side of Theorems 1 and 2: it knows nothing
about Bäcklund maps.  It provides

* :func:`trace_polynomial` -- :math:`\operatorname{tr}L(\lambda)` of eq. ``tra`` as an explicit
  polynomial in :math:`\lambda`, :math:`p_j` and the bond variables
  :math:`a_j = e^{q_{j+1}-q_j}` (cyclic), by the closed-walk expansion of
  :math:`l_N\cdots l_1`: a sum over the matchings of the N-cycle,
  :math:`\sum_M\prod_{j\notin M}(\lambda+p_j)\prod_{b\in M}(-a_b)`;
* :func:`hamiltonians` -- :math:`H_0,\dots,H_N` (coefficients of :math:`\lambda^k`, :math:`H_N=1`);
* :func:`flow_coefficients_mp` -- the constants of eq. ``eqdisc``,
  :math:`c_k = -b\int_{\lambda_0-\mu}^{\lambda_0+\mu}\lambda^k/\sqrt{\operatorname{tr}L(\lambda)^2-4}\,d\lambda`
  (positive root; ``branch`` b as in :mod:`symbt.literal`), by tanh-sinh quadrature;
* :func:`hamiltonian_flow` -- the time-t flow of :math:`G=\sum_k c_kH_k` for
  :math:`\dot q = \partial G/\partial p`, :math:`\dot p = -\partial G/\partial q`
  (paper's :math:`\{p_i,q_j\}=\delta_{ij}`, :math:`\dot x=\{G,x\}`), integrated by an adaptive
  high-order **Taylor series method** in mpmath.  In the variables :math:`(q, p, a)` the
  equations are polynomial (:math:`\dot a_j = a_j(\dot q_{j+1}-\dot q_j)`), so Taylor
  coefficients follow from Cauchy products alone (no numerical differentiation);
* :func:`solve_parameters` -- the inverse problem :math:`c\mapsto(\lambda_0,\mu)` on a fixed orbit.

Example
-------
>>> import mpmath as mp
>>> mp.mp.dps = 30
>>> p, q = [mp.mpf("0.3"), mp.mpf("-0.2")], [mp.mpf("0.1"), mp.mpf("0.4")]
>>> H = hamiltonians(p, q)
>>> mp.nstr(H[1], 5), H[2]
('0.1', mpf('1.0'))
>>> pt, qt = hamiltonian_flow(p, q, [0, 0, 1], mp.mpf(2))   # G = H_2 = 1: nothing moves
>>> mp.nstr(max(abs(a - b) for a, b in zip(pt + qt, p + q)), 3)
'0.0'
"""
from __future__ import annotations

from functools import lru_cache
from itertools import combinations

import mpmath as mp

from .literal import phi_from_traces

__all__ = [
    "trace_polynomial", "hamiltonians", "trace", "trace_gradient", "phi_real", "phi_gradient",
    "flow_coefficients_mp", "flow_coefficients_jacobian", "hamiltonian_flow", "FlowResult",
    "trace_gap", "solve_parameters", "NoRealFlowError", "hamilton_rhs_float", "hamilton_equations",
]


class NoRealFlowError(ValueError):
    """|tr L| <= 2 somewhere on [lam0 - mu, lam0 + mu]: Phi and the c_k are not real there."""


# --------------------------------------------------------------------------- tr L as a polynomial

@lru_cache(maxsize=None)
def trace_polynomial(N: int) -> dict:
    """``{(k, e_p1..e_pN, e_a1..e_aN): integer coefficient}`` with tr L = sum coef * lam^k p^e a^e.

    ``a_j = exp(q_{j+1} - q_j)`` (indices mod N).  Bond j joins sites j, j+1 and
    carries the weight ``-a_j`` (the walk 1 -> 2 at site j, 2 -> 1 at site j+1
    of the product ``l_N ... l_1``); a matching is a set of bonds with disjoint
    sites.  For N = 2 the two bonds join the same two sites (weights
    ``-e^{q2-q1}``, ``-e^{q1-q2}``) and are never matched together.
    """
    if N < 2:
        raise ValueError("N >= 2")
    bonds = [frozenset((j, (j + 1) % N)) for j in range(N)]
    poly: dict = {}
    for r in range(N // 2 + 1):
        for M in combinations(range(N), r):
            covered = [s for b in M for s in bonds[b]]
            if len(covered) != len(set(covered)):
                continue
            free = [j for j in range(N) if j not in covered]
            # prod_{j free} (lam + p_j): choose a subset S of free sites contributing p_j
            for s in range(len(free) + 1):
                for S in combinations(free, s):
                    e = [0] * (2 * N)
                    for j in S:
                        e[j] = 1
                    for b in M:
                        e[N + b] = 1
                    key = (len(free) - s, *e)
                    poly[key] = poly.get(key, 0) + (-1) ** r
    return {k: v for k, v in poly.items() if v}


def _bonds(q):
    N = len(q)
    return [mp.exp(q[(j + 1) % N] - q[j]) for j in range(N)]


def _mono(vals, e):
    out = mp.mpf(1)
    for v, k in zip(vals, e):
        if k:
            out *= v ** k
    return out


def hamiltonians(p, q):
    """``[H_0, ..., H_N]`` with tr L(lam) = sum_k H_k lam^k (eq. ``tra``)."""
    N = len(p)
    p = [mp.mpmathify(v) for v in p]
    vals = p + _bonds([mp.mpmathify(v) for v in q])
    H = [mp.mpf(0)] * (N + 1)
    for key, c in trace_polynomial(N).items():
        H[key[0]] += c * _mono(vals, key[1:])
    return H


def trace(lam, p, q):
    H = hamiltonians(p, q)
    return mp.polyval(H[::-1], mp.mpmathify(lam))


def trace_gradient(lam, p, q):
    """``(d tr/dp_j, d tr/dq_j)`` at lam, from the polynomial (chain rule through a_j)."""
    N = len(p)
    p = [mp.mpmathify(v) for v in p]
    a = _bonds([mp.mpmathify(v) for v in q])
    vals = p + a
    lam = mp.mpmathify(lam)
    dvals = [mp.mpf(0)] * (2 * N)  # d tr / d p_j, d tr / d a_j
    for key, c in trace_polynomial(N).items():
        k, e = key[0], key[1:]
        base = c * lam ** k
        for i, ei in enumerate(e):
            if ei:
                ee = list(e)
                ee[i] -= 1
                dvals[i] += base * ei * _mono(vals, ee)
    dp = dvals[:N]
    da = dvals[N:]
    # a_j = exp(q_{j+1} - q_j): d a_j/d q_j = -a_j, d a_{j-1}/d q_j = +a_{j-1}
    dq = [da[(j - 1) % N] * a[(j - 1) % N] - da[j] * a[j] for j in range(N)]
    return dp, dq


# --------------------------------------------------------------------------- Phi and the c_k

def phi_real(p, q, lam0, mu, branch):
    """Real Phi = -b (sgn tr1 arccosh(|tr1|/2) + sgn tr2 arccosh(|tr2|/2)), tr_i = tr L(lam0 +- mu)."""
    return phi_from_traces(trace(lam0 + mu, p, q), trace(lam0 - mu, p, q), branch)


def phi_gradient(p, q, lam0, mu, branch):
    """``(dPhi/dp, dPhi/dq)``: dPhi/dtr_i = -b / sqrt(tr_i^2 - 4) (positive root, either sign of tr)."""
    N = len(p)
    gp, gq = [mp.mpf(0)] * N, [mp.mpf(0)] * N
    for lv in (lam0 + mu, lam0 - mu):
        t = trace(lv, p, q)
        if abs(t) <= 2:
            raise NoRealFlowError(f"|tr L({mp.nstr(lv, 8)})| <= 2")
        w = -branch / mp.sqrt(t ** 2 - 4)
        dp, dq = trace_gradient(lv, p, q)
        gp = [g + w * d for g, d in zip(gp, dp)]
        gq = [g + w * d for g, d in zip(gq, dq)]
    return gp, gq


def trace_gap(p, q, lo, hi):
    """min over [lo, hi] of |tr L(lam)| - 2 (end points and critical points), or 0 if tr L = +-2 somewhere."""
    H = hamiltonians(p, q)
    lo, hi = mp.mpmathify(lo), mp.mpmathify(hi)
    if lo > hi:
        lo, hi = hi, lo
    coeffs = H[::-1]
    small = mp.mpf(10) ** (-mp.mp.dps // 2)
    for shift in (2, -2):  # a root of tr = +-2 in [lo, hi] means |tr| <= 2 there: not admissible
        c = list(coeffs)
        c[-1] -= shift
        if any(abs(r.imag) < small and lo <= r.real <= hi for r in mp.polyroots(c, maxsteps=200, extraprec=60)):
            return mp.mpf(0)
    cands = [lo, hi]
    d = [coeffs[i] * (len(coeffs) - 1 - i) for i in range(len(coeffs) - 1)]
    if len(d) > 1:
        cands += [r.real for r in mp.polyroots(d, maxsteps=200, extraprec=60) if abs(r.imag) < small]
    cands = [x for x in cands if lo <= x <= hi]
    return min(abs(mp.polyval(coeffs, x)) - 2 for x in cands)


def flow_coefficients_mp(p, q, lam0, mu, branch=1, *, check=True, ks=None):
    """``[c_0, ..., c_N]``, c_k = -b int_{lam0-mu}^{lam0+mu} lam^k / sqrt(tr L^2 - 4) dlam (eq. ``eqdisc``).

    The positive root is used for both signs of tr L; ``branch`` b = +1 is the
    branch of the printed eq. ``eqdisc`` (see :mod:`symbt.claims.theorems`).
    ``c_N`` multiplies H_N = 1 and does not move anything.  Raises
    :class:`NoRealFlowError` if |tr L| <= 2 somewhere on the interval.
    """
    lam0, mu = mp.mpmathify(lam0), mp.mpmathify(mu)
    if check and trace_gap(p, q, lam0 - mu, lam0 + mu) <= 0:
        raise NoRealFlowError("|tr L| <= 2 inside [lam0 - mu, lam0 + mu]")
    H = hamiltonians(p, q)
    coeffs = H[::-1]
    N = len(p)
    out = []
    for k in range(N + 1):
        if ks is not None and k not in ks:
            out.append(None)
            continue
        f = lambda x, k=k: x ** k / mp.sqrt(mp.polyval(coeffs, x) ** 2 - 4)
        out.append(-branch * mp.quad(f, [lam0 - mu, lam0, lam0 + mu]))
    return out


def flow_coefficients_jacobian(p, q, lam0, mu, branch=1):
    """``J[k] = (dc_k/dlam0, dc_k/dmu)`` in closed form (fundamental theorem of calculus)."""
    H = hamiltonians(p, q)
    coeffs = H[::-1]
    f = lambda x, k: x ** k / mp.sqrt(mp.polyval(coeffs, x) ** 2 - 4)
    lp, lm = lam0 + mu, lam0 - mu
    return [(-branch * (f(lp, k) - f(lm, k)), -branch * (f(lp, k) + f(lm, k))) for k in range(len(p) + 1)]


# --------------------------------------------------------------------------- Hamilton's equations

def _poly_G(N, c):
    """G = sum_k c_k H_k as {(e_p, e_a): coef}."""
    G: dict = {}
    for key, v in trace_polynomial(N).items():
        k, e = key[0], key[1:]
        if k < len(c) and c[k]:
            G[e] = G.get(e, 0) + c[k] * v
    return G


def _d(poly, i):
    out = {}
    for e, v in poly.items():
        if e[i]:
            ee = list(e)
            ee[i] -= 1
            out[tuple(ee)] = out.get(tuple(ee), 0) + v * e[i]
    return out


def _mul_var(poly, i):
    out = {}
    for e, v in poly.items():
        ee = list(e)
        ee[i] += 1
        out[tuple(ee)] = out.get(tuple(ee), 0) + v
    return out


def _add(*polys, signs=None):
    out = {}
    for s, P in zip(signs or [1] * len(polys), polys):
        for e, v in P.items():
            out[e] = out.get(e, 0) + s * v
    return {e: v for e, v in out.items() if v != 0}


def hamilton_equations(N, c, sign=1):
    """Right-hand sides in the state (q_1..q_N, p_1..p_N, a_1..a_N) as polynomials in (p, a).

    qdot_j = dG/dp_j;  pdot_j = -dG/dq_j = a_j dG/da_j - a_{j-1} dG/da_{j-1};
    adot_j = a_j (qdot_{j+1} - qdot_j).  ``sign = -1`` gives the reversed flow.
    """
    G = _poly_G(N, [sign * ci for ci in c])
    qd = [_d(G, j) for j in range(N)]
    pd = [_add(_mul_var(_d(G, N + j), N + j), _mul_var(_d(G, N + (j - 1) % N), N + (j - 1) % N), signs=[1, -1])
          for j in range(N)]
    ad = [_mul_var(_add(qd[(j + 1) % N], qd[j], signs=[1, -1]), N + j) for j in range(N)]
    return qd + pd + ad


class _TaylorSystem:
    """Jet evaluation of a polynomial vector field by a DAG of binary products."""

    def __init__(self, N, rhs):
        self.N = N
        self.nvar = 3 * N
        # variable index of monomial factor i (i < N: p_i -> state N + i; i >= N: a -> state 2N + i - N)
        self.fac_state = [N + i for i in range(N)] + [2 * N + i for i in range(N)]
        nodes = {}  # key: sorted tuple of factor indices -> (prefix key, factor)
        self.terms = []
        for P in rhs:
            tl = []
            for e, v in P.items():
                key = tuple(i for i, k in enumerate(e) for _ in range(k))
                for d in range(1, len(key) + 1):
                    nodes.setdefault(key[:d], (key[:d - 1], key[d - 1]))
                tl.append((v, key))
            self.terms.append(tl)
        self.order = sorted(nodes, key=len)
        self.nodes = nodes

    def jets(self, x0, K):
        X = [[v] for v in x0]
        J = {}
        for key in self.order:
            J[key] = []
        for n in range(K):
            for key in self.order:
                prefix, f = self.nodes[key]
                leaf = X[self.fac_state[f]]
                if not prefix:
                    J[key].append(leaf[n])
                else:
                    pj = J[prefix]
                    J[key].append(mp.fsum(pj[m] * leaf[n - m] for m in range(n + 1)))
            for i, tl in enumerate(self.terms):
                s = mp.fsum(v * (J[key][n] if key else (1 if n == 0 else 0)) for v, key in tl)
                X[i].append(s / (n + 1))
        return X


class FlowResult(tuple):
    """``(p, q)`` with attributes ``steps`` and ``order``."""
    steps: int = 0
    order: int = 0


def hamiltonian_flow(p, q, c, t, *, tol=None, order=None, max_steps=200000):
    """Time-``t`` flow of G = sum_k c_k H_k from (p, q), by an adaptive Taylor method at ``mp.dps``.

    ``c = [c_0, ..., c_N]`` (missing trailing entries are 0).  Negative ``t``
    integrates backwards.  Error per unit time about ``tol`` (default
    ``10**-(dps+2)``, working precision dps + 15).  Returns a :class:`FlowResult`.
    """
    N = len(p)
    dps = mp.mp.dps
    c = list(c) + [0] * (N + 1 - len(c))
    with mp.workdps(dps + 15):
        tol = mp.mpf(10) ** (-(dps + 2)) if tol is None else mp.mpf(tol)
        K = order or max(12, int(-mp.log(tol) / 2) + 6)
        t = mp.mpmathify(t)
        sign = 1 if t >= 0 else -1
        sysm = _TaylorSystem(N, hamilton_equations(N, [mp.mpmathify(v) for v in c], sign))
        x = [mp.mpmathify(v) for v in q] + [mp.mpmathify(v) for v in p] + _bonds([mp.mpmathify(v) for v in q])
        T, done, steps = abs(t), mp.mpf(0), 0
        while done < T:
            if steps >= max_steps:
                raise RuntimeError("hamiltonian_flow: too many steps")
            X = sysm.jets(x, K)
            scale = max(1, max(abs(v) for v in x))
            nK = max(abs(Xi[K]) for Xi in X) / scale
            nK1 = max(abs(Xi[K - 1]) for Xi in X) / scale
            hs = []
            if nK > 0:
                hs.append((tol / nK) ** (mp.mpf(1) / K))
            if nK1 > 0:
                hs.append((tol / nK1) ** (mp.mpf(1) / (K - 1)))
            h = min(hs) * mp.mpf("0.7") if hs else T - done
            h = min(h, T - done)
            x = [mp.polyval(Xi[::-1], h) for Xi in X]
            done += h
            steps += 1
        qn, pn = x[:N], x[N:2 * N]
    out = FlowResult(([+v for v in pn], [+v for v in qn]))
    out.steps, out.order = steps, K
    return out


# --------------------------------------------------------------------------- inverse problem

def _newton(F, J, x0, tol, maxit=40):
    x = [mp.mpmathify(v) for v in x0]
    for it in range(maxit):
        r = F(x)
        if r is None:
            return None
        Jm = mp.matrix(J(x))
        if max(abs(v) for v in r) < tol:  # converged: one more (quadratically convergent) step, then stop
            try:
                dx = mp.lu_solve(Jm, -mp.matrix(r))
                xn = [a + d for a, d in zip(x, dx)]
                rn = F(xn)
                if rn is not None and max(abs(v) for v in rn) <= max(abs(v) for v in r):
                    x = xn
            except ZeroDivisionError:
                pass
            return x, it + 1
        try:
            dx = mp.lu_solve(Jm, -mp.matrix(r)) if Jm.rows == Jm.cols else mp.qr_solve(Jm, -mp.matrix(r))[0]
        except ZeroDivisionError:
            return None
        # damping: halve until the interval stays admissible and the residual decreases
        lam = mp.mpf(1)
        r0 = mp.sqrt(mp.fsum(v ** 2 for v in r))
        while lam > mp.mpf(2) ** -30:
            xn = [a + lam * d for a, d in zip(x, dx)]
            rn = F(xn)
            if rn is not None and mp.sqrt(mp.fsum(v ** 2 for v in rn)) < r0 * (1 - lam / 4) + tol:
                x = xn
                break
            lam /= 2
        else:
            return None
    r = F(x)
    return (x, maxit) if r is not None and max(abs(v) for v in r) < tol else None


def solve_parameters(p, q, c_target, *, mode="exact", indices=None, guess=None, tol=None):
    r"""Find (lam0, mu, branch) whose BT samples the flow of sum_k c_k H_k through (p, q).

    Uses the signed form c_k(lam0, mu) = -int_{lam0-mu}^{lam0+mu} lam^k/sqrt(tr^2-4) dlam
    (branch b at mu>0 = branch +1 at b*mu), so the unknowns are (lam0, m) in R^2 and
    ``branch = sign(m)``, ``mu = |m|``.

    ``mode``:

    * ``"exact"``: solve c_k = c_target[k] for k in ``indices`` (two indices;
      default (0, 1) -- for N = 2 these are *all* non-trivial constants);
    * ``"direction"``: match c up to a positive factor kappa (same trajectory,
      time step kappa): c_k/c_r for the two k in ``indices`` other than r =
      ``indices[-1]`` (N = 3 default (0, 1, 2), i.e. ratios to c_2);
    * ``"lstsq"``: Gauss-Newton on sum_k (c_k - c_target_k)^2 over k < N.

    Returns a dict with lam0, mu, branch, c (achieved), kappa (achieved/target
    along the target direction), iterations, residual.  Raises ValueError if
    Newton fails (no admissible solution near the initial guess).
    """
    N = len(p)
    c_target = [mp.mpmathify(v) for v in c_target] + [mp.mpf(0)] * (N + 1 - len(c_target))
    tol = mp.mpf(10) ** (-(mp.mp.dps - 8)) if tol is None else mp.mpf(tol)
    H = hamiltonians(p, q)
    coeffs = H[::-1]

    memo = {}

    def cvec(x):
        l0, m = x
        key = (l0, m)
        if key not in memo:
            if m == 0 or trace_gap(p, q, l0 - m, l0 + m) <= 0:
                memo[key] = None
            else:
                memo[key] = flow_coefficients_mp(p, q, l0, m, 1, check=False, ks=range(N))
        return memo[key]

    def jac(x):
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

        def J(x):
            jj, c = jac(x), cvec(x)
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
    for attempt in range(16):  # shrink mu until [lam0 - mu, lam0 + mu] avoids |tr| <= 2, then Newton
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


def _gauss_newton(F, J, x0, tol, maxit=80):
    x = [mp.mpmathify(v) for v in x0]
    for it in range(maxit):
        r = F(x)
        if r is None:
            return None
        Jm = mp.matrix(J(x))
        dx = mp.qr_solve(Jm, -mp.matrix(r))[0]
        lam = mp.mpf(1)
        r0 = mp.fsum(v ** 2 for v in r)
        while lam > mp.mpf(2) ** -30:
            xn = [a + lam * d for a, d in zip(x, dx)]
            rn = F(xn)
            if rn is not None and mp.fsum(v ** 2 for v in rn) <= r0:
                x = xn
                break
            lam /= 2
        else:
            return x, it
        if max(abs(d) for d in dx) * lam < tol:
            return x, it
    return x, maxit


# --------------------------------------------------------------------------- float64 right-hand side

def hamilton_rhs_float(N, c):
    """A plain-Python ``f(t, y)`` for y = (q_1..q_N, p_1..p_N): Hamilton's equations of sum c_k H_k.

    Generated as source from the same polynomials as :func:`hamiltonian_flow` (with the bond
    variables a_j = exp(q_{j+1} - q_j) recomputed from q), for ``scipy.integrate.solve_ivp``.
    """
    c = [float(v) for v in c] + [0.0] * (N + 1 - len(c))
    eqs = hamilton_equations(N, c)[:2 * N]
    names = [f"p{j}" for j in range(N)] + [f"a{j}" for j in range(N)]

    def term(e, v):
        fac = [names[i] if k == 1 else f"{names[i]}**{k}" for i, k in enumerate(e) if k]
        return "*".join([repr(float(v))] + fac)

    lines = ["def f(t, y):",
             "    " + ", ".join(f"q{j}" for j in range(N)) + ", " + ", ".join(f"p{j}" for j in range(N))
             + " = y",
             *[f"    a{j} = exp(q{(j + 1) % N} - q{j})" for j in range(N)],
             "    return [" + ", ".join("(" + (" + ".join(term(e, v) for e, v in P.items()) or "0.0") + ")"
                                     for P in eqs) + "]"]
    ns = {"exp": __import__("math").exp}
    exec("\n".join(lines), ns)
    f = ns["f"]
    f.source = "\n".join(lines)
    return f
