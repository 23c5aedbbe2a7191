r"""Two rules of the proof engine that no claim ran (scene ``checker``; issue 21, seed 10's ``exact:26``,
``exact:107`` and ``lambdify:63``).

* ``checker.exact_route_names`` -- :func:`symbt.proof.exact.exact_route`: ``"sympy"`` asked is ``"sympy"``; ``"auto"``
  reads ``SYMBT_EXACT`` first (``sympy`` there gives ``"sympy"``), else takes ``"flint"`` exactly when python-flint
  imports (found here by ``importlib``, not by the code under test), and without it (the import check answering no
  for the length of the fact) ``"flint"`` asked is an ``ImportError`` naming python-flint while ``"auto"`` is
  ``"sympy"`` (seed 21); the exact layer's method names the route it
  took -- "one fraction in FLINT fmpq_mpoly" or "together/cancel" -- and both routes prove
  :math:`(x + 1)^2 = x^2 + 2x + 1` and :math:`(x + i)(x - i) = x^2 + 1` (the flint route's generator
  :math:`i`, reduced modulo :math:`i^2 + 1`) and refute :math:`(x + 1)^2 = x^2 + 2x + 2` and
  :math:`(1 + i)^2 x = 2x`.
* ``library.codegen_c_out`` -- :func:`symbt.codegen.files.generate` with the C target and no output directory
  refuses at once with a ``ValueError`` naming ``--out`` (its docstring: "required for C"), writing nothing.
* ``checker.lambdify_memo`` -- :func:`symbt.proof.lambdify.plain_lambdify`'s memo keeps the most recent
  ``MAX_ENTRIES`` functions: with the bound set to 3 (and the memo emptied, both restored after), four
  expressions made in turn leave the first one evicted (asked again, a new function) and the last three kept (the
  same objects), and a hit moves its entry to the recent end (the one evicted next is then another).
"""
from __future__ import annotations

import importlib.util
import os
from collections import OrderedDict

import sympy as sp

from ._facts import Facts
from ._facts import facts_failed as _bad
from ._facts import facts_verified as _ok
from .base import Outcome, claim


@claim("checker.exact_route_names", equation="checker", scene="checker",
       where="symbt.proof.exact: exact_route and the route exact_zero takes",
       statement="exact_route('sympy') is 'sympy'; 'auto' reads SYMBT_EXACT first, else is 'flint' exactly when "
                 "python-flint imports (without it, 'flint' is an ImportError naming python-flint); the method names "
                 "the route taken (FLINT fmpq_mpoly or together/cancel); "
                 "both routes prove (x + 1)^2 = x^2 + 2x + 1 and (x + i)(x - i) = x^2 + 1 and refute them off by 1 "
                 "and (1 + i)^2 x = 2x; unevaluated, (e^q)^(1/2) + e^(q/3) for a real q is S^3 + S^2 in S = e^(q/6), "
                 "(e^q)^(1/2) = e^(q/2) (q real) and (e^q)^2 = e^(2q) are proved exactly, and for a complex q "
                 "(e^q)^(1/2) is left alone")
def exact_routes() -> Outcome:
    from ..proof.exact import exact_route, exact_zero

    got: Facts = []
    flint = importlib.util.find_spec("flint") is not None
    got.append(("exact_route('sympy')", exact_route("sympy"), "sympy"))
    saved = os.environ.pop("SYMBT_EXACT", None)
    try:
        got.append(("exact_route('auto'), SYMBT_EXACT unset", exact_route("auto"), "flint" if flint else "sympy"))
        os.environ["SYMBT_EXACT"] = "sympy"
        got.append(("exact_route('auto'), SYMBT_EXACT=sympy", exact_route("auto"), "sympy"))
    finally:
        os.environ.pop("SYMBT_EXACT", None)
        if saved is not None:
            os.environ["SYMBT_EXACT"] = saved
    # python-flint missing (its import check answering no for the length of this fact): 'flint' asked for is an
    # ImportError that says what to install, 'auto' falls back to SymPy
    from ..proof import exact as exact_module
    found = exact_module._flint_imports
    exact_module._flint_imports = lambda: False      # type: ignore[assignment]
    try:
        try:
            asked: str = exact_route("flint")
        except ImportError as exc:
            asked = "ImportError naming python-flint" if "python-flint" in str(exc) else f"ImportError: {exc}"
        got.append(("without python-flint: exact_route('flint'), exact_route('auto')",
                    (asked, exact_route("auto")), ("ImportError naming python-flint", "sympy")))
    finally:
        exact_module._flint_imports = found
    x = sp.Symbol("x")
    names = {"flint": "one fraction in FLINT fmpq_mpoly", "sympy": "together/cancel"}
    for route in (["flint"] if flint else []) + ["sympy"]:
        zero, method, _ = exact_zero((x + 1) ** 2 - (x ** 2 + 2 * x + 1), {}, route=route)
        got.append((f"route {route}: proves, names itself", (zero, names[route] in method), (True, True)))
        off, method, definite = exact_zero((x + 1) ** 2 - (x ** 2 + 2 * x + 2), {}, route=route)
        got.append((f"route {route}: off by 1 refuted", (off, definite, names[route] in method), (False, True, True)))
    # the imaginary unit: the flint route adds a generator i and reduces modulo i^2 + 1
    for route in (["flint"] if flint else []) + ["sympy"]:
        zero, _, _ = exact_zero((x + sp.I) * (x - sp.I) - (x ** 2 + 1), {}, route=route)
        off, _, definite = exact_zero((1 + sp.I) ** 2 * x - 2 * x, {}, route=route)
        got.append((f"route {route}: (x + i)(x - i) = x^2 + 1 proved, (1 + i)^2 x = 2x refuted",
                    (zero, off, definite), (True, False, True)))
    from ..proof.exponentials import describe_variables, exponentials_as_monomials
    q = sp.Symbol("q")
    names_of = describe_variables(exponentials_as_monomials(sp.exp(q) + sp.E)[1])
    got.append(("the exponentials' names for e^q + e", names_of, "exp_1=e, exp_q=e^q"))
    # a power of an exponential, as written (SymPy's own evaluation would combine it): read as one for an integer
    # power, for a rational one exactly when the exponent is real (the principal power)
    qr = sp.Symbol("q", real=True)
    half, square = sp.Pow(sp.exp(qr), sp.S.Half, evaluate=False), sp.Pow(sp.exp(q), 2, evaluate=False)
    (rat,), variables = exponentials_as_monomials(half + sp.exp(qr / 3))
    S, d = variables[qr]
    got.append(("(e^q)^(1/2) + e^(q/3), q real: (d, the monomials)", (d, sp.expand(rat - S ** 3 - S ** 2)), (6, 0)))
    for diff, what in ((half - sp.exp(qr / 2), "(e^q)^(1/2) = e^(q/2), q real"),
                       (square - sp.exp(2 * q), "(e^q)^2 = e^(2q), q complex")):
        got.append((f"{what}: proved by the exact layer", exact_zero(diff, {})[0], True))
    (rat_c,), variables_c = exponentials_as_monomials(sp.Pow(sp.exp(q), sp.S.Half, evaluate=False))
    got.append(("(e^q)^(1/2), q complex: no exponential variable", q in variables_c, False))
    zero, method, _ = exact_zero((x + 1) ** 2 - (x ** 2 + 2 * x + 1), {})
    got.append(("the default route's method", names["flint" if flint else "sympy"] in method, True))
    bad = _bad("the exact routes", got)
    return bad or _ok("exact_route and exact_zero on both routes; python-flint found by importlib",
                      f"{len(got)} facts (python-flint {'installed' if flint else 'absent'})", "proof")


@claim("checker.lambdify_memo", equation="checker", scene="checker",
       where="symbt.proof.lambdify: plain_lambdify's memo, bounded by MAX_ENTRIES (least recently used out)",
       statement="with MAX_ENTRIES = 3 and an empty memo (both restored): of four expressions made in turn the first "
                 "is evicted and the last three kept; a hit moves its entry to the recent end")
def lambdify_memo() -> Outcome:
    from ..proof import lambdify as L

    got: Facts = []
    x = sp.Symbol("x")
    saved_memo, saved_max = L._MEMO, L.MAX_ENTRIES
    L._MEMO, L.MAX_ENTRIES = OrderedDict(), 3
    try:
        exprs = [x + k for k in range(4)]
        made = [L.plain_lambdify([x], e) for e in exprs]
        again = [L.plain_lambdify([x], e) is f for e, f in zip(exprs[1:], made[1:])]
        got.append(("the last three kept", again, [True, True, True]))
        got.append(("the first evicted", L.plain_lambdify([x], exprs[0]) is made[0], False))
        # the memo now holds x+2, x+3, x+0 (x+1 evicted by the re-made x+0); a hit on x+2 makes x+3 the oldest,
        # so a new x+9 evicts x+3
        L.plain_lambdify([x], exprs[2])
        L.plain_lambdify([x], x + 9)
        got.append(("after a hit on x+2 and a new x+9: x+2 kept, three entries",
                    (L.plain_lambdify([x], exprs[2]) is made[2], len(L._MEMO)), (True, 3)))
        got.append(("the evicted entry was x+3", sorted(str(k[1]) for k in L._MEMO), sorted(["x + 2", "x + 9", "x"])))
    finally:
        L._MEMO, L.MAX_ENTRIES = saved_memo, saved_max
    bad = _bad("plain_lambdify's memo", got)
    return bad or _ok("plain_lambdify's memo with a bound of 3", f"{len(got)} facts", "proof")


@claim("library.codegen_c_out", equation="checker", scene="library",
       where="symbt.codegen.files.generate: the C target's output directory",
       statement="generate(target='c') with no output directory raises ValueError naming --out before it renders "
                 "or writes anything")
def codegen_c_out() -> Outcome:
    from ..codegen import files

    got: Facts = []
    try:
        files.generate(None, ns=(2,), target="c")
        got.append(("generate(None, target='c')", "returned", "ValueError naming --out"))
    except ValueError as exc:
        got.append(("generate(None, target='c')", "ValueError naming --out" if "--out" in str(exc) else str(exc),
                    "ValueError naming --out"))
    bad = _bad("the C target's output directory", got)
    return bad or _ok("generate refuses the C target without an output directory", "1 fact", "proof")
