"""One-step accuracy of the float64 Bäcklund map against independent mpmath references.

Reference: ``symbt.reference.literal.reference_step`` -- the paper's literal
route (2x2 mpmath matrices, forward transport) at >= 50 digits plus automatic
guard digits, i.e. a different algorithm from the one under test.  Error
metric: ``symbt.benchmarks.numeric_cases.state_error`` (normwise relative, centre of
mass of q removed from the denominator only).  Measured worst cases are noted
next to each assertion; the bound asserted everywhere is 1e-13.
"""

import mpmath
import numpy as np
import pytest

from symbt.benchmarks.numeric_cases import outer_gap_case, random_gap_case, state_error
from symbt.numeric import NoRealMapError, bt_step, invariants, spectral_trace
from symbt.numeric.core.context import FLOAT
from symbt.numeric.core.step import step_core
from symbt.reference.literal import reference_step as literal_step

# the acceptance bound for one-step normwise relative error; measured worst case is ~2e-15,
# so the margin (50x) absorbs platform libm differences without hiding an O(1e-12) regression
TOL = 1e-13
P0 = np.array([-20.0, 10.0, 1.0])
Q0 = np.array([1.0, 0.0, 0.9])


def ref(p, q, lam0, mu, branch=1, dps=50):
    with mpmath.workdps(dps):
        return literal_step([float(v) for v in p], [float(v) for v in q], float(lam0), float(mu),
                            branch=branch)


def err(p, q, lam0, mu, branch=1):
    pt, qt = bt_step(p, q, lam0, mu, branch=branch)
    return state_error(pt, qt, *ref(p, q, lam0, mu, branch))


def test_paper_example_reference_numbers():
    # regression pins: 12-digit values of the literal route at 50 digits (computed once with
    # symbt.reference.literal.literal_step; test_paper_example_accuracy recomputes them at run time)
    pt, qt = bt_step(P0, Q0, 10.0, 5.0)
    np.testing.assert_allclose(pt, [-19.9965676649, 9.78635494921, 1.21021271571], rtol=0, atol=2e-10)
    np.testing.assert_allclose(qt, [-0.0861422421882, 0.519849719775, 1.88339322702], rtol=0, atol=2e-12)
    pm, _ = bt_step(P0, Q0, 10.0, 5.0, branch=-1)
    np.testing.assert_allclose(pm, [-19.6458715826, 10.1116945682, 0.534177014405], rtol=0, atol=2e-10)
    assert spectral_trace(15.0, P0, Q0) < -2 and spectral_trace(5.0, P0, Q0) < -2


@pytest.mark.parametrize("branch", [1, -1])
def test_paper_example_accuracy(branch):
    assert err(P0, Q0, 10.0, 5.0, branch) <= TOL  # measured ~6e-17


@pytest.mark.parametrize("N", [2, 3, 5, 8])
@pytest.mark.parametrize("branch", [1, -1])
def test_random_inner_gaps_batched(N, branch):
    rng = np.random.default_rng(100 * N + (branch > 0))
    cases = [random_gap_case(rng, N) for _ in range(6)]
    # one batched call with per-row lam0, mu
    p = np.array([c[0] for c in cases])
    q = np.array([c[1] for c in cases])
    lam0 = np.array([c[2] for c in cases])
    mu = np.array([c[3] for c in cases])
    pt, qt = bt_step(p, q, lam0, mu, branch=branch)
    assert pt.shape == qt.shape == (6, N)
    for i, c in enumerate(cases):
        e = state_error(pt[i], qt[i], *ref(*c, branch=branch))
        assert e <= TOL, (c, e)  # measured <= 2e-15


def test_batch_shape_and_consistency():
    from symbt.numeric.float64.jit import numba_available

    rng = np.random.default_rng(7)
    p = P0 + 0.01 * rng.normal(size=(4, 5, 3))
    q = Q0 + 0.01 * rng.normal(size=(4, 5, 3))
    pt, qt = bt_step(p, q, 10.0, 5.0)
    assert pt.shape == (4, 5, 3)
    # with numba a batch runs the compiled block kernel: each state's step is the single-state fused kernel's,
    # bit for bit.  Without numba a batch takes the vectorised numpy route (same formulas; q~ = q + increment may
    # round differently by an ulp of max(|q|, |q~|)).  The numpy route agrees with both to that ulp.
    for i, j in ((2, 3), (0, 0), (3, 4)):
        p1, q1 = bt_step(p[i, j], q[i, j], 10.0, 5.0)
        p2, q2 = bt_step(p[i, j], q[i, j], 10.0, 5.0, backend="numpy")
        ulp_p = np.spacing(max(np.abs(p[i, j]).max(), np.abs(p1).max()))
        ulp_q = np.spacing(max(np.abs(q[i, j]).max(), np.abs(q1).max()))
        if numba_available():
            np.testing.assert_array_equal(pt[i, j], p1)
            np.testing.assert_array_equal(qt[i, j], q1)
        else:
            np.testing.assert_array_equal(pt[i, j], p2)
            np.testing.assert_array_equal(qt[i, j], q2)
        np.testing.assert_allclose(p1, p2, rtol=0, atol=ulp_p)
        np.testing.assert_allclose(q1, q2, rtol=0, atol=ulp_q)


def test_batch_errors_name_every_failing_state_on_both_routes():
    # the block kernel (numba) and the numpy route raise the same typed error with the same `where`
    from symbt.numeric import NoRealMapError

    p = np.tile(P0, (6, 1))
    q = np.tile(Q0, (6, 1))
    p[[1, 4]] = [0.0, 0.0, 0.0]     # a state whose spectral points lie in a band: |tr L| <= 2
    q[[1, 4]] = [0.0, 0.0, 0.0]
    for backend in ("auto", "numpy"):
        with pytest.raises(NoRealMapError) as e:
            bt_step(p, q, 0.5, 0.2, backend=backend)
        assert tuple(e.value.where) == ((1,), (4,)), (backend, e.value.where)


@pytest.mark.parametrize("logmu", list(range(-14, 1)))
def test_small_mu_paper_gap(logmu):
    mu = 10.0**logmu
    for branch in (1, -1):
        pt, qt = bt_step(P0, Q0, 10.0, mu, branch=branch)
        rp, rq = ref(P0, Q0, 10.0, mu, branch)
        assert state_error(pt, qt, rp, rq) <= TOL  # measured <= 1e-16
        # the increments themselves (O(mu), before being added to p, q) are accurate
        # *relative to mu*: no 1/mu error amplification (the literal route has ~1e-10/mu)
        P, Q = [np.array([v]) for v in P0], [np.array([v]) for v in Q0]
        with np.errstate(all="ignore"):
            _, _, aux = step_core(FLOAT, P, Q, 10.0, mu, branch)
        gq = [g[0] for g in aux["gq"]]
        inc_p = np.array([2 * mu * (gq[(j + 1) % 3] - gq[j]) for j in range(3)])
        with mpmath.workdps(50):
            inc_ref = np.array([float(a - mpmath.mpf(b)) for a, b in zip(rp, P0)])
        assert np.max(np.abs(inc_p - inc_ref)) <= 1e-12 * mu  # measured <= 1e-15 mu; increments are mu-relative


def test_large_mu_outer_gap():
    # mu = 1e2 with lam0 +- mu beyond the spectrum
    for lam0 in (300.0, -300.0):
        for branch in (1, -1):
            assert err(P0, Q0, lam0, 100.0, branch) <= TOL  # measured ~2e-15


HARD = {
    "momenta x1e4": (P0 * 1e4, Q0, 1e5, 5e4),
    "lam0 = 1e5": (P0, Q0, 1e5, 5.0),
    "lam0 = 1e5, mu = 1e2": (P0, Q0, 1e5, 1e2),
    "q spread (0,-20,-40)": (P0, np.array([0.0, -20.0, -40.0]), 10.0, 5.0),
    "q near +800": (P0, Q0 + 800.0, 10.0, 5.0),
    "q near -800": (P0, Q0 - 800.0, 10.0, 5.0),
    "negative mu": (P0, Q0, 10.0, -5.0),
    "negative mu small": (P0, Q0, 10.0, -1e-9),
}


@pytest.mark.parametrize("name", sorted(HARD))
@pytest.mark.parametrize("branch", [1, -1])
def test_hard_inputs(name, branch):
    p, q, lam0, mu = HARD[name]
    e = err(p, q, lam0, mu, branch)
    assert e <= TOL, e  # measured <= 2e-15 (q near 800: output rounding of q dominates)


@pytest.mark.parametrize("N", [16, 32, 64])
def test_long_chains(N):
    rng = np.random.default_rng(N)
    for side in (1, -1):
        case = outer_gap_case(rng, N, side=side)
        for branch in (1, -1):
            assert err(*case, branch=branch) <= TOL  # measured <= 1e-15
    case = random_gap_case(rng, N, pscale=40.0)  # an inner gap of a longer chain
    assert err(*case) <= TOL


def test_shift_covariance_exact():
    # the map commutes with q -> q + c and the float code only sees differences
    for c in (0.0, 1.0, 800.0, -750.0):
        pt, qt = bt_step(P0, Q0 + c, 10.0, 5.0)
        p0, q0 = bt_step(P0, Q0, 10.0, 5.0)
        np.testing.assert_allclose(pt, p0, rtol=0, atol=1e-14 * (1 + abs(c)))
        np.testing.assert_allclose(qt - c, q0, rtol=0, atol=2e-16 * (1 + abs(c)))


@pytest.mark.parametrize("branch", [1, -1])
def test_branch_minus_is_inverse(branch):
    rng = np.random.default_rng(11)
    for N in (2, 3, 5, 8):
        p, q, lam0, mu = random_gap_case(rng, N)
        pt, qt = bt_step(p, q, lam0, mu, branch=branch)
        pb, qb = bt_step(pt, qt, lam0, mu, branch=-branch)
        scale = np.linalg.norm(np.r_[p, q - q.mean()])
        assert np.linalg.norm(np.r_[pb - p, qb - q]) <= 1e-13 * scale


def test_branch_minus_equals_negative_mu():
    rng = np.random.default_rng(12)
    for N in (2, 3, 5):
        p, q, lam0, mu = random_gap_case(rng, N)
        a = np.r_[bt_step(p, q, lam0, mu, branch=-1)]
        b = np.r_[bt_step(p, q, lam0, -mu, branch=1)]
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-13 * np.abs(a).max())


def test_invariants_preserved():
    rng = np.random.default_rng(13)
    for N in (2, 3, 5, 8):
        p, q, lam0, mu = random_gap_case(rng, N)
        pt, qt = bt_step(p, q, lam0, mu)
        H, Ht = invariants(p, q), invariants(pt, qt)
        np.testing.assert_allclose(Ht, H, rtol=1e-11, atol=1e-11 * np.abs(H).max())
        for lam in (lam0, lam0 + 2 * mu, -3.0):
            t0, t1 = spectral_trace(lam, p, q), spectral_trace(lam, pt, qt)
            assert abs(t1 - t0) <= 1e-11 * max(1.0, abs(t0))


def test_mpmath_path_matches_literal_at_60_digits():
    with mpmath.workdps(60):
        p = [mpmath.mpf(-20), mpmath.mpf(10), mpmath.mpf(1)]
        q = [mpmath.mpf(1), mpmath.mpf(0), mpmath.mpf("0.9")]
        for branch in (1, -1):
            pt, qt = bt_step(p, q, 10, 5, branch=branch)
            assert all(isinstance(v, mpmath.mpf) for v in pt + qt)
            rp, rq = literal_step(p, q, 10, 5, branch=branch, verify=True)
            assert max(abs(a - b) for a, b in zip(pt + qt, rp + rq)) < mpmath.mpf(10) ** -55
        # tr L invariance at several lam, at 60 digits
        pt, qt = bt_step(p, q, 10, 5)
        for lam in (-7, 0, 3, 12.5, 40):
            assert abs(spectral_trace(mpmath.mpf(lam), pt, qt) - spectral_trace(mpmath.mpf(lam), p, q)) \
                < mpmath.mpf(10) ** -50 * (1 + abs(spectral_trace(mpmath.mpf(lam), p, q)))


def test_mpmath_complex_continuation():
    # lam1 = 16 is past the gap edge of the paper's example: no real map
    p, q = [mpmath.mpf(v) for v in P0], [mpmath.mpf(v) for v in Q0]
    lam0, mu = 10, 12
    with pytest.raises(NoRealMapError):
        bt_step(p, q, lam0, mu)
    pt, qt = bt_step(p, q, lam0, mu, allow_complex=True)
    assert any(isinstance(v, mpmath.mpc) for v in pt + qt)
    rp, rq = literal_step(p, q, lam0, mu)
    assert max(abs(a - b) for a, b in zip(pt, rp)) < 1e-10
    # float path returns complex128 with allow_complex
    fp, fq = bt_step(P0, Q0, lam0, mu, allow_complex=True)
    assert fp.dtype == np.complex128
    np.testing.assert_allclose(fp, [complex(v) for v in pt], rtol=1e-10)
    np.testing.assert_allclose(np.exp(fq), [complex(mpmath.exp(v)) for v in qt], rtol=1e-10)


def test_interval_context_encloses():
    iv = mpmath.iv
    with mpmath.workdps(30):
        ref_p, ref_q = literal_step(list(P0), list(Q0), 10, 5)
    pt, qt = bt_step([iv.mpf(v) for v in P0], [iv.mpf(v) for v in Q0], 10, 5)
    for a, b in zip(pt + qt, ref_p + ref_q):
        assert a.a <= b <= a.b
        assert a.delta < 1e-9


def test_batch_far_from_the_spectrum_takes_the_kernel_member_by_member():
    # N = 256 at lam0 = 3N + 20: |tr L| ~ 790^256 ~ 1e742, far past 1e150.  The kernels rescale the
    # monodromy, so no member is routed to the numpy path any more: each member of the default batch is its
    # single-state kernel step bit for bit, and within 8 ulps of max(|p|, |q|, |lam0| + |mu|) of the
    # independent 40-digit mpmath step
    from symbt.numeric.float64.jit import numba_available
    from symbt.numeric.float64.orbit import kernel_step

    rng = np.random.default_rng(1)
    mu = 2.0
    for N, lam0 in ((256, 3.0 * 256 + 20), (64, 3.0 * 64 + 20), (3, 10.0)):
        p = rng.normal(size=(4, N))
        q = 0.5 * rng.normal(size=(4, N))
        pt, qt = bt_step(p, q, lam0, mu)
        for m in range(4):
            single = kernel_step(p[m], q[m], lam0, mu, 1)
            assert single is not None, (N, m)                  # the kernel finishes it: no hand-back
            assert np.array_equal(bt_step(p[m], q[m], lam0, mu)[0], single[0])
            if numba_available():                              # the block kernel: bit-identical
                assert np.array_equal(pt[m], single[0]) and np.array_equal(qt[m], single[1]), (N, m)
            with mpmath.workdps(40):
                rp, rq = bt_step([mpmath.mpf(float(x)) for x in p[m]], [mpmath.mpf(float(x)) for x in q[m]],
                                 mpmath.mpf(lam0), mpmath.mpf(mu))
            scale = max(np.abs(p[m]).max(), np.abs(q[m]).max(), lam0 + mu, 1.0)
            err = max(np.abs(pt[m] - np.array([float(x) for x in rp])).max(),
                      np.abs(qt[m] - np.array([float(x) for x in rq])).max())
            assert err <= 8 * 2.0**-52 * scale, (N, m, err / (2.0**-52 * scale))


def test_which_batches_go_to_the_block_kernel():
    from symbt.numeric.float64.step import _block_kernel_pays

    z = np.zeros
    assert _block_kernel_pays(z((1, 3))) and _block_kernel_pays(z((4095, 3)))
    assert not _block_kernel_pays(z((4096, 3)))          # N = 3: numpy's vectorised step wins
    assert _block_kernel_pays(z((100_000, 8)))            # from N = 8 the kernel wins at any size
    assert _block_kernel_pays(z((16, 256)))               # far from the spectrum too: the kernels rescale


def test_large_batch_at_small_n_equals_the_numpy_route():
    rng = np.random.default_rng(3)
    p = P0 + 0.01 * rng.normal(size=(5000, 3))
    q = Q0 + 0.01 * rng.normal(size=(5000, 3))
    pt, qt = bt_step(p, q, 10.0, 5.0)
    pn, qn = bt_step(p, q, 10.0, 5.0, backend="numpy")
    np.testing.assert_array_equal(pt, pn)
    np.testing.assert_array_equal(qt, qn)
