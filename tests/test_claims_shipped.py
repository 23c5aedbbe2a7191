"""The claims about what ships (scene ``shipped``, ``Hdiscr.routes``, ``codegen.orbit``): each passes on the
shipped routes and FAILS when a route is broken by a little (one output off by 1e-10 relative, a swapped branch,
a sign error in the built-in flow): what proves that they can fail."""
from __future__ import annotations

import time

import mpmath as mp
import numpy as np
import pytest

import symbt.numeric as numeric
from symbt.claims import REGISTRY, load_all
from symbt.claims import _shipped as sh

load_all()


def run(cid):
    return REGISTRY[cid].run()


def _bump(x, rel):
    """``x`` (an array or a list of numbers) with its first component times (1 + rel)."""
    if isinstance(x, np.ndarray):
        y = np.array(x, dtype=float, copy=True)
        y.reshape(-1)[0] *= 1 + rel
        return y
    y = list(x)
    with mp.workdps(60):
        y[0] = y[0] * (1 + mp.mpf(rel)) if isinstance(y[0], mp.mpf) else y[0] * (1 + rel)
    return y


def bumped_step(fn, rel):
    def wrapped(*a, **k):
        p, q = fn(*a, **k)
        return _bump(p, rel), q
    return wrapped


@pytest.mark.parametrize("cid", ["shipped.step.n2", "shipped.batch.n2", "shipped.mp.n2"])
def test_step_claims_pass_and_fail_on_a_perturbed_step(cid, monkeypatch):
    assert run(cid).status == "verified"
    rel = 1e-20 if cid == "shipped.mp.n2" else 1e-10       # mpmath at 30 digits: a 1e-20 error is gross
    monkeypatch.setattr(numeric, "bt_step", bumped_step(numeric.bt_step, rel))
    assert run(cid).status == "failed"


def test_batch_claim_catches_the_block_kernel_alone(monkeypatch):
    orig = numeric.bt_orbit

    def orbit(p, q, *a, **k):
        P, Q = orig(p, q, *a, **k)
        if np.ndim(p) == 2:                     # only ensembles: the block kernel's route
            P = P.copy()
            P[-1, :, 0] *= 1 + 1e-10
        return P, Q
    monkeypatch.setattr(numeric, "bt_orbit", orbit)
    out = run("shipped.batch.n2")
    assert out.status == "failed" and "route=ensemble (block kernel)" in out.counterexample["cell"]


def test_orbit_claim_fails_on_a_swapped_branch_and_on_a_small_drift(monkeypatch):
    assert run("shipped.orbit.n2").status == "verified"
    orig = numeric.bt_orbit
    monkeypatch.setattr(numeric, "bt_orbit", lambda *a, branch=1, **k: orig(*a, branch=-branch, **k))
    assert run("shipped.orbit.n2").status == "failed"

    def drift(p, q, *a, **k):
        P, Q = orig(p, q, *a, **k)
        if isinstance(P, np.ndarray) and np.ndim(p) == 1:
            P = P.copy()
            P[-1, 0] *= 1 + 1e-9
        return P, Q
    monkeypatch.setattr(numeric, "bt_orbit", drift)
    out = run("shipped.orbit.n2")
    assert out.status == "failed" and "orbit: fused kernel" in out.counterexample["cell"]


@pytest.mark.skipif(not sh.__name__ or __import__("importlib").util.find_spec("flint") is None,
                    reason="python-flint not installed")
def test_certified_claim_fails_when_an_enclosure_misses(monkeypatch):
    assert run("shipped.certified.n2").status == "verified"
    orig = numeric.bt_orbit

    def shifted(*a, **k):
        P, Q, Pr, Qr = orig(*a, **k)
        P = [list(r) for r in P]
        P[-1][0] = P[-1][0] + 10 * Pr[-1][0] + mp.mpf(10) ** -40
        return P, Q, Pr, Qr
    monkeypatch.setattr(numeric, "bt_orbit", shifted)
    assert run("shipped.certified.n2").status == "failed"


@pytest.mark.parametrize("cid, name", [("shipped.invariants.n2", "invariants"), ("shipped.phi.n2", "phi"),
                                       ("shipped.coefficients.n2", "flow_coefficients")])
def test_spectral_claims_pass_and_fail_on_a_perturbed_value(cid, name, monkeypatch):
    assert run(cid).status == "verified"
    orig = getattr(numeric, name)

    def wrong(*a, **k):
        out = orig(*a, **k)
        if isinstance(out, mp.mpf):
            return out * (1 + mp.mpf(10) ** -20)
        if isinstance(out, list):
            return _bump(out, 1e-20)
        return _bump(np.atleast_1d(out), 1e-10).reshape(np.shape(out))
    monkeypatch.setattr(numeric, name, wrong)
    assert run(cid).status == "failed"


def test_field_claim_fails_on_a_perturbed_field(monkeypatch):
    assert run("shipped.field.n2").status == "verified"
    orig = numeric.FlowField.__call__
    monkeypatch.setattr(numeric.FlowField, "__call__", lambda self, p, q: (_bump(orig(self, p, q)[0], 1e-10),
                                                                         orig(self, p, q)[1]))
    assert run("shipped.field.n2").status == "failed"


def test_emitted_closed_form_fails_on_a_perturbed_step(monkeypatch):
    from symbt.generated import toda2

    assert run("shipped.emitted.n2").status == "verified"
    monkeypatch.setattr(toda2, "bt_step", bumped_step(toda2.bt_step, 1e-10))
    assert run("shipped.emitted.n2").status == "failed"


def test_emitted_toda3_fails_only_at_the_wide_states():
    """Issue 21: the closed form of toda3 returned a wrong finite state at large |q_i - q_j| (the fix is another
    branch's).  Whatever the state of that fix, the moderate states pass: every failing cell is a wide one."""
    out = run("shipped.emitted.n3")
    bad = [c for c in out.cells if c["printed_holds"] < c["n"]]
    assert all(c["cell"].get("q") == "wide" for c in bad), bad
    assert out.status == ("failed" if bad else "verified")


def test_emitted_toda3_claim_fails_on_the_issue_answer(monkeypatch):
    """The wrong answer the issue reports (p~ = p at the state of issue 21) is caught."""
    from symbt.generated import toda3

    orig = toda3.bt_step

    def issue(p, q, lam0, mu, branch, **k):
        pt, qt = orig(p, q, lam0, mu, branch, **k)
        return (np.array(p, dtype=float), qt) if q[0] > 900 else (pt, qt)
    monkeypatch.setattr(toda3, "bt_step", issue)
    out = run("shipped.emitted.n3")
    assert out.status == "failed" and "q=wide" in out.counterexample["cell"]


def test_loop_form_claim(monkeypatch):
    from symbt.claims import shipped_emitted as se

    assert run("shipped.loop.n4").status == "verified"
    mod = se.emitted_module(4)
    monkeypatch.setattr(mod, "bt_step", bumped_step(mod.bt_step, 1e-10))
    assert run("shipped.loop.n4").status == "failed"


@pytest.mark.skipif(__import__("shutil").which("cc") is None and __import__("shutil").which("gcc") is None,
                    reason="no C compiler")
def test_c_target_claim(monkeypatch):
    from symbt.claims import shipped_emitted as se

    assert run("shipped.c.n2").status == "verified"
    orig = se.c_step

    def broken(N):
        call = orig(N)

        def wrong(*a):
            rc, pt, qt = call(*a)
            return rc, _bump(pt, 1e-10), qt
        return wrong
    monkeypatch.setattr(se, "c_step", broken)
    assert run("shipped.c.n2").status == "failed"
    monkeypatch.setattr(se, "c_compiler", lambda: None)
    out = run("shipped.c.n2")
    assert out.status == "skipped" and "no C compiler" in out.detail


def test_nomap_claim_fails_when_a_route_returns_a_state(monkeypatch):
    from symbt.claims import shipped_emitted as se

    st, b, (cond, decided) = se.nomap_states(2)[0]
    assert decided and cond == "opposite signs"                     # the state of issue 21
    orig = numeric.bt_step

    def silent(p, q, lam0, mu, *, branch=1, backend="auto", **k):   # a finite state where no map exists
        if backend == "numpy":
            return np.array(p, dtype=float), np.array(q, dtype=float)
        return orig(p, q, lam0, mu, branch=branch, backend=backend, **k)
    monkeypatch.setattr(numeric, "bt_step", silent)
    out = run("shipped.nomap")
    assert out.status == "failed"
    failing = {c["cell"]["route"] for c in out.cells if c["printed_holds"] < c["n"]}
    assert failing == {"bt_step (general path)", "batch"}, failing   # every other route raised


def test_flow_routes_claim_fails_fast_on_a_sign_error_in_the_builtin_route(monkeypatch):
    from symbt.reference import taylor

    assert run("Hdiscr.routes.n2").status == "verified"
    orig = taylor.hamilton_equations

    def wrong_sign(N, c, sign=1):
        eqs = orig(N, c, sign)
        return eqs[:N] + [{e: -v for e, v in P.items()} for P in eqs[N:2 * N]] + eqs[2 * N:]
    monkeypatch.setattr(taylor, "hamilton_equations", wrong_sign)
    t0 = time.perf_counter()
    out = run("Hdiscr.routes.n2")
    assert out.status == "failed" and time.perf_counter() - t0 < 60
    assert {c["cell"]["route"] for c in out.cells if c["printed_holds"] < c["n"]} == {"taylor"}
    assert all(c["printed_holds"] == 0 for c in out.cells)      # every sample of the built-in route fails


def test_builtin_flow_route_has_a_budget(monkeypatch):
    from symbt.claims import _flow

    monkeypatch.setattr(_flow, "TAYLOR_MAX_STEPS", 1)
    with pytest.raises(_flow.FlowBudgetExceeded):
        _flow.time_flow([3.0, -2.0], [0.0, 2.0], [1.0, 0.0], 3.0, route="taylor")   # G = H_0: a Toda flow


def test_codegen_orbit_bound_is_two_sided(monkeypatch):
    """A worse symbt.numeric orbit used to loosen the emitted orbit's own bound; now each is judged alone."""
    assert run("codegen.orbit.n2").status == "verified"
    orig = numeric.bt_orbit

    def worse(*a, **k):
        P, Q = orig(*a, **k)
        return P * (1 + 1e-7), Q
    monkeypatch.setattr(numeric, "bt_orbit", worse)
    assert run("codegen.orbit.n2").status == "failed"
    monkeypatch.undo()
    c = REGISTRY["codegen.orbit.n2"]
    assert c.run_with(c.parts().replace("printed", "scale", 1 + 1e-9)).status == "failed"


def test_tally_is_two_sided():
    st = ((0.1, 0.2), (0.0, 0.3), 4.0, 0.5)
    t = sh.Tally()
    t.add("r", {"branch": 1}, st, 1, 0.5, allowed=1e-3)           # within a bound that allows 1e-3: uninformative
    assert t.outcome(method="m", printed="s").status == "inconclusive"
    t = sh.Tally()
    t.add("r", {"branch": 1}, st, 1, 0.5, agree=1e-20)            # the reference disagrees with itself
    assert t.outcome(method="m", printed="s").status == "failed"
    t = sh.Tally()
    t.add("r", {"branch": 1}, st, 1, 0.5, allowed=1e-12, agree=1e-60)
    assert t.outcome(method="m", printed="s").status == "verified"


@pytest.mark.parametrize("cid", ["shipped.step.n2", "shipped.invariants.n2", "shipped.phi.n2", "shipped.emitted.n2",
                                 "Hdiscr.routes.n2"])
def test_statement_mutants_are_killed(cid):
    """symbt mutate's operators on the claims' parts (scale negated or perturbed by 1e-6; Theorem 2's Phi, upper
    limit and time): every mutant fails the claim."""
    from symbt.engine.mutate import mutate_claim

    rec = mutate_claim(REGISTRY[cid], limit=4, seed=1).to_dict()
    assert rec["mutants"] >= 2 and not rec["survivors"], rec
