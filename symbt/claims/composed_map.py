"""The composed map: eqs. ``D``, ``new``, ``l1l2``, ``v1v2``, ``xy``, ``lam0mu`` (N = 2, 3).

Branch convention (settled here, used everywhere): ``branch = b`` means
:math:`\\gamma(\\lambda_i) = b\\sqrt{\\operatorname{tr}L(\\lambda_i)^2-4}` with the *positive* root, the
same sign b at :math:`\\lambda_1` and :math:`\\lambda_2`, inserted in eq. ``xy``.  Both b = +1 and
b = -1 give maps connected to the identity; b = -1 at mu is b = +1 at -mu, and is its
inverse.  Mixed signs give maps that do not tend to the identity as mu -> 0.
"""
from __future__ import annotations

from functools import cache

import mpmath as mp
import sympy as sp

from ..proof import Verdict, Worst, decide
from ..reference.literal import lax_matrix, literal_step
from ..reference.samples import admissible_states
from ..symbolic.darboux import composed_darboux, lam1, lam2
from ..symbolic.toda import lam
from .base import Outcome, claim, from_decision, judge, scene

scene("map", "the composed two-parameter BT: Darboux matrix, explicit x, y, eigenvalues, branches (N=2,3)")

DPS = 60
TOL = mp.mpf(10) ** -40


def worst_over(cases, residual, *, method, dps=DPS, tol=TOL) -> Verdict:
    """Largest ``residual(state, branch)`` over ``cases`` at ``dps`` digits, as a sampled :class:`Verdict`."""
    w = Worst()
    with mp.workdps(dps):
        for state, b in cases:
            w.add(residual(state, b), _fmt_state(state, b))
    return w.verdict(method, tol=tol, dps=dps)


def darboux_numeric(lv, l0, mu, x, y):
    """Eq. ``D`` at a number ``lv`` (mpmath)."""
    return mp.matrix([[lv - (l0 + mu) - x * y, -x], [y * (2 * mu + x * y), lv - (l0 - mu) + x * y]])


def _states(N):
    return [(s, b) for sign in (+1, -1) for s in admissible_states(N, sign, 2) for b in (+1, -1)]


def _fmt_state(state, branch):
    p, q, l0, m = state
    return {"p": [mp.nstr(v, 15) for v in p], "q": [mp.nstr(v, 15) for v in q],
            "lambda0": mp.nstr(l0, 15), "mu": mp.nstr(m, 15), "branch": branch}


def _rel(a, b):
    return abs(a - b) / max(mp.mpf(1), abs(a), abs(b))


def eta_from_states(p, q, pt, qt, lam0):
    """Recover eta_j from (p, q) and the image (p~, q~) alone, via eq. ``imptransf``.

    Per site: p~_j - p_j = eta_j - eta_{j+1} and (p~_j + lam0)(E_j - E~_j) = -(E~_j eta_j + E_j eta_{j+1}),
    so eta_j = (E_j (p~_j - p_j) - (p~_j + lam0)(E_j - E~_j)) / (E_j + E~_j).
    """
    out = []
    for j in range(len(p)):
        E, Et = mp.exp(q[j]), mp.exp(qt[j])
        out.append((E * (pt[j] - p[j]) - (pt[j] + lam0) * (E - Et)) / (E + Et))
    return out


@cache
def _xy_generic():
    """Eq. ``xy`` for two generic unimodular 2x2 matrices standing for L(l1), L(l2).

    The eigen-statements are polynomial identities in the entries that only use
    det = 1 (C = (A D - 1)/B) and gamma_i^2 = tr_i^2 - 4, so proving them for
    generic entries proves them for L(lambda) of every N (det L = 1 is claim
    ``lax.nN``).  This keeps the exact proof small (seconds instead of minutes
    for the expanded N=3 entries).
    """
    A1, B1, D1, A2, B2, D2 = sp.symbols("A1 B1 D1 A2 B2 D2")
    g1, g2 = sp.symbols("gamma1 gamma2")
    C1, C2 = (A1 * D1 - 1) / B1, (A2 * D2 - 1) / B2
    L1, L2 = sp.Matrix([[A1, B1], [C1, D1]]), sp.Matrix([[A2, B2], [C2, D2]])
    tr1, tr2 = A1 + D1, A2 + D2
    y = (A1 - D1 + g1) / (2 * B1)
    x = 2 * B1 * B2 * (lam2 - lam1) / (B2 * (A1 - D1 + g1) - B1 * (A2 - D2 - g2))
    rel = {g1: g1 ** 2 - (tr1 ** 2 - 4), g2: g2 ** 2 - (tr2 ** 2 - 4)}
    Om1 = sp.Matrix([1, -y])
    Om2 = sp.Matrix([x, lam2 - lam1 - x * y])
    return L1, L2, tr1, tr2, g1, g2, x, y, Om1, Om2, rel


def _on_lattice(N, expr_of_generic):
    """Evaluate a generic statement on the actual N-site L at random points (50-digit screen)."""
    import random

    from ..reference.literal import lax_matrix

    L1, L2, tr1, tr2, g1, g2, x, y, Om1, Om2, rel = _xy_generic()
    lhs, rhs = expr_of_generic
    free = sorted((sp.Matrix([lhs]).free_symbols | sp.Matrix([rhs]).free_symbols), key=str)
    f = sp.lambdify(free, sp.Matrix([lhs - rhs]), "mpmath")
    rng = random.Random(N)
    worst = mp.mpf(0)
    with mp.workdps(50):
        for _ in range(4):
            p = [mp.mpf(rng.uniform(-3, 3)) for _ in range(N)]
            q = [mp.mpf(rng.uniform(-1, 1)) for _ in range(N)]
            l1v, l2v = mp.mpf(rng.uniform(-4, 4)), mp.mpf(rng.uniform(-4, 4))
            M1, M2 = lax_matrix(l1v, p, q), lax_matrix(l2v, p, q)
            vals = {"A1": M1[0, 0], "B1": M1[0, 1], "D1": M1[1, 1], "A2": M2[0, 0], "B2": M2[0, 1],
                    "D2": M2[1, 1], "lambda1": l1v, "lambda2": l2v}
            vals["gamma1"] = mp.sqrt((M1[0, 0] + M1[1, 1]) ** 2 - 4) * rng.choice((1, -1))
            vals["gamma2"] = mp.sqrt((M2[0, 0] + M2[1, 1]) ** 2 - 4) * rng.choice((1, -1))
            r = f(*[vals[str(s)] for s in free])
            scale = max(1, *(abs(v) for v in vals.values()))
            worst = max(worst, max(abs(v) for v in r) / scale)
    return worst


def _cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


for _N in (2, 3):
    def _make(N):
        @claim(f"xy.n{N}", equation="xy", scene="map", N=N,
               statement="with gamma_i^2 = tr L(lambda_i)^2 - 4, the printed y and x make Omega_1 = (1,-y) an "
                         "eigenvector of L(lambda_1) and Omega_2 = (x, lambda_2-lambda_1-xy) one of L(lambda_2) "
                         f"(either sign of gamma_i) (N={N})")
        def xy_check():
            L1, L2, tr1, tr2, g1, g2, x, y, Om1, Om2, rel = _xy_generic()
            d1 = decide(_cross(L1 * Om1, Om1), 0, relations={g1: rel[g1]})
            if not d1.holds:
                return from_decision(d1, detail="Omega_1")
            d2 = decide(_cross(L2 * Om2, Om2), 0, relations=rel)
            if not d2.holds:
                return from_decision(d2, detail="Omega_2")
            r = _on_lattice(N, (sp.Matrix([_cross(L1 * Om1, Om1), _cross(L2 * Om2, Om2)]), sp.zeros(2, 1)))
            out = from_decision(d2, detail="generic unimodular 2x2 matrices (det L = 1 by lax.nN): both "
                                           "eigenvector conditions reduce to 0 modulo gamma_i^2 = tr_i^2 - 4; "
                                           f"on the N={N} Lax matrix at 50 digits: residual {mp.nstr(r, 3)}")
            if r > mp.mpf(10) ** -40:
                out.status = "failed"
            return out

        @claim(f"v1v2.n{N}", equation="v1v2", scene="map", N=N,
               statement="L(l1) Omega_1 = v(l1) Omega_1, L(l2) Omega_2 = v(l2)^{-1} Omega_2 with "
                         f"v(l1) = (tr1 - gamma1)/2, v(l2) = (tr2 + gamma2)/2 (eqs. l1l2 + v1v2, N={N})")
        def v1v2_check():
            L1, L2, tr1, tr2, g1, g2, x, y, Om1, Om2, rel = _xy_generic()
            d1 = decide(L1 * Om1, (tr1 - g1) / 2 * Om1, relations={g1: rel[g1]})
            if not d1.holds:
                return from_decision(d1, detail="eigenvalue on Omega_1")
            printed = decide(L2 * Om2, 2 / (tr2 + g2) * Om2, relations=rel)
            r = _on_lattice(N, (L2 * Om2, (tr2 + g2) / 2 * Om2))
            return judge(printed,
                         printed="v(lambda2) = (A(l2)+D(l2)+gamma(l2))/2 and L(l2)|Omega_2> = v(l2)^{-1}|Omega_2>",
                         corrected="L(l2)|Omega_2> = ((tr2 + gamma2)/2)|Omega_2>: with l1l2's convention "
                                   "v(l2) = (tr2 - gamma2)/2, as Appendix B (eq. spec) uses; the lambda_1 half "
                                   "v(l1) = (tr1 - gamma1)/2 holds as printed",
                         corrected_check=lambda: decide(L2 * Om2, (tr2 + g2) / 2 * Om2, relations=rel),
                         detail=f"generic unimodular 2x2 matrices; corrected statement on the N={N} Lax matrix "
                                f"at 50 digits: residual {mp.nstr(r, 3)}")

        @claim(f"D.n{N}", equation="D", scene="map", N=N,
               statement="D(lambda) (eq. D) is degenerate exactly at l1, l2 with kernels Omega_1 = (1,-y), "
                         "Omega_2 = (x, l2-l1-xy), and with x, y of eq. xy, D L adj(D) vanishes at l1 and l2, "
                         f"so L~ = D L D^-1 is polynomial in lambda (N={N})")
        def D_check():
            x, y = sp.symbols("x y")
            Dm = composed_darboux(x, y)
            d = decide(sp.Matrix([Dm.det(), *(Dm.subs(lam, lam1) * sp.Matrix([1, -y])),
                                  *(Dm.subs(lam, lam2) * sp.Matrix([x, lam2 - lam1 - x * y]))]),
                       sp.Matrix([(lam - lam1) * (lam - lam2), 0, 0, 0, 0]))
            if not d.holds:
                return from_decision(d)
            def residual(state, b):
                p, q, l0, mu = state
                _, _, info = literal_step(p, q, l0, mu, b)
                xx, yy = info["x_formula"], info["y"][0]
                worst = mp.mpf(0)
                for lv in (l0 + mu, l0 - mu):
                    Dn = darboux_numeric(lv, l0, mu, xx, yy)
                    adj = mp.matrix([[Dn[1, 1], -Dn[0, 1]], [-Dn[1, 0], Dn[0, 0]]])
                    L = lax_matrix(lv, p, q)
                    scale = mp.mnorm(Dn, 1) * mp.mnorm(L, 1) * mp.mnorm(adj, 1)
                    worst = max(worst, mp.mnorm(Dn * L * adj, 1) / scale)
                return worst

            return from_decision(worst_over(
                _states(N), residual,
                method=f"exact: kernels and det; numeric: mpmath {DPS} digits, D L adj D at l1, l2 on 8 states "
                       "(both branches, both signs of tr)"))

        @claim(f"new.n{N}", equation="new", scene="map", N=N,
               statement="L~(lambda) D(lambda) = D(lambda) L(lambda) where L~ is the Lax matrix of the image "
                         f"(p~, q~) of the explicit map (N={N})")
        def new_check():
            def residual(state, b):
                p, q, l0, mu = state
                pt, qt, info = literal_step(p, q, l0, mu, b)
                xx, yy = info["x_formula"], info["y"][0]
                worst = mp.mpf(0)
                for lv in (mp.mpf("0.37"), mp.mpf("-1.91"), l0 + 3):
                    Dn = darboux_numeric(lv, l0, mu, xx, yy)
                    Lt, L = lax_matrix(lv, pt, qt), lax_matrix(lv, p, q)
                    worst = max(worst, mp.mnorm(Lt * Dn - Dn * L, 1) / (mp.mnorm(Lt, 1) * mp.mnorm(Dn, 1)))
                return worst

            return from_decision(worst_over(_states(N), residual, method=f"numeric: mpmath {DPS} digits, 8 states "
                                            "x 3 lambdas (both branches, both signs of tr)"))

        @claim(f"l1l2.n{N}", equation="l1l2", scene="map", N=N,
               statement="the kernels Omega_1, Omega_2 of D at l1, l2 are eigenvectors of L(l1), L(l2), "
                         f"with x, y recovered from the image (p~, q~) alone (N={N})")
        def l1l2_check():
            def residual(state, b):
                p, q, l0, mu = state
                pt, qt, _ = literal_step(p, q, l0, mu, b)
                # x = e^{q1} - e^{q~1} (eq. xyqqt), eta_1 from eq. imptransf, y = (eta_1 - mu)/x
                xx = mp.exp(q[0]) - mp.exp(qt[0])
                yy = (eta_from_states(p, q, pt, qt, l0)[0] - mu) / xx
                worst = mp.mpf(0)
                for lv, Om in ((l0 + mu, [mp.mpf(1), -yy]), (l0 - mu, [xx, -2 * mu - xx * yy])):
                    L = lax_matrix(lv, p, q)
                    LO = [L[0, 0] * Om[0] + L[0, 1] * Om[1], L[1, 0] * Om[0] + L[1, 1] * Om[1]]
                    worst = max(worst, abs(_cross(LO, Om)) / (mp.mnorm(L, 1) * (abs(Om[0]) + abs(Om[1])) ** 2))
                return worst

            return from_decision(worst_over(_states(N), residual, method=f"numeric: mpmath {DPS} digits, 8 states "
                                            "(both branches, both signs of tr)"))

        @claim(f"lam0mu.n{N}", equation="lam0mu", scene="map", N=N,
               statement="with l1 = l0 + mu, l2 = l0 - mu the map tends to the identity as mu -> 0, for "
                         "branch = +1 and branch = -1 (gamma with the same sign at l1 and l2); mixed signs do not "
                         f"(N={N})")
        def lam0mu_check():
            worst = mp.mpf(0)
            mixed_gap = mp.inf
            with mp.workdps(80):
                for state, b in _states(N)[::2]:
                    p, q, l0, _ = state
                    incs = []
                    for k in (10, 20):
                        mu = mp.mpf(10) ** -k
                        pt, qt, _ = literal_step(p, q, l0, mu, b)
                        incs.append(max(abs(a - c) for a, c in zip(pt + qt, p + q)) / mu)
                    # O(mu) increments: |step - id|/mu converges (to the vector field of Theorem 1)
                    worst = max(worst, abs(incs[0] - incs[1]) / incs[1])
                    for signs in ((1, -1), (-1, 1)):
                        pt, qt, _ = literal_step(p, q, l0, mp.mpf(10) ** -20, gamma_signs=signs)
                        gap = max(abs(a - c) for a, c in zip(pt + qt, p + q))
                        mixed_gap = min(mixed_gap, gap)
            ok = worst < mp.mpf(10) ** -8 and mixed_gap > mp.mpf("1e-3")
            return Outcome("verified" if ok else "failed",
                           "numeric: mpmath 80 digits, |step-id|/mu at mu = 1e-10, 1e-20",
                           residual=float(worst),
                           detail=f"same-sign branches: |step - id| = O(mu) (relative change of |step-id|/mu "
                                  f"{mp.nstr(worst, 3)}); mixed signs stay at distance >= {mp.nstr(mixed_gap, 3)} "
                                  "from the identity at mu = 1e-20")

        @claim(f"xy.branches.n{N}", equation="xy", scene="map", N=N,
               where="branch convention (not in the paper): gamma = branch * sqrt(tr^2 - 4) at l1 and l2",
               statement="branch = -1 at mu equals branch = +1 at -mu, and inverts branch = +1: "
                         f"T_-(T_+(p,q)) = (p,q) (N={N})")
        def branches_check():
            def residual(state, b):
                p, q, l0, mu = state
                pp, qp, _ = literal_step(p, q, l0, mu, 1)
                pm, qm, _ = literal_step(p, q, l0, mu, -1)
                pn, qn, _ = literal_step(p, q, l0, -mu, 1)
                pb, qb, _ = literal_step(pp, qp, l0, mu, -1)
                return max(max(_rel(a, c) for a, c in zip(pm + qm, pn + qn)),
                           max(_rel(a, c) for a, c in zip(pb + qb, p + q)))

            return from_decision(worst_over(_states(N)[::2], residual, method=f"numeric: mpmath {DPS} digits, 4 states"))

    _make(_N)
