r"""The independent routes checked, 2: the sampler of the numeric claims and the Carlson integral (scene ``library``).

What the claims of the paper draw their states from, and the elliptic integral the N = 2 claims are built on,
against their documented contracts -- a slip there changes the samples or the last digits, which no verdict
of the paper shows:

* ``library.samples`` -- :func:`symbt.reference.samples.admissible_states` returns exactly ``count`` states,
  pairwise distinct, the same decimal points whatever the working precision (its docstring: exact decimal
  strings, "the same at any dps"; drawn at 30 and at 60 digits), and ``count`` states are the first ``count`` of
  ``count + 2`` (the seeded stream is read in order), for N = 2, 3 and both signs of the trace.
* ``library.carlson`` -- :func:`symbt.reference.elliptic.carlson_rf` against :func:`mpmath.elliprf` (Carlson's
  duplication in mpmath's own implementation) at 50 digits, on 24 seeded real positive triples and 24 complex
  ones off the cut: within :data:`RF_ULPS` = 4 units of 2^-prec relative.  ``carlson_rf`` runs at
  ``prec + 10`` bits with a truncation below ``2^-(prec+10)`` and rounds once; ``elliprf`` is correct to its
  last bits: both within an ulp, so 4 is a margin of 2.  A wrong term of the series (order 5, size
  ``2^-(5/6)(prec+10)``) is 60 ulps off at 50 digits.

* ``library.regime`` -- :func:`symbt.reference.elliptic.regime_of_state` (N = 2) against the zones of
  ``lambda_+- = lam0 +- mu`` read off the literal trace (:func:`~symbt.reference.literal.literal_trace`, the 2x2
  product, not the actions): ``tr < -2`` inner gap ``in``, ``|tr| <= 2`` a band (``gap`` in the module's
  s-coordinate), ``tr > 2`` outside, ``out+`` or ``out-`` by the sign of ``d tr / d lambda`` (central differences);
  the regime is ``gap`` if a zone is, ``inner`` if both are ``in``, ``outer-same`` for equal outer zones, ``mixed``
  for ``in`` and an outer zone, else ``outer-opposite`` -- on 4 cases of :func:`~symbt.reference.elliptic.sample_case`
  per regime and sign of ``q1 - q2`` (which also must be of the regime asked) and 60 uniform random draws.

Shown to fail on planted bugs in ``tests/test_killers_reference.py``.

>>> carlson_against_mpmath.run().status
'verified'
"""
from __future__ import annotations

import random

import mpmath as mp

from ..reference import elliptic as E
from ..reference.elliptic import carlson_rf
from ..reference.literal import literal_trace
from ..reference.samples import admissible_states
from .base import Outcome, claim, failed

#: library.carlson: accepted relative difference in units of 2^-prec (module docstring), digits, draws
RF_ULPS, RF_DPS, RF_DRAWS = 4, 50, 24
#: library.regime: cases per regime and sign of q1 - q2, uniform draws, the difference step of d tr / d lambda
REGIME_CASES, REGIME_DRAWS, REGIME_H = 4, 60, "1e-12"
#: library.samples: sizes and count
SAMPLE_SIZES, SAMPLE_COUNT = (2, 3), 3


def _decimals(states: list) -> list[tuple]:
    """The states as 30-digit strings (the sampler's 6-decimal values are exact there)."""
    return [tuple(mp.nstr(v, 30) for v in list(p) + list(q) + [l0, m]) for p, q, l0, m in states]


@claim("library.samples", equation="newkmu", scene="library", N=3,
       where="symbt.reference.samples.admissible_states",
       statement="admissible_states(N, s, 3) (N = 2, 3; s = +-1) gives exactly 3 distinct states, the same "
                 "decimal points at 30 and at 60 digits, and the first 3 of admissible_states(N, s, 5)")
def sampler_contract() -> Outcome:
    for N in SAMPLE_SIZES:
        for s in (1, -1):
            with mp.workdps(30):
                a = _decimals(admissible_states(N, s, SAMPLE_COUNT))
                longer = _decimals(admissible_states(N, s, SAMPLE_COUNT + 2))
            with mp.workdps(60):
                b = _decimals(admissible_states(N, s, SAMPLE_COUNT))
            where = {"N": N, "sign_tr": s}
            if len(a) != SAMPLE_COUNT or len(set(a)) != len(a):
                return failed("admissible_states: count", counterexample=where,
                              detail=f"{len(a)} states ({len(set(a))} distinct) for count {SAMPLE_COUNT}")
            if a != b:
                return failed("admissible_states: 30 vs 60 digits", counterexample=where,
                              detail="the states drawn at 60 digits are not those drawn at 30")
            if longer[:SAMPLE_COUNT] != a or len(longer) != SAMPLE_COUNT + 2:
                return failed("admissible_states: prefix", counterexample=where,
                              detail=f"count {SAMPLE_COUNT + 2} does not start with the {SAMPLE_COUNT} states")
    return Outcome("verified", "admissible_states against its documented contract", evidence="sampled",
                   detail=f"N in {SAMPLE_SIZES}, both trace signs: count, distinct, 30 = 60 digits, prefix.",
                   printed="admissible_states(N, s, count): count reproducible states")


@claim("library.carlson", equation="addform", scene="library", N=2,
       where="symbt.reference.elliptic.carlson_rf (Carlson's duplication, gmpy2 or mpmath loop)",
       statement="carlson_rf(x, y, z) = mpmath.elliprf(x, y, z) within 4 units of 2^-prec at 50 digits, on 24 "
                 "seeded real positive and 24 complex triples")
def carlson_against_mpmath() -> Outcome:
    rng = random.Random(20261126)
    worst, at = mp.mpf(0), None
    with mp.workdps(RF_DPS):
        triples = [tuple(mp.mpf(rng.uniform(0.01, 3)) for _ in range(3)) for _ in range(RF_DRAWS)]
        triples += [tuple(mp.mpc(rng.uniform(-2, 2), rng.uniform(-2, 2)) for _ in range(3)) for _ in range(RF_DRAWS)]
        for t in triples:
            ref = mp.elliprf(*t)
            e = abs(carlson_rf(*t) - ref) / (abs(ref) * mp.eps)
            if e > worst:
                worst, at = e, t
    detail = f"{2 * RF_DRAWS} triples at {RF_DPS} digits; largest difference {mp.nstr(worst, 3)} units of 2^-prec."
    if not worst <= RF_ULPS:
        return failed("carlson_rf vs mpmath.elliprf", counterexample={"xyz": [mp.nstr(v, 10) for v in at or ()]},
                      detail=detail)
    return Outcome("verified", "carlson_rf vs mpmath.elliprf at 50 digits", evidence="sampled", detail=detail,
                   printed="carlson_rf = R_F")


def _zone(lam: mp.mpf, p: list, q: list) -> str:
    """The zone of ``lam`` by the literal trace alone (module docstring)."""
    t = literal_trace(lam, p, q)
    if t < -2:
        return "in"
    if t <= 2:
        return "gap"
    h = mp.mpf(REGIME_H)
    slope = literal_trace(lam + h, p, q) - literal_trace(lam - h, p, q)
    return "out+" if slope > 0 else "out-"


def _trace_regime(p: list, q: list, lam0: mp.mpf, mu: mp.mpf) -> str:
    zp, zm = _zone(lam0 + mu, p, q), _zone(lam0 - mu, p, q)
    if "gap" in (zp, zm):
        return "gap"
    if zp == zm:
        return "inner" if zp == "in" else "outer-same"
    return "mixed" if "in" in (zp, zm) else "outer-opposite"


@claim("library.regime", equation="addform", scene="library", N=2,
       where="symbt.reference.elliptic.regime_of_state, regime and sample_case",
       statement="regime_of_state (N = 2) = the regime from the zones of lam0 +- mu by the literal trace "
                 "(tr < -2, |tr| <= 2, tr > 2 and the sign of d tr/d lambda), on 4 sample_case cases per regime "
                 "and sign of q1 - q2 (of the regime asked) and 60 uniform draws")
def regime_by_trace() -> Outcome:
    rng = random.Random(2026)
    draws: list[tuple[str | None, tuple]] = []
    for reg in E.REGIMES:
        for xs in (1, -1):
            draws += [(reg, E.sample_case(reg, rng, x_sign=xs)) for _ in range(REGIME_CASES)]
    for _ in range(REGIME_DRAWS):
        draws.append((None, ([f"{rng.uniform(-3, 3):.6f}" for _ in range(2)],
                             [f"{rng.uniform(-1.5, 1.5):.6f}" for _ in range(2)],
                             f"{rng.uniform(-5, 5):.6f}", f"{rng.uniform(0.05, 3):.6f}")))
    seen: dict[str, int] = {}
    with mp.workdps(30):
        for asked, (p, q, l0, m) in draws:
            P, Q, L0, M = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m)
            got, ref = E.regime_of_state(P, Q, L0, M), _trace_regime(P, Q, L0, M)
            seen[ref] = seen.get(ref, 0) + 1
            if got != ref or (asked is not None and asked != ref):
                return failed("regime_of_state vs the literal trace",
                              counterexample={"p": p, "q": q, "lam0": l0, "mu": m, "asked": asked},
                              detail=f"regime_of_state {got!r}, by the literal trace {ref!r}")
    return Outcome("verified", "regime_of_state vs the zones of the literal trace", evidence="sampled",
                   detail=f"{len(draws)} states; regimes by the trace: {dict(sorted(seen.items()))}.",
                   printed="regime_of_state = the regime of the spectral zones")
