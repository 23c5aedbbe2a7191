"""A user's model: the open Toda lattice of N particles, H = sum p_j^2/2 + sum exp(q_j - q_{j+1})."""
from __future__ import annotations

import sympy as sp

t = sp.Symbol("t", real=True)
c = sp.Symbol("c", positive=True)


def coordinates(N: int) -> tuple[list[sp.Symbol], list[sp.Symbol]]:
    return list(sp.symbols(f"p1:{N + 1}", real=True)), list(sp.symbols(f"q1:{N + 1}", real=True))


def hamiltonian(N: int) -> sp.Expr:
    p, q = coordinates(N)
    return sum(pj ** 2 for pj in p) / 2 + sum(sp.exp(q[j] - q[j + 1]) for j in range(N - 1))


def equations_of_motion(N: int) -> dict[sp.Symbol, sp.Expr]:
    """qdot_j = dH/dp_j, pdot_j = -dH/dq_j."""
    p, q = coordinates(N)
    H = hamiltonian(N)
    return {**{qj: sp.diff(H, pj) for pj, qj in zip(p, q)}, **{pj: -sp.diff(H, qj) for pj, qj in zip(p, q)}}


def time_derivative(f: sp.Expr, flow: dict[sp.Symbol, sp.Expr]) -> sp.Expr:
    """df/dt along the flow (chain rule)."""
    return sum(sp.diff(f, x) * xdot for x, xdot in flow.items())


# the relative motion of two particles, r = q1 - q2: r'' = -2 exp(r), solved by exp(r) = c^2/2 sech^2(c t)
R_OF_T = sp.log(c ** 2 / 2) - 2 * sp.log(sp.cosh(c * t))
