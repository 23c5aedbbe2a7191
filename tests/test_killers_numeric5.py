"""The claims of ``symbt/claims/shipped_sample45.py`` kill the bugs they were written for, and the proofs of the
equivalence marks of seeds 4 and 5's numeric survivors (issue 21, item 4; docs/mutation.md, "Seeds 4 and 5").

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own text, with
:func:`planting.planted` -- and requires the claim to fail; unpatched, every claim verifies.
"""
from __future__ import annotations

import inspect

import numpy as np
import pytest
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

SAMPLE45 = ["paths.track_hooks", "paths.kappa_rows.n2", "paths.mp_verdict.n3", "paths.jacobian_dual.n3",
            "paths.inline_boolop", "paths.side_by_side.n3", "paths.growth_law",
            "paths.root_slope", "paths.dq_edge.n3"]
NEEDS_FLINT = ("paths.jacobian_dual.n3",)


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.mark.parametrize("cid", SAMPLE45)
def test_unpatched_verified(cid):
    if cid in NEEDS_FLINT:
        pytest.importorskip("flint")
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- paths.track_hooks

def test_track_init_signed_lam(monkeypatch):
    # mutant kernels:180 (abs): kn = lam + |p0| -- the cancellation ratio wrong wherever lam < 0
    from symbt.numeric.float64 import kernels

    monkeypatch.setitem(kernels.HOOKS, "track_init", planted(kernels._track_init, "abs(lam) + abs(p0), abs(a0)",
                                                             "lam + abs(p0), abs(a0)"))
    assert status("paths.track_hooks") == "failed"


def test_rescale_inverted(monkeypatch):
    # mutant kernels:200 (branch, uncovered): the monodromy shrunk where it is small and kept where it is past 2**400
    from symbt.numeric.float64 import kernels

    monkeypatch.setitem(kernels.HOOKS, "rescale", planted(kernels._rescale, "if aux[0] > _BIG or aux[1] > _BIG:",
                                                          "if not (aux[0] > _BIG or aux[1] > _BIG):"))
    assert status("paths.track_hooks") == "failed"


def test_rescale_only_first_track(monkeypatch):
    # a neighbour: the Ba test dropped (a monodromy whose second column grows alone is never shrunk)
    from symbt.numeric.float64 import kernels

    monkeypatch.setitem(kernels.HOOKS, "rescale", planted(kernels._rescale, "if aux[0] > _BIG or aux[1] > _BIG:",
                                                          "if aux[0] > _BIG:"))
    assert status("paths.track_hooks") == "failed"


def test_bounded_edge(monkeypatch):
    # mutant kernels:259 (compare, uncovered): |x| <= 1e300 takes 1e300 itself in range
    from symbt.numeric.float64 import kernels

    monkeypatch.setitem(kernels.HOOKS, "bounded", planted(kernels._bounded, "return abs(x) < 1e300",
                                                          "return abs(x) <= 1e300"))
    assert status("paths.track_hooks") == "failed"


# --------------------------------------------------------------------------- paths.kappa_rows

def test_rows_rescaled_the_wrong_way(monkeypatch):
    # mutant condition:244 (unary-minus, uncovered): ldexp(x, f) -- the rows' rescaling multiplies by 2**f
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_rescaled", planted(condition._rescaled,
                                                        "return [np.ldexp(x, -f) for x in xs], e + f",
                                                        "return [np.ldexp(x, f) for x in xs], e + f"))
    assert status("paths.kappa_rows.n2") == "failed"


def test_rows_exponent_not_recorded(monkeypatch):
    # a neighbour: the rows rescaled but the exponent not kept
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_rescaled", planted(condition._rescaled,
                                                        "return [np.ldexp(x, -f) for x in xs], e + f",
                                                        "return [np.ldexp(x, -f) for x in xs], e"))
    assert status("paths.kappa_rows.n2") == "failed"


# --------------------------------------------------------------------------- paths.mp_verdict

def test_mp_verdict_trace_codes_swapped(monkeypatch):
    # mutant rows:60 (branch, uncovered): TRACE1 for a band at lam2 and TRACE2 for one at lam1
    from symbt.numeric.float64 import rows

    monkeypatch.setattr(rows, "_mp_verdict", planted(rows._mp_verdict, 'return (TRACE2 if "lam2" in str(err)',
                                                     'return (TRACE2 if not ("lam2" in str(err))'))
    assert status("paths.mp_verdict.n3") == "failed"


# --------------------------------------------------------------------------- paths.jacobian_dual

def test_jacobian_dual_zero_rows(monkeypatch):
    # mutant lohner_checks:166 (constant, uncovered): the seed derivatives as 0 x n matrices
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "jacobian_dual", planted(lohner_checks.jacobian_dual, "arb_mat(1, n, [1 if",
                                                                "arb_mat(0, n, [1 if"))
    assert status("paths.jacobian_dual.n3") == "failed"


def test_jacobian_dual_seed_shifted(monkeypatch):
    # a neighbour: every variable seeded with the next one's direction
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "jacobian_dual", planted(lohner_checks.jacobian_dual, "1 if k == i else 0",
                                                                "1 if k == (i + 1) % n else 0"))
    assert status("paths.jacobian_dual.n3") == "failed"


# --------------------------------------------------------------------------- paths.inline_boolop

def test_inline_boolop_second_operand_twice(monkeypatch):
    # mutant inline:252 (constant): a BoolOp's first operand replaced by its second, rewritten
    from symbt.numeric.core import inline

    monkeypatch.setattr(inline._Bodies, "expr", planted(inline._Bodies.expr,
                                                        "e.values[0] = self.expr(e.values[0], pre, at)",
                                                        "e.values[0] = self.expr(e.values[1], pre, at)"))
    assert status("paths.inline_boolop") == "failed"


# --------------------------------------------------------------------------- paths.side_by_side

def test_side_by_side_span_minimum(monkeypatch):
    # mutant condition:481 (min-max): the span of an entry as min(max, -min): a product past 2**500 whose entries
    # keep one sign over the rows is taken as in range, and not renormalised
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_both_in_range", planted(condition._both_in_range,
                                                             "spans = np.maximum(S.max(axis=2)",
                                                             "spans = np.minimum(S.max(axis=2)"))
    assert status("paths.side_by_side.n3") == "failed"



# --------------------------------------------------------------------------- equivalent: condition:121

def test_forward_rescaling_at_an_infinite_maximum_is_equivalent():
    # mutants-equivalent.toml, condition:121: `m < math.inf` -> `m <= math.inf` in sharp_trace_kappa's forward
    # rescaling.  The two differ only at m == inf (m = max(|A|, |B|, |C|, |D|) >= 0, or NaN, which fails `m > 0.0`
    # either way).  There the mutant runs the body with f = math.frexp(inf)[1] = 0: ldexp(x, 0) is x for every double
    # (infinities, NaN, signed zeros and subnormals included) and e + 0 is e -- the identity.  Checked: that arithmetic,
    # the body's text, and sharp_trace_kappa with the mutant on states whose forward products overflow, bit for bit.
    import math

    import numpy as np

    from symbt.numeric.core import condition

    src = inspect.getsource(condition.sharp_trace_kappa)
    body = ("and m > 0.0 and m < math.inf:      # exact power-of-two rescaling\n"
            "            f = math.frexp(m)[1]\n"
            "            A, B, C, D, e = math.ldexp(A, -f), math.ldexp(B, -f), math.ldexp(C, -f), math.ldexp(D, -f), "
            "e + f\n")
    assert src.count(body) == 1
    assert math.frexp(math.inf) == (math.inf, 0)
    for x in (math.inf, -math.inf, 0.0, -0.0, 5e-324, -2.5e-310, 1.5, -1.7976931348623157e308):
        y = math.ldexp(x, -0)
        assert y == x and math.copysign(1.0, y) == math.copysign(1.0, x)
    assert math.isnan(math.ldexp(math.nan, 0))
    mutant = planted(condition.sharp_trace_kappa, "m < math.inf:      # exact", "m <= math.inf:      # exact")
    for lam in (1e200, -1e250, 1e300, 3.0):
        for N in (3, 5):
            p = np.linspace(-2.0, 2.0, N)
            r = np.full(N, 1e200 if lam != 3.0 else 0.5)
            a, b = condition.sharp_trace_kappa(p, r, lam, 0.0), mutant(p, r, lam, 0.0)
            assert repr(a) == repr(b)


# --------------------------------------------------------------------------- equivalent: kernels_block:286

def test_block_sharp_tier_positivity_at_minus_one_is_equivalent():
    # mutants-equivalent.toml, kernels_block:286: `not x + 1.0 > 0.0` -> `not x + 1.0 >= 0.0` in run_block's sharp
    # tier.  They differ only where x + 1.0 == 0.0, i.e. x == -1.0 exactly (a NaN fails both).  There the read-out
    # test just before is `kt (|u| + |w|) (|x + 1| + |x|) <= KAPPA_MAX |dn| |x + 1|`: its right side is 0 (dn = u - w
    # is finite and nonzero, since x = tm / dn = -1), its left side kt (|u| + |w|) * 1 >= |u| + |w| >= |dn| > 0
    # (kt >= 1: `decided`'s docstring; rounding is monotone), or NaN -- so `ok` is False and the status is ILLCOND
    # (RANGE cannot be: |x| = 1) before the positivity test is read.  Checked: the expression's order in the source,
    # and both expressions evaluated at x = -1 over kt, u, w (w = u + tm) of every scale.
    import itertools
    import math

    from symbt.numeric.core.limits import ILLCOND, KAPPA_MAX, OK, POSITIVITY, RANGE
    from symbt.numeric.float64 import kernels_block

    src = inspect.getsource(kernels_block.run_block)
    chain = ("bad = (RANGE if not abs(x) < 1e300 else ILLCOND if not ok\n"
             "                           else POSITIVITY if not x + 1.0 > 0.0 else OK)")
    assert src.count(chain) == 1 and src.count("x = xr[j, k]\n                    dn = u[j, k] - w[j, k]") == 1

    def status_of(x, u, w, kt, strict):
        dn = u - w
        ok = (kt * (abs(u) + abs(w)) * (abs(x + 1.0) + abs(x)) <= KAPPA_MAX * abs(dn) * abs(x + 1.0))
        pos = (x + 1.0 > 0.0) if strict else (x + 1.0 >= 0.0)
        return RANGE if not abs(x) < 1e300 else ILLCOND if not ok else POSITIVITY if not pos else OK

    n = 0
    for kt, u, tm in itertools.product((1.0, 1.5, 2.0 ** 24, 1e300, math.inf, math.nan),
                                       (0.0, 1e-300, -3.5, 2.0 ** 60, -1e300),
                                       (5e-324, 1e-200, 0.75, -4.0, 1e290)):
        w = u + tm                     # dn = u - w = -tm (rounded), x = tm / dn
        dn = u - w
        if dn == 0.0 or not math.isfinite(dn):
            continue
        x = tm / dn
        if x != -1.0:
            continue
        n += 1
        assert status_of(x, u, w, kt, True) == status_of(x, u, w, kt, False) == ILLCOND
    assert n > 50


# --------------------------------------------------------------------------- equivalent: lohner:449

def test_next_precision_extrapolation_at_the_last_step_is_equivalent():
    # mutants-equivalent.toml, lohner:449: `if i1 < n:` -> `if i1 <= n:` in _next_prec.  i1 <= done <= n, so they
    # differ only at i1 == n, where the mutant adds 1.5 * degree * log2(n / i1) = 1.5 * degree * 0.0: degree is
    # max(slope or 2.0, 1.0), and the slope is a finite least-squares fit (growth_law keeps finite log-radii only and
    # fits only points with distinct abscissae), so the term is +0.0 and extra keeps its value (e1 + 0.0 == e1; only
    # a -0.0 becomes +0.0, and `int(prec + extra + _MARGIN)` reads the value).  Checked: the text, and _next_prec of
    # both on passes that ran to n with growing, flat, shrinking, partly infinite records.
    import math

    from symbt.numeric.multiprec import lohner

    src = inspect.getsource(lohner._next_prec)
    assert "extra = e1 + 1.5 * degree * math.log2(n / i1)" in src and "degree = max(law[\"degree\"] or 2.0, 1.0)" in src
    mutant = planted(lohner._next_prec, "    if i1 < n:", "    if i1 <= n:")
    n_seen = 0
    for n in (1, 2, 5, 40, 300):
        for hist_of, lograd_of in ((lambda i: -3.0 + 0.1 * i, lambda i: -200.0 + 0.5 * i),
                                   (lambda i: 2.0, lambda i: -100.0),
                                   (lambda i: 5.0 - i, lambda i: -50.0 - i),
                                   (lambda i: math.inf if i % 3 == 2 else 1.0 * i, lambda i: -math.inf if i % 4 == 1
                                    else -80.0 + i),
                                   (lambda i: -0.0, lambda i: -60.0 + 2.0 * math.log2(i + 1))):
            hist = [math.inf] + [hist_of(i) for i in range(1, n + 1)]
            lograd = [-300.0] + [lograd_of(i) for i in range(1, n + 1)]
            run = lohner.LohnerPass(False, [], hist, lograd, n)
            for prec in (64, 200):
                assert lohner._next_prec(prec, run, n) == mutant(prec, run, n)
                n_seen += 1
    assert n_seen == 50


# --------------------------------------------------------------------------- killed by tests: qd:154

def test_mark_ready_writes_the_digest(tmp_path, monkeypatch):
    # mutant qd:154 (sign, uncovered; its default claims load no numba): `_digest() - "\n"` raises TypeError (not an
    # OSError) after the first compile.  qd_ready's rule: the marker holds the current sources' digest
    from symbt.numeric.multiprec import qd

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    qd._mark_ready()
    assert (tmp_path / qd._MARKER).read_text(encoding="utf-8") == qd._digest() + "\n"
    mutant = planted(qd._mark_ready, 'tmp.write_text(_digest() + "\\n"', 'tmp.write_text(_digest() - "\\n"')
    with pytest.raises(TypeError):
        mutant()


# --------------------------------------------------------------------------- paths.growth_law

def test_growth_law_needs_two_points(monkeypatch):
    # the fit's guard (`len(xy) >= 2`; seed 21 removed a second test, `xy[-1][0] > xy[0][0]`, which always holds for
    # two distinct steps): asking for three points leaves a two-point law without its degree (paths.edges)
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner, "growth_law", planted(lohner.growth_law, "if len(xy) >= 2:", "if len(xy) >= 3:"))
    assert status("paths.edges.n3") == "failed"


def test_growth_law_window_from_the_start(monkeypatch):
    # a neighbour: the fit's window from step 1 (`first` ignored)
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner, "growth_law", planted(lohner.growth_law, "first = max(1, min(first, last // 10))",
                                                      "first = 1"))
    assert status("paths.growth_law") == "failed"


# --------------------------------------------------------------------------- killed by tests: arb:190

def _acb_half_plane_agrees(ctx) -> bool:
    from flint import acb

    from symbt.numeric.core.context import COMPLEX

    ok = True
    for a, g in ((1j, 1.0), (-1j, 1.0), (1.0, 1j), (2.0 + 1j, 1.0 - 2j), (1.0, 1.0), (-1.0, 1.0), (1j, 1j)):
        want = bool(COMPLEX.half_plane(np.array([a]), np.array([g]))[0])
        ok &= ctx.half_plane(acb(a.real, a.imag) if isinstance(a, complex) else acb(a),
                             acb(g.real, g.imag) if isinstance(g, complex) else acb(g)) == want
    return ok


def test_acb_half_plane_at_a_zero_real_part_as_the_complex_route():
    # arb:190 (compare): AcbContext.half_plane's `re_dot(a, g).mid() >= 0` -> `> 0`.  FloatContext.half_plane's
    # docstring: `Re(a * conj(g)) >= 0`; the complex numpy route (COMPLEX) and the complex balls must decide alike,
    # also where Re(a conj g) is exactly 0 (a = i, g = 1), which the complex continuation's claims never meet.
    pytest.importorskip("flint")
    from symbt.numeric.multiprec.arb import ACB, AcbContext

    assert _acb_half_plane_agrees(ACB)
    mutant = planted(AcbContext.half_plane, "return bool(self.re_dot(a, g).mid() >= 0)",
                     "return bool(self.re_dot(a, g).mid() > 0)")
    mutant_cls = type("AcbMutant", (AcbContext,), {"half_plane": mutant})
    assert not _acb_half_plane_agrees(mutant_cls(certain=False))


# --------------------------------------------------------------------------- paths.root_slope

def test_root_slope_two_sum_sign(monkeypatch):
    # mutant spectral_sum:101 (sign): `bp = dl + A` -- the error of fl(A - D) computed wrongly
    from symbt.numeric.core import spectral_sum

    monkeypatch.setattr(spectral_sum, "root_slope", planted(spectral_sum.root_slope, "    bp = dl - A\n",
                                                            "    bp = dl + A\n"))
    assert status("paths.root_slope") == "failed"


def test_root_slope_rows_correction_sign(monkeypatch):
    # mutant spectral_sum:213 (sign): the numpy form corrects the quotient by -rem/den
    from symbt.numeric.core import spectral_sum

    monkeypatch.setattr(spectral_sum, "root_slope_rows", planted(
        spectral_sum.root_slope_rows, "return np.where(ok, q + rem / np.where(wantk, den, k + kl), q)",
        "return np.where(ok, q - rem / np.where(wantk, den, k + kl), q)"))
    assert status("paths.root_slope") == "failed"


# --------------------------------------------------------------------------- paths.dq_edge

def test_block_anchor_refuses_the_documented_largest_distance(monkeypatch):
    # mutant kernels_block:176 (compare): `abs(dq) < MAX_DQ_FLOAT64` refuses a neighbour distance of exactly 700
    from symbt.numeric.float64 import kernels_block

    mutant = planted(kernels_block._anchor, "if not (abs(dq) <= MAX_DQ_FLOAT64 and",
                     "if not (abs(dq) < MAX_DQ_FLOAT64 and")
    monkeypatch.setattr(kernels_block, "_anchor", mutant)
    assert status("paths.dq_edge.n3") == "failed"
