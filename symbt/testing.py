"""Helpers for test suites: ``assert_identity`` for pytest (or any test runner).

>>> import sympy as sp
>>> from symbt.testing import assert_identity
>>> x = sp.Symbol("x", positive=True)
>>> assert_identity(sp.sqrt(x**2), x).status
'proved'

A false identity raises :class:`AssertionError` whose message gives the
statement, the relative residual and the counterexample point, so a failing
test says *where* the identity breaks.  ``require="proved"`` additionally
rejects identities that only pass the numeric screen.
"""
from __future__ import annotations

from .proof.identity import IdentityResult, check_identity

__all__ = ["assert_identity", "IdentityAssertionError"]


class IdentityAssertionError(AssertionError):
    """Raised by :func:`assert_identity`; ``.result`` is the :class:`IdentityResult`."""

    def __init__(self, message: str, result: IdentityResult):
        super().__init__(message)
        self.result = result


def _message(r: IdentityResult, msg: str | None) -> str:
    what = "cannot be decided (inconclusive)" if r.status == "inconclusive" else "does not hold"
    lines = [f"identity {what}: {r.statement}"]
    if msg:
        lines.insert(0, msg)
    res = "undefined" if r.residual is None else f"{r.residual:.6g}"
    lines.append(f"  relative residual: {res}")
    if r.counterexample:
        lines.append("  counterexample:")
        lines.extend(f"    {k} = {v}" for k, v in r.counterexample.items())
    lines.append(f"  method: {r.method}")
    if r.note:
        lines.append(f"  note: {r.note}")
    return "\n".join(lines)


def assert_identity(lhs, rhs=0, *, require: str = "verified", msg: str | None = None,
                    **kw) -> IdentityResult:
    """Assert ``lhs == rhs`` with :func:`symbt.proof.identity.check_identity`; return the result.

    Keyword arguments (``relations``, ``assumptions``, ``digits``, ``points``,
    ``seed``, ...) go to :func:`~symbt.proof.identity.check_identity`.
    ``require="verified"`` (default) accepts proved or numerically verified
    identities; ``require="proved"`` accepts only exact proofs.
    """
    __tracebackhide__ = True  # pytest: show the caller's line
    if require not in ("verified", "proved"):
        raise ValueError("require must be 'verified' or 'proved'")
    r = check_identity(lhs, rhs, **kw)
    if not r:
        raise IdentityAssertionError(_message(r, msg), r)
    if require == "proved" and r.status != "proved":
        raise IdentityAssertionError(
            (msg + "\n" if msg else "") +
            f"identity only verified numerically, not proved: {r.statement}\n  {r.summary()}", r)
    return r
