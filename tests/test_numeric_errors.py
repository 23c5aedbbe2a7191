"""Typed errors, mu = 0, and import hygiene of symbt.numeric."""

import subprocess
import sys

import mpmath
import numpy as np
import pytest

from symbt.numeric import (
    InvalidInputError,
    NoRealMapError,
    NumericRangeError,
    bt_orbit,
    bt_step,
    flow_coefficients,
    invariants,
    phi,
    spectral_trace,
)

P0 = np.array([-20.0, 10.0, 1.0])
Q0 = np.array([1.0, 0.0, 0.9])


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite(bad):
    p = P0.copy()
    p[1] = bad
    with pytest.raises(InvalidInputError):
        bt_step(p, Q0, 10.0, 5.0)
    with pytest.raises(InvalidInputError):
        bt_step(P0, np.where(np.arange(3) == 2, bad, Q0), 10.0, 5.0)
    with pytest.raises(InvalidInputError):
        bt_step(P0, Q0, bad, 5.0)
    with pytest.raises(InvalidInputError):
        bt_step(P0, Q0, 10.0, bad)
    with pytest.raises(InvalidInputError):
        bt_step([mpmath.mpf(bad), 1, 2], [0, 0, 0], 10, 5)


def test_shapes_and_sizes():
    with pytest.raises(InvalidInputError):
        bt_step(P0, Q0[:2], 10.0, 5.0)
    with pytest.raises(InvalidInputError):
        bt_step(np.zeros((2, 3)), np.zeros((3, 3)), 10.0, 5.0)
    with pytest.raises(InvalidInputError):
        bt_step([1.0], [0.0], 10.0, 5.0)
    with pytest.raises(InvalidInputError):
        bt_step(1.0, 0.0, 10.0, 5.0)
    with pytest.raises(InvalidInputError):
        bt_step(np.zeros((4, 3)), np.zeros((4, 3)), 10.0, np.ones(5))
    with pytest.raises(InvalidInputError):
        invariants([1.0], [2.0])
    with pytest.raises(InvalidInputError):
        bt_orbit(P0, Q0, 10.0, 5.0, -1)


@pytest.mark.parametrize("branch", [0, 2, -2, 1.0, True, "1", None])
def test_bad_branch(branch):
    with pytest.raises(InvalidInputError):
        bt_step(P0, Q0, 10.0, 5.0, branch=branch)


def test_errors_are_value_errors():
    assert issubclass(InvalidInputError, ValueError)
    assert issubclass(NoRealMapError, ValueError)


def test_no_real_map_trace_condition():
    # lam1 = 20.5 lies in a band of the paper's example (|tr| <= 2 there)
    lam = np.linspace(15, 25, 2001)
    tr = spectral_trace(lam, np.broadcast_to(P0, (lam.size, 3)), np.broadcast_to(Q0, (lam.size, 3)))
    lam_band = lam[np.argmin(np.abs(tr))]
    with pytest.raises(NoRealMapError) as info:
        bt_step(P0, Q0, 10.0, lam_band - 10.0)
    assert info.value.condition == "trace"
    assert "|tr L(lam1" in str(info.value)
    with pytest.raises(NoRealMapError):
        phi(P0, Q0, 10.0, lam_band - 10.0)


def test_no_real_map_different_gaps_and_batch_index():
    # lam2 = 5 in the paper's gap, lam1 = 40 beyond the spectrum: a band lies between
    assert spectral_trace(40.0, P0, Q0) > 2 and spectral_trace(5.0, P0, Q0) < -2
    with pytest.raises(NoRealMapError) as info:
        bt_step(P0, Q0, 22.5, 17.5)
    assert info.value.condition == "positivity"
    p = np.stack([P0, P0, P0])
    q = np.stack([Q0, Q0, Q0])
    with pytest.raises(NoRealMapError) as info:
        bt_step(p, q, np.array([10.0, 22.5, 10.0]), np.array([5.0, 17.5, 5.0]))
    assert info.value.where == ((1,),)
    with pytest.raises(NoRealMapError):
        flow_coefficients(P0, Q0, 22.5, 17.5)
    # the complex continuation is available on request
    pc, qc = bt_step(P0, Q0, 22.5, 17.5, allow_complex=True)
    assert np.iscomplexobj(qc) and np.all(np.isfinite(qc))


def test_gaps_two_apart_same_trace_sign_are_rejected():
    # N = 3: gaps alternate in the sign of tr; take lam1, lam2 in the two
    # outer gaps of the same sign (N odd: lam -> -inf has tr < 0; use the
    # middle-ish structure by scanning) and check the map is refused.
    p = np.array([-30.0, 0.0, 30.0])
    q = np.zeros(3)
    lam = np.linspace(-60, 60, 24001)
    tr = spectral_trace(lam, np.broadcast_to(p, (lam.size, 3)), np.broadcast_to(q, (lam.size, 3)))
    gap = np.abs(tr) > 2.5
    neg = lam[gap & (tr < 0)]
    a, b = neg.min(), neg.max()  # leftmost and the inner negative gap: a band pair between
    assert spectral_trace(a, p, q) < -2 and spectral_trace(b, p, q) < -2
    assert np.any(tr[(lam > a) & (lam < b)] > 2)
    with pytest.raises(NoRealMapError):
        bt_step(p, q, 0.5 * (a + b), 0.5 * (b - a))


def test_mu_zero_identity_copies():
    pt, qt = bt_step(P0, Q0, 10.0, 0.0)
    np.testing.assert_array_equal(pt, P0)
    np.testing.assert_array_equal(qt, Q0)
    assert pt is not P0 and not np.shares_memory(pt, P0)
    # mu = 0 is the identity even where the real map would not exist
    pt, qt = bt_step(P0, Q0, 20.0, 0.0)
    np.testing.assert_array_equal(pt, P0)
    # per-row mu with zeros
    p = np.stack([P0, P0])
    q = np.stack([Q0, Q0])
    pt, qt = bt_step(p, q, 10.0, np.array([0.0, 5.0]))
    np.testing.assert_array_equal(pt[0], P0)
    np.testing.assert_array_equal(pt[1], bt_step(P0, Q0, 10.0, 5.0)[0])
    with mpmath.workdps(30):
        mp_p = [mpmath.mpf(v) for v in P0]
        a, b = bt_step(mp_p, list(Q0), 10, 0)
        assert a == mp_p and a is not mp_p


def test_range_error_for_huge_neighbour_differences():
    with pytest.raises(NumericRangeError):
        bt_step(P0, np.array([0.0, 900.0, 0.0]), 10.0, 5.0)


def test_no_silent_nan():
    rng = np.random.default_rng(3)
    for _ in range(200):
        p = rng.normal(size=3) * 10
        q = rng.normal(size=3) * 3
        lam0, mu = rng.normal() * 20, rng.normal() * 10
        try:
            pt, qt = bt_step(p, q, lam0, mu, branch=int(rng.choice([-1, 1])))
        except (NoRealMapError, NumericRangeError):
            continue
        assert np.all(np.isfinite(pt)) and np.all(np.isfinite(qt))


def test_import_is_light():
    # the whole numeric side: runtime, literal reference, elliptic helpers, flows, generated code
    code = ("import sys, symbt.numeric, symbt.reference.literal, symbt.reference.elliptic, symbt.reference.taylor, "
            "symbt.generated.toda2, symbt.generated.toda3; "
            "bad = [m for m in ('sympy', 'scipy', 'matplotlib') if m in sys.modules]; "
            "print(','.join(bad))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", out.stdout


def test_empty_batch_phi_and_interval_phi_and_parameter_overflow():
    from symbt.numeric import phi

    z = np.zeros((0, 3))
    assert phi(z, z, 10.0, 5.0).shape == (0,)
    ivs = [mpmath.iv.mpf(v) for v in (-20, 10, 1)]
    with pytest.raises(InvalidInputError):
        phi(ivs, [mpmath.iv.mpf(v) for v in (1, 0, 0.9)], 10, 5)
    # lam0 and mu finite, lam0 + mu not: a range problem, not "lam1 in a band"
    with pytest.raises(NumericRangeError):
        bt_step(np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9]), 1e308, 1e308)
    with pytest.raises(NumericRangeError):
        phi(np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9]), 1e308, 1e308)


@pytest.mark.parametrize("kw", [{"branch": 0}, {"branch": 2}, {"branch": 0.5}, {"branch": True},
                                {"n": -1}, {"n": 2.5}, {"every": 0}])
def test_float_orbit_driver_validates_branch_and_steps(kw):
    # the documented driver (docs/numeric.md) refuses what bt_orbit refuses: before, branch 0, 2 and 0.5 ran
    # (a map of no branch, or of branch +1 silently) and n = -1 returned an empty orbit
    from symbt.numeric.float64.orbit import float_orbit
    args = {"n": 2, **kw}
    n = args.pop("n")
    with pytest.raises(InvalidInputError):
        float_orbit([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, n, **args)
