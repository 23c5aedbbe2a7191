r"""What ships, 2: ``invariants``, ``spectral_trace``, ``phi``, ``flow_coefficients`` and ``FlowField`` of
:mod:`symbt.numeric` against routes that share nothing with them (scene ``shipped``).

* ``invariants``, ``spectral_trace`` -- the polynomial trace (:func:`symbt.reference.trace.hamiltonians`: the
  closed-walk expansion of tr L over the matchings of the N-cycle, no 2x2 product), at 50 and 75 digits;
  bound ``16 N u S`` with ``S = |H_k| + sum_j max(|x_j|,1)|dH_k/dx_j| + sum_m |t_m|`` (the last sum: the terms
  of the expansion, the scale of its cancellation);
* ``phi`` -- the literal Phi, ``sum_k ln|(eta_k + mu)/(eta_k - mu)|`` with the ``eta_k`` of the literal map
  (eq. ``imptransf``, 50 and 75 digits plus guard; not the arccosh-of-traces form ``phi`` uses); ``S`` by
  forward differences;
* ``flow_coefficients`` -- tanh-sinh quadrature (``mpmath.quad``) of ``-b int lam^k / sqrt(tr^2 - 4)`` with the
  polynomial trace, at 30 and 42 digits; bound ``10 (rtol A_k + eps (max(|lam0|,1)|dc/dlam0| +
  max(|mu|,1)|dc/dmu|))`` with ``A_k = max(|lam_1|, |lam_2|)^k int 1/sqrt(tr^2 - 4)``, which bounds
  ``int |lam|^k / sqrt(tr^2 - 4)`` (the quadrature's documented relative tolerance on the absolute integral,
  and the end points' conditioning); mpmath at 30 digits: ``10**-25 A_k`` (its documented ``10**(5 - dps)``);
* ``FlowField`` -- ``(dG/dp, -dG/dq)`` of ``G = sum_k c_k H_k`` by central differences of the polynomial
  ``H_k`` at 40 digits (``c_k`` from the quadrature above); bound ``10 rtol sum_k A_k |grad H_k| + 16 N eps
  sum_k |c_k| |grad H_k|``.

Cells: branch x sign(mu) x sign(tr) (:func:`symbt.claims._shipped.ship_cells`).
"""
from __future__ import annotations

from functools import cache

import mpmath as mp
import numpy as np

from ..reference.trace import hamiltonians, trace_polynomial
from ._shipped import (
    CHECK_DPS,
    EPS,
    FD_DPS,
    REF_DPS,
    Tally,
    guard_digits,
    literal_state,
    scale_parts,
    scaled,
    ship_cells,
    step_constant,
    without_numba,
)
from .base import Outcome, Parts, claim

MP_DPS = 30
RTOL = 1e-13       # flow_coefficients' and FlowField's default rtol
QUAD_C = 10
QUAD_DPS = 30      # the quadrature reference (and 42 to check it): far below rtol = 1e-13 and 10**-25


def _inputs(st: tuple) -> list:
    return list(st[0]) + list(st[1])


def _ratio(v, ref, bound) -> float:
    """``|v - ref| / bound`` (``v`` a float64, a 0-d array or an mpf kept at its own precision); inf if not finite."""
    try:
        v = v if isinstance(v, mp.mpf) else mp.mpf(float(v))
    except (TypeError, ValueError):
        return float("inf")
    if not mp.isfinite(v):
        return float("inf")
    return float(abs(v - ref) / bound)


def _vals(p: list, q: list) -> list:
    N = len(p)
    return list(p) + [mp.exp(q[(j + 1) % N] - q[j]) for j in range(N)]


@cache
def _invariant_ref(p: tuple, q: tuple) -> tuple:
    """``(H_0..H_{N-1} at 50 digits, agreement with 75 digits, S_k)``."""
    N = len(p)
    with mp.workdps(CHECK_DPS):
        hi = hamiltonians([mp.mpf(v) for v in p], [mp.mpf(v) for v in q])
    with mp.workdps(REF_DPS):
        H = hamiltonians([mp.mpf(v) for v in p], [mp.mpf(v) for v in q])
        agree = float(max(abs(a - c) for a, c in zip(H, hi)) / max(1, *(abs(c) for c in hi)))
        vals = _vals([mp.mpf(v) for v in p], [mp.mpf(v) for v in q])
        terms = [mp.mpf(0)] * (N + 1)
        for key, c in trace_polynomial(N).items():
            t = abs(c)
            for v, e in zip(vals, key[1:]):
                t *= v ** e
            terms[key[0]] += t
        S = [abs(h) + t for h, t in zip(H, terms)]
        x = [mp.mpf(v) for v in p + q]
        for j, v in enumerate(x):
            w = max(abs(v), 1)
            h = mp.mpf(10) ** -20 * w
            y = list(x)
            y[j] += h
            Hh = hamiltonians(y[:N], y[N:])
            S = [s + w * abs(a - c) / h for s, a, c in zip(S, Hh, H)]
    return tuple(H[:N]), agree, tuple(S[:N]), tuple(terms)


@claim("shipped.invariants", equation="tra", scene="shipped",
       parts=scale_parts, sizes=(2, 3, 5),
       where="symbt/numeric/flow/invariants.py: invariants, spectral_trace",
       statement="symbt.numeric.invariants (float64 one state and batch, mpmath 30 digits) and spectral_trace "
                 "(float64, mpmath) at lambda0 +- mu = the polynomial trace (closed-walk expansion, 50 digits) "
                 "within 16 N u S, every cell (N={N})")
def invariants(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import invariants as inv
    from ..numeric import spectral_trace

    tally, C = Tally(), step_constant(N)
    samples = ship_cells(N, 8 if deep else 2)
    batch = inv(np.array([st[0] for _, st, _ in samples]), np.array([st[1] for _, st, _ in samples]))
    for i, (cell, st, b) in enumerate(samples):
        H, agree, S, terms = _invariant_ref(st[0], st[1])
        with mp.workdps(MP_DPS):
            hm = inv([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]])
            u_mp = 2.0 ** -mp.mp.prec
        for name, vals, u in (("invariants (float64)", inv(np.array(st[0]), np.array(st[1])), EPS),
                              ("invariants (batch)", batch[i], EPS), ("invariants (mpmath)", hm, u_mp)):
            r = max(_ratio(v, h, C * u * s) for v, h, s in zip(scaled(vals, parts.printed["scale"]), H, S))
            tally.add(name, cell, st, b, r, 0.0, agree)
        for lam in (st[2] + st[3], st[2] - st[3]):
            with mp.workdps(REF_DPS):
                L = mp.mpf(lam)
                tr = mp.polyval(list(H[::-1]), L) + L ** N
                Hx = list(H) + [mp.mpf(1)]
                S_tr = sum(s * abs(L) ** k for k, s in enumerate(list(S) + [mp.mpf(1)]))
                S_tr += max(abs(L), 1) * abs(sum(k * h * L ** (k - 1) for k, h in enumerate(Hx) if k))
            v = scaled([float(spectral_trace(lam, np.array(st[0]), np.array(st[1])))], parts.printed["scale"])[0]
            r = _ratio(v, tr, C * EPS * S_tr)
            tally.add("spectral_trace", cell, st, b, r, 0.0, agree)
            with mp.workdps(MP_DPS):
                vm = spectral_trace(mp.mpf(lam), [mp.mpf(x) for x in st[0]], [mp.mpf(x) for x in st[1]])
                u_mp = 2.0 ** -mp.mp.prec
            r = _ratio(scaled([vm], parts.printed["scale"])[0], tr, C * u_mp * S_tr)
            tally.add("spectral_trace (mpmath)", cell, st, b, r, 0.0, agree)
    return tally.outcome(method=f"numeric: vs the polynomial trace ({REF_DPS} digits), bound 16 N u S",
                         printed=f"|invariants - polynomial| <= {C} u S_k; |spectral_trace - polynomial| <= {C} eps S")


def _phi_literal(st: tuple, b: int, dps: int, g: int):
    _, _, info = literal_state(st, b, dps + g)
    mu = mp.mpf(st[3])
    with mp.workdps(dps + g):
        return mp.fsum(mp.log(abs((e + mu) / (e - mu))) for e in info["eta"])


@cache
def _phi_ref(st: tuple, b: int) -> tuple:
    g = guard_digits(st)
    ref = _phi_literal(st, b, REF_DPS, g)
    agree = float(abs(ref - _phi_literal(st, b, CHECK_DPS, g + 25)) / max(1, abs(ref)))
    S = abs(ref)
    N = len(st[0])
    with mp.workdps(FD_DPS + g):
        base = _phi_literal(st, b, FD_DPS, g)
        x = [mp.mpf(v) for v in list(st[0]) + list(st[1]) + [st[2], st[3]]]
        for j, v in enumerate(x):
            w = max(abs(v), 1)
            h = mp.mpf(10) ** -12 * w
            y = list(x)
            y[j] += h
            S += w * abs(_phi_literal((y[:N], y[N:2 * N], y[2 * N], y[2 * N + 1]), b, FD_DPS, g) - base) / h
    return ref, agree, S


@claim("shipped.phi", equation="newkmu", scene="shipped",
       parts=scale_parts, sizes=(2, 3, 5), where="symbt/numeric/flow/phi.py: phi",
       statement="symbt.numeric.phi (float64 one state and batch, mpmath 30 digits) = the literal Phi = sum_k "
                 "ln|(eta_k + mu)/(eta_k - mu)|, eta_k of the literal map (50 digits), within 16 N u S, every "
                 "branch x sign(mu) x sign(tr) cell (N={N})")
def phi(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import phi as phi_num

    tally, C = Tally(), step_constant(N)
    samples = ship_cells(N, 8 if deep else 2)
    for b in (1, -1):
        rows = [(cell, st) for cell, st, bb in samples if bb == b]
        batch = phi_num(np.array([st[0] for _, st in rows]), np.array([st[1] for _, st in rows]),
                        np.array([st[2] for _, st in rows]), np.array([st[3] for _, st in rows]), branch=b)
        for i, (cell, st) in enumerate(rows):
            ref, agree, S = _phi_ref(st, b)
            with mp.workdps(MP_DPS):
                pm = phi_num([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]], mp.mpf(st[2]), mp.mpf(st[3]),
                             branch=b)
                u_mp = 2.0 ** -mp.mp.prec
            for name, v, u in (("phi (float64)", phi_num(np.array(st[0]), np.array(st[1]), st[2], st[3], branch=b),
                                EPS), ("phi (batch)", batch[i], EPS), ("phi (mpmath)", pm, u_mp)):
                v = scaled([v if isinstance(v, mp.mpf) else float(v)], parts.printed["scale"])[0]
                tally.add(name, cell, st, b, _ratio(v, ref, C * u * S), float(C * u * S / max(1, abs(ref))), agree)
    return tally.outcome(method=f"numeric: vs sum ln|(eta+mu)/(eta-mu)| of the literal map ({REF_DPS} digits)",
                         printed=f"|phi - literal Phi| <= {C} u S")


def _quad(st: tuple, dps: int) -> tuple:
    """``(c_k(b=+1), A_k, dc_k/dlam0, dc_k/dmu)`` for k < N at ``dps`` digits (the oriented integral)."""
    N = len(st[0])
    with mp.workdps(dps):
        H = hamiltonians([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]])[::-1]
        l0, m = mp.mpf(st[2]), mp.mpf(st[3])
        lo, hi = l0 - m, l0 + m

        def w(x):
            return 1 / mp.sqrt(mp.polyval(H, x) ** 2 - 4)
        c = [-mp.quad(lambda x, k=k: x ** k * w(x), [lo, l0, hi]) for k in range(N)]
        # int |lam|^k w <= max(|lam1|, |lam2|)^k int w = max(...)^k |c_0| (w > 0): the scale of the integral
        A = [max(abs(lo), abs(hi)) ** k * abs(c[0]) for k in range(N)]
        d0 = [-(hi ** k * w(hi) - lo ** k * w(lo)) for k in range(N)]
        dm = [-(hi ** k * w(hi) + lo ** k * w(lo)) for k in range(N)]
    return c, A, d0, dm


@cache
def _c_ref(st: tuple) -> tuple:
    c, A, d0, dm = _quad(st, QUAD_DPS)
    c2 = _quad(st, QUAD_DPS + 12)[0]
    agree = float(max(abs(a - b_) / max(1, abs(b_)) for a, b_ in zip(c, c2)))
    w0, wm = max(abs(st[2]), 1), max(abs(st[3]), 1)
    bound = [QUAD_C * (RTOL * a + EPS * (w0 * abs(x) + wm * abs(y))) for a, x, y in zip(A, d0, dm)]
    return c, A, agree, bound


@claim("shipped.coefficients", equation="eqdisc", scene="shipped",
       parts=scale_parts, sizes=(2,), deep=True,
       where="symbt/numeric/flow/coefficients.py: flow_coefficients",
       statement="symbt.numeric.flow_coefficients (float64, rtol 1e-13; mpmath 30 digits) = tanh-sinh quadrature "
                 "of -b int_{lam0-mu}^{lam0+mu} lam^k/sqrt(tr^2-4) with the polynomial trace (30 digits, checked at "
                 "42), within 10 (rtol A_k + eps end-point conditioning), every cell (N={N})")
@claim("shipped.coefficients", equation="eqdisc", scene="shipped",
       parts=scale_parts, sizes=(3,),
       where="symbt/numeric/flow/coefficients.py: flow_coefficients",
       statement="symbt.numeric.flow_coefficients (float64, rtol 1e-13; mpmath 30 digits) = tanh-sinh quadrature "
                 "of -b int_{lam0-mu}^{lam0+mu} lam^k/sqrt(tr^2-4) with the polynomial trace (30 digits, checked at "
                 "42), within 10 (rtol A_k + eps end-point conditioning), every cell (N={N})")
def coefficients(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import flow_coefficients

    tally = Tally()
    for cell, st, b in ship_cells(N, 4 if deep else 1):
        c, A, agree, bound = _c_ref(st)
        # check=False: the existence test is bt_step's (claims shipped.step, shipped.nomap), and with numba installed
        # it would load the compiled kernel here
        f = flow_coefficients(np.array(st[0]), np.array(st[1]), st[2], st[3], branch=b, check=False)
        with mp.workdps(QUAD_DPS):   # b * c at the reference's precision, not rounded to 53 bits
            ref = [b * x for x in c]
        r = max(_ratio(v, x, bd) for v, x, bd in zip(scaled(f, parts.printed["scale"]), ref, bound))
        tally.add("flow_coefficients (float64)", cell, st, b, r, 0.0, agree, agree_tol=1e-27)
        with mp.workdps(MP_DPS):
            fm = flow_coefficients([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]], mp.mpf(st[2]),
                                   mp.mpf(st[3]), branch=b, check=False)
        r = max(_ratio(v, x, QUAD_C * mp.mpf(10) ** (5 - MP_DPS) * a)
                for v, x, a in zip(scaled(fm, parts.printed["scale"]), ref, A))
        tally.add("flow_coefficients (mpmath)", cell, st, b, r, 0.0, agree, agree_tol=1e-27)
    return tally.outcome(method="numeric: vs mpmath.quad of the eqdisc integral with the polynomial trace",
                         printed="|c_k - quadrature| <= 10 (rtol A_k + eps end-point conditioning)")


@cache
def _field_ref(st: tuple, b: int, x: tuple) -> tuple:
    """``(qdot, pdot)`` at the state x = (p, q) by central differences of G = sum_k c_k H_k, and the bounds."""
    N = len(st[0])
    c, A, _, _ = _c_ref(st)
    with mp.workdps(QUAD_DPS + 10):
        z = [mp.mpf(v) for v in x[0]] + [mp.mpf(v) for v in x[1]]
        grads = []   # grads[j][k] = dH_k/dz_j
        for j, v in enumerate(z):
            h = mp.mpf(10) ** -15 * max(abs(v), 1)
            zp, zm = list(z), list(z)
            zp[j] += h
            zm[j] -= h
            Hp, Hm = hamiltonians(zp[:N], zp[N:]), hamiltonians(zm[:N], zm[N:])
            grads.append([(a - d) / (2 * h) for a, d in zip(Hp[:N], Hm[:N])])
        dG = [b * mp.fsum(ck * g for ck, g in zip(c, gj)) for gj in grads]
        bound = [QUAD_C * RTOL * mp.fsum(a * abs(g) for a, g in zip(A, gj))
                 + step_constant(N) * EPS * mp.fsum(abs(ck * g) for ck, g in zip(c, gj)) for gj in grads]
        qdot, pdot = dG[:N], [-v for v in dG[N:]]
    return qdot, pdot, bound[:N], bound[N:]


@claim("shipped.field", equation="eqdisc", scene="shipped",
       parts=scale_parts, sizes=(2,), deep=True,
       where="symbt/numeric/flow/field.py: FlowField",
       statement="symbt.numeric.FlowField (built at (p0, q0), evaluated there and at a displaced state, one state "
                 "and a batch) = (dG/dp, -dG/dq), G = sum_k c_k H_k, by central differences of the polynomial H_k "
                 "(40 digits) and quadrature c_k, within 10 rtol sum_k A_k|grad H_k| + 16 N eps sum_k |c_k grad H_k|, "
                 "every cell (N={N})")
@claim("shipped.field", equation="eqdisc", scene="shipped",
       parts=scale_parts, sizes=(3,), where="symbt/numeric/flow/field.py: FlowField",
       statement="symbt.numeric.FlowField (built at (p0, q0), evaluated there and at a displaced state, one state "
                 "and a batch) = (dG/dp, -dG/dq), G = sum_k c_k H_k, by central differences of the polynomial H_k "
                 "(40 digits) and quadrature c_k, within 10 rtol sum_k A_k|grad H_k| + 16 N eps sum_k |c_k grad H_k|, "
                 "every cell (N={N})")
def field(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import FlowField

    tally = Tally()
    for cell, st, b in ship_cells(N, 4 if deep else 1):
        with without_numba():   # FlowField's existence check is bt_step(backend="auto")
            F = FlowField(np.array(st[0]), np.array(st[1]), st[2], st[3], branch=b)
        moved = (tuple(v + 0.1 for v in st[0]), tuple(v - 0.05 * j for j, v in enumerate(st[1])))
        states = [(st[0], st[1]), moved]
        both = F(np.array([s[0] for s in states]), np.array([s[1] for s in states]))
        for i, (name, x) in enumerate((("FlowField at (p0, q0)", states[0]), ("FlowField displaced", states[1]))):
            qd, pd, bq, bp = _field_ref(st, b, x)
            one = F(np.array(x[0]), np.array(x[1]))
            for label, out in ((name, one), (name + " (batch)", (both[0][i], both[1][i]))):
                vals = scaled(list(out[0]) + list(out[1]), parts.printed["scale"])
                r = max(_ratio(v, ref, bd) for v, ref, bd in zip(vals, qd + pd, bq + bp))
                tally.add(label, cell, st, b, r)
    return tally.outcome(method="numeric: vs central differences of sum_k c_k H_k (polynomial trace, 40 digits)",
                         printed="|FlowField - (dG/dp, -dG/dq)| <= 10 rtol sum A|grad H| + 16 N eps sum |c grad H|")
