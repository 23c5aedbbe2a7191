r"""The claims of ``note.tex`` (a body falling with quadratic drag), written with symbt's public API only.

Each labelled display of the note is either a claim below -- its printed formula kept as data in
:class:`symbt.Parts`, so that ``symbt mutate`` can inject errors into it -- or a reason in the
``[tool.symbt] reasons`` table of ``pyproject.toml`` (eq. ``model`` is a definition).

Exact claims are decided by :func:`symbt.decide` in the dimensionless time ``s = sqrt(g k) t``
(``drag_model.dimensionless``): every exponential is then ``e^{n s}`` and the identity is a
polynomial one, so the evidence is ``proof``.  The claim of eq. ``v0`` holds only for some initial
velocities: it is sampled in every domain cell (``|v0| < v_T`` or ``> v_T``, times the sign of
``v0``) and its scope sentence is generated from the :class:`symbt.CellTable`.

>>> drag_t99.run().status
'erratum'
"""
from __future__ import annotations

import random

import mpmath as mp
import sympy as sp
from symbt import CellTable, Outcome, Parts, claim, decide, from_decision, judge, scene

from drag_model import RATE, V_T, dimensionless, drag_rhs, g, k, t, v0

scene("rest", "dropped from rest: v(t), x(t), v(x), the time to 99 % of v_T")
scene("thrown", "thrown with an initial velocity v0: where the printed solution holds")

x = sp.Symbol("x", real=True)

# The displays as printed in note.tex.
V_REST = V_T * sp.tanh(RATE * t)                                      # eq. v
X_REST = sp.log(sp.cosh(RATE * t)) / k                                # eq. x
V2_OF_X = (g / k) * (1 - sp.exp(-2 * k * x))                          # eq. v2x
T99_PRINTED = sp.log(199) / RATE                                      # eq. t99, as printed
T99_CORRECTED = sp.log(199) / (2 * RATE)
V_THROWN_PRINTED = V_T * sp.tanh(RATE * t + sp.log(sp.Abs((V_T + v0) / (V_T - v0))) / 2)   # eq. v0
V_THROWN_CORRECTED = sp.Piecewise((V_T * sp.tanh(RATE * t + sp.atanh(v0 / V_T)), sp.Abs(v0) < V_T),
                                  (V_T * sp.coth(RATE * t + sp.acoth(v0 / V_T)), True))


def solves(v):
    """The model's residuals of a velocity ``v(t)``, as a column: ``v' - f(v)`` and ``v(0)``."""
    return sp.Matrix([sp.diff(v, t) - drag_rhs(v), v.subs(t, 0)])


# --------------------------------------------------------------------------- eq. vT

def parts_vT() -> Parts:
    return Parts(printed={"vT": V_T})


@claim("drag.vT", equation="vT", scene="rest", parts=parts_vT,
       statement="v_T = sqrt(g/k) is an equilibrium of v' = g - k v^2")
def drag_vT(parts: Parts):
    return from_decision(decide(drag_rhs(parts.printed["vT"]), 0), detail="f(v_T) = 0")


# --------------------------------------------------------------------------- eq. v

def parts_v() -> Parts:
    return Parts(printed={"v": V_REST})


@claim("drag.v", equation="v", scene="rest", parts=parts_v,
       statement="v(t) = sqrt(g/k) tanh(sqrt(g k) t) solves v' = g - k v^2 with v(0) = 0")
def drag_v(parts: Parts):
    return from_decision(decide(dimensionless(solves(parts.printed["v"])), sp.zeros(2, 1)),
                         detail="v' - f(v) and v(0) in s = sqrt(g k) t")


# --------------------------------------------------------------------------- eq. x

def parts_x() -> Parts:
    return Parts(printed={"x": X_REST}, context={"v": V_REST})


@claim("drag.x", equation="x", scene="rest", parts=parts_x,
       statement="x(t) = ln(cosh(sqrt(g k) t))/k: x' = v(t) of eq. v and x(0) = 0")
def drag_x(parts: Parts):
    X = parts.printed["x"]
    return from_decision(decide(dimensionless(sp.Matrix([sp.diff(X, t), X.subs(t, 0)])),
                                dimensionless(sp.Matrix([parts.context["v"], 0]))),
                         detail="x' - v and x(0) in s = sqrt(g k) t")


# --------------------------------------------------------------------------- eq. v2x

def parts_v2x() -> Parts:
    return Parts(printed={"v2": V2_OF_X}, context={"v": V_REST, "x": X_REST})


@claim("drag.v2x", equation="v2x", scene="rest", parts=parts_v2x,
       statement="v^2 = (g/k)(1 - exp(-2 k x)) along the motion of eqs. v and x")
def drag_v2x(parts: Parts):
    along = parts.printed["v2"].subs(x, parts.context["x"])
    return from_decision(decide(dimensionless(parts.context["v"] ** 2), dimensionless(along)),
                         detail="both sides at x = x(t), in s = sqrt(g k) t: a polynomial identity in e^s")


# --------------------------------------------------------------------------- eq. t99 (printed wrong)

def parts_t99() -> Parts:
    return Parts(printed={"t99": T99_PRINTED}, corrected={"t99": T99_CORRECTED}, context={"v": V_REST})


@claim("drag.t99", equation="t99", scene="rest", parts=parts_t99,
       statement="v reaches 99 % of v_T at t_99 = ln(199)/sqrt(g k)")
def drag_t99(parts: Parts):
    v = parts.context["v"]

    def reaches(t99):  # v(t_99) = 0.99 v_T, both sides divided by v_T
        return decide(dimensionless(v.subs(t, t99) / V_T), sp.Rational(99, 100))

    return judge(reaches(parts.printed["t99"]), printed="t_99 = ln(199)/sqrt(g k)",
                 corrected="t_99 = ln(199)/(2 sqrt(g k)), i.e. artanh(0.99)/sqrt(g k)",
                 corrected_check=lambda: reaches(parts.corrected["t99"]),
                 detail="v(t_99)/v_T = 99/100")


# --------------------------------------------------------------------------- eq. v0 (holds in some cells)

DPS = 50
TOL = mp.mpf(10) ** -30
PER_CELL = 16
CELLS = [{"regime": regime, "sign_v0": sign} for regime in ("|v0|<v_T", "|v0|>v_T") for sign in (1, -1)]


def sample_cell(cell: dict, count: int, seed: int = 0) -> list[dict]:
    """``count`` seeded points ``{g, k, v0, t}`` of a cell, inside the domain of the statement.

    The domain is where the solution exists: for ``v0 < -v_T`` it blows up to ``-inf`` at
    ``sqrt(g k) t = arcoth(|v0|/v_T)``, and points at or after that time are rejected.
    """
    rng = random.Random(f"{seed}/{cell['regime']}/{cell['sign_v0']}")
    out: list[dict] = []
    while len(out) < count:
        gv, kv = mp.mpf(rng.uniform(1, 20)), mp.mpf(rng.uniform(0.05, 2))
        vT, rate = mp.sqrt(gv / kv), mp.sqrt(gv * kv)
        ratio = rng.uniform(0.02, 0.98) if cell["regime"] == "|v0|<v_T" else rng.uniform(1.02, 5)
        tv = mp.mpf(rng.uniform(0, 4)) / rate
        if cell["sign_v0"] < 0 and ratio > 1 and rate * tv >= 0.99 * mp.acoth(ratio):
            continue  # past the blow-up: outside the domain
        out.append({"g": gv, "k": kv, "v0": cell["sign_v0"] * mp.mpf(ratio) * vT, "t": tv})
    return out


def ode_residual(v) -> callable:
    """A function of a point ``{g, k, v0, t}``: the relative residual of ``v`` as a solution of the
    model with ``v(0) = v0`` (the larger of the ODE's and the initial condition's)."""
    args = (g, k, v0, t)
    f = sp.lambdify(args, [v, sp.diff(v, t) - drag_rhs(v), v.subs(t, 0) - v0], "mpmath")

    def residual(p: dict):
        val, ode, ini = f(*(p[str(a)] for a in args))
        return max(abs(ode) / max(1, abs(val), abs(p["g"])), abs(ini) / max(1, abs(p["v0"])))

    return residual


def parts_v0() -> Parts:
    return Parts(printed={"v": V_THROWN_PRINTED}, corrected={"v": V_THROWN_CORRECTED})


@claim("drag.v0", equation="v0", scene="thrown", parts=parts_v0,
       statement="v(t) = v_T tanh(sqrt(g k) t + (1/2) ln|(v_T + v0)/(v_T - v0)|) solves the model with v(0) = v0")
def drag_v0(parts: Parts, deep: bool = False):
    per_cell = 4 * PER_CELL if deep else PER_CELL
    table = CellTable(tol=TOL)
    with mp.workdps(DPS):
        printed, corrected = ode_residual(parts.printed["v"]), ode_residual(parts.corrected["v"])
        for cell in CELLS:
            for p in sample_cell(cell, per_cell):
                table.add(cell, printed=printed(p), corrected=corrected(p),
                          point={name: mp.nstr(val, 15) for name, val in p.items()})
    return cell_outcome(table, method=f"numeric: mpmath {DPS} digits, v' - f(v) and v(0) - v0 at seeded points",
                        printed="v = v_T tanh(sqrt(g k) t + (1/2) ln|(v_T + v0)/(v_T - v0)|)",
                        corrected="v = v_T tanh(sqrt(g k) t + artanh(v0/v_T)) for |v0| < v_T, "
                                  "v_T coth(sqrt(g k) t + arcoth(v0/v_T)) for |v0| > v_T")


def cell_outcome(table: CellTable, *, method: str, printed: str, corrected: str) -> Outcome:
    """``verified`` if the printed statement holds at every sample, ``erratum`` if it fails somewhere and
    the corrected one holds everywhere, else ``failed``; with the cell table and its scope sentence."""
    residual, where = table.worst("printed")
    status = ("verified" if table.printed_holds_everywhere()
              else "erratum" if table.corrected_holds_everywhere() else "failed")
    return Outcome(status, method, residual=residual, evidence="sampled", printed=printed,
                   corrected=None if status == "verified" else corrected,
                   counterexample=None if status == "verified" else where,
                   cells=table.cells(), scope=table.scope(),
                   detail=f"[{sum(c['n'] for c in table.cells())} samples in {len(table.cells())} cells]")
