r"""What ships, 4c: the Lohner method's Jacobian and its sharpness on a box (scene ``numeric-paths``, issue 21).

The certified orbit's stored enclosure is the Lohner set intersected with the plain ball image of the step
(:mod:`symbt.numeric.multiprec.lohner`, step 4): a wrong Jacobian or a lost term of the set stays rigorous
through that intersection, and only loses the sharpness the method exists for.  These claims look at the two
things the intersection hides, each against central differences of the literal map of
:mod:`symbt.reference.literal` (which shares nothing with the slopes' implicit relations):

* ``paths.jacobian.n3`` -- :func:`~symbt.numeric.multiprec.lohner.step_jacobian` at a point (exact balls, 200
  bits), one state per cell ``{branch, sign_mu, sign_tr}``: every entry of the enclosure is within its radius
  plus the central differences' error of ``(f(x + h e_k) - f(x - h e_k)) / 2h`` (literal map at 60 digits,
  ``h = 1e-20``: truncation ``h**2 |f'''| / 6`` and rounding ``10**-60 |f| / h``, both ~1e-40; accepted below
  :data:`FD_TOL` = 1e-36, a margin of 1e4 for ``|f'''|``, ``|f|`` up to 1e3), and its radius is below
  ``2**-150`` (an enclosure at 200 bits that lost more than 50 bits is not the sharp one documented).
* ``paths.lohner_box.n3`` -- a :class:`~symbt.numeric.multiprec.lohner.LohnerSet` started from the box of
  radius ``rho = 1e-30`` around a state, 20 steps: the true image of the box has half-width
  ``W_i = rho sum_k |D_ik|`` to first order (``D`` the Jacobian of the 20-step literal map, central differences
  as above; the second-order terms are ``O(rho)`` relative, 1e-30), so an enclosure has ``rad_i >= W_i`` (less
  the differences' relative error, below 1e-15: :data:`BOX_LOW`).  The upper bound is the method's own
  conditioning (:func:`box_high`).  The set is ``xh + C r0 + B r``: ``C`` the exact product of the steps'
  midpoint Jacobians (rounded at ``jac_prec`` = 96 bits, relative ``2**-96`` per step), ``r0`` the input box,
  ``r`` the 200-bit roundings of the centre steps (``n 2**-200 |x|``, 1e-29 of ``W`` here) and the wrapping of
  the Jacobian's width over the box (second order: ``O(rho)`` relative).  The Lohner update does not grow the
  width beyond first order -- ``C r0`` is recomputed from exact matrices at every step, only ``r`` is carried
  -- so what remains is the radius arithmetic of the read-out: Arb keeps radii as 30-bit ``mag_t`` rounded
  upward, each operation at most ``2**-30`` relative.  A coordinate's radius goes through the box's
  conversion from decimal (3 roundings: measured ``2.2 * 2**-30`` for ``1e-30``), ``|C_ik|`` as a ``mag`` and
  its product with ``rho`` (2), the ``2N - 1`` additions of the row, ``B r`` added (1), the centre added
  (1), the intersection's re-centring (2) and the dot product's final bound (1): ``2N + 10`` roundings,
  doubled for the operations whose internal rounding count was not audited (``arb_dot``, the intersection):
  ``rad_i / W_i <= (1 + 2**-30) ** (4N + 20) + 1e-15`` = 1 + 3.0e-8 at N = 3 (:data:`BOX_HIGH`; measured
  1 + 6.2e-9 to 1 + 1.4e-8 for 1 to 80 steps and ``rho`` from 1e-35 to 1e-25, independent of both, as
  derived).  The plain ball path, which the intersection falls back to, is wider by about 2 bits per step,
  ``2**40`` here.  The centre is within ``rad_i`` of the literal orbit of the box's centre.
* ``paths.frame_inverse.n13`` -- :func:`~symbt.numeric.multiprec.lohner.frame_inverse` of an exact frame ``B``
  of size ``2N = 26`` (above the size where it uses its one-product bound instead of Arb's ``inv``), with its
  default approximate inverse ``X = B^T``: a random orthogonal frame and one near ``-I`` (every large entry
  negative), rounded to doubles.  Its docstring's lemma: with ``d = max_i sum_j |(X B - I)_ij| < 1/2`` every
  entry of ``B^-1 - X`` is at most ``beta d / (1 - d)``, ``beta = max |X_ij|``.  Against ``d`` and ``beta``
  computed *exactly* (rational arithmetic on the doubles, :mod:`fractions`): the midpoints are ``X`` and every
  radius is at least ``beta d / (1 - d)`` (less would not be the lemma's enclosure) and at most
  ``beta (d + e) / (1 - d - e) (1 + 2**-30)**8`` with ``e = 2 n**2 2**-96`` (``X B - I`` evaluated in balls at
  96 bits: each of the ``n`` products of a row's ``n`` entries rounds by ``2**-96`` of at most 1, mid and
  radius; the radius' own ``mag_t`` arithmetic rounds upward by ``2**-30`` per operation, a few operations).
* ``paths.next_prec.n3`` -- the precision schedule of :func:`~symbt.numeric.multiprec.lohner.lohner_certified`:
  a first pass forced too low (135 bits for a 1e-40 target, 60 steps of the paper's state) fails after ``i``
  steps, and the second pass must run at the precision its docstring states -- the excess so far ``e`` plus 1.5
  times the fitted degree ``g`` times ``log2(n / i)`` plus 16 bits, at least 32 bits more:
  ``max(floor(p + e + 1.5 g log2(n / i) + 16) + 1, p + 32)`` -- with ``e``, ``i`` and the radii read off the
  same first pass run by :func:`~symbt.numeric.multiprec.lohner.lohner_pass` and ``g`` fitted by
  :func:`~symbt.numeric.multiprec.lohner.growth_law` over the steps done (a consistency check of the code with
  its documented rule: the schedule changes only how many passes a certified orbit takes, never its rigour);
  and the orbit it returns meets the target.

* ``paths.lohner_unsound.n3`` -- the checker of certified orbits checked: the Lohner passes
  (:func:`~symbt.numeric.multiprec.lohner.lohner_pass`, both frames) of the paper's state, 40 steps at 160 bits,
  contain the literal orbit at 300 digits at every stored step, and the deliberately unsound variant
  (``unsound=True``: the rounding errors and the Jacobian's radius dropped, no intersection with the ball image)
  misses it at every step taken -- so a containment test that passes is not passing by default.
* ``paths.ball_schedule.n3`` -- the plain ball path's precision schedule
  (:func:`~symbt.numeric.multiprec.certified.certified_orbit` with ``method="ball"``): first passes forced low so
  that they stop early, at step 1, at step 2 and at the last step, from an inexact and an exact input (whose first
  excess is ``-inf``); the second pass (``info["passes"]``) must run at the precision of the stated rule computed
  from the same first pass's excess history (a consistency check of the code with its rule, as ``paths.next_prec``
  for the Lohner path), and the radii meet the target plus the rounding of the returned midpoints.

Shown to fail on planted bugs in ``tests/test_killers_numeric.py``.
"""
from __future__ import annotations

import importlib.util
from typing import Any

import mpmath as mp

from ._shipped import scale_parts, ship_cells
from .base import Outcome, Parts, claim, failed, skipped

#: central differences: step, digits, and the accepted difference to the enclosure (module docstring)
FD_H, FD_DPS, FD_TOL = "1e-20", 60, 1e-36
#: paths.jacobian: the working precision (bits) and the largest radius accepted (log2)
JAC_PREC, JAC_LOG2_RAD = 200, -150
#: paths.lohner_box: the box radius, the steps, and the lower end of the accepted band of rad_i / W_i
BOX_RHO, BOX_STEPS, BOX_LOW = "1e-30", 20, 1 - 1e-15
#: one rounding of Arb's radius arithmetic (``mag_t``: 30 bits, rounded upward)
MAG_U = 2.0 ** -30


def box_high(N: int) -> float:
    """The upper end of the accepted band of ``rad_i / W_i`` (module docstring: ``4N + 20`` radius roundings).

    >>> round((box_high(3) - 1) / MAG_U)
    32
    """
    return (1 + MAG_U) ** (4 * N + 20) + 1e-15


#: the upper end at the claim's size N = 3
BOX_HIGH = box_high(3)


def _flat(P: Any, Q: Any) -> list:
    return list(P) + list(Q)


def _mid(x: Any) -> mp.mpf:
    """The midpoint of an Arb ball as an mpf at the current precision (exact to 70 digits)."""
    return mp.mpf(x.mid().str(70, radius=False))


def _fd_jacobian(f: Any, x0: list, h: mp.mpf) -> list[list[mp.mpf]]:
    """``D[i][k] = (f(x0 + h e_k) - f(x0 - h e_k)) / 2h`` (at the caller's precision)."""
    cols = []
    for k in range(len(x0)):
        xp, xm = list(x0), list(x0)
        xp[k] += h
        xm[k] -= h
        fp, fm = f(xp), f(xm)
        cols.append([(a - b) / (2 * h) for a, b in zip(fp, fm)])
    return [[cols[k][i] for k in range(len(x0))] for i in range(len(x0))]


def _literal_orbit(N: int, lam0: Any, mu: Any, b: int, n: int) -> Any:
    from ..reference.literal import literal_step

    def f(x: list) -> list:
        P, Q = x[:N], x[N:]
        for _ in range(n):
            P, Q, _ = literal_step(P, Q, mp.mpf(lam0), mp.mpf(mu), b)
        return _flat(P, Q)
    return f


@claim("paths.jacobian", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts, requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: step_jacobian (the slopes' implicit relations, the read-out)",
       statement="step_jacobian at a point (200 bits), N={N}, one state per branch x sign_mu x sign_tr cell, "
                 "encloses the central differences (h = 1e-20) of the literal map at 60 digits within 1e-36, "
                 "with radii below 2^-150")
def jacobian_enclosure(N: int, parts: Parts) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    import flint
    from flint import arb

    from ..numeric.multiprec.arb import flint_prec
    from ..numeric.multiprec.lohner import step_jacobian

    worst, widest, bad = mp.mpf(0), 0.0, []
    for cell, st, b in ship_cells(N, 1):
        p, q, l0, m = st
        with flint_prec(JAC_PREC):
            _, J = step_jacobian([arb(v) for v in _flat(p, q)], arb(l0), arb(m), b)
        with mp.workdps(FD_DPS):
            D = _fd_jacobian(_literal_orbit(N, l0, m, b, 1), [mp.mpf(v) for v in _flat(p, q)], mp.mpf(FD_H))
            for i in range(2 * N):
                for k in range(2 * N):
                    off = abs(_mid(J[i, k]) * parts.printed["scale"] - D[i][k]) - mp.mpf(J[i, k].rad())
                    widest = max(widest, float(J[i, k].rad()))
                    worst = max(worst, off)
                    if not off <= FD_TOL * max(1, abs(D[i][k])):
                        bad.append(f"{cell}: J[{i},{k}] = {_mid(J[i, k])!s:.12} vs differences {mp.nstr(D[i][k], 12)}")
    if not widest <= 2.0 ** JAC_LOG2_RAD:
        bad.append(f"largest radius {widest:.3g} > 2^{JAC_LOG2_RAD}")
    detail = (f"{len(ship_cells(N, 1))} cells; largest |mid J - differences| beyond the radius "
              f"{mp.nstr(worst, 3)}, largest radius {widest:.3g} (flint {flint.__version__}).")
    if bad:
        return failed("numeric: step_jacobian vs central differences of the literal map",
                      detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: step_jacobian vs central differences of the literal map at 60 digits",
                   evidence="sampled", detail=detail, printed="step_jacobian encloses the Jacobian of the step")


@claim("paths.lohner_box", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       parts=scale_parts, requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: LohnerSet (the set xh + C r0 + B r of a box input)",
       statement="LohnerSet from the box of radius 1e-30 around a state (N={N}, 200 bits), 20 steps: every "
                 "radius is within [1 - 1e-15, (1 + 2^-30)^(4N + 20) + 1e-15] of the first-order half-width "
                 "rho sum_k |D_ik| of the box's image (D: central differences of the 20-step literal map), and "
                 "the centre within it of the literal orbit")
def lohner_box(N: int, parts: Parts) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from flint import arb

    from ..numeric.multiprec.arb import flint_prec
    from ..numeric.multiprec.lohner import LohnerSet

    cell, st, b = ship_cells(N, 1)[0]
    p, q, l0, m = st
    with flint_prec(JAC_PREC):
        S = LohnerSet([arb(v, BOX_RHO) for v in _flat(p, q)])
        for _ in range(BOX_STEPS):
            S.step(arb(l0), arb(m), b)
        hull = list(S.hull)
    bad, lo, hi = [], mp.inf, mp.mpf(0)
    with mp.workdps(FD_DPS):
        f = _literal_orbit(N, l0, m, b, BOX_STEPS)
        x0 = [mp.mpf(v) for v in _flat(p, q)]
        D = _fd_jacobian(f, x0, mp.mpf(FD_H))
        f0 = f(x0)
        for i in range(2 * N):
            W = mp.mpf(BOX_RHO) * mp.fsum(abs(d) for d in D[i])
            rad = mp.mpf(hull[i].rad())
            ratio = rad / W
            lo, hi = min(lo, ratio), max(hi, ratio)
            if not BOX_LOW <= ratio <= box_high(N):
                bad.append(f"coordinate {i}: radius / first-order width = {mp.nstr(ratio, 12)}")
            if not abs(_mid(hull[i]) * parts.printed["scale"] - f0[i]) <= rad:
                bad.append(f"coordinate {i}: the centre is farther than the radius from the literal orbit")
    detail = (f"{cell}, branch {b}: radius / first-order width in [{mp.nstr(lo, 12)}, {mp.nstr(hi, 12)}]; "
              f"frame re-orthogonalised {S.reorthogonalised} times.")
    if bad:
        return failed("numeric: Lohner set of a box vs the literal map's first-order image",
                      detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: Lohner set of a box vs the literal map's first-order image",
                   evidence="sampled", detail=detail, printed="the Lohner enclosure of a box is sharp")


#: paths.frame_inverse: the working precision of the frame algebra (LohnerSet's jac_prec) and the seed
FRAME_INV_PREC, FRAME_INV_SEED = 96, 7


def inverse_frames(n: int) -> list[tuple[str, Any]]:
    """``(name, B)``: a random orthogonal frame and one near ``-I`` (float64 arrays, ``n x n``)."""
    import numpy as np

    rng = np.random.default_rng(FRAME_INV_SEED)
    Q = np.linalg.qr(rng.standard_normal((n, n)))[0]
    Qi, R = np.linalg.qr(np.eye(n) + 0.05 * rng.standard_normal((n, n)))
    return [("random orthogonal", Q), ("near -I", -Qi * np.sign(np.diag(R)))]


def lemma_radius(B: Any) -> tuple[Any, Any]:
    """``(d, beta)`` of frame_inverse's lemma for ``X = B^T``, exactly: the doubles as integers times ``2**-S``
    (one common scale), so every product and sum below is an exact integer operation."""
    from fractions import Fraction

    S = 1100                                        # 2**S x (any double of magnitude <= 1) is an integer
    Z = [[int(Fraction(float(v)) * 2 ** S) for v in row] for row in B]
    n = len(Z)
    cols = [[Z[k][j] for k in range(n)] for j in range(n)]
    one = 1 << (2 * S)
    d = max(sum(abs(sum(a * c for a, c in zip(cols[i], cols[j])) - (one if i == j else 0)) for j in range(n))
            for i in range(n))
    return Fraction(d, one), Fraction(max(abs(x) for row in Z for x in row), 1 << S)


@claim("paths.frame_inverse", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths",
       sizes=(13,), requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: frame_inverse (the one-product bound, X = B^T)",
       statement="frame_inverse(B) for exact 26 x 26 frames (random orthogonal; near -I), X = B^T, at 96 bits: "
                 "midpoints X, every radius in [beta d/(1-d), beta (d+e)/(1-d-e) (1+2^-30)^8] with d, beta of "
                 "the docstring's lemma computed exactly and e = 2 n^2 2^-96 (N={N})")
def frame_inverse_lemma(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from flint import arb, arb_mat

    from ..numeric.multiprec.arb import flint_prec
    from ..numeric.multiprec.lohner import frame_inverse

    n, bad, worst = 2 * N, [], (mp.inf, mp.mpf(0))
    e = mp.mpf(2) * n * n * mp.mpf(2) ** -FRAME_INV_PREC
    for name, B in inverse_frames(n):
        d, beta = lemma_radius(B)
        d, beta = mp.mpf(d.numerator) / d.denominator, mp.mpf(beta.numerator) / beta.denominator
        low = beta * d / (1 - d)
        high = beta * (d + e) / (1 - d - e) * (1 + mp.mpf(2) ** -30) ** 8
        with flint_prec(FRAME_INV_PREC):
            E = frame_inverse(arb_mat(B.tolist()))
        for i in range(n):
            for j in range(n):
                r = mp.mpf(float(E[i, j].rad()))
                worst = (min(worst[0], r / low), max(worst[1], r / low))
                if not E[i, j].mid() == arb(float(B[j, i])):
                    bad.append(f"{name}: the midpoint ({i}, {j}) is not X = B^T")
                elif not low <= r <= high:
                    bad.append(f"{name}: radius ({i}, {j}) = {mp.nstr(r / low, 6)} x the lemma's "
                               f"beta d / (1 - d) (accepted 1 .. {mp.nstr(high / low, 6)})")
    detail = f"radius / (beta d / (1 - d)) in [{mp.nstr(worst[0], 8)}, {mp.nstr(worst[1], 8)}]."
    if bad:
        return failed("numeric: frame_inverse vs its lemma with exact d", detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: frame_inverse vs its lemma with d, beta exact (fractions)",
                   evidence="sampled", detail=detail, printed="radius = beta d / (1 - d), upper rounding only")


#: paths.next_prec: steps, the target radius and its bits, the forced first precision
NEXT_STEPS, NEXT_TARGET, NEXT_BITS, NEXT_FIRST = 60, 1e-40, 133, 135


@claim("paths.next_prec", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: lohner_certified's precision schedule (_next_prec)",
       statement="lohner_certified on the paper's state (N={N}), 60 steps, target 1e-40, first pass forced to 135 "
                 "bits: the second pass runs at max(floor(p + e + 1.5 g log2(n/i) + 16) + 1, p + 32) (its "
                 "docstring's rule, e, i, g from the same first pass by lohner_pass and growth_law) and the "
                 "returned orbit meets the target; unforced, 10 steps, the first pass runs at 133 + 24 + 5 bitlen(10) "
                 "bits, and through certified_orbit at max(1, ceil(-log2 tol)) + 24 + 5 bitlen(10) for tol 1e-40 "
                 "and 4")
def next_precision(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    import math

    from flint import arb

    from ..numeric.multiprec.arb import flint_prec
    from ..numeric.multiprec.lohner import growth_law, lohner_certified, lohner_pass

    def state() -> tuple:
        return [arb(-20), arb(10), arb(1)], [arb(1), arb(0), arb(0.9)], arb(10), arb(5)

    def excess(xs: list) -> float:
        return max(math.log2(float(x.rad()) / NEXT_TARGET) if x.rad() > 0 else -math.inf for x in xs)

    n = NEXT_STEPS
    passes: list[int] = []
    stored, _, _ = lohner_certified(state, n, 1, {n}, excess, NEXT_BITS, NEXT_FIRST, 4096, passes)
    with flint_prec(NEXT_FIRST):
        P, Q, l0, m = state()
        run = lohner_pass(P, Q, l0, m, n, 1, {n}, excess)
    done = [i for i in range(1, run.done + 1) if math.isfinite(run.hist[i])]
    bad = []
    if run.ok or not done or done[-1] >= n:
        return failed("numeric: lohner_certified's schedule", detail=f"the forced first pass did not stop early "
                      f"(ok {run.ok}, {run.done} steps): the claim's premise fails")
    i, e = done[-1], max(run.hist[k] for k in done)
    g = growth_law(run.lograd[:i + 1], first=max(1, i // 10))["degree"]
    want = max(int(NEXT_FIRST + e + 1.5 * max(g or 2.0, 1.0) * math.log2(n / i) + 16) + 1, NEXT_FIRST + 32)
    if passes[:2] != [NEXT_FIRST, want]:
        bad.append(f"passes {passes}, the documented rule gives {want} after {NEXT_FIRST} (stopped at step {i}, "
                   f"excess {e:.3g}, degree {g})")
    if not excess(stored[-1][0] + stored[-1][1]) <= 0:
        bad.append("the returned orbit does not meet the target radius")
    # without a forced first precision the first pass runs at target_bits + 24 + 5 bitlen(n) (the docstring's rule),
    # target_bits = max(1, ceil(-log2 tol)) through certified_orbit (tol 1e-40: 133; tol 4: 1)
    from ..numeric import certified_orbit

    short: list[int] = []
    lohner_certified(state, 10, 1, {10}, excess, NEXT_BITS, None, 4096, short)
    if short[:1] != [NEXT_BITS + 24 + 5 * (10).bit_length()]:
        bad.append(f"10 steps, no precision given: passes {short}, the documented first pass "
                   f"{NEXT_BITS + 24 + 5 * (10).bit_length()} bits")
    for tol, bits in ((NEXT_TARGET, NEXT_BITS), (4.0, 1)):
        info: dict = {}
        with mp.workdps(30):
            certified_orbit([-20, 10, 1], [1, 0, 0.9], 10, 5, 10, tol=tol, method="lohner", info=info)
        if info["passes"][:1] != [bits + 24 + 5 * (10).bit_length()]:
            bad.append(f"certified_orbit, tol {tol:g}: first pass {info['passes'][:1]}, documented "
                       f"{bits + 24 + 5 * (10).bit_length()} bits")
    detail = f"first pass {NEXT_FIRST} bits stopped at step {i} (excess {e:.3g} bits, degree {g}); passes {passes}."
    if bad:
        return failed("numeric: lohner_certified's schedule vs its documented rule", detail="; ".join(bad) + " "
                      + detail)
    return Outcome("verified", "numeric: lohner_certified's schedule vs its documented rule (consistency)",
                   evidence="sampled", detail=detail, printed="the second pass at the documented precision")


#: paths.lohner_unsound: steps, the balls' precision (bits) and the reference's digits
UNSOUND_STEPS, UNSOUND_PREC, UNSOUND_DPS = 40, 160, 300


@claim("paths.lohner_unsound", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: lohner_pass, LohnerSet (its deliberately unsound variant: the "
             "rounding errors and the Jacobian's radius dropped)",
       statement="the Lohner passes of the paper's state (N={N}, 40 steps, 160 bits, frames product and qr) contain "
                 "the literal orbit at 300 digits at every stored step; the deliberately unsound variant (rounding "
                 "errors and the Jacobian's radius dropped, the intersection with the ball image skipped) misses "
                 "it at every step taken (40 of the 41 stored states; the first is the exact input) -- the "
                 "containment test is not vacuous")
def lohner_unsound(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    import math

    from flint import arb

    from ..numeric.multiprec.arb import flint_prec
    from ..numeric.multiprec.lohner import lohner_pass
    from ..paper import LAM0_EXAMPLE, MU_EXAMPLE, P_EXAMPLE, Q_EXAMPLE
    from ..reference.literal import reference_step

    p, q, l0, m = list(P_EXAMPLE), list(Q_EXAMPLE), LAM0_EXAMPLE, MU_EXAMPLE[0]
    with mp.workdps(UNSOUND_DPS):
        P, Q = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]
        ref = [P + Q]
        for _ in range(UNSOUND_STEPS):
            P, Q = reference_step(P, Q, mp.mpf(l0), mp.mpf(m))
            ref.append(P + Q)
    misses: dict[tuple[str, bool], int] = {}
    for frame in ("product", "qr"):
        for unsound in (False, True):
            with flint_prec(UNSOUND_PREC):
                run = lohner_pass([arb(x) for x in p], [arb(x) for x in q], arb(l0), arb(m), UNSOUND_STEPS, 1,
                                  set(range(UNSOUND_STEPS + 1)), lambda xs: -math.inf, unsound=unsound, frame=frame)
            with flint_prec(1100):
                misses[frame, unsound] = sum(
                    any(not ball.contains(arb(mp.nstr(x, UNSOUND_DPS))) for x, ball in zip(r, Pb + Qb))
                    for r, (Pb, Qb) in zip(ref, run.stored))
    bad = [f"frame {f}: the sound pass misses the literal orbit at {k} steps" for (f, u), k in misses.items()
           if not u and k]
    bad += [f"frame {f}: the unsound variant misses it at only {k} of the {UNSOUND_STEPS} steps taken"
            for (f, u), k in misses.items() if u and not k >= UNSOUND_STEPS]
    detail = "; ".join(f"{f} {'unsound' if u else 'sound'}: {k} misses" for (f, u), k in misses.items()) + "."
    if bad:
        return failed("numeric: the Lohner passes and their unsound variant vs the literal orbit",
                      detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: the Lohner passes and their unsound variant vs the literal orbit "
                   "(300 digits)", evidence="sampled", n_scope=[N], detail=detail,
                   printed="sound contains, unsound misses")


#: paths.ball_schedule: (q_3, the first pass's forced bits): a first pass that stops early, the same from an exact input
#: (its first excess is -inf: the growth is measured from step 1), ones that stop at step 1 and at step 2 (one and two
#: finite excesses) and one that misses the target only at the last step (the floor p + p // 4 + 32 decides); steps,
#: target radius
BALL_CASES, BALL_STEPS, BALL_TOL = (("0.9", 170), (1, 170), (1, 60), (1, 130), ("0.9", 255)), 60, 1e-40


def ball_rule(first: int, hist: list, n: int) -> int:
    """The next pass's bits by the rule the claim states (from the first pass's excess history)."""
    import math

    finite = [(i, e) for i, e in enumerate(hist) if math.isfinite(e)]
    extra = 0.0
    if len(finite) >= 2:
        (i0, e0), (i1, e1) = finite[0], finite[-1]
        rate = max(0.0, (e1 - e0) / max(1, i1 - i0))
        extra = e1 + 1.15 * rate * (n - i1) + 4 * rate + 24
    elif finite:
        extra = finite[-1][1] + 24
    return max(int(first + extra) + 1, first + first // 4 + 32)


@claim("paths.ball_schedule", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/certified.py: the plain ball path's precision schedule (_next_prec)",
       statement="certified_orbit(method='ball') on the paper's state (N={N}; q_3 = 0.9 and q_3 = 1, exact), 60 "
                 "steps, tol 1e-40, first pass forced to 170, 60, 130 or 255 bits: the second pass runs at "
                 "max(floor(p + x) + 1, p + p // 4 + 32), x = e1 + 1.15 r (n - i1) + 4 r + 24 with r = max(0, (e1 - "
                 "e0) / (i1 - i0)) the growth (bits per step) between the first and the last finite excess (i0, "
                 "e0), (i1, e1) of the same first pass, x = e1 + 24 with one finite excess; the returned radii are "
                 "within the target plus the rounding of the midpoints to mp.prec; capped at max_prec = its second "
                 "pass, a run that succeeds there runs there")
def ball_schedule(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from ..numeric import certified_orbit
    from ..numeric.multiprec import certified

    n, bad, notes = BALL_STEPS, [], []
    for q3, first in BALL_CASES:
        p, q = [-20, 10, 1], [1, 0, q3]
        info: dict[str, object] = {}
        with mp.workdps(40):
            P, Q, Pr, Qr = certified_orbit(p, q, 10, 5, n, tol=BALL_TOL, prec=first, method="ball", info=info)
            ok, _, hist, done = certified._run(p, q, 10, 5, n, 1, {n}, first, BALL_TOL, mp.mp.prec)
            ulp = mp.mpf(2) ** -mp.mp.prec
        want = ball_rule(first, hist, n)
        passes = list(info.get("passes", []))         # type: ignore[call-overload]
        if ok or passes[:2] != [first, want] or info.get("method") != "ball":
            bad.append(f"q_3 = {q3}, first {first} bits: passes {passes} (method {info.get('method')}, first pass "
                       f"ok {ok} after {done} steps), the rule gives {want}")
        # the target is the balls' radius; the returned radius adds the rounding of the midpoint to mp.prec
        worst = max(float(r / (BALL_TOL + abs(x) * ulp)) for xs, rs in zip(P + Q, Pr + Qr) for x, r in zip(xs, rs))
        if not worst <= 1:
            bad.append(f"q_3 = {q3}: a returned radius {worst:.3g} times the target plus the output's rounding")
        notes.append(f"q_3 = {q3}, {first} bits: stopped at step {done}, passes {passes}")
        if len(passes) == 2:
            # max_prec is a precision the path may use: the same run capped at its second pass
            capped: dict[str, object] = {}
            with mp.workdps(40):
                try:
                    certified_orbit(p, q, 10, 5, n, tol=BALL_TOL, prec=first, max_prec=want, method="ball",
                                    info=capped)
                except ArithmeticError as exc:
                    bad.append(f"q_3 = {q3}: capped at max_prec = {want}, its second pass, it raised {exc}")
            if capped.get("passes") not in (None, passes):
                bad.append(f"q_3 = {q3}: capped at max_prec = {want}: passes {capped.get('passes')}")
    detail = "; ".join(notes) + "."
    if bad:
        return failed("numeric: the ball path's schedule vs its rule", detail="; ".join(bad) + " " + detail)
    return Outcome("verified", "numeric: the ball path's schedule vs its rule (consistency)", evidence="sampled",
                   n_scope=[N], detail=detail, printed="the second pass at the documented precision")
