r"""``symbt bench``: work-precision benchmark of the Bäcklund map as an integrator.

Usage::

    symbt bench [--quick] [--out DIR] [--figure PNG] [--skip-50]

Problem.  By Theorem 2 of the paper (checked by the claims ``Hdiscr.n3`` and
``Hdiscr.deep.n3`` of scene ``theorem2``) ``n`` Bäcklund steps with parameters
``(lam0, mu, branch)`` are *exactly* the time-``n`` flow of ``G = sum_k c_k H_k``
with ``c_k = -b int_{lam0-mu}^{lam0+mu} lam^k / sqrt(tr^2 - 4) dlam``.  So the BT
orbit computed in 50-digit mpmath is the reference solution of Hamilton's
equations ``qdot = dG/dp``, ``pdot = -dG/dq`` and every ODE integrator can be
scored against it.  Cases: the paper's N=3 example (``p=(-20,10,1)``,
``q=(1,0,0.9)``, ``lam0=10``, ``mu=5`` and ``mu=2``) for 3500 steps; an N=2 case
in the *bounded* gap (``tr < -2``); an N=64 chain with ``lam0 +- mu`` beyond
the spectrum.

Contenders.  float64 BT: the library :func:`~symbt.numeric.bt_orbit` (numpy),
the fused kernel :func:`~symbt.numeric.fast.fast_orbit` (numba if installed,
plain Python otherwise -- both are timed when numba is present) and the
emitted closed-form step ``symbt.generated.toda{N}.bt_step`` (if present).
ODE solvers on Hamilton's equations of ``G``: scipy ``solve_ivp`` DOP853,
RK45, LSODA with ``rtol = atol`` swept over ``1e-3 .. 1e-14``, and the
symplectic 3-stage Gauss--Legendre collocation method (order 6, fixed-point
iteration to round-off) at several step sizes.  The vector field is the
emitted ``toda{N}.flow_field`` (N = 2, 3) or :class:`FlowField` (any N; exact
``sum_k c_k grad H_k`` through interpolatory quadrature weights on N
Chebyshev nodes and prefix/suffix monodromy products, O(N^2) per call).  The
``c_k`` given to the ODE solvers are the 30-digit values rounded to float64.

Metrics.  Error at checkpoints (every n/100 steps): the normwise relative
error ``||x - x_ref|| / ||(p_ref, q_ref - mean q_ref)||``.  The numerator
includes everything (also the error of the centre of mass ``mean q``); the
denominator leaves the centre of mass out because it drifts linearly (|mean
q| ~ 500 after 3500 steps of the paper's example) and including it would make
every error look ~100x smaller.  ``final`` = error at step n, ``max`` = over
all checkpoints.  Invariant drift: ``max |H_k(x) - H_k(x_0)| / |H_k(x_0)|`` over
checkpoints and k (N <= 8; float64 evaluation), for N = 64 the relative change
of ``tr L`` at ``lam0`` and ``lam0 +- mu``.  Wall time: median of repeats after
a warm-up run (5 repeats for runs < 0.5 s, 3 below 5 s, else 1); function
evaluations (``nfev``; GL: stage evaluations).  Set-up (30-digit ``c_k``,
quadrature weights, numba compilation, module import) is reported apart.

Headline.  ``time(cheapest contender whose final error <= the BT's) / time(BT)``
measured in the same run; if no contender reaches it, the ratio against the
most accurate contender is reported together with its error.  At 50 digits
the mpmath BT is compared with a Taylor-series integrator
(:func:`symbt.reference.taylor.hamiltonian_flow`, exact Taylor coefficients by Cauchy
products; plus ``mpmath.odefun`` on a short horizon in the full run).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import sys
import time
from dataclasses import dataclass

import mpmath
import numpy as np

from .numeric import bt_orbit, bt_step, flow_coefficients, invariants, spectral_trace
from .numeric.fast import HAVE_NUMBA, fast_orbit
from .paper import P_EXAMPLE, Q_EXAMPLE

__all__ = ["main", "FlowField", "gauss_legendre_orbit", "Case", "CASES", "band_edge_case",
           "map_condition"]

P_PAPER, Q_PAPER = P_EXAMPLE, Q_EXAMPLE


@dataclass
class Case:
    name: str
    p: tuple
    q: tuple
    lam0: float
    mu: float
    n: int
    branch: int = 1
    note: str = ""

    @property
    def N(self):
        return len(self.p)


def _chain64():
    rng = np.random.default_rng(64)
    p = tuple(float(v) for v in np.round(rng.normal(size=64), 6))
    q = tuple(float(v) for v in np.round(0.5 * rng.normal(size=64), 6))
    return p, q


def CASES(quick=False):
    n3 = 300 if quick else 3500
    p64, q64 = _chain64()
    return [
        Case("paper-mu5", P_PAPER, Q_PAPER, 10.0, 5.0, n3, note="paper's N=3 example, mu=5"),
        Case("paper-mu2", P_PAPER, Q_PAPER, 10.0, 2.0, n3, note="paper's N=3 example, mu=2"),
        Case("n2-inner-gap", (3.0, -1.0), (0.4, -0.3), -1.0, 1.5, 300 if quick else 1000,
             note="N=2, bounded gap (tr < -2 on [lam0-mu, lam0+mu])"),
        Case("n64-chain", p64, q64, 5.0, 1.5, 20 if quick else 50,
             note="N=64, p~N(0,1), q~N(0,1/4) (seed 64, 6 decimals); [3.5, 6.5] lies above the "
                  "spectrum (top band edge ~2.98)"),
    ]


# --------------------------------------------------------------------------- timing

def _timed(fn, warm=None, quick=False):
    """Run ``warm()`` (or ``fn()``) once untimed, then repeats; returns (result, median, repeats)."""
    (warm or fn)()
    t0 = time.perf_counter()
    res = fn()
    times = [time.perf_counter() - t0]
    reps = 1 if times[0] >= 5 else (3 if times[0] >= 0.5 else 5)
    if quick:
        reps = min(reps, 3 if times[0] < 0.5 else 1)
    for _ in range(reps - 1):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return res, statistics.median(times), len(times)


# --------------------------------------------------------------------------- reference

def reference_orbit(case, dps=50, every=1):
    """Checkpoint states of the mpmath BT orbit as double-double (hi, lo) arrays."""
    rows = list(range(0, case.n + 1, every))
    if rows[-1] != case.n:
        rows.append(case.n)
    want = set(rows)
    hi = np.empty((len(rows), 2 * case.N))
    lo = np.empty_like(hi)
    with mpmath.workdps(dps):
        p = [mpmath.mpf(v) for v in case.p]
        q = [mpmath.mpf(v) for v in case.q]
        k = 0
        for i in range(case.n + 1):
            if i:
                p, q = bt_step(p, q, case.lam0, case.mu, branch=case.branch)
            if i in want:
                for j, v in enumerate(p + q):
                    h = float(v)
                    hi[k, j] = h
                    lo[k, j] = float(v - h)
                k += 1
    return np.array(rows), hi, lo


def flow_coeffs_mp(case, dps=30):
    """``c_k`` at ``dps`` digits, rounded to float64.

    Integrates ``(lam/s)^k s^N / sqrt(tr^2 - 4)`` (``s = |lam0| + |mu|``) with
    ``mpmath.quad`` and rescales: ``mpmath.quad``'s error control is absolute, so
    unscaled integrals of size ~1e-149 (N = 64) would only be good to ~1e-11
    relative (``numeric.flow_coefficients`` on mpmath input has this problem).
    """
    N = case.N
    with mpmath.workdps(dps):
        P = [mpmath.mpf(v) for v in case.p]
        Q = [mpmath.mpf(v) for v in case.q]
        s = mpmath.mpf(max(1.0, abs(case.lam0) + abs(case.mu)))
        sN = s**N
        l0, mu = mpmath.mpf(case.lam0), mpmath.mpf(case.mu)
        out = []
        for k in range(N):
            def f(lam, k=k):
                t = spectral_trace(lam, P, Q) / sN
                return (lam / s) ** k / mpmath.sqrt((t - 2 / sN) * (t + 2 / sN))
            v = mpmath.quad(f, [l0 - mu, l0, l0 + mu])
            out.append(float(-case.branch * v * s ** (k - N)))
        return out


def state_errors(P, Q, hi, lo):
    """Normwise relative errors (see module docstring) at every checkpoint row."""
    X = np.concatenate([P, Q], axis=-1)
    d = (X - hi) - lo
    N = P.shape[-1]
    pr = hi[:, :N]
    qr = hi[:, N:]
    den = np.sqrt(np.sum(pr**2, -1) + np.sum((qr - qr.mean(-1, keepdims=True))**2, -1))
    return np.sqrt(np.sum(d**2, -1)) / den


class InvariantMeter:
    def __init__(self, case):
        self.case = case
        with mpmath.workdps(40):
            P = [mpmath.mpf(v) for v in case.p]
            Q = [mpmath.mpf(v) for v in case.q]
            if case.N <= 8:
                self.ref = np.array([float(v) for v in invariants(P, Q)])
            else:
                self.lams = (case.lam0 - case.mu, case.lam0, case.lam0 + case.mu)
                self.ref = np.array([float(spectral_trace(l, P, Q)) for l in self.lams])

    def drift(self, P, Q):
        Qc = Q - Q.mean(-1, keepdims=True)
        with np.errstate(all="ignore"):
            if self.case.N <= 8:
                H = invariants(P, Qc)
            else:
                H = np.stack([spectral_trace(l, P, Qc) for l in self.lams], -1)
        return float(np.max(np.abs(H - self.ref) / np.abs(self.ref)))


# --------------------------------------------------------------------------- vector fields

class FlowField:
    r"""Hamilton's equations of ``G = sum_k c_k H_k`` for any N (numpy, batched).

    ``sum_k c_k grad H_k = sum_i W_i grad tr L(lam_i)`` exactly when ``lam_i`` are
    N distinct nodes and ``W_i = -b int l_i(lam) / sqrt(tr^2 - 4) dlam`` are the
    interpolatory quadrature weights (``l_i`` the Lagrange basis; ``grad tr`` is a
    polynomial of degree N-1 in lam).  Chebyshev nodes on ``[lam0-mu, lam0+mu]``
    keep the weights well conditioned; ``W_i`` are computed by composite
    Gauss--Legendre in float64 (``sum_i W_i lam_i^k`` reproduces ``c_k``).
    ``grad tr L(lam_i)`` comes from prefix/suffix products of the scaled 2x2
    factors ``m_j / sigma`` (no overflow; ``tr L = sigma^N tr(M)``).
    """

    def __init__(self, case, panels=32, order=24):
        N, lam0, mu = case.N, case.lam0, case.mu
        k = np.arange(N)
        self.nodes = lam0 + mu * np.cos((2 * k + 1) * np.pi / (2 * N))
        self.sigma = max(1.0, abs(lam0) + abs(mu))
        self.N = N
        # composite Gauss-Legendre for W_i sigma^N
        x, w = np.polynomial.legendre.leggauss(order)
        edges = np.linspace(lam0 - mu, lam0 + mu, panels + 1)
        lam = ((edges[:-1, None] + edges[1:, None]) / 2 + (edges[1:, None] - edges[:-1, None]) / 2 * x).ravel()
        wt = ((edges[1:, None] - edges[:-1, None]) / 2 * w).ravel()
        p0 = np.broadcast_to(np.asarray(case.p), (lam.size, N))
        q0 = np.broadcast_to(np.asarray(case.q), (lam.size, N))
        ts = spectral_trace(lam, p0, q0) / self.sigma**N
        inv = 1.0 / np.sqrt((ts - 2 / self.sigma**N) * (ts + 2 / self.sigma**N))
        # barycentric Lagrange basis at the quadrature points
        bw = (-1.0) ** k * np.sin((2 * k + 1) * np.pi / (2 * N))
        diff = lam[:, None] - self.nodes[None, :]
        basis = (bw / diff) / np.sum(bw / diff, axis=1, keepdims=True)
        self.What = -case.branch * (basis.T @ (wt * inv))           # W_i sigma^N
        self.c = self.What @ (self.nodes[:, None] / self.sigma) ** k[None, :] * 1.0
        # self.c[k] = sum_i W_i sigma^N (lam_i/sigma)^k = c_k sigma^(N-k): kept for checks
        self.c = self.c * self.sigma ** (k - N).astype(float)
        self.nfev = 0

    def __call__(self, p, q):
        """``(qdot, pdot)`` for states of shape ``batch + (N,)``."""
        self.nfev += 1
        N, s = self.N, self.sigma
        lam = self.nodes
        p = np.asarray(p, float)
        q = np.asarray(q, float)
        r = np.exp(np.roll(q, -1, axis=-1) - q)       # r_j = exp(q_{j+1} - q_j), batch + (N,)
        a = (lam[:, None] + p[..., None, :]) / s      # batch, nodes, N
        rs = np.broadcast_to(r[..., None, :] / s, a.shape)
        shp = a.shape[:-1]
        one, zero = np.ones(shp), np.zeros(shp)
        pre = np.empty((4, N) + shp)
        X00, X01, X10, X11 = one, zero, zero, one
        for j in range(N):
            pre[0, j], pre[1, j], pre[2, j], pre[3, j] = X00, X01, X10, X11
            aj, rj = a[..., j], rs[..., j]
            X00, X01, X10, X11 = aj * X00 - X10 / s, aj * X01 - X11 / s, rj * X00, rj * X01
        suf = np.empty((4, N) + shp)
        Y00, Y01, Y10, Y11 = one, zero, zero, one
        for j in range(N - 1, -1, -1):
            suf[0, j], suf[1, j], suf[2, j], suf[3, j] = Y00, Y01, Y10, Y11
            aj, rj = a[..., j], rs[..., j]
            Y00, Y01, Y10, Y11 = Y00 * aj + Y01 * rj, -Y00 / s, Y10 * aj + Y11 * rj, -Y10 / s
        dA = pre[0] * suf[0] + pre[1] * suf[2]        # (N, batch, nodes): sigma^(1-N) dtr/dp_j
        dR = pre[0] * suf[1] + pre[1] * suf[3]        # sigma^(1-N) dtr/dr_j
        gp = np.moveaxis(dA @ self.What / s, 0, -1)   # batch + (N,)
        gr = np.moveaxis(dR @ self.What / s, 0, -1)
        rr = r * gr
        gq = np.roll(rr, 1, axis=-1) - rr             # dG/dq_j = r_{j-1} dG/dr_{j-1} - r_j dG/dr_j
        return gp, -gq


def _generated(N):
    try:
        import importlib
        return importlib.import_module("symbt.generated.toda%d" % N)
    except Exception:
        return None


def make_field(case, c):
    """(callable (p, q) -> (qdot, pdot), description)."""
    gen = _generated(case.N)
    if gen is not None and hasattr(gen, "flow_field"):
        cf = np.asarray(c, float)

        def f(p, q):
            return gen.flow_field(cf, p, q)
        return f, "symbt.generated.toda%d.flow_field" % case.N
    return FlowField(case), "symbt.bench.FlowField (O(N^2))"


# --------------------------------------------------------------------------- integrators

_GL_TABLES = {}


def _gl_table(s):
    if s not in _GL_TABLES:
        x, w = np.polynomial.legendre.leggauss(s)
        c = (x + 1) / 2
        b = w / 2
        # A_ij = int_0^{c_i} l_j(t) dt
        A = np.empty((s, s))
        for j in range(s):
            others = np.delete(c, j)
            coef = np.poly(others) / np.prod(c[j] - others)
            integ = np.polyint(coef)
            A[:, j] = np.polyval(integ, c)
        _GL_TABLES[s] = (A, b, c)
    return _GL_TABLES[s]


def gauss_legendre_orbit(f, p0, q0, h, nsteps, every, s=3, maxit=60):
    """Symplectic s-stage Gauss--Legendre collocation with step ``h`` (fixed-point iteration).

    Returns sampled ``P, Q`` (every ``every`` steps, plus the last) and stage evaluations.
    """
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


def scipy_orbit(method, f, p0, q0, T, t_eval, tol):
    from scipy.integrate import solve_ivp
    N = len(p0)

    def rhs(t, y):
        qd, pd = f(y[N:], y[:N])
        return np.concatenate([qd, pd])

    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = solve_ivp(rhs, (0.0, T), np.concatenate([q0, p0]), method=method, rtol=tol,
                        atol=tol, t_eval=t_eval)
    Y = sol.y.T
    if not sol.success or Y.shape[0] != len(t_eval):
        return None, None, sol.nfev, sol.message
    return Y[:, N:], Y[:, :N], sol.nfev, None


# --------------------------------------------------------------------------- one case

def run_case(case, quick=False, log=print):
    every = max(1, case.n // 100)
    out = {"case": case.name, "note": case.note, "N": case.N, "p0": list(case.p), "q0": list(case.q),
           "lam0": case.lam0, "mu": case.mu, "branch": case.branch, "steps": case.n, "T": case.n,
           "checkpoint_every": every, "runs": [], "setup": {}}
    t0 = time.perf_counter()
    rows, hi, lo = reference_orbit(case, 50, every)
    out["setup"]["reference_mp50_orbit_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    c = flow_coeffs_mp(case)
    out["setup"]["c_k_30digits_s"] = time.perf_counter() - t0
    out["c"] = c
    inv = InvariantMeter(case)
    p0, q0 = np.array(case.p), np.array(case.q)
    t_eval = rows.astype(float)

    def record(name, kind, P, Q, secs, reps, nfev=None, param=None, msg=None):
        if P is None:
            out["runs"].append({"method": name, "kind": kind, "param": param, "failed": msg})
            log("  %-34s %-10s failed: %s" % (name, param, msg))
            return
        e = state_errors(P, Q, hi, lo)
        r = {"method": name, "kind": kind, "param": param, "final_err": float(e[-1]),
             "max_err": float(np.max(e)), "inv_drift": inv.drift(P, Q), "time_s": secs,
             "repeats": reps, "nfev": nfev}
        out["runs"].append(r)
        log("  %-34s %-10s final %.2e  max %.2e  drift %.1e  %.3e s  nfev %s" % (
            name, "" if param is None else "%g" % param, r["final_err"], r["max_err"],
            r["inv_drift"], secs, nfev))

    # --- BT contenders
    warm_n = max(1, case.n // 20)
    (P, Q), t, reps = _timed(lambda: bt_orbit(p0, q0, case.lam0, case.mu, case.n, branch=case.branch),
                             lambda: bt_orbit(p0, q0, case.lam0, case.mu, warm_n, branch=case.branch), quick)
    record("BT bt_orbit (numpy)", "bt", P[rows], Q[rows], t, reps, nfev=case.n)
    backends = ["numba", "python"] if HAVE_NUMBA else ["python"]
    for be in backends:
        t0 = time.perf_counter()
        fast_orbit(p0, q0, case.lam0, case.mu, 1, branch=case.branch, backend=be)
        if be == "numba":
            out["setup"]["numba_first_call_s"] = time.perf_counter() - t0
        (P, Q), t, reps = _timed(lambda: fast_orbit(p0, q0, case.lam0, case.mu, case.n,
                                                    branch=case.branch, every=every, backend=be),
                                 None, quick)
        record("BT fast_orbit (%s)" % be, "bt", P, Q, t, reps, nfev=case.n)
    t0 = time.perf_counter()
    gen = _generated(case.N)
    out["setup"]["generated_import_s"] = time.perf_counter() - t0
    if gen is not None and hasattr(gen, "bt_step"):
        def run_gen(n=case.n):
            p, q = p0.copy(), q0.copy()
            Ps, Qs = [p], [q]
            for i in range(1, n + 1):
                p, q = gen.bt_step(p, q, case.lam0, case.mu, case.branch)
                if i % every == 0 or i == n:
                    Ps.append(p)
                    Qs.append(q)
            return np.array(Ps), np.array(Qs)
        (P, Q), t, reps = _timed(run_gen, lambda: run_gen(warm_n), quick)
        if np.all(np.isfinite(P)) and np.all(np.isfinite(Q)):
            record("BT generated toda%d.bt_step" % case.N, "bt", P, Q, t, reps, nfev=case.n)
        else:
            record("BT generated toda%d.bt_step" % case.N, "bt", None, None, t, reps, msg="non-finite")

    # --- ODE contenders
    t0 = time.perf_counter()
    f, fdesc = make_field(case, c)
    if isinstance(f, FlowField):
        out["field_c_check"] = float(np.max(np.abs(f.c - c) / np.maximum(np.abs(c), 1e-300)))
    out["setup"]["field_setup_s"] = time.perf_counter() - t0
    out["field"] = fdesc
    T = float(case.n)
    if case.N > 8:
        # the N = 64 field costs ~0.6 ms per call and the flow is fast: short horizon
        # FlowField is too noisy at N = 64 (cancellation in sum_i W_i grad tr(lam_i)):
        # DOP853 needs ~8000 evaluations for t = 0.01.  ODE contenders are skipped for
        # N > 8 unless SYMBT_BENCH_LARGE_N_ODE=1 (then the numbers are not meaningful).
        tols = [1e-3, 1e-4]
        methods = ["DOP853"] if os.environ.get("SYMBT_BENCH_LARGE_N_ODE") == "1" else []
    else:
        tols = [1e-4, 1e-8, 1e-12] if quick else [1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-12, 1e-13, 1e-14]
        methods = ["DOP853", "RK45", "LSODA"]
    for m in methods:
        for tol in tols:
            if m == "RK45" and tol < 1e-12 and case.N > 8:
                continue
            res, t, reps = _timed(lambda: scipy_orbit(m, f, p0, q0, T, t_eval, tol),
                                  lambda: scipy_orbit(m, f, p0, q0, T / 50, t_eval[t_eval <= T / 50], tol),
                                  quick)
            P, Q, nfev, msg = res
            record("scipy %s" % m, "ode", P, Q, t, reps, nfev=nfev, param=tol, msg=msg)
    if case.N > 8:
        hs = []
    else:
        hs = [0.25] if quick else [0.5, 0.25, 0.125, 0.0625]
    for h in hs:
        nsteps = int(round(T / h))
        per = int(round(every / h))
        res, t, reps = _timed(lambda: gauss_legendre_orbit(f, p0, q0, h, nsteps, per),
                              lambda: gauss_legendre_orbit(f, p0, q0, h, max(1, nsteps // 50), per), quick)
        P, Q, nfev = res
        ok = np.all(np.isfinite(P)) and np.all(np.isfinite(Q))
        record("Gauss-Legendre s=3 (order 6)", "symplectic", P if ok else None, Q, t, reps, nfev=nfev,
               param=h, msg="diverged")
    if any(r["kind"] != "bt" for r in out["runs"] if "final_err" in r):
        out["headline"] = headline(out)
    else:
        out["headline"] = {"text": "BT contenders only (no valid ODE vector field for N = %d)" % case.N}
    log("  headline: %s" % out["headline"]["text"])
    return out


def headline(out):
    runs = [r for r in out["runs"] if "final_err" in r]
    bts = {r["method"]: r for r in runs if r["kind"] == "bt"}
    bt = bts.get("BT fast_orbit (numba)") or bts.get("BT fast_orbit (python)")
    lib = bts.get("BT bt_orbit (numpy)")
    others = [r for r in runs if r["kind"] != "bt"]
    res = {"bt_method": bt["method"], "bt_time_s": bt["time_s"], "bt_final_err": bt["final_err"],
           "bt_numpy_time_s": lib["time_s"], "bt_numpy_final_err": lib["final_err"]}
    reach = [r for r in others if r["final_err"] <= bt["final_err"]]
    if reach:
        best = min(reach, key=lambda r: r["time_s"])
        res.update(reached=True, contender=best["method"], param=best["param"],
                   contender_time_s=best["time_s"], contender_final_err=best["final_err"],
                   ratio=best["time_s"] / bt["time_s"], ratio_numpy=best["time_s"] / lib["time_s"])
        res["text"] = ("%s (%g) reaches the BT's final error %.1e in %.3g s: %.0fx the BT (%s, %.3g s); "
                       "%.0fx the numpy bt_orbit" % (best["method"], best["param"], bt["final_err"],
                                                     best["time_s"], res["ratio"], bt["method"],
                                                     bt["time_s"], res["ratio_numpy"]))
    else:
        best = min(others, key=lambda r: (r["final_err"], r["time_s"]))
        res.update(reached=False, contender=best["method"], param=best["param"],
                   contender_time_s=best["time_s"], contender_final_err=best["final_err"],
                   ratio=best["time_s"] / bt["time_s"], ratio_numpy=best["time_s"] / lib["time_s"])
        res["text"] = ("no contender reaches the BT's final error %.1e; the most accurate, %s (%g), "
                       "has %.1e (%.0fx worse) and takes %.3g s = %.0fx the BT (%s, %.3g s), %.0fx the "
                       "numpy bt_orbit" % (bt["final_err"], best["method"], best["param"],
                                           best["final_err"], best["final_err"] / bt["final_err"],
                                           best["time_s"], res["ratio"], bt["method"], bt["time_s"],
                                           res["ratio_numpy"]))
    return res


# --------------------------------------------------------------------------- 50 digits

def run_mp50(quick=False, log=print):
    """BT (mpmath, 50 digits) vs Taylor integration at 50 digits on a short horizon."""
    case = CASES()[0]
    n = 2 if quick else 10
    out = {"case": case.name, "dps": 50, "horizon": n}
    with mpmath.workdps(90):
        p = [mpmath.mpf(v) for v in case.p]
        q = [mpmath.mpf(v) for v in case.q]
        for _ in range(n):
            p, q = bt_step(p, q, case.lam0, case.mu)
        ref = p + q
    with mpmath.workdps(50):
        c_t0 = time.perf_counter()
        with mpmath.workdps(70):
            c = flow_coefficients([mpmath.mpf(v) for v in case.p], [mpmath.mpf(v) for v in case.q],
                                  case.lam0, case.mu)
        out["c_k_setup_s"] = time.perf_counter() - c_t0
        c = [+v for v in c]
        P0 = [mpmath.mpf(v) for v in case.p]
        Q0 = [mpmath.mpf(v) for v in case.q]

        def err(p, q):
            with mpmath.workdps(90):
                mq = mpmath.fsum(ref[3:]) / 3
                den = mpmath.sqrt(mpmath.fsum(v**2 for v in ref[:3]) + mpmath.fsum((v - mq)**2 for v in ref[3:]))
                return float(mpmath.sqrt(mpmath.fsum((a - b)**2 for a, b in zip(list(p) + list(q), ref))) / den)

        (bp, bq), tbt, reps = _timed(lambda: bt_orbit(P0, Q0, case.lam0, case.mu, n), None, quick)
        out["bt"] = {"time_s": tbt, "repeats": reps, "err": err(bp[-1], bq[-1])}
        log("  BT mpmath 50 digits, %d steps: err %.2e, %.3e s" % (n, out["bt"]["err"], tbt))
        try:
            from .reference.taylor import hamiltonian_flow
            t0 = time.perf_counter()
            res = hamiltonian_flow(P0, Q0, list(c) + [0], n)
            tt = time.perf_counter() - t0
            out["taylor"] = {"method": "symbt.reference.taylor.hamiltonian_flow (adaptive Taylor, Cauchy-product jets)",
                             "time_s": tt, "repeats": 1, "err": err(res[0], res[1]),
                             "steps": getattr(res, "steps", None), "order": getattr(res, "order", None)}
            log("  Taylor (flows.hamiltonian_flow) t=%d: err %.2e, %.3e s, %s steps of order %s" % (
                n, out["taylor"]["err"], tt, out["taylor"]["steps"], out["taylor"]["order"]))
        except Exception as exc:  # pragma: no cover - depends on a module under development
            out["taylor"] = {"failed": repr(exc)}
            log("  Taylor (flows.hamiltonian_flow) failed: %r" % (exc,))
        if not quick:
            gen = _generated(3)
            th = 1
            if gen is not None and hasattr(gen, "flow_field_mp"):
                with mpmath.workdps(90):
                    p1, q1 = bt_step([mpmath.mpf(v) for v in case.p], [mpmath.mpf(v) for v in case.q],
                                     case.lam0, case.mu)
                    ref1 = p1 + q1

                def rhs(t, y):
                    qd, pd = gen.flow_field_mp(c, y[3:], y[:3])
                    return list(qd) + list(pd)
                t0 = time.perf_counter()
                sol = mpmath.odefun(rhs, 0, Q0 + P0)
                y = sol(th)
                tt = time.perf_counter() - t0
                with mpmath.workdps(90):
                    yy = list(y[3:]) + list(y[:3])
                    mq = mpmath.fsum(ref1[3:]) / 3
                    den = mpmath.sqrt(mpmath.fsum(v**2 for v in ref1[:3]) + mpmath.fsum((v - mq)**2 for v in ref1[3:]))
                    e = float(mpmath.sqrt(mpmath.fsum((a - b)**2 for a, b in zip(yy, ref1))) / den)
                (b1p, b1q), tb1, _ = _timed(lambda: bt_orbit(P0, Q0, case.lam0, case.mu, th), None, quick)
                out["odefun"] = {"horizon": th, "time_s": tt, "err": e, "bt_time_s": tb1,
                                 "ratio": tt / tb1}
                log("  mpmath.odefun t=%d: err %.2e, %.3e s (BT %.3e s): %.0fx" % (th, e, tt, tb1, tt / tb1))
        tay = out.get("taylor", {})
        if "time_s" in tay:
            out["ratio"] = tay["time_s"] / tbt
            out["text"] = ("50 digits, t = %d: Taylor %.3g s (err %.1e) vs BT %.3g s (err %.1e): %.0fx" % (
                n, tay["time_s"], tay["err"], tbt, out["bt"]["err"], out["ratio"]))
            log("  headline: " + out["text"])
    return out


# --------------------------------------------------------------------------- throughput

def _best_time(fn, min_time, repeats=5):
    fn()
    best = float("inf")
    for _ in range(repeats):
        reps, t0 = 0, time.perf_counter()
        while True:
            fn()
            reps += 1
            dt = time.perf_counter() - t0
            if dt >= min_time / repeats:
                break
        best = min(best, dt / reps)
    return best


def run_throughput(quick=False, log=print):
    """Same problems and timing as benchmarks/bench_step.py (best of repeats)."""
    rng = np.random.default_rng(0)
    P0, Q0 = np.array(P_PAPER), np.array(Q_PAPER)
    sizes = [1, 100, 10**4, 10**5] if quick else [1, 10, 100, 1000, 10**4, 10**5, 10**6]
    mt = 0.2 if quick else 1.0
    out = {"batch": [], "vsN": []}
    log("  N = 3 batched bt_step (paper example + 1e-2 noise, lam0=10, mu=5)")
    for B in sizes:
        p = P0 + 1e-2 * rng.normal(size=(B, 3))
        q = Q0 + 1e-2 * rng.normal(size=(B, 3))
        t = _best_time(lambda: bt_step(p, q, 10.0, 5.0), mt)
        out["batch"].append({"batch": B, "time_s": t, "steps_per_s": B / t})
        log("    batch %8d: %.3e s/call, %.3e system-steps/s" % (B, t, B / t))
    Ns = [2, 3, 8, 32, 128, 1024] if quick else [2, 3, 8, 16, 64, 256, 1024, 4096, 10000]
    B = 256
    rng = np.random.default_rng(1)
    log("  cost vs N (fixed batch %d, lam0 = 3N + 20, mu = 2; N >= ~110 uses the renormalised "
        "monodromy)" % B)
    for N in Ns:
        p = rng.normal(size=(B, N))
        q = 0.5 * rng.normal(size=(B, N))
        lam0 = 3.0 * N + 20.0
        t = _best_time(lambda: bt_step(p, q, lam0, 2.0), mt)
        out["vsN"].append({"N": N, "batch": B, "steps_per_s": B / t, "ns_per_site_step": 1e9 * t / (B * N)})
        log("    N %6d batch %7d: %.3e system-steps/s, %.2f ns per site-step" % (N, B, B / t, 1e9 * t / (B * N)))
    big = [r for r in out["vsN"] if r["N"] >= 128]
    if len(big) >= 2:
        x = np.log([r["N"] for r in big])
        y = np.log([1.0 / r["steps_per_s"] for r in big])       # time per system-step
        out["slope_time_vs_N"] = float(np.polyfit(x, y, 1)[0])
        log("    log-log slope of time per system-step vs N (N >= 128): %.3f" % out["slope_time_vs_N"])
    return out


# --------------------------------------------------------------------------- band-edge conditioning

def band_edge_case(delta, side=+1, mu=0.5):
    """Paper state with ``|tr L(lam_edge)| - 2 = delta`` at one end of [lam0-mu, lam0+mu].

    The gap of the paper's example containing ``[5, 15]`` ends at the band near
    ``lam = -0.79``; ``side=+1`` puts ``lam2 = lam0 - mu`` at distance ``delta``
    (in |tr| - 2) from that band edge.  ``side=-1`` does the same for the band
    edge near ``lam = -10.28`` from the left, i.e. ``lam1 = lam0 + mu`` close to
    it.  Returns ``(p, q, lam0, mu, delta_actual)`` with float64 parameters
    (``delta_actual`` recomputed at 50 digits from the rounded values).
    """
    p, q = list(P_PAPER), list(Q_PAPER)
    with mpmath.workdps(60):
        P = [mpmath.mpf(v) for v in p]
        Q = [mpmath.mpf(v) for v in q]

        def trm(l):
            return spectral_trace(l, P, Q)
        # bracket the edge: find where |tr| - 2 changes sign near the band
        if side > 0:
            lo, hi = mpmath.mpf(-0.78), mpmath.mpf(2)      # gap side: hi
        else:
            lo, hi = mpmath.mpf(-10.28), mpmath.mpf(-14)    # gap side: hi (left of the band)
        f = lambda l: abs(trm(l)) - 2 - delta
        a, b = lo, hi
        fa = f(a)
        if fa > 0:
            raise RuntimeError("bracket")
        for _ in range(400):
            m = (a + b) / 2
            if f(m) > 0:
                b = m
            else:
                a = m
            if abs(b - a) < mpmath.mpf(10) ** -40:
                break
        le = b
        lam0 = float(le + mu) if side > 0 else float(le - mu)
        lam0_m = mpmath.mpf(lam0)
        edge = lam0_m - mu if side > 0 else lam0_m + mu
        d_act = float(abs(trm(edge)) - 2)
    return p, q, lam0, mu, d_act


def map_condition(p, q, lam0, mu, branch=1, dps=50):
    """Relative normwise condition number of the map (p, q, lam0, mu) -> (p~, q~) at 50 digits.

    ``kappa = ||J|| ||x|| / ||f(x)||`` with the 2-norm, ``x = (p, q - mean q, lam0, mu)``
    and ``f = (p~, q~ - mean q~)`` (the shift of q is a symmetry); ``J`` by central
    differences with step ``1e-20`` at ``dps`` digits (the map's error is then
    far below the O(1e-40) differencing error).  Returns ``(kappa, f(x))``.
    """
    N = len(p)
    with mpmath.workdps(dps):
        x = [mpmath.mpf(v) for v in list(p) + list(q) + [lam0, mu]]

        def F(x):
            pt, qt = bt_step(x[:N], x[N:2 * N], x[2 * N], x[2 * N + 1], branch=branch)
            return pt + qt
        f0 = F(x)
        h = mpmath.mpf(10) ** -20
        cols = []
        for i in range(len(x)):
            xp = list(x)
            xm = list(x)
            xp[i] += h
            xm[i] -= h
            fp, fm = F(xp), F(xm)
            cols.append([(a - b) / (2 * h) for a, b in zip(fp, fm)])
        J = mpmath.matrix(2 * N, len(x))
        for i, col in enumerate(cols):
            for k, v in enumerate(col):
                J[k, i] = v
        Jf = np.array(J.tolist(), dtype=float)
        nJ = np.linalg.norm(Jf, 2)
        xq = [float(v) for v in x]
        mq = sum(xq[N:2 * N]) / N
        xn = math.sqrt(sum(v * v for v in xq[:N]) + sum((v - mq)**2 for v in xq[N:2 * N]) +
                       xq[2 * N]**2 + xq[2 * N + 1]**2)
        ff = [float(v) for v in f0]
        mf = sum(ff[N:]) / N
        fn = math.sqrt(sum(v * v for v in ff[:N]) + sum((v - mf)**2 for v in ff[N:]))
        return nJ * xn / fn, f0


def run_band_edge(log=print):
    from .numeric.testing import state_error
    eps = 2.0**-53
    rows = []
    log("  one float64 step near the band edge: error vs eps*cond (cond at 50 digits)")
    for side in (+1, -1):
        for delta in (1e-2, 1e-4, 1e-6, 1e-8):
            p, q, lam0, mu, d = band_edge_case(delta, side)
            kappa, f0 = map_condition(p, q, lam0, mu)
            pt, qt = bt_step(np.array(p), np.array(q), lam0, mu)
            e = state_error(pt, qt, f0[:3], f0[3:])
            rows.append({"side": side, "delta": d, "lam0": lam0, "mu": mu, "err": e, "cond": kappa,
                         "eps_cond": eps * kappa, "ratio": e / (eps * kappa)})
            log("    side %+d  |tr|-2 = %.1e  err %.2e  cond %.2e  eps*cond %.2e  err/(eps cond) %.2f" % (
                side, d, e, kappa, eps * kappa, e / (eps * kappa)))
    return rows


# --------------------------------------------------------------------------- output

def _plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cases = results["cases"]
    fig, axes = plt.subplots(1, len(cases), figsize=(4.2 * len(cases), 4.2), squeeze=False)
    styles = {"scipy DOP853": ("o-", "C0"), "scipy RK45": ("s-", "C1"), "scipy LSODA": ("^-", "C2"),
              "Gauss-Legendre s=3 (order 6)": ("d-", "C3")}
    for ax, cr in zip(axes[0], cases):
        runs = [r for r in cr["runs"] if "final_err" in r
                and not (cr.get("invalid_ode") and r.get("kind") == "ode")]  # invalid rows stay out
        for name, (mk, col) in styles.items():
            rr = sorted([r for r in runs if r["method"] == name], key=lambda r: r["time_s"])
            if rr:
                ax.loglog([r["time_s"] for r in rr], [max(r["final_err"], 1e-17) for r in rr], mk,
                          color=col, ms=4, label=name.replace("scipy ", ""))
        bmark = {"BT fast_orbit (numba)": ("*", "k", 14), "BT fast_orbit (python)": ("P", "k", 9),
                 "BT bt_orbit (numpy)": ("X", "0.4", 9)}
        for r in runs:
            if r["method"] in bmark:
                mk, col, ms = bmark[r["method"]]
                ax.loglog([r["time_s"]], [max(r["final_err"], 1e-17)], mk, color=col, ms=ms,
                          ls="none", label=r["method"].replace("BT ", "BT: "))
            elif r["method"].startswith("BT generated"):
                ax.loglog([r["time_s"]], [max(r["final_err"], 1e-17)], "v", color="m", ms=8,
                          ls="none", label="BT: generated step")
        ax.set_title("%s (N=%d, %d steps)" % (cr["case"], cr["N"], cr["steps"]), fontsize=9)
        ax.set_xlabel("wall time [s]")
        ax.grid(True, which="major", alpha=0.3)
    axes[0][0].set_ylabel("final relative error")
    handles = {}
    for ax in axes[0]:  # one legend for the figure: every method that appears in some panel
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(list(handles.values()), list(handles.keys()), fontsize=8, loc="lower center",
               ncol=min(len(handles), 8), frameon=False)
    fig.suptitle("Work-precision: Bäcklund map vs ODE solvers on the flow of sum c_k H_k", fontsize=10)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def format_tables(results):
    lines = []
    for cr in results["cases"]:
        lines.append("### %s -- %s" % (cr["case"], cr["note"]))
        lines.append("")
        lines.append("N=%d, lam0=%g, mu=%g, branch=%+d, %d steps (T=%d); field: %s; c_k = %s" % (
            cr["N"], cr["lam0"], cr["mu"], cr["branch"], cr["steps"], cr["T"], cr.get("field"),
            ", ".join("%.6g" % v for v in cr["c"]) if cr["N"] <= 8 else "(64 values)"))
        lines.append("")
        lines.append("| method | tol / h | final err | max err | invariant drift | time [s] | repeats | nfev / steps |")
        lines.append("|---|---|---|---|---|---|---|---|")
        for r in cr["runs"]:
            par = "" if r.get("param") is None else "%g" % r["param"]
            if "failed" in r:
                lines.append("| %s | %s | failed: %s | | | | | |" % (r["method"], par, r["failed"]))
                continue
            lines.append("| %s | %s | %.2e | %.2e | %.1e | %.3e | %d | %s |" % (
                r["method"], par, r["final_err"], r["max_err"], r["inv_drift"], r["time_s"],
                r["repeats"], r["nfev"]))
        lines.append("")
        lines.append("Set-up (not in the times above): " + ", ".join(
            "%s %.3g s" % (k, v) for k, v in cr["setup"].items()))
        lines.append("")
        lines.append("**Headline:** " + cr["headline"]["text"])
        lines.append("")
    return "\n".join(lines)


def machine_info():
    import scipy
    cpu = ""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    info = {"python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
            "mpmath": mpmath.__version__, "cpu": cpu, "cores": os.cpu_count(),
            "platform": platform.platform()}
    try:
        import numba
        info["numba"] = numba.__version__
    except Exception:
        info["numba"] = None
    return info


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="symbt bench", description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="short horizons, few tolerances (< 2 min)")
    ap.add_argument("--out", default="bench-results", metavar="DIR",
                    help="directory for bench.json, bench.md, work_precision.png")
    ap.add_argument("--figure", metavar="PNG", help="also write the work-precision diagram here")
    ap.add_argument("--skip-50", action="store_true", help="skip the 50-digit comparison")
    ap.add_argument("--skip-throughput", action="store_true")
    ap.add_argument("--cases", help="comma-separated case names (default: all)")
    ap.add_argument("--resume", action="store_true",
                    help="keep cases already in DIR/bench.json (saved after every case)")
    args = ap.parse_args(argv)
    t_start = time.perf_counter()
    os.makedirs(args.out, exist_ok=True)

    def log(msg):
        print(msg, flush=True)

    results = {"machine": machine_info(), "quick": args.quick,
               "date": time.strftime("%Y-%m-%d"), "cases": []}
    log("symbt bench%s: %s" % (" --quick" if args.quick else "", json.dumps(results["machine"])))
    cases = CASES(args.quick)
    if args.cases:
        want = set(args.cases.split(","))
        cases = [c for c in cases if c.name in want]
    done = {}
    if args.resume and os.path.exists(os.path.join(args.out, "bench.json")):
        with open(os.path.join(args.out, "bench.json")) as fh:
            old = json.load(fh)
        done = {c["case"]: c for c in old.get("cases", [])}
    for case in cases:
        if case.name in done:
            log("\n== %s: kept from the previous run (--resume)" % case.name)
            results["cases"].append(done[case.name])
            continue
        log("\n== %s: %s (N=%d, %d steps)" % (case.name, case.note, case.N, case.n))
        results["cases"].append(run_case(case, args.quick, log))
        with open(os.path.join(args.out, "bench.json"), "w") as fh:
            json.dump(results, fh, indent=1)
    if not args.skip_50:
        log("\n== 50 digits: mpmath BT vs Taylor integration")
        results["mp50"] = run_mp50(args.quick, log)
    if not args.skip_throughput:
        log("\n== throughput of the batched float64 step")
        results["throughput"] = run_throughput(args.quick, log)
    if not args.quick:
        log("\n== band-edge conditioning")
        results["band_edge"] = run_band_edge(log)
    results["total_s"] = time.perf_counter() - t_start
    with open(os.path.join(args.out, "bench.json"), "w") as fh:
        json.dump(results, fh, indent=1)
    with open(os.path.join(args.out, "bench.md"), "w") as fh:
        fh.write(format_tables(results))
    png = os.path.join(args.out, "work_precision.png")
    if results["cases"]:
        _plot(results, png)
        if args.figure:
            _plot(results, args.figure)
    log("\nwrote %s/{bench.json,bench.md,work_precision.png}; total %.1f s" % (args.out, results["total_s"]))
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())


# --------------------------------------------------------------------------- invariant drift

def invariant_drift_curve(n=10**5, members=16, npoints=40, lam0=10.0, mu=5.0, seed=0, spread=1e-9,
                          keep_first=False):
    """Relative invariant drift of float64 BT orbits of the paper's example, for a growth fit.

    ``members`` orbits start at the paper's state perturbed by ``spread``
    (independent round-off, same torus to ~1e-9); they are advanced together
    with the batched :func:`~symbt.numeric.bt_step` (centre of mass removed each
    step -- the invariants only see ``q`` differences).  At ``npoints``
    log-spaced steps the invariants of the float64 states are evaluated at 40
    digits (so evaluation round-off does not mask the drift).  Returns
    ``(steps, drift)`` with ``drift[i, m, k] = |H_k(x_n) - H_k(x_0)| / |H_k(x_0)|``
    and the RMS over members and k, and the fitted log-log slope of the RMS
    drift versus n (over n >= 100).  Member 0 is the paper's state itself;
    ``keep_first=True`` also returns its whole centred trajectory ``(P, Q)``.
    """
    rng = np.random.default_rng(seed)
    p = np.array(P_PAPER) + spread * rng.normal(size=(members, 3))
    q = np.array(Q_PAPER) + spread * rng.normal(size=(members, 3))
    p[0], q[0] = P_PAPER, Q_PAPER                 # member 0: the paper's state itself
    q = q - q.mean(-1, keepdims=True)
    traj = (np.empty((n + 1, 3)), np.empty((n + 1, 3))) if keep_first else None
    if keep_first:
        traj[0][0], traj[1][0] = p[0], q[0]
    steps = np.unique(np.round(np.logspace(0, np.log10(n), npoints)).astype(int))

    def inv_mp(p, q):
        with mpmath.workdps(40):
            return [invariants([mpmath.mpf(float(a)) for a in pp], [mpmath.mpf(float(b)) for b in qq])
                    for pp, qq in zip(p, q)]
    H0 = inv_mp(p, q)
    drift = np.empty((len(steps), members, 3))
    k = 0
    for i in range(1, n + 1):
        p, q = bt_step(p, q, lam0, mu)
        q = q - q.mean(-1, keepdims=True)
        if keep_first:
            traj[0][i], traj[1][i] = p[0], q[0]
        if i == steps[k]:
            H = inv_mp(p, q)
            with mpmath.workdps(40):
                for m in range(members):
                    for j in range(3):
                        drift[k, m, j] = float(abs(H[m][j] - H0[m][j]) / abs(H0[m][j]))
            k += 1
    rms = np.sqrt(np.mean(drift**2, axis=(1, 2)))
    sel = steps >= 100
    slope = float(np.polyfit(np.log(steps[sel]), np.log(rms[sel]), 1)[0])
    if keep_first:
        return steps, drift, rms, slope, traj
    return steps, drift, rms, slope
