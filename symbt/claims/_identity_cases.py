"""The answers the claims of :mod:`symbt.claims.checker_identity` compare with: refused arguments and the
exceptions they deserve, relation forms and the polynomials they mean, hints, the complete mutant lists of a few
expressions -- each written down from the functions' docstrings, not computed by the code checked."""
from __future__ import annotations

from typing import Any

import sympy as sp

x = sp.Symbol("x", real=True)
y = sp.Symbol("y", positive=True)
SIDES = "declare both sides of the statement as parts (e.g. lhs and rhs) and let the check compare them"
SEVEN = {f"a{k}": str(k) for k in range(1, 8)}
SIX_SHOWN = "a1=1, a2=2, a3=3, a4=4, a5=5, a6=6, ..."


def calls_refused() -> list[tuple[str, dict[str, Any], str, str]]:
    """(what, keyword arguments of check_identity(x, x, ...), exception, words of its message)."""
    return [
        ("digits True", {"digits": True}, "TypeError", "digits must be an int"),
        ("digits 30.0", {"digits": 30.0}, "TypeError", "digits must be an int"),
        ("digits 0", {"digits": 0}, "ValueError", "digits must be positive"),
        ("digits -3", {"digits": -3}, "ValueError", "digits must be positive"),
        ("digits 1", {"digits": 1}, "ValueError", "digits must be at least 9"),
        ("digits 8", {"digits": 8}, "ValueError", "digits must be at least 9"),
        ("points True", {"points": True}, "TypeError", "points must be an int"),
        ("points 2.5", {"points": 2.5}, "TypeError", "points must be an int"),
        ("points 0", {"points": 0}, "ValueError", "points must be positive"),
        ("seed False", {"seed": False}, "TypeError", "seed must be an int"),
        ("seed 1.5", {"seed": 1.5}, "TypeError", "seed must be an int"),
        ("exact 1", {"exact": 1}, "TypeError", "exact must be True or False"),
        ("fixed a list", {"fixed": [1]}, "TypeError", "fixed must be a dict"),
        ("assumptions a list", {"assumptions": [x]}, "TypeError", "assumptions must be a dict"),
        ("assumptions of x True", {"assumptions": {x: True}}, "TypeError", "assumptions[x] must be a dict"),
        ("relations a string", {"relations": "x"}, "TypeError", "relations must be a dict"),
        ("relations bytes", {"relations": b"x"}, "TypeError", "relations must be a dict"),
        ("relations a number", {"relations": 3}, "TypeError", "relations must be a dict"),
    ]


def sides_refused() -> list[tuple[str, Any, Any, str, str]]:
    """(what, lhs, rhs, exception, words): sides SymPy cannot read, each naming its argument."""
    return [
        ("lhs None", None, x, "TypeError", "lhs must be a SymPy expression"),
        ("rhs a set", x, {1}, "TypeError", "rhs must be a SymPy expression"),
        ("lhs bytes", b"x", x, "TypeError", "lhs must be"),
        ("rhs a dict", x, {x: 1}, "TypeError", "rhs must be"),
        ("lhs a function", lambda: 1, x, "TypeError", "lhs must be"),
        ("rhs sp.sin", x, sp.sin, "TypeError", "rhs must be"),
        ("lhs an object", object(), x, "TypeError", "lhs must be a SymPy expression, number or matrix, not object"),
        ("lhs unparseable", "x +", x, "ValueError", "cannot parse lhs"),
        ("rhs an evaluated Eq", x, sp.Eq(x, x), "TypeError", "rhs is True"),
        ("an Eq and rhs 1", sp.Eq(x ** 2, x + 1), 1, "ValueError", "give either an Eq or lhs and rhs"),
        ("an Eq and rhs 2.5", sp.Eq(x ** 2, x + 1), 2.5, "ValueError", "give either an Eq or lhs and rhs"),
    ]


def relations_cases() -> list[tuple[str, Any, Any]]:
    """(what, relations, the {symbol: polynomial} the documented rules give, or an exception and its words)."""
    eta, mu, w, zeta, a, b, z = sp.symbols("eta mu w zeta a b z")
    quad = eta ** 2 - mu ** 2 - w
    return [
        ("None", None, {}),
        ("one Eq", sp.Eq(eta ** 2, mu ** 2 + w), {eta: quad}),
        ("one polynomial", eta ** 2 - mu - w, {eta: eta ** 2 - mu - w}),
        ("a dict of an Eq", {mu: sp.Eq(eta ** 2, mu ** 2 + w)}, {mu: quad}),
        ("a dict of a polynomial", {w: quad}, {w: quad}),
        ("pairs", [(mu, sp.Eq(eta ** 2, mu ** 2 + w)), (zeta, zeta ** 3 - a)], {mu: quad, zeta: zeta ** 3 - a}),
        ("a tuple of Eqs", (sp.Eq(eta ** 2, w), sp.Eq(zeta ** 3, mu)), {eta: eta ** 2 - w, zeta: zeta ** 3 - mu}),
        # the side with a single symbol, from either side -- not the symbol of highest degree
        ("Eq(w + mu^3, eta)", [sp.Eq(w + mu ** 3, eta)], {eta: -eta + mu ** 3 + w}),
        ("Eq(w, mu^3 + eta mu)", [sp.Eq(w, mu ** 3 + eta * mu)], {w: -eta * mu - mu ** 3 + w}),
        ("Eq(eta^2, eta + 1)", [sp.Eq(eta ** 2, eta + 1)], {eta: eta ** 2 - eta - 1}),
        # no single-symbol side: the symbol of highest degree, whatever its place in the alphabet
        ("Eq(a z, b^3 + z^2)", [sp.Eq(a * z, b ** 3 + z ** 2)], {b: a * z - b ** 3 - z ** 2}),
        ("a z + b^3 + z^2", [a * z + b ** 3 + z ** 2], {b: a * z + b ** 3 + z ** 2}),
        ("a tie", [eta * mu - 1], ("ValueError", "cannot tell which symbol it constrains")),
        ("no symbol", [sp.Integer(1)], ("ValueError", "involves no symbol")),
        ("a key that is a name", {"eta": quad}, ("TypeError", "relation key must be a symbol")),
        ("a relation without its key", {zeta: quad}, ("ValueError", "does not involve zeta")),
        ("two relations for eta", [sp.Eq(eta ** 2, w), (eta, eta ** 3 - w)], ("ValueError", "two relations for eta")),
    ]


def hint_cases() -> list[tuple[str, Any, Any, str]]:
    """(what, lhs, rhs, the start of the hint): K(k) written with the modulus, on either side, and the reverse."""
    k, z = sp.symbols("k z", positive=True)
    by_modulus = sp.pi / 2 * sp.hyper([sp.S.Half, sp.S.Half], [1], k ** 2)      # K of modulus k
    by_parameter = sp.pi / 2 * sp.hyper([sp.S.Half, sp.S.Half], [1], k)          # K of parameter k
    to_m = "hint: the sides agree if the modulus k is read as the parameter m = k**2"
    to_k = "hint: the sides agree if the parameter m is read as the modulus k = sqrt(m)"
    return [("elliptic lhs", sp.elliptic_k(k), by_modulus, to_m), ("elliptic rhs", by_modulus, sp.elliptic_k(k), to_m),
            ("parameter for modulus", sp.elliptic_k(k ** 2), by_parameter, to_k),
            ("matrices", sp.Matrix([[by_modulus, k]]), sp.Matrix([[sp.elliptic_k(k), k]]), to_m),
            ("incomplete, two arguments", sp.elliptic_f(z, k), sp.elliptic_f(z, k ** 2), to_m),
            # the screen alone decides: exactly, K(k^2) + 1e-40 is no K(k^2), at 20 digits it is
            ("within the screen's tolerance", sp.elliptic_k(k), sp.elliptic_k(k ** 2) + sp.Integer(10) ** -40, to_m),
            ("no elliptic function", sp.Matrix([[k, 1]]), sp.Matrix([[k + 1, 1]]), ""),
            ("no swap agrees", sp.elliptic_k(k), sp.elliptic_e(k), "")]


def domain_refusals() -> list[tuple[str, Any, str, str]]:
    from ..proof.domain import Domain as TypedDomain
    from ..proof.domain import choice as typed_choice
    from ..proof.domain import regime as typed_regime
    from ..proof.domain import sign as typed_sign

    # typed Any: the arguments below are wrong on purpose
    Domain: Any = TypedDomain
    choice: Any = typed_choice
    regime: Any = typed_regime
    sign: Any = typed_sign
    dom = Domain({"t": (0, 1)})
    return [
        ("Domain of a list", lambda: Domain([("t", (0, 1))]), "TypeError", "non-empty mapping"),
        ("Domain of {}", lambda: Domain({}), "TypeError", "non-empty mapping"),
        ("a number as a name", lambda: Domain({3: (0, 1)}), "TypeError", "variable names"),
        ("an empty name", lambda: Domain({"": (0, 1)}), "TypeError", "variable names"),
        ("where not a function", lambda: Domain({"t": (0, 1)}, where=3), "TypeError", "where"),
        ("seed a string", lambda: Domain({"t": (0, 1)}, seed="1"), "TypeError", "seed is an integer"),
        ("draws_per_point 0", lambda: Domain({"t": (0, 1)}, draws_per_point=0), "TypeError", "draws_per_point"),
        ("draws_per_point 1.5", lambda: Domain({"t": (0, 1)}, draws_per_point=1.5), "TypeError", "draws_per_point"),
        ("a cell of a non-split", lambda: dom.cells("t"), "TypeError", "a split is made by"),
        ("two splits named b", lambda: dom.cells(choice("b", (1,)), choice("b", (2,))), "ValueError", ": b"),
        ("a split named as a variable", lambda: dom.cells(choice("t", (1,))), "ValueError", ": t"),
        ("per_cell 0", lambda: dom.sample(per_cell=0), "ValueError", "per_cell"),
        ("per_cell True", lambda: dom.sample(per_cell=True), "ValueError", "per_cell"),
        ("per_cell 1.5", lambda: dom.sample(per_cell=1.5), "ValueError", "per_cell"),
        ("dps 14", lambda: dom.sample(dps=14), "ValueError", "dps"),
        ("dps True", lambda: dom.sample(dps=True), "ValueError", "dps"),
        ("tol -1", lambda: dom.evaluate(printed=lambda t: 0, tol=-1), "ValueError", "tol"),
        ("tol nan", lambda: dom.evaluate(printed=lambda t: 0, tol=float("nan")), "ValueError", "tol"),
        ("a residual of a missing variable", lambda: dom.evaluate(printed=lambda t, q: 0), "ValueError",
         "takes q, which the points lack"),
        ("a residual without a signature", lambda: dom.evaluate(printed=max), "TypeError", "cannot read"),
        ("a residual that returns a string", lambda: dom.evaluate(printed=lambda t: "a", per_cell=1), "TypeError",
         "returned 'a'"),
        ("a split of a missing variable", lambda: dom.sample(sign("t - q")), "ValueError", "names q"),
        ("a regime's unknown label", lambda: dom.sample(regime("r", lambda t: "c", ("a", "b"))), "ValueError",
         "returned 'c'"),
        ("a regime without a function", lambda: regime("r", 3, ("a",)), "TypeError", "func must be"),
        ("a choice of nothing", lambda: choice("b", ()), "ValueError", "one or more distinct"),
        ("a choice of 1 twice", lambda: choice("b", (1, 1)), "ValueError", "one or more distinct"),
        ("a choice of None", lambda: choice("b", (None,)), "TypeError", "numbers or strings"),
        ("sign of a number", lambda: sign(3), "TypeError", "sign(expr)"),
        ("sign of an unnamed lambda", lambda: sign(lambda t: t), "ValueError", "give the split a name"),
        ("sign with one label", lambda: sign("t", labels=("a",)), "ValueError", "two different labels"),
        ("sign with equal labels", lambda: sign("t", labels=("a", "a")), "ValueError", "two different labels"),
        ("sign of a non-expression", lambda: sign("t +"), "ValueError", "not an expression"),
    ]


def mutant_lists() -> list[tuple[Any, set[tuple[str, str, Any]]]]:
    """Expressions with every mutant the documented operators give: (operator, words, expression)."""
    f = sp.Function("f")
    b, p1, p2 = sp.symbols("branch p1 p2")
    third = sp.Rational(3000003, 1000000)
    return [
        (3 * sp.sqrt(y) + sp.Abs(x) - 1, {
            ("flip_sign", "flip the sign of -1", 3 * sp.sqrt(y) + sp.Abs(x) + 1),
            ("flip_sign", "flip the sign of 3*sqrt(y)", -3 * sp.sqrt(y) + sp.Abs(x) - 1),
            ("flip_sign", "flip the sign of Abs(x)", 3 * sp.sqrt(y) - sp.Abs(x) - 1),
            ("drop_term", "drop the term -1", 3 * sp.sqrt(y) + sp.Abs(x)),
            ("drop_term", "drop the term 3*sqrt(y)", sp.Abs(x) - 1),
            ("drop_term", "drop the term Abs(x)", 3 * sp.sqrt(y) - 1),
            ("change_const", "change the constant -1 to -2", 3 * sp.sqrt(y) + sp.Abs(x) - 2),
            ("change_const", "change the constant 3 to 4", 4 * sp.sqrt(y) + sp.Abs(x) - 1),
            ("perturb", "perturb the coefficient -1 by a relative 1e-6",
             3 * sp.sqrt(y) + sp.Abs(x) - sp.Rational(1000001, 1000000)),
            ("perturb", "perturb the coefficient 3 by a relative 1e-6", third * sp.sqrt(y) + sp.Abs(x) - 1),
            # sqrt(y) -> -sqrt(y) is -3 sqrt(y), the flip above: one mutant, not two
            ("convention", "drop the absolute value in Abs(x)", x + 3 * sp.sqrt(y) - 1)}),
        # the exponents 3 and -1 are structure, not constants; sign(x) -> -sign(x) inside exp is its own mutant
        (sp.exp(sp.sign(x)) + x ** 3 + 1 / y, {
            ("flip_sign", "flip the sign of x**3", -x ** 3 + sp.exp(sp.sign(x)) + 1 / y),
            ("flip_sign", "flip the sign of 1/y", x ** 3 + sp.exp(sp.sign(x)) - 1 / y),
            ("flip_sign", "flip the sign of exp(sign(x))", x ** 3 - sp.exp(sp.sign(x)) + 1 / y),
            ("drop_term", "drop the term x**3", sp.exp(sp.sign(x)) + 1 / y),
            ("drop_term", "drop the term 1/y", x ** 3 + sp.exp(sp.sign(x))),
            ("drop_term", "drop the term exp(sign(x))", x ** 3 + 1 / y),
            ("convention", "swap the sign convention sign(x) -> -sign(x)", x ** 3 + sp.exp(-sp.sign(x)) + 1 / y)}),
        # a sum inside a function, under a coefficient
        (2 * f(x + 1), {
            ("flip_sign", "flip the sign of 1", 2 * f(x - 1)), ("flip_sign", "flip the sign of x", 2 * f(1 - x)),
            ("drop_term", "drop the term 1", 2 * f(x)), ("drop_term", "drop the term x", 2 * f(sp.Integer(1))),
            ("change_const", "change the constant 2 to 3", 3 * f(x + 1)),
            ("change_const", "change the constant 1 to 2", 2 * f(x + 2)),
            ("perturb", "perturb the coefficient 2 by a relative 1e-6", sp.Rational(1000001, 500000) * f(x + 1)),
            ("perturb", "perturb the coefficient 1 by a relative 1e-6", 2 * f(x + sp.Rational(1000001, 1000000)))}),
        # a branch symbol and indexed symbols: branch -> -branch, and p1 <-> p2 inside the middle term of three
        (sp.exp(b * x) + p1 * p2 ** 2 + 3, {
            ("flip_sign", "flip the sign of 3", p1 * p2 ** 2 + sp.exp(b * x) - 3),
            ("flip_sign", "flip the sign of p1*p2**2", -p1 * p2 ** 2 + sp.exp(b * x) + 3),
            ("flip_sign", "flip the sign of exp(branch*x)", p1 * p2 ** 2 - sp.exp(b * x) + 3),
            ("drop_term", "drop the term 3", p1 * p2 ** 2 + sp.exp(b * x)),
            ("drop_term", "drop the term p1*p2**2", sp.exp(b * x) + 3),
            ("drop_term", "drop the term exp(branch*x)", p1 * p2 ** 2 + 3),
            ("swap_index", "swap p1 and p2 in p1*p2**2", p1 ** 2 * p2 + sp.exp(b * x) + 3),
            ("change_const", "change the constant 3 to 4", p1 * p2 ** 2 + sp.exp(b * x) + 4),
            ("perturb", "perturb the coefficient 3 by a relative 1e-6", p1 * p2 ** 2 + sp.exp(b * x) + third),
            ("convention", "swap the branch convention branch -> -branch", p1 * p2 ** 2 + 3 + sp.exp(-b * x))}),
        # no sum: only the square root is a convention (y**2 is not, and its 2 is structure)
        (sp.exp(sp.sqrt(y)) * sp.sin(y ** 2), {
            ("convention", "swap the sign convention sqrt(y) -> -sqrt(y)", sp.exp(-sp.sqrt(y)) * sp.sin(y ** 2))}),
    ]


def value_mutants() -> list[tuple[Any, list[tuple[str, str, Any]]]]:
    return [(True, [("convention", "negate True", False)]), (False, [("convention", "negate False", True)]),
            (1, [("convention", "swap the branch +1 -> -1", -1)]),
            (-1, [("convention", "swap the branch -1 -> +1", 1)]),
            (0, []), (0.0, []), ("", []), (None, []), ([1], []),
            (2, [("flip_sign", "negate 2", -2), ("perturb", "perturb 2 by a relative 1e-6", 2 * (1 + 1e-6))]),
            (-2.5, [("flip_sign", "negate -2.5", 2.5), ("perturb", "perturb -2.5 by a relative 1e-6",
                                                         -2.5 * (1 + 1e-6))]),
            (sp.Float(1.5), [("flip_sign", "negate 1.50000000000000", sp.Float(-1.5)),
                             ("perturb", "perturb 1.50000000000000 by a relative 1e-6", sp.Float(1.5) * (1 + 1e-6))]),
            ("abc", [("change_const", "change the last character of abc... to 0", "ab0")]),
            ("a0", [("change_const", "change the last character of a0... to 1", "a1")]),
            ((1, "x0"), [("convention", "entry 0: swap the branch +1 -> -1", (-1, "x0")),
                         ("change_const", "entry 1: change the last character of x0... to 1", (1, "x1"))])]


def ordered_mutants() -> list[tuple[Any, list[tuple[str, str]]]]:
    """Expressions with their mutants' (operator, words) in the documented order: operator by operator, and for
    each its sites in preorder (a node, then the subtree of its first argument, then of its second ...)."""
    p1, p2, p3 = sp.symbols("p1 p2 p3")
    z = sp.Symbol("z")
    nested = [("flip_sign", "flip the sign of sqrt(z + 1)"), ("flip_sign", "flip the sign of 2*Abs(z - 3)"),
              ("flip_sign", "flip the sign of 1"), ("flip_sign", "flip the sign of z"),
              ("flip_sign", "flip the sign of -3"),
              ("drop_term", "drop the term sqrt(z + 1)"), ("drop_term", "drop the term 2*Abs(z - 3)"),
              ("drop_term", "drop the term 1"), ("drop_term", "drop the term z"), ("drop_term", "drop the term -3"),
              ("drop_term", "drop the term z"),
              ("change_const", "change the constant 1 to 2"), ("change_const", "change the constant 2 to 3"),
              ("change_const", "change the constant -3 to -2"),
              ("perturb", "perturb the coefficient 1 by a relative 1e-6"),
              ("perturb", "perturb the coefficient 2 by a relative 1e-6"),
              ("perturb", "perturb the coefficient -3 by a relative 1e-6"),
              ("convention", "drop the absolute value in Abs(z - 3)")]
    three = [("flip_sign", "flip the sign of 1"), ("flip_sign", "flip the sign of p1*p2**2*p3**3"),
             ("drop_term", "drop the term 1"), ("drop_term", "drop the term p1*p2**2*p3**3"),
             ("swap_index", "swap p1 and p2 in p1*p2**2*p3**3"), ("swap_index", "swap p1 and p3 in p1*p2**2*p3**3"),
             ("swap_index", "swap p2 and p3 in p1*p2**2*p3**3"),
             ("change_const", "change the constant 1 to 2"),
             ("perturb", "perturb the coefficient 1 by a relative 1e-6")]
    return [(sp.sqrt(z + 1) + 2 * sp.Abs(z - 3), nested), (p1 * p2 ** 2 * p3 ** 3 + 1, three)]


def summaries() -> list[tuple[str, dict[str, Any], str]]:
    """(status, fields of an IdentityResult with method "m" and sides x + 1, its summary)."""
    return [
        ("proved", {"residual": 0.0}, "proved by m"),
        ("verified", {"residual": 1e-60, "digits": 50.0, "points": [{"x": "1"}, {"x": "2"}]},
         "verified numerically to 50 digits at 2 random points (worst relative residual 1.0e-60; m)"),
        ("verified", {"residual": 1e-60, "digits": 51.0, "points": [{}]},
         "verified numerically to 50 digits at 1 random points (worst relative residual 1.0e-60; m)"),
        ("verified", {"residual": 4e-13, "digits": 12.4, "points": [{}], "requested_digits": 30},
         "verified numerically to 12 of the 30 digits asked for at 1 random points (worst relative residual "
         "4.0e-13; m)"),
        ("verified", {"residual": 1e-31, "digits": None, "points": [{}], "requested_digits": 30},
         "verified numerically to 30 digits at 1 random points (worst relative residual 1.0e-31; m)"),
        ("inconclusive", {"residual": 3e-21, "error": 2e-20, "requested_digits": 30},
         "inconclusive: cannot tell at 30 digits (relative residual 3e-21, evaluation error 2.0e-20; m)"),
        ("inconclusive", {"residual": None, "error": None},
         "inconclusive: cannot tell at 50 digits (relative residual undefined, evaluation error unknown; m)"),
        ("false", {"residual": 0.5, "counterexample": SEVEN, "note": "hint: k is m"},
         f"false: counterexample {SIX_SHOWN} (relative residual 0.5; m); hint: k is m"),
        ("false", {"residual": 0.5, "counterexample": dict(list(SEVEN.items())[:6])},
         "false: counterexample a1=1, a2=2, a3=3, a4=4, a5=5, a6=6 (relative residual 0.5; m)"),
        ("false", {"residual": None, "counterexample": {"x": "2"}, "note": "other words"},
         "false: counterexample x=2 (relative residual undefined; m)"),
        ("false", {"residual": 2.0, "counterexample": None}, "false: counterexample - (relative residual 2; m)"),
        ("false", {"residual": 2.0, "counterexample": {}}, "false: counterexample - (relative residual 2; m)"),
    ]


def displays() -> list[tuple[str, dict[str, Any], list[str], list[str]]]:
    """(status, fields, what the HTML display must contain, what it must not)."""
    return [
        ("proved", {"residual": 0.0}, ["symbt-proved", "<th style='text-align:left;padding-right:1em'>method</th>"
                                       "<td>m</td>", "#2e7d32"], ["residual", "note"]),
        ("verified", {"residual": 1e-60, "digits": 48.0, "points": [{"x": "1"}, {"x": "2"}]},
         ["1.00e-60 (48 digits agree, 50 requested)", "x=1<br>x=2"], ["counterexample", "note"]),
        ("inconclusive", {"residual": 3e-21, "error": 2e-20, "requested_digits": 30},
         ["3.00e-21 (evaluation error 2.0e-20: cannot tell at 30 digits)", "#6a1b9a"], ["counterexample"]),
        ("inconclusive", {"residual": 3e-21, "error": None}, ["evaluation error unknown: cannot tell"], []),
        ("false", {"residual": 0.5, "counterexample": SEVEN, "note": "a note"},
         ["<td>0.5</td>", "a7=7", ">note</th><td>a note</td>", "#c62828"], ["..."]),
        ("false", {"residual": None, "counterexample": {"x": "2"}}, ["<td>undefined</td>", "<td>x=2</td>"], ["note"]),
    ]


def why_cases() -> list[tuple[Any, str]]:
    """(a part without mutants, the words why_no_mutants gives for it)."""
    a = sp.Symbol("a")
    why = [(sp.zeros(2, 2), "it is a zero matrix: " + SIDES),
             (sp.Matrix([[a, 1]]), "a matrix of bare symbols and zeros: declare the entries' expressions (the matrix "
                                   "the statement is about)"),
             (sp.Matrix([[sp.sin(x) * sp.cos(x)]]), "no operator applies to any entry (no sum, no numeric constant, "
                                                    "no sign, Abs or sqrt): declare the entries' expressions with "
                                                    "their terms, or " + SIDES),
             (sp.S(0), "it is 0: " + SIDES), (a, "it is the bare symbol a: declare the expression it stands for"),
             (sp.sin(x) * sp.cos(x), "no operator applies to sin(x)*cos(x) (no sum, no numeric constant other than 0, "
                                     "no sign, Abs or sqrt): declare the expression with its terms, or " + SIDES),
             (False, "it is False: " + SIDES), (0.0, "it is 0.0: " + SIDES), ((), "it is (): " + SIDES),
             ("", "it is '': " + SIDES), ("abc", "no operator applies to 'abc': " + SIDES),
             (2, "no operator applies to 2: " + SIDES),
             ([1], "a list is not mutated: parts must be SymPy expressions or matrices, numbers, strings or tuples of "
                   "them")]
    for width in (60, 61):     # an expression of 60 characters is shown whole, one of 61 cut to 57 and "..."
        long_name = sp.Function("g" * (width - 10))(x) * sp.sin(x)
        text = sp.sstr(long_name)
        why.append((long_name, f"no operator applies to {text if width == 60 else text[:57] + '...'} (no sum, no "
                                "numeric constant other than 0, no sign, Abs or sqrt): declare the expression with "
                                "its terms, or " + SIDES))
    return why
