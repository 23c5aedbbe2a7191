"""The claims of ``symbt/claims/checker_screen.py`` observe ``symbt.proof.screen``, ``decider`` and ``ranges`` as whole
functions (issue 21, item 4: fresh samples; docs/mutation.md, "Fresh samples of symbt/proof/screen.py, decider.py,
ranges.py").

Each test plants one single-point bug of ``symbt mutate --source``'s kind with :func:`planting.planted` -- the
mutants of the fresh samples (seeds 11 and 12) and their neighbours of the same class -- where the claim reads it
from, and requires the claim to fail *by its comparison* (not by a crash, unless the mutant itself crashes);
unpatched, every claim verifies.
"""
from __future__ import annotations

from collections import OrderedDict

import pytest
import sympy as sp
from planting import planted

from symbt.claims import REGISTRY, load_all
from symbt.claims.base import Outcome
from symbt.proof import decider, lambdify, ranges
from symbt.proof import screen as screen_module

load_all()

CLAIMS = ["checker.sample_symbol", "checker.screen_relations", "checker.screen_arithmetic", "checker.screen_scale",
          "checker.decide_rules", "checker.ranges"]


def outcome(cid: str) -> Outcome:
    return REGISTRY[cid].run()


#: the mutants that raise where the claim runs them (the claim fails as "exception"); every other one must fail by
#: the claim's own comparison
CRASH = {"scale abs(rv)", "scale abs(lv)", "screen:350 no scale", "screen:354 no checks",
         "screen:354 finite skipped", "decider:98 refusal", "decider:117 undecided", "decider:79 nan",
         "decider:82 oo"}


def fails(cid: str, *, crash: bool = False) -> bool:
    """The claim fails; by its own comparison unless ``crash`` (the mutant raises where the claim runs it)."""
    out = outcome(cid)
    return out.status == "failed" and (crash or out.method != "exception")


def screen_claims_fail(*, crash: bool = False) -> bool:
    """``checker.screen_arithmetic`` or ``checker.screen_scale`` fails (the residual's arithmetic and its scale:
    a mutant of a line both run is killed by whichever sees it)."""
    return fails("checker.screen_arithmetic", crash=crash) or fails("checker.screen_scale", crash=crash)


@pytest.fixture(autouse=True)
def fresh_memo(monkeypatch):
    # the lambdified functions built afresh (a memoised one would skip nothing, but keeps runs independent)
    monkeypatch.setattr(lambdify, "_MEMO", OrderedDict())


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    out = outcome(cid)
    assert out.status == "verified", out.detail
    assert out.evidence in ("sampled", "proof") and out.n_scope == "all"


def test_relations_deep_variant_reaches_every_root_of_the_quartic():
    out = REGISTRY["checker.screen_relations"].run(deep=True)
    assert out.status == "verified", out.detail
    assert "degrees 1..4" in out.detail


# --------------------------------------------------------------------------- checker.sample_symbol

SAMPLE = [   # (mutant, old, new) in screen.sample_symbol
    ("screen:36 integer branch", '    if a.get("integer"):', '    if not (a.get("integer")):'),
    ("screen:38 positive integers", "lo, hi = 1, 9", "lo, hi = 0, 9"),
    ("screen:45 even move", "v = v - 1 if v - 1 >= lo else v + 1", "v = v - 1 if v - 1 >= lo else v - 1"),
    ("screen:48 nonzero", "v = 2 if a.get(\"even\") else 1", "v = 2 if a.get(\"even\") else 0"),
    ("screen:52 drop /10", "mpmath.mpf(rng.randint(3, 30)) / 10 +", "mpmath.mpf(rng.randint(3, 30)) +"),
    ("screen:52 sign", "/ 10 + mpmath.mpf(rng.random()) / 7", "/ 10 - mpmath.mpf(rng.random()) / 7"),
    ("screen:52 drop /7", "mpmath.mpf(rng.random()) / 7", "mpmath.mpf(rng.random())"),
    ("screen:55 negative branch", '    if a.get("negative") or a.get("nonpositive"):\n        return -mag',
     '    if not (a.get("negative") or a.get("nonpositive")):\n        return -mag'),
    ("screen:56 unary minus", "return -mag", "return mag"),
    ("screen:57 constant", "sign = 1 if rng.random() < 0.5 else -1", "sign = 1 if rng.random() < 0.5 else -0"),
    ("screen:58 real branch", 'if a.get("real") or a.get("extended_real"):',
     'if not (a.get("real") or a.get("extended_real")):'),
    ("screen:60 imaginary branch", '    if a.get("imaginary"):', '    if not (a.get("imaginary")):'),
    ("screen:62 drop /11", "mpmath.mpf(rng.random()) / 11", "mpmath.mpf(rng.random())"),
    ("screen:62 imaginary range", "rng.randint(-40, 40)) / 10", "rng.randint(-40, 40)) / 20"),
]


@pytest.mark.parametrize("where, old, new", SAMPLE, ids=[s[0] for s in SAMPLE])
def test_sample_symbol_cells_kill(monkeypatch, where, old, new):
    monkeypatch.setattr(screen_module, "sample_symbol", planted(screen_module.sample_symbol, old, new))
    assert fails("checker.sample_symbol")


# --------------------------------------------------------------------------- checker.screen_relations

ROOTS = [   # (mutant, function, old, new, crash): crash -- the mutant raises where the claim runs it
    ("screen:100 discriminant sign", "_generic_roots", "a[1] ** 2 - 4 * a[0] * a[2]", "a[1] ** 2 + 4 * a[0] * a[2]",
     False),
    ("screen:101 denominator a1", "_generic_roots", "(-a[1] + disc) / (2 * a[0])", "(-a[1] + disc) / (2 * a[1])",
     True),
    ("screen:101 drop 2", "_generic_roots", "(-a[1] - disc) / (2 * a[0])", "(-a[1] - disc) / (a[0])", False),
    ("screen:101 one root twice", "_generic_roots", "[(-a[1] - disc) / (2 * a[0]), (-a[1] + disc)",
     "[(-a[1] + disc) / (2 * a[0]), (-a[1] + disc)", False),
    ("screen:104 degree shift", "_generic_roots", "x ** (degree - i)", "x ** (degree - i - 1)", True),
    # the degree rule (screen:115 before it went to symbt.proof.relations, which the screen calls)
    ("relations degree bound", "relation_poly", "poly.degree() > max_degree", "poly.degree() < max_degree", True),
    ("relations degree 1 refused", "relation_poly", "poly.degree() < 1", "poly.degree() <= 1", True),
    ("relations non-polynomial", "relation_poly", "if poly is None or", "if poly is not None and", True),
    ("screen:134 order", "_solve_order", "if all(r.free_symbols <= known for r in roots):",
     "if not (all(r.free_symbols <= known for r in roots)):", True),
]


def _source_of(name: str):
    # _generic_roots is cached: plant into the function it wraps (its source keeps the @cache line)
    func = getattr(screen_module, name)
    return getattr(func, "__wrapped__", func)


@pytest.mark.parametrize("where, name, old, new, crash", ROOTS, ids=[s[0] for s in ROOTS])
def test_screen_relations_kill(monkeypatch, where, name, old, new, crash):
    mutant = planted(_source_of(name), old, new)
    assert hasattr(mutant, "cache_clear") == (name == "_generic_roots")
    monkeypatch.setattr(screen_module, name, mutant)
    assert fails("checker.screen_relations", crash=crash)


def test_relations_max_degree_lowered(monkeypatch):
    # MAX_RELATION_DEGREE 4 -> 2: the cubic is refused (a ValueError where the claim asks for its roots)
    monkeypatch.setattr(screen_module, "MAX_RELATION_DEGREE", 2)
    assert fails("checker.screen_relations", crash=True)


def test_quartic_refused_is_seen_by_the_deep_variant_only(monkeypatch):
    # screen:115 `<= MAX_RELATION_DEGREE` -> `< MAX_RELATION_DEGREE` (now relation_poly's `> max_degree` -> `>=`):
    # quartics refused; the default variant stops at cubics (the generic quartic's closed form costs 0.7 s), so
    # only `symbt verify --deep` sees it
    monkeypatch.setattr(screen_module, "relation_poly", planted(
        screen_module.relation_poly, "poly.degree() > max_degree", "poly.degree() >= max_degree"))
    assert outcome("checker.screen_relations").status == "verified"
    out = REGISTRY["checker.screen_relations"].run(deep=True)
    assert out.status == "failed"


def test_root_pick_shifted_in_the_screen(monkeypatch):
    # the root picked for a point shifted by one (an index-shift of sols[k]): a quadratic's one root only
    monkeypatch.setattr(screen_module, "screen", planted(
        screen_module.screen, "k = rng.randrange(len(sols))", "k = rng.randrange(len(sols)) * 0"))
    assert fails("checker.screen_relations")


def test_root_pick_shifted_in_the_recheck(monkeypatch):
    # seed 12's screen:269: the re-evaluation takes the next root (out of range for one root: IndexError)
    monkeypatch.setattr(screen_module, "_recheck", planted(
        screen_module._recheck, "allv.append(sols[k](*allv))", "allv.append(sols[k + 1](*allv))"))
    assert fails("checker.screen_relations", crash=True)


# --------------------------------------------------------------------------- checker.screen_arithmetic

def plant_screen(monkeypatch, old: str, new: str) -> None:
    mutant = planted(screen_module.screen, old, new)
    monkeypatch.setattr(screen_module, "screen", mutant)
    monkeypatch.setattr(decider, "screen", mutant)


SCREEN = [   # (mutant, old, new) in screen.screen
    ("screen:335 first precision", "with mpmath.workdps(digits + 10):", "with mpmath.workdps(digits - 10):"),
    ("screen:350 no scale", "(el + er) / scale) if scale else", "(el + er) / scale) if not scale else"),
    ("screen:350 absolute residual", "rel, err = (abs(lv - rv) / scale, (el + er) / scale)",
     "rel, err = (abs(lv - rv), (el + er) / scale)"),
    ("screen:365 counterexample", "pc.residual > SAFETY * pc.error", "pc.residual < SAFETY * pc.error"),
    ("screen:374 clear point", "if pc.residual <= clear and pc.error <= clear:",
     "if not (pc.residual <= clear and pc.error <= clear):"),
    ("screen:354 no checks", "    if not checks:\n", "    if checks:\n"),
    ("screen:343 draw budget", "attempts < 6 * points + 10", "attempts < 6 * points + 11"),
    ("screen:354 finite skipped", "            if not (_finite(lv) and _finite(rv)):",
     "            if _finite(lv) and _finite(rv):"),
]


@pytest.mark.parametrize("where, old, new", SCREEN, ids=[s[0] for s in SCREEN])
def test_screen_arithmetic_kills_screen(monkeypatch, where, old, new):
    plant_screen(monkeypatch, old, new)
    assert screen_claims_fail(crash=where in CRASH)


RECHECK = [   # (mutant, old, new) in screen._recheck
    ("screen:265 second precision", "with mpmath.workdps(hi + 10):", "with mpmath.workdps(hi - 10):"),
    ("screen:278 error not scaled", "pc.error = abs(diff - pc.diff) / scale", "pc.error = abs(diff - pc.diff)"),
    ("screen:278 drift dropped", "pc.error = abs(diff - pc.diff) / scale", "pc.error = abs(diff) * 0 / scale"),
    ("screen:280 residual", "pc.residual = abs(diff) / scale", "pc.residual = abs(diff - pc.diff) / scale"),
]


SCALE = [   # (mutant, old, new) in screen._scale: what a point's difference is measured against
    ("scale abs(rv)", "floored_scale(max(abs(lv), abs(rv)), size)", "floored_scale(max(abs(lv), rv), size)"),
    ("scale abs(lv)", "floored_scale(max(abs(lv), abs(rv)), size)", "floored_scale(max(lv, abs(rv)), size)"),
]

FLOOR = [   # (mutant, old, new) in magnitude.floored_scale: the floor below 1, one rule for the screen and the ODE
    ("floor not capped", "min(mpmath.mpf(1), size())", "max(mpmath.mpf(1), size())"),   # the old floor 1
    ("no floor", "return max(big, min(mpmath.mpf(1), size()))", "return big"),
    ("floor from 1 up", "    if big >= 1:\n", "    if big >= 0:\n"),
    ("floor at 0", "min(mpmath.mpf(1), size())", "min(mpmath.mpf(0), size())"),
    ("floor as a cap", "return max(big, min(", "return min(big, min("),
    ("floor above 1", "    if big >= 1:\n", "    if big <= 1:\n"),
]


@pytest.mark.parametrize("where, old, new", SCALE, ids=[s[0] for s in SCALE])
def test_screen_arithmetic_kills_scale(monkeypatch, where, old, new):
    monkeypatch.setattr(screen_module, "_scale", planted(screen_module._scale, old, new))
    assert screen_claims_fail(crash=where in CRASH)


def plant_floor(monkeypatch, old: str, new: str) -> None:
    """The floor rule mutated where it is written, seen by both its users (as the mutation tool mutates it)."""
    from symbt.proof import magnitude, ode
    mutant = planted(magnitude.floored_scale, old, new)
    for module in (magnitude, screen_module, ode):
        monkeypatch.setattr(module, "floored_scale", mutant)


@pytest.mark.parametrize("where, old, new", FLOOR, ids=[s[0] for s in FLOOR])
def test_screen_claims_kill_the_floor(monkeypatch, where, old, new):
    plant_floor(monkeypatch, old, new)
    assert screen_claims_fail()


def test_screen_size_is_each_sides_terms(monkeypatch):
    # the size of the rhs's terms only (the lhs's dropped): sin^2 + cos^2 - 1 = 0 is measured against 0's terms
    monkeypatch.setattr(screen_module, "_sizer", planted(
        screen_module._sizer, "size_or_inf(lambda: f_size(*allv))", "size_or_inf(lambda: f_size(*allv)[1:])"))
    assert screen_claims_fail()


@pytest.mark.parametrize("old, new", [
    ("m = max(sizes())", "m = min(sizes())"),   # the smaller side's terms: measured against 0's terms
    ("return m if mpmath.isfinite(m) else", "return m if not mpmath.isfinite(m) else"),   # every size infinite
])
def test_size_or_inf_is_the_largest_finite(monkeypatch, old, new):
    from symbt.proof import magnitude
    mutant = planted(magnitude.size_or_inf, old, new)
    for module in (magnitude, screen_module):
        monkeypatch.setattr(module, "size_or_inf", mutant)
    assert screen_claims_fail()


@pytest.mark.parametrize("where, old, new", RECHECK, ids=[s[0] for s in RECHECK])
def test_screen_arithmetic_kills_recheck(monkeypatch, where, old, new):
    monkeypatch.setattr(screen_module, "_recheck", planted(screen_module._recheck, old, new))
    assert screen_claims_fail(crash=where in CRASH)


def test_fixed_int_kept_as_a_python_int(monkeypatch):
    # screen:73: `if not isinstance(x, (mpf, mpc))`: a fixed int stays an int, and 1/b is a double
    monkeypatch.setattr(screen_module, "_as_mp", planted(
        screen_module._as_mp, "    if isinstance(x, (mpmath.mpf, mpmath.mpc)):",
        "    if not isinstance(x, (mpmath.mpf, mpmath.mpc)):"))
    assert fails("checker.screen_arithmetic")


def test_high_precision_shifted(monkeypatch):
    # seed 12's screen:255
    monkeypatch.setattr(screen_module, "high_precision", planted(
        screen_module.high_precision, "return 2 * digits + 10", "return 2 * digits - 10"))
    assert fails("checker.screen_arithmetic")


QUAD = [   # (mutant, function, old, new)
    ("screen:171 abs(value)", "tracked_quad", "log.append((abs(value), abs(err)))", "log.append((value, abs(err)))"),
    ("screen:193 max", "_quad_error", "return max(absolute, abs(value) * relative)",
     "return min(absolute, abs(value) * relative)"),
    ("screen:192 relative of an absolute", "_quad_error", "fsum(e / v for v, e in errors if v)",
     "fsum(e for v, e in errors if v)"),
    ("screen:189 no error", "_quad_error", "    if not errors:\n", "    if errors:\n"),
]


@pytest.mark.parametrize("where, name, old, new", QUAD, ids=[s[0] for s in QUAD])
def test_screen_arithmetic_kills_quadrature_errors(monkeypatch, where, name, old, new):
    mutant = planted(getattr(screen_module, name), old, new)
    monkeypatch.setattr(screen_module, name, mutant)
    if name == "tracked_quad":   # the lambdify namespace holds the function itself
        monkeypatch.setitem(screen_module._NAMESPACE, "quad", mutant)
    assert fails("checker.screen_arithmetic", crash=where in CRASH)


# --------------------------------------------------------------------------- checker.decide_rules

DECIDE = [   # (mutant, old, new) in decider.decide
    ("decider:86 default exact", "exact: bool = True", "exact: bool = False"),
    ("decider:98 nine digits", "digits < MIN_DIGITS:", "digits <= MIN_DIGITS:"),
    ("decider:98 refusal", "    if isinstance(digits, int) and digits < MIN_DIGITS:",
     "    if not (isinstance(digits, int) and digits < MIN_DIGITS):"),
    ("decider:113 empty", "            return Verdict.from_proof(\"exact: empty matrices\")",
     "            return Verdict(False, \"proof\", \"exact: empty matrices\")"),
    ("decider:115 worst entry", "return max(bad, key=lambda d: d.residual or 0.0)",
     "return min(bad, key=lambda d: d.residual or 0.0)"),
    ("decider:117 undecided", "        if undecided:", "        if not (undecided):"),
    ("decider:120 residual", "res = max((d.residual or 0.0) for d in parts)",
     "res = min((d.residual or 0.0) for d in parts)"),
    ("decider:127 note", "note=numeric[0].note, error", "note=numeric[1].note, error"),
    ("decider:189 points (seed 10)", "points=numeric[0].points", "points=numeric[1].points"),
    ("decider:127 error", "error=max(errors) if errors else None", "error=max(errors) if not (errors) else None"),
    ("decider:141 re-evaluated", "    if sr.rechecked:", "    if not (sr.rechecked):"),
    ("decider:143 sampled", "    if sr.ok and not definite:", "    if not (sr.ok and not definite):"),
    ("decider:144 note", "note = \"\" if not method_exact else", "note = \"\" if method_exact else"),
    ("decider:149 tiny", "if sr.residual <= 10.0 ** (-(digits - 8)):", "if sr.residual >= 10.0 ** (-(digits - 8)):"),
    ("decider:153 method", "method = nmethod if not method_exact else", "method = nmethod if method_exact else"),
    ("decider:156 inconclusive", "inconclusive=True, error=sr.error)", "inconclusive=False, error=sr.error)"),
    ("decider:157 false", "    return Verdict(False, \"sampled\", method, residual=res, digits=dig, counterexample",
     "    return Verdict(True, \"sampled\", method, residual=res, digits=dig, counterexample"),
]


@pytest.mark.parametrize("where, old, new", DECIDE, ids=[s[0] for s in DECIDE])
def test_decide_rules_kill_decide(monkeypatch, where, old, new):
    monkeypatch.setattr(decider, "decide", planted(decider.decide, old, new))
    assert fails("checker.decide_rules", crash=where in CRASH)


def test_decide_rules_kill_the_shape_rule(monkeypatch):
    # decider:107 (the shapes' test, now in match_shapes, which decide and check_identity share) inverted:
    # matrices of one shape are refused
    monkeypatch.setattr(decider, "match_shapes", planted(decider.match_shapes, "    if lm and lhs.shape != rhs.shape:",
                                                         "    if lm and not (lhs.shape != rhs.shape):"))
    assert fails("checker.decide_rules", crash=True)


WORDS = [   # (mutant, function, old, new)
    ("decider:163 tolerance", "_cannot_tell", "tol = 10.0 ** (-(digits - 8))", "tol = 10.0 ** (-(digits + 8))"),
    ("decider:165 kind", "_cannot_tell", "    if sr.residual > tol:", "    if not (sr.residual > tol):"),
    ("decider:178 limit", "_point_brief", "if len(items) > limit else", "if len(items) >= limit else"),
    ("decider:178 branch", "_point_brief", "if len(items) > limit else", "if not (len(items) > limit) else"),
    ("decider:177 first items", "_point_brief", "items[:limit]", "items[:limit + 1]"),
    ("decider:178 no point", "_point_brief", 'or "a sample point"', 'or "a point"'),
    ("decider:78 nan", "_undefined", "    if expr.has(sp.nan, sp.zoo):", "    if not (expr.has(sp.nan, sp.zoo)):"),
    ("decider:79 nan", "_undefined", "        return True\n", "        return False\n"),
    ("decider:82 oo", "_undefined", "return bool(expr.has(sp.oo, -sp.oo))", "return bool(expr.has(-sp.oo))"),
]


@pytest.mark.parametrize("where, name, old, new", WORDS, ids=[s[0] for s in WORDS])
def test_decide_rules_kill_words(monkeypatch, where, name, old, new):
    monkeypatch.setattr(decider, name, planted(getattr(decider, name), old, new))
    assert fails("checker.decide_rules", crash=where in CRASH)


# --------------------------------------------------------------------------- checker.ranges

DRAW = [   # (mutant, old, new) in Range.draw
    ("ranges:33 uniform", '    if self.kind == "uniform":', '    if not (self.kind == "uniform"):'),
    ("ranges:35 log_uniform", '    if self.kind == "log_uniform":', '    if self.kind != "log_uniform":'),
    ("ranges:36 exp", "math.exp(rng.uniform(math.log(self.lo)", "(rng.uniform(math.log(self.lo)"),
    ("ranges:37 integers", '    if self.kind == "integers":', '    if not (self.kind == "integers"):'),
    ("ranges:39 complex parts", "rng.uniform(self.lo.imag, self.hi.imag)", "rng.uniform(self.lo.real, self.hi.real)"),
]


@pytest.mark.parametrize("where, old, new", DRAW, ids=[s[0] for s in DRAW])
def test_ranges_kill_draw(monkeypatch, where, old, new):
    monkeypatch.setattr(ranges.Range, "draw", planted(ranges.Range.draw, old, new))
    assert fails("checker.ranges", crash=True)


def test_ranges_kill_str(monkeypatch):
    # ranges:43: the complex box printed as a real interval (a format error) and the real kinds as a box
    monkeypatch.setattr(ranges.Range, "__str__", planted(
        ranges.Range.__str__, 'if self.kind != "complex_box"', 'if self.kind == "complex_box"'))
    assert fails("checker.ranges", crash=True)


MAKERS = [   # (mutant, function, old, new)
    ("ranges:52 branch", "_interval", "    if not (math.isfinite(a) and math.isfinite(b) and a < b):",
     "    if math.isfinite(a) and math.isfinite(b) and a < b:"),
    ("ranges:52 lo == hi", "_interval", "and a < b):", "and a <= b):"),
    ("ranges:52 finite", "_interval", "math.isfinite(a) and math.isfinite(b) and", "math.isfinite(a) and"),
    ("ranges:49 non-numbers", "_interval", "    except (TypeError, ValueError):\n        a = b = math.nan",
     "    except (TypeError, ValueError):\n        a, b = 0.0, 1.0"),
    ("ranges:73 log lo", "log_uniform", "    if a <= 0:", "    if a < 0:"),
    ("ranges:84 bool", "integers", "and not isinstance(v, bool)", "and isinstance(v, int)"),
    ("ranges:84 lo == hi", "integers", "or lo > hi:", "or lo >= hi:"),
    ("ranges:84 branch", "integers", "    if not all(isinstance(v, int) and not isinstance(v, bool) for v in (lo, hi)) "
                                     "or lo > hi:",
     "    if not (not all(isinstance(v, int) and not isinstance(v, bool) for v in (lo, hi)) or lo > hi):"),
    ("ranges:105 Range", "as_range", "    if isinstance(spec, Range):", "    if not (isinstance(spec, Range)):"),
    ("ranges:107 range", "as_range", "    if isinstance(spec, range):", "    if not (isinstance(spec, range)):"),
    ("ranges:108 bad range", "as_range", "if spec.step != 1 or len(spec) == 0:",
     "if not (spec.step != 1 or len(spec) == 0):"),
    ("ranges:108 empty", "as_range", "or len(spec) == 0:", "or len(spec) == 1:"),
    ("ranges:110 stop", "as_range", "integers(spec.start, spec.stop - 1)", "integers(spec.start, spec.stop + 1)"),
    ("ranges:111 pair", "as_range", "and len(spec) == 2:", "and len(spec) != 2:"),
    ("ranges:113 complex", "as_range", "if isinstance(lo, complex) or isinstance(hi, complex):",
     "if not (isinstance(lo, complex) or isinstance(hi, complex)):"),
]


@pytest.mark.parametrize("where, name, old, new", MAKERS, ids=[s[0] for s in MAKERS])
def test_ranges_kill_makers(monkeypatch, where, name, old, new):
    monkeypatch.setattr(ranges, name, planted(getattr(ranges, name), old, new))
    assert fails("checker.ranges", crash=True)


# --------------------------------------------------------------------------- a tie (killed by tests)

def test_definite_falsity_at_exactly_the_tolerance_is_noted_tiny(monkeypatch):
    # decider:149 `residual <= tol` -> `residual < tol`: differs only at a residual exactly the double 10^-(d-8),
    # which no statement evaluates to; a screen stub returns that tie for a definite falsity (x + 1 = x)
    from symbt.proof.screen import ScreenResult
    from symbt.proof.verdict import Verdict

    x = sp.Symbol("x", real=True)
    tie = 10.0 ** -(30 - 8)

    def stub(*args, **kwargs):
        return ScreenResult("false", tie, 0.0, 22.0, {"x": "1"}, [{"x": "1"}])

    monkeypatch.setattr(decider, "screen", stub)

    def note(decide) -> str:
        v: Verdict = decide(x + 1, x, digits=30)
        assert (v.verdict, v.evidence, v.definite, v.residual) == ("false", "proof", True, tie)
        return v.note

    assert "numerically tiny" in note(decider.decide)
    mutant = planted(decider.decide, "if sr.residual <= 10.0 ** (-(digits - 8)):",
                     "if sr.residual < 10.0 ** (-(digits - 8)):")
    assert "numerically tiny" not in note(mutant)


def test_inconclusive_note_at_exactly_the_tolerance_says_the_sides_agree():
    # decider:165 `residual > tol` -> `residual >= tol`: differs only at a residual exactly the double 10^-(d-8);
    # there the sides agree to the tolerance (Verdict.sampled's `residual <= tol`), so the note says so
    from symbt.proof.screen import ScreenResult

    tie = 10.0 ** -(30 - 8)
    sr = ScreenResult("inconclusive", tie, 1e-3, 3.0, {"x": "1"}, [{"x": "1"}], rechecked=1, high_digits=70)
    assert "the sides agree to 1.0e-22" in decider._cannot_tell(sr, 30)
    mutant = planted(decider._cannot_tell, "    if sr.residual > tol:", "    if sr.residual >= tol:")
    assert "is within 10x the evaluation's own error" in mutant(sr, 30)
