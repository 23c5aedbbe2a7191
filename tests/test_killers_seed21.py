"""Seeds 20 and 21's survivors (docs/mutation.md, "Seed 21"): planted bugs that the new claims and facts now see,
and the proofs of the mutants marked equivalent.  Unpatched, every claim verifies."""
from __future__ import annotations

import pytest
from planting import claim_fails as fails
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["library.fresh_toda2", "library.emissions_of", "paths.field_ivp.n3", "paths.inline_globals",
          "paths.qd_decompose", "checker.undefined_points"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


# --------------------------------------------------------------------------- the emitted text

@pytest.fixture
def fresh_declarations():
    """The closed-form declarations are cached per N: rebuilt under the planted bug, and again after it."""
    from symbt.codegen import zullo

    zullo.declarations.cache_clear()
    yield zullo
    zullo.declarations.cache_clear()


@pytest.mark.parametrize("old, new", [
    # pymodule:50: the numpy docstrings' output shapes ("batch" for a scalar output)
    ('"batch" + ("" if not o.shape else', '"batch" + ("" if o.shape else'),
    # pymodule:57: the error list of bt_step and dapp_xy (the ill-conditioning error named)
    ('if spec.name in ("bt_step", "dapp_xy"):', 'if not (spec.name in ("bt_step", "dapp_xy")):'),
])
def test_docstring_words(fresh_declarations, monkeypatch, old, new):
    from symbt.codegen import pymodule

    monkeypatch.setattr(fresh_declarations, "function_doc", planted(pymodule.function_doc, old, new))
    assert fails("library.fresh_toda2")



def test_forms_boundary(monkeypatch):
    # forms:30 (`N < LOOP_FROM` -> `<=`): N = 4 would be emitted in the closed form
    from symbt.codegen import forms

    monkeypatch.setattr(forms, "form_of", planted(forms.form_of, "N < LOOP_FROM", "N <= LOOP_FROM"))
    assert fails("library.fresh_toda2")


def test_c_power_is_a_call(monkeypatch):
    # printing:103 (`if self.flavour == "c"` negated): the C text of z**y read z**y, which C does not have
    from symbt.codegen.user.printing import UserPrinter

    monkeypatch.setattr(UserPrinter, "_pow", planted(UserPrinter._pow, 'if self.flavour == "c":\n        return f"pow',
                                                     'if not (self.flavour == "c"):\n        return f"pow'))
    assert fails("library.user_printer")


def test_c_reciprocal_numerator_is_a_double():
    # printing:101 (`"1.0" if self.flavour == "c"` -> `!=`): the same values in every flavour (a double denominator),
    # other text; the C text divides 1.0, the Python texts 1
    import sympy as sp

    from symbt.codegen.user.printing import UserPrinter

    z = sp.Symbol("z", positive=True)
    texts = {fl: UserPrinter(fl, {z: "z"}).text(z ** sp.Rational(-2, 3)) for fl in ("c", "numpy", "mpmath")}
    assert texts["c"].startswith("1.0/") and texts["numpy"].startswith("1/") and texts["mpmath"].startswith("1/")


def test_emissions_of_prefix(monkeypatch):
    # declare:324 (`e.declared_in == m` -> `!=`): every other module's declarations counted as the package's
    from symbt.codegen.user import declare

    monkeypatch.setattr(declare, "emissions_of", planted(declare.emissions_of, "e.declared_in == m or",
                                                         "e.declared_in != m or"))
    assert fails("library.emissions_of")


# --------------------------------------------------------------------------- the numeric paths

def test_field_counts_its_calls(monkeypatch):
    # field:197 (`self.nfev += 1` -> `+= 0`): FlowField.nfev stood still while scipy called it
    from symbt.numeric.flow.field import FlowField

    monkeypatch.setattr(FlowField, "__call__", planted(FlowField.__call__, "self.nfev += 1", "self.nfev += 0"))
    assert fails("paths.field_ivp.n3")


def test_field_flow_is_the_map(monkeypatch):
    # a wrong sign in the field's q-part: scipy's integration converges, to the flow of another Hamiltonian
    from symbt.numeric.flow.field import FlowField

    monkeypatch.setattr(FlowField, "__call__", planted(FlowField.__call__, "gq = np.roll(rr, 1, axis=-1) - rr",
                                                       "gq = rr - np.roll(rr, 1, axis=-1)"))
    assert fails("paths.field_ivp.n3")


def test_renormalised_by_the_largest_magnitude(monkeypatch):
    # condition:415 (`abs(D)` -> `D`): a negative D larger than every other entry was not the scale
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_renormalised_on_floats",
                        planted(condition._renormalised_on_floats, "_nanmax(abs(C), abs(D))", "_nanmax(abs(C), D)"))
    assert fails("paths.abs_products.n2") and fails("paths.abs_products.n3")


def test_dual_sign_test_with_positive_traces(monkeypatch):
    # lohner_checks:94 (Dual.__lt__ as >): two positive traces taken for opposite signs, the map refused
    pytest.importorskip("flint")
    from symbt.numeric.multiprec.lohner_checks import Dual

    monkeypatch.setattr(Dual, "__lt__", planted(Dual.__lt__, "self.v < (o.v", "self.v > (o.v"))
    assert fails("paths.jacobian_dual.n3", crash=True)


# --------------------------------------------------------------------------- simplifications, shown sound

def test_escalation_commutes_with_a_shift_of_q():
    # rows:52 (a shift's low part dropped) went with the shift: the map reads q through e^{q_{j+1} - q_j} only, so
    # escalating the relative coordinates and adding the centre gives the shifted state's result
    import numpy as np

    from symbt.numeric.float64.rows import escalate_rows

    p, q = np.array([[-20.0, 10.0, 1.0]]), np.array([[1.0, 0.0, 0.875]])
    c = 2.0 ** 30                                    # q + c exact: 0.875 needs 3 bits below the point
    pt, qt, st = escalate_rows(p, q, 10.0, 5.0, 1)
    ps, qs, ss = escalate_rows(p, q + c, 10.0, 5.0, 1)
    assert st.tolist() == ss.tolist() == [0]
    assert np.array_equal(pt, ps) and np.allclose(qs - c, qt, rtol=0, atol=2.0 ** -22)


@pytest.mark.parametrize("old, new", [("if nK > 0:", "if nK < 0:"),                       # taylor:167
                                      ('h = min(hs) * mp.mpf("0.7")', 'h = max(hs) * mp.mpf("0.7")')])   # :171
def test_taylor_step_takes_the_smaller_estimate(monkeypatch, old, new):
    # the last coefficient's estimate ignored, or the larger estimate taken: the first step of H_0's flow is longer
    from symbt.claims import library_elliptic_flows as flows
    from symbt.reference import taylor

    monkeypatch.setattr(flows, "hamiltonian_flow", planted(taylor.hamiltonian_flow, old, new))
    assert fails("library.flow_steps")


def test_inlined_globals_of_one_name(monkeypatch):
    # inline:334 (the clash test negated): both bodies' TABLE bound to one name, one body reads the other's table
    from symbt.numeric.core import inline

    monkeypatch.setattr(inline._Bodies, "global_name", planted(
        inline._Bodies.global_name, "if name in self.globals and self.globals[name] is not v:",
        "if not (name in self.globals and self.globals[name] is not v):"))
    assert fails("paths.inline_globals")


def test_flint_route_without_flint(monkeypatch):
    # exact:33 (uncovered: `route == "flint"` negated): without python-flint, 'auto' raised instead of using SymPy
    from symbt.proof import exact

    monkeypatch.setattr(exact, "exact_route", planted(exact.exact_route, 'if route == "flint":',
                                                      'if route != "flint":'))
    assert fails("checker.exact_route_names", crash=True)


def test_undefined_value_is_no_test(monkeypatch):
    # screen:87 (uncovered: `_finite` True for a value mpmath cannot read): the screen crashed on SymPy's None
    from symbt.proof import screen

    monkeypatch.setattr(screen, "_finite", planted(screen._finite, "        return False", "        return True"))
    assert fails("checker.undefined_points")


def test_decompose_equal_exponents_either_order():
    # qd:249 (`es[pos - 1] < e` -> `<=`), marked equivalent: components of equal exponent change places, their shift
    # is 0 and ((a << 0) + b) = ((b << 0) + a): the integers differ, the value they encode does not
    from fractions import Fraction

    import numpy as np

    from symbt.claims.seed21 import decompose_rows, decomposed_value
    from symbt.numeric.multiprec import qd

    mutant = planted(qd._decompose, "es[pos - 1] < e:", "es[pos - 1] <= e:")
    x = np.concatenate([decompose_rows(90), [[1.5, -1.25, 2.0 ** -60, 1.0], [3.0, 3.0, 3.0, 3.0]]])
    ours, theirs = np.zeros((len(x), 8), np.int64), np.zeros((len(x), 8), np.int64)
    qd._decompose(x, ours)
    mutant(x, theirs)

    assert not np.array_equal(ours, theirs)                          # the order of equal exponents does differ
    assert [decomposed_value(r) for r in ours.tolist()] == [decomposed_value(r) for r in theirs.tolist()] \
        == [sum(Fraction(float(v)) for v in row) for row in x]


def test_decompose_plain_shift(monkeypatch):
    # a planted bug in the read-out: one shift off by one -- the exact sum sees it
    from symbt.numeric.multiprec import qd

    monkeypatch.setattr(qd, "_decompose", planted(qd._decompose, "out[i, 3 + c] = es[c - 1] - es[c]",
                                                  "out[i, 3 + c] = es[c - 1] - es[c] + 1"))
    assert fails("paths.qd_decompose")
