"""The claims of ``symbt/claims/shipped_condition_file.py`` kill the mutants of ``symbt/numeric/core/condition.py``
they were written for -- one or more per function and branch, not one per survivor -- the tests kill the ones that
change only cost, and the equivalence proofs of the marks hold (issue 21, item 4; docs/mutation.md, "Fresh samples
of symbt/numeric/core/condition.py").

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own line, applied by
:func:`planting.mutated` to a copy of the module, whose functions then replace the module's -- and requires the claim
to fail; unpatched, every claim verifies.
"""
from __future__ import annotations

import inspect
import math

import numpy as np
import pytest
from planting import mutated

from symbt.claims import REGISTRY, load_all
from symbt.numeric.core import condition

load_all()

CLAIMS = ["paths.kappa_cells.n2", "paths.kappa_cells.n3", "paths.kappa_cells.n5", "paths.kappa_cells_rows.n2",
          "paths.kappa_cells_rows.n3", "paths.kappa_cells_rows.n5", "paths.abs_products.n2", "paths.abs_products.n3"]
MODULE = "symbt.numeric.core.condition"
#: what the claims read from the module (the copy's functions call each other within the copy)
PUBLIC = ("sharp_trace_kappa", "SHARP_ON_FLOATS", "sharp_trace_kappa_rows", "abs_trace_rows", "monodromy_and_abs")


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


def plant(monkeypatch, before: str, after: str, within=None) -> None:
    """The module's functions replaced by those of a copy with the one mutant ``before -> after`` (whole lines; in
    the function ``within`` where the line occurs in several)."""
    if within is None:
        copy = mutated(MODULE, before, after)
    else:
        copy = mutated_within(within, before, after)
    for name in PUBLIC:
        monkeypatch.setattr(condition, name, getattr(copy, name))


def mutated_within(func, before: str, after: str):
    """As :func:`planting.mutated`, for the one mutant of ``symbt mutate --source`` on the line ``before`` inside
    ``func``."""
    import types
    from pathlib import Path

    from symbt.engine.mutants import find_mutants

    lines, first = inspect.getsourcelines(func)
    data = Path(condition.__file__).read_bytes()
    hits = [m for m in find_mutants(data, MODULE) if first <= m.line < first + len(lines)
            and m.line_text.strip() == before.strip() and m.mutated_line.strip() == after.strip()]
    assert len(hits) == 1, hits
    copy = types.ModuleType(MODULE + "_mutant")
    copy.__dict__.update(__name__=MODULE, __package__=condition.__package__, __file__=condition.__file__)
    exec(compile(hits[0].apply(data), condition.__file__, "exec"), copy.__dict__)  # noqa: S102 -- symbt's own source
    return copy


def fails(monkeypatch, before: str, after: str, *cids: str, within=None) -> None:
    plant(monkeypatch, before, after, within)
    for cid in cids:
        assert status(cid) == "failed", cid


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- sharp_trace_kappa (paths.kappa_cells)

KN = "    kn = abs(lam) + abs(p[0])           # max_j (|lam| + |p_j|) / |a_j| as kn / kd (as the kernels' track)"
UPD = "        if cn * kd > kn * abs(a):"
OVER = ("        if term > 0.0 and sh > 0 and math.frexp(term)[1] + sh > 1024:     # beyond float64: math.ldexp "
        "would raise")
FR = "                fr = r[j - 1] if pe[j - 2] == ep else math.ldexp(r[j - 1], int(pe[j - 2]) - ep)"


@pytest.mark.parametrize("before, after", [
    ("    C = r[0]", "    C = r[1]"),                                   # the first factor's r from the next site
    (KN, KN.replace("p[0]", "p[1]")),                                   # the cancellation factor's first site
    (UPD, "        if not (cn * kd > kn * abs(a)):"),                   # the cancellation factor's update inverted
    ("        a = lam_add(lam, lo, p[j])", "        a = lam_add(lam, lo, p[j - 1])"),
    ("    disc = (t - two) * (t + two)        # 2**(-2e) (tr**2 - 4), no cancellation",
     "    disc = (t - two) * (t - two)        # 2**(-2e) (tr**2 - 4), no cancellation"),
    ("            ep = int(pe[j - 1])", "            ep = int(pe[j + 1])"),   # the prefix's exponent one site late
    (FR, FR.replace("int(pe[j - 2]) - ep)", "int(pe[j - 2]) + ep)")),   # the stored row's exponent difference
    ("    if disc == 0.0 or kd == 0.0:        # t = +-2, or some a_j = 0 with lam, p_j not both 0: not decided",
     "    if not (disc == 0.0 or kd == 0.0):        # t = +-2, or some a_j = 0 with lam, p_j not both 0: not decided"),
], ids=["r0", "kn-site", "kn-update", "a-site", "disc", "ep", "fr", "inf-test"])
def test_sharp_kappa_mutants_killed(monkeypatch, before, after):
    fails(monkeypatch, before, after, "paths.kappa_cells.n3", "paths.kappa_cells_rows.n3")


@pytest.mark.parametrize("after", [OVER.replace("term > 0.0", "term < 0.0"), OVER.replace("[1] + sh", "[0] + sh")],
                         ids=["sign", "mantissa"])
def test_overflowing_term_raises_instead_of_inf(monkeypatch, after):
    # condition:152 (seed 31): the overflow test of a term lost or read from the mantissa -- where the products leave
    # the double range, math.ldexp raises OverflowError instead of the documented inf (the untrusted cell, N = 2)
    fails(monkeypatch, OVER, after, "paths.kappa_cells.n2", "paths.kappa_cells_rows.n2")


def test_tiny_products_rescaled_the_wrong_way(monkeypatch):
    # the suffix's rescaling by 2**f instead of 2**-f: off by a factor wherever a suffix leaves [2**-200, 2**200]
    fails(monkeypatch, "            S11, S12 = math.ldexp(S11, -f), math.ldexp(S12, -f)",
          "            S11, S12 = math.ldexp(S11, f), math.ldexp(S12, -f)", "paths.kappa_cells.n5")


# --------------------------------------------------------------------------- sharp_trace_kappa_rows (numpy form)

KNR = "    kn, kd = np.abs(lam) + np.abs(p[:, 0]), aa[:, 0]"
PARTS = "    parts = np.ldexp(term, np.where(term > 0.0, np.minimum(sh, 1100), 0))"
TOTAL = ("    total = np.add.accumulate(np.concatenate([np.zeros((R, 1)), parts[:, ::-1]], axis=1), axis=1)"
         "[:, -1]")


@pytest.mark.parametrize("before, after", [
    (KNR, KNR.replace("np.abs(lam) + ", "lam + ")),                     # condition:279 (seed 31)
    (KNR, KNR.replace("aa[:, 0]", "aa[:, 1]")),                         # condition:279 (seed 31)
    ("        cn = np.abs(lam) + np.abs(p[:, j])", "        cn = np.abs(lam) + p[:, j]"),  # condition:282 (seed 31)
    ("        P21[:, 1], P22[:, 1] = r[:, 0], 0.0           # math.ldexp(r[0], -pe[0]) with pe[0] = 0",
     "        P21[:, 1], P22[:, 1] = r[:, 1], 0.0           # math.ldexp(r[0], -pe[0]) with pe[0] = 0"),
    (PARTS, PARTS.replace("term > 0.0", "term < 0.0")),                 # condition:318 (seed 31)
    (PARTS, PARTS.replace("np.minimum", "np.maximum")),                 # condition:318 (seed 31)
    (TOTAL, TOTAL.replace("axis=1)[:, -1]", "axis=0)[:, -1]")),         # condition:319 (seed 31)
], ids=["kn-signed-lam", "kd-site", "cn-signed-p", "P21-site", "parts-sign", "parts-max", "accumulate-axis"])
def test_sharp_rows_mutants_killed(monkeypatch, before, after):
    fails(monkeypatch, before, after, "paths.kappa_cells_rows.n3")


# --------------------------------------------------------------------------- abs_trace_rows, monodromy_and_abs

SHAPES = "    if am.ndim != 2 or am.shape != rm.shape or not 0 < am.shape[1] <= FEW_ROWS or am.shape[0] < 2:"
STEP = "            A, B, C, D = a[j] * A - C, a[j] * B - D, r[j] * A, r[j] * B"
MX = "        mx = _nanmax(_nanmax(abs(A), abs(B)), _nanmax(abs(C), abs(D)))"
K = "        k = math.frexp(mx)[1] if mx > 0.0 and mx < math.inf else 0      # np.frexp(inf) has exponent 0"
FEW = ("        (main, e), (ents, ea) = (_product_on_floats(*few), _product_on_floats(np.abs(few[0]), "
       "-few[1]))")


@pytest.mark.parametrize("before, after", [
    ("    ents, e = _product_on_floats(np.abs(sites[0]), -sites[1])",
     "    ents, e = _product_on_floats(np.abs(sites[1]), -sites[1])"),   # condition:354 (seed 31)
    (SHAPES, SHAPES.replace("am.shape != rm.shape", "am.shape == rm.shape")),   # condition:367 (seed 31)
    ("        for j in range(1, N):", "        for j in range(0, N):"),    # condition:383 (seed 31)
    ("    return x if x != x or x >= y else y", "    return x if x != x or x <= y else y"),   # condition:404
    ("    A, B, C, D, e = a[0], -1.0, r[0], 0.0, 0", "    A, B, C, D, e = a[1], -1.0, r[0], 0.0, 0"),   # :411
    (STEP, STEP.replace("a[j] * B - D", "a[j] * B + D")),               # condition:414 (seed 31)
    (STEP, STEP.replace("r[j] * A", "r[j - 1] * A")),                   # condition:414 (seed 31)
    (MX, MX.replace("abs(A)", "A")),                                    # condition:415
    (MX, MX.replace("abs(C)", "C")),                                    # condition:415 (seed 31)
    (K, K.replace("mx > 0.0", "mx < 0.0")),                             # condition:416 (seed 31)
    ("    if few is not None:                 # a few rows: both products on Python floats",
     "    if not (few is not None):                 # a few rows: both products on Python floats"),   # :438
    (FEW, FEW.replace("np.abs(few[0])", "few[0]")),                     # condition:439 (seed 31)
    ("    a2, r2 = np.concatenate([am, np.abs(am)], axis=1), np.concatenate([rm, -rm], axis=1)",
     "    a2, r2 = np.concatenate([am, np.abs(am)], axis=0), np.concatenate([rm, -rm], axis=1)"),   # :449
    ("                es[i] = _merged(np.zeros(R, np.int64), b, np.asarray(e2)[sl])",
     "                es[i] = _merged(np.zeros(R, np.int64), b, np.asarray(e2)[sl + 1])"),   # :469
    ("    return (A, B, C, D, es[0]), (np.asarray(out[1][0] + out[1][3]), es[1])",
     "    return (A, B, C, D, es[0]), (np.asarray(out[1][0] - out[1][3]), es[1])"),   # :471
], ids=["abs-site", "shapes", "extra-site", "nanmax", "a0", "B-sign", "C-site", "mx-abs-A", "mx-abs-C", "k-sign",
        "few-branch", "few-abs", "concat-axis", "merge-slice", "trace-sign"])
def test_products_mutants_killed(monkeypatch, before, after):
    within = condition._product_on_floats if "range(1, N)" in before else None    # (three such loops)
    fails(monkeypatch, before, after, "paths.abs_products.n3", within=within)


def test_products_largest_entry_negative_n2(monkeypatch):
    # condition:415 at N = 2: the renormalisation by a smaller entry than the largest magnitude (a0 = -1e300) leaves
    # a1 a0 past the double range at the next site
    fails(monkeypatch, MX, MX.replace("abs(A)", "A"), "paths.abs_products.n2")


# --------------------------------------------------------------------------- equivalent: condition:240, condition:318

def grid_rows(N: int):
    from symbt.claims.shipped_condition_file import kappa_grid

    cases = sum(kappa_grid(N), ())
    return (np.array([c[0] for c in cases]), np.array([c[1] for c in cases]), np.array([c[2] for c in cases]),
            np.array([c[3] for c in cases]))


def test_rows_rescaling_at_an_infinite_maximum_is_equivalent():
    # mutants-equivalent.toml, condition:240: `(m < math.inf)` -> `(m <= math.inf)` in _rescaled (the numpy form's
    # power-of-two rescaling).  The two differ only where m == inf (m is a maximum of absolute values, >= 0, or NaN,
    # which fails `m > 0.0` either way).  There the mutant sets f = _exponent(inf) = 0, and np.ldexp(x, -0) is x for
    # every double (infinities, NaN, signed zeros, subnormals), e + 0 is e: the identity.  Checked: the body's text,
    # that arithmetic, and the mutant's sharp_trace_kappa_rows bit for bit on the grid rows (products past the
    # double range included) of N = 2, 3, 5.
    src = inspect.getsource(condition._rescaled)
    assert src.count("f = np.where(hit, _exponent(m), 0)") == 1
    assert src.count("return [np.ldexp(x, -f) for x in xs], e + f") == 1
    assert condition._exponent(np.array([math.inf, -math.inf, math.nan, 0.0])).tolist() == [0, 0, 0, 0]
    x = np.array([math.inf, -math.inf, 0.0, -0.0, 5e-324, -2.5e-310, 1.5, -1.7976931348623157e308])
    y = np.ldexp(x, -np.zeros(len(x), np.int64))
    assert np.array_equal(y, x) and np.array_equal(np.signbit(y), np.signbit(x))
    assert np.isnan(np.ldexp(np.array([math.nan]), 0)).all()
    line = "    hit = ((m > _FAR) | (m < _NEAR)) & (m > 0.0) & (m < math.inf)"
    copy = mutated(MODULE, line, line.replace("(m < math.inf)", "(m <= math.inf)"))
    with np.errstate(all="ignore"):
        for N in (2, 3, 5):
            P, R, L, O = grid_rows(N)
            P = np.concatenate([P, P * 1e300])         # rows whose products overflow at every site
            R, L, O = np.concatenate([R, R]), np.concatenate([L, L]), np.concatenate([O, O])
            assert np.array_equal(copy.sharp_trace_kappa_rows(P, R, L, O),
                                  condition.sharp_trace_kappa_rows(P, R, L, O), equal_nan=True)


def test_zero_terms_shift_is_equivalent():
    # mutants-equivalent.toml, condition:318: `np.where(term > 0.0, ...)` -> `term >= 0.0` in _sharp_over_rows.  A
    # term is a sum of products of absolute values (|S|, |a_j|, |P|) and of r_j, fr = 2**k r_j >= 0, so it is +0.0,
    # positive or NaN/inf (the rows' r are positive); the two differ only at term == 0, where the mutant shifts
    # 0.0 by min(sh, 1100) instead of by 0, and np.ldexp(0.0, k) is 0.0 for every k; the overflow test `over` has
    # its own `term > 0.0` (unchanged).  Checked: the text, that arithmetic over every shift the line can give,
    # and the mutant bit for bit on the grid rows (a_j = 0 and t = +-2 rows included).
    src = inspect.getsource(condition._sharp_over_rows)
    assert src.count("np.where(term > 0.0, np.minimum(sh, 1100), 0)") == 1
    assert src.count("over = ((term > 0.0) & (_exponent(term) + sh > 1024)).any(axis=1)") == 1
    k = np.arange(-3000, 1101)
    z = np.ldexp(np.zeros(len(k)), k)
    assert np.all(z == 0.0) and not np.signbit(z).any()
    line = "    parts = np.ldexp(term, np.where(term > 0.0, np.minimum(sh, 1100), 0))"
    copy = mutated(MODULE, line, line.replace("term > 0.0", "term >= 0.0"))
    with np.errstate(all="ignore"):
        for N in (2, 3, 5):
            P, R, L, O = grid_rows(N)
            P = np.concatenate([P, np.zeros_like(P)])           # p = 0: a_j = lam exactly
            R, L, O = np.concatenate([R, R]), np.concatenate([L, np.zeros_like(L)]), np.concatenate([O, O])
            assert np.array_equal(copy.sharp_trace_kappa_rows(P, R, L, O),
                                  condition.sharp_trace_kappa_rows(P, R, L, O), equal_nan=True)


# --------------------------------------------------------------------------- cost only: the rows' route (condition:367)

@pytest.mark.parametrize("before, after", [
    (SHAPES, SHAPES.replace("not 0 < am.shape[1] <= FEW_ROWS", "not 0 > am.shape[1] <= FEW_ROWS")),
    (SHAPES, SHAPES.replace("<= FEW_ROWS", "< FEW_ROWS")),
    (SHAPES, SHAPES.replace("not 0 < am.shape[1]", "not 1 < am.shape[1]")),         # seed 26: one row
], ids=["never-few", "few-edge", "one-row"])
def test_few_rows_on_python_floats(monkeypatch, before, after):
    # condition:367's range of the few-rows form mutated: the general form (numpy, monodromy) gives the same bits, so
    # only the route changes -- a cost (a numpy operation on a few elements costs ~20 Python float operations).
    # abs_trace_rows' docstring: up to FEW_ROWS rows the product runs on Python floats.  The test: that route taken
    # at 1 and at FEW_ROWS rows, not at FEW_ROWS + 1.
    def routes(mod) -> list[bool]:
        seen = []
        real = mod._product_on_floats

        def spy(*args):
            seen.append(True)
            return real(*args)
        monkeypatch.setattr(mod, "_product_on_floats", spy)
        out = []
        for R in (1, condition.FEW_ROWS, condition.FEW_ROWS + 1):
            seen.clear()
            a = [np.linspace(1.0, 2.0, R), np.linspace(-3.0, 1.0, R)]
            r = [np.full(R, 0.5), np.full(R, 2.0)]
            mod.abs_trace_rows(a, r)
            out.append(bool(seen))
        return out

    assert routes(condition) == [True, True, False]
    assert routes(mutated(MODULE, before, after)) != [True, True, False]


# --------------------------------------------------------------------------- cost only: sharp_on_floats

def test_sharp_on_floats_clones_exactly_the_hooks_that_call_the_sharp_tier():
    # sharp_on_floats only changes which function a hook calls (the same source on Python floats: the same bits), so
    # a mutant of it is a cost -- seen here, not by verify: every hook whose code names sharp_trace_kappa (and whose
    # global is it) is a clone calling SHARP_ON_FLOATS, every other hook is returned as it is, and the clones give
    # the originals' results bit for bit.
    from symbt.numeric.float64.kernels import HOOKS

    new = condition.sharp_on_floats(HOOKS)
    assert new.keys() == HOOKS.keys()
    calling = [k for k, v in HOOKS.items() if "sharp_trace_kappa" in getattr(v, "__code__", type("", (), {
        "co_names": ()})).co_names]
    assert calling, "no hook calls the sharp tier"
    for k, v in HOOKS.items():
        if k in calling:
            assert new[k] is not v and new[k].__globals__["sharp_trace_kappa"] is condition.SHARP_ON_FLOATS, k
            assert new[k].__code__.co_code == v.__code__.co_code, k
        else:
            assert new[k] is v, k
    other = {"sharp": condition.sharp_trace_kappa_rows}             # a callable that does not call the sharp tier
    assert condition.sharp_on_floats(other)["sharp"] is other["sharp"]
    p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
    for lam in (15.0, -5.0, 0.5):
        a = condition.sharp_trace_kappa(p, r, lam, 0.0)
        b = condition.SHARP_ON_FLOATS(condition._Sites(p.tolist()), condition._Sites(r.tolist()), lam, 0.0)
        assert repr(a) == repr(b)


def test_range_stats_signed(monkeypatch):
    # _range_stats without abs: a batch whose every large entry is negative (a_1 = -1e300) looks in range, and its
    # overflowing product is returned unrenormalised
    fails(monkeypatch, "        m = max(m, abs(x))", "        m = max(m, x)", "paths.abs_products.n2")


def test_side_by_side_and_sharp_rows_routes():
    # the documented routes by row count (cost only: every route gives the same bits): monodromy_and_abs runs the
    # two products on Python floats up to FEW_ROWS rows, side by side from FEW_ROWS + 1 to SIDE_BY_SIDE_ROWS rows
    # (N >= 2: checked at N = 2 and 3, which kills condition:446's `N > 2` and `FEW_ROWS > ...`, seed 32) and as two
    # calls beyond;
    # sharp_trace_kappa_rows runs the scalar source on Python floats up to FEW_ROWS rows and numpy beyond
    few, side = condition.FEW_ROWS, condition.SIDE_BY_SIDE_ROWS
    calls: list[str] = []
    real_mono, real_sharp = condition.monodromy, condition.SHARP_ON_FLOATS

    def mono(*args):
        calls.append("monodromy")
        return real_mono(*args)

    def sharp(*args):
        calls.append("scalar")
        return real_sharp(*args)

    with pytest.MonkeyPatch.context() as mp_:
        mp_.setattr(condition, "monodromy", mono)
        mp_.setattr(condition, "SHARP_ON_FLOATS", sharp)
        seen = {}
        for N in (2, 3):
            for R in (1, few, few + 1, side, side + 1):
                calls.clear()
                a = [np.linspace(1.0, 2.0, R) + j for j in range(N)]
                condition.monodromy_and_abs(a, [np.full(R, 0.5 + j) for j in range(N)])
                seen[("side by side", N, R)] = "monodromy" not in calls
        for R in (1, few, few + 1):
            calls.clear()
            P, Rr = np.tile([-20.0, 10.0, 1.0], (R, 1)), np.tile([0.5, 2.0, 1.0], (R, 1))
            condition.sharp_trace_kappa_rows(P, Rr, np.full(R, 15.0), np.zeros(R))
            seen[("scalar", R)] = calls.count("scalar") == R
    # up to FEW_ROWS rows both products on Python floats (no numpy monodromy either; seed 22: condition:361 sent
    # every batch to the general form)
    assert seen == {**{("side by side", N, R): R <= side for N in (2, 3) for R in (1, few, few + 1, side, side + 1)},
                    ("scalar", 1): True, ("scalar", few): True, ("scalar", few + 1): False}


def test_both_in_range_is_out_of_range_of_both_halves():
    # _both_in_range's docstring: whether FloatContext.out_of_range is False for both halves of the side-by-side
    # entries (a cost-saving form: a mutant that answers False more often changes only the route); against
    # out_of_range itself on halves in range, one half past 2**500 (either), both, a NaN entry and an infinity
    from symbt.numeric.core.context import FLOAT

    R = 5
    base = [np.linspace(-3.0, 3.0, 2 * R) + k for k in range(4)]
    cases = {"in range": base}
    for h in (0, 1):
        X = [x.copy() for x in base]
        X[2][h * R + 1] = -2.0 ** 501
        cases[f"half {h} past 2**500"] = X
        Y = [x.copy() for x in base]
        Y[3][h * R] = math.nan
        cases[f"half {h} NaN"] = Y
        Z = [x.copy() for x in base]
        Z[0][h * R + 2] = math.inf
        cases[f"half {h} inf"] = Z
    for name, X in cases.items():
        want = not any(np.any(FLOAT.out_of_range(*[x[s] for x in X])) for s in (slice(0, R), slice(R, None)))
        assert condition._both_in_range(X, R) == want, name
    assert condition._both_in_range(base, R) is True


# --------------------------------------------------------------------------- equivalent: the rescaling guards

SCAL_F = "        if (m > _FAR or m < _NEAR) and m > 0.0 and m < math.inf:      # exact power-of-two rescaling"
SCAL_B = "        if (m > _FAR or m < _NEAR) and m > 0.0 and m < math.inf:"
ROWS_H = "    hit = ((m > _FAR) | (m < _NEAR)) & (m > 0.0) & (m < math.inf)"


@pytest.mark.parametrize("before, after", [
    (SCAL_F, SCAL_F.replace("m > 0.0", "m >= 0.0")),            # condition:121:compare:96d63511
    (SCAL_B, SCAL_B.replace("m > 0.0", "m >= 0.0")),            # condition:157:compare:3273f737
    (SCAL_B, SCAL_B.replace("m < math.inf", "m <= math.inf")),  # condition:157:compare:6f5e35c7
    (ROWS_H, ROWS_H.replace("(m > 0.0)", "(m >= 0.0)")),        # condition:240:compare:67125b35
], ids=["forward-zero", "backward-zero", "backward-inf", "rows-zero"])
def test_rescaling_guards_skip_only_the_identity(before, after):
    # mutants-equivalent.toml: the guards `m > 0.0` and `m < math.inf` of the three power-of-two rescalings only keep
    # the body from running at m == 0 (all four entries zero; m is a maximum of absolute values, so never negative,
    # and NaN fails both forms) and at m == inf.  There the body rescales by the exponent of m, which is 0
    # (math.frexp(0.0) = (0.0, 0), math.frexp(inf) = (inf, 0), _exponent likewise), and ldexp(x, -0) is x for every
    # double, e + 0 is e: the identity.  Checked: the bodies' text, that arithmetic, and the mutants bit for bit on
    # the grid rows of paths.kappa_cells (and the same rows scaled by 1e300, whose products overflow, and at
    # p = lam = 0 with r = 0, whose products are exactly zero) through the scalar and both row forms.
    src = inspect.getsource(condition)
    assert src.count("            f = math.frexp(m)[1]\n") == 2 and src.count("f = np.where(hit, _exponent(m), 0)") == 1
    assert math.frexp(0.0) == (0.0, 0) and math.frexp(math.inf) == (math.inf, 0)
    assert condition._exponent(np.array([0.0, math.inf])).tolist() == [0, 0]
    for x in (math.inf, -math.inf, 0.0, -0.0, 5e-324, 1.5, -1.7976931348623157e308):
        assert repr(math.ldexp(x, -0)) == repr(x)
    copy = mutated(MODULE, before, after)
    with np.errstate(all="ignore"):
        for N in (2, 3, 5):
            P, R, L, O = grid_rows(N)
            P = np.concatenate([P, P * 1e300, np.zeros_like(P)])
            R = np.concatenate([R, R, np.zeros_like(R)])
            L, O = np.concatenate([L, L, np.zeros_like(L)]), np.concatenate([O, O, np.zeros_like(O)])
            assert np.array_equal(copy.sharp_trace_kappa_rows(P, R, L, O),
                                  condition.sharp_trace_kappa_rows(P, R, L, O), equal_nan=True)
            for k in range(0, len(L), 3):
                a = condition.sharp_trace_kappa(P[k], R[k], float(L[k]), float(O[k]))
                b = copy.sharp_trace_kappa(P[k], R[k], float(L[k]), float(O[k]))
                assert repr(a) == repr(b)


def test_merged_without_a_copy_is_equivalent(monkeypatch):
    # condition:492 (seed 8), `np.array(full, copy=False)`: _merged then writes the renormalised rows into `full`
    # itself.  Its callers pass either a fresh zeros array or a half (a slice) of one of the four side-by-side
    # entries X of monodromy_and_abs -- distinct fresh arrays (N >= 2: every entry is a product), the two halves
    # disjoint, X read no more -- so the values returned are the same
    from planting import planted

    rng = np.random.default_rng(492)
    cases = []
    for N, R in ((2, 20), (3, 40), (5, 17)):
        a = rng.uniform(-3, 3, (N, R))
        r = np.exp(rng.uniform(-1, 1, (N, R)))
        a[:, 3] = 1e200 * np.sign(a[:, 3])                  # this row's products leave the range in both halves
        a[:, 7] = -1e160                                     # and this one
        r[:, 11] = 1e-200                                    # a row whose products fall below 2**-500
        cases.append((list(a), list(r)))
    want = [condition.monodromy_and_abs(a, r) for a, r in cases]
    mutant, partial = planted(condition._merged, "out = np.array(full, copy=True)",
                              "out = np.array(full, copy=False)"), []

    def spy(full, mask, part):
        partial.append(not mask.all())
        return mutant(full, mask, part)
    monkeypatch.setattr(condition, "_merged", spy)
    got = [condition.monodromy_and_abs(a, r) for a, r in cases]
    assert any(partial)                                      # the copy's branch ran: some rows kept, some merged
    for (w_main, w_abs), (g_main, g_abs) in zip(want, got):
        for x, y in zip([*w_main, *w_abs], [*g_main, *g_abs]):
            assert np.array_equal(x, y, equal_nan=True)


def test_sum_without_its_leading_zero_is_equivalent(monkeypatch):
    # condition:319 (seed 9): the accumulated sum of the sites' parts without its leading zero column.  Every part
    # is +0.0, positive, inf or NaN (absolute values times non-negative products), and 0.0 + x = x exactly for each,
    # so the running sums -- and the total -- are the same, bit for bit
    from planting import planted

    from symbt.claims.shipped_condition_file import kappa_grid

    mutant = planted(condition._sharp_over_rows, "np.concatenate([np.zeros((R, 1)), parts[:, ::-1]], axis=1)",
                     "np.concatenate([np.zeros((R, 0)), parts[:, ::-1]], axis=1)")
    for N in (2, 3, 5):
        cases = [c for part in kappa_grid(N) for c in part]
        P, R_ = np.array([c[0] for c in cases]), np.array([c[1] for c in cases])
        L, O = np.array([c[2] for c in cases]), np.array([c[3] for c in cases])
        with np.errstate(all="ignore"):
            want, got = condition._sharp_over_rows(P, R_, L, O), mutant(P, R_, L, O)
        assert np.array_equal(want, got, equal_nan=True)
