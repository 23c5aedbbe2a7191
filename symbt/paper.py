"""Facts taken from the paper: its worked example and the constants printed in its figure captions.

F. Zullo, *Bäcklund transformations and Hamiltonian flows* (periodic Toda lattice).
Only numbers and labels live here -- never the paper's text.  Every other module
takes the example and the printed constants from this one place.

* :data:`EXAMPLE` -- the Numerics example (Sec. 3.2): ``N = 3``, ``p = (-20, 10, 1)``,
  ``q = (1, 0, 0.9)``, ``lambda_0 = 10`` and the two values of ``mu`` of Figs. 1-2, as
  exact decimal strings (turned into mpf at any working precision);
* :data:`P_EXAMPLE`, :data:`Q_EXAMPLE`, :data:`LAM0_EXAMPLE` -- the same as floats;
* :data:`CAPTIONS` -- the printed ``(c_0, c_1, c_2)`` of the captions of Figs. 1 and 2;
* :data:`LABELS` -- every ``\\label`` of the paper as :class:`Label` (name, section as printed, kind),
  in the paper's order; :data:`DISPLAYS` -- those that are displays (kinds ``equation``, ``figure``);
  :data:`SECTIONS` -- the section numbers with their LaTeX label and a short name of our own.

What counts as a display: a labelled ``equation``-like environment (58) or figure (2).  Section
labels (``intr``, ``sec1``, ``sec2``, ``Numerics``, ``Appendix``, ``AppendixB``) and the two theorem
environments (``th1``, ``th2``: a theorem is stated by its displays, eqs. ``x`` and ``recus``) are
labels but not displays.  Note the LaTeX label ``sec1`` is Section 2 in print, ``sec2`` Section 3.

>>> P_EXAMPLE, Q_EXAMPLE, LAM0_EXAMPLE
((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 10.0)
>>> CAPTIONS["fig:2"]["2"]
('-0.0018', '-0.0183', '-0.1849')
>>> len(LABELS), len(DISPLAYS), LABEL["intertwin"]
(68, 60, Label(label='intertwin', section='2', kind='equation'))
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["EXAMPLE", "P_EXAMPLE", "Q_EXAMPLE", "LAM0_EXAMPLE", "MU_EXAMPLE", "CAPTIONS", "Label", "LABELS",
           "LABEL", "DISPLAYS", "DISPLAY_KINDS", "SECTIONS"]

#: The paper's Numerics example: p, q, lambda0, and the two values of mu of Figs. 1-2 (decimal strings).
EXAMPLE: dict[str, Any] = dict(p=("-20", "10", "1"), q=("1", "0", "0.9"), lam0="10", mu=("5", "2"))

P_EXAMPLE: tuple[float, ...] = tuple(float(v) for v in EXAMPLE["p"])
Q_EXAMPLE: tuple[float, ...] = tuple(float(v) for v in EXAMPLE["q"])
LAM0_EXAMPLE: float = float(EXAMPLE["lam0"])
MU_EXAMPLE: tuple[float, ...] = tuple(float(v) for v in EXAMPLE["mu"])

#: printed caption constants (c_0, c_1, c_2) of Figs. 1 and 2, keyed by figure label and mu
CAPTIONS: dict[str, dict[str, tuple[str, str, str]]] = {
    "fig:1": {"5": ("-0.005", "-0.048", "-0.512")},
    "fig:2": {"5": ("-0.005", "-0.048", "-0.512"), "2": ("-0.0018", "-0.0183", "-0.1849")},
}

#: kinds of label that are displays (see the module docstring)
DISPLAY_KINDS: tuple[str, ...] = ("equation", "figure")


@dataclass(frozen=True)
class Label:
    """One ``\\label`` of the paper: its name, its section as printed (``"2"``, ``"3.1"``, ``"A"``) and its kind
    (``"equation"``, ``"figure"``, ``"section"`` or ``"theorem"``)."""

    label: str
    section: str
    kind: str

    @property
    def is_display(self) -> bool:
        return self.kind in DISPLAY_KINDS


#: section as printed -> (its LaTeX label or None, a short name of our own)
SECTIONS: dict[str, tuple[str | None, str]] = {
    "1": ("intr", "Introduction"),
    "2": ("sec1", "BTs as Hamiltonian flows (general theory)"),
    "3": ("sec2", "The periodic Toda lattice"),
    "3.1": (None, "Generating function and Hamiltonian flows"),
    "3.2": ("Numerics", "Numerics"),
    "A": ("Appendix", "The two-parameter Darboux matrix"),
    "B": ("AppendixB", "The function Phi"),
}

#: every \label of the paper, in its order (kinds: equation, figure, section, theorem)
LABELS: tuple[Label, ...] = (
    # Section 1
    Label("intr", "1", "section"), Label("intdis", "1", "equation"),
    # Section 2
    Label("sec1", "2", "section"), Label("speccurve", "2", "equation"), Label("Hj", "2", "equation"),
    Label("backlund", "2", "equation"), Label("rec", "2", "equation"), Label("intertwin", "2", "equation"),
    Label("K", "2", "equation"), Label("ccvtm", "2", "equation"), Label("spe", "2", "equation"),
    Label("PoincareCartan", "2", "equation"), Label("hamil", "2", "equation"), Label("ICI", "2", "equation"),
    Label("th1", "2", "theorem"), Label("x", "2", "equation"), Label("AA", "2", "equation"),
    Label("vgf", "2", "equation"), Label("discr", "2", "equation"), Label("Hdiscr", "2", "equation"),
    Label("th2", "2", "theorem"), Label("recus", "2", "equation"), Label("linearcomb", "2", "equation"),
    # Section 3
    Label("sec2", "3", "section"), Label("eq:lax", "3", "equation"), Label("tra", "3", "equation"),
    Label("local", "3", "equation"), Label("dj", "3", "equation"), Label("alphabeta", "3", "equation"),
    Label("ptp", "3", "equation"), Label("D", "3", "equation"), Label("new", "3", "equation"),
    Label("l1l2", "3", "equation"), Label("v1v2", "3", "equation"), Label("xy", "3", "equation"),
    Label("lam0mu", "3", "equation"),
    # Section 3.1
    Label("GF", "3.1", "equation"), Label("nlocal", "3.1", "equation"), Label("daj", "3.1", "equation"),
    Label("xyqqt", "3.1", "equation"), Label("imptransf", "3.1", "equation"), Label("newgf", "3.1", "equation"),
    Label("vqqtmu", "3.1", "equation"), Label("newkmu", "3.1", "equation"), Label("tn2", "3.1", "equation"),
    Label("th1th2", "3.1", "equation"), Label("AA2", "3.1", "equation"), Label("citn", "3.1", "equation"),
    Label("linBts", "3.1", "equation"), Label("addform", "3.1", "equation"),
    # Section 3.2
    Label("Numerics", "3.2", "section"), Label("Hdis", "3.2", "equation"), Label("eqdisc", "3.2", "equation"),
    Label("fig:1", "3.2", "figure"), Label("fig:2", "3.2", "figure"),
    # Section A
    Label("Appendix", "A", "section"), Label("d1", "A", "equation"), Label("v1", "A", "equation"),
    Label("LhDhDL", "A", "equation"), Label("hd", "A", "equation"), Label("v11", "A", "equation"),
    Label("tiltil", "A", "equation"), Label("D1D2", "A", "equation"), Label("Dapp", "A", "equation"),
    # Section B
    Label("AppendixB", "B", "section"), Label("rte", "B", "equation"), Label("2122", "B", "equation"),
    Label("spec", "B", "equation"),
)
DISPLAYS: tuple[Label, ...] = tuple(lab for lab in LABELS if lab.is_display)
LABEL: dict[str, Label] = {lab.label: lab for lab in LABELS}
