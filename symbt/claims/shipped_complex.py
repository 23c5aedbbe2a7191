r"""What ships, 4c: the complex continuation, ``bt_step(..., allow_complex=True)`` (scene ``numeric-paths``).

``paths.complex.n3`` -- where no real map exists (``lam1`` in a band, or ``lam1``, ``lam2`` in different gaps),
``allow_complex=True`` returns the complex continuation of the map.  Its multiprecision routes --
python-flint's complex Arb balls (``backend="flint"``, the ``ACB`` context) and mpmath (``"mpmath"``), both at 30
digits -- are compared with the literal map of :mod:`symbt.reference.literal`, which continues into the complex
numbers by itself (mpc arithmetic), at 60 digits and checked at 85 (``p~`` exactly, ``q~`` modulo ``2 pi i``: it
enters the map only through ``e^q~``), within
``16 N u S_i`` with ``S_i = |x~_i| + sum_j max(|x_j|, 1) |d x~_i / d x_j|`` (forward differences of the literal map
at 30 digits plus guard, as for the real map in :mod:`symbt.claims._shipped`).  The choice of the square root's
half-plane (which eigenvector the continuation follows) is what this tests: a wrong choice is an O(1) error.

Not claimed: the float64 continuation (complex128 rows of the general path).  Its accuracy is not documented,
and at the state with ``lam1``, ``lam2`` in different gaps (branch -1) its ``q~_1`` is ~140 ulps off the
literal one (error/bound 1.38 at ``C = 16 N``); its ``q~`` also takes ``-i pi`` where mpmath takes ``+i pi``
(the same point modulo ``2 pi i``).

Shown to fail on a planted bug in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

import importlib.util
import math
from functools import cache
from typing import Any

import mpmath as mp

from ..proof.cells import CellTable
from ..reference.literal import literal_step
from ._common import fmt_state
from ._shipped import scale_parts, scaled, step_constant
from .base import Outcome, Parts, claim, judge_cells

MP_DPS = 30
#: the literal continuation's digits (checked at REF_DPS + 25) and those of its forward differences (step 1e-15)
REF_DPS, FD_DPS = 60, 45
#: the paper's N = 3 state (bands near -10.28, -0.787 and 20.06; the gaps between them carry traces of opposite
#: signs): lam2 = -0.787 in the middle band; lam2 = -0.787 with lam1 = 0.787; lam1 = 2, lam2 = -5 in different gaps;
#: lam1 = 1000, lam2 = -1000 in the two outer gaps (|tr| ~ 1e9: the transport's direction matters there, the wrong
#: one loses about 5 digits)
STATES = (((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 4.213, 5.0),
          ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 0.0, 0.787),
          ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), -1.5, 3.5),
          ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 0.0, 1000.0))
#: the reference's accepted disagreement with itself at REF_DPS + 25 digits: the literal continuation loses about
#: 2 log10 |tr| digits in its forward transport (18 at the last state); 20 digits leave it (1e-40) 11 digits below
#: the smallest bound, 16 N u = 4e-29 at 30 digits
REF_LOSS = 20


def _literal(st: tuple, b: int, dps: int) -> list:
    p, q, l0, m = st
    with mp.workdps(dps):
        P, Q, _ = literal_step([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m), b)
        return [+v for v in list(P) + list(Q)]


@cache
def complex_ref(st: tuple, b: int) -> tuple[tuple, tuple, float]:
    """``(x, S, agree)``: the literal continuation at REF_DPS digits, its condition scales (forward differences at
    FD_DPS digits, step 1e-15), and its disagreement with the same at REF_DPS + 25 digits relative to the state's
    size."""
    x = _literal(st, b, REF_DPS)
    chk = _literal(st, b, REF_DPS + 25)
    size = max(max(abs(v) for v in x), 1)
    agree = float(max(abs(a - c) for a, c in zip(x, chk)) / size)
    xin = list(st[0]) + list(st[1]) + [st[2], st[3]]
    N = len(st[0])
    S = [abs(v) for v in x]
    with mp.workdps(FD_DPS):
        x0 = _literal(st, b, FD_DPS)
        for j, v in enumerate(xin):
            w = max(abs(v), 1)
            h = mp.mpf(10) ** -15 * w
            hi = [mp.mpf(t) for t in xin]
            hi[j] += h
            fp = _literal((hi[:N], hi[N:2 * N], hi[2 * N], hi[2 * N + 1]), b, FD_DPS)
            S = [s + w * abs(a - c) / h for s, a, c in zip(S, fp, x0)]
    return tuple(x), tuple(S), agree


def _mod_2pi_i(d: Any) -> Any:
    """``d`` with its imaginary part reduced to ``[-pi, pi]``: ``q~`` enters the map only through ``e^q~``, so the
    continuation's ``q~`` is defined modulo ``2 pi i`` (``log`` of a negative ``1 + x_j``: mpmath's principal
    branch gives ``+i pi``, numpy's ``log1p`` of a value with a signed zero imaginary part ``-i pi``)."""
    d = mp.mpc(d)
    two_pi = 2 * mp.pi
    return mp.mpc(d.real, d.imag - two_pi * mp.nint(d.imag / two_pi))


@claim("paths.complex", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/multiprec/arb.py (ACB: the complex Arb context), runners.py, core/context.py: "
             "bt_step(..., allow_complex=True) on mpmath numbers",
       statement="where no real map exists, bt_step(allow_complex=True) on Arb (flint) and mpmath (30 digits) "
                 "= the literal map's complex continuation (60 digits; q~ modulo 2 pi i) within 16 N u S_i "
                 "(N={N})")
def complex_continuation(N: int, parts: Parts) -> Outcome:
    from ..numeric import bt_step

    table = CellTable(tol=1.0)
    C = step_constant(N)
    worst: dict[str, float] = {}
    routes: dict[str, Any] = {"mpmath": "mpmath"}
    if importlib.util.find_spec("flint") is not None:
        routes = {"Arb (flint)": "flint", **routes}
    for k, st in enumerate(STATES):
        for b in (1, -1):
            x, S, agree = complex_ref(st, b)
            for name, be in routes.items():
                try:
                    with mp.workdps(MP_DPS):
                        u = 2.0 ** -mp.mp.prec
                        pt, qt = bt_step([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]], mp.mpf(st[2]),
                                         mp.mpf(st[3]), branch=b, allow_complex=True, backend=be)
                    # mpf/mpc kept at their own precision (mp.mpc(v) would round them to the current one)
                    got = scaled(list(pt) + list(qt), parts.printed["scale"])
                    with mp.workdps(60):
                        r = max(float(abs(_mod_2pi_i(g - xr) if i >= N else g - xr) / (C * u * s))
                                for i, (g, xr, s) in enumerate(zip(got, x, S)))
                except Exception:  # the continuation exists (a complex state): any error fails
                    r = math.inf
                if agree > 10.0 ** (REF_LOSS - REF_DPS):
                    r = math.inf
                worst[name] = max(worst.get(name, 0.0), r)
                table.add({"route": name, "state": k, "branch": b}, printed=r,
                          point=fmt_state(([mp.mpf(v) for v in st[0]], [mp.mpf(v) for v in st[1]], mp.mpf(st[2]),
                                           mp.mpf(st[3])), b))
    detail = "worst error/bound per route: " + "; ".join(f"{k}: {v:.3g}" for k, v in worst.items()) + "."
    return judge_cells(table, printed=f"|continuation - literal| <= {C} u S_i",
                       method="numeric: allow_complex routes vs the literal map's complex continuation (60 digits)",
                       detail=detail)
