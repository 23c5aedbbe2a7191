r"""What the samples of seeds 26 and 27 found unread (issue 21).

* ``library.forced_backend`` -- a backend named by the caller is the one that runs: its own refusal stands, where
  ``backend="auto"`` goes on to the next backend of the table.  A state with a coordinate of ``1e-200`` (an
  exponent below the quad-double's ``2**-600``): :func:`symbt.numeric.bt_step` and
  :func:`~symbt.numeric.bt_orbit` (3 steps) with ``backend="qd"`` raise
  :class:`~symbt.numeric.NumericRangeError` (or, without numba, :class:`~symbt.numeric.MissingDependencyError`:
  the documented refusal of a forced backend that is not installed) -- never a result from another backend --
  and with ``backend="auto"`` they return the step and the orbit, within ``1e-25`` of the literal map at 40
  digits (:mod:`symbt.reference.literal`, the same mpf inputs; computed at 30 digits).  Seed 26: the ``forced``
  flag inverted, so that a forced ``qd`` fell back to Arb.  No kernel is compiled: the quad-double route refuses
  while converting its inputs.
* ``library.emit_range`` -- typed declarations of a user's expressions with a ``range`` guard on ``x`` in
  ``[600, 800]``: ``grow(x) = e^x`` guarded by ``e^x``, and ``logistic(x) = 1/(1 + e^x)`` guarded by ``-e^x`` (a
  guard's value of either sign: only its size is tested).  The numpy flavour returns the value at ``x = 700``
  within ``2 eps`` relative of mpmath's and refuses ``x = 720`` (``e^720`` is beyond the float64 range) with its
  module's ``NumericRangeError``, whose message names no cause of the Toda lattice; the mpmath flavour returns the
  value at 720 within ``1e-45``; and :func:`symbt.codegen.user.check.compare` of the numpy flavour counts refusals
  by ``range`` beside compared points, of the mpmath flavour compared points only (seed 26: no claim reached the
  ``range`` guard's test in ``compare``, uncovered; seed 27: the test without the modulus, which only a negative
  guard value tells).

Seed 27:

* ``library.deep_band`` -- a spectral parameter ``2**-300`` inside a band, decided by interval arithmetic only past
  256 bits: the free chain ``p = q = (0, 0)`` (N = 2: ``tr L(lam) = lam^2 - 2``, the closed form) at ``lam0 =
  2**-150``, ``mu = 2**-151``, where ``tr L(lam1) + 2 = (3/2)^2 2**-300`` exactly (mpmath at 400 digits).  float64
  ``bt_step`` (numpy and python routes; one state and a batch of three) raises
  :class:`~symbt.numeric.NoRealMapError` with ``condition == "trace"``, never a range error; and
  :func:`~symbt.numeric.float64.existence.decide_existence` says so (``TRACE1``) at 512 bits, with and without a
  deadline (seed 27: the batch's deadline taken as already passed, so the doubling stopped at 256 bits and the
  step raised :class:`~symbt.numeric.NumericRangeError`).
* ``library.degenerate_step`` -- the step at a degenerate eigenvector (``p = (-3, 0)``, ``q = (0, 1)``, ``lam0 =
  mu = 1``: ``lam2 = 0`` and ``p_2 = 0``, so a slope of the backward transport is infinite while the map is smooth)
  against its limit by the literal map, ``(T(mu + d) + T(mu - d))/2`` with ``d = 10**-35`` at 125 digits (error
  ``O(d^2)``): the Arb and mpmath backends at 50 digits within ``1e-49``, float64 within ``1e-14`` (seed 27: the
  Arb step's retry with projective division skipped).

Shown to fail on planted bugs in ``tests/test_killers_seed26.py``.

>>> emit_range.run().status
'verified'
"""
from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np
import sympy as sp

from ._shipped import without_numba
from .base import Outcome, claim, failed

#: library.forced_backend: the paper's state with one coordinate outside the quad-double range; digits, steps
FORCED_P, FORCED_Q, FORCED_LAM0, FORCED_MU = ("-20", "10", "1"), ("1", "1e-200", "0.9"), 10, 5
FORCED_DPS, FORCED_REF_DPS, FORCED_STEPS, FORCED_TOL = 30, 40, 3, mp.mpf("1e-25")


@claim("library.forced_backend", equation="bt_orbit", source_equation="imptransf", scene="library", N=3,
       where="symbt.numeric.dispatch (bt_step, bt_orbit: forced=backend != 'auto') and backends.run_step/run_orbit",
       statement="at a state with q_2 = 1e-200 (outside the quad-double range) bt_step and bt_orbit (3 steps) with "
                 "backend='qd' raise NumericRangeError (MissingDependencyError without numba), never another "
                 "backend's result; with backend='auto' they return the step and the orbit within 1e-25 of the "
                 "literal map at 40 digits (30-digit inputs)")
def forced_backend() -> Outcome:
    from ..numeric import MissingDependencyError, NumericRangeError, bt_orbit, bt_step
    from ..reference.literal import literal_step

    bad: list[str] = []
    refusals = []
    with mp.workdps(FORCED_DPS):
        P, Q = [mp.mpf(v) for v in FORCED_P], [mp.mpf(v) for v in FORCED_Q]
        for name, call in (("bt_step", lambda: bt_step(P, Q, FORCED_LAM0, FORCED_MU, backend="qd")),
                           ("bt_orbit", lambda: bt_orbit(P, Q, FORCED_LAM0, FORCED_MU, FORCED_STEPS, backend="qd"))):
            try:
                call()
                bad.append(f"{name}(backend='qd') returned a result (another backend's)")
            except (NumericRangeError, MissingDependencyError) as exc:
                refusals.append(type(exc).__name__)
        with without_numba():       # auto: the table's first mpmath backend that is ready
            step = bt_step(P, Q, FORCED_LAM0, FORCED_MU)
            orbit = bt_orbit(P, Q, FORCED_LAM0, FORCED_MU, FORCED_STEPS)
    with mp.workdps(FORCED_REF_DPS):
        ref, x, y = [], list(P), list(Q)
        for _ in range(FORCED_STEPS):
            x, y, _ = literal_step(x, y, FORCED_LAM0, FORCED_MU, 1)
            ref.append(x + y)
        # the step, and the orbit's stored states after the initial one, against the literal map's
        pairs = [(step[0] + step[1], ref[0])] + [(orbit[0][k + 1] + orbit[1][k + 1], ref[k])
                                                 for k in range(FORCED_STEPS)]
        worst = max(abs(a - b) / max(1, abs(b)) for got, want in pairs for a, b in zip(got, want))
    if not worst <= FORCED_TOL:
        bad.append(f"auto: {mp.nstr(worst, 3)} from the literal map (accepted {mp.nstr(FORCED_TOL, 2)})")
    detail = f"forced qd: {', '.join(refusals)}; auto within {mp.nstr(worst, 2)} of the literal map"
    if bad:
        return failed("numeric: forced and auto backends vs the literal map", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: forced qd refuses; auto vs the literal map (mpmath, 40 digits)",
                   evidence="sampled", n_scope=[3], residual=float(worst), detail=detail)


#: library.emit_range: the module name of the control emission, its domain, the points read by hand
RANGE_MODULE, RANGE_DOMAIN, RANGE_IN, RANGE_OUT = "symbt_range_control", (600, 800), 700.0, 720.0
EPS = float(np.finfo(np.float64).eps)


def _range_declarations() -> list[tuple[Any, Any, Any]]:
    """``(emission, numpy flavour's name, the value by hand)``: ``grow = e^x`` guarded by ``e^x``, and ``logistic =
    1/(1 + e^x)`` guarded by ``-e^x`` (a guard's value of either sign: only its size is tested)."""
    from ..codegen.user.declare import emit
    from ..codegen.user.typed import Guard
    from ..proof import Domain

    x = sp.Symbol("x", real=True)
    dom = Domain({"x": RANGE_DOMAIN}, seed=26)
    return [(emit("grow", {"v": sp.exp(x)}, args=(x,), module=RANGE_MODULE, guards=[Guard("range", "e^x", sp.exp(x))],
                  domain=dom, register=False), "grow", mp.exp),
            (emit("logistic", {"v": 1 / (1 + sp.exp(x))}, args=(x,), module=RANGE_MODULE,
                  guards=[Guard("range", "-e^x", -sp.exp(x))], domain=dom, register=False), "logistic",
             lambda t: 1 / (1 + mp.exp(t)))]


@claim("library.emit_range", equation="checker", scene="library",
       where="symbt.codegen.user (a typed declaration's range guard: check._expected, the runtime's _finish)",
       statement="grow(x) = e^x guarded by e^x and logistic(x) = 1/(1 + e^x) guarded by -e^x, x in [600, 800]: numpy "
                 "returns the value at 700 within 2 eps of mpmath's and refuses x = 720 with NumericRangeError naming "
                 "no Toda cause; mpmath returns the value at 720 within 1e-45; compare counts range refusals and "
                 "compared points for numpy, compared points only for mpmath")
def emit_range() -> Outcome:
    from ..codegen.user.check import Comparison, compare, load_python
    from ..codegen.user.files import generate

    decls = _range_declarations()
    bad: list[str] = []
    counts: dict[str, Any] = {}
    with tempfile.TemporaryDirectory(prefix="symbt-range-control-") as tmp:
        out = Path(tmp)
        generate([e for e, _, _ in decls], out, out)
        mod = load_python(out / f"{RANGE_MODULE}.py")
        for e, name, exact in decls:
            f, f_mp = getattr(mod, name), getattr(mod, name + "_mp")
            with mp.workdps(30):
                got, want = mp.mpf(float(f(RANGE_IN))), exact(mp.mpf(RANGE_IN))
                if not abs(got / want - 1) <= 2 * EPS:
                    bad.append(f"{name}({RANGE_IN}) = {mp.nstr(got, 17)}, by mpmath {mp.nstr(want, 17)}")
            try:
                v = f(RANGE_OUT)
                bad.append(f"{name}({RANGE_OUT}) returned {v} (e^{RANGE_OUT:g} is beyond the float64 range)")
            except mod.NumericRangeError as exc:
                if "q_i" in str(exc) or "eigenvector" in str(exc):
                    bad.append(f"{name}: the range refusal names a cause of the Toda lattice: {exc}")
            with mp.workdps(50):
                if not abs(f_mp(RANGE_OUT) / exact(mp.mpf(RANGE_OUT)) - 1) <= mp.mpf("1e-45"):
                    bad.append(f"{name}_mp({RANGE_OUT}) differs from mpmath's value at 45 digits")
            for fl in ("numpy", "mpmath"):
                seen = Comparison()
                table = compare(e, out / f"{RANGE_MODULE}.py", fl, per_cell=3, seen=seen)
                counts[f"{name}, {fl}"] = (seen.refused, seen.compared)
                want_seen = seen.refused > 0 and set(seen.conditions) == {"range"} if fl == "numpy" else \
                    seen.refused == 0
                if not (table.printed_holds_everywhere() and seen.compared and want_seen):
                    bad.append(f"compare({name}, {fl}): holds {table.printed_holds_everywhere()}, refused "
                               f"{seen.refused} {seen.conditions}, compared {seen.compared}")
    detail = "; ".join(f"compare({k}): {r} refused, {c} compared" for k, (r, c) in counts.items())
    if bad:
        return failed("numeric: range guards' emitted code vs mpmath", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: range guards' emitted code vs mpmath; compare's refusals",
                   evidence="sampled", n_scope="all", detail=detail)


#: library.deep_band: the free chain N = 2 and spectral parameters 2**-300 inside its band (tr = lam^2 - 2)
BAND_LAM0, BAND_MU = 2.0 ** -150, 2.0 ** -151


@claim("library.deep_band", equation="bt_step", source_equation="imptransf", scene="library", N=2,
       where="symbt.numeric.float64.existence.decide_existence (the batch deadline) via rows.escalate_rows",
       statement="p = q = (0, 0), lam0 = 2^-150, mu = 2^-151 (tr L(lam1) + 2 = (9/4) 2^-300 exactly): float64 bt_step "
                 "(numpy and python, one state and a batch) raises NoRealMapError with condition 'trace'; "
                 "decide_existence says TRACE1 at 512 bits, with and without a deadline")
def deep_band() -> Outcome:
    import time

    from ..numeric import NoRealMapError, bt_step
    from ..numeric.core.limits import TRACE1
    from ..numeric.float64.existence import decide_existence

    bad: list[str] = []
    with mp.workdps(400):               # the premise, by the closed form tr = lam^2 - 2 of the free chain
        lam1 = mp.mpf(BAND_LAM0) + mp.mpf(BAND_MU)
        if not (lam1 ** 2 == mp.mpf(9) / 4 * mp.mpf(2) ** -300 and abs(lam1 ** 2 - 2) < 2):
            bad.append("premise: tr L(lam1) + 2 is not (9/4) 2^-300")
    zero = np.zeros(2)
    for dl in (None, time.monotonic() + 60):
        got = decide_existence(zero, zero, BAND_LAM0, BAND_MU, 1, deadline=dl)
        if got != (TRACE1, 512):
            bad.append(f"decide_existence (deadline {'none' if dl is None else 'in 60 s'}): {got}, want "
                       f"({TRACE1}, 512)")
    seen = []
    with without_numba():
        for backend in ("numpy", "python"):
            for shape in ((2,), (3, 2)):
                try:
                    bt_step(np.zeros(shape), np.zeros(shape), BAND_LAM0, BAND_MU, backend=backend)
                    bad.append(f"{backend}, shape {shape}: a state returned")
                except NoRealMapError as exc:
                    seen.append(exc.condition)
                    if exc.condition != "trace":
                        bad.append(f"{backend}, shape {shape}: NoRealMapError({exc.condition!r})")
                except ArithmeticError as exc:
                    bad.append(f"{backend}, shape {shape}: {type(exc).__name__}: {exc}")
    if bad:
        return failed("interval arithmetic vs the closed form of the free chain's trace", detail="; ".join(bad))
    return Outcome("verified", "interval arithmetic vs the closed form of the free chain's trace (400 digits)",
                   evidence="proof", n_scope=[2],
                   detail=f"TRACE1 at 512 bits with and without a deadline; bt_step refused {len(seen)} times (trace)")


#: library.degenerate_step: the state (lam2 = 0, p_2 = 0: an infinite slope), the digits, the limit's half-width
DEG_P, DEG_Q, DEG_LAM0, DEG_MU = (-3, 0), (0, 1), 1, 1
DEG_DPS, DEG_E = 50, 35


@claim("library.degenerate_step", equation="bt_step", source_equation="imptransf", scene="library", N=2,
       where="symbt.numeric.multiprec.runners._safe_step (projective division), the mpmath and float64 steps",
       statement="at p = (-3, 0), q = (0, 1), lam0 = mu = 1 (a degenerate eigenvector: an infinite slope) the Arb and "
                 "mpmath steps at 50 digits are within 1e-49 of the limit (T(mu + d) + T(mu - d))/2, d = 1e-35, "
                 "of the literal map at 125 digits, float64 within 1e-14")
def degenerate_step() -> Outcome:
    from ..numeric import MissingDependencyError, bt_step
    from ..reference.literal import reference_step

    with mp.workdps(DEG_DPS + DEG_E + 40):
        d = mp.mpf(10) ** -DEG_E
        a = reference_step(DEG_P, DEG_Q, DEG_LAM0, DEG_MU + d)
        b = reference_step(DEG_P, DEG_Q, DEG_LAM0, DEG_MU - d)
        limit = [(x + y) / 2 for x, y in zip(a[0] + a[1], b[0] + b[1])]
    bad: list[str] = []
    worst: dict[str, Any] = {}
    with mp.workdps(DEG_DPS):
        for backend in ("flint", "mpmath"):
            try:
                pt, qt = bt_step([mp.mpf(v) for v in DEG_P], list(DEG_Q), DEG_LAM0, DEG_MU, backend=backend)
            except MissingDependencyError:
                worst[backend] = "not installed"
                continue
            worst[backend] = max(abs(x - y) for x, y in zip(pt + qt, limit))
            if not worst[backend] <= mp.mpf(10) ** (1 - DEG_DPS):
                bad.append(f"{backend}: {mp.nstr(worst[backend], 3)} from the limit")
    with without_numba():
        pt, qt = bt_step(np.array(DEG_P, float), np.array(DEG_Q, float), DEG_LAM0, DEG_MU)
    worst["float64"] = float(np.max(np.abs(np.r_[pt, qt] - np.array([float(v) for v in limit]))))
    if not worst["float64"] <= 1e-14:
        bad.append(f"float64: {worst['float64']:.3g} from the limit")
    detail = ", ".join(f"{k} {v if isinstance(v, str) else mp.nstr(mp.mpf(v), 2)}" for k, v in worst.items())
    if bad:
        return failed("numeric: the steps vs the literal map's symmetric limit", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: the steps vs the literal map's symmetric limit (125 digits)",
                   evidence="sampled", n_scope=[2], detail=detail)
