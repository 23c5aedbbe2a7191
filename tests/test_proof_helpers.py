"""The proof layer's helpers: memoised lambdify and the linear solver that stands in for sympy.solve."""
import random

import mpmath as mp
import pytest
import sympy as sp

from symbt.proof.lambdify import _MEMO, MAX_ENTRIES, plain_lambdify
from symbt.symbolic.linear import solve_linear

lam, x, y = sp.symbols("lambda x y")


def test_memo_returns_the_same_function_for_the_same_expression():
    f = plain_lambdify([lam, x], sp.exp(lam) * x)
    assert plain_lambdify([lam, x], sp.exp(lam) * x) is f
    assert f(mp.mpf(0), 3) == 3


def test_a_mutated_expression_is_a_new_function():
    # mutation testing relies on this: a changed statement must not reuse the original's function
    f = plain_lambdify([lam, x], lam * x + 1)
    g = plain_lambdify([lam, x], lam * x + 2)
    assert f is not g and f(2, 3) == 7 and g(2, 3) == 8


def test_modules_and_nesting_are_part_of_the_key():
    expr = [lam + x, [lam * x]]
    fm = plain_lambdify([lam, x], expr, "mpmath")
    fn = plain_lambdify([lam, x], expr, "math")
    assert fm is not fn
    assert fm(2, 3) == [5, [6]] and fn(2, 3) == [5, [6]]
    M = sp.Matrix([[lam, x]])
    assert plain_lambdify([lam, x], M, "mpmath")(1, 2).tolist() == [[1, 2]]


def test_memo_is_bounded():
    for k in range(MAX_ENTRIES + 10):
        plain_lambdify([x], x + k)
    assert len(_MEMO) <= MAX_ENTRIES


@pytest.mark.parametrize("seed", range(20))
def test_solve_linear_agrees_with_sympy_solve(seed):
    rng = random.Random(seed)
    a, b, c = (sp.Integer(rng.randint(-5, 5)) * sp.exp(lam) + sp.Integer(rng.randint(-5, 5)) * y
               + sp.Integer(rng.randint(1, 5)) for _ in range(3))
    for eq in (a * x + b, sp.Eq(a * x, b + c * y), a * x + b * x + c):
        got, want = solve_linear(eq, x), sp.solve(eq, x)
        assert len(got) == len(want) == 1
        assert sp.cancel(got[0] - want[0]) == 0


def test_solve_linear_falls_back_for_nonlinear_and_degenerate_equations():
    assert solve_linear(sp.Eq(x ** 2, 4), x) == sp.solve(sp.Eq(x ** 2, 4), x)
    assert solve_linear(y * x - y * x + 1, x) == []               # no x at all: no solution
    assert solve_linear((y + 1) ** 2 * x - y ** 2 * x - (2 * y + 1) * x + 3, x) == []   # c1 cancels to 0
