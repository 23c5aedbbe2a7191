"""N = 2 action-angle variables and the elliptic addition formula (symbt.reference.elliptic, claims elliptic/certified)."""
from __future__ import annotations

import random

import mpmath as mp
import pytest

from symbt.reference import elliptic as E
from symbt.reference.literal import literal_step


def _mp(case):
    p, q, l0, m = case
    return [mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m)


@pytest.fixture(autouse=True)
def _dps():
    with mp.workdps(40):
        yield


# --------------------------------------------------------------------------- F, modulus vs parameter

@pytest.mark.parametrize("z", ["-0.9", "-0.3", "0", "0.5", "0.99"])
def test_F_is_incomplete_jacobi_form_with_parameter_k2(z):
    z, k = mp.mpf(z), mp.mpf("0.7")
    alg = mp.quad(lambda t: 1 / mp.sqrt((1 - t ** 2) * (1 - k ** 2 * t ** 2)), [0, z])
    assert abs(E.F(z, k) - alg) < mp.mpf(10) ** -30
    if z != 0:  # passing the modulus where mpmath expects the parameter is a different function
        assert abs(mp.ellipf(mp.asin(z), k) - alg) > mp.mpf(10) ** -4


def test_F_refuses_beyond_one_and_F_real_refuses_gap():
    k = mp.mpf("0.6")
    with pytest.raises(ValueError):
        E.F(mp.mpf("1.2"), k)
    with pytest.raises(ValueError):
        E.F_real(mp.mpf("1.2"), k)  # 1 < 1.2 < 1/k
    assert E.F_real(mp.mpf(3), k) == -E.F_real(mp.mpf(-3), k)


# --------------------------------------------------------------------------- global angle, both signs of sinh(q1-q2)

@pytest.mark.parametrize("x_sign", [1, -1])
@pytest.mark.parametrize("p_sign", [1, -1])
def test_global_angle_and_printed_theta2(x_sign, p_sign):
    I1, I2 = mp.mpf("0.4"), mp.mpf("4.5")
    p, q = E.state_on_level(I1, I2, x_sign * mp.mpf("0.6"), mp.mpf("0.3"), p_sign)
    u, m = E.global_u(p, q)
    sn, cn, _ = E.sn_cn_dn(u, m)
    P = (p[1] - p[0]) / (2 * mp.sqrt(I2 - 2))
    C = 2 * mp.sinh((q[0] - q[1]) / 2) / mp.sqrt(I2 - 2)
    assert abs(P ** 2 + C ** 2 - 1) < mp.mpf(10) ** -35
    assert abs(sn - P) < mp.mpf(10) ** -30 and abs(cn - C) < mp.mpf(10) ** -30
    printed = E.theta2_printed(p, q) * mp.sqrt(I2 + 2)
    K = mp.ellipk(m)
    expected = u if x_sign > 0 else (2 * K - u if u > 0 else -2 * K - u)
    assert abs(printed - expected) < mp.mpf(10) ** -30


# --------------------------------------------------------------------------- the Abel map: every zone, both sheets, dps

@pytest.mark.parametrize("s", ["0.4", "-0.8", "1.1", "-1.2", "2.5", "-4"])
@pytest.mark.parametrize("sheet", [1, -1])
def test_abel_inverts_sn_and_cndn(s, sheet):
    m = mp.mpf(3) / 7
    s = mp.mpf(s)
    w = sheet * mp.sqrt((1 - s ** 2) * (1 - m * s ** 2))
    u = E.abel(s, w, m)
    sn, cn, dn = E.sn_cn_dn(u, m)
    assert abs(sn - s) < mp.mpf(10) ** -30
    assert abs(cn * dn - w) < mp.mpf(10) ** -30


@pytest.mark.parametrize("s", ["0.4", "1.1", "2", "-2", "5"])
def test_abel_is_dps_independent(s):
    vals = []
    for d in (30, 50, 80):
        with mp.workdps(d):
            m, z = mp.mpf(3) / 7, mp.mpf(s)
            vals.append(E.abel(z, mp.sqrt((1 - z ** 2) * (1 - m * z ** 2)), m))
    with mp.workdps(30):
        assert max(abs(a - b) for a in vals for b in vals) < mp.mpf(10) ** -28


def test_shift_is_dps_independent_in_every_regime():
    rng = random.Random(4)
    cases = [E.sample_case(reg, rng) for reg in E.REGIMES]
    out = {}
    for d in (30, 50, 80):
        with mp.workdps(d):
            row = []
            for c in cases:
                p, q, l0, m = _mp(c)
                I1, I2 = E.actions(p, q)
                row.append(E.shift(I1, I2, l0, m, 1)["du"])
                assert E.addition_residual(p, q, l0, m, 1) < mp.mpf(10) ** -(d - 12)
            out[d] = row
    with mp.workdps(30):
        for i in range(len(cases)):
            assert abs(out[30][i] - out[50][i]) < mp.mpf(10) ** -27
            assert abs(out[80][i] - out[50][i]) < mp.mpf(10) ** -27


# --------------------------------------------------------------------------- regimes x branches x orientation

@pytest.mark.parametrize("reg", E.REGIMES)
@pytest.mark.parametrize("branch", [1, -1])
@pytest.mark.parametrize("x_sign", [1, -1])
def test_corrected_addition_formula(reg, branch, x_sign):
    rng = random.Random(f"{reg}/{branch}/{x_sign}")  # str seeds are deterministic
    for _ in range(2):
        p, q, l0, m = _mp(E.sample_case(reg, rng, x_sign=x_sign))
        assert E.regime_of_state(p, q, l0, m) == reg
        pt, qt, info = literal_step(p, q, l0, m, branch)
        assert E.addition_residual(p, q, l0, m, branch, pt=pt, qt=qt, Et=info["E_new"]) < mp.mpf(10) ** -30
        I, It = E.actions(p, q), E.actions(pt, qt)
        assert abs(I[0] - It[0]) < mp.mpf(10) ** -30 and abs(I[1] - It[1]) < mp.mpf(10) ** -30
        if reg in ("inner", "outer-same"):  # real form, mod 4K
            I1, I2 = I
            k, mm = E.modulus(I2)
            sh = E.shift(I1, I2, l0, m, branch)
            d = E.global_u(pt, qt)[0] - E.global_u(p, q)[0] - branch * (E.F_real(sh["s_plus"], k)
                                                                       - E.F_real(sh["s_minus"], k))
            K4 = 4 * mp.ellipk(mm)
            assert abs(d - K4 * mp.nint(d / K4)) < mp.mpf(10) ** -30
            assert abs((qt[0] + qt[1]) - (q[0] + q[1]) - sh["dtheta1_real"]) < mp.mpf(10) ** -30


@pytest.mark.parametrize("reg", E.REGIMES)
def test_regime_signatures(reg):
    p, q, l0, m = _mp(E.sample_case(reg, random.Random(9)))
    pt, qt, info = literal_step(p, q, l0, m, 1)
    Et = info["E_new"]
    if reg == "gap":
        assert any(isinstance(g, mp.mpc) and abs(mp.im(g)) > 0 for g in (info["gamma1"], info["gamma2"]))
        assert any(abs(mp.im(v)) > mp.mpf(10) ** -10 for v in pt)
        return
    assert all(abs(mp.im(v)) < mp.mpf(10) ** -30 for v in pt)
    signs = [mp.sign(mp.re(e)) for e in Et]
    expected = {"inner": [1, 1], "outer-same": [1, 1], "outer-opposite": [-1, -1]}.get(reg)
    if expected:
        assert signs == expected
    else:  # mixed
        assert signs[0] * signs[1] == -1


# --------------------------------------------------------------------------- wrong formulas are caught

def test_wrong_addition_formulas_are_caught():
    rng = random.Random(2)
    for reg in ("inner", "outer-same", "mixed"):
        p, q, l0, m = _mp(E.sample_case(reg, rng))
        I1, I2 = E.actions(p, q)
        sh = E.shift(I1, I2, l0, m, 1)
        assert E.addition_residual(p, q, l0, m, 1) < mp.mpf(10) ** -30
        assert E.addition_residual(p, q, l0, m, 1, du=-sh["du"]) > mp.mpf(10) ** -3  # sign flipped
        assert E.addition_residual(p, q, l0, m, 1, du=2 * sh["du"]) > mp.mpf(10) ** -3  # doubled
        assert E.addition_residual(p, q, l0, m, -1, du=sh["du"]) > mp.mpf(10) ** -3  # other branch


def test_printed_addform_sign_in_inner_regime():
    """Printed (b=+1) holds in the inner regime iff q1 < q2 before and after the step."""
    rng = random.Random(5)
    seen = set()
    for i in range(16):
        p, q, l0, m = _mp(E.sample_case("inner", rng, x_sign=(1 if i % 2 else -1)))
        pt, qt, _ = literal_step(p, q, l0, m, 1)
        I1, I2 = E.actions(p, q)
        holds = E.printed_addform_residual(p, q, pt, I2, l0, m, I1) < mp.mpf(10) ** -30
        assert holds == (q[0] < q[1] and qt[0] < qt[1])
        seen.add(holds)
    assert seen == {True, False}


# --------------------------------------------------------------------------- claims

def test_elliptic_claims():
    from symbt.claims import REGISTRY, load_all

    load_all()
    ids = {c for c in REGISTRY if REGISTRY[c].scene == "elliptic"}
    # pinned outcomes (README, "Errata found"): a change of status must be deliberate
    expected = {"th1th2.actions": "verified", "addform.regimes": "verified", "th1th2.F": "erratum",
                "th1th2.brackets": "erratum", "AA2.n2": "erratum", "citn.theta1": "erratum",
                "citn.theta2": "erratum", "linBts": "erratum", "addform.n2": "erratum",
                "addform.continuation": "erratum"}
    assert ids == set(expected)
    for cid in sorted(ids):
        out = REGISTRY[cid].run()
        assert out.status == expected[cid], (cid, out.detail, out.counterexample)
        if out.status == "erratum":
            assert out.counterexample and out.corrected, cid


def test_certified_claims():
    pytest.importorskip("flint")
    from symbt.claims import REGISTRY, load_all

    load_all()
    for cid, status in (("addform.arb", "erratum"), ("addform.arb_real", "verified")):
        out = REGISTRY[cid].run()
        assert out.status == status, (cid, out.detail)


def test_certified_wrong_formula_excluded():
    pytest.importorskip("flint")
    from symbt.claims.certified import _prec, certified_residuals

    case = E.sample_case("inner", random.Random(3))
    with _prec(170):
        good, _ = certified_residuals(case, 1)
        bad, _ = certified_residuals(case, 1, flip=True)
    assert all(r.contains(0) for r in good)
    assert not all(r.contains(0) for r in bad)
