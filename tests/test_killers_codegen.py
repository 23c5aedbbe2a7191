"""The claims of ``symbt/claims/emitted_*.py`` kill the mutants of ``symbt.codegen`` they were written for.

Each test plants one survivor of ``symbt mutate --source codegen --sample 40 --seed 1`` (docs/mutation.md) -- the
mutant itself, found by ``symbt.engine.mutants.find_mutants`` from its line's text before and after (not its line
number, which moves when the file is edited), executed as a copy of the module -- with ``monkeypatch`` and requires
the claim to fail; unpatched, every claim verifies (or is skipped without a C compiler, with its reason).
"""
from __future__ import annotations

import sys

import pytest
import sympy as sp
from planting import mutated

from symbt.claims import REGISTRY, load_all
from symbt.codegen.user.check import compiler

load_all()

CLAIMS = ["library.emit_c_errors", "library.emit_typed", "library.illcond", "library.sources_step",
          "library.zullo_registry"]
HAS_CC = compiler() is not None


def status(cid: str) -> str:
    return REGISTRY[cid].run().status




def plant(monkeypatch, module: str, before: str, after: str, *names: str, into=()) -> None:
    """Replace ``names`` of ``module`` (and of the modules ``into``, which imported them) by the mutant's."""
    copy = mutated(module, before, after)
    for target in (sys.modules[module], *into):
        for name in names:
            monkeypatch.setattr(target, name, getattr(copy, name))


def test_the_claims_named_here_are_registered():
    assert all(cid in REGISTRY and REGISTRY[cid].scene == "library" for cid in CLAIMS)


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched(cid):
    want = "verified" if HAS_CC or cid != "library.emit_c_errors" else "skipped"
    assert status(cid) == want


# --------------------------------------------------------------------------- library.sources_step

def test_sources_step_eta_of_the_previous_site(monkeypatch):
    # derive:492 -- p~_j = p_j + eta_j - eta_{j-1}: the same at N = 2, wrong at N = 3
    from symbt.codegen import derive, verify

    copy = mutated("symbt.codegen.derive", "pt = [p[j] + eta[j] - eta[(j + 1) % N] for j in range(N)]",
                   "pt = [p[j] + eta[j] - eta[(j - 1) % N] for j in range(N)]", same_classes=True)
    monkeypatch.setattr(derive, "sources", copy.sources)
    monkeypatch.setattr(verify, "sources", copy.sources)
    assert status("library.sources_step") == "failed"


# --------------------------------------------------------------------------- library.illcond

def test_illcond_cancellation_of_the_neighbour(monkeypatch):
    # transport:90 -- the cancellation (|lam| + |p_j|)/|lam + p_{j-1}|
    plant(monkeypatch, "symbt.codegen.transport",
          "kta.append(k * sp.Max(*(Quotient(A(lam_) + A(p[j]), A(lam_ + p[j])) for j in range(N)), evaluate=False))",
          "kta.append(k * sp.Max(*(Quotient(A(lam_) + A(p[j]), A(lam_ + p[j - 1])) for j in range(N)), "
          "evaluate=False))",
          "illcond_guards")
    assert status("library.illcond") == "failed"


def test_illcond_trace_guard_zero(monkeypatch):
    # transport:80 -- an ill-conditioned trace guard valued 0 instead of -1 (refuses alike: "> 0" fails for both)
    plant(monkeypatch, "symbt.codegen.transport",
          "return sp.Piecewise((-1, sp.StrictGreaterThan(big, small, evaluate=False)), (1, True),",
          "return sp.Piecewise((-0, sp.StrictGreaterThan(big, small, evaluate=False)), (1, True),",
          "illcond_guards")
    assert status("library.illcond") == "failed"


# --------------------------------------------------------------------------- library.zullo_registry

def test_zullo_declarations_registered(monkeypatch):
    # zullo:66 -- Zullo's declarations recorded in the user's registry
    from symbt.codegen.user import declare

    monkeypatch.setattr(declare, "EMISSIONS", dict(declare.EMISSIONS))    # the planted registration is undone
    plant(monkeypatch, "symbt.codegen.zullo",
          "optimize=False, equation=s.equation, guards=guards, register=False)",
          "optimize=False, equation=s.equation, guards=guards, register=True)", "declaration")
    assert status("library.zullo_registry") == "failed"


# --------------------------------------------------------------------------- library.emit_typed

def test_typed_integer_powers_printed_as_roots(monkeypatch):
    # printer:171 -- every rational exponent but 1/2 printed as a square root
    from symbt.codegen import printer

    copy = mutated("symbt.codegen.printer", "if x == sp.Rational(1, 2):", "if x != sp.Rational(1, 2):")
    monkeypatch.setattr(printer.ExprPrinter, "_pow", copy.ExprPrinter._pow)
    assert status("library.emit_typed") == "failed"


def test_typed_without_expm1(monkeypatch):
    # printing:127 -- the expm1/log1p rewriting skipped exactly where exp/log occur
    from symbt.codegen.user import render, render_typed

    plant(monkeypatch, "symbt.codegen.user.printing", "if not x.has(fn):", "if x.has(fn):", "rewritten",
          into=(render, render_typed))
    assert status("library.emit_typed") == "failed"


def test_typed_piecewise_not_split(monkeypatch):
    # declare:315 -- the sign cells of a Piecewise's conditions dropped: one branch may go unsampled
    plant(monkeypatch, "symbt.codegen.user.declare",
          "if d.free_symbols and not d.free_symbols & (exact or set()) and str(d) not in seen:",
          "if not (d.free_symbols and not d.free_symbols & (exact or set()) and str(d) not in seen):",
          "_branch_splits")
    assert status("library.emit_typed") == "failed"


def test_typed_domain_per_element(monkeypatch):
    # typed:205 -- an array's first element taken as a scalar's range: a domain given per element is refused
    from symbt.codegen.user import declare

    plant(monkeypatch, "symbt.codegen.user.typed", 'if a.kind == "scalar" and whole is None:',
          'if a.kind != "scalar" and whole is None:', "typed_domain", into=(declare,))
    assert status("library.emit_typed") == "failed"


def test_typed_message_of_a_missing_scalar(monkeypatch):
    # typed:213 -- a missing scalar named as an array in the message
    from symbt.codegen.user import declare

    plant(monkeypatch, "symbt.codegen.user.typed", 'what = (f"argument {a.name}" if a.kind == "scalar" else',
          'what = (f"argument {a.name}" if not (a.kind == "scalar") else', "typed_domain", into=(declare,))
    assert status("library.emit_typed") == "failed"


def test_typed_python_flavours_swapped(monkeypatch):
    # check:173 -- compare's typed evaluator calls the numpy function for the mpmath flavour and vice versa
    plant(monkeypatch, "symbt.codegen.user.check", 'f = getattr(mod, e.name if flavour == "numpy" else e.name + "_mp")',
          'f = getattr(mod, e.name if flavour != "numpy" else e.name + "_mp")', "_typed_evaluator")
    assert status("library.emit_typed") == "failed"


@pytest.mark.skipif(not HAS_CC, reason="no C compiler (cc, gcc or clang) on PATH")
def test_typed_c_refusal_taken_for_invalid_input(monkeypatch):
    # check:168 -- every refusal of the typed C function raised as INVALID_INPUT
    plant(monkeypatch, "symbt.codegen.user.check", 'if what == "invalid":', 'if not (what == "invalid"):',
          "_typed_evaluator")
    assert status("library.emit_typed") == "failed"


@pytest.mark.skipif(not HAS_CC, reason="no C compiler (cc, gcc or clang) on PATH")
def test_typed_c_header(monkeypatch):
    # render_typed_c:144 -- the header's prototypes: a TypeError when the typed C header is rendered
    plant(monkeypatch, "symbt.codegen.user.render_typed_c",
          'hdr += [_signature(e, t) + ";" for e in emissions] + ["", f"#endif /* {guard} */"]',
          'hdr += [_signature(e, t) - ";" for e in emissions] + ["", f"#endif /* {guard} */"]',
          "default_template")
    assert status("library.emit_typed") == "failed"


# --------------------------------------------------------------------------- library.emit_c_errors

@pytest.mark.skipif(not HAS_CC, reason="no C compiler (cc, gcc or clang) on PATH")
def test_c_diagnostic_not_captured(monkeypatch):
    # check:108 -- the compiler's output not captured: no diagnostic to report
    plant(monkeypatch, "symbt.codegen.user.check", 'str(source), "-lm"], capture_output=True, text=True, timeout=120)',
          'str(source), "-lm"], capture_output=False, text=True, timeout=120)', "load_c")
    assert status("library.emit_c_errors") == "failed"


# --------------------------------------------------------------------------- equivalent (mutants-equivalent.toml)

def test_kernels_chain_rule_symbols_without_assumptions_equivalent():
    # kernels:143 -- qm, q0, qp declared without real=True: d/dq0 exp(q0 - qm) does not depend on assumptions and
    # the three symbols are replaced before the result is returned, so every kernel expression is the same
    from symbt.codegen import kernels

    copy = mutated("symbt.codegen.kernels", 'qm, q0, qp = sp.symbols("qm q0 qp", real=True)',
                   'qm, q0, qp = sp.symbols("qm q0 qp", real=False)')
    want, got = kernels.kernels(), copy.kernels()
    assert want.keys() == got.keys()
    assert all(got[k] == want[k] and sp.srepr(got[k]) == sp.srepr(want[k]) for k in want)
