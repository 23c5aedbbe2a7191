r"""A documented range rule of the float64 inputs that no claim pinned (scene ``numeric-paths``; issue 21, seed 10's
``inputs:297``).

* ``paths.spectral_overflow.n3`` -- ``bt_step`` where ``lam0`` and ``mu`` are finite doubles but ``lam0 + mu`` or
  ``lam0 - mu`` overflows (``1e308`` and ``+-1e308``): a :class:`~symbt.numeric.NumericRangeError` saying that
  ``lam0 +- mu`` overflows -- a range problem, not a statement about the spectrum (the docstring of
  ``core.inputs.prepare_spectral_pair``) -- for each of the four sign patterns, one state (scalars) and a batch of
  two (arrays); a control at ``lam0 = mu = 1e307`` (both sums finite) gets past that test.  Missing one of the two
  sums turned the overflow into a wrong "no real map" (``lam2 = lam0 - mu = 0`` in a band).
"""
from __future__ import annotations

import numpy as np

from .base import Outcome, claim, failed

#: finite doubles whose sum or difference overflows, in the four sign patterns
OVERFLOWING = ((1e308, 1e308), (-1e308, -1e308), (1e308, -1e308), (-1e308, 1e308))


@claim("paths.spectral_overflow", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       sizes=(3,),
       where="symbt/numeric/core/inputs.py: prepare_spectral_pair's range test (scalars and arrays)",
       statement="bt_step, N={N}, p = 0, q = (0, 1, 2), at lam0, mu = (1e308, 1e308), (-1e308, -1e308), "
                 "(1e308, -1e308), (-1e308, 1e308) (lam0 + mu or lam0 - mu overflows): NumericRangeError naming "
                 "'lam0 +- mu overflows', for one state and a batch of two; at lam0 = mu = 1e307 no such error")
def spectral_overflow(N: int) -> Outcome:
    from ..numeric import NumericRangeError, bt_step

    p, q = np.zeros(N), np.arange(float(N))
    bad, seen = [], []
    for l0, m in OVERFLOWING:
        for what, args in (("one state", (p, q, l0, m)),
                           ("a batch of two", (np.stack([p, p]), np.stack([q, q]), np.array([l0, l0]),
                                               np.array([m, m])))):
            try:
                bt_step(*args)
                got = "a state"
            except NumericRangeError as exc:
                got = "range" if "lam0 +- mu overflows" in str(exc) else f"NumericRangeError: {exc}"
            except Exception as exc:  # noqa: BLE001 -- any other outcome is the finding
                got = f"{type(exc).__name__}: {exc}"
            seen.append(got)
            if got != "range":
                bad.append(f"lam0 = {l0:g}, mu = {m:g}, {what}: {got}")
    try:
        bt_step(p, q, 1e307, 1e307, backend="numpy")    # past the range test; the numpy route loads no numba
        control = "a state"
    except Exception as exc:  # noqa: BLE001 -- the control only asks that the range test lets it pass
        control = f"{type(exc).__name__}: {exc}"
    if "lam0 +- mu overflows" in control:
        bad.append(f"lam0 = mu = 1e307 (both sums finite): {control}")
    detail = f"{seen.count('range')} of {len(seen)} overflowing calls refused as a range problem; 1e307: {control}."
    if bad:
        return failed("numeric: the range test of lam0 +- mu", detail="; ".join(bad[:6]) + ". " + detail)
    return Outcome("verified", "numeric: bt_step at finite lam0, mu whose sum or difference overflows",
                   evidence="sampled", detail=detail, printed="NumericRangeError for every sign pattern")
