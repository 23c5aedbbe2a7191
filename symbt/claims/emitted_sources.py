r"""Zullo's code generation checked where the ``codegen`` claims do not look (scene ``library``).

The ``codegen`` claims compare the shipped ``toda{N}.py`` with :func:`symbt.codegen.derive.sources`: code
compared with what it was printed from.  These claims check what ``derive`` builds, each against a route that
shares nothing with it (issue 21, item 4: the survivors of ``symbt mutate --source codegen``,
docs/mutation.md):

* ``library.sources_step`` -- the SymPy source of ``bt_step`` for N = 3 (the paper's route, eq. ``xy``:
  ``p~_j = p_j + eta_j - eta_{j+1}``, ``q~_j = log(E_j - x_j)``), evaluated at 30 digits, against
  the literal map (:func:`symbt.reference.literal.literal_step`, 30 digits): within ``1e-20 max(1, |x|)`` at the
  states of the ``codegen`` claims, both branches.
* ``library.illcond`` -- the float64 conditioning guards of the closed form
  (:func:`symbt.codegen.transport.illcond_guards`, N = 3, evaluated at 40 digits) against the rule as documented
  (docs/codegen.md, "Ill-conditioned states are refused"), computed here with mpmath from the literal monodromy and
  the literal map's eigenvector slopes ``u_j = E_j y_j``, ``w_j = E_j z_j``: per spectral parameter the
  trace guard is exactly ``-1`` where ``T (|t| + 2)/|t^2 - 4| > KAPPA_MAX`` (``T`` the trace of
  ``|m_N| ... |m_1|``) and ``+1`` elsewhere; per site the margin
  ``KAPPA_MAX |d_j| |1 + x_j| - kt (|u_j| + |w_j|)(|1 + x_j| + |x_j|)`` agrees within ``1e-25`` of the sum of its two
  terms, ``kt`` the larger trace estimate times the cancellation ``max_j (|lambda| + |p_j|)/|lambda + p_j|``.
  States: two of the ``codegen`` claims' (both branches), one 1e-9 from a band edge (the trace guard refuses) and
  one where ``lambda_1 + p_2 = 1e-9`` (a cancellation of 5e9); the claim also checks that these two reach the
  cases they are there for.
* ``library.zullo_registry`` -- declaring a closed-form function of ``toda{N}`` (:func:`symbt.codegen.zullo.
  declaration`) leaves :data:`symbt.codegen.user.EMISSIONS` -- the user's declarations, which ``symbt codegen
  --claims`` writes and the ``emit.*`` claims check -- unchanged.

>>> zullo_registry.run().status
'verified'
"""
from __future__ import annotations

from typing import Any

import mpmath as mp
import sympy as sp

from .base import Outcome, claim, failed

STEP_TOL = mp.mpf(10) ** -20
GUARD_TOL = mp.mpf(10) ** -25
#: (p, q, lam0, mu) as decimal strings: lam_1 = 2 + 1e-9, 1e-9 above the band edge tr = 2 of the free lattice
#: (tr L = lam^3 - 3 lam); lam_1 = 2.5 = -p_2 + 1e-9
EDGE = (("0", "0", "0"), ("0", "0", "0"), "2.5000000005", "-0.4999999995")
CANCEL = (("0.3", "-2.499999999", "0.1"), ("0", "0.2", "-0.1"), "-1.75", "4.25")


@claim("library.sources_step", equation="imptransf", scene="library", N=3,
       where="symbt.codegen.derive.sources: bt_step (the paper's route), N = 3",
       statement="the SymPy source of bt_step (N = 3, eq. xy as printed) equals the literal map "
                 "(30 digits) within 1e-20 max(1, |x|), both branches")
def sources_step() -> Outcome:
    from ..codegen.verify import evaluate_source, map_states
    from ..reference.literal import literal_step

    N = 3
    worst, where = mp.mpf(0), None
    states = map_states(N)
    with mp.workdps(30):
        for p, q, l0, m in states:
            for b in (1, -1):
                got = evaluate_source(N, "bt_step", {"p": p, "q": q, "lam0": l0, "mu": m, "branch": b}, dps=30)
                pt, qt, _ = literal_step([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m), b)
                for k, (g, w) in enumerate(zip(got, list(pt) + list(qt))):
                    r = abs(g - w) / max(1, abs(w))
                    if r > worst:
                        worst, where = r, {"output": ("p~", "q~")[k // N] + str(k % N + 1), "branch": b, "p": p,
                                           "q": q, "lam0": l0, "mu": m}
    detail = (f"{len(states)} states x 2 branches, 2N outputs: worst |source - literal| / max(1, |literal|) "
              f"{float(worst):.1e} (accepted below 1e-20)")
    if worst > STEP_TOL:
        return failed("numeric: literal map at 30 digits", residual=float(worst), counterexample=where, detail=detail)
    return Outcome("verified", "numeric: literal map (symbt.reference.literal) at 30 digits", residual=float(worst),
                   evidence="sampled", n_scope=[N], detail=detail)


def documented_rule(p: list[Any], q: list[Any], lam0: Any, mu: Any, traces: tuple[Any, Any], u: list[Any],
                    w: list[Any], d: list[Any]) -> tuple[list[int], list[tuple[Any, Any]], list[Any], Any]:
    """docs/codegen.md's conditioning test, with mpmath: ``(trace guards +-1, [(site margin, its scale)],
    [trace estimates], the largest cancellation)``."""
    from ..numeric.core.limits import KAPPA_MAX

    N, K = len(p), mp.mpf(KAPPA_MAX)
    ks, cancel = [], []
    for lam, t in zip((lam0 + mu, lam0 - mu), traces):
        T = mp.eye(2)
        for j in range(N):
            T = mp.matrix([[abs(lam + p[j]), 1], [mp.exp(q[(j + 1) % N] - q[j]), 0]]) * T
        ks.append((T[0, 0] + T[1, 1]) * (abs(t) + 2) / abs(t ** 2 - 4))
        cancel.append(max((abs(lam) + abs(pj)) / abs(lam + pj) for pj in p))
    kt = max(k * c for k, c in zip(ks, cancel))
    sites = []
    for j in range(N):
        x = -2 * mu / d[j]
        a, b = K * abs(d[j]) * abs(1 + x), kt * (abs(u[j]) + abs(w[j])) * (abs(1 + x) + abs(x))
        sites.append((a - b, a + b))
    return [-1 if k > K else 1 for k in ks], sites, ks, max(cancel)


@claim("library.illcond", equation="imptransf", scene="library", N=3,
       where="symbt.codegen.transport.illcond_guards (the emitted closed form's IllConditionedError guards)",
       statement="the conditioning guards of the emitted closed form (N = 3) are the documented rule (docs/codegen.md) "
                 "computed from the literal monodromy and slopes: trace guards exactly -1/+1, site margins within "
                 "1e-25 of their scale, at a band edge and at a cancellation lambda_1 + p_2 = 1e-9 too")
def illcond() -> Outcome:
    from ..codegen.transport import illcond_guards
    from ..codegen.verify import map_states
    from ..numeric.core.limits import KAPPA_MAX
    from ..reference.literal import literal_step
    from ..symbolic.darboux import lam0 as L0
    from ..symbolic.darboux import mu as MU
    from ..symbolic.toda import toda_model

    N, dps = 3, 40
    m = toda_model(N)
    t = sp.symbols("t1 t2", real=True)
    u, w, d = (list(sp.symbols(f"{c}1:{N + 1}", real=True)) for c in "uwd")
    ill_t, ill_s = illcond_guards(m, lambda c, label, e, stage: e, t, u, w, d, lambda x: (x - 2) * (x + 2))
    args = [*m.p, *m.q, L0, MU, *t, *u, *w, *d]
    # Quotient (IEEE-style a/b in the emitted code) divides plainly here: every denominator is finite and nonzero
    fns = [sp.lambdify(args, g, modules=[{"Quotient": lambda a, b: a / b}, "mpmath"]) for g in ill_t + ill_s]
    with mp.workdps(dps):
        states = [([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(mu_), b)
                  for p, q, l0, mu_ in map_states(N)[:2] for b in (1, -1)]
        states += [([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(mu_), 1)
                   for p, q, l0, mu_ in (EDGE, CANCEL)]
        worst, bad, notes = mp.mpf(0), [], []
        for k, (p, q, l0, mu_, b) in enumerate(states):
            info = literal_step(p, q, l0, mu_, b)[2]
            U = [mp.exp(q[j]) * info["y"][j] for j in range(N)]
            W = [mp.exp(q[j]) * info["z"][j] for j in range(N)]
            D = [W[j] - U[j] for j in range(N)]
            tr = (info["tr1"], info["tr2"])
            if not all(isinstance(v, mp.mpf) for v in U + W + list(tr)):
                bad.append(f"state {k}: the literal slopes are not real")
                continue
            got = [mp.mpf(f(*p, *q, l0, mu_, *tr, *U, *W, *D)) for f in fns]
            want_t, sites, ks, cancel = documented_rule(p, q, l0, mu_, tr, U, W, D)
            if got[:2] != want_t:
                bad.append(f"state {k}: trace guards {[mp.nstr(v, 3) for v in got[:2]]}, the rule gives {want_t} "
                           f"(estimates {[mp.nstr(v, 3) for v in ks]}, KAPPA_MAX {KAPPA_MAX:g})")
            for j, (g, (margin, scale)) in enumerate(zip(got[2:], sites)):
                r = abs(g - margin) / scale
                worst = max(worst, r)
                if r > GUARD_TOL:
                    bad.append(f"state {k}, site {j + 1}: margin {mp.nstr(g, 8)}, the rule gives {mp.nstr(margin, 8)}")
            if (p, q) == tuple([mp.mpf(v) for v in x] for x in EDGE[:2]):
                notes.append(f"band edge: estimate {mp.nstr(max(ks), 3)}, guards {want_t}")
                if -1 not in want_t:
                    bad.append("the band-edge state does not reach an ill-conditioned trace")
            if k == len(states) - 1:
                notes.append(f"cancellation {mp.nstr(cancel, 3)}")
                if cancel < 1e9:
                    bad.append(f"the cancellation state's largest cancellation is only {mp.nstr(cancel, 3)}")
    detail = (f"{len(states)} states: {2 + N} guards each vs the documented rule; worst site margin difference "
              f"{float(worst):.1e} of its scale (accepted below 1e-25); " + "; ".join(notes))
    if bad:
        return failed("numeric: documented rule from the literal map at 40 digits", residual=float(worst),
                      detail="; ".join(bad[:6]) + "; " + detail)
    return Outcome("verified", "numeric: documented rule from the literal map at 40 digits", residual=float(worst),
                   evidence="sampled", n_scope=[N], detail=detail)


@claim("library.zullo_registry", equation="checker", scene="library", N=3,
       where="symbt.codegen.zullo.declaration (Zullo's toda{N} functions as symbt.emit declarations)",
       statement="declaring Zullo's closed-form functions (toda3) and the loop form's (toda4) leaves the user's "
                 "registry symbt.codegen.user.EMISSIONS unchanged")
def zullo_registry() -> Outcome:
    from dataclasses import replace

    from ..codegen import derive, zullo
    from ..codegen.user.declare import EMISSIONS

    # two functions of toda3's interface with stand-in expressions (the registry is what is checked, not the
    # derivation: derive.specs(3) would cost seconds)
    face = derive.interface(3)
    p = face["invariants"].args[0].symbols
    inv = replace(face["invariants"], outputs=(replace(face["invariants"].outputs[0], exprs=tuple(p)),))
    t1, t2 = (a.symbols[0] for a in face["phi_tr"].args[:2])
    phi = replace(face["phi_tr"], outputs=(replace(face["phi_tr"].outputs[0], exprs=(t1 + t2,)),),
                  guards=tuple(replace(g, expr=(t - 2) * (t + 2)) for g, t in zip(face["phi_tr"].guards, (t1, t2))))
    before = dict(EMISSIONS)
    made = [zullo.declaration(s, 3) for s in (inv, phi)]
    loops, _ = zullo.loop_declarations(4)
    after = dict(EMISSIONS)
    if after.keys() != before.keys() or any(after[k] is not before[k] for k in before):
        added = sorted(set(after) - set(before))
        return failed("symbt.codegen.zullo.declaration", detail=f"EMISSIONS changed: added {added}")
    if [(e.module, e.name, e.typed) for e in made] != [("toda3", "invariants", True), ("toda3", "phi_tr", True)]:
        return failed("symbt.codegen.zullo.declaration",
                      detail=f"declared {[(e.module, e.name, e.typed) for e in made]}")
    if {e.module for e in loops} != {"toda4"} or len(loops) != len(derive.FUNCTIONS):
        return failed("symbt.codegen.zullo.loop_declarations",
                      detail=f"declared {sorted((e.module, e.name) for e in loops)}")
    return Outcome("verified", "EMISSIONS compared before and after", evidence="proof", n_scope=[3, 4],
                   detail=f"toda3.invariants and toda3.phi_tr declared (typed), and toda4's {len(loops)} loop "
                          f"functions; EMISSIONS keeps its {len(before)} entries")
