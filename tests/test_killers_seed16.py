"""Seeds 16 and 17's survivors (docs/mutation.md, "Seed 16", "Seed 17"): planted bugs that the new claims and facts
now see, the proofs of the mutants marked equivalent, and planted bugs only a test sees.  Unpatched, every claim
verifies."""
from __future__ import annotations

import inspect
import math
import random

import mpmath as mp
import numpy as np
import pytest
from planting import claim_fails as fails
from planting import planted

from symbt.claims import REGISTRY, load_all

load_all()

CLAIMS = ["shipped.loop_phi_grad.n5", "paths.symmetric_monodromy.n2", "paths.many_rows.n3", "shipped.guard_boundary.n2",
          "shipped.guard_boundary.n3", "checker.codegen_metrics", "paths.kappa_rows.n2", "checker.exact",
          "library.emit_typed", "library.emit", "library.reference_verify", "library.input_kinds", "paths.contexts",
          "paths.dq_edge.n9", "paths.lohner_unsound.n3", "paths.ball_schedule.n3", "paths.panels",
          "library.inverse_fields"]


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert REGISTRY[cid].run().status == "verified"


# --------------------------------------------------------------------------- planted bugs the claims now see

def test_interpreter_min(monkeypatch):
    # codegen.verify:144 (`min(vs)` -> `max(vs)`): the reference interpreter's Min, read by no shipped derivation
    from symbt.codegen import verify

    monkeypatch.setattr(verify, "interpret", planted(verify.interpret, "else min(vs)", "else max(vs)"))
    assert fails("checker.codegen_metrics")


def test_sharp_rows_at_one_site(monkeypatch):
    # condition:296 (`if N > 1` -> `N >= 1`): the prefix's second row written at a site that does not exist (an
    # IndexError at one site, where the scalar form returns its value)
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "_sharp_over_rows", planted(condition._sharp_over_rows, "if N > 1:", "if N >= 1:"))
    assert fails("paths.kappa_rows.n2", crash=True)


def test_tiny_note_at_the_screen_tolerance(monkeypatch):
    # decider:211 (`10 ** -(digits - 8)` -> `-(digits + 8)`): "numerically tiny" only below 1e-58 at 50 digits
    from symbt.claims import checker
    from symbt.proof import decider

    monkeypatch.setattr(checker, "decide", planted(decider.decide, "if sr.residual <= 10.0 ** (-(digits - 8)):",
                                                   "if sr.residual <= 10.0 ** (-(digits + 8)):"))
    assert fails("checker.exact")


@pytest.mark.parametrize("old, new", [
    ("sp.sympify(v, strict=True)", "sp.sympify(v, strict=False)"),                    # declare:134: text parsed
])
def test_text_is_no_expression(monkeypatch, old, new):
    from symbt.codegen.user import declare

    monkeypatch.setattr(declare, "_elements", planted(declare._elements, old, new))
    assert fails("library.emit_typed")


def test_negative_infinity_is_non_finite(monkeypatch):
    # declare:161 (`-sp.oo` -> `sp.oo` in the non-finite constants): -oo then refused as a "complex constant"
    from symbt.codegen.user import declare

    monkeypatch.setattr(declare, "_check_expr", planted(declare._check_expr, "(sp.nan, sp.oo, -sp.oo, sp.zoo)",
                                                        "(sp.nan, sp.oo, sp.oo, sp.zoo)"))
    assert fails("library.emit_typed")


def test_reference_verify_runs_when_asked(monkeypatch):
    # literal:284 (`if verify:` -> `if not verify:`): the convergence check skipped exactly when asked for
    from symbt.claims import library_ref45
    from symbt.reference import literal

    monkeypatch.setattr(library_ref45, "reference_step",
                        planted(literal.reference_step, "    if verify:\n", "    if not verify:\n"))
    assert fails("library.reference_verify")


@pytest.mark.parametrize("old, new", [
    ('-branch * (x1 / sp.sqrt(disc(tr1)) + x2', '-branch * (x1 / sp.sqrt(disc(tr1)) - x2'),     # kernels:166 sign
    ('out["grad"] = -branch *', 'out["grad"] = branch *'),                                       # kernels:166 minus
])
def test_loop_form_gradient(monkeypatch, old, new):
    from symbt.claims import shipped_emitted
    from symbt.codegen import emit_loop, kernels, zullo

    monkeypatch.setattr(emit_loop, "kernels", planted(kernels.kernels.__wrapped__, old, new))
    caches = (shipped_emitted.emitted_module, zullo.declarations)
    for f in caches:
        f.cache_clear()
    try:
        assert fails("shipped.loop_phi_grad.n5")
    finally:
        for f in caches:
            f.cache_clear()


def test_c_sign_helper_only_where_used(monkeypatch):
    # render:262 (`if "sgn(" not in ...` inverted): sgn() defined where no function calls it (a -Wall warning) and
    # dropped where one does (does not compile)
    from symbt.codegen.user import check, render

    if check.compiler() is None:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    monkeypatch.setattr(render, "c_source", planted(render.c_source, 'if "sgn(" not in "\\n".join(lines[5:]):',
                                                    'if "sgn(" in "\\n".join(lines[5:]):'))
    assert fails("library.emit")


@pytest.mark.parametrize("old, new", [("ref >= 0", "ref > 0"), ("ref >= 0", "ref <= 0")])
def test_float_align_at_a_symmetric_monodromy(monkeypatch, old, new):
    # context:178 (`ref >= 0` -> `ref > 0`): at A - D = 0 exactly the numpy route takes the other root formula
    from symbt.numeric.core import context

    monkeypatch.setattr(context.FloatContext, "align", planted(context.FloatContext.align, old, new))
    assert fails("paths.symmetric_monodromy.n2")


def test_cheap_estimate_takes_the_larger_condition(monkeypatch):
    # kernels:320 (`max(tt[2], tt[3])` -> `min`): the cheap kernels' read-out test with the better-conditioned trace
    from symbt.numeric.float64 import kernels

    monkeypatch.setattr(kernels, "_sharpen_off", planted(kernels._sharpen_off, "return max(", "return min("))
    kernels.cheap_kernels.cache_clear()
    try:
        assert fails("shipped.guard_boundary.n2")
    finally:
        kernels.cheap_kernels.cache_clear()


@pytest.mark.parametrize("old, new", [
    ("[~(kt * a * b <= c) for a, b, c in", "[~(kt * a * b >= c) for a, b, c in"),
    ("zip(us[0], us[1], rhs)", "zip(us[0], us[0], rhs)"),
])
def test_site_by_site_condition_test(monkeypatch, old, new):
    # step:367 (uncovered in seed 16: no claim had a batch past SIDE_BY_SIDE_ROWS rows)
    from symbt.numeric.core import step

    monkeypatch.setattr(step, "float_status", planted(step.float_status, old, new))
    assert fails("paths.many_rows.n3")


@pytest.mark.parametrize("func, old, new", [
    ("_has_text", 'if x.dtype.kind in "US":', 'if x.dtype.kind in "S":'),        # numpy str arrays let through
    ("_is_complex", 'if x.dtype.kind == "c":', 'if x.dtype.kind == "f":'),       # numpy complex arrays let through
    ("_kind", "if x.dtype != object:", "if x.dtype == object:"),                # object arrays of mpf as floats
    ("float_array", 'if kind not in "mMV":', 'if kind not in "V":'),            # dates cast to days
    ("validate_float_pair", "if not (np.all(np.isfinite(pa)) and np.all(np.isfinite(qa))):",
     "if not (np.all(np.isfinite(pa)) or np.all(np.isfinite(qa))):"),          # one non-finite side let through
])
def test_input_rules(monkeypatch, func, old, new):
    # inputs:39, :155-158, :221 (uncovered in seed 16: no claim gave the public entry points malformed input)
    from symbt.numeric.core import inputs

    monkeypatch.setattr(inputs, func, planted(getattr(inputs, func), old, new))
    assert fails("library.input_kinds", crash=True)


@pytest.mark.parametrize("where, func, old, new", [
    ("context", "FloatContext.ldexp", "if np.iscomplexobj(x):", "if False:"),             # numpy's real ldexp
    ("context", "FloatContext.positive", "(np.imag(x) == 0) & (np.real(x) > 0)", "np.real(x) > 0"),
    ("context", "MPContext.ldexp", "if isinstance(z, mpmath.mpc):", "if False:"),
    ("context", "IVContext.acosh_half_abs", "h = abs(IVContext.ldexp(t, e)) / 2", "h = abs(t) / 2"),
    ("context", "MPContext.align", "plus = self.re_dot(ref, g) >= 0", "plus = self.re_dot(ref, g) > 0"),
    ("arb", "ArbContext.positive", "if x <= 0:", "if x <= 1:"),
    ("arb", "AcbContext.half_plane", ".mid() >= 0)", ".mid() > 0)"),
])
def test_context_primitives(monkeypatch, where, func, old, new):
    # context:155-167, :214, :274, :321, :367-376, arb:99-175 (uncovered in seed 16: the contexts' rare cases)
    pytest.importorskip("flint")
    from symbt.numeric.core import context
    from symbt.numeric.multiprec import arb

    module = context if where == "context" else arb
    cls, name = func.split(".")
    monkeypatch.setattr(getattr(module, cls), name, planted(getattr(getattr(module, cls), name), old, new))
    assert fails("paths.contexts", crash=True)


def test_complex_log1p_near_zero(monkeypatch):
    # the complex float64 context's log1p was numpy's (log(1 + x): 6e-9 relative at |x| = 1e-8), found by
    # paths.contexts' elementary functions
    from symbt.numeric.core import context

    monkeypatch.setattr(context.FloatContext, "log1p", lambda self, x: np.log1p(x))
    assert fails("paths.contexts", crash=True)


@pytest.mark.parametrize("func, old, new", [
    ("Dual.__rsub__", "return Dual(o - self.v, -self.d)", "return Dual(o - self.v, self.d)"),      # lohner_checks:71
    ("Dual.__truediv__", "return Dual(self.v / o, self.d * (1 / arb(o)))",
     "return Dual(self.v / o, self.d * arb(o))"),                                                 # lohner_checks:87
    ("_dlog", "x.d * (1 / x.v)", "x.d * (1 / (1 + x.v))"),                                        # lohner_checks:120
])
def test_dual_rules(monkeypatch, func, old, new):
    # lohner_checks:71, :87, :120 (uncovered in seed 16: the dual numbers' rules no Jacobian of a step reaches)
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks as L

    if "." in func:
        cls, name = func.split(".")
        monkeypatch.setattr(getattr(L, cls), name, planted(getattr(getattr(L, cls), name), old, new))
    else:
        mutant = planted(getattr(L, func), old, new)
        monkeypatch.setattr(L, func, mutant)
        monkeypatch.setattr(L._DualContext, "log", staticmethod(mutant))
    assert fails("paths.contexts", crash=True)


@pytest.mark.parametrize("old, new", [
    ("        if self.unsound:\n            J, err", "        if not self.unsound:\n            J, err"),   # lohner:328
    ("J, err = J.mid(), arb_mat(self.n, 1)", "J, err = J.mid(), arb_mat(self.n, 0)"),                      # lohner:329
])
def test_lohner_unsound_variant(monkeypatch, old, new):
    # lohner:328-329 (uncovered in seed 16: no claim ran the unsound variant, the control of the containment test)
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner.LohnerSet, "step", planted(lohner.LohnerSet.step, old, new))
    assert fails("paths.lohner_unsound.n3", crash=True)


@pytest.mark.parametrize("old, new", [
    ("np.subtract(q[:, 1:], q[:, :-1], out=d[:, :-1])", "np.subtract(q[:, 0:], q[:, :-1], out=d[:, :-1])"),
    ("np.subtract(q[:, 0], q[:, -1], out=d[:, -1])", "np.subtract(q[:, 1], q[:, -1], out=d[:, -1])"),
    ("np.abs(d, out=d).max(axis=1)", "np.abs(d, out=d).min(axis=1)"),
])
def test_range_test_past_eight_sites(monkeypatch, old, new):
    # rows:255-257 (uncovered in seed 16: the numpy route's array form of the range test runs from 9 sites on)
    from symbt.numeric.float64 import rows

    monkeypatch.setattr(rows, "_largest_step", planted(rows._largest_step, old, new))
    assert fails("paths.dq_edge.n9", crash=True)


# --------------------------------------------------------------------------- planted bugs only a test sees

def test_newton_residual_exactly_at_the_tolerance():
    # inverse:80 (`< tol` -> `<= tol` in _newton's test after the last iterate): a residual of exactly tol is not
    # converged (the strict test of the loop); no claim meets a residual equal to its tolerance.  F = tol everywhere
    # with J = 1: every damped step is accepted, none converges
    from symbt.reference import inverse

    tol = mp.mpf(2) ** -40

    def F(x):
        return [tol]

    def J(x):
        return [[1]]

    mutant = planted(inverse._newton, "max(abs(v) for v in rf) < tol else None",
                     "max(abs(v) for v in rf) <= tol else None")
    assert inverse._newton(F, J, [mp.mpf(1)], tol, maxit=3) is None
    assert mutant(F, J, [mp.mpf(1)], tol, maxit=3) is not None


# --------------------------------------------------------------------------- equivalent mutants (proofs)

def test_arb_step_branch_sign_is_equivalent():
    # runners:130 (`fwd = (not tg) if s > 0 else tg` -> `s >= 0`): _slopes is called only by arb_step, with
    # +-branch after check_branch (so s is +-1 and s > 0 <=> s >= 0); a branch of 0 is refused before
    flint = pytest.importorskip("flint")
    from symbt.numeric.core.errors import InvalidInputError
    from symbt.numeric.multiprec import runners

    src = inspect.getsource(runners)
    assert src.count("_slopes(") == 3                   # the definition and arb_step's two calls
    body = inspect.getsource(runners.arb_step)
    assert body.index("branch = check_branch(branch)") < body.index("_slopes(") and \
        "_slopes([lam1 + pj for pj in P], r, branch," in body and "_slopes([lam2 + pj for pj in P], r, -branch," in body
    P, Q = [flint.arb(-20), flint.arb(10), flint.arb(1)], [flint.arb(1), flint.arb(0), flint.arb("0.9")]
    for b in (0, 2, True):
        with pytest.raises(InvalidInputError):
            runners.arb_step(P, Q, flint.arb(10), flint.arb(5), b)


def test_arb_align_at_a_zero_root_is_equivalent():
    # arb:124 (ArbContext.align's `g.mid() >= 0` -> `> 0`): they differ only at g.mid() == 0.  align is called only
    # by eigen_slopes with g = ctx.sqrt(disc), disc = trace_ok; Arb's sqrt has midpoint 0 only for the exact zero
    # ball (a ball holding negatives gives nan, where both tests are false), and every Arb caller of eigen_slopes
    # (step_core with check_real, as certified, lohner and the Jacobian's dual context call it) raises
    # NoRealMapError at trace_ok = 0 before the slopes are used.  Checked: the call sites, sqrt's midpoints, and
    # the certified step at tr = 2 exactly (p = q = 0, lam1 = 2: tr = lam^3 - 3 lam) with both versions of align
    flint = pytest.importorskip("flint")
    import symbt
    from symbt.numeric import NoRealMapError
    from symbt.numeric.core import step as core_step
    from symbt.numeric.multiprec import arb as arbmod

    # arb:128 (half_plane's `g.mid() >= 0` -> `> 0`) likewise: its one caller passes the same g
    package = __import__("pathlib").Path(symbt.__file__).parent
    for call in (".align(", ".half_plane("):
        callers = [p.relative_to(package).as_posix() for p in package.rglob("*.py")
                   if call in p.read_text(encoding="utf-8") and p.parts[-2] != "claims"]
        assert callers == ["numeric/core/step.py"], (call, callers)
    src = inspect.getsource(core_step.eigen_slopes)
    assert src.index("g = ctx.sqrt(disc)") < src.index("ctx.half_plane(t, g)") < src.index("ctx.align(g, dl)")
    for ball in (flint.arb(0), flint.arb(0, 1e-10), flint.arb(-1, 0.5), flint.arb("1e-400"), flint.arb(3, 1)):
        m = ball.sqrt().mid()
        assert (m == 0) == (ball == 0 and ball.rad() == 0)
    zero = [flint.arb(0)] * 3
    for name, old in (("align", "(g.mid() >= 0)"), ("half_plane", "(g.mid() >= 0)")):
        original = getattr(arbmod.ArbContext, name)
        for version in (original, planted(original, old, "(g.mid() > 0)")):
            setattr(arbmod.ArbContext, name, version)
            try:
                for ctx in (arbmod.ARB_CERTAIN, arbmod.ARB_MID):
                    with pytest.raises(NoRealMapError):
                        core_step.step_core(ctx, zero, zero, flint.arb("1.5"), flint.arb("0.5"), 1)
            finally:
                setattr(arbmod.ArbContext, name, original)


def test_acb_certain_flag_is_unread():
    # arb:193 (`ACB = AcbContext(certain=False)` -> `certain=True`): `certain` is read only by ArbContext.positive,
    # which AcbContext overrides (its decisions are on midpoints); checked on the source and on decisions
    flint = pytest.importorskip("flint")
    from symbt.numeric.multiprec import arb as arbmod

    src = inspect.getsource(arbmod)
    assert src.count("self.certain") == 2                     # set in __init__, read in ArbContext.positive
    assert "self.certain" in inspect.getsource(arbmod.ArbContext.positive)
    assert arbmod.AcbContext.positive is not arbmod.ArbContext.positive
    assert "certain" not in inspect.getsource(arbmod.AcbContext)
    both = (arbmod.AcbContext(certain=False), arbmod.AcbContext(certain=True))
    for x in (flint.acb(flint.arb(0.25, 0.5)), flint.acb(1, 0), flint.acb(-1, 0), flint.acb(1, 1)):
        assert both[0].positive(x) == both[1].positive(x) and both[0].all_positive(x) == both[1].all_positive(x)


def test_flow_moment_sign_at_a_zero_node_is_equivalent():
    # coefficients:182 (`lam < 0` -> `lam <= 0` in _log2_rows' sign): at a node lam = 0 the term of an odd k is
    # sgn * exp2(-inf) * w = +-0, and a sum holding a nonzero term (the node of the largest L contributes
    # exp2(L - E) >= 1) is unchanged by a +-0 (x + -0 = x; an exact cancellation rounds to +0 either way, and
    # +0 + -0 = +0 in round-to-nearest).  Checked bit for bit on rules with a node at 0 (weights of both signs)
    from symbt.numeric.flow import coefficients as C

    mutant = planted(C._log2_rows, "(lam < 0)[None, :]", "(lam <= 0)[None, :]")
    rng = np.random.default_rng(16)
    for sign in (1.0, -1.0):
        for n in (3, 5, 9):
            nodes = np.concatenate([rng.uniform(-2, -0.1, n // 2), [0.0], rng.uniform(0.1, 2, n // 2)])
            log2_inv = rng.uniform(-3, 1, nodes.size)
            ks = np.arange(0, 7, dtype=float)
            L0, s0 = C._log2_rows(nodes, log2_inv, ks)
            L1, s1 = mutant(nodes, log2_inv, ks)
            w = sign * rng.uniform(0.1, 1.0, nodes.size)
            E = np.floor(np.max(L0, axis=1))
            a = (s0 * np.exp2(L0 - E[:, None])) @ w
            b = (s1 * np.exp2(L1 - E[:, None])) @ w
            assert np.array_equal(a, b) and np.array_equal(np.signbit(a), np.signbit(b))
            assert not np.array_equal(s0, s1)            # the mutant does change the sign of the zero term


def test_quadrature_error_is_nonnegative_so_abs_is_equivalent():
    # screen:175 (`abs(err)` -> `err` in tracked_quad's log): mpmath.quad's error estimate is a sum of
    # QuadratureRule.estimate_error values, each abs(...), zero, epsilon or a power of ten: never negative
    from mpmath.calculus import quadrature as Q

    src = inspect.getsource(Q.QuadratureRule.estimate_error)
    returns = [line.strip() for line in src.splitlines() if line.strip().startswith("return")]
    assert returns == ["return abs(results[0]-results[1])", "return self.ctx.zero", "return epsilon",
                       "return self.ctx.mpf(10) ** int(D4)"]
    assert "total_err += err" in inspect.getsource(Q.QuadratureRule.summation)
    for f, iv in ((lambda t: t * t, (0, 1)), (lambda t: mp.exp(1j * t), (0, 3)), (lambda t: 1 / mp.sqrt(t), (0, 1)),
                  (lambda t: mp.sin(50 * t), (0, 1))):
        _, err = mp.quad(f, iv, error=True)
        assert err >= 0


def test_abel_sheet_at_a_branch_point_is_equivalent():
    # elliptic:236 (`abs(cd - w) <= abs(cd + w)` -> `<`): on the curve cd = +-w, so the two sides tie only where
    # cd w = 0, i.e. cd = 0: s = +-1 or s = +-1/sqrt(m) (branch points of the curve); there u0 and 2K - u0 differ
    # by a period (4K, 2iK'), and abel is documented mod those periods: the same sn and cn dn
    from symbt.reference import elliptic as E

    mutant = planted(E.abel, "abs(cd - w) <= abs(cd + w)", "abs(cd - w) < abs(cd + w)")
    with mp.workdps(30):
        m = mp.mpf(3) / 7
        K, Kp = mp.ellipk(m), mp.ellipk(1 - m)
        for s in (mp.mpf(1), mp.mpf(-1), 1 / mp.sqrt(m), -1 / mp.sqrt(m)):
            for w in (mp.mpf(0), mp.mpf(10) ** -40, -mp.mpf(10) ** -40):
                a, b = E.abel(s, w, m), mutant(s, w, m)
                d = (b - a) / 1
                n4 = mp.re(d) / (4 * K)
                n2 = mp.im(d) / (2 * Kp)
                assert abs(n4 - mp.nint(n4)) < mp.mpf(10) ** -25 and abs(n2 - mp.nint(n2)) < mp.mpf(10) ** -25
                sa, ca, da = E.sn_cn_dn(a, m)
                sb, cb, db = E.sn_cn_dn(b, m)
                assert abs(sa - sb) < mp.mpf(10) ** -20 and abs(ca * da - cb * db) < mp.mpf(10) ** -20
        # away from the branch points the two agree (the tie needs cd = 0)
        for s in (mp.mpf("0.3"), mp.mpf("-0.8"), mp.mpf(2), mp.mpf(-4)):
            W = mp.sqrt((1 - s * s) * (1 - m * s * s))
            for w in (W, -W):
                assert E.abel(s, w, m) == mutant(s, w, m)


@pytest.mark.parametrize("old, new", [("am.shape != rm.shape", "am.shape == rm.shape"),
                                      ("am.ndim != 2", "am.ndim == 2")])
def test_side_by_side_shape_guard_is_equivalent(old, new):
    # condition:446 (`am.shape != rm.shape` -> `==`; seed 18: `am.ndim != 2` -> `==`): every batch of
    # FEW_ROWS < R <= SIDE_BY_SIDE_ROWS rows then takes the two calls, whose results are the side-by-side form's bit
    # for bit (its docstring; paths.side_by_side), and no caller passes a and r of different shapes or other than
    # one row array per site (eigen_slopes' a_j = lam + p_j and r_j = exp(dq_j) share the batch's shape; up to
    # FEW_ROWS rows, scalars included, _few_rows answers first).  Checked bit for bit on side_by_side's batches,
    # renormalised rows included
    from symbt.numeric.core import condition

    mutant = planted(condition.monodromy_and_abs, old, new)
    rng = np.random.default_rng(446)
    for R, scale in ((20, 1.0), (300, 1.0), (64, 1e170)):
        a = [rng.uniform(-3, 3, R) * scale for _ in range(3)]
        r = [np.exp(rng.uniform(-2, 2, R)) for _ in range(3)]
        (A, B, C_, D, e), (T, ea) = condition.monodromy_and_abs(a, r)
        (A2, B2, C2, D2, e2), (T2, ea2) = mutant(a, r)
        for x, y in ((A, A2), (B, B2), (C_, C2), (D, D2), (e, e2), (T, T2), (ea, ea2)):
            assert np.array_equal(np.broadcast_to(x, (R,)), np.broadcast_to(y, (R,)))
    src = inspect.getsource(condition)
    assert src.count("monodromy_and_abs(") == 2     # its definition and its docstring; the one caller is in step.py
    assert "monodromy_and_abs(a, r)" in inspect.getsource(__import__("symbt.numeric.core.step",
                                                                     fromlist=["eigen_slopes"]).eigen_slopes)



@pytest.mark.parametrize("old, new", [("if N <= 8:", "if not (N <= 8):"), ("if N <= 8:", "if N < 8:"),
                                      ("if N <= 8:", "if N >= 8:"), ("for j in range(1, N):", "for j in range(0, N):")])
def test_largest_step_forms_are_equivalent(old, new):
    # rows:249, :251 (`_largest_step`'s switch between its two forms, and the loop form's first site taken twice):
    # both forms take max_j |q_{j+1} - q_j| of the same rounded differences (a subtraction, abs, max: exact
    # operations after the subtraction), so any N gives the same floats, NaN rows included
    from symbt.numeric.float64 import rows

    mutant = planted(rows._largest_step, old, new)
    rng = np.random.default_rng(249)
    for N in (2, 3, 8, 9, 12):
        q = rng.uniform(-800, 800, (40, N))
        q[3, N // 2] = np.nan
        q[5] = 1e300 * np.array([(-1) ** j for j in range(N)])
        assert np.array_equal(rows._largest_step(q), mutant(q), equal_nan=True)


# --------------------------------------------------------------------------- seed 17

def test_panels_group_scale_is_a_size(monkeypatch):
    # coefficients:213 (`_group_scale(np.abs(i32))` -> `i32`): a group's scale taken as the signed maximum, the tiny
    # peak's own where its partner row is negative
    from symbt.numeric.flow import coefficients

    monkeypatch.setattr(coefficients, "adaptive_panels", planted(
        coefficients.adaptive_panels, "scale = _group_scale(np.abs(i32), groups)", "scale = _group_scale(i32, groups)"))
    assert fails("paths.panels")            # the claim imports adaptive_panels from the module when it runs


def test_certified_two_sites(monkeypatch):
    # certified:126 (`len(P) < 2` -> `<= 2`): two sites refused by the certified orbit; no claim ran one at N = 2
    from symbt.numeric.multiprec import certified

    monkeypatch.setattr(certified, "_state", planted(certified._state, "len(P) < 2:", "len(P) <= 2:"))
    assert fails("library.input_kinds", crash=True)


def test_cauchy_schwarz_only_with_all_three_fitted(monkeypatch):
    # inverse:171 (`{0, 1, 2} <= used` -> `{0, 0, 2}`): the refusal where c_1 is not fitted
    from symbt.reference import inverse

    monkeypatch.setattr(inverse, "solve_parameters", planted(inverse.solve_parameters, "if {0, 1, 2} <= used",
                                                             "if {0, 0, 2} <= used"))
    assert fails("library.inverse_fields")


def test_reduction_to_the_fixed_point(monkeypatch):
    # flint_exact:180 (`if num == before: break` inverted): one round of reductions where a second is needed
    from symbt.proof import flint_exact

    mutant = planted(flint_exact.rational_zero, "            if num == before:", "            if not (num == before):")
    monkeypatch.setattr(flint_exact, "rational_zero", mutant)
    assert fails("checker.exact")


def test_invariants_zero_from_another_site_is_equivalent():
    # invariants:76 (`zero = 0.0 * P[0]` -> `P[1]`): the zero of the batch's shape (or an mpf zero) from another site
    # of the same shape; P is finite (validated), so 0.0 * P[1] is a zero too, at most of the other sign, and a
    # signed zero is not a different number: the invariants compare equal, batches and mpf alike
    from symbt.numeric.flow import invariants

    mutant = planted(invariants._invariants, "zero = 0.0 * P[0]", "zero = 0.0 * P[1]")
    rng = np.random.default_rng(76)
    for N in (2, 3, 5):
        p = rng.normal(size=(7, N))
        p[0, 0], p[1, :] = 0.0, -np.abs(p[1, :])
        q = rng.normal(size=(7, N))
        assert all(np.array_equal(a, b) for a, b in zip(invariants._invariants(p, q), mutant(p, q)))
        with mp.workdps(30):
            pm, qm = [mp.mpf(v) for v in p[2]], [mp.mpf(v) for v in q[2]]
            assert invariants._invariants(pm, qm) == mutant(pm, qm)


def test_transfer_gradient_first_suffix_from_the_identity_is_equivalent():
    # field:84 (`if j == N - 1` -> `N - 0`: never true): the suffix product's first update then runs the general
    # formula from B_N = I: 1 a + 0 r = a, -s 1 = -s, 0 a + 1 r = r, -s 0 = 0 -- the same entries for finite a, r
    # (FlowField's r = exp(dq), |dq| <= 700), at most a zero of the other sign; the gradients compare equal
    from symbt.numeric.flow import field

    mutant = planted(field.transfer_gradient, "            if j == N - 1:\n                b00",
                     "            if j == N - 0:\n                b00")
    rng = np.random.default_rng(84)
    for N in range(2, 8):
        for _ in range(30):
            a, r, s = list(rng.normal(size=N)), list(rng.uniform(0.1, 3, size=N)), float(rng.uniform(0.5, 2))
            assert mutant(a, r, s) == field.transfer_gradient(a, r, s)
        with mp.workdps(30):
            am, rm = [mp.mpf(v) for v in a], [mp.mpf(v) for v in r]
            assert mutant(am, rm, mp.mpf(s)) == field.transfer_gradient(am, rm, mp.mpf(s))


def test_sample_case_separation_tie_is_equivalent():
    # elliptic:436 (`abs(sa - sb) < 0.05` -> `<=`): a draw is redrawn when its two ends are closer than 0.05; the
    # two tests differ only where two random doubles differ by exactly 0.05: the same cases for every seed tried
    from symbt.reference import elliptic as E

    mutant = planted(E.sample_case, "if abs(sa - sb) < 0.05:", "if abs(sa - sb) <= 0.05:")
    for reg in E._ZONES:
        for seed in range(300):
            assert mutant(reg, random.Random(seed)) == E.sample_case(reg, random.Random(seed))


def test_spread_tuples_single_pair_is_equivalent(monkeypatch):
    # inline:424 (`pairs[0][0] is n.targets[0]` -> `pairs[0][1] is ...`): an assignment whose target is no spread
    # tuple is then rebuilt as the one assignment `Assign([t], v)` of its single pair instead of returned as it is:
    # the same statement (unless the target is the value, which _same drops: `x = x`, a no-op).  Checked: the
    # fused kernels built with the mutant have the very same bytecode, constants and names
    from symbt.numeric.core import inline
    from symbt.numeric.float64 import kernels

    def code(fn):
        c = fn.__code__
        return c.co_code, c.co_consts, c.co_names, c.co_varnames

    want = {k: code(f) for k, f in kernels.python_kernels.__wrapped__().items()}
    original = inline._SpreadTuples.visit_Assign
    monkeypatch.setattr(inline._SpreadTuples, "visit_Assign", planted(
        original, "pairs[0][0] is n.targets[0]", "pairs[0][1] is n.targets[0]"))
    got = {k: code(f) for k, f in kernels.python_kernels.__wrapped__().items()}
    assert got == want
    # the control: the method does run in this build -- doubling the statements it returns as they are changes it
    monkeypatch.setattr(inline._SpreadTuples, "visit_Assign", planted(
        original, "pairs[0][0] is n.targets[0]:\n        return n",
        "pairs[0][0] is n.targets[0]:\n        return [n, n]"))
    assert {k: code(f) for k, f in kernels.python_kernels.__wrapped__().items()} != want


@pytest.mark.parametrize("old, new", [("max(1, i1 - i0)", "max(0, i1 - i0)"),            # certified:181
                                      ("extra = finite[-1][1] + _MARGIN", "extra = finite[-0][1] + _MARGIN")])  # :185
def test_ball_schedule_forms_are_equivalent(old, new):
    # certified:181 (`max(1, i1 - i0)` -> `max(0, ...)`): with two finite excesses or more, i0 < i1 (indices of one
    # list, ascending), so i1 - i0 >= 1 either way; certified:185 (`finite[-1]` -> `finite[-0]`): that branch has
    # exactly one finite excess, finite[0] is finite[-1].  Checked on random histories with 0, 1, 2 and more
    # finite entries (-inf where a radius is 0)
    from symbt.numeric.multiprec import certified

    mutant = planted(certified._next_prec, old, new)
    rng = random.Random(181)
    for _ in range(2000):
        k = rng.randint(0, 30)
        hist = [rng.choice([-math.inf, rng.uniform(-60, 20)]) for _ in range(k)]
        prec, n = rng.randint(60, 400), rng.randint(max(k, 1), 200)
        assert mutant(prec, hist, k, n) == certified._next_prec(prec, hist, k, n)


@pytest.mark.parametrize("old, new", [
    ("4 * rate + _MARGIN", "4 * rate - _MARGIN"),
    ("elif finite:", "elif not finite:"),
    ("prec + prec // 4 + 32)", "prec + prec // 4 - 32)"),
])
def test_ball_schedule(monkeypatch, old, new):
    # certified:183 (uncovered in seed 17: no claim ran the ball path's schedule), :184, :186
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import certified

    monkeypatch.setattr(certified, "_next_prec", planted(certified._next_prec, old, new))
    assert fails("paths.ball_schedule.n3", crash=True)
