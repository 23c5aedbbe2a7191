"""Seeds 12 and 13's survivors (docs/mutation.md, "Seed 12", "Seed 13"): planted bugs that the new facts now see, and
the proofs of the mutants marked equivalent.  Unpatched, every claim verifies."""
from __future__ import annotations

from dataclasses import replace

import pytest
from planting import claim_fails as fails
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["paths.dq_edge.n3", "paths.side_by_side.n3", "library.guard_far_trace", "library.emit_typed",
          "library.zullo_registry", "paths.jacobian_dual.n3", "library.codegen_check", "paths.scaled_trace.n4",
          "paths.scaled_trace.n5", "paths.band_edge.n3", "paths.existence_iv.n3", "shipped.orbit.n3",
          "library.addition", "library.state_ranges", "paths.complex.n3", "paths.transfer_gradient.n4",
          "paths.transfer_gradient.n5", "paths.mixed_block.n3", "shipped.loop_integrand.n5", "checker.screen_relations"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


def test_rows_range_at_the_documented_largest_distance(monkeypatch):
    # seed 12's rows:215 (`dq <= MAX_DQ_FLOAT64` -> `<`): a neighbour distance of exactly 700 refused by the numpy route
    from symbt.numeric.float64 import orbit, rows, step

    mutant = planted(rows.float_rows_step, "far = ~(dq <= MAX_DQ_FLOAT64)", "far = ~(dq < MAX_DQ_FLOAT64)")
    for module in (rows, step, orbit):
        monkeypatch.setattr(module, "float_rows_step", mutant)
    assert fails("paths.dq_edge.n3")


def test_side_by_side_range_test_of_the_absolute_half(monkeypatch):
    # seed 12's condition:482 (`for h in (0, 1)` -> `(0, 0)`): the absolute product's range never tested side by side
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_both_in_range", planted(condition._both_in_range, "for h in (0, 1):",
                                                             "for h in (0, 0):"))
    assert fails("paths.side_by_side.n3")


def test_side_by_side_mixed_rows_are_exercised(monkeypatch):
    # control of the above: with the whole-batch test on the signed half alone the absolute rows go unrenormalised
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_both_in_range", lambda X, R: True)
    assert fails("paths.side_by_side.n3")


def test_guard_from_both_traces(monkeypatch):
    # seed 12's literal:276 (`t2 = literal_trace(l0 - m)` -> `l0 + m`): the guard sized from lam1's trace alone
    from symbt.reference import literal

    monkeypatch.setattr(literal, "reference_step", planted(
        literal.reference_step, "t2 = literal_trace(l0 - m, P, Q)", "t2 = literal_trace(l0 + m, P, Q)"))
    assert fails("library.guard_far_trace")


def test_numerator_one_or_one_point_zero_is_equivalent(monkeypatch, tmp_path):
    # seed 12's printer:153 (`"1.0" if flavour == "c" else "1"` swapped): a quotient with no numerator factor prints
    # `1/d` in C and `1.0/d` elsewhere.  Every flavour converts the 1 exactly to the denominator's type before one
    # correctly rounded division: C prints every number as a double literal and reads every argument as a double
    # (the typed sign `b` as `b_value`), and Python's 1/x and 1.0/x agree on float, numpy float64, mpf and mpc.
    # Checked on the typed control declaration, whose output v3 = 1/(2 b) is such a quotient: the emitted texts differ
    # only by that numerator, and every flavour's values are the same bits at the claim's points.
    import mpmath as mp

    from symbt.claims import emitted_user as eu
    from symbt.codegen import printer
    from symbt.codegen.user.check import compiler, load_python
    from symbt.codegen.user.files import generate

    cc = compiler()
    texts, values, keep = [], [], []
    for version in ("original", "mutant"):
        if version == "mutant":
            monkeypatch.setattr(printer.ExprPrinter, "_mul", planted(
                printer.ExprPrinter._mul, '("1.0" if self.flavour == "c" else "1")',
                '("1.0" if not (self.flavour == "c") else "1")'))
        out = tmp_path / version
        out.mkdir()
        e = eu.declaration()
        generate([e], out, out)
        if cc is not None:
            generate([e], out, out, target="c")
        texts.append({x.suffix: x.read_text() for x in out.iterdir() if x.suffix in (".py", ".c")})
        mod = load_python(out / f"{eu.MODULE}.py")
        call = eu._c_probe(out / f"{eu.MODULE}.c", e, keep) if cc is not None else None
        got = []
        for x, y, s, b in eu.POINTS:
            v, w = mod.probe([x, y], s, b)
            with mp.workdps(50):
                vm, wm = mod.probe_mp([x, y], s, b)
            got.append(([float(t) for t in v], float(w), [repr(t) for t in vm], repr(wm),
                        call(x, y, s, b) if call is not None else None))
        values.append(got)
    for t in keep:
        t.cleanup()
    assert values[0] == values[1]
    changed = 0
    for suffix, text in texts[0].items():
        lines = [(a, b) for a, b in zip(text.splitlines(), texts[1][suffix].splitlines())
                 if a != b and "content-sha256" not in a]      # the header's hash of the text itself
        assert all(a.replace("1.0/", "1/") == b.replace("1.0/", "1/") for a, b in lines), lines
        changed += len(lines)
    assert changed     # the quotient is printed: the mutant's text differs


def test_short_coefficient_lists_mean_zeros():
    # seed 12's taylor:151 (the padding of c to N + 1 entries) removed as dead code: the polynomial of G reads c_k
    # only for k < len(c) (taylor._poly_G), so missing trailing entries are 0 without it -- the flow of a short list
    # is the flow of the padded one, bit for bit, and a nonzero c_2 changes it
    import mpmath as mp

    from symbt.reference.taylor import hamiltonian_flow

    p, q = [mp.mpf("0.3"), mp.mpf("-0.2"), mp.mpf("0.1")], [mp.mpf(0), mp.mpf("0.5"), mp.mpf("0.2")]
    with mp.workdps(20):
        short = hamiltonian_flow(p, q, [0, mp.mpf("0.7")], mp.mpf("0.3"))
        padded = hamiltonian_flow(p, q, [0, mp.mpf("0.7"), 0, 0], mp.mpf("0.3"))
        other = hamiltonian_flow(p, q, [0, mp.mpf("0.7"), mp.mpf("0.1")], mp.mpf("0.3"))
    assert list(short[0]) + list(short[1]) == list(padded[0]) + list(padded[1])
    assert list(short[0]) + list(short[1]) != list(other[0]) + list(other[1])


def test_loop_declarations_leave_the_users_registry(monkeypatch):
    # seed 12's zullo:106 (`register=False` -> `True` in loop_declarations): toda4's loop functions recorded among
    # the user's declarations (which `symbt codegen` would then write as the user's own)
    from symbt.codegen import zullo
    from symbt.codegen.user import declare

    monkeypatch.setattr(declare, "EMISSIONS", {})       # the mutant's entries go into a dict thrown away after
    monkeypatch.setattr(zullo, "loop_declarations", planted(
        zullo.loop_declarations, "equation=s.equation, register=False,", "equation=s.equation, register=True,"))
    assert fails("library.zullo_registry")


def test_dual_positivity_reads_the_value_ball(monkeypatch):
    # seed 12's lohner_checks:142 (`x.v if isinstance(x, Dual) else x` negated): a Dual handed to the Arb test,
    # which cannot order it where the value is not positive (a spectral parameter in a band)
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks._DualContext, "positive", planted(
        lohner_checks._DualContext.positive, "x.v if isinstance(x, Dual) else x",
        "x.v if not (isinstance(x, Dual)) else x"))
    assert fails("paths.jacobian_dual.n3")


@pytest.mark.parametrize("old, new", [
    ('if argv[:1] == ["--"]:', 'if argv[:0] == ["--"]:'),               # seed 12's codegen.cli:81
    ("return 1 if problems else 0", "return 0 if problems else 0"),    # seed 12's codegen.cli:125
    ("return 1 if problems else 0", "return 1 if problems else 1"),
])
def test_codegen_check_exit_status(monkeypatch, old, new):
    from symbt.codegen import cli

    monkeypatch.setattr(cli, "main", planted(cli.main, old, new))
    assert fails("library.codegen_check")


@pytest.mark.parametrize("old, new", [
    # seed 13's coefficients:132: the float64 product's B recurrence (read only from the fourth site on)
    ("                A, B, C, D = a * A - C, a * B - D, r[j] * A, r[j] * B",
     "                A, B, C, D = a * A - C, a * B + D, r[j] * A, r[j] * B"),
    # the same in the mpmath form
    ("            A, B, C, D = a * A - C, a * B - D, r[j] * A, r[j] * B\n        return A + D, 0",
     "            A, B, C, D = a * A - C, a * B + D, r[j] * A, r[j] * B\n        return A + D, 0"),
])
@pytest.mark.parametrize("cid", ["paths.scaled_trace.n4", "paths.scaled_trace.n5"])
def test_scaled_trace_at_four_sites_and_more(monkeypatch, old, new, cid):
    from symbt.numeric.flow import coefficients

    monkeypatch.setattr(coefficients, "scaled_trace", planted(coefficients.scaled_trace, old, new))
    assert fails(cid)


def test_escalation_decides_existence_on_its_own_row(monkeypatch):
    # seed 13's rows:102 (`qa[k]` -> `qa[k + 1]`): the interval verdict of a row taken with the next row's q
    from symbt.numeric.float64 import orbit, rows

    mutant = planted(rows.escalate_rows, "decide_existence(pa[k], qa[k], l0,", "decide_existence(pa[k], qa[k + 1], l0,")
    for module in (rows, orbit):
        monkeypatch.setattr(module, "escalate_rows", mutant)
    assert fails("paths.existence_iv.n3", crash=True)


def test_interval_verdict_at_an_exact_band_edge(monkeypatch):
    # seed 13's existence:73 (`OK if s > 0` -> `s >= 0`): |t| = 2 exactly counted as a gap
    from symbt.numeric.float64 import existence

    monkeypatch.setattr(existence, "_at", planted(existence._at, "OK if s > 0 else code", "OK if s >= 0 else code"))
    assert fails("paths.band_edge.n3")


def test_printed_addform_residual_is_a_modulus(monkeypatch):
    # seed 13's elliptic:383 (the abs dropped): a signed residual, negative for one of the two moves of P~
    from symbt.reference import elliptic

    monkeypatch.setattr(elliptic, "printed_addform_residual", planted(
        elliptic.printed_addform_residual, "return abs(F_principal(Pt, k) - F_principal(P, k) - F_principal(lm, k) "
        "+ F_principal(lp, k))", "return F_principal(Pt, k) - F_principal(P, k) - F_principal(lm, k) + "
        "F_principal(lp, k)"))
    assert fails("library.addition")


def test_legendre_memo_size_is_equivalent():
    # seed 13's elliptic:136 (`lru_cache(maxsize=1 << 16)` -> `maxsize=0`): no value is kept, every call computes.
    # _F_memo is pure -- z R_F(1 - z^2, 1 - m z^2, 1) at the precision passed in, of immutable mpmath numbers -- so a
    # computed value equals the memoised one bit for bit (real and complex z, both precisions), and the cache is
    # read by nothing else
    import ast
    import inspect

    import mpmath as mp

    from symbt.reference import elliptic

    fresh = elliptic._F_memo.__wrapped__
    for prec in (70, 140):
        for z in (mp.mpf("0.3"), mp.mpf("-0.97"), mp.mpc("0.4", "0.2"), mp.mpf(1)):
            m = mp.mpf("0.6")
            assert elliptic._F_memo(z, m, prec) == fresh(z, m, prec) == elliptic._F_memo(z, m, prec)
    tree = ast.parse(inspect.getsource(elliptic))
    reads = [n for n in ast.walk(tree) if isinstance(n, ast.Attribute) and n.attr in ("cache_info", "cache_clear",
                                                                                     "cache_parameters")]
    assert not reads


def test_user_numerator_one_or_one_point_zero_is_equivalent(monkeypatch, tmp_path):
    # seed 13's codegen.user.printing:101 (the same swap in the user printer's negative rational powers): x**(-1/3)
    # printed `1/x**(1/3)` in C and `1.0/...` elsewhere -- the same values, as for printer:153
    import ctypes

    import mpmath as mp
    import sympy as sp

    from symbt.codegen.user import printing
    from symbt.codegen.user.check import compiler, load_c, load_python
    from symbt.codegen.user.declare import emit
    from symbt.codegen.user.files import generate
    from symbt.codegen.user.render import c_name

    x = sp.Symbol("x", positive=True)
    module = "symbt_root_control"
    cc = compiler()
    texts, values, keep = [], [], []
    for version in ("original", "mutant"):
        if version == "mutant":
            monkeypatch.setattr(printing.UserPrinter, "_pow", planted(
                printing.UserPrinter._pow, 'one = "1.0" if self.flavour == "c" else "1"',
                'one = "1.0" if not (self.flavour == "c") else "1"'))
        out = tmp_path / version
        out.mkdir()
        e = emit("root", x ** sp.Rational(-1, 3) + x ** sp.Rational(-5, 7), args=(x,), module=module, register=False)
        generate([e], out, out)
        if cc is not None:
            generate([e], out, out, target="c")
        texts.append({f.suffix: f.read_text() for f in out.iterdir() if f.suffix in (".py", ".c")})
        mod = load_python(out / f"{module}.py")
        got = [float(mod.root(v)) for v in (0.3, 2.0, 1e-5, 7e10)]
        with mp.workdps(40):
            got += [repr(mod.root_mp(mp.mpf(v))) for v in ("0.3", "2", "1e-5")]
        if cc is not None:
            fn = getattr(load_c(out / f"{module}.c", keep), c_name(module, e))
            fn.restype, fn.argtypes = ctypes.c_int, [ctypes.POINTER(ctypes.c_double)] * 2
            for v in (0.3, 2.0, 1e-5, 7e10):
                res = (ctypes.c_double * 1)()
                got.append((fn((ctypes.c_double * 1)(v), res), res[0]))
        values.append(got)
    for t in keep:
        t.cleanup()
    assert values[0] == values[1]
    changed = 0
    for suffix, text in texts[0].items():
        lines = [(a, b) for a, b in zip(text.splitlines(), texts[1][suffix].splitlines())
                 if a != b and "content-sha256" not in a]
        assert all(a.replace("1.0/", "1/") == b.replace("1.0/", "1/") for a, b in lines), lines
        changed += len(lines)
    assert changed


def test_mpmath_orbit_stores_each_step_once(monkeypatch):
    # seed 13's runners:259 (`range(1, n + 1)` -> `range(0, n + 1)`): one step more, every stored row after step 0
    # shifted by one and an extra row -- row n right by chance, the count wrong
    from symbt.numeric import backends
    from symbt.numeric.multiprec import runners

    mutant = planted(runners.mpmath_orbit, "for i in range(1, pr.n + 1):", "for i in range(0, pr.n + 1):")
    assert backends.BACKENDS["mpmath"].orbit is runners.mpmath_orbit        # the table holds the function itself
    monkeypatch.setattr(runners, "mpmath_orbit", mutant)
    monkeypatch.setitem(backends.BACKENDS, "mpmath", replace(backends.BACKENDS["mpmath"], orbit=mutant))
    assert fails("shipped.orbit.n3")


def test_c_target_body_is_the_form_its_header_names(monkeypatch):
    # seed 13's emit_c:53 (`form == "closed"` -> `!=`): N = 3 rendered as the loop, N = 5 as the closed form -- each
    # accurate, the size policy inverted (the header still names form_of(N))
    from symbt.claims import shipped_emitted
    from symbt.codegen import emit_c
    from symbt.codegen.user.check import compiler

    if compiler() is None:
        pytest.skip("no C compiler on PATH: shipped.c is skipped")
    monkeypatch.setattr(emit_c, "c_files", planted(emit_c.c_files, 'if form == "closed":', 'if form != "closed":'))
    for f in (shipped_emitted.c_texts, shipped_emitted.c_step):
        f.cache_clear()
    try:
        assert fails("shipped.c.n3")
    finally:
        for f in (shipped_emitted.c_texts, shipped_emitted.c_step):
            f.cache_clear()


@pytest.mark.parametrize("old, new", [
    ("th1 = rng.uniform(-1, 1)", "th1 = rng.uniform(-0, 1)"),         # seed 13's elliptic:406
    ("I1, I2 = rng.uniform(-2, 2), rng.uniform(2.3, 9)", "I1, I2 = rng.uniform(-2, 2), rng.uniform(2.3, 5)"),
])
def test_sampled_states_fill_their_ranges(monkeypatch, old, new):
    from symbt.reference import elliptic

    monkeypatch.setattr(elliptic, "sample_state", planted(elliptic.sample_state, old, new))
    assert fails("library.state_ranges")


def test_codegen_check_project_option(monkeypatch):
    # seed 13's codegen.cli:99 (`if args.project is not None` negated): --project ignored, the checkout searched from
    # the working directory instead
    from symbt.codegen import cli

    monkeypatch.setattr(cli, "main", planted(cli.main, "        if args.project is not None:\n",
                                             "        if not (args.project is not None):\n"))
    assert fails("library.codegen_check")


def test_inconclusive_screen_reports_its_least_trustworthy_point(monkeypatch):
    # seed 13's screen:413 (`max(c.residual, c.error)` -> `min(...)` as the key): the point with the largest residual
    # reported, not the one with the largest error
    from symbt.proof import screen as screen_module

    monkeypatch.setattr(screen_module, "screen", planted(
        screen_module.screen, "worst = max(undecided, key=lambda c: max(c.residual, c.error))",
        "worst = max(undecided, key=lambda c: min(c.residual, c.error))"))
    assert fails("checker.screen_arithmetic")


def test_complex_arb_transport_direction(monkeypatch):
    # seed 13's arb:188 (ACB.half_plane's `>= 0` -> `<= 0`): the slopes transported against the dominant direction;
    # harmless at moderate traces, about 5 digits lost at |tr| ~ 1e9 (paths.complex's outer-gap state)
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import arb

    cls = type(arb.ACB)
    monkeypatch.setattr(cls, "half_plane", planted(cls.half_plane, "return bool(self.re_dot(a, g).mid() >= 0)",
                                                   "return bool(self.re_dot(a, g).mid() <= 0)"))
    assert fails("paths.complex.n3")


@pytest.mark.parametrize("old, new", [
    # seed 14's field:71: the prefix product's r-row with the next site's r (read only from the fourth site on)
    ("a[j] * f01 - inv_s * f11, r[j] * f00, r[j] * f01", "a[j] * f01 - inv_s * f11, r[j + 1] * f00, r[j] * f01"),
    ("b10 * a[j] + b11 * r[j], -inv_s * b10)", "b10 * a[j] + b11 * r[j], inv_s * b10)"),
])
@pytest.mark.parametrize("cid", ["paths.transfer_gradient.n4", "paths.transfer_gradient.n5"])
def test_transfer_gradient_at_four_sites_and_more(monkeypatch, old, new, cid):
    from symbt.numeric.flow import field

    monkeypatch.setattr(field, "transfer_gradient", planted(field.transfer_gradient, old, new))
    assert fails(cid)


def test_typed_docstrings_given_or_generated(monkeypatch):
    # seed 14's render_typed:78 (`if given is not None` negated): a given docstring replaced by the generated one,
    # and none at all where none was given
    from symbt.codegen.user import render_typed

    mutant = planted(render_typed.typed_doc, "    if given is not None:\n", "    if not (given is not None):\n")
    monkeypatch.setattr(render_typed, "typed_doc", mutant)
    assert fails("library.emit_typed")


def test_block_rescale_counter_start_is_equivalent(monkeypatch):
    # seed 14's kernels_block:78 (`big = 0` -> `big = 1` at each site): `big` is read only by `if big > 0:`, whose
    # loop re-tests every member (`Ab[0, k] > _BIG or Ab[1, k] > _BIG`) before it shrinks one -- the mutant runs that
    # loop at every site, shrinking exactly the same members.  Checked: a block of a moderate member and one whose
    # absolute product passes _BIG (2**400), the same bits either way; control: without the shrink the bits differ
    import inspect

    import numpy as np

    from symbt.numeric.float64 import kernels_block
    from symbt.numeric.float64.kernels import ANCHOR

    src = kernels_block._slopes
    uses = [line.split("#")[0].strip() for line in inspect.getsource(src).splitlines() if "big" in line]
    assert uses == ["big = 0", "big += 1 if (Ab[0, k] > _BIG or Ab[1, k] > _BIG) else 0", "if big > 0:"]
    P0 = np.array([[0.5, -0.25, 0.125, 1.0, -1.5], [0.5, -0.25, 0.125, 1.0, -1.5]])
    Q0 = np.array([[0.0, 0.5, -0.25, 0.75, 0.1]] * 2)
    lam0, mu = np.array([30.0, 1e100]), np.array([1.0, 1e98])

    def run() -> tuple:
        st = np.zeros(2, np.int64)
        outP, outQ = np.empty((2, 2, 5)), np.empty((2, 2, 5))
        kernels_block.run_block(P0, Q0, lam0 + mu, lam0 - mu, 2 * mu, 1, 1, 1, ANCHOR, outP, outQ, st, 0, 2)
        return outP.tobytes(), outQ.tobytes(), st.tolist()

    original = run()
    assert original[2] == [0, 0]
    monkeypatch.setattr(kernels_block, "_slopes", planted(src, "        big = 0\n", "        big = 1\n"))
    assert run() == original
    monkeypatch.setattr(kernels_block, "_slopes", planted(src, "        if big > 0:", "        if big < 0:"))
    with np.errstate(over="ignore", invalid="ignore"):      # unshrunk, the big member's products overflow
        assert run() != original


def test_single_denominator_in_parentheses_is_equivalent():
    # seed 14's printer:156 (`len(den) == 1` -> `== 0`): a single denominator factor printed in parentheses too,
    # `x/(y**2)` for `x/y**2` -- the wrapped factor is already an operand of `/` (its precedence is at least _MUL's), so
    # the parentheses change no parse: the same value in every flavour
    import numpy as np
    import sympy as sp

    from symbt.codegen import printer

    x, y = sp.symbols("x y", positive=True)
    mutant = planted(printer.ExprPrinter._mul, "    if len(den) == 1:\n", "    if len(den) == 0:\n")
    exprs = [x / y, x / y ** 2, x / sp.exp(y), x / (y + 1), 3 * x / y ** 3, x * y / sp.sqrt(y), x ** 2 / (x - y)]
    evaluated = 0
    for flavour in ("numpy", "mpmath", "ops", "c"):
        pr = printer.ExprPrinter(flavour, {x: "x", y: "y"})
        for e in exprs:
            text, _ = pr._mul(e)
            mtext, _ = mutant(pr, e)
            num, _, den = text.partition("/")
            assert mtext in (text, f"{num}/({den})"), (flavour, text, mtext)
            if flavour in ("numpy", "ops"):
                env = {"x": 1.7, "y": 0.3, "np": np, "_X": np}
                assert eval(mtext, env) == eval(text, env)     # noqa: S307 -- the printer's own text
                evaluated += 1
    assert evaluated == 2 * len(exprs)


def test_block_sharp_tier_reads_each_members_own_status(monkeypatch):
    # seed 14's kernels_block:257 (`sh[k] = st[k]` -> `sh[k - 1] = st[k]`): the sharp tier of a member decided by its
    # neighbour's status before the read-out; each member in its scan's block shifts alike, a block of one does not
    from symbt.numeric.float64 import block_python, kernels_block

    assert block_python.kernel("run_block") is block_python.run_block    # built from the source before the plant
    monkeypatch.setattr(kernels_block, "run_block", planted(kernels_block.run_block, "            sh[k] = st[k]\n",
                                                            "            sh[k - 1] = st[k]\n"))
    assert fails("paths.mixed_block.n3")


@pytest.mark.parametrize("old, new", [
    # seed 14's inverse:159: the least-squares residual with the target's sign flipped
    ("[wk * (c[k] - c_target[k]) for wk, k in zip(w, idx)]", "[wk * (c[k] + c_target[k]) for wk, k in zip(w, idx)]"),
])
def test_least_squares_mode_recovers_its_start(monkeypatch, old, new):
    from symbt.reference import inverse

    monkeypatch.setattr(inverse, "solve_parameters", planted(inverse.solve_parameters, old, new))
    assert fails("library.inverse_fields")


def test_gauss_newton_counts_the_iterates_evaluated(monkeypatch):
    # _gauss_newton reported one iterate fewer than solve_parameters documents (0 where the start meets tol): fixed;
    # the old count is seen by library.newton_rule and library.inverse_fields
    from symbt.reference import inverse

    converged = "* lam < tol:\n            return x, it"
    mutant = planted(inverse._gauss_newton, converged + " + 1\n", converged + "\n")
    monkeypatch.setattr(inverse, "_gauss_newton", mutant)
    assert fails("library.inverse_fields") and fails("library.newton_rule")


def test_general_orbit_block_size_is_equivalent(monkeypatch):
    # seed 14's orbit:161 (`N = pa.shape[1]` -> `pa.shape[0]`, the batch size M for the site count): N is read only
    # by `block = max(256, BLOCK_ELEMENTS // N)`, the rows per numpy block, and a row's result never depends on
    # the block it falls in (docs/numeric.md, float64.rows) -- so only the partition changes.  Checked: 700 rows,
    # one block of 700 against three of 256, 256 and 188, the same bits and statuses (rows without a real map among
    # them); M >= 1 whenever general_orbit is called (the drivers call it only for a non-empty `todo`)
    import inspect

    import numpy as np

    from symbt.numeric.float64 import orbit

    uses = [line.strip() for line in inspect.getsource(orbit.general_orbit).split('"""')[-1].splitlines()
            if "N" in line.replace("NoReal", "")]
    assert uses == ["N = pa.shape[1]", "block = max(256, BLOCK_ELEMENTS // N)"]
    rng = np.random.default_rng(5)
    M = 700
    pa, qa = rng.uniform(-2, 2, (M, 3)), rng.uniform(-1, 1, (M, 3))
    lam0, mu = rng.uniform(-6, 6, M), rng.uniform(0.1, 1.5, M)

    def run(fn) -> tuple:
        P, Q = np.zeros((3, M, 3)), np.zeros((3, M, 3))
        st, fs = fn(pa, qa, lam0, mu, 1, 2, 1, P, Q, np.arange(M))
        return P.tobytes(), Q.tobytes(), st.tolist(), fs.tolist()

    original = run(orbit.general_orbit)
    assert 0 < original[2].count(0) < M          # some rows finish, some have no real map
    mutant = planted(orbit.general_orbit, "    N = pa.shape[1]\n", "    N = pa.shape[0]\n")
    assert run(mutant) == original


def test_range_test_at_two_to_the_500(monkeypatch):
    # seed 12's condition:388 (`big < 2.0 ** 500` -> `<=`): a batch whose largest entry is 2**500 exactly taken as in
    # range, so a row below 2**-500 beside it is not renormalised
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_product_on_floats", planted(
        condition._product_on_floats, "if big < 2.0 ** 500 and math.isfinite(big):",
        "if big <= 2.0 ** 500 and math.isfinite(big):"))
    assert fails("paths.abs_products.n2")


def test_guard_from_the_larger_trace_in_modulus(monkeypatch):
    # seed 15's literal:278 (`abs(t1)` -> `t1`): a large negative trace at lam1 counted as small
    from symbt.reference import literal

    monkeypatch.setattr(literal, "reference_step", planted(
        literal.reference_step, "big = max(abs(t1), abs(t2), mp.mpf(10))", "big = max(t1, abs(t2), mp.mpf(10))"))
    assert fails("library.guard_far_trace")


def test_relation_of_degree_zero_refused_by_its_degree(monkeypatch):
    # seed 15's screen:119 (`1 <= degree` -> `0 <= degree`): a relation without its symbol taken to the generic roots
    # of degree 0 -- still refused, but as unsolvable, not for its degree
    from symbt.proof import screen as screen_module

    monkeypatch.setattr(screen_module, "relation_poly", planted(screen_module.relation_poly, "poly.degree() < 1",
                                                                "poly.degree() < 0"))
    assert fails("checker.screen_relations")


def test_arb_trace_sign_at_a_zero_midpoint_is_equivalent():
    # seed 15's runners:129 (`tg = t.mid() >= 0` -> `> 0`): they differ only at a trace ball whose midpoint is 0, and
    # _slopes raises NoRealMapError before it reads tg whenever disc = (t - 2)(t + 2) has a midpoint <= 0: Arb's
    # product of [-2 +- R] and [2 +- R] has the midpoint -4 (the product of the midpoints) for every radius R, so
    # a zero midpoint never reaches the line.  Checked on the source (the raise precedes the read) and on balls
    import inspect

    flint = pytest.importorskip("flint")
    from symbt.numeric.multiprec import runners

    src = inspect.getsource(runners._slopes)
    assert src.index("if not disc.mid() > 0:") < src.index("raise NoRealMapError") < src.index("tg = t.mid() >= 0")
    for rad in ("0", "1e-30", "0.5", "3", "1e10"):
        t = flint.arb(0, rad)
        disc = (t - 2.0) * (t + 2.0)
        assert not disc.mid() > 0


def test_loop_form_integrand_weight(monkeypatch):
    # seed 15's codegen.kernels:89 (`1 / sqrt(disc)` -> `0 / sqrt(disc)`): the loop form's c_k integrand identically 0
    from symbt.claims import shipped_emitted
    from symbt.codegen import emit_loop, kernels, zullo

    mutant = planted(kernels.kernels.__wrapped__, 'out["inv_sqrt_disc"] = 1 / sp.sqrt(disc(t))',
                     'out["inv_sqrt_disc"] = 0 / sp.sqrt(disc(t))')
    monkeypatch.setattr(emit_loop, "kernels", mutant)       # what the loop form's printed core reads
    caches = (shipped_emitted.emitted_module, zullo.declarations)     # the module and its declarations, rendered
    for f in caches:
        f.cache_clear()
    try:
        assert fails("shipped.loop_integrand.n5")
    finally:
        for f in caches:
            f.cache_clear()
