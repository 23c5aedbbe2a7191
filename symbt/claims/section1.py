r"""The general statements of Sections 1-2 specialised to the Toda BT (eqs. ``intdis``, ``speccurve``,
``backlund``, ``intertwin``, ``spe``, ``PoincareCartan``, ``hamil``, ``ICI`` and the running text).

Each statement is read on the actual two-parameter map of Section 3 (the literal route,
:func:`symbt.reference.literal.literal_step`) or, for ``intertwin``, on the single BT
(:func:`symbt.claims._maps.single_bt`); sampled claims use the cells of
:func:`~symbt.claims._common.map_cells` (``{branch, sign_tr}``) or ``{root}``.

* ``intdis``: to first order in mu the BT is the flow (x' = {H, x}) of
  :math:`\sum_k c_k H_k`, :math:`c_k = -2b\lambda_0^k/\sqrt{\operatorname{tr}L(\lambda_0)^2-4}`;
* ``speccurve``: :math:`\det(L(\lambda)-v) = v^2-\operatorname{tr}L(\lambda)\,v+1` (2x2 unimodular algebra);
* ``backlund``: every :math:`H_k` is invariant; ``canonical``: the image coordinates have the canonical
  Poisson brackets (Jacobian by forward differences at 60 digits, no generating function);
* ``intertwin``: :math:`\tilde L D = D L` for the single BT with :math:`D = d_1`;
* ``spe`` (erratum): the spectrality that holds is :math:`\det(L(\lambda_i)-\operatorname{sgn}(\operatorname{tr}_i)
  e^{\partial F/\partial\lambda_i}) = 0` at the BT's own points :math:`\lambda_{1,2}=\lambda_0\pm\mu`
  (F of eq. ``newgf`` with :math:`\ln|\cdot|`, a function of q, q~, lambda_1, lambda_2), the eigenvalue on the
  kernel of :math:`\mathcal D(\lambda_i)`; not :math:`\det(L(\mu)-\ln\Phi) = 0`;
* ``PoincareCartan``: :math:`dF = \sum_i p_i dq_i - \tilde p_i d\tilde q_i + \Phi d\mu` at fixed lambda_0,
  exactly, per site (hence every N);
* ``hamil``: the image of a trajectory of :math:`T = \operatorname{tr}L(\kappa)` follows
  :math:`K = \hat T + \hat\Phi`;
* ``ICI``: the map tends to the identity as mu -> 0.

>>> speccurve.run().status, ici.claims[0].run().scope
('verified', 'printed statement holds in all 4 cells')
"""
from __future__ import annotations

import random
from dataclasses import replace

import mpmath as mp
import sympy as sp

from ..proof import decide
from ..proof.cells import CellTable
from ..reference.literal import literal_step
from ..reference.spectral import phi_gradient
from ..reference.trace import trace, trace_gradient
from ..symbolic.darboux import lam0, mu
from ..symbolic.generating import implicit_derivative
from ..symbolic.toda import lam, local_lax, toda_model
from ._common import DPS, TOL, fmt_state, judge_cells, lambdified, per_cell
from ._maps import TINY_DPS, TINY_MU, lax, map_images, mat_mul, mat_norm, mat_sub, single_cells, tiny_images
from .base import Outcome, Parts, claim, from_decision, scene

scene("general", "Sections 1-2 on the Toda BT: first-order flow, spectral curve, invariance, canonicity, "
                 "intertwining, spectrality, Poincare-Cartan form, eq. hamil, identity at mu = 0 (N=2,3 / all N)")

T, branch, v = sp.symbols("T branch v", real=True)
FD_TOL = mp.mpf(10) ** -18   # forward differences at 60 digits, step 1e-28: truncation error ~ 1e-27
FD_STEP = mp.mpf(10) ** -28


def _sized(out: Outcome, N: int) -> Outcome:
    out = replace(out, n_scope=[N])
    return out


def _hamiltonian_field(gp: list, gq: list) -> list:
    """(p', q') = (-dH/dq, dH/dp) for x' = {H, x} with {p_i, q_j} = delta_ij."""
    return [-g for g in gq] + list(gp)


# --------------------------------------------------------------------------- intdis (Introduction)

def _parts_intdis(N: int) -> Parts:
    return Parts(printed={"c": -2 * branch / sp.sqrt(T ** 2 - 4)})


@claim("intdis", equation="intdis", scene="general", sizes=(2, 3), parts=_parts_intdis,
       where="Introduction: an integrable discretization approximates the flow of eq. intdis to first order in mu",
       statement="to first order in mu the BT is the Hamiltonian flow x' = {H, x} (eq. intdis) of H = c tr L(l0), "
                 "c = -2b/sqrt(tr L(l0)^2 - 4), i.e. of sum_k c_k H_k with c_k = c l0^k: x~ = x + mu {H, x} + "
                 "O(mu^2) (N={N})")
def intdis(N: int, parts: Parts, deep: bool = False) -> Outcome:
    c_of = lambdified((T, branch), parts.printed["c"])
    table = CellTable(tol=1e-20)
    with mp.workdps(TINY_DPS):
        for cell, (p, q, l0, m), b, pt, qt in tiny_images(N, per_cell(deep)):
            c = c_of(trace(l0, p, q), b)
            gp, gq = trace_gradient(l0, p, q)
            field = [c * f for f in _hamiltonian_field(gp, gq)]
            step = [(a - z) / m for a, z in zip(pt + qt, p + q)]
            scale = max(1, *(abs(f) for f in field))
            table.add(cell, printed=max(abs(s - f) for s, f in zip(step, field)) / scale,
                      point=fmt_state((p, q, l0, m), b))
    return _sized(judge_cells(table, method=f"numeric: (x~ - x)/mu at mu = {TINY_MU}, {TINY_DPS} digits, vs "
                                            "c {tr L(l0), x} (gradient of tr L from its polynomial)",
                              printed="x~ = x + mu c {tr L(l0), x} + O(mu^2), c = -2b/sqrt(tr L(l0)^2 - 4)",
                              dps=TINY_DPS, detail="l0 = the sample's lambda_1, where |tr L| > 2.2"), N)


# --------------------------------------------------------------------------- speccurve

def _parts_speccurve() -> Parts:
    return Parts(printed={"curve": v ** 2 - T * v + 1})


@claim("speccurve", equation="speccurve", scene="general", parts=_parts_speccurve,
       statement="for the Toda Lax matrix det(L(lambda) - v 1) = v^2 - tr L(lambda) v + 1, so the spectral curve is "
                 "v^2 - tr L v + 1 = 0 with tr L = sum_k H_k lambda^k (all N)")
def speccurve(parts: Parts) -> Outcome:
    curve = parts.printed["curve"]
    a, b_, c_ = sp.symbols("a b c", nonzero=True)
    M = sp.Matrix([[a, b_], [c_, (1 + b_ * c_) / a]])          # generic unimodular 2x2
    d = decide((M - v * sp.eye(2)).det(), curve.subs(T, M.trace()))
    if not d.holds:
        return from_decision(d, detail="generic unimodular 2x2 matrix")
    p_, E_ = sp.Symbol("p_j", real=True), sp.Symbol("E_j", positive=True)
    d = decide(local_lax(lam, p_, E_).det(), 1)
    if not d.holds:
        return from_decision(d, detail="det l_j")
    for N in (2, 3):
        m = toda_model(N)
        d = decide((m.L - v * sp.eye(2)).det(), curve.subs(T, m.trace))
        if not d.holds:
            return from_decision(d, detail=f"N={N}")
    out = from_decision(d, detail="all N: det(M - v) = v^2 - tr M v + det M for a 2x2 M, and det L = prod det l_j = 1 "
                                  "(det l_j = 1 per site); the N=2, 3 Lax matrices also exactly")
    out = replace(out, n_scope="all")
    return out


# --------------------------------------------------------------------------- backlund: invariance, canonicity

def _parts_backlund(N: int) -> Parts:
    return Parts(printed={"H": sp.Matrix(toda_model(N).hamiltonians[:N])})


@claim("backlund", equation="backlund", scene="general", sizes=(2, 3), parts=_parts_backlund,
       statement="the BT leaves every H_k (coefficient of tr L) invariant: H_k(p~, q~) = H_k(p, q) (N={N})")
def backlund(N: int, parts: Parts, deep: bool = False) -> Outcome:
    m = toda_model(N)
    H = lambdified((*m.p, *m.E), parts.printed["H"])
    table = CellTable(tol=float(TOL))
    with mp.workdps(DPS):
        for cell, state, b, pt, qt, _ in map_images(N, per_cell(deep)):
            h0 = H(*state[0], *(mp.exp(x) for x in state[1]))
            h1 = H(*pt, *(mp.exp(x) for x in qt))
            table.add(cell, printed=max(abs(x - y) / max(1, abs(x)) for x, y in zip(h0, h1)),
                      point=fmt_state(state, b))
    return _sized(judge_cells(table, method=f"numeric: mpmath {DPS} digits on the literal map",
                              printed="H_k(p~, q~) = H_k(p, q), k = 0..N-1"), N)


def _parts_canonical(N: int) -> Parts:
    B = sp.zeros(2 * N, 2 * N)
    for i in range(N):
        B[i, N + i], B[N + i, i] = 1, -1
    return Parts(printed={"brackets": B})


def _jacobian(state: tuple, b: int, image: list) -> list:
    """d(p~, q~)/d(p, q) by forward differences (step FD_STEP) of the literal map; J[row][col]."""
    p, q, l0, m = state
    N = len(p)
    cols = []
    for k in range(2 * N):
        z = list(p) + list(q)
        z[k] += FD_STEP
        a, c, _ = literal_step(z[:N], z[N:], l0, m, b)
        cols.append([(u - w) / FD_STEP for u, w in zip(a + c, image)])
    return [[cols[k][i] for k in range(2 * N)] for i in range(2 * N)]


@claim("canonical", equation="backlund", scene="general", sizes=(2, 3), parts=_parts_canonical,
       where="running text: BTs are canonical transformations (definition around eq. backlund; Introduction)",
       statement="the BT is canonical, checked without the generating function: the image coordinates have the "
                 "canonical brackets {p~_i, q~_j} = delta_ij, {p~_i, p~_j} = {q~_i, q~_j} = 0 (N={N})")
def canonical(N: int, parts: Parts, deep: bool = False) -> Outcome:
    target = lambdified((), parts.printed["brackets"])()
    table = CellTable(tol=float(FD_TOL))
    with mp.workdps(DPS):
        for cell, state, b, pt, qt, _ in map_images(N, per_cell(deep)):
            J = _jacobian(state, b, pt + qt)
            worst = mp.mpf(0)
            for r in range(2 * N):
                for s in range(2 * N):
                    br = mp.fsum(J[r][i] * J[s][N + i] - J[r][N + i] * J[s][i] for i in range(N))
                    worst = max(worst, abs(br - target[r, s]))
            scale = max(1, max(abs(x) for row in J for x in row)) ** 2
            table.add(cell, printed=worst / scale, point=fmt_state(state, b))
    return _sized(judge_cells(table, method=f"numeric: Jacobian of the literal map by forward differences (step "
                                            f"1e-28) at {DPS} digits; brackets J P J^T",
                              printed="{p~_i, q~_j} = delta_ij, {p~_i, p~_j} = {q~_i, q~_j} = 0"), N)


# --------------------------------------------------------------------------- intertwin (single BT)

alpha, beta, zeta = sp.symbols("alpha beta zeta")


def _parts_intertwin(N: int) -> Parts:
    return Parts(printed={"D": sp.Matrix([[lam - zeta - alpha * beta, -alpha], [beta, 1]])},
                 context={"alpha": "e^{q_1}", "beta": "e^{-q~_N}"})


@claim("intertwin", equation="intertwin", scene="general", sizes=(2, 3), parts=_parts_intertwin,
       statement="for the single BT with parameter zeta (eqs. dj, alphabeta, ptp as an explicit map) the dressing "
                 "matrix D = d_1 = [[lambda-zeta-alpha beta, -alpha],[beta, 1]], alpha = e^{q_1}, beta = e^{-q~_N}, "
                 "intertwines: L~(lambda) D(lambda) = D(lambda) L(lambda) (N={N})")
def intertwin(N: int, parts: Parts, deep: bool = False) -> Outcome:
    D = lambdified((lam, zeta, alpha, beta), parts.printed["D"])
    table = CellTable(tol=float(TOL))
    with mp.workdps(DPS):
        for cell, (p, q, z), r, pt, qt in single_cells(N, per_cell(deep)):
            a, bb = mp.exp(q[0]), mp.exp(-qt[N - 1])
            worst = mp.mpf(0)
            for lv in (z, z + mp.mpf("1.7"), mp.mpf("0.3"), mp.mpf("-2.1")):
                Dm = tuple(D(lv, z, a, bb))
                L, Lt = lax(lv, p, q), lax(lv, pt, qt)
                res = mat_sub(mat_mul(Lt, Dm), mat_mul(Dm, L))
                worst = max(worst, mat_norm(res) / (mat_norm(Lt) * max(1, mat_norm(Dm))))
            table.add(cell, printed=worst, point=fmt_state((p, q, z, mp.mpf(0)), r))
    return _sized(judge_cells(table, method=f"numeric: mpmath {DPS} digits, 4 values of lambda (one = zeta)",
                              printed="L~ D = D L with D = d_1"), N)


# --------------------------------------------------------------------------- spe (spectrality)

Phi, F0, Fmu, T1, T2 = sp.symbols("Phi F_lam0 F_mu T1 T2", real=True)


def _parts_spe(N: int) -> Parts:
    return Parts(printed={"digamma": sp.log(Phi), "point": mu},
                 corrected={"eig1": sp.sign(T1) * sp.exp((F0 + Fmu) / 2), "eig2": sp.sign(T2) * sp.exp((F0 - Fmu) / 2),
                            "points": sp.Matrix([lam0 + mu, lam0 - mu])})


def _F(q: list, qt: list, signs: list, l0, m, *, real: bool):
    """Eq. newgf at fixed q, q~: eta_k = s_k sqrt(mu^2 + w_k) (sign as on the map); ln|.| if ``real``."""
    N = len(q)
    E, Et = [mp.exp(x) for x in q], [mp.exp(x) for x in qt]
    total = mp.mpf(0)
    for k in range(N):
        w = (E[k] - Et[k]) * (1 / Et[k - 1] - 1 / E[k - 1])
        e = signs[k] * mp.sqrt(m ** 2 + w)
        ratio = (e + m) / (e - m)
        total += m * (mp.log(abs(ratio)) if real else mp.log(ratio)) - 2 * e - l0 * (q[k] - qt[k])
    return total


def _curve_residual(Lm: tuple, val) -> mp.mpf:
    """det(L - val 1) = val^2 - tr L val + 1, relative."""
    tr = Lm[0] + Lm[3]
    return abs(val ** 2 - tr * val + 1) / (abs(val) ** 2 + abs(tr * val) + 1)


def _eig_residual(Lm: tuple, val, vec: list) -> mp.mpf:
    """|L vec - val vec| and the characteristic polynomial at val, relative."""
    Lv = (Lm[0] * vec[0] + Lm[1] * vec[1], Lm[2] * vec[0] + Lm[3] * vec[1])
    r1 = max(abs(Lv[0] - val * vec[0]), abs(Lv[1] - val * vec[1])) / (max(1, abs(val)) * max(abs(x) for x in vec))
    return max(r1, _curve_residual(Lm, val))


@claim("spe", equation="spe", scene="general", sizes=(2, 3), parts=_parts_spe,
       statement="spectrality for the Toda F: with Phi = dF/dmu on the map and digamma = log, the pair "
                 "(mu, digamma(Phi)) lies on the spectral curve: det(L(mu) - log(Phi) 1) = 0 (N={N})")
def spe(N: int, parts: Parts, deep: bool = False) -> Outcome:
    dig = lambdified((Phi,), parts.printed["digamma"])
    point = lambdified((lam0, mu), parts.printed["point"])
    c = parts.corrected
    eig = [lambdified((F0, Fmu, T1, T2), c["eig1"]), lambdified((F0, Fmu, T1, T2), c["eig2"])]
    pts = lambdified((lam0, mu), c["points"])
    table = CellTable(tol=float(TOL))
    other_readings = mp.inf
    with mp.workdps(DPS):
        for cell, state, b, _, qt, info in map_images(N, per_cell(deep)):
            p, q, l0, m = state
            signs = [mp.sign(e) for e in info["eta"]]
            phi_c = mp.diff(lambda t: _F(q, qt, signs, l0, t, real=False), m)        # Phi, principal logs
            Lm = lax(point(l0, m), p, q)
            printed = _curve_residual(Lm, dig(phi_c))
            other_readings = min(other_readings, _curve_residual(Lm, mp.exp(phi_c)), _curve_residual(Lm, phi_c))
            f0 = mp.diff(lambda t: _F(q, qt, signs, t, m, real=True), l0)
            fm = mp.diff(lambda t: _F(q, qt, signs, l0, t, real=True), m)
            l1, l2 = pts(l0, m)
            L1, L2 = lax(l1, p, q), lax(l2, p, q)
            t1, t2 = L1[0] + L1[3], L2[0] + L2[3]
            x, y = info["x_formula"], info["y"][0]
            kernels = ([mp.mpf(1), -y], [x, -2 * m - x * y])          # of D(l1), D(l2) (eq. D)
            corrected = max(_eig_residual(L1, eig[0](f0, fm, t1, t2), kernels[0]),
                            _eig_residual(L2, eig[1](f0, fm, t1, t2), kernels[1]))
            table.add(cell, printed=printed, corrected=corrected, point=fmt_state(state, b, Phi=phi_c))
    return _sized(judge_cells(
        table, method=f"numeric: mpmath {DPS} digits on the literal map, dF by mpmath.diff of eq. newgf at fixed q, q~",
        printed="det(L(mu) - log(Phi) 1) = 0, Phi = dF/dmu (principal logarithms)",
        corrected="with F(q, q~, l1, l2) of eq. newgf (ln|.|), l1,2 = l0 +- mu: sgn(tr L(l_i)) exp(dF/dl_i) is the "
                  "eigenvalue of L(l_i) on the kernel of D(l_i), so det(L(l_i) - sgn(tr_i) e^{dF/dl_i} 1) = 0, "
                  "i = 1, 2 (dF/dl_1,2 = (dF/dl0 +- dF/dmu)/2): digamma = sgn(tr) exp at the BT's own points; "
                  "Phi = dF/dmu = ln|v(l1)| - ln|v'(l2)| involves both points",
        detail=f"other readings at lambda = mu fail too: det(L(mu) - e^Phi) and det(L(mu) - Phi) are at least "
               f"{mp.nstr(other_readings, 3)} (relative) at every sample"), N)


# --------------------------------------------------------------------------- PoincareCartan

dq, dqt, dmu, P, Pt = sp.symbols("dq_j dqt_j dmu P_j Pt_j")


def _parts_pc() -> Parts:
    return Parts(printed={"form": P * dq - Pt * dqt + Phi * dmu})


@claim("PoincareCartan", equation="PoincareCartan", scene="general", parts=_parts_pc,
       statement="for the Toda F (eq. newgf) at fixed lambda_0: dF = sum_i p_i dq_i - p~_i dq~_i + Phi dmu with p, p~ "
                 "of eq. imptransf and Phi = sum_k ln((eta_k+mu)/(eta_k-mu)) (all N, modulo eta_k^2 = mu^2 + w_k)")
def poincare_cartan(parts: Parts) -> Outcome:
    form = parts.printed["form"]
    Em, E, En = sp.symbols("E_jm1 E_j E_jp1", positive=True)
    Etm, Et, Etn = sp.symbols("Et_jm1 Et_j Et_jp1", positive=True)
    eta, etan = sp.symbols("eta_j eta_jp1", real=True)
    w, wn = (E - Et) * (1 / Etm - 1 / Em), (En - Etn) * (1 / Et - 1 / E)
    rel = {eta: eta ** 2 - mu ** 2 - w, etan: etan ** 2 - mu ** 2 - wn}

    def f(e, Eo, Eto):                      # the term of F at one site (eq. newgf)
        return mu * sp.log((e + mu) / (e - mu)) - 2 * e - lam0 * (sp.log(Eo) - sp.log(Eto))

    def d(expr, var):                       # total derivative, eta_k = eta_k(q, q~, mu) implicit (the library's)
        return implicit_derivative(expr, var, {eta: w, etan: wn}, mu)

    F_site = f(eta, E, Et) + f(etan, En, Etn)          # every term of F that depends on q_j, q~_j
    subs = {P: -lam0 - (Et * etan + E * eta) / (E - Et), Pt: -lam0 - (Et * eta + E * etan) / (E - Et),
            Phi: sp.log((eta + mu) / (eta - mu))}
    checks = (("dq_j", E * d(F_site, E), form.coeff(dq)), ("dq~_j", Et * d(F_site, Et), form.coeff(dqt)),
              ("dmu", d(f(eta, E, Et), mu), form.coeff(dmu)))
    for name, lhs, coeff in checks:
        r = decide(lhs, coeff.subs(subs), relations=rel)
        if not r.holds:
            return from_decision(r, detail=f"coefficient of {name}")
    extra = decide(d(f(eta, E, Et), lam0), sp.log(Et) - sp.log(E))
    out = from_decision(r, detail="per site, hence every N: F = sum_k f_k with f_k depending on sites k-1, k; the "
                                  "dq_j, dq~_j coefficients involve f_j, f_{j+1} only (N = 2 identifies sites j-1 and "
                                  "j+1, which d/dq_j does not see); the dmu coefficient is a sum of per-site terms. "
                                  "With lambda_0 varying dF gains sum_k (q~_k - q_k) dlambda_0 "
                                  f"({'proved' if extra.holds else 'NOT proved'})")
    out = replace(out, n_scope="all")
    return out


# --------------------------------------------------------------------------- hamil

That, Phihat = sp.symbols("That Phihat", real=True)


def _parts_hamil(N: int) -> Parts:
    return Parts(printed={"K": That + Phihat})


@claim("hamil", equation="hamil", scene="general", sizes=(2, 3), parts=_parts_hamil,
       statement="if (p, q) follow T = tr L(kappa) = sum_k kappa^k H_k (time mu), the image (p~, q~) follows "
                 "K = T^ + Phi^ with T^ = T(p(p~,q~), q(p~,q~)) = T(p~, q~) and Phi^ the real Phi at (p~, q~) (N={N})")
def hamil(N: int, parts: Parts, deep: bool = False) -> Outcome:
    K = parts.printed["K"]
    cT, cPhi = (float(sp.diff(K, s)) for s in (That, Phihat))
    rng = random.Random(N)
    table = CellTable(tol=float(FD_TOL))
    with mp.workdps(DPS):
        for cell, state, b, pt, qt, _ in map_images(N, per_cell(deep)):
            p, q, l0, m = state
            kappa = mp.mpf(f"{rng.uniform(-4, 4):.6f}")
            XT = _hamiltonian_field(*trace_gradient(kappa, p, q))
            z = [x + FD_STEP * X for x, X in zip(p + q, XT)]
            a, c, _ = literal_step(z[:N], z[N:], l0, m + FD_STEP, b)      # along (X_T, 1) in (z, mu)
            lhs = [(u - w) / FD_STEP for u, w in zip(a + c, pt + qt)]
            gT, gPhi = _hamiltonian_field(*trace_gradient(kappa, pt, qt)), _hamiltonian_field(*phi_gradient(pt, qt, l0,
                                                                                                           m, b))
            rhs = [cT * x + cPhi * y for x, y in zip(gT, gPhi)]
            scale = max(1, *(abs(x) for x in rhs))
            table.add(cell, printed=max(abs(x - y) for x, y in zip(lhs, rhs)) / scale,
                      point=fmt_state(state, b, kappa=kappa))
    return _sized(judge_cells(table, method=f"numeric: d/dmu of the image along (X_T, 1) by a forward difference "
                                            f"(step 1e-28) at {DPS} digits",
                              printed="d(p~, q~)/dmu = X_K(p~, q~), K = T^ + Phi^",
                              detail="the Phi^ part is Theorem 1 (x.nN); the T^ part says the BT maps trajectories "
                                     "of the Toda flows to trajectories (T^ = T by invariance)"), N)


# --------------------------------------------------------------------------- ICI

def _ici_symbols(N: int) -> tuple:
    """(p~, q~, p, q) as symbols p~_j = ptj, q~_j = qtj."""
    return tuple(sp.symbols(f"{s}1:{N + 1}", real=True) for s in ("pt", "qt", "p", "q"))


def _parts_ici(N: int) -> Parts:
    pt, qt, p, q = _ici_symbols(N)
    return Parts(printed={"gap": sp.Matrix([a - c for a, c in zip(pt + qt, p + q)])})


@claim("ICI", equation="ICI", scene="general", sizes=(2, 3), parts=_parts_ici,
       statement="the BT is connected to the identity: p~_i -> p_i, q~_i -> q_i as mu -> 0 (both branches) (N={N})")
def ici(N: int, parts: Parts, deep: bool = False) -> Outcome:
    gap = lambdified([s for group in _ici_symbols(N) for s in group], parts.printed["gap"])
    table = CellTable(tol=1e-20)
    with mp.workdps(TINY_DPS):
        for cell, state, b, pt, qt in tiny_images(N, per_cell(deep)):
            g = gap(*pt, *qt, *state[0], *state[1])
            table.add(cell, printed=max(abs(x) for x in g), point=fmt_state(state, b))
    return _sized(judge_cells(table, method=f"numeric: literal map at mu = {TINY_MU}, {TINY_DPS} digits",
                              printed="|(p~, q~) - (p, q)| -> 0 as mu -> 0", dps=TINY_DPS), N)
