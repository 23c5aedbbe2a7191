r"""The library's moment condition: the inverse problem refuses unattainable targets (scene ``library``, issue 21).

The flow coefficients are moments :math:`c_k = \int \lambda^k w(\lambda)\,d\lambda` of a positive weight
(:math:`w = 1/\sqrt{\operatorname{tr}^2 - 4}` on an interval of a gap, times a sign), so by Cauchy--Schwarz
:math:`c_0 c_2 > c_1^2` strictly wherever they exist, and
:func:`~symbt.reference.inverse.solve_parameters` refuses a target with :math:`c_0 c_2 \le c_1^2` (modes
``exact`` with the indices 0, 1, 2 and ``direction``) before any Newton step, with that reason.

* ``library.moments`` -- the inequality itself on the paper's N = 3 orbit at several :math:`(\lambda_0, \mu)`,
  both branches, by :func:`~symbt.reference.spectral.flow_coefficients_mp` (the independent side: the
  quadrature the forward map uses, not the solver); and the refusal on both sides of the boundary: targets
  with :math:`c_0 c_2 = c_1^2` exactly (``(1, 2, 4)``, exact in binary; mode ``direction``) and
  :math:`c_0 c_2 < c_1^2` (both modes) are refused with the Cauchy--Schwarz reason, an attainable target (the
  paper's own :math:`c_k`) is solved.  The boundary matters: it is the limit :math:`\mu \to 0` (a point mass
  at :math:`\lambda_0`), so without the refusal ``direction`` "solves" ``(1, 2, 4)`` with
  :math:`\lambda_0 = 2` and a vanishing :math:`\mu` -- a target no :math:`\mu \ne 0` attains.

Shown to fail on a planted bug in ``tests/test_killers_reference.py``.
"""
from __future__ import annotations

import mpmath as mp

from ..reference.inverse import solve_parameters
from ..reference.samples import paper_state
from ..reference.spectral import flow_coefficients_mp
from .base import Outcome, claim, failed

#: (lam0, mu) on the paper's orbit: both spectral parameters in the gap of lam0 = 10 (the claim library.inverse's)
MOMENT_POINTS = (("10", "1"), ("10", "0.25"), ("9.5", "0.5"))
#: targets (c0, c1, c2) on and beyond the boundary c0 c2 = c1**2 (exact binary numbers)
REFUSED = ((1, 2, 4), (1, 2, 3), (-1, 2, -4))


@claim("library.moments", equation="linearcomb", scene="library", N=3,
       where="symbt.reference.inverse.solve_parameters (the Cauchy-Schwarz refusal); "
             "symbt.reference.spectral.flow_coefficients_mp",
       statement="c_0 c_2 > c_1^2 for the c_k of the paper's N = 3 orbit at three (lam0, mu), both branches; "
                 "solve_parameters refuses (1, 2, 4) (mode direction), (1, 2, 3), (-1, 2, -4) (modes direction and "
                 "exact) with the Cauchy-Schwarz reason, and solves the paper's own c_k")
def moment_condition() -> Outcome:
    bad = []
    with mp.workdps(15):
        p, q, _, _ = paper_state("1")
        for l0, m in MOMENT_POINTS:
            for b in (1, -1):
                c = flow_coefficients_mp(p, q, mp.mpf(l0), mp.mpf(m), b)
                if c[0] is None or c[1] is None or c[2] is None or not c[0] * c[2] > c[1] ** 2:
                    bad.append(f"c_0 c_2 <= c_1^2 at lam0 = {l0}, mu = {m}, b = {b}")
        for target in REFUSED:
            modes: list[dict] = [{"mode": "direction"}]
            if target[0] * target[2] != target[1] ** 2:      # at the boundary exact mode's Newton would run long
                modes.append({"mode": "exact", "indices": (0, 1, 2)})
            for kw in modes:
                try:
                    r = solve_parameters(p, q, [mp.mpf(v) for v in target], **kw)
                    bad.append(f"{target} ({kw['mode']}): solved, lam0 = {mp.nstr(r['lam0'], 6) if r else None}")
                except ValueError as exc:
                    if "Cauchy-Schwarz" not in str(exc):
                        bad.append(f"{target} ({kw['mode']}): refused for another reason: {str(exc)[:80]}")
        c = flow_coefficients_mp(p, q, mp.mpf(10), mp.mpf(1), 1)
        try:
            solve_parameters(p, q, c, mode="direction")
        except ValueError as exc:
            bad.append(f"the paper's own c_k refused: {str(exc)[:80]}")
    detail = f"{2 * len(MOMENT_POINTS)} forward points, {2 * len(REFUSED)} refused targets, 1 attainable one."
    if bad:
        return failed("solve_parameters' moment condition", detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "reference: Cauchy-Schwarz on the forward map's c_k; the solver's refusals on both "
                   "sides of c_0 c_2 = c_1^2", evidence="sampled", detail=detail,
                   printed="c_0 c_2 > c_1^2; targets without it are refused")
