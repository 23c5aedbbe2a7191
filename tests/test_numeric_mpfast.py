"""High precision, fast: mpmath input through python-flint's Arb (midpoint arithmetic) vs the mpmath path.

Reference: ``reference_step`` (the paper's literal route, mpmath, automatic guard digits) at 40 more
digits than the working precision.  Both backends must agree with it to the working precision.
"""

import mpmath
import numpy as np
import pytest

from symbt.benchmarks.numeric_cases import random_gap_case
from symbt.numeric import InvalidInputError, MissingDependencyError, NoRealMapError, bt_orbit, bt_step
from symbt.numeric.core import errors as numeric_errors
from symbt.reference.literal import reference_step

pytest.importorskip("flint")

P0 = ["-20", "10", "1"]
Q0 = ["1", "0", "0.9"]


def mp_state(p, q):
    return [mpmath.mpf(v) for v in p], [mpmath.mpf(v) for v in q]


def ref_orbit(p, q, lam0, mu, n, dps, branch=1):
    out = []
    with mpmath.workdps(dps):
        a, b = [mpmath.mpf(v) for v in p], [mpmath.mpf(v) for v in q]
        for _ in range(n):
            a, b = reference_step(a, b, lam0, mu, branch=branch)
            out.append((a, b))
    return out


def maxdiff(a, b):
    return max(abs(x - y) for x, y in zip(a, b))


@pytest.mark.parametrize("dps", [50, 100])
@pytest.mark.parametrize("branch", [1, -1])
def test_step_both_backends_to_working_precision(dps, branch):
    with mpmath.workdps(dps):
        p, q = mp_state(P0, Q0)
        rp, rq = ref_orbit(p, q, 10, 5, 1, dps + 40, branch)[0]
        tol = mpmath.mpf(10) ** (2 - dps)          # |state| ~ 20: two digits of headroom
        for backend in ("flint", "mpmath"):
            pt, qt = bt_step(p, q, 10, 5, branch=branch, backend=backend)
            assert all(isinstance(v, mpmath.mpf) and +v == v for v in pt + qt)   # mpf at the caller's precision
            assert maxdiff(pt + qt, rp + rq) < tol, backend
        from symbt.numeric.backends import pick

        auto = bt_step(p, q, 10, 5, branch=branch)            # auto is the backend the table picks
        assert auto == bt_step(p, q, 10, 5, branch=branch, backend=pick("auto", "mpmath", 1).name)


@pytest.mark.parametrize("dps", [50, 100])
def test_orbit_both_backends_to_working_precision(dps):
    n = 25
    with mpmath.workdps(dps):
        p, q = mp_state(P0, Q0)
        refs = ref_orbit(p, q, 10, 5, n, dps + 40)
        tol = mpmath.mpf(10) ** (3 - dps)          # orbit growth ~n^2 ulps, |q| ~ 10
        for backend in ("flint", "mpmath"):
            P, Q = bt_orbit(p, q, 10, 5, n, every=5, backend=backend)
            assert len(P) == 6
            for k, i in enumerate(range(0, n + 1, 5)):
                if i:
                    assert maxdiff(P[k] + Q[k], refs[i - 1][0] + refs[i - 1][1]) < tol, (backend, i)
        # the Arb path at 50 digits does not degrade over many steps (the radii are dropped each step)
        P, Q = bt_orbit(p, q, 10, 5, 300, every=300)
        Pm, Qm = bt_orbit(p, q, 10, 5, 300, every=300, backend="mpmath")
        assert maxdiff(P[-1] + Q[-1], Pm[-1] + Qm[-1]) < mpmath.mpf(10) ** (6 - dps)


def test_random_states_and_sizes():
    rng = np.random.default_rng(8)
    for N in (2, 4, 7):
        p, q, lam0, mu = random_gap_case(rng, N)
        with mpmath.workdps(60):
            P, Q = mp_state(p, q)
            rp, rq = ref_orbit(P, Q, lam0, mu, 1, 100)[0]
            pt, qt = bt_step(P, Q, lam0, mu)
            scale = 1 + max(abs(v) for v in rp + rq)
            assert maxdiff(pt + qt, rp + rq) < mpmath.mpf(10) ** -57 * scale


def test_complex_continuation_with_acb():
    with mpmath.workdps(40):
        p, q = mp_state(P0, Q0)
        with pytest.raises(NoRealMapError):
            bt_step(p, q, 10, 12, backend="flint")
        a = bt_step(p, q, 10, 12, allow_complex=True, backend="flint")
        b = bt_step(p, q, 10, 12, allow_complex=True, backend="mpmath")
        assert any(isinstance(v, mpmath.mpc) for v in a[0] + a[1])
        assert maxdiff(a[0], b[0]) < mpmath.mpf(10) ** -35
        # log branch of q~ may differ by 2 pi i between routes: compare exp(q~)
        assert maxdiff([mpmath.exp(v) for v in a[1]], [mpmath.exp(v) for v in b[1]]) < mpmath.mpf(10) ** -35


def test_backend_selection_and_missing_flint(monkeypatch):
    with mpmath.workdps(30):
        p, q = mp_state(P0, Q0)
        with pytest.raises(InvalidInputError):
            bt_step(p, q, 10, 5, backend="numba")
        with pytest.raises(InvalidInputError):
            bt_orbit(p, q, 10, 5, 2, backend="cuda")
        monkeypatch.setitem(numeric_errors._IMPORTABLE, "flint", False)
        with pytest.raises(MissingDependencyError, match="python-flint"):
            bt_step(p, q, 10, 5, backend="flint")
        # auto falls back to mpmath silently
        pt, qt = bt_step(p, q, 10, 5)
        assert mpmath.nstr(qt[0], 15) == "-0.0861422421882023"


def test_intervals_still_take_the_interval_path():
    iv = mpmath.iv
    P, Q = bt_orbit([iv.mpf(v) for v in (-20, 10, 1)], [iv.mpf(v) for v in (1, 0, 0.9)], 10, 5, 2)
    assert len(P) == 3 and all(hasattr(v, "delta") for v in P[-1])


def test_fused_arb_step_is_step_core_on_arb_midpoints():
    """The fused Arb step performs step_core's operations in the same order: identical midpoints (the fast
    path drops the radii; they differ in the last bits of the radius because ``-a_1`` is a negation there
    and a multiplication by ``-1.0`` in step_core)."""
    from flint import arb

    from symbt.numeric.core.step import step_core
    from symbt.numeric.multiprec.arb import ARB_MID, flint_prec
    from symbt.numeric.multiprec.runners import arb_step

    rng = np.random.default_rng(21)
    with flint_prec(250):
        for N in (2, 3, 6):
            for branch in (1, -1):
                p, q, lam0, mu = random_gap_case(rng, N)
                P, Q = [arb(float(v)) for v in p], [arb(float(v)) for v in q]
                a = arb_step(P, Q, arb(lam0), arb(mu), branch)
                b = step_core(ARB_MID, P, Q, arb(lam0), arb(mu), branch)[:2]
                for x, y in zip(a[0] + a[1], b[0] + b[1]):
                    assert x.mid() == y.mid()
                    assert abs(x.rad() - y.rad()) <= 1e-6 * y.rad()
        with pytest.raises(NoRealMapError, match="different spectral gaps"):
            arb_step([arb(-20), arb(10), arb(1)], [arb(1), arb(0), arb(0.9)], arb(22.5), arb(17.5), 1)
