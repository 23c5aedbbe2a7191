r"""What ships, 4d: the float64 kernels' decisions and re-anchoring, two numeric helpers' edges (scene
``numeric-paths``, issue 21).

The fused kernel (:mod:`symbt.numeric.float64.kernels`, the hooks of :mod:`symbt.numeric.core.fused`) and the
block kernel (:mod:`symbt.numeric.float64.kernels_block`) are two implementations of one step, documented to
agree bit for bit (docs/numeric.md) -- their statuses included: a member the block kernel hands back goes the
way the single-state call goes.  Their condition estimates decide only *which* states are handed back to the
general path, which is right for every state, so accuracy claims cannot see a slip there; the statuses can.

* ``paths.threshold.n3`` -- the paper's state and its mirror image ``p -> -p`` (whose bands are the paper's
  negated: ``tr L(-lam; -p) = (-1)**N tr L(lam; p)``, so the cancellation in ``a_j = lam + p_j`` falls on a
  negative ``p_j``), with ``lam1`` (or ``lam2``) at ``delta`` of the gap's width inside a band edge and the
  other at the gap's middle, ``delta = 10**(-k/16)`` for ``k = 64 .. 127`` (1e-4 to 1e-8: across
  ``KAPPA_MAX`` = 2^24, both branches): at every state the fused kernel
  (:func:`~symbt.numeric.float64.orbit.kernel_step`) and the block kernel take the same decision (handed back
  = status ``ILLCOND``, else status ``OK`` and the same bits), and so does the numpy route of ``bt_step``'s
  batches (:func:`~symbt.numeric.core.step.float_status` of one vectorised ``step_core``: "in the order of the
  fused kernels") -- a consistency check of three implementations of one documented estimate (its positivity
  term takes the larger of the two traces' conditions); the scan must cross the threshold (its widest state
  finished, its narrowest handed back), and the finished state nearest each edge -- the most ill-conditioned
  one a kernel keeps -- is the literal map of :mod:`symbt.reference.literal` within ``16 N eps S_i`` (the
  independent route).
* ``paths.anchored.n3`` -- the fused orbit (:func:`~symbt.numeric.float64.kernels.orbit`) and the block
  kernel's ensemble, ``2 ANCHOR + 3`` steps stored at every step, one state per cell: both pass the
  re-anchoring (the double-double flush of ``F`` into ``q`` and ``r = exp(dq)``) twice, and must agree bit
  for bit at every step (documented; a consistency check -- the orbits' accuracy against the literal map is
  ``shipped.orbit``'s) with status 0.
* ``paths.ill_member.n3`` -- ``bt_orbit(backend="numpy")`` (the general path, :func:`~symbt.numeric.float64.orbit.
  general_orbit`) on two-member ensembles, a moderate state and one of ``paths.kernels``' band-edge states
  (``lam1`` or ``lam2`` 1e-9 of the gap inside an edge: status ``ILLCOND`` at every step, escalated to higher
  precision), 3 steps: each member is the literal orbit within ``16 N n eps S_i`` (the orbit bound of
  ``shipped.orbit``) and equals its single-state call bit for bit (documented) -- the escalated member's place
  in the batch (the second) is where an index slip in the escalation shows; and ``bt_step(backend="numpy")`` on
  the same batches (the numpy rows of :mod:`symbt.numeric.float64.rows`, which escalate the ``ILLCOND`` row
  themselves): each member within ``16 N eps S_i`` of the literal step and equal to its single-state step.
* ``paths.edges.n3`` -- :func:`~symbt.numeric.multiprec.lohner.growth_law` without two usable points
  (one recorded step, or every radius zero) returns ``degree = None`` as documented, with exactly two the slope
  between them (``log2 rad = 5, 8`` at steps 1, 2: degree 3), and the float64
  context's ``out_of_range`` (the monodromy's rescaling trigger) on complex rows against its documented
  per-entry rule ``|x| > 2**500 or nan`` (the large side), evaluated entry by entry with Python's ``abs``;
  and the float64 range limit ``MAX_DQ_FLOAT64`` (700, the largest neighbour distance ``|q_{j+1} - q_j|``,
  docs/numeric.md) on both sides, where one distance is large and the others are not: ``invariants`` and
  ``phi`` at ``q = (0, 700, 0)`` return finite values, at ``(0, 700.1, 0)`` raise ``NumericRangeError``.

Shown to fail on planted bugs in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

import math
from functools import cache
from typing import Any

import mpmath as mp
import numpy as np

from ..reference.literal import literal_trace
from ._shipped import (
    EPS,
    Tally,
    orbit_ref,
    ratios,
    scale_parts,
    scaled,
    ship_cells,
    step_constant,
    step_ref,
    without_numba,
)
from .base import Outcome, Parts, claim, failed
from .shipped_paths import _block_kernel, edge_states

#: paths.threshold: delta = 10**(-k / THRESHOLD_DIV) of the gap's width, k in THRESHOLD_KS
THRESHOLD_DIV, THRESHOLD_KS = 16, range(64, 128)
#: the paper's N = 3 state and the rough ends of its gap (refined by findroot on the literal trace)
PAPER_P, PAPER_Q, PAPER_GAP = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), ((-10.28, -10.26), (-0.80, -0.79))


@cache
def _gap(p: tuple, guesses: tuple) -> tuple[float, float]:
    """The gap's edges: ``tr L(lam) = +-2`` by ``findroot`` on the literal trace at 40 digits."""
    with mp.workdps(40):
        s = mp.sign(literal_trace(mp.mpf((guesses[0][0] + guesses[1][0]) / 2), p, PAPER_Q))
        lo, hi = (float(mp.findroot(lambda x: literal_trace(x, p, PAPER_Q) - 2 * s, x0, solver="anderson"))
                  for x0 in guesses)
    return lo, hi


@cache
def threshold_states() -> tuple:
    """``(label, branch, states)``: per state (paper / mirror), edge (top / bottom) and branch, the scan of
    ``delta`` from the widest to the narrowest."""
    mirror = tuple(-x for x in PAPER_P)
    out = []
    for name, p, guesses in (("paper", PAPER_P, PAPER_GAP),
                             ("mirror", mirror, tuple((-b, -a) for a, b in reversed(PAPER_GAP)))):
        lo, hi = _gap(p, guesses)
        mid = (lo + hi) / 2
        for side in ("top", "bottom"):
            rows = []
            for k in THRESHOLD_KS:
                d = 10 ** (-k / THRESHOLD_DIV) * (hi - lo)
                l1, l2 = (hi - d, mid) if side == "top" else (mid, lo + d)
                rows.append((p, PAPER_Q, (l1 + l2) / 2, (l1 - l2) / 2))
            for b in (1, -1):
                out.append((f"{name} {side}", b, tuple(rows)))
    return tuple(out)


def _numpy_rows_status(rows: tuple, b: int) -> Any:
    """The statuses the numpy route of ``bt_step``'s batches gives the states ``rows`` (one vectorised
    :func:`~symbt.numeric.core.step.step_core` and :func:`~symbt.numeric.core.step.float_status`, as
    ``float64.rows`` decides a block; no escalation)."""
    from ..numeric.core.context import FLOAT
    from ..numeric.core.step import float_status, step_core

    pa, qa = np.array([st[0] for st in rows]), np.array([st[1] for st in rows])
    l0, m = np.array([st[2] for st in rows]), np.array([st[3] for st in rows])
    with np.errstate(all="ignore"):
        Pn, Qn, aux = step_core(FLOAT, list(pa.T.copy()), list(qa.T.copy()), l0, m, b, check_real=False)
    return float_status(aux, Pn, Qn)


@claim("paths.threshold", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/float64/kernels.py (the fused hooks' condition estimate), kernels_block.py, "
             "core/step.py (float_status: the numpy rows)",
       statement="N={N}: the paper's state and its mirror p -> -p with lam1 (or lam2) at 1e-4 .. 1e-8 of the gap "
                 "inside a band edge, both branches: the fused and the block kernel hand back the same states "
                 "(ILLCOND) and give the same bits for the others, the numpy rows' statuses are the same, the "
                 "scan crosses the threshold, and the finished state nearest each edge = the literal map within "
                 "16 N eps S_i")
def threshold(N: int, parts: Parts) -> Outcome:
    from ..numeric.core.limits import ILLCOND, OK
    from ..numeric.float64.orbit import kernel_step

    tally, C, s = Tally(), step_constant(N), parts.printed["scale"]
    scans = threshold_states()
    for label, b, rows in scans:
        cell = {"branch": b, "edge": label}
        try:
            BP, BQ, status = _block_kernel(list(rows), b)
        except (FloatingPointError, ZeroDivisionError, OverflowError, ValueError, IndexError) as exc:
            tally.notes.append(f"{label}, branch {b}: the block kernel raised {type(exc).__name__}.")
            tally.add("decisions", cell, rows[0], b, math.inf)
            continue
        differ, kept = [], None
        rows_status = _numpy_rows_status(rows, b)
        for i, st in enumerate(rows):
            out = kernel_step(np.array(st[0]), np.array(st[1]), st[2], st[3], b, "python")
            code = int(status[i])
            same = (code == ILLCOND if out is None else
                    code == OK and np.array_equal(out[0], BP[i]) and np.array_equal(out[1], BQ[i]))
            if not same or int(rows_status[i]) != code:
                differ.append(i)
            if out is not None:
                kept = (i, out)
        crosses = kernel_step(np.array(rows[0][0]), np.array(rows[0][1]), rows[0][2], rows[0][3], b,
                              "python") is not None and int(status[-1]) == ILLCOND
        if differ:
            first = THRESHOLD_KS[differ[0]] / THRESHOLD_DIV
            tally.notes.append(f"{label}, branch {b}: fused kernel, block kernel and numpy rows decide differently at "
                               f"{len(differ)} of {len(rows)} states (first: delta = 1e-{first:.4g}).")
        if not crosses:
            tally.notes.append(f"{label}, branch {b}: the scan does not cross the threshold (widest state handed "
                               "back, or narrowest finished).")
        tally.add("decisions", cell, rows[0], b, 0.0 if not differ and crosses else math.inf)
        if kept is not None:
            i, out = kept
            ref = step_ref(rows[i], b)
            r, allowed = ratios(scaled(list(out[0]) + list(out[1]), s), ref.x, ref.S, EPS, C)
            tally.add("nearest finished state", cell, rows[i], b, r, allowed, ref.agree)
    return tally.outcome(method="numeric: fused vs block kernel decisions across KAPPA_MAX (consistency), the "
                                "nearest kept state vs the literal map",
                         printed=f"the kernels decide alike; kept states within {C} eps S_i",
                         detail=f"{len(scans)} scans of {len(THRESHOLD_KS)} states.")


#: paths.ill_member: the steps
ILL_STEPS = 3


@claim("paths.ill_member", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/float64/orbit.py: general_orbit (the escalation of ILLCOND members)",
       statement="bt_orbit(backend='numpy'), N={N}, 3 steps, ensembles [moderate state, state 1e-9 of the gap "
                 "inside a band edge] per edge and branch: every member = the literal orbit within 16 N n eps S_i "
                 "and = its single-state call bit for bit; bt_step(backend='numpy') on the same batches likewise "
                 "(one step, 16 N eps S_i)")
def ill_member(N: int, parts: Parts) -> Outcome:
    from ..numeric import bt_orbit, bt_step

    tally, C, s, n = Tally(), step_constant(N), parts.printed["scale"], ILL_STEPS
    for cell, st, b in edge_states():
        mod = next(x for c, x, bb in ship_cells(N, 1) if bb == b and c["sign_mu"] == 1)
        members = (mod, st)
        with without_numba():
            try:
                P, Q = bt_orbit(np.array([m[0] for m in members]), np.array([m[1] for m in members]),
                                np.array([m[2] for m in members]), np.array([m[3] for m in members]), n,
                                branch=b, backend="numpy")
            except (ArithmeticError, ValueError) as exc:      # NoRealMapError, NumericRangeError
                tally.notes.append(f"{cell}: the ensemble raised {type(exc).__name__}: {str(exc)[:120]}")
                tally.add("ensemble member", cell, st, b, math.inf)
                continue
            for k, m in enumerate(members):
                try:
                    sp, sq = bt_orbit(np.array(m[0]), np.array(m[1]), m[2], m[3], n, branch=b, backend="numpy")
                except (ArithmeticError, ValueError) as exc:
                    tally.notes.append(f"{cell}: member {k} alone raised {type(exc).__name__}.")
                    sp = sq = None
                ref = orbit_ref(m, b, n)
                r, allowed = ratios(scaled(list(P[n][k]) + list(Q[n][k]), s), ref.xs[n], ref.S, EPS, C * n)
                if sp is None or not (np.array_equal(P[:, k], sp) and np.array_equal(Q[:, k], sq)):
                    tally.notes.append(f"{cell}: member {k} differs from its single-state orbit.")
                    r = math.inf
                tally.add("ensemble member" if k else "moderate member", dict(cell, member=k), m, b, r, allowed,
                          ref.agree)
            # bt_step's numpy rows on the same batch (float64.rows escalates the ILLCOND row): one step each
            try:
                bp, bq = bt_step(np.array([m[0] for m in members]), np.array([m[1] for m in members]),
                                 np.array([m[2] for m in members]), np.array([m[3] for m in members]), branch=b,
                                 backend="numpy")
            except (ArithmeticError, ValueError) as exc:
                tally.notes.append(f"{cell}: bt_step on the batch raised {type(exc).__name__}: {str(exc)[:120]}")
                tally.add("bt_step batch member", cell, st, b, math.inf)
                continue
            for k, m in enumerate(members):
                sp, sq = bt_step(np.array(m[0]), np.array(m[1]), m[2], m[3], branch=b, backend="numpy")
                sref = step_ref(m, b)
                r, allowed = ratios(scaled(list(bp[k]) + list(bq[k]), s), sref.x, sref.S, EPS, C)
                if not (np.array_equal(bp[k], sp) and np.array_equal(bq[k], sq)):
                    tally.notes.append(f"{cell}: bt_step's batch member {k} differs from its single-state step.")
                    r = math.inf
                tally.add("bt_step batch member", dict(cell, member=k), m, b, r, allowed, sref.agree)
    return tally.outcome(method="numeric: general-path ensembles with an escalated member vs the literal orbit "
                                "and the single-state calls",
                         printed=f"|member - literal| <= {C} n eps S_i, = the single-state orbit")


#: paths.anchored: the steps (two re-anchorings at ANCHOR and 2 ANCHOR)
def anchored_steps() -> int:
    """``2 ANCHOR + 3``.

    >>> anchored_steps()
    35
    """
    from ..numeric.float64.kernels import ANCHOR

    return 2 * ANCHOR + 3


@claim("paths.anchored", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/kernels.py (_anchor1, orbit), kernels_block.py (_anchor, run_block)",
       statement="N={N}, one state per cell, 2 ANCHOR + 3 steps stored at every step: the fused orbit kernel and "
                 "the block kernel's ensemble (both through two re-anchorings) report status 0 and agree bit for "
                 "bit at every step (documented; a consistency check)")
def anchored(N: int) -> Outcome:
    from ..numeric.float64.jit import kernel
    from ..numeric.float64.kernels import ANCHOR, orbit, orbit_rows

    n, bad = anchored_steps(), []
    cells = ship_cells(N, 1)
    fn, _ = kernel("ensemble", "python")
    for b in (1, -1):
        rows = [(cell, st) for cell, st, bb in cells if bb == b]
        M, R = len(rows), orbit_rows(n, 1)
        p0 = np.ascontiguousarray([st[0] for _, st in rows], dtype=float)
        q0 = np.ascontiguousarray([st[1] for _, st in rows], dtype=float)
        l0, m = np.array([st[2] for _, st in rows]), np.array([st[3] for _, st in rows])
        BP, BQ, status = np.empty((R, M, N)), np.empty((R, M, N)), np.zeros(M, np.int64)
        with np.errstate(all="raise"):
            fn(p0, q0, l0 + m, l0 - m, 2.0 * m, b, n, 1, ANCHOR, max(8, min(64, 2048 // N)), BP, BQ, status)
        for i, (cell, st) in enumerate(rows):
            P, Q = np.empty((R, N)), np.empty((R, N))
            s1 = orbit(np.array(st[0]), np.array(st[1]), st[2] + st[3], st[2] - st[3], 2 * st[3], b, n, 1, ANCHOR,
                       P, Q)
            if s1 != 0 or status[i] != 0:
                bad.append(f"{cell}: status {s1} (fused), {status[i]} (block)")
                continue
            off = [k for k in range(R) if not (np.array_equal(P[k], BP[k, i]) and np.array_equal(Q[k], BQ[k, i]))]
            if off:
                bad.append(f"{cell}: the orbits differ from step {off[0]} on")
    detail = f"{len(cells)} cells, {n} steps (re-anchored at steps {ANCHOR} and {2 * ANCHOR})."
    if bad:
        return failed("numeric: fused vs block orbit through the re-anchoring", detail="; ".join(bad[:3]) + " "
                      + detail)
    return Outcome("verified", "numeric: fused vs block orbit through the re-anchoring, bit for bit (consistency)",
                   evidence="sampled", detail=detail, printed="the fused and the block orbit are the same bits")


def _rule(row: Any) -> bool:
    """The documented out-of-range rule on the large side, entry by entry (Python's ``abs`` of each complex
    entry; a nan fails the comparison).  The small side (``< 2**-500``) is tested only once some row is large
    (``det M = 1`` keeps each row's largest entry at 1 or above), so no row here is tiny."""
    return any(not abs(complex(v)) <= 2.0 ** 500 for v in row)


#: paths.edges: two batches of complex rows (one row per batch member): large entries of either sign and phase,
#: then a nan (which makes every row go through the per-row test)
EDGE_BATCHES = (((-2.0 ** 600, 1.0), (1.0 + 0j, 3j), (0.5, -(2.0 ** 501) * 1j), (7.0, -7.0)),
                ((complex("nan"), 1.0), (7.0, -7.0)))


@claim("paths.edges", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/multiprec/lohner.py: growth_law; symbt/numeric/core/context.py: out_of_range; "
             "core/monodromy.py: neighbour_ratios' range check",
       statement="growth_law without two usable points (one recorded step; radii all zero) gives degree None, with "
                 "two (log2 rad = 5, 8 at steps 1, 2) their slope 3; the "
                 "float64 context's out_of_range on complex rows = the documented per-entry rule (|x| > 2^500 or "
                 "nan); invariants and phi finite at |q2 - q1| = 700, NumericRangeError at 700.1")
def edges(N: int) -> Outcome:
    from ..numeric.core.context import FloatContext
    from ..numeric.multiprec.lohner import growth_law

    bad = []
    for lograd in ([-3.0], [-math.inf, -math.inf, -math.inf]):
        try:
            law = growth_law(lograd)
        except (ValueError, ZeroDivisionError, IndexError) as exc:
            bad.append(f"growth_law({lograd}) raised {type(exc).__name__}")
            continue
        if law["degree"] is not None:
            bad.append(f"growth_law({lograd}) gave degree {law['degree']}")
    two = growth_law([-math.inf, 5.0, 8.0])          # exactly two usable points: the slope between them
    if two["degree"] != 3.0:
        bad.append(f"growth_law([-inf, 5, 8]) gave degree {two['degree']}, the slope between its points 3")
    ctx = FloatContext(np.complex128)
    for rows in EDGE_BATCHES:
        cols = [np.array([r[k] for r in rows], dtype=complex) for k in range(2)]
        want = [_rule(r) for r in rows]
        with np.errstate(invalid="ignore"):
            got = [bool(x) for x in np.broadcast_to(ctx.out_of_range(*cols), (len(rows),))]
        if got != want:
            bad.append(f"out_of_range on complex rows {got}, the documented rule {want}")
    from ..numeric import invariants, phi
    from ..numeric.core.errors import NumericRangeError
    from ..numeric.core.limits import MAX_DQ_FLOAT64

    for d, beyond in ((MAX_DQ_FLOAT64, False), (MAX_DQ_FLOAT64 + 0.1, True)):
        q = [0.0, d, 0.0]
        for name, f in (("invariants", lambda: invariants([0.0] * 3, q)), ("phi", lambda: phi([0.0] * 3, q, 3.0, 1.0))):
            try:
                finite = bool(np.all(np.isfinite(f())))
            except NumericRangeError:
                finite = None
            if finite is not (None if beyond else True):
                seen = "refused" if finite is None else "finite" if finite else "not finite"
                bad.append(f"{name} at |q2 - q1| = {d:g}: {seen}")
    detail = (f"growth_law on 2 short histories; out_of_range on {sum(map(len, EDGE_BATCHES))} complex rows; "
              f"invariants and phi on both sides of |dq| = {MAX_DQ_FLOAT64:g}.")
    if bad:
        return failed("numeric: documented edges of growth_law and out_of_range", detail="; ".join(bad) + ". "
                      + detail)
    return Outcome("verified", "numeric: growth_law and out_of_range against their documented rules",
                   evidence="sampled", detail=detail, printed="the documented edges hold")
