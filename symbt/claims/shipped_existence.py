r"""What ships, 4f: certified orbits decide existence on whole balls (scene ``numeric-paths``, issue 21).

:func:`symbt.numeric.certified_orbit` steps with the context
:data:`~symbt.numeric.multiprec.arb.ARB_CERTAIN`: existence -- the traces of one sign, every
:math:`\tilde E_j / E_j = 1 + x_j > 0` -- is decided only where it holds on the whole ball, and a ball
certainly on the wrong side is a :class:`~symbt.numeric.NoRealMapError` (condition ``positivity``), not a
number: the issue's "existence is decided alike on every route".

* ``paths.certified_nomap.n3`` -- ``certified_orbit`` (methods ``ball`` and ``lohner``, one step, 30 digits) on
  the states without a real map of ``shipped.nomap`` (traces of opposite signs; some :math:`\tilde E_j \le 0`),
  both branches, whose absence of a real map is decided by the literal route of :mod:`symbt.reference` at 50
  digits with guard digits (the independent side): each raises ``NoRealMapError`` with the condition the
  float64 single-state call ``bt_step(backend="numpy")`` gives.  A positivity test that accepts a ball certainly
  at or below 0 computes on -- the logarithm of a negative ball -- and ends in another error or a number.

Shown to fail on a planted bug in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

import importlib.util
from typing import Literal

import mpmath as mp
import numpy as np

from .base import Outcome, claim, failed, skipped

#: paths.certified_nomap: the digits and the methods
NOMAP_DPS = 30
NOMAP_METHODS: tuple[Literal["ball", "lohner"], ...] = ("ball", "lohner")


def _error(fn: object) -> BaseException | None:
    try:
        fn()  # type: ignore[operator]
    except Exception as exc:  # compared by type and condition by the caller
        return exc
    return None


@claim("paths.certified_nomap", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths",
       sizes=(3,), requires=("flint",),
       where="symbt/numeric/multiprec/arb.py (ARB_CERTAIN.positive), certified.py, lohner.py",
       statement="certified_orbit (ball and lohner, one step, 30 digits, N={N}) on the states without a real map "
                 "(opposite traces; some E~_j <= 0; decided by the literal route at 50 digits), both branches: "
                 "NoRealMapError with the condition of bt_step(backend='numpy') on the same state")
def certified_nomap(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from ..numeric import NoRealMapError, bt_step, certified_orbit
    from .shipped_emitted import nomap_states

    bad, n = [], 0
    for st, b, (cond, decided) in nomap_states(N):
        if not decided:
            continue
        single = _error(lambda: bt_step(np.array(st[0]), np.array(st[1]), st[2], st[3], branch=b, backend="numpy"))
        want = getattr(single, "condition", None)
        for method in NOMAP_METHODS:
            n += 1
            with mp.workdps(NOMAP_DPS):
                exc = _error(lambda: certified_orbit(list(st[0]), list(st[1]), st[2], st[3], 1, branch=b,
                                                     method=method))
            if not isinstance(exc, NoRealMapError) or not isinstance(single, NoRealMapError):
                bad.append(f"{cond}, branch {b}, {method}: {type(exc).__name__ if exc else 'a state'} "
                           f"(float64: {type(single).__name__ if single else 'a state'})")
            elif exc.condition != want:
                bad.append(f"{cond}, branch {b}, {method}: condition {exc.condition!r}, float64 {want!r}")
    detail = f"{n} certified orbits on states without a real map."
    if not n:
        return skipped("no state without a real map was decided by the literal route")
    if bad:
        return failed("numeric: certified orbits on states without a real map", detail="; ".join(bad[:3]) + ". "
                      + detail)
    return Outcome("verified", "numeric: certified orbits vs the literal route's decision (no real map)",
                   evidence="sampled", detail=detail, printed="NoRealMapError, the float64 condition")
