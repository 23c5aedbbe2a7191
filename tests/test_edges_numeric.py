"""Typed errors at the edges of the numeric API and of the emitted modules (issue 26, item 4)."""
from __future__ import annotations

import warnings

import mpmath
import numpy as np
import pytest

import symbt.generated.toda2 as toda2
import symbt.generated.toda3 as toda3
from symbt.numeric import (
    FlowField,
    InvalidInputError,
    bt_orbit,
    bt_step,
    flow_coefficients,
    invariants,
    phi,
    spectral_trace,
)

P3, Q3 = [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9]     # the paper's example: the real map exists at (10, 5)
HUGE = 10 ** 400                                   # a Python int no float64 holds

FLOAT_CALLS = {
    "bt_step": lambda p, q, lam0=10.0: bt_step(p, q, lam0, 5.0),
    "bt_orbit": lambda p, q, lam0=10.0: bt_orbit(p, q, lam0, 5.0, 3),
    "phi": lambda p, q, lam0=10.0: phi(p, q, lam0, 5.0),
    "spectral_trace": lambda p, q, lam0=10.0: spectral_trace(lam0, p, q),
    "invariants": lambda p, q, lam0=10.0: invariants(p, q),
    "flow_coefficients": lambda p, q, lam0=10.0: flow_coefficients(p, q, lam0, 5.0),
    "FlowField": lambda p, q, lam0=10.0: FlowField(p, q, lam0, 5.0),
}


@pytest.mark.parametrize("name", sorted(FLOAT_CALLS))
def test_integer_beyond_float64_is_a_typed_error(name):
    call = FLOAT_CALLS[name]
    with pytest.raises(InvalidInputError, match="float64 range"):
        call([HUGE, 10, 1], Q3)
    if name != "invariants":                      # the one function without a spectral parameter
        with pytest.raises(InvalidInputError, match="float64 range"):
            call(P3, Q3, HUGE)


@pytest.mark.parametrize("name", sorted(FLOAT_CALLS))
@pytest.mark.parametrize("bad", [[1 + 1j, 10, 1], np.array([-20, 10, 1], dtype=complex)], ids=["list", "array"])
def test_complex_states_are_refused_everywhere(name, bad):
    with warnings.catch_warnings():
        warnings.simplefilter("error")            # no ComplexWarning: refused, not cast
        with pytest.raises(InvalidInputError, match="complex"):
            FLOAT_CALLS[name](bad, Q3)


@pytest.mark.parametrize("bad", ["-20 10 1", ["-20", "10", "1"], {"p": 1}, [[-20.0, 10.0], [1.0]]],
                         ids=["string", "strings", "dict", "ragged"])
def test_flow_field_validates_its_input(bad):
    with pytest.raises(InvalidInputError):
        FlowField(bad, Q3, 10.0, 5.0)
    field = FlowField(P3, Q3, 10.0, 5.0)
    with pytest.raises(InvalidInputError):
        field(bad, Q3)
    with pytest.raises(InvalidInputError, match="complex"):
        field(np.array(P3, dtype=complex), Q3)
    qdot, pdot = field(P3, Q3)                    # the valid call still works
    assert qdot.shape == pdot.shape == (3,) and np.all(np.isfinite(qdot))


def test_every_beyond_n_stores_initial_and_final_state():
    P, Q = bt_orbit(P3, Q3, 10.0, 5.0, 7, every=10 ** 20)
    P7, Q7 = bt_orbit(P3, Q3, 10.0, 5.0, 7, every=7)
    assert np.array_equal(P, P7) and np.array_equal(Q, Q7) and P.shape == (2, 3)


def test_n_beyond_int64_is_a_typed_error():
    with pytest.raises(InvalidInputError, match="int64"):
        bt_orbit(P3, Q3, 10.0, 5.0, 10 ** 20)


def test_mpmath_coefficient_that_cancels_to_zero():
    # k = 1 over [-mu, mu] with tr nearly even: the integral cancels to exactly 0 at working precision
    p = [mpmath.mpf(0), mpmath.mpf(-10) ** 6]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        c = flow_coefficients(p, [350, 0], 0, 6.1e-5)
    assert len(c) == 2 and all(isinstance(v, mpmath.mpf) for v in c)
    assert c[1] == 0
    ref = flow_coefficients([0.0, -1e6], [350.0, 0.0], 0.0, 6.1e-5)
    assert abs(float(c[1]) - ref[1]) <= 1e-300
    assert abs(float(c[0]) - ref[0]) <= 1e-12 * abs(ref[0])


def _emitted_calls(m, n):
    e = np.zeros((0, n))
    return {
        "bt_step": lambda: m.bt_step(e, e, 5.0, 1.0, 1),
        "bt_step mask": lambda: m.bt_step(e, e, 5.0, 1.0, 1, errors="mask"),
        "phi": lambda: m.phi(e, e, 5.0, 1.0, 1),
        "phi_grad": lambda: m.phi_grad(e, e, 5.0, 1.0, 1),
        "ck_integrand": lambda: m.ck_integrand(5.0, e, e),
        "flow_field": lambda: m.flow_field(np.zeros(n), e, e),
        "hamiltonian_fields": lambda: m.hamiltonian_fields(e, e),
        "invariants": lambda: m.invariants(e, e),
        "spectral_trace": lambda: m.spectral_trace(5.0, e, e),
        "bt_orbit": lambda: m.bt_orbit(e, e, 5.0, 1.0, 3),
    }


@pytest.mark.parametrize("module, n", [(toda2, 2), (toda3, 3)], ids=["toda2", "toda3"])
def test_emitted_functions_on_an_empty_batch(module, n):
    for name, call in _emitted_calls(module, n).items():
        out = call()
        for a in out if isinstance(out, tuple) else (out,):
            assert 0 in np.shape(a), (name, np.shape(a))
    P, Q = module.bt_step(np.zeros((0, n)), np.zeros((0, n)), 5.0, 1.0, 1)
    assert P.shape == Q.shape == (0, n)


@pytest.mark.parametrize("branch", [1 + 0j, np.complex128(1), mpmath.mpc(1)])
def test_emitted_mp_refuses_complex_branch(branch):
    with pytest.raises(toda2.InvalidInputError, match="branch"):
        toda2.bt_step_mp([1, 2], [0, 0], 5, 1, branch)
    with pytest.raises(toda3.InvalidInputError, match="branch"):
        toda3.phi_mp([1, 2, 3], [0, 0, 0], 5, 1, branch)


def test_emitted_float_refuses_huge_integers_and_text():
    with pytest.raises(toda2.InvalidInputError, match="float64 range"):
        toda2.bt_step([HUGE, 2.0], [0.0, 0.0], 5.0, 1.0, 1)
    with pytest.raises(toda2.InvalidInputError):
        toda2.bt_step(["1", "2"], [0.0, 0.0], 5.0, 1.0, 1)
