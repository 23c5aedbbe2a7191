"""Lohner-type certified orbits (symbt.numeric.multiprec.lohner): every enclosure contains an independent
reference orbit.

Reference: the paper's literal route (``reference_step``) at 300 digits from the *same* exact input -- a
different algorithm at more than three times the working precision.  The Jacobian enclosure is checked
against forward-mode dual numbers through ``step_core`` and against central finite differences at 200
digits.  A deliberately unsound variant (rounding errors and Jacobian radii dropped) must fail the same
containment check, so the check can fail.
"""

import math

import mpmath
import numpy as np
import pytest

pytest.importorskip("flint")

from flint import arb  # noqa: E402

from symbt.numeric import InvalidInputError, NumericRangeError, bt_orbit, bt_step, certified_orbit  # noqa: E402
from symbt.numeric.multiprec.arb import flint_prec  # noqa: E402
from symbt.numeric.multiprec.lohner import LohnerSet, growth_law, lohner_pass, step_jacobian  # noqa: E402
from symbt.numeric.multiprec.lohner_checks import (  # noqa: E402
    InconsistentEnclosure,
    common_invariants,
    float64_error_bounds,
    invariant_enclosures,
    jacobian_dual,
)
from symbt.paper import LAM0_EXAMPLE, MU_EXAMPLE, P_EXAMPLE, Q_EXAMPLE  # noqa: E402

P64, Q64 = list(P_EXAMPLE), list(Q_EXAMPLE)          # exact binary input (0.9 is the double nearest 0.9)
LAM0, MU = LAM0_EXAMPLE, MU_EXAMPLE[0]


def reference_orbit(p, q, lam0, mu, n, every, branch=1, dps=300):
    """The literal map at ``dps`` digits from the exact input (mpf of floats / decimal strings)."""
    from symbt.reference.literal import reference_step

    out = []
    with mpmath.workdps(dps):
        a, b = [mpmath.mpf(v) for v in p], [mpmath.mpf(v) for v in q]
        out.append((a, b))
        for i in range(1, n + 1):
            a, b = reference_step(a, b, mpmath.mpf(lam0), mpmath.mpf(mu), branch=branch)
            if i % every == 0 or i == n:
                out.append((a, b))
    return out


def misses(ref, P, Q, Pr, Qr):
    """Stored states where the enclosure ``mid +- rad`` misses the reference: ``[(state, coordinate, excess)]``."""
    bad = []
    with mpmath.workdps(300):
        for i, ((a, b), Pm, Qm, Pr_, Qr_) in enumerate(zip(ref, P, Q, Pr, Qr)):
            for k, (x, m, r) in enumerate(zip(a + b, Pm + Qm, Pr_ + Qr_)):
                if not abs(x - m) <= r:
                    bad.append((i, k, abs(x - m) - r))
    return bad


def ball_misses(ref, stored):
    """The same check on Arb balls (``lohner_pass`` output): ``x in ball`` for the 300-digit reference."""
    bad = []
    with flint_prec(1100):
        for i, ((a, b), (Pb, Qb)) in enumerate(zip(ref, stored)):
            for k, (x, ball) in enumerate(zip(a + b, Pb + Qb)):
                if not ball.contains(arb(x)):
                    bad.append((i, k))
    return bad


def random_state(N, seed):
    rng = np.random.default_rng(seed)
    p, q = np.round(rng.normal(size=N), 6), np.round(0.5 * rng.normal(size=N), 6)
    return [float(v) for v in p], [float(v) for v in q]


P5, Q5 = random_state(5, 5)
LAM5, MU5 = 6.0, 1.5


def test_random_state_has_a_real_map():
    pt, _ = bt_step(P5, Q5, LAM5, MU5, backend="numpy")      # raises NoRealMapError otherwise
    assert np.all(np.isfinite(pt))


@pytest.mark.parametrize("case", ["paper", "paper-decimal", "random5", "random5-inverse"])
def test_every_enclosure_contains_the_300_digit_reference(case):
    p, q, lam0, mu, branch, n = {
        "paper": (P64, Q64, LAM0, MU, 1, 300),
        "paper-decimal": (["-20", "10", "1"], ["1", "0", "0.9"], "10", "5", 1, 150),   # r0 != 0: the C r0 term
        "random5": (P5, Q5, LAM5, MU5, 1, 150),
        "random5-inverse": (P5, Q5, LAM5, MU5, -1, 100),
    }[case]
    info = {}
    with mpmath.workdps(40):
        P, Q, Pr, Qr = certified_orbit(p, q, lam0, mu, n, branch=branch, info=info)
    assert info["method"] == "lohner", info
    assert len(P) == n + 1
    ref = reference_orbit(p, q, lam0, mu, n, 1, branch)
    assert misses(ref, P, Q, Pr, Qr) == []
    # sharp: the radii are a few ulps of the returned 40 digits, not a growing ball
    worst = max(max(a + b) for a, b in zip(Pr, Qr))
    assert worst <= 1e-38
    # the midpoints are not the reference itself: the containment check is not vacuous
    with mpmath.workdps(300):
        assert max(abs(x - m) for x, m in zip(ref[-1][0], P[-1])) > 0


@pytest.mark.parametrize("frame", ["product", "qr"])
def test_the_unsound_variant_fails_the_containment_check(frame):
    """Rounding errors and the Jacobian's radius dropped: the enclosure shrinks to the midpoint orbit, which
    the same check (same precision, same steps, same frame) rejects, while the sound pass passes it."""
    n = 40
    ref = reference_orbit(P64, Q64, LAM0, MU, n, 1)
    for unsound in (False, True):
        with flint_prec(160):
            run = lohner_pass([arb(x) for x in P64], [arb(x) for x in Q64], arb(LAM0), arb(MU), n, 1,
                              set(range(n + 1)), lambda xs: -math.inf, unsound=unsound, frame=frame)
        assert len(run.stored) == n + 1
        bad = ball_misses(ref, run.stored)
        if unsound:
            assert len(bad) > n           # misses at (almost) every step
        else:
            assert bad == []


def test_small_frame_reorthogonalised_stays_sound(monkeypatch):
    """The small product frame (formed in Arb) re-orthogonalised at a low condition threshold: the QR steps
    really happen and every enclosure still contains the 300-digit reference."""
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner, "MAX_FRAME_COND", 50.0)
    n = 200
    ref = reference_orbit(P64, Q64, LAM0, MU, n, 1)
    with flint_prec(160):
        S = LohnerSet([arb(x) for x in P64 + Q64])
        stored = [(S.hull[:3], S.hull[3:])]
        for _ in range(n):
            S.step(arb(LAM0), arb(MU), 1)
            stored.append((S.hull[:3], S.hull[3:]))
    assert S.reorthogonalised >= 2
    assert ball_misses(ref, stored) == []
    assert max(float(x.rad()) for x in S.hull) < 1e-30


def test_precision_raised_from_the_measured_growth():
    """A first pass at too few bits measures the polynomial growth; the next pass meets the target."""
    info = {}
    with mpmath.workdps(50):
        P, Q, Pr, Qr = certified_orbit(P64, Q64, LAM0, MU, 400, every=100, tol=1e-40, prec=100, info=info)
    assert info["method"] == "lohner" and info["passes"][0] == 100 and len(info["passes"]) >= 2, info
    assert info["prec"] <= 256
    assert max(max(a + b) for a, b in zip(Pr, Qr)) <= 1e-40


def fd_jacobian(p, q, lam0, mu, branch, h, dps=200):
    from symbt.numeric.core.context import MP
    from symbt.numeric.core.step import step_core

    x0 = [mpmath.mpf(v) for v in p + q]
    N = len(p)
    cols = []
    with mpmath.workdps(dps):
        for k in range(2 * N):
            vals = []
            for s in (1, -1):
                x = list(x0)
                x[k] += s * h
                Pn, Qn, _ = step_core(MP, x[:N], x[N:], mpmath.mpf(lam0), mpmath.mpf(mu), branch)
                vals.append(Pn + Qn)
            cols.append([(a - b) / (2 * h) for a, b in zip(*vals)])
    return [[cols[k][i] for k in range(2 * N)] for i in range(2 * N)]


@pytest.mark.parametrize("case", ["paper", "paper-inverse", "random5"])
def test_jacobian_enclosure_contains_dual_numbers_and_finite_differences(case):
    p, q, lam0, mu, branch = {"paper": (P64, Q64, LAM0, MU, 1), "paper-inverse": (P64, Q64, LAM0, MU, -1),
                              "random5": (P5, Q5, LAM5, MU5, 1)}[case]
    h = mpmath.mpf(10) ** -40
    fd = fd_jacobian(p, q, lam0, mu, branch, h)         # truncation ~ h**2 |f'''| ~ 1e-75: far below rad(J)
    with flint_prec(256):
        box = [arb(x) for x in p + q]
        img, J = step_jacobian(box, arb(lam0), arb(mu), branch, 96)
        img2, J2 = jacobian_dual(box, arb(lam0), arb(mu), branch)
        assert J.overlaps(J2)
        n = len(box)
        for i in range(n):
            for k in range(n):
                assert J[i, k].contains(arb(fd[i][k])), (i, k, J[i, k], fd[i][k])
                assert float(J[i, k].rad()) < 1e-20 * max(1.0, abs(float(J[i, k].mid())))    # a sharp enclosure
            # the map commutes with q -> q + c: the q-columns of every row sum to the p/q shift (0 or 1)
            assert sum(J[i, k] for k in range(n // 2, n)).contains(1 if i >= n // 2 else 0)


def test_fallback_to_the_ball_path_at_a_degenerate_eigenvector():
    """p = (-3, 0), q = (0, 1), lam0 = mu = 1: lam2 + p_2 = 0, a slope passes through infinity (a branch point of
    the slope chart): the Jacobian enclosure is not finite and the plain ball path runs (its enclosure of this
    limit is tested in test_numeric_corner.py; here it is compared with the 60-digit mpmath step, a consistency
    check -- the literal route divides by zero at this state)."""
    p, q = [-3, 0], [0, 1]
    info = {}
    with mpmath.workdps(30):
        P, Q, Pr, Qr = certified_orbit(p, q, 1, 1, 1, info=info)
    assert info["method"] == "ball" and "not finite" in info["fallback"], info
    with mpmath.workdps(60):
        pm, qm = bt_step([mpmath.mpf(v) for v in p], [mpmath.mpf(v) for v in q], 1, 1, backend="mpmath")
        assert all(abs(x - m) <= r for x, m, r in zip(pm + qm, P[1] + Q[1], Pr[1] + Qr[1]))
    with pytest.raises(NumericRangeError, match="Lohner"):
        with mpmath.workdps(30):
            certified_orbit(p, q, 1, 1, 1, method="lohner")


def test_methods_and_info():
    infos = {}
    with mpmath.workdps(30):
        out = {m: certified_orbit(P64, Q64, LAM0, MU, 150, every=50, info=infos.setdefault(m, {}), method=m)
               for m in ("auto", "ball")}
        with pytest.raises(InvalidInputError):
            certified_orbit(P64, Q64, LAM0, MU, 1, method="qr")
    assert infos["auto"]["method"] == "lohner" and infos["ball"]["method"] == "ball"
    assert infos["auto"]["prec"] < infos["ball"]["prec"]                # fewer working bits at 150 steps
    assert infos["auto"]["growth"]["steps"] == (15, 150) and infos["auto"]["growth"]["degree"] is not None
    # both enclose the same exact orbit: the balls overlap
    for a, b in ((out["auto"], out["ball"]),):
        with mpmath.workdps(60):
            for i in range(4):
                for x, r, y, s in zip(a[0][i], a[2][i], b[0][i], b[2][i]):
                    assert abs(x - y) <= r + s
    # bt_orbit(certified=True) takes the same route
    with mpmath.workdps(30):
        P, _, _, _ = bt_orbit(P64, Q64, LAM0, MU, 150, certified=True, every=50)
    assert P == out["auto"][0]


def test_invariants_along_the_orbit_intersect_and_the_check_can_fail():
    from symbt.numeric import invariants

    with mpmath.workdps(40):
        P, Q, Pr, Qr = certified_orbit(P64, Q64, LAM0, MU, 200, every=20)
    H = invariant_enclosures(P, Q, Pr, Qr)
    common = common_invariants(H)
    with mpmath.workdps(100):
        exact = invariants([mpmath.mpf(x) for x in P64], [mpmath.mpf(x) for x in Q64])
    with flint_prec(400):
        for h, x in zip(common, exact):
            assert h.contains(arb(x))
            assert float(h.rad()) < 1e-30 * max(1.0, abs(float(x)))
    # a state moved by 1e-20 (far outside its radius) gives a disjoint enclosure of some H_k
    P[5] = [P[5][0] + mpmath.mpf("1e-20")] + P[5][1:]
    with pytest.raises(InconsistentEnclosure):
        common_invariants(invariant_enclosures(P, Q, Pr, Qr))


def test_float64_error_bound_is_certified_and_two_sided():
    n = 300
    with mpmath.workdps(40):
        orbit = certified_orbit(P64, Q64, LAM0, MU, n, every=50)
    Pf, Qf = bt_orbit(P64, Q64, LAM0, MU, n, every=50)
    bounds = float64_error_bounds(*orbit, Pf, Qf)
    ref = reference_orbit(P64, Q64, LAM0, MU, n, 50, dps=60)
    with mpmath.workdps(60):
        for i, (a, b) in enumerate(ref):
            true = max(abs(mpmath.mpf(float(x)) - y) for x, y in zip(np.r_[Pf[i], Qf[i]], a + b))
            slack = 2 * max(orbit[2][i] + orbit[3][i]) + mpmath.mpf(2) ** -52 * true    # + rounding up to a float
            assert true <= bounds[i] <= true + slack
    assert bounds[0] == 0.0                     # the same exact input
    assert 1e-15 < bounds[-1] < 1e-11          # the float64 orbit's error at 300 steps (test_numeric_orbit.py)


def test_growth_law_reads_polynomial_growth():
    law = growth_law([math.log2(3e-60 * max(i, 1) ** 1.5) for i in range(2001)])
    assert abs(law["degree"] - 1.5) < 1e-9 and law["steps"] == (100, 2000)


@pytest.mark.slow
def test_3500_steps_below_1e_minus_40_at_most_256_bits():
    """Issue 23's first target (~10-20 s): every stored radius <= 1e-40, working precision <= 256 bits."""
    info = {}
    with mpmath.workdps(50):
        P, Q, Pr, Qr = certified_orbit(P64, Q64, LAM0, MU, 3500, every=500, tol=1e-40, info=info)
    assert info["method"] == "lohner" and info["prec"] <= 256, info
    assert max(max(a + b) for a, b in zip(Pr, Qr)) <= 1e-40
    ref = reference_orbit(P64, Q64, LAM0, MU, 3500, 500, dps=120)
    with mpmath.workdps(120):
        for (a, b), Pm, Qm, Pr_, Qr_ in zip(ref, P, Q, Pr, Qr):
            assert all(abs(x - m) <= r for x, m, r in zip(a + b, Pm + Qm, Pr_ + Qr_))


def test_docs_certified_examples_run():
    import doctest
    import pathlib

    doc = pathlib.Path(__file__).resolve().parents[1] / "docs" / "certified.md"
    result = doctest.testfile(str(doc), module_relative=False, optionflags=doctest.ELLIPSIS)
    assert result.attempted >= 8 and result.failed == 0, result
