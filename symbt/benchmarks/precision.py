"""High precision: the mpmath BT orbit vs Taylor integrators of the same flow, at 50 and 100 digits.

The paper's example (mu = 5), ``n = 10`` steps (horizon ``t = 10``).  Reference: the BT at
``2 digits + 20`` digits.  Contenders at ``digits``: ``bt_orbit`` on mpf input (its ``auto`` backend: the quad-double
orbit where the precision fits, compiled before the timing and reported apart, else Arb); heyoka's
``taylor_adaptive`` with ``fp_type = heyoka.real`` (tolerance ``10**-digits``, ``c_k`` at
``digits + 15`` digits); at 50 digits also symbt's own adaptive Taylor integrator
(:func:`symbt.reference.taylor.hamiltonian_flow`, exact jets by Cauchy products; not with
``--quick``).  Errors: the normwise relative state error of :mod:`symbt.benchmarks.metrics`.
"""
from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import mpmath

from ..numeric import bt_orbit, flow_coefficients
from ..paper import EXAMPLE
from .metrics import mp_state_error
from .reference import reference_states
from .timing import timed

__all__ = ["run_precision"]


def run_precision(quick: bool = False, log: Callable[[str], None] = print, hy: Any = None,
                  digits_list: tuple = (50, 100), n: int = 10) -> dict:
    """``{"50": {...}, "100": {...}}`` with the BT, heyoka.real and (50 digits) Taylor rows."""
    p0, q0 = list(EXAMPLE["p"]), list(EXAMPLE["q"])
    lam0, mu = EXAMPLE["lam0"], EXAMPLE["mu"][0]
    out: dict = {"case": "paper-mu5", "steps": n}
    from ..numeric.backends import pick
    from ..numeric.multiprec.qd import qd_available, warm

    if qd_available():          # compiled (or loaded) apart, like heyoka's JIT: bt_orbit's auto then uses it
        out["qd_compile_s"] = warm()
        log("  quad-double orbit compiled/loaded in %.1f s (apart)" % out["qd_compile_s"])
    for digits in digits_list:
        row: dict = {"digits": digits}
        ref = reference_states(p0, q0, lam0, mu, n, 2 * digits + 20)
        with mpmath.workdps(digits):
            P0 = [mpmath.mpf(v) for v in p0]
            Q0 = [mpmath.mpf(v) for v in q0]
            (bp, bq), tbt, reps = timed(lambda: bt_orbit(P0, Q0, mpmath.mpf(lam0), mpmath.mpf(mu), n), None, quick)
            row["bt"] = {"time_s": tbt, "repeats": reps, "err": mp_state_error(bp[-1] + bq[-1], ref),
                         "backend": pick("auto", "mpmath", n).name}
        log("  %d digits, %d steps: BT (%s) %.3e s, err %.1e" % (digits, n, row["bt"]["backend"], tbt,
                                                                 row["bt"]["err"]))
        if hy is not None:
            from .heyoka_peer import high_precision
            try:
                row["heyoka"] = high_precision(hy, p0, q0, lam0, mu, n, digits, tbt, ref, quick)
                h = row["heyoka"]
                log("  %d digits: heyoka.real (%d bits, order %d) %.3e s (JIT %.2f s), err %.1e: %.3gx the BT" % (
                    digits, h["prec_bits"], h["order"], h["time_s"], h["jit_s"], h["err"], h["ratio"]))
            except Exception as exc:            # a broken heyoka.real build must not end the run
                row["heyoka"] = {"failed": repr(exc)}
                log("  heyoka.real failed: %r" % (exc,))
        if digits == 50 and not quick:
            from ..reference.taylor import hamiltonian_flow
            with mpmath.workdps(digits):
                with mpmath.workdps(digits + 20):
                    c = flow_coefficients([mpmath.mpf(v) for v in p0], [mpmath.mpf(v) for v in q0],
                                          mpmath.mpf(lam0), mpmath.mpf(mu), check=False)
                c = [+v for v in c]
                t0 = time.perf_counter()
                res = hamiltonian_flow([mpmath.mpf(v) for v in p0], [mpmath.mpf(v) for v in q0], c + [0], n)
                tt = time.perf_counter() - t0
            row["symbt_taylor"] = {"time_s": tt, "repeats": 1, "err": mp_state_error(list(res[0]) + list(res[1]), ref),
                                   "steps": res.steps, "order": res.order, "ratio": tt / tbt}
            log("  50 digits: symbt Taylor (hamiltonian_flow) %.3e s, err %.1e, %d steps of order %d" % (
                tt, row["symbt_taylor"]["err"], res.steps, res.order))
        out[str(digits)] = row
    return out
