r"""The symbolic sources of the emitted functions (one :class:`FunctionSpec` each).

Everything here is derived from :mod:`symbt.symbolic` (the Toda model in the
rational variables :math:`E_j = e^{q_j}`) and then rewritten for evaluation:

* *Shift invariance.*  Every output except Dapp's ``x, y`` is homogeneous of
  degree 0 in ``E`` (the Toda lattice only sees ``q_i - q_j``), so ``E_1 -> 1``,
  ``E_j -> exp(q_j - q_1)`` changes nothing mathematically; after
  ``powsimp`` every exponential is ``exp(q_i - q_j)`` -- no ``exp(q_j)`` that
  could overflow when the centre of mass drifts.
* ``tr^2 - 4`` is written ``(tr - 2)(tr + 2)`` (no cancellation in float64).
* The step is the paper's map (eqs. ``D``, ``xy``, ``lam0mu``, ``xyqqt``,
  ``imptransf``) in closed form: the slopes at site ``j`` are read off the
  *cyclically shifted* monodromy ``L^(j) = l_{j-1} ... l_1 l_N ... l_j``
  (the transported eigenvector is its eigenvector with the same eigenvalue),
  instead of transporting them site by site -- no loop, and no loss of
  ``log10(v^2)`` digits along the transport.  Of the two algebraically equal
  forms of a slope, ``(A - D + g)/(2B) = -2C/(A - D - g)``, the one without
  cancellation is selected (``Piecewise`` on the sign of ``(A - D) g``);
  ``q~_j = q_j + log1p(-x_j/E_j)`` and
  ``p~_j = p_j + 2 mu (u_j/d_j - u_{j+1}/d_{j+1})`` with the scaled slopes
  ``u_j = E_j y_j``, ``w_j = E_j z_j``, ``d_j = w_j - u_j`` (so
  ``x_j/E_j = 2 mu/d_j`` and ``eta_j = mu + 2 mu u_j/d_j``).

Branch ``b = +-1``: ``gamma_i = b sqrt(tr L(lambda_i)^2 - 4)`` (positive root) at
``lambda_1 = lambda_0 + mu`` and ``lambda_2 = lambda_0 - mu``.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp
from sympy.codegen.cfunctions import log1p

from ..symbolic.darboux import lam0, mu
from ..symbolic.toda import local_lax, toda_model

__all__ = ["ArgSpec", "Output", "FunctionSpec", "specs", "branch", "tr1", "tr2", "lam", "lam0", "mu",
           "coefficient_symbols", "disc"]

lam = sp.Symbol("lambda", real=True)
branch = sp.Symbol("branch", real=True)
tr1, tr2 = sp.symbols("tr1 tr2", real=True)


@dataclass(frozen=True)
class ArgSpec:
    """A function argument: ``kind`` is ``state`` (length-N array), ``scalar`` or ``branch``."""

    name: str
    kind: str
    symbols: tuple
    doc: str


@dataclass(frozen=True)
class Output:
    """One returned array: ``shape`` () / (N,) / (N, N); ``exprs`` flattened row-major."""

    name: str
    shape: tuple
    exprs: tuple
    doc: str


@dataclass(frozen=True)
class FunctionSpec:
    name: str
    equation: str
    summary: str
    args: tuple
    outputs: tuple
    kind: str  # "polynomial" (error scale: sum of |terms|) or "general"


def coefficient_symbols(N):
    return sp.symbols(f"c0:{N}", real=True)


def disc(t):
    """``tr^2 - 4`` as ``(tr - 2)(tr + 2)`` (kept unexpanded)."""
    return sp.Mul(t - 2, t + 2, evaluate=False)


def _shift(m, expr, expand=False):
    """``E_1 -> 1, E_j -> exp(q_j - q_1)`` then combine exponentials (valid for degree-0 expressions).

    ``expand=True`` (Laurent polynomials in E) expands first, so that every
    monomial becomes a single ``exp(q_i - q_j)``."""
    expr = sp.sympify(expr)
    if expand:
        expr = sp.expand(expr)
    sub = {m.E[0]: sp.Integer(1)}
    sub.update({m.E[j]: sp.exp(m.q[j] - m.q[0]) for j in range(1, m.N)})
    return sp.powsimp(expr.xreplace(sub), combine="exp", deep=True)


def _cyclic_monodromy(m, lam_, j):
    """``l_{j-1} ... l_1 l_N ... l_j`` (0-based j; j = 0 is L), expanded in lambda, then
    ``lambda -> lam_`` (so ``lambda_0 + mu`` stays one quantity: no binomial cancellation)."""
    M = sp.eye(2)
    for k in list(range(j, m.N)) + list(range(0, j)):
        M = local_lax(m.lam, m.p[k], m.E[k]) * M
    return M.applyfunc(sp.expand).xreplace({m.lam: lam_})


def _state_args(m):
    return (ArgSpec("p", "state", tuple(m.p), f"momenta p_1..p_{m.N}"),
            ArgSpec("q", "state", tuple(m.q), f"positions q_1..q_{m.N}"))


def _map_args(m):
    return _state_args(m) + (ArgSpec("lam0", "scalar", (lam0,), "lambda_0 (eq. lam0mu)"),
                             ArgSpec("mu", "scalar", (mu,), "mu > 0 (eq. lam0mu)"),
                             ArgSpec("branch", "branch", (branch,), "b = +1 or -1"))


def _slope(M, g, sign):
    """Eigenvector slope ``s`` of ``(1, -s)``: ``(A - D + sign g)/(2B) = -2C/(A - D - sign g)``,
    the form without cancellation selected by the sign of ``(A - D) * sign * g``."""
    A, B, C, D = M[0, 0], M[0, 1], M[1, 0], M[1, 1]
    dl = A - D
    first = (dl + sign * g) / (2 * B)
    second = -2 * C / (dl - sign * g)
    return A, B, C, D, first, second, sp.GreaterThan(sign * dl * g, 0)


@cache
def specs(N: int) -> tuple:
    """All emitted functions for the N-site lattice, in file order."""
    m = toda_model(N)
    p, q, E = m.p, m.q, m.E
    c = coefficient_symbols(N)
    H = m.hamiltonians
    out = []
    S = lambda e: _shift(m, e)  # noqa: E731
    P = lambda e: _shift(m, e, expand=True)  # noqa: E731

    # --- invariants (eq. tra) -------------------------------------------------
    out.append(FunctionSpec(
        "invariants", "tra", "H_0 .. H_{N-1}: coefficients of tr L(lambda) = sum_k H_k lambda^k (H_N = 1)",
        _state_args(m), (Output("H", (N,), tuple(P(H[k]) for k in range(N)), "H[..., k] = H_k"),),
        "polynomial"))
    trace = m.trace
    out.append(FunctionSpec(
        "spectral_trace", "tra", "tr L(lambda) = A(lambda) + D(lambda)",
        (ArgSpec("lam", "scalar", (lam,), "spectral parameter lambda"),) + _state_args(m),
        (Output("tr", (), (P(trace.xreplace({m.lam: lam})),), "tr L(lambda)"),), "polynomial"))

    # --- Hamiltonian vector fields (xdot = {H, x}: qdot = H_p, pdot = -H_q) -----
    fields = [m.hamiltonian_vector_field(H[k]) for k in range(N)]
    qd = tuple(P(fields[k][0][i]) for k in range(N) for i in range(N))
    pd = tuple(P(fields[k][1][i]) for k in range(N) for i in range(N))
    out.append(FunctionSpec(
        "hamiltonian_fields", "tra", "vector fields of H_0 .. H_{N-1}: qdot = dH_k/dp, pdot = -dH_k/dq",
        _state_args(m), (Output("qdot", (N, N), qd, "qdot[..., k, j] = dH_k/dp_j"),
                         Output("pdot", (N, N), pd, "pdot[..., k, j] = -dH_k/dq_j")), "polynomial"))
    qf = tuple(P(sp.Add(*[c[k] * fields[k][0][i] for k in range(N)])) for i in range(N))
    pf = tuple(P(sp.Add(*[c[k] * fields[k][1][i] for k in range(N)])) for i in range(N))
    out.append(FunctionSpec(
        "flow_field", "eqdisc", "vector field of sum_k c_k H_k (eq. eqdisc)",
        (ArgSpec("c", "state", tuple(c), "coefficients c_0 .. c_{N-1}"),) + _state_args(m),
        (Output("qdot", (N,), qf, "qdot_j"), Output("pdot", (N,), pf, "pdot_j")), "polynomial"))

    # --- Phi (eq. newkmu, real form) and its gradient ---------------------------
    def phi_of(t1, t2):
        return -branch * (sp.sign(t1) * sp.acosh(sp.Abs(t1) / 2) + sp.sign(t2) * sp.acosh(sp.Abs(t2) / 2))

    out.append(FunctionSpec(
        "phi_tr", "newkmu", "real Phi = -b (sgn(tr1) arccosh(|tr1|/2) + sgn(tr2) arccosh(|tr2|/2))",
        (ArgSpec("tr1", "scalar", (tr1,), "tr L(lambda_0 + mu)"), ArgSpec("tr2", "scalar", (tr2,), "tr L(lambda_0 - mu)"),
         ArgSpec("branch", "branch", (branch,), "b = +1 or -1")),
        (Output("phi", (), (phi_of(tr1, tr2),), "Phi"),), "general"))
    t_1 = S(trace.xreplace({m.lam: lam0 + mu}))
    t_2 = S(trace.xreplace({m.lam: lam0 - mu}))
    out.append(FunctionSpec(
        "phi", "newkmu", "real Phi on the map as a function of (p, q, lambda_0, mu, b)",
        _map_args(m), (Output("phi", (), (phi_of(t_1, t_2),), "Phi"),), "general"))
    # d/dx [sgn(t) arccosh(|t|/2)] = t_x / sqrt(t^2 - 4) for |t| > 2, either sign of t
    T = sp.Symbol("T", positive=True)
    dacosh = 1 / sp.sqrt(disc(T))
    if sp.simplify(sp.diff(sp.acosh(T / 2), T) ** 2 - dacosh ** 2) != 0:  # both positive for T > 2
        raise AssertionError("d/dT arccosh(T/2) != 1/sqrt(T^2 - 4)")
    tr_l1 = trace.xreplace({m.lam: lam0 + mu})
    tr_l2 = trace.xreplace({m.lam: lam0 - mu})
    w1 = 1 / sp.sqrt(disc(t_1))  # built directly: with T > 0 SymPy splits sqrt((T-2)(T+2))
    w2 = 1 / sp.sqrt(disc(t_2))
    gp = tuple(-branch * (P(m.d_p(tr_l1, i)) * w1 + P(m.d_p(tr_l2, i)) * w2) for i in range(N))
    gq = tuple(-branch * (P(m.d_q(tr_l1, i)) * w1 + P(m.d_q(tr_l2, i)) * w2) for i in range(N))
    out.append(FunctionSpec(
        "phi_grad", "newkmu", "gradient of the real Phi: dPhi/dx = -b (tr1_x / sqrt(tr1^2-4) + tr2_x / sqrt(tr2^2-4))",
        _map_args(m), (Output("dphi_dp", (N,), gp, "dPhi/dp_j"), Output("dphi_dq", (N,), gq, "dPhi/dq_j")),
        "general"))

    # --- c_k integrand (eq. eqdisc) ---------------------------------------------
    tl = S(trace.xreplace({m.lam: lam}))
    out.append(FunctionSpec(
        "ck_integrand", "eqdisc", "lambda^k / sqrt(tr L(lambda)^2 - 4), k = 0 .. N-1 (positive root; "
        "c_k = -b * integral over [lambda_0 - mu, lambda_0 + mu])",
        (ArgSpec("lam", "scalar", (lam,), "spectral parameter lambda"),) + _state_args(m),
        (Output("integrand", (N,), tuple(lam ** k / sp.sqrt(disc(tl)) for k in range(N)), "[..., k]"),),
        "general"))

    # --- scaled eigenvector slopes u_j = E_j y_j, w_j = E_j z_j at every site (eqs. l1l2, xy) ----
    G1 = branch * sp.sqrt(disc(t_1))
    G2 = branch * sp.sqrt(disc(t_2))
    u, w = [], []
    for j in range(N):
        Mj1 = _cyclic_monodromy(m, lam0 + mu, j)
        Mj2 = _cyclic_monodromy(m, lam0 - mu, j)
        *_, f1, s1, c1 = _slope(Mj1, sp.Symbol("g"), +1)
        *_, f2, s2, c2 = _slope(Mj2, sp.Symbol("g"), -1)
        gs = sp.Symbol("g")
        u.append(sp.Piecewise((S(E[j] * f1).xreplace({gs: G1}), S(c1).xreplace({gs: G1})),
                              (S(E[j] * s1).xreplace({gs: G1}), True)))
        w.append(sp.Piecewise((S(E[j] * f2).xreplace({gs: G2}), S(c2).xreplace({gs: G2})),
                              (S(E[j] * s2).xreplace({gs: G2}), True)))
    # --- eq. xy: x, y of Dapp (unscaled, E_1 = exp(q_1)), from the stable slopes -------------
    # y = (A1 - D1 + g1)/(2 B1) = u_1/E_1 and, with z = (A2 - D2 - g2)/(2 B2) = w_1/E_1,
    # the printed x = 2 B1 B2 (l2 - l1)/(B2 (A1-D1+g1) - B1 (A2-D2-g2)) = 2 mu/(z - y) = E_1 (2 mu/d_1).
    d = [w[j] - u[j] for j in range(N)]
    out.append(FunctionSpec(
        "dapp_xy", "xy", "x, y of the Darboux matrix (eq. xy; gamma_i = b sqrt(tr_i^2 - 4); the printed "
        "quotients rewritten without cancellation: y = u_1 e^{-q_1}, x = 2 mu e^{q_1}/(w_1 - u_1))",
        _map_args(m), (Output("x", (), (sp.exp(q[0]) * 2 * mu / d[0],), "x"),
                       Output("y", (), (sp.exp(-q[0]) * u[0],), "y")),
        "general"))

    # --- the step (eqs. xyqqt, imptransf) ---------------------------------------------------
    qt = tuple(q[j] + log1p(-2 * mu / d[j]) for j in range(N))
    pt = tuple(p[j] + 2 * mu * (u[j] / d[j] - u[(j + 1) % N] / d[(j + 1) % N]) for j in range(N))
    out.append(FunctionSpec(
        "bt_step", "imptransf", "one Backlund step (p, q) -> (p~, q~) (eqs. D, xy, lam0mu, xyqqt, imptransf)",
        _map_args(m), (Output("p_new", (N,), pt, "p~"), Output("q_new", (N,), qt, "q~")), "general"))
    return tuple(out)
