r"""What ships, 4h: ensembles in which not every member is stepped (scene ``numeric-paths``, issue 21).

A member with ``mu = 0`` is the identity (docs/numeric.md): ``float_orbit`` copies it into every stored row and
hands only the *active* members to the ensemble kernel, through a compacted buffer of shape
``(rows, active, N)`` scattered back afterwards.  Every other claim steps ensembles whose members are all active,
where the kernel writes the caller's arrays directly -- the compaction is never run.

* ``paths.members.n3`` -- per branch, the ensemble of the ``ship_cells`` states of that branch (both signs of
  ``mu`` and of the traces; per-state ``lam0``, ``mu``) with a copy of its first state at ``mu = 0`` inserted as
  member 1, ``MEMBER_STEPS`` steps stored at every step (so ``n + 1`` rows, not ``N``), through the plain-Python
  ensemble kernel (``backend="python"``: the same code numba compiles, traced): every active member's last state
  is the literal orbit of :mod:`symbt.reference.literal` (50 digits with guard digits: the independent route)
  within ``16 N n eps S_i`` (the orbit bound of ``shipped.orbit``), and the idle member equals its input at every
  row, bit for bit (documented; ``q`` and ``p`` are copied, not computed).  And each of those states alone, as
  an ensemble of one member (one block holding one member: exactly one or no member transported forward), within
  the same bound of the same literal orbit.  And a block of two: the branch's fourth state and its second moved
  to ``lam0 = FAR_LAM0`` (one member transported forward, the other backward: each must get the slopes of its
  own direction), within the same bound of their literal orbits.  The ensemble also holds, last, the paper's
  state at ``mu = 1`` exactly (``UNIT_MEMBER``: a member is idle by ``mu == 0``, not by any other value), within
  the same bound.

Shown to fail on a planted bug in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

import math

import numpy as np

from ._shipped import EPS, Tally, orbit_ref, ratios, scale_parts, scaled, ship_cells, step_constant
from .base import Outcome, Parts, claim

#: paths.members: the steps (rows = steps + 1 differs from N = 3, so a buffer of the wrong width cannot fit)
MEMBER_STEPS = 3
#: paths.members: where the idle member goes (not first and not last: the compaction must skip it)
IDLE_AT = 1
#: paths.members: the paper's state at mu = 1 exactly, the ensemble's last member
UNIT_MEMBER = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 10.0, 1.0)
#: paths.members: lam0 of the far member of the two-member block (|tr L| ~ lam0**N: transported in the wrong
#: direction, its slopes lose ~ 2 log10(lam0) digits per period -- measured 1e-10 relative at one step)
FAR_LAM0 = 200.0


@claim("paths.members", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/float64/orbit.py: validated_float_orbit, _ensemble (idle members, compacted buffers)",
       statement="bt_orbit(backend='python'), N={N}, 3 steps stored at every step, per branch the ensemble of every "
                 "sign cell's state, one idle member (mu = 0) at index 1 and the paper's state at mu = 1 last: "
                 "every active member = the literal orbit "
                 "within 16 N n eps S_i; the idle member = its input at every row, bit for bit; each state as an "
                 "ensemble of one member, and a block of two (one far member at lam0 = 200), within the same bound")
def idle_members(N: int, parts: Parts) -> Outcome:
    from ..numeric import bt_orbit

    tally, C, s, n = Tally(), step_constant(N), parts.printed["scale"], MEMBER_STEPS
    for b in (1, -1):
        rows = [(cell, st) for cell, st, bb in ship_cells(N, 1) if bb == b]
        idle = (rows[0][1][0], rows[0][1][1], rows[0][1][2], 0.0)
        members = [st for _, st in rows]
        members.insert(IDLE_AT, idle)
        members.append(UNIT_MEMBER)
        cols = [np.array([st[k] for st in members]) for k in range(4)]
        try:
            P, Q = bt_orbit(cols[0], cols[1], cols[2], cols[3], n, branch=b, backend="python")
        except (ArithmeticError, ValueError) as exc:     # NoRealMapError, NumericRangeError, a broadcast error
            tally.notes.append(f"branch {b}: bt_orbit raised {type(exc).__name__}: {str(exc)[:120]}")
            tally.add("ensemble member", {"branch": b}, rows[0][1], b, math.inf)
            continue
        same = (np.array_equal(P[:, IDLE_AT], np.broadcast_to(cols[0][IDLE_AT], P[:, IDLE_AT].shape))
                and np.array_equal(Q[:, IDLE_AT], np.broadcast_to(cols[1][IDLE_AT], Q[:, IDLE_AT].shape)))
        if not same:
            tally.notes.append(f"branch {b}: the idle member differs from its input.")
        tally.add("idle member", {"branch": b}, idle, b, 0.0 if same else math.inf)
        ref = orbit_ref(UNIT_MEMBER, b, n)
        r, allowed = ratios(scaled(list(P[n][-1]) + list(Q[n][-1]), s), ref.xs[n], ref.S, EPS, C * n)
        tally.add("ensemble member", {"branch": b, "mu": 1}, UNIT_MEMBER, b, r, allowed, ref.agree)
        for k, (cell, st) in enumerate(rows):
            m = k if k < IDLE_AT else k + 1
            ref = orbit_ref(st, b, n)
            r, allowed = ratios(scaled(list(P[n][m]) + list(Q[n][m]), s), ref.xs[n], ref.S, EPS, C * n)
            tally.add("ensemble member", cell, st, b, r, allowed, ref.agree)
            # the same state as an ensemble of one: its block holds one member, so the count of members
            # transported forward is exactly 0 or 1 (in the ensemble above both directions share one block)
            try:
                P1, Q1 = bt_orbit(np.array([st[0]]), np.array([st[1]]), st[2], st[3], n, branch=b, backend="python")
                r1, _ = ratios(scaled(list(P1[n][0]) + list(Q1[n][0]), s), ref.xs[n], ref.S, EPS, C * n)
            except (ArithmeticError, ValueError) as exc:
                tally.notes.append(f"{cell}: the one-member ensemble raised {type(exc).__name__}.")
                r1 = math.inf
            tally.add("one-member ensemble", cell, st, b, r1, allowed, ref.agree)
        _mixed_block(N, b, [st for _, st in rows], n, s, C, tally)
    return tally.outcome(method="numeric: an ensemble with an idle member (python kernel) vs the literal orbit",
                         printed=f"|member - literal| <= {C} n eps S_i; idle member = its input")


def _mixed_block(N: int, b: int, states: list, n: int, s: float, C: int, tally: Tally) -> None:
    """The branch's fourth state and its second at ``lam0 = FAR_LAM0`` as one block of the python kernel."""
    from ..numeric import bt_orbit

    far = (states[1][0], states[1][1], FAR_LAM0, states[1][3])
    members = [states[3], far]
    cols = [np.array([st[k] for st in members]) for k in range(4)]
    try:
        P, Q = bt_orbit(cols[0], cols[1], cols[2], cols[3], n, branch=b, backend="python")
    except (ArithmeticError, ValueError) as exc:
        tally.notes.append(f"branch {b}: the two-member block raised {type(exc).__name__}.")
        tally.add("two-member block", {"branch": b}, far, b, math.inf)
        return
    for k, st in enumerate(members):
        ref = orbit_ref(st, b, n)
        r, allowed = ratios(scaled(list(P[n][k]) + list(Q[n][k]), s), ref.xs[n], ref.S, EPS, C * n)
        tally.add("two-member block", {"branch": b, "member": k}, st, b, r, allowed, ref.agree)
