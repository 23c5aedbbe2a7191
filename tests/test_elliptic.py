"""N = 2 action-angle variables, the addition formula (symbt.reference.elliptic; scenes elliptic, certified)."""
from __future__ import annotations

import random

import mpmath as mp
import numpy as np
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


# --------------------------------------------------------------------------- F, modulus vs parameter, Carlson

@pytest.mark.parametrize("z", ["-0.9", "-0.3", "0", "0.5", "0.99"])
def test_F_is_incomplete_jacobi_form_with_parameter_k2(z):
    z, k = mp.mpf(z), mp.mpf("0.7")
    alg = mp.quad(lambda t: 1 / mp.sqrt((1 - t ** 2) * (1 - k ** 2 * t ** 2)), [0, z])
    assert abs(E.F(z, k) - alg) < mp.mpf(10) ** -30
    assert abs(E.F(z, k) - mp.ellipf(mp.asin(z), k ** 2)) < mp.mpf(10) ** -35
    if z != 0:  # passing the modulus where mpmath expects the parameter is a different function
        assert abs(mp.ellipf(mp.asin(z), k) - alg) > mp.mpf(10) ** -4


@pytest.mark.parametrize("dps", [20, 30, 50])
def test_carlson_rf_matches_mpmath_real_and_complex(dps):
    rng = random.Random(dps)
    with mp.workdps(dps):
        for i in range(40):
            if i % 2:
                args = [mp.mpc(rng.uniform(-3, 3), rng.uniform(-3, 3)) for _ in range(3)]
            else:
                args = [mp.mpf(rng.uniform(0, 3)) for _ in range(3)]
            ref = mp.elliprf(*args)
            assert abs(E.carlson_rf(*args) - ref) <= abs(ref) * mp.mpf(10) ** -(dps - 2)


def test_F_refuses_beyond_one_and_F_real_refuses_gap():
    k = mp.mpf("0.6")
    with pytest.raises(ValueError):
        E.F(mp.mpf("1.2"), k)
    with pytest.raises(ValueError):
        E.F_real(mp.mpf("1.2"), k)  # 1 < 1.2 < 1/k
    assert E.F_real(mp.mpf(3), k) == -E.F_real(mp.mpf(-3), k)


# --------------------------------------------------------------------------- the map for N = 2

@pytest.mark.parametrize("reg", E.REGIMES)
def test_step2_is_literal_step(reg):
    rng = random.Random(reg)
    for _ in range(3):
        p, q, l0, m = _mp(E.sample_case(reg, rng))
        for b in (1, -1):
            a = E.step2(p, q, l0, m, b)
            c = literal_step(p, q, l0, m, b)
            for x, y in zip(a[0] + a[1] + a[2]["E_new"], c[0] + c[1] + c[2]["E_new"]):
                assert abs(x - y) < mp.mpf(10) ** -33


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

@pytest.mark.parametrize("s", ["0.4", "-0.8", "1.1", "-1.2", "2.5", "-4", "1.3+0.4j", "-0.2-1.1j", "3-0.01j"])
@pytest.mark.parametrize("sheet", [1, -1])
def test_abel_inverts_sn_and_cndn(s, sheet):
    m = mp.mpf(3) / 7
    s = mp.mpmathify(complex(s)) if "j" in s else mp.mpf(s)
    w = sheet * mp.sqrt(1 - s ** 2) * mp.sqrt(1 - m * s ** 2)
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
def test_corrected_addition_formula_forward_and_by_lattice(reg, branch, x_sign):
    """The forward check (sn, cn dn at u + du) and the lattice test of the claims agree."""
    rng = random.Random(f"{reg}/{branch}/{x_sign}")  # str seeds are deterministic
    for _ in range(2):
        p, q, l0, m = _mp(E.sample_case(reg, rng, x_sign=x_sign))
        assert E.regime_of_state(p, q, l0, m) == reg
        pt, qt, info = literal_step(p, q, l0, m, branch)
        assert E.addition_residual(p, q, l0, m, branch, pt=pt, qt=qt, Et=info["E_new"]) < mp.mpf(10) ** -30
        I, It = E.actions(p, q), E.actions(pt, qt)
        assert abs(I[0] - It[0]) < mp.mpf(10) ** -30 and abs(I[1] - It[1]) < mp.mpf(10) ** -30
        I1, I2 = I
        k, mm = E.modulus(I2)
        sh = E.shift(I1, I2, l0, m, branch)
        Et = info["E_new"]
        P, w = E.curve_point((p[1] - p[0]) / (2 * mp.sqrt(I2 - 2)), mp.exp(q[0]), mp.exp(q[1]), I2)
        Pt, wt = E.curve_point((pt[1] - pt[0]) / (2 * mp.sqrt(I2 - 2)), Et[0], Et[1], I2)
        d = E.abel(Pt, wt, mm) - E.abel(P, w, mm) - sh["du"]
        assert E.lattice_residual(d, mm) < mp.mpf(10) ** -30
        assert E.lattice_residual(d + sh["du"] / 3, mm) > mp.mpf(10) ** -3
        if reg in ("inner", "outer-same"):  # real form, mod 4K
            d = E.global_u(pt, qt)[0] - E.global_u(p, q)[0] - branch * (E.F_real(sh["s_plus"], k)
                                                                       - E.F_real(sh["s_minus"], k))
            K4 = 4 * mp.ellipk(mm)
            assert abs(d - K4 * mp.nint(d / K4)) < mp.mpf(10) ** -30
            assert abs((qt[0] + qt[1]) - (q[0] + q[1]) - sh["dtheta1_real"]) < mp.mpf(10) ** -30


def test_iterates_need_the_curve_points_of_the_first_step():
    """From a complex state (gap regime) tr^2 - 4 < 0 carries rounding noise: with the gammas of the first
    step the iterates follow u_n = u_0 + n du."""
    p, q, l0, m = _mp(E.sample_case("gap", random.Random(7)))
    I1, I2 = E.actions(p, q)
    _, mm = E.modulus(I2)
    sh = E.shift(I1, I2, l0, m, 1)
    pt, qt, info = E.step2(p, q, l0, m, 1)
    g = (info["gamma1"], info["gamma2"])
    u0 = E.abel(*E.curve_point((p[1] - p[0]) / (2 * mp.sqrt(I2 - 2)), mp.exp(q[0]), mp.exp(q[1]), I2), mm)
    for n in (2, 3):
        pt, qt, info = E.step2(pt, qt, l0, m, 1, gammas=g)
        Et = info["E_new"]
        un = E.abel(*E.curve_point((pt[1] - pt[0]) / (2 * mp.sqrt(I2 - 2)), Et[0], Et[1], I2), mm)
        assert E.lattice_residual(un - u0 - n * sh["du"], mm) < mp.mpf(10) ** -28


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


def test_printed_addform_in_inner_regime():
    """All F real: the printed formula holds iff b sgn(q1-q2) = -1 and the step keeps sgn(q1-q2)."""
    rng = random.Random(5)
    seen = set()
    for i in range(16):
        p, q, l0, m = _mp(E.sample_case("inner", rng, x_sign=(1 if i % 2 else -1)))
        I1, I2 = E.actions(p, q)
        for b in (1, -1):
            pt, qt, _ = literal_step(p, q, l0, m, b)
            holds = E.printed_addform_residual(p, q, pt, I2, l0, m, I1) < mp.mpf(10) ** -30
            x0, x1 = mp.sign(q[0] - q[1]), mp.sign(qt[0] - qt[1])
            assert holds == (x0 == x1 and b * x0 == -1)
            seen.add(holds)
    assert seen == {True, False}


# --------------------------------------------------------------------------- claim helpers

def test_principal_F_fast_path_is_mpmaths_ellipf():
    from symbt.claims._elliptic import _F_principal

    rng = random.Random(3)
    with mp.workdps(30):
        for _ in range(30):
            m = mp.mpf(rng.uniform(0.05, 0.95))
            for z in (mp.mpf(rng.uniform(-0.99, 0.99)), mp.mpc(rng.uniform(-3, 3), rng.uniform(-2, 2)),
                      mp.mpf(rng.uniform(1.01, 4))):
                ref = mp.ellipf(mp.asin(z), m)
                assert abs(_F_principal(z, m) - ref) <= mp.mpf(10) ** -27 * max(1, abs(ref))


def test_quadrature_of_the_AA2_integrands():
    """quad_many (float64, pieces between the zeros of tr -+ 2) against mp.quad cut at the exact zeros,
    within the tolerance QTOL of claim AA2.n2, in every regime (crossing the gaps included)."""
    from symbt.claims._elliptic import QTOL, breaks, quad_many

    def f(x, a1, a2, b):
        T = (x + a1) ** 2 - a2
        return b / np.sqrt((T ** 2 - 4).astype(complex))

    rng = random.Random(11)
    jobs, ref = [], []
    for reg in E.REGIMES:
        for _ in range(3):
            p, q, l0, m = _mp(E.sample_case(reg, rng))
            I1, I2 = E.actions(p, q)
            jobs.append((float(l0 - m), float(l0 + m), breaks(float(I1), float(I2)), (float(I1), float(I2), 1.0)))
            with mp.workdps(25):
                roots = [-I1 + s * mp.sqrt(I2 + c) for s in (1, -1) for c in (2, 0, -2)]
                cuts = [l0 - m] + sorted(x for x in roots if l0 - m < x < l0 + m) + [l0 + m]
                ref.append(complex(mp.quad(lambda x: 1 / mp.sqrt(((x + I1) ** 2 - I2) ** 2 - 4), cuts)))
    got = quad_many(f, jobs)
    for g, r in zip(got, ref):
        assert abs(g - r) < QTOL / 10 * max(1, abs(r))


def test_scoped_table_lists_cells_where_a_statement_does_not_apply():
    from symbt.claims._elliptic import ScopedTable

    t = ScopedTable(tol=1e-30)
    t.add({"regime": "inner"}, printed=0.0)
    t.add_na({"regime": "gap"}, "no real image")
    assert t.printed_holds_everywhere()
    assert "does not apply in 1 cells (no real image, at 1/1 samples): {regime=gap}" in t.scope()
    assert {"cell": {"regime": "gap"}, "n": 1, "applies": False, "reason": "no real image"} in t.cells()


# --------------------------------------------------------------------------- claims

EXPECTED = {"th1th2.actions": "verified", "addform.regimes": "verified", "th1th2.F": "erratum",
            "th1th2.brackets": "erratum", "AA2.n2": "erratum", "citn.theta1": "erratum",
            "citn.theta2": "erratum", "linBts": "erratum", "addform.n2": "erratum",
            "addform.continuation": "erratum"}


@pytest.fixture(scope="module")
def elliptic_outcomes():
    from symbt.claims import REGISTRY, load_all

    load_all()
    ids = {c for c in REGISTRY if REGISTRY[c].scene == "elliptic"}
    assert ids == set(EXPECTED)
    return {cid: REGISTRY[cid].run() for cid in sorted(ids)}


def test_elliptic_claims(elliptic_outcomes):
    # pinned outcomes (docs/claims.md, "Errata found"): a change of status must be deliberate
    for cid, out in elliptic_outcomes.items():
        assert out.status == EXPECTED[cid], (cid, out.detail, out.counterexample)
        assert out.n_scope == [2] and out.evidence == "sampled", cid
        if out.status == "erratum":
            assert out.counterexample and out.corrected, cid
            assert "corrected statement holds in all" in out.scope, (cid, out.scope)


def test_elliptic_cells_cover_every_regime_branch_and_orientation(elliptic_outcomes):
    for cid in ("th1th2.actions", "AA2.n2", "citn.theta1", "citn.theta2", "linBts", "addform.n2", "addform.regimes"):
        cells = elliptic_outcomes[cid].cells
        keys = {(c["cell"]["regime"], c["cell"]["branch"], c["cell"]["sign_q1_q2"]) for c in cells}
        assert keys == {(r, b, x) for r in E.REGIMES for b in (1, -1) for x in (1, -1)}, cid
        assert all(c["n"] >= 16 for c in cells), cid
    # the printed angle is the global one for q1 > q2 only: generated, not written
    scope = elliptic_outcomes["th1th2.brackets"].scope
    assert "holds exactly in cells {sign_q1_q2=+1, sign_p2_p1=+1}, {sign_q1_q2=+1, sign_p2_p1=-1}" in scope
    # citn.theta1 as printed: right for b = +1 where tr L > 2 and for b = -1 where tr L < -2
    s1 = elliptic_outcomes["citn.theta1"].scope
    assert "{regime=outer-same, branch=+1, sign_q1_q2=+1}" in s1.split(" and ")[0]
    assert "{regime=inner, branch=-1, sign_q1_q2=+1}" in s1.split(" and ")[0]


def test_certified_claims():
    pytest.importorskip("flint")
    from symbt.claims import REGISTRY, load_all

    load_all()
    for cid, status in (("addform.arb", "erratum"), ("addform.arb_real", "verified")):
        out = REGISTRY[cid].run()
        assert out.status == status, (cid, out.detail)
        assert out.evidence == "certified" and out.n_scope == [2], cid
    real = REGISTRY["addform.arb_real"].run()
    na = [c for c in real.cells if c.get("applies") is False]
    assert {c["cell"]["regime"] for c in na} == {"outer-opposite", "mixed", "gap"}


def test_certified_wrong_formula_excluded():
    pytest.importorskip("flint")
    import sympy as sp

    from symbt.claims import load_all
    from symbt.claims._elliptic import map_samples
    from symbt.claims.certified import FNS, PREC, _case, _env, _parts_arb, _prec, _residual, arb_fn

    load_all()
    shift = _parts_arb().corrected["shift"]
    s = next(x for x in map_samples(16) if x.cell["regime"] == "inner")
    with _prec(PREC):
        c = _case(s.key, s.b, PREC)
        for expr, ok in ((shift, True), (-shift, False), (2 * shift, False), (shift + sp.Rational(1, 10**6), False)):
            sn, cn, dn = c["J"].sncndn(c["u"] + arb_fn(expr, FNS)(_env(c)))
            assert (_residual([sn - c["Pt"], cn * dn - c["wt"]]) <= 1e-30) == ok
