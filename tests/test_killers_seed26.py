"""Seeds 26 and 27's survivors (docs/mutation.md, "Seed 26", "Seed 27"): planted bugs that the new claims (and the
extended ones) now see.  Unpatched, every claim verifies."""
from __future__ import annotations

import mpmath as mp
import pytest
from planting import claim_fails as fails
from planting import planted

import symbt.numeric
from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["library.forced_backend", "library.emit_range"]


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
