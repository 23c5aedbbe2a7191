"""The checker checked (issue 21, item 3).

1. The decider, the numeric screen, the exact layer and the cell machinery are fed statements that are
   false *by a little* -- a near-miss transcendental identity, an identity wrong by ``1e-20 x``, a
   perturbation at ``1e-20`` relative, a statement false in exactly one cell of each kind (sign,
   choice, regime) -- and each must come out false: not holding, not inconclusive, with a
   counterexample.  The screen's tolerance is pinned to its working precision from both sides, so a
   loosened tolerance (the issue's ``1e-42 -> 1e-2``) fails here; a test shows it on a mutated copy
   of the screen, and that the claim ``newkmu.screen`` of ``symbt verify`` fails with it.
2. The scope sentences of Zullo's errata (``newkmu``, ``x.newkmu``), generated from the claims' cell
   tables, are compared with cell truth computed *independently*: a sampler written here (other
   ranges, other seeds, the trace from the polynomial of :mod:`symbt.reference.trace`), the two
   sides of the erratum evaluated here with plain mpmath, a verdict per cell, and the sentence must
   name exactly those cells.  A planted bug, "every cell sampled on branch +1", makes it fail.
"""
from __future__ import annotations

import random
import re
import sys
import types
from pathlib import Path

import mpmath as mp
import pytest
import sympy as sp

import symbt
from symbt.claims import load_all
from symbt.proof import CellTable, Domain, choice, decide, regime, sign
from symbt.proof import decider as decider_module
from symbt.proof.exact import exact_zero
from symbt.proof.screen import screen
from symbt.reference.literal import literal_step
from symbt.reference.trace import trace, trace_gradient

x = sp.Symbol("x", real=True)
xp = sp.Symbol("xp", positive=True)
eta, mu, w = sp.symbols("eta mu w", real=True)
q1, q2 = sp.symbols("q1 q2", real=True)
TINY = sp.Integer(10) ** -20


def refuted(d) -> bool:
    """False, decided (not 'cannot tell'), and with a counterexample."""
    return not d.holds and not d.inconclusive and bool(d.counterexample)


# --------------------------------------------------------------------------- near misses for the decider

def near_misses() -> dict:
    """name -> Verdict for statements that are false by a little (all must be refuted)."""
    series = sum((-1) ** (k + 1) * (xp / 40) ** k / k for k in range(1, 21))   # log(1 + y) to y^20, y < 0.08
    return {
        "sin x vs 1.001 sin x": decide(sp.sin(x), sp.Rational(1001, 1000) * sp.sin(x)),
        "sin x vs 1.001 sin x (screen only)": decide(sp.sin(x), sp.Rational(1001, 1000) * sp.sin(x), exact=False),
        "log(1 + x/40) vs its series to order 20": decide(sp.log(1 + xp / 40), series),
        "sin^2 + cos^2 vs 1 + 1e-20 x": decide(sp.sin(x) ** 2 + sp.cos(x) ** 2, 1 + TINY * x),
        "exp(q1) exp(q2) vs exp(q1 + q2) (1 + 1e-20)": decide(sp.exp(q1) * sp.exp(q2), sp.exp(q1 + q2) * (1 + TINY)),
        "x^2 - 1 vs (x-1)(x+1) + 1e-20 x": decide(x ** 2 - 1, (x - 1) * (x + 1) + TINY * x),
        "(eta-mu)(eta+mu) vs w (1 + 1e-20) mod eta^2 = mu^2 + w":
            decide((eta - mu) * (eta + mu), w * (1 + TINY), relations={eta: eta ** 2 - mu ** 2 - w}),
        "acosh(x/2 + 2) vs log(...) (1 + 1e-20)":
            decide(sp.acosh(xp / 2 + 2), sp.log(xp / 2 + 2 + sp.sqrt((xp / 2 + 2) ** 2 - 1)) * (1 + TINY)),
        "a matrix with one entry off by 1e-20":
            decide(sp.Matrix([[sp.sin(2 * x), 1], [sp.exp(x), x]]),
                   sp.Matrix([[2 * sp.sin(x) * sp.cos(x), 1], [sp.exp(x) * (1 + TINY), x]])),
    }


def accepted_near_misses() -> list[str]:
    return [name for name, d in near_misses().items() if not refuted(d)]


def test_near_misses_are_refuted():
    assert accepted_near_misses() == []


def test_residuals_of_near_misses_are_the_planted_errors():
    # two-sided: the residual reported is the error planted, not just "something nonzero"
    d = decide(sp.sin(x), sp.Rational(1001, 1000) * sp.sin(x), exact=False)
    assert 1e-6 < d.residual <= 1.0001e-3
    d = decide(sp.sin(x) ** 2 + sp.cos(x) ** 2, 1 + TINY * x)
    assert 1e-22 < d.residual < 4e-20
    assert d.evidence == "sampled" and "numeric" in d.method


def test_the_exact_layer_refutes_tiny_rational_differences_definitely():
    zero, method, definite = exact_zero(sp.expand((x - 1) * (x + 1) + TINY * x - (x ** 2 - 1)), {})
    assert zero is False and definite
    d = decide(x ** 2 - 1, (x - 1) * (x + 1) + TINY * x)
    assert d.evidence == "proof" and d.definite and not d.holds
    zero, _, _ = exact_zero(sp.expand((eta - mu) * (eta + mu) - w * (1 + TINY)), {eta: eta ** 2 - mu ** 2 - w})
    assert zero is False


@pytest.mark.parametrize("digits", [20, 30, 50])
def test_the_screen_tolerance_follows_its_working_precision(digits):
    # an error 100x the tolerance 10^-(digits-8) is refuted; one far below the working precision is not:
    # so the tolerance lies in (10^-(digits+5), 10^-(digits-10)) at every precision -- a fixed 1e-2 (or 1e-42) fails
    above = sp.Integer(10) ** -(digits - 10)
    below = sp.Integer(10) ** -(digits + 5)
    assert refuted(decide(sp.sin(x), sp.sin(x) * (1 + above), exact=False, digits=digits))
    assert decide(sp.sin(x), sp.sin(x) * (1 + below), exact=False, digits=digits).holds
    r = screen(sp.sin(x), sp.sin(x) * (1 + above), {}, digits, 4, 5, {})
    assert r.status == "false" and r.point


# --------------------------------------------------------------------------- a loosened screen is noticed

def mutated_screen(old: str, new: str) -> types.ModuleType:
    """A copy of :mod:`symbt.proof.screen` with ``old`` replaced by ``new`` in its source."""
    import symbt.proof.screen as real

    src = Path(real.__file__).read_text()
    assert src.count(old) == 1, old
    mod = types.ModuleType("symbt.proof._screen_mutant")
    mod.__package__ = "symbt.proof"
    mod.__file__ = real.__file__
    sys.modules[mod.__name__] = mod      # dataclasses look their module up
    try:
        exec(compile(src.replace(old, new), real.__file__, "exec"), mod.__dict__)
    finally:
        del sys.modules[mod.__name__]
    return mod


LOOSE = ("tol = mpmath.mpf(10) ** (-(digits - 8))", "tol = mpmath.mpf(10) ** -2")


def test_a_loosened_screen_tolerance_is_caught(monkeypatch):
    monkeypatch.setattr(decider_module, "screen", mutated_screen(*LOOSE).screen)
    assert decide(sp.sin(x), sp.Rational(1001, 1000) * sp.sin(x)).holds      # the symptom
    assert "sin x vs 1.001 sin x" in accepted_near_misses()                  # ... which the tests above see
    load_all()
    [r] = symbt.verify(["newkmu.screen"], use_cache=False, budget=None)      # ... and so does symbt verify
    assert r.status == "failed" and "tolerance" in r.outcome.detail


def test_newkmu_screen_goes_through_the_screen():
    load_all()
    [r] = symbt.verify(["newkmu.screen"], use_cache=False, budget=None)
    assert r.status == "verified" and r.outcome.evidence == "sampled"
    assert "numeric screen" in r.outcome.detail and r.outcome.method.startswith("numeric: mpmath 50 digits")


# --------------------------------------------------------------------------- the cell machinery

EPS = mp.mpf("1e-20")


def _off(bad: bool):
    return 1 + EPS if bad else 1


def one_bad_cell_tables() -> dict:
    """name -> (CellTable, the one cell that is false by 1e-20 relative), one per kind of split."""
    dom = Domain({"x": (-2, 2)}, where=lambda x: abs(x) > 0.05, seed=11)
    by_sign = dom.evaluate(sign("x"), printed=lambda x: (mp.exp(x) * _off(x < 0), mp.exp(x)), dps=40)
    by_choice = dom.evaluate(sign("x"), choice("b", (1, -1)),
                             printed=lambda x, b: (b * mp.exp(x) * _off(x > 0 and b == -1), b * mp.exp(x)), dps=40)
    size = regime("size", lambda x: "small" if abs(x) < 1 else "large", ("small", "large"))
    by_regime = dom.evaluate(size, printed=lambda x: (mp.sin(x) * _off(abs(x) >= 1), mp.sin(x)), dps=40)
    return {"sign": (by_sign, "{x<0}"), "choice": (by_choice, "{x>0, b=-1}"), "regime": (by_regime, "{size=large}")}


def misjudged_cells() -> list[str]:
    bad = []
    for kind, (table, cell) in one_bad_cell_tables().items():
        v = table.verdict()
        fails = re.search(r"fails in (.*?)(;|$)", table.scope())
        if v.holds or v.inconclusive or table.printed_holds_everywhere() or not fails or fails.group(1) != cell:
            bad.append(f"{kind}: {table.scope()}")
    return bad


def test_a_statement_false_in_one_cell_only_is_false_there_and_only_there():
    assert misjudged_cells() == []
    table, cell = one_bad_cell_tables()["choice"]
    out = symbt.judge(table, printed="b e^x = b e^x")
    assert out.status == "failed" and out.counterexample["cell"] == cell


def test_one_sample_just_above_the_tolerance_makes_its_cell_partial():
    t = CellTable(tol=1e-40)
    for k in range(16):
        t.add({"branch": 1}, printed=1e-39 if k == 7 else 0.0)
        t.add({"branch": -1}, printed=0.0)
    assert not t.printed_holds_everywhere() and not t.verdict().holds
    assert t.scope() == "printed statement holds exactly in cells {branch=-1} and holds at some samples of " \
                        "{branch=+1} (15/16)"


def test_a_choice_sampled_on_one_value_is_caught(monkeypatch):
    # the planted bug: every point gets the first value of each choice (the cell label is kept)
    real = Domain.sample

    def first_choice_only(self, *splits, **kw):
        firsts = {s.name: s.values[0] for s in splits if s.kind == "choice"}
        return [(cell, {**pt, **firsts}) for cell, pt in real(self, *splits, **kw)]

    monkeypatch.setattr(Domain, "sample", first_choice_only)
    assert any(m.startswith("choice") for m in misjudged_cells())


# --------------------------------------------------------------------------- scope sentences vs independent truth

def _clear_claim_caches():
    """The claims memoise their samples (functools.cache); a planted bug must not leak in or out."""
    for name, mod in list(sys.modules.items()):
        if name.startswith("symbt.claims"):
            for obj in vars(mod).values():
                if callable(getattr(obj, "cache_clear", None)) and getattr(obj, "__module__", "") == name:
                    obj.cache_clear()


@pytest.fixture
def fresh_claims():
    load_all()
    _clear_claim_caches()
    yield
    _clear_claim_caches()


def own_samples(N: int, b: int, s: int, count: int, seed: int):
    """States in the cell {branch=b, sign_tr=s}: drawn here (not by the claims' sampler), tr L from the
    polynomial trace, the image by the literal map of branch b; 60 digits."""
    rng = random.Random(f"checker-checked|{N}|{b}|{s}|{seed}")
    out, draws = [], 0
    with mp.workdps(60):
        while len(out) < count:
            draws += 1
            if draws > 5000 * count:      # a budget, not a hang: about 1 draw in 5 has the sign
                raise RuntimeError(f"cannot fill the cell branch={b}, sign_tr={s} (N={N}) in {draws} draws")
            p = [mp.mpf(rng.uniform(-2.5, 2.5)) for _ in range(N)]
            q = [mp.mpf(rng.uniform(-1, 1)) for _ in range(N)]
            l0, m = mp.mpf(rng.uniform(-4, 4)), mp.mpf(rng.uniform(0.1, 0.6))
            t1, t2 = trace(l0 + m, p, q), trace(l0 - m, p, q)
            if not (s * t1 > 2.1 and s * t2 > 2.1):
                continue
            try:
                pt, qt, info = literal_step(p, q, l0, m, b)
            except (ZeroDivisionError, ValueError):
                continue
            if not all(isinstance(v, mp.mpf) and v > 0 for v in info["E_new"]):
                continue
            out.append(((p, q, l0, m), (pt, qt), info, (t1, t2)))
    return out


def printed_phi(t1, t2):
    return -mp.acosh(t1 / 2) - mp.acosh(t2 / 2)           # eq. newkmu as printed, principal arccosh


def newkmu_holds(N, b, state, image, info, traces) -> bool:
    """eq. newkmu at one sample: sum_k log((eta_k+mu)/(eta_k-mu)) (principal) = printed Phi."""
    m = state[3]
    lhs = mp.fsum(mp.log((e + m) / (e - m)) for e in info["eta"])
    rhs = printed_phi(*traces)
    return abs(lhs - rhs) <= mp.mpf(10) ** -30 * max(1, abs(rhs))


def x_newkmu_holds(N, b, state, image, info, traces) -> bool:
    """Theorem 1 with the printed Phi at one sample: d(p~, q~)/dmu (central differences of the literal map)
    = (-dPhi/dq~, dPhi/dp~), dPhi/dp~ = sum_i Phi_i'(tr_i) d tr_i/dp~ at the image."""
    p, q, l0, m = state
    pt, qt = image
    h = mp.mpf(10) ** -20
    plus, minus = literal_step(p, q, l0, m + h, b), literal_step(p, q, l0, m - h, b)
    dp = [(u - v) / (2 * h) for u, v in zip(plus[0], minus[0])]
    dq = [(u - v) / (2 * h) for u, v in zip(plus[1], minus[1])]
    gp, gq = [mp.mpf(0)] * N, [mp.mpf(0)] * N
    for lv, t in ((l0 + m, traces[0]), (l0 - m, traces[1])):
        slope = mp.diff(lambda u: -mp.acosh(u / 2), t)
        tp, tq = trace_gradient(lv, pt, qt)
        gp = [g + slope * d for g, d in zip(gp, tp)]
        gq = [g + slope * d for g, d in zip(gq, tq)]
    want = gp + [-g for g in gq]
    got = dq + dp
    scale = max(1, *(abs(v) for v in want))
    return max(abs(a - c) for a, c in zip(got, want)) <= mp.mpf(10) ** -25 * scale


def truth_by_cell(N: int, holds, per_cell: int = 6) -> dict:
    """'{branch=+1, sign_tr=-1}' -> 'all' / 'some' / 'none' of this module's samples where the printed side holds."""
    out = {}
    with mp.workdps(60):
        for s in (1, -1):
            for b in (1, -1):
                n = sum(bool(holds(N, b, *smp)) for smp in own_samples(N, b, s, per_cell, seed=N))
                out[f"{{branch={b:+d}, sign_tr={s:+d}}}"] = "all" if n == per_cell else ("none" if n == 0 else "some")
    return out


def cells_named(scope: str) -> dict:
    """The printed statement's part of a scope sentence: cell -> 'all' / 'some' / 'none'."""
    text = scope.split(";")[0]
    if re.fullmatch(r"printed statement holds in all \d+ cells", text):
        return {"*": "all"}
    if re.fullmatch(r"printed statement fails in all \d+ cells", text):
        return {"*": "none"}
    out = {}
    for part, kind in ((r"holds exactly in cells (.*?)(?: and |$)", "all"),
                       (r"holds at some samples of (.*?)(?: and |$)", "some"),
                       (r"fails in (.*?)$", "none")):
        m = re.search(part, text)
        if m:
            for cell in re.findall(r"\{[^}]*\}", m.group(1)):
                out[cell] = kind
    return out


def compatible(named: dict, truth: dict) -> list[str]:
    """Cells where the sentence and the independent truth disagree ('some' in the sentence needs at least
    one holding sample here; an 'all' or 'none' must be met by every sample)."""
    if "*" in named:
        named = {cell: named["*"] for cell in truth}
    bad = [f"{c}: sentence says {named.get(c)}, truth {t}" for c, t in truth.items()
           if named.get(c) != t and not (named.get(c) == "some" and t != "none")]
    bad += [f"{c}: named but not a cell" for c in named if c not in truth]
    return bad


SCOPED = [("newkmu.n2", 2, newkmu_holds), ("newkmu.n3", 3, newkmu_holds), ("x.newkmu.n2", 2, x_newkmu_holds)]


def scope_disagreements() -> list[str]:
    results = {r.claim.id: r for r in symbt.verify([c for c, _, _ in SCOPED], use_cache=False, budget=None)}
    bad = []
    for cid, N, holds in SCOPED:
        r = results[cid]
        if r.status != "erratum" or not r.outcome.scope:
            bad.append(f"{cid}: {r.status}")
            continue
        bad += [f"{cid} {m}" for m in compatible(cells_named(r.outcome.scope), truth_by_cell(N, holds))]
    return bad


def test_scope_sentences_name_the_cells_where_the_printed_statement_holds(fresh_claims):
    assert scope_disagreements() == []


def test_scope_parser_reads_every_form():
    s = ("printed statement holds exactly in cells {branch=+1, sign_tr=+1} and holds at some samples of "
         "{branch=-1, sign_tr=+1} (3/16) and fails in {branch=+1, sign_tr=-1}, {branch=-1, sign_tr=-1}; "
         "corrected statement holds in all 4 cells")
    assert cells_named(s) == {"{branch=+1, sign_tr=+1}": "all", "{branch=-1, sign_tr=+1}": "some",
                              "{branch=+1, sign_tr=-1}": "none", "{branch=-1, sign_tr=-1}": "none"}
    assert cells_named("printed statement holds in all 4 cells") == {"*": "all"}


def test_cells_all_sampled_on_branch_plus_one_is_caught(monkeypatch, fresh_claims):
    from symbt.claims import _common

    real = _common.map_cells

    def map_cells(N, count, *, seed=0, paper=True):
        # the planted bug: each cell keeps its label, but every state is mapped with branch +1
        return [(cell, st, 1) for cell, st, _ in real(N, count, seed=seed, paper=paper)]

    for name, mod in list(sys.modules.items()):
        if name.startswith("symbt.claims") and getattr(mod, "map_cells", None) is real:
            monkeypatch.setattr(mod, "map_cells", map_cells)
    assert scope_disagreements() != []
