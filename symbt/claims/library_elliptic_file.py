r"""The independent routes checked, 6: whole functions of :mod:`symbt.reference.elliptic`,
:mod:`~symbt.reference.taylor` and :mod:`~symbt.reference.inverse` across their branches (scene ``library``; fresh
samples of ``symbt mutate --source``, docs/mutation.md, "Fresh samples of symbt/reference/elliptic.py, taylor.py,
inverse.py").  Each observes every documented output of its functions in every zone, sign and mode, against a route
that does not share their derivation.

* ``library.abel_cell`` -- :func:`symbt.reference.elliptic.abel` at real ``s`` in every zone (``|s| <= 1``, the
  gaps ``1 < |s| < 1/k``, ``|s| >= 1/k``; both signs, both band edges ``s = +-1``) and at complex ``s``, on both
  sheets (``+-w``): ``sn u = s`` and ``cn u dn u = w`` by mpmath's ``ellipfun`` (not the Carlson integrals abel
  sums), and ``u`` in the closed period cell ``-K <= Re u <= 3K``, ``|Im u| <= K'`` its docstring states, with
  ``K, K'`` by the arithmetic-geometric mean; for real ``|s| <= 1`` (the real oval, ``s = +-1`` included) ``u`` is
  real, an ``mpf`` (the module docstring: ``v = F(|s|)``; seed 26: at ``|s| = 1`` the gap's form ``K + i F(0)``, a
  complex number); :func:`~symbt.reference.elliptic.lattice_residual` of
  ``e + 4K a + 2iK' b`` is ``|e|`` for lattice vectors of every sign.
* ``library.F_forms`` -- :func:`~symbt.reference.elliptic.F` is Legendre's ``ellipf(asin z, k^2)`` on ``[-1, 1]``
  (both signs; the library sums Carlson's form) and refuses ``|z| > 1``; :func:`~symbt.reference.elliptic.F_real`
  is ``F`` on ``[-1, 1]``, ``-F(1/(k s))`` on ``|s| >= 1/k``, its derivative (central differences) is
  ``1/|sqrt((1 - s^2)(1 - k^2 s^2))|`` on the three real pieces (both signs) and it refuses both gaps;
  :func:`~symbt.reference.elliptic.F_principal` is ``z R_F(1 - z^2, 1 - k^2 z^2, 1)`` (mpmath ``elliprf``) at
  complex ``z``; :func:`~symbt.reference.elliptic.theta2_printed` with its ``m`` override is
  ``F(P, sqrt m)/sqrt(I_2 + 2)``; :func:`~symbt.reference.elliptic.angles` is ``(q_1 + q_2, u/sqrt(I_2 + 2))`` with
  ``sn u = P``, ``cn u = C`` (``ellipfun``) and ``|u| <= 2K``; :func:`~symbt.reference.elliptic.g_real` is
  ``sgn(T) log((|T| + sqrt(T^2 - 4))/2)``.
* ``library.shift_fields`` -- :func:`~symbt.reference.elliptic.shift` in every regime, both branches: ``T1, T2`` are
  ``tr L(lam0 +- mu)`` by the literal trace, ``s_plus, s_minus`` and ``m`` are those of ``I_1, I_2`` read off the
  literal trace, ``v1, v2`` are the eigenvalues of ``L(lam0 +- mu)`` (``v + 1/v = T``) with
  ``v1 - 1/v1 = -gamma_1``, ``v2 - 1/v2 = gamma_2``, ``gamma = b sqrt(T^2 - 4)``, ``exp(dtheta1) = v1 v2`` with the
  principal ``|Im| <= pi``, ``dtheta2 sqrt(I_2 + 2) = du`` and ``du`` carries the Abel image of ``lambda_-`` to that
  of ``lambda_+`` (``sn``, ``cn dn`` by ``ellipfun``); the points of
  :func:`~symbt.reference.elliptic.spectral_point` lie on the curve ``w^2 = (1 - s^2)(1 - m s^2)``, and
  :func:`~symbt.reference.elliptic.curve_point`'s ``w`` is ``cn u dn u`` at the state's global angle.
* ``library.addition_third`` -- :func:`~symbt.reference.elliptic.addition_residual`'s third term: with ``E~`` scaled
  by ``f`` (the ratio kept) the residual is ``|f^2 - 1| |X| / max(1, |X|)``, ``X = e^{q_1 + q_2} v_1 v_2`` from the
  literal trace's eigenvalues, at states with ``|X| < 1`` and ``> 1``; its ``du`` override is read (``+4K``: still a
  solution, ``+2K``: not).

Each is shown to fail on planted mutants in ``tests/test_killers_elliptic.py``.

>>> abel_cell.run().status
'verified'
"""
from __future__ import annotations

import random
from typing import Any

import mpmath as mp

from ..reference import elliptic as E
from ..reference.literal import literal_trace
from .base import Outcome, claim, failed
from .library_sampler import trace_actions as _actions


def _periods(m: mp.mpf) -> tuple[mp.mpf, mp.mpf]:
    """``(K, K')`` by the arithmetic-geometric mean (not ``ellipk``): ``K = pi / (2 agm(1, sqrt(1 - m)))``."""
    return mp.pi / (2 * mp.agm(1, mp.sqrt(1 - m))), mp.pi / (2 * mp.agm(1, mp.sqrt(m)))



#: library.abel_cell: digits, the parameter m, real s (in units of 1 and of 1/k), complex s, lattice vectors
ABEL_DPS, ABEL_M = 15, mp.mpf(3) / 7
ABEL_REAL = ("0.3", "1")
ABEL_GAP = ("0.35",)                      # s = 1 + f (1/k - 1): inside the gap
ABEL_OUT = ("1.6",)                       # s = f / k
ABEL_COMPLEX = (("0.4", "0.3"), ("-1.5", "-0.8"))
LATTICE = ((1, 0), (-2, 1), (0, -1), (3, 2), (-1, -3))


@claim("library.abel_cell", equation="addform", scene="library", N=2,
       where="symbt.reference.elliptic.abel, lattice_residual and sn_cn_dn",
       statement="abel(s, +-w, m) (m = 3/7, 15 digits) at real s in every zone (|s| <= 1, both gaps, |s| >= 1/k; both "
                 "signs, s = +-1) and at complex s: sn u = s and cn u dn u = w by mpmath ellipfun within "
                 "10^(4 - dps) max(1, |s|, |w|), u in the period cell -K <= Re u <= 3K, |Im u| <= K' (K, K' by the "
                 "AGM), u real (an mpf) for real |s| <= 1; lattice_residual(e + 4Ka + 2iK'b) = |e| for 5 lattice "
                 "vectors")
def abel_cell() -> Outcome:
    bad: list[str] = []
    n, worst = 0, mp.mpf(0)
    with mp.workdps(ABEL_DPS):
        m = ABEL_M
        k = mp.sqrt(m)
        K, Kp = _periods(m)
        tol = mp.mpf(10) ** (4 - ABEL_DPS)
        real = [mp.mpf(v) for v in ABEL_REAL] + [1 + mp.mpf(f) * (1 / k - 1) for f in ABEL_GAP]
        real += [mp.mpf(f) / k for f in ABEL_OUT]
        points: list[mp.mpf | mp.mpc] = [sg * s for s in real for sg in (1, -1)]
        points += [mp.mpc(a, b) for a, b in ABEL_COMPLEX]
        for s in points:
            if isinstance(s, mp.mpc):   # principal roots (module docstring)
                W = mp.sqrt(1 - s * s) * mp.sqrt(1 - m * s * s)
            else:
                W = mp.sqrt((1 - s * s) * (1 - m * s * s))
            for w in ((W, -W) if W != 0 else (W,)):
                n += 1
                u = E.abel(s, w, m)
                sn, cn, dn = (mp.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
                err = max(abs(sn - s), abs(cn * dn - w)) / max(1, abs(s), abs(w))
                worst = max(worst, err)
                if not err <= tol:
                    bad.append(f"s = {mp.nstr(s, 6)}, w = {mp.nstr(w, 6)}: sn, cn dn off by {mp.nstr(err, 3)}")
                if isinstance(s, mp.mpf) and abs(s) <= 1 and not isinstance(u, mp.mpf):
                    bad.append(f"s = {mp.nstr(s, 6)}, w = {mp.nstr(w, 6)}: u = {mp.nstr(u, 8)} is not real (|s| <= 1: "
                               "v = F(|s|), a real integral)")
                slack = 1 + tol
                if not (-K * slack <= mp.re(u) <= 3 * K * slack and abs(mp.im(u)) <= Kp * slack):
                    bad.append(f"s = {mp.nstr(s, 6)}, w = {mp.nstr(w, 6)}: u = {mp.nstr(u, 8)} outside the cell "
                               f"[-K, 3K] x [-K', K'] (K = {mp.nstr(K, 8)}, K' = {mp.nstr(Kp, 8)})")
        if E.sn_cn_dn(u, m) != (sn, cn, dn):   # the last point: sn_cn_dn is ellipfun's three functions
            bad.append(f"u = {mp.nstr(u, 8)}: sn_cn_dn is not (sn, cn, dn) of ellipfun")
        e = mp.mpc("1e-3", "-2e-3")
        for a, b in LATTICE:
            got = E.lattice_residual(e + 4 * K * a + 2j * Kp * b, m)
            if not abs(got - abs(e)) <= tol * (abs(a) + abs(b) + 1):
                bad.append(f"lattice_residual(e + {4 * a}K + {2 * b}iK') = {mp.nstr(got, 8)}, "
                           f"|e| = {mp.nstr(abs(e), 8)}")
    detail = (f"{n} points (s, w), worst {mp.nstr(worst, 2)} (accepted 1e{4 - ABEL_DPS}); {len(LATTICE)} lattice "
              "vectors")
    if bad:
        return failed("abel vs ellipfun and the period cell", detail="; ".join(bad[:4]) + ". " + detail)
    return Outcome("verified", f"numeric: mpmath ellipfun and the AGM periods at {ABEL_DPS} digits",
                   evidence="sampled", n_scope=[2], residual=float(worst), detail=detail)


#: library.F_forms: digits, modulus, the real arguments of F, the real s of F_real (units 1 and 1/k), complex z
FORMS_DPS, FORMS_K = 25, mp.mpf("0.6")
FORMS_Z = ("-1", "-0.7", "-0.2", "0", "0.5", "1")
FORMS_IN, FORMS_OUT, FORMS_GAP = ("0.3", "-0.8"), ("1.2", "-3"), ("0.2", "-0.7")   # gap: s = +-(1 + f (1/k - 1))
FORMS_COMPLEX = (("0.4", "0.3"), ("-2", "0.5"), ("0.1", "-1.7"))
FORMS_STATES = ((("0.7", "-0.4"), ("0.3", "-0.5")), (("-0.7", "0.4"), ("-0.6", "0.2")),
                (("1.3", "0.2"), ("-1.1", "0.4")))
FORMS_T = ("2", "2.5", "40")


def _refused(f, *args, says: str = "") -> bool:
    """``f(*args)`` raises ValueError (whose message contains ``says``)."""
    try:
        f(*args)
    except ValueError as exc:
        return says in str(exc)
    return False


@claim("library.F_forms", equation="th1th2", scene="library", N=2,
       where="symbt.reference.elliptic.F, F_real, F_principal, theta2_printed (its m), angles and g_real",
       statement="F(z, k) = ellipf(asin z, k^2) on [-1, 1] (both signs), ValueError for |z| > 1; F_real = F on "
                 "[-1, 1], "
                 "-F(1/(k s)) on |s| >= 1/k (the edges s = +-1/k included), d F_real/ds = "
                 "1/|sqrt((1-s^2)(1-k^2 s^2))| (central differences) on the "
                 "three pieces, ValueError naming the gap in both gaps; F_principal(z) = z elliprf(1-z^2, 1-k^2z^2, "
                 "1) at complex z; "
                 "theta2_printed(p, q, m=m') = F(P, sqrt m')/sqrt(I2 + 2); angles = (q1 + q2, u/sqrt(I2 + 2)) with "
                 "sn u = P, cn u = C, |u| <= 2K; g_real(T) = sgn T log((|T| + sqrt(T^2 - 4))/2); 25 digits")
def F_forms() -> Outcome:
    bad: list[str] = []
    with mp.workdps(FORMS_DPS):
        k = FORMS_K
        m = k * k
        tol = mp.mpf(10) ** (5 - FORMS_DPS)
        for zs in FORMS_Z:
            z = mp.mpf(zs)
            if not abs(E.F(z, k) - mp.ellipf(mp.asin(z), m)) <= tol:
                bad.append(f"F({zs}) = {mp.nstr(E.F(z, k), 10)}, ellipf {mp.nstr(mp.ellipf(mp.asin(z), m), 10)}")
            if not abs(E.F_real(z, k) - mp.ellipf(mp.asin(z), m)) <= tol:
                bad.append(f"F_real({zs}) = {mp.nstr(E.F_real(z, k), 10)}, not F")
        for z in (mp.mpf("1.2"), mp.mpf("-1.2")):
            if not _refused(E.F, z, k):
                bad.append(f"F({mp.nstr(z, 3)}) did not raise ValueError")
        for ss in FORMS_OUT:
            s = mp.mpf(ss) / k
            want = -mp.ellipf(mp.asin(1 / (k * s)), m)
            if not abs(E.F_real(s, k) - want) <= tol:
                bad.append(f"F_real({ss}/k) = {mp.nstr(E.F_real(s, k), 10)}, -F(1/(ks)) = {mp.nstr(want, 10)}")
        for s in (2, -2):          # the outer edges |s| = 1/k exactly (k = 1/2: k s = +-1 with no rounding)
            want = -mp.sign(s) * mp.ellipk(mp.mpf(1) / 4)
            half = mp.mpf(1) / 2
            if _refused(E.F_real, mp.mpf(s), half) or not abs(E.F_real(mp.mpf(s), half) - want) <= tol:
                bad.append(f"F_real({s}, 1/2) at the edge |s| = 1/k: want -sgn(s) K(1/4) = {mp.nstr(want, 10)}")
        for ss in FORMS_IN + FORMS_OUT:
            s = mp.mpf(ss) / (k if ss in FORMS_OUT else 1)
            slope = mp.diff(lambda x: E.F_real(x, k), s)
            want = 1 / abs(mp.sqrt((1 - s * s) * (1 - m * s * s)))
            if not abs(slope - want) <= tol * want:
                bad.append(f"F_real' at {mp.nstr(s, 6)}: {mp.nstr(slope, 10)}, want {mp.nstr(want, 10)}")
        for gs in FORMS_GAP:
            g = mp.mpf(gs)
            s = mp.sign(g) * (1 + abs(g) * (1 / k - 1))
            if not 1 < abs(s) < 1 / k:
                bad.append(f"control: {mp.nstr(s, 6)} is not in a gap")
            elif not _refused(E.F_real, s, k, says="in a gap"):
                bad.append(f"F_real({mp.nstr(s, 6)}) in a gap did not raise ValueError saying so")
        for a, b in FORMS_COMPLEX:
            z = mp.mpc(a, b)
            want = z * mp.elliprf(1 - z * z, 1 - m * z * z, 1)
            if not abs(E.F_principal(z, k) - want) <= tol * max(1, abs(want)):
                bad.append(f"F_principal({mp.nstr(z, 4)}) = {mp.nstr(E.F_principal(z, k), 10)}, elliprf "
                           f"{mp.nstr(want, 10)}")
        for ps, qs in FORMS_STATES:
            p, q = [mp.mpf(v) for v in ps], [mp.mpf(v) for v in qs]
            I1, I2 = _actions(p, q)
            r = mp.sqrt(I2 - 2)
            P, C = (p[1] - p[0]) / (2 * r), 2 * mp.sinh((q[0] - q[1]) / 2) / r
            mo = mp.mpf("0.37")
            want = mp.ellipf(mp.asin(P), mo) / mp.sqrt(I2 + 2)
            if not abs(E.theta2_printed(p, q, m=mo) - want) <= tol:
                bad.append(f"theta2_printed(m = 0.37) = {mp.nstr(E.theta2_printed(p, q, m=mo), 10)}, "
                           f"want {mp.nstr(want, 10)}")
            th1, th2 = E.angles(p, q)
            mm = (I2 - 2) / (I2 + 2)
            u = th2 * mp.sqrt(I2 + 2)
            K, _ = _periods(mm)
            res = max(abs(th1 - q[0] - q[1]), abs(mp.ellipfun("sn", u, m=mm) - P), abs(mp.ellipfun("cn", u, m=mm) - C))
            if not (res <= tol and abs(u) <= 2 * K * (1 + tol)):
                bad.append(f"angles{ps, qs} = ({mp.nstr(th1, 8)}, {mp.nstr(th2, 8)}): off by {mp.nstr(res, 3)} or "
                           f"|u| > 2K")
        for ts in FORMS_T:
            for sg in (1, -1):
                T = sg * mp.mpf(ts)
                want = sg * mp.log((abs(T) + mp.sqrt(T * T - 4)) / 2)
                if not abs(E.g_real(T) - want) <= tol:
                    bad.append(f"g_real({mp.nstr(T, 4)}) = {mp.nstr(E.g_real(T), 10)}, want {mp.nstr(want, 10)}")
    detail = (f"F at {len(FORMS_Z)} points, F_real on its three pieces and both gaps, F_principal at "
              f"{len(FORMS_COMPLEX)} complex points, theta2_printed and angles at {len(FORMS_STATES)} states, g_real "
              f"at {2 * len(FORMS_T)} traces (accepted 1e{5 - FORMS_DPS})")
    if bad:
        return failed("the forms of F vs Legendre, Carlson and the definitions", detail="; ".join(bad[:4]) + ". "
                      + detail)
    return Outcome("verified", f"numeric: mpmath ellipf, elliprf, ellipfun, diff at {FORMS_DPS} digits",
                   evidence="sampled", n_scope=[2], detail=detail)


#: library.shift_fields: digits, one case per regime (rng seed)
SHIFT_DPS, SHIFT_SEED = 25, "efile shift"


@claim("library.shift_fields", equation="citn", scene="library", N=2,
       where="symbt.reference.elliptic.shift, spectral_point and curve_point",
       statement="shift(I1, I2, lam0, mu, b) (N = 2, one sample_case per regime, b = +-1, 25 digits): T1, T2 = "
                 "tr L(lam0 +- mu) by the literal trace; s_plus, s_minus, m from I1, I2 read off the literal trace; "
                 "v + 1/v = T for v1, v2, v1 - 1/v1 = -gamma1, v2 - 1/v2 = gamma2 (gamma = b sqrt(T^2 - 4)); "
                 "exp(dtheta1) = v1 v2, |Im dtheta1| <= pi; dtheta2 sqrt(I2 + 2) = du; sn, cn dn of A(lambda-) + du "
                 "are s_plus, w_plus (ellipfun); spectral points on w^2 = (1 - s^2)(1 - m s^2); curve_point's w = "
                 "cn u dn u at the global angle; within 10^(6 - dps) of the sizes")
def shift_fields() -> Outcome:
    bad: list[str] = []
    n = 0
    rng = random.Random(SHIFT_SEED)
    with mp.workdps(SHIFT_DPS):
        tol = mp.mpf(10) ** (6 - SHIFT_DPS)

        def off(a: mp.mpf | mp.mpc, b: mp.mpf | mp.mpc) -> bool:
            return not abs(a - b) <= tol * max(1, abs(a), abs(b))

        for reg in E.REGIMES:
            ps, qs, l0s, ms = E.sample_case(reg, rng)
            p, q, L0, M = [mp.mpf(v) for v in ps], [mp.mpf(v) for v in qs], mp.mpf(l0s), mp.mpf(ms)
            I1, I2 = _actions(p, q)
            r, m = mp.sqrt(I2 - 2), (I2 - 2) / (I2 + 2)
            Tp, Tm = literal_trace(L0 + M, p, q), literal_trace(L0 - M, p, q)
            u, _ = E.global_u(p, q)
            P = (p[1] - p[0]) / (2 * r)
            _, w = E.curve_point(P, mp.exp(q[0]), mp.exp(q[1]), I2)
            if off(w, mp.ellipfun("cn", u, m=m) * mp.ellipfun("dn", u, m=m)):
                bad.append(f"{reg}: curve_point's w = {mp.nstr(w, 8)}, cn dn at the global angle differs")
            for b in (1, -1):
                n += 1
                sh: dict[str, Any] = E.shift(I1, I2, L0, M, b)   # every field but dtheta1_real is a number
                g1, g2 = b * mp.sqrt(Tp ** 2 - 4), b * mp.sqrt(Tm ** 2 - 4)
                checks = {"T1": (sh["T1"], Tp), "T2": (sh["T2"], Tm), "m": (sh["m"], m),
                          "s_plus": (sh["s_plus"], (L0 + M + I1) / r), "s_minus": (sh["s_minus"], (L0 - M + I1) / r),
                          "v1 + 1/v1": (sh["v1"] + 1 / sh["v1"], Tp), "v2 + 1/v2": (sh["v2"] + 1 / sh["v2"], Tm),
                          "v1 - 1/v1": (sh["v1"] - 1 / sh["v1"], -g1), "v2 - 1/v2": (sh["v2"] - 1 / sh["v2"], g2),
                          "exp dtheta1": (mp.exp(sh["dtheta1"]), sh["v1"] * sh["v2"]),
                          "dtheta2": (sh["dtheta2"] * mp.sqrt(I2 + 2), sh["du"])}
                for name, (got, want) in checks.items():
                    if off(got, want):
                        bad.append(f"{reg}, b = {b}: {name} = {mp.nstr(got, 8)}, want {mp.nstr(want, 8)}")
                if not abs(mp.im(sh["dtheta1"])) <= mp.pi:
                    bad.append(f"{reg}, b = {b}: dtheta1 = {mp.nstr(sh['dtheta1'], 8)} not the principal log")
                pts = [E.spectral_point(lam, I1, I2, b) for lam in (L0 + M, L0 - M)]
                for s, wv, T, g in pts:
                    if off(wv ** 2, (1 - s * s) * (1 - m * s * s)) or off(g ** 2, T ** 2 - 4):
                        bad.append(f"{reg}, b = {b}: spectral_point ({mp.nstr(s, 6)}, {mp.nstr(wv, 6)}) off the curve")
                a2 = E.abel(pts[1][0], pts[1][1], m) + sh["du"]
                sn, cn, dn = (mp.ellipfun(f, a2, m=m) for f in ("sn", "cn", "dn"))
                if off(sn, pts[0][0]) or off(cn * dn, pts[0][1]):
                    bad.append(f"{reg}, b = {b}: A(lambda-) + du does not reach (s_plus, w_plus)")
    detail = f"{n} shifts ({len(E.REGIMES)} regimes, both branches), accepted 1e{6 - SHIFT_DPS} relative"
    if bad:
        return failed("shift's fields vs the literal trace and ellipfun", detail="; ".join(bad[:4]) + ". " + detail)
    return Outcome("verified", f"numeric: the literal trace and mpmath ellipfun at {SHIFT_DPS} digits",
                   evidence="sampled", n_scope=[2], detail=detail)


#: library.addition_third: digits, the rng seed of an outer-same case (e^{q1 + q2} v1 v2 far from 1), the move of E~
ADD3_DPS, ADD3_SEED, ADD3_F, ADD3_DRAWS = 20, "efile addition third", mp.mpf("1e-6"), 40


@claim("library.addition_third", equation="addform", scene="library", N=2,
       where="symbt.reference.elliptic.addition_residual (its third term; the du override)",
       statement="with E~ moved to (E~_1 f, E~_2 f), f = 1 +- 1e-6 (the ratio kept: sn and cn dn unchanged), "
                 "addition_residual at a step2 step is |f^2 - 1| |X| / max(1, |X|), X = e^{q1 + q2} v1 v2 = E~_1 E~_2 "
                 "(v by the literal trace's eigenvalues), within twice the unmoved residual, at a state with |X| "
                 "< 1 and one with |X| > 1; with du overridden by the shift + 4K the residual stays below 10^(12 - "
                 "dps), by the shift + 2K it is >= 1 (sn(u + 2K) = -sn u)")
def addition_third() -> Outcome:
    bad: list[str] = []
    sizes: set[bool] = set()
    rng = random.Random(ADD3_SEED)
    with mp.workdps(ADD3_DPS):
        for _ in range(ADD3_DRAWS):
            if len(sizes) == 2:
                break
            p, q, l0, m = E.sample_case("outer-same", rng)
            P, Q, L0, M = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m)
            _, I2 = _actions(P, Q)
            b = 1
            pt, _, info = E.step2(P, Q, L0, M, b)
            Et = info["E_new"]
            X = Et[0] * Et[1]
            if abs(abs(X) - 1) < mp.mpf("0.1") or (abs(X) > 1) in sizes:
                continue
            sizes.add(abs(X) > 1)
            # X from the eigenvalues v of L(lam0 +- mu): v + 1/v = T by the literal trace (v1 the root of branch b)
            T1, T2 = literal_trace(L0 + M, P, Q), literal_trace(L0 - M, P, Q)
            v1, v2 = (T1 - b * mp.sqrt(T1 ** 2 - 4)) / 2, (T2 + b * mp.sqrt(T2 ** 2 - 4)) / 2
            if not abs(mp.exp(Q[0] + Q[1]) * v1 * v2 - X) <= mp.mpf(10) ** (10 - ADD3_DPS) * max(1, abs(X)):
                bad.append(f"control: E~_1 E~_2 = {mp.nstr(X, 8)}, e^(q1+q2) v1 v2 differs")
                continue
            res0 = E.addition_residual(P, Q, L0, M, b, pt=pt, Et=Et)
            for f in (1 + ADD3_F, 1 - ADD3_F):
                want = abs(f * f - 1) * abs(X) / max(1, abs(X))
                got = E.addition_residual(P, Q, L0, M, b, pt=pt, Et=[Et[0] * f, Et[1] * f])
                if not abs(got - want) <= 2 * res0 + mp.mpf(10) ** (2 - ADD3_DPS):
                    bad.append(f"|X| = {mp.nstr(abs(X), 4)}, f = {mp.nstr(f, 8)}: residual {mp.nstr(got, 6)}, "
                               f"want {mp.nstr(want, 6)}")
            du = E.shift(*E.actions(P, Q), L0, M, b)["du"]
            K = mp.ellipk((I2 - 2) / (I2 + 2))
            r4 = E.addition_residual(P, Q, L0, M, b, pt=pt, Et=Et, du=du + 4 * K)
            r2 = E.addition_residual(P, Q, L0, M, b, pt=pt, Et=Et, du=du + 2 * K)
            if not (r4 <= mp.mpf(10) ** (12 - ADD3_DPS) and r2 >= mp.mpf("1e-3")):
                bad.append(f"|X| = {mp.nstr(abs(X), 4)}: du + 4K gives {mp.nstr(r4, 3)}, du + 2K {mp.nstr(r2, 3)}")
    if sizes != {True, False}:
        bad.append(f"control: the cases drawn have |X| > 1 only {sizes}")
    detail = "two outer-same steps (|E~_1 E~_2| < 1 and > 1), E~ scaled by 1 +- 1e-6; du + 4K and du + 2K"
    if bad:
        return failed("addition_residual's third term and du", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", f"numeric: {ADD3_DPS} digits, the literal trace's eigenvalues", evidence="sampled",
                   n_scope=[2], detail=detail)


from . import library_elliptic_flows  # noqa: E402,F401 -- registers the flow and inverse claims of this file's set
