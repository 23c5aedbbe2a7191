r"""The independent routes checked, 3: where the N = 2 sampler puts its cases (scene ``library``, issue 21).

:func:`symbt.reference.elliptic.sample_case` draws the N = 2 cases of the elliptic claims (``addform``,
``citn``, ...) per regime: actions ``(I_1, I_2)``, then the two spectral parameters ``lambda_+- = lam0 +- mu``
in the zones of the regime, in the coordinate ``s = (lambda + I_1)/r``, ``r = sqrt(I_2 - 2)``, whose band
edges are ``s = +-1`` and ``s = +-1/k``, ``1/k = R/r``, ``R = sqrt(I_2 + 2)``; then ``q_1 - q_2 = x`` on the
level set.  Its proposal keeps every case away from the degenerate places of the formulas it feeds (a branch
point ``tr = +-2``, ``mu -> 0``, a turning point ``p_1 = p_2``) by fixed margins:

* zone ``in`` (``|s| < 1``): ``|s| <= 0.95``; zone ``gap`` (a band, ``1 < |s| < 1/k``): ``|s|`` in
  ``1 + (1/k - 1) [0.1, 0.9]``; outer zones: ``|s|`` in ``[1.05, 2.5] / k``; and ``|s_+ - s_-| >= 0.05``;
* ``|x|`` in ``[0.03, 0.97] acosh(I_2 / 2)`` (``acosh(I_2/2)`` is the largest ``|q_1 - q_2|`` on the level).

So, in ``lambda``: every spectral parameter is at least ``min(r/20, (R - r)/10)`` from every band edge and
within ``2.5 R`` of the centre ``-I_1``, ``2 |mu| >= r/20``, and ``|x| / acosh(I_2/2)`` lies in
``[0.03, 0.97]``; every zone pair the regime admits occurs.

* ``library.proposal`` -- checks exactly that on 12 seeded cases per regime and sign of ``q_1 - q_2`` (120),
  with the band edges, the centre and ``I_2`` read off the *literal trace*
  (:func:`~symbt.reference.literal.literal_trace`: the quadratic ``tr(lambda)`` from its values at
  ``lambda = 0, +-1``, its roots of ``tr = +-2``; ``I_2 = -min tr``), not from the sampler's actions or
  :func:`~symbt.reference.elliptic.modulus`.  The bounds are the proposal's own, with a relative allowance of
  1e-9 for the 17-digit decimal strings the cases are returned as (their rounding is ~1e-16).  The
  regime of each case is ``library.regime``'s.

A proposal bug that ``library.regime`` cannot see -- the case is filtered by its regime, so it is still of the
regime asked -- changes where the case lies: a gap zone drawn past ``1/k``, a level set built from a wrong
``I_2`` (the state's own actions are then not the proposal's, and its spectral parameters fall anywhere in
their zones), an ``x`` range past the turning point (``p_1 = p_2``).  Shown to fail on such bugs in
``tests/test_killers_reference.py``.

* ``library.shift_real`` -- :func:`symbt.reference.elliptic.shift` (the translation of one step, N = 2) on 3 cases
  of every regime, both branches: its ``dtheta1_real = b (g(T2) - g(T1))`` is ``None`` exactly where a spectral
  parameter lies in a band -- ``|tr L(lambda)| < 2`` by the literal trace, not by the ``T`` that ``shift``
  returns -- and elsewhere equals the real part of its ``dtheta1 = log(v1 v2)`` (the complex logarithm of the
  product of the eigenvalues, a different formula) within ``10**(5 - dps)`` of its size.

>>> proposal_margins.run().status
'verified'
"""
from __future__ import annotations

import random

import mpmath as mp

from ..reference import elliptic as E
from ..reference.literal import literal_trace
from .base import Outcome, claim, failed

#: cases per regime and sign of q1 - q2
PROPOSAL_CASES = 12
#: relative allowance of the bounds: the cases are 17-digit decimal strings of doubles
PROPOSAL_SLACK = mp.mpf("1e-9")
#: the zone pairs each regime admits (zones by the literal trace: in = tr < -2 between the bands, gap = a band)
ZONE_PAIRS = {"inner": {("in", "in")}, "outer-same": {("out+", "out+"), ("out-", "out-")},
              "outer-opposite": {("out+", "out-")}, "mixed": {("in", "out+"), ("in", "out-")},
              "gap": {("gap", "in"), ("gap", "out+"), ("gap", "gap")}}


def trace_quadratic(p: list, q: list) -> tuple[mp.mpf, mp.mpf, mp.mpf]:
    """``(a, b, c)`` with ``tr L(lambda) = a lambda^2 + b lambda + c`` (N = 2) from the literal trace at 0, +-1."""
    t0, t1, tm = (literal_trace(mp.mpf(x), p, q) for x in (0, 1, -1))
    return (t1 + tm) / 2 - t0, (t1 - tm) / 2, t0


def trace_actions(p: list, q: list) -> tuple[mp.mpf, mp.mpf]:
    """``(I_1, I_2)`` read off the literal trace (N = 2): ``tr L(lambda) = (lambda + I_1)^2 - I_2``."""
    a, b, c = trace_quadratic(list(p), list(q))
    return b / (2 * a), b * b / (4 * a) - c


def _edges(a: mp.mpf, b: mp.mpf, c: mp.mpf) -> list:
    """The four band edges, sorted: the roots of ``tr = -2`` and ``tr = 2``."""
    out = []
    for v in (-2, 2):
        d = mp.sqrt(b * b - 4 * a * (c - v))
        out += [(-b - d) / (2 * a), (-b + d) / (2 * a)]
    return sorted(out)


def _zone(lam: mp.mpf, e: list) -> str:
    if e[1] < lam < e[2]:
        return "in"
    if lam > e[3]:
        return "out+"
    return "out-" if lam < e[0] else "gap"


def case_violations(case: tuple) -> tuple[list[str], tuple[str, str]]:
    """The documented margins a case breaks (module docstring), and its pair of zones ``(zone+, zone-)``."""
    p, q = [mp.mpf(v) for v in case[0]], [mp.mpf(v) for v in case[1]]
    l0, m = mp.mpf(case[2]), mp.mpf(case[3])
    a, b, c = trace_quadratic(p, q)
    e = _edges(a, b, c)
    r, R, centre = (e[2] - e[1]) / 2, (e[3] - e[0]) / 2, -b / (2 * a)
    margin = min(r / 20, (R - r) / 10) * (1 - PROPOSAL_SLACK)
    bad = []
    for name, lam in (("lambda+", l0 + abs(m)), ("lambda-", l0 - abs(m))):
        d = min(abs(lam - x) for x in e)
        if not d >= margin:
            bad.append(f"{name} {mp.nstr(d / margin, 3)} x the margin from a band edge")
        if not abs(lam - centre) <= 2.5 * R * (1 + PROPOSAL_SLACK):
            bad.append(f"{name} {mp.nstr(abs(lam - centre) / R, 4)} R from the centre (> 2.5)")
    if not 2 * abs(m) >= r / 20 * (1 - PROPOSAL_SLACK):
        bad.append(f"2|mu| = {mp.nstr(2 * abs(m) / r, 3)} r < r/20")
    I2 = -(c - b * b / (4 * a))
    xr = abs(q[0] - q[1]) / mp.acosh(I2 / 2)
    if not mp.mpf("0.03") * (1 - PROPOSAL_SLACK) <= xr <= mp.mpf("0.97") * (1 + PROPOSAL_SLACK):
        bad.append(f"|q1 - q2| = {mp.nstr(xr, 4)} acosh(I2/2), outside [0.03, 0.97]")
    return bad, (_zone(l0 + abs(m), e), _zone(l0 - abs(m), e))


@claim("library.proposal", equation="addform", scene="library", N=2,
       where="symbt.reference.elliptic.sample_case (its proposal)",
       statement="sample_case (N = 2), 12 cases per regime and sign of q1 - q2: every lam0 +- mu at least "
                 "min(r/20, (R - r)/10) from every band edge and within 2.5 R of the centre, 2|mu| >= r/20, "
                 "|q1 - q2| in [0.03, 0.97] acosh(I2/2) (edges, centre, I2 by the literal trace), and every "
                 "zone pair of each regime occurs")
def proposal_margins() -> Outcome:
    bad: list[str] = []
    counter: dict = {}
    n = 0
    with mp.workdps(30):
        for reg in E.REGIMES:
            pairs = set()
            for xs in (1, -1):
                rng = random.Random(f"proposal {reg} {xs}")
                for _ in range(PROPOSAL_CASES):
                    case = E.sample_case(reg, rng, x_sign=xs)
                    n += 1
                    why, zones = case_violations(case)
                    pairs.add(tuple(sorted(zones, key=lambda z: ("gap", "in", "out+", "out-").index(z))))
                    if why and not bad:
                        counter = {"regime": reg, "p": case[0], "q": case[1], "lam0": case[2], "mu": case[3]}
                    bad += [f"{reg}: {w}" for w in why]
            missing = ZONE_PAIRS[reg] - pairs
            if missing:
                bad.append(f"{reg}: the zone pairs {sorted(missing)} never occur in {2 * PROPOSAL_CASES} cases")
    detail = f"{n} cases, {len(E.REGIMES)} regimes."
    if bad:
        return failed("sample_case's margins vs the band edges of the literal trace", counterexample=counter or None,
                      detail="; ".join(bad[:3]) + f" ({len(bad)} in all). " + detail)
    return Outcome("verified", "sample_case's margins vs the band edges of the literal trace", evidence="sampled",
                   detail=detail, printed="every case inside its zones with the proposal's margins")


#: library.shift_real: cases per regime (one rng stream per regime)
SHIFT_CASES, SHIFT_DPS = 3, 30


@claim("library.shift_real", equation="citn", scene="library", N=2,
       where="symbt.reference.elliptic.shift (dtheta1_real)",
       statement="shift (N = 2), 3 sample_case cases per regime, both branches: dtheta1_real is None exactly where "
                 "|tr L(lam0 +- mu)| < 2 by the literal trace, and otherwise = Re dtheta1 (log(v1 v2)) within "
                 "10^(5 - dps) of its size")
def shift_real_part() -> Outcome:
    bad, n = [], 0
    with mp.workdps(SHIFT_DPS):
        tol = mp.mpf(10) ** (5 - SHIFT_DPS)
        for reg in E.REGIMES:
            rng = random.Random(f"shift {reg}")
            for _ in range(SHIFT_CASES):
                p, q, l0, m = E.sample_case(reg, rng)
                P, Q, L0, M = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m)
                I1, I2 = E.actions(P, Q)
                in_band = any(abs(literal_trace(lam, P, Q)) < 2 for lam in (L0 + M, L0 - M))
                for b in (1, -1):
                    n += 1
                    sh = E.shift(I1, I2, L0, M, b)
                    re = sh["dtheta1_real"]
                    if in_band or re is None:
                        if in_band != (re is None):
                            bad.append(f"{reg}, b = {b}: dtheta1_real {'None' if re is None else mp.nstr(re, 5)} "
                                       f"with {'a' if in_band else 'no'} spectral parameter in a band")
                    elif not abs(re - mp.re(sh["dtheta1"])) <= tol * max(1, abs(re)):
                        bad.append(f"{reg}, b = {b}: dtheta1_real - Re dtheta1 = "
                                   f"{mp.nstr(re - mp.re(sh['dtheta1']), 3)}")
    detail = f"{n} shifts, {len(E.REGIMES)} regimes."
    if bad:
        return failed("shift's real dtheta1 vs the literal trace and Re log(v1 v2)", detail="; ".join(bad[:3]) + ". "
                      + detail)
    return Outcome("verified", "shift's real dtheta1 vs the literal trace's bands and Re log(v1 v2)",
                   evidence="sampled", detail=detail, printed="dtheta1_real = Re dtheta1 off the bands, None in them")
