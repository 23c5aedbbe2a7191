"""The claims of the scenes ``checker`` and ``library`` kill the bugs they were written for (issue 21, item 4).

Each test plants one single-point bug of ``symbt mutate --source``'s kind (the survivors of its run of
2026-11-26, docs/mutation.md) with ``monkeypatch`` and requires the claim to fail; unpatched, it verifies.
"""
from __future__ import annotations

import mpmath as mp
import pytest
import sympy as sp

from symbt.claims import checker, library
from symbt.codegen import derive
from symbt.proof import screen as screen_module
from symbt.proof import verdict as verdict_module
from symbt.reference import spectral
from symbt.symbolic import darboux, generating


def _status(c) -> str:
    return c.run().status


@pytest.mark.parametrize("c", [checker.screen_controls, checker.exact_controls, checker.cell_controls,
                               library.darboux_by_adjugate, library.spectral_routines,
                               *library.generating_derivatives.claims, *library.field_sources.claims])
def test_unpatched_verified(c):
    assert _status(c) == "verified"


def test_screen_recheck_precision(monkeypatch):
    # the recheck at digits + 10 cannot see an 80-digit cancellation: a true identity is refuted
    monkeypatch.setattr(screen_module, "high_precision", lambda d: d + 10)
    assert _status(checker.screen_controls) == "failed"


def test_screen_quadratic_root(monkeypatch):
    a = sp.symbols("_c0:3")
    wrong = sp.sqrt(a[1] ** 2 - 4 * a[1] * a[2])
    monkeypatch.setattr(screen_module, "_generic_roots",
                        lambda d: (a, [(-a[1] - wrong) / (2 * a[0]), (-a[1] + wrong) / (2 * a[0])]))
    assert _status(checker.screen_controls) == "failed"


def test_sampled_digits_cap(monkeypatch):
    real = verdict_module.Verdict.sampled.__func__

    def uncapped(cls, residual, *a, dps=None, **k):
        return real(cls, residual, *a, dps=None, **k)
    monkeypatch.setattr(verdict_module.Verdict, "sampled", classmethod(uncapped))
    assert _status(checker.exact_controls) == "failed"


def test_cells_worst_is_the_largest(monkeypatch):
    from symbt.proof import cells
    real = cells.CellTable.worst

    def best(self, which="printed"):
        rows = list(self.rows.values())
        attr = "printed_worst" if which == "printed" else "corrected_worst"
        row = min(rows, key=lambda r: getattr(r, attr))
        return getattr(row, attr), {"cell": "?"}
    monkeypatch.setattr(cells.CellTable, "worst", best)
    assert _status(checker.cell_controls) == "failed"
    monkeypatch.setattr(cells.CellTable, "worst", real)
    assert _status(checker.cell_controls) == "verified"


def test_darboux_composition_sign(monkeypatch):
    def wrong(x1, x2, y1, y2, l1=darboux.lam1, l2=darboux.lam2, lam_=darboux.lam):
        Dhat2 = sp.Matrix([[1, x2], [-y2, lam_ + l2 - x2 * y2]])
        D1 = sp.Matrix([[lam_ - l1 - x1 * y1, -x1], [y1, 1]])
        return (Dhat2 * D1).applyfunc(sp.expand)
    monkeypatch.setattr(library, "darboux_composition", wrong)
    assert _status(library.darboux_by_adjugate) == "failed"


def test_dF_index(monkeypatch):
    generating.generating_function.cache_clear()
    monkeypatch.setattr(generating.GeneratingFunction, "dF_dq",
                        lambda self, j: self.E[j] * self.total_derivative(self.F, self.E[j - 1]))
    try:
        assert _status(library.generating_derivatives.claims[0]) == "failed"
    finally:
        generating.generating_function.cache_clear()


@pytest.mark.parametrize("bug", ["d_p", "pdot"])
def test_field_sources(monkeypatch, bug):
    derive.sources.cache_clear()
    derive._trace_ring.cache_clear()
    if bug == "d_p":
        monkeypatch.setattr(derive._TraceRing, "d_p", lambda self, f, i: f.diff(self.p[i - 1]))
    else:
        real = derive._TraceRing.d_q
        monkeypatch.setattr(derive._TraceRing, "d_q", lambda self, f, i: -real(self, f, i))
    try:
        assert _status(library.field_sources.claims[0]) == "failed"
    finally:
        derive.sources.cache_clear()
        derive._trace_ring.cache_clear()


def test_spectral_band_check(monkeypatch):
    real = spectral.trace_gap
    monkeypatch.setattr(spectral, "trace_gap", lambda p, q, lo, hi: real(p, q, lo, lo))
    assert _status(library.spectral_routines) == "failed"


def test_phi_real_sign(monkeypatch):
    monkeypatch.setattr(spectral, "phi_real", lambda p, q, l0, m, b: spectral.phi_from_traces(
        spectral.trace(l0 - m, p, q), spectral.trace(l0 - m, p, q), b))
    assert _status(library.spectral_routines) == "failed"
    assert mp.mp.dps == 15


def test_solve_linear_degree_zero():
    # no root: sympy.solve's answer, not the shortcut's (which needs two coefficients)
    from symbt.symbolic.linear import solve_linear
    a, xx = sp.symbols("a xx")
    assert solve_linear(a + 1, xx) == []
    assert solve_linear(sp.Eq(xx ** 2, 4), xx) == [-2, 2]
