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

Shown to fail on planted bugs in ``tests/test_killers_reference.py``.

>>> carlson_against_mpmath.run().status
'verified'
"""
from __future__ import annotations

import random

import mpmath as mp

from ..reference.elliptic import carlson_rf
from ..reference.samples import admissible_states
from .base import Outcome, claim, failed

#: library.carlson: accepted relative difference in units of 2^-prec (module docstring), digits, draws
RF_ULPS, RF_DPS, RF_DRAWS = 4, 50, 24
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
