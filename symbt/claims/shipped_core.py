r"""What ships, 4i: :func:`symbt.numeric.core.step.step_core` in float64 with its existence test on (scene
``numeric-paths``, issue 21).

Every float64 route calls ``step_core`` with ``check_real=False`` and decides existence per row afterwards
(``float_status``); the default ``check_real=True`` -- the test a caller of the public ``step_core`` gets, which
raises :class:`~symbt.numeric.NoRealMapError` from the traces' signs and from ``Etilde_j / E_j``, naming the batch
rows -- runs on arrays nowhere else.

* ``paths.step_core.n3`` -- per branch, the batch of the ``ship_cells`` states of that branch (both signs of
  ``mu`` and of the traces; per-state ``lam0``, ``mu``) through ``step_core(FLOAT, ...)`` with ``check_real``: no
  error, and every row = the literal map of :mod:`symbt.reference.literal` (50 digits with guard digits: the
  independent route) within ``16 N eps S_i`` (the bound of ``shipped.step``); and each state without a real map
  of ``shipped.nomap`` (decided by the literal route) as row 1 of a batch of three (the others with a real map):
  ``NoRealMapError`` with the condition ``"positivity"`` and ``where = ((1,),)``.
* ``paths.device.n3`` -- :func:`~symbt.numeric.float64.kernels.python_orbit_with` with no hook replaced (the
  benchmarks' measuring device, built afresh by the inlining rewrite of :mod:`symbt.numeric.core.inline`), on
  every ``ship_cells`` state, ``DEVICE_STEPS`` steps: status 0, the last state = the literal orbit within
  ``16 N n eps S_i``, and every stored row = :func:`~symbt.numeric.float64.kernels.python_orbit`'s bit for bit
  (documented: the same operations on the same doubles; a consistency check).
* ``paths.enclosures.n3`` -- :func:`~symbt.numeric.multiprec.lohner_checks.common_invariants` (the check of the
  certified benchmark that the enclosures of the conserved ``H_k`` along an orbit overlap) on exact balls
  (dyadic midpoints and radii): the intersection over three stored states equals the one computed with
  fractions, and where the enclosure at state 1 or at state 2 is disjoint from the one at state 0, the
  ``InconsistentEnclosure`` names ``H_k`` and the states ``0 and 1``, resp. ``0 and 2`` (its docstring's
  message).  Skipped without python-flint.

Shown to fail on a planted bug in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

import importlib.util
import math
from fractions import Fraction

import numpy as np

from ._shipped import EPS, Tally, orbit_ref, ratios, scale_parts, scaled, ship_cells, step_constant, step_ref
from .base import Outcome, Parts, claim, failed, skipped
from .shipped_emitted import nomap_states

#: paths.step_core: where the state without a real map goes in its batch of three
NOMAP_ROW = 1
#: paths.device: the steps of each orbit
DEVICE_STEPS = 3


def _core(states: list, b: int) -> tuple[np.ndarray, np.ndarray]:
    """``step_core(FLOAT, ...)`` with ``check_real`` on the batch ``states``: ``(P~, Q~)`` of shape (B, N)."""
    from ..numeric.core.inputs import FLOAT
    from ..numeric.core.step import step_core

    P = [np.array([st[0][j] for st in states]) for j in range(len(states[0][0]))]
    Q = [np.array([st[1][j] for st in states]) for j in range(len(states[0][0]))]
    l0, m = np.array([st[2] for st in states]), np.array([st[3] for st in states])
    with np.errstate(all="ignore"):
        Pn, Qn, _ = step_core(FLOAT, P, Q, l0, m, b, shape=(len(states),))
    return np.stack(Pn, axis=-1), np.stack(Qn, axis=-1)


@claim("paths.step_core", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/core/step.py: step_core with check_real on float64 arrays (_opposite, the E~ test)",
       statement="step_core(FLOAT, ...) with check_real, N={N}, per branch a batch of every sign cell's state: "
                 "every row = the literal map within 16 N eps S_i; a state without a real map as row 1 of a "
                 "batch of three: NoRealMapError('positivity') with where = ((1,),)")
def step_core_checked(N: int, parts: Parts) -> Outcome:
    from ..numeric import NoRealMapError

    tally, C, s = Tally(), step_constant(N), parts.printed["scale"]
    good: dict[int, list] = {1: [], -1: []}
    for b in (1, -1):
        rows = [(cell, st) for cell, st, bb in ship_cells(N, 1) if bb == b]
        good[b] = [st for _, st in rows]
        try:
            Pt, Qt = _core(good[b], b)
        except (ArithmeticError, ValueError) as exc:     # NoRealMapError on states with a real map
            tally.notes.append(f"branch {b}: step_core raised {type(exc).__name__}: {str(exc)[:120]}")
            tally.add("step_core row", {"branch": b}, rows[0][1], b, math.inf)
            continue
        for k, (cell, st) in enumerate(rows):
            ref = step_ref(st, b)
            r, allowed = ratios(scaled(list(Pt[k]) + list(Qt[k]), s), ref.x, ref.S, EPS, C)
            tally.add("step_core row", cell, st, b, r, allowed, ref.agree)
    for st, b, (cond, decided) in nomap_states(N):
        if not decided:
            continue
        batch = list(good[b][:2])
        batch.insert(NOMAP_ROW, st)
        try:
            _core(batch, b)
            tally.notes.append(f"{cond}, branch {b}: a state, no NoRealMapError.")
            r = math.inf
        except NoRealMapError as exc:
            r = 0.0 if (exc.condition == "positivity" and tuple(exc.where) == ((NOMAP_ROW,),)) else math.inf
            if r:
                tally.notes.append(f"{cond}, branch {b}: condition {exc.condition!r}, where {exc.where!r}.")
        except (ArithmeticError, ValueError) as exc:
            tally.notes.append(f"{cond}, branch {b}: {type(exc).__name__}: {str(exc)[:100]}")
            r = math.inf
        tally.add("no-map row", {"branch": b, "condition": str(cond)}, st, b, r)
    return tally.outcome(method="numeric: step_core(FLOAT) with check_real vs the literal map and its existence",
                         printed=f"|row - literal| <= {C} eps S_i; NoRealMapError at the row without a real map")


@claim("paths.device", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/float64/kernels.py: python_orbit_with; symbt/numeric/core/inline.py (the rewrite)",
       statement="python_orbit_with({}) (no hook replaced), N={N}, 3 steps, every sign cell's state: status 0, "
                 "the last state = the literal orbit within 16 N n eps S_i, every row = python_orbit's bit for bit")
def device_orbit(N: int, parts: Parts) -> Outcome:
    from ..numeric.float64.kernels import ANCHOR, orbit_rows, python_orbit, python_orbit_with

    tally, C, s, n = Tally(), step_constant(N), parts.printed["scale"], DEVICE_STEPS
    try:
        device = python_orbit_with({})
    except (ValueError, NameError) as exc:               # the rewrite refused the source
        return failed("numeric: python_orbit_with",
                      detail=f"python_orbit_with({{}}) raised {type(exc).__name__}: {str(exc)[:160]}")
    for cell, st, b in ship_cells(N, 1):
        p, q, l0, m = np.array(st[0]), np.array(st[1]), st[2], st[3]
        runs = []
        for fn in (device, python_orbit):
            P, Q = np.empty((orbit_rows(n, 1), N)), np.empty((orbit_rows(n, 1), N))
            with np.errstate(all="ignore"):
                runs.append((fn(p, q, l0 + m, l0 - m, 2 * m, b, n, 1, ANCHOR, P, Q), P, Q))
        (sd, Pd, Qd), (so, Po, Qo) = runs
        if sd != 0 or so != 0 or not (np.array_equal(Pd, Po) and np.array_equal(Qd, Qo)):
            tally.notes.append(f"{cell}: status {sd} (device), {so} (python_orbit), or rows that differ.")
            tally.add("device orbit", cell, st, b, math.inf)
            continue
        ref = orbit_ref(st, b, n)
        r, allowed = ratios(scaled(list(Pd[n]) + list(Qd[n]), s), ref.xs[n], ref.S, EPS, C * n)
        tally.add("device orbit", cell, st, b, r, allowed, ref.agree)
    return tally.outcome(method="numeric: python_orbit_with({}) vs the literal orbit and python_orbit",
                         printed=f"|last - literal| <= {C} n eps S_i; = python_orbit bit for bit")


#: paths.enclosures: (midpoint, radius) of H_0, H_1 at three stored states (dyadic: exact balls); the
#: disjoint third state of each inconsistent case, and the states the message must name
ENCLOSURES = (((1, "0.5"), (-3, "0.25")), (("1.25", "0.5"), ("-3.125", "0.25")), (("1.125", "0.25"), (-3, "0.5")))
#: paths.enclosures: the radius roundings allowed in the intersection's width
ENCL_ROUNDINGS = 16
DISJOINT = ((1, ("1.75", "0.125"), "H_0 at stored states 0 and 1"),
            (2, ("1.875", "0.0625"), "H_0 at stored states 0 and 2"))


@claim("paths.enclosures", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/lohner_checks.py: common_invariants",
       statement="common_invariants on exact balls of H_0, H_1 at three stored states: the intersection = the "
                 "one computed with fractions (wider by 16 radius roundings at most); an enclosure of H_0 at "
                 "state 1 (or 2) disjoint from state 0's: InconsistentEnclosure naming H_0 and the states 0 and 1 "
                 "(0 and 2); invariant_enclosures of a certified orbit (N = 4, 2 steps) contain the initial "
                 "state's H_k from the polynomial trace at every stored state")
def enclosures(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from flint import arb

    from ..numeric.multiprec.lohner_checks import InconsistentEnclosure, common_invariants

    def ball(mr: tuple) -> arb:
        return arb(str(mr[0]), str(mr[1]))

    def exact(x: arb) -> Fraction:
        man, exp = x.man_exp()
        return Fraction(int(man)) * Fraction(2) ** int(exp)

    bad = []
    got = common_invariants([[ball(mr) for mr in st] for st in ENCLOSURES])
    for k in range(2):
        lo = max(Fraction(str(st[k][0])) - Fraction(str(st[k][1])) for st in ENCLOSURES)
        hi = min(Fraction(str(st[k][0])) + Fraction(str(st[k][1])) for st in ENCLOSURES)
        mid, rad = exact(got[k].mid()), exact(arb(got[k].rad()))
        # an enclosure of [lo, hi], wider by at most Arb's upward roundings of the radius (30-bit mag_t: ENCL_ROUNDINGS
        # of them, relative 2**-30 each; measured 2**-27.6)
        if not (mid - rad <= lo and hi <= mid + rad
                and 2 * rad <= (hi - lo) * (1 + Fraction(ENCL_ROUNDINGS, 2 ** 30))):
            bad.append(f"H_{k}: [{float(mid - rad)}, {float(mid + rad)}], the fractions give [{lo}, {hi}]")
    for at, mr, want in DISJOINT:
        states = [list(st) for st in ENCLOSURES]
        states[at][0] = mr
        try:
            common_invariants([[ball(x) for x in st] for st in states])
            bad.append(f"H_0 disjoint at state {at}: no InconsistentEnclosure")
        except InconsistentEnclosure as exc:
            if want not in str(exc):
                bad.append(f"H_0 disjoint at state {at}: {exc}")
        except Exception as exc:  # any other error fails the claim
            bad.append(f"H_0 disjoint at state {at}: {type(exc).__name__} {exc}")
    # invariant_enclosures of a certified orbit (an admissible N = 4 state -- at N = 3 the recursion's last B is
    # never read --, exact input, 2 steps at 30 digits) against the coefficients of the polynomial trace of the
    # initial state (reference.trace at 60 digits): every stored state's enclosure of each H_k contains them (the
    # exact orbit preserves them)
    import mpmath as mp

    from ..numeric import certified_orbit
    from ..numeric.multiprec.lohner_checks import invariant_enclosures
    from ..reference.samples import admissible_states
    from ..reference.trace import hamiltonians

    with mp.workdps(30):
        p4, q4, l4, m4 = admissible_states(4, 1, 1)[0]       # six-decimal numbers: exact as strings
        text = [[mp.nstr(v, 20) for v in p4], [mp.nstr(v, 20) for v in q4], mp.nstr(l4, 20), mp.nstr(m4, 20)]
        orbit = certified_orbit(text[0], text[1], text[2], text[3], 2)
    with mp.workdps(60):
        H = hamiltonians([mp.mpf(v) for v in text[0]], [mp.mpf(v) for v in text[1]])
    from ..numeric.multiprec.arb import flint_prec

    for i, row in enumerate(invariant_enclosures(*orbit)):
        for k, (ball_k, h) in enumerate(zip(row, H)):
            with flint_prec(256):              # the reference as a ball far narrower than the enclosure
                ref = arb(mp.nstr(h, 60))
            if not ball_k.contains(ref):
                bad.append(f"invariant_enclosures: H_{k} at stored state {i} misses the polynomial trace's")
    if bad:
        return failed("exact: common_invariants vs intervals of fractions", detail="; ".join(bad))
    return Outcome("verified", "exact: common_invariants vs intervals of fractions, and its refusals",
                   evidence="sampled", detail="2 invariants x 3 stored states; 2 inconsistent cases.",
                   printed="the intersection; InconsistentEnclosure naming the states")
