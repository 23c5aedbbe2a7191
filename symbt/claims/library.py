r"""The library's own symbolic routines against routes that share nothing with them (scene ``library``).

The claims of the paper re-derive much of what :mod:`symbt.symbolic` and :mod:`symbt.codegen.derive` compute,
so a slip in the library itself (a wrong entry of the composed Darboux matrix, a derivative taken by the
neighbour's variable, a lost minus of :math:`\dot p = -\partial H/\partial q`) changed no verdict.  Here the
library is called and compared with an independent route:

* ``library.darboux`` -- :func:`symbt.symbolic.darboux.darboux_composition` (eq. ``D1D2``) equals
  ``adj d(x2, y2; lambda_2) * d(x1, y1; lambda_1)`` with the adjugate taken by SymPy's ``Matrix.adjugate``
  (not the printed ``hd``), :func:`~symbt.symbolic.darboux.single_darboux_adjugate` is that adjugate,
  and :func:`~symbt.symbolic.darboux.composed_darboux` (eq. ``D``) has determinant
  :math:`(\lambda-\lambda_1)(\lambda-\lambda_2)` for every :math:`x, y`; decided exactly.
* ``library.dF.n{N}`` (N = 2; N = 3 under ``--deep``) -- :meth:`GeneratingFunction.dF_dq`, ``dF_dqt``
  and ``dF_dmu`` (the implicit derivatives of eq. ``newgf``), and ``total_derivative`` of :math:`\eta_1` itself
  (by :math:`\mu` and :math:`q_1`), at sample points against central
  differences (``mpmath.diff``, 40 digits) of :math:`F` with :math:`\eta_j = \pm\sqrt{\mu^2 + w_j}`
  written out and :math:`E_j = e^{q_j}`: no implicit differentiation, no chain rule.  Both signs of
  the :math:`\eta_j`.  Accepted when the relative difference is below :math:`10^{-25}` (the
  differences are good to ~35 digits at 40, the library's expression is exact); above it fails.
* ``library.fields.n{N}`` (N = 2; N = 3 under ``--deep``) -- the sources of the emitted
  ``hamiltonian_fields``, ``flow_field`` and ``phi_grad`` (:func:`symbt.codegen.derive.sources`, evaluated by
  :func:`symbt.codegen.verify.evaluate_source` at 40 digits) against central differences of the
  polynomial trace (:func:`symbt.reference.trace.hamiltonians`, the closed-walk expansion, no 2x2
  product) and of :math:`\Phi` of the traces (:func:`symbt.reference.literal.phi_from_traces` of
  :func:`symbt.reference.trace.trace`): the signs :math:`\dot q = \partial H_k/\partial p`,
  :math:`\dot p = -\partial H_k/\partial q` and the variable each derivative is taken by.  Same
  acceptance, relative to :math:`\max(1, |\text{value}|)`.

* ``library.symbols`` -- the assumptions the library's symbols are documented with, read through what SymPy
  infers from them (not the flags): :math:`E_j, \tilde E_j > 0` and :math:`\lambda_0` real make
  :math:`\lambda_0(\ln E_j - \ln\tilde E_j)` (the last term of eq. ``newgf``) real, :math:`\eta_j` real makes
  :math:`\sqrt{\eta_j^2} = |\eta_j|`, :math:`\lambda_0 \pm \mu` are real, and a user's
  ``Symbol("E1", positive=True)`` is the library's :math:`E_1` (so substituting a state into :math:`F` by name
  gives a number).

>>> darboux_by_adjugate.run().status
'verified'
"""
from __future__ import annotations

import random
from dataclasses import replace

import mpmath as mp
import sympy as sp

from ..proof import decide
from ..reference.literal import phi_from_traces
from ..reference.trace import hamiltonians, trace
from ..symbolic.darboux import (
    composed_darboux,
    darboux_composition,
    lam0,
    lam1,
    lam2,
    mu,
    single_darboux,
    single_darboux_adjugate,
)
from ..symbolic.generating import generating_function
from .base import Outcome, claim, failed, from_decision, scene

scene("library", "the library's own symbolic routines (Darboux composition, the generating function's "
                 "derivatives, the emitted fields' sources) against routes that share nothing with them")

DPS = 40
TOL = mp.mpf(10) ** -25
LAM0 = mp.mpf("0.37")   # lambda_0 of F (F is affine in it: any value)


@claim("library.darboux", equation="D1D2", scene="library",
       where="symbt.symbolic.darboux: darboux_composition and single_darboux_adjugate (eqs. D1D2, hd)",
       statement="darboux_composition(x1, x2, y1, y2) = adj(d(x2, y2; lambda2)) d(x1, y1; lambda1), the adjugate "
                 "by SymPy; single_darboux_adjugate = adj(single_darboux); det composed_darboux(x, y) = "
                 "(lambda - lambda1)(lambda - lambda2)")
def darboux_by_adjugate() -> Outcome:
    x1, x2, y1, y2, a, bb, z = sp.symbols("x1 x2 y1 y2 a b z")
    adj = single_darboux(a, bb, z).adjugate()
    d = decide(single_darboux_adjugate(a, bb, z), adj)
    if not d.holds:
        return from_decision(d, detail="single_darboux_adjugate is not the adjugate of single_darboux")
    want = single_darboux(x2, y2, lam2).adjugate() * single_darboux(x1, y1, lam1)
    d = decide(darboux_composition(x1, x2, y1, y2), want)
    if not d.holds:
        return from_decision(d, detail="darboux_composition is not adj d(lambda2) d(lambda1)")
    # eq. D: det = (lambda - lambda1)(lambda - lambda2) for every x, y (the determinant of the product above)
    lam_ = sp.Symbol("lambda")
    d = decide(composed_darboux(a, bb, lam_=lam_).det(), (lam_ - lam1) * (lam_ - lam2))
    out = from_decision(d, detail="exactly: entrywise, against Matrix.adjugate of eq. dj; det composed_darboux(x, y) "
                                  "= (lambda - lambda1)(lambda - lambda2)" + ("" if d.holds else ": it is not"))
    return replace(out, n_scope="all")


def _rel(a, b) -> mp.mpf:
    return abs(a - b) / max(1, abs(b))


@claim("library.dF", equation="newgf", scene="library", sizes=(3,), deep=True,
       where="symbt.symbolic.generating.GeneratingFunction: dF_dq, dF_dqt, dF_dmu (N={N})",
       statement="the library's implicit derivatives dF/dq_j = E_j dF/dE_j, dF/dq~_j and dF/dmu of eq. newgf (and "
                 "deta_1/dmu, deta_1/dq_1) equal central differences of F with eta_j = +-sqrt(mu^2 + w_j) written out "
                 "(N={N})")
@claim("library.dF", equation="newgf", scene="library", sizes=(2,),
       where="symbt.symbolic.generating.GeneratingFunction: dF_dq, dF_dqt, dF_dmu (N={N})",
       statement="the library's implicit derivatives dF/dq_j = E_j dF/dE_j, dF/dq~_j and dF/dmu of eq. newgf (and "
                 "deta_1/dmu, deta_1/dq_1) equal central differences of F with eta_j = +-sqrt(mu^2 + w_j) written out "
                 "(N={N})")
def generating_derivatives(N: int) -> Outcome:
    g = generating_function(N)
    rng = random.Random(4243 + N)
    worst, where = mp.mpf(0), None
    names = [f"dF/d{v}{j + 1}" for j in range(N) for v in ("q", "qt")] + ["dF/dmu", "deta1/dmu", "deta1/dq1"]
    # and eta_1 itself (linear in eta: the implicit term is all there is)
    exprs = [d for j in range(N) for d in (g.dF_dq(j), g.dF_dqt(j))] + [
        g.dF_dmu(), g.total_derivative(g.eta[0], g.mu), g.E[0] * g.total_derivative(g.eta[0], g.E[0])]
    syms = sorted(set().union(*(e.free_symbols for e in exprs)), key=str)
    library_values = sp.lambdify(syms, exprs, "mpmath")     # one compilation for every derivative
    with mp.workdps(DPS):
        for sign in (1, -1):
            # q~_j < q_j and q~_{j-1} < q_{j-1}: w_j = (E_j - E~_j)(1/E~_{j-1} - 1/E_{j-1}) > 0
            q = [mp.mpf(rng.uniform(-1, 1)) for _ in range(N)]
            qt = [v - mp.mpf(rng.uniform(0.2, 1)) for v in q]
            m0 = mp.mpf(rng.uniform(0.3, 1.5))

            def F(qq, qqt, m, sign=sign):
                E, Et = [mp.exp(v) for v in qq], [mp.exp(v) for v in qqt]
                out = mp.mpf(0)
                for j in range(N):
                    k = (j - 1) % N
                    e = sign * mp.sqrt(m ** 2 + (E[j] - Et[j]) * (1 / Et[k] - 1 / E[k]))
                    out += m * mp.log((e + m) / (e - m)) - 2 * e - LAM0 * (qq[j] - qqt[j])
                return out

            def eta1(qq, m, sign=sign):     # w_1 = (E_1 - E~_1)(1/E~_N - 1/E_N)
                w1 = (mp.exp(qq[0]) - mp.exp(qt[0])) * (1 / mp.exp(qt[N - 1]) - 1 / mp.exp(qq[N - 1]))
                return sign * mp.sqrt(m ** 2 + w1)

            E, Et = [mp.exp(v) for v in q], [mp.exp(v) for v in qt]
            env = {**dict(zip(g.E, E)), **dict(zip(g.Et, Et)), g.mu: m0, g.lam0: LAM0}
            for j in range(N):
                k = (j - 1) % N
                env[g.eta[j]] = sign * mp.sqrt(m0 ** 2 + (E[j] - Et[j]) * (1 / Et[k] - 1 / E[k]))
            fds = []
            for j in range(N):
                fds.append(mp.diff(lambda s, j=j: F([s if i == j else v for i, v in enumerate(q)], qt, m0), q[j]))
                fds.append(mp.diff(lambda s, j=j: F(q, [s if i == j else v for i, v in enumerate(qt)], m0), qt[j]))
            fds.append(mp.diff(lambda s: F(q, qt, s), m0))
            fds.append(mp.diff(lambda s: eta1(q, s), m0))
            fds.append(mp.diff(lambda s: eta1([s, *q[1:]], m0), q[0]))
            for name, val, fd in zip(names, library_values(*(env[s_] for s_ in syms)), fds):
                r = _rel(val, fd)
                if r > worst:
                    worst, where = r, {"derivative": name, "eta_sign": sign}
    if worst > TOL:
        return failed(f"numeric: central differences at {DPS} digits", residual=float(worst), counterexample=where,
                      detail=f"a library derivative of F differs from the differences by {float(worst):.2e} "
                             f"(relative; accepted below 1e-25)")
    return Outcome("verified", f"numeric: central differences (mpmath.diff) at {DPS} digits", residual=float(worst),
                   evidence="sampled", n_scope=[N],
                   detail=f"{len(names)} derivatives at 2 points (eta_j of either sign), worst relative difference "
                          f"{float(worst):.1e} (accepted below 1e-25)")



@claim("library.fields", equation="tra", scene="library", sizes=(3,), deep=True,
       where="symbt.codegen.derive.sources: hamiltonian_fields, flow_field and phi_grad (N={N})",
       statement="the sources of the emitted hamiltonian_fields (qdot = dH_k/dp, pdot = -dH_k/dq), flow_field "
                 "(sum_k c_k of those) and phi_grad equal central differences of the polynomial trace's H_k and of "
                 "Phi(tr L(l1), tr L(l2)) (N={N})")
@claim("library.fields", equation="tra", scene="library", sizes=(2,),
       where="symbt.codegen.derive.sources: hamiltonian_fields, flow_field and phi_grad (N={N})",
       statement="the sources of the emitted hamiltonian_fields (qdot = dH_k/dp, pdot = -dH_k/dq), flow_field "
                 "(sum_k c_k of those) and phi_grad equal central differences of the polynomial trace's H_k and of "
                 "Phi(tr L(l1), tr L(l2)) (N={N})")
def field_sources(N: int) -> Outcome:
    from ..codegen.verify import evaluate_source, map_states

    worst = mp.mpf(0)
    where: dict[str, object] | None = None
    states = map_states(N)[:2] + map_states(N)[-1:]
    with mp.workdps(DPS):
        for p, q, l0, m in states:
            pt = {"p": p, "q": q}
            qdot_pdot = evaluate_source(N, "hamiltonian_fields", pt, dps=DPS)
            P, Q = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]

            def H(k, which, i, s):
                pp, qq = list(P), list(Q)
                (pp if which == "p" else qq)[i] = s
                return hamiltonians(pp, qq)[k]

            cs = [mp.mpf(k + 1) / 7 - mp.mpf(1) / 3 for k in range(N)]   # c_k of the flow field: any numbers
            flow = evaluate_source(N, "flow_field", {"c": [float(v) for v in cs], "p": p, "q": q}, dps=DPS)
            cs = [mp.mpf(float(v)) for v in cs]
            comb = [mp.mpf(0)] * (2 * N)
            for k in range(N):
                for i in range(N):
                    for which, off, sign in (("p", 0, 1), ("q", N * N, -1)):
                        fd = sign * mp.diff(lambda s: H(k, which, i, s), (P if which == "p" else Q)[i])
                        comb[(0 if which == "p" else N) + i] += cs[k] * fd
                        r = _rel(qdot_pdot[off + k * N + i], fd)
                        if r > worst:
                            worst, where = r, {"field": f"{'qdot' if which == 'p' else 'pdot'}[{k},{i}]", "p": p,
                                               "q": q}
            for i in range(2 * N):
                r = _rel(flow[i], comb[i])
                if r > worst:
                    worst, where = r, {"field": f"flow_field {'qdot' if i < N else 'pdot'}[{i % N}]", "p": p, "q": q}
            for b in (1, -1):
                grad = evaluate_source(N, "phi_grad", {"p": p, "q": q, "lam0": l0, "mu": m, "branch": b}, dps=DPS)

                def phi(which, i, s, b=b):
                    pp, qq = list(P), list(Q)
                    (pp if which == "p" else qq)[i] = s
                    return phi_from_traces(trace(mp.mpf(l0) + mp.mpf(m), pp, qq),
                                           trace(mp.mpf(l0) - mp.mpf(m), pp, qq), b)

                for i in range(N):
                    for which, off in (("p", 0), ("q", N)):
                        fd = mp.diff(lambda s: phi(which, i, s), (P if which == "p" else Q)[i])
                        r = _rel(grad[off + i], fd)
                        if r > worst:
                            worst, where = r, {"field": f"dPhi/d{which}{i + 1}", "branch": b, "p": p, "q": q}
    if worst > TOL:
        return failed(f"numeric: central differences at {DPS} digits", residual=float(worst), counterexample=where,
                      detail=f"a source of codegen.derive differs from the differences by {float(worst):.2e} "
                             f"(relative to max(1, |value|); accepted below 1e-25)")
    return Outcome("verified", f"numeric: central differences (mpmath.diff) at {DPS} digits", residual=float(worst),
                   evidence="sampled", n_scope=[N],
                   detail=f"hamiltonian_fields ({2 * N * N} entries), flow_field (c_k = (k + 1)/7 - 1/3) and "
                          f"phi_grad ({2 * N} entries, b = +-1) at {len(states)} states against the polynomial trace "
                          f"and Phi of the traces; worst relative difference {float(worst):.1e} (accepted below 1e-25)")


@claim("library.spectral", equation="newkmu", scene="library", N=2,
       where="symbt.reference.spectral (phi_real, phi_gradient, flow_coefficients_mp's band check) and "
             "symbt.reference.samples.admissible_states",
       statement="admissible_states(N, s) gives states with s tr L(lambda_i) > 2.2 and a real map for b = +-1 "
                 "(RuntimeError for 5 states from max_proposals = 3); "
                 "phi_real = sum_k ln|(eta_k + mu)/(eta_k - mu)| of the literal map; phi_gradient = central "
                 "differences of phi_real; flow_coefficients_mp refuses an interval that contains a band (N=2)")
def spectral_routines() -> Outcome:
    from ..reference.literal import literal_step
    from ..reference.samples import admissible_states
    from ..reference.spectral import NoRealFlowError, flow_coefficients_mp, phi_gradient, phi_real

    N = 2
    worst, where = mp.mpf(0), None
    # a proposal whose literal step raises is not admissible (no information): a sign other than +-1
    from ..reference.samples import _real_map
    if _real_map([mp.mpf(1), mp.mpf(2)], [mp.mpf(0), mp.mpf(0)], mp.mpf(5), mp.mpf(1), 0) != (False, None):
        return failed("admissible_states", detail="a proposal whose literal step raises was admitted")
    # nor one whose lam1, lam2 lie across a band (some Etilde_j <= 0: the paper's state at lam0 = -2, mu = 2.5)
    across = _real_map([mp.mpf(-20), mp.mpf(10), mp.mpf(1)], [mp.mpf(1), mp.mpf(0), mp.mpf("0.9")], mp.mpf(-2),
                       mp.mpf("2.5"), 1)
    if across[0] or across[1] is None or min(across[1]["E_new"]) > 0:
        return failed("admissible_states", detail="a proposal with some Etilde_j <= 0 was admitted")
    # the sampler gives up after max_proposals proposals (three cannot give five admissible states)
    try:
        admissible_states(N, 1, 5, max_proposals=3)
        return failed("admissible_states", detail="five states from three proposals")
    except RuntimeError:
        pass
    with mp.workdps(DPS):
        for s in (1, -1):
            for p, q, l0, m in admissible_states(N, s, 1):
                t1, t2 = trace(l0 + m, p, q), trace(l0 - m, p, q)   # the polynomial trace, not the sampler's
                if not (s * t1 > 2.2 and s * t2 > 2.2):
                    return failed("admissible_states", counterexample={"sign_tr": s, "tr1": mp.nstr(t1, 8),
                                                                       "tr2": mp.nstr(t2, 8)},
                                  detail="a sampled state's traces are not of the sign asked for")
                for b in (1, -1):
                    info = literal_step(p, q, l0, m, b)[2]
                    if not all(mp.im(e) == 0 and e > 0 for e in info["E_new"]):
                        return failed("admissible_states", detail=f"no real map at a sampled state, branch {b}")
                    lit = mp.fsum(mp.log(abs((e + m) / (e - m))) for e in info["eta"])
                    r = _rel(phi_real(p, q, l0, m, b), lit)
                    if r > worst:
                        worst, where = r, {"what": "phi_real", "sign_tr": s, "branch": b}
                    gp, gq = phi_gradient(p, q, l0, m, b)
                    for i in range(N):
                        for which, g in (("p", gp[i]), ("q", gq[i])):
                            def f(x, which=which, i=i, b=b):
                                pp, qq = list(p), list(q)
                                (pp if which == "p" else qq)[i] = x
                                return phi_real(pp, qq, l0, m, b)
                            r = _rel(g, mp.diff(f, (p if which == "p" else q)[i]))
                            if r > worst:
                                worst, where = r, {"what": f"phi_gradient d/d{which}{i + 1}", "sign_tr": s,
                                                   "branch": b}
        # a band inside [lam0 - mu, lam0 + mu] with both ends in gaps (|tr| > 2 there)
        p0, q0, l0, m = [mp.mpf(0)] * N, [mp.mpf(0)] * N, mp.mpf(0), mp.mpf(10)
        grid = [trace(l0 - m + 2 * m * k / 400, p0, q0) for k in range(401)]
        if not (abs(grid[0]) > 2 and abs(grid[-1]) > 2 and min(abs(v) for v in grid) <= 2):
            return failed("control", detail="the control interval is not a band between two gaps")
        try:
            flow_coefficients_mp(p0, q0, l0, m)
            return failed("flow_coefficients_mp", detail="c_k returned over [-10, 10], which contains a band of "
                                                         "p = q = 0 (|tr L| <= 2 at a grid point)")
        except NoRealFlowError:
            pass
    if worst > TOL:
        return failed(f"numeric: {DPS} digits", residual=float(worst), counterexample=where,
                      detail=f"phi_real or phi_gradient differs from its independent route by {float(worst):.2e}")
    return Outcome("verified", f"numeric: literal map and central differences at {DPS} digits",
                   residual=float(worst), evidence="sampled", n_scope=[N],
                   detail=f"states of each sign of tr (polynomial trace), b = +-1: phi_real vs the literal eta "
                          f"form, phi_gradient vs differences, worst relative {float(worst):.1e} (accepted below "
                          f"1e-25); flow_coefficients_mp refuses [-10, 10] at p = q = 0 (a band inside, the ends "
                          f"in gaps)")


@claim("library.symbols", equation="newgf", scene="library", N=2,
       where="symbt.symbolic.generating.GeneratingFunction (E, Et, eta) and symbt.symbolic.darboux (lambda0, mu)",
       statement="the library's symbols have their documented assumptions, as SymPy infers from them: lambda0 (ln E_j "
                 "- ln E~_j) is real, sqrt(eta_j^2) = |eta_j|, lambda0 +- mu is real, and Symbol('E1', positive=True) "
                 "is the library's E_1 (F at a state given by name is a number)")
def symbol_assumptions() -> Outcome:
    from ..symbolic.generating import GeneratingFunction

    # a fresh instance, not generating_function's cached one: the symbols are this claim's own (and symbt mutate
    # --source's line map credits it with the lines that make them)
    g = GeneratingFunction(2)
    checks = {
        "lambda0 (ln E_j - ln E~_j) is real": all((g.lam0 * (sp.log(E) - sp.log(Et))).is_real is True
                                                  for E, Et in zip(g.E, g.Et)),
        "sqrt(eta_j^2) = |eta_j|": all(sp.sqrt(e ** 2) == sp.Abs(e) for e in g.eta),
        "lambda0 +- mu is real": (lam0 + mu).is_real is True and (lam0 - mu).is_real is True,
    }
    # a state given by name: E_j = e^{q_j}, E~_j = e^{q~_j} with q~_j < q_j, eta_j > 0 from its relation
    by_name = {sp.Symbol(f"E{j + 1}", positive=True): sp.exp(sp.Rational(j, 3)) for j in range(2)}
    by_name.update({sp.Symbol(f"Et{j + 1}", positive=True): sp.exp(sp.Rational(j, 3) - 1) for j in range(2)})
    by_name.update({sp.Symbol("mu", real=True): sp.Rational(1, 2), sp.Symbol("lambda0", real=True): sp.Rational(1, 3)})
    eta_vals = {sp.Symbol(f"eta{j + 1}", real=True): sp.sqrt((sp.Rational(1, 2) ** 2 + g.w(j)).xreplace(by_name))
                for j in range(2)}
    value = g.F.xreplace({**by_name, **eta_vals})
    checks["F at a state given by name is a number"] = not value.free_symbols and value.evalf(20).is_real is True
    bad = [k for k, ok in checks.items() if not ok]
    if bad:
        return failed("SymPy assumptions", detail="; ".join(bad))
    return Outcome("verified", "exact: SymPy's inference from the symbols' assumptions", evidence="proof",
                   n_scope="all", detail="; ".join(checks))


@claim("library.linear", equation="l1l2", scene="library",
       where="symbt.symbolic.linear.solve_linear (the eigen-equations and transports of the derivations)",
       statement="solve_linear gives -b/a for a x + b = 0, no root for the constant equation a + 1 = 0 and for "
                 "(a - a) x + 1 = 0, and sympy.solve's roots for x^2 = 4; a x + b = 0 and x - b = 0 are solved "
                 "without calling sympy.solve")
def linear_solutions() -> Outcome:
    from ..symbolic.linear import solve_linear

    a, bb, xx = sp.symbols("a b x")
    cases = [("a x + b = 0", solve_linear(a * xx + bb, xx), [-bb / a]),
             ("a + 1 = 0 (no x)", solve_linear(a + 1, xx), []),
             ("0 x + 1 = 0", solve_linear(sp.Add(a * xx, -a * xx, 1, evaluate=False), xx), []),
             ("x^2 = 4", sorted(solve_linear(sp.Eq(xx ** 2, 4), xx)), [-2, 2])]
    bad = [f"{what}: {got} (want {want})" for what, got, want in cases if got != want]
    # the point of the module: a linear equation, monic or not, never reaches sympy.solve
    from unittest import mock

    def no_solve(*args: object, **kwargs: object) -> None:
        raise AssertionError("sympy.solve called")
    with mock.patch.object(sp, "solve", no_solve):
        for what, eq, want in (("a x + b = 0", a * xx + bb, [-bb / a]), ("x - b = 0", xx - bb, [bb])):
            try:
                got = solve_linear(eq, xx)
                if got != want:
                    bad.append(f"{what} without sympy.solve: {got} (want {want})")
            except AssertionError:
                bad.append(f"{what}: solve_linear called sympy.solve")
    if bad:
        return failed("solve_linear", detail="; ".join(bad))
    return Outcome("verified", "exact: solve_linear on equations of known roots", evidence="proof", n_scope="all",
                   detail="; ".join(f"{what}: {got}" for what, got, _ in cases))
