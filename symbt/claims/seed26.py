r"""What the sample of seed 26 found unread (issue 21).

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
* ``library.emit_range`` -- a typed declaration of a user's expression with a ``range`` guard,
  ``grow(x) = e^x`` guarded by ``Guard("range", ..., e^x)`` on ``x`` in ``[600, 800]``: the numpy flavour
  returns ``e^700`` within ``2 eps`` relative of mpmath's ``exp`` and refuses ``x = 720`` (``e^720`` is beyond
  the float64 range) with its module's ``NumericRangeError``, whose message names no cause of the Toda lattice;
  the mpmath flavour returns ``e^720`` within ``1e-45``; and :func:`symbt.codegen.user.check.compare` of the
  numpy flavour counts refusals by ``range`` beside compared points, of the mpmath flavour compared points only
  (seed 26: no claim reached the ``range`` guard's test in ``compare``, uncovered).

Shown to fail on planted bugs in ``tests/test_killers_seed26.py``.

>>> emit_range().status
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


@claim("library.emit_range", equation="checker", scene="library",
       where="symbt.codegen.user (a typed declaration's range guard: check._expected, the runtime's _finish)",
       statement="grow(x) = e^x with a range guard, x in [600, 800]: numpy returns e^700 within 2 eps of mpmath's "
                 "exp and refuses x = 720 with NumericRangeError naming no Toda cause; mpmath returns e^720 within "
                 "1e-45; compare counts range refusals and compared points for numpy, compared points only for "
                 "mpmath")
def emit_range() -> Outcome:
    from ..codegen.user.check import Comparison, compare, load_python
    from ..codegen.user.declare import emit
    from ..codegen.user.files import generate
    from ..codegen.user.typed import Guard
    from ..proof import Domain

    x = sp.Symbol("x", real=True)
    e = emit("grow", {"v": sp.exp(x)}, args=(x,), module=RANGE_MODULE, guards=[Guard("range", "e^x", sp.exp(x))],
             domain=Domain({"x": RANGE_DOMAIN}, seed=26), register=False)
    bad: list[str] = []
    counts: dict[str, Any] = {}
    with tempfile.TemporaryDirectory(prefix="symbt-range-control-") as tmp:
        out = Path(tmp)
        generate([e], out, out)
        mod = load_python(out / f"{RANGE_MODULE}.py")
        with mp.workdps(30):
            got = mp.mpf(float(mod.grow(RANGE_IN)))
            if not abs(got / mp.exp(RANGE_IN) - 1) <= 2 * EPS:
                bad.append(f"grow({RANGE_IN}) = {mp.nstr(got, 17)}, e^{RANGE_IN:g} = {mp.nstr(mp.exp(RANGE_IN), 17)}")
        try:
            v = mod.grow(RANGE_OUT)
            bad.append(f"grow({RANGE_OUT}) returned {v} (e^{RANGE_OUT:g} is beyond the float64 range)")
        except mod.NumericRangeError as exc:
            if "q_i" in str(exc) or "eigenvector" in str(exc):
                bad.append(f"the range refusal names a cause of the Toda lattice: {exc}")
        with mp.workdps(50):
            if not abs(mod.grow_mp(RANGE_OUT) / mp.exp(RANGE_OUT) - 1) <= mp.mpf("1e-45"):
                bad.append(f"grow_mp({RANGE_OUT}) is not e^{RANGE_OUT:g} to 45 digits")
        for fl in ("numpy", "mpmath"):
            seen = Comparison()
            table = compare(e, out / f"{RANGE_MODULE}.py", fl, per_cell=3, seen=seen)
            counts[fl] = (seen.refused, seen.compared, dict(seen.conditions))
            want = seen.refused > 0 and set(seen.conditions) == {"range"} if fl == "numpy" else seen.refused == 0
            if not (table.printed_holds_everywhere() and seen.compared and want):
                bad.append(f"compare({fl}): holds {table.printed_holds_everywhere()}, refused {seen.refused} "
                           f"{seen.conditions}, compared {seen.compared}")
    detail = "; ".join(f"compare({fl}): {r} refused, {c} compared" for fl, (r, c, _) in counts.items())
    if bad:
        return failed("numeric: a range guard's emitted code vs mpmath's exp", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: a range guard's emitted code vs mpmath's exp; compare's refusals",
                   evidence="sampled", n_scope="all", detail=detail)
