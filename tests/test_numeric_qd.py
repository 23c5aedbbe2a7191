"""Quad-double backend (symbt.numeric.multiprec.qd): arithmetic against mpmath at 80 digits, exact conversions,
the orbit against a 120-digit reference (the Arb path at 120 digits, itself checked against
``reference_step`` in tests/test_numeric_mpfast.py), agreement with the flint path, typed errors,
backend choice."""

import math
import random

import mpmath
import numpy as np
import pytest

from symbt.benchmarks.numeric_cases import random_gap_case
from symbt.numeric import (
    InvalidInputError,
    MissingDependencyError,
    NoRealMapError,
    NumericRangeError,
    bt_orbit,
    bt_step,
)
from symbt.numeric.core import errors as numeric_errors
from symbt.numeric.multiprec.qd import QD_BITS, from_qd, qd_available, qd_fits, qd_kernel, qd_need, qd_orbit_mp, to_qd
from symbt.reference.literal import reference_step

pytestmark = pytest.mark.skipif(not qd_available(), reason="the qd backend needs numba")

P0, Q0 = ["-20", "10", "1"], ["1", "0", "0.9"]


def mp_state(p, q):
    return [mpmath.mpf(v) for v in p], [mpmath.mpf(v) for v in q]


def exact(x):
    """A quad-double (4 floats) as an exact mpf."""
    with mpmath.workprec(1200):
        return mpmath.fsum(mpmath.mpf(float(c)) for c in x)


def rand_qd(rng, lo=-20, hi=20):
    """A random renormalised quad-double with all four components in use."""
    with mpmath.workprec(400):
        v = mpmath.mpf(rng.uniform(0.5, 1.0)) * (1 + mpmath.mpf(rng.random()) * 2 ** -55
                                                 + mpmath.mpf(rng.random()) * 2 ** -110
                                                 + mpmath.mpf(rng.random()) * 2 ** -165)
        v *= rng.choice((-1, 1)) * mpmath.mpf(2) ** rng.randint(lo, hi)
        out, rest = [], v
        for _ in range(4):
            out.append(float(rest))
            rest -= out[-1]
    return tuple(out)


def relerr(got, want):
    with mpmath.workprec(1200):
        return float(abs(exact(got) - want) / abs(want))


# bounds (measured worst over 400 points: add/mul/div ~2**-213, sqrt/expm1/log1p ~2**-211, exp ~2**-208.6
# for |a| up to 2**8; the QD algorithms' error analyses give a few 2**-209); one bit of headroom
BOUNDS = {"add": 2.0 ** -210, "mul": 2.0 ** -210, "div": 2.0 ** -210, "sqrt": 2.0 ** -208, "exp": 2.0 ** -206,
          "expm1": 2.0 ** -207, "log1p": 2.0 ** -208}


def test_arithmetic_against_mpmath_at_80_digits():
    rng = random.Random(5)
    f = {name: qd_kernel(name) for name in BOUNDS}
    worst = dict.fromkeys(BOUNDS, 0.0)
    with mpmath.workdps(80):
        for _ in range(400):
            a, b = rand_qd(rng), rand_qd(rng)
            A, B = exact(a), exact(b)
            worst["add"] = max(worst["add"], relerr(f["add"](a, b), A + B))
            worst["mul"] = max(worst["mul"], relerr(f["mul"](a, b), A * B))
            worst["div"] = max(worst["div"], relerr(f["div"](a, b), A / B))
            pos = a if A > 0 else tuple(-c for c in a)
            worst["sqrt"] = max(worst["sqrt"], relerr(f["sqrt"](pos), mpmath.sqrt(abs(A))))
            x = rand_qd(rng, -60, 8)            # |x| < 256: exp and expm1 down to tiny arguments
            X = exact(x)
            worst["exp"] = max(worst["exp"], relerr(f["exp"](x), mpmath.exp(X)))
            worst["expm1"] = max(worst["expm1"], relerr(f["expm1"](x), mpmath.expm1(X)))
            y = rand_qd(rng, -80, 6)
            Y = exact(y)
            if Y > -1:
                worst["log1p"] = max(worst["log1p"], relerr(f["log1p"](y), mpmath.log1p(Y)))
    for name, bound in BOUNDS.items():
        assert worst[name] <= bound, (name, math.log2(worst[name]))
        assert worst[name] > 0, name                      # the comparison saw the low components


def test_log1p_relative_accuracy_near_minus_one_and_zero():
    f = qd_kernel("log1p")
    with mpmath.workprec(400):
        for X in (-1 + mpmath.mpf(2) ** -70 / 3, mpmath.mpf(-0.5) - mpmath.mpf(2) ** -90 / 3, mpmath.mpf(2) ** -300 / 3,
                  -mpmath.mpf(2) ** -200 / 7, mpmath.mpf(10) ** 12 / 7):
            rest, comps = X, []
            for _ in range(4):
                comps.append(float(rest))
                rest -= comps[-1]
            x = tuple(comps)
            assert relerr(f(x), mpmath.log1p(exact(x))) <= BOUNDS["log1p"], X
        assert math.isnan(f((-1.0, 0.0, 0.0, 0.0))[0])


def test_add_cancellation_is_absolutely_accurate():
    """QD's sloppy addition: in a cancellation the error is bounded by 2**-210 (|a| + |b|), not relative."""
    rng = random.Random(9)
    add = qd_kernel("add")
    for _ in range(200):
        a = rand_qd(rng)
        b = tuple(-c for c in a[:2]) + rand_qd(rng, -130, -110)[:2]
        with mpmath.workprec(1200):
            A, B = exact(a), exact(b)
            err = abs(exact(add(a, b)) - (A + B))
            assert err <= 2.0 ** -210 * (abs(A) + abs(B))


def test_conversions_round_trip_exactly():
    rng = random.Random(2)
    with mpmath.workdps(50):
        vals = [mpmath.mpf(rng.uniform(-1, 1)) * mpmath.mpf(10) ** rng.randint(-30, 30) + mpmath.rand() / 3
                for _ in range(200)] + [mpmath.mpf(0), mpmath.mpf(-1), mpmath.mpf(2) ** 500]
        x = to_qd(vals)
        assert x is not None
        assert all(exact(row) == v for row, v in zip(x, vals))              # the chunks are exact
        assert from_qd(x, mpmath.mp.prec) == vals                           # and come back exactly
    # rounding to nearest at a lower precision, ties and carries included
    with mpmath.workprec(53):
        y = np.array([[1.0, 2.0 ** -53, 0.0, 0.0], [1.0, 2.0 ** -53, 2.0 ** -120, 0.0], [1.0, -2.0 ** -54, 0.0, 0.0]])
        assert from_qd(y, 53) == [mpmath.mpf(1), 1 + mpmath.mpf(2) ** -52, mpmath.mpf(1)]
    with mpmath.workprec(300):
        assert to_qd([mpmath.mpf(1) + mpmath.mpf(2) ** -250]) is None       # more than 212 bits
    assert to_qd([mpmath.mpf(2) ** 700]) is None                          # outside the exponent range


def ref_orbit(p, q, lam0, mu, n, branch=1):
    with mpmath.workdps(120):
        return bt_orbit(p, q, lam0, mu, n, branch=branch, backend="flint")


@pytest.mark.parametrize("branch", [1, -1])
def test_orbit_against_120_digit_reference(branch):
    """At 50 digits the qd orbit is rounded from a value within 2**-200 (relative to the state) of the
    exact orbit: it equals the correctly rounded reference to half an ulp, like the Arb path."""
    n = 100
    with mpmath.workdps(50):
        p, q = mp_state(P0, Q0)
        P, Q = qd_orbit_mp(p, q, 10, 5, n, branch=branch, every=10)
        RP, RQ = ref_orbit(p, q, 10, 5, n, branch)
        for k, i in enumerate(range(0, n + 1, 10)):
            ref = RP[i] + RQ[i]
            scale = max(abs(v) for v in ref)
            ulp = mpmath.mpf(2) ** (int(mpmath.floor(mpmath.log(scale, 2))) - mpmath.mp.prec + 1)
            assert max(abs(a - b) for a, b in zip(P[k] + Q[k], ref)) <= ulp / 2 + ulp / 16, i


def test_one_step_against_reference_step():
    with mpmath.workdps(50):
        p, q = mp_state(P0, Q0)
        with mpmath.workdps(90):
            rp, rq = reference_step(p, q, 10, 5)
        pt, qt = bt_step(p, q, 10, 5, backend="qd")
        assert max(abs(a - b) for a, b in zip(pt + qt, rp + rq)) < mpmath.mpf(10) ** -48


@pytest.mark.parametrize("N", [2, 3, 5])
def test_random_states_agree_with_flint(N):
    rng = np.random.default_rng(40 + N)
    for _ in range(3):
        p, q, lam0, mu = random_gap_case(rng, N)
        with mpmath.workdps(45):
            P, Q = mp_state([float(v) for v in p], [float(v) for v in q])
            for branch in (1, -1):
                a = bt_orbit(P, Q, float(lam0), float(mu), 20, branch=branch, every=5, backend="qd")
                b = bt_orbit(P, Q, float(lam0), float(mu), 20, branch=branch, every=5, backend="flint")
                scale = max(abs(v) for v in b[0][-1] + b[1][-1])
                for x, y in zip(a[0] + a[1], b[0] + b[1]):
                    assert max(abs(u - v) for u, v in zip(x, y)) <= scale * mpmath.mpf(2) ** (2 - mpmath.mp.prec)


def test_typed_errors():
    with mpmath.workdps(50):
        p, q = mp_state(P0, Q0)
        lam0, mu = mpmath.mpf("2.5"), mpmath.mpf("3.285")          # lam2 = -0.785: tr L = -0.32, inside a band
        with pytest.raises(NoRealMapError, match="lam2") as e:
            bt_orbit(p, q, lam0, mu, 3, backend="qd")
        assert e.value.condition == "trace"
        with pytest.raises(NoRealMapError, match="lam2"):
            bt_orbit(p, q, lam0, mu, 3, backend="flint")
        with pytest.raises(NoRealMapError, match="lam1"):
            bt_orbit(p, q, lam0 - 5, -mu, 3, backend="qd")         # the same point as lam1
        with pytest.raises(NoRealMapError, match="different spectral gaps") as e:
            bt_orbit(p, q, mpmath.mpf("22.5"), mpmath.mpf("17.5"), 2, backend="qd")
        assert e.value.condition == "positivity"
        # the complex continuation goes on along the Arb path
        a = bt_step(p, q, 10, 12, allow_complex=True, backend="qd")
        assert any(isinstance(v, mpmath.mpc) for v in a[0] + a[1])
        with pytest.raises(InvalidInputError, match="backend"):
            bt_orbit(p, q, 10, 5, 2, backend="quad")
        with pytest.raises(NumericRangeError):                        # |q_2 - q_1| = 400: beyond the qd range
            bt_orbit(p, [mpmath.mpf(0), mpmath.mpf(400), mpmath.mpf(0)], 10, 5, 1, backend="qd")
    with mpmath.workdps(100):
        p, q = mp_state(P0, Q0)
        with pytest.raises(InvalidInputError, match="209 bits"):
            bt_orbit(p, q, 10, 5, 2, backend="qd")


def test_auto_chooses_qd_when_ready_and_the_precision_fits(monkeypatch):
    from symbt.numeric.backends import pick
    from symbt.numeric.multiprec import qd as qd_mod

    qd_mod.warm()
    with mpmath.workdps(50):
        assert qd_fits(mpmath.mp.prec, 10) and qd_need(mpmath.mp.prec, 10) <= QD_BITS
        assert qd_mod.qd_ready() and pick("auto", "mpmath", 10).name == "qd"
        p, q = mp_state(P0, Q0)
        assert bt_orbit(p, q, 10, 5, 10) == bt_orbit(p, q, 10, 5, 10, backend="qd")
        # out of range for qd: auto falls back to Arb
        far = [mpmath.mpf(0), mpmath.mpf(400), mpmath.mpf(0)]
        assert bt_orbit(p, far, 10, 5, 1) == bt_orbit(p, far, 10, 5, 1, backend="flint")
    with mpmath.workdps(100):
        assert pick("auto", "mpmath", 10).name == "flint"
    monkeypatch.setitem(numeric_errors._IMPORTABLE, "numba", False)
    with mpmath.workdps(50):
        assert pick("auto", "mpmath", 10).name == "flint"
        with pytest.raises(MissingDependencyError, match="numba"):
            pick("qd", "mpmath", 10)


def test_no_numba_switch(monkeypatch):
    monkeypatch.setenv("SYMBT_NO_NUMBA", "1")
    assert not qd_available()
    with mpmath.workdps(50), pytest.raises(MissingDependencyError):
        p, q = mp_state(P0, Q0)
        bt_orbit(p, q, 10, 5, 2, backend="qd")


@pytest.mark.parametrize("branch", [1, -1])
def test_unrounded_error_is_below_the_model_behind_the_rule(branch):
    """The premise of qd_fits: the unrounded qd orbit stays below 2**(-209 - 8 + 2 n.bit_length()) of the
    state's size (measured down to 2**-213 at n = 10; the model allows 2**-209)."""
    n = 100
    with mpmath.workdps(50):
        p, q = mp_state(P0, Q0)
        x = to_qd(p + q + [mpmath.mpf(10), mpmath.mpf(5)])
    outP, outQ = np.empty((n + 1, 3, 4)), np.empty((n + 1, 3, 4))
    assert qd_kernel()(x[:3], x[3:6], x[6:], branch, n, 1, outP, outQ) == (0, n)
    RP, RQ = ref_orbit(p, q, 10, 5, n, branch)
    for i in (1, 10, 100):
        with mpmath.workprec(400):
            raw = from_qd(np.concatenate([outP[i], outQ[i]]), 400)
            ref = RP[i] + RQ[i]
            err = max(abs(a - b) for a, b in zip(raw, ref)) / max(abs(v) for v in ref)
            assert 0 < err <= mpmath.mpf(2) ** (-217 + 2 * i.bit_length()), (i, float(mpmath.log(err, 2)))


def test_auto_never_compiles(tmp_path):
    """Without a current ready-marker (a fresh install, or edited sources) auto takes Arb: the ~30 s first
    compile is never imposed.  With the marker of the current sources it takes qd (fresh processes)."""
    import subprocess
    import sys
    import textwrap

    def fresh(marker):
        code = textwrap.dedent(f"""
            import pathlib, mpmath
            from symbt.numeric.multiprec import qd
            from symbt.numeric.backends import pick
            qd._marker_dirs = lambda: [pathlib.Path({str(tmp_path)!r})]
            if {marker!r} is not None:
                (qd._marker_dirs()[0] / qd._MARKER).write_text({marker!r} or qd._digest())
            with mpmath.workdps(50):
                print(pick("auto", "mpmath", 10).name, qd.qd_ready(), bool(qd._compiled))
        """)
        return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              check=True).stdout.split()

    assert fresh(None) == ["flint", "False", "False"]                 # no marker, nothing compiled
    assert fresh("0" * 64) == ["flint", "False", "False"]             # the marker of other sources
    assert fresh("") == ["qd", "True", "False"]                       # current marker: qd, compiled on use
