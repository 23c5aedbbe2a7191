"""Claims as data: a paper label, a statement, and a check that could fail.

A :class:`Claim` is a small declarative object (in the spirit of
``sympy.codegen.rewriting`` rules): the engine (:mod:`symbt.engine`) selects,
caches and runs them; the check returns an :class:`Outcome`.

Statuses
--------
``verified``  the printed statement holds;
``erratum``   the printed statement fails (counterexample + residual), and a
              corrected statement, as close to the paper as the truth allows, holds;
``failed``    something that should hold does not (a bug here or in the paper
              with no verified correction);
``skipped``   the check could not run (e.g. an optional extra is missing).

Writing a claim
---------------
>>> from symbt.claims.base import claim, from_decision
>>> from symbt.proof import decide
>>> import sympy as sp
>>> @claim("demo.square", equation="demo", scene="demo",
...        statement="(a+b)^2 = a^2 + 2ab + b^2", register=False)
... def demo_square():
...     a, b = sp.symbols("a b")
...     return from_decision(decide((a + b)**2, a**2 + 2*a*b + b**2))
>>> demo_square.run().status
'verified'
"""
from __future__ import annotations

import time
import traceback
from dataclasses import asdict, dataclass, field
from typing import Any, Callable

__all__ = [
    "Claim", "ClaimResult", "Outcome", "claim", "REGISTRY", "SCENES", "scene",
    "from_decision", "judge", "skipped", "failed",
]

STATUSES = ("verified", "erratum", "failed", "skipped")


@dataclass
class Outcome:
    """Result of one claim check (JSON-serialisable via :meth:`to_dict`)."""

    status: str
    method: str
    residual: float | None = None
    digits: float | None = None
    printed: str | None = None
    corrected: str | None = None
    counterexample: dict[str, Any] | None = None
    detail: str = ""
    seconds: float = 0.0
    cached: bool = False

    def __post_init__(self):
        if self.status not in STATUSES:
            raise ValueError(f"unknown status {self.status!r}")

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> "Outcome":
        known = {f for f in cls.__dataclass_fields__}
        return cls(**{k: v for k, v in d.items() if k in known})


@dataclass(frozen=True)
class Claim:
    """One checkable statement of the paper.

    ``equation`` is the paper's ``\\label{}`` exactly (or a short descriptive
    label for an unlabelled statement, with ``where`` saying where it is);
    ``scene`` names the group the claim belongs to; ``N`` the lattice size it
    needs (``None`` = none or any); ``deep`` marks checks that need minutes and
    are left out of the default run; ``requires`` lists optional modules.
    """

    id: str
    equation: str
    statement: str
    check: Callable[[], Outcome] = field(compare=False, repr=False)
    scene: str = "core"
    N: int | None = None
    where: str = ""
    deep: bool = False
    requires: tuple[str, ...] = ()

    def result(self) -> "ClaimResult":
        """Run and wrap with the claim (renders richly in Jupyter, see :mod:`symbt.report.html`)."""
        return ClaimResult(self, self.run())

    def run(self) -> Outcome:
        """Run the check, timing it; an exception becomes a ``failed`` outcome."""
        import importlib.util

        missing = [m for m in self.requires if importlib.util.find_spec(m) is None]
        t0 = time.perf_counter()
        if missing:
            out = skipped(f"optional dependency missing: {', '.join(missing)}")
        else:
            try:
                out = self.check()
            except Exception as exc:  # a crash is a failure, reported with its cause
                out = failed("exception", detail=f"{type(exc).__name__}: {exc}\n{traceback.format_exc(limit=4)}")
        out.seconds = round(time.perf_counter() - t0, 4)
        return out


@dataclass
class ClaimResult:
    """A claim together with its outcome (what reports and notebooks show)."""

    claim: Claim
    outcome: Outcome

    @property
    def status(self) -> str:
        return self.outcome.status

    def to_dict(self) -> dict[str, Any]:
        c = self.claim
        d = {"id": c.id, "equation": c.equation, "scene": c.scene, "N": c.N,
             "statement": c.statement, "where": c.where or None}
        d.update(self.outcome.to_dict())
        return d

    def _repr_html_(self) -> str:
        from ..report.html import result_html
        return result_html(self)

    def _repr_latex_(self) -> str:
        from ..report.html import result_latex
        return result_latex(self)

    def __repr__(self) -> str:
        o = self.outcome
        return f"<{self.claim.id} (eq. {self.claim.equation}): {o.status} by {o.method}>"


REGISTRY: dict[str, Claim] = {}
SCENES: dict[str, dict[str, Any]] = {}


def scene(name: str, description: str, *, deep: bool = False) -> None:
    """Declare a scene (a named target: a group of claims)."""
    SCENES.setdefault(name, {"description": description, "deep": deep})


def claim(id: str, *, equation: str, statement: str, scene: str, N: int | None = None,
          where: str = "", deep: bool = False, requires: tuple[str, ...] = (),
          register: bool = True):
    """Decorator turning ``check() -> Outcome`` into a registered :class:`Claim`."""

    def wrap(fn: Callable[[], Outcome]) -> Claim:
        c = Claim(id=id, equation=equation, statement=statement, check=fn, scene=scene, N=N,
                  where=where, deep=deep, requires=tuple(requires))
        if register:
            if id in REGISTRY:
                raise ValueError(f"duplicate claim id {id}")
            REGISTRY[id] = c
        return c

    return wrap


# --------------------------------------------------------------------------- outcome helpers

def skipped(reason: str) -> Outcome:
    return Outcome("skipped", "none", detail=reason)


def failed(method: str, *, residual=None, detail: str = "", counterexample=None) -> Outcome:
    return Outcome("failed", method, residual=residual, detail=detail, counterexample=counterexample)


def from_decision(d, *, detail: str = "") -> Outcome:
    """``verified`` if the :class:`~symbt.proof.Decision` holds, else ``failed`` with its counterexample."""
    if d.holds:
        return Outcome("verified", d.method, residual=d.residual, digits=d.digits,
                       detail=(detail + (" " + d.note if d.note else "")).strip())
    return Outcome("failed", d.method, residual=d.residual, digits=d.digits,
                   counterexample=d.counterexample, detail=detail)


def judge(printed_decision, *, printed: str, corrected: str | None = None,
          corrected_check: Callable[[], Any] | None = None, detail: str = "") -> Outcome:
    """Check a statement *as printed*; if it fails, check the correction.

    ``printed_decision`` and the result of ``corrected_check`` are
    :class:`~symbt.proof.Decision` objects (or anything with ``holds``,
    ``method``, ``residual``, ``counterexample``).  Returns ``verified`` when
    the printed statement holds, ``erratum`` when it fails and the correction
    holds, ``failed`` otherwise.
    """
    if printed_decision.holds:
        return Outcome("verified", printed_decision.method, residual=printed_decision.residual,
                       digits=getattr(printed_decision, "digits", None), printed=printed, detail=detail)
    if corrected_check is None:
        return Outcome("failed", printed_decision.method, residual=printed_decision.residual,
                       printed=printed, counterexample=printed_decision.counterexample,
                       detail=detail or "printed statement fails and no correction is known")
    cd = corrected_check()
    status = "erratum" if cd.holds else "failed"
    method = f"printed: {printed_decision.method} | corrected: {cd.method}"
    return Outcome(status, method, residual=printed_decision.residual,
                   digits=getattr(cd, "digits", None), printed=printed, corrected=corrected,
                   counterexample=printed_decision.counterexample,
                   detail=(detail + ("" if cd.holds else f" correction also fails (residual {cd.residual})")).strip())
