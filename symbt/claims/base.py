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
``skipped``   the check could not run (e.g. an optional extra is missing);
``inconclusive``  the check cannot decide at the precision or budget given
              ("cannot tell": a residual within the evaluation's own error);
``todo``      a claim stub with no check written yet.

``verified``, ``erratum`` and ``skipped`` are ok; ``failed``, ``inconclusive`` and
``todo`` are not (:data:`NOT_OK`): ``symbt verify`` exits 1 and the pytest plugin
fails the item.

Writing a claim
---------------
>>> from symbt import claim, decide, from_decision
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

import functools
import inspect
import sys
import time
import traceback
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, replace
from typing import Any, Literal, get_args

from ..proof.cells import CellTable
from ..proof.verdict import EVIDENCE, Evidence, Verdict

__all__ = [
    "Claim", "ClaimResult", "Outcome", "Parts", "claim", "REGISTRY", "SCENES", "scene",
    "from_decision", "judge", "judge_cells", "skipped", "failed", "inconclusive", "todo", "STATUSES", "NOT_OK",
    "Status",
]

#: the verdict of a claim (docs: the verdict reference)
Status = Literal["verified", "erratum", "failed", "skipped", "inconclusive", "todo"]
STATUSES: tuple[Status, ...] = get_args(Status)
#: statuses that make a run fail (exit 1, a failed pytest item, a JUnit <failure>)
NOT_OK = ("failed", "inconclusive", "todo")


@dataclass(frozen=True)
class Outcome:
    """Result of one claim check (JSON-serialisable via :meth:`to_dict`).

    ``evidence`` says how the statement reported as holding was decided
    (``"proof"``, ``"certified"`` or ``"sampled"``, see :class:`symbt.proof.Verdict`):
    the printed statement for ``verified``, the corrected one for ``erratum``, the
    failing check for ``failed``.  ``cells`` is the per-domain-cell table of a
    sampled check (``{"cell": {...}, "n", "printed_holds", "corrected_holds",
    "worst_residual"}``), ``scope`` the sentence generated from it, and
    ``n_scope`` the lattice sizes the claim covers (a list, or ``"all"`` with the
    argument in ``detail``).

    Frozen: a check builds a changed outcome with :func:`dataclasses.replace`.

    >>> from dataclasses import replace
    >>> o = Outcome("verified", "exact")
    >>> replace(o, n_scope=[3]).n_scope, o.n_scope
    ([3], None)
    >>> import mpmath
    >>> type(Outcome("verified", "numeric", residual=mpmath.mpf("2.5e-14")).residual).__name__
    'float'
    >>> o.status = "failed"
    Traceback (most recent call last):
    ...
    dataclasses.FrozenInstanceError: cannot assign to field 'status'
    """

    status: Status
    method: str
    residual: float | None = None
    digits: float | None = None
    printed: str | None = None
    corrected: str | None = None
    counterexample: dict[str, Any] | None = None
    detail: str = ""
    seconds: float = 0.0
    cached: bool = False
    evidence: Evidence | None = None
    cells: list[dict[str, Any]] = field(default_factory=list)
    scope: str = ""
    n_scope: list[int] | str | None = None

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise ValueError(f"unknown status {self.status!r}")
        if self.evidence is not None and self.evidence not in EVIDENCE:
            raise ValueError(f"unknown evidence {self.evidence!r}")
        # numbers of any kind (an mpf, a numpy scalar) are stored as floats: the report, the cache and the
        # JSON schema take a residual and digits as numbers, never as an mpf's text
        for name in ("residual", "digits"):
            value = getattr(self, name)
            if value is not None and type(value) is not float:
                object.__setattr__(self, name, float(value))

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Outcome:
        known = {f for f in cls.__dataclass_fields__}
        return cls(**{k: v for k, v in d.items() if k in known})


@dataclass
class Parts:
    """What a claim checks, as data: named statement parts, printed and corrected.

    Values are SymPy expressions or matrices (the right-hand side of a printed
    formula, a Darboux matrix, ...) or plain numbers (a branch sign, a printed
    constant).  The claim's check reads them instead of hard-coding them, so the
    mutation harness can rerun the same check on mutated parts.  ``printed``
    holds what the paper prints; ``corrected`` what symbt verifies instead
    (empty when the printed statement is right).  ``context`` holds fixed
    ingredients that are not the statement (symbols, relations) and are never
    mutated.
    """

    printed: dict[str, Any]
    corrected: dict[str, Any] = field(default_factory=dict)
    context: dict[str, Any] = field(default_factory=dict)

    def replace(self, side: str, name: str, value: Any) -> Parts:
        """A copy with ``side`` (``"printed"`` or ``"corrected"``) part ``name`` replaced."""
        new = Parts(dict(self.printed), dict(self.corrected), self.context)
        getattr(new, side)[name] = value
        return new


@dataclass(frozen=True)
class Claim:
    """One checkable statement of the paper.

    ``equation`` is the paper's ``\\label{}`` exactly (or a short descriptive
    label for an unlabelled statement, with ``where`` saying where it is);
    ``scene`` names the group the claim belongs to; ``N`` the lattice size it
    needs (``None`` = none or any); ``deep`` marks checks that need minutes and
    are left out of the default run; ``requires`` lists optional modules;
    ``source_equation`` is the paper label a derived artefact (e.g. emitted
    code) comes from, when ``equation`` names the artefact itself.
    ``uses`` names the claim ids or paper labels the statement relies on (the dependency
    graph of ``symbt report --html``; a verified claim that uses an erratum is shown as such).
    ``func`` is the check as written (taking ``N`` for a family of sizes);
    ``check`` is the zero-argument callable that runs it.
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
    source_equation: str | None = None
    uses: tuple[str, ...] = ()
    func: Callable[..., Outcome] | None = field(default=None, compare=False, repr=False)
    parts: Callable[[], Parts] | None = field(default=None, compare=False, repr=False)
    run_parts: Callable[[Parts], Outcome] | None = field(default=None, compare=False, repr=False)
    deep_check: Callable[[], Outcome] | None = field(default=None, compare=False, repr=False)
    #: the module that declared the claim (its claims source owns it; see :mod:`symbt.engine.project`)
    module: str = field(default="", compare=False, repr=False)

    def result(self) -> ClaimResult:
        """Run and wrap with the claim (renders richly in Jupyter, see :mod:`symbt.report.html`)."""
        return ClaimResult(self, self.run())

    def run(self, *, deep: bool = False) -> Outcome:
        """Run the check, timing it; an exception becomes a ``failed`` outcome.

        ``deep`` runs the claim's deep variant (more samples per cell) when it has one.
        """
        check = self.deep_check if (deep and self.deep_check is not None) else self.check
        return self._timed(check)

    def run_with(self, parts: Parts) -> Outcome:
        """Run the check on other statement parts (used by ``symbt mutate``)."""
        if self.run_parts is None:
            raise TypeError(f"claim {self.id} exposes no statement parts")
        run_parts = self.run_parts
        return self._timed(lambda: run_parts(parts))

    def _timed(self, check: Callable[[], Outcome]) -> Outcome:
        import importlib.util

        missing = [m for m in self.requires if importlib.util.find_spec(m) is None]
        t0 = time.perf_counter()
        if missing:
            out = skipped(f"optional dependency missing: {', '.join(missing)}")
        else:
            try:
                out = check()
            except Exception as exc:  # a crash is a failure, reported with its cause
                out = failed("exception", detail=f"{type(exc).__name__}: {exc}\n{traceback.format_exc(limit=4)}")
        out = replace(out, seconds=round(time.perf_counter() - t0, 4))
        if out.n_scope is None and self.N is not None and out.status not in ("skipped", "todo"):
            # a claim about one lattice size covers that size (unless it says more)
            out = replace(out, n_scope=[self.N])
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
             "statement": c.statement, "where": c.where or None, "uses": list(c.uses)}
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
    """Declare a scene (a named target: a group of claims) with its description.

    Optional: ``@claim(..., scene=NAME)`` creates an undeclared scene with no description.
    """
    current = SCENES.get(name)
    if current is None or not current.get("description"):
        SCENES[name] = {"description": description, "deep": deep}


def _with_parts(run_parts: Callable[..., Outcome], builder: Callable[[], Parts], **kw: Any) -> Outcome:
    return run_parts(builder(), **kw)


def _for_size(text: str, N: int) -> str:
    return text.replace("{N}", str(N))


def claim(id: str, *, equation: str, statement: str, scene: str, N: int | None = None,  # noqa: A002
          sizes: tuple[int, ...] | None = None, where: str = "", deep: bool = False,
          requires: tuple[str, ...] = (), source_equation: str | None = None,
          parts: Callable[..., Parts] | None = None, register: bool = True, uses: tuple[str, ...] = ()
          ) -> Callable[[Callable[..., Outcome]], Any]:
    """Decorator turning a check into registered :class:`Claim` s (claims as data).

    Without ``sizes`` the check takes no argument and one claim ``id`` is made
    (``N`` records the lattice size it needs, if any).  With ``sizes=(2, 3)``
    the check takes ``N`` and one claim per size is made, with id
    ``f"{id}.n{N}"``; ``{N}`` in ``statement``, ``equation`` and ``where`` is
    replaced by the size, and the check unchanged is returned, so it can be called
    directly; the claims are in :data:`REGISTRY` (and on ``check.claims``).  Without
    ``sizes`` the :class:`Claim` itself is returned.

    ``parts`` (called with ``N`` for a family) builds the :class:`Parts` the check
    reads; the check then takes them as its last argument: ``check(N, parts)``
    (or ``check(parts)``).  A check may also take a keyword ``deep`` (more
    samples per domain cell under ``symbt verify --deep``).  ``uses`` lists the claim ids or
    paper labels the statement relies on (``{N}`` is replaced as in ``statement``).
    """
    if sizes is not None and N is not None:
        raise ValueError("give either N (one claim) or sizes (one claim per size)")
    declared_in = sys._getframe(1).f_globals.get("__name__", "")  # the claims module, whatever the check's origin

    def make(cid: str, n: int | None, fn: Callable[..., Outcome]) -> Claim:
        sub = (lambda t: _for_size(t, n)) if (sizes is not None and n is not None) else (lambda t: t)
        head: tuple[int, ...] = (n,) if sizes is not None and n is not None else ()
        takes_deep = "deep" in inspect.signature(fn).parameters
        builder = None if parts is None else functools.partial(parts, *head)
        if builder is None:
            run_parts = None
            check = functools.partial(fn, *head)
        else:
            run_parts = functools.partial(fn, *head)
            check = functools.partial(_with_parts, run_parts, builder)
        deep_check = functools.partial(check, deep=True) if takes_deep else None
        c = Claim(id=cid, equation=sub(equation), statement=sub(statement), check=check, scene=scene, N=n,
                  where=sub(where), deep=deep, requires=tuple(requires),
                  source_equation=None if source_equation is None else sub(source_equation),
                  uses=tuple(sub(u) for u in uses), func=fn,
                  parts=builder, run_parts=run_parts, deep_check=deep_check, module=declared_in)
        if register:
            if cid in REGISTRY:
                raise ValueError(f"duplicate claim id {cid}")
            REGISTRY[cid] = c
            SCENES.setdefault(scene, {"description": "", "deep": False})  # a scene needs no declaration
        return c

    def wrap(fn: Callable[..., Outcome]) -> Any:
        if sizes is None:
            return make(id, N, fn)
        fn.claims = [make(f"{id}.n{n}", n, fn) for n in sizes]  # type: ignore[attr-defined]
        return fn

    return wrap


# --------------------------------------------------------------------------- outcome helpers

def skipped(reason: str) -> Outcome:
    """The check could not run (e.g. ``"optional dependency missing: flint"``)."""
    return Outcome("skipped", "none", detail=reason)


def failed(method: str, *, residual: float | None = None, detail: str = "",
           counterexample: dict[str, Any] | None = None) -> Outcome:
    """Something that should hold does not (with the residual and counterexample when known)."""
    return Outcome("failed", method, residual=residual, detail=detail, counterexample=counterexample)


def judge_cells(table: CellTable, *, printed: str, corrected: str | None = None, method: str | None = None,
                dps: int | None = None, detail: str = "") -> Outcome:
    """A sampled claim's outcome from its :class:`~symbt.proof.cells.CellTable` (what ``judge(table, ...)`` does).

    ``verified`` if the printed statement held at every sample, ``erratum`` if it failed somewhere and
    the corrected statement held everywhere, else ``failed``; ``evidence="sampled"``, the table's
    ``cells``, the worst printed sample as counterexample, and the ``scope`` sentence generated from
    the table.  ``method`` and ``dps`` default to the table's own (set by ``Domain.evaluate``).

    >>> t = CellTable(tol=1e-20, method="numeric: demo", dps=30)
    >>> t.add({"b": 1}, printed=0.0, corrected=0.0); t.add({"b": -1}, printed=2.0, corrected=0.0)
    >>> o = judge_cells(t, printed="x = b y", corrected="x = y")
    >>> o.status, o.evidence, o.counterexample
    ('erratum', 'sampled', {'cell': '{b=-1}'})
    >>> print(o.scope.replace("; ", ";\\n"))
    printed statement holds exactly in cells {b=+1} and fails in {b=-1};
    corrected statement holds in all 2 cells
    """
    method = method or table.method or "numeric: sampled cells"
    dps = table.dps if dps is None else dps
    pv = table.verdict(method=method, dps=dps)
    cells, (_, where_p) = pv.cells, table.worst("printed")
    n = sum(c["n"] for c in cells)
    base: dict[str, Any] = dict(printed=printed, scope=pv.note, cells=cells, evidence="sampled",
                                detail=(detail + f" [{n} samples in {len(cells)} cells]").strip())
    if table.printed_holds_everywhere():
        return Outcome("verified", method, residual=pv.residual, digits=pv.digits, **base)
    if corrected is None:
        return Outcome("failed", method, residual=pv.residual, digits=pv.digits, counterexample=where_p, **base)
    rc, _ = table.worst("corrected")
    cv = Verdict.sampled(rc, tol=table.tol, method=method, dps=dps)
    status: Status = "erratum" if table.corrected_holds_everywhere() else "failed"
    return Outcome(status, f"printed: {method} | corrected: {method}", residual=pv.residual, digits=cv.digits,
                   corrected=corrected, counterexample=where_p, **base)


def inconclusive(method: str, *, detail: str = "", residual: float | None = None, digits: float | None = None,
                 evidence: Evidence | None = None,
                 printed: str | None = None, cells: list[dict[str, Any]] | None = None) -> Outcome:
    """The check cannot decide at the precision or budget given ("cannot tell"); not ok.

    >>> o = inconclusive("numeric: 30 digits", detail="residual within the evaluation error", residual=1e-22)
    >>> o.status, o.residual
    ('inconclusive', 1e-22)
    """
    return Outcome("inconclusive", method, residual=residual, digits=digits, detail=detail, evidence=evidence,
                   printed=printed, cells=list(cells or []))


def todo(reason: str = "no check written yet") -> Outcome:
    """A claim stub without a check (e.g. scaffolded from a paper's labels); never verified, not ok.

    >>> todo().status, todo().detail
    ('todo', 'no check written yet')
    """
    return Outcome("todo", "none", detail=reason)


def from_decision(d: Verdict, *, detail: str = "") -> Outcome:
    """``verified`` if the :class:`~symbt.proof.Verdict` holds, ``inconclusive`` if it cannot tell,
    else ``failed`` with its counterexample."""
    if d.holds:
        return Outcome("verified", d.method, residual=d.residual, digits=d.digits, evidence=d.evidence,
                       cells=list(d.cells), detail=(detail + (" " + d.note if d.note else "")).strip())
    if d.inconclusive:
        return Outcome("inconclusive", d.method, residual=d.residual, digits=d.digits, evidence=d.evidence,
                       cells=list(d.cells), detail=(detail + (" " + d.note if d.note else "")).strip())
    return Outcome("failed", d.method, residual=d.residual, digits=d.digits, evidence=d.evidence,
                   cells=list(d.cells), counterexample=d.counterexample, detail=detail)


def judge(printed_decision: Verdict | CellTable, *, printed: str, corrected: str | None = None,
          corrected_check: Callable[[], Verdict] | None = None, detail: str = "") -> Outcome:
    """Check a statement *as printed*; if it fails, check the correction.

    ``printed_decision`` and the result of ``corrected_check`` are
    :class:`~symbt.proof.Verdict` objects.  Returns ``verified`` when
    the printed statement holds, ``erratum`` when it fails and the correction
    holds, ``inconclusive`` when the printed statement (or, once it fails, the
    correction) cannot be decided at the precision given, ``failed`` otherwise.
    An inconclusive verdict is never reported as failed or verified.  A sampled
    claim passes its :class:`~symbt.proof.cells.CellTable` instead (the corrected
    residuals are in the table): see :func:`judge_cells`.
    """
    if isinstance(printed_decision, CellTable):
        if corrected_check is not None:
            raise TypeError("judge(CellTable, ...): the corrected statement's residuals belong in the table "
                            "(Domain.evaluate(..., corrected=...)), not in corrected_check")
        return judge_cells(printed_decision, printed=printed, corrected=corrected, detail=detail)
    if printed_decision.holds:
        return Outcome("verified", printed_decision.method, residual=printed_decision.residual,
                       digits=printed_decision.digits, printed=printed, detail=detail,
                       evidence=printed_decision.evidence, cells=list(printed_decision.cells))
    if printed_decision.inconclusive:
        return inconclusive(printed_decision.method, residual=printed_decision.residual,
                            digits=printed_decision.digits, evidence=printed_decision.evidence, printed=printed,
                            cells=list(printed_decision.cells),
                            detail=(detail + " printed statement: " + (printed_decision.note or "cannot tell")).strip())
    if corrected_check is None:
        return Outcome("failed", printed_decision.method, residual=printed_decision.residual,
                       printed=printed, counterexample=printed_decision.counterexample,
                       evidence=printed_decision.evidence, cells=list(printed_decision.cells),
                       detail=detail or "printed statement fails and no correction is known")
    cd = corrected_check()
    status: Status = "erratum" if cd.holds else ("inconclusive" if cd.inconclusive else "failed")
    method = f"printed: {printed_decision.method} | corrected: {cd.method}"
    if cd.holds:
        extra = ""
    elif cd.inconclusive:
        extra = f" printed statement fails; the correction cannot be decided: {cd.note or 'cannot tell'}"
    else:
        extra = f" correction also fails (residual {cd.residual})"
    return Outcome(status, method, residual=printed_decision.residual,
                   digits=cd.digits, printed=printed, corrected=corrected,
                   counterexample=printed_decision.counterexample, evidence=cd.evidence,
                   cells=list(cd.cells) or list(printed_decision.cells),
                   detail=(detail + extra).strip())
