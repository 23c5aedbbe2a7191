"""Seed 22's survivors (docs/mutation.md, "Seed 22"): planted bugs that the new claims and facts now see, and the
proofs of the mutants marked equivalent.  Unpatched, every claim verifies."""
from __future__ import annotations

import mpmath as mp
import pytest
from planting import claim_fails as fails
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["checker.ode_system", "paths.field_nomap.n3", "checker.codegen_metrics", "library.defaults",
          "checker.matrix_scalar", "checker.scope_counts", "library.spectral"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


def test_sampled_method_names_the_exact_layer_tried(monkeypatch):
    # ode:229 (`elif exact:` negated): the sentence "exact layer does not apply" under exact=False, none when tried
    from symbt.proof import ode

    monkeypatch.setattr(ode, "solves_ode", planted(ode.solves_ode, "    elif exact:", "    elif not (exact):"))
    assert fails("checker.ode_system")


def test_tuple_paired_in_equation_order(monkeypatch):
    # a tuple paired with the unknowns by name instead of the equations' order
    from symbt.proof import ode

    monkeypatch.setattr(ode, "_solution", planted(ode._solution, "items = list(zip(explicit, solution))",
                                                  "items = list(zip(sorted(explicit, key=str), solution))"))
    assert fails("checker.ode_system")


def test_flow_routes_refuse_with_bt_steps_condition(monkeypatch):
    # coefficients:277 (`check: bool = True` -> False): the quadrature's own band test named a positivity case trace
    from symbt.numeric.flow import coefficients, field

    mutant = planted(coefficients.flow_quadrature, "check: bool = True", "check: bool = False")
    monkeypatch.setattr(coefficients, "flow_quadrature", mutant)
    monkeypatch.setattr(field, "flow_quadrature", mutant)
    assert fails("paths.field_nomap.n3")


def test_interpret_not_equal(monkeypatch):
    # verify:146 (`"!=": a != b` -> `a == b`)
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "interpret", planted(verify.interpret, '"!=": a != b}', '"!=": a == b}'))
    assert fails("checker.codegen_metrics")


def test_float_orbit_default_every(monkeypatch):
    # orbit:305 (`every: int = 1` -> 0)
    from symbt.numeric.float64 import orbit

    monkeypatch.setattr(orbit, "float_orbit", planted(orbit.float_orbit, "every: int = 1", "every: int = 0"))
    assert fails("library.defaults", crash=True)


def test_F_odd_either_sign_canonical():
    # elliptic:145 (`z < 0` -> `z > 0`), marked equivalent: the memo keeps F at the other sign's argument; F is odd
    # and (-z) R = -(z R) exactly in binary floating point, so every value is the same bits
    from symbt.reference import elliptic as E

    mutant = planted(E._F_m, "isinstance(z, mp.mpf) and z < 0:", "isinstance(z, mp.mpf) and z > 0:")
    rng = mp.mp.rand
    with mp.workdps(40):
        for k in range(60):
            z = (rng() * 2 - 1) * (1 if k % 3 else mp.mpf(10) ** -20)
            m = rng() * mp.mpf("0.99")
            E._F_memo.cache_clear()
            ours = E._F_m(z, m)
            E._F_memo.cache_clear()
            assert mutant(z, m) == ours and E._F_m(-z, m) == -ours
        w = mp.mpc("0.3", "0.4")                         # complex arguments are not touched by either
        assert mutant(w, mp.mpf("0.5")) == E._F_m(w, mp.mpf("0.5"))


def test_matrix_side_named(monkeypatch):
    # decider:136 (seed 23: the condition negated): the message named the scalar side as the matrix
    from symbt.proof import decider

    monkeypatch.setattr(decider, "match_shapes", planted(decider.match_shapes, 'if lm else ("rhs", "lhs")',
                                                         'if not (lm) else ("rhs", "lhs")'))
    assert fails("checker.matrix_scalar")


def test_sampler_refuses_a_map_across_a_band(monkeypatch):
    # samples:35 (seed 23: `return False, info` -> True): a proposal with some Etilde_j <= 0 admitted
    from symbt.reference import samples

    monkeypatch.setattr(samples, "_real_map", planted(samples._real_map, "        return False, info",
                                                      "        return True, info"))
    assert fails("library.spectral")


def test_scope_names_a_cell_holding_once(monkeypatch):
    # cells:161 (seed 23: `0 < r.printed_holds` -> `1 <`): a cell holding at one sample left out of the sentence
    from symbt.proof.cells import CellTable

    monkeypatch.setattr(CellTable, "scope", planted(CellTable.scope, "if 0 < r.printed_holds < r.n]",
                                                    "if 1 < r.printed_holds < r.n]"))
    assert fails("checker.scope_counts")
