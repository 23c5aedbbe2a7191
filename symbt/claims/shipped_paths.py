r"""What ships, 4b: the numeric paths the other claims do not reach (scene ``numeric-paths``, issue 21).

The claims of the scene ``shipped`` call the public entry points; the routes behind them that those calls do
not take -- or whose choice they cannot see -- are checked here, each against the literal map of
:mod:`symbt.reference` at high precision or against an exact computation:

* ``paths.kernels.n{3,5}`` -- which float64 path ran: the fused kernel finishes every moderate state itself
  (:func:`~symbt.numeric.float64.orbit.kernel_step` does not give it back), the block kernel
  (``symbt.numeric.float64.jit.kernel("ensemble", "python")``) reports status ``OK`` for each member and
  equals the fused kernel bit for bit (documented in docs/numeric.md), and both agree with the literal map
  within ``16 N eps S_i`` -- so a range or condition test that sends moderate states to the general path
  (whose results are right too) is seen; states without a real map get a no-map status from both kernels;
  and at ``lam1`` (or ``lam2``) 1e-9 of the gap inside a band edge (N = 3) both kernels give the state back
  (``ILLCOND``) and ``bt_step`` (the general path, escalated) is still within ``16 N eps S_i``.
* ``paths.failing_rows.n3`` -- batches with one member without a real map (or beyond the float64 range)
  among moderate ones: ``bt_step`` (numpy rows) and ``bt_orbit`` ensembles (block kernel with the general
  path's retry of the members it gives back; numpy) raise the single-state call's typed error, with ``where``
  naming exactly that member and the single-state call's ``condition``; with ``allow_complex=True`` the
  other members equal their single-state steps bit for bit and are real, and the failing member equals its
  single-state continuation bit for bit.
* ``paths.tiny_mu.n3`` -- ``flow_coefficients`` where ``lam0 - mu == lam0 + mu`` in float64 (its
  ``2 mu f(lam0)`` branch), against ``-b 2 mu lam0**k / sqrt(tr**2 - 4)`` with ``tr`` the literal 2x2 product at
  40 digits, at ``lam0 < 0`` (the sign of ``lam0**k`` alternates with k).
* ``paths.frame.n13`` -- the Lohner path above ``2N = 24`` (float64 frame algebra,
  :func:`~symbt.numeric.multiprec.lohner.frame_inverse`): a 4-step certified orbit of a binary-exact
  N = 13 state contains the literal orbit at 160 digits, radii <= 1e-50.
* ``paths.growth.n3`` -- the ``info=`` record of a certified orbit: ``info["growth"]`` (the radius growth law
  of :func:`~symbt.numeric.multiprec.lohner.growth_law`) against a least-squares fit of the radii the call
  returned, and its ``log2_radius`` against the largest returned radius.

* ``paths.stored.n3`` -- the fused kernel's orbit (:func:`~symbt.numeric.float64.kernels.orbit`, plain Python)
  stored every 3rd step equals, bit for bit, the same orbit stored at every step at the steps of
  :func:`~symbt.numeric.float64.kernels.stored_steps` (documented: the orbit does not depend on ``every``).

The quad-double step is ``paths.qd`` (:mod:`symbt.claims.shipped_qd`); the Lohner method's Jacobian and its
sharpness on a box are ``paths.jacobian`` and ``paths.lohner_box`` (:mod:`symbt.claims.shipped_lohner`).
Each claim is shown to fail on a planted
bug in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

import importlib.util
import math
from functools import cache
from typing import Any

import mpmath as mp
import numpy as np

from ..proof.cells import CellTable
from ..reference.literal import literal_trace
from ._common import fmt_state
from ._shipped import EPS, Tally, ratios, scale_parts, scaled, ship_cells, step_constant, step_ref, without_numba
from .base import Outcome, Parts, claim, failed, judge_cells, scene, skipped

scene("numeric-paths", "the numeric paths the entry-point claims do not reach or cannot tell apart: quad-double "
                       "step, fused/block/general path selection, failing batch members, tiny mu, the growth "
                       "record of certified orbits (issue 21)")

#: paths.kernels: lam1 (or lam2) this fraction of the gap's width inside a band edge
EDGE_GAP = 1e-9
#: the kernels' statuses for "no real map" (symbt.numeric.core.limits: TRACE1, TRACE2, POSITIVITY)
NO_MAP_STATUS = (1, 2, 3)
#: paths.growth: the certified orbit's tolerance, and how far the record may be from the returned radii (log2)
GROWTH_TOL, GROWTH_LOG_TOL = 1e-12, 1e-9
#: paths.growth's steps
GROWTH_STEPS = 12


def _mpf_list(xs: Any) -> list:
    return [mp.mpf(v) for v in xs]


# --------------------------------------------------------------------------- which float64 path ran

def _block_kernel(rows: list[tuple], b: int) -> tuple[Any, Any, Any]:
    """One step of the states ``rows`` by the block kernel alone (plain Python): ``(P, Q, status)``."""
    from ..numeric.float64.jit import kernel
    from ..numeric.float64.kernels import ANCHOR

    fn, _ = kernel("ensemble", "python")
    M, N = len(rows), len(rows[0][0])
    p0 = np.ascontiguousarray([st[0] for st in rows], dtype=float)
    q0 = np.ascontiguousarray([st[1] for st in rows], dtype=float)
    l0, m = np.array([st[2] for st in rows]), np.array([st[3] for st in rows])
    P, Q, status = np.empty((2, M, N)), np.empty((2, M, N)), np.zeros(M, np.int64)
    with np.errstate(all="raise"):
        fn(p0, q0, l0 + m, l0 - m, 2.0 * m, b, 1, 1, ANCHOR, max(8, min(64, 2048 // N)), P, Q, status)
    return P[1], Q[1], status


@cache
def edge_states() -> tuple:
    """``(cell, state, branch)``: the paper's N = 3 state with ``lam1`` (or ``lam2``) at ``EDGE_GAP`` of the gap
    width inside the edge of the gap (-10.27, -0.80) (edges by ``findroot`` on the literal trace, 40 digits)
    and the other at the gap's middle: ill-conditioned (the kernels' condition estimate beyond KAPPA_MAX)."""
    p, q = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9)
    with mp.workdps(40):
        s = mp.sign(literal_trace(mp.mpf(-5), p, q))
        lo, hi = (mp.findroot(lambda x: literal_trace(x, p, q) - 2 * s, x0, solver="anderson")
                  for x0 in ((-10.28, -10.26), (-0.80, -0.79)))
    lo, hi, mid = float(lo), float(hi), float((lo + hi) / 2)
    out = []
    for side, (l1, l2) in (("top", (hi - EDGE_GAP * (hi - lo), mid)), ("bottom", (mid, lo + EDGE_GAP * (hi - lo)))):
        for b in (1, -1):
            out.append(({"branch": b, "edge": side}, (p, q, (l1 + l2) / 2, (l1 - l2) / 2), b))
    return tuple(out)


def _near_edge(tally: Tally, s: float) -> None:
    """Near a band edge both kernels give the state back (ILLCOND) and bt_step's result -- the general path,
    recomputed at higher precision -- is still the literal map within 16 N eps S_i."""
    from ..numeric import bt_step
    from ..numeric.core.limits import ILLCOND
    from ..numeric.float64.orbit import kernel_step

    for cell, st, b in edge_states():
        ref = step_ref(st, b)
        single = kernel_step(np.array(st[0]), np.array(st[1]), st[2], st[3], b, "python")
        if single is not None:
            tally.notes.append("the fused kernel finished a state at a band edge (condition beyond KAPPA_MAX).")
        try:
            code = int(_block_kernel([st], b)[2][0])
        except (FloatingPointError, ZeroDivisionError, OverflowError, ValueError, IndexError):
            code = -1
        if code != ILLCOND:
            tally.notes.append(f"the block kernel reported status {code} at a band edge (expected ILLCOND).")
        with without_numba():
            out = bt_step(np.array(st[0]), np.array(st[1]), st[2], st[3], branch=b)
        r, allowed = ratios(scaled(list(out[0]) + list(out[1]), s), ref.x, ref.S, EPS, step_constant(3))
        ok = single is None and code == ILLCOND
        tally.add("band edge: kernels give back, bt_step", cell, st, b, r if ok else math.inf, allowed, ref.agree)


@claim("paths.kernels", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3, 5),
       parts=scale_parts,
       where="symbt/numeric/float64/kernels.py, kernels_block.py, orbit.py (kernel_step), step.py",
       statement="on moderate float64 states in every branch x sign(mu) x sign(tr) cell the fused kernel finishes "
                 "each step itself (kernel_step gives none back), the block kernel reports OK for every member "
                 "and equals the fused kernel bit for bit, and both = the literal map within 16 N eps S_i; where "
                 "no real map exists both kernels report it; 1e-9 of the gap inside a band edge (N = 3) both give "
                 "the state back (ILLCOND) and bt_step is still within 16 N eps S_i (N={N})")
def kernel_paths(N: int, parts: Parts) -> Outcome:
    from ..numeric.float64.orbit import kernel_step

    tally, C = Tally(), step_constant(N)
    s = parts.printed["scale"]
    for b in (1, -1):
        rows = [(cell, st) for cell, st, bb in ship_cells(N, 1) if bb == b]
        try:
            BP, BQ, status = _block_kernel([st for _, st in rows], b)
        except (FloatingPointError, ZeroDivisionError, OverflowError, ValueError, IndexError) as exc:
            tally.notes.append(f"the block kernel raised {type(exc).__name__}.")
            BP = BQ = status = None
        for i, (cell, st) in enumerate(rows):
            ref = step_ref(st, b)
            out = kernel_step(np.array(st[0]), np.array(st[1]), st[2], st[3], b, "python")
            if out is None:
                tally.notes.append("the fused kernel gave a moderate state back to the general path.")
                tally.add("fused kernel", cell, st, b, math.inf)
            else:
                r, allowed = ratios(scaled(list(out[0]) + list(out[1]), s), ref.x, ref.S, EPS, C)
                tally.add("fused kernel", cell, st, b, r, allowed, ref.agree)
            if status is None or BP is None or BQ is None:
                tally.add("block kernel", cell, st, b, math.inf)
                continue
            r, allowed = ratios(scaled(list(BP[i]) + list(BQ[i]), s), ref.x, ref.S, EPS, C)
            if status[i] != 0:
                tally.notes.append(f"the block kernel gave a moderate state back (status {status[i]}).")
                r = math.inf
            elif out is not None and not (np.array_equal(BP[i], out[0]) and np.array_equal(BQ[i], out[1])):
                tally.notes.append("a block-kernel member differs from the fused kernel's step (documented: bit "
                                   "for bit equal).")
                r = math.inf
            tally.add("block kernel", cell, st, b, r, allowed, ref.agree)
    if N == 3:
        _near_edge(tally, s)
    # without a real map the kernels themselves say so (the drivers' typed error rests on their status)
    from .shipped_emitted import nomap_states

    for st, b, (cond, decided) in nomap_states(N):
        if not decided:
            continue
        cell = {"branch": b, "no map": str(cond)}
        single = kernel_step(np.array(st[0]), np.array(st[1]), st[2], st[3], b, "python")
        tally.add("fused kernel", cell, st, b, 0.0 if single is None else math.inf)
        try:
            status = _block_kernel([st], b)[2]
            ok = int(status[0]) in NO_MAP_STATUS
        except (FloatingPointError, ZeroDivisionError, OverflowError, ValueError, IndexError):
            ok = False
        if not ok:
            tally.notes.append(f"the block kernel did not report a state without a real map ({cond}).")
        tally.add("block kernel", cell, st, b, 0.0 if ok else math.inf)
    return tally.outcome(method="numeric: the fused and block kernels alone (no fallback) vs the literal map, "
                                "statuses and bit identity",
                         printed=f"kernels finish and |kernel - literal| <= {C} eps S_i")


# --------------------------------------------------------------------------- failing batch members

def failing_parts(N: int | None = None) -> Parts:
    """``scale`` and the name of the error a batch with a member without a real map must raise."""
    return Parts(printed={"scale": 1.0, "error": "NoRealMapError"})


def _single_error(fn: Any) -> BaseException | None:
    try:
        fn()
    except Exception as exc:  # the typed error (or any other: compared by type below)
        return exc
    return None


@claim("paths.failing_rows", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=failing_parts,
       where="symbt/numeric/float64/orbit.py (validated_float_orbit, general_orbit, raise_for_status), rows.py, "
             "core/step.py (where_text)",
       statement="a batch with one member without a real map among moderate ones: bt_step (numpy rows) and "
                 "bt_orbit ensembles (block kernel + the general path's retry; numpy) raise NoRealMapError with "
                 "where = that member and the single-state call's condition; a member beyond the float64 range "
                 "gives NumericRangeError; with allow_complex=True the other members equal their single-state "
                 "steps bit for bit and the failing member its single-state continuation; where_text names the "
                 "failing row as documented; under --deep also the numba block kernel's batch step and ensemble "
                 "(N={N})")
def failing_rows(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import NumericRangeError, bt_orbit, bt_step
    from .shipped_emitted import nomap_states

    table = CellTable(tol=0.5)
    bad: list[str] = []
    s = parts.printed["scale"]

    def note(cell: dict, st: tuple, b: int, why: str) -> None:
        if why and len(bad) < 6:
            bad.append(f"{cell['route']} ({cell['member']}): {why}")
        table.add(cell, printed=1.0 if why else 0.0,
                  point=fmt_state(tuple(_mpf_list(v) if isinstance(v, tuple) else mp.mpf(v) for v in st), b))

    for st_bad, b, (cond, decided) in nomap_states(N):
        if not decided:
            continue
        good = [st for _, st, bb in ship_cells(N, 1) if bb == b][:2]
        rows = [good[0], st_bad, good[1]]
        P, Q = np.array([r[0] for r in rows]), np.array([r[1] for r in rows])
        L, M = np.array([r[2] for r in rows]), np.array([r[3] for r in rows])
        single = _single_error(lambda: bt_step(np.array(st_bad[0]), np.array(st_bad[1]), st_bad[2], st_bad[3],
                                               branch=b, backend="numpy"))
        routes = {"bt_step batch (numpy rows)": lambda: bt_step(P, Q, L, M, branch=b, backend="numpy"),
                  "bt_orbit ensemble (block kernel, retry)": lambda: bt_orbit(P, Q, L, M, 3, branch=b,
                                                                              backend="python"),
                  "bt_orbit ensemble (numpy)": lambda: bt_orbit(P, Q, L, M, 3, branch=b, backend="numpy")}
        if deep and importlib.util.find_spec("numba") is not None:   # the compiled block kernel and its retry
            routes["bt_step batch (numba block kernel, retry)"] = lambda: bt_step(P, Q, L, M, branch=b,
                                                                                  backend="numba")
            routes["bt_orbit ensemble (numba)"] = lambda: bt_orbit(P, Q, L, M, 3, branch=b, backend="numba")
        for name, fn in routes.items():
            cell = {"route": name, "member": str(cond)}
            exc = _single_error(fn)
            if exc is None:
                why = "returned a finite batch"
            elif type(exc).__name__ != parts.printed["error"] or type(single).__name__ != parts.printed["error"]:
                why = f"raised {type(exc).__name__} (single state: {type(single).__name__})"
            elif getattr(exc, "where", None) != [(1,)] and tuple(getattr(exc, "where", ())) != ((1,),):
                why = f"where = {getattr(exc, 'where', None)}, expected member (1,)"
            elif getattr(exc, "condition", None) != getattr(single, "condition", None):
                why = f"condition {getattr(exc, 'condition', None)!r}, single state {single.condition!r}"  # type: ignore[union-attr]
            else:
                why = ""
            note(cell, st_bad, b, why)
        # the complex continuation: the moderate members are their own single-state steps, real
        cell = {"route": "bt_step batch, allow_complex", "member": "moderate"}
        try:
            pt, qt = bt_step(P, Q, L, M, branch=b, backend="numpy", allow_complex=True)
            why = ""
            for i in (0, 2):
                sp_, sq_ = bt_step(np.array(rows[i][0]), np.array(rows[i][1]), rows[i][2], rows[i][3], branch=b,
                                   backend="numpy")
                re_p, re_q = np.asarray(scaled(np.real(pt[i]), s)), np.asarray(scaled(np.real(qt[i]), s))
                if np.any(np.imag(pt[i])) or np.any(np.imag(qt[i])):
                    why = "a moderate member came back complex"
                elif not (np.array_equal(re_p, sp_) and np.array_equal(re_q, sq_)):
                    why = "a moderate member differs from its single-state step"
            # the member without a real map: its continuation is the single-state call's, bit for bit
            cp_, cq_ = bt_step(np.array(st_bad[0]), np.array(st_bad[1]), st_bad[2], st_bad[3], branch=b,
                               backend="numpy", allow_complex=True)
            if not why and not (np.array_equal(pt[1], cp_) and np.array_equal(qt[1], cq_)):
                why = "the member without a real map differs from its single-state continuation"
        except Exception as exc:  # allow_complex must not raise on a batch with a real map elsewhere
            why = f"raised {type(exc).__name__}"
        note(cell, st_bad, b, why)
    # a member beyond the float64 range among moderate ones: the typed range error, from every route
    good = [st for _, st, bb in ship_cells(N, 1) if bb == 1][:2]
    far = (good[0][0], (0.0, 710.0) + good[0][1][2:], good[0][2], good[0][3])
    rows = [good[0], far, good[1]]
    P, Q = np.array([r[0] for r in rows]), np.array([r[1] for r in rows])
    L, M = np.array([r[2] for r in rows]), np.array([r[3] for r in rows])
    for name, fn in {"bt_step batch (numpy rows)": lambda: bt_step(P, Q, L, M, backend="numpy"),
                     "bt_orbit ensemble (block kernel, retry)": lambda: bt_orbit(P, Q, L, M, 2, backend="python"),
                     "bt_orbit ensemble (numpy)": lambda: bt_orbit(P, Q, L, M, 2, backend="numpy")}.items():
        err = _single_error(fn)
        why = "" if isinstance(err, NumericRangeError) else f"raised {type(err).__name__ if err else 'nothing'}"
        note({"route": name, "member": "|dq| = 710"}, far, 1, why)
    # the helper that names the failing rows, called as documented (offset 0 by default): row 1 of a (2, 2) batch
    from ..numeric.core.step import where_text

    named = where_text([True, True, False, True], (2, 2))[0]
    note({"route": "where_text", "member": "(1, 0)"}, far, 1, "" if named == [(1, 0)] else f"named {named}")
    detail = ("; ".join(bad) + ".") if bad else ("every batch raised the single-state call's error, naming exactly "
                                                "the failing member; the other members are their own steps.")
    return judge_cells(table, printed="batch error = single-state error, where = the failing member",
                       method="numeric: batches with one failing member vs the single-state calls", detail=detail)


# --------------------------------------------------------------------------- tiny mu

@claim("paths.tiny_mu", equation="eqdisc", source_equation="eqdisc", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/flow/coefficients.py: flow_coefficients where lam0 - mu == lam0 + mu in float64",
       statement="flow_coefficients at |mu| below the spacing of doubles at lam0 < 0 = -b 2 mu lam0^k / "
                 "sqrt(tr^2 - 4) (tr by the literal 2x2 product, 40 digits) within 16 N eps of it (N={N})")
def tiny_mu(N: int, parts: Parts) -> Outcome:
    from ..numeric import flow_coefficients

    table = CellTable(tol=1.0)
    worst = 0.0
    for cell, st, b in ship_cells(N, 1):
        if cell["sign_mu"] < 0:
            continue
        p, q, l0, _ = st
        l0 = -abs(l0) if l0 != 0 else -1.0
        with mp.workdps(40):
            tr = literal_trace(mp.mpf(l0), p, q)
        if abs(tr) <= 2.2:
            continue
        mu = math.ulp(l0) / 8      # lam0 -+ mu round to lam0
        try:
            with without_numba():   # its existence check runs the plain-Python kernel (bit-identical)
                c = flow_coefficients(np.array(p), np.array(q), l0, mu, branch=b)
        except Exception:  # the state has a real map at lam0 (|tr| > 2): any error fails
            table.add({"sign_tr": cell["sign_tr"], "branch": b}, printed=math.inf)
            worst = math.inf
            continue
        with mp.workdps(40):
            ref = [-b * 2 * mp.mpf(mu) * mp.mpf(l0) ** k / mp.sqrt(tr * tr - 4) for k in range(N)]
            got = scaled(c, parts.printed["scale"])
            r = max(float(abs(mp.mpf(x) - y) / (16 * N * EPS * abs(y))) for x, y in zip(got, ref))
        worst = max(worst, r)
        table.add({"sign_tr": cell["sign_tr"], "branch": b}, printed=r,
                  point=fmt_state((_mpf_list(p), _mpf_list(q), mp.mpf(l0), mp.mpf(mu)), b))
    if not table.rows:
        return skipped("no sample with |tr L(lam0)| > 2.2 at lam0 < 0")
    return judge_cells(table, printed="|c_k - (-b 2 mu lam0^k / sqrt(tr^2 - 4))| <= 16 N eps |c_k|",
                       method="numeric: flow_coefficients' tiny-mu branch vs the polynomial trace (40 digits)",
                       detail=f"worst error/bound {worst:.3g}.")


# --------------------------------------------------------------------------- growth record

@claim("paths.growth", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts, requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: growth_law, the info= record of certified_orbit",
       statement="certified_orbit's info['growth'] (N={N}, 12 steps, tol 1e-12, every step stored): log2_radius "
                 "at its first and last step = log2 of the largest returned radius there, and degree = the "
                 "least-squares slope of log2(largest radius) against log2(step) over its steps, within 1e-9")
def growth_record(N: int, parts: Parts) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from ..numeric import certified_orbit

    cell, st, b = ship_cells(N, 1)[0]
    info: dict[str, Any] = {}
    n = GROWTH_STEPS
    # tol 1e-12 at 30 digits: the enclosures' radii (~2^-75) dwarf the rounding of the returned midpoints
    # (~2^-103); measured, the returned radii are the record's to the last bit (the fits agree to 2e-14)
    with mp.workdps(30):
        _, _, Pr, Qr = certified_orbit(list(st[0]), list(st[1]), st[2], st[3], n, branch=b, every=1, info=info,
                                       tol=GROWTH_TOL)
    growth = info.get("growth")
    if info.get("method") != "lohner" or not growth:
        return failed("numeric: certified_orbit info record", detail=f"info = {info!r}"[:300])
    # step 0 is the exact input (radius 0): the record's law starts at step 1
    lograd = [-math.inf] + [math.log2(max(float(r) for r in list(a) + list(c))) for a, c in zip(Pr[1:], Qr[1:])]
    first, last = growth["steps"]
    bad = []
    for k, i in enumerate((first, last)):
        if not abs(growth["log2_radius"][k] - lograd[i]) <= GROWTH_LOG_TOL:
            bad.append(f"log2_radius at step {i} = {growth['log2_radius'][k]}, the returned radii give {lograd[i]:.6g}")
    pts = sorted({int(round(first * 10 ** (k / 10))) for k in range(200)} & set(range(first, last + 1)) | {last})
    xs = np.log2(np.array(pts, dtype=float))
    ys = np.array([lograd[i] for i in pts])
    slope = float(np.polyfit(xs, ys, 1)[0]) * parts.printed["scale"]
    deg = growth.get("degree")
    if deg is None or not abs(deg - slope) <= GROWTH_LOG_TOL:
        bad.append(f"degree {deg}, least squares of the returned radii {slope:.6g}")
    detail = f"steps {first}..{last}, degree {deg}, fit {slope:.6g}."
    if bad:
        return failed("numeric: certified_orbit info record vs the returned radii", detail="; ".join(bad) + ". "
                      + detail)
    return Outcome("verified", "numeric: certified_orbit info record vs the returned radii", evidence="sampled",
                   detail=detail, printed="info['growth'] = the growth of the returned radii")


# --------------------------------------------------------------------------- the large-frame Lohner path

#: paths.frame: the lattice size (2N > 24: the float64 frame algebra and frame_inverse's one-product bound),
#: the steps, and the radius target (absolute)
FRAME_N, FRAME_STEPS, FRAME_TOL, FRAME_DPS = 13, 4, 1e-50, 80


def frame_state() -> tuple[list[float], list[float], int, float]:
    """The binary-exact N = 13 state of ``paths.frame`` (no decimal rounding: the exact input is the same at
    every precision, so the literal orbit at 60 digits and the certified one start from the same point)."""
    N = FRAME_N
    return [((j * 7) % 5 - 2) / 8 for j in range(N)], [((j * 3) % 4) / 16 for j in range(N)], 3, 0.5


@claim("paths.frame", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(13,),
       parts=scale_parts, requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: LohnerSet above 2N = 24 (float64 frame, frame_inverse)",
       statement="certified_orbit(method='lohner') at N={N}, 4 steps, tol 1e-50, 80 digits: every returned ball "
                 "contains the literal orbit (160 digits, the same binary input) and every radius is <= tol")
def frame_path(N: int, parts: Parts) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from ..numeric import certified_orbit
    from ..reference.literal import literal_step

    p, q, lam0, mu = frame_state()
    info: dict[str, Any] = {}
    with mp.workdps(FRAME_DPS):
        P, Q, Pr, Qr = certified_orbit(p, q, lam0, mu, FRAME_STEPS, branch=1, every=1, info=info,
                                       tol=FRAME_TOL, method="lohner")
    bad, worst, widest = [], 0.0, 0.0
    with mp.workdps(2 * FRAME_DPS):
        pp, qq = _mpf_list(p), _mpf_list(q)
        for k in range(1, FRAME_STEPS + 1):
            pp, qq, _ = literal_step(pp, qq, mp.mpf(lam0), mp.mpf(mu), 1)
            for x, c, r in zip(pp + qq, list(P[k]) + list(Q[k]), list(Pr[k]) + list(Qr[k])):
                # the returned ball, scaled by the printed 1: a ball that misses the literal value fails
                off = abs(x - mp.mpf(c) * parts.printed["scale"])
                widest = max(widest, float(r))
                if not off <= r:
                    bad.append(f"step {k}: |literal - returned| = {mp.nstr(off, 3)} > radius {mp.nstr(r, 3)}")
                elif r > 0:
                    worst = max(worst, float(off / r))
    if not widest <= FRAME_TOL:
        bad.append(f"largest radius {widest:.3g} > tol {FRAME_TOL:g}")
    detail = (f"method {info.get('method')}, prec {info.get('prec')} bits; largest radius {widest:.3g}, "
              f"largest |literal - returned| / radius {worst:.3g}.")
    if bad or info.get("method") != "lohner":
        return failed("numeric: certified Lohner orbit (N=13) vs the literal map", detail="; ".join(bad[:3]) + ". "
                      + detail)
    return Outcome("verified", "numeric: certified Lohner orbit (N=13) vs the literal map at 60 digits",
                   evidence="sampled", detail=detail, printed="the literal orbit lies in every returned ball")


# --------------------------------------------------------------------------- stored states of the fused orbit

#: paths.stored: steps and the storage interval (n not a multiple of every: the last state is stored apart)
STORED_STEPS, STORED_EVERY = 10, 3


@claim("paths.stored", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/kernels.py: orbit, orbit_rows, stored_steps (plain Python)",
       statement="the fused orbit kernel, N={N}, 10 steps stored every 3rd, one state per cell: status 0, "
                 "orbit_rows(10, 3) = 5 rows, equal bit for bit to the rows 0, 3, 6, 9, 10 of the same orbit "
                 "stored at every step (documented: the orbit does not depend on every)")
def stored_states(N: int) -> Outcome:
    from ..numeric.float64.kernels import ANCHOR, orbit, orbit_rows, stored_steps

    # a consistency check of a documented invariance (the same kernel twice); the rows' accuracy against the
    # literal map is shipped.orbit's
    n, every = STORED_STEPS, STORED_EVERY
    bad = []
    cells = ship_cells(N, 1)
    for cell, st, b in cells:
        p, q, l0, m = st
        runs = []
        for ev in (every, 1):
            rows = orbit_rows(n, ev)
            P, Q = np.full((rows + 1, N), np.nan), np.full((rows + 1, N), np.nan)    # one spare row: overruns show
            status = orbit(np.array(p), np.array(q), l0 + m, l0 - m, 2 * m, b, n, ev, ANCHOR, P, Q)
            runs.append((status, P, Q, rows))
        (s3, P3, Q3, r3), (s1, P1, Q1, _) = runs
        keep = stored_steps(n, every)
        if s3 != 0 or s1 != 0:
            bad.append(f"{cell}: status {s3} (every {every}), {s1} (every 1)")
        elif r3 != len(keep) or not (np.isnan(P3[r3]).all() and np.isnan(Q3[r3]).all()):
            bad.append(f"{cell}: {r3} rows for steps {keep}, or a row written past them")
        elif not (np.array_equal(P3[:r3], P1[keep]) and np.array_equal(Q3[:r3], Q1[keep])):
            bad.append(f"{cell}: the rows stored every {every} differ from the steps {keep} stored every step")
    detail = f"{len(cells)} cells, steps {stored_steps(n, every)}."
    if bad:
        return failed("numeric: fused orbit's stored states", detail="; ".join(bad[:3]) + " " + detail)
    return Outcome("verified", "numeric: fused orbit's stored states, every 3 vs every step (bit for bit)",
                   evidence="sampled", detail=detail, printed="the orbit does not depend on every")
