"""Seed 26's survivors (docs/mutation.md, "Seed 26"): planted bugs that the new claims now see.  Unpatched, every
claim verifies."""
from __future__ import annotations

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
