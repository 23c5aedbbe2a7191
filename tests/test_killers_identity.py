"""The claims of ``symbt/claims/checker_identity.py`` observe whole functions of ``symbt.proof.identity``,
``symbt.proof.domain`` and ``symbt.proof.mutation`` (issue 21, item 4; docs/mutation.md, "Fresh samples of
symbt/proof/identity.py, domain.py, mutation.py").

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- most of them mutants of the
fresh sample of seed 21, the others of the same functions -- with :func:`planting.planted` (a function) or
:func:`planting.mutated` (a module copy, for class fields and defaults), and requires the claim to fail;
unpatched, every claim verifies.
"""
from __future__ import annotations

import pytest
from planting import mutated, planted

from symbt.claims import REGISTRY, load_all
from symbt.proof import decider, domain, identity, mutation

load_all()

CLAIMS = ["checker.identity_result", "checker.identity_arguments", "checker.identity_relations",
          "checker.domain_rules", "checker.mutation_rules"]


def status(cid: str) -> str:
    try:
        return REGISTRY[cid].run().status
    except Exception as exc:   # noqa: BLE001 -- a claim that raises has not verified
        return f"raised {type(exc).__name__}"


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- checker.identity_result

RESULT = [   # (attribute of IdentityResult or module function, old, new)
    ("summary", 'if self.status == "proved":', 'if self.status != "proved":'),               # seed 21, :144
    ("summary", 'if self.status == "inconclusive":', 'if not (self.status == "inconclusive"):'),   # seed 21, :150
    ("summary", 'if self.note.startswith("hint:") else ""', 'if not self.note.startswith("hint:") else ""'),
    ("_digits_text", "if got >= self.requested_digits:", "if got > self.requested_digits:"),
    ("_repr_html_", 'elif self.status == "false":', 'elif self.status != "false":'),
    ("_repr_html_", "if self.note:", "if not (self.note):"),
]


@pytest.mark.parametrize("attr, old, new", RESULT, ids=[f"{a}:{o}" for a, o, _ in RESULT])
def test_identity_result_kills_method_mutants(monkeypatch, attr, old, new):
    monkeypatch.setattr(identity.IdentityResult, attr, planted(getattr(identity.IdentityResult, attr), old, new))
    assert status("checker.identity_result") == "failed"


@pytest.mark.parametrize("func, old, new", [
    ("_point_text", 'len(items) > limit else ""', 'len(items) >= limit else ""'),
    ("_point_text", "if not point:", "if point:"),
    ("_short", "if len(s) <= limit else", "if len(s) < limit else"),
])
def test_identity_result_kills_text_helpers(monkeypatch, func, old, new):
    monkeypatch.setattr(identity, func, planted(getattr(identity, func), old, new))
    assert status("checker.identity_result") == "failed"


def test_identity_result_kills_a_side_in_the_repr(monkeypatch):
    copy = mutated("symbt.proof.identity", "lhs: Any = field(default=None, repr=False)",
                   "lhs: Any = field(default=None, repr=True)")
    monkeypatch.setattr(identity, "IdentityResult", copy.IdentityResult)
    assert status("checker.identity_result") == "failed"


# --------------------------------------------------------------------------- checker.identity_arguments

ARGUMENTS = [   # planted into a module function, seen through check_identity
    ("_positive_int", "if value <= 0:", "if value < 0:"),                                  # seed 21, :323
    ("_validate", "if digits < MIN_DIGITS:", "if digits <= MIN_DIGITS:"),
    ("_validate", "if not isinstance(exact, bool):", "if isinstance(exact, bool):"),
    ("_validate", "if isinstance(seed, bool) or", "if not isinstance(seed, bool) or"),
    ("read_side", "if isinstance(value, str):", "if not (isinstance(value, str)):"),   # decider's, shared
    ("check_identity", "if not (isinstance(rhs, (int, float)) and rhs == 0):",              # seed 21, :402
     "if isinstance(rhs, (int, float)) and rhs == 0:"),
    ("check_identity", "exact: bool = True,", "exact: bool = False,"),                        # seed 21, :383
    ("check_identity", "points=list(d.points) if not d.exact else []", "points=list(d.points) if d.exact else []"),
    ("match_shapes", "if lm and not rm and rhs == 0:", "if lm and not rm and rhs == 1:"),  # decider's, shared
    ("match_shapes", "if rm and not lm and lhs == 0:", "if not (rm and not lm and lhs == 0):"),
]


@pytest.mark.parametrize("func, old, new", ARGUMENTS, ids=[f"{f}:{o}" for f, o, _ in ARGUMENTS])
def test_identity_arguments_kill(monkeypatch, func, old, new):
    mutant = planted(getattr(identity, func), old, new)
    monkeypatch.setattr(identity, func, mutant)
    if hasattr(decider, func):     # the side reader and the shape rule are decider's, imported by name
        monkeypatch.setattr(decider, func, mutant)
    assert status("checker.identity_arguments") == "failed"


# --------------------------------------------------------------------------- checker.identity_relations

RELATIONS = [
    ("normalize_relations", "out[sym] = poly", "out[sym + 1] = poly"),                      # seed 21, :314
    ("normalize_relations", "if isinstance(relations, Mapping):", "if not (isinstance(relations, Mapping)):"),
    ("_pick_symbol", "top = max(degs.values())", "top = min(degs.values())"),
    ("_pick_symbol", "if len(fs) == 1 and", "if len(fs) != 1 and"),
    ("_pick_symbol", "!= fs:", "== fs:"),
    ("apply_assumptions", "if not assumptions:", "if assumptions:"),                        # seed 21, :228
    ("apply_assumptions", "if name is None:", "if not (name is None):"),                    # seed 21, :234
    ("apply_assumptions", "lookup[name] != old:", "lookup[name - 1] != old:"),              # seed 21, :244
    ("apply_assumptions", "old = key if isinstance(key, sp.Symbol) else",
     "old = key if not (isinstance(key, sp.Symbol)) else"),
    ("apply_assumptions", "elif isinstance(e, sp.MatrixBase):", "elif not (isinstance(e, sp.MatrixBase)):"),
    ("_reparametrised", "if all(e is None for e in entries):", "if not (all(e is None for e in entries)):"),
    ("convention_hint", "if swapped is None:", "if not (swapped is None):"),                # seed 21, :475
    ("convention_hint", "(swapped, rhs) if side == \"lhs\" else", "(swapped, rhs) if side != \"lhs\" else"),
    ("check_identity", 'if d.verdict == "false" and not d.definite:',                       # seed 21, :423
     'if not (d.verdict == "false" and not d.definite):'),
    ("check_identity", "    if assumptions:\n        rel_exprs", "    if not (assumptions):\n        rel_exprs"),
]


@pytest.mark.parametrize("func, old, new", RELATIONS, ids=[f"{f}:{o}" for f, o, _ in RELATIONS])
def test_identity_relations_kill(monkeypatch, func, old, new):
    monkeypatch.setattr(identity, func, planted(getattr(identity, func), old, new))
    assert status("checker.identity_relations") == "failed"


def test_validate_assumption_values_seed_21(monkeypatch):
    # seed 21, :350: the check of each assumption dict inverted -- a dict is refused, a non-dict let through
    monkeypatch.setattr(identity, "_validate", planted(identity._validate, "if not isinstance(extra, Mapping):",
                                                       "if isinstance(extra, Mapping):"))
    assert status("checker.identity_relations") == "failed"
    assert status("checker.identity_arguments") == "failed"


# --------------------------------------------------------------------------- checker.domain_rules

DOMAIN = [   # (object in symbt.proof.domain, attribute or None, old, new)
    ("_caller", None, "if p.kind in (p.VAR_POSITIONAL, p.POSITIONAL_ONLY):",                   # seed 21, :85
     "if not (p.kind in (p.VAR_POSITIONAL, p.POSITIONAL_ONLY)):"),
    ("_caller", None, "if p.default is p.empty:", "if not (p.default is p.empty):"),
    ("relative_residual", None, "max(mp.mpf(1), abs(lhs), abs(rhs))", "max(mp.mpf(1), lhs, abs(rhs))"),
    ("_residual", None, "return r if not math.isnan(r) else math.inf", "return r if math.isnan(r) else math.inf"),
    ("_residual", None, "r = float(abs(mp.mpmathify(value)))", "r = float(mp.mpmathify(value))"),
    ("default_tol", None, "-(2 * dps // 3)", "-(2 * dps // 2)"),
    ("_sign_label", None, "if v == 0 or not mp.isfinite(v):", "if v != 0 or not mp.isfinite(v):"),
    ("_sign_label", None, "split.values[0] if v < 0 else", "split.values[1] if v < 0 else"),
    ("sign", None, "neg = [-a for a", "neg = [a for a"),                                          # seed 21, :218
    ("sign", None, "pair[0] == pair[1]:", "pair[0] != pair[1]:"),                                 # seed 21, :227
    ("_per_cell", None, "or isinstance(n, bool) or n < 1:", "or isinstance(n, bool) or n < 0:"),
    ("_dps", None, "dps < 15:", "dps <= 15:"),
    ("_check_values", None, "if bad:", "if not (bad):"),
    ("Split", "bind", 'if self.kind == "sign":', 'if self.kind != "sign":'),                    # seed 21, :175
    ("Domain", "__init__", "self.variables[name] = as_range(name, spec)",                         # seed 21, :311
     "self.variables[name + 1] = as_range(name, spec)"),
    ("Domain", "__init__", "draws_per_point < 1:", "draws_per_point < 0:"),
    ("Domain", "cells", "names.count(n) > 1}", "names.count(n) < 1}"),                            # seed 21, :334
    ("Domain", "sample", "where = None if self.where is None else",                               # seed 21, :351
     "where = None if not (self.where is None) else"),
    ("Domain", "sample", "point.update({c: cell[c] for c in choices})",                           # seed 21, :363
     "point.update({c: cell[c + 1] for c in choices})"),
    ("Domain", "sample", "elsewhere += 1", "elsewhere += 0"),
    ("Domain", "sample", 'names = [*self.variables, *(s.name for s in splits if s.kind == "choice")]',
     'names = [*self.variables, *(s.name for s in splits if s.kind != "choice")]'),
    ("Domain", "sample", "while got < n and draws < n * self.draws_per_point:",
     "while got < n and draws <= n * self.draws_per_point:"),
    ("Domain", "evaluate", "if not tol >= 0:", "if not tol > 0:"),
    ("Domain", "evaluate", "rc = None if run_c is None else", "rc = None if not (run_c is None) else"),
]


@pytest.mark.parametrize("obj, attr, old, new", DOMAIN, ids=[f"{o}.{a}:{old}" for o, a, old, _ in DOMAIN])
def test_domain_rules_kill(monkeypatch, obj, attr, old, new):
    if attr is None:
        monkeypatch.setattr(domain, obj, planted(getattr(domain, obj), old, new))
    else:
        cls = getattr(domain, obj)
        monkeypatch.setattr(cls, attr, planted(getattr(cls, attr), old, new))
    assert status("checker.domain_rules") == "failed"


def test_domain_rules_kills_an_expression_compared(monkeypatch):
    copy = mutated("symbt.proof.domain", "expr: Any = field(default=None, compare=False, repr=False)",
                   "expr: Any = field(default=None, compare=True, repr=False)")
    monkeypatch.setattr(domain, "Split", copy.Split)
    monkeypatch.setattr(domain, "sign", copy.sign)
    assert status("checker.domain_rules") == "failed"


def test_domain_rules_kills_a_function_in_the_split_repr(monkeypatch):
    # seed 21, :156: Split's func shown in its repr
    copy = mutated("symbt.proof.domain", "func: Callable[..., Any] | None = field(default=None, compare=False, "
                   "repr=False)", "func: Callable[..., Any] | None = field(default=None, compare=False, repr=True)")
    monkeypatch.setattr(domain, "Split", copy.Split)
    monkeypatch.setattr(domain, "sign", copy.sign)
    assert status("checker.domain_rules") == "failed"


# --------------------------------------------------------------------------- checker.mutation_rules

MUTATION = [
    ("_swap", "*e.args[i + 1:])))", "*e.args[i - 1:])))"),                                   # seed 21, :114
    ("_const", "new = n - 1 if n == -1 else n + 1", "new = n - 1 if not (n == -1) else n + 1"),   # seed 21, :124
    ("_is_coefficient", "and e != 0", "and e != 1"),                                           # seed 21, :137
    ("_convention", "if isinstance(e, sp.Abs):", "if not (isinstance(e, sp.Abs)):"),           # seed 21, :141
    ("_is_convention", "if isinstance(e, (sp.sign, sp.Abs)):",                                  # seed 21, :149
     "if not (isinstance(e, (sp.sign, sp.Abs))):"),
    ("_is_convention", "e.exp == sp.Rational(1, 2)", "e.exp != sp.Rational(1, 2)"),
    ("_sites", "[(path + (i,), a) for", "[(path - (i,), a) for"),                             # seed 21, :184
    ("_sites", "stack[0:0] = [", "stack[1:0] = ["),
    ("_index_pairs", "for b in syms[i + 1:]]", "for b in syms[i - 1:]]"),
    ("_replace_at", "args[path[0]] = _replace_at(", "args[path[1]] = _replace_at("),           # seed 21, :191
    ("_expr_mutants", "if mutated == expr or mutated in seen:",                                # seed 21, :207
     "if mutated != expr or mutated in seen:"),
    ("_parent_is_pow_exp", "node = node.args[i]", "node = node.args[i - 1]"),                  # seed 21, :217
    ("_parent_is_pow_exp", "and path[-1] == 1", "and path[-1] == 0"),
    ("index_parts", 'if idx.startswith("_"):', 'if not (idx.startswith("_")):'),
    ("mutate_value", "value in (1, -1):", "value in (0, -1):"),                                # seed 21, :230
    ("mutate_value", "(m.expr,) + value[i + 1:]", "(m.expr,) - value[i + 1:]"),
    ("mutate_value", 'last = "0" if value[-1] != "0" else "1"', 'last = "0" if value[-1] == "0" else "1"'),
    ("mutants", "seed: int = 0)", "seed: int = 1)"),                                           # seed 21, :250
    ("mutants", "elif isinstance(value, sp.Basic):", "elif not (isinstance(value, sp.Basic)):"),   # seed 21, :262
    ("mutants", "len(out) > limit:", "len(out) < limit:"),                                     # seed 21, :266
    ("why_no_mutants", 'return "it is a zero matrix: " + _SIDES', 'return "it is a zero matrix: " - _SIDES'),
    ("why_no_mutants", 'if value == 0 or value in ("", ()):', 'if value != 0 or value in ("", ()):'),
    ("_short", "if len(text) <= limit else", "if len(text) < limit else"),
    ("_short", "text[:limit - 3]", "text[:limit + 3]"),
]


@pytest.mark.parametrize("func, old, new", MUTATION, ids=[f"{f}:{o}" for f, o, _ in MUTATION])
def test_mutation_rules_kill(monkeypatch, func, old, new):
    fn = planted(getattr(mutation, func), old, new)
    monkeypatch.setattr(mutation, func, fn)
    if func.startswith("_is_") or func in ("_swap", "_const", "_convention"):
        # the operator table holds the functions it was built with: rebuild it from the module
        ops = {"_is_convention": "convention", "_convention": "convention", "_const": "change_const",
               "_swap": "swap_index", "_is_coefficient": "perturb"}
        name = ops[func]
        old_op = getattr(mutation.OPERATORS, name)
        new_op = old_op._replace(query=fn) if func.startswith("_is_") else old_op._replace(value=fn)
        monkeypatch.setattr(mutation, "OPERATORS", mutation.OPERATORS._replace(**{name: new_op}))
        monkeypatch.setattr(mutation.mutants, "__defaults__", (mutation.OPERATORS,))
    assert status("checker.mutation_rules") == "failed"


# ---------------------------------------------------------------- equivalent mutants (mutants-equivalent.toml)

def _source_lines(func) -> list[str]:
    import inspect
    import textwrap

    return [ln.strip() for ln in textwrap.dedent(inspect.getsource(func)).splitlines()]


def test_sign_label_at_zero_is_equivalent():
    # domain:189 `values[0] if v < 0` -> `if v <= 0`: they differ only at v == 0, and the line before returns None
    # for v == 0 (and for every non-finite v) -- so the mutant's extra case is never reached
    import mpmath as mp

    lines = _source_lines(domain._sign_label)
    guard = lines.index("if v == 0 or not mp.isfinite(v):")
    assert lines[guard + 1] == "return None"
    assert lines[guard + 2] == "return split.values[0] if v < 0 else split.values[1]"
    mutant = planted(domain._sign_label, "split.values[0] if v < 0 else", "split.values[0] if v <= 0 else")
    split = domain.sign(lambda z: z, name="s")
    values = [0, -0.0, 0.0, 1e-300, -1e-300, 1, -1, mp.mpf("1e-100000"), -mp.mpf("1e-100000"), mp.inf, -mp.inf,
              mp.nan, mp.mpc(0, 0), mp.mpc(-2, 0), mp.mpc(3, 0)]
    for v in values:
        assert mutant(v, split) == domain._sign_label(v, split), v


def test_seeded_subset_of_every_mutant_is_equivalent():
    # mutation:266 `len(out) > limit` -> `>= limit`: they differ only at limit == len(out), where the mutant draws
    # rng.sample(out, len(out)) -- a permutation of all of out -- and sorts it back by out.index: the list itself
    # (equal mutants are equal objects, so a tie in out.index leaves an equal list)
    import sympy as sp

    lines = _source_lines(mutation.mutants)
    assert "if limit is not None and len(out) > limit:" in lines
    assert "out = sorted(rng.sample(out, limit), key=out.index)" in lines
    mutant = planted(mutation.mutants, "len(out) > limit:", "len(out) >= limit:")
    x, y = sp.symbols("x y")
    for expr in (x + 2 * y, 3 * sp.sqrt(y) + sp.Abs(x) - 1, sp.Matrix([[x + 1, 2 * x]]), (1, 2.0, "ab"), x * y):
        full = mutation.mutants(expr)
        for seed in range(5):
            assert mutant(expr, limit=len(full), seed=seed) == full == mutation.mutants(expr, limit=len(full),
                                                                                          seed=seed)


def test_hint_joined_to_an_empty_note_is_equivalent():
    # identity:426 `" " + note` -> `" " - note`: the mutated operand is evaluated only when note is non-empty, and
    # check_identity joins a hint only to the note of a false verdict that is neither definite nor inconclusive.
    # decide builds such a verdict without a note: every `Verdict(False, ...)` it returns is definite, inconclusive
    # or has no note= (the default ""), and its other returns are true verdicts or entries of a matrix decided by
    # decide itself.  So note is "" there and the mutant's operand is never evaluated.
    import ast
    import inspect
    import textwrap

    from symbt.proof import decider

    tree = ast.parse(textwrap.dedent(inspect.getsource(decider.decide)))
    returns = [n.value for n in ast.walk(tree) if isinstance(n, ast.Return)]
    assert returns
    for value in returns:
        text = ast.unparse(value)
        if isinstance(value, ast.Call) and ast.unparse(value.func) == "Verdict" and value.args and \
                ast.unparse(value.args[0]) == "False":
            kw = {k.arg: ast.unparse(k.value) for k in value.keywords}
            assert kw.get("definite") == "True" or kw.get("inconclusive") == "True" or "note" not in kw, text
        else:
            assert (text.startswith("Verdict(True,") or text.startswith("Verdict.from_proof(")
                    or text in ("max(bad, key=lambda d: d.residual or 0.0)",
                                "max(undecided, key=lambda d: d.residual or 0.0)")), text
    assert "bad = [d for d in parts if not d.holds and not d.inconclusive]" in _source_lines(decider.decide)
    line = [ln for ln in _source_lines(identity.check_identity) if ln.startswith("note = (hint")]
    assert line == ['note = (hint + (" " + note if note else "")) if hint else note']
    original = eval(compile("lambda hint, note: " + line[0][len("note = "):], "identity", "eval"))
    mutant = eval(compile("lambda hint, note: " + line[0][len("note = "):].replace('" " + note', '" " - note'),
                          "identity", "eval"))
    for hint in ("", "hint: the sides agree"):
        assert original(hint, "") == mutant(hint, "")


def test_index_pairs_with_self_pairs_is_equivalent():
    # mutation:91 `syms[i + 1:]` -> `syms[i + 0:]`: the mutant adds the pairs (a, a); their only user, _swap, maps a
    # term t to t.xreplace({a: a}) == t for them and keeps a swap only `if u != t` -- so no mutant is added
    import sympy as sp

    assert [n for n in dir(mutation) if "_index_pairs" in _source_text(getattr(mutation, n))] == ["_index_pairs",
                                                                                                  "_swap"]
    assert "if u != t:" in _source_lines(mutation._swap)
    mutant = planted(mutation._index_pairs, "for b in syms[i + 1:]]", "for b in syms[i + 0:]]")
    p1, p2, p3, q1, x = sp.symbols("p1 p2 p3 q_1 x")
    for expr in (p1 * p2 ** 2 * p3 ** 3 + 1, p1 - 2 * p2 + x, q1 * p1 + p3 - q1, x + 1, p1 * sp.exp(p2) - p3 * q1):
        try:
            mutation._index_pairs, original = mutant, mutation._index_pairs
            got = mutation.mutants(expr)
        finally:
            mutation._index_pairs = original
        assert got == mutation.mutants(expr), expr


def _source_text(obj) -> str:
    import inspect

    try:
        return inspect.getsource(obj) if callable(obj) and getattr(obj, "__module__", "") == mutation.__name__ else ""
    except (OSError, TypeError):
        return ""
