"""The claims of ``symbt/claims/shipped_rules.py`` kill the bugs they were written for, and the equivalence proof of
``mutants-equivalent.toml``'s ``kernels:236`` (issue 21, item 4; docs/mutation.md, branch ``killnum2``).

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own text, with
:func:`planting.planted` -- and requires the claim to fail; unpatched, every claim verifies.
"""
from __future__ import annotations

import ast
import inspect
import linecache
import textwrap

import numpy as np
import pytest
from planting import planted

from symbt.claims import REGISTRY, load_all
from symbt.numeric.float64 import kernels, rows

load_all()

RULES = ["paths.ball_prec.n3", "paths.batch_range.n3", "paths.enclosure_poly.n3", "paths.escalation.n3",
         "paths.existence_iv.n3", "paths.failure_text.n3", "paths.idle_rows.n3", "paths.mixed_block.n3",
         "paths.range_edge.n2", "paths.zero_radius.n3"]


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.mark.parametrize("cid", RULES)
def test_unpatched_verified(cid):
    if cid in ("paths.ball_prec.n3", "paths.enclosure_poly.n3", "paths.zero_radius.n3"):
        pytest.importorskip("flint")
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- paths.escalation

def test_escalation_returns_the_less_precise_run(monkeypatch):
    # mutant rows:94 (sign): the second run at dps - 20 instead of dps + 20.  The two runs still agree to
    # 2**-64 s, so the documented agreement holds, but the returned run is the less precise one: q~_1 (~1e-23)
    # comes back wrong in its 11th digit
    monkeypatch.setattr(rows, "escalate_rows", planted(rows.escalate_rows,
                                                       "branch, dps + 20)", "branch, dps - 20)"))
    assert status("paths.escalation.n3") == "failed"


# --------------------------------------------------------------------------- paths.ball_prec

def test_ball_schedule_one_finite_excess_from_its_index(monkeypatch):
    # mutant certified:177 (constant): `extra = finite[-1][1] + _MARGIN` -> `finite[-1][0] + _MARGIN` (the step
    # number instead of the excess): the second pass at the floor p + p/4 + 32 = 112 bits instead of 229
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import certified

    monkeypatch.setattr(certified, "_next_prec", planted(certified._next_prec, "extra = finite[-1][1] + _MARGIN",
                                                         "extra = finite[-1][0] + _MARGIN"))
    assert status("paths.ball_prec.n3") == "failed"


def test_ball_schedule_without_the_margin(monkeypatch):
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import certified

    monkeypatch.setattr(certified, "_next_prec", planted(certified._next_prec, "extra = finite[-1][1] + _MARGIN",
                                                         "extra = finite[-1][1]"))
    assert status("paths.ball_prec.n3") == "failed"


# --------------------------------------------------------------------------- equivalent: kernels:236

def _planted_with_source(func, old: str, new: str):
    """As :func:`planting.planted`, with the edited source registered in ``linecache`` under its own name, so that
    ``inspect.getsource`` of the result -- which ``core.inline`` reads to write a hook inline -- is the mutant's."""
    src = textwrap.dedent(inspect.getsource(func))
    assert src.count(old) == 1, (func.__name__, old)
    text = src.replace(old, new)
    name = f"<planted {func.__module__}.{func.__name__}>"
    linecache.cache[name] = (len(text), None, text.splitlines(True), name)
    ns: dict = {}
    exec(compile(text, name, "exec"), func.__globals__, ns)
    return ns[func.__name__]


def _calls(fn, name: str) -> list[ast.Call]:
    tree = ast.parse(textwrap.dedent(inspect.getsource(fn)))
    return [n for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
            and n.func.id == name]


def test_decided_condition_slot_negative_index_is_equivalent():
    # mutants-equivalent.toml, kernels:236 (235 before the docstring grew a line): `tt[i + 2] = k` ->
    # `tt[i - 2] = k` in the float64 hook `decided`.
    # (1) The hook is called only by the fused step's `slopes`, with slopes' own `i`, and `slopes` only by `step`,
    # with i = 0 and i = 1; (2) every tt the float64 step receives has 4 entries (kernels.orbit's np.empty(4), which
    # python_orbit runs on lists of 4 and numba compiles); so i - 2 is -2 or -1, and tt[-2], tt[-1] are tt[2], tt[3]
    # (numpy, list and numba indexing wrap a negative index once).  (3) Run: python_orbit with the mutated hook
    # equals python_orbit bit for bit (statuses included) on every sign cell's state and the band-edge states
    # (the sharp tier runs there) and states whose slope differences cancel (the stored condition decides there),
    # three steps.
    from symbt.claims._shipped import ship_cells
    from symbt.claims.shipped_paths import edge_states
    from symbt.numeric.core import fused

    decided = _calls(fused.slopes, "decided")
    assert len(decided) == 1 and isinstance(decided[0].args[4], ast.Name) and decided[0].args[4].id == "i"
    assert {"i"} == {a.arg for a in ast.parse(textwrap.dedent(inspect.getsource(fused.slopes))).body[0].args.args
                     if a.arg == "i"}
    slopes = _calls(fused.step, "slopes")
    assert sorted(c.args[8].value for c in slopes) == [0, 1]
    assert not _calls(fused.step, "decided")
    assert "tt = np.empty(4)" in inspect.getsource(kernels.orbit)
    assert [k for k, v in kernels.HOOKS.items() if v is kernels._decided] == ["decided"]

    mutant = _planted_with_source(kernels._decided, "tt[i + 2] = k", "tt[i - 2] = k")
    assert "tt[i - 2] = k" in inspect.getsource(mutant)
    orbit_mutated = kernels.python_orbit_with({"decided": mutant})
    states = [(st, b) for N in (3, 5) for _, st, b in ship_cells(N, 1)] + [(st, b) for _, st, b in edge_states()]
    # lam1 ~ lam2 ~ -p_j at a large neighbour distance: the slope difference u_j - w_j cancels, so the read-out
    # test `trusted` reads the stored condition and decides between finishing and handing back (ILLCOND) -- states
    # where the value in tt[2], tt[3] matters (with `tt[i + 2] = 0.0 * k` planted instead, 8 of them finish)
    states += [(((-20.0, 10.0, 1.0), (0.0, 30.0, 3.0), l0, m), b) for l0 in (20.0 - 1e-5, -10.0 - 1e-7, -1.0 + 1e-6)
               for m in (1e-5, -1e-5, 1e-7, -1e-7) for b in (1, -1)]
    seen = set()
    for (p, q, l0, m), b in states:
        N, n = len(p), 3
        runs = []
        for orbit in (kernels.python_orbit, orbit_mutated):
            P, Q = np.full((n + 1, N), -1.0), np.full((n + 1, N), -1.0)
            code = orbit(np.array(p), np.array(q), l0 + m, l0 - m, 2 * m, b, n, 1, kernels.ANCHOR, P, Q)
            runs.append((code, P, Q))
        (c0, P0, Q0), (c1, P1, Q1) = runs
        assert c0 == c1
        assert np.array_equal(P0, P1, equal_nan=True) and np.array_equal(Q0, Q1, equal_nan=True)
        seen.add(c0)
    assert {kernels.OK, 5} <= seen         # finished states and states handed back (ILLCOND) both ran


# --------------------------------------------------------------------------- paths.range_edge

def test_block_kernel_range_edge_inclusive(monkeypatch):
    # mutant kernels_block:118 (compare): `abs(a_) > 1e-290` -> `abs(a_) >= 1e-290`: the block kernel finishes the
    # state at the edge, the fused kernel gives it back
    from symbt.numeric.float64 import kernels_block

    monkeypatch.setattr(kernels_block, "_slopes", planted(kernels_block._slopes, "and (abs(a_) > 1e-290 or",
                                                          "and (abs(a_) >= 1e-290 or"))
    assert status("paths.range_edge.n2") == "failed"


def test_fused_kernel_range_edge_inclusive(monkeypatch):
    # the same slip in the fused kernel's hook `in_range` (python_orbit writes the hooks inline when it is built:
    # rebuilt with the planted hook)
    hook = _planted_with_source(kernels._in_range, "(abs(A) > 1e-290 or", "(abs(A) >= 1e-290 or")
    monkeypatch.setattr(kernels, "python_orbit", kernels.python_orbit_with({"in_range": hook}))
    assert status("paths.range_edge.n2") == "failed"


def test_block_kernel_range_edge_shifted(monkeypatch):
    # the limit moved by a factor 2 (an entry must exceed 2e-290): the state one ulp inside is given back
    from symbt.numeric.float64 import kernels_block

    monkeypatch.setattr(kernels_block, "_slopes", planted(kernels_block._slopes, "and (abs(a_) > 1e-290 or",
                                                          "and (abs(a_) > 2e-290 or"))
    assert status("paths.range_edge.n2") == "failed"


def test_block_kernel_second_entry_tolerance(monkeypatch):
    # mutant kernels_block:118 (tolerance): `abs(b_) > 1e-290` -> `abs(b_) > 1e-145`: the state whose first row is
    # (0, ~4e-271) is given back by the block kernel alone
    from symbt.numeric.float64 import kernels_block

    monkeypatch.setattr(kernels_block, "_slopes", planted(kernels_block._slopes, "or abs(b_) > 1e-290))",
                                                          "or abs(b_) > 1e-145))"))
    assert status("paths.range_edge.n2") == "failed"


def test_fused_kernel_range_edge_signed(monkeypatch):
    # mutant kernels:214 (abs): `abs(A) > 1e-290` -> `A > 1e-290`: the fused kernel gives the state one ulp inside
    # (A < 0) back
    hook = _planted_with_source(kernels._in_range, "(abs(A) > 1e-290 or", "(A > 1e-290 or")
    monkeypatch.setattr(kernels, "python_orbit", kernels.python_orbit_with({"in_range": hook}))
    assert status("paths.range_edge.n2") == "failed"


def test_escalation_second_run_on_the_previous_row(monkeypatch):
    # mutant rows:94 (index-shift): the second run on `qa[k - 1]`: with one row that is the row itself (qa[-1]), in
    # the two-row call the neighbour's positions -- the runs never agree, the row ends RANGE
    monkeypatch.setattr(rows, "escalate_rows", planted(rows.escalate_rows, "(pa[k], qa[k], l0, m, branch, dps + 20",
                                                       "(pa[k], qa[k - 1], l0, m, branch, dps + 20"))
    assert status("paths.escalation.n3") == "failed"


# --------------------------------------------------------------------------- equivalent: the seed-2 sample

def _states(N: int) -> list[tuple[np.ndarray, np.ndarray, float, float]]:
    """Every sign cell's state (both branches' states), states without a real map, a state whose trace at lam2 is
    exactly 0 (p = (1, 2, 0...), q = 0, lam2 = 0: tr = a_1 a_2 - r_1 - r_2 = 2 - 2 at N = 2), and states far from
    the spectrum (|tr| ~ 1e70 N: the block kernel's power-of-two rescaling runs)."""
    from symbt.claims._shipped import ship_cells
    from symbt.claims.shipped_emitted import nomap_states

    out = [(np.array(st[0]), np.array(st[1]), st[2], st[3]) for _, st, _ in ship_cells(N, 1)]
    out += [(np.array(st[0]), np.array(st[1]), st[2], st[3]) for st, _, _ in nomap_states(N)]
    if N == 2:
        out.append((np.array([1.0, 2.0]), np.zeros(2), 1.5, 1.5))          # lam1 = 3, lam2 = 0: tr L(lam2) = 0
    out += [(np.linspace(-1.0, 1.0, N), np.linspace(0.0, 0.5, N), s * 1e70, 3.0) for s in (1, -1)]
    return out


def _block_runs(slopes_fn, run_block_fn, states, b: int):
    """The block kernel (plain Python) on ``states`` as one block, with ``_slopes``/``run_block`` as given."""
    from symbt.numeric.float64 import kernels_block

    M, N = len(states), states[0][0].size
    P0, Q0 = np.array([s[0] for s in states]), np.array([s[1] for s in states])
    l0, m = np.array([s[2] for s in states]), np.array([s[3] for s in states])
    P, Q, st = np.full((3, M, N), -1.0), np.full((3, M, N), -1.0), np.zeros(M, np.int64)
    with np.errstate(all="ignore"):
        old = kernels_block._slopes
        kernels_block._slopes = slopes_fn
        try:
            run_block_fn(P0, Q0, l0 + m, l0 - m, 2.0 * m, b, 2, 1, kernels.ANCHOR, P, Q, st, 0, M)
        finally:
            kernels_block._slopes = old
    return st, P, Q


def _same_block_runs(mutant_slopes=None, mutant_run_block=None) -> set:
    from symbt.numeric.float64 import kernels_block

    seen = set()
    for N in (2, 3, 5):
        for b in (1, -1):
            states = _states(N)
            st0, P0, Q0 = _block_runs(kernels_block._slopes, kernels_block.run_block, states, b)
            st1, P1, Q1 = _block_runs(mutant_slopes or kernels_block._slopes,
                                      mutant_run_block or kernels_block.run_block, states, b)
            assert np.array_equal(st0, st1)
            ok = st0 == 0
            assert np.array_equal(P0[:, ok], P1[:, ok]) and np.array_equal(Q0[:, ok], Q1[:, ok])
            seen |= set(st0.tolist())
    return seen


def test_block_rescale_loop_entered_when_nothing_is_big_is_equivalent():
    # mutants-equivalent.toml, kernels_block:99: `if big > 0:` -> `if big >= 0:`.  `big` counts the members k with
    # `Ab[0, k] > _BIG or Ab[1, k] > _BIG`, and the loop it guards shrinks exactly those members (the same test, the
    # same Ab, nothing written in between); with big == 0 no member passes it, so the loop writes nothing.  Checked:
    # the guard and the loop's test are the same expression, and blocks of every sign cell's state, no-map states
    # and states far from the spectrum (the rescaling runs) step alike, statuses and states bit for bit.
    from symbt.numeric.float64 import kernels_block

    src = inspect.getsource(kernels_block._slopes)
    assert src.count("Ab[0, k] > _BIG or Ab[1, k] > _BIG") == 2
    mutant = planted(kernels_block._slopes, "        if big > 0:", "        if big >= 0:")
    assert {0} < _same_block_runs(mutant_slopes=mutant)


def test_block_opposite_traces_at_a_zero_trace_is_equivalent():
    # mutants-equivalent.toml, kernels_block:255: `(t2[k] < 0.0)` -> `(t2[k] <= 0.0)` in the opposite-traces test.
    # The two differ only at t2[k] == 0 (or -0.0), and the test runs only where st[k] == OK after both slopes calls:
    # there the second call found `disc > 0.0`, disc = (t2 - two) (t2 + two) with two = 2 sc >= 0, which is
    # -two**2 <= 0 at t2 = 0 -- so t2 != 0 wherever the test runs.  Checked on the states above, with one whose
    # trace at lam2 is exactly 0 (status TRACE2 either way).
    from symbt.numeric.float64 import kernels_block

    mutant = planted(kernels_block.run_block, "(t1[k] < 0.0) != (t2[k] < 0.0)", "(t1[k] < 0.0) != (t2[k] <= 0.0)")
    assert {0, 2} <= _same_block_runs(mutant_run_block=mutant)


def test_float_status_opposite_traces_at_a_zero_trace_is_equivalent():
    # mutants-equivalent.toml, step:314: `opp = (S1.t < 0) != (S2.t < 0)` -> `(S2.t <= 0)` in float_status.  They
    # differ only where S2.t is 0 (or -0.0); there S2.trace_ok = (t - two) (t + two) = -two**2 <= 0, so ~t2 holds,
    # and the where-chain (the last np.where wins) applies opp's POSITIVITY before the codes of ~t2, ~t1 and ill_t:
    # TRACE2 or ILLCOND, never opp's POSITIVITY; opp is read nowhere else.  Checked: that order in the source, and
    # float_status on one step_core batch of the states above (the zero trace included) alike.
    from symbt.numeric.core import step as step_module
    from symbt.numeric.core.context import FLOAT

    tree = ast.parse(textwrap.dedent(inspect.getsource(step_module.float_status)))
    chain = [ast.unparse(n.value) for n in ast.walk(tree) if isinstance(n, ast.Assign)
             and getattr(n.targets[0], "id", "") == "out" and "np.where" in ast.unparse(n.value)]
    firsts = [c.split("(", 1)[1].split(",", 1)[0] for c in chain]       # the condition of each np.where, in order
    assert firsts[-3:] == ["opp", "t2", "t1"], chain                    # opp, then t2, t1 override it
    last = tree.body[0].body[-1]                                         # float_status' own return
    assert isinstance(last, ast.Return) and ast.unparse(last.value).startswith("np.where(ill_t, ILLCOND, out)")
    assert sum(isinstance(n, ast.Name) and n.id == "opp" for n in ast.walk(tree)) == 2     # set once, read once
    mutant = planted(step_module.float_status, "(S1.t < 0) != (S2.t < 0)", "(S1.t < 0) != (S2.t <= 0)")
    seen = set()
    for N in (2, 3, 5):
        states = _states(N)
        P = [np.array([s[0][j] for s in states]) for j in range(N)]
        Q = [np.array([s[1][j] for s in states]) for j in range(N)]
        l0, m = np.array([s[2] for s in states]), np.array([s[3] for s in states])
        for b in (1, -1):
            with np.errstate(all="ignore"):
                Pn, Qn, aux = step_module.step_core(FLOAT, P, Q, l0, m, b, check_real=False)
                a, c = step_module.float_status(aux, Pn, Qn), mutant(aux, Pn, Qn)
            assert np.array_equal(a, c)
            seen |= set(a.tolist())
    assert {0, 2} <= seen


def test_fused_kernel_hook_range_edge_signed(monkeypatch):
    # mutant kernels:214 (abs) in the hook itself (HOOKS["in_range"], which the claim also calls directly: the
    # line map cannot see an inlined hook run, so the claim runs it as a function too)
    hook = _planted_with_source(kernels._in_range, "(abs(A) > 1e-290 or", "(A > 1e-290 or")
    monkeypatch.setitem(kernels.HOOKS, "in_range", hook)
    assert status("paths.range_edge.n2") == "failed"


# --------------------------------------------------------------------------- paths.idle_rows

def test_idle_rows_first_row_stepped(monkeypatch):
    # mutant rows:203 (constant): `idx_all = idx_all[:0]` -> `idx_all[:1]`: with a scalar mu = 0 the first row is
    # stepped -- at lam0 inside a band it has no real map, and the identity raises NoRealMapError
    monkeypatch.setattr(rows, "float_rows_step", planted(rows.float_rows_step, "idx_all = idx_all[:0]",
                                                         "idx_all = idx_all[:1]"))
    assert status("paths.idle_rows.n3") == "failed"


# --------------------------------------------------------------------------- paths.failure_text

def test_failure_text_ellipsis_inverted(monkeypatch):
    # mutant orbit:295 (branch): `", ..." if len(where) > 5 else ""` inverted
    from symbt.numeric.float64 import orbit

    monkeypatch.setattr(orbit, "raise_for_status", planted(orbit.raise_for_status, '", ..." if len(where) > 5',
                                                           '", ..." if not (len(where) > 5)'))
    assert status("paths.failure_text.n3") == "failed"


# --------------------------------------------------------------------------- paths.batch_range

def test_batch_range_test_reads_the_minimum_only(monkeypatch):
    # mutant monodromy:59 (min-max): `max(np.max(d), -np.min(d))` -> `max(np.min(d), -np.min(d))`: a batch whose
    # largest difference is positive and past 700 is stepped (exp(701) is still a finite double)
    from symbt.numeric.core import monodromy
    from symbt.numeric.flow import invariants, phi

    # (the range test takes every site's span in two reductions now: the same mutant on that form)
    mutant = planted(monodromy.neighbour_ratios, "np.maximum(re.max(axis=1), -re.min(axis=1))",
                     "np.maximum(re.min(axis=1), -re.min(axis=1))")
    for module in (invariants, phi):
        monkeypatch.setattr(module, "neighbour_ratios", mutant)
    assert status("paths.batch_range.n3") == "failed"


# --------------------------------------------------------------------------- paths.mixed_block

def test_block_condition_tracked_on_the_previous_member(monkeypatch):
    # mutant kernels_block:83 (index-shift): `Kn[k] = cn` -> `Kn[k - 1] = cn`: a member's cancellation factor lands
    # on its neighbour -- invisible in a block of similar members (paths.threshold's scans), 13 of 128 members
    # decided differently when the paper's and the mirror's scans are interleaved
    from symbt.numeric.float64 import kernels_block

    monkeypatch.setattr(kernels_block, "_slopes", planted(kernels_block._slopes, "                Kn[k] = cn",
                                                          "                Kn[k - 1] = cn"))
    assert status("paths.mixed_block.n3") == "failed"


# --------------------------------------------------------------------------- paths.existence_iv

def test_existence_interval_sign_of_a_negative_interval(monkeypatch):
    # mutant existence:52 (compare): `if x.b < 0:` -> `if x.b > 0:`: an interval below 0 is undecided
    from symbt.numeric.float64 import existence

    monkeypatch.setattr(existence, "_sign", planted(existence._sign, "if x.b < 0:", "if x.b > 0:"))
    assert status("paths.existence_iv.n3") == "failed"


# --------------------------------------------------------------------------- paths.enclosure_poly

def test_enclosure_polynomial_site_shifted(monkeypatch):
    # mutant lohner_checks:214 (index-shift): `arb_poly([pb[j], 1])` -> `pb[j + 1]` (uncovered before)
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "invariant_enclosures", planted(
        lohner_checks.invariant_enclosures, "a = arb_poly([pb[j], 1])", "a = arb_poly([pb[j + 1], 1])"))
    assert status("paths.enclosure_poly.n3") == "failed"


# --------------------------------------------------------------------------- paths.zero_radius

def test_zero_radius_logged_as_plus_infinity(monkeypatch):
    # mutant lohner:378 (unary-minus): `_lograd`'s `-math.inf` for a zero radius -> `math.inf`: invisible to the
    # growth fit (both infinities are dropped), visible in the record of an orbit whose radius stays 0
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner, "_lograd", planted(lohner._lograd, "else -math.inf", "else math.inf"))
    assert status("paths.zero_radius.n3") == "failed"
