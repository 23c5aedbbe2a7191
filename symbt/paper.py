"""Facts taken from the paper: its worked example and the constants printed in its figure captions.

F. Zullo, *Bäcklund transformations and Hamiltonian flows* (periodic Toda lattice).
Only numbers and labels live here -- never the paper's text.  Every other module
takes the example and the printed constants from this one place.

* :data:`EXAMPLE` -- the Numerics example (Sec. 3.3): ``N = 3``, ``p = (-20, 10, 1)``,
  ``q = (1, 0, 0.9)``, ``lambda_0 = 10`` and the two values of ``mu`` of Figs. 1-2, as
  exact decimal strings (turned into mpf at any working precision);
* :data:`P_EXAMPLE`, :data:`Q_EXAMPLE`, :data:`LAM0_EXAMPLE` -- the same as floats;
* :data:`CAPTIONS` -- the printed ``(c_0, c_1, c_2)`` of the captions of Figs. 1 and 2.

>>> P_EXAMPLE, Q_EXAMPLE, LAM0_EXAMPLE
((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 10.0)
>>> CAPTIONS["fig:2"]["2"]
('-0.0018', '-0.0183', '-0.1849')
"""
from __future__ import annotations

__all__ = ["EXAMPLE", "P_EXAMPLE", "Q_EXAMPLE", "LAM0_EXAMPLE", "MU_EXAMPLE", "CAPTIONS"]

#: The paper's Numerics example: p, q, lambda0, and the two values of mu of Figs. 1-2 (decimal strings).
EXAMPLE: dict = dict(p=("-20", "10", "1"), q=("1", "0", "0.9"), lam0="10", mu=("5", "2"))

P_EXAMPLE: tuple[float, ...] = tuple(float(v) for v in EXAMPLE["p"])
Q_EXAMPLE: tuple[float, ...] = tuple(float(v) for v in EXAMPLE["q"])
LAM0_EXAMPLE: float = float(EXAMPLE["lam0"])
MU_EXAMPLE: tuple[float, ...] = tuple(float(v) for v in EXAMPLE["mu"])

#: printed caption constants (c_0, c_1, c_2) of Figs. 1 and 2, keyed by figure label and mu
CAPTIONS: dict[str, dict[str, tuple[str, str, str]]] = {
    "fig:1": {"5": ("-0.005", "-0.048", "-0.512")},
    "fig:2": {"5": ("-0.005", "-0.048", "-0.512"), "2": ("-0.0018", "-0.0183", "-0.1849")},
}
