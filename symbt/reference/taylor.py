r"""Hamiltonian flows of the periodic Toda lattice by an adaptive Taylor-series method (mpmath).

The *independent* side of Theorems 1 and 2: it knows nothing about Bäcklund maps.
:func:`hamiltonian_flow` integrates the time-t flow of :math:`G=\sum_k c_kH_k` for
:math:`\dot q = \partial G/\partial p`, :math:`\dot p = -\partial G/\partial q` (paper's
:math:`\{p_i,q_j\}=\delta_{ij}`, :math:`\dot x=\{G,x\}`).  In the variables :math:`(q, p, a)`,
:math:`a_j = e^{q_{j+1}-q_j}`, the equations are polynomial
(:math:`\dot a_j = a_j(\dot q_{j+1}-\dot q_j)`), so Taylor coefficients follow from Cauchy
products alone (no numerical differentiation).

>>> import mpmath as mp
>>> p, q = [mp.mpf("0.3"), mp.mpf("-0.2")], [mp.mpf("0.1"), mp.mpf("0.4")]
>>> with mp.workdps(30):
...     pt, qt = hamiltonian_flow(p, q, [0, 0, 1], mp.mpf(2))   # G = H_2 = 1: nothing moves
>>> mp.nstr(max(abs(a - b) for a, b in zip(pt + qt, p + q)), 3)
'0.0'
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any, TypeAlias

import mpmath as mp

from .literal import MPLike
from .trace import bonds, trace_polynomial

#: a coefficient of the flow's polynomials: an integer of the trace polynomial times an mpmath c_k
Coefficient: TypeAlias = "int | mp.mpf"
#: a polynomial in (p, a) as ``{exponents: coefficient}``
Polynomial: TypeAlias = "dict[tuple[int, ...], Coefficient]"

__all__ = ["hamilton_equations", "hamiltonian_flow", "FlowResult"]


def _poly_G(N: int, c: Sequence[Coefficient]) -> Polynomial:
    """G = sum_k c_k H_k as {(e_p, e_a): coef}."""
    G: Polynomial = {}
    for key, v in trace_polynomial(N).items():
        k, e = key[0], key[1:]
        if k < len(c) and c[k]:
            G[e] = G.get(e, 0) + c[k] * v
    return G


def _d(poly: Polynomial, i: int) -> Polynomial:
    out: Polynomial = {}
    for e, v in poly.items():
        if e[i]:
            ee = list(e)
            ee[i] -= 1
            out[tuple(ee)] = out.get(tuple(ee), 0) + v * e[i]
    return out


def _mul_var(poly: Polynomial, i: int) -> Polynomial:
    out: Polynomial = {}
    for e, v in poly.items():
        ee = list(e)
        ee[i] += 1
        out[tuple(ee)] = out.get(tuple(ee), 0) + v
    return out


def _sub(P: Polynomial, Q: Polynomial) -> Polynomial:
    """``P - Q`` (zero terms dropped)."""
    out = dict(P)
    for e, v in Q.items():
        out[e] = out.get(e, 0) - v
    return {e: v for e, v in out.items() if v != 0}


def hamilton_equations(N: int, c: Sequence[Coefficient], sign: int = 1) -> list[Polynomial]:
    """Right-hand sides in the state (q_1..q_N, p_1..p_N, a_1..a_N) as polynomials in (p, a).

    qdot_j = dG/dp_j;  pdot_j = -dG/dq_j = a_j dG/da_j - a_{j-1} dG/da_{j-1};
    adot_j = a_j (qdot_{j+1} - qdot_j).  ``sign = -1`` gives the reversed flow.  Missing trailing entries of ``c``
    are 0.
    """
    G = _poly_G(N, [sign * ci for ci in c])
    qd = [_d(G, j) for j in range(N)]
    pd = [_sub(_mul_var(_d(G, N + j), N + j), _mul_var(_d(G, N + (j - 1) % N), N + (j - 1) % N))
          for j in range(N)]
    ad = [_mul_var(_sub(qd[(j + 1) % N], qd[j]), N + j) for j in range(N)]
    return qd + pd + ad


class _TaylorSystem:
    """Jet evaluation of a polynomial vector field by a DAG of binary products."""

    def __init__(self, N: int, rhs: Sequence[Polynomial]) -> None:
        self.N = N
        self.nvar = 3 * N
        # variable index of monomial factor i (i < N: p_i -> state N + i; i >= N: a -> state 2N + i - N)
        self.fac_state = [N + i for i in range(N)] + [2 * N + i for i in range(N)]
        # key: sorted tuple of factor indices -> (prefix key, factor)
        nodes: dict[tuple[int, ...], tuple[tuple[int, ...], int]] = {}
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

    def jets(self, x0: Sequence[mp.mpf], K: int) -> list[list[mp.mpf]]:
        X = [[v] for v in x0]
        J: dict[tuple[int, ...], list[mp.mpf]] = {}
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


class FlowResult(tuple[Any, ...]):
    """``(p, q)`` with attributes ``steps`` and ``order`` (set by :func:`hamiltonian_flow`)."""
    steps: int
    order: int


def hamiltonian_flow(p: Sequence[MPLike], q: Sequence[MPLike], c: Sequence[MPLike], t: MPLike, *,
                     tol: MPLike | None = None, order: int | None = None, max_steps: int = 200000) -> FlowResult:
    """Time-``t`` flow of G = sum_k c_k H_k from (p, q), by an adaptive Taylor method at ``mp.dps``.

    ``c = [c_0, ..., c_N]`` (missing trailing entries are 0).  Negative ``t``
    integrates backwards.  Error per unit time about ``tol`` (default
    ``10**-(dps+2)``, working precision dps + 15).  Returns a :class:`FlowResult`.

    At most ``max_steps`` steps are taken (RuntimeError beyond); ``t = 0`` takes none.
    The order is ``order`` or ``max(12, floor(ln(1/tol)/2) + 6)``; each step is 0.7 times the smaller of
    ``(tol/|X_K|)^(1/K)`` and ``(tol/|X_{K-1}|)^(1/(K-1))`` over the last two Taylor coefficients (scaled by
    ``max(1, |x|)``, the ones that are not 0), so a vanishing last coefficient does not make a long step.
    """
    N = len(p)
    dps = mp.mp.dps
    with mp.workdps(dps + 15):
        tol = mp.mpf(10) ** (-(dps + 2)) if tol is None else mp.mpf(tol)
        K = order or max(12, int(-mp.log(tol) / 2) + 6)
        t = mp.mpmathify(t)
        sign = 1 if t >= 0 else -1
        sysm = _TaylorSystem(N, hamilton_equations(N, [mp.mpmathify(v) for v in c], sign))
        x = [mp.mpmathify(v) for v in q] + [mp.mpmathify(v) for v in p] + bonds([mp.mpmathify(v) for v in q])
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
