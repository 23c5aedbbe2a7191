r"""What ships, 4i: nine documented rules of the numeric routes that no accuracy bound shows (scene ``numeric-paths``).

* ``paths.escalation.n3`` -- :func:`symbt.numeric.float64.rows.escalate_rows` (the escalation of every float64
  route) returns the *more precise* of its two agreeing mpmath runs, rounded to float64 (docs/numeric.md,
  "Conditioned decisions and escalation"): the runs agree to ``2**-64 s`` (``s`` the state's scale), so the
  returned run, 20 digits more precise, is off by about ``1e-20`` of that, and every component -- even one far
  below ``s`` -- is the exact map's value correctly rounded.  Checked on one state per branch built so that
  ``q~_1`` is about ``1e-23`` (a cancellation: ``q_1 + log(...)`` with both terms near 1; the states were found
  offline by a root search of the literal map in ``q_1`` and a lattice search in the last bits of ``q_1`` and
  ``p_3``, and the claim checks that the component is that small): every component within
  ``ulp(r_i)/2 + 2**-64 10**-20 s`` of the literal map at 50 digits with guard digits (checked at 75), alone
  and as row 0 of a two-row call whose row 1 is the paper's state (each row decided on its own input).  The
  documented agreement bound alone (``2**-64 s``) admits a ``q~_1`` wrong in its 11th digit.
* ``paths.ball_prec.n3`` -- the plain ball method of :func:`~symbt.numeric.multiprec.certified.certified_orbit`
  (``method="ball"``): a first pass at 64 bits on exact input with target ``1e-60`` stops after its first step
  (its radii already exceed the target by far more than 8 bits), so exactly one excess is finite, and the next
  pass must run at its docstring's rule for that case, ``max(floor(p + e + 24) + 1, p + floor(p/4) + 32)``
  (``e = max_i log2(rad_i / tol)`` of that step).  The radii of that step are read from an independent call at
  the same 64 bits with a target it meets at once (``tol = 1``, one step, at 300 bits of output, where the
  returned radius is the ball's radius exactly): a consistency check -- the schedule decides how many passes
  run, not the rigour of the enclosure, which is also checked (every returned radius <= the target).
* ``paths.range_edge.n2`` -- the float64 kernels' range test at its lower edge (``kernels.py``'s status 4: the
  rescaled monodromy's first row needs an entry *above* ``1e-290``).  At ``p = (1, 0)``, ``q = (0, -389.9)``,
  ``lam0 = mu = lam1 / 2`` with ``lam1 = r_1 - 1e-290 2**400`` (``r_1 = exp(-389.9)``), the first row at
  ``lam1`` is ``(-1e-290, -lam1 2**-400)`` after the exact rescaling by ``2**-400`` -- computed with exact
  rationals from the same doubles, each rounding shown exact -- so both the block kernel and the fused kernel
  (plain Python) must give the state back with ``RANGE``; with ``1e-290`` replaced by the next double, one ulp
  inside, both must finish it (``OK``), bit for bit alike; and likewise at ``q = (0, -345.4)``, ``lam1 = r_1``,
  where ``A = 0`` exactly and ``|B| = r_1 2**-400 ~ 4e-271`` (in range by ``B`` alone).  Branch -1 (at branch 1
  the eigenvector slope overflows at ``q = (0, -389.9)``, a second reason for ``RANGE`` on both sides of the edge).
  The fused kernel's hook ``HOOKS["in_range"]`` is also called directly on the same entries: ``python_orbit`` writes
  it inline, so only a direct call lets ``symbt mutate --source``'s line map see its lines run.
* ``paths.idle_rows.n3`` -- :func:`~symbt.numeric.float64.rows.float_rows_step` with a scalar ``mu = 0`` returns
  its input (docs/numeric.md: ``mu = 0`` is the identity), also at ``lam0`` inside a band, where a step would have
  no real map.
* ``paths.failure_text.n3`` -- :func:`~symbt.numeric.float64.orbit.raise_for_status`' message (its docstring):
  the first five failing members, ``, ...`` exactly when there are more than five, their count.
* ``paths.batch_range.n3`` -- the float64 range limit ``|q_{j+1} - q_j| <= 700`` on batches: ``invariants`` and
  ``phi`` refuse a batch whose one member has a difference of +701 (its others -350.5) with
  ``NumericRangeError``.
* ``paths.existence_iv.n3`` -- :func:`~symbt.numeric.float64.existence.decide_existence` (the escalation's
  interval verdict; no other default claim reaches it): ``OK`` at the paper's state and its mirror (traces of
  both signs), ``POSITIVITY`` at the no-map states of ``shipped.nomap`` (the literal route's decision).
* ``paths.enclosure_poly.n3`` -- :func:`~symbt.numeric.multiprec.lohner_checks.invariant_enclosures` (``tr L`` as
  a ball polynomial; ``paths.enclosures`` checks only their intersection) on an exact box: the literal trace at
  four ``lam`` inside the enclosed polynomial, radii below ``1e-60`` of the trace.

Shown to fail on planted bugs in ``tests/test_killers_numeric2.py``.
"""
from __future__ import annotations

import importlib.util
import math
from fractions import Fraction

import mpmath as mp
import numpy as np

from ._shipped import Tally, scale_parts, scaled, step_ref
from .base import Outcome, Parts, claim, failed, skipped

#: paths.escalation: per branch, a state whose q~_1 cancels to ~1e-23 (p, q, lam0, mu)
ESCALATION_STATES = {
    1: ((-20.0, 10.0, 1.0000000008767729), (1.0856038108756834, 0.0, 0.9), 10.0, 5.0),
    -1: ((-20.0, 10.0, 1.0000000010917003), (-1.080009029320847, 0.0, 0.9), 10.0, 5.0),
}
#: the component that cancels (q~_1: index N in the list p~ + q~) and how small it must be against the scale
TINY_INDEX, TINY_BELOW = 3, 1e-20
#: the accuracy of the returned run beyond rounding: the agreement tolerance 2**-64 s times 10**-20
ESCALATED_SLACK = 2.0 ** -64 * 1e-20
#: the second row of the two-row call: the paper's state (its own lam0, mu: those of the escalated state)
PAPER_STATE = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9))


def _rounded_ratio(xs: list, ref: tuple, l0: float, m: float) -> float:
    """``max_i |x_i - r_i| / (ulp(r_i)/2 + ESCALATED_SLACK s)``, ``s = max(|r|, |lam0| + |mu|)``."""
    with mp.workdps(60):
        s = max(max(abs(v) for v in ref), abs(mp.mpf(l0)) + abs(mp.mpf(m)))
        return max(float(abs(mp.mpf(x) - r) / (mp.mpf(math.ulp(float(r))) / 2 + ESCALATED_SLACK * s))
                   for x, r in zip(xs, ref))


@claim("paths.escalation", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/float64/rows.py: escalate_rows (the escalation's result: the more precise run, rounded)",
       statement="escalate_rows, N={N}, one state per branch whose q~_1 cancels to ~1e-23 of the scale s, alone and "
                 "as row 0 of two (row 1 the paper's state): every "
                 "component within ulp(r_i)/2 + 2**-64 10**-20 s of the literal map r (the more precise of the two "
                 "agreeing mpmath runs, correctly rounded)")
def escalation(N: int, parts: Parts) -> Outcome:
    from ..numeric.float64.rows import escalate_rows

    tally, sc = Tally(), parts.printed["scale"]
    for b, st in ESCALATION_STATES.items():
        p, q, l0, m = st
        ref = step_ref(st, b)
        with mp.workdps(60):
            s = max(max(abs(v) for v in ref.x), abs(mp.mpf(l0)) + abs(mp.mpf(m)))
            tiny = abs(ref.x[TINY_INDEX]) / s
        if not tiny < TINY_BELOW:
            return failed("numeric: escalate_rows vs the literal map",
                          detail=f"branch {b}: |q~_1| / s = {float(tiny):.3g}, not below {TINY_BELOW:g}: the claim's "
                                 "premise (a component far below the agreement tolerance) fails")
        # alone, and as row 0 of two with the paper's state (each row is decided on its own input)
        other = (PAPER_STATE[0], PAPER_STATE[1], l0, m)
        for rows_in in ([st], [st, other]):
            pt, qt, status = escalate_rows(np.array([r[0] for r in rows_in]), np.array([r[1] for r in rows_in]),
                                           l0, m, b)
            for k, row in enumerate(rows_in):
                cell = {"branch": b, "rows": len(rows_in), "row": k}
                rref = ref if k == 0 else step_ref(row, b)
                if int(status[k]) != 0:
                    tally.notes.append(f"branch {b}, row {k} of {len(rows_in)}: status {int(status[k])}, not OK.")
                    tally.add("escalate_rows", cell, row, b, math.inf)
                    continue
                xs = scaled([float(v) for v in list(pt[k]) + list(qt[k])], sc)
                tally.add("escalate_rows", cell, row, b, _rounded_ratio(xs, rref.x, l0, m), 0.0, rref.agree)
    return tally.outcome(method="numeric: escalate_rows vs the literal map (50 digits, checked at 75)",
                         printed="|x_i - r_i| <= ulp(r_i)/2 + 2**-64 1e-20 s")


#: paths.ball_prec: the state (exact binary numbers), the forced first precision, the target, the steps
BALL_STATE = ((-20, 10, 1), (1, 0, 0.9), 10, 5)
BALL_FIRST, BALL_TOL, BALL_STEPS, BALL_OUT_BITS = 64, 1e-60, 3, 300


def ball_rule(prec: int, e: float) -> int:
    """The ball method's next precision after a pass with one finite excess ``e`` (certified.py's docstring).

    >>> ball_rule(64, 140.4), ball_rule(64, 1.0)          # the rule, and its floor p + p/4 + 32
    (229, 112)
    """
    return max(int(prec + e + 24) + 1, prec + prec // 4 + 32)


@claim("paths.ball_prec", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/certified.py: the ball method's precision schedule (_next_prec)",
       statement="certified_orbit(method='ball') on the paper's state (N={N}, exact input), 3 steps, target 1e-60, "
                 "first pass forced to 64 bits (it stops after one step: one finite excess e): the second pass runs "
                 "at max(floor(64 + e + 24) + 1, 64 + 16 + 32) (its docstring's rule; e from the radii of the same "
                 "64-bit step, returned by an independent call) and every returned radius meets the target; with no "
                 "prec the first pass runs at mp.prec + 32")
def ball_precision(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from ..numeric.multiprec.certified import certified_orbit

    p, q, l0, m = BALL_STATE
    with mp.workprec(BALL_OUT_BITS):
        first: dict[str, object] = {}
        _, _, Pr, Qr = certified_orbit(p, q, l0, m, 1, method="ball", prec=BALL_FIRST, tol=1.0, info=first)
        info: dict[str, object] = {}
        _, _, Pr3, Qr3 = certified_orbit(p, q, l0, m, BALL_STEPS, method="ball", prec=BALL_FIRST, tol=BALL_TOL,
                                         info=info)
        default: dict[str, object] = {}      # no prec given: the first pass at mp.prec + 32 (the docstring)
        certified_orbit(p, q, l0, m, 1, method="ball", tol=1.0, info=default)
    radii = [float(r) for r in list(Pr[-1]) + list(Qr[-1]) if r != 0]
    e = max(math.log2(r) - math.log2(BALL_TOL) for r in radii)
    want = ball_rule(BALL_FIRST, e)
    passes = list(info["passes"])  # type: ignore[call-overload]
    bad = []
    if first.get("passes") != [BALL_FIRST]:
        bad.append(f"the one-step call at tol = 1 ran passes {first.get('passes')}, not one pass at {BALL_FIRST}")
    if not (e > 8 and want > BALL_FIRST + BALL_FIRST // 4 + 32):
        bad.append(f"excess {e:.3g} bits after the first step: the case (one finite excess above the floor) is "
                   "not reached")
    if list(default.get("passes", []))[:1] != [BALL_OUT_BITS + 32]:  # type: ignore[call-overload]
        bad.append(f"with no prec the first pass ran at {default.get('passes')}, not mp.prec + 32 = "
                   f"{BALL_OUT_BITS + 32}")
    if passes[:2] != [BALL_FIRST, want]:
        bad.append(f"passes {passes}, the documented rule gives {want} after {BALL_FIRST} (excess {e:.3g})")
    if not all(r <= BALL_TOL for r in list(Pr3[-1]) + list(Qr3[-1])):
        bad.append("the returned orbit does not meet the target radius")
    detail = f"first step at {BALL_FIRST} bits: excess {e:.4g} bits; passes {passes}."
    if bad:
        return failed("numeric: the ball method's schedule vs its documented rule",
                      detail="; ".join(bad) + " " + detail)
    return Outcome("verified", "numeric: the ball method's schedule vs its documented rule (consistency)",
                   evidence="sampled", detail=detail, printed="the second pass at the documented precision")


#: paths.range_edge: the neighbour distances q_2 - q_1 (r_1 = exp of the first lies in (T, 2T), T = 1e-290 2**400;
#: of the second near 1e-150, so that 2**-400 r_1 lies between 1e-290 and 1e-145)
EDGE_DQ, EDGE_DQ_ZERO = -389.9, -345.4
#: the kernels' range limit of a monodromy entry and the power of two the monodromy is rescaled by (kernels.py)
EDGE_LIMIT, EDGE_SHRINK_BITS = 1e-290, 400
#: the branch: its eigenvector slope is the root -2C/k, finite here (at branch 1 the slope k/(2B) overflows at
#: EDGE_DQ, so both kernels give that state back for that reason too, on either side of the edge)
EDGE_BRANCH = -1


def edge_row(lam1: float, dq: float) -> tuple[Fraction, Fraction, Fraction, bool]:
    """The first row ``(A, B)`` of the N = 2 monodromy ``m_2 m_1`` at ``lam1`` for ``p = (1, 0)``, ``q = (0, dq)``,
    computed as the kernels document it (``r_1 = exp(dq)`` rounded once, ``a_j = lam1 + p_j`` rounded once, each
    product and difference rounded once), then rescaled by ``2**-400``, as exact rationals; the second-row product
    ``r_2 |a_1|`` that triggers the rescaling; and whether every rounding on the way is exact (``a_1 = 1``,
    ``a_2 = lam1``, ``lam1 a_1 - r_1`` representable).

    >>> name, dq, lam1, inside = edge_states()[0]
    >>> A, B, big, exact = edge_row(lam1, dq)
    >>> float(A), abs(B) < 1e-290, exact
    (-1e-290, True, True)
    """
    r1, r2 = math.exp(dq), math.exp(-dq)
    a1, a2 = lam1 + 1.0, lam1 + 0.0
    A = a2 * a1 - r1                     # fl(fl(a2 a1) - r_1)
    exact = a1 == 1.0 and a2 == lam1 and Fraction(A) == Fraction(lam1) - Fraction(r1)
    scale = Fraction(1, 2 ** EDGE_SHRINK_BITS)
    return Fraction(A) * scale, Fraction(-a2) * scale, Fraction(r2) * Fraction(a1), exact


def edge_states() -> list[tuple[str, float, float, bool]]:
    """``(name, dq, lam1, in range)``: ``lam1 = r_1 - T`` puts the rescaled ``A`` at ``-1e-290`` exactly (the edge:
    not above the limit, ``|B| < 1e-290`` too: out of range); ``r_1 - T'``, ``T'`` the next double's multiple, one
    ulp above (in range); ``lam1 = r_1`` at ``EDGE_DQ_ZERO``: ``A = 0`` and ``1e-290 < |B| <= 1e-145`` (in range by
    ``B`` alone).

    >>> [(name, inside) for name, _, _, inside in edge_states()]
    [('at the edge', False), ('one ulp inside', True), ('A = 0, B above the edge', True)]
    """
    r1 = math.exp(EDGE_DQ)
    T = math.ldexp(EDGE_LIMIT, EDGE_SHRINK_BITS)
    T_in = math.ldexp(math.nextafter(EDGE_LIMIT, 1.0), EDGE_SHRINK_BITS)
    return [("at the edge", EDGE_DQ, r1 - T, False), ("one ulp inside", EDGE_DQ, r1 - T_in, True),
            ("A = 0, B above the edge", EDGE_DQ_ZERO, math.exp(EDGE_DQ_ZERO), True)]


@claim("paths.range_edge", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(2,),
       where="symbt/numeric/float64/kernels_block.py, kernels.py: the range test's lower edge (in_range)",
       statement="the block and the fused kernel (plain Python), N={N}, p = (1, 0), q = (0, -389.9), lam0 = mu = "
                 "lam1/2, branch -1: where the rescaled monodromy's first row is (-1e-290, b), |b| < 1e-290 "
                 "exactly (exact rationals), both report RANGE (the documented rule: an entry above 1e-290 is "
                 "needed); one ulp inside, and where A = 0 and 1e-290 < |b| <= 1e-145 (q = (0, -345.4), lam1 = r_1), "
                 "both finish the state, bit for bit alike")
def range_edge(N: int) -> Outcome:
    from ..numeric.core.limits import OK, RANGE
    from ..numeric.float64.jit import kernel
    from ..numeric.float64.kernels import ANCHOR, HOOKS, python_orbit

    ensemble, _ = kernel("ensemble", "python")
    in_range = HOOKS["in_range"]      # the fused kernel's hook itself (python_orbit writes it inline)
    bad, seen = [], []
    limit = Fraction(EDGE_LIMIT)
    for name, dq, lam1, inside in edge_states():
        A, B, big, exact = edge_row(lam1, dq)
        rule_in = abs(A) > limit or abs(B) > limit
        if not (exact and big > 2 ** EDGE_SHRINK_BITS and rule_in == inside and abs(B) <= Fraction(1e-145)):
            bad.append(f"{name}: the construction does not hold (A = {float(A):.17g}, B = {float(B):.3g}, "
                       f"exact {exact})")
            continue
        if bool(in_range(float(A), float(B), 1.0, -1.0, 0.0)) != inside:
            bad.append(f"{name}: the fused kernel's hook in_range({float(A):.17g}, {float(B):.3g}, 1, -1) says "
                       f"{not inside}")
        for b in (EDGE_BRANCH,):
            p0, q0 = np.array([[1.0, 0.0]]), np.array([[0.0, dq]])
            P, Q, st = np.empty((2, 1, N)), np.empty((2, 1, N)), np.zeros(1, np.int64)
            Pf, Qf = np.empty((2, N)), np.empty((2, N))
            with np.errstate(all="ignore"):
                ensemble(p0, q0, np.array([lam1]), np.array([0.0]), np.array([lam1]), b, 1, 1, ANCHOR, 8, P, Q, st)
                fused = python_orbit(p0[0], q0[0], lam1, 0.0, lam1, b, 1, 1, ANCHOR, Pf, Qf)
            block = int(st[0])
            seen.append(f"{name}, branch {b}: block {block}, fused {fused}")
            want = OK if inside else RANGE
            if block != want or fused != want:
                bad.append(f"{name}, branch {b}: block kernel status {block}, fused kernel {fused}, the rule gives "
                           f"{want}")
            elif inside and not (np.array_equal(P[1, 0], Pf[1]) and np.array_equal(Q[1, 0], Qf[1])):
                bad.append(f"{name}, branch {b}: the two kernels' states differ")
    detail = "; ".join(seen) + "."
    if bad:
        return failed("numeric: the kernels' range test at its lower edge vs the documented rule (exact rationals)",
                      detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: the kernels' range test at its lower edge vs the documented rule "
                   "(exact rationals)", evidence="sampled", detail=detail,
                   printed="RANGE at |A| = 1e-290 exactly, finished one ulp above")



#: paths.idle_rows: lam0 inside a band of the paper's state (|tr L(-10.28)| = 0.48) and in a gap
IDLE_LAMS = (-10.28, 15.0)


@claim("paths.idle_rows", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts,
       where="symbt/numeric/float64/rows.py: float_rows_step with a scalar mu = 0 (no row is stepped)",
       statement="float_rows_step (the numpy rows), N={N}, a batch of three states with a scalar mu = 0 at lam0 "
                 "inside a band (where a step would have no real map) and in a gap, both branches: the input "
                 "itself, bit for bit, no error (docs/numeric.md: mu = 0 is the identity)")
def idle_rows(N: int, parts: Parts) -> Outcome:
    from ..numeric.float64.rows import float_rows_step
    from ..reference.literal import literal_trace

    pa = np.array([[-20.0, 10.0, 1.0], [-1.0, 2.0, 0.5], [3.0, -4.0, 0.25]])
    qa = np.array([[1.0, 0.0, 0.9], [0.0, 0.3, -0.2], [2.0, 1.0, 0.0]])
    bad, seen = [], []
    with mp.workdps(30):
        band = abs(literal_trace(mp.mpf(IDLE_LAMS[0]), pa[0].tolist(), qa[0].tolist())) < 2
    if not band:
        bad.append(f"lam0 = {IDLE_LAMS[0]} is not inside a band of the first state: the premise fails")
    for l0 in IDLE_LAMS:
        for b in (1, -1):
            try:
                pt, qt = float_rows_step(pa.copy(), qa.copy(), l0, 0.0, b, False, (3,))
            except (ArithmeticError, ValueError) as exc:
                bad.append(f"lam0 {l0}, branch {b}: {type(exc).__name__}: {str(exc)[:100]}")
                continue
            sc = parts.printed["scale"]      # outputs x scale = input (symbt mutate perturbs the scale)
            same = np.array_equal(pt * sc, pa) and np.array_equal(qt * sc, qa)
            seen.append(f"lam0 {l0}, branch {b}: {'the input' if same else 'changed'}")
            if not same:
                bad.append(f"lam0 {l0}, branch {b}: the result differs from the input")
    detail = "; ".join(seen) + "."
    if bad:
        return failed("numeric: float_rows_step at mu = 0 vs the identity", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: float_rows_step at mu = 0 vs the identity (the input)", evidence="sampled",
                   detail=detail, printed="the input, bit for bit")


@claim("paths.failure_text", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/orbit.py: raise_for_status (the message of a failed ensemble)",
       statement="raise_for_status on 8 members of which 7, 5 or 6 have no real map (N={N}): NoRealMapError whose "
                 "message names the first five failing members, ', ...' exactly when there are more than five, "
                 "and their count (its docstring), where = every failing member")
def failure_text(N: int) -> Outcome:
    from ..numeric.core.errors import NoRealMapError
    from ..numeric.core.limits import OK, POSITIVITY
    from ..numeric.float64.orbit import raise_for_status

    bad, seen = [], []
    for k in (5, 6, 7):
        status = np.array([POSITIVITY] * k + [OK] * (8 - k), np.int64)
        steps = np.full(8, 2, np.int64)
        members = [(i,) for i in range(k)]
        want = "(at step 2; batch index %s%s; %d state(s) in all)" % (
            ", ".join(str(m) for m in members[:5]), ", ..." if k > 5 else "", k)
        try:
            raise_for_status(status, steps, (8,))
            bad.append(f"{k} failing members: nothing raised")
            continue
        except NoRealMapError as exc:
            text, where = str(exc), tuple(exc.where)
        seen.append(f"{k}: ...{text[-60:]}")
        if not text.endswith(want) or where != tuple(members):
            bad.append(f"{k} failing members: message ends {text[-80:]!r}, want {want!r}; where {where}")
    detail = "; ".join(seen)
    if bad:
        return failed("numeric: raise_for_status' message vs its docstring", detail="; ".join(bad))
    return Outcome("verified", "numeric: raise_for_status' message vs its docstring", evidence="sampled",
                   detail=detail, printed="the first five members, ', ...' beyond five, the count")


#: paths.batch_range: a batch whose first member has q_2 - q_1 = 701 > MAX_DQ_FLOAT64 = 700 (and no neighbour
#: difference below -700: the positive side alone is past the limit) and a moderate second member
RANGE_P = ((1.0, -0.5, 0.2), (0.3, 0.1, -0.4))
RANGE_Q = ((0.0, 701.0, 350.5), (0.0, 0.0, 0.0))


@claim("paths.batch_range", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/core/monodromy.py: neighbour_ratios' float64 range test on batches",
       statement="invariants and phi on a batch (N={N}) whose first member has q_2 - q_1 = 701 (its other neighbour "
                 "differences -350.5, -350.5) and whose second is moderate: NumericRangeError (the documented limit "
                 "|q_{j+1} - q_j| <= 700, tested on every member); the moderate member alone: finite")
def batch_range(N: int) -> Outcome:
    from ..numeric import invariants, phi
    from ..numeric.core.errors import NumericRangeError

    P, Q = np.array(RANGE_P), np.array(RANGE_Q)
    bad, seen = [], []
    for name, fn in (("invariants", lambda p, q: invariants(p, q)), ("phi", lambda p, q: phi(p, q, 10.0, 5.0))):
        try:
            fn(P, Q)
            bad.append(f"{name}: the batch with |q_2 - q_1| = 701 returned a result")
        except NumericRangeError:
            seen.append(f"{name}: NumericRangeError")
        with np.errstate(all="ignore"):
            alone = np.asarray(fn(P[1:], Q[1:]), dtype=float)
        if not np.all(np.isfinite(alone)):
            bad.append(f"{name}: the moderate member alone is not finite")
    detail = "; ".join(seen) + "."
    if bad:
        return failed("numeric: the batch range test vs the documented limit", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: the batch range test vs the documented limit |q_{j+1} - q_j| <= 700",
                   evidence="sampled", detail=detail, printed="NumericRangeError for the batch")


#: paths.existence_iv: a state without a real map whose Etilde_j (-0.23, -0.015, 0.012) are near 0
NEAR_EDGE = ((-4.82, 2.88, -1.34), (0.47, -2.95, -2.72), -5.11, 3.82)


@claim("paths.existence_iv", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/existence.py: decide_existence (the escalation's interval verdict)",
       statement="decide_existence (interval arithmetic, 256 bits up), N={N}: OK at the paper's state (traces "
                 "-2021, -1332: both negative) and at its mirror p -> -p, lam0 -> -lam0 (traces positive), both "
                 "branches; the no-real-map status (POSITIVITY) at the states without a real map of shipped.nomap, "
                 "as the literal route decides them (50 digits with guard digits), also through escalate_rows with "
                 "the paper's state as a second row (whose status is its own, as alone); POSITIVITY near the "
                 "positivity edge (a state whose Etilde_j are -0.23, -0.015, 0.012 by the literal route)")
def existence_iv(N: int) -> Outcome:
    from ..numeric.core.limits import OK, POSITIVITY
    from ..numeric.float64.existence import decide_existence
    from ._shipped import literal_state
    from .shipped_emitted import _no_map, nomap_states

    paper = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 10.0, 5.0)
    mirror = ((20.0, -10.0, -1.0), (1.0, 0.0, 0.9), -10.0, -5.0)
    cases = [(st, b, OK, name) for name, st in (("paper", paper), ("mirror", mirror)) for b in (1, -1)]
    cases += [(st, b, POSITIVITY, "no map (%s)" % (cond[0] if isinstance(cond, tuple) else cond))
              for st, b, cond in nomap_states(N)]
    bad, seen = [], []
    if N == 3:          # seed 23: the seeded states' Etilde_j are far below 0; a halved 2 mu in the test missed this
        cases.append((NEAR_EDGE, 1, POSITIVITY, "near the positivity edge"))
        # the premise, by the literal route: no real map for E~ <= 0, and the smallest E~_j in (-1, 0] (a test with
        # 2 mu halved says OK wherever every E~_j > -1)
        smallest = min(literal_state(NEAR_EDGE, 1)[2]["E_new"])
        if _no_map(NEAR_EDGE, 1) != ("E~ <= 0", True) or not -1 < smallest <= 0:
            bad.append(f"the literal route finds {_no_map(NEAR_EDGE, 1)} at the near-edge state, smallest E~_j "
                       f"{mp.nstr(smallest, 5)}: want E~ <= 0, the smallest in (-1, 0]")
    for st, b, want, name in cases:
        got, bits = decide_existence(np.array(st[0]), np.array(st[1]), float(st[2]), float(st[3]), b)
        seen.append(f"{name}, branch {b}: {got} at {bits} bits")
        if got != want:
            bad.append(f"{name}, branch {b}: verdict {got}, want {want}")
    # through the escalation of a two-row batch: the no-map state first, the paper's state (at that lam0, mu) after
    # it -- each row's verdict its own (rows.py: a row's result never depends on the other rows)
    from ..numeric.float64.rows import escalate_rows
    for st, b, _ in nomap_states(N):
        P, Q = np.array([st[0], paper[0]]), np.array([st[1], paper[1]])
        _, _, both = escalate_rows(P, Q, float(st[2]), float(st[3]), b)
        _, _, alone = escalate_rows(P[1:], Q[1:], float(st[2]), float(st[3]), b)
        if (int(both[0]), int(both[1])) != (POSITIVITY, int(alone[0])):
            bad.append(f"escalate_rows of [no map, paper's state] at lam0 = {st[2]}, branch {b}: statuses "
                       f"{both.tolist()}, want [{POSITIVITY}, {int(alone[0])}] (the second row alone)")
    detail = "; ".join(seen) + "; escalate_rows of two-row batches: each row's own verdict."
    if bad:
        return failed("numeric: decide_existence vs the literal route's decision", detail="; ".join(bad) + ". "
                      + detail)
    return Outcome("verified", "numeric: decide_existence vs the literal route's decision", evidence="sampled",
                   detail=detail, printed="OK where the map exists, POSITIVITY where it does not")


#: paths.enclosure_poly: where the enclosed trace polynomial is compared with the literal trace
POLY_LAMS = (-3.0, 0.5, 7.0, -12.0)


@claim("paths.enclosure_poly", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/lohner_checks.py: invariant_enclosures (tr L as a ball polynomial)",
       statement="invariant_enclosures of the paper's state as an exact box (N={N}, radius 0, 256 bits): "
                 "lam**N + sum_k H_k lam**k contains the literal trace tr L(lam) (60 digits) at lam = -3, 0.5, 7, "
                 "-12, every radius below 1e-60 of max(1, |tr|)")
def enclosure_poly(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from flint import arb

    from ..numeric.multiprec.arb import flint_prec
    from ..numeric.multiprec.lohner_checks import invariant_enclosures
    from ..reference.literal import literal_trace

    p, q = [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9]
    zero = [mp.mpf(0)] * N
    H = invariant_enclosures([[mp.mpf(v) for v in p]], [[mp.mpf(v) for v in q]], [zero], [zero])[0]
    bad, worst = [], 0.0
    for lam in POLY_LAMS:
        with flint_prec(256):
            val = arb(lam) ** N + sum((H[k] * arb(lam) ** k for k in range(N)), arb(0))
        with mp.workdps(60):
            lit = literal_trace(mp.mpf(lam), p, q)
            mid, rad = mp.mpf(val.mid().str(70, radius=False)), mp.mpf(val.rad().str(10, radius=False))
            scale = max(1, abs(lit))
            off = abs(mid - lit)
            worst = max(worst, float(off / scale))
            if not (off <= rad + scale * mp.mpf(10) ** -55 and rad <= scale * mp.mpf(10) ** -60):
                bad.append(f"lam {lam}: enclosure {mp.nstr(mid, 20)} +- {mp.nstr(rad, 3)}, literal "
                           f"{mp.nstr(lit, 20)}")
    detail = f"worst |mid - tr| / max(1, |tr|) = {worst:.3g} at {len(POLY_LAMS)} points."
    if bad:
        return failed("numeric: invariant_enclosures vs the literal trace", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: invariant_enclosures vs the literal trace (60 digits)", evidence="sampled",
                   detail=detail, printed="the literal trace inside the enclosed polynomial")
