r"""What the samples of seeds 22 and 23 found unread (issue 21).

* ``checker.ode_system`` -- :func:`symbt.proof.solves_ode` on a system whose equations name the unknowns in an order
  other than their names' (``y' = -x``, ``x' = y``): a tuple solution is read in the order of the equations, as
  documented -- ``(cos t, sin t)`` is proved, the same tuple swapped is refuted, and the dict ``{x: sin t, y: cos
  t}`` is proved (no claim had checked a system; seed 22's mutant of the unknowns' sort key turned out to change
  nothing -- the tuple is paired in the equations' order by ``_solution`` -- and the key went); a sampled
  verdict's method says the exact layer did not apply when it was tried (a solution times ``exp(sin^2 t + cos^2 t -
  1)``, which is 1) and names no exact layer under ``exact=False`` (seed 22: the sentence under the other setting).
* ``paths.field_nomap.n3`` -- existence decided alike on the flow routes: at the paper's state with ``lam1`` in a
  band (``lam0 = -2, mu = 1.215``) and with ``lam1``, ``lam2`` on opposite sides of a band (``lam0 = -2, mu =
  2.5``; the literal traces of opposite signs at 40 digits), ``flow_quadrature``, ``flow_coefficients`` (float64)
  and ``FlowField`` raise :class:`~symbt.numeric.NoRealMapError` with the condition ``bt_step`` gives -- ``trace``,
  then ``positivity`` -- and at ``lam0 = 10, mu = 5`` none refuses (seed 22: the quadrature's own band test alone
  named a positivity case ``trace``).
* ``checker.matrix_scalar`` -- :func:`symbt.decide` with a matrix on one side and a nonzero scalar on the other
  refuses with a ``ValueError`` naming the matrix side, its shape and the scalar (seed 23: the sides swapped in
  the message).
* ``checker.scope_counts`` -- :meth:`symbt.proof.cells.CellTable.scope` on a table written by hand (residuals below
  and above the tolerance): a cell holding at 3 of 3 samples is named among the exact cells, one holding at 1 of 3
  with its count ``(1/3)``, one at 0 of 3 among the failing ones (seed 23: a cell holding at a single sample was
  dropped from the sentence).
"""
from __future__ import annotations

from typing import Any

import mpmath as mp
import sympy as sp

from ._shipped import without_numba
from .base import Outcome, claim, failed


@claim("checker.ode_system", equation="checker", scene="checker",
       where="symbt.proof.ode: solves_ode on a system (the unknowns' order, _unknowns)",
       statement="solves_ode([y' = -x, x' = y], (cos t, sin t)) is proved (the tuple in the order of the equations: y "
                 "= cos t, x = sin t); the tuple swapped is refuted; the dict {x: sin t, y: cos t} is proved; the "
                 "method of a sampled verdict says the exact layer did not apply when it was tried, and names no "
                 "exact layer with exact=False")
def ode_system() -> Outcome:
    from ..proof.ode import solves_ode

    t = sp.Symbol("t", real=True)
    x, y = sp.Function("x"), sp.Function("y")
    system = [sp.Eq(y(t).diff(t), -x(t)), sp.Eq(x(t).diff(t), y(t))]
    got: dict[str, Any] = {name: solves_ode(system, sol).verdict for name, sol in
           (("tuple", (sp.cos(t), sp.sin(t))), ("swapped", (sp.sin(t), sp.cos(t))),
            ("dict", {x: sp.sin(t), y: sp.cos(t)}))}
    want: dict[str, Any] = {"tuple": "proved", "swapped": "false", "dict": "proved"}
    # how the sampled verdict was reached: the exact layer named as tried only when it was
    one = sp.exp(sp.sin(t) ** 2 + sp.cos(t) ** 2 - 1)      # 1, in a form the exact layer cannot reduce
    tried = solves_ode(system, (sp.cos(t), sp.sin(t) * one))
    skipped_exact = solves_ode(system, (sp.cos(t), sp.sin(t)), exact=False)
    got["method, exact layer tried"] = "exact layer does not apply" in tried.method
    got["method, exact=False"] = "exact" in skipped_exact.method
    want.update({"method, exact layer tried": True, "method, exact=False": False})
    if got != want:
        return failed("solves_ode on a system in equation order", detail=f"got {got}, want {want}")
    return Outcome("verified", "solves_ode on a system in equation order (exact and sampled verdicts)",
                   evidence="proof", n_scope="all", detail=f"{got}")


#: paths.field_nomap: the paper's state and (lam0, mu) with lam1 in a band, lam1 and lam2 across a band, a real map
NOMAP_STATE = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9))
NOMAP_CASES = ((-2.0, 1.215), (-2.0, 2.5), (10.0, 5.0))


@claim("paths.field_nomap", equation="eqdisc", source_equation="eqdisc", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/flow: flow_quadrature, flow_coefficients, FlowField where no real map exists",
       statement="at the paper's state (N={N}) with lam0 = -2 and mu = 1.215 (lam1 in a band) and mu = 2.5 (the "
                 "literal traces at lam1, lam2 of opposite signs, 40 digits) flow_quadrature, flow_coefficients and "
                 "FlowField raise NoRealMapError with bt_step's condition (trace, then positivity); at lam0 = 10, "
                 "mu = 5 none refuses")
def field_nomap(N: int) -> Outcome:
    from ..numeric import FlowField, NoRealMapError, bt_step, flow_coefficients
    from ..numeric.flow.coefficients import flow_quadrature
    from ..reference.literal import literal_trace

    p, q = NOMAP_STATE
    routes: dict[str, Any] = {"bt_step": bt_step, "flow_quadrature": flow_quadrature,
                              "flow_coefficients": flow_coefficients, "FlowField": FlowField}
    bad, seen = [], []
    for l0, m in NOMAP_CASES:
        with mp.workdps(40):
            t1, t2 = (literal_trace(mp.mpf(l0) + s * mp.mpf(m), [mp.mpf(v) for v in p], [mp.mpf(v) for v in q])
                      for s in (1, -1))
        want = "trace" if min(abs(t1), abs(t2)) <= 2 else "positivity" if t1 * t2 < 0 else None
        for name, route in routes.items():
            try:
                with without_numba():       # bt_step(backend="auto") here and inside the flow routes
                    route(list(p), list(q), l0, m)
                got = None
            except NoRealMapError as exc:
                got = exc.condition
            if got != want:
                bad.append(f"lam0 = {l0}, mu = {m}: {name} refused with {got!r}, the literal traces say {want!r}")
        seen.append(f"mu = {m}: {want}")
    if bad:
        return failed("numeric: the flow routes' refusals vs the literal traces", detail="; ".join(bad[:4]))
    return Outcome("verified", "numeric: the flow routes' refusals vs the literal traces (40 digits)",
                   evidence="sampled", n_scope=[N], detail="; ".join(seen))


@claim("checker.matrix_scalar", equation="checker", scene="checker",
       where="symbt.proof.decider: a matrix side against a scalar side",
       statement="decide(Matrix([x, 1]), 1) and decide(1, Matrix([x, 1])) raise ValueError naming the matrix side "
                 "(lhs, then rhs), its shape 2x1 and the scalar 1")
def matrix_scalar() -> Outcome:
    from ..proof import decide

    x = sp.Symbol("x")
    col = sp.Matrix([x, 1])
    got = []
    for lhs, rhs, side in ((col, sp.Integer(1), "lhs"), (sp.Integer(1), col, "rhs")):
        other = "rhs" if side == "lhs" else "lhs"
        try:
            decide(lhs, rhs)
            got.append(f"{side}: no error")
        except ValueError as exc:
            if f"{side} is a 2x1 matrix and {other} the scalar 1" not in str(exc):
                got.append(f"{side}: {exc}")
    if got:
        return failed("exact: the refusal's words", detail="; ".join(got))
    return Outcome("verified", "exact: the refusal's words", evidence="proof", n_scope="all",
                   detail="both sides named")


@claim("checker.scope_counts", equation="checker", scene="checker",
       where="symbt.proof.cells: CellTable.scope (the generated scope sentence)",
       statement="a CellTable (tol 0.5) whose cells hold at 3, 1 and 0 of 3 samples (residuals 0 and 1 written by "
                 "hand) has the scope 'printed statement holds exactly in cells {side=a} and holds at some samples "
                 "of {side=b} (1/3) and fails in {side=c}'")
def scope_counts() -> Outcome:
    from ..proof.cells import CellTable

    table = CellTable(tol=0.5)
    for side, residuals in (("a", (0, 0, 0)), ("b", (0, 1, 1)), ("c", (1, 1, 1))):
        for r in residuals:
            table.add({"side": side}, printed=r)
    want = ("printed statement holds exactly in cells {side=a} and holds at some samples of {side=b} (1/3) and "
            "fails in {side=c}")
    if table.scope() != want:
        return failed("exact: the sentence against cell counts written by hand", detail=f"{table.scope()!r}")
    return Outcome("verified", "exact: the sentence against cell counts written by hand", evidence="proof",
                   n_scope="all", detail="3 cells: exact, partly (1/3), failing")
