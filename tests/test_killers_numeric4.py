"""The claims of ``symbt/claims/shipped_sample3.py`` kill the bugs they were written for; the equivalence proof of
a unit test for a float-equality edge of ``core/context.py``
(issue 21, item 4; docs/mutation.md, seed 3's sample).

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own text, with
:func:`planting.planted` -- and requires the claim to fail; unpatched, every claim verifies.
"""
from __future__ import annotations

import numpy as np
import pytest
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

SAMPLE3 = ["paths.compress.n3", "paths.decimal_input.n3", "paths.error_bounds.n3", "paths.inline_lines",
           "paths.python_kernel.n3", "paths.qd_tables"]
NEEDS_FLINT = ("paths.decimal_input.n3", "paths.error_bounds.n3")


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.mark.parametrize("cid", SAMPLE3)
def test_unpatched_verified(cid):
    if cid in NEEDS_FLINT:
        pytest.importorskip("flint")
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- paths.qd_tables

def test_qd_expm1_table_one_row_short(monkeypatch):
    # mutant qd_arith:360 (constant): the expm1 table built over range(-89, 89 + 0): 178 rows; expm1 at an argument
    # whose reduction lands on j = 89 (m = 0) reads row 178.  At import the module's table is the builder's.
    from symbt.numeric.multiprec import qd_arith

    build = planted(qd_arith._constants, "expm1(mpmath.mpf(j) / _TAB)) for j in range(-_TAB_HALF, _TAB_HALF + 1)",
                    "expm1(mpmath.mpf(j) / _TAB)) for j in range(-_TAB_HALF, _TAB_HALF + 0)")
    monkeypatch.setattr(qd_arith, "_constants", build)
    monkeypatch.setattr(qd_arith, "EXPM1_TAB", build()[4])
    assert status("paths.qd_tables") == "failed"


def test_qd_exp_table_off_by_one_row(monkeypatch):
    # the exp table's rows shifted by one (row j + 89 holds exp((j + 1)/256))
    from symbt.numeric.multiprec import qd_arith

    build = planted(qd_arith._constants, "qd_of(mpmath.exp(mpmath.mpf(j) / _TAB))",
                    "qd_of(mpmath.exp(mpmath.mpf(j + 1) / _TAB))")
    monkeypatch.setattr(qd_arith, "_constants", build)
    monkeypatch.setattr(qd_arith, "EXP_TAB", build()[3])
    assert status("paths.qd_tables") == "failed"


# --------------------------------------------------------------------------- paths.inline_lines

def test_inlined_code_two_lines_late(monkeypatch):
    # mutant inline:471 (sign): `co_firstlineno - 1` -> `co_firstlineno + 1`: every line of the inlined code is
    # named two lines after its source line (tracebacks, coverage)
    from symbt.numeric.core import inline

    monkeypatch.setattr(inline, "inlined", planted(inline.inlined, "fn.__code__.co_firstlineno - 1)",
                                                   "fn.__code__.co_firstlineno + 1)"))
    assert status("paths.inline_lines") == "failed"


# --------------------------------------------------------------------------- paths.compress

def test_compression_never_taken(monkeypatch):
    # mutant coefficients:335 (branch): `if n >= nodes.size: break` inverted: the candidate loop stops at once,
    # the composite rule stays (32 nodes, where 12 and 16 agree)
    from symbt.numeric.flow import coefficients

    monkeypatch.setattr(coefficients, "flow_quadrature", planted(coefficients.flow_quadrature,
                                                                 "if n >= nodes.size:", "if not (n >= nodes.size):"))
    assert status("paths.compress.n3") == "failed"


def test_compression_candidates_off_the_interval(monkeypatch):
    # the candidate rules' nodes centred at (a - b)/2 instead of (a + b)/2 (a sign slip): no candidate agrees,
    # the composite rule stays
    from symbt.numeric.flow import coefficients

    monkeypatch.setattr(coefficients, "flow_quadrature", planted(
        coefficients.flow_quadrature, "nd, wt = 0.5 * (a + b) + 0.5 * (b - a) * x",
        "nd, wt = 0.5 * (a - b) + 0.5 * (b - a) * x"))
    assert status("paths.compress.n3") == "failed"


def test_compression_takes_a_larger_rule(monkeypatch):
    # the candidates tried from the largest down: a rule that agrees, but not the smallest
    from symbt.numeric.flow import coefficients

    monkeypatch.setattr(coefficients, "flow_quadrature", planted(
        coefficients.flow_quadrature, "for n in (8, 12, 16, 20, 24, 32, 40, 48, 56, 64, 80, 96, 112, 128):",
        "for n in (24, 8, 12, 16, 20, 32, 40, 48, 56, 64, 80, 96, 112, 128):"))
    assert status("paths.compress.n3") == "failed"


# --------------------------------------------------------------------------- paths.python_kernel

def test_python_backend_asks_for_numba(monkeypatch):
    # mutant orbit:387 (compare): `"numba" if backend == "auto"` -> `!=`: backend="python" runs the numba kernel
    # (the same bits where numba is installed -- compiled in seconds --, MissingDependencyError where it is not)
    from symbt.numeric.float64 import orbit

    monkeypatch.setattr(orbit, "_ensemble", planted(orbit._ensemble, '"numba" if backend == "auto" else backend',
                                                    '"numba" if backend != "auto" else backend'))
    assert status("paths.python_kernel.n3") == "failed"


# --------------------------------------------------------------------------- paths.decimal_input

def test_decimal_strings_not_parsed(monkeypatch):
    # mutant certified:105 (branch): `if isinstance(x, str)` inverted: a decimal string is refused as an unsupported
    # type (InvalidInputError)
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import certified

    monkeypatch.setattr(certified, "_ball", planted(certified._ball, "if isinstance(x, str):",
                                                    "if not (isinstance(x, str)):"))
    assert status("paths.decimal_input.n3") == "failed"


def test_decimal_strings_rounded_to_doubles(monkeypatch):
    # a decimal string read as the nearest double (arb(float(x))): a ball around another number
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import certified

    monkeypatch.setattr(certified, "_ball", planted(certified._ball, "b = arb(x.strip())", "b = arb(float(x))"))
    assert status("paths.decimal_input.n3") == "failed"


# --------------------------------------------------------------------------- paths.error_bounds

def test_error_bound_without_abs(monkeypatch):
    # mutant lohner_checks:274 (abs): `abs(arb(x) - arb(m)) + arb(r)` -> `arb(x) - arb(m) + arb(r)`: a float64
    # component below the enclosure's midpoint no longer counts
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "float64_error_bounds", planted(
        lohner_checks.float64_error_bounds, "worst.max(abs(arb(x) - arb(m)) + arb(r))",
        "worst.max(arb(x) - arb(m) + arb(r))"))
    assert status("paths.error_bounds.n3") == "failed"


def test_error_bound_halved(monkeypatch):
    # the deviation halved (a dropped factor): below the float64 error
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "float64_error_bounds", planted(
        lohner_checks.float64_error_bounds, "worst.max(abs(arb(x) - arb(m)) + arb(r))",
        "worst.max(abs(arb(x) - arb(m)) / 2 + arb(r))"))
    assert status("paths.error_bounds.n3") == "failed"


def test_error_bound_loose(monkeypatch):
    # the two-sided bound: a bound twice too large fails too
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "float64_error_bounds", planted(
        lohner_checks.float64_error_bounds, "worst.max(abs(arb(x) - arb(m)) + arb(r))",
        "worst.max(2 * abs(arb(x) - arb(m)) + arb(r))"))
    assert status("paths.error_bounds.n3") == "failed"


# --------------------------------------------------------------------------- unit: context:166

def test_complex_all_positive_at_a_zero_real_part():
    # mutant context:166 (branch): FloatContext.all_positive with `if self.is_complex` inverted.  On real arrays the
    # two bodies agree (np.real of a real array is the array); on a complex array the mutant compares the
    # lexicographic minimum with 0, which differs exactly where the smallest real part is 0 and its imaginary part
    # positive.  (No step calls it: the complex continuation runs step_core with check_real=False; paths.contexts
    # now checks the primitive against the interface table.)
    from planting import planted as plant

    from symbt.numeric.core import context

    x = np.array([1.0 + 0.0j, 0.0 + 1.0j])
    assert context.COMPLEX.all_positive(x) is False
    # "certainly > 0" is real and positive (as MP and ACB decide it; paths.contexts): a nonzero imaginary part fails
    assert context.COMPLEX.all_positive(np.array([1.0 + 0.0j, 2.0 + 0.0j])) is True
    assert context.COMPLEX.all_positive(np.array([1.0 + 5.0j, 2.0 - 1.0j])) is False
    assert context.FLOAT.all_positive(np.array([1.0, np.nan])) is False
    mutant = plant(context.FloatContext.all_positive, "if self.is_complex:", "if not (self.is_complex):")
    assert mutant(context.COMPLEX, x) is True            # the planted mutant says "positive"
    assert mutant(context.FLOAT, np.array([1.0, 2.0])) is True and mutant(context.FLOAT, np.array([1.0, 0.0])) is False
