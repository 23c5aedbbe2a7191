"""Seed 23's survivors (docs/mutation.md, "Seed 23"): planted bugs that the new claims now see, and the proof of a
rewrite that removed a tie.  Unpatched, every claim verifies."""
from __future__ import annotations

import mpmath as mp
import pytest
from planting import claim_fails as fails
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["checker.relation_degree", "checker.inclusive_bounds", "library.source_lines", "checker.magnitude_moduli",
          "library.reference_edges", "paths.rows_apart.n3", "library.project_roots", "checker.matrix_methods",
          "library.verify_points", "library.fresh_toda2"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


def test_a_relation_constant_in_its_symbol_is_refused(monkeypatch):
    # exact:73 (a degree test at `< 0`; the test is now symbt.proof.relations.relation_poly's, which reduce_modulo
    # calls): the constant relation divides, and x y reduces to 0
    from symbt.proof import exact

    monkeypatch.setattr(exact, "relation_poly", planted(exact.relation_poly, "poly.degree() < 1", "poly.degree() < 0"))
    assert fails("checker.relation_degree")


@pytest.mark.parametrize(("old", "new"), [("(err is None or err <= t)", "(err is None or err < t)"),
                                          ("holds = r <= t and", "holds = r < t and")])
def test_verdict_tolerance_is_inclusive(monkeypatch, old, new):
    # verdict:131 (the estimated error at the tolerance taken as too large)
    from symbt.proof.verdict import Verdict

    monkeypatch.setattr(Verdict, "sampled", classmethod(planted(Verdict.sampled.__func__, old, new)))
    assert fails("checker.inclusive_bounds")


@pytest.mark.parametrize(("old", "new"), [("if rp >= row.printed_worst:", "if rp > row.printed_worst:"),
                                          ("if rp <= self.tol:", "if rp < self.tol:")])
def test_cell_table_edges(monkeypatch, old, new):
    # cells:106 (an all-zero cell names no worst point), and a sample at the tolerance counted as failing
    from symbt.proof.cells import CellTable

    monkeypatch.setattr(CellTable, "add", planted(CellTable.add, old, new))
    assert fails("checker.inclusive_bounds")


def test_block_kernels_keep_their_source_lines(monkeypatch):
    # block_python:109 (the kernels' lines shifted by one)
    from symbt.numeric.float64 import block_python

    monkeypatch.setattr(block_python, "_rewritten", planted(block_python._rewritten, "co_firstlineno - 1)",
                                                            "co_firstlineno - 0)"))
    monkeypatch.setattr(block_python, "_KERNELS", block_python._build())
    assert fails("library.source_lines")


@pytest.mark.parametrize(("fn", "old", "new"), [("inlined", "co_firstlineno - 1)", "co_firstlineno - 2)"),
                                                ("_index", "n.slice.value >= 0:", "n.slice.value > 0:")])
def test_inliner_lines_and_spread_tuples(monkeypatch, fn, old, new):
    # inline:363 (a tuple read at index 0 left built) and the inlined function's lines
    from symbt.numeric.core import inline

    monkeypatch.setattr(inline, fn, planted(getattr(inline, fn), old, new))
    assert fails("library.source_lines")


def test_abel_at_zero_is_zero():
    # elliptic:223's tie went with the rewrite `u0 = sign(s) v`: at s = 0 both factors are 0 (F(0) = 0), and
    # mpmath has no signed zero, so the old `1 if s >= 0 else -1` and any other choice of sign give the same u0
    from symbt.reference.elliptic import _F_m, abel

    for m in (mp.mpf("0.25"), mp.mpf("0.9")):
        assert _F_m(mp.mpf(0), m) == 0
        assert abel(mp.mpf(0), mp.mpf(1), m) == 0
        assert -mp.mpf(0) == mp.mpf(0) and str(-mp.mpf(0)) == "0.0"


def test_existence_near_the_positivity_edge(monkeypatch):
    # existence:84 (the interval test's 2 mu halved): says OK wherever every Etilde_j > -1
    from symbt.numeric.float64 import existence

    monkeypatch.setattr(existence, "_at", planted(existence._at, "IV.div(2 * m, a - b)", "IV.div(m, a - b)"))
    assert fails("paths.existence_iv.n3")


@pytest.mark.parametrize(("old", "new"), [("sp.Abs(expr, evaluate=False)", "sp.Abs(expr, evaluate=True)"),
                                          ("return sp.Pow(magnitude(expr.base), expr.exp, evaluate=False)",
                                           "return sp.Pow(magnitude(expr.base), expr.exp, evaluate=True)")])
def test_magnitude_stays_a_modulus(monkeypatch, old, new):
    # magnitude:42 (an evaluated Abs of a positive symbol is the symbol)
    from symbt.proof import magnitude as M

    monkeypatch.setattr(M, "magnitude", planted(M.magnitude, old, new))
    assert fails("checker.magnitude_moduli")


def test_magnitude_has_no_power_one():
    # magnitude:40's old `exp > 0` mutated to `> 1` differed only at exponent 1, which SymPy never builds as a
    # Pow (x**1 is x); the test is now `is_positive`, which names what it means
    import sympy as sp

    x = sp.Symbol("x")
    assert not isinstance(x ** 1, sp.Pow) and isinstance(x ** 2, sp.Pow)


@pytest.mark.parametrize(("module", "fn", "old", "new"), [
    ("symbt.reference.elliptic", "shift", "abs(T1) >= 2 and abs(T2) >= 2:", "abs(T1) >= 2 and abs(T2) > 2:"),
    ("symbt.reference.spectral", "flow_coefficients_jacobian", "for k in range(len(p) + 1)]",
     "for k in range(len(p) + 0)]"),
    ("symbt.reference.spectral", "flow_coefficients_jacobian", "-branch * (f(lp, k) + f(lm, k))",
     "-branch * (f(lp, k) - f(lm, k))"),
    ("symbt.reference.inverse", "solve_parameters", "mp.sqrt(abs(t0 ** 2 - 4))", "mp.sqrt(t0 ** 2 - 4)"),
    # seed 25: spectral:40 (a strict band test divides by zero at the edge), :70 (the quadrature checks anyway),
    # :76 (the Jacobian's default branch)
    ("symbt.reference.spectral", "phi_gradient", "if abs(t) <= 2:", "if abs(t) < 2:"),
    ("symbt.reference.spectral", "flow_coefficients_mp", "branch=branch, ks=want, check=False)",
     "branch=branch, ks=want, check=True)"),
    ("symbt.reference.spectral", "flow_coefficients_jacobian", "branch: int = 1)", "branch: int = 0)"),
])
def test_reference_edges(monkeypatch, module, fn, old, new):
    # elliptic:270 (a band edge taken as inside a band), spectral:82 (the last pair dropped), inverse:178
    import importlib

    mod = importlib.import_module(module)
    monkeypatch.setattr(mod, fn, planted(getattr(mod, fn), old, new))
    if module == "symbt.reference.spectral" and fn != "phi_gradient":            # inverse binds them by name
        monkeypatch.setattr("symbt.reference.inverse." + fn, getattr(mod, fn))
    assert fails("library.reference_edges")


def test_rows_apart_keep_their_own_centre(monkeypatch):
    # orbit:246 (the compensated centre of mass written one row off once a row has left)
    from symbt.numeric.float64 import orbit

    monkeypatch.setattr(orbit, "_general_block", planted(orbit._general_block, "c_hi[alive], c_lo[alive] = t, lo",
                                                         "c_hi[alive], c_lo[alive - 1] = t, lo"))
    assert fails("paths.rows_apart.n3")


@pytest.mark.parametrize(("old", "new"), [('== "symbt")', '!= "symbt")'),
                                          ('(root / "symbt" / "__init__.py").is_file()',
                                           '(root / "symbt" / "__init__.py").exists() or True')])
def test_project_roots(monkeypatch, old, new):
    # codegen.project:47 (the name test negated: no claim had reached it), and the package test dropped
    from symbt.codegen import project

    monkeypatch.setattr(project, "is_project", planted(project.is_project, old, new))
    assert fails("library.project_roots")


def test_screen_scale_zero_only_where_both_sides_are_zero():
    # screen:384's old branch for scale 0 built its own PointCheck with `lv - rv` (mutated to `lv + rv`: the same
    # there); one construction now.  Scale 0 happens only where both sides are exactly 0 (so lv - rv = lv + rv = 0)
    import itertools

    import sympy as sp

    from symbt.proof import screen as S

    values = [mp.mpf(0), mp.mpf("1e-30"), mp.mpf(-2), mp.mpc(0, 1)]
    for lv, rv, m in itertools.product(values, values, [mp.mpf(0), mp.mpf("1e-20"), mp.mpf(3), mp.inf]):
        assert (S._scale(lv, rv, lambda m=m: m) == 0) == (lv == rv == 0 and m == 0), (lv, rv, m)
    x = sp.Symbol("x")
    zero = sp.Mul(x, 0, evaluate=False)
    r = S.screen(zero, zero, {}, 30, 3, 1, {})
    assert r.status == "verified" and r.residual == 0


def test_matrix_method_names_every_entry(monkeypatch):
    # decider:184 (the second entry's method; a 1x1 matrix then raises IndexError) and the first entry's only
    from symbt.proof import decider

    for new in ("parts[1].method", "parts[0].method"):
        monkeypatch.setattr(decider, "decide", planted(decider.decide,
                                                       '" | ".join(dict.fromkeys(d.method for d in parts))', new))
        assert fails("checker.matrix_methods", crash=True)
        monkeypatch.undo()


def test_verify_points_both_parameters(monkeypatch):
    # codegen.verify:73 (lam0 - mu sampled twice)
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "points", planted(verify.points, "for lv in (l0 + m, l0 - m):",
                                                  "for lv in (l0 - m, l0 - m):"))
    assert fails("library.verify_points")


@pytest.mark.parametrize("old, new", [
    ("q=[signed(k, i + 1, 1.5)", "q=[signed(k, i + 0, 1.5)"),           # codegen.verify:86 (seed 26): q signed as p
    ('pt["c"] = [signed(k, i + 2, 1)', 'pt["c"] = [signed(k, i + 1, 1)'),   # c signed as q
    ("return v if (k >> (bit % 3)) & 1 else -v", "return v"),            # every coordinate positive
])
def test_verify_points_sign_patterns(monkeypatch, old, new):
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "points", planted(verify.points, old, new))
    assert fails("library.verify_points")


def test_codegen_names_what_it_wrote(monkeypatch):
    # codegen.cli:131 (`if not args.quiet` negated: the report printed only under --quiet)
    from symbt.codegen import cli

    monkeypatch.setattr(cli, "main", planted(cli.main, "    if not args.quiet:\n        for p in paths:",
                                             "    if args.quiet:\n        for p in paths:"))
    assert fails("library.fresh_toda2")
