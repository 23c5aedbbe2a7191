r"""Defaults, a range message and an edge rule that no claim pinned (issue 21, seed 11's ``ode:182``,
``elliptic:314``, ``coefficients:97``; seed 12's ``context:152``).

* ``library.defaults`` -- :func:`symbt.proof.solves_ode`'s default is the ordinary sample, not ``deep`` (as many
  points per cell as ``deep=False``, fewer than ``deep=True``); :func:`symbt.reference.elliptic.step2`'s default
  branch is ``+1`` (the same step as ``branch=1``, another than ``branch=-1``); the float64 orbit's
  (``float_orbit``) are ``every=1`` and ``branch=1``: the explicit call's bits, ``n + 1`` rows (seed 22).
* ``paths.dq_range.n3`` -- :class:`symbt.numeric.FlowField` and ``flow_quadrature`` at ``q = (0, -800, -400)``: the
  neighbour distance ``-800`` is beyond the float64 range while the other two are ``400``; both refuse with a
  :class:`~symbt.numeric.NumericRangeError` naming ``|q_{j+1} - q_j| = 800`` -- the cause, not a later non-finite
  intermediate (a test of the signed distances missed the negative one).
* ``paths.acosh_edge`` -- the float64 context's ``acosh_half_abs(t, g, e)`` = ``arccosh(|t| 2**e / 2)`` (its
  docstring: ``log1p`` at ``e = 0``, accurate near the band edge; ``e ln 2 + log`` for scaled traces) at
  ``|t| = 2 (1 + 2**-k)``, ``k = 10, 20, 40``, both signs, and at scaled traces ``(3, e = 1)``, ``(0.75, e = 3)``:
  within 2 ulps of ``mpmath.acosh`` at 40 digits (near the edge the ``log`` form loses about ``k/2`` bits).
"""
from __future__ import annotations

import mpmath as mp
import numpy as np
import sympy as sp

from ._facts import Facts
from ._facts import facts_failed as _bad
from ._facts import facts_verified as _ok
from .base import Outcome, claim


@claim("library.defaults", equation="checker", scene="library",
       where="symbt.proof.solves_ode (deep), symbt.reference.elliptic.step2 (branch), "
             "symbt.numeric.float64.orbit.float_orbit (every, branch)",
       statement="solves_ode's default samples as deep=False (as many per cell; deep=True takes more); step2's default "
                 "branch is +1 (the same step as branch=1, not that of branch=-1); float_orbit's defaults are every=1 "
                 "and branch=1 (the explicit call's bits, n + 1 rows)")
def defaults() -> Outcome:
    from ..proof.ode import solves_ode
    from ..reference.elliptic import step2

    got: Facts = []
    t = sp.Symbol("t")
    X = sp.Function("x")
    ode, sol = sp.Eq(X(t).diff(t), -X(t)), sp.exp(-t)
    plain = [c["n"] for c in solves_ode(ode, sol, exact=False).cells]
    shallow = [c["n"] for c in solves_ode(ode, sol, exact=False, deep=False).cells]
    deep = [c["n"] for c in solves_ode(ode, sol, exact=False, deep=True).cells]
    got.append(("solves_ode's default: the samples of deep=False per cell, fewer than deep=True's",
                (plain == shallow, sum(deep) > sum(plain)), (True, True)))
    with mp.workdps(30):
        p, q, l0, m = [mp.mpf(-1) / 2, mp.mpf(1) / 4], [mp.mpf(0), mp.mpf(1) / 3], mp.mpf(3), mp.mpf(1) / 2
        default, plus, minus = (step2(p, q, l0, m, *b)[:2] for b in ((), (1,), (-1,)))
        got.append(("step2's default branch: that of branch=1, not of branch=-1",
                    (default == plus, default != minus), (True, True)))
    # the float64 orbit's defaults (every = 1: every state, n + 1 rows; branch = 1), bit for bit the explicit call
    from ..numeric.float64.orbit import float_orbit
    from ._shipped import without_numba
    with without_numba():
        orbit = float_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 3)
        explicit = float_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 3, every=1, branch=1)
    got.append(("float_orbit's defaults: every=1 (4 rows for 3 steps), branch=1",
                (orbit[0].shape[0], all(np.array_equal(a, b) for a, b in zip(orbit, explicit))), (4, True)))
    bad = _bad("the defaults", got)
    return bad or _ok("the defaults against explicit calls", f"{len(got)} facts", "proof")


@claim("paths.dq_range", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/flow/coefficients.py: neighbour_ratios_of's range test (FlowField, flow_quadrature)",
       statement="FlowField and flow_quadrature (N={N}) at p = 0, q = (0, -800, -400), lam0 = 3, mu = 1: "
                 "NumericRangeError naming |q_{j+1} - q_j| = 800 (the one distance beyond 700; the others are 400)")
def dq_range(N: int) -> Outcome:
    from ..numeric import FlowField, NumericRangeError
    from ..numeric.flow.coefficients import flow_quadrature

    p, q = np.zeros(N), np.array([0.0, -800.0, -400.0])
    got: Facts = []
    for name, make in (("FlowField", lambda: FlowField(p, q, 3.0, 1.0)),
                       ("flow_quadrature", lambda: flow_quadrature(p, q, 3.0, 1.0))):
        try:
            make()
            seen = "no error"
        except NumericRangeError as exc:
            seen = "names 800" if "|q_{j+1} - q_j| = 800" in str(exc) else f"NumericRangeError: {exc}"
        got.append((name, seen, "names 800"))
    bad = _bad("the float64 range of the neighbour distances", got)
    return bad or _ok("FlowField and flow_quadrature at a negative neighbour distance beyond the range",
                      f"{len(got)} facts", "sampled")


#: paths.acosh_edge: (t, e) near the band edge (e = 0) and scaled
ACOSH_CASES = tuple((sgn * 2 * (1 + 2.0 ** -k), 0) for k in (10, 20, 40) for sgn in (1, -1)) + ((3.0, 1), (0.75, 3))


@claim("paths.acosh_edge", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/core/context.py: FloatContext.acosh_half_abs (log1p at e = 0, log when scaled)",
       statement="acosh_half_abs(t, g, e) = arccosh(|t| 2**e / 2) within 2 ulps of mpmath.acosh (40 digits) at "
                 "|t| = 2 (1 + 2**-k), k = 10, 20, 40, both signs, e = 0, and at (t, e) = (3, 1), (0.75, 3)")
def acosh_edge() -> Outcome:
    import math

    from ..numeric.core.context import FLOAT

    got: Facts = []
    worst = 0.0
    for t, e in ACOSH_CASES:
        c = 2.0 ** (1 - e)
        g = math.sqrt((t - c) * (t + c))        # as the kernels form it: (t - c)(t + c) is exact near the edge
        v = float(FLOAT.acosh_half_abs(np.array(t), np.array(g), e))
        with mp.workdps(40):
            ref = mp.acosh(abs(mp.mpf(t)) * 2 ** e / 2)
            ulps = float(abs(v - ref) / ref) / 2.0 ** -52
        worst = max(worst, ulps)
        got.append((f"t = {t!r}, e = {e}: within 2 ulps", ulps <= 2, True))
    bad = _bad("arccosh near the band edge", got)
    return bad or _ok("acosh_half_abs vs mpmath.acosh (40 digits)", f"{len(got)} cases, worst {worst:.3g} ulps",
                      "sampled")
