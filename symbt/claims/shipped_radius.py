r"""What ships, 4j: the growth record of an orbit whose radius stays 0 (scene ``numeric-paths``, issue 21).

* ``paths.zero_radius.n3`` -- :func:`~symbt.numeric.multiprec.certified.certified_orbit` (the Lohner method) with
  ``mu = 0`` on exact input: the map is the identity, and in ball arithmetic every step multiplies by an exact
  ``2 mu = 0`` and adds ``log1p(0) = 0``, so every returned radius is exactly 0 and the midpoints are the input;
  ``info["growth"]`` (:func:`~symbt.numeric.multiprec.lohner.growth_law`: ``log2`` of the largest radius at its
  first and last step) must record ``log2(0) = -inf`` at both, with no fitted degree.

Shown to fail on a planted bug in ``tests/test_killers_numeric2.py``.
"""
from __future__ import annotations

import importlib.util
import math

import mpmath as mp

from .base import Outcome, claim, failed, skipped

#: paths.zero_radius: the paper's state, exact binary input, the steps
ZERO_P, ZERO_Q, ZERO_LAM0, ZERO_STEPS = (-20, 10, 1), (1, 0, 0.9), 10, 3


@claim("paths.zero_radius", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: the growth record (_lograd, growth_law) of a zero radius",
       statement="certified_orbit (Lohner) with mu = 0 on the paper's state (N={N}, exact input), 3 steps, 30 "
                 "digits: the input with every radius exactly 0, and info['growth'] = log2 of the largest radius = "
                 "-inf at its first and last step, degree None")
def zero_radius(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from ..numeric.multiprec.certified import certified_orbit

    info: dict[str, object] = {}
    with mp.workdps(30):
        P, Q, Pr, Qr = certified_orbit(list(ZERO_P), list(ZERO_Q), ZERO_LAM0, 0, ZERO_STEPS, info=info)
    growth = info.get("growth")
    bad = []
    if info.get("method") != "lohner":
        bad.append(f"method {info.get('method')}, not lohner")
    if any(r != 0 for row in list(Pr) + list(Qr) for r in row):
        bad.append("a radius is not 0")
    if [list(P[-1]), list(Q[-1])] != [[mp.mpf(v) for v in ZERO_P], [mp.mpf(v) for v in ZERO_Q]]:
        bad.append("the last state is not the input")
    if not (isinstance(growth, dict) and growth.get("degree") is None
            and growth.get("log2_radius") == (-math.inf, -math.inf)):
        bad.append(f"growth record {growth}")
    detail = f"growth record {growth}; method {info.get('method')}."
    if bad:
        return failed("numeric: the growth record of a zero radius vs log2(0) = -inf", detail="; ".join(bad) + ". "
                      + detail)
    return Outcome("verified", "numeric: the growth record of a zero radius vs log2(0) = -inf", evidence="sampled",
                   detail=detail, printed="radii 0, log2_radius (-inf, -inf), degree None")
