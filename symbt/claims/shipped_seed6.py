r"""Documented rules of the float64 library that no other claim pinned (scene ``numeric-paths``; issue 21, seed 6's
``rows:209``, seed 8's ``coefficients:226`` and its uncovered ``orbit:345``).

* ``paths.rows_out.n3`` -- :func:`~symbt.numeric.float64.rows.float_rows_step` with ``rows`` and ``out`` (how the
  batched kernel step hands back the members its kernel gave up on): the rows named are stepped, the others are
  taken from ``out`` (its docstring), and the result is written into ``out``'s arrays.  Three rows -- the paper's
  state, another state, the paper's state shifted by 1/2 in ``q`` -- with ``rows = [0, 2]`` and ``out`` filled with
  ``+7`` (``p``) and ``-7`` (``q``): row 1 of the result is ``out``'s row 1 exactly, rows 0 and 2 are within
  ``1e-12 (1 + |x|)`` of the literal map at 40 digits (the paper's state is well conditioned: the float64 step is
  ~1e-15 off there), ``p~`` in ``out[0]`` and ``q~`` in ``out[1]``.

* ``paths.panels`` -- :func:`~symbt.numeric.flow.coefficients.adaptive_panels` (the panels of
  :func:`symbt.numeric.flow_coefficients`) on four integrands over ``[-1, 3]`` -- ``1/sqrt(x + 1 + 2**-10)`` (near
  a singularity), ``sin(60 x) e^x`` (panels whose integrals cancel; its integral is negative), a tiny peak
  ``1e-6 / sqrt(|x - 0.3| + 1e-4)``, ``-1/sqrt(3 + 2**-10 - x)`` (negative, near the other end) -- alone and with
  the peak grouped with the fourth row (a group's scale is its largest *size*, here a negative row's): the panels tile
  ``[-1, 3]``, every panel meets the documented test (16- and 32-point Gauss--Legendre agree to ``rtol`` relative
  to ``max(|local integral|, scale * width / (b - a))``, ``scale`` the row's whole integral or its group's
  largest) and no panel's bisection parent does (the panels are the coarsest bisection that passes), evaluated
  here with numpy's own Gauss--Legendre nodes; grouping the peak with the fourth row takes fewer panels; the
  budget is exact: with ``max_intervals`` the number of panels needed it gives the same panels, with one fewer it
  raises :class:`~symbt.numeric.QuadratureError` (seed 26: the count started at 0, one panel past the budget).
  (All ends are dyadic: the bisection points are exact, so the parents are recomputed exactly.)
* ``paths.q_low.n3`` -- ``bt_orbit(..., q_low=True)`` (the low parts of the carried positions, docs/numeric.md "Long
  orbits"), kernel and general path, both branches, 3 steps of the paper's state moved to ``q + 1e6 + 0.1`` (where
  a double's rounding is ``ulp(1e6) = 1.2e-10``): ``P`` and ``Q`` bit for bit those of ``q_low=False``, ``|Q_low|
  <= ulp(Q)/2``, and the neighbour differences of ``Q + Q_low`` within ``16 N n eps (1 + max |d|)`` of the literal
  orbit's (40 digits, from the same double inputs), while those of ``Q`` alone are not (a control: the low parts
  carry what the rounding at ``|q| ~ 1e6`` drops).

Shown to fail on planted bugs in ``tests/test_killers_controls.py``.

>>> rows_out(3).status
'verified'
"""
from __future__ import annotations

import mpmath as mp
import numpy as np

from .base import Outcome, claim, failed

#: paths.rows_out: the three rows (p, q), lam0, mu, the rows stepped, the fill of out (p, q)
ROWS_P = ((-20.0, 10.0, 1.0), (1.0, -2.0, 0.5), (-20.0, 10.0, 1.0))
ROWS_Q = ((1.0, 0.0, 0.9), (0.0, 0.3, -0.2), (1.5, 0.5, 1.4))
ROWS_LAM0, ROWS_MU, ROWS_STEPPED, ROWS_FILL = 10.0, 5.0, (0, 2), (7.0, -7.0)


@claim("paths.rows_out", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/rows.py: float_rows_step(rows=..., out=...)",
       statement="float_rows_step on 3 rows (N={N}) with rows = [0, 2] and out filled with +7 (p) and -7 (q): row 1 "
                 "is out's row 1 exactly, rows 0 and 2 within 1e-12 (1 + |x|) of the literal map at 40 digits, p~ "
                 "written into out[0] and q~ into out[1]")
def rows_out(N: int) -> Outcome:
    from ..numeric.float64.rows import float_rows_step
    from ..reference.literal import literal_step

    pa, qa = np.array(ROWS_P), np.array(ROWS_Q)
    out = (np.full(pa.shape, ROWS_FILL[0]), np.full(qa.shape, ROWS_FILL[1]))
    pt, qt = float_rows_step(pa, qa, ROWS_LAM0, ROWS_MU, 1, False, (len(pa),), rows=np.array(ROWS_STEPPED),
                             out=out)
    bad, worst = [], 0.0
    if pt is not out[0] or qt is not out[1]:
        bad.append("the result is not written into out's arrays (p~ into out[0], q~ into out[1])")
    for i in range(len(pa)):
        if i not in ROWS_STEPPED:
            if not (np.all(pt[i] == ROWS_FILL[0]) and np.all(qt[i] == ROWS_FILL[1])):
                bad.append(f"row {i} (not stepped): {pt[i].tolist()}, {qt[i].tolist()}, not out's row")
            continue
        with mp.workdps(40):
            rp, rq, _ = literal_step([mp.mpf(v) for v in pa[i]], [mp.mpf(v) for v in qa[i]], mp.mpf(ROWS_LAM0),
                                     mp.mpf(ROWS_MU), 1)
            ref = [float(v) for v in rp + rq]
        got = list(pt[i]) + list(qt[i])
        err = max(abs(a - b) / (1 + abs(b)) for a, b in zip(got, ref))
        worst = max(worst, err)
        if not err <= 1e-12:
            bad.append(f"row {i}: {err:.3g} (relative to 1 + |x|) from the literal map")
    detail = f"rows {list(ROWS_STEPPED)} stepped, worst {worst:.2g} (accepted 1e-12); the other row out's"
    if bad:
        return failed("numeric: float_rows_step(rows, out) vs the literal map and out", detail="; ".join(bad))
    return Outcome("verified", "numeric: float_rows_step(rows, out) vs the literal map (40 digits) and out",
                   evidence="sampled", n_scope=[N], residual=worst, detail=detail)


#: paths.panels: the interval (dyadic ends), the tolerance, the panels allowed, the grouping (the peak with row 0)
PANELS_A, PANELS_B, PANELS_RTOL, PANELS_MAX, PANELS_GROUPS = -1.0, 3.0, 1e-12, 400, (0, 1, 2, 2)


def _panel_rows(x: np.ndarray) -> np.ndarray:
    # the peak (third row) is grouped with the fourth; both are negative: the group's scale is the larger size
    # |integral| (a signed maximum would pick the tiny peak's own), and a panel at the peak, whose local integral
    # is far above its share of the whole, is judged against |local| (a signed local would judge it against the
    # share alone: seed 18)
    return np.stack([1 / np.sqrt(x + 1.0009765625), np.sin(60 * x) * np.exp(x),
                     -1e-6 / np.sqrt(np.abs(x - 0.3) + 1e-4), -1 / np.sqrt(3.0009765625 - x)])


def _panel_rule(lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """32- and 16-point Gauss--Legendre of the rows on ``[lo, hi]`` (numpy's nodes)."""
    out = []
    for n in (32, 16):
        x, w = np.polynomial.legendre.leggauss(n)
        c, h = 0.5 * (lo + hi), 0.5 * (hi - lo)
        out.append(h * (_panel_rows(c + h * x) @ w))
    return out[0], out[1]


def _panel_passes(lo: float, hi: float, scale: np.ndarray) -> bool:
    i32, i16 = _panel_rule(lo, hi)
    share = scale * (hi - lo) / (PANELS_B - PANELS_A)
    return bool(np.all(np.abs(i32 - i16) <= PANELS_RTOL * np.maximum(np.abs(i32), share)))


def panel_faults(panels: list[tuple[float, float]], groups: tuple[int, ...] | None) -> list[str]:
    """What breaks the documented rule in ``panels`` (see the module docstring)."""
    a, b = PANELS_A, PANELS_B
    whole = np.abs(_panel_rule(a, b)[0])
    scale = whole if groups is None else np.array([max(whole[[i for i, h in enumerate(groups) if h == g]])
                                                     for g in groups])
    bad = []
    if [lo for lo, _ in panels] != [a] + [hi for _, hi in panels[:-1]] or panels[-1][1] != b:
        bad.append(f"the panels do not tile [{a:g}, {b:g}]")
    for lo, hi in panels:
        if not _panel_passes(lo, hi, scale):
            bad.append(f"[{lo:g}, {hi:g}] fails the test")
        w = hi - lo
        if w < b - a:
            parent = (lo, hi + w) if round((lo - a) / w) % 2 == 0 else (lo - w, hi)
            if _panel_passes(*parent, scale):
                bad.append(f"[{lo:g}, {hi:g}]'s parent [{parent[0]:g}, {parent[1]:g}] passes: it was split")
    return bad


@claim("paths.panels", equation="flow", source_equation="eqdisc", scene="numeric-paths",
       where="symbt/numeric/flow/coefficients.py: adaptive_panels",
       statement="adaptive_panels on four integrands over [-1, 3] (near a singularity at either end, the second "
                 "negative, cancelling panels, a tiny negative peak), alone and with the peak grouped with the "
                 "negative one: the panels tile the interval, each passes the documented 16/32-point test against "
                 "max(|local|, scale * width share) and no "
                 "bisection parent does (numpy's Gauss-Legendre nodes); grouping takes fewer panels; "
                 "max_intervals = the panels needed gives them, one fewer QuadratureError")
def panels() -> Outcome:
    from ..numeric import QuadratureError
    from ..numeric.flow.coefficients import adaptive_panels

    bad, counts = [], []
    alone: list[tuple[float, float]] = []
    for groups in (None, PANELS_GROUPS):
        got = adaptive_panels(_panel_rows, PANELS_A, PANELS_B, PANELS_RTOL, PANELS_MAX,
                              None if groups is None else np.array(groups))
        counts.append(len(got))
        alone = got if groups is None else alone
        bad += [f"{'grouped' if groups else 'alone'}: {b}" for b in panel_faults(got, groups)]
    if not counts[1] < counts[0]:
        bad.append(f"grouped {counts[1]} panels, alone {counts[0]}: the group's scale did not relax the peak")
    # the budget is exact: the panels needed fit max_intervals = their number, one fewer raises
    if adaptive_panels(_panel_rows, PANELS_A, PANELS_B, PANELS_RTOL, counts[0]) != alone:
        bad.append(f"max_intervals = {counts[0]}, the panels needed, did not give the same panels")
    try:
        got = adaptive_panels(_panel_rows, PANELS_A, PANELS_B, PANELS_RTOL, counts[0] - 1)
        bad.append(f"max_intervals {counts[0] - 1} (of {counts[0]} needed) gave {len(got)} panels, no "
                   "QuadratureError")
    except QuadratureError:
        pass
    detail = f"{counts[0]} panels alone, {counts[1]} grouped; each passes, no parent does."
    if bad:
        return failed("numeric: adaptive_panels vs its documented test", detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: adaptive_panels vs its documented test (numpy's Gauss-Legendre)",
                   evidence="sampled", n_scope="all", detail=detail)


#: paths.q_low: the state (the paper's, moved far along q), the steps, the digits of the literal orbit
QLOW_P, QLOW_Q, QLOW_LAM0, QLOW_MU = (-20.0, 10.0, 1.0), tuple(x + 1e6 + 0.1 for x in (1.0, 0.0, 0.9)), 10.0, 5.0
QLOW_STEPS, QLOW_DPS = 3, 40


@claim("paths.q_low", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/orbit.py: float_orbit_low (bt_orbit(q_low=True))",
       statement="bt_orbit(q_low=True) (N={N}), kernel and general path, both branches, 3 steps of the paper's state "
                 "at q + 1e6 + 0.1: P, Q bit for bit those of q_low=False, |Q_low| <= ulp(Q)/2, the neighbour "
                 "differences of Q + Q_low within 16 N n eps (1 + max|d|) of the literal orbit's (40 digits), those "
                 "of Q alone not; at mu = 0 and at n = 0 the input repeated with zero low parts")
def q_low(N: int) -> Outcome:
    from ..numeric import bt_orbit
    from ..reference.literal import literal_step

    bad, worst = [], 0.0
    n = QLOW_STEPS
    for b in (1, -1):
        with mp.workdps(QLOW_DPS):
            pp, qq = [mp.mpf(x) for x in QLOW_P], [mp.mpf(x) for x in QLOW_Q]
            for _ in range(n):
                pp, qq, _ = literal_step(pp, qq, QLOW_LAM0, QLOW_MU, b)
            dref = [qq[(j + 1) % N] - qq[j] for j in range(N)]
        bound = 16 * N * n * 2.0 ** -52 * (1 + float(max(abs(d) for d in dref)))
        for be in ("python", "numpy"):
            P, Q, L = bt_orbit(np.array(QLOW_P), np.array(QLOW_Q), QLOW_LAM0, QLOW_MU, n, branch=b, q_low=True,
                               backend=be)
            P0, Q0 = bt_orbit(np.array(QLOW_P), np.array(QLOW_Q), QLOW_LAM0, QLOW_MU, n, branch=b, backend=be)
            if not (np.array_equal(P, P0) and np.array_equal(Q, Q0)):
                bad.append(f"{be}, b = {b}: P, Q differ from those of q_low=False")
            if not bool(np.all(np.abs(L) <= np.spacing(np.abs(Q)) / 2)):
                bad.append(f"{be}, b = {b}: a low part exceeds half an ulp of its position")
            both = [mp.mpf(float(Q[-1][(j + 1) % N])) - mp.mpf(float(Q[-1][j]))
                    + mp.mpf(float(L[-1][(j + 1) % N])) - mp.mpf(float(L[-1][j])) for j in range(N)]
            high = [mp.mpf(float(Q[-1][(j + 1) % N])) - mp.mpf(float(Q[-1][j])) for j in range(N)]
            e_both = float(max(abs(a - r) for a, r in zip(both, dref)))
            e_high = float(max(abs(a - r) for a, r in zip(high, dref)))
            worst = max(worst, e_both / bound)
            if not e_both <= bound:
                bad.append(f"{be}, b = {b}: Q + Q_low's differences {e_both:.3g} off the literal orbit's "
                           f"(bound {bound:.3g})")
            if not e_high > bound:
                bad.append(f"{be}, b = {b}: control: Q alone is within the bound ({e_high:.3g}): the state does not "
                           "test the low parts")
    # mu = 0 (the identity) and n = 0: the input repeated, its low parts 0, in the documented shapes
    for mu, steps in ((0.0, n), (QLOW_MU, 0)):
        P, Q, L = bt_orbit(np.array(QLOW_P), np.array(QLOW_Q), QLOW_LAM0, mu, steps, q_low=True)
        want = np.tile(np.array(QLOW_Q), (steps + 1, 1))
        if not (np.array_equal(Q, want) and np.array_equal(L, np.zeros_like(want))
                and np.array_equal(P, np.tile(np.array(QLOW_P), (steps + 1, 1)))):
            bad.append(f"mu = {mu}, n = {steps}: not the input repeated with zero low parts (shapes {np.shape(Q)}, "
                       f"{np.shape(L)})")
    detail = f"kernel and general path, both branches: worst {worst:.3g} x the bound."
    if bad:
        return failed("numeric: bt_orbit(q_low=True) vs the literal orbit", detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: bt_orbit(q_low=True) vs the literal orbit (40 digits)", evidence="sampled",
                   detail=detail)
