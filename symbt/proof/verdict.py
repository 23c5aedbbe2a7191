r"""The one verdict type: what every decider returns and every reporter reads.

A :class:`Verdict` says whether a statement holds *and how that was decided*
(its ``evidence``):

``"proof"``
    an exact reduction (rational-function arithmetic modulo algebraic relations),
    or a polynomial identity of degree ``d`` decided at ``d + 1`` points -- a
    proof, and the ``method`` says which;
``"certified"``
    ball arithmetic: every residual ball contains 0 (holds), or some ball
    excludes 0 (a certified counterexample);
``"sampled"``
    high-precision evaluation at finitely many points (``points``; for claims,
    at every *domain cell*, see ``cells``).

A false verdict carries the worst ``counterexample`` and its relative
``residual``.  ``definite`` marks a falsity that is itself proved (a nonzero
rational function, a ball excluding 0), not just observed at a sample.

A numeric check that *cannot tell* -- the residual is within the evaluation's
own estimated ``error``, or the evaluation is not trustworthy to the tolerance --
is ``inconclusive``: it neither holds nor is a counterexample (``holds`` is
False, ``verdict`` is ``"inconclusive"``, ``counterexample`` is None).

Like pytest's ``CallInfo``, the record is plain data: deciders build it, the
claim layer turns verdicts into an :class:`~symbt.claims.Outcome`, and
reporters only read.

>>> v = Verdict.sampled(1e-55, tol=1e-40, method="numeric: 60 digits at 8 states")
>>> v.holds, v.evidence, v.verdict, round(v.digits)
(True, 'sampled', 'verified', 55)
>>> Verdict.from_proof("exact: together/cancel").verdict
'proved'
>>> v = Verdict.sampled(3e-23, tol=1e-22, error=2e-20, method="numeric: 30 digits")
>>> v.verdict, v.holds
('inconclusive', False)
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any, Literal

__all__ = ["Verdict", "Evidence", "EVIDENCE", "STATUS_COLOURS", "LATEX_COLOURS", "latex_text", "SAFETY"]

Evidence = Literal["proof", "certified", "sampled"]
EVIDENCE: tuple[str, ...] = ("proof", "certified", "sampled")

#: colours of statuses and verdicts, shared by every rich display (HTML reports, notebooks)
STATUS_COLOURS = {
    "verified": "#2e7d32",   # green
    "proved": "#2e7d32",
    "erratum": "#b26a00",    # amber: the paper is wrong, the correction holds
    "failed": "#c62828",     # red
    "false": "#c62828",
    "skipped": "#757575",    # grey
    "inconclusive": "#6a1b9a",  # purple: cannot tell at this precision or budget
    "todo": "#1565c0",       # blue: no check written yet
}
LATEX_COLOURS = {"verified": "green", "proved": "green", "erratum": "orange",
                 "failed": "red", "false": "red", "skipped": "gray",
                 "inconclusive": "violet", "todo": "blue"}
#: a residual within this factor of the evaluation's own error estimate cannot be told apart from noise
SAFETY = 10.0
_LATEX_ESC = {
    "\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "#": r"\#", "$": r"\$", "%": r"\%",
    "&": r"\&", "_": r"\_", "^": r"\textasciicircum{}", "~": r"\textasciitilde{}",
}


def latex_text(s: str) -> str:
    """Escape plain text for use inside ``\\text{...}``."""
    return "".join(_LATEX_ESC.get(ch, ch) for ch in str(s))


def _as_float(x: Any) -> float:
    return float(abs(x))


@dataclass
class Verdict:
    """Whether a statement holds, how that was decided, and where it fails if it does."""

    holds: bool
    evidence: Evidence
    method: str
    residual: float | None = None
    digits: float | None = None
    counterexample: dict[str, Any] | None = None
    points: list[dict[str, str]] = field(default_factory=list)
    note: str = ""
    definite: bool = False
    cells: list[dict[str, Any]] = field(default_factory=list)
    inconclusive: bool = False
    error: float | None = None

    def __post_init__(self) -> None:
        if self.evidence not in EVIDENCE:
            raise ValueError(f"unknown evidence {self.evidence!r}; expected one of {EVIDENCE}")
        self.inconclusive = bool(self.inconclusive)
        if self.inconclusive and (self.holds or self.definite):
            raise ValueError("an inconclusive verdict neither holds nor is definitely false")
        self.holds = bool(self.holds)

    # -- constructors ---------------------------------------------------------
    @classmethod
    def from_proof(cls, method: str, *, note: str = "") -> Verdict:
        """An exact proof (residual 0)."""
        return cls(True, "proof", method, residual=0.0, note=note)

    @classmethod
    def sampled(cls, residual: Any, *, tol: Any, method: str = "", counterexample: dict[str, Any] | None = None,
                dps: float | None = None, points: list[dict[str, str]] | None = None,
                note: str = "", cells: list[dict[str, Any]] | None = None, error: Any = None) -> Verdict:
        """A verdict from the worst relative ``residual`` over finitely many samples.

        Without ``error``: holds iff ``residual <= tol``; ``digits`` is ``-log10(residual)``
        (capped at ``dps`` when given); the counterexample is kept only when it fails.

        ``error`` is the estimated error of the evaluation (relative, like the residual).
        Then the statement holds iff ``residual <= tol`` *and* ``error <= tol`` (the
        evaluation is trustworthy at the tolerance), and ``digits`` counts only the digits
        that agree and are trustworthy, ``-log10(max(residual, error))``; a residual above
        ``tol`` is a counterexample only if it exceeds ``SAFETY * error``; anything else is
        ``inconclusive``.
        """
        r = _as_float(residual)
        err = None if error is None else _as_float(error)
        t = _as_float(tol)
        holds = r <= t and (err is None or err <= t)
        inconclusive = not holds and err is not None and not (r > t and r > SAFETY * err)
        worst = r if err is None else max(r, err)
        digits: float | None
        if worst > 0 and math.isfinite(worst):
            digits = -math.log10(worst) if dps is None else min(-math.log10(worst), float(dps))
        elif math.isinf(worst):
            digits = 0.0
        else:
            digits = None if dps is None else float(dps)
        if inconclusive and not note:
            note = (f"inconclusive: the residual {r:.1e} cannot be told apart from the evaluation's own "
                    f"error {err:.1e} at tolerance {t:.1e}")
        return cls(holds, "sampled", method, residual=r, digits=None if digits is None else round(digits, 1),
                   counterexample=None if (holds or inconclusive) else counterexample, points=list(points or []),
                   note=note, cells=list(cells or []), inconclusive=inconclusive, error=err)

    # -- views ----------------------------------------------------------------
    @property
    def verdict(self) -> str:
        """``"proved"`` (exact proof), ``"verified"`` (holds otherwise), ``"inconclusive"`` or ``"false"``."""
        if self.inconclusive:
            return "inconclusive"
        if not self.holds:
            return "false"
        return "proved" if self.evidence == "proof" else "verified"

    @property
    def exact(self) -> bool:
        """True for a statement proved by exact reduction."""
        return self.holds and self.evidence == "proof"

    def __bool__(self) -> bool:
        return self.holds

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Verdict:
        known = set(cls.__dataclass_fields__)
        return cls(**{k: v for k, v in d.items() if k in known})
