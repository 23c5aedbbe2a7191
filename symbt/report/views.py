"""What the reports read of a claim and its outcome, as protocols.

The claim layer (:mod:`symbt.claims.base`) sits above the reports, so a report names the fields it
reads instead of importing :class:`~symbt.claims.base.Outcome`, :class:`~symbt.claims.base.Claim` and
:class:`~symbt.claims.base.ClaimResult`; those classes satisfy these protocols (the type checker
verifies it where the engine hands its results to a report).  The fields are read-only properties,
so the frozen ``Outcome`` with its ``Status``/``Evidence`` literals fits them.

>>> from symbt.claims.base import Claim, ClaimResult, Outcome
>>> r: ResultView = ClaimResult(Claim("t", "eq", "s", check=None), Outcome("verified", "m"))
>>> r.outcome.status, r.claim.equation
('verified', 'eq')
"""

from __future__ import annotations

from typing import Any, Protocol

__all__ = ["OutcomeView", "ClaimView", "ResultView"]


class OutcomeView(Protocol):
    """The fields of :class:`symbt.claims.base.Outcome` the reports read.

    >>> from symbt.claims.base import Outcome
    >>> o: OutcomeView = Outcome("erratum", "exact", corrected="x = 1")
    >>> o.corrected
    'x = 1'
    """

    @property
    def status(self) -> str: ...
    @property
    def method(self) -> str: ...
    @property
    def residual(self) -> float | None: ...
    @property
    def digits(self) -> float | None: ...
    @property
    def printed(self) -> str | None: ...
    @property
    def corrected(self) -> str | None: ...
    @property
    def counterexample(self) -> dict[str, Any] | None: ...
    @property
    def detail(self) -> str: ...
    @property
    def seconds(self) -> float: ...
    @property
    def cached(self) -> bool: ...
    @property
    def evidence(self) -> str | None: ...
    @property
    def cells(self) -> list[dict[str, Any]]: ...
    @property
    def scope(self) -> str: ...
    @property
    def n_scope(self) -> list[int] | str | None: ...
    def to_dict(self) -> dict[str, Any]: ...


class ClaimView(Protocol):
    """The fields of :class:`symbt.claims.base.Claim` the reports read.

    >>> from symbt.claims.base import Claim
    >>> c: ClaimView = Claim("t", "eq", "s", check=None, scene="demo")
    >>> c.scene
    'demo'
    """

    @property
    def id(self) -> str: ...
    @property
    def equation(self) -> str: ...
    @property
    def statement(self) -> str: ...
    @property
    def scene(self) -> str: ...
    @property
    def where(self) -> str: ...
    @property
    def source_equation(self) -> str | None: ...
    @property
    def N(self) -> int | None: ...


class ResultView(Protocol):
    """A claim with its outcome (:class:`symbt.claims.base.ClaimResult`).

    >>> from symbt.claims.base import Claim, ClaimResult, Outcome
    >>> ClaimResult(Claim("t", "eq", "s", check=None), Outcome("failed", "m")).to_dict()["status"]
    'failed'
    """

    @property
    def claim(self) -> ClaimView: ...
    @property
    def outcome(self) -> OutcomeView: ...
    def to_dict(self) -> dict[str, Any]: ...
