r"""The SymPy sources of the emitted functions (one :class:`FunctionSpec` each).

Everything here is derived from :mod:`symbt.symbolic` (the Toda model in the
rational variables :math:`E_j = e^{q_j}`).  Two builds of the same catalogue:

* :func:`sources` -- *the* SymPy source of every function, as the model states
  it (``E_j -> exp(q_j)``, no rewriting; the step along the paper's eqs. ``D``,
  ``xy``, ``lam0mu``, ``xyqqt``, ``imptransf`` with the eigenvector at site ``j``
  read off the cyclically shifted monodromy).  Every emitted module is checked
  against these, evaluated with mpmath at high precision (scene ``codegen``,
  ``tests/test_codegen_any_n.py``);
* :func:`specs` -- the closed forms actually printed for small N, rewritten for
  float64 evaluation:

  - *Shift invariance.*  Every output except Dapp's ``x, y`` is homogeneous of
    degree 0 in ``E`` (the lattice only sees ``q_i - q_j``), so ``E_1 -> 1``,
    ``E_j -> exp(q_j - q_1)`` changes nothing; the powers of ``E`` in each product
    are combined into one ``exp(q_i - q_j)`` -- no ``exp(q_j)`` that could overflow
    when the centre of mass drifts.
  - ``tr^2 - 4`` is written ``(tr - 2)(tr + 2)``, near a closed gap ``(A - D)^2 + 4BC`` (:mod:`.closed_gap`).
  - The slope at site 1 is read off the monodromy; of ``(A - D + g)/(2B) = -2C/(A - D - g)`` the
    form without cancellation is selected (``Piecewise`` on the sign of ``(A - D) g``, ``sign g = b``); the other
    sites by transport in the contracting direction (:func:`.transport.transported`, as ``symbt.numeric``,
    the root refined by one turn first: :func:`.transport.turned`); ``q~_j = q_j + log1p(-x_j/E_j)``,
    ``p~_j = p_j + 2 mu (u_j/d_j - u_{j+1}/d_{j+1})`` (:func:`.transport.read_out`), ``u_j = E_j y_j``,
    ``w_j = E_j z_j``, ``d_j = w_j - u_j`` the scaled slopes.
  - *Guards*: positive exactly where the real function exists (``tr_i^2 - 4``, the sign of
    ``tr_1 tr_2``, ``1 - x_j/E_j = e^{q~_j - q_j}``), or finite (``range``: every slope); the code
    raises ``NoRealMapError`` / ``NumericRangeError`` (or masks) where one is not.

Branch ``b = +-1``: ``gamma_i = b sqrt(tr L(lambda_i)^2 - 4)`` (positive root) at
``lambda_1 = lambda_0 + mu`` and ``lambda_2 = lambda_0 - mu``.

>>> [s.name for s in specs(2)][:3]
['invariants', 'spectral_trace', 'hamiltonian_fields']
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from typing import Any

import sympy as sp
from sympy.codegen.cfunctions import log1p
from sympy.polys.rings import PolyElement

from ..reference.literal import phi_from_traces
from ..symbolic.darboux import lam0, mu
from ..symbolic.toda import TodaModel, local_lax, toda_model
from .closed_gap import trace_discriminant
from .transport import illcond_guards, read_out, scaled_monodromy, transported, turned

__all__ = ["ArgSpec", "Output", "Guard", "FunctionSpec", "specs", "sources", "interface", "branch", "tr1", "tr2", "lam",
           "lam0", "mu", "coefficient_symbols", "disc", "phi_of", "FUNCTIONS"]

lam = sp.Symbol("lambda", real=True)
branch = sp.Symbol("branch", real=True)
tr1, tr2 = sp.symbols("tr1 tr2", real=True)

#: the emitted functions, in file order
FUNCTIONS = ("invariants", "spectral_trace", "hamiltonian_fields", "flow_field", "phi_tr", "phi", "phi_grad",
             "ck_integrand", "dapp_xy", "bt_step")


@dataclass(frozen=True)
class ArgSpec:
    """A function argument: ``kind`` is ``state`` (length-N array), ``scalar`` or ``branch``."""

    name: str
    kind: str
    symbols: tuple[sp.Symbol, ...]
    doc: str


@dataclass(frozen=True)
class Output:
    """One returned array: ``shape`` () / (N,) / (N, N); ``exprs`` flattened row-major."""

    name: str
    shape: tuple[int, ...]
    exprs: tuple[Any, ...]
    doc: str


@dataclass(frozen=True)
class Guard:
    """``expr > 0`` exactly where the real function exists; ``condition`` is ``trace`` or ``positivity``
    (as in ``NoRealMapError.condition``); ``stage`` 0 guards can be tested before anything else.
    ``condition = "range"``: ``expr`` must only be finite (else ``NumericRangeError``): an intermediate
    whose overflow would otherwise read out as a finite wrong value."""

    condition: str
    label: str
    expr: object
    stage: int


@dataclass(frozen=True)
class FunctionSpec:
    name: str
    equation: str
    summary: str
    args: tuple[ArgSpec, ...]
    outputs: tuple[Output, ...]
    kind: str  # "polynomial" (defined everywhere) or "general" (guarded real domain)
    guards: tuple[Guard, ...] = ()
    defs: tuple[tuple[sp.Symbol, Any], ...] = ()  # (Symbol, expr) pairs evaluated first (sources only)


def coefficient_symbols(N: int) -> tuple[sp.Symbol, ...]:
    return sp.symbols(f"c0:{N}", real=True)


def disc(t: sp.Expr) -> sp.Expr:
    """``tr^2 - 4`` as ``(tr - 2)(tr + 2)`` (kept unexpanded)."""
    return sp.Mul(t - 2, t + 2, evaluate=False)


def phi_of(t1: sp.Expr, t2: sp.Expr) -> sp.Expr:
    """Real Phi from the two traces (corrects eq. ``newkmu``): the one formula, ``symbt.reference.literal``'s."""
    return phi_from_traces(t1, t2, branch, ns=sp)


def _shift(m: TodaModel, expr: Any, expand: bool = False) -> sp.Basic:
    """``E_1 -> 1, E_j -> exp(q_j - q_1)``, the powers of ``E`` in every product combined into one
    exponential (valid for degree-0 expressions).

    ``expand=True`` (Laurent polynomials in E) expands first, so that every
    monomial becomes a single ``exp(q_i - q_j)``.  One pass over the tree (linear in
    its size; ``powsimp`` did the same in time growing much faster with N)."""
    expr = sp.sympify(expr)
    if expand:
        expr = sp.expand(expr)
    index = {E: j for j, E in enumerate(m.E)}

    def exp_of(powers: dict[int, int]) -> sp.Expr:
        arg = sp.Add(*[k * (m.q[j] - m.q[0]) for j, k in sorted(powers.items()) if j > 0 and k])
        return sp.exp(sp.expand(arg))           # exp(0) is SymPy's 1

    def rec(e: sp.Basic) -> sp.Basic:
        if e in index:
            return exp_of({index[e]: 1})
        if e.is_Atom:
            return e
        if e.is_Mul or (e.is_Pow and e.base in index):
            powers: dict[int, int] = {}
            rest: list[sp.Basic] = []
            for f in sp.Mul.make_args(e):
                b, x = f.as_base_exp()
                if b in index and x.is_Integer:
                    powers[index[b]] = powers.get(index[b], 0) + int(x)
                else:
                    rest.append(rec(f))
            return sp.Mul(*rest) * exp_of(powers)
        return e.func(*[rec(x) for x in e.args])

    return rec(expr)


class _TraceRing:
    """``tr L`` of the model multiplied out in a sparse polynomial ring, with its derivatives.

    The same product ``l_N ... l_1`` of the model's :func:`~symbt.symbolic.toda.local_lax` as
    ``TodaModel.trace``/``hamiltonians`` (checked equal, derivatives included, for N <= 3 in
    :func:`_build`), with ``1/E_j`` as extra generators and the flow coefficients ``c_k`` as
    generators too: ~100x faster than expression ``expand``/``diff`` for N = 8.  tr L has
    ``Q_N = (1 + sqrt 2)^N + (1 - sqrt 2)^N`` monomials (14, 82, 1154, 39202 for N = 3, 5, 8, 12).
    """

    def __init__(self, N: int) -> None:
        m = self.m = toda_model(N)
        self.N = N
        self.inv = sp.symbols(f"Einv1:{N + 1}")      # ring generators: no assumptions read
        self.c = coefficient_symbols(N)
        self.R, *g = sp.ring([m.lam, *m.p, *m.E, *self.inv, *self.c], sp.ZZ)
        self.lam, self.p, self.E = g[0], g[1:N + 1], g[N + 1:2 * N + 1]
        self.Einv, self.cg = g[2 * N + 1:3 * N + 1], g[3 * N + 1:]
        R = self.R
        M = [[R.one, R.zero], [R.zero, R.one]]
        for j in range(N):
            l = local_lax(m.lam, m.p[j], m.E[j]).xreplace({1 / m.E[j]: self.inv[j]})
            L = [[R.from_expr(x) if x != 0 else R.zero for x in l[i, :]] for i in range(2)]
            M = [[L[i][0] * M[0][k] + L[i][1] * M[1][k] for k in range(2)] for i in range(2)]
        self.tr = M[0][0] + M[1][1]
        parts: list[dict[tuple[int, ...], Any]] = [{} for _ in range(N + 1)]
        for mon, coeff in self.tr.terms():
            parts[mon[0]][(0,) + mon[1:]] = coeff
        self.H = [R.from_dict(h) if h else R.zero for h in parts]

    def d_p(self, f: PolyElement, i: int) -> PolyElement:
        return f.diff(self.p[i])

    def d_q(self, f: PolyElement, i: int) -> PolyElement:
        """``d/dq_i = E_i d/dE_i - E_i^{-1} d/dE_i^{-1}``."""
        return self.E[i] * f.diff(self.E[i]) - self.Einv[i] * f.diff(self.Einv[i])

    def expr(self, f: PolyElement, lam_: sp.Expr | None = None, q_exp: bool = False) -> sp.Expr:
        """As a SymPy expression: ``lambda -> lam_``; ``E_j -> exp(q_j)`` if ``q_exp`` (else E_j)."""
        m = self.m
        E = [sp.exp(x) for x in m.q] if q_exp else list(m.E)
        Ei = [sp.exp(-x) for x in m.q] if q_exp else [1 / x for x in m.E]
        return f.as_expr(m.lam if lam_ is None else lam_, *m.p, *E, *Ei, *self.c)


@cache
def _trace_ring(N: int) -> _TraceRing:
    return _TraceRing(N)


@dataclass(frozen=True)
class RingValue:
    """A source value kept as a ring polynomial (``lam`` = what lambda stands for; None = the symbol)
    and evaluated term by term (see :func:`symbt.codegen.verify.evaluate_source`): building a SymPy
    expression of the ~10^4 monomials of the N = 8 fields would take longer than the check."""

    ring: _TraceRing
    poly: PolyElement
    lam: object = None

    def evaluate(self, env: dict[Any, Any], exp: Callable[[Any], Any], memo: dict[Any, Any] | None = None) -> Any:
        """Value at ``env`` (Symbol -> number; ``E_j = exp(q_j)`` via ``exp``); ``memo`` shares the
        powers of the generators between values at the same point."""
        T, m = self.ring, self.ring.m
        lam_ = env.get(lam) if self.lam is None else _value(self.lam, env)   # None: read only by a lambda term
        memo = {} if memo is None else memo
        key = ("ringpowers", str(self.lam))
        if key not in memo:
            gens = [lam_] + [env[x] for x in m.p] + [exp(env[x]) for x in m.q] + [exp(-env[x]) for x in m.q]
            memo[key] = (gens + [env.get(x) for x in T.c], {})      # None: a c_k the value has no term in
        gens, powers = memo[key]
        total = 0
        for coeff, factors in self._terms():
            t = coeff
            for i, e in factors:
                v = powers.get((i, e))
                if v is None:
                    v = powers[(i, e)] = gens[i] ** e
                t = t * v
            total += t
        return total

    def _terms(self) -> list[tuple[int, tuple[tuple[int, int], ...]]]:
        cached = _TERMS.get(id(self.poly))
        if cached is None or cached[0] is not self.poly:
            terms = [(int(c), tuple((i, e) for i, e in enumerate(mon) if e)) for mon, c in self.poly.terms()]
            cached = _TERMS[id(self.poly)] = (self.poly, terms)
        return cached[1]


_TERMS: dict[int, tuple[PolyElement, list[tuple[int, tuple[tuple[int, int], ...]]]]] = {}


def _value(e: sp.Expr, env: dict[Any, Any]) -> Any:
    """Value of an integer combination of symbols (``lambda0 +- mu``)."""
    return sum(int(c) * env[x] for x, c in e.as_coefficients_dict().items())


def _cyclic_monodromy(m: TodaModel, lam_: sp.Expr, j: int, expand: bool = True) -> sp.Matrix:
    """``l_{j-1} ... l_1 l_N ... l_j`` (0-based j; j = 0 is L); with ``expand`` expanded in lambda
    and then ``lambda -> lam_`` (so ``lambda_0 + mu`` stays one quantity: no binomial cancellation)."""
    M = sp.eye(2)
    for k in list(range(j, m.N)) + list(range(0, j)):
        M = local_lax(m.lam, m.p[k], m.E[k]) * M
    if expand:
        M = M.applyfunc(sp.expand)
    return M.xreplace({m.lam: lam_})


def _state_args(m: TodaModel) -> tuple[ArgSpec, ...]:
    return (ArgSpec("p", "state", tuple(m.p), f"momenta p_1..p_{m.N}"),
            ArgSpec("q", "state", tuple(m.q), f"positions q_1..q_{m.N}"))


def _map_args(m: TodaModel) -> tuple[ArgSpec, ...]:
    return _state_args(m) + (ArgSpec("lam0", "scalar", (lam0,), "lambda_0 (eq. lam0mu)"),
                             ArgSpec("mu", "scalar", (mu,), "mu (eq. lam0mu)"),
                             ArgSpec("branch", "branch", (branch,), "b = +1 or -1"))


def _slope(M: sp.Matrix, g: sp.Expr, sign: int) -> tuple[sp.Expr, sp.Expr, sp.Basic]:
    """Eigenvector slope ``s`` of ``(1, -s)``: ``(A - D + sign g)/(2B) = -2C/(A - D - sign g)``,
    the form without cancellation selected by the sign of ``(A - D) * sign * g``."""
    A, B, C, D = M[0, 0], M[0, 1], M[1, 0], M[1, 1]
    dl = A - D
    return (dl + sign * g) / (2 * B), -2 * C / (dl - sign * g), sp.GreaterThan(sign * dl * g, 0)


def _with_guards(spec: FunctionSpec, extra: tuple[Guard, ...], ill_t: tuple[Guard, ...] = (),
                 ill_s: tuple[Guard, ...] = ()) -> FunctionSpec:
    """``spec`` with the guards ``extra`` after its trace guards (decided in order: an overflowed slope is a
    range error, not a positivity decided from a wrong value), each trace guard after its conditioning
    guard ``ill_t`` and the slopes' conditioning ``ill_s`` before the positivity guards: the order of
    ``symbt.numeric``'s fused kernel (:mod:`symbt.numeric.core.fused`)."""
    k = sum(g.condition == "trace" for g in spec.guards)
    traces = tuple(g for pair in zip(ill_t, spec.guards[:k]) for g in pair) if ill_t else spec.guards[:k]
    return FunctionSpec(spec.name, spec.equation, spec.summary, spec.args, spec.outputs, spec.kind,
                        traces + tuple(extra) + tuple(ill_s) + spec.guards[k:], spec.defs)


def _check_dacosh() -> None:
    # d/dT arccosh(T/2) = 1/sqrt(T^2 - 4) for T > 2 (both sides positive: squares compared, no assumption on T)
    T = sp.Symbol("T")
    if sp.cancel(sp.diff(sp.acosh(T / 2), T) ** 2 - 1 / (T ** 2 - 4)) != 0:
        raise AssertionError("d/dT arccosh(T/2) != 1/sqrt(T^2 - 4)")


@cache
def interface(N: int) -> dict[str, FunctionSpec]:
    """Name -> :class:`FunctionSpec` without expressions (``exprs = ()``, guard ``expr = None``): what every
    emitted ``toda{N}`` offers, whatever its form.  Cheap (no derivation)."""
    m = toda_model(N)
    st, mp_ = _state_args(m), _map_args(m)
    lam_arg = (ArgSpec("lam", "scalar", (lam,), "spectral parameter lambda"),)
    trace_g = (Guard("trace", "lam1 = lam0 + mu", None, 0), Guard("trace", "lam2 = lam0 - mu", None, 0))
    O = lambda name, shape, doc: Output(name, shape, (), doc)  # noqa: E731
    F = FunctionSpec
    specs_ = [
        F("invariants", "tra", "H_0 .. H_{N-1}: coefficients of tr L(lambda) = sum_k H_k lambda^k (H_N = 1)",
          st, (O("H", (N,), "H[..., k] = H_k"),), "polynomial"),
        F("spectral_trace", "tra", "tr L(lambda) = A(lambda) + D(lambda)", lam_arg + st,
          (O("tr", (), "tr L(lambda)"),), "polynomial"),
        F("hamiltonian_fields", "tra", "vector fields of H_0 .. H_{N-1}: qdot = dH_k/dp, pdot = -dH_k/dq", st,
          (O("qdot", (N, N), "qdot[..., k, j] = dH_k/dp_j"), O("pdot", (N, N), "pdot[..., k, j] = -dH_k/dq_j")),
          "polynomial"),
        F("flow_field", "eqdisc", "vector field of sum_k c_k H_k (eq. eqdisc)",
          (ArgSpec("c", "state", tuple(coefficient_symbols(N)), "coefficients c_0 .. c_{N-1}"),) + st,
          (O("qdot", (N,), "qdot_j"), O("pdot", (N,), "pdot_j")), "polynomial"),
        F("phi_tr", "newkmu", "real Phi = -b (sgn(tr1) arccosh(|tr1|/2) + sgn(tr2) arccosh(|tr2|/2))",
          (ArgSpec("tr1", "scalar", (tr1,), "tr L(lambda_0 + mu)"),
           ArgSpec("tr2", "scalar", (tr2,), "tr L(lambda_0 - mu)"),
           ArgSpec("branch", "branch", (branch,), "b = +1 or -1")),
          (O("phi", (), "Phi"),), "general", (Guard("trace", "tr1", None, 0), Guard("trace", "tr2", None, 0))),
        F("phi", "newkmu", "real Phi on the map as a function of (p, q, lambda_0, mu, b)", mp_,
          (O("phi", (), "Phi"),), "general", trace_g),
        F("phi_grad", "newkmu", "gradient of the real Phi: dPhi/dx = -b (tr1_x / sqrt(tr1^2-4) + "
          "tr2_x / sqrt(tr2^2-4))", mp_, (O("dphi_dp", (N,), "dPhi/dp_j"), O("dphi_dq", (N,), "dPhi/dq_j")),
          "general", trace_g),
        F("ck_integrand", "eqdisc", "lambda^k / sqrt(tr L(lambda)^2 - 4), k = 0 .. N-1 (positive root; "
          "c_k = -b * integral over [lambda_0 - mu, lambda_0 + mu])", lam_arg + st,
          (O("integrand", (N,), "[..., k]"),), "general", (Guard("trace", "lam", None, 0),)),
        F("dapp_xy", "xy", "x, y of the Darboux matrix (eq. xy; gamma_i = b sqrt(tr_i^2 - 4); computed without "
          "cancellation: y = u_1 e^{-q_1}, x = 2 mu e^{q_1}/(w_1 - u_1), u, w the scaled slopes)", mp_,
          (O("x", (), "x"), O("y", (), "y")), "general", trace_g),
        F("bt_step", "imptransf", "one Backlund step (p, q) -> (p~, q~) (eqs. D, xy, lam0mu, xyqqt, imptransf)",
          mp_, (O("p_new", (N,), "p~"), O("q_new", (N,), "q~")), "general",
          trace_g + tuple(Guard("positivity", f"Etilde_{j + 1}", None, 1) for j in range(N))),
    ]
    if tuple(s.name for s in specs_) != FUNCTIONS:
        raise AssertionError("catalogue out of order")
    return {s.name: s for s in specs_}


def _fill(spec: FunctionSpec, exprs: Sequence[Sequence[Any]], guard_exprs: Sequence[Any] = (),
          defs: Sequence[tuple[sp.Symbol, Any]] = ()) -> FunctionSpec:
    """``spec`` with the output expressions (one tuple per output), guard expressions and definitions."""
    outs = tuple(Output(o.name, o.shape, tuple(e), o.doc) for o, e in zip(spec.outputs, exprs))
    if any(len(o.exprs) != math.prod(o.shape) for o in outs):
        raise AssertionError(f"{spec.name}: wrong number of expressions")
    guards = tuple(Guard(g.condition, g.label, e, g.stage) for g, e in zip(spec.guards, guard_exprs))
    return FunctionSpec(spec.name, spec.equation, spec.summary, spec.args, outs, spec.kind, guards, tuple(defs))


@cache
def specs(N: int) -> tuple[FunctionSpec, ...]:
    """All emitted functions for the N-site lattice in closed form, rewritten for float64 (file order)."""
    return _build(N, rewrite=True)


@cache
def sources(N: int) -> tuple[FunctionSpec, ...]:
    """The same functions as the model states them (``E_j = exp(q_j)``; no rewriting, no guards)."""
    return _build(N, rewrite=False)


def _build(N: int, rewrite: bool) -> tuple[FunctionSpec, ...]:
    m = toda_model(N)
    p, q, E = m.p, m.q, m.E
    T = _trace_ring(N)
    if rewrite:
        X = lambda f, lam_=None: T.expr(f, lam_)  # noqa: E731
    else:
        X = lambda f, lam_=None: RingValue(T, f, lam_)  # noqa: E731
    if N <= 3 and rewrite:   # the ring computation is the model's
        checks = [(X(T.tr), m.trace)] + [(X(h), h2) for h, h2 in zip(T.H, m.hamiltonians)]
        checks += [(X(T.d_p(T.H[0], i)), m.d_p(m.hamiltonians[0], i)) for i in range(N)]
        checks += [(X(T.d_q(T.H[0], i)), m.d_q(m.hamiltonians[0], i)) for i in range(N)]
        if any(sp.expand(a - b) != 0 for a, b in checks):
            raise AssertionError("ring product differs from TodaModel.trace / hamiltonians / d_p / d_q")
    I = interface(N)
    to_q = {E[j]: sp.exp(q[j]) for j in range(N)}
    if rewrite:
        S = lambda e: _shift(m, e)  # noqa: E731
        P = lambda e: _shift(m, e, expand=True)  # noqa: E731
    else:
        S = P = lambda e: e  # noqa: E731
    out = {}

    # --- invariants, trace (eq. tra); Hamiltonian vector fields (xdot = {H, x}) ------------
    out["invariants"] = _fill(I["invariants"], [[P(X(T.H[k])) for k in range(N)]])
    out["spectral_trace"] = _fill(I["spectral_trace"], [[P(X(T.tr, lam))]])
    qd = [[T.d_p(T.H[k], i) for i in range(N)] for k in range(N)]
    pd = [[-T.d_q(T.H[k], i) for i in range(N)] for k in range(N)]
    out["hamiltonian_fields"] = _fill(I["hamiltonian_fields"], [
        [P(X(qd[k][i])) for k in range(N) for i in range(N)], [P(X(pd[k][i])) for k in range(N) for i in range(N)]])
    out["flow_field"] = _fill(I["flow_field"], [
        [P(X(sum((T.cg[k] * qd[k][i] for k in range(N)), T.R.zero))) for i in range(N)],
        [P(X(sum((T.cg[k] * pd[k][i] for k in range(N)), T.R.zero))) for i in range(N)]])

    # --- Phi (eq. newkmu, real form) and its gradient; the c_k integrand (eq. eqdisc) ----------
    # The sources name the traces (T1, T2, Tl: definitions evaluated first) -- SymPy's automatic
    # assumptions on sqrt(huge polynomial) would take minutes for N = 8.
    out["phi_tr"] = _fill(I["phi_tr"], [[phi_of(tr1, tr2)]], [disc(tr1), disc(tr2)])
    l1, l2 = lam0 + mu, lam0 - mu
    defs: tuple[tuple[sp.Symbol, Any], ...] = ()
    if rewrite:
        t_1, t_2, tl = S(X(T.tr, l1)), S(X(T.tr, l2)), S(X(T.tr, lam))
    else:
        t_1, t_2, tl = sp.symbols("T1 T2 Tl", real=True)
        defs = ((t_1, X(T.tr, l1)), (t_2, X(T.tr, l2)))
    tg = [disc(t_1), disc(t_2)]
    out["phi"] = _fill(I["phi"], [[phi_of(t_1, t_2)]], tg, defs)
    _check_dacosh()
    w1 = 1 / sp.sqrt(disc(t_1))  # built directly: with T > 0 SymPy splits sqrt((T-2)(T+2))
    w2 = 1 / sp.sqrt(disc(t_2))
    gdefs = list(defs)

    def named(name: str, value: Any) -> Any:   # sources: a named definition; closed form: the expression
        if rewrite:
            return P(value)
        sym = sp.Symbol(name, real=True)
        gdefs.append((sym, value))
        return sym

    dtr = {(v, i, k): named(f"d{v}{i}_{k}", X((T.d_p if v == "p" else T.d_q)(T.tr, i), lk))
           for v in "pq" for i in range(N) for k, lk in ((1, l1), (2, l2))}
    out["phi_grad"] = _fill(I["phi_grad"], [
        [-branch * (dtr["p", i, 1] * w1 + dtr["p", i, 2] * w2) for i in range(N)],
        [-branch * (dtr["q", i, 1] * w1 + dtr["q", i, 2] * w2) for i in range(N)]], tg, gdefs)
    out["ck_integrand"] = _fill(I["ck_integrand"], [[lam ** k / sp.sqrt(disc(tl)) for k in range(N)]], [disc(tl)],
                                () if rewrite else ((tl, X(T.tr, lam)),))

    # --- eigenvector slopes at every site (eqs. l1l2, xy); Dapp's x, y; the step --------------
    G1, G2 = branch * sp.sqrt(disc(t_1)), branch * sp.sqrt(disc(t_2))
    gs = sp.Symbol("g")
    if rewrite:   # scaled slopes u_j = E_j y_j, w_j = E_j z_j: site 1 from the monodromy, then transported
        # the step's monodromies and traces as products of the scaled m_j, a_j = lambda + p_j kept whole (the
        # trace expanded in lambda lost ~log10(lambda^N/|tr|) digits to cancellation: 115 eps x condition)
        M1, M2 = scaled_monodromy(m, lam0 + mu), scaled_monodromy(m, lam0 - mu)
        t_1, t_2 = M1[0, 0] + M1[1, 1], M2[0, 0] + M2[1, 1]
        tg = [trace_discriminant(M1), trace_discriminant(M2)]   # near a closed gap: (A - D)^2 + 4BC (closed_gap)
        G1, G2 = branch * sp.sqrt(tg[0]), branch * sp.sqrt(tg[1])
        f1, s1, c1 = (x.xreplace({gs: G1 if i < 2 else branch}) for i, x in enumerate(_slope(M1, gs, +1)))
        f2, s2, c2 = (x.xreplace({gs: G2 if i < 2 else branch}) for i, x in enumerate(_slope(M2, gs, -1)))
        u0, w0 = sp.Piecewise((f1, c1), (s1, True)), sp.Piecewise((f2, c2), (s2, True))
        # u's eigenvalue (t1 - g1)/2 has |v| >= 1 iff t1 g1 <= 0, w's (t2 + g2)/2 iff t2 g2 >= 0: there the forward
        # transport contracts, else the backward one (signs only); each root refined by one turn first (turned)
        fw1, fw2 = sp.LessThan(branch * sp.sign(t_1), 0), sp.GreaterThan(branch * sp.sign(t_2), 0)
        u = transported(m, lam0 + mu, turned(m, lam0 + mu, u0, fw1), fw1)
        w = transported(m, lam0 - mu, turned(m, lam0 - mu, w0, fw2), fw2)
        # y = u_1/E_1; the printed x = 2 B1 B2 (l2 - l1)/(B2 (A1-D1+g1) - B1 (A2-D2-g2)) = 2 mu/(z - y)
        d = [w[j] - u[j] for j in range(N)]
        x_, y_ = sp.exp(q[0]) * 2 * mu / d[0], sp.exp(-q[0]) * u[0]
        xr, eta = read_out(mu, u, w, d)         # 2 mu/d_j divided once; p~ without cancelling fractions
        qt, pt = [q[j] + log1p(-x) for j, x in enumerate(xr)], [p[j] + e for j, e in enumerate(eta)]
        pos = [1 - x for x in xr]
        # opposite traces: different gaps (decided on the signs); slopes finite (inf reads out as 2 mu/d = 0)
        gap = "Etilde_j for some j (tr L(lam1), tr L(lam2) of opposite signs)"
        extra: tuple[Guard, ...] = (Guard("positivity", gap, sp.sign(t_1) * sp.sign(t_2), 0),)
        extra += tuple(Guard("range", f"{name}_{j + 1}", v, 1)
                       for name, vs in (("u", u), ("w", w), ("d", d)) for j, v in enumerate(vs))
        ill_t, ill_s = illcond_guards(m, Guard, (t_1, t_2), u, w, d, disc)
        sdefs: tuple[tuple[sp.Symbol, Any], ...] = ()
    else:         # the paper's route: eq. xy as printed, x_j = 2 mu/(z_j - y_j), E~ = E - x, eta = x y + mu
        g1, g2 = sp.symbols("G1 G2", real=True)
        sdefs = defs + ((g1, G1), (g2, G2))
        ys, zs = [], []
        for j in range(N):
            ent = sp.symbols(f"A1_{j} B1_{j} D1_{j} A2_{j} B2_{j} D2_{j}", real=True)
            M1 = _cyclic_monodromy(m, lam0 + mu, j, expand=False).xreplace(to_q)
            M2 = _cyclic_monodromy(m, lam0 - mu, j, expand=False).xreplace(to_q)
            sdefs += tuple(zip(ent, (M1[0, 0], M1[0, 1], M1[1, 1], M2[0, 0], M2[0, 1], M2[1, 1])))
            A1, B1, D1, A2, B2, D2 = ent
            ys.append((A1 - D1 + g1) / (2 * B1))
            zs.append((A2 - D2 - g2) / (2 * B2))
            if j == 0:   # eq. xy as printed (lambda_2 - lambda_1 = -2 mu)
                x_ = 2 * B1 * B2 * ((lam0 - mu) - (lam0 + mu)) / (B2 * (A1 - D1 + g1) - B1 * (A2 - D2 - g2))
        y_ = ys[0]
        xs = [2 * mu / (zs[j] - ys[j]) for j in range(N)]
        eta = [xs[j] * ys[j] + mu for j in range(N)]
        qt = [sp.log(sp.exp(q[j]) - xs[j]) for j in range(N)]
        pt = [p[j] + eta[j] - eta[(j + 1) % N] for j in range(N)]
        pos = [1 - xs[j] / sp.exp(q[j]) for j in range(N)]
    out["dapp_xy"] = _fill(I["dapp_xy"], [[x_], [y_]], tg, sdefs)
    out["bt_step"] = _fill(I["bt_step"], [pt, qt], tg + pos, sdefs)
    if rewrite:
        out["dapp_xy"] = _with_guards(out["dapp_xy"], extra, ill_t, ill_s)
        out["bt_step"] = _with_guards(out["bt_step"], extra, ill_t, ill_s)
    return tuple(out[name] for name in FUNCTIONS)
