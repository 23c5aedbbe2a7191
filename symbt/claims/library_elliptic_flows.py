r"""The independent routes checked, 6 (continued from :mod:`symbt.claims.library_elliptic_file`, which imports this
module): whole functions of :mod:`symbt.reference.taylor` and :mod:`symbt.reference.inverse` (scene ``library``).

* ``library.flow_angles`` -- :func:`symbt.reference.taylor.hamiltonian_flow` of ``G = c_0 H_0 + c_1 H_1 + c_2 H_2``
  (N = 2, forward and backward) moves along the action-angle solution: ``I_1, I_2`` kept, ``q_1 + q_2`` advances by
  ``(2 c_0 I_1 + 2 c_1) t`` and the global angle ``u`` by ``-c_0 sqrt(I_2 + 2) t`` (``H_0 = I_1^2 - I_2``,
  ``H_1 = 2 I_1``, ``{I_j, theta_k} = delta_jk``): ``sn``, ``cn`` of the moved angle are the flowed state's ``P, C``.
* ``library.flow_field`` -- :func:`symbt.reference.taylor.hamilton_equations` for N = 3 (``sign = +-1``, every
  ``c_k``) evaluated at a state is ``(sign dG/dp, -sign dG/dq, a_j (qdot_{j+1} - qdot_j))`` with
  ``G = sum_k c_k H_k``, ``H_k`` the coefficients of the literal trace (interpolated at ``lambda = 0..3``) and the
  derivatives by mpmath's ``diff``.
* ``library.inverse_fields`` -- :func:`symbt.reference.inverse.solve_parameters` returns every field its docstring
  defines: from the documented small-``mu`` start (no guess) a target of ``mu = 10^-3`` meets ``tol`` at once
  (``iterations = 1``) and ``(lam0, mu, b = -1)`` comes back; in mode ``direction`` (N = 3) the target ``c/2`` gives
  ``kappa = 2`` and ``residual = max |c_k|/2`` (the c_k all negative: a signed residual would differ); in mode ``exact``
  on three indices (N = 3: the least-squares
  Newton step; under ``--deep``) from a start ``10^-4`` off it recovers the target's ``(lam0, mu)``; ``c`` is
  ``[c_0, ..., c_N]`` at the answer (N = 2: mpmath ``quad`` of the literal trace), ``kappa`` and ``residual`` are
  their definitions.
* ``library.flow_steps`` -- :func:`~symbt.reference.taylor.hamiltonian_flow`'s step rule scales by ``max(1, |x|)``
  (the linear flow of ``H_1`` takes 6 steps from a state of size 5 and 29 from one of size 1, at order 2 and
  ``tol = 0.05``), ``max_steps`` allows exactly that many steps, ``t = 0`` takes none and the still flow of
  ``H_2 = 1`` one; :func:`~symbt.reference.taylor.hamilton_equations` pads a short ``c`` with zeros.  And the rule's
  minimum over both estimates, where the last coefficient's is the smaller (the linear flow has no second
  coefficient): the flow of ``H_0`` (written by hand, checked against the literal trace) from ``p = (1, -1)/1000``,
  ``q = 0`` takes one step to ``t = h1 (1 - 1e-6)`` and two to ``h1 (1 + 1e-6)``, ``h1 = 0.7 min((tol/n_2)^(1/2),
  tol/n_1) = 3.5`` from its first two Taylor coefficients by SymPy (seed 21: the rule with ``max`` passed).
* ``library.newton_rule`` -- the Newton loop of :func:`~symbt.reference.inverse.solve_parameters` on a toy residual
  ``-x^3`` (iterates ``(2/3)^n`` exactly): the stop at the first iterate below ``tol``, ``iterations``, the extra
  step, least-squares steps, giving up after ``maxit``; Gauss-Newton's stop on an inconsistent linear pair.

Each is shown to fail on planted mutants in ``tests/test_killers_elliptic.py``.

>>> flow_steps.run().status
'verified'
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import mpmath as mp
import sympy as sp

from ..reference import elliptic as E
from ..reference.literal import literal_trace
from ..reference.taylor import hamilton_equations, hamiltonian_flow
from .base import Outcome, claim, failed
from .library_sampler import trace_actions as _actions

#: library.flow_angles: digits, (p, q, c, t): G = c0 H0 + c1 H1 + c2 H2, forward and backward
FLOWA_DPS = 15
FLOWA_CASES = ((("0.7", "-0.4"), ("0.3", "-0.5"), ("0.8", "0.3", "5"), "0.6"),
               (("-0.7", "0.4"), ("-0.6", "0.2"), ("-1.1", "-0.6"), "-0.5"))


@claim("library.flow_angles", equation="flow", scene="library", N=2,
       where="symbt.reference.taylor.hamiltonian_flow (N = 2, against the action-angle solution)",
       statement="hamiltonian_flow(p, q, (c0, c1, c2), t) (N = 2, 15 digits, t > 0 and t < 0) keeps I1, I2, moves "
                 "q1 + q2 by (2 c0 I1 + 2 c1) t and the global angle u by -c0 sqrt(I2 + 2) t: sn, cn of the moved u "
                 "(ellipfun) are P, C of the flowed state within 10^(3 - dps)")
def flow_angles() -> Outcome:
    bad: list[str] = []
    worst = mp.mpf(0)
    with mp.workdps(FLOWA_DPS):
        for ps, qs, cs, ts in FLOWA_CASES:
            p, q, c, t = [mp.mpf(v) for v in ps], [mp.mpf(v) for v in qs], [mp.mpf(v) for v in cs], mp.mpf(ts)
            I1, I2 = _actions(p, q)
            u, m = E.global_u(p, q)
            pt, qt = hamiltonian_flow(p, q, c, t)
            J1, J2 = _actions(pt, qt)
            r = mp.sqrt(I2 - 2)
            ut = u - c[0] * mp.sqrt(I2 + 2) * t
            P, C = (pt[1] - pt[0]) / (2 * r), 2 * mp.sinh((qt[0] - qt[1]) / 2) / r
            err = max(abs(J1 - I1), abs(J2 - I2), abs(qt[0] + qt[1] - q[0] - q[1] - (2 * c[0] * I1 + 2 * c[1]) * t),
                      abs(mp.ellipfun("sn", ut, m=m) - P), abs(mp.ellipfun("cn", ut, m=m) - C))
            worst = max(worst, err)
            if not err <= mp.mpf(10) ** (3 - FLOWA_DPS):
                bad.append(f"c = {cs}, t = {ts}: the flowed state is {mp.nstr(err, 3)} off the action-angle solution")
    detail = f"{len(FLOWA_CASES)} flows (t > 0, t < 0), worst {mp.nstr(worst, 2)} (accepted 1e{3 - FLOWA_DPS})"
    if bad:
        return failed("hamiltonian_flow vs the action-angle solution", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", f"numeric: the elliptic action-angle solution (ellipfun) at {FLOWA_DPS} digits",
                   evidence="sampled", n_scope=[2], residual=float(worst), detail=detail)


#: library.flow_field: digits, the N = 3 state and the c_k
FIELD_DPS = 20
FIELD_STATE = (("0.3", "-0.2", "0.5"), ("0.1", "0.4", "-0.3"), ("0.7", "-0.4", "1.3", "2"))


def _poly_value(poly: dict, pv: Sequence[mp.mpf], av: Sequence[mp.mpf]) -> mp.mpf:
    vals = list(pv) + list(av)
    return mp.fsum(mp.mpf(v) * mp.fprod(x ** e for x, e in zip(vals, ex)) for ex, v in poly.items())


def _G_literal(p: Sequence[mp.mpf], q: Sequence[mp.mpf], c: Sequence[mp.mpf]) -> mp.mpf:
    """``sum_k c_k H_k`` with ``H_k`` interpolated from the literal trace at ``lambda = 0..N``."""
    N = len(p)
    V = mp.matrix([[mp.mpf(x) ** k for k in range(N + 1)] for x in range(N + 1)])
    H = mp.lu_solve(V, mp.matrix([literal_trace(mp.mpf(x), list(p), list(q)) for x in range(N + 1)]))
    return mp.fsum(ck * H[k] for k, ck in enumerate(c))


@claim("library.flow_field", equation="flow", scene="library", N=3,
       where="symbt.reference.taylor.hamilton_equations",
       statement="hamilton_equations(3, c, sign) at a state (sign = +-1, every c_k nonzero) is (sign dG/dp, "
                 "-sign dG/dq, a_j (qdot_{j+1} - qdot_j)), G = sum c_k H_k with H_k interpolated from the literal "
                 "trace, derivatives by mpmath diff (20 digits), within 10^(5 - dps)")
def flow_field() -> Outcome:
    bad: list[str] = []
    with mp.workdps(FIELD_DPS):
        ps, qs, cs = FIELD_STATE
        p, q, c = [mp.mpf(v) for v in ps], [mp.mpf(v) for v in qs], [mp.mpf(v) for v in cs]
        N = len(p)
        a = [mp.exp(q[(j + 1) % N] - q[j]) for j in range(N)]
        dGp = [mp.diff(lambda x, j=j: _G_literal(p[:j] + [x] + p[j + 1:], q, c), p[j]) for j in range(N)]
        dGq = [mp.diff(lambda x, j=j: _G_literal(p, q[:j] + [x] + q[j + 1:], c), q[j]) for j in range(N)]
        worst = mp.mpf(0)
        for sign in (1, -1):
            qd = [sign * v for v in dGp]
            want = qd + [-sign * v for v in dGq] + [a[j] * (qd[(j + 1) % N] - qd[j]) for j in range(N)]
            got = [_poly_value(P, p, a) for P in hamilton_equations(N, c, sign)]
            err = max(abs(x - y) for x, y in zip(got, want)) / max(abs(y) for y in want)
            worst = max(worst, err)
            if len(got) != 3 * N or not err <= mp.mpf(10) ** (5 - FIELD_DPS):
                bad.append(f"sign {sign}: {len(got)} equations, off by {mp.nstr(err, 3)} (relative)")
    detail = f"N = 3, both signs: worst {mp.nstr(worst, 2)} relative (accepted 1e{5 - FIELD_DPS})"
    if bad:
        return failed("hamilton_equations vs the literal trace's gradient", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", f"numeric: finite differences of the literal trace at {FIELD_DPS} digits",
                   evidence="sampled", n_scope=[3], residual=float(worst), detail=detail)


#: library.inverse_fields: digits; (a) N = 2, a small mu at branch -1, from the documented start; (b) N = 3, the
#: target 2 c (direction), from the exact (lam0, mu)
INVF_DPS = 15
INVF_SMALL = (("0.518591", "-0.82529"), ("-1.341917", "0.453427"), "4.504539", "0.001")
INVF_DIR = (("0.3", "-0.2", "0.5"), ("0.1", "0.4", "-0.3"), "6", "0.3")
#: (c) the same N = 3 target c fitted in mode exact with three indices (a least-squares Newton step: qr_solve), from
#: lam0 moved by this much (its residual is above tol: one step at least)
INVF_OFF = mp.mpf("1e-4")


def _c_quad(p: list, q: list, l0: mp.mpf, mu: mp.mpf, b: int) -> list:
    """``c_k = -b int lambda^k / sqrt(tr^2 - 4)`` over ``[l0 - mu, l0 + mu]`` by mpmath's quad of the literal trace."""
    return [-b * mp.quad(lambda x, k=k: x ** k / mp.sqrt(literal_trace(x, p, q) ** 2 - 4), [l0 - mu, l0 + mu])
            for k in range(len(p) + 1)]


@claim("library.inverse_fields", equation="linearcomb", scene="library", N=3,
       where="symbt.reference.inverse.solve_parameters (every field of its answer; the documented start)",
       statement="solve_parameters (15 digits) returns every documented field: (a) N = 2, the target c_k of "
                 "(lam0, mu, b) = (4.504539, 1e-3, -1), no guess: the small-mu start meets tol, so iterations = 1, "
                 "(lam0, mu, b) recovered to 1e-12; (b) N = 3, mode direction, the target c/2 of (6, 0.3, +1) from "
                 "the guess (6, 0.3): iterations = 1, kappa = 2, residual = max_(k<3) |c_k|/2; mode lstsq, the "
                 "target c from the guess (6, 0.3): iterations = 1, kappa = 1, residual 0 to 1e-12; (c) N = 3, mode "
                 "exact, "
                 "indices (0, 1, 2) (least squares; under --deep), the target c from (6 + 1e-4, 0.3): iterations "
                 ">= 2, (6, 0.3, +1) to 1e-12, kappa = 1; c = [c_0..c_N] at the "
                 "answer (N = 2: by mpmath quad of the literal trace; N = 3: the coefficients the target was made "
                 "from), kappa = sum c_k t_k / "
                 "sum t_k^2 and residual = max |c_k - t_k| (k < N) within 1e-12 of the size; with indices (0, 2) a "
                 "c_1 that violates Cauchy-Schwarz is not read ((6, 0.3) found from c_0, c_2)")
def inverse_fields(deep: bool = False) -> Outcome:
    from ..reference.inverse import solve_parameters
    from ..reference.spectral import flow_coefficients_mp

    bad: list[str] = []
    with mp.workdps(INVF_DPS):
        tol = mp.mpf("1e-12")
        coeffs: dict[tuple, list] = {}
        # mode exact on three indices from INVF_OFF off (the least-squares step) runs under --deep only: its cost;
        # library.newton_rule observes the least-squares step on a toy residual in the default run
        cases: list[tuple[Any, ...]] = [(INVF_SMALL, -1, "exact", 1, None, None),
                                        (INVF_DIR, 1, "direction", mp.mpf("0.5"), None, 0),
                                        (INVF_DIR, 1, "lstsq", 1, None, 0)]
        if deep:
            cases.append((INVF_DIR, 1, "exact", 1, (0, 1, 2), INVF_OFF))
        for (ps, qs, l0s, ms), b, mode, scale, idx, off in cases:
            p, q, l0, mu = [mp.mpf(v) for v in ps], [mp.mpf(v) for v in qs], mp.mpf(l0s), mp.mpf(ms)
            N = len(p)
            key = (ps, qs, l0s, ms, b)
            if key not in coeffs:
                coeffs[key] = [v for v in flow_coefficients_mp(p, q, l0, b * mu, 1) if v is not None]
            target = [scale * v for v in coeffs[key]]
            guess = None if off is None else (l0 + off, b * mu)
            try:
                r = solve_parameters(p, q, target, mode=mode, guess=guess, indices=idx)
            except ValueError as exc:
                bad.append(f"N={N}, {mode}: {exc}")
                continue
            if r is None:
                bad.append(f"N={N}, {mode}: no answer")
                continue
            # N = 2: c by quad of the literal trace (independent); N = 3: the answer is the target's own (lam0, mu),
            # so c is target / 2 there (a consistency of the field; the direction's ratios are quad-free)
            c = _c_quad(p, q, r["lam0"], r["mu"], r["branch"]) if N == 2 else list(coeffs[key])
            size = max(abs(v) for v in c)
            kappa = mp.fsum(a * t for a, t in zip(c[:N], target[:N])) / mp.fsum(t * t for t in target[:N])
            resid = max(abs(a - t) for a, t in zip(c[:N], target[:N]))
            why = []
            if (r["iterations"] != 1) if off in (None, 0) else not r["iterations"] >= 2:
                why.append(f"iterations {r['iterations']} (1 where the start meets tol, else at least 2)")
            if r["branch"] != b or not max(abs(r["lam0"] - l0), abs(r["mu"] - mu)) <= tol * max(1, abs(l0)):
                why.append(f"(lam0, mu, b) = ({mp.nstr(r['lam0'], 12)}, {mp.nstr(r['mu'], 12)}, {r['branch']})")
            if len(r["c"]) != N + 1 or not max(abs(a - e) for a, e in zip(r["c"], c)) <= tol * size:
                why.append(f"c = {[mp.nstr(v, 8) for v in r['c']]}, by quad {[mp.nstr(v, 8) for v in c]}")
            if not (abs(r["kappa"] - kappa) <= tol and abs(kappa - mp.mpf(1) / scale) <= tol):
                why.append(f"kappa {mp.nstr(r['kappa'], 10)}, by the definition {mp.nstr(kappa, 10)}")
            if not abs(r["residual"] - resid) <= tol * size:
                why.append(f"residual {mp.nstr(r['residual'], 8)}, by the definition {mp.nstr(resid, 8)}")
            if why:
                bad.append(f"N={N}, {mode}: " + ", ".join(why))
        # the Cauchy-Schwarz refusal needs c_0, c_1, c_2 all fitted: with indices (0, 2) a c_1 that violates it is
        # not read, and (6, 0.3, +1) is found from its own c_0, c_2
        ps, qs, l0s, ms = INVF_DIR
        c = coeffs[(ps, qs, l0s, ms, 1)]
        bogus = [c[0], 10 * mp.sqrt(abs(c[0] * c[2])), c[2]]            # c_0 c_2 <= c_1^2
        try:
            r = solve_parameters([mp.mpf(v) for v in ps], [mp.mpf(v) for v in qs], bogus, indices=(0, 2),
                                 guess=(mp.mpf(l0s), mp.mpf(ms)))
            if r is None or abs(r["lam0"] - mp.mpf(l0s)) > tol * abs(mp.mpf(l0s)) or abs(r["mu"] - mp.mpf(ms)) > tol:
                bad.append(f"indices (0, 2) with c_1 ignored: {r and (r['lam0'], r['mu'])}")
        except ValueError as exc:
            bad.append(f"indices (0, 2): refused although c_1 is not fitted: {exc}")
    detail = ("N = 2 from the small-mu start at branch -1; N = 3 by direction to c/2, by least squares to c (and "
              "exact on 3 indices under --deep): "
              "iterations, (lam0, mu, b), c (by quad for N = 2), kappa and residual by their definitions (accepted "
              "1e-12)")
    if bad:
        return failed("solve_parameters' answer vs quad and the definitions", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", f"numeric: mpmath quad of the literal trace at {INVF_DPS} digits", evidence="sampled",
                   n_scope=[2, 3], detail=detail)


#: library.flow_steps: digits, tol: the linear flow of H_1 at order 2 from p = (5, -5) (|x| = 5) and p = (1/2, -1/2)
STEPS_DPS, STEPS_TOL = 20, mp.mpf("5e-2")


#: library.flow_steps: (p, q) near the equilibrium of H_0, where the second-order estimate of the step is the smaller
FIRST_STEP_STATE = ([mp.mpf(1) / 1000, -mp.mpf(1) / 1000], [mp.mpf(0), mp.mpf(0)])


def _first_step() -> mp.mpf:
    """``0.7 min((tol/n_2)^(1/2), tol/n_1)`` at :data:`FIRST_STEP_STATE` (order 2): ``n_k`` the largest k-th Taylor
    coefficient of ``(q, p, e^{q_2 - q_1}, e^{q_1 - q_2})`` along the flow of ``H_0 = p_1 p_2 - e^{q_2 - q_1} -
    e^{q_1 - q_2}`` (N = 2, written by hand and checked against the literal trace at 0), by SymPy's derivatives;
    the state's size is below 1, so the scale is 1."""
    q1, q2, p1, p2 = sp.symbols("q1 q2 p1 p2", real=True)
    H0 = p1 * p2 - sp.exp(q2 - q1) - sp.exp(q1 - q2)
    at = dict(zip((p1, p2, q1, q2), (sp.Rational(1, 1000), sp.Rational(-1, 1000), 0, 0)))
    if abs(mp.mpf(sp.N(H0.subs(at), 30)) - literal_trace(mp.mpf(0), *FIRST_STEP_STATE)) > mp.mpf(10) ** (5 - STEPS_DPS):
        raise AssertionError("H_0 written by hand is not the literal trace at lambda = 0")

    def along(F: sp.Expr) -> sp.Expr:       # dF/dt = {F, H_0}: qdot = dH/dp, pdot = -dH/dq
        return sum(sp.diff(F, q) * sp.diff(H0, p) - sp.diff(F, p) * sp.diff(H0, q) for q, p in ((q1, p1), (q2, p2)))
    xs = [q1, q2, p1, p2, sp.exp(q2 - q1), sp.exp(q1 - q2)]
    n1 = max(abs(along(F).subs(at)) for F in xs)
    n2 = max(abs((along(along(F)) / 2).subs(at)) for F in xs)
    tol = sp.Rational(mp.nstr(STEPS_TOL, 15))
    return mp.mpf(sp.Rational(7, 10) * min(sp.sqrt(tol / n2), tol / n1))


@claim("library.flow_steps", equation="flow", scene="library", N=2,
       where="symbt.reference.taylor.hamiltonian_flow (its step rule's scale, max_steps, t = 0, a still flow) and "
             "hamilton_equations (a short c)",
       statement="the linear flow of H_1 (order 2, tol 0.05, t = 1) from p = (5, -5), q = 0 takes ceil(1/(0.7 tol "
                 "max(1, |x|))) = 6 steps (the step scaled by the state's size 5) and from p = (1/2, -1/2) 29 "
                 "steps, exactly (q_j(1) = q_j + 1); with max_steps = 29 the second runs and with 28 it raises "
                 "RuntimeError; t = 0 takes no step and returns the state; the flow of H_2 = 1 takes one step and "
                 "moves nothing; hamilton_equations(3, c) with c = (c_0, c_1) equals it with c padded by zeros and "
                 "with sign = 1 given (the default: the forward flow); the flow of H_0 from p = (1, -1)/1000, q = 0 "
                 "takes one step to t = h1 (1 - 1e-6) and two to h1 (1 + 1e-6), h1 = 0.7 min((tol/n_2)^(1/2), "
                 "tol/n_1) from its Taylor coefficients by SymPy (the second-order estimate the smaller)")
def flow_steps() -> Outcome:
    bad: list[str] = []
    with mp.workdps(STEPS_DPS):
        q0 = [mp.mpf(0), mp.mpf(0)]
        for p0, want in (([mp.mpf(5), mp.mpf(-5)], 6), ([mp.mpf("0.5"), mp.mpf("-0.5")], 29)):
            out = hamiltonian_flow(p0, q0, [0, 1, 0], mp.mpf(1), tol=STEPS_TOL, order=2)
            err = max(abs(a - b) for a, b in zip([*out[0], *out[1]], [*p0, mp.mpf(1), mp.mpf(1)]))
            if out.steps != want or not err <= mp.mpf(10) ** (3 - STEPS_DPS):
                bad.append(f"H_1 flow from p = {mp.nstr(p0[0], 3)}: {out.steps} steps (rule: {want}), error "
                           f"{mp.nstr(err, 3)}")
        p0 = [mp.mpf("0.5"), mp.mpf("-0.5")]
        try:
            hamiltonian_flow(p0, q0, [0, 1, 0], mp.mpf(1), tol=STEPS_TOL, order=2, max_steps=29)
        except RuntimeError:
            bad.append("max_steps = 29 refused a flow of 29 steps")
        try:
            hamiltonian_flow(p0, q0, [0, 1, 0], mp.mpf(1), tol=STEPS_TOL, order=2, max_steps=28)
            bad.append("max_steps = 28 let a flow of 29 steps run")
        except RuntimeError:
            pass
        p, q = [mp.mpf("0.3"), mp.mpf("-0.2")], [mp.mpf("0.1"), mp.mpf("0.4")]
        for c, t, steps in (([1, 0, 0], mp.mpf(0), 0), ([0, 0, 1], mp.mpf(2), 1)):
            out = hamiltonian_flow(p, q, c, t)
            if out.steps != steps or [*out[0], *out[1]] != [*p, *q]:
                bad.append(f"c = {c}, t = {t}: {out.steps} steps (want {steps}), state moved")
        # the rule's min over both estimates, where the last coefficient's is the smaller: the flow of H_0 near its
        # equilibrium, the first and second Taylor coefficients by SymPy from H_0 written by hand
        h1 = _first_step()
        got = [hamiltonian_flow(*FIRST_STEP_STATE, [1, 0, 0], h1 * (1 + s * mp.mpf(10) ** -6), tol=STEPS_TOL,
                                order=2).steps for s in (-1, 1)]
        if got != [1, 2]:
            bad.append(f"H_0 flow: {got} steps for t = h1 (1 -+ 1e-6), h1 = {mp.nstr(h1, 6)} by the rule (want [1, 2])")
        c3 = [mp.mpf("0.7"), mp.mpf("-0.4")]
        if not hamilton_equations(3, c3) == hamilton_equations(3, c3 + [0, 0]) == hamilton_equations(3, c3, 1):
            bad.append("hamilton_equations with c = (c_0, c_1) differs from c padded by zeros, or from the forward "
                       "flow (sign = 1, the default)")
    detail = "6 and 29 steps by the documented rule, max_steps at its edge, t = 0, H_2, a short c"
    if bad:
        return failed("hamiltonian_flow's step rule and limits", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "exact: the documented step counts; the linear flow's exact solution",
                   evidence="sampled", n_scope=[2, 3], detail=detail)


#: library.newton_rule: Newton on f(x) = -x^3 from x = 1 (each full step x -> 2x/3, the residual times 8/27)
NEWTON_TOLS = (mp.mpf("1e-6"), mp.mpf("1e-300"))


@claim("library.newton_rule", equation="linearcomb", scene="library", N=2,
       where="symbt.reference.inverse's Newton and Gauss-Newton loops (the rules solve_parameters documents)",
       statement="solve_parameters' Newton on f(x) = -x^3 from x = 1 (full steps x -> 2x/3: the residual falls by "
                 "8/27, so the damping keeps them) with tol = 1e-6 stops at the first iterate below tol, the 12th, "
                 "reports iterations = 13 and takes one more step: x = (2/3)^13 (also with the equation twice: "
                 "least-squares steps); with tol = 1e-300 it gives up after its 40 iterations (None: the residual "
                 "-(2/3)^120 is negative, its size above tol; also with x_1 - 1 = 0, solved at once, beside it: the "
                 "largest component is judged); Gauss-Newton "
                 "on the inconsistent (x - 1, x + 1) returns the least-squares x = 0 after one step (iterations = 2: "
                 "the iterates evaluated); the line "
                 "search tries lam = 1, 1/2, ..., 2**-29 and no smaller")
def newton_rule() -> Outcome:
    from ..reference import inverse as inv

    bad: list[str] = []
    with mp.workdps(30):
        F = lambda x: [-x[0] ** 3]                        # noqa: E731 -- a toy residual
        J = lambda x: [[-3 * x[0] ** 2]]                  # noqa: E731
        got = inv._newton(F, J, [mp.mpf(1)], NEWTON_TOLS[0])
        want = (mp.mpf(2) / 3) ** 13
        if got is None or got[1] != 13 or not abs(got[0][0] - want) <= mp.mpf(10) ** -25 * want:
            bad.append(f"tol 1e-6: {got if got is None else (mp.nstr(got[0][0], 10), got[1])}, want "
                       f"({mp.nstr(want, 10)}, 13)")
        # the same equation twice: a 2 x 1 Jacobian, so the steps are least-squares (qr_solve) steps, the same x
        got = inv._newton(lambda x: F(x) * 2, lambda x: J(x) * 2, [mp.mpf(1)], NEWTON_TOLS[0])
        if got is None or got[1] != 13 or not abs(got[0][0] - want) <= mp.mpf(10) ** -25 * want:
            bad.append(f"tol 1e-6, the equation twice: {got if got is None else (mp.nstr(got[0][0], 10), got[1])}")
        got = inv._newton(F, J, [mp.mpf(1)], NEWTON_TOLS[1])
        if got is not None:
            bad.append(f"tol 1e-300: returned {mp.nstr(got[0][0], 5)} after {got[1]} iterations, not None")
        # beside x_1 - 1 (solved by the first step, exactly): the residual judged is the largest component
        got = inv._newton(lambda x: [-x[0] ** 3, x[1] - 1], lambda x: [[-3 * x[0] ** 2, 0], [0, 1]],
                          [mp.mpf(1), mp.mpf(0)], NEWTON_TOLS[1])
        if got is not None:
            bad.append(f"tol 1e-300 with x_1 - 1 beside: returned after {got[1]} iterations, not None")
        G = lambda x: [x[0] - 1, x[0] + 1]                # noqa: E731
        JG = lambda x: [[mp.mpf(1)], [mp.mpf(1)]]         # noqa: E731
        gn = inv._gauss_newton(G, JG, [mp.mpf("0.4")], mp.mpf("1e-20"))
        if gn is None or gn[1] != 2 or not abs(gn[0][0]) <= mp.mpf(10) ** -25:
            bad.append(f"Gauss-Newton: {gn}, want ([0], 2): one step, evaluated at two iterates")
        # the line search's 30 tries, lam = 1 ... 2**-29: the last is taken when it alone is accepted, 2**-30 never
        for last, want_lam in ((29, mp.mpf(2) ** -29), (30, None)):
            def below(r: list[mp.mpf], lam: mp.mpf, last: int = last) -> bool:
                return bool(lam <= mp.mpf(2) ** -last)
            ls = inv._line_search(lambda x: [x[0]], [mp.mpf(0)], [mp.mpf(1)], below)
            if (ls and ls[1]) != want_lam:
                bad.append(f"line search accepting lam <= 2**-{last} only: {ls}, want lam = {want_lam}")
    detail = ("Newton: 13 iterations and the extra step at tol 1e-6, None at 1e-300; Gauss-Newton: x = 0 after 1 step "
              "(2 iterates); "
              "the line search stops at lam = 2**-29")
    if bad:
        return failed("the Newton loops' documented rules on toy residuals", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "exact: Newton's iterates on -x^3 are (2/3)^n", evidence="sampled", n_scope=[2],
                   detail=detail)
