"""Seeds 26, 27 and 28's survivors (docs/mutation.md, "Seed 26", "Seed 27", "Seed 28"): planted bugs that the new
claims (and the extended ones) now see, tests of routes and costs, and the fact behind an equivalence mark.
Unpatched, every claim verifies."""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from planting import claim_fails as fails
from planting import planted

import symbt.numeric
from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["library.forced_backend", "library.emit_range", "library.deep_band", "library.degenerate_step"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


@pytest.mark.parametrize("name, old, new", [
    ("bt_step", 'forced=backend != "auto")', 'forced=backend == "auto")'),      # dispatch:97 (seed 26)
    ("bt_orbit", 'forced=backend != "auto")', 'forced=backend == "auto")'),
    ("bt_orbit", 'forced=backend != "auto")', "forced=False)"),
])
def test_a_forced_backend_refuses(monkeypatch, name, old, new):
    # the claim imports bt_step and bt_orbit from symbt.numeric when it runs
    monkeypatch.setattr(symbt.numeric, name, planted(getattr(symbt.numeric, name), old, new))
    assert fails("library.forced_backend")


def test_a_forced_backend_refuses_in_the_table(monkeypatch):
    # the table's hand-back rule: a forced backend handing its NumericRangeError on
    from symbt.numeric import backends

    monkeypatch.setattr(backends, "_next", planted(backends._next, "(not forced and isinstance", "(isinstance"))
    assert fails("library.forced_backend")


@pytest.mark.parametrize("old, new", [
    ("abs(v) > _BIG:", "abs(v) < _BIG:"),                      # user.check:291 (seed 26, uncovered)
    ("abs(v) > _BIG:", "v > _BIG:"),                           # user.check:291 (seed 27)
    ('if flavour != "mpmath" and abs(v) > _BIG:', "if abs(v) > _BIG:"),
])
def test_a_range_guard_is_decided_on_the_reference(monkeypatch, old, new):
    from symbt.codegen.user import check

    monkeypatch.setattr(check, "_expected", planted(check._expected, old, new))
    assert fails("library.emit_range")


def test_a_range_refusal_of_a_users_module_names_no_lattice(monkeypatch):
    from symbt.codegen.user import render

    monkeypatch.setattr(render, "_typed_head", planted(
        render._typed_head, ''', "_RANGE_CAUSE = 'an overflow or a non-finite intermediate'"])''', "])"))
    assert fails("library.emit_range")


@pytest.mark.parametrize("old, new", [
    ('what = "a scalar" if e.shape == () else', 'what = "a scalar" if e.shape != () else'),   # user.render:60
    ('f"numpy float64; the arguments broadcast, the result is batch + {e.shape}; "',
     'f"numpy float64; the arguments broadcast, the result is batch + (); "'),
])
def test_an_emitted_docstring_names_the_shape_returned(monkeypatch, old, new):
    from symbt.codegen.user import render

    monkeypatch.setattr(render, "_doc", planted(render._doc, old, new))
    assert fails("library.emit")


# --------------------------------------------------------------------------- seed 27

def test_a_wide_row_leaves_the_batch_before_the_step(monkeypatch):
    # orbit:202 (seed 27, `if far.any()` negated): the wide row stays in the batch, and the step raises on it
    from symbt.numeric.float64 import orbit

    monkeypatch.setattr(orbit, "_general_block", planted(orbit._general_block, "            if far.any():",
                                                         "            if not (far.any()):"))
    assert fails("paths.rows_apart.n3", crash=True)


def test_a_batch_deadline_still_doubles_the_precision(monkeypatch):
    # existence:100 (seed 27, `start + BUDGET_S` -> `start - BUDGET_S` beside a deadline): the batch's existence
    # check stopped at 256 bits, and the step raised a range error where the band is certain at 512
    from symbt.numeric.float64 import existence, rows

    bad = planted(existence.decide_existence, "min(deadline, start + BUDGET_S)", "min(deadline, start - BUDGET_S)")
    monkeypatch.setattr(existence, "decide_existence", bad)
    monkeypatch.setattr(rows, "decide_existence", bad)
    assert fails("library.deep_band")


def test_the_arb_step_retries_with_projective_division(monkeypatch):
    # runners:195 (seed 27, `if not ok` negated): a division by an exact zero is not redone
    from symbt.numeric.multiprec import runners

    pytest.importorskip("flint")
    monkeypatch.setattr(runners, "_safe_step", planted(runners._safe_step, "    if not ok:\n", "    if ok:\n"))
    assert fails("library.degenerate_step", crash=True)


def test_store_calls_and_tuple_assignments_are_written_inline():
    # inline:103 and inline:347 (seed 27): a cost, not a value -- the module docstring's "those calls disappear"
    # and "no tuple is built": st(u, j, x) becomes u[j] = x, and (a, b) = (x, y) two assignments
    import ast

    from symbt.numeric.core import inline

    def put(u, x):
        st(u, 0, x)     # noqa: F821  (a name the rewrite replaces)
        return u

    g = inline.inlined(put, "put_inline", inline.FLOAT64_INLINE, {})
    assert "st" not in g.__code__.co_names and g([0.0], 2.5) == [2.5]
    stmt = ast.parse("a, b = x, y").body[0]
    pairs = inline._pairs(stmt.targets[0], stmt.value, {})
    assert [(ast.unparse(t), ast.unparse(v)) for t, v in pairs] == [("a", "x"), ("b", "y")]


def test_the_angle_interval_is_closed_at_2k(monkeypatch):
    # elliptic:192 (seed 27, `P >= 0` -> `P > 0`): at P = 0, C = -1 the angle -2K, outside (-2K, 2K]
    from symbt.reference import elliptic

    monkeypatch.setattr(elliptic, "global_u", planted(elliptic.global_u, "if P >= 0 else -2 * K - v",
                                                      "if P > 0 else -2 * K - v"))
    assert fails("library.angle")


def test_carlson_loop_runs_in_gmpy2_where_installed(monkeypatch):
    # elliptic:89 (seed 27, `if gmpy2 is None` negated): the route, not the value -- carlson_rf's docstring: "the
    # loop runs in gmpy2 (mpmath's own backend) when it is installed, else in mpmath"
    from symbt.reference import elliptic

    gmpy2 = pytest.importorskip("gmpy2")
    calls = []

    class Spy:
        def __getattr__(self, name):
            return getattr(gmpy2, name)

        def context(self, *args, **kwargs):
            calls.append(1)
            return gmpy2.context(*args, **kwargs)
    monkeypatch.setattr(elliptic, "gmpy2", Spy())
    with mp.workdps(30):
        v = elliptic.carlson_rf(mp.mpf(1), mp.mpf(2), mp.mpf(3))
        assert abs(v - mp.elliprf(1, 2, 3)) < mp.mpf(10) ** -28
    assert calls, "the Carlson loop did not enter gmpy2's context"


# --------------------------------------------------------------------------- seed 28

def test_the_qd_orbit_stores_its_input_first(monkeypatch):
    # qd_step:190 (seed 28, `outQ[0] = Q` -> `outQ[1] = Q`): the first stored positions not written (row 1 is
    # overwritten by the first step), so the orbit's first row is whatever the buffer held
    from symbt.numeric.multiprec import qd_step

    monkeypatch.setattr(qd_step, "qd_orbit", planted(qd_step.qd_orbit, "    outQ[0] = Q\n", "    outQ[1] = Q\n"))
    assert fails("paths.qd.n2")


def test_the_finiteness_test_of_a_sum_is_the_same_with_a_difference():
    # the fact behind the equivalence mark orbit:201 (`np.add.reduce(Ps) + np.add.reduce(Qs)` -> `-`): the sum is
    # only tested for finiteness; Qs are coordinates relative to the centre of mass, within (N - 1) MAX_DQ_FLOAT64 of
    # each other or the row is already out (the line before), so |sum Qs| is far below half an ulp of any sum of Ps
    # that could overflow, and x + y, x - y are non-finite together (inf - inf and inf + -inf are both NaN).
    # Rows at the edges: sums of Ps near and past the float64 maximum, inf and NaN in P or Q, huge equal q, a wide row
    import warnings

    from symbt.numeric.float64 import orbit

    N, n = 3, 3
    pa = np.array([[-20.0, 10.0, 1.0], [1.7e308, 0.0, 0.0], [8e307, 8e307, 8e307], [np.inf, 0, 0], [np.nan, 1, 2],
                   [-1.7e308, 1e308, 0.0], [1.0, 2.0, 3.0], [1.0, 2.0, 3.0], [1e308, 1e308, -1e308]])
    qa = np.array([[1.0, 0.0, 0.9], [0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 1, 2], [np.nan, 0, 0],
                   [1e300, 1e300, 1e300], [0, 650, 0]])
    m = len(pa)

    def run(block):
        P, Q = np.full((n + 1, m, N), 7.0), np.full((n + 1, m, 2 * N), 7.0)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            orbit._general_block, real = block, orbit._general_block
            try:
                st, step = orbit.general_orbit(pa, qa, np.full(m, 10.0), np.full(m, 5.0), 1, n, 1, P, Q,
                                               np.arange(m))
            finally:
                orbit._general_block = real
        return P, Q, st.tolist(), step.tolist()

    a = run(orbit._general_block)
    b = run(planted(orbit._general_block, "np.add.reduce(Ps) + np.add.reduce(Qs)",
                    "np.add.reduce(Ps) - np.add.reduce(Qs)"))
    assert a[2] == b[2] and a[3] == b[3] and 4 in a[2] and 0 in a[2]
    assert np.array_equal(a[0], b[0], equal_nan=True) and np.array_equal(a[1], b[1], equal_nan=True)


def test_the_exact_layer_refuses_a_relation_constant_in_its_symbol(monkeypatch):
    # flint_exact:121 (seed 28, `d < 1` -> `d < 0`): FLINT's reduction divided by a relation of degree 0 in its
    # symbol and proved x y = 0 from {x: y - 1}; the exact layer now refuses such a relation on every route before
    # either divides -- without that test, FLINT's route (where installed) proves it
    pytest.importorskip("flint")
    from symbt.proof import exact

    monkeypatch.setattr(exact, "exact_zero", planted(exact.exact_zero, "        relation_poly(rel, sym)\n",
                                                     "        pass\n"))
    assert fails("checker.relation_degree")


def test_the_codegen_verifier_refuses_to_compare_at_no_point():
    # codegen.verify:230 (seed 28, `nout = 0` -> 1): only an empty list of points read the initial value -- and such
    # a comparison passed, comparing nothing; it is now refused
    import symbt.generated.toda2 as toda2
    from symbt.codegen.verify import compare

    with pytest.raises(ValueError, match="no point"):
        compare(toda2, 2, "invariants", pts=[])
    assert compare(toda2, 2, "invariants")["nout"] == 2


def test_the_real_phase_at_a_band_edge_of_the_upper_parameter(monkeypatch):
    # elliptic:270 (seed 28, `abs(T1) >= 2` -> `> 2`): at T1 = 2 exactly the real phase was None
    from symbt.reference import elliptic

    monkeypatch.setattr(elliptic, "shift", planted(elliptic.shift, "and abs(T1) >= 2 and", "and abs(T1) > 2 and"))
    assert fails("library.reference_edges")


def test_the_reference_verification_reads_moduli(monkeypatch):
    # literal:292 (seed 28, `abs(a - b)` -> `a - b`): a reference whose largest disagreement is negative passed
    from symbt.claims import library_ref45
    from symbt.reference import literal

    # the claim's module binds reference_step at its import
    monkeypatch.setattr(library_ref45, "reference_step", planted(literal.reference_step, "diff = max(abs(a - b) for",
                                                                 "diff = max(a - b for"))
    assert fails("library.reference_verify", crash=True)     # (complex differences at one state: a TypeError)
