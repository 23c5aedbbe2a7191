r"""Code generation observed function by function: both builds of :mod:`symbt.codegen.derive`, the user path.

Scene ``library`` (issue 21, item 4: fresh samples of ``symbt mutate --source codegen.derive codegen.user``,
docs/mutation.md).  Each claim observes *whole* functions across their branches against a route that shares
nothing with the code under test -- the literal map and the literal trace of :mod:`symbt.reference.literal` at
high precision, central differences of them, SymPy's own rewriting, Python's arithmetic on dyadic numbers -- or an
exact fact:

* ``library.specs_literal`` (N = 2; ``library.specs_literal_n3`` under ``--deep``, N = 3, 2-3 s) --
  :func:`symbt.codegen.derive.specs`, the closed forms the emitted modules are printed from,
  evaluated at 40 digits (every ``Piecewise`` by its selected piece, ``Quotient`` IEEE-style):
  every output of every function against the reference (below) within ``1e-22 max(1, |x|)``; the guards of the
  map's functions in the order ``_with_guards`` documents (conditioning before each trace, the gap sign, the
  ``range`` guards ``u_j, w_j, d_j``, the slopes' conditioning, the positivity of ``E~_j``; stages 0 and 1) with
  the values ``tr_i^2 - 4``, ``sign(tr_1) sign(tr_2)``, ``u_j = E_j y_j``, ``w_j = E_j z_j``,
  ``d_j = w_j - u_j`` (the scaled slopes of the literal map) and ``E~_j/E_j``; the conditioning
  guards positive at these well-conditioned states.  Off the map: a state whose ``lambda_1`` lies in a band
  (``tr_1^2 - 4 < 0``), one whose traces have opposite signs (gap guard ``-1``), a ``lambda`` in a band for the
  ``c_k`` integrand, traces ``|tr| < 2`` for ``phi_tr``: the guard values there too; and at 10 seeded random states,
  on and off the map, the closed form's trace guards and gap sign (the traces it *decides* with: a trace read from
  the wrong entry changes only which transport runs, not a value at 40 digits, but it flips the gap sign).
* ``library.sources_literal`` (N = 2; ``library.sources_literal_n3`` under ``--deep``) --
  :func:`symbt.codegen.derive.sources` (the paper's route): every output and every guard of every
  function (:func:`symbt.codegen.verify.evaluate_source`, 40 digits) against the same reference.

The reference, per function: ``H_k`` the coefficients of the literal ``tr L(lambda)`` (solved from ``N + 1``
values); the fields ``dH_k/dp_j``, ``-dH_k/dq_j`` and the gradient of ``Phi`` by central differences of the
literal trace at 60 digits (step ``1e-22``: truncation ~1e-44, rounding ~1e-38); ``Phi = -b (sgn(t_1)
arccosh(|t_1|/2) + sgn(t_2) arccosh(|t_2|/2))`` written out here; ``lambda^k / sqrt(tr^2 - 4)``; ``x, y`` and the
step from :func:`~symbt.reference.literal.literal_step` (self-agreement at 40 and 60 digits required).  The bound
``1e-22`` leaves 18 of the 40 digits to cancellation (the states' condition numbers are below 1e6); a planted slip
moves a value by O(1).

The user path (:mod:`symbt.codegen.user`): see :mod:`symbt.claims.library_user_file`.

>>> specs_literal.run().status
'verified'
"""
from __future__ import annotations

import random
from functools import cache
from typing import Any

import mpmath as mp

from .base import Outcome, claim, failed

TOL = mp.mpf(10) ** -22
DPS = 40
#: the order of the map's guards, written out from ``_with_guards``' docstring (N sites)
ORDER = lambda N: (["illcond", "trace", "illcond", "trace", "positivity"] + ["range"] * (3 * N)  # noqa: E731
                   + ["illcond"] * N)


def _trace(lam: Any, p: list[Any], q: list[Any]) -> Any:
    from ..reference.literal import literal_trace

    return literal_trace(lam, p, q)


def trace_invariants(p: list[Any], q: list[Any]) -> list[Any]:
    """``H_0 .. H_{N-1}``: ``tr L(lambda) - lambda^N`` at ``lambda = 0 .. N - 1`` solved for its coefficients."""
    N = len(p)
    V = mp.matrix([[mp.mpf(k) ** i for i in range(N)] for k in range(N)])
    rhs = mp.matrix([_trace(k, p, q) - mp.mpf(k) ** N for k in range(N)])
    return list(mp.lu_solve(V, rhs))


def _sa(t: Any) -> Any:
    return mp.sign(t) * mp.acosh(abs(t) / 2)


def _phi(p: list[Any], q: list[Any], l0: Any, m: Any, b: int) -> Any:
    return -b * (_sa(_trace(l0 + m, p, q)) + _sa(_trace(l0 - m, p, q)))


def _grad(f: Any, p: list[Any], q: list[Any]) -> tuple[list[Any], list[Any]]:
    """Central differences of ``f(p, q)`` (a list of values) at 60 digits, step 1e-22: ``(d/dp_j, d/dq_j)``."""
    with mp.workdps(60):
        h = mp.mpf(10) ** -22
        out = []
        for which in (0, 1):
            cols = []
            for j in range(len(p)):
                xs = [list(p), list(q)]
                xs[which][j] += h
                plus = f(*xs)
                xs[which][j] -= 2 * h
                minus = f(*xs)
                cols.append([(a - c) / (2 * h) for a, c in zip(plus, minus)])
            out.append(cols)
    return out[0], out[1]


def reference(name: str, pt: dict[str, Any]) -> tuple[list[Any], list[Any] | None]:
    """(outputs, guard values of the paper's route or None) of the function ``name`` at ``pt``, independently."""
    from ..reference.literal import literal_step

    if name == "phi_tr":
        t1, t2, b = pt["tr1"], pt["tr2"], pt["branch"]
        return [-b * (_sa(t1) + _sa(t2))], [t1 ** 2 - 4, t2 ** 2 - 4]
    if name in ("spectral_trace", "ck_integrand"):
        t = _trace(pt["lam"], pt["p"], pt["q"])
        N = len(pt["p"])
        if name == "spectral_trace":
            return [t], None
        return [pt["lam"] ** k / mp.sqrt(t ** 2 - 4) for k in range(N)], [t ** 2 - 4]
    p, q = pt["p"], pt["q"]
    N = len(p)
    if name == "invariants":
        return trace_invariants(p, q), None
    if name in ("hamiltonian_fields", "flow_field"):
        dp, dq = _grad(trace_invariants, p, q)          # dp[j][k] = dH_k/dp_j
        qd = [dp[j][k] for k in range(N) for j in range(N)]
        pd = [-dq[j][k] for k in range(N) for j in range(N)]
        if name == "hamiltonian_fields":
            return qd + pd, None
        c = pt["c"]
        return ([mp.fsum(c[k] * qd[k * N + j] for k in range(N)) for j in range(N)]
                + [mp.fsum(c[k] * pd[k * N + j] for k in range(N)) for j in range(N)]), None
    l0, m, b = pt["lam0"], pt["mu"], pt["branch"]
    tg = [_trace(l0 + m, p, q) ** 2 - 4, _trace(l0 - m, p, q) ** 2 - 4]
    if name == "phi":
        return [_phi(p, q, l0, m, b)], tg
    if name == "phi_grad":
        gp, gq = _grad(lambda P, Q: [_phi(P, Q, l0, m, b)], p, q)
        return [g[0] for g in gp] + [g[0] for g in gq], tg
    pn, qn, info = literal_step(p, q, l0, m, b)
    if name == "dapp_xy":
        return [info["x"][0], info["y"][0]], tg
    return list(pn) + list(qn), tg + [e / mp.exp(v) for e, v in zip(info["E_new"], q)]


def points(N: int, name: str) -> list[dict[str, Any]]:
    """The arguments of ``name`` (mpf): the ``codegen`` claims' map states x both branches, seeded random states
    and coefficients, both spectral parameters, traces of every sign."""
    from ..codegen.verify import map_states

    rng = random.Random(4099 * N + len(name))
    mk = lambda v: [mp.mpf(x) for x in v]  # noqa: E731
    states = [(mk(p), mk(q), mp.mpf(l0), mp.mpf(m)) for p, q, l0, m in map_states(N, per_sign=1)]
    if name == "phi_tr":
        return [dict(tr1=mp.mpf(s1 * rng.uniform(2.2, 30)), tr2=mp.mpf(s2 * rng.uniform(2.2, 30)), branch=b)
                for s1 in (1, -1) for s2 in (1, -1) for b in (1, -1)]
    if name in ("spectral_trace", "ck_integrand"):
        return [dict(lam=lv, p=p, q=q) for p, q, l0, m in states for lv in (l0 + m, l0 - m)]
    if name in ("invariants", "hamiltonian_fields", "flow_field"):
        out = [dict(p=mk(rng.uniform(-2, 2) for _ in range(N)), q=mk(rng.uniform(-1, 1) for _ in range(N)),
                    c=mk(rng.uniform(-1, 1) for _ in range(N))) for _ in range(2)]
        return out
    return [dict(p=p, q=q, lam0=l0, mu=m, branch=b) for p, q, l0, m in states for b in (1, -1)]


def _close(got: list[Any], want: list[Any], tol: Any = TOL) -> Any:
    if len(got) != len(want):
        return mp.inf
    return max((abs(g - w) / max(1, abs(w)) for g, w in zip(got, want)), default=mp.mpf(0))


#: (function, point) -> the reference: it shares nothing with the code under test, so the claims share it
_REFS: dict[tuple[str, str], Any] = {}


def _stable(name: str, pt: dict[str, Any]) -> tuple[list[Any], list[Any] | None] | None:
    """The reference at 40 digits; for the map (where the literal route subtracts) None where it disagrees with
    itself at 60 digits beyond 1e-30."""
    key = (name, repr(sorted(pt.items())))
    if key not in _REFS:
        _REFS[key] = _reference_at(name, pt)
    return _REFS[key]


def _reference_at(name: str, pt: dict[str, Any]) -> tuple[list[Any], list[Any] | None] | None:
    with mp.workdps(DPS):
        want = reference(name, pt)
    if name not in ("dapp_xy", "bt_step"):
        return want
    with mp.workdps(60):
        hi = reference(name, pt)
    if _close(want[0], hi[0]) > mp.mpf(10) ** -30:
        return None
    return want


@cache
def _off_states(N: int) -> list[tuple[str, dict[str, Any]]]:
    """Where the map does not exist, at ``p = (0.13, -0.07, ..)``, ``q = (0, .., 0, 1.5)``: ``lambda_1`` in a band
    (``|tr| < 1.5``), and ``tr L(lambda_1) > 2.5``, ``tr L(lambda_2) < -2.5`` (opposite signs: two gaps), the
    ``lambda`` found on the grid ``k/4`` (the check then requires each state to reach its case)."""
    p = [mp.mpf(13 - 20 * (j % 2)) / 100 for j in range(N)]
    q = [mp.mpf(0)] * (N - 1) + [mp.mpf("1.5")]
    grid = [(mp.mpf(k) / 4, _trace(mp.mpf(k) / 4, p, q)) for k in range(-16, 17)]
    band = next(lv for lv, t in grid if abs(t) < mp.mpf("1.5"))
    hi = next(lv for lv, t in reversed(grid) if t > mp.mpf("2.5"))
    lo = next((lv for lv, t in grid if t < mp.mpf("-2.5")), hi - 1)
    return [(case, dict(p=p, q=q, lam0=(l1 + l2) / 2, mu=(l1 - l2) / 2, branch=b))
            for case, l1, l2 in (("band", band, band - 1), ("gap", hi, lo)) for b in (1, -1)]


def _env(spec: Any, pt: dict[str, Any]) -> dict[Any, Any]:
    env: dict[Any, Any] = {}
    for a in spec.args:
        vals = pt[a.name] if a.kind == "state" else [pt[a.name]]
        env.update({s: (int(v) if a.kind == "branch" else mp.mpf(v)) for s, v in zip(a.symbols, vals)})
    return env


def _scaled(pt: dict[str, Any]) -> list[Any]:
    """``u_j = E_j y_j``, ``w_j = E_j z_j``, ``d_j = w_j - u_j`` of the literal map (the scaled slopes)."""
    from ..reference.literal import literal_step

    p, q = pt["p"], pt["q"]
    info = literal_step(p, q, pt["lam0"], pt["mu"], pt["branch"])[2]
    u = [mp.exp(v) * y for v, y in zip(q, info["y"])]
    w = [mp.exp(v) * z for v, z in zip(q, info["z"])]
    return u + w + [b - a for a, b in zip(u, w)]


def check_specs(N: int) -> Outcome:
    """``library.specs_literal``: the closed forms of ``derive.specs(N)`` against the reference."""
    from ..codegen import derive
    from ..codegen.verify import interpret

    specs = {s.name: s for s in derive.specs(N)}
    bad: list[str] = []
    worst, n = mp.mpf(0), 0
    with mp.workdps(DPS):
        for name, s in specs.items():
            conds = [g.condition for g in s.guards]
            if name in ("dapp_xy", "bt_step"):
                want_c = ORDER(N) + (["positivity"] * N if name == "bt_step" else [])
                stages = [g.stage for g in s.guards]
                want_s = [0] * 5 + [1] * (len(conds) - 5)
                if conds != want_c or stages != want_s:
                    bad.append(f"{name}: guards {list(zip(conds, stages))}, documented {list(zip(want_c, want_s))}")
                    continue
            for pt in points(N, name):
                ref = _stable(name, pt)
                if ref is None:
                    bad.append(f"{name}: the reference is unstable at {pt}")
                    continue
                env, memo = _env(s, pt), dict[Any, Any]()
                got = [interpret(e, env, memo) for o in s.outputs for e in o.exprs]
                gv = [interpret(g.expr, env, memo) for g in s.guards]
                r = _close(got, ref[0])
                if name in ("dapp_xy", "bt_step"):
                    tg = [gv[1], gv[3], gv[4]] + gv[5:5 + 3 * N] + gv[5 + 4 * N:]
                    t1 = _trace(pt["lam0"] + pt["mu"], pt["p"], pt["q"])
                    t2 = _trace(pt["lam0"] - pt["mu"], pt["p"], pt["q"])
                    tr = ref[1] or []
                    want_g = tr[:2] + [mp.sign(t1) * mp.sign(t2)] + _scaled(pt) + tr[2:]
                    r = max(r, _close(tg, want_g))
                    ill = [v for c, v in zip(conds, gv) if c == "illcond"]
                    if not all(v > 0 for v in ill):
                        bad.append(f"{name}: a conditioning guard <= 0 at a well-conditioned state {pt}: {ill}")
                elif ref[1] is not None:
                    r = max(r, _close(gv, ref[1]))
                n += 1
                if r > worst:
                    worst = r
                if r > TOL:
                    bad.append(f"{name} at {_brief(pt)}: off by {mp.nstr(r, 3)}")
            if name in ("phi_tr", "ck_integrand", "bt_step"):   # phi, phi_grad, dapp_xy: the same guard expressions
                bad += _off_map(N, s, name)
            if name == "bt_step":
                bad += _decisions(N, s)
    detail = f"{n} points over {len(specs)} functions (outputs and guards), worst {mp.nstr(worst, 3)} (bound 1e-22); " \
             f"trace and gap-sign guards at {RANDOM} random states"
    if bad:
        return failed("numeric: literal map and trace (symbt.reference.literal) at 40 digits",
                      residual=float(worst), detail="; ".join(bad[:6]) + "; " + detail)
    return Outcome("verified", "numeric: literal map and trace (symbt.reference.literal), central differences, at "
                   "40 digits", residual=float(worst), evidence="sampled", n_scope=[N], detail=detail)


def _brief(pt: dict[str, Any]) -> str:
    return ", ".join(f"{k}={[mp.nstr(x, 4) for x in v] if isinstance(v, list) else mp.nstr(v, 4)}"
                     for k, v in pt.items())


def _off_cases(N: int, name: str) -> list[tuple[str, dict[str, Any]]]:
    """Where the real function ``name`` does not exist: traces ``|tr| < 2`` for ``phi_tr``, a ``lambda`` in a band
    for the integrand, else the band and gap states of :func:`_off_states`."""
    if name == "phi_tr":
        return [("band", dict(tr1=mp.mpf("1.5"), tr2=mp.mpf(3), branch=1)),
                ("band", dict(tr1=mp.mpf(-5), tr2=mp.mpf("-0.5"), branch=-1))]
    if name == "ck_integrand":
        band = _off_states(N)[0][1]
        return [("band", dict(lam=band["lam0"] + band["mu"], p=band["p"], q=band["q"]))]
    return _off_states(N)


def _off_reference(name: str, pt: dict[str, Any]) -> list[Any]:
    """The trace guards ``tr^2 - 4`` (and, for the closed form, the gap sign) where the function does not exist."""
    if name in ("phi_tr", "ck_integrand"):
        return reference(name, pt)[1] or []
    t1 = _trace(pt["lam0"] + pt["mu"], pt["p"], pt["q"])
    t2 = _trace(pt["lam0"] - pt["mu"], pt["p"], pt["q"])
    return [t1 ** 2 - 4, t2 ** 2 - 4, mp.sign(t1) * mp.sign(t2)]


def _off_map(N: int, s: Any, name: str) -> list[str]:
    """Guard values of the closed form ``s`` where the real function does not exist (traces, gap sign)."""
    from ..codegen.verify import interpret

    bad = []
    for case, pt in _off_cases(N, name):
        env, memo = _env(s, pt), dict[Any, Any]()
        want = _off_reference(name, pt)
        if name in ("phi_tr", "ck_integrand", "phi", "phi_grad"):
            idx = list(range(len(s.guards)))
        else:   # conditioning, trace, conditioning, trace, gap sign; the gap sign only where both traces are real
            idx = [1, 3, 4] if case == "gap" else [1, 3]
            t1, t2 = (want[0] + 4, want[1] + 4)
            if not (case == "band" and t1 < 4 or case == "gap" and want[2] < 0):
                bad.append(f"the {case} state does not reach its case: tr1^2 = {mp.nstr(t1, 5)}, "
                           f"tr2^2 = {mp.nstr(t2, 5)}")
        got = [interpret(s.guards[i].expr, env, memo) for i in idx]
        if _close(got, want[:len(idx)]) > TOL:
            bad.append(f"{name}: guards {[mp.nstr(v, 5) for v in got]} at the {case} state {_brief(pt)}, "
                       f"reference {[mp.nstr(v, 5) for v in want]}")
    return bad


#: random states (p, q, lambda_0, mu, b) at which the closed form's stage-0 decisions are compared
RANDOM = 10


def _decisions(N: int, s: Any) -> list[str]:
    """The trace guards ``tr_i^2 - 4`` and the gap sign ``sign(tr_1) sign(tr_2)`` of the closed form ``s`` at seeded
    random states, on and off the map (the traces the closed form decides with, not only the ones it reads out)."""
    from ..codegen.verify import interpret

    rng = random.Random(733 * N)
    bad = []
    for _ in range(RANDOM):
        pt = dict(p=[mp.mpf(rng.uniform(-2, 2)) for _ in range(N)],
                  q=[mp.mpf(rng.uniform(-1.5, 1.5)) for _ in range(N)], lam0=mp.mpf(rng.uniform(-3, 3)),
                  mu=mp.mpf(rng.uniform(0.1, 3)), branch=rng.choice((1, -1)))
        env, memo = _env(s, pt), dict[Any, Any]()
        with mp.workdps(DPS):
            got = [interpret(s.guards[i].expr, env, memo) for i in (1, 3, 4)]
            if _close(got, _off_reference("bt_step", pt)) > TOL:
                bad.append(f"bt_step: trace and gap guards {[mp.nstr(v, 5) for v in got]} at {_brief(pt)}, reference "
                           f"{[mp.nstr(v, 5) for v in _off_reference('bt_step', pt)]}")
    return bad


@claim("library.specs_literal", equation="imptransf", scene="library", N=2,
       where="symbt.codegen.derive.specs (the closed forms printed into toda2)",
       statement="every output and guard of every function of specs(2) (evaluated at 40 digits) equals the literal "
                 "trace and map of symbt.reference.literal (central differences for the fields and the gradient) "
                 "within 1e-22 max(1, |x|), at map states of both branches and trace signs and off the map; the map's "
                 "guards come in the documented order and stages")
def specs_literal() -> Outcome:
    return check_specs(2)


@claim("library.specs_literal_n3", equation="imptransf", scene="library", N=3, deep=True,
       where="symbt.codegen.derive.specs (the closed forms printed into toda3)",
       statement="every output and guard of every function of specs(3) (evaluated at 40 digits) equals the literal "
                 "trace and map within 1e-22 max(1, |x|), on and off the map; the guards in the documented order")
def specs_literal_n3() -> Outcome:
    return check_specs(3)


def check_sources(N: int) -> Outcome:
    """``library.sources_literal``: every function of ``derive.sources(N)`` against the reference."""
    from ..codegen import derive
    from ..codegen.verify import evaluate_source

    bad: list[str] = []
    worst, n = mp.mpf(0), 0
    for name in derive.FUNCTIONS:
        for pt in points(N, name):
            ref = _stable(name, pt)
            if ref is None:
                bad.append(f"{name}: the reference is unstable at {_brief(pt)}")
                continue
            got = evaluate_source(N, name, pt, dps=DPS)
            gv = evaluate_source(N, name, pt, dps=DPS, part="guards")
            with mp.workdps(DPS):
                r = max(_close(got, ref[0]), _close(gv, ref[1] or []))
            n += 1
            worst = max(worst, r)
            if r > TOL:
                bad.append(f"{name} at {_brief(pt)}: off by {mp.nstr(r, 3)}")
        if name in ("phi_tr", "ck_integrand", "phi", "phi_grad", "dapp_xy", "bt_step"):
            for case, pt in _off_cases(N, name):
                with mp.workdps(DPS):
                    want = _off_reference(name, pt)[:2]     # the paper's route has no gap-sign guard
                    got = evaluate_source(N, name, pt, dps=DPS, part="guards")[:len(want)]
                    if _close(got, want) > TOL:
                        bad.append(f"{name}: trace guards {[mp.nstr(v, 5) for v in got]} at the {case} state "
                                   f"{_brief(pt)}, reference {[mp.nstr(v, 5) for v in want]}")
    detail = f"{n} points over {len(derive.FUNCTIONS)} functions (outputs and guards), worst {mp.nstr(worst, 3)} " \
             "(bound 1e-22); trace guards at band and gap states"
    if bad:
        return failed("numeric: literal map and trace (symbt.reference.literal) at 40 digits",
                      residual=float(worst), detail="; ".join(bad[:6]) + "; " + detail)
    return Outcome("verified", "numeric: literal map and trace (symbt.reference.literal), central differences, at "
                   "40 digits", residual=float(worst), evidence="sampled", n_scope=[N], detail=detail)


@claim("library.sources_literal", equation="imptransf", scene="library", N=2,
       where="symbt.codegen.derive.sources (the paper's route the emitted modules are checked against), N = 2",
       statement="every output and guard of every function of sources(2), evaluated at 40 digits, "
                 "equals the literal trace and map of symbt.reference.literal (central differences for the fields and "
                 "the gradient) within 1e-22 max(1, |x|), on the map and (trace guards) off it")
def sources_literal() -> Outcome:
    return check_sources(2)


@claim("library.sources_literal_n3", equation="imptransf", scene="library", N=3, deep=True,
       where="symbt.codegen.derive.sources (the paper's route), N = 3",
       statement="every output and guard of every function of sources(3), evaluated at 40 digits, "
                 "equals the literal trace and map within 1e-22 max(1, |x|), on the map and (trace guards) off it")
def sources_literal_n3() -> Outcome:
    return check_sources(3)
