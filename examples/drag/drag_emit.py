r"""What ``symbt codegen`` emits from the note: the velocity of a thrown body as a numpy/mpmath function.

The corrected form of eq. ``v0`` (the one ``drag_claims.drag_v0`` verifies in every cell) is
declared with :func:`symbt.emit`; ``symbt codegen`` writes ``generated/drag_numeric.py`` with
``velocity(t, v0, g, k)`` (numpy, vectorised) and ``velocity_mp`` (mpmath), and ``symbt verify``
checks each against this expression at 60 digits (claims ``emit.drag_numeric.velocity.*``, counted
by ``symbt coverage`` as claims of eq. ``v0``).  The ``coth`` branch is written ``1/tanh`` with
``artanh(v_T/v0)`` -- the functions every target prints.

>>> from symbt.codegen.user import EMISSIONS
>>> EMISSIONS["drag_numeric", "velocity"].arg_names
('t', 'v0', 'g', 'k')
"""
from __future__ import annotations

import mpmath as mp
import sympy as sp
from symbt import Domain, emit

from drag_model import RATE, V_T, g, k, t, v0

#: eq. v0, corrected: tanh below the terminal velocity, coth above it
VELOCITY = sp.Piecewise((V_T * sp.tanh(RATE * t + sp.atanh(v0 / V_T)), sp.Abs(v0) < V_T),
                        (V_T / sp.tanh(RATE * t + sp.atanh(V_T / v0)), True))


def solution_exists(t, v0, g, k):
    """The solution exists on [0, t] (for v0 < -v_T it blows up at sqrt(g k) t = arcoth(|v0|/v_T));
    points from just before that time on are left out, as in ``drag_claims``."""
    vT = mp.sqrt(g / k)
    return v0 >= -vT or mp.sqrt(g * k) * t < 0.99 * mp.acoth(-v0 / vT)


emit("velocity", VELOCITY, args=(t, v0, g, k), module="drag_numeric", equation="v0",
     doc="v(t) of a body thrown with velocity v0 (eq. v0, corrected): v_T tanh(...) for |v0| < v_T, "
         "v_T coth(...) above",
     domain=Domain({"t": (0, 1), "v0": (-25, 25), "g": (5, 15), "k": (0.2, 2)}, where=solution_exists, seed=0))
