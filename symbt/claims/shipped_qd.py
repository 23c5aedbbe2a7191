r"""What ships, 4a: the quad-double step, run as plain Python (scene ``numeric-paths``, issue 21).

``paths.qd.n{2,3}`` -- the quad-double step (:func:`symbt.numeric.multiprec.qd_step.qd_orbit`, run as plain Python:
the functions numba compiles, without numba, so the default ``symbt verify`` loads no numba) on inputs of 200
significant bits, negative ones included, converted by :func:`~symbt.numeric.multiprec.qd.to_qd`: one step per
cell (three, stored every second, at a state with a neighbour distance in ``(250, 300]``) against the literal
orbit of the same input at 80 digits (checked at 105), within ``16 N n 2**-209 S_i`` (the quad-double's 209
bits; ``S_i`` the condition scale of :mod:`symbt.claims._shipped`), and informative: a bound that admits a
relative error above 1e-50 makes the claim inconclusive, so a step that fell back to double-double or double
precision fails.  Also: a state beyond ``MAX_DQ_QD = 300`` is given back with the status ``RANGE`` at the first
step (where ``backend="auto"`` continues on the Arb path); states without a real map get a no-map status;
``to_qd`` splits values exactly (the sum of the limbs is the value, sign included) and refuses what it documents
it refuses; ``from_qd``'s integer decomposition (``_decompose``, plain Python) is exact;
:func:`~symbt.numeric.multiprec.qd.qd_fits` admits exactly ``mp.prec + 16 + 2 bitlen(n) <= 209``;
:func:`~symbt.numeric.multiprec.qd.qd_orbit_mp` refuses an input of ``2**601`` with ``NumericRangeError`` before
any kernel runs (its documented range; run without numba, the refusal does not depend on it).

The compiled route (``backend="qd"``, numba) is checked by ``shipped.mp`` and ``shipped.orbit`` under ``--deep``.
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
    Tally,
    guard_digits,
    literal_orbit,
    literal_state,
    orbit_ref,
    ratios,
    scaled,
    ship_cells,
    step_constant,
    step_ref,
    without_numba,
)
from .base import Outcome, Parts, claim, failed

QD_BITS = 209                     # a quad-double's precision (docs/numeric.md)
QD_WIDE_STEPS = 3
QD_REF_DPS, QD_CHECK_DPS = 80, 105
#: a quad-double sample whose bound admits a larger relative error is not informative
QD_INFORMATIVE = 1e-50
#: significant bits of the quad-double inputs (below to_qd's 212)
QD_INPUT_BITS = 200


def _mpf_list(xs: Any) -> list:
    return [mp.mpf(v) for v in xs]


def qd_parts(N: int | None = None) -> Parts:
    """``scale`` (outputs x scale = reference), the quad-double's bits and its neighbour-distance limit."""
    return Parts(printed={"scale": 1.0, "qd_bits": QD_BITS, "max_dq": 300.0})


def _tail(v: float, k: int) -> Any:
    """``v`` with a tail of ``QD_INPUT_BITS`` significant bits (a value no double-double carries exactly)."""
    with mp.workprec(QD_INPUT_BITS):
        x = mp.mpf(v) if v != 0 else mp.mpf(2) ** -7
        return x * (1 + mp.mpf(2 * k + 1) / 3 * mp.mpf(2) ** -60)


def qd_state(st: tuple) -> tuple:
    """The float state ``st`` with every component given a 200-bit tail (signs kept)."""
    p, q, l0, m = st
    N = len(p)
    return ([_tail(v, j) for j, v in enumerate(p)], [_tail(v, N + j) for j, v in enumerate(q)],
            _tail(l0, 2 * N), _tail(m, 2 * N + 1))


def qd_value(row: Any) -> Any:
    """The exact value of a quad-double (four doubles summed exactly)."""
    with mp.workprec(2400):
        return mp.fsum(mp.mpf(float(c)) for c in row)


def run_qd(st: tuple, b: int, n: int, every: int = 1) -> tuple[int, int, list]:
    """``qd_orbit`` (plain Python) of the mpf state ``st``: ``(status, step, final state as exact mpf)``; status
    ``-2`` if a completed orbit's first stored state is not the input itself (a row it must hold exactly)."""
    from ..numeric.float64.kernels import orbit_rows
    from ..numeric.multiprec.qd import to_qd
    from ..numeric.multiprec.qd_step import qd_orbit

    P0, Q0, spec = to_qd(st[0]), to_qd(st[1]), to_qd([st[2], st[3]])
    if P0 is None or Q0 is None or spec is None:
        return -1, 0, []
    N = len(st[0])
    rows = orbit_rows(n, every)
    outP, outQ = np.zeros((rows, N, 4)), np.zeros((rows, N, 4))
    code, step = qd_orbit(P0, Q0, spec, b, n, every, outP, outQ)
    first = [qd_value(outP[0, j]) for j in range(N)] + [qd_value(outQ[0, j]) for j in range(N)]
    if code == 0 and first != list(st[0]) + list(st[1]):
        return -2, 0, []            # the orbit's first stored state is not the input (exact: 200-bit inputs)
    last = rows - 1
    return (int(code), int(step),
            [qd_value(outP[last, j]) for j in range(N)] + [qd_value(outQ[last, j]) for j in range(N)])


@cache
def qd_wide_state(N: int, lo: float = 250.0, hi: float = 300.0) -> tuple | None:
    """A seeded state with a real map (both branches) whose largest neighbour distance lies in ``(lo, hi]``."""
    rng = np.random.default_rng(3000 + N)
    for _ in range(400):
        q = [0.0] + [float(v) for v in np.round(rng.uniform(0, hi, N - 1), 3)]
        dq = max(abs(q[(j + 1) % N] - q[j]) for j in range(N))
        if not lo < dq <= hi:
            continue
        p = tuple(float(v) for v in np.round(rng.uniform(-5, 5, N), 3))
        l0, m = float(np.round(rng.uniform(-50, 50), 3)), float(np.round(rng.uniform(5, 40), 3))
        st = (p, tuple(q), l0, m)
        with mp.workdps(40):
            t1, t2 = literal_trace(mp.mpf(l0) + m, p, q), literal_trace(mp.mpf(l0) - m, p, q)
        if not (abs(t1) > 2.2 and abs(t2) > 2.2 and t1 * t2 > 0):
            continue
        g = guard_digits(st)
        if all(all(isinstance(v, mp.mpf) for v in literal_state(st, b, 50 + g)[0]) for b in (1, -1)):
            return st
    return None


def _qd_accuracy(tally: Tally, cell: dict, st: tuple, b: int, n: int, scale: float) -> None:
    """One sample of ``paths.qd``: the quad-double orbit against the literal orbit of the same 200-bit input."""
    x = qd_state(st)
    g = guard_digits(st)
    ref = literal_orbit(x, b, n, QD_REF_DPS, g)[n]
    chk = literal_orbit(x, b, n, QD_CHECK_DPS, g + 25)[n]
    with mp.workdps(QD_REF_DPS):
        size = max(max(abs(v) for v in chk), 1)
        agree = float(max(abs(a - c) for a, c in zip(ref, chk)) / size)
    S = step_ref(st, b).S if n == 1 else orbit_ref(st, b, n).S
    code, step, vals = run_qd(x, b, n, every=2)
    if code != 0:
        tally.notes.append(f"quad-double status {code} at step {step} on a state with a real map.")
        tally.add("quad-double", cell, st, b, math.inf)
        return
    C = step_constant(len(st[0])) * n
    r, allowed = ratios(scaled(vals, scale), ref, S, 2.0 ** -QD_BITS, C)
    if allowed > QD_INFORMATIVE:
        tally.loose += 1
    tally.add("quad-double", cell, st, b, r, 0.0, agree, agree_tol=1e-70)


def _qd_statuses(N: int, parts: Parts) -> list[str]:
    """The quad-double step's decisions and conversions (empty: all as documented)."""
    from ..numeric.core.limits import MAX_DQ_QD, OK, POSITIVITY, RANGE, TRACE1, TRACE2
    from ..numeric.multiprec.qd import _decompose, qd_fits, to_qd
    from .shipped_emitted import nomap_states

    bad = []
    if MAX_DQ_QD != parts.printed["max_dq"]:
        bad.append(f"MAX_DQ_QD = {MAX_DQ_QD}, documented {parts.printed['max_dq']}")
    # beyond the limit: given back (RANGE) at the first step, before any arithmetic can overflow
    far = ((0.5,) + (0.25,) * (N - 1), (0.0, parts.printed["max_dq"] + 10.0) + (5.0,) * (N - 2), 3.0, 1.0)
    code, step, _ = run_qd(qd_state(far), 1, 1)
    if (code, step) != (RANGE, 1):
        bad.append(f"|dq| = {far[1][1]:g}: status {code} at step {step}, expected RANGE at step 1")
    for st, b, (cond, decided) in nomap_states(N):
        if not decided:
            continue
        code, step, _ = run_qd(tuple(_mpf_list(v) if isinstance(v, tuple) else mp.mpf(v) for v in st), b, 1)
        want = (POSITIVITY,) if cond in ("opposite signs", "E~ <= 0") else (TRACE1, TRACE2)
        if code not in want:
            bad.append(f"no real map ({cond}): quad-double status {code}")
    # to_qd: exact limbs (the sum is the value, sign included) and its documented refusals
    with mp.workprec(QD_INPUT_BITS):   # the last two: at the edges of the documented range 2**+-600
        vals = [mp.mpf(-3), -mp.pi, mp.mpf(2) ** -500 * mp.e, -mp.mpf(10) ** 150 * mp.sqrt(2), mp.mpf(0),
                mp.mpf(2) ** 590 / 3, mp.mpf(2) ** -601, -(mp.mpf(2) ** 599) * (1 + mp.mpf(2) ** -100)]
    limbs = to_qd(vals)
    if limbs is None or any(qd_value(row) != v for row, v in zip(limbs, vals)):
        bad.append("to_qd does not split 200-bit values (negative ones included) exactly")
    # from_qd's integer decomposition (plain Python here; numba compiles the same function): exact, also for
    # quad-doubles with fewer than four non-zero components
    ints = np.zeros((len(vals), 8), np.int64)
    if limbs is not None:
        _decompose(np.ascontiguousarray(limbs, dtype=np.float64), ints)
    for row, v in zip(ints.tolist(), vals):
        m0, m1, m2, m3, s1, s2, s3, e = row
        with mp.workprec(2400):
            if mp.ldexp(mp.mpf((((((m0 << s1) + m1) << s2) + m2) << s3) + m3), e) != v:
                bad.append(f"the decomposition of {mp.nstr(v, 5)} is not exact")
    with mp.workprec(260):
        refused = [+mp.pi, mp.mpf(2) ** 700, mp.mpf(2) ** -700, mp.inf, mp.mpf(2) ** 600, -mp.mpf(2) ** -602]
    for v in refused:
        if to_qd([v]) is not None:
            bad.append(f"to_qd accepted {mp.nstr(v, 5)} (documented: more than 212 bits or beyond 2**+-600)")
    # qd_fits: the documented rule prec + 16 + 2 bitlen(n) <= 209, on both sides of its boundary
    for n in (1, 3, 10, 1000, 10**6):
        edge = parts.printed["qd_bits"] - 16 - 2 * n.bit_length()      # the largest precision admitted
        for prec in (edge - 20, edge, edge + 1):
            rule = prec + 16 + 2 * n.bit_length() <= parts.printed["qd_bits"]
            if qd_fits(prec, n) != rule:
                bad.append(f"qd_fits({prec}, {n}) = {qd_fits(prec, n)}, the documented rule says {rule}")
    # backend="auto" on mpf input takes the quad-double path exactly where qd_fits(prec, steps) (a stand-in
    # row, available and ready, that records its calls and answers with the mpmath row's result)
    from dataclasses import replace

    from ..numeric import backends as BK
    from ..numeric import bt_orbit, bt_step

    taken: list[str] = []
    qd_row, mp_row = BK.BACKENDS["qd"], BK.BACKENDS["mpmath"]

    def record_step(pr: Any, allow_complex: bool) -> Any:
        taken.append("step")
        return mp_row.step(pr, allow_complex)

    def record_orbit(pr: Any) -> Any:
        taken.append("orbit")
        return mp_row.orbit(pr)
    BK.BACKENDS["qd"] = replace(qd_row, available=lambda: True, ready=lambda: True, step=record_step,
                                   orbit=record_orbit)
    try:
        for steps in (1, 3):
            edge = parts.printed["qd_bits"] - 16 - 2 * steps.bit_length()
            for prec in (edge, edge + 1):
                taken.clear()
                with mp.workprec(prec):
                    st = ([mp.mpf(-20), mp.mpf(10)] + [mp.mpf(1)] * (N - 2), [mp.mpf(1)] + [mp.mpf(0)] * (N - 1))
                    if steps == 1:
                        bt_step(*st, mp.mpf(10), mp.mpf(5))
                    else:
                        bt_orbit(*st, mp.mpf(10), mp.mpf(5), steps)
                if bool(taken) != (prec == edge):
                    bad.append(f"auto, {steps} step(s) at {prec} bits: quad-double taken {bool(taken)}, qd_fits "
                               f"says {prec == edge}")
    finally:
        BK.BACKENDS["qd"] = qd_row
    # qd_orbit_mp refuses an input beyond 2**600 with NumericRangeError before any kernel runs (so with and
    # without numba alike; without_numba: the default verify compiles nothing)
    from ..numeric import NumericRangeError
    from ..numeric.multiprec.qd import qd_orbit_mp

    with mp.workprec(150), without_numba():
        big = [mp.mpf(-20), mp.mpf(2) ** 601] + [mp.mpf(1)] * (N - 2)
        try:
            qd_orbit_mp(big, [mp.mpf(0)] * N, mp.mpf(10), mp.mpf(5), 2)
            bad.append("qd_orbit_mp accepted an input of 2**601")
        except NumericRangeError:
            pass
        except Exception as exc:  # any other error: not the documented refusal
            bad.append(f"qd_orbit_mp raised {type(exc).__name__} on an input of 2**601, not NumericRangeError")
    if OK != 0:
        bad.append("status OK is not 0")
    return bad


@claim("paths.qd", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(2, 3),
       parts=qd_parts,
       where="symbt/numeric/multiprec/qd.py (to_qd, qd_fits), qd_step.py, qd_arith.py",
       statement="the quad-double step (plain Python, the functions numba compiles) on 200-bit inputs, one step "
                 "(three at the wide state) = the literal orbit (80 digits) within 16 N n 2^-209 S_i in every "
                 "branch x sign(mu) x sign(tr) "
                 "cell and at a neighbour distance in (250, 300]; beyond 300 it gives the state back (RANGE), "
                 "without a real map it says so; to_qd splits exactly; qd_fits follows its rule and backend='auto' "
                 "takes the quad-double path (when ready) exactly where it admits the steps; qd_orbit_mp "
                 "refuses an input of 2^601 (NumericRangeError) (N={N})")
def qd_paths(N: int, parts: Parts) -> Outcome:
    tally = Tally()
    samples = list(ship_cells(N, 1))
    wide = qd_wide_state(N)
    if wide is not None:
        samples += [({"branch": b, "sign_mu": 1, "sign_tr": 0, "q": "wide"}, wide, b) for b in (1, -1)]
    else:
        tally.notes.append("no seeded state with a neighbour distance in (250, 300] was found.")
        tally.loose += 1
    for cell, st, b in samples:   # one step per cell; the wide state for QD_WIDE_STEPS (stored every 2nd)
        _qd_accuracy(tally, cell, st, b, QD_WIDE_STEPS if cell.get("q") == "wide" else 1, parts.printed["scale"])
    bad = _qd_statuses(N, parts)
    out = tally.outcome(method=f"numeric: quad-double orbit vs the literal orbit ({QD_REF_DPS} digits), bound "
                               f"16 N n 2^-{QD_BITS} S", printed=f"|qd - literal| <= 16 N n 2^-{QD_BITS} S_i")
    if bad:
        return failed(out.method or "", detail="; ".join(bad[:6]) + ". " + (out.detail or ""))
    return out
