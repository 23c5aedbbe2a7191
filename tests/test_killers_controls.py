"""The claims of ``symbt/claims/codegen_controls.py`` and ``checker_seed6.py`` kill survivors of seeds 4, 5 and 6 in
``symbt.codegen`` and ``symbt.proof.verdict``.

Each test plants one mutant's own text (``tests/planting.py``) and requires the claim written for it to fail;
unpatched, every claim verifies.
"""
from __future__ import annotations

import pytest
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.mark.parametrize("cid", ["checker.codegen_metrics", "library.printer_powers", "checker.verdict_digits",
                                 "paths.rows_out.n3", "paths.panels", "paths.q_low.n3"])
def test_unpatched_verified(cid):
    assert status(cid) == "verified"


def test_compare_keeps_a_stale_mp_measure(monkeypatch):
    # seed 4, verify:216 (compare): `if em > worst_m` -> `if em < worst_m`: worst_mp stays 0, every mpmath
    # flavour passes
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "compare", planted(verify.compare, "if em > worst_m:", "if em < worst_m:"))
    assert status("checker.codegen_metrics") == "failed"


def test_compare_mp_tolerance_loosened(monkeypatch):
    # the mpmath flavour's tolerance loosened from 1e-45 to 1e-35: a 1e-40 error passes
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "MP_TOL", verify.MP_TOL * 10 ** 10)
    assert status("checker.codegen_metrics") == "failed"


def test_phi_grad_measure_relative_to_the_smaller(monkeypatch):
    # seed 4, verify:258 (phi_grad_vs_fd): `/ max(1, abs(g))` -> `/ min(1, abs(g))`
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "phi_grad_vs_fd", planted(verify.phi_grad_vs_fd, "/ max(1, abs(g)))",
                                                          "/ min(1, abs(g)))"))
    assert status("checker.codegen_metrics") == "failed"


@pytest.mark.parametrize("old, new", [
    ("if x.is_Integer or x.q == 2:", "if x.is_Integer or x.q != 2:"),       # seed 5, printer:176 (C flavour)
    ("if x.q == 2:", "if x.q != 2:"),                                       # numpy / mpmath half-integers
    ("n = int(x) if x.is_Integer else x.p", "n = int(x) if x.is_Integer else x.q"),
    ("if x.is_negative:", "if x.is_positive:"),
    ('one = "1.0" if self.flavour == "c" else "1"', 'one = "1.0" if self.flavour == "c" else "2"'),
])
def test_printed_powers(monkeypatch, old, new):
    from symbt.codegen.printer import ExprPrinter

    monkeypatch.setattr(ExprPrinter, "_pow", planted(ExprPrinter._pow, old, new))
    assert status("library.printer_powers") == "failed"


@pytest.mark.parametrize("old, new", [
    ("if f.p != 1:", "if f.p == 1:"),                                            # seed 6, printer:148
    ("den.append(sp.Integer(f.q))", "den.append(sp.Integer(f.p))"),
])
def test_printed_coefficients(monkeypatch, old, new):
    from symbt.codegen.printer import ExprPrinter

    monkeypatch.setattr(ExprPrinter, "_mul", planted(ExprPrinter._mul, old, new))
    assert status("library.printer_powers") == "failed"


@pytest.mark.parametrize("old, new", [
    ("if worst > 0 and math.isfinite(worst):", "if worst > 1 and math.isfinite(worst):"),   # seed 6, verdict:137
    ("min(-math.log10(worst), float(dps))", "max(-math.log10(worst), float(dps))"),
    ("worst = r if err is None else max(r, err)", "worst = r if err is None else min(r, err)"),
])
def test_verdict_digits(monkeypatch, old, new):
    from symbt.proof.verdict import Verdict

    monkeypatch.setattr(Verdict, "sampled", classmethod(planted(Verdict.sampled.__func__, old, new)))
    assert status("checker.verdict_digits") == "failed"


@pytest.mark.parametrize("old, new", [
    ("outq: FloatValue = qa.copy() if out is None else out[1]",
     "outq: FloatValue = qa.copy() if out is None else out[0]"),                    # seed 6, rows:209
    ("outp: FloatValue = pa.copy() if out is None else out[0]",
     "outp: FloatValue = pa.copy() if out is None else out[0].copy()"),
    ("idx_all = np.arange(M) if rows is None else rows", "idx_all = np.arange(M)"),
])
def test_rows_out(monkeypatch, old, new):
    from symbt.numeric.float64 import rows

    monkeypatch.setattr(rows, "float_rows_step", planted(rows.float_rows_step, old, new))
    assert status("paths.rows_out.n3") == "failed"


@pytest.mark.parametrize("old, new", [
    ("if sp.cancel(c1) != 0:", "if not (sp.cancel(c1) != 0):"),                  # seed 6, linear:37 (twice)
    ("if sp.cancel(c1) != 0:", "if sp.cancel(c1) == 0:"),
])
def test_solve_linear_avoids_sympy_solve(monkeypatch, old, new):
    # killed by tests: the mutants send a linear equation to sympy.solve, which gives the same root (a cost: the
    # module exists to avoid it); the original never calls it for c1 x + c0 = 0
    import sympy as sp

    from symbt.symbolic import linear

    a, b, x = sp.symbols("a b x")

    def refused(*args, **kwargs):
        raise AssertionError("sympy.solve called for a linear equation")

    assert linear.solve_linear(a * x + b, x) == [-b / a]
    monkeypatch.setattr(linear.sp, "solve", refused)
    assert linear.solve_linear(a * x + b, x) == [-b / a]
    bad = planted(linear.solve_linear, old, new)
    with pytest.raises(AssertionError, match="sympy.solve called"):
        bad(a * x + b, x)


@pytest.mark.parametrize("old, new", [
    ("width = abs(hi - lo) / abs(b - a)", "width = abs(hi + lo) / abs(b - a)"),          # coefficients:226 (seed 8)
    ("scale = _group_scale(np.abs(i32), groups)", "scale = np.abs(i32)"),
    ("rtol * np.maximum(np.abs(i32), scale * width)", "rtol * np.minimum(np.abs(i32), scale * width)"),
    ("if n >= max_intervals or mid in (lo, hi):", "if n > 2 * max_intervals or mid in (lo, hi):"),
    ("todo.append((mid, hi) + rule(mid, hi))", "todo.append((mid, hi) + rule(lo, hi))"),
    ("    n = 1\n", "    n = 0\n"),                                                         # coefficients:216 (seed 26)
    ("if n >= max_intervals or mid in (lo, hi):", "if n > max_intervals or mid in (lo, hi):"),
])
def test_adaptive_panels(monkeypatch, old, new):
    from symbt.numeric.flow import coefficients

    monkeypatch.setattr(coefficients, "adaptive_panels", planted(coefficients.adaptive_panels, old, new))
    assert status("paths.panels") == "failed"


@pytest.mark.parametrize("old, new", [
    ("    N = pr.p.shape[-1]\n    return P, np", "    N = pr.p.shape[-0]\n    return P, np"),   # orbit:345 (seed 8)
    ("np.ascontiguousarray(Q[..., N:])", "np.ascontiguousarray(Q[..., N - 1:-1])"),
    ("np.ascontiguousarray(Q[..., N:])", "np.zeros_like(Q[..., N:])"),
])
def test_q_low(monkeypatch, old, new):
    from symbt.numeric.float64 import orbit

    monkeypatch.setattr(orbit, "float_orbit_low", planted(orbit.float_orbit_low, old, new))
    assert status("paths.q_low.n3") == "failed"


def test_scale_weights_a_small_coordinate_by_one(monkeypatch):
    # seed 10, verify:215 (_scale): `max(abs(x0), 1)` -> `max(abs(x0), 0)`: the worst of the three points has every
    # |x_i| >= 1, so only the point-by-point measures see it
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "_scale", planted(verify._scale, "S[k] += max(abs(x0), 1) * abs(fh[k] - f0[k]) / h",
                                                  "S[k] += max(abs(x0), 0) * abs(fh[k] - f0[k]) / h"))
    assert status("checker.codegen_metrics") == "failed"


def test_xy_measure_keeps_the_modulus(monkeypatch):
    # seed 10, verify:300 (xy_vs_printed): the relative error over y itself, negative where y is: not seen by max
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "xy_vs_printed", planted(verify.xy_vs_printed,
                                                         'abs(y - info["y"][0]) / abs(info["y"][0]))',
                                                         'abs(y - info["y"][0]) / info["y"][0])'))
    assert status("checker.codegen_metrics") == "failed"


def test_quotient_by_one_divides(monkeypatch):
    # seed 10, verify:124 (interpret): `b != 0` -> `b != 1`: a quotient by 1 is infinite (and by 0 raises)
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "interpret", planted(verify.interpret, "v = a / b if b != 0 else",
                                                     "v = a / b if b != 1 else"))
    assert status("checker.codegen_metrics") == "failed"


def test_ops_flavour_dyadic_test(monkeypatch):
    # seed 10, printer:92 (no claim ran it): `e.q & (e.q - 1)` -> `e.q & (e.q - 0)`: every rational refused
    from symbt.codegen import printer

    monkeypatch.setattr(printer.ExprPrinter, "_p", planted(printer.ExprPrinter._p, "if e.q & (e.q - 1):",
                                                           "if e.q & (e.q - 0):"))
    assert status("library.printer_powers") == "failed"
