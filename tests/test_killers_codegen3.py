"""The claims of ``symbt/claims/library_emit3.py`` kill the survivors of seed 3's sample of ``symbt.codegen``.

``symbt mutate --source numeric reference codegen symbolic proof --sample 40 --seed 3`` left 17 survivors in
``symbt.codegen`` (docs/mutation.md, "Seed 3's sample").  Each test below plants one of them -- the mutant's own
text, with ``tests/planting.py`` -- and requires the claim written for it to fail; unpatched, every claim
verifies.  The last tests prove the three equivalent mutants of the sample equivalent (mutants-equivalent.toml)
and kill, as tests, the two that change only the order of work or the association of a long sum.
"""
from __future__ import annotations

import ast
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from planting import mutated, planted

from symbt.claims import REGISTRY, load_all
from symbt.codegen.user.check import compiler

load_all()

CLAIMS = ["library.emit_shapes", "library.printer_precedence", "library.compare_refusal", "library.sources_real",
          "library.signatures", "library.codegen_rerun_argv"]
HAS_CC = compiler() is not None
PACKAGE = Path(__file__).resolve().parents[1] / "symbt"


def status(cid: str) -> str:
    return REGISTRY[cid].run().status




@pytest.fixture
def fresh_sources():
    """``derive.sources``/``specs`` caches emptied before and after (a planted ``_build`` must not leak)."""
    from symbt.codegen import derive

    derive.sources.cache_clear()
    derive.specs.cache_clear()
    yield derive
    derive.sources.cache_clear()
    derive.specs.cache_clear()


def test_the_claims_named_here_are_registered():
    assert all(cid in REGISTRY and REGISTRY[cid].scene == "library" for cid in CLAIMS + ["library.emit_c_sign"])
    assert REGISTRY["library.emit_c_sign"].deep and not any(REGISTRY[c].deep for c in CLAIMS)


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched(cid):
    assert status(cid) == "verified"


def test_unpatched_c_sign():
    assert status("library.emit_c_sign") == ("verified" if HAS_CC else "skipped")


# --------------------------------------------------------------------------- library.codegen_rerun_argv

def test_rerun_keeps_out_equals_and_drops_the_rest(monkeypatch):
    # cli:74 -- `--out=`/`--project=` kept and every other argument dropped
    from symbt.codegen import cli

    monkeypatch.setattr(cli, "_delegate_argv", planted(cli._delegate_argv,
                                                       'elif not a.startswith(("--project=", "--out=")):',
                                                       'elif a.startswith(("--project=", "--out=")):'))
    assert status("library.codegen_rerun_argv") == "failed"


# --------------------------------------------------------------------------- library.signatures

def test_signature_errors_on_the_mpmath_flavour(monkeypatch):
    # pymodule:19 -- errors="raise" on the mpmath flavour instead of the numpy one
    from symbt.codegen import pymodule

    monkeypatch.setattr(pymodule, "signature", planted(pymodule.signature, 'flavour == "numpy"',
                                                       'flavour != "numpy"'))
    assert status("library.signatures") == "failed"


# --------------------------------------------------------------------------- library.emit_shapes

def _source_property(old: str, new: str) -> property:
    from symbt.codegen.user.declare import Emission

    got = planted(Emission.source.fget, old, new)    # the rebuilt source carries its @property
    return got if isinstance(got, property) else property(got)


def test_source_of_a_scalar_as_a_matrix(monkeypatch):
    # declare:103 -- the scalar/array test inverted
    from symbt.codegen.user.declare import Emission

    monkeypatch.setattr(Emission, "source", _source_property("if self.shape == ():", "if not (self.shape == ()):"))
    assert status("library.emit_shapes") == "failed"


def test_source_of_a_column_as_a_matrix(monkeypatch):
    # declare:105 -- a column taken for a matrix (IndexError on its shape)
    from symbt.codegen.user.declare import Emission

    monkeypatch.setattr(Emission, "source", _source_property("if len(self.shape) == 1:", "if len(self.shape) == 0:"))
    assert status("library.emit_shapes") == "failed"


def test_module_template_registered_under_a_wrong_key(monkeypatch):
    # typed:135 -- TEMPLATES[module - 1] (a TypeError for every registered template)
    from symbt.codegen.user import typed

    monkeypatch.setattr(typed, "module_template", planted(typed.module_template, "TEMPLATES[module] = t",
                                                          "TEMPLATES[module - 1] = t"))
    assert status("library.emit_shapes") == "failed"


def test_files_check_reports_the_files_that_are_right(monkeypatch):
    # files:164 -- a problem line appended exactly when there is none
    from symbt.codegen.user import files

    monkeypatch.setattr(files, "check", planted(files.check, "if p:", "if not (p):"))
    assert status("library.emit_shapes") == "failed"


def test_plain_matrix_rows_of_the_wrong_length(monkeypatch):
    # render:97 -- the mpmath flavour's rows cut at shape[0] entries (a 2 x 3 matrix read as rows of 2)
    from symbt.codegen.user import render

    monkeypatch.setattr(render, "_mp_function", planted(render._mp_function, "n = e.shape[1]", "n = e.shape[0]"))
    assert status("library.emit_shapes") == "failed"


@pytest.mark.skipif(not HAS_CC, reason="no C compiler (cc, gcc or clang) on PATH")
def test_c_sgn_helper_dropped_where_called(monkeypatch):
    # render:262 -- the sgn helper dropped exactly when the plain functions call it
    from symbt.codegen.user import render

    monkeypatch.setattr(render, "c_source", planted(render.c_source, 'if "sgn(" not in "\\n".join(lines[5:]):',
                                                    'if not ("sgn(" not in "\\n".join(lines[5:])):'))
    assert status("library.emit_c_sign") == "failed"


# --------------------------------------------------------------------------- library.printer_precedence

def test_printer_parentheses_at_equal_precedence(monkeypatch):
    # printer:124 -- no parentheses around an operand of the same precedence: x/(y*z) printed x/y*z
    from symbt.codegen.printer import ExprPrinter

    monkeypatch.setattr(ExprPrinter, "_wrap", planted(ExprPrinter._wrap, "p > prec", "p >= prec"))
    assert status("library.printer_precedence") == "failed"


# --------------------------------------------------------------------------- library.compare_refusal

def test_compare_refused_point_counted_at_the_bound(monkeypatch):
    # check:338 -- a point both sides refuse scored 1 (at the bound) instead of 0
    from symbt.codegen.user import check

    monkeypatch.setattr(check, "compare", planted(check.compare, "return mp.mpf(0)", "return mp.mpf(1)"))
    assert status("library.compare_refusal") == "failed"


def test_compare_typed_flavours_called_the_other_way(monkeypatch):
    # check:178 -- the mpmath flavour called like the numpy one, outside MP_DPS (at the caller's 60 digits)
    from symbt.codegen.user import check

    monkeypatch.setattr(check, "_typed_evaluator", planted(
        check._typed_evaluator, 'if flavour == "numpy":\n                res = f(',
        'if not (flavour == "numpy"):\n                res = f('))
    assert status("library.compare_refusal") == "failed"


# --------------------------------------------------------------------------- library.sources_real

def test_sources_named_definitions_not_real(monkeypatch, fresh_sources):
    # derive:432 -- the named definitions of phi_grad's source declared without real=True
    derive = fresh_sources
    monkeypatch.setattr(derive, "_build", planted(derive._build, "sym = sp.Symbol(name, real=True)",
                                                  "sym = sp.Symbol(name, real=False)"))
    assert status("library.sources_real") == "failed"


# --------------------------------------------------------------------------- killed by tests

def test_opposite_traces_decided_before_the_slopes(monkeypatch, fresh_sources):
    # derive:470 -- the opposite-traces guard at stage 1: the mpmath closed form would compute every slope
    # before refusing (the same NoRealMapError: it is still the first stage-1 guard; only the work differs)
    from symbt.codegen.user.render_typed import mpmath_function
    from symbt.codegen.zullo import declaration

    derive = fresh_sources
    label = "Etilde_j for some j (tr L(lam1), tr L(lam2) of opposite signs)"
    spec = next(s for s in derive.specs(2) if s.name == "bt_step")
    assert [g.stage for g in spec.guards if g.label == label] == [0]
    text = mpmath_function(declaration(spec, 2))
    first_slope = text.index("        t0 = ")
    assert text.index(f"_mp_guard('positivity', {label!r}") < first_slope
    derive.specs.cache_clear()
    monkeypatch.setattr(derive, "_build", planted(
        derive._build, 'extra: tuple[Guard, ...] = (Guard("positivity", gap, sp.sign(t_1) * sp.sign(t_2), 0),)',
        'extra: tuple[Guard, ...] = (Guard("positivity", gap, sp.sign(t_1) * sp.sign(t_2), 1),)'))
    spec = next(s for s in derive.specs(2) if s.name == "bt_step")
    assert [g.stage for g in spec.guards if g.label == label] == [1]


def test_long_sum_chunks_keep_their_terms():
    # printing:86 -- the chunks of a sum of more than LONG_SUM terms re-evaluated (like terms combined): the
    # chunked text must hold the terms as given, as the unchunked printing of a shorter sum does
    from symbt.codegen.printer import ExprPrinter
    from symbt.codegen.user import printing

    x, y = sp.symbols("x y", real=True)
    terms = [x, y] * 75 + [sp.Integer(1)]
    s = sp.Add(*terms, evaluate=False)
    names = {x: "x", y: "y"}
    for flavour in ("numpy", "mpmath"):
        text = printing.UserPrinter(flavour, names).text(s)
        flat = text.replace("(", "").replace(")", "")
        assert flat == ExprPrinter(flavour, names).text(s)          # the same terms, one association
        assert flat.count("x") == 75 and flat.count("y") == 75
    copy = mutated("symbt.codegen.user.printing",
                   "chunks = [super(UserPrinter, self)._add(sp.Add(*terms[k:k + LONG_SUM], evaluate=False))",
                   "chunks = [super(UserPrinter, self)._add(sp.Add(*terms[k:k + LONG_SUM], evaluate=True))")
    flat = copy.UserPrinter("numpy", names).text(s).replace("(", "").replace(")", "")
    assert flat.count("x") != 75        # the mutant combines like terms: 50*x + 25*x


# --------------------------------------------------------------------------- equivalent (mutants-equivalent.toml)

def test_disc_scaled_evaluated_mul_equivalent():
    # kernels:91 -- Mul(t - two, t + two, evaluate=True): the same two factors in the other order; a correctly
    # rounded product is commutative (IEEE 754 float64, mpmath's mpf_mul), so every printed flavour computes the
    # same bits
    from symbt.codegen import kernels
    from symbt.codegen.printer import ExprPrinter

    copy = mutated("symbt.codegen.kernels", 'out["disc_scaled"] = sp.Mul(t - two, t + two, evaluate=False)',
                   'out["disc_scaled"] = sp.Mul(t - two, t + two, evaluate=True)')
    want, got = kernels.kernels(), copy.kernels()
    assert want.keys() == got.keys()
    assert [k for k in want if not (got[k] == want[k] and sp.srepr(got[k]) == sp.srepr(want[k]))] == ["disc_scaled"]
    a, b = want["disc_scaled"], got["disc_scaled"]
    assert a.is_Mul and b.is_Mul and len(a.args) == 2 and set(a.args) == set(b.args)
    names = {s: str(s) for s in a.free_symbols}
    for flavour in ("numpy", "mpmath", "ops", "c"):
        ta, tb = ExprPrinter(flavour, names).text(a), ExprPrinter(flavour, names).text(b)
        fa, fb = ta.split("*"), tb.split("*")
        assert len(fa) == len(fb) == 2 and fa == fb[::-1], (ta, tb)
    rng = np.random.default_rng(5)
    for t_, two in rng.normal(size=(200, 2)) * np.array([3.0, 1.0]):
        assert (t_ - two) * (t_ + two) == (t_ + two) * (t_ - two)
        with mp.workdps(40):
            T, W = mp.mpf(t_) / 3, mp.mpf(two) / 7
            assert (T - W) * (T + W) == (T + W) * (T - W)


def test_contracted_unit_coefficient_equivalent():
    # emit_c_fill:69 -- `call if coeff != 1 else "1.0*call"`: every term of the kernels the C template contracts
    # (@@cdot:...@@) has coefficient 1, so the mutant only prefixes "1.0*" -- exact for every double (IEEE 754:
    # x * 1 = x, signed zeros, infinities and NaN included)
    import re

    from symbt.codegen import emit_c_fill
    from symbt.codegen.c_template import LOOP
    from symbt.codegen.kernels import kernels

    used = set(re.findall(r"@@cdot:(\w+)@@", LOOP))
    assert used
    for name in used:
        assert {t.as_coeff_mul()[0] for t in sp.Add.make_args(sp.expand(kernels()[name]))} == {1}
    copy = mutated("symbt.codegen.emit_c_fill", 'out.append(call if coeff == 1 else f"{int(coeff)}.0*{call}")',
                   'out.append(call if coeff != 1 else f"{int(coeff)}.0*{call}")')
    for N in (4, 5):
        want, got = emit_c_fill.loop_c_parts(N), copy.loop_c_parts(N)
        mark = f"1.0*toda{N}_cdot("
        texts_w, texts_g = [want[0], *want[1].values()], [got[0], *got[1].values()]
        assert want[1].keys() == got[1].keys() and not any(mark in t for t in texts_w)
        n_terms = sum(len(sp.Add.make_args(sp.expand(kernels()[name]))) for name in re.findall(r"@@cdot:(\w+)@@", LOOP))
        assert sum(t.count(mark) for t in texts_g) == n_terms       # one "1.0*" per term of each contraction
        assert [t.replace(mark, f"toda{N}_cdot(") for t in texts_g] == texts_w
    vals = np.array([0.0, -0.0, 1e-310, -2.5, 1.7976931348623157e308, np.inf, -np.inf, np.nan])
    assert np.array_equal((1.0 * vals).view(np.uint64), vals.view(np.uint64))


def test_illcond_site_guard_stage_never_read_equivalent():
    # transport:136 -- the slope guards' stage 1 -> 0: a guard's stage reaches the emitted code only as
    # `early` (zullo.declaration), and `early` is read only by the mpmath flavour's renderer, which skips
    # every "illcond" guard (float64's own); numpy and C ignore it.  Proof in two parts: where the attributes
    # are read (the syntax trees of symbt), and the rendered mpmath text with the flag either way.
    from symbt.codegen.user.declare import emit
    from symbt.codegen.user.render_typed import mpmath_function, numpy_function
    from symbt.codegen.user.typed import Guard

    reads: dict[str, list[str]] = {"early": [], "stage": []}
    for path in sorted(PACKAGE.rglob("*.py")):
        if "claims" in path.parts or "generated" in path.parts:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Attribute) and node.attr in reads and isinstance(node.ctx, ast.Load):
                reads[node.attr].append(f"{path.relative_to(PACKAGE).as_posix()}:{node.lineno}")
    files = {k: sorted({r.split(":")[0] for r in v}) for k, v in reads.items()}
    assert files == {"early": ["codegen/user/declare.py", "codegen/user/render_typed.py"],
                     "stage": ["codegen/derive.py", "codegen/zullo.py"]}, reads
    for r in reads["early"]:
        f, line = r.split(":")
        text = (PACKAGE / f).read_text(encoding="utf-8").splitlines()[int(line) - 1]
        if f.endswith("render_typed.py"):
            assert 'g.condition != "illcond"' in text, text       # the read skips illcond guards
        else:
            assert "Guard(g.condition, str(g.label), gx, bool(g.early))" in text, text   # a copy
    x, y = sp.symbols("x y", real=True)
    texts = []
    for early in (False, True):
        e = emit("f", {"r": sp.sqrt(x) * y}, args=(("v", (x, y)),), module="m", register=False,
                 guards=[Guard("domain", "x", x, early=True), Guard("illcond", "site", y - x, early=early)])
        texts.append((mpmath_function(e), numpy_function(e)))
    assert texts[0] == texts[1]


CLOSED_GAP = [   # (the line, mutated): symbt.codegen.closed_gap:49 and :58 (seed 5)
    ("    return sp.StrictLessThan(_abs(A - D) + 2 * (_abs(B) + _abs(C)), _abs(A + D) + two, evaluate=False)",
     "    return sp.StrictLessThan(_abs(A - D) + 2 * (_abs(B) + _abs(C)), _abs(A + D) + two, evaluate=True)"),
    ("                         (sp.Mul(t - 2, t + 2, evaluate=False), True), evaluate=False)",
     "                         (sp.Mul(t - 2, t + 2, evaluate=True), True), evaluate=False)"),
]


@pytest.mark.parametrize("before, after", CLOSED_GAP, ids=["closed_gap:49", "closed_gap:58"])
def test_closed_gap_evaluated_is_equivalent(monkeypatch, before, after):
    # evaluate=True of the closed-gap test |A - D| + 2(|B| + |C|) < |A + D| + two (SymPy cannot decide it on the
    # symbolic entries, so it stays the same relation) and of the product (t - 2)(t + 2) (SymPy orders the same two
    # factors the same way, and does not expand): the functions' only callers -- derive's closed forms (through
    # trace_discriminant) and the kernels of the transfer-matrix form and the C target (near_closed_gap) -- build
    # the same expressions, so every emitted module is the same text
    from symbt.codegen import closed_gap, derive, kernels, zullo

    def built() -> tuple:
        for f in (derive.specs, derive.sources, derive.interface, derive._trace_ring, kernels.kernels,
                  zullo.declarations):
            f.cache_clear()
        return (zullo.module_text(2), zullo.module_text(3),
                {k: sp.srepr(v) for k, v in kernels.kernels().items()})

    want = built()
    copy = mutated("symbt.codegen.closed_gap", before, after)
    try:
        monkeypatch.setattr(derive, "trace_discriminant", copy.trace_discriminant)
        monkeypatch.setattr(closed_gap, "near_closed_gap", copy.near_closed_gap)   # kernels imports it at call time
        got = built()
        # the control: a wrong discriminant and a wrong test change the texts (the comparison sees both)
        monkeypatch.setattr(derive, "trace_discriminant", lambda M: sp.Piecewise((M[0, 0] ** 2 + 7, True)))
        monkeypatch.setattr(closed_gap, "near_closed_gap", lambda A, B, C, D, two=2: sp.StrictLessThan(A, two))
        wrong = built()
    finally:
        monkeypatch.undo()
        built()
    assert got == want
    assert all(w != g for w, g in zip(wrong, want))


def test_transport_extra_forward_slope_is_equivalent():
    # transport:39 (seed 8), `for j in range(N - 0)`: the forward transport builds one more slope, fwd[N], which
    # nothing reads (the sites returned are fwd[1] ... fwd[N - 1]): the same expressions
    from symbt.codegen import transport
    from symbt.symbolic.toda import toda_model

    bad = planted(transport.transported, "for j in range(N - 1):\n        fwd.append", "for j in range(N - 0):\n"
                                                                                     "        fwd.append")
    for N in (2, 3):
        m = toda_model(N)
        u0, fw = sp.Symbol("u0"), sp.Symbol("fw")
        assert [sp.srepr(e) for e in bad(m, m.lam, u0, fw)] == [sp.srepr(e) for e in transport.transported(m, m.lam, u0,
                                                                                                           fw)]


def _illcond_guard_texts(module) -> list[str]:
    """The srepr of every trace and site guard of ``module.illcond_guards`` at N = 3 (symbols for the traces,
    slopes and denominators)."""
    from symbt.symbolic.toda import toda_model

    m = toda_model(3)
    t = sp.symbols("t1 t2", real=True)
    u, w, d = (list(sp.symbols(f"{c}1:4", real=True)) for c in "uwd")
    ill_t, ill_s = module.illcond_guards(m, lambda c, label, e, stage: e, t, u, w, d, lambda x: (x - 2) * (x + 2))
    return [sp.srepr(g) for g in ill_t + ill_s]


def test_illcond_max_evaluated_is_equivalent():
    # transport:129 (seed 9), `sp.Max(kta[0], kta[1], evaluate=True)`: SymPy cannot order the two symbolic
    # condition estimates, so it keeps the same Max of the same two arguments: every guard is the same expression
    # (and a wrong Max -- kta[0] twice -- is not: the comparison sees kt)
    from planting import mutated

    from symbt.codegen import transport

    guards = _illcond_guard_texts
    before = "    kt = sp.Max(kta[0], kta[1], evaluate=False)"
    assert guards(mutated("symbt.codegen.transport", before, before.replace("False", "True"))) == guards(transport)
    wrong = transport.__dict__.copy()
    exec(compile(Path(transport.__file__).read_text().replace("sp.Max(kta[0], kta[1], evaluate=False)",
                                                               "sp.Max(kta[0], kta[0], evaluate=False)"),
                 transport.__file__, "exec"), wrong)
    assert guards(type("M", (), {"illcond_guards": staticmethod(wrong["illcond_guards"])})) != guards(transport)


def test_illcond_piecewise_evaluated_is_equivalent():
    # transport:118 (seed 26), `ill`'s `sp.Piecewise(..., evaluate=False)` -> `evaluate=True`: the one condition is
    # an unevaluated `big > small` of symbolic estimates, which Piecewise cannot decide, so it keeps both pieces:
    # every guard is the same expression (and with a piece's value changed, another mutant, it is not: the
    # comparison sees `ill`)
    from planting import mutated

    from symbt.codegen import transport

    guards = _illcond_guard_texts
    before = "                            evaluate=False)"
    assert guards(mutated("symbt.codegen.transport", before, before.replace("False", "True"))) == guards(transport)
    line = "        return sp.Piecewise((-1, sp.StrictGreaterThan(big, small, evaluate=False)), (1, True),"
    assert guards(mutated("symbt.codegen.transport", line, line.replace("(1, True)", "(0, True)"))) != \
        guards(transport)
