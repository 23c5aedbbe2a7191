r"""The independent routes checked, 4: documented rules of :mod:`symbt.reference` and :mod:`symbt.symbolic` no
claim observed (scene ``library``; the survivors of seed 3's sample of ``symbt mutate --source``, docs/mutation.md).

* ``library.model_symbols`` -- :class:`symbt.symbolic.toda.TodaModel`'s ``p_j``, ``q_j`` and ``lambda`` are real and
  its ``E_j = e^{q_j}`` positive, as SymPy infers from the symbols (``conjugate(x) = x``, ``|E_j| = E_j``), so a
  state given by name (``Symbol('p1', real=True)``) is the model's; and
  :func:`~symbt.symbolic.rewriting.rationalize_exponentials` given no mapping makes a *positive* symbol for each
  ``exp(s)`` and rewrites ``exp(q_1 - 2 q_2) + 2 cosh(q_1 - q_2)`` to the Laurent monomials it stands for (decided
  by ``cancel``).
* ``library.addition`` -- :func:`symbt.reference.elliptic.addition_residual` (the corrected addition formula's
  residual) is at most ``10^(12 - dps)`` at a step of :func:`~symbt.reference.elliptic.step2`, and moving
  ``P~ = (p~_2 - p~_1)/(2 sqrt(I_2 - 2))`` by ``delta = +-10^-6`` (``E~`` kept) makes it
  ``|delta| / max(1, |P~ + delta|)`` within twice the unperturbed residual (its first term: ``sn`` is unchanged,
  the other two do not read ``p~``); :func:`~symbt.reference.elliptic.printed_addform_residual` equals
  ``|F(P~) - F(P) - F(s_-) + F(s_+)|`` with ``F(z) = z R_F(1 - z^2, 1 - k^2 z^2, 1)`` by mpmath's ``elliprf``
  (Carlson's form, not the Legendre ``ellipf`` the library calls), ``I_1, I_2`` and ``k`` from the literal trace,
  within ``10^(5 - dps)``, on an inner-regime case (every argument in ``[-1, 1]``), both branches.
* ``library.state_ranges`` -- :func:`symbt.reference.elliptic.sample_state` draws on the level sets its docstring
  states: ``I_1`` in ``[-2, 2]``, ``I_2`` in ``[2.3, 9]``, ``|q_1 - q_2|`` in ``[0.03, 0.97] acosh(I_2/2)``,
  ``q_1 + q_2`` in ``[-1, 1]``, with ``I_1 = (p_1 + p_2)/2`` and ``I_2 = -min tr L`` read off the literal trace
  (24 draws, every sign pair; a relative allowance of 1e-9 for the 17-digit strings).
* ``library.inverse_polish`` -- :func:`symbt.reference.inverse.solve_parameters` from a guess whose interval
  ``[lam0 - mu, lam0 + mu]`` reaches into a band (so it first shrinks ``mu``, as documented) recovers the
  ``(lam0, mu, +1)`` its target ``c_k`` were computed at, to ``tol^(3/2)``: Newton stops at the first iterate with
  residual below ``tol`` (error about ``tol`` here, the Jacobian being of order 1) and then takes one more step,
  which squares the error (docstring); without that step the error is of the order of ``tol``.
* ``library.sample_stream`` -- :func:`symbt.reference.samples.admissible_states` draws from the stream its docstring
  documents (``random.Random(1000 N + 10 seed + (trace_sign > 0))``, each proposal ``p``, ``q``, ``lam0``, ``mu``
  uniform on the stated ranges, 6 decimals): its states are, in order, proposals of that replayed stream (N = 2, 3,
  both signs) -- so the two signs draw from different streams and a published sample can be reproduced.
* ``library.trace_gap`` -- :func:`symbt.reference.trace.trace_gap` is 0 on an interval one of whose *end points*
  is a band edge (the interval is closed), at every real root of ``tr L = +-2`` as mpmath's ``polyroots``
  computes it from :func:`~symbt.reference.trace.hamiltonians` -- the same numbers the function compares with its
  end points: the rule is about the end points, so the check needs them bit for bit (a consistency of the rule,
  not an independent route to the band edges).

Each is shown to fail on the planted mutant it was written for in ``tests/test_killers_reference3.py``.

>>> model_symbols.run().status
'verified'
"""
from __future__ import annotations

import random

import mpmath as mp
import sympy as sp

from ..reference import elliptic as E
from ..reference.inverse import solve_parameters
from ..reference.literal import literal_trace
from ..reference.samples import admissible_states
from ..reference.spectral import flow_coefficients_mp
from ..reference.trace import hamiltonians, trace_gap
from ..symbolic.rewriting import rationalize_exponentials
from ..symbolic.toda import TodaModel
from .base import Outcome, claim, failed
from .library_sampler import trace_quadratic


@claim("library.model_symbols", equation="tra", scene="library", N=3,
       where="symbt.symbolic.toda.TodaModel (p, q, E, lambda) and symbt.symbolic.rewriting.rationalize_exponentials",
       statement="TodaModel(N) (N = 2, 3): p_j, q_j, lambda real and E_j positive as SymPy infers (conjugate(x) = x, "
                 "|E_j| = E_j; Symbol('p1', real=True) is the model's p_1); rationalize_exponentials without a "
                 "mapping gives positive symbols m_s for exp(s), and exp(q1 - 2 q2) + 2 cosh(q1 - q2) = "
                 "m1/m2^2 + m1/m2 + m2/m1 (cancel)")
def model_symbols() -> Outcome:
    checks: dict[str, bool] = {}
    for N in (2, 3):
        m = TodaModel(N)                              # a fresh model, not toda_model's cached one
        real = [*m.p, *m.q, m.lam]
        checks[f"N={N}: p_j, q_j, lambda real (conjugate(x) = x)"] = all(sp.conjugate(x) == x for x in real)
        checks[f"N={N}: E_j positive (|E_j| = E_j)"] = all(sp.Abs(e) == e and e.is_positive is True for e in m.E)
        by_name = {sp.Symbol(f"p{j + 1}", real=True): sp.Rational(j + 1, 3) for j in range(N)}
        by_name.update({sp.Symbol(f"E{j + 1}", positive=True): sp.Integer(j + 2) for j in range(N)})
        checks[f"N={N}: tr L at a state given by name is a number"] = not m.trace.xreplace(
            {**by_name, m.lam: sp.Rational(1, 2)}).free_symbols
    q1, q2 = sp.symbols("q1 q2", real=True)
    out, ms = rationalize_exponentials(sp.exp(q1 - 2 * q2) + 2 * sp.cosh(q1 - q2))
    checks["rationalize_exponentials: one symbol for each of q1, q2"] = set(ms) == {q1, q2}
    if set(ms) == {q1, q2}:
        m1, m2 = ms[q1], ms[q2]
        checks["rationalize_exponentials: positive symbols (|m| = m)"] = all(
            sp.Abs(v) == v and v.is_positive is True for v in (m1, m2))
        checks["exp(q1 - 2 q2) + 2 cosh(q1 - q2) = m1/m2^2 + m1/m2 + m2/m1"] = sp.cancel(
            out - (m1 / m2 ** 2 + m1 / m2 + m2 / m1)) == 0
    bad = [k for k, ok in checks.items() if not ok]
    if bad:
        return failed("SymPy assumptions and cancel", detail="; ".join(bad))
    return Outcome("verified", "exact: SymPy's inference from the symbols' assumptions, cancel", evidence="proof",
                   n_scope=[2, 3], detail="; ".join(checks))


#: library.addition: digits, the move of P~, cases (regime, rng seed string)
ADD_DPS, ADD_DELTA = 20, mp.mpf("1e-6")
ADD_CASES = (("inner", "ref3 addition inner"),)


def carlson_F(z: mp.mpf, k: mp.mpf) -> mp.mpf:
    """F(z, k) = z R_F(1 - z^2, 1 - k^2 z^2, 1) for real |z| <= 1, by mpmath's ``elliprf``."""
    return z * mp.elliprf(1 - z * z, 1 - k * k * z * z, 1)


@claim("library.addition", equation="addform", scene="library", N=2,
       where="symbt.reference.elliptic.addition_residual and printed_addform_residual",
       statement="addition_residual <= 10^(12 - dps) at a step2 step; with P~ moved by +-1e-6 (E~ kept) it is "
                 "|delta|/max(1, |P~ + delta|) within twice the unmoved residual; printed_addform_residual = "
                 "|F(P~) - F(P) - F(s-) + F(s+)| with F by mpmath's elliprf (I1, I2, k by the literal trace) within "
                 "10^(5 - dps), also with P~ moved by +-1e-6 (a sum of either sign); N = 2, 20 digits, an inner "
                 "case, both branches")
def addition_checks() -> Outcome:
    bad, n, worst = [], 0, mp.mpf(0)
    with mp.workdps(ADD_DPS):
        tol0 = mp.mpf(10) ** (12 - ADD_DPS)
        for reg, seed in ADD_CASES:
            p, q, l0, m = E.sample_case(reg, random.Random(seed))
            P, Q, L0, M = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m)
            a, b, c = trace_quadratic(P, Q)
            I1, I2 = b / (2 * a), b * b / (4 * a) - c
            r = mp.sqrt(I2 - 2)
            for br in (1, -1):
                n += 1
                pt, _, info = E.step2(P, Q, L0, M, br)
                Et = info["E_new"]
                res0 = E.addition_residual(P, Q, L0, M, br, pt=pt, Et=Et)
                worst = max(worst, res0)
                if not res0 <= tol0:
                    bad.append(f"{reg}, b = {br}: residual {mp.nstr(res0, 3)} at a step2 step (> 1e{12 - ADD_DPS})")
                    continue
                Pt = (pt[1] - pt[0]) / (2 * r)
                for d in (ADD_DELTA, -ADD_DELTA):
                    moved = [pt[0] - d * r, pt[1] + d * r]
                    want = abs(d) / max(1, abs(Pt + d))
                    got = E.addition_residual(P, Q, L0, M, br, pt=moved, Et=Et)
                    if not abs(got - want) <= 2 * res0 + mp.mpf(10) ** (2 - ADD_DPS):
                        bad.append(f"{reg}, b = {br}: P~ moved by {mp.nstr(d, 2)}: residual {mp.nstr(got, 6)}, "
                                   f"want {mp.nstr(want, 6)}")
                if reg != "inner":
                    continue
                k = mp.sqrt((I2 - 2) / (I2 + 2))
                s_m, s_p = (L0 - M + I1) / r, (L0 + M + I1) / r
                args = (Pt, (P[1] - P[0]) / (2 * r), s_m, s_p)
                if not all(abs(x) <= 1 for x in args):
                    bad.append(f"inner case, b = {br}: an argument of F outside [-1, 1] (control)")
                    continue
                F = [carlson_F(x, k) for x in args]
                want = abs(F[0] - F[1] - F[2] + F[3])
                got = E.printed_addform_residual(P, Q, pt, I2, L0, M, I1)
                if not abs(got - want) <= mp.mpf(10) ** (5 - ADD_DPS):
                    bad.append(f"inner, b = {br}: printed_addform_residual {mp.nstr(got, 8)}, "
                               f"Carlson {mp.nstr(want, 8)}")
                # P~ moved both ways: the four terms' sum is about +-delta F'(P~), one of them negative -- a modulus
                for d in (ADD_DELTA, -ADD_DELTA):
                    moved = [pt[0] - d * r, pt[1] + d * r]
                    want = abs(carlson_F(Pt + d, k) - F[1] - F[2] + F[3])
                    got = E.printed_addform_residual(P, Q, moved, I2, L0, M, I1)
                    if not abs(got - want) <= mp.mpf(10) ** (5 - ADD_DPS) + 2 * res0:
                        bad.append(f"inner, b = {br}, P~ moved by {mp.nstr(d, 2)}: printed_addform_residual "
                                   f"{mp.nstr(got, 8)}, Carlson {mp.nstr(want, 8)}")
    detail = (f"{n} steps (an inner case, both branches), residual at the step <= {mp.nstr(worst, 2)} "
              f"(accepted <= 1e{12 - ADD_DPS}); P~ moved by +-1e-6; the printed residual against elliprf (inner)")
    if bad:
        return failed("addition residuals vs their defining terms", detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", f"numeric: {ADD_DPS} digits, mpmath elliprf and the literal trace", evidence="sampled",
                   n_scope=[2], residual=float(worst), detail=detail)


#: library.state_ranges: draws, relative allowance (17-digit decimal strings)
STATE_DRAWS, STATE_SLACK = 24, mp.mpf("1e-9")


@claim("library.state_ranges", equation="th1th2", scene="library", N=2,
       where="symbt.reference.elliptic.sample_state (its level sets)",
       statement="sample_state, 24 draws (every sign pair): I1 = (p1 + p2)/2 in [-2, 2], I2 = -min tr L in [2.3, 9], "
                 "|q1 - q2| in [0.03, 0.97] acosh(I2/2), q1 + q2 in [-1, 1] (I1, I2 by the literal trace), each "
                 "reaching both outer fifths of its range")
def state_ranges() -> Outcome:
    bad: list[str] = []
    seen: list[tuple[float, float, float, float]] = []
    rng = random.Random("ref3 sample_state")
    one = 1 + STATE_SLACK
    with mp.workdps(30):
        for k in range(STATE_DRAWS):
            xs, ps = (1, -1)[k % 2], (1, -1)[(k // 2) % 2]
            p, q = E.sample_state(rng, x_sign=xs, p_sign=ps)
            P, Q = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]
            a, b, c = trace_quadratic(P, Q)
            I1, I2 = b / (2 * a), b * b / (4 * a) - c
            x = abs(Q[0] - Q[1])
            why = []
            if not abs(I1) <= 2 * one:
                why.append(f"I1 = {mp.nstr(I1, 6)}")
            if not 2.3 / one <= I2 <= 9 * one:
                why.append(f"I2 = {mp.nstr(I2, 6)}")
            elif not 0.03 / one <= x / mp.acosh(I2 / 2) <= 0.97 * one:
                why.append(f"|q1 - q2| = {mp.nstr(x / mp.acosh(I2 / 2), 6)} acosh(I2/2)")
            if not abs(Q[0] + Q[1]) <= one:
                why.append(f"q1 + q2 = {mp.nstr(Q[0] + Q[1], 6)}")
            if why:
                bad.append(f"draw {k}: " + ", ".join(why))
            seen.append((float(I1), float(I2), float(x / mp.acosh(I2 / 2)), float(Q[0] + Q[1])))
    # and the draws fill their ranges: each quantity reaches the outer fifth of its interval at both ends (a uniform
    # draw misses one such fifth in 24 draws with probability 2 * 0.8**24 = 0.9 %; the stream is seeded and fixed)
    for name, (lo, hi), vals in zip(("I1", "I2", "|q1 - q2|/acosh(I2/2)", "q1 + q2"),
                                    ((-2, 2), (2.3, 9), (0.03, 0.97), (-1, 1)), zip(*seen)):
        fifth = (hi - lo) / 5
        if not (min(vals) < lo + fifth and max(vals) > hi - fifth):
            bad.append(f"{name}: draws in [{min(vals):.3g}, {max(vals):.3g}], not reaching both ends of [{lo}, {hi}]")
    detail = f"{STATE_DRAWS} draws, x_sign and p_sign +-1, each quantity reaching both outer fifths of its range"
    if bad:
        return failed("sample_state's ranges vs the literal trace", detail="; ".join(bad[:3]) + f" ({len(bad)} draws). "
                      + detail)
    return Outcome("verified", "sample_state's ranges vs the literal trace (30 digits)", evidence="sampled",
                   n_scope=[2], detail=detail)


#: library.inverse_polish: the state (decimal inputs), digits, the solver's stopping residual, the guess's mu factor
INV_STATE = (("0.518591", "-0.82529"), ("-1.341917", "0.453427"), "4.504539", "0.494889")
INV_DPS, INV_TOL, INV_GUESS = 15, mp.mpf("1e-6"), 3


@claim("library.inverse_polish", equation="linearcomb", scene="library", N=2,
       where="symbt.reference.inverse.solve_parameters (mode exact: the shrinking start and the final Newton step)",
       statement="solve_parameters (N = 2, 15 digits, tol = 1e-6) from a guess (lam0, 3 mu) whose interval reaches "
                 "into a band recovers (lam0, mu, +1) to tol^(3/2) = 1e-9 from c_k computed there")
def inverse_polish() -> Outcome:
    with mp.workdps(INV_DPS):
        p, q = [mp.mpf(v) for v in INV_STATE[0]], [mp.mpf(v) for v in INV_STATE[1]]
        l0, m = mp.mpf(INV_STATE[2]), mp.mpf(INV_STATE[3])
        guess = (l0, INV_GUESS * m)
        lo = guess[0] - guess[1]
        if not abs(literal_trace(lo, p, q)) < 2:    # control: the guess's interval has an end in a band
            return failed("control", detail=f"|tr L({mp.nstr(lo, 8)})| >= 2: the guess does not reach into a band")
        c = flow_coefficients_mp(p, q, l0, m, 1)
        try:
            r = solve_parameters(p, q, c, tol=INV_TOL, guess=guess)
        except ValueError as exc:
            return failed("solve_parameters", detail=str(exc))
        if r is None:
            return failed("solve_parameters", detail="no solution returned")
        err = max(abs(r["lam0"] - l0), abs(r["mu"] - m))
        bound = INV_TOL ** mp.mpf(1.5)
    if err > bound or r["branch"] != 1:
        return failed("solve_parameters", residual=float(err),
                      detail=f"got lam0 = {mp.nstr(r['lam0'], 15)}, mu = {mp.nstr(r['mu'], 15)}, branch {r['branch']}: "
                             f"off by {float(err):.2e} (accepted below tol^(3/2) = {float(bound):.0e})")
    return Outcome("verified", f"numeric: round trip through flow_coefficients_mp ({INV_DPS} digits)",
                   evidence="sampled", n_scope=[2], residual=float(err),
                   detail=f"from (lam0, 3 mu) (an end in a band): recovered to {float(err):.1e} after "
                          f"{r['iterations']} iterations (accepted below tol^(3/2) = {float(bound):.0e}, tol = 1e-6)")


#: library.sample_stream: sizes, count, the largest number of proposals replayed
STREAM_SIZES, STREAM_COUNT, STREAM_MAX = (2, 3), 3, 20000


def replayed_proposals(N: int, trace_sign: int, seed: int = 0):
    """The proposals of :func:`~symbt.reference.samples.admissible_states`' documented stream, as decimal strings."""
    rng = random.Random(1000 * N + 10 * seed + (trace_sign > 0))
    for _ in range(STREAM_MAX):
        p = [f"{rng.uniform(-3, 3):.6f}" for _ in range(N)]
        q = [f"{rng.uniform(-1.5, 1.5):.6f}" for _ in range(N)]
        yield p + q + [f"{rng.uniform(-5, 5):.6f}", f"{rng.uniform(0.05, 0.8):.6f}"]


@claim("library.sample_stream", equation="newkmu", scene="library", N=3,
       where="symbt.reference.samples.admissible_states (its documented stream)",
       statement="admissible_states(N, s, 3) (N = 2, 3; s = +-1) returns, in order, proposals of the documented "
                 "stream random.Random(1000 N + 10 seed + (s > 0)) (p_j, q_j, lam0, mu uniform on [-3, 3], "
                 "[-1.5, 1.5], [-5, 5], [0.05, 0.8], 6 decimals)")
def sample_stream() -> Outcome:
    bad: list[str] = []
    used = {}
    with mp.workdps(30):
        for N in STREAM_SIZES:
            for s in (1, -1):
                states = admissible_states(N, s, STREAM_COUNT)
                want = [[*p, *q, l0, m] for p, q, l0, m in states]
                i, k = 0, 0
                for prop in replayed_proposals(N, s):
                    k += 1
                    if i < len(want) and all(mp.mpf(x) == y for x, y in zip(prop, want[i])):
                        i += 1
                        if i == len(want):
                            break
                used[(N, s)] = k
                if i < len(want):
                    bad.append(f"N = {N}, sign {s}: state {i} is not among the stream's next {STREAM_MAX - k} "
                               "proposals")
    if bad:
        return failed("admissible_states vs its replayed stream", detail="; ".join(bad))
    return Outcome("verified", "exact: the documented stream replayed (decimal strings compared at 30 digits)",
                   evidence="sampled", n_scope=list(STREAM_SIZES),
                   detail="; ".join(f"N = {N}, sign {s}: {STREAM_COUNT} states within the first {k} proposals"
                                    for (N, s), k in used.items()))


#: library.trace_gap: states (p, q) and the width of the intervals at a band edge
GAP_STATES = ((("0.518591", "-0.82529"), ("-1.341917", "0.453427")),)
GAP_H = mp.mpf("1e-3")


@claim("library.trace_gap", equation="tra", scene="library", N=2,
       where="symbt.reference.trace.trace_gap (the end points of its closed interval)",
       statement="trace_gap(p, q, e, e + 1e-3) = trace_gap(p, q, e - 1e-3, e) = 0 at every real root e of tr L = +-2 "
                 "(mpmath polyroots of the hamiltonians' polynomial), at a state of N = 2")
def trace_gap_ends() -> Outcome:
    bad, n = [], 0
    with mp.workdps(30):
        small = mp.mpf(10) ** (-mp.mp.dps // 2)
        for ps, qs in GAP_STATES:
            p, q = [mp.mpf(v) for v in ps], [mp.mpf(v) for v in qs]
            coeffs = hamiltonians(p, q)[::-1]
            for shift in (2, -2):
                c = list(coeffs)
                c[-1] -= shift
                for root in mp.polyroots(c, maxsteps=200, extraprec=60):
                    if abs(mp.im(root)) >= small:
                        continue
                    e = mp.re(root)
                    n += 1
                    for lo, hi in ((e, e + GAP_H), (e - GAP_H, e)):
                        g = trace_gap(p, q, lo, hi)
                        if g != 0:
                            bad.append(f"N = {len(p)}, tr = {shift} at {mp.nstr(e, 12)}: trace_gap on "
                                       f"[{mp.nstr(lo, 8)}, {mp.nstr(hi, 8)}] = {mp.nstr(g, 3)}, not 0")
    if bad or n < 2 * len(GAP_STATES):
        return failed("trace_gap at band edges", detail="; ".join(bad[:3]) or f"only {n} band edges (control)")
    return Outcome("verified", "numeric: trace_gap at the band edges from mpmath polyroots (30 digits)",
                   evidence="sampled", n_scope=[2],
                   detail=f"{n} band edges, each as the lower and as the upper end of an interval")
