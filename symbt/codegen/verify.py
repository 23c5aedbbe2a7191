r"""Checks of an emitted module against its SymPy source (used by the ``codegen`` claims and the tests).

For every emitted function ``f`` of ``toda{N}`` and every sample point ``x``
(float64 values, so that both flavours see exactly the same input):

* reference: the SymPy source of ``f`` (:func:`symbt.codegen.derive.sources`: the
  model itself, no rewriting) evaluated with mpmath at ``REF_DPS = 80`` digits --
  independent of the emission form, the printer and CSE;
* *condition scale* ``S = |f| + sum_i max(|x_i|, 1) |df/dx_i|`` (forward differences
  of the emitted mpmath flavour at 50 digits): the change of ``f`` under
  relative-or-absolute input perturbations of one unit.  A float64 evaluation that is
  backward stable up to a few roundings per input is within a few ``eps * S``;
* numpy flavour: ``|f64 - ref| <= F64_TOL_ULPS * eps * S`` (``F64_TOL_ULPS = 16``);
* mpmath flavour at 50 digits: ``|mp - ref| <= 1e-45 * S``.

Sample points: seeded admissible states (real map, both signs of tr L, both
branches; the paper's example for N = 3) and random states for the polynomial
functions.  :func:`step_accuracy` compares ``bt_step`` with
:func:`symbt.reference.literal.reference_step` (50 digits).

>>> from symbt.generated import toda2
>>> r = compare(toda2, 2, "invariants")
>>> r["ok"], r["npts"]
(True, 6)
"""
from __future__ import annotations

import random
from collections.abc import Callable, Mapping, Sequence
from functools import cache
from types import ModuleType
from typing import Any

import mpmath as mp
import numpy as np
import sympy as sp
from sympy.codegen.cfunctions import log1p

from ..reference.literal import literal_step, reference_step
from ..reference.samples import admissible_states, paper_state
from .derive import FunctionSpec, RingValue, interface, sources

__all__ = ["compare", "evaluate_source", "interpret", "map_states", "points", "step_accuracy", "phi_grad_vs_fd",
           "xy_vs_printed", "F64_TOL_ULPS", "MP_TOL", "REF_DPS", "MP_DPS", "EPS"]

F64_TOL_ULPS = 16
MP_TOL = mp.mpf(10) ** -45
REF_DPS, MP_DPS = 80, 50
EPS = float(np.finfo(np.float64).eps)


@cache
def map_states(N: int, per_sign: int = 2) -> list[tuple[list[float], list[float], float, float]]:
    """``(p, q, lam0, mu)`` as floats: ``per_sign`` per sign of tr L (+ the paper's example for N = 3)."""
    with mp.workdps(30):
        st = admissible_states(N, 1, per_sign) + admissible_states(N, -1, per_sign)
        if N == 3:
            st.append(paper_state("5"))
    return [([float(v) for v in p], [float(v) for v in q], float(l0), float(m)) for p, q, l0, m in st]


def points(spec: FunctionSpec, N: int) -> list[dict[str, Any]]:
    """Argument dicts (python floats / lists of floats / branch ints) for one function."""
    rng = random.Random(7919 * N + len(spec.name))
    kinds = {a.name for a in spec.args}
    pts: list[dict[str, Any]] = []
    if "lam0" in kinds:
        for p, q, l0, m in map_states(N):
            for b in (1, -1):
                pts.append(dict(p=p, q=q, lam0=l0, mu=m, branch=b))
    elif "lam" in kinds:
        for p, q, l0, m in map_states(N):
            for lv in (l0 + m, l0 - m):
                pts.append(dict(lam=lv, p=p, q=q))
    elif "tr1" in kinds:
        for _ in range(6):
            t1, t2 = (rng.choice((1, -1)) * rng.uniform(2.2, 40) for _ in range(2))
            pts.append(dict(tr1=t1, tr2=t2, branch=rng.choice((1, -1))))
    else:
        # coordinate i of p, q, c takes the sign of bit (i + 0, 1, 2) mod 3 of the point's index: each takes
        # both signs over the six points (six uniform draws left one sign out for toda2.hamiltonian_fields)
        def signed(k: int, bit: int, hi: float) -> float:
            v = rng.uniform(0, hi)
            return v if (k >> (bit % 3)) & 1 else -v
        for k in range(6):
            pt = dict(p=[signed(k, i, 3) for i in range(N)], q=[signed(k, i + 1, 1.5) for i in range(N)])
            if "c" in kinds:
                pt["c"] = [signed(k, i + 2, 1) for i in range(N)]
            pts.append(pt)
    return pts


_FUNCS = {sp.exp: mp.exp, sp.log: mp.log, log1p: mp.log1p, sp.sign: mp.sign, sp.Abs: abs, sp.acosh: mp.acosh}


def interpret(e: sp.Basic, env: dict[sp.Basic, Any], memo: dict[Any, Any]) -> Any:
    """Value of a SymPy expression DAG with mpmath at the working precision, each distinct subexpression once
    (the sources' products of local Lax matrices share their subexpressions; a tree walk or ``lambdify`` would
    see 2^N copies).  What the derived sources and closed forms contain is read: numbers, ``+ * **`` (integer
    and half-integer powers, ``E**x``), ``exp log log1p sign Abs acosh``, ``Max Min``, relations and ``true``/
    ``false``, ``Piecewise`` -- only its selected piece is evaluated, as the printed code does -- and the printer's
    ``Quotient(a, b)``, IEEE-style (``a/0 = sgn(a) inf``).  Anything else is a ``ValueError``.

    >>> x, y = sp.symbols("x y")
    >>> e = sp.Piecewise((sp.log(x), x > 0), (y, True)) + sp.Rational(1, 2)
    >>> [float(interpret(e, {x: mp.mpf(v), y: mp.mpf(7)}, {})) for v in (1, -1)]
    [0.5, 7.5]
    """
    from .printer import Quotient

    try:
        return memo[e]
    except KeyError:
        pass
    if e.is_Symbol:
        v = env[e]
    elif e is sp.true or e is sp.false:
        v = bool(e)
    elif e.is_Integer:
        v = mp.mpf(int(e))
    elif e.is_Rational:
        v = mp.mpf(e.p) / e.q
    elif e.is_Float:
        v = mp.mpf(e)
    elif isinstance(e, sp.Piecewise):
        v = next(interpret(x, env, memo) for x, c in e.args if interpret(c, env, memo))
    elif isinstance(e, Quotient):
        a, b = (interpret(x, env, memo) for x in e.args)
        v = a / b if b != 0 else mp.sign(a) * mp.inf
    elif e.is_Add:
        v = mp.fsum(interpret(x, env, memo) for x in e.args)
    elif e.is_Mul:
        v = mp.fprod(interpret(x, env, memo) for x in e.args)
    elif e.is_Pow:
        b, x = interpret(e.base, env, memo), e.exp
        if e.base is sp.E:
            v = mp.exp(interpret(x, env, memo))
        elif x.is_Integer:
            v = b ** int(x)
        elif x.is_Rational and x.q == 2:
            v = mp.sqrt(b) ** x.p
        else:
            raise ValueError(f"cannot evaluate {e}")
    elif isinstance(e, sp.core.relational.Relational):
        a, b = interpret(e.lhs, env, memo), interpret(e.rhs, env, memo)
        v = {">=": a >= b, ">": a > b, "<=": a <= b, "<": a < b, "==": a == b, "!=": a != b}[e.rel_op]
    elif isinstance(e, (sp.Max, sp.Min)):
        vs = [interpret(x, env, memo) for x in e.args]
        v = max(vs) if isinstance(e, sp.Max) else min(vs)
    elif len(e.args) == 1 and e.func in _FUNCS:
        v = _FUNCS[e.func](interpret(e.args[0], env, memo))
    else:
        raise ValueError(f"cannot evaluate {type(e).__name__}: {e}")
    memo[e] = v
    return v


def _eval(c: Any, env: dict[sp.Basic, Any], memo: dict[Any, Any]) -> Any:
    if isinstance(c, RingValue):
        return c.evaluate(env, mp.exp, memo)
    return interpret(sp.sympify(c), env, memo)


def evaluate_source(N: int, name: str, pt: dict[str, Any], dps: int = REF_DPS, part: str = "outputs") -> list[Any]:
    """The SymPy source of every output (``part="guards"``: every guard expression) of ``name`` at ``pt``
    (inputs taken exactly), at ``dps`` digits."""
    spec = next(s for s in sources(N) if s.name == name)
    if part not in ("outputs", "guards"):
        raise ValueError(f"part must be 'outputs' or 'guards', got {part!r}")
    with mp.workdps(dps):
        env: dict[sp.Basic, Any] = {}
        memo: dict[Any, Any] = {}
        for a in spec.args:
            vals = pt[a.name] if a.kind == "state" else [pt[a.name]]
            for s, v in zip(a.symbols, vals):
                env[s] = int(v) if a.kind == "branch" else mp.mpf(v)
        for s, c in spec.defs:
            env[s] = _eval(c, env, memo)
        if part == "guards":
            return [+_eval(g.expr, env, memo) for g in spec.guards]
        return [+_eval(e, env, memo) for o in spec.outputs for e in o.exprs]


def _flat(out: Any) -> list[Any]:
    """Flatten the (tuple of) outputs of an emitted function into a list of scalars."""
    outs = out if isinstance(out, tuple) else (out,)
    res = []
    for o in outs:
        if isinstance(o, np.ndarray):
            res += [float(v) for v in o.reshape(-1)]
        elif isinstance(o, list):
            for v in o:
                res += v if isinstance(v, list) else [v]
        else:
            res.append(o)
    return res


def _scale(spec: FunctionSpec, fn_mp: Callable[..., Any], pt: Mapping[str, Any], ref: Sequence[Any],
           f0: Sequence[Any]) -> list[Any]:
    """S_k = |f_k| + sum_i max(|x_i|, 1) |df_k/dx_i| (forward differences of the mpmath flavour, whose value
    at the point is ``f0``: with h = 1e-18 max(|x_i|, 1) at 50 digits the quotient is good to ~18 digits,
    far more than a scale needs, at half the evaluations of central differences)."""
    S = [abs(r) for r in ref]
    with mp.workdps(MP_DPS):
        for a in spec.args:
            if a.kind == "branch":
                continue
            n = len(pt[a.name]) if a.kind == "state" else 1
            for i in range(n):
                x0 = mp.mpf(pt[a.name][i] if a.kind == "state" else pt[a.name])
                h = mp.mpf(10) ** -18 * max(abs(x0), 1)
                args = {k: (list(v) if isinstance(v, list) else v) for k, v in pt.items()}
                if a.kind == "state":
                    args[a.name][i] = x0 + h
                else:
                    args[a.name] = x0 + h
                fh = _flat(fn_mp(**args))
                for k in range(len(S)):
                    S[k] += max(abs(x0), 1) * abs(fh[k] - f0[k]) / h
    return S


def compare(mod: ModuleType, N: int, name: str, pts: Sequence[dict[str, Any]] | None = None) -> dict[str, Any]:
    """Emitted ``name`` (numpy and mpmath flavours of ``mod``) vs its SymPy source; see the module doc.  An empty
    ``pts`` raises ``ValueError`` (a comparison at no point would pass)."""
    spec = interface(N)[name]
    fn, fn_mp = getattr(mod, name), getattr(mod, name + "_mp")
    worst_f, worst_m, bad = 0.0, mp.mpf(0), None
    pts = points(spec, N) if pts is None else pts
    if not pts:                     # no point: nothing compared, and nothing could fail
        raise ValueError(f"codegen.verify.compare({name}): no point to compare at")
    for pt in pts:
        ref = evaluate_source(N, name, pt)
        with mp.workdps(MP_DPS):
            fm = _flat(fn_mp(**pt))
        S = _scale(spec, fn_mp, pt, ref, fm)
        with np.errstate(all="ignore"):
            f64 = _flat(fn(**pt))
        with mp.workdps(REF_DPS):
            for k, (r, s) in enumerate(zip(ref, S)):
                s = max(s, mp.mpf(10) ** -300)
                ef = float(abs(mp.mpf(f64[k]) - r) / (EPS * s))
                em = abs(mp.mpmathify(fm[k]) - r) / s
                if not ef <= worst_f:
                    worst_f = ef
                    if ef > F64_TOL_ULPS:
                        bad = dict(point=repr(pt), output=k, ref=mp.nstr(r, 17), f64=repr(f64[k]))
                if em > worst_m:
                    worst_m = em
                    if em > MP_TOL:
                        bad = dict(point=repr(pt), output=k, ref=mp.nstr(r, 30), mp=mp.nstr(fm[k], 30))
    ok = worst_f <= F64_TOL_ULPS and worst_m <= MP_TOL
    nout = len(ref)                 # the outputs of every point (of the last one read)
    return dict(ok=ok, worst_f64=worst_f, worst_mp=worst_m, npts=len(pts), nout=nout, bad=bad,
                detail=(f"{len(pts)} points x {nout} outputs; numpy: max |f64 - ref| = {worst_f:.2f} eps*S "
                        f"(tolerance {F64_TOL_ULPS}); mpmath at {MP_DPS} digits: max |mp - ref|/S = "
                        f"{mp.nstr(worst_m, 3)} (tolerance 1e-45); ref = SymPy source at {REF_DPS} digits, "
                        "S = |f| + sum_i max(|x_i|,1)|df/dx_i|"))


def step_accuracy(mod: ModuleType, N: int, states: Sequence[Any] | None = None) -> float:
    """Max over admissible states and both branches of the normwise relative error of the float64
    ``bt_step`` against ``reference_step`` at 50 digits: ``||x64 - x_ref||_2 / ||x_ref||_2``, x = (p~, q~)."""
    worst = 0.0
    for p, q, l0, m in (map_states(N) if states is None else states):
        for b in (1, -1):
            with mp.workdps(MP_DPS):
                rp, rq = reference_step(p, q, l0, m, branch=b)
            pt, qt = mod.bt_step(p, q, l0, m, b)
            with mp.workdps(MP_DPS):
                err = mp.sqrt(sum((mp.mpf(float(a)) - c) ** 2 for a, c in zip(list(pt) + list(qt), rp + rq)))
                nrm = mp.sqrt(sum(c ** 2 for c in rp + rq))
            worst = max(worst, float(err / nrm))
    return worst


def phi_grad_vs_fd(mod: ModuleType, N: int) -> mp.mpf:
    """Emitted gradient vs numerical differentiation (mp.diff) of the emitted Phi, relative to max(1, |g|)."""
    worst = mp.mpf(0)
    with mp.workdps(MP_DPS):
        for p, q, l0, m in map_states(N):
            for b in (1, -1):
                gp, gq = mod.phi_grad_mp(p, q, l0, m, b)
                for i in range(N):
                    for which, g in (("p", gp[i]), ("q", gq[i])):
                        def f(t: mp.mpf, which: str = which, i: int = i) -> mp.mpf:
                            pp, qq = list(map(mp.mpf, p)), list(map(mp.mpf, q))
                            (pp if which == "p" else qq)[i] = t
                            return mod.phi_mp(pp, qq, l0, m, b)
                        x0 = mp.mpf((p if which == "p" else q)[i])
                        worst = max(worst, abs(mp.diff(f, x0) - g) / max(1, abs(g)))
    return worst


def xy_vs_printed(mod: ModuleType, N: int) -> mp.mpf:
    """Emitted x, y vs the printed quotients of eq. xy (symbt.reference.literal, 70 digits), relative."""
    worst = mp.mpf(0)
    for p, q, l0, m in map_states(N):
        for b in (1, -1):
            with mp.workdps(70):
                info = literal_step(p, q, l0, m, b)[2]
            with mp.workdps(MP_DPS):
                x, y = mod.dapp_xy_mp(p, q, l0, m, b)
            with mp.workdps(70):
                worst = max(worst, abs(x - info["x_formula"]) / abs(info["x_formula"]),
                            abs(y - info["y"][0]) / abs(info["y"][0]))
    return worst
