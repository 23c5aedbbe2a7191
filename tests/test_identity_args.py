"""check_identity validates its arguments: a clear TypeError / ValueError instead of a confusing failure later."""
from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symbt import check_identity, decide
from symbt.testing import assert_identity

x = sp.Symbol("x", real=True)


@pytest.mark.parametrize("kw, exc, words", [
    ({"digits": 0}, ValueError, "digits must be positive, got 0"),
    ({"digits": -5}, ValueError, "digits must be positive"),
    ({"points": 0}, ValueError, "points must be positive"),
    ({"points": -1}, ValueError, "points must be positive"),
    ({"digits": 30.5}, TypeError, "digits must be an int, not float"),
    ({"digits": "50"}, TypeError, "digits must be an int, not str"),
    ({"points": 2.0}, TypeError, "points must be an int, not float"),
    ({"points": True}, TypeError, "points must be an int, not bool"),
    ({"seed": 1.5}, TypeError, "seed must be an int"),
    ({"seed": None}, TypeError, "seed must be an int"),
    ({"exact": "yes"}, TypeError, "exact must be True or False"),
    ({"fixed": [1, 2]}, TypeError, "fixed must be a dict"),
    ({"assumptions": ["positive"]}, TypeError, "assumptions must be a dict"),
    ({"assumptions": {x: True}}, TypeError, "assumptions[x] must be a dict"),
    ({"relations": "x**2 - 1"}, TypeError, "relations must be a dict, a list or an Eq"),
    ({"relations": 3.5}, TypeError, "relations must be a dict, a list or an Eq"),
])
def test_bad_options(kw, exc, words):
    with pytest.raises(exc) as info:
        check_identity(x, x, **kw)
    assert words in str(info.value)


@pytest.mark.parametrize("side", [None, object(), sp.sin, {1: 2}, {x}, b"x", [1, 2]],
                         ids=["None", "object", "sin", "dict", "set", "bytes", "list"])
def test_sides_sympy_cannot_read_are_type_errors(side):
    with pytest.raises(TypeError, match="lhs must be a SymPy expression, number or matrix"):
        check_identity(side, 0)
    with pytest.raises(TypeError, match="rhs must be"):
        check_identity(x, side)


def test_unparsable_string_is_a_value_error():
    with pytest.raises(ValueError, match="cannot parse lhs 'x \\+'"):
        check_identity("x +", 0)


@pytest.mark.parametrize("who", [check_identity, decide], ids=["check_identity", "decide"])
def test_sides_of_no_common_shape_name_both_arguments(who):
    name = who.__name__
    with pytest.raises(ValueError, match=rf"{name}: lhs is a 1x1 matrix and rhs the scalar 1"):
        who(sp.Matrix([[x]]), 1)          # was SymPy's TypeError "Data type not understood" from inside decide
    with pytest.raises(ValueError, match=rf"{name}: rhs is a 2x1 matrix and lhs the scalar x"):
        who(x, sp.Matrix([x, 1]))
    with pytest.raises(ValueError, match=rf"{name}: shape mismatch: lhs is 2x1, rhs 1x2"):
        who(sp.Matrix([x, 1]), sp.Matrix([[x, 1]]))
    assert who(sp.Matrix([x - x, 0]), 0).holds          # a scalar 0 is the zero matrix of the other side's shape
    assert not who(0, sp.Matrix([x, 0])).holds


@pytest.mark.parametrize("who", [check_identity, decide], ids=["check_identity", "decide"])
@pytest.mark.parametrize("side", [sp.Gt(x, 1), sp.And(x > 1, x < 2), sp.true, [x], "x +"],
                         ids=["relation", "and", "true", "list", "unparsable"])
def test_a_side_that_is_no_expression_is_named(who, side):
    with pytest.raises((TypeError, ValueError), match=rf"{who.__name__}: (cannot parse )?rhs"):
        who(x, side)


def test_accepted_forms_still_work():
    assert check_identity(x, x, digits=np.int64(30), points=np.int32(3), seed=np.int64(7)).status == "proved"
    assert check_identity("x - x", 0).status == "proved"
    assert check_identity(1.5, sp.Rational(3, 2)).status == "proved"
    assert check_identity(sp.Matrix([x]), sp.Matrix([x])).status == "proved"
    assert check_identity(sp.asinh(x), sp.log(x + sp.sqrt(x**2 + 1)), digits=20, points=2).status == "verified"


def test_assert_identity_passes_the_checks_on():
    with pytest.raises(ValueError, match="points must be positive"):
        assert_identity(x, x, points=0)
