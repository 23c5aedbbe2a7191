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

import mpmath as mp
import sympy as sp
from symbt import Domain, Parts, claim, decide, from_decision, judge, ode_residual, scene, sign, solves_ode

from drag_model import RATE, V_T, dimensionless, drag_rhs, g, k, model_ode, t, v0, w

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


# --------------------------------------------------------------------------- eq. vT

def parts_vT() -> Parts:
    return Parts(printed={"vT": V_T})


@claim("drag.vT", equation="vT", scene="rest", parts=parts_vT,
       statement="v_T = sqrt(g/k) is the stable equilibrium of v' = g - k v^2: f(v_T) = 0, f'(v_T) = -2 sqrt(g k) < 0")
def drag_vT(parts: Parts):
    vT, v = parts.printed["vT"], sp.Symbol("v")
    slope = sp.diff(drag_rhs(v), v).subs(v, vT)
    # in g = k w^2 the slope is -2 k w, negative since k, w > 0; -v_T would be an equilibrium too, but unstable
    return from_decision(decide(dimensionless(sp.Matrix([drag_rhs(vT), slope])), sp.Matrix([0, -2 * k * w])),
                         detail="f(v_T) = 0 and f'(v_T) = -2 k w (g = k w^2), negative: solutions approach v_T")


# --------------------------------------------------------------------------- eq. v

def parts_v() -> Parts:
    return Parts(printed={"v": V_REST})


@claim("drag.v", equation="v", scene="rest", parts=parts_v,
       statement="v(t) = sqrt(g/k) tanh(sqrt(g k) t) solves v' = g - k v^2 with v(0) = 0")
def drag_v(parts: Parts):
    v = parts.printed["v"]
    start = decide(v.subs(t, 0), 0)
    if not start.holds:
        return from_decision(start, detail="v(0) = 0")
    return from_decision(solves_ode(model_ode(in_s=True), dimensionless(v)),
                         detail="the model in s = sqrt(g k) t; v(0) = 0 proved too")


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
        # tanh of a number (log(199)/2) written with exponentials: exact arithmetic in sqrt(199)
        return decide(dimensionless(v.subs(t, t99) / V_T).rewrite(sp.exp), sp.Rational(99, 100))

    return judge(reaches(parts.printed["t99"]), printed="t_99 = ln(199)/sqrt(g k)",
                 corrected="t_99 = ln(199)/(2 sqrt(g k)), i.e. artanh(0.99)/sqrt(g k)",
                 corrected_check=lambda: reaches(parts.corrected["t99"]),
                 detail="v(t_99)/v_T = 99/100")


# --------------------------------------------------------------------------- eq. v0 (holds in some cells)

DPS = 50


def solution_exists(g, k, v0, t):
    """The domain of eq. v0: the solution exists on [0, t].  For v0 < -v_T it blows up to -infinity at
    sqrt(g k) t = arcoth(|v0|/v_T); points from just before that time on are left out."""
    vT = mp.sqrt(g / k)
    return v0 >= -vT or mp.sqrt(g * k) * t < 0.99 * mp.acoth(-v0 / vT)


#: where eq. v0 is sampled: g, k, v0 and t, cut into cells by |v0| against v_T and the sign of v0
DOMAIN = Domain({"g": (5, 15), "k": (0.2, 2), "v0": (-25, 25), "t": (0, 1)}, where=solution_exists, seed=0)
SPLITS = (sign(k * v0**2 - g, name="regime", labels=("|v0|<v_T", "|v0|>v_T")),
          sign(v0, name="sign(v0)", labels=("v0<0", "v0>0")))


def solution_residual(v):
    """The residual of a closed form ``v(t)`` as the solution of the model with v(0) = v0, at a point of
    :data:`DOMAIN`: the larger of the ODE's residual (:func:`symbt.ode_residual`) and the initial
    condition's relative residual."""
    ode = ode_residual(model_ode(), v)
    start = sp.lambdify((g, k, v0), v.subs(t, 0), "mpmath")

    def residual(g, k, v0, t):
        v_start = start(g, k, v0)
        return max(ode(g=g, k=k, v0=v0, t=t), abs(v_start - v0) / max(1, abs(v_start), abs(v0)))

    return residual


def parts_v0() -> Parts:
    return Parts(printed={"v": V_THROWN_PRINTED}, corrected={"v": V_THROWN_CORRECTED})


@claim("drag.v0", equation="v0", scene="thrown", parts=parts_v0,
       statement="v(t) = v_T tanh(sqrt(g k) t + (1/2) ln|(v_T + v0)/(v_T - v0)|) solves the model with v(0) = v0")
def drag_v0(parts: Parts, deep: bool = False):
    table = DOMAIN.evaluate(*SPLITS, printed=solution_residual(parts.printed["v"]),
                            corrected=solution_residual(parts.corrected["v"]), dps=DPS, deep=deep)
    return judge(table, printed="v = v_T tanh(sqrt(g k) t + (1/2) ln|(v_T + v0)/(v_T - v0)|)",
                 corrected="v = v_T tanh(sqrt(g k) t + artanh(v0/v_T)) for |v0| < v_T, "
                           "v_T coth(sqrt(g k) t + arcoth(v0/v_T)) for |v0| > v_T",
                 detail="v' - f(v) and v(0) - v0")
