r"""The model of ``note.tex``: a body falling with quadratic air drag, :math:`v' = g - k v^2` (eq. ``model``).

``g`` (gravity) and ``k`` (drag per unit mass) are positive; ``v`` is the downward velocity and ``t``
the time.  The claims module (``drag_claims.py``) imports everything it checks against from here, so
changing the model changes the verdicts -- and symbt's cache knows it (its key covers every Python
file of the project).

>>> drag_rhs(V_T)
0
>>> dimensionless(RATE * t)
s
>>> model_ode()
Eq(Derivative(v(t), t), g - k*v(t)**2)
"""
from __future__ import annotations

import sympy as sp

g, k = sp.symbols("g k", positive=True)
t = sp.Symbol("t", real=True)
v0 = sp.Symbol("v0", real=True)
#: the unknown of the model, v(t)
velocity = sp.Function("v")

#: terminal velocity: the equilibrium of the model
V_T = sp.sqrt(g / k)
#: the model's rate: 1/RATE is its time scale
RATE = sp.sqrt(g * k)

# Dimensionless variables for exact proofs: with g = k w^2 (w stands for v_T) and t = s/(k w) every
# exponential of the solutions is exp(integer * s) and no square root of a symbol is left, so an
# identity between them is a polynomial identity in e^s -- which symbt.decide proves.
w = sp.Symbol("w", positive=True)
s = sp.Symbol("s", real=True)


def drag_rhs(v):
    """The right-hand side f(v) of the model v' = f(v) = g - k v^2.

    >>> drag_rhs(sp.Symbol("v"))
    g - k*v**2
    """
    return g - k * v**2


def dimensionless(expr):
    """``expr`` in the dimensionless time ``s = sqrt(g k) t`` with ``g = k w^2`` (``w = v_T``).

    >>> dimensionless(V_T * sp.tanh(RATE * t))
    w*tanh(s)
    """
    return sp.sympify(expr).subs(g, k * w**2).subs(t, s / (k * w))


def model_ode(*, in_s: bool = False) -> sp.Eq:
    """The model as an ODE in the unknown ``v(t)``; ``in_s``: in the dimensionless time ``s`` (with
    ``g = k w^2``, ``t = s/(k w)``, so ``d/dt = k w d/ds``), the form whose residuals are proved exactly.

    >>> model_ode(in_s=True)
    Eq(k*w*Derivative(v(s), s), k*w**2 - k*v(s)**2)
    """
    if not in_s:
        return sp.Eq(velocity(t).diff(t), drag_rhs(velocity(t)))
    return sp.Eq(k * w * velocity(s).diff(s), dimensionless(drag_rhs(velocity(s))))
