"""Why some of the paper's labelled displays have no claim of their own (coverage as data).

Every display of :data:`symbt.paper.DISPLAYS` is covered either by registered claims (their
``equation`` or ``source_equation`` is its label) or by an entry here: a :class:`Reason` saying why
the display is not a checkable statement on the Toda lattice -- a definition, or a general
statement whose Toda instance is checked by the claims it names in ``see``.
``symbt coverage`` (:mod:`symbt.engine.coverage`) joins both; ``tests/test_coverage.py`` fails
if a display has neither, if a reason names an unknown claim, or if a label with claims still
carries a reason.

>>> REASONS["rec"].see[:2]
('Hdiscr.n2', 'Hdiscr.n3')
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Reason", "REASONS"]


@dataclass(frozen=True)
class Reason:
    """Why a display has no claim: ``text``, and the claims that check its Toda content (``see``)."""

    text: str
    see: tuple[str, ...] = ()


REASONS: dict[str, Reason] = {
    "rec": Reason("a definition: the recurrences are the BT iterated, (p, q)_{n+1} = BT((p, q)_n); iterates of the "
                  "Toda map are checked where the paper uses them",
                  ("Hdiscr.n2", "Hdiscr.n3", "linBts")),
    "K": Reason("a general existence statement (a parametric family of canonical maps is the mu-flow of some "
                "Hamiltonian K); on the Toda BT K is explicit: K = Phi^ for T = 0 (Theorem 1) and K = T^ + Phi^ "
                "(eq. hamil); the toy map of Sec. 2 with a polynomial T",
                ("x.n2", "x.n3", "hamil.n2", "hamil.n3", "toy.K")),
    "ccvtm": Reason("a definition (Phi = dF/dmu on the map); the Toda Phi is computed and checked from F",
                    ("vqqtmu.n2", "vqqtmu.n3", "spec.n2", "spec.n3", "newkmu.n2", "newkmu.n3", "spe.n2", "spe.n3")),
    "AA": Reason("a general property of action-angle variables of a Liouville-integrable system; the Toda N = 2 "
                 "action-angle variables of eq. th1th2 are checked to be canonical",
                 ("th1th2.brackets",)),
    "vgf": Reason("Theorem 1 written in action-angle variables of a general integrable system; its Toda N = 2 "
                  "instance (I~ = I, theta~ = theta + d/dI int Phi dmu) is eq. AA2/citn",
                  ("th1th2.actions", "AA2.n2", "citn.theta1", "citn.theta2")),
    "discr": Reason("the general linearised iterates (theta)_n = (theta)_0 + n d/dI int Phi; Toda N = 2 instance "
                    "eq. linBts; for N = 2, 3 the iterates as the time-n flow of H (Theorem 2)",
                    ("linBts", "Hdiscr.n2", "Hdiscr.n3")),
    "recus": Reason("a definition (Theorem 2's recurrences: the BT iterated, mu explicit); Theorem 2 on these "
                    "recurrences is checked",
                    ("Hdiscr.n2", "Hdiscr.n3", "linearcomb.n2", "linearcomb.n3", "caption.fig:1", "caption.fig:2")),
}
