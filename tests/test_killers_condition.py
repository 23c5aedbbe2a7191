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
], ids=["abs-site", "shapes", "extra-site", "nanmax", "a0", "B-sign", "C-site", "mx-abs-A", "mx-abs-C", "k-sign", "few-branch",
        "few-abs", "concat-axis", "merge-slice", "trace-sign"])
def test_products_mutants_killed(monkeypatch, before, after):
    within = condition._product_on_floats if "range(1, N)" in before else None    # (three such loops)
    fails(monkeypatch, before, after, "paths.abs_products.n3", within=within)


def test_products_largest_entry_negative_n2(monkeypatch):
    # condition:415 at N = 2: the renormalisation by a smaller entry than the largest magnitude (a0 = -1e300) leaves
    # a1 a0 past the double range at the next site
    fails(monkeypatch, MX, MX.replace("abs(A)", "A"), "paths.abs_products.n2")
