"""The backend table of :mod:`symbt.numeric.backends`: names, arithmetic, the fallback chain, validation once.

The fallback tests put a stand-in quad-double backend into the table (``monkeypatch.setitem``) that gives
every problem back, so they run without numba and check the table's rule, not the quad-double arithmetic
(``tests/test_numeric_qd.py`` does that).
"""
import dataclasses
import sys
import typing

import mpmath
import numpy as np
import pytest

import symbt.numeric.backends as B
from symbt.numeric import (
    InvalidInputError,
    MissingDependencyError,
    NoRealMapError,
    NumericRangeError,
    bt_orbit,
    bt_step,
)
from symbt.numeric.multiprec.runners import flint_available

P0, Q0 = [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9]


def _mp(x):
    return [mpmath.mpf(v) for v in x]


def test_the_table_names_every_backend_once_with_its_arithmetic():
    names = set(typing.get_args(B.BackendName))
    assert names == set(B.BACKENDS) | {"auto"}
    assert {n for n, b in B.BACKENDS.items() if b.accepts == "float64"} == {"numba", "python", "numpy"}
    assert [n for n, b in B.BACKENDS.items() if b.accepts == "mpmath"] == ["qd", "flint", "mpmath"]
    for b in B.BACKENDS.values():       # a fallback computes in the same arithmetic; the chain ends
        assert b.fallback is None or B.BACKENDS[b.fallback].accepts == b.accepts
    assert B.BACKENDS["mpmath"].available() and B.BACKENDS["mpmath"].fallback is None


@pytest.mark.parametrize("backend, p, message", [
    ("fortran", P0, "must be one of"), ("qd", P0, "needs mpmath inputs"), ("numpy", _mp(P0), "needs float64 inputs")])
def test_a_name_the_input_cannot_take_is_refused(backend, p, message):
    for call in (lambda: bt_step(p, Q0, 10, 5, backend=backend), lambda: bt_orbit(p, Q0, 10, 5, 3, backend=backend)):
        with pytest.raises(InvalidInputError, match=message):
            call()


def test_a_forced_backend_without_its_extra_raises(monkeypatch):
    monkeypatch.setitem(B.BACKENDS, "flint", dataclasses.replace(B.BACKENDS["flint"], available=lambda: False))
    with pytest.raises(MissingDependencyError, match="python-flint"):
        bt_step(_mp(P0), Q0, 10, 5, backend="flint")
    # "auto" walks on to the next backend of the chain instead
    monkeypatch.setitem(B.BACKENDS, "qd", dataclasses.replace(B.BACKENDS["qd"], available=lambda: False))
    assert B.pick("auto", "mpmath").name == "mpmath"


def _giving_back(exc):
    def run(*args):
        raise exc("given back")
    return dataclasses.replace(B.BACKENDS["qd"], available=lambda: True, fits=lambda prec, n: True,
                               ready=lambda: True, step=run, orbit=run)


def test_auto_continues_on_the_fallback_where_the_first_backend_gives_the_problem_back(monkeypatch):
    with mpmath.workdps(30):
        want_step = bt_step(_mp(P0), Q0, 10, 5, backend="flint" if flint_available() else "mpmath")
        want_orbit = bt_orbit(_mp(P0), Q0, 10, 5, 4, backend="flint" if flint_available() else "mpmath")
        monkeypatch.setitem(B.BACKENDS, "qd", _giving_back(NumericRangeError))
        assert B.pick("auto", "mpmath").name == "qd"
        assert bt_step(_mp(P0), Q0, 10, 5) == want_step
        assert bt_orbit(_mp(P0), Q0, 10, 5, 4) == want_orbit
        # forced, the backend's own error stands
        with pytest.raises(NumericRangeError, match="given back"):
            bt_step(_mp(P0), Q0, 10, 5, backend="qd")
        with pytest.raises(NumericRangeError, match="given back"):
            bt_orbit(_mp(P0), Q0, 10, 5, 4, backend="qd")


def test_a_real_only_backend_hands_the_complex_continuation_on(monkeypatch):
    monkeypatch.setitem(B.BACKENDS, "qd", _giving_back(NoRealMapError))
    p, q, lam0, mu = _mp([0.0, 0.0]), _mp([0.0, 0.0]), 0, mpmath.mpf("0.5")     # |tr| < 2: inside a band
    with mpmath.workdps(30):
        with pytest.raises(NoRealMapError):
            bt_step(p, q, lam0, mu)
        pt, qt = bt_step(p, q, lam0, mu, allow_complex=True)
        assert any(isinstance(v, mpmath.mpc) for v in pt + qt)


def test_the_documented_calls_validate_their_input_once(monkeypatch):
    """Every binding of the converters in the loaded numeric modules counts its calls: one per argument."""
    from symbt.numeric.core import inputs

    calls = []
    for name in ("float_array", "_to_mp", "prepare_scalar"):
        orig = getattr(inputs, name)

        def counted(*a, _orig=orig, _name=name, **k):
            calls.append(_name)
            return _orig(*a, **k)
        for mod in [m for n, m in sys.modules.items() if n.startswith("symbt.numeric") and m is not None]:
            if getattr(mod, name, None) is orig:
                monkeypatch.setattr(mod, name, counted)
    for call in (lambda: bt_orbit(np.array(P0), np.array(Q0), 10.0, 5.0, 3),
                 lambda: bt_step(np.array(P0), np.array(Q0), 10.0, 5.0),
                 lambda: bt_orbit(_mp(P0), Q0, 10, 5, 3), lambda: bt_step(_mp(P0), Q0, 10, 5)):
        calls.clear()
        call()
        assert sorted(calls) in (["float_array", "float_array", "prepare_scalar", "prepare_scalar"],
                                 ["_to_mp", "_to_mp", "prepare_scalar", "prepare_scalar"]), calls


def test_prepared_record_is_the_dataclass_record():
    """``core.problem._record`` builds the frozen ``Problem`` without its ``__init__`` (per-call cost): it must
    set exactly the dataclass's fields, compare equal to ``Problem(...)`` and stay frozen -- a field added to
    ``Problem`` (or a ``__post_init__``) that ``_record`` does not know fails here."""
    import dataclasses

    from symbt.numeric.core.problem import Problem, _record, prepare

    pr = prepare([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, n=3, every=2)
    names = [f.name for f in dataclasses.fields(Problem)]
    assert list(vars(pr)) == names
    assert not hasattr(Problem, "__post_init__")
    assert pr == Problem(*(getattr(pr, k) for k in names))
    assert _record(*(getattr(pr, k) for k in names)) == pr
    with pytest.raises(dataclasses.FrozenInstanceError):
        pr.n = 4
