r"""Theorem 2 on both flow routes (issue 21, item 5): the built-in Taylor integrator always, heyoka when installed.

The claims ``Hdiscr.n{2,3}`` integrate Hamilton's equations by the fastest route installed
(:func:`symbt.claims._flow.flow_route`); with heyoka the built-in route
(:func:`symbt.reference.taylor.hamiltonian_flow`) would never run in ``symbt verify``, and a defect in it would
be seen only where heyoka is absent.  ``Hdiscr.routes.n{2,3}`` runs the built-in route whatever is installed
on one state per cell (branch x sign tr) at the same tolerance -- with
heyoka installed, ``Hdiscr.n{2,3}`` is heyoka's evidence and this claim the built-in route's; under ``--deep``
it runs every installed route (:func:`symbt.claims._flow.flow_routes`) on 4 states per cell, each route a
coordinate of the cell table.  The built-in route runs within its budget (``_flow.TAYLOR_MAX_STEPS`` steps per unit of
time, ``_flow.TAYLOR_SECONDS``): a wrong vector field that blows up makes the sample fail within seconds.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..proof.cells import CellTable
from . import _flow
from ._common import fmt_state, judge_cells
from .base import Outcome, Parts, claim
from .theorem2 import TOL2, _limit, _parts_Hdiscr, c_from_phi, samples

ROUTE_TEXT = {"heyoka": "heyoka.taylor_adaptive (float64)", "taylor": "symbt.reference.taylor (20 digits)"}


def _residual(s: dict, c: np.ndarray, t: float, route: str) -> tuple[float, str]:
    """Relative distance between the BT image and the time-t flow by ``route`` (inf, with the reason, if the
    route fails or the c_k are not real)."""
    if not np.all(np.isfinite(c)) or np.max(np.abs(np.imag(c))) > 1e-12 * max(1e-300, np.max(np.abs(c))):
        return float("inf"), "complex c_k"
    try:
        fp, fq = _flow.time_flow(s["p"], s["q"], np.real(c), t, route=route)
    except ArithmeticError as exc:
        return float("inf"), f"{type(exc).__name__}: {exc}"
    return _flow.rel_diff(fp + fq, s["image"]), ""


@claim("Hdiscr.routes", equation="Hdiscr", scene="theorem2", sizes=(2, 3), parts=_parts_Hdiscr,
       uses=("Hdiscr.n{N}",),
       statement="Theorem 2 (eq. Hdiscr) by the built-in Taylor integrator whatever is installed (and, under "
                 "--deep, by every installed flow route): one BT step of branch b = the time-1 flow of sum_k c_k H_k, "
                 "c_k = dH/dH_k, one state per branch x sign(tr) cell (N={N})")
def routes(N: int, parts: Parts, deep: bool = False) -> Outcome:
    P = parts.printed
    table = CellTable(tol=TOL2)
    notes: list[str] = []
    seen: set = set()
    for s in samples(N, 4 if deep else 1):
        key = tuple(s["cell"].items())
        if not s["ok"] or (not deep and key in seen):   # one state per cell by default (not the paper's too)
            continue
        seen.add(key)
        c, im = c_from_phi(P["Phi"], s, _limit(P["upper"], s))
        for route in (_flow.flow_routes() if deep else ("taylor",)):
            r, why = _residual(s, c, float(P["time"]), route)
            if why and len(notes) < 3:
                notes.append(f"{route}: {why}")
            table.add(dict(route=route, **s["cell"]), printed=max(r, im), point=fmt_state(s["state"], s["b"]))
    used = ", ".join(ROUTE_TEXT[r] for r in (_flow.flow_routes() if deep else ("taylor",)))
    out = judge_cells(table, method=f"numeric: explicit map (mpmath 60 digits) vs the time-1 flow by each route "
                                    f"({used})", printed="one BT step of branch b = time-1 flow of sum c_k H_k",
                      dps=15, detail=("; ".join(notes) + ";" if notes else "")
                      + ("" if deep else " the built-in route (heyoka's, when installed, is claim Hdiscr.n%d);" % N))
    out = replace(out, n_scope=[N])
    return out
