"""symbt.testing.assert_identity: usable from any pytest suite."""
from __future__ import annotations

import pytest
import sympy as sp

from symbt.proof.identity import IdentityResult
from symbt.testing import IdentityAssertionError, assert_identity

x = sp.Symbol("x", real=True)
eta, mu, w = sp.symbols("eta mu w", real=True)


def test_returns_the_result_when_it_holds():
    r = assert_identity(sp.cosh(x) ** 2 - sp.sinh(x) ** 2, 1)
    assert isinstance(r, IdentityResult) and r.status == "proved"
    r = assert_identity(sp.asinh(x), sp.log(x + sp.sqrt(x ** 2 + 1)), points=4)
    assert r.status == "verified"


def test_passes_keywords_through():
    assert_identity((eta - mu) * (eta + mu), w, relations=[sp.Eq(eta ** 2, mu ** 2 + w)], require="proved")
    assert_identity(sp.sqrt(x ** 2), x, assumptions={x: {"positive": True}})


def test_false_identity_raises_with_residual_and_point():
    with pytest.raises(AssertionError) as info:
        assert_identity(sp.sqrt(x ** 2), x)
    msg = str(info.value)
    assert "identity does not hold" in msg and "Abs(x) == x" in msg
    assert "relative residual: 2" in msg
    assert "counterexample:" in msg and "x = -" in msg
    assert isinstance(info.value, IdentityAssertionError) and info.value.result.status == "false"


def test_custom_message_and_require_proved():
    with pytest.raises(AssertionError, match="eq. 42"):
        assert_identity(x + 1, x, msg="eq. 42")
    with pytest.raises(AssertionError, match="only verified numerically"):
        assert_identity(sp.asinh(x), sp.log(x + sp.sqrt(x ** 2 + 1)), require="proved", points=3)
    with pytest.raises(ValueError):
        assert_identity(x, x, require="maybe")
