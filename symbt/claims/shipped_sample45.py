r"""What ships, 4l: documented rules of the numeric routes that the fresh mutation samples of seeds 4 and 5 showed
unchecked (scene ``numeric-paths``; issue 21 item 4, docs/mutation.md "Seeds 4 and 5").

* ``paths.track_hooks`` -- the fused kernel's hooks of the trace's rounding scale, called directly
  (:data:`~symbt.numeric.float64.kernels.HOOKS`; ``python_orbit`` writes them inline, so the line map never sees
  their own lines run): ``track_init`` after the first factor holds the entrywise absolute values of
  ``[[a_0, -1], [r_0, 0]]``, the cancellation ratio ``kn / kd = (|lam| + |p_0|) / |lam + p_0|`` (its docstring) and
  the scale 1, at a negative ``lam`` too; ``rescale`` multiplies by ``2**-400`` exactly the monodromies whose
  tracked ``Aa`` or ``Ba`` is past ``2**400`` (the monodromy ``[[A, B], [C, D]] / sc`` unchanged, exact
  rationals) and leaves the
  others alone; ``bounded`` is the read-out's range ``|x| < 1e300`` (``1e300`` itself is out).
* ``paths.kappa_rows.n2`` -- :func:`~symbt.numeric.core.condition.sharp_trace_kappa_rows` on more than
  ``FEW_ROWS`` rows (its numpy form) where some rows' products leave ``[2**-200, 2**200]`` (``paths.renorm_top``'s
  states and two others) equals the scalar :func:`~symbt.numeric.core.condition.sharp_trace_kappa` row by row, bit
  for bit (its docstring; a consistency check -- the scalar is checked against its definition by
  ``paths.renorm_top`` and ``paths.kappa_cells``).
* ``paths.mp_verdict.n3`` -- the escalation's mpmath verdict (:mod:`symbt.numeric.float64.rows`) names the point
  whose trace lies in a band: ``TRACE1`` where ``lam1 = lam0 + mu`` does, ``TRACE2`` where ``lam2 = lam0 - mu``
  does, ``OK`` where neither (the codes' meaning in :mod:`symbt.numeric.core.limits` and ``raise_for_rows``), the
  bands decided independently by the literal trace at 30 digits.
* ``paths.inline_boolop`` -- :func:`~symbt.numeric.core.inline.inlined` writes a pure body called in the first
  operand of ``and`` / ``or`` (the operand always evaluated) inline, with the plain function's values.
* ``paths.side_by_side.n3`` -- :func:`~symbt.numeric.core.condition.monodromy_and_abs` on 20 rows, half of them
  past ``2**500`` (renormalised), and on a batch where only the absolute product leaves the range in some rows,
  equals ``monodromy(FLOAT)`` and ``abs_trace_rows`` bit for bit (its docstring), and its trace the literal trace
  at 30 digits within ``1e-13`` relative.
* ``paths.growth_law`` -- :func:`~symbt.numeric.multiprec.lohner.growth_law` on exact power-law records returns
  their degree (within ``1e-9``), window and end values.
* ``paths.root_slope`` -- :func:`~symbt.numeric.core.spectral_sum.root_slope` and its numpy form
  ``root_slope_rows`` are within half an ulp of the exact slope (60 digits) on 192 cases, a quarter of them at
  |A| from 1e9 to 1e14 (where the quotient -2C/k once lost 1600 ulps) and a quarter near :math:`2^{27}` (where
  :math:`t^2 - 4` rounds): "rounded once".
* ``paths.jacobian_dual.n3`` -- :func:`~symbt.numeric.multiprec.lohner_checks.jacobian_dual` (the step on dual
  numbers) at the paper's state, both branches: its image encloses the literal map at 50 digits and every entry of
  its Jacobian is within ``1e-12 (1 + |J|)`` of a central finite difference of the literal map at 50 digits
  (step ``1e-15``: truncation ``~1e-30``), an independent route; where both traces are positive (``lam0 = 30``,
  ``mu = 5``) it computes the map and its image encloses it (the paper's state has both negative; seed 21: a sign
  test that took two positive traces for opposite ones refused there).

Shown to fail on planted bugs in ``tests/test_killers_numeric5.py``.
"""
from __future__ import annotations

import importlib.util
import math
from fractions import Fraction

import mpmath as mp
import numpy as np

from .base import Outcome, claim, failed, skipped
from .shipped_edges import RENORM_CASES, renorm_inputs

PAPER = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 10.0, 5.0)


def _exact_unscaled(sc: float, xs: tuple) -> list[Fraction]:
    """The monodromy's entries: the tracked ones are ``sc`` times them (``track_init``'s docstring)."""
    return [Fraction(x) / Fraction(sc) for x in xs]


@claim("paths.track_hooks", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/float64/kernels.py: the hooks track_init, rescale and bounded",
       statement="the fused kernel's hooks called directly: track_init at lam = -3, p0 = 1 (and lam = 3, p0 = -1) "
                 "holds |[[a0, -1], [r0, 0]]|, kn/kd = (|lam| + |p0|)/|lam + p0| and scale 1; rescale multiplies by "
                 "2**-400 exactly where Aa or Ba is past 2**400 ([[A, B], [C, D]] / sc unchanged, exact rationals) and "
                 "returns the others as they are; bounded(x) is |x| < 1e300 (1e300 out, the double below in)")
def track_hooks() -> Outcome:
    from ..numeric.float64.kernels import HOOKS

    bad, seen = [], []
    for lam, p0, r0 in ((-3.0, 1.0, 0.5), (3.0, -1.0, 0.5), (-7.5, -0.25, 2.0)):
        a0 = lam + p0
        Aa, Ba, Ca, Da, kn, kd, sc = HOOKS["track_init"](lam, p0, a0, r0)
        want = (Fraction(abs(lam)) + Fraction(abs(p0))) / abs(Fraction(lam) + Fraction(p0))
        if (Aa, Ba, Ca, Da, sc) != (abs(a0), 1.0, abs(r0), 0.0, 1.0) or Fraction(kn) / Fraction(kd) != want:
            bad.append(f"track_init at lam = {lam}, p0 = {p0}: {(Aa, Ba, Ca, Da, kn, kd, sc)}, kn/kd wanted {want}")
        seen.append(f"kn/kd = {float(want):g}")
    big = 2.0 ** 400
    ABCD = (3.0 * big, -big, 0.5 * big, 2.0 ** -30)
    for name, aux, shrink in (("Aa past 2**400", (2.0 * big, 1.0, 1.0, 1.0, 1.0, 1.0, 0.5), True),
                              ("Ba past 2**400", (1.0, 4.0 * big, 1.0, 1.0, 1.0, 1.0, 1.0), True),
                              ("Aa = 2**400", (big, big, 1.0, 1.0, 1.0, 1.0, 1.0), False)):
        A, B, C, D, aux2 = HOOKS["rescale"](*ABCD, aux)
        same_value = _exact_unscaled(aux2[6], (A, B, C, D)) == _exact_unscaled(aux[6], ABCD)
        moved = (A, B, C, D) != ABCD
        shrunk = (A == ABCD[0] * 2.0 ** -400 and aux2[0] == aux[0] * 2.0 ** -400
                  and aux2[1] == aux[1] * 2.0 ** -400 and aux2[4:6] == aux[4:6])
        if not (same_value and moved == shrink and (shrunk or not shrink)):
            bad.append(f"rescale, {name}: entries {'moved' if moved else 'kept'} (wanted "
                       f"{'shrunk' if shrink else 'kept'}), M / sc unchanged {same_value}")
    edge = (1e300, -1e300, math.nextafter(1e300, 0.0), -math.nextafter(1e300, 0.0), math.inf, math.nan)
    got = [bool(HOOKS["bounded"](x)) for x in edge]
    if got != [False, False, True, True, False, False]:
        bad.append(f"bounded at +-1e300, the doubles inside, inf, nan: {got}")
    detail = "; ".join(seen) + "; rescale at 3 aux; bounded at 6 values."
    if bad:
        return failed("numeric: the kernel's track/rescale/bounded hooks vs their documented rules",
                      detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: the kernel's track/rescale/bounded hooks vs their documented rules (exact "
                   "rationals)", evidence="sampled", n_scope="all", detail=detail,
                   printed="the documented scale, rescaling and range")


#: paths.kappa_rows: more rows than FEW_ROWS; paths.renorm_top's states and two with products far outside 2**+-200
KAPPA_ROW_CASES = RENORM_CASES + (((1.0, -2.0), (0.0, 300.0), 3.0), ((0.5, 0.25), (0.0, -300.0), 1e-200))


@claim("paths.kappa_rows", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(2,),
       where="symbt/numeric/core/condition.py: sharp_trace_kappa_rows (the rows' power-of-two rescaling)",
       statement="sharp_trace_kappa_rows on 20 rows (N={N}: paths.renorm_top's states, p = (1, -2), q = (0, 300), "
                 "lam = 3 and p = (1/2, 1/4), q = (0, -300), lam = 1e-200, five times each) equals "
                 "sharp_trace_kappa row by row, bit for bit; so do their first sites alone (one site)")
def kappa_rows(N: int) -> Outcome:
    from ..numeric.core.condition import FEW_ROWS, sharp_trace_kappa, sharp_trace_kappa_rows

    reps = FEW_ROWS // len(KAPPA_ROW_CASES) + 1
    P = np.array([renorm_inputs(*c)[0] for c in KAPPA_ROW_CASES] * reps, dtype=float)
    R = np.array([renorm_inputs(*c)[1] for c in KAPPA_ROW_CASES] * reps, dtype=float)
    L = np.array([c[2] for c in KAPPA_ROW_CASES] * reps, dtype=float)
    got = sharp_trace_kappa_rows(P, R, L, np.zeros(len(L)))
    want = np.array([sharp_trace_kappa(P[i], R[i], float(L[i]), 0.0) for i in range(len(L))])
    # one site (the product is m_1 alone: no prefix row to copy), the first site of the same rows
    got1 = sharp_trace_kappa_rows(P[:, :1], R[:, :1], L, np.zeros(len(L)))
    want1 = np.array([sharp_trace_kappa(P[i, :1], R[i, :1], float(L[i]), 0.0) for i in range(len(L))])
    detail = (f"{len(L)} rows (FEW_ROWS = {FEW_ROWS}); scalar values {', '.join('%.6g' % v for v in want[:4])}; "
              f"one site: {', '.join('%.6g' % v for v in want1[:2])}.")
    if not (len(L) > FEW_ROWS and np.array_equal(got, want) and np.array_equal(got1, want1)):
        return failed("numeric: sharp_trace_kappa_rows vs the scalar sharp_trace_kappa",
                      detail=f"rows {', '.join('%.6g' % v for v in got[:4])}. " + detail)
    return Outcome("verified", "numeric: sharp_trace_kappa_rows vs the scalar sharp_trace_kappa, bit for bit "
                   "(consistency)", evidence="sampled", detail=detail, printed="every row the scalar's value")


#: paths.mp_verdict: lam0 with lam1 = lam0 + mu, then lam2 = lam0 - mu, near the band at lam ~ 20.065 of the paper's
#: state (tr L ~ 1e-12 there), and the paper's own (lam0, mu)
VERDICT_CASES = ((15.064953325452297, 5.0), (25.064953325452297, 5.0), (10.0, 5.0))


@claim("paths.mp_verdict", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/rows.py: the escalation's mpmath verdict (which trace lies in a band)",
       statement="the escalation's mpmath verdict at the paper's p, q (N={N}), both branches, 40 digits: TRACE1 where "
                 "|tr L(lam0 + mu)| <= 2, TRACE2 where |tr L(lam0 - mu)| <= 2 (and not the first), OK at the paper's "
                 "(lam0, mu) = (10, 5); the bands decided by the literal trace at 30 digits")
def mp_verdict(N: int) -> Outcome:
    from ..numeric.core.limits import OK, TRACE1, TRACE2
    from ..numeric.float64 import rows
    from ..reference.literal import literal_trace

    p, q = PAPER[0], PAPER[1]
    bad, seen = [], []
    for l0, m in VERDICT_CASES:
        with mp.workdps(30):
            in1 = abs(literal_trace(mp.mpf(l0) + m, p, q)) <= 2
            in2 = abs(literal_trace(mp.mpf(l0) - m, p, q)) <= 2
        want = TRACE1 if in1 else TRACE2 if in2 else OK
        for b in (1, -1):
            code = rows._mp_verdict(np.array(p), np.array(q), l0, m, b, 40)[0]
            if code != want:
                bad.append(f"lam0 = {l0}, mu = {m}, branch {b}: code {code}, the literal trace says {want}")
        seen.append(f"lam0 = {l0:g}: {want}")
    detail = "; ".join(seen) + f" (OK {OK}, TRACE1 {TRACE1}, TRACE2 {TRACE2})."
    if bad:
        return failed("numeric: the escalation's mpmath verdict vs the literal trace", detail="; ".join(bad) + ". "
                      + detail)
    return Outcome("verified", "numeric: the escalation's mpmath verdict vs the literal trace (30 digits)",
                   evidence="sampled", detail=detail, printed="TRACE1, TRACE2, OK as the bands say")


@claim("paths.jacobian_dual", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/lohner_checks.py: jacobian_dual (the step on dual numbers)",
       statement="jacobian_dual at the paper's state (N={N}), both branches, 30 digits: its image encloses the literal "
                 "map (50 digits) and every Jacobian entry is within 1e-12 (1 + |J|) of the central finite difference "
                 "of the literal map at 50 digits (step 1e-15); at lam0 = -2, mu = +-1.215 (lam1 or lam2 in the band "
                 "near -0.785, by the literal trace at 30 digits) NoRealMapError with condition 'trace'; at lam0 = "
                 "30, mu = 5 (both traces positive) the image encloses the literal map, both branches")
def jacobian_dual(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from flint import arb

    from ..numeric.multiprec.lohner_checks import jacobian_dual as jd
    from ..reference.literal import literal_step
    from .seed21 import encloses, positive_traces_enclosed

    p, q, l0, m = PAPER
    bad, worst = [], 0.0
    for b in (1, -1):
        with mp.workdps(30):
            img, J = jd([arb(v) for v in list(p) + list(q)], arb(l0), arb(m), b)
        with mp.workdps(50):
            x0 = [mp.mpf(v) for v in list(p) + list(q)]

            def f(x: list) -> list:
                pt, qt, _ = literal_step(x[:N], x[N:], mp.mpf(l0), mp.mpf(m), b)
                return list(pt) + list(qt)

            y0 = f(x0)
            inside = encloses(img, y0)
            h = mp.mpf(10) ** -15
            for j in range(2 * N):
                xp, xm = list(x0), list(x0)
                xp[j] += h
                xm[j] -= h
                col = [(u - v) / (2 * h) for u, v in zip(f(xp), f(xm))]
                for i in range(2 * N):
                    got = float(J[i, j].mid())
                    err = abs(got - float(col[i]))
                    worst = max(worst, err)
                    if not err <= 1e-12 * (1 + abs(float(col[i]))):
                        bad.append(f"branch {b}: J[{i}, {j}] = {got!r}, finite difference {mp.nstr(col[i], 15)}")
        if not inside:
            bad.append(f"branch {b}: the image does not enclose the literal map")
    # refusal: one of lam0 +- mu in a band (the existence decision on the dual numbers' value balls)
    from ..numeric import NoRealMapError
    from ..reference.literal import literal_trace
    refused = 0
    for mu in (1.215, -1.215):
        with mp.workdps(30):
            in_band = any(abs(literal_trace(mp.mpf(-2 + s * mu), [mp.mpf(v) for v in p], [mp.mpf(v) for v in q])) <= 2
                          for s in (1, -1))
            try:
                jd([arb(v) for v in list(p) + list(q)], arb(-2), arb(mu), 1)
                seen = "a Jacobian"
            except NoRealMapError as exc:
                seen = exc.condition
                refused += 1
            except Exception as exc:  # noqa: BLE001 -- any other outcome is the finding
                seen = f"{type(exc).__name__}: {exc}"
        if not in_band or seen != "trace":
            bad.append(f"lam0 = -2, mu = {mu}: lam0 +- mu in a band {in_band}, jacobian_dual gave {seen}")
    bad += positive_traces_enclosed(jd, p, q)      # the paper's state has both traces negative
    detail = (f"worst |J - finite difference| {worst:.3g} over 2 x {(2 * N) ** 2} entries; {refused} of 2 states "
              "with a spectral parameter in a band refused.")
    if bad:
        return failed("numeric: jacobian_dual vs finite differences of the literal map",
                      detail="; ".join(bad[:6]) + ". " + detail)
    return Outcome("verified", "numeric: jacobian_dual vs central finite differences of the literal map (50 digits)",
                   evidence="sampled", detail=detail, printed="image enclosed, J within 1e-12")


def _half(x: float) -> float:          # a pure body for the inliner
    y = x * 0.5
    return y


def _boolop_first(x: float) -> bool:    # the body in the operand a BoolOp always evaluates
    ok = _half(x) > 1.0 and x < 5.0
    return ok


def _boolop_or(x: float) -> bool:
    ok = _half(x) < -1.0 or x > 5.0
    return ok


@claim("paths.inline_boolop", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/core/inline.py: inlined's rewrite of a body in a BoolOp's first operand",
       statement="inlined with a pure body called in the first operand of 'and' / 'or' (the operand always "
                 "evaluated: written inline before the statement) gives the plain function's value at x = -4, 1, 3, "
                 "6, and the body is no longer called")
def inline_boolop() -> Outcome:
    from ..numeric.core.inline import FLOAT64_INLINE, inlined

    kinds, env = {**FLOAT64_INLINE, "_half": "body"}, {"_half": _half}
    bad = []
    for fn in (_boolop_first, _boolop_or):
        g = inlined(fn, fn.__name__ + "_inline", kinds, env)
        if "_half" in g.__code__.co_names:
            bad.append(f"{fn.__name__}: the body is still called")
        for x in (-4.0, 1.0, 3.0, 6.0):
            if g(x) is not fn(x):
                bad.append(f"{fn.__name__}({x}): {g(x)}, the plain call {fn(x)}")
    detail = "2 functions x 4 arguments."
    if bad:
        return failed("numeric: inlined BoolOps vs the plain calls", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: inlined BoolOps vs the plain calls (consistency of the rewrite)",
                   evidence="sampled", n_scope="all", detail=detail, printed="the plain function's values")


@claim("paths.side_by_side", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/core/condition.py: monodromy_and_abs's side-by-side range test (_both_in_range)",
       statement="monodromy_and_abs on 20 rows of the paper's p, q (N={N}), lam = 1e40 (products in range) and "
                 "lam = 1e170 (products past 2**500: renormalised), and on a second batch (its first 10 rows, and "
                 "10 rows a = (X (1 + 2**-20), 1, 1), r = (X, 1, 1/X), X = 2e150: every signed product in range, the "
                 "absolute one past 2**500 in those 10 rows, renormalised there only): the monodromy and the "
                 "absolute trace bit for bit those of monodromy(FLOAT) and abs_trace_rows, and 2**e tr within 1e-13 "
                 "relative of the literal trace at 30 digits")
def side_by_side(N: int) -> Outcome:
    from ..numeric.core.condition import abs_trace_rows, monodromy_and_abs
    from ..numeric.core.context import FLOAT
    from ..numeric.core.monodromy import monodromy
    from ..reference.literal import literal_trace

    p, q = PAPER[0], PAPER[1]
    lam = np.concatenate([np.full(10, 1e40), np.full(10, 1e170)])
    a = [lam + pj for pj in p]
    r = [np.full(len(lam), math.exp(q[(j + 1) % N] - q[j])) for j in range(N)]
    # a second batch, every signed product in range: 10 rows at lam = 1e40 and 10 where only the absolute product
    # is past 2**500 (a1 a2 - r1 cancels in the signed one: |A| ~ X there, 3 X in the absolute one)
    X = 2e150
    mixed_a, mixed_r = (X * (1 + 2.0 ** -20), 1.0, 1.0), (X, 1.0, 1 / X)
    a2 = [np.concatenate([x[:10], np.full(10, mixed_a[j])]) for j, x in enumerate(a)]
    r2 = [np.concatenate([x[:10], np.full(10, mixed_r[j])]) for j, x in enumerate(r)]
    bad = []
    for aa, rr in ((a, r), (a2, r2)):
        got = monodromy_and_abs(aa, rr)
        want = (*monodromy(FLOAT, aa, rr), *abs_trace_rows(aa, rr))
        if not all(np.array_equal(np.asarray(x), np.asarray(y)) for x, y in zip((*got[0], *got[1]), want)):
            bad.append("differs from monodromy(FLOAT) and abs_trace_rows" + (" (the mixed batch)" if aa is a2 else ""))
    (A, B, C, D, e), (T, ea) = monodromy_and_abs(a, r)
    _, (_, ea2) = monodromy_and_abs(a2, r2)
    worst = 0.0
    with mp.workdps(30):
        for k in (0, len(lam) - 1):
            ref = literal_trace(mp.mpf(float(lam[k])), p, q)
            got = mp.ldexp(mp.mpf(float(A[k] + D[k])), int(np.asarray(e)[k] if np.ndim(e) else e))
            worst = max(worst, float(abs(got / ref - 1)))
    if not worst <= 1e-13:
        bad.append(f"2**e tr off the literal trace by {worst:.3g} relative")
    exa = np.broadcast_to(np.asarray(ea2), (20,))
    if not (np.all(exa[:10] == 0) and np.all(exa[10:] != 0)):
        bad.append(f"the mixed batch's absolute exponents {exa.tolist()} (renormalised in its last 10 rows only)")
    detail = (f"exponents {sorted(set(np.atleast_1d(e).tolist()))}; the mixed batch's absolute ones "
              f"{sorted(set(exa.tolist()))}; worst trace error {worst:.3g} relative.")
    if bad:
        return failed("numeric: monodromy_and_abs vs the separate calls and the literal trace",
                      detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: monodromy_and_abs vs the separate calls (bit for bit) and the literal trace "
                   "(30 digits)", evidence="sampled", detail=detail, printed="the same bits, the trace to 1e-13")


#: paths.growth_law: (log2 c, degree) of synthetic radius records rad(i) = c i**degree, 1000 steps
GROWTH_CASES = ((40.0, 1.5), (-166.0, 2.0), (3.0, 1.0))


@claim("paths.growth_law", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/multiprec/lohner.py: growth_law (the radius growth fitted in log-log)",
       statement="growth_law on the records log2 rad(i) = log2 c + degree log2 i (i = 1..1000; c = 2**40, 2**-166, "
                 "2**3; degree 1.5, 2, 1) returns that degree within 1e-9, steps (100, 1000) and the record's values "
                 "at both ends (its docstring: the least-squares slope over log-spaced steps from first)")
def growth_record() -> Outcome:
    from ..numeric.multiprec.lohner import growth_law

    bad, seen = [], []
    for logc, deg in GROWTH_CASES:
        lograd = [-math.inf] + [logc + deg * math.log2(i) for i in range(1, 1001)]
        law = growth_law(lograd)
        got = law["degree"]
        if not (got is not None and abs(got - deg) <= 1e-9 and law["steps"] == (100, 1000)
                and law["log2_radius"] == (lograd[100], lograd[1000])):
            bad.append(f"log2 c = {logc}, degree {deg}: {law}")
        seen.append(f"{deg}: {got!r}")
    detail = "degrees " + ", ".join(seen) + "."
    if bad:
        return failed("numeric: growth_law vs synthetic power laws", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: growth_law vs synthetic power laws (exact records)", evidence="sampled",
                   n_scope="all", detail=detail, printed="the law's degree")


def _slope_cases() -> list[tuple[float, float, float, float, bool, bool]]:
    """``(A, D, B, C, plus, wantk)``: monodromies with |A + D| > 3, entries of mixed scale (A - D inexact); the
    second half with |A| from 1e9 to 1e14, where the low parts of ``k = (A - D) -+ g`` exceed an ulp of ``k``
    (the quotient -2 C / k lost its second-order term there: 1600 ulps at |A| = 1e12, now repaired), and near
    2**27."""
    rng = np.random.default_rng(45)
    out: list[tuple[float, float, float, float, bool, bool]] = []
    while len(out) < 192:
        # the second half: |A| from 1e9 to 1e14, and |A| near 2**27 (where fl(t**2) has an ulp of 2 to 8, so that
        # the two-sum t**2 - 4 is inexact: its error term is then needed)
        big = 0 if len(out) < 96 else (1 if len(out) < 144 else 2)
        A = float(rng.uniform(-3000, 3000)) if not big else float(rng.choice([-1.0, 1.0])) * (
            10.0 ** float(rng.uniform(9, 14)) if big == 1 else float(rng.uniform(9.5e7, 2.7e8)))
        D = float(rng.uniform(-300, 300)) * (1 + 1e-9 * float(rng.random()))
        B, C = float(rng.uniform(0.5, 9)) * float(rng.choice([-1.0, 1.0])), float(rng.uniform(0.5, 9))
        if abs(A + D) > 3.0:
            out += [(A, D, B, C, plus, wantk) for plus in (True, False) for wantk in (True, False)]
    return out


@claim("paths.root_slope", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/core/spectral_sum.py: root_slope and root_slope_rows (the slope rounded once)",
       statement="root_slope and root_slope_rows (192 rows: its numpy form) on 48 monodromies x (plus, wantk), 12 "
                 "of them with |A| from 1e9 to 1e14 and 12 near 2**27: within "
                 "half an ulp (1 + 2**-20) of the exact slope k / (2 B) or -2 C / k, "
                 "k = (A - D) +- sqrt((A + D)**2 - 4) of A, D at 60 digits (their docstrings: rounded once)")
def root_slope_claim() -> Outcome:
    from ..numeric.core.spectral_sum import root_slope, root_slope_rows

    cases = _slope_cases()
    A, D, B, C = (np.array([c[i] for c in cases]) for i in range(4))
    plus, wantk = np.array([c[4] for c in cases]), np.array([c[5] for c in cases])
    t, dl = A + D, A - D
    g = np.sqrt((t - 2.0) * (t + 2.0))
    rows = root_slope_rows(A, D, dl, g, B, C, 2.0, plus, wantk)
    worst, bad = 0.0, []
    for i, (a, d, b, c, pl, wk) in enumerate(cases):
        u = root_slope(a, d, float(dl[i]), float(g[i]), b, c, 2.0, pl, wk)
        with mp.workdps(60):
            am, dm = mp.mpf(a), mp.mpf(d)
            root = mp.sqrt((am + dm) ** 2 - 4)
            k = (am - dm) + root if pl else (am - dm) - root
            exact = k / (2 * b) if wk else -2 * c / k
            for name, v in (("root_slope", u), ("root_slope_rows", float(rows[i]))):
                err = float(abs(v - exact)) / math.ulp(v)
                worst = max(worst, err)
                if not err <= 0.5 * (1 + 2.0 ** -20):
                    bad.append(f"{name} case {i}: {err:.3g} ulp")
    detail = f"{len(cases)} cases, worst {worst:.6f} ulp."
    if bad:
        return failed("numeric: root_slope vs the exact slope", detail="; ".join(bad[:6]) + ". " + detail)
    return Outcome("verified", "numeric: root_slope and root_slope_rows vs the exact slope (60 digits)",
                   evidence="sampled", n_scope="all", detail=detail, printed="within half an ulp")


def dq_edge_state(N: int) -> tuple:
    """paths.dq_edge's state: a neighbour distance of exactly MAX_DQ_FLOAT64 (q_2 - q_1 = -700), the others 350
    or 0; lam0, mu."""
    return (0.5, -0.25, 0.125) + (0.0,) * (N - 3), (0.0, -700.0) + (-350.0,) * (N - 2), 1e3, 10.0


@claim("paths.dq_edge", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3, 9),
       where="symbt/numeric/float64/kernels_block.py: the re-anchoring's range test |dq| <= MAX_DQ_FLOAT64; "
             "rows.py: the numpy route's per-row range test (past 8 sites: one array of the differences)",
       statement="the block kernel (run_block, one step, both branches) and bt_step (one state and a batch of two, "
                 "backends python and numpy) at p = (1/2, -1/4, 1/8, 0, ...), "
                 "q = (0, -700, -350, ..., -350) (N={N}; a neighbour distance of exactly MAX_DQ_FLOAT64 = 700, the "
                 "documented largest; and the state turned by one site, the 700 between site N and site 1), "
                 "lam0 = 1000, mu = 10: "
                 "status OK and the state within 1e-9 (1 + |x|) of the mpmath step at 40 digits (the literal map "
                 "loses every digit there); with q_2 one ulp further (|dq| > 700) status RANGE, and bt_step a "
                 "NumericRangeError naming the range")
def dq_edge(N: int) -> Outcome:
    from ..numeric import NumericRangeError, bt_step
    from ..numeric.core.limits import MAX_DQ_FLOAT64, OK, RANGE
    from ..numeric.float64.kernels import ANCHOR
    from ..numeric.float64.kernels_block import run_block
    from ..numeric.float64.rows import _mp_verdict

    p0, q, l0, m = dq_edge_state(N)
    bad, worst = [], 0.0
    # the 700 between sites 1 and 2, and (the state turned by one site) between site N and site 1
    for b, turn in ((1, 0), (-1, 0), (1, 1), (-1, 1)):
        for q2, want in ((q[1], OK), (math.nextafter(q[1], -math.inf), RANGE)):
            p = tuple(np.roll(p0, -turn).tolist())
            qq = tuple(np.roll((q[0], q2, *q[2:]), -turn).tolist())
            st = np.zeros(1, np.int64)
            outP, outQ = np.empty((2, 1, N)), np.empty((2, 1, N))
            run_block(np.array([p]), np.array([qq]), np.array([l0 + m]), np.array([l0 - m]), np.array([2 * m]), b, 1,
                      1, ANCHOR, outP, outQ, st, 0, 1)
            if int(st[0]) != want:
                bad.append(f"branch {b}, q_2 = {q2!r}: status {int(st[0])}, the documented {want}")
            states = {"run_block": list(outP[1, 0]) + list(outQ[1, 0])} if int(st[0]) == OK else {}
            for be in ("python", "numpy"):
                for what, args in (("one state", (np.array(p), np.array(qq))),
                                   ("a batch of two", (np.array([p, p]), np.array([qq, qq])))):
                    route = f"bt_step({be}, {what})"
                    try:
                        pt, qt = bt_step(*args, l0, m, branch=b, backend=be)
                        states[route] = list(np.reshape(pt, (-1, N))[-1]) + list(np.reshape(qt, (-1, N))[-1])
                        if want != OK:
                            bad.append(f"branch {b}, q_2 = {q2!r}, {route}: a state beyond the range")
                    except NumericRangeError as exc:
                        if want == OK or "|q_{j+1} - q_j| > 700" not in str(exc):
                            bad.append(f"branch {b}, q_2 = {q2!r}, {route}: {exc}")
            if want != OK or not states:
                continue
            # the literal map loses every digit here (E_j ~ e**-700): the mpmath step at 40 digits is the reference
            code, ref = _mp_verdict(np.array(p), np.array(qq), l0, m, b, 40)
            with mp.workdps(40):
                for route, xs in states.items():
                    for x, y in zip(xs, ref if code == OK else []):
                        err = float(abs(mp.mpf(float(x)) - y) / (1 + abs(y)))
                        worst = max(worst, err)
                        if not err <= 1e-9:
                            bad.append(f"branch {b}, {route}: {float(x)!r} vs the mpmath step's {mp.nstr(y, 17)}")
            if code != OK:
                bad.append(f"branch {b}: the mpmath step's status {code}")
    detail = f"|dq| = {MAX_DQ_FLOAT64} accepted, one ulp more refused; worst error {worst:.3g} (relative to 1 + |x|)."
    if bad:
        return failed("numeric: the block kernel at the documented largest neighbour distance",
                      detail="; ".join(bad[:6]) + ". " + detail)
    return Outcome("verified", "numeric: the block kernel and bt_step at |dq| = MAX_DQ_FLOAT64 vs the mpmath step "
                   "(40 digits)",
                   evidence="sampled", detail=detail, printed="700 accepted, 700 + ulp refused")
