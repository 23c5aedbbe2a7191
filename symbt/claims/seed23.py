r"""What the samples of seeds 23 and 24 found unread (issue 21).

* ``checker.relation_degree`` -- :func:`symbt.proof.reduce_modulo` refuses (``ValueError``) a relation that is not a
  polynomial of degree 1 or more in its own symbol (``{x: y - 1}``, ``{x: 2}``): the remainder of a division by
  something constant in ``x`` is 0, so such a relation would "prove" any statement, ``x y = 0`` included -- and so
  does the exact layer, :func:`symbt.proof.exact.exact_zero`, on the sympy route and on FLINT's where python-flint is
  installed (seed 28: FLINT's reduction divided by a relation of degree 0 and proved ``x y = 0``, the relation
  tested only later, in the screen); a relation of degree 2 reduces ``x^3 + y`` to ``x y + y`` (written out by
  hand).  Seed 23: a degree test at ``< 0`` let the constant relation through.
* ``checker.inclusive_bounds`` -- the tolerances are inclusive, as their docstrings say: a sampled
  :class:`~symbt.proof.verdict.Verdict` whose residual and estimated error both *equal* the tolerance holds; a
  :class:`~symbt.proof.cells.CellTable` sample at the tolerance counts as holding, and a cell whose residuals are all
  exactly 0 still names a sample as its worst point (seed 23: the last two as strict comparisons).
* ``library.source_lines`` -- the rewritten kernels keep their source's place, so tracebacks (and the line map
  ``symbt mutate --source`` traces) name the source's lines: the plain-Python block kernels of
  :mod:`symbt.numeric.float64.block_python` and a function rewritten by
  :func:`symbt.numeric.core.inline.inlined` start at their source function's first line in its file.  And the
  inliner spreads a body's tuple read by constant index, ``t[0]`` included, into one local per element: the inlined
  code subscripts nothing and gives the plain call's value (seed 23: index 0 left the tuple built).
* ``checker.magnitude_moduli`` -- :func:`symbt.proof.magnitude.magnitude`, the size the screen divides by, stays a
  modulus whatever the symbols' assumptions (a relation's root can be complex at a sample): ``magnitude(p)`` for a
  positive ``p`` is 5 at ``p = 3 + 4i``, ``magnitude(eta^2)`` is 1 at ``eta = i`` (seed 24: an evaluated ``Abs``
  dropped the modulus of a positive symbol).
* ``library.reference_edges`` -- three edges of :mod:`symbt.reference` checked against routes outside it: the
  one-step shift of the elliptic solution at a band edge (``I1 = 0, I2 = 7, lam0 = 4, mu = 1``: ``T2 = 2``,
  ``T1 = 18`` exactly) has the real phase ``dtheta1_real = -branch arccosh(9)`` (mpmath's ``acosh``), and with
  ``lam0 = 2`` (``T1 = 2``, ``T2 = -6``; seed 28: a strict test at ``T1``) ``-branch arccosh(3)``, as its
  docstring says (None only where some ``|T| < 2``); :func:`~symbt.reference.spectral.flow_coefficients_jacobian`
  gives all ``N + 1`` pairs ``(dc_k/dlam0, dc_k/dmu)``, each within ``1e-12`` of central differences of the
  quadrature route ``flow_coefficients_mp`` (both branches); and
  :func:`~symbt.reference.inverse.solve_parameters` from a target whose small-mu start ``c_1/c_0 = 2`` lies in a
  band (``tr = 0.74`` there) refuses with ``ValueError`` (seed 24: the start's square root of a negative number
  made it complex, and the refusal a ``TypeError``).  At an exact band edge of the free chain (``p = q = 0``,
  N = 2: ``tr L(lam) = lam^2 - 2``, so ``tr = 2`` at ``lam = 2``): ``flow_coefficients_mp`` over ``[2, 3]`` with
  ``check=False`` integrates through the edge's integrable singularity to the closed forms
  ``c_0 = -b arccos(2/3)/2``, ``c_1 = -b arccosh(3/2)``, ``c_2 = -b sqrt 5`` (within ``1e-8`` at 15 digits; seed 25: the
  quadrature asked to check anyway), with the default ``check`` it refuses, and ``phi_gradient`` there refuses with
  ``NoRealFlowError`` (seed 25: a strict test divided by zero); the Jacobian's default branch is +1 (seed 25).
* ``paths.rows_apart.n3`` -- the general float64 orbit (``general_orbit``, what ``backend="numpy"`` runs for an
  ensemble) with a row that has no real map beside two rows far from the origin (``q + 300.3``, ``q - 211.7``):
  the first is refused at step 1 with the positivity code, a fourth row whose neighbours are ``MAX_DQ_FLOAT64 + 50``
  apart with the range code (it leaves the batch before the step, which would raise on it), and every stored state
  of the others, low parts of the positions included, is bit for bit that of each row alone (a consistency check;
  seed 24: the compensated centre of mass written to the neighbouring row once a row had left the batch; seed 27:
  the range test's branch inverted).
* ``checker.matrix_methods`` -- :func:`symbt.decide` on matrices says how each entry was proved: a 1x1 matrix is
  proved with its entry's method, and ``[(x + 1)^2, cosh^2 x - sinh^2 x] = [x^2 + 2x + 1, 1]`` names both entries'
  exact methods (the second rewrites ``exp``), in entry order (seed 25: the method taken from the second entry;
  before, a matrix named its first entry's method only).
* ``library.verify_points`` -- :func:`symbt.codegen.verify.points`, where the emitted functions of ``lam`` are
  compared with their source, samples both spectral parameters ``lam0 + mu`` and ``lam0 - mu`` of every state
  it draws (N = 2, 3; seed 25: ``lam0 - mu`` twice), and at the points of the functions of ``p, q`` (and ``c``) --
  ``invariants``, ``hamiltonian_fields``, ``flow_field`` -- every coordinate takes both signs and every two of one
  site (``p_i, q_i``, ...) are alike in sign at one point and opposite at another (seed 26: ``q``'s signs those of
  ``p``, so ``p_i q_i`` was never negative).  A check of the verifier's coverage, not of a value.
* ``library.project_roots`` -- :func:`symbt.codegen.project.find_project` (which checkout ``symbt codegen`` acts on)
  in throw-away directories: from two levels below a directory holding a ``pyproject.toml`` named ``symbt`` and a
  ``symbt/`` package it finds that directory; named ``other``, or without the package, none (seed 24: the name
  test negated, which no claim had reached).
"""
from __future__ import annotations

import dis
import inspect
import tempfile
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import Any

import mpmath as mp
import numpy as np
import sympy as sp

from .base import Outcome, claim, failed


def _by_hand(method: str, got: Any, want: Any, detail: str | None = None) -> Outcome:
    """The outcome of a comparison with values written out by hand: verified iff ``got == want``."""
    if got != want:
        return failed(method, detail=f"got {got}, want {want}")
    return Outcome("verified", method, evidence="proof", n_scope="all", detail=f"{got}" if detail is None else detail)


@claim("checker.relation_degree", equation="checker", scene="checker",
       where="symbt.proof.exact.reduce_modulo, exact_zero (both routes): the relations' degree in their own symbols",
       statement="reduce_modulo(x y, {x: y - 1}) and reduce_modulo(x y, {x: 2}) raise ValueError (a division by "
                 "something constant in x leaves remainder 0: it would prove x y = 0), and so does the exact layer "
                 "(exact_zero) on the sympy route and on FLINT's where installed; reduce_modulo(x^3 + y, "
                 "{x: x^2 - y}) = x y + y")
def relation_degree() -> Outcome:
    from ..proof import reduce_modulo
    from ..proof.exact import exact_route, exact_zero

    x, y = sp.symbols("x y")
    got: dict[str, Any] = {}
    want: dict[str, Any] = {}
    # reduce_modulo, and the exact layer on each route it has here (FLINT's reduction divides too)
    routes = sorted({"sympy", exact_route("auto")})
    for name, rel in (("y - 1", y - 1), ("2", sp.Integer(2))):
        calls: list[tuple[str, Callable[[], object]]] = [("reduce_modulo", partial(reduce_modulo, x * y, {x: rel}))]
        calls += [(f"exact_zero[{rt}]", partial(exact_zero, x * y, {x: rel}, rt)) for rt in routes]
        for what, call in calls:
            try:
                got[f"{what}, {name}"] = f"gave {call()}"
            except ValueError:
                got[f"{what}, {name}"] = "ValueError"
            want[f"{what}, {name}"] = "ValueError"
    got["x^2 - y"] = sp.expand(reduce_modulo(x ** 3 + y, {x: x ** 2 - y}) - (x * y + y)) == 0
    want["x^2 - y"] = True
    return _by_hand("exact: relations written out by hand", got, want)


@claim("checker.inclusive_bounds", equation="checker", scene="checker",
       where="symbt.proof.verdict.Verdict.sampled, symbt.proof.cells.CellTable.add: the tolerance's edge",
       statement="Verdict.sampled(1e-20, tol=1e-20, error=1e-20) holds; a CellTable sample with residual equal "
                 "to the tolerance holds; a cell whose residuals are all exactly 0 names a sample as its worst")
def inclusive_bounds() -> Outcome:
    from ..proof.cells import CellTable
    from ..proof.verdict import Verdict

    tol = 1e-20
    got: dict[str, Any] = {"verdict at tol": Verdict.sampled(tol, tol=tol, error=tol).holds}
    table = CellTable(tol=tol)
    table.add({"s": 1}, printed=tol, point={"x": "1"})
    got["cell at tol"] = (table.rows[(("s", 1),)].printed_holds, table.printed_holds_everywhere())
    zeros = CellTable(tol=tol)
    for k in range(3):
        zeros.add({"s": -1}, printed=0, point={"x": str(k)})
    worst, point = zeros.worst()
    got["all-zero cell's worst"] = (worst, (point or {}).get("x") in ("0", "1", "2"))
    want: dict[str, Any] = {"verdict at tol": True, "cell at tol": (1, True), "all-zero cell's worst": (0.0, True)}
    return _by_hand("exact: values at the tolerance written by hand", got, want)


def _pair(a: float, b: float) -> tuple[float, float]:
    return a + b, a - b


def _reads_pair(a: float, b: float) -> float:
    t = _pair(a, b)
    return t[0] * t[1]


def _subscripts(fn: Any) -> int:
    return sum(i.opname == "BINARY_SUBSCR" for i in dis.get_instructions(fn))


@claim("library.source_lines", equation="checker", scene="library",
       where="symbt.numeric.float64.block_python.kernel, symbt.numeric.core.inline.inlined",
       statement="every plain-Python block kernel and an inlined function start at their source function's first "
                 "line in its file (tracebacks name the source); a body's tuple read as t[0], t[1] is spread: the "
                 "inlined code subscripts nothing and gives (a + b)(a - b)")
def source_lines() -> Outcome:
    from ..numeric.core.inline import inlined
    from ..numeric.float64 import block_python
    from ..numeric.float64 import kernels_block as KB

    bad = []
    # the functions rewritten from source (the others are the module's own, bound as they are)
    names = [n for n, f in block_python._KERNELS.items() if inspect.isfunction(f) and f is not getattr(KB, n, f)]
    for name in names:
        made, src = block_python._KERNELS[name].__code__, getattr(KB, name).__code__
        if (made.co_firstlineno, made.co_filename) != (src.co_firstlineno, src.co_filename):
            bad.append(f"block kernel {name}: line {made.co_firstlineno} of {made.co_filename}, source at "
                       f"{src.co_firstlineno} of {src.co_filename}")
    g = inlined(_reads_pair, "reads_pair_inline", {"_pair": "body"}, {"_pair": _pair})
    src = _reads_pair.__code__
    if (g.__code__.co_firstlineno, g.__code__.co_filename) != (src.co_firstlineno, src.co_filename):
        bad.append(f"inlined: line {g.__code__.co_firstlineno}, source at {src.co_firstlineno}")
    if _subscripts(_reads_pair) == 0 or _subscripts(g) != 0:
        bad.append(f"subscripts: {_subscripts(_reads_pair)} in the source, {_subscripts(g)} inlined (want 0)")
    if g(3.0, 1.0) != 8.0:
        bad.append(f"inlined value {g(3.0, 1.0)!r} at (3, 1), want 8.0")
    if bad:
        return failed(f"{len(bad)} of {len(names) + 3} facts", detail="; ".join(bad))
    return Outcome("verified", f"{len(names)} block kernels and an inlined function at their source's lines; "
                   "the tuple spread", evidence="proof", n_scope="all")


@claim("checker.magnitude_moduli", equation="checker", scene="checker",
       where="symbt.proof.magnitude.magnitude (the screen's scale)",
       statement="magnitude(p) for a positive symbol p is 5 at p = 3 + 4i; magnitude(eta^2) for a real eta is 1 at "
                 "eta = i (moduli, whatever the assumptions)")
def magnitude_moduli() -> Outcome:
    from ..proof.magnitude import magnitude

    p, eta = sp.Symbol("p", positive=True), sp.Symbol("eta", real=True)
    got = [complex(sp.N(magnitude(p).subs(p, 3 + 4 * sp.I))), complex(sp.N(magnitude(eta ** 2).subs(eta, sp.I)))]
    return _by_hand("exact: moduli written by hand", got, [5, 1])


#: library.reference_edges: an N = 2 state, a real (lam0, mu) in its outer gap, a target's c_1/c_0 in a band
EDGE_STATE, EDGE_PARAMS, EDGE_BAND_RATIO = (("1", "-1"), ("0", "0.5")), ("3.5", "0.3"), 2


def _defined(cs: list[Any]) -> list[Any]:
    """The coefficients, each defined (``flow_coefficients_mp`` gives None where one is not)."""
    if any(c is None for c in cs):
        raise ArithmeticError(f"a flow coefficient undefined at a real parameter: {cs}")
    return cs


def _free_chain_edge() -> list[str]:
    """library.reference_edges at the free chain's band edge lam = 2 (N = 2): what differs from the closed forms."""
    import warnings

    from ..reference.spectral import NoRealFlowError, flow_coefficients_mp, phi_gradient

    bad = []
    zero, l0, mu = [mp.mpf(0)] * 2, mp.mpf("2.5"), mp.mpf("0.5")
    for b in (1, -1):
        want = [-b * mp.acos(mp.mpf(2) / 3) / 2, -b * mp.acosh(mp.mpf(3) / 2), -b * mp.sqrt(5)]
        # at 15 digits: tanh-sinh at the inverse-square-root end meets the closed forms to ~4e-10 (it warns that
        # its estimate is above the working precision); 1e-8 leaves a factor 25
        try:
            with warnings.catch_warnings(), mp.workdps(15):
                warnings.simplefilter("ignore", RuntimeWarning)
                got = flow_coefficients_mp(zero, zero, l0, mu, b, check=False)
        except Exception as exc:          # noqa: BLE001 -- a refusal asked not to check is the finding
            bad.append(f"free chain over [2, 3] with check=False, branch {b}: {type(exc).__name__}: {exc}")
            continue
        if any(g is None or abs(g - w) > mp.mpf(10) ** -8 for g, w in zip(got, want)):
            bad.append(f"free chain over [2, 3], branch {b}: c = {got}, closed forms {want}")
    for name, call in (("flow_coefficients_mp", lambda: flow_coefficients_mp(zero, zero, l0, mu, 1)),
                       ("phi_gradient", lambda: phi_gradient(zero, zero, l0, mu, 1))):
        try:
            call()
            bad.append(f"{name} at the band edge lam = 2: no refusal")
        except NoRealFlowError:
            pass
        except Exception as exc:          # noqa: BLE001 -- any other error is the finding
            bad.append(f"{name} at the band edge lam = 2: {type(exc).__name__}: {exc}")
    return bad


@claim("library.reference_edges", equation="checker", scene="library", N=2,
       where="symbt.reference: elliptic.shift at a band edge, spectral.flow_coefficients_jacobian, "
             "inverse.solve_parameters' start",
       statement="shift(I1 = 0, I2 = 7, lam0 = 4, mu = 1) (T2 = 2, T1 = 18) has dtheta1_real = -branch arccosh(9), and"
                 " with lam0 = 2 (T1 = 2, T2 = -6) -branch arccosh(3) (mpmath acosh, 30 digits); "
                 "flow_coefficients_jacobian at p = (1, -1), q = (0, 1/2), lam0 = 3.5, mu = 0.3 gives N + 1 pairs, "
                 "each within 1e-12 of central differences (h = 1e-8) of flow_coefficients_mp, both branches, and "
                 "branch +1 by default; solve_parameters from the target (c_0, 2 c_0) (its start lam0 = 2 in a band) "
                 "raises ValueError; on the free chain (N = 2) over [2, 3] (tr = 2 at lam = 2), flow_coefficients_mp "
                 "with check=False (15 digits) = -b (arccos(2/3)/2, arccosh(3/2), sqrt 5) within 1e-8, and "
                 "flow_coefficients_mp (checked) and phi_gradient raise NoRealFlowError")
def reference_edges() -> Outcome:
    from ..reference.elliptic import shift
    from ..reference.inverse import solve_parameters
    from ..reference.literal import literal_trace
    from ..reference.spectral import flow_coefficients_jacobian, flow_coefficients_mp

    bad: list[str] = []
    with mp.workdps(30):
        # an exact band edge at either parameter: T = (lam +- 0)^2 - 7 (I1 = 0, I2 = 7); the real phase
        # branch (sgn(T2) arccosh(|T2|/2) - sgn(T1) arccosh(|T1|/2)) by mpmath's acosh
        for lam0, traces, edge_free in ((4, (18, 2), -mp.acosh(9)), (2, (2, -6), -mp.acosh(3))):
            for b in (1, -1):
                sh = shift(mp.mpf(0), mp.mpf(7), mp.mpf(lam0), mp.mpf(1), b)
                if (sh["T1"], sh["T2"]) != traces:       # the premise: an exact band edge
                    bad.append(f"shift's traces {sh['T1']}, {sh['T2']}, want {traces} exactly")
                real = sh["dtheta1_real"]
                if real is None or not abs(real - b * edge_free) <= mp.mpf(10) ** -25:
                    bad.append(f"shift at T = {traces}, branch {b}: dtheta1_real {real}, want "
                               f"{mp.nstr(b * edge_free, 20)}")
        p, q = [[mp.mpf(v) for v in x] for x in EDGE_STATE]
        l0, mu = (mp.mpf(v) for v in EDGE_PARAMS)
        h = mp.mpf("1e-8")
        for b in (1, -1):
            J = flow_coefficients_jacobian(p, q, l0, b * mu, b)
            around = [[_defined(flow_coefficients_mp(p, q, l0 + s * h, b * mu, b)) for s in (1, -1)],
                      [_defined(flow_coefficients_mp(p, q, l0, b * mu + s * h, b)) for s in (1, -1)]]
            fd = [tuple((c[0][k] - c[1][k]) / (2 * h) for c in around) for k in range(len(p) + 1)]
            if len(J) != len(fd) or any(abs(a - e) > mp.mpf(10) ** -12 * max(1, abs(e))
                                        for pair, want in zip(J, fd) for a, e in zip(pair, want)):
                bad.append(f"jacobian, branch {b}: {len(J)} pairs {[[mp.nstr(v, 8) for v in x] for x in J]}, "
                           f"central differences {[[mp.nstr(v, 8) for v in x] for x in fd]}")
        if flow_coefficients_jacobian(p, q, l0, mu) != flow_coefficients_jacobian(p, q, l0, mu, 1):
            bad.append("flow_coefficients_jacobian's default branch is not +1")
        bad += _free_chain_edge()
        c0 = _defined(flow_coefficients_mp(p, q, l0, mu, 1))[0]
        start = literal_trace(mp.mpf(EDGE_BAND_RATIO), p, q)      # the premise: the start lam0 = c_1/c_0 in a band
        if not abs(start) < 2:
            bad.append(f"the start lam0 = {EDGE_BAND_RATIO}: tr = {mp.nstr(start, 5)}, not in a band")
        try:
            r = solve_parameters(p, q, [c0, EDGE_BAND_RATIO * c0])
            bad.append(f"solve_parameters from a start in a band: answered {r}")
        except ValueError:
            pass
        except Exception as exc:          # noqa: BLE001 -- any other error is the finding
            bad.append(f"solve_parameters from a start in a band: {type(exc).__name__}: {exc}")
    if bad:
        return failed("numeric: mpmath acosh, central differences, the documented refusal", detail="; ".join(bad))
    return Outcome("verified", "numeric: mpmath acosh, central differences, the documented refusal",
                   evidence="sampled", n_scope=[2], detail="3 edges, both branches")


@claim("paths.rows_apart", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/orbit.py: general_orbit (backend='numpy' ensembles) after a row leaves",
       statement="general_orbit (N={N}, 4 steps, low parts kept) of four rows -- a state without a real map "
                 "(paths.existence_iv's near-edge state), the paper's state at q + 300.3 and its reverse at q - "
                 "211.7 (mu = 5, 4), a state with |q_2 - q_1| = MAX_DQ_FLOAT64 + 50 -- refuses the first at step 1 "
                 "(positivity) and the last (range), and stores the others bit for bit as each row alone (a "
                 "consistency check)")
def rows_apart(N: int) -> Outcome:
    from ..numeric.core.limits import MAX_DQ_FLOAT64, OK, POSITIVITY, RANGE
    from ..numeric.float64.orbit import general_orbit
    from .shipped_rules import NEAR_EDGE

    def run(pa: np.ndarray, qa: np.ndarray, l0: np.ndarray, m: np.ndarray) -> tuple[Any, ...]:
        P, Q = np.empty((5, len(pa), N)), np.empty((5, len(pa), 2 * N))
        st, step = general_orbit(pa, qa, l0, m, 1, 4, 1, P, Q, np.arange(len(pa)))
        return P, Q, st.tolist(), step.tolist()

    p, q = np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9])
    wide = np.array([0.0, MAX_DQ_FLOAT64 + 50, 0.0])         # beyond the scaled formulation's float64 range
    pa, qa = np.array([NEAR_EDGE[0], p, p[::-1], p]), np.array([NEAR_EDGE[1], q + 300.3, q - 211.7, wide])
    l0, m = np.array([NEAR_EDGE[2], 10.0, 10.0, 10.0]), np.array([NEAR_EDGE[3], 5.0, 4.0, 5.0])
    P, Q, st, step = run(pa, qa, l0, m)
    bad = [] if (st[0], step[0]) == (POSITIVITY, 1) else [f"the no-map row: status {st[0]} at step {step[0]}"]
    if (st[3], step[3]) != (RANGE, 1):
        bad.append(f"the wide row: status {st[3]} at step {step[3]}, not the range code at step 1")
    for k in (1, 2):
        P1, Q1, s1, _ = run(pa[k:k + 1], qa[k:k + 1], l0[k:k + 1], m[k:k + 1])
        if not (st[k] == s1[0] == OK and np.array_equal(P[:, k], P1[:, 0]) and np.array_equal(Q[:, k], Q1[:, 0])):
            bad.append(f"row {k}: status {st[k]} (alone {s1[0]}), largest difference from alone "
                       f"{float(np.abs(Q[:, k] - Q1[:, 0]).max()):.3g}")
    if bad:
        return failed("numeric: each row against itself alone", detail="; ".join(bad))
    return Outcome("verified", "numeric: each row against itself alone (consistency)", evidence="sampled",
                   detail="the no-map row and the wide row refused at step 1 (positivity, range); two rows bit "
                          "for bit as alone",
                   printed="every row = itself alone")


@claim("library.project_roots", equation="checker", scene="library",
       where="symbt.codegen.project.find_project, is_project",
       statement="in a temporary tree, find_project from root/a/b is root when root holds pyproject.toml with "
                 "[project] name = 'symbt' and symbt/__init__.py; None when the name is 'other' or the package is "
                 "missing")
def project_roots() -> Outcome:
    from ..codegen.project import find_project

    got = {}
    cases = (("symbt", "symbt", True), ("other name", "other", True), ("no package", "symbt", False))
    for case, name, package in cases:
        with tempfile.TemporaryDirectory() as d:
            root = Path(d).resolve()
            (root / "pyproject.toml").write_text(f'[project]\nname = "{name}"\n', encoding="utf-8")
            if package:
                (root / "symbt").mkdir()
                (root / "symbt" / "__init__.py").write_text("", encoding="utf-8")
            (root / "a" / "b").mkdir(parents=True)
            found = find_project(root / "a" / "b")
            got[case] = "root" if found == root else found
    want = {"symbt": "root", "other name": None, "no package": None}
    return _by_hand("exact: directories written by hand", got, want)


@claim("checker.matrix_methods", equation="checker", scene="checker",
       where="symbt.proof.decider.decide on matrices (the method of a proved matrix)",
       statement="decide(Matrix([[(x + 1)^2]]), Matrix([[x^2 + 2x + 1]])) is proved with the scalar decision's method; "
                 "decide([(x + 1)^2, cosh^2 x - sinh^2 x], [x^2 + 2x + 1, 1]) is proved with both entries' (distinct) "
                 "methods in entry order, joined by ' | '")
def matrix_methods() -> Outcome:
    from ..proof import decide

    x = sp.Symbol("x")
    lhs, rhs = [(x + 1) ** 2, sp.cosh(x) ** 2 - sp.sinh(x) ** 2], [x ** 2 + 2 * x + 1, sp.Integer(1)]
    each = [decide(a, b) for a, b in zip(lhs, rhs)]
    one = decide(sp.Matrix([[lhs[0]]]), sp.Matrix([[rhs[0]]]))
    two = decide(sp.Matrix(lhs), sp.Matrix(rhs))
    got = [(one.verdict, one.method), (two.verdict, two.method)]
    want = [("proved", each[0].method), ("proved", f"{each[0].method} | {each[1].method}")]
    if each[0].method == each[1].method:
        return failed("exact: entries decided one by one", detail=f"one method for both entries: {each[0].method}")
    return _by_hand("exact: entries decided one by one", got, want, detail=two.method)


@claim("library.verify_points", equation="checker", scene="library",
       where="symbt.codegen.verify.points (spectral_trace, ck_integrand; invariants, hamiltonian_fields, flow_field)",
       statement="for N = 2, 3 the points at which codegen.verify compares each emitted function of lam with its "
                 "source are lam0 + mu and lam0 - mu of every state of map_states(N), each once with its state; at "
                 "those of the functions of p, q (and c) every coordinate takes both signs and every two of one "
                 "site are alike in sign at some point and opposite at another (a check of the verifier's coverage)")
def verify_points() -> Outcome:
    from ..codegen.verify import interface, map_states, points

    bad = []
    for N in (2, 3):
        want = sorted((lv, tuple(p), tuple(q)) for p, q, l0, m in map_states(N) for lv in (l0 + m, l0 - m))
        for name, spec in interface(N).items():
            if "lam" in {a.name for a in spec.args}:
                got = sorted((pt["lam"], tuple(pt["p"]), tuple(pt["q"])) for pt in points(spec, N))
                if got != want:
                    bad.append(f"N={N}, {name}: {len(got)} points, want the {len(want)} of lam0 +- mu")
            elif not {a.name for a in spec.args} & {"lam0", "lam", "tr1"}:
                bad += [f"N={N}, {name}: {b}" for b in _sign_faults(points(spec, N), N)]
    if bad:
        return failed("exact: the sampled points against the states and sign patterns", detail="; ".join(bad))
    return Outcome("verified", "exact: the sampled points against the states and sign patterns (coverage)",
                   evidence="proof", n_scope=[2, 3],
                   detail="spectral_trace and ck_integrand at lam0 +- mu; invariants, hamiltonian_fields and "
                          "flow_field: every p_i, q_i, c_i of both signs, every two of one site alike and opposite")


def _sign_faults(pts: list[dict[str, Any]], N: int) -> list[str]:
    """What the points of a function of ``p, q`` (and ``c``) leave out: a coordinate of one sign only, or two
    coordinates of one site (``p_i, q_i``, ...) never alike or never opposite in sign (with ``p_i`` and
    ``q_i`` always alike, ``|p_i q_i|`` and ``p_i q_i`` could not be told apart)."""
    names = [k for k in ("p", "q", "c") if k in pts[0]]
    bad = []
    for i in range(N):
        signs = {k: [pt[k][i] > 0 for pt in pts] for k in names}
        bad += [f"{k}_{i + 1} of one sign" for k in names if len(set(signs[k])) < 2]
        for a, b in ((a, b) for n, a in enumerate(names) for b in names[n + 1:]):
            if len({x == y for x, y in zip(signs[a], signs[b])}) < 2:
                bad.append(f"{a}_{i + 1}, {b}_{i + 1} {'always' if signs[a] == signs[b] else 'never'} alike")
    return bad
