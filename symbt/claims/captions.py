r"""The constants printed in the captions of Figs. 1-2 (the paper's N = 3 example, eq. ``eqdisc``).

The parts are the printed numbers; the number of printed decimals d of each (context, from
the paper's digits) says what a printed constant asserts: :math:`|c_{\rm printed} - c_k| \le
\tfrac12 10^{-d}`, with :math:`c_k` of eq. ``eqdisc`` (branch :math:`\gamma=+\sqrt{\cdot}`) at 30
digits.  That is all the check can honestly decide: a change of a printed constant smaller than
the half unit of its last printed decimal (e.g. a relative 1e-6 of a 1-4 digit constant)
asserts the same and cannot be refuted by any computation.
"""
from __future__ import annotations

from typing import Any

import mpmath as mp

from ..paper import CAPTIONS, EXAMPLE
from ..reference.samples import paper_state
from ..reference.spectral import flow_coefficients_mp
from .base import Outcome, Parts, claim

__all__ = ["caption_constants"]

#: the captions' constants rounded correctly to the printed decimals (the correction)
CORRECTED = {"5": ("-0.005", "-0.049", "-0.512"), "2": ("-0.0018", "-0.0183", "-0.1849")}


def caption_constants(mu: str, dps: int = 30) -> list:
    """Our c_0, c_1, c_2 (branch +1) for the paper's example at lam0 = 10 and the given mu."""
    with mp.workdps(dps):
        p, q, l0, m = paper_state(mu)
        return flow_coefficients_mp(p, q, l0, m, 1)[:3]


def _decimals(s: str) -> int:
    return len(s.split(".")[1]) if "." in s else 0


def _parts(label: str) -> Parts:
    printed = CAPTIONS[label]
    return Parts(printed={f"mu={m}": tuple(float(v) for v in vals) for m, vals in printed.items()},
                 corrected={f"mu={m}": tuple(float(v) for v in CORRECTED[m]) for m in printed},
                 context={"decimals": {f"mu={m}": tuple(_decimals(v) for v in vals) for m, vals in printed.items()}})


def _compare(side: dict, decimals: dict) -> tuple[float, list, dict]:
    """Worst |printed - ours|, the lines of the detail, and the entries off by more than half a unit."""
    worst, lines, wrong = 0.0, [], {}
    for name, values in side.items():
        ours = caption_constants(name.split("=")[1])
        for j, (v, c, d) in enumerate(zip(values, ours, decimals[name])):
            diff = abs(mp.mpf(v) - c)
            worst = max(worst, float(diff))
            ok = diff <= mp.mpf(10) ** -d / 2
            lines.append(f"{name} c_{j}: {v} vs {mp.nstr(c, 12)}" + ("" if ok else " (off by more than half a unit)"))
            if not ok:
                wrong[f"{name} c_{j}"] = f"{v}, value {mp.nstr(c, 12)}"
    return worst, lines, wrong


def _check(label: str, parts: Parts) -> Outcome:
    dec = parts.context["decimals"]
    method = "numeric: mpmath 30 digits (tanh-sinh quadrature of eq. eqdisc); a printed constant with d decimals " \
             "asserts |printed - c_k| <= 10^-d/2"
    worst, lines, wrong = _compare(parts.printed, dec)
    printed = "; ".join(f"{n}: (c_0, c_1, c_2) = {v}" for n, v in parts.printed.items())
    base: dict[str, Any] = dict(residual=worst, printed=printed, evidence="sampled", n_scope=[3])
    index = " Index check: c_1/c_0 and c_2/c_1 are about lam0 = 10, so the printed c_k multiply H_k = [lam^k] tr L" \
            " (eq. eqdisc's lam^k), branch gamma = +sqrt (all negative)."
    if not wrong:
        return Outcome("verified", method, detail="; ".join(lines) + "." + index, **base)
    worst_c, lines_c, wrong_c = _compare(parts.corrected, dec)
    with mp.workdps(30):
        truncated = all(abs(mp.mpf(v.split(",")[0])) < abs(mp.mpf(v.split("value ")[1])) for v in wrong.values())
    corrected = "; ".join(f"{n}: (c_0, c_1, c_2) = {v}" for n, v in parts.corrected.items())
    return Outcome("erratum" if not wrong_c else "failed", method, digits=None, corrected=corrected,
                   counterexample=wrong,
                   detail="; ".join(lines) + "." + index + (" The printed digits are the value truncated, not rounded."
                                                            if truncated else "")
                   + ("" if not wrong_c else " Correction also off: " + "; ".join(lines_c)), **base)


_where = f"p = {EXAMPLE['p']}, q = {EXAMPLE['q']}, lam0 = {EXAMPLE['lam0']}"


@claim("caption.fig:1", equation="fig:1", scene="theorem2", N=3, parts=lambda: _parts("fig:1"),
       statement=f"the caption of Fig. 1: for {_where}, mu = 5: (c_0, c_1, c_2) = (-0.005, -0.048, -0.512) "
                 "(c_k of eq. eqdisc, the coefficient of H_k = [lam^k] tr L, each to its printed decimals)")
def caption_fig1(parts: Parts) -> Outcome:
    return _check("fig:1", parts)


@claim("caption.fig:2", equation="fig:2", scene="theorem2", N=3, parts=lambda: _parts("fig:2"),
       statement=f"the caption of Fig. 2: for {_where}, mu = 5: (c_0, c_1, c_2) = (-0.005, -0.048, -0.512); "
                 "mu = 2: (-0.0018, -0.0183, -0.1849) (c_k of eq. eqdisc, each to its printed decimals)")
def caption_fig2(parts: Parts) -> Outcome:
    return _check("fig:2", parts)
