"""The claims of the scenes ``checker`` and ``library`` kill the bugs they were written for (issue 21, item 4).

Each test plants one single-point bug of ``symbt mutate --source``'s kind (the survivors of its run of
2026-11-26, docs/mutation.md) with ``monkeypatch`` and requires the claim to fail; unpatched, it verifies.
"""
from __future__ import annotations

import mpmath as mp
import pytest
import sympy as sp
from planting import planted

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


# --------------------------------------------------------------------------- the claims of issue 21's second round

from symbt.claims import checker_mutation, library_codegen, library_reference  # noqa: E402


@pytest.mark.parametrize("c", [checker.api_controls, checker.domain_controls, checker_mutation.mutation_controls,
                               library.symbol_assumptions, library.linear_solutions,
                               library_reference.inverse_round_trip,
                               library_reference.angle_quadrants, library_codegen.emitted_user_functions,
                               library_codegen.guard_sources, library_codegen.codegen_check_controls])
def test_second_round_unpatched_verified(c):
    assert _status(c) == "verified"


def test_api_convention_hint_lost(monkeypatch):
    from symbt.proof import identity
    monkeypatch.setattr(identity, "convention_hint", lambda *a, **k: "")
    assert _status(checker.api_controls) == "failed"


def test_api_decide_one_side_is_against_zero(monkeypatch):
    # decider:147 (seed 8): decide's default rhs 0 -> 1
    from planting import mutated

    from symbt.proof import decider
    copy = mutated("symbt.proof.decider", "def decide(lhs: sp.Expr, rhs: sp.Expr = 0, *, relations: Mapping[sp.Symbol, "
                   "sp.Expr] | None = None,", "def decide(lhs: sp.Expr, rhs: sp.Expr = 1, *, relations: "
                   "Mapping[sp.Symbol, sp.Expr] | None = None,")
    monkeypatch.setattr(decider, "decide", copy.decide)
    assert _status(checker.api_controls) == "failed"


def test_api_relation_symbol(monkeypatch):
    # an equation's constrained symbol taken from the other side (mu or w instead of eta)
    from symbt.proof import identity
    real = identity._pick_symbol
    monkeypatch.setattr(identity, "_pick_symbol", lambda rel: (sorted(rel.rhs.free_symbols, key=str)[0]
                                                                if isinstance(rel, sp.Equality) else real(rel)))
    assert _status(checker.api_controls) == "failed"


@pytest.mark.parametrize("old, new", [
    ('    if relations:\n        parts.append("remainder mod "',
     '    if not (relations):\n        parts.append("remainder mod "'),
    ('parts.append("remainder mod " + ", ".join(', 'parts.append("remainder modulo " + ", ".join('),
])
def test_api_method_names_the_relation(monkeypatch, old, new):
    # exact:123 (seed 9): the method's "remainder mod ..." where there is no relation, and none where there is
    from planting import planted

    from symbt.proof import decider, exact
    monkeypatch.setattr(decider, "exact_zero", planted(exact.exact_zero, old, new))
    assert _status(checker.api_controls) == "failed"


def test_api_ode_scale_signed(monkeypatch):
    from symbt.proof import ode

    monkeypatch.setattr(ode.OdeResidual, "__call__", planted(
        ode.OdeResidual.__call__, "floored_scale(max(abs(v) for v in values)", "floored_scale(max(v for v in values)"))
    assert _status(checker.api_controls) == "failed"


@pytest.mark.parametrize("where, old, new", [
    ("magnitude", "min(mpmath.mpf(1), size())", "max(mpmath.mpf(1), size())"),   # the old floor 1
    ("magnitude", "    if big >= 1:\n", "    if big >= 0:\n"),   # no floor below 1 ...
    ("magnitude", "return max(big, min(mpmath.mpf(1), size()))", "return big"),   # ... or none at all
    ("ode", "floored_scale(max(abs(v) for v in values)", "floored_scale(min(abs(v) for v in values)"),   # ode:158
])
def test_api_ode_scale_floor(monkeypatch, where, old, new):
    # x = 1e-30 e^t for x' = -x is false at its own size; x = e^t (cosh^2 - sinh^2 - 1) solves x'' = 0 up to rounding
    from symbt.proof import magnitude, ode
    if where == "ode":
        monkeypatch.setattr(ode.OdeResidual, "__call__", planted(ode.OdeResidual.__call__, old, new))
    else:   # the floor rule is shared with the screen: the ODE's claim must see it alone
        monkeypatch.setattr(ode, "floored_scale", planted(magnitude.floored_scale, old, new))
    assert _status(checker.api_controls) == "failed"


def test_domain_counterexample_shown_raw(monkeypatch):
    from symbt.proof import domain
    monkeypatch.setattr(domain, "_shown", lambda v: v)
    assert _status(checker.domain_controls) == "failed"


def test_domain_args_accepted(monkeypatch):
    # *args read as a parameter named "a": a ValueError about a missing variable instead of the TypeError
    from symbt.proof import domain
    real = domain._caller

    def lax(fn, what, names):
        try:
            return real(fn, what, names)
        except TypeError:
            return lambda point: fn(*point.values())
    monkeypatch.setattr(domain, "_caller", lax)
    assert _status(checker.domain_controls) == "failed"


@pytest.mark.parametrize("bug", ["const", "sqrt"])
def test_mutation_operators(monkeypatch, bug):
    from symbt.proof import mutation as m
    if bug == "const":      # -1 -> 0 (n + 1 for every n): a repeat of drop_term, silently lost
        op = m.OPERATORS._replace(change_const=m.Mutation("change_const", m.OPERATORS.change_const.query,
                                                          lambda e: [(f"{e} -> {e + 1}", e + 1)]))
    else:                   # the convention operator on powers other than 1/2
        op = m.OPERATORS._replace(convention=m.Mutation(
            "convention", lambda e: isinstance(e, sp.Pow) and e.exp != sp.Rational(1, 2),
            m.OPERATORS.convention.value))
    monkeypatch.setattr(checker_mutation, "mutants", lambda v: m.mutants(v, op))
    assert _status(checker_mutation.mutation_controls) == "failed"


def test_symbols_not_positive(monkeypatch):
    real = generating.GeneratingFunction.__init__

    def init(self, N):
        real(self, N)
        self.E = sp.symbols(f"E1:{N + 1}")
    generating.generating_function.cache_clear()
    monkeypatch.setattr(generating.GeneratingFunction, "__init__", init)
    try:
        assert _status(library.symbol_assumptions) == "failed"
    finally:
        generating.generating_function.cache_clear()


@pytest.mark.parametrize("bug", ["lstsq_stalls", "direction_jacobian"])
def test_inverse(monkeypatch, bug):
    from symbt.reference import inverse
    if bug == "lstsq_stalls":  # Gauss-Newton that stops where it starts: not a minimum (the swap of _newton for
        # _gauss_newton, symbt mutate's inverse:149, also fails, but only after minutes of line searches)
        monkeypatch.setattr(inverse, "_gauss_newton", lambda F, J, x0, tol, maxit=80: (list(x0), 0))
    else:                   # d(c_k/c_r)/dmu replaced by d/dlam0: a singular Jacobian
        real = inverse.flow_coefficients_jacobian
        monkeypatch.setattr(inverse, "flow_coefficients_jacobian",
                            lambda *a: [[row[0], row[0]] for row in real(*a)])
    assert _status(library_reference.inverse_round_trip) == "failed"


def test_angle_quadrant(monkeypatch):
    # the branch of u for cn u < 0 chosen by P <= 0 instead of P >= 0: u moves by -+4K, a period of sn and cn,
    # out of (-2K, 2K]
    from symbt.reference import elliptic as E
    real = E.global_u

    def wrong(p, q):
        u, m = real(p, q)
        K = mp.ellipk(m)
        return (u - 4 * K if u > K else u + 4 * K if u < -K else u), m
    monkeypatch.setattr(E, "global_u", wrong)
    assert _status(library_reference.angle_quadrants) == "failed"


@pytest.mark.parametrize("bug", ["stale_kept", "minmax"])
def test_emit_user_path(monkeypatch, bug):
    from symbt.codegen.user import files, printing
    if bug == "stale_kept":   # a file that exists is never rewritten
        real = files.atomic_write
        monkeypatch.setattr(files, "atomic_write", lambda path, text: None if path.exists() else real(path, text))
    else:                     # numpy's Min and Max printed the other way round
        monkeypatch.setitem(printing._MINMAX, "numpy", ("np.maximum", "np.minimum"))
    assert _status(library_codegen.emitted_user_functions) == "failed"


def test_guards_trace(monkeypatch):
    derive.sources.cache_clear()
    monkeypatch.setattr(derive, "disc", lambda t: sp.Mul(t - 2, t + 3, evaluate=False))
    try:
        assert _status(library_codegen.guard_sources) == "failed"
    finally:
        derive.sources.cache_clear()


def test_linear_shortcut_on_constants(monkeypatch):
    # the shortcut taken for degree 0 instead of 1: a constant equation has no two coefficients
    from symbt.symbolic import linear

    def wrong(eq, x):
        poly = sp.Poly(eq, x)
        if poly.degree() == 0:
            c1, c0 = poly.all_coeffs()
            return [sp.cancel(-c0 / c1)]
        return list(sp.solve(eq, x))
    monkeypatch.setattr(linear, "solve_linear", wrong)
    assert _status(library.linear_solutions) == "failed"


def test_dF_eta_itself(monkeypatch):
    # the implicit term skipped where d expr/d eta is 1 (generating:61's mutant): eta_1's own derivative is lost
    generating.generating_function.cache_clear()
    real = generating.implicit_derivative

    def wrong(expr, var, etas, mu_):
        if any(sp.diff(expr, e) == 1 for e in etas):
            return sp.diff(expr, var)
        return real(expr, var, etas, mu_)
    monkeypatch.setattr(generating, "implicit_derivative", wrong)
    try:
        assert _status(library.generating_derivatives.claims[0]) == "failed"
    finally:
        generating.generating_function.cache_clear()


def test_codegen_check_tolerance(monkeypatch):
    # a tolerance of 1e12 eps x condition: a function off by 1e-9 passes
    from symbt.codegen import verify
    monkeypatch.setattr(verify, "F64_TOL_ULPS", 1e12)
    assert _status(library_codegen.codegen_check_controls) == "failed"


def test_api_discrete_parameter(monkeypatch):
    # every nonzero exact remainder taken as a proof of falsity, also where a parameter is discrete
    from symbt.proof import ode
    real = ode.solves_ode

    def eager(*a, **k):
        v = real(*a, **k)
        if "left a nonzero remainder" in v.method:
            return verdict_module.Verdict(False, "proof", v.method, residual=v.residual, definite=True)
        return v
    monkeypatch.setattr(ode, "solves_ode", eager)
    assert _status(checker.api_controls) == "failed"


@pytest.mark.parametrize("bug", ["sample_range", "state_on_level"])
def test_angle_states(monkeypatch, bug):
    import math

    from symbt.reference import elliptic as E
    if bug == "sample_range":   # x drawn up to acosh(I2), past acosh(I2/2): the root is clipped to 0, p1 = p2
        def wrong(rng, *, x_sign, p_sign):
            I1, I2 = rng.uniform(-2, 2), rng.uniform(2.3, 9)
            x = x_sign * rng.uniform(0.03, 0.97) * math.acosh(I2)
            Pr = -p_sign * math.sqrt(max(I2 - 2 * math.cosh(x), 0.0))
            th1 = rng.uniform(-1, 1)
            return [E._fmt(I1 + Pr), E._fmt(I1 - Pr)], [E._fmt((th1 + x) / 2), E._fmt((th1 - x) / 2)]
        monkeypatch.setattr(E, "sample_state", wrong)
    else:                       # q1 = (theta1 - x)/2: q1 - q2 = 0
        real = E.state_on_level
        monkeypatch.setattr(E, "state_on_level", lambda I1, I2, x, th, s: (
            real(I1, I2, x, th, s)[0], [(th - x) / 2, (th - x) / 2]))
    assert _status(library_reference.angle_quadrants) == "failed"


def test_floor_from_one_is_equivalent(monkeypatch):
    # magnitude.floored_scale's `big >= 1` -> `big > 1` (seed 10's ode:159, now the one floor rule of the screen and
    # the ODE residual): at big == 1 exactly the mutant gives max(1, min(1, m)) = 1, big itself, for any size m
    # (size_or_inf never raises: a size that cannot be evaluated is inf); elsewhere both take the same branch.
    # x = e^t - 1 for x' = x + 1/2 at t = 0 has terms 1 and -1/2 (big exactly 1, residual 1/2); at t = -1 and 1 big
    # is below and above 1.  Control: the tie is exercised -- the mutant's branch with a floor of 2 halves it.
    from symbt.proof import magnitude, ode

    original = magnitude.floored_scale
    mutant = planted(original, "    if big >= 1:\n", "    if big > 1:\n")
    control = planted(original, "    if big >= 1:\n        return big\n    return max(big, min(mpmath.mpf(1), size()))",
                      "    if big > 1:\n        return big\n    return max(big, max(mpmath.mpf(2), size()))")
    values = [mp.mpf(0), mp.mpf("1e-30"), mp.mpf(1) / 2, mp.mpf(1), mp.mpf(2), mp.inf]
    for big in values:
        for m in values:
            assert mutant(big, lambda m=m: m) == original(big, lambda m=m: m)
    tt = sp.Symbol("t")
    X = sp.Function("x")
    r = ode.ode_residual(sp.Eq(X(tt).diff(tt), X(tt) + sp.Rational(1, 2)), sp.exp(tt) - 1)
    with mp.workdps(30):
        assert max(abs(v) for v in r._f(mp.mpf(0))[0]) == 1
        assert r(t=mp.mpf(0)) == mp.mpf(1) / 2
        expected = [r(t=t) for t in (mp.mpf(-1), mp.mpf(0), mp.mpf(1))]
        monkeypatch.setattr(ode, "floored_scale", mutant)
        assert [r(t=t) for t in (mp.mpf(-1), mp.mpf(0), mp.mpf(1))] == expected
        monkeypatch.setattr(ode, "floored_scale", control)
        assert r(t=mp.mpf(0)) == mp.mpf(1) / 4
