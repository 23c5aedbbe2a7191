"""The claims of ``symbt/claims/library_ref3.py`` kill the survivors of seed 3's sample they were written for, tests
kill the ones that change only cost or a resource limit, and the equivalence proof of ``elliptic:187`` (issue 21,
item 4; docs/mutation.md, "Seed 3's sample: the survivors of symbt.reference and symbt.symbolic").

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own text, with
:func:`planting.planted` -- and requires the claim (or the documented rule) to fail; unpatched, every claim verifies.
"""
from __future__ import annotations

import ast
import inspect
import math
import textwrap

import mpmath as mp
import pytest
import sympy as sp
from planting import planted

from symbt.claims import library_ref3 as L
from symbt.reference import elliptic as E
from symbt.reference import inverse, samples, taylor
from symbt.reference import trace as T
from symbt.symbolic import rewriting
from symbt.symbolic.toda import TodaModel

CLAIMS = [L.model_symbols, L.addition_checks, L.state_ranges, L.inverse_polish, L.sample_stream, L.trace_gap_ends]


def status(check) -> str:
    return check.run().status


@pytest.mark.parametrize("check", CLAIMS, ids=lambda c: c.id)
def test_unpatched_verified(check):
    assert status(check) == "verified"


# --------------------------------------------------------------------------- symbolic: library.model_symbols

def test_model_momenta_not_real_killed(monkeypatch):
    # symbt.symbolic.toda:50 (seed 3): the momenta declared without real=True
    bad = planted(TodaModel.__init__, 'sp.symbols(f"p1:{N + 1}", real=True)', 'sp.symbols(f"p1:{N + 1}", real=False)')
    monkeypatch.setattr(TodaModel, "__init__", bad)
    assert status(L.model_symbols) == "failed"


def test_exp_symbol_keyed_wrong_killed(monkeypatch):
    # symbt.symbolic.rewriting:61 index-shift (seed 3, uncovered before): the fresh symbol stored under s - 1
    bad = planted(rewriting.rationalize_exponentials, "exp_symbols[s] = sp.Dummy(", "exp_symbols[s - 1] = sp.Dummy(")
    monkeypatch.setattr(L, "rationalize_exponentials", bad)
    assert status(L.model_symbols) == "failed"


def test_exp_symbol_not_positive_killed(monkeypatch):
    # symbt.symbolic.rewriting:61 constant (seed 3, uncovered before): the symbol for exp(s) not positive
    bad = planted(rewriting.rationalize_exponentials, "positive=True)", "positive=False)")
    monkeypatch.setattr(L, "rationalize_exponentials", bad)
    assert status(L.model_symbols) == "failed"


# --------------------------------------------------------------------------- reference.elliptic: library.addition

def test_addition_residual_pt_factor_killed(monkeypatch):
    # elliptic:369 (seed 3, uncovered before): P~ without the factor 2 of 2 sqrt(I2 - 2)
    bad = planted(E.addition_residual, "Pt = (pt[1] - pt[0]) / (2 * mp.sqrt(I2 - 2))",
                  "Pt = (pt[1] - pt[0]) / (mp.sqrt(I2 - 2))")
    monkeypatch.setattr(E, "addition_residual", bad)
    assert status(L.addition_checks) == "failed"


def test_addition_residual_lost_abs_killed(monkeypatch):
    # elliptic:372 (seed 3, uncovered before): max(sn - Pt / max(1, |Pt|), ...): a signed first term, so a P~ above
    # sn no longer counts
    bad = planted(E.addition_residual, "max(abs(sn - Pt) / max(1, abs(Pt)),", "max(sn - Pt / max(1, abs(Pt)),")
    monkeypatch.setattr(E, "addition_residual", bad)
    assert status(L.addition_checks) == "failed"


def test_printed_addform_sign_killed(monkeypatch):
    # elliptic:381 (seed 3, uncovered before): P~ from p~_2 + p~_1
    bad = planted(E.printed_addform_residual, "(pt[1] - pt[0]) / (2 * r)", "(pt[1] + pt[0]) / (2 * r)")
    monkeypatch.setattr(E, "printed_addform_residual", bad)
    assert status(L.addition_checks) == "failed"


# --------------------------------------------------------------------------- reference.elliptic: library.state_ranges

def test_sample_state_level_set_killed(monkeypatch):
    # elliptic:401 (seed 3): Pr = sqrt(I2 - cosh x): the state's own I2 is I2 + cosh x, off the documented range
    bad = planted(E.sample_state, "math.sqrt(max(I2 - 2 * math.cosh(x), 0.0))",
                  "math.sqrt(max(I2 - math.cosh(x), 0.0))")
    monkeypatch.setattr(E, "sample_state", bad)
    assert status(L.state_ranges) == "failed"


# --------------------------------------------------------------------------- reference.inverse: library.inverse_polish

def test_inverse_final_step_reversed_killed(monkeypatch):
    # inverse:61 (seed 3): the final Newton step taken as J^-1 r: it raises the residual, so it is dropped and the
    # answer is the iterate at tol
    bad = planted(inverse._newton, "dx = _solve(Jm, r)\n                xn",
                  "dx = _solve(Jm, [-v for v in r])\n                xn")
    monkeypatch.setattr(inverse, "_newton", bad)
    assert status(L.inverse_polish) == "failed"


def test_inverse_band_guess_memo_killed(monkeypatch):
    # inverse:118 (seed 3, uncovered before): the not-admissible mark stored under key + 1 (a TypeError on the tuple)
    bad = planted(inverse.solve_parameters, "memo[key] = None", "memo[key + 1] = None")
    monkeypatch.setattr(L, "solve_parameters", bad)
    assert status(L.inverse_polish) == "failed"


# --------------------------------------------------------------------------- reference.samples

def test_sampler_stream_of_the_other_sign_killed(monkeypatch):
    # samples:42 (seed 3): (trace_sign > 1): sign +1 draws from sign -1's stream
    bad = planted(samples.admissible_states, "10 * seed + (trace_sign > 0)", "10 * seed + (trace_sign > 1)")
    monkeypatch.setattr(L, "admissible_states", bad)
    assert status(L.sample_stream) == "failed"


class _Stop(Exception):
    pass


def _never_admissible(monkeypatch, limit: int) -> list[int]:
    calls = [0]

    def refuse(*args):
        calls[0] += 1
        if calls[0] > limit:
            raise _Stop
        return False, None
    monkeypatch.setattr(samples, "_real_map", refuse)
    return calls


def test_sampler_gives_up_after_20000_proposals(monkeypatch):
    # samples:47 (seed 3) -- killed by tests: the documented limit (RuntimeError after 20000 proposals).  The mutant
    # `tries += 0` never gives up (a hang where no state is admissible); no claim can afford 20000 literal steps
    calls = _never_admissible(monkeypatch, 20001)
    with pytest.raises(RuntimeError, match="no admissible state"):
        samples.admissible_states(2, 1, 1)
    assert calls[0] == 20000


def test_sampler_without_limit_killed(monkeypatch):
    calls = _never_admissible(monkeypatch, 20001)
    bad = planted(samples.admissible_states, "tries += 1", "tries += 0")
    with pytest.raises(_Stop):                        # past the limit, still drawing
        bad(2, 1, 1)
    assert calls[0] > 20000


# --------------------------------------------------------------------------- reference.trace: library.trace_gap

def test_trace_gap_open_lower_end_killed(monkeypatch):
    # trace:126 (seed 3): `lo < r.real`: a band edge at the lower end no longer counts
    bad = planted(T.trace_gap, "lo <= r.real <= hi", "lo < r.real <= hi")
    monkeypatch.setattr(L, "trace_gap", bad)
    assert status(L.trace_gap_ends) == "failed"


# --------------------------------------------------------------------------- reference.taylor (killed by tests)

def _flow_order(flow, dps: int) -> int:
    p, q = [mp.mpf("0.3"), mp.mpf("-0.2")], [mp.mpf("0.1"), mp.mpf("0.4")]
    with mp.workdps(dps):
        return flow(p, q, [0, 0, 1], mp.mpf("0.01")).order


@pytest.mark.parametrize("dps", [15, 30])
def test_taylor_default_order(dps):
    # taylor:148 (seed 3) -- killed by tests: the documented default order max(12, floor(ln(1/tol)/2) + 6) with
    # tol = 10^-(dps + 2); the mutant (- 6) runs 12 orders lower.  A cost change: the step rule keeps the error per
    # unit time about tol at any order, with more steps
    want = max(12, math.floor((dps + 2) * math.log(10) / 2) + 6)
    assert _flow_order(taylor.hamiltonian_flow, dps) == want
    bad = planted(taylor.hamiltonian_flow, "int(-mp.log(tol) / 2) + 6)", "int(-mp.log(tol) / 2) - 6)")
    assert _flow_order(bad, dps) == max(12, want - 12)
    if want - 12 > 12:
        assert _flow_order(bad, dps) != want


def _linear_flow_steps(flow) -> tuple[int, list]:
    # G = H_1 = p1 + p2: q_j(t) = q_j + t exactly, p and the bonds constant; at order 2 the last Taylor coefficient
    # is 0 and the one before is the velocity 1 (scale 1: every |x| <= 1)
    p, q = [mp.mpf("0.5"), mp.mpf("-0.5")], [mp.mpf(0), mp.mpf(0)]
    with mp.workdps(20):
        out = flow(p, q, [0, 1, 0], mp.mpf(1), tol=mp.mpf("1e-2"), order=2)
    return out.steps, [*out[0], *out[1]]


def test_taylor_step_rule_reads_the_coefficient_before_the_last():
    # taylor:164 (seed 3) -- killed by tests: the step is bounded by both of the last two Taylor coefficients that
    # are not 0 (docstring), so h = 0.7 (tol/1)^(1/1) = 0.007 here: ceil(1/0.007) = 143 steps.  The mutant
    # (`nK1 > 1`) ignores a coefficient below 1 and takes the whole interval at once.  Both are exact on this
    # polynomial flow: a cost change (the rule guards a vanishing last coefficient of a non-polynomial flow)
    steps, state = _linear_flow_steps(taylor.hamiltonian_flow)
    assert abs(steps - math.ceil(1 / 0.007)) <= 1
    assert max(abs(a - b) for a, b in zip(state, [0.5, -0.5, 1, 1])) < 1e-15
    bad = planted(taylor.hamiltonian_flow, "if nK1 > 0:", "if nK1 > 1:")
    assert _linear_flow_steps(bad)[0] == 1


# --------------------------------------------------------------------------- the equivalence of elliptic:187

#: (p1, p2, q1, q2) in every quadrant of (P, C), and one at C = 0 (q1 = q2)
QUADRANT_STATES = (("0.7", "-0.4", "0.3", "-0.5"), ("-0.7", "0.4", "0.3", "-0.5"), ("0.7", "-0.4", "-0.6", "0.2"),
                   ("-0.7", "0.4", "-0.6", "0.2"), ("0.9", "0.1", "0.2", "0.2"))


def test_global_u_cosine_factor_is_equivalent():
    # elliptic:187 (seed 3): C = sinh((q1 - q2)/2)/r instead of 2 sinh(...)/r.  C is assigned once and read only
    # in `C >= 0`; halving it (exactly, in binary; mpmath has no underflow) keeps its sign, so the branch and the
    # returned u are the same for every input -- checked on the syntax tree, and bit for bit on states in all four
    # quadrants of (P, C) and at C = 0
    tree = ast.parse(textwrap.dedent(inspect.getsource(E.global_u)))
    stores = [n for n in ast.walk(tree) if isinstance(n, ast.Name) and n.id == "C" and isinstance(n.ctx, ast.Store)]
    loads = [n for n in ast.walk(tree) if isinstance(n, ast.Name) and n.id == "C" and isinstance(n.ctx, ast.Load)]
    assert len(stores) == 1 and len(loads) == 1
    compares = [n for n in ast.walk(tree) if isinstance(n, ast.Compare) and n.left is loads[0]]
    assert len(compares) == 1 and isinstance(compares[0].ops[0], ast.GtE)
    assert isinstance(compares[0].comparators[0], ast.Constant) and compares[0].comparators[0].value == 0
    bad = planted(E.global_u, "C = 2 * mp.sinh(", "C = mp.sinh(")
    with mp.workdps(30):
        for p1, p2, q1, q2 in QUADRANT_STATES:
            p, q = [mp.mpf(p1), mp.mpf(p2)], [mp.mpf(q1), mp.mpf(q2)]
            assert bad(p, q) == E.global_u(p, q)


def test_rewriting_docstring_symbols_positive():
    # the rule library.model_symbols checks, stated where users read it: exp(s) stands for a positive symbol
    _, m = rewriting.rationalize_exponentials(sp.exp(sp.Symbol("x", real=True)))
    assert all(v.is_positive for v in m.values())
