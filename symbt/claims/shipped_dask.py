r"""What ships, 4g: ensembles out of core -- :func:`symbt.numeric.dask_orbit` (scene ``numeric-paths``, issue 21).

:func:`~symbt.numeric.dask_orbit` chunks an ensemble along its state axis, carries each state's ``lam0, mu`` as
two extra columns and maps the float64 ensemble orbit onto the chunks.  A slip there (the wrong columns, a chunk
shape, a lost offset) gives states of *other* parameters or a crash, which the kernels' own claims never see.

* ``paths.dask.n3`` -- for each branch, an ensemble of the ``ship_cells`` states of that branch (both signs of
  ``mu`` and of the traces; per-state ``lam0`` and ``mu``), ``chunks=3`` (so several chunks, one of them short),
  ``DASK_STEPS`` steps stored at every step: every member's last state is the literal orbit of
  :mod:`symbt.reference.literal` (50 digits with guard digits: the independent route) within ``16 N n eps S_i``
  (the orbit bound of ``shipped.orbit``), and the whole stored orbit equals the member's single-state
  ``bt_orbit(backend="numpy")`` bit for bit (documented for ensembles without numba, docs/numeric.md; a consistency
  check).  Run without numba: the chunking is under test here, the kernels' two instances are other claims'.
  And for the first state without a real map of ``shipped.nomap`` of each branch (decided by the literal
  route), the ensemble of the four ``ship_cells`` states of its branch with it as member 4 -- in the second chunk,
  at offset 1 there: the computation raises ``NoRealMapError`` whose ``where`` is ``((4,),)`` (the batch index in
  the ensemble, not in the chunk) with the condition ``bt_step(backend='numpy')`` gives on the state alone.
  Skipped without dask.

Shown to fail on a planted bug in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

import importlib.util
import math

import numpy as np

from ._shipped import EPS, Tally, orbit_ref, ratios, scale_parts, scaled, ship_cells, step_constant, without_numba
from .base import Outcome, Parts, claim, skipped
from .shipped_emitted import nomap_states

#: paths.dask: the steps and the states per chunk
DASK_STEPS = 3
DASK_CHUNK = 3


@claim("paths.dask", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts, requires=("dask",),
       where="symbt/numeric/float64/dask_orbit.py: dask_orbit (chunks, per-state columns)",
       statement="dask_orbit, N={N}, 3 steps, chunks of 3 states, per branch the ensemble of every sign cell's "
                 "state with per-state lam0, mu: every member = the literal orbit within 16 N n eps S_i and = its "
                 "single-state bt_orbit(backend='numpy') bit for bit (without numba); a member without a real map "
                 "at index 4 (second chunk): NoRealMapError.where = ((4,),)")
def dask_orbit_members(N: int, parts: Parts) -> Outcome:
    if importlib.util.find_spec("dask") is None:
        return skipped("dask is not installed (.[dask])")
    from ..numeric import bt_orbit, dask_orbit

    tally, C, s, n = Tally(), step_constant(N), parts.printed["scale"], DASK_STEPS
    for b in (1, -1):
        rows = [(cell, st) for cell, st, bb in ship_cells(N, 1) if bb == b]
        cols = [np.array([st[k] for _, st in rows]) for k in range(4)]
        try:
            # the chunking is under test, not the kernel (its claims run both instances); without numba an
            # ensemble is the single-state call with backend="numpy" bit for bit (docs/numeric.md)
            with without_numba():
                lazy = dask_orbit(cols[0], cols[1], cols[2], cols[3], n, chunks=DASK_CHUNK, branch=b)
                P, Q = (a.compute(scheduler="synchronous") for a in lazy)
        except (ArithmeticError, ValueError) as exc:        # NoRealMapError, NumericRangeError, InvalidInputError
            tally.notes.append(f"branch {b}: dask_orbit raised {type(exc).__name__}: {str(exc)[:120]}")
            tally.add("dask member", {"branch": b}, rows[0][1], b, math.inf)
            continue
        for k, (cell, st) in enumerate(rows):
            with without_numba():
                sp, sq = bt_orbit(np.array(st[0]), np.array(st[1]), st[2], st[3], n, branch=b, backend="numpy")
            ref = orbit_ref(st, b, n)
            r, allowed = ratios(scaled(list(P[n][k]) + list(Q[n][k]), s), ref.xs[n], ref.S, EPS, C * n)
            if not (np.array_equal(P[:, k], sp) and np.array_equal(Q[:, k], sq)):
                tally.notes.append(f"{cell}: member {k} differs from its single-state orbit.")
                r = math.inf
            tally.add("dask member", cell, st, b, r, allowed, ref.agree)
    seen: set = set()
    for st, b, (_cond, decided) in nomap_states(N):
        if decided and b not in seen:       # one per branch (each is a dask graph: ~0.2 s)
            seen.add(b)
            tally.add("dask no-map member", {"branch": b}, st, b, _nomap_where(N, st, b, tally.notes))
    return tally.outcome(method="numeric: dask_orbit's members vs the literal orbit and the single-state calls",
                         printed=f"|member - literal| <= {C} n eps S_i, = the single-state orbit")


def _nomap_where(N: int, st: tuple, b: int, notes: list) -> float:
    """0 when ``dask_orbit`` on the branch's ship states with ``st`` appended (index 4) raises the single-state
    ``NoRealMapError`` naming index 4, else ``inf`` (with a note)."""
    from ..numeric import NoRealMapError, bt_step, dask_orbit

    members = [s for _, s, bb in ship_cells(N, 1) if bb == b] + [st]
    cols = [np.array([m[k] for m in members]) for k in range(4)]
    want = (len(members) - 1,)
    try:
        bt_step(np.array(st[0]), np.array(st[1]), st[2], st[3], branch=b, backend="numpy")
        single = None
    except NoRealMapError as exc:
        single = exc.condition
    try:
        with without_numba():
            for a in dask_orbit(cols[0], cols[1], cols[2], cols[3], 1, chunks=DASK_CHUNK, branch=b):
                a.compute(scheduler="synchronous")
    except NoRealMapError as exc:
        if tuple(exc.where) == (want,) and exc.condition == single:
            return 0.0
        notes.append(f"no-map member {want}: where {exc.where!r}, condition {exc.condition!r} (single {single!r}).")
        return math.inf
    except (ArithmeticError, ValueError) as exc:
        notes.append(f"no-map member {want}: {type(exc).__name__}: {str(exc)[:100]}")
        return math.inf
    notes.append(f"no-map member {want}: a finite orbit, no NoRealMapError.")
    return math.inf
