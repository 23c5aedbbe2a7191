"""Seed 18's survivors (docs/mutation.md, "Seed 18"): planted bugs that the new facts now see, and the proofs of the
mutants marked equivalent.  Unpatched, every claim verifies."""
from __future__ import annotations

import inspect
import math
import random
from fractions import Fraction

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from planting import claim_fails as fails
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["checker.exact_route_names", "checker.codegen_metrics", "library.emit_typed", "library.linear",
          "library.spectral", "paths.qd.n2", "paths.qd.n3", "paths.many_rows.n3", "paths.next_prec.n3",
          "paths.panels", "library.qd_marker", "library.importable", "paths.lohner_reorth.n3",
          "paths.lohner_reorth.n13", "library.user_printer", "library.F_forms", "shipped.loop_xy.n5",
          "paths.enclosures.n3", "library.input_kinds"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


# --------------------------------------------------------------------------- planted bugs the facts see

def test_rational_power_of_an_exponential(monkeypatch):
    # exponentials:132 (`if r.is_Rational` -> `if not ...`): (e^q)^(1/2) as written is no exponential any more
    from symbt.proof import exponentials as E

    monkeypatch.setattr(E, "_exponent", planted(E._exponent, "        if r.is_Rational:",
                                                "        if not (r.is_Rational):"))
    assert fails("checker.exact_route_names")


def test_one_column_matrix(monkeypatch):
    # declare:121 (`c == 0` -> `c == 1`): a column vector refused as an empty matrix
    from symbt.codegen.user import declare

    monkeypatch.setattr(declare, "_elements", planted(declare._elements, "if r == 0 or c == 0:",
                                                      "if r == 0 or c == 1:"))
    assert fails("library.emit_typed")


def test_linear_without_sympy_solve(monkeypatch):
    # linear:37 (`!= 0` -> `!= 1`, and the test negated): a linear equation sent to sympy.solve
    from symbt.symbolic import linear

    for new in ("if sp.cancel(c1) != 1:", "if not (sp.cancel(c1) != 0):"):
        monkeypatch.setattr(linear, "solve_linear", planted(linear.solve_linear, "if sp.cancel(c1) != 0:", new))
        assert fails("library.linear"), new
        monkeypatch.undo()


def test_sampler_gives_up(monkeypatch):
    # samples:57 (`tries += 1` -> `+= 0`): the sampler never gives up; here the count of proposals is read back
    from symbt.reference import samples

    calls = []
    real = samples._real_map

    def counting(*args):
        calls.append(1)
        return real(*args)
    monkeypatch.setattr(samples, "_real_map", counting)
    with pytest.raises(RuntimeError):
        samples.admissible_states(2, 1, 5, max_proposals=3)
    assert len(calls) <= 2 * 3          # at most two maps (both branches) per proposal


def test_first_pass_precision(monkeypatch):
    # lohner:484 (`+ 5 bitlen(n)` -> `-`): the unforced first pass below the documented precision
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner, "lohner_certified", planted(
        lohner.lohner_certified, "target_bits + 24 + _BITS_PER_OCTAVE", "target_bits + 24 - _BITS_PER_OCTAVE"))
    assert fails("paths.next_prec.n3")      # the claim imports lohner_certified from the module when it runs


def test_points_take_both_signs(monkeypatch):
    # codegen.verify's points without a map: one sign of a coordinate only (seed 18's `uniform(-0, 1)` for c, now
    # the bit rule) -- the fact in checker.codegen_metrics
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "points", planted(verify.points, "return v if (k >> (bit % 3)) & 1 else -v",
                                                  "return v"))
    assert fails("checker.codegen_metrics")


def test_qd_marker(monkeypatch):
    # qd.py's cache marker (lines no default claim ran: the default run loads no numba, so nothing asked whether
    # the compiled kernel was ready).  Only a mutant that writes nothing is planted here: one that misses the
    # temporary NUMBA_CACHE_DIR would write its marker into the package's own __pycache__ (symbt mutate runs
    # mutants in a copy, where that is harmless; all 12 of those lines' mutants are killed there)
    pytest.importorskip("numba")
    from symbt.numeric.multiprec import qd

    monkeypatch.setattr(qd, "qd_ready", planted(qd.qd_ready, ".strip() == want:", ".strip() != want:"))
    assert fails("library.qd_marker")


@pytest.mark.parametrize("old, new, cid", [
    ("if work > max_prec:\n            break\n        passes.append(work)\n        ok,",
     "if work >= max_prec:\n            break\n        passes.append(work)\n        ok,", "paths.ball_schedule.n3"),
    ("else max(1, math.ceil(-math.log2(tol)))", "else min(1, math.ceil(-math.log2(tol)))", "paths.next_prec.n3")])
def test_certified_schedule(monkeypatch, old, new, cid):
    # certified:283 (the ball path refuses to run at max_prec itself), certified:273 (the target bits handed to the
    # Lohner schedule): lines the sample did not draw, found beside it
    pytest.importorskip("flint")
    import symbt.numeric as N
    from symbt.numeric.multiprec import certified

    monkeypatch.setattr(N, "certified_orbit", planted(certified.certified_orbit, old, new))
    assert fails(cid, crash=True)


def test_literal_step_refuses_other_signs():
    # literal_step's signs: +-1 only (a 0 would have taken the generic route with a vanishing root)
    from symbt.reference.literal import literal_step

    for kw in ({"branch": 0}, {"gamma_signs": (1, 0)}, {"gamma_signs": (2, -1)}):
        with pytest.raises(ValueError, match="must be \\+1 or -1"):
            literal_step([-20, 10, 1], [1, 0, 0.9], 10, 5, **kw)


def test_newton_step_on_a_singular_jacobian():
    from symbt.reference.inverse import _solve

    with pytest.raises(ZeroDivisionError):
        _solve(mp.matrix([[1, 2], [2, 4]]), [mp.mpf(1), mp.mpf(1)])
    # least squares where the equations outnumber the unknowns: the exact solution of a consistent system
    dx = _solve(mp.matrix([[1, 0], [0, 1], [1, 1]]), [mp.mpf(-1), mp.mpf(-2), mp.mpf(-3)])
    assert abs(dx[0] - 1) < mp.mpf(10) ** -14 and abs(dx[1] - 2) < mp.mpf(10) ** -14


# --------------------------------------------------------------------------- the equivalences' proofs

def test_zero_trace_stops_at_the_trace_test():
    # marked equivalent: fused:142 (`tt[0] < 0.0` -> `<=`): tt[i] is the trace's leading double, and slopes returns OK
    # only when hi(disc) > 0 for disc = (t - two)(t + two); at t = +-0 that is -two^2 <= 0, so slopes returns the
    # trace code first and the sign test never sees a zero.  The premise on states whose trace is exactly 0 at lam1 or
    # lam2 (p = (2, 1), q = 0: tr L(0) = 2 * 1 - 2 = 0 in floating point), every float64 route
    from symbt.numeric import NoRealMapError, bt_step

    for lam0, mu, which in ((-2.0, 2.0, "lam1"), (2.0, -2.0, "lam1"), (2.0, 2.0, "lam2")):
        for be in ("python", "numpy"):
            with pytest.raises(NoRealMapError) as info:
                bt_step([2.0, 1.0], [0.0, 0.0], lam0, mu, backend=be)
            assert info.value.condition == "trace" and which in str(info.value)
    from symbt.numeric.core import fused

    src = inspect.getsource(fused)
    assert "if not hi(disc) > 0.0:\n        return code" in src       # the test that answers first


def _exact(t):
    return sum(Fraction(v) for v in t)


def test_mul_d_last_term_below_the_format():
    # qd_arith:270 (`q2 + p2` -> `q2 - p2` in mul_d), a survivor, not marked: p2 is the third output of
    # three_sum(s2, q1, p2), the rounding error of t2 + t3 (two rounding errors of sums of terms below u^2 |a b|),
    # so the sign flip moves the result by 2 |p2|, about u^4 |a b| at most: below the 2^-209 relative the
    # quad-double carries (QD_BITS), where no claim can see it -- yet it can change a last bit, so it is no
    # equivalence.  What holds: both products within 2^-209 |a b| of the exact one
    from symbt.numeric.multiprec import qd_arith as Q

    mutant = planted(Q.mul_d, "return renorm5(p0, s1, s2, q1, q2 + p2)", "return renorm5(p0, s1, s2, q1, q2 - p2)")
    rng = random.Random(270)
    worst = 0.0
    for k in range(4000):
        if k % 2:
            a = tuple(math.ldexp(rng.uniform(-1, 1), -53 * i) for i in range(4))
        else:
            a = tuple(math.ldexp((-1) ** i * rng.uniform(0.5, 1), -52 * i) for i in range(4))
        a = Q.renorm5(*a, 0.0)
        b = rng.uniform(-4, 4)
        exact = _exact(a) * Fraction(b)
        if exact == 0:
            continue
        for f in (Q.mul_d, mutant):
            worst = max(worst, abs(float((_exact(f(a, b)) - exact) / exact)))
    assert 0 < worst < 2.0 ** -209


# --------------------------------------------------------------------------- seed 19

@pytest.mark.parametrize("method, cid", [("_small_frame", "paths.lohner_reorth.n3"),
                                         ("_frame_of", "paths.lohner_reorth.n13")])
def test_reorthogonalisation_counted(monkeypatch, method, cid):
    # lohner:292 (and the small frame's twin): the re-orthogonalisation counter, which no claim's frame reached
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner.LohnerSet, method, planted(getattr(lohner.LohnerSet, method),
                                                          "self.reorthogonalised += 1", "self.reorthogonalised += 0"))
    assert fails(cid)


def test_broken_module_is_not_importable(monkeypatch):
    # errors:111 (seed 19, on no line a claim ran: a module whose import raises counted importable)
    from symbt.numeric.core import errors

    monkeypatch.setattr(errors, "importable", planted(errors.importable, "                ok = False",
                                                      "                ok = True"))
    assert fails("library.importable")


def test_anchor_range_test_order_is_equivalent():
    # marked equivalent: kernels:369 (`abs(qh[j]) < 1e300` -> `abs(qh[j - 1])` in _anchor1's second loop): over the
    # loop j = 0 .. N-1 the mutant tests qh[N-1], qh[0], .., qh[N-2] -- every position once, as the original does --
    # and both return RANGE as soon as one test fails; the dq and p tests are the same per j, and r (a work array)
    # is only read after OK.  So the status is the same, and r too where it is OK.  Checked on random states with
    # one position (or none) past 1e300, each position in turn, and with a dq or p failure beside it
    from symbt.numeric.float64 import kernels as K

    mutant = planted(K._anchor1, "abs(qh[j]) < 1e300):", "abs(qh[j - 1]) < 1e300):")
    rng = np.random.default_rng(369)
    for N in (2, 3, 5):
        for bad_at in [None] + list(range(N)):
            for p_bad in (None, 0, N - 1):
                qh, ql = rng.uniform(-5, 5, N), rng.uniform(-1e-17, 1e-17, N)
                if bad_at is not None:
                    qh[:] = 2e300                   # every dq 0, one position still past the range test's bound
                    qh[bad_at] = 3e300
                p = rng.uniform(-5, 5, N)
                if p_bad is not None:
                    p[p_bad] = 2e300
                fh, fl = rng.uniform(0.5, 2, N), np.zeros(N)
                outs = []
                for fn in (K._anchor1, mutant):
                    args = [x.copy() for x in (qh, ql, fh, fl)] + [np.zeros(N), p.copy()]
                    st = fn(*args)
                    outs.append((st, args[4].tolist() if st == K.OK else None, [a.tolist() for a in args[:4]]))
                assert outs[0] == outs[1], (N, bad_at, p_bad)


def test_zero_argument_c_function():
    # codegen.user.check's C evaluator passes an empty input array for a function of no arguments (user.check:205,
    # `max(n_in, 1)` -> `max(n_in, 0)`, seed 19: the guard went, an empty ctypes array is a valid pointer the
    # function never reads)
    import tempfile
    from pathlib import Path

    from symbt.codegen.user import check as C
    from symbt.codegen.user.declare import emit
    from symbt.codegen.user.files import generate

    if C.compiler() is None:
        pytest.skip("no C compiler")
    e = emit("zero_args", sp.Integer(3) + sp.pi, args=(), module="zero_args_probe", register=False)
    with tempfile.TemporaryDirectory() as d:
        out = Path(d)
        generate([e], out, out, target="c")
        keep: list = []
        assert C._evaluator(e, "c", out / "zero_args_probe.c", keep)([]) == [3 + math.pi]


def _extreme_sweeps(count):
    """Transfer sweeps of 12 sites with neighbour ratios e^x, x uniform on [-690, 690]: far beyond any state's."""
    rng = np.random.default_rng(1)
    for _ in range(count):
        a = [rng.uniform(-1, 1, 4) * 10.0 ** rng.uniform(-300, 300) * 0 for _ in range(12)]
        r = [np.exp(rng.uniform(-690, 690, 4)) for _ in range(12)]
        yield a, r, np.full(4, 2.0 ** float(rng.integers(-500, 500)))


def test_renormalised_gradient_is_finite_where_the_products_are(monkeypatch):
    # field:101 (seed 19, a survivor of verify: a signed maximum for the renormalisation's scale) -- in range the
    # scale is a power of two and the bits are the same, so no state a claim uses tells them apart; on extreme
    # sweeps the mutant's unrenormalised entries overflow into NaN where the exact products (mpmath, 60 digits)
    # are finite, and the original's do not
    from symbt.numeric.flow import field as F

    def nan_where_finite(fn):
        count = 0
        for a, r, inv_s in _extreme_sweeps(12):
            with np.errstate(all="ignore"):
                da, dr = fn(a, r, inv_s)
            for row in range(4):
                with mp.workdps(60):
                    ra, rr = F.transfer_gradient([mp.mpf(float(x[row])) for x in a],
                                                 [mp.mpf(float(x[row])) for x in r], mp.mpf(float(inv_s[row])))
                for got, want in zip(list(da[:, row]) + list(dr[:, row]), ra + rr):
                    if mp.isfinite(want) and abs(want) < mp.mpf(2) ** 1000 and np.isnan(got):
                        count += 1
        return count

    assert nan_where_finite(F._gradient_renormalised) == 0
    assert nan_where_finite(planted(F._gradient_renormalised, "m = np.maximum(m, np.abs(x))",
                                    "m = np.maximum(m, x)")) > 0


def test_trace_gap_searches_the_critical_points(monkeypatch):
    # trace:136 (seed 19, a survivor of verify: the derivative's coefficients) -- trace_gap's critical points are
    # the roots of d tr / d lambda; they change its value only where polyroots misses a double root of tr = +-2,
    # which no claim's state reaches, so this test reads the polynomial handed to polyroots and compares it with
    # mpmath's derivative of the trace at four points
    from symbt.reference import trace as T

    asked = []
    real = mp.polyroots

    def recording(c, **kw):
        asked.append([mp.mpf(v) for v in c])
        return real(c, **kw)
    monkeypatch.setattr(T.mp, "polyroots", recording)
    p, q = [mp.mpf(-2), mp.mpf("0.5"), mp.mpf(1)], [mp.mpf(0), mp.mpf("0.3"), mp.mpf("-0.2")]
    T.trace_gap(p, q, 1, 2)                          # inside the gap around the critical point 1.55 (tr = -8)
    coeffs = T.hamiltonians(p, q)[::-1]            # highest first, as trace_gap passes them
    assert len(asked) == 3 and len(asked[2]) == len(coeffs) - 1
    for x in (mp.mpf(0), mp.mpf(1), mp.mpf("-1.5"), mp.mpf(3)):   # the derivative, by mpmath's differentiation
        want = mp.diff(lambda t: mp.polyval(coeffs, t), x)
        assert abs(mp.polyval(asked[2], x) - want) <= mp.mpf(10) ** -10 * max(1, abs(want))


def test_scale_is_a_forward_difference():
    # codegen.verify:215 (seed 19, a survivor of verify: a backward difference) -- _scale's docstring says forward
    # differences; at a kink (max(x, 0) at 0) the two sides differ: slope 1 forward, 0 backward.  No sample point
    # sits on a kink, so only this test sees it
    from types import SimpleNamespace

    from symbt.codegen import verify

    spec = SimpleNamespace(args=[SimpleNamespace(name="x", kind="scalar")])
    S = verify._scale(spec, lambda x: [max(mp.mpf(x), 0)], {"x": 0.0}, [mp.mpf(0)], [mp.mpf(0)])
    assert S == [1]


# --------------------------------------------------------------------------- seed 20

def test_few_rows_range_test_index_permutation_is_equivalent():
    # marked equivalent: condition:387 (`x[i]` -> `x[i - 1]` over i in range(4) of 4-tuples): the indices 3, 0, 1, 2
    # -- the same four columns -- and np.max, which propagates a NaN wherever it is (seed 20 found Python's max,
    # which depended on the order with a NaN column: now np.max), gives the same value for every order.  Checked
    # on rows with NaN, inf and huge entries in each column in turn
    from symbt.numeric.core import condition as C

    src = inspect.getsource(C)
    line = next(ln for ln in src.splitlines() if "big = float(np.max([_range_stats(" in ln)
    assert "for i in range(4)" in line and "ents.append((A, B, C, D))" in src
    stats = C._range_stats
    rng = np.random.default_rng(387)
    for _ in range(200):
        ents = [tuple(rng.choice([1.0, -3e300, np.inf, np.nan, 2.0 ** -600, 0.0], 4)) for _ in range(3)]
        orig = float(np.max([stats([x[i] for x in ents]) for i in range(4)]))
        mut = float(np.max([stats([x[i - 1] for x in ents]) for i in range(4)]))
        assert orig == mut or (math.isnan(orig) and math.isnan(mut))


def test_panels_sorted_by_either_end_is_equivalent():
    # marked equivalent: coefficients:230 (`done.sort(key=min)` -> `max`): the panels are disjoint pieces of a
    # bisection of [a, b] (or [b, a]), so ordering them by their left or right ends gives the same order.  Checked
    # on the panels of paths.panels' rows and of a reversed interval, both flavours of rows
    from symbt.claims.shipped_seed6 import PANELS_A, PANELS_B, PANELS_MAX, PANELS_RTOL, _panel_rows
    from symbt.numeric.flow import coefficients as Cf

    mutant = planted(Cf.adaptive_panels, "done.sort(key=lambda t: min(t))", "done.sort(key=lambda t: max(t))")
    for a, b in ((PANELS_A, PANELS_B), (PANELS_B, PANELS_A), (-0.5, 2.0)):
        got = Cf.adaptive_panels(_panel_rows, a, b, PANELS_RTOL, PANELS_MAX)
        assert mutant(_panel_rows, a, b, PANELS_RTOL, PANELS_MAX) == got and len(got) > 10
