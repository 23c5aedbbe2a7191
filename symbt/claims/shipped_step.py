r"""What ships, 1: :func:`symbt.numeric.bt_step` and :func:`symbt.numeric.bt_orbit` on every route, against the
literal map at 50 digits (scene ``shipped``).

Each claim runs a public entry point on every route it has and compares each output component with the
paper's map computed literally (:func:`symbt.reference.literal.reference_step`, 50 digits, checked against
itself at 75), accepting ``|route - reference| <= C u S_i`` -- ``S_i`` the condition scale of the component
(forward differences of the reference), ``u`` the route's unit roundoff, ``C = 16 N`` -- in every cell
branch x sign(mu) x sign(tr L(lambda_1,2)) (:mod:`symbt.claims._shipped`), plus states with q spread over
~1000.  Routes forced with ``backend=``: the fused kernel (``"python"``: the numba kernel's code, bit for bit,
without loading numba), the general path (``"numpy"``), batches (numpy rows), the block kernel (an ensemble
``bt_orbit``, ``"python"``), mpmath and Arb (``"mpmath"``, ``"flint"``) at 30 digits; under ``--deep`` also the
numba-compiled kernels, ``backend="auto"`` and the quad-double orbit (``"qd"``), and N = 8.
"""
from __future__ import annotations

import importlib.util
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import mpmath as mp
import numpy as np

from ._shipped import (
    EPS,
    REF_DPS,
    Tally,
    orbit_ref,
    range_error,
    ratios,
    scale_parts,
    scaled,
    ship_cells,
    step_constant,
    step_outputs,
    step_ref,
    wide_states,
)
from .base import Outcome, Parts, claim, scene

if TYPE_CHECKING:
    from ..numeric import BackendName

scene("shipped", "what ships: every public numeric entry point and emitted form against the literal map (or "
                 "another independent route), with two-sided bounds from the conditioning (issue 21)")

MP_DPS = 30
#: states per cell {branch, sign_mu, sign_tr} of the one-step claims (orbits: one, two under --deep)
PER_CELL, PER_CELL_DEEP = 2, 8
ORBIT_STEPS, DEEP_ORBIT_STEPS = 10, 40


def _has(mod: str) -> bool:
    return importlib.util.find_spec(mod) is not None


def _mpf_state(st: tuple) -> tuple:
    return [mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]], mp.mpf(st[2]), mp.mpf(st[3])


class Declined(Exception):
    """A route's documented NumericRangeError at a wide state (see :meth:`Tally.decline`)."""


def _run(tally: Tally, route: str, fn: Callable[[], Any], wide: bool = False) -> Any:
    """``fn()``, or ``None`` (noted once per route) if it raises: an admissible state has a real map."""
    try:
        return fn()
    except Exception as exc:  # a route that raises on an admissible state fails that sample
        if wide and range_error(exc):
            raise Declined(route) from exc
        note = f"{route} raised {type(exc).__name__}: {exc}"[:200]
        if not any(n.startswith(route + " raised") for n in tally.notes):
            tally.notes.append(note + ".")
        return None


def _samples(N: int, deep: bool) -> tuple:
    return ship_cells(N, PER_CELL_DEEP if deep else PER_CELL) + wide_states(N)


def _float_routes(deep: bool) -> list[BackendName]:
    routes: list[BackendName] = ["python", "numpy"]
    return routes + (["numba", "auto"] if deep and _has("numba") else [])


def _mp_routes(deep: bool) -> list[BackendName]:
    routes: list[BackendName] = ["mpmath"]
    return (routes + (["flint"] if _has("flint") else [])
            + (["qd"] if deep and _has("numba") else []))


_ROUTE_NAMES = {"python": "fused kernel", "numpy": "general path", "numba": "fused kernel (numba)",
                "auto": "auto", "mpmath": "mpmath", "flint": "Arb", "qd": "quad-double"}


@claim("shipped.step", equation="bt_step", source_equation="imptransf", scene="shipped", sizes=(8,), deep=True,
       parts=scale_parts, where="symbt/numeric/dispatch.py, float64/step.py: bt_step (float64 one state)",
       statement="symbt.numeric.bt_step, one float64 state, on every route, = the literal map (50 digits) within "
                 "16 N eps S_i per component, in every branch x sign(mu) x sign(tr) cell (N={N})")
@claim("shipped.step", equation="bt_step", source_equation="imptransf", scene="shipped", sizes=(2, 3, 5),
       parts=scale_parts, where="symbt/numeric/dispatch.py, float64/step.py: bt_step (float64 one state)",
       statement="symbt.numeric.bt_step, one float64 state, on every route (fused kernel, general path; numba "
                 "and auto under --deep), = the literal map (50 digits) within 16 N eps S_i per component "
                 "(S_i: condition scale), in every branch x sign(mu) x sign(tr) cell and at q spread over ~1000 "
                 "(N={N})")
def step(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import bt_step

    tally, C = Tally(), step_constant(N)
    for cell, st, b in _samples(N, deep):
        ref = step_ref(st, b)
        for be in _float_routes(deep):
            try:
                out = _run(tally, be, lambda: bt_step(np.array(st[0]), np.array(st[1]), st[2], st[3], branch=b,
                                                      backend=be), wide=cell.get("q") == "wide")
            except Declined:
                tally.decline(_ROUTE_NAMES[be], cell, st, b)
                continue
            r, allowed = (ratios(scaled(step_outputs(out), parts.printed["scale"]), ref.x, ref.S, EPS, C)
                          if out is not None else (np.inf, 0.0))
            tally.add(_ROUTE_NAMES[be], cell, st, b, r, allowed, ref.agree)
    return tally.outcome(method=f"numeric: float64 routes vs the literal map ({REF_DPS} digits), bound 16 N eps S",
                         printed=f"|bt_step - literal| <= {C} eps S_i")


@claim("shipped.batch", equation="bt_step", source_equation="imptransf", scene="shipped", sizes=(2, 3, 5),
       parts=scale_parts,
       where="symbt/numeric/float64/step.py, rows.py, kernels_block.py: bt_step on (M, N) batches, bt_orbit ensembles",
       statement="symbt.numeric.bt_step on an (M, N) batch with per-state lambda0, mu (numpy rows; the numba "
                 "block kernel under --deep) and the block kernel of an ensemble bt_orbit (one step, plain "
                 "Python) = the literal map (50 digits) member by member within 16 N eps S_i, every cell (N={N})")
def batch(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import bt_orbit, bt_step

    tally, C = Tally(), step_constant(N)
    samples = _samples(N, deep)
    routes: dict[str, Callable[..., Any]] = {
        "batch (numpy rows)": lambda P, Q, L, M, b: bt_step(P, Q, L, M, branch=b, backend="numpy"),
        "ensemble (block kernel)": lambda P, Q, L, M, b: tuple(a[1] for a in bt_orbit(P, Q, L, M, 1, branch=b,
                                                                                      backend="python")),
    }
    if deep and _has("numba"):
        routes["batch (numba block kernel)"] = lambda P, Q, L, M, b: bt_step(P, Q, L, M, branch=b, backend="numba")
    for b in (1, -1):
        rows = [(cell, st) for cell, st, bb in samples if bb == b]
        P, Q = np.array([st[0] for _, st in rows]), np.array([st[1] for _, st in rows])
        L, M = np.array([st[2] for _, st in rows]), np.array([st[3] for _, st in rows])
        for name, fn in routes.items():
            out = _run(tally, name, lambda fn=fn: fn(P, Q, L, M, b))  # type: ignore[misc]
            for i, (cell, st) in enumerate(rows):
                ref = step_ref(st, b)
                r, allowed = (ratios(scaled(list(out[0][i]) + list(out[1][i]), parts.printed["scale"]), ref.x,
                                     ref.S, EPS, C) if out is not None else (np.inf, 0.0))
                tally.add(name, cell, st, b, r, allowed, ref.agree)
    return tally.outcome(method=f"numeric: float64 batches vs the literal map ({REF_DPS} digits), member by member",
                         printed=f"|batch member - literal| <= {C} eps S_i")


@claim("shipped.mp", equation="bt_step", source_equation="imptransf", scene="shipped", sizes=(2, 3, 5),
       parts=scale_parts,
       where="symbt/numeric/dispatch.py, multiprec/runners.py, qd.py: bt_step on mpmath numbers",
       statement="symbt.numeric.bt_step on mpmath numbers at 30 digits (backends mpmath, Arb; quad-double under "
                 "--deep) = the literal map (50 digits) within 16 N 2^-prec S_i, every cell (N={N})")
def mp_step(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import bt_step

    tally, C = Tally(), step_constant(N)
    if not _has("flint"):
        tally.notes.append("Arb route not run: python-flint not installed (.[certified]).")
    for cell, st, b in _samples(N, deep):
        ref = step_ref(st, b)
        for be in _mp_routes(deep):
            with mp.workdps(MP_DPS):
                u = 2.0 ** -mp.mp.prec
                try:
                    out = _run(tally, be, lambda: bt_step(*_mpf_state(st), branch=b, backend=be),
                               wide=cell.get("q") == "wide")
                except Declined:   # quad-double: neighbour distances beyond 300 (documented)
                    tally.decline(_ROUTE_NAMES[be], cell, st, b)
                    continue
            r, allowed = (ratios(scaled(step_outputs(out), parts.printed["scale"]), ref.x, ref.S, u, C)
                          if out is not None else (np.inf, 0.0))
            tally.add(_ROUTE_NAMES[be], cell, st, b, r, allowed, ref.agree)
    return tally.outcome(method=f"numeric: mpmath routes ({MP_DPS} digits) vs the literal map ({REF_DPS} digits)",
                         printed=f"|bt_step(mpf) - literal| <= {C} 2^-prec S_i")


def _orbit_routes(deep: bool) -> dict[str, Callable[..., Any]]:
    from ..numeric import bt_orbit

    def single(be):
        return lambda st, b, n: bt_orbit(np.array(st[0]), np.array(st[1]), st[2], st[3], n, branch=b, backend=be)

    def ensemble(be):   # the state twice in an ensemble: member 1 must be the state's own orbit
        def run(st, b, n):
            P, Q = bt_orbit(np.array([st[0]] * 2), np.array([st[1]] * 2), np.array([st[2]] * 2),
                            np.array([st[3]] * 2), n, branch=b, backend=be)
            return P[:, 1], Q[:, 1]
        return run

    def mpr(be):
        def run(st, b, n):
            with mp.workdps(MP_DPS):
                return bt_orbit(*_mpf_state(st), n, branch=b, backend=be)
        return run

    routes = {"orbit: fused kernel": single("python"), "orbit: general path": single("numpy"),
              "ensemble: block kernel": ensemble("python"), "ensemble: numpy": ensemble("numpy")}
    for be in _mp_routes(deep):
        routes[f"orbit: {_ROUTE_NAMES[be]}"] = mpr(be)
    if deep and _has("numba"):
        routes["orbit: numba"], routes["ensemble: numba"] = single("numba"), ensemble("numba")
    return routes


@claim("shipped.orbit", equation="bt_orbit", source_equation="imptransf", scene="shipped", sizes=(2,), deep=True,
       parts=scale_parts,
       where="symbt/numeric/dispatch.py, float64/orbit.py, kernels*.py, multiprec/runners.py: bt_orbit",
       statement="symbt.numeric.bt_orbit (one state, ensemble, mpmath/Arb; numba and quad-double under --deep) "
                 "after n = 10 steps (40 under --deep) = the literal orbit (50 digits) within 16 N u n "
                 "max_m S^(m)_i (the bound grows with n as the orbit's conditioning), every cell (N={N})")
@claim("shipped.orbit", equation="bt_orbit", source_equation="imptransf", scene="shipped", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/dispatch.py, float64/orbit.py, kernels*.py, multiprec/runners.py: bt_orbit",
       statement="symbt.numeric.bt_orbit (one state, ensemble, mpmath/Arb; numba and quad-double under --deep) "
                 "after n = 10 steps (40 under --deep) = the literal orbit (50 digits) within 16 N u n "
                 "max_m S^(m)_i (the bound grows with n as the orbit's conditioning), n + 1 states stored (every "
                 "step), every cell (N={N})")
def orbit(N: int, parts: Parts, deep: bool = False) -> Outcome:
    tally, C = Tally(), step_constant(N)
    n = DEEP_ORBIT_STEPS if deep else ORBIT_STEPS
    if not _has("flint"):
        tally.notes.append("Arb route not run: python-flint not installed (.[certified]).")
    for cell, st, b in ship_cells(N, 2 if deep else 1):
        ref = orbit_ref(st, b, n)
        for name, fn in _orbit_routes(deep).items():
            with mp.workdps(MP_DPS):
                u = EPS if name.startswith(("orbit: fused", "orbit: general", "ensemble", "orbit: numba")) \
                    else 2.0 ** -mp.mp.prec
            out = _run(tally, name, lambda fn=fn: fn(st, b, n))  # type: ignore[misc]
            r, allowed = (ratios(scaled(list(out[0][n]) + list(out[1][n]), parts.printed["scale"]), ref.xs[n], ref.S,
                                 u, C * n)
                          if out is not None else (np.inf, 0.0))
            if out is not None and not len(out[0]) == len(out[1]) == n + 1:     # every step stored, none more
                tally.notes.append(f"{name}: {len(out[0])} stored states, not the {n + 1} of steps 0..{n}")
                r = np.inf
            tally.add(name, cell, st, b, r, allowed, ref.agree)
    return tally.outcome(method=f"numeric: {n}-step orbits vs the literal orbit ({REF_DPS} digits), bound 16 N u n S",
                         printed=f"|orbit_n - literal_n| <= {C} u n max_m S^(m)_i")


@claim("shipped.certified", equation="bt_orbit", source_equation="imptransf", scene="shipped", sizes=(2,), deep=True,
       parts=scale_parts,
       requires=("flint",), where="symbt/numeric/multiprec/certified.py: certified_orbit, bt_orbit(certified=True)",
       statement="bt_orbit(certified=True) at 30 digits, n = 10 steps: every enclosure [mid - rad, mid + rad] "
                 "contains the literal orbit (50 digits), and is informative (rad <= 1e-20 of the state's size), "
                 "every cell (N={N})")
@claim("shipped.certified", equation="bt_orbit", source_equation="imptransf", scene="shipped", sizes=(3,),
       parts=scale_parts,
       requires=("flint",), where="symbt/numeric/multiprec/certified.py: certified_orbit, bt_orbit(certified=True)",
       statement="bt_orbit(certified=True) at 30 digits, n = 10 steps: every enclosure [mid - rad, mid + rad] "
                 "contains the literal orbit (50 digits), and is informative (rad <= 1e-20 of the state's size), "
                 "every cell (N={N})")
def certified(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import bt_orbit

    tally = Tally()
    n = DEEP_ORBIT_STEPS if deep else ORBIT_STEPS
    worst_rad = 0.0
    for cell, st, b in ship_cells(N, 2 if deep else 1):
        ref = orbit_ref(st, b, n)
        with mp.workdps(MP_DPS):
            out = _run(tally, "certified", lambda: bt_orbit(list(st[0]), list(st[1]), st[2], st[3], n, branch=b,
                                                           certified=True, every=n))
        if out is None:
            tally.add("certified", cell, st, b, np.inf)
            continue
        P, Q, Pr, Qr = out
        scale = max(max(abs(v) for v in ref.xs[n]), 1)
        ratio = 0.0
        mids = scaled(list(P[-1]) + list(Q[-1]), parts.printed["scale"])
        for mid, rad, r in zip(mids, list(Pr[-1]) + list(Qr[-1]), ref.xs[n]):
            # contained: |mid - exact| <= rad; the 50-digit reference is exact to 1e-45 of the scale
            ratio = max(ratio, float(abs(mid - r) / (rad + scale * mp.mpf(10) ** -45)))
            worst_rad = max(worst_rad, float(rad / scale))
        if worst_rad > 1e-20:
            ratio = np.inf   # an enclosure that wide would contain a grossly wrong orbit too
        tally.add("certified", cell, st, b, ratio, 0.0, ref.agree)
    return tally.outcome(method=f"certified: Arb enclosures vs the literal orbit ({REF_DPS} digits)",
                         printed="literal orbit in every enclosure, radius <= 1e-20 relative",
                         detail=f"largest relative radius {worst_rad:.2e}.")
